"""Throughput of the wear power kernel on four signals, against the memory floor and numpy.

For each size N (default 10⁷ samples; ``--large`` adds 10⁸) and each signal of
``benchmarks/_signals.py`` (smooth impacting oscillator, the example history tiled, a
``fretwear.dynamics`` rattling tube tiled, white noise), the history is generated chunk by chunk
(``--chunk`` samples, bounded memory) and folded into a :class:`fretwear.power.PowerAccumulator`
with ``--sectors`` sectors and ``--blocks`` blocks (statistics included). Timed per chunk, best of
``--repeat`` interleaved tries:

* the *floor*: one pass that only sums the six input arrays (``np.sum`` of t, Fn, Vt1, Vt2, Dy,
  Dz), the memory-bandwidth bound of any one-pass algorithm;
* the compiled kernel (``backend="numba"``), through ``PowerAccumulator.update`` of a
  ContactHistory built outside the timing (the history's stick flags included when it has them);
* the plain numpy kernel (``backend="numpy"``) up to ``--numpy-up-to`` samples.

The whole measurement runs ``--runs`` times; printed are the median times and ratios to the
floor, with the spread (min-max of the ratio over the runs) since the machine may be shared.

Usage::

    .venv/bin/python benchmarks/bench_power.py                     # 1e7 samples, four signals
    .venv/bin/python benchmarks/bench_power.py --large --runs 3    # 1e7 and 1e8
    .venv/bin/python benchmarks/bench_power.py --samples 1e6 --signals noise smooth
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _signals  # noqa: E402 - the benchmark's own helper module

from fretwear.history import ContactHistory  # noqa: E402
from fretwear.power import PowerAccumulator  # noqa: E402
from fretwear.power.kernels import HAVE_NUMBA  # noqa: E402


def floor_pass(arrays) -> float:
    """Time [s] of one pass that only sums each array."""
    t0 = time.perf_counter()
    for a in arrays:
        a.sum()
    return time.perf_counter() - t0


def run(signal: str, samples: int, chunk: int, sectors: int, blocks: int,
        backends: list[str], repeat: int) -> dict:
    """Stream ``samples`` samples of ``signal``; per chunk, the best of ``repeat`` tries."""
    gen = _signals.generator(signal)
    t_end = float(gen(samples - 1, 1)["time"][0])
    kw = dict(t_start=0.0, t_end=t_end, blocks=blocks, sectors=sectors)
    accs = {b: PowerAccumulator(backend=b, **kw) for b in backends}
    times = dict.fromkeys(backends, 0.0)
    floor = 0.0
    start = 0
    while start < samples - 1:
        size = min(chunk, samples - start)
        arrays = gen(start, size)
        h = ContactHistory(**arrays)
        six = [getattr(h, c) for c in _signals.SIX]
        best = dict.fromkeys(["floor", *backends], np.inf)
        parts = {}
        for _ in range(repeat):  # interleaved, so that a busy moment hits every contender
            best["floor"] = min(best["floor"], floor_pass(six))
            for b in backends:
                parts[b] = PowerAccumulator(backend=b, **kw)
                t0 = time.perf_counter()
                parts[b].update(h)
                best[b] = min(best[b], time.perf_counter() - t0)
        for b in backends:
            accs[b].merge(parts[b])
            times[b] += best[b]
        floor += best["floor"]
        del h, arrays, six
        start += size - 1  # chunks share their boundary sample
    results = {b: accs[b].result(stationarity_threshold=np.inf) for b in backends}
    totals = [r.total for r in results.values()]
    assert np.allclose(totals, totals[0], rtol=1e-12), totals
    return {"floor": floor, "times": times, "total": totals[0]}


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--samples", type=float, nargs="+", default=[1e7])
    p.add_argument("--large", action="store_true", help="also 1e8 samples")
    p.add_argument("--signals", nargs="+", default=list(_signals.SIGNALS),
                   choices=_signals.SIGNALS)
    p.add_argument("--chunk", type=float, default=1e6, help="samples per chunk")
    p.add_argument("--sectors", type=int, default=10)
    p.add_argument("--blocks", type=int, default=4)
    p.add_argument("--repeat", type=int, default=3,
                   help="interleaved tries per chunk; the best time of each is kept")
    p.add_argument("--runs", type=int, default=3, help="whole measurements; medians printed")
    p.add_argument("--numpy-up-to", type=float, default=1e7,
                   help="run the plain-numpy backend only up to this many samples")
    args = p.parse_args(argv)
    sizes = [int(n) for n in args.samples] + ([int(1e8)] if args.large else [])
    for name in args.signals:  # compile (or load the cache) and build the tiles outside timings
        run(name, 3000, 1000, args.sectors, args.blocks, ["numba"] if HAVE_NUMBA else [], 1)
    print(f"{args.sectors} sectors, {args.blocks} blocks, statistics; chunks of "
          f"{int(args.chunk):.0e} samples; medians of {args.runs} runs (ratio spread min-max)")
    print(f"{'samples':>8} {'signal':>9} {'floor [s]':>10} {'numba [s]':>10} {'ratio':>6} "
          f"{'spread':>11} {'numpy [s]':>10} {'ratio':>6}")
    for n in sizes:
        for name in args.signals:
            backends = (["numba"] if HAVE_NUMBA else []) + (
                ["numpy"] if n <= args.numpy_up_to else [])
            runs = [run(name, n, int(args.chunk), args.sectors, args.blocks, backends,
                        args.repeat) for _ in range(args.runs)]
            floor = float(np.median([r["floor"] for r in runs]))
            line = f"{n:>8.0e} {name:>9} {floor:>10.4f}"
            for b in ("numba", "numpy"):
                if b not in backends:
                    line += f" {'-':>10} {'-':>6}" + (f" {'':>11}" if b == "numba" else "")
                    continue
                t = float(np.median([r["times"][b] for r in runs]))
                ratios = [r["times"][b] / r["floor"] for r in runs]
                line += f" {t:>10.4f} {t / floor:>6.2f}"
                if b == "numba":
                    line += f" {min(ratios):>5.2f}-{max(ratios):<5.2f}"
            print(line, flush=True)


if __name__ == "__main__":
    main()
