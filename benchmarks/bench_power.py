"""Throughput of the wear power (fused kernel vs plain numpy) against the memory floor.

For each size N (default 1e7 and 1e8 samples) a synthetic impacting-sliding history with
``--sectors`` sectors and ``--blocks`` blocks is generated chunk by chunk (memory bounded by
``--chunk`` samples × 6 float64 arrays) and fed to :class:`fretwear.power.PowerAccumulator`
(the streaming path, statistics included). The *floor* is a single pass that only sums each input
array (``np.sum`` of t, Fn, Vt1, Vt2, Dy, Dz): the memory-bandwidth bound of any one-pass
algorithm. Printed: samples/s and the ratio time/floor per backend.

Usage::

    .venv/bin/python benchmarks/bench_power.py                  # 1e7 and 1e8 samples
    .venv/bin/python benchmarks/bench_power.py --samples 1e6 --numpy-up-to 1e8

The synthetic signal: an oscillator of period 10 ms impacting a gap (Fn = max(0, F·sin) + noise,
about 40 % contact), a sliding velocity turning with the orbit, and a contact point wandering
around the circle, so contact and sector changes come in runs as in a real history.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from fretwear.kernels import HAVE_NUMBA
from fretwear.power import PowerAccumulator

DT = 1e-5  # time step [s]


def make_chunk(start: int, size: int, rng: np.random.Generator) -> tuple[np.ndarray, ...]:
    """Samples ``start .. start+size-1`` of the synthetic history (SI units)."""
    t = (start + np.arange(size)) * DT
    w = 2 * np.pi * 100.0
    fn = np.maximum(0.0, 50.0 * np.sin(w * t) - 15.0 + rng.normal(0.0, 2.0, size))
    phi = 0.7 * np.sin(2 * np.pi * 0.37 * t) * np.pi + rng.normal(0.0, 0.05, size)
    vt1 = 0.05 * np.cos(w * t + phi)
    vt2 = 0.05 * np.sin(w * t)
    dy = 1e-4 * np.cos(phi)
    dz = 1e-4 * np.sin(phi)
    return t, fn, vt1, vt2, dy, dz


def floor_pass(arrays) -> float:
    """Time [s] of one pass that only sums each array."""
    t0 = time.perf_counter()
    for a in arrays:
        a.sum()
    return time.perf_counter() - t0


def run(samples: int, chunk: int, sectors: int, blocks: int, backends: list[str],
        repeat: int = 1) -> dict:
    """Stream ``samples`` samples; per chunk, the best of ``repeat`` interleaved timings."""
    from fretwear.history import ContactHistory

    t_end = (samples - 1) * DT
    kw = dict(t_start=0.0, t_end=t_end, blocks=blocks, sectors=sectors)
    accs = {b: PowerAccumulator(backend=b, **kw) for b in backends}
    times = dict.fromkeys(backends, 0.0)
    floor = 0.0
    rng = np.random.default_rng(0)
    start = 0
    while start < samples - 1:
        size = min(chunk, samples - start)
        arrays = make_chunk(start, size, rng)
        h = ContactHistory(time=arrays[0], normal_force=arrays[1], vt1=arrays[2],
                           vt2=arrays[3], dy=arrays[4], dz=arrays[5])
        best = dict.fromkeys(["floor", *backends], np.inf)
        parts = {}
        for _ in range(repeat):  # interleaved, so that a busy moment hits every contender
            best["floor"] = min(best["floor"],
                                floor_pass([h.time, h.normal_force, h.vt1, h.vt2, h.dy, h.dz]))
            for b in backends:
                parts[b] = PowerAccumulator(backend=b, **kw)
                t0 = time.perf_counter()
                parts[b].update(h)
                best[b] = min(best[b], time.perf_counter() - t0)
        for b in backends:
            accs[b].merge(parts[b])
            times[b] += best[b]
        floor += best["floor"]
        del h, arrays
        start += size - 1  # chunks share their boundary sample
    results = {b: accs[b].result(stationarity_threshold=np.inf) for b in backends}
    totals = [r.total for r in results.values()]
    assert np.allclose(totals, totals[0], rtol=1e-9), totals
    return {"floor": floor, "times": times, "total": totals[0]}


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--samples", type=float, nargs="+", default=[1e7, 1e8])
    p.add_argument("--chunk", type=float, default=1e7, help="samples per chunk")
    p.add_argument("--sectors", type=int, default=10)
    p.add_argument("--blocks", type=int, default=4)
    p.add_argument("--repeat", type=int, default=3,
                   help="interleaved repetitions per chunk; the best time of each is kept")
    p.add_argument("--numpy-up-to", type=float, default=1e7,
                   help="run the plain-numpy backend only up to this many samples")
    args = p.parse_args(argv)
    if HAVE_NUMBA:  # compile (or load the cache) outside the timings
        run(1000, 1000, args.sectors, args.blocks, ["numba"])
    print(f"{'samples':>10} {'backend':>8} {'time [s]':>9} {'samples/s':>11} {'floor [s]':>9} "
          f"{'ratio':>6}")
    for n in args.samples:
        n = int(n)
        backends = (["numba"] if HAVE_NUMBA else []) + (
            ["numpy"] if n <= args.numpy_up_to else [])
        res = run(n, int(args.chunk), args.sectors, args.blocks, backends, args.repeat)
        for b, t in res["times"].items():
            print(f"{n:>10.0e} {b:>8} {t:>9.3f} {n / t:>11.3e} {res['floor']:>9.3f} "
                  f"{t / res['floor']:>6.2f}")


if __name__ == "__main__":
    main()
