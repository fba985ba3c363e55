"""Synthetic contact histories for the benchmarks, generated chunk by chunk (bounded memory).

Four signals, from the easiest to the hardest for a one-pass kernel:

``smooth``
    An oscillator of period 10 ms impacting a gap: Fn = max(0, 50 sin(ωt) − 15 + noise) [N]
    (about 40 % contact), a sliding velocity turning with the orbit [m/s] and a contact point
    wandering slowly around the circle [m]: contact and sector changes come in long runs.
``example``
    ``examples/data/oscillator_gap.csv`` (a tube section rattling in a circular gap, 15 001
    samples at 5 kHz, 4 % contact, stick flags) tiled end to end, time shifted by 3 s per tile.
``dynamics``
    A rattling tube from :func:`fretwear.dynamics.simulate` (10 modes, circular support of
    radial gap 0.2 mm, Coulomb friction, two random forces; the model of
    ``benchmarks/bench_dynamics.py``), 10⁶ samples at 25 kHz (12 % contact, stick flags),
    tiled end to end. Simulated once and cached under the temporary directory.
``noise``
    White noise: Fn = max(0, N(0, 10 N)) (half the samples in contact, a threshold crossing on
    half the intervals), Vt1, Vt2 ~ N(0, 0.05 m/s), Dy, Dz ~ N(0, 0.1 mm) (a random sector at
    every sample): no run of anything, the worst case for branches.

Every chunk is a dict of float64 arrays named as :class:`fretwear.history.ContactHistory`
channels (``stick`` only for the tiled records). Samples ``start .. start + size − 1`` of a
signal are the same whatever the chunking (the random generators are keyed by the chunk start
only through ``numpy.random.SeedSequence``; chunks of the same size give the same values).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

DT = 1e-5  # time step of the smooth and noise signals [s]
SIGNALS = ("smooth", "example", "dynamics", "noise")
#: The six arrays every signal has (the floor sums these).
SIX = ("time", "normal_force", "vt1", "vt2", "dy", "dz")
_ROOT = Path(__file__).resolve().parents[1]
#: The benchmarks' wear case (``WearCase.from_keywords`` / ``wear_table`` keywords): a 3/4"
#: steam-generator tube against a 12.7 mm anti-vibration bar, Archard, 8 sectors, 6 instants
#: [years].
TUBE_BAV = dict(contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                                     "obstacle_width": 12.7e-3},
                law="ARCHARD", coefficients={"COEF_USURE": 1e-17}, sectors=8,
                instants=[1, 2, 5, 10, 20, 40], time_scale=3.15576e7)


def _rng(start: int, salt: int) -> np.random.Generator:
    return np.random.default_rng([salt, start])


def smooth(start: int, size: int) -> dict[str, np.ndarray]:
    """Samples ``start .. start+size-1`` of the smooth impacting oscillator (SI units)."""
    rng = _rng(start, 1)
    t = (start + np.arange(size)) * DT
    w = 2 * np.pi * 100.0
    fn = np.maximum(0.0, 50.0 * np.sin(w * t) - 15.0 + rng.normal(0.0, 2.0, size))
    phi = 0.7 * np.sin(2 * np.pi * 0.37 * t) * np.pi + rng.normal(0.0, 0.05, size)
    return {"time": t, "normal_force": fn, "vt1": 0.05 * np.cos(w * t + phi),
            "vt2": 0.05 * np.sin(w * t), "dy": 1e-4 * np.cos(phi), "dz": 1e-4 * np.sin(phi)}


def noise(start: int, size: int) -> dict[str, np.ndarray]:
    """Samples ``start .. start+size-1`` of the white-noise signal (SI units)."""
    rng = _rng(start, 2)
    return {"time": (start + np.arange(size)) * DT,
            "normal_force": np.maximum(0.0, rng.normal(0.0, 10.0, size)),
            "vt1": rng.normal(0.0, 0.05, size), "vt2": rng.normal(0.0, 0.05, size),
            "dy": rng.normal(0.0, 1e-4, size), "dz": rng.normal(0.0, 1e-4, size)}


class Tiled:
    """A finite record repeated end to end; tile k is shifted by k times the record's length."""

    def __init__(self, record: dict[str, np.ndarray]) -> None:
        t = np.asarray(record["time"])
        # one tile = every sample but the last (the next tile starts one step after it)
        self.base = {k: np.ascontiguousarray(v[:-1]) for k, v in record.items()}
        self.n = t.size - 1
        self.period = float(t[-1] - t[0])
        self.base["time"] = self.base["time"] - t[0]

    def __call__(self, start: int, size: int) -> dict[str, np.ndarray]:
        idx = start + np.arange(size)
        tile, off = np.divmod(idx, self.n)
        out = {k: v[off] for k, v in self.base.items()}
        out["time"] = out["time"] + tile * self.period
        return out


def _channels(history) -> dict[str, np.ndarray]:
    keep = (*SIX, "stick")
    return {c: np.asarray(getattr(history, c)) for c in keep if getattr(history, c) is not None}


def example() -> Tiled:
    """The example history of the repository, tiled."""
    from fretwear.io import read_history

    return Tiled(_channels(read_history(_ROOT / "examples" / "data" / "oscillator_gap.csv")))


def dynamics(samples: int = 1_000_000) -> Tiled:
    """A rattling tube simulated by :mod:`fretwear.dynamics`, tiled (cached on disk)."""
    cache = Path(os.environ.get("FRETWEAR_BENCH_CACHE", tempfile.gettempdir())) / (
        f"fretwear_bench_dynamics_{samples}.npz")
    if cache.is_file():
        with np.load(cache) as z:
            return Tiled({k: z[k] for k in z.files})
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_dynamics import H, loads, setup

    from fretwear.dynamics import simulate

    model, shocks = setup()
    duration = (samples - 1) * 2 * H
    r = simulate(model, shocks, loads(duration), duration=duration, time_step=H,
                 archive_step=2 * H, chunk_size=200_000)
    record = _channels(r.history(0))
    tmp = cache.with_suffix(".tmp.npz")
    np.savez(tmp, **record)
    os.replace(tmp, cache)
    return Tiled(record)


def generator(name: str):
    """``generator(name)(start, size)`` -> dict of arrays of that signal."""
    if name == "smooth":
        return smooth
    if name == "noise":
        return noise
    if name == "example":
        return example()
    if name == "dynamics":
        return dynamics()
    raise ValueError(f"unknown signal {name!r}; choose among {SIGNALS}")
