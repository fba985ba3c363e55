"""Bundles held in one xarray Dataset or Zarr / NetCDF store: dimensions ``(contact, time)``.

Layout: one 2-D variable per channel along ``(contact, time)`` named as the columns of a history
file (``normal_force`` or ``FN``, ``vt1``, ``dy`` ...; see :mod:`fretwear.io.channels`), the
instants either a 1-D ``time`` coordinate shared by every contact or a 2-D ``time`` variable
(contacts of different lengths padded with NaN at the end). Units in each variable's ``units``
attribute (converted to SI like a file's declared units). 1-D variables or coordinates along
``contact`` are the manifest's other columns (``tube_row``, ``support``, case-key overrides such
as ``mobile_radius_m``); the ``contact`` coordinate gives the ids (else ``c0``, ``c1`` ...).
"""

from __future__ import annotations

import functools
import os
import stat
import warnings
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import require as _require
from fretwear.errors import FormatError

CONTACT_DIM = "contact"


def require(module: str, purpose: str = "the bundle runner"):
    """Import an optional dependency, or a MissingDependencyError naming the extra to install
    (``fretwear[bundle]`` for dask, distributed, xarray, zarr)."""
    return _require(module, purpose=purpose)


def path_stamp(path: str | os.PathLike) -> tuple:
    """What identifies a file's content cheaply: (size, modification time [ns]); for a
    directory (a Zarr store), the number of files, their total size and the latest time."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):  # a NUL byte in the name: the reader names it
        return ("missing",)
    if not stat.S_ISDIR(st.st_mode):  # one stat a file (the client stamps every contact)
        return (st.st_size, st.st_mtime_ns)
    count = size = 0
    latest = st.st_mtime_ns
    for root, _, files in os.walk(Path(path)):  # a Path for a store only (not per file)
        for f in files:
            s = os.stat(os.path.join(root, f))
            count, size, latest = count + 1, size + s.st_size, max(latest, s.st_mtime_ns)
    return (count, size, latest)


def open_store(path: str | os.PathLike):
    """Open a Zarr or NetCDF store lazily (nothing is read until sliced)."""
    xr = require("xarray")
    p = Path(path)
    is_zarr = p.suffix.lower() == ".zarr" or p.is_dir()
    if is_zarr:
        require("zarr")
    try:
        with warnings.catch_warnings():
            # a store without consolidated metadata is read all the same: not the user's concern
            warnings.filterwarnings("ignore", message=".*consolidated metadata.*")
            return xr.open_dataset(p, engine="zarr" if is_zarr else None,
                                   **({"chunks": None} if is_zarr else {}))
    except (OSError, ValueError, KeyError) as exc:
        raise FormatError(f"{p}: not a readable {'Zarr' if is_zarr else 'NetCDF'} store "
                          f"({exc})") from None


@functools.lru_cache(maxsize=4)
def _cached_store(path: str, stamp: tuple):
    return open_store(path)


def cached_store(ref):
    """The store of a :class:`~fretwear.bundle.manifest.HistoryRef`, opened once per process
    (reopened when its stamp, taken once when the manifest was read, changed)."""
    stamp = tuple(ref.stamp) if ref.stamp else path_stamp(ref.path)
    return _cached_store(ref.path, stamp)


def time_dim(ds, label: str) -> str:
    if CONTACT_DIM not in ds.dims:
        raise FormatError(f"{label}: a bundle Dataset needs a {CONTACT_DIM!r} dimension; "
                          f"dimensions found: {list(ds.dims)}")
    others = [d for d in ds.dims if d != CONTACT_DIM]
    if "time" in others:
        return "time"
    two_d = {d for v in ds.data_vars.values() if v.ndim == 2 and CONTACT_DIM in v.dims
             for d in v.dims if d != CONTACT_DIM}
    if len(two_d) != 1:
        raise FormatError(f"{label}: cannot tell the time dimension among {others}; name it "
                          "'time'")
    return two_d.pop()


def channel_variables(ds, time_dim: str) -> list[str]:
    """Names of the variables along (contact, time) (the channels, with a 2-D time)."""
    names = [n for n, v in ds.variables.items()
             if set(v.dims) == {CONTACT_DIM, time_dim}]
    if not names:
        raise FormatError(f"no variable along ({CONTACT_DIM}, {time_dim}): one variable per "
                          "channel is expected (normal_force, vt1, vt2, ...)")
    return names


def trim(arrays: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Drop the NaN padding at the end of a contact shorter than the store's time axis."""
    t = arrays.get("time")
    if t is None or t.size == 0 or np.isfinite(t[-1]):
        return arrays
    finite = np.flatnonzero(np.isfinite(t))
    stop = 0 if finite.size == 0 else int(finite[-1]) + 1
    return {k: v[:stop] for k, v in arrays.items()}


def store_arrays(ref, start: int = 0, stop: int | None = None) -> dict[str, np.ndarray]:
    """``{variable: samples [start, stop)}`` of one contact of a store (only that part is read)."""
    ds = cached_store(ref)
    tdim = ref.time_dim
    channels = channel_variables(ds, tdim)
    sel = {CONTACT_DIM: ref.index, tdim: slice(start, stop)}
    arrays = {c: np.asarray(ds[c].isel(sel).values, dtype=float) for c in channels}
    if "time" not in arrays:
        if "time" not in ds.coords:
            raise FormatError(f"{ref.path}: no 'time' coordinate or variable along "
                              f"({CONTACT_DIM}, {tdim})")
        arrays["time"] = np.asarray(ds["time"].isel({tdim: slice(start, stop)}).values,
                                    dtype=float)
    return trim(arrays)


def store_length(ref) -> int:
    """Number of samples of one contact of a store (its time axis without NaN padding)."""
    ds = cached_store(ref)
    tdim = ref.time_dim
    if "time" in ds.variables and ds["time"].ndim == 2:
        stamp = tuple(ref.stamp) if ref.stamp else path_stamp(ref.path)
        return int(_store_lengths(ref.path, stamp, tdim)[ref.index])
    return int(ds.sizes[tdim])


#: Samples of a 2-D ``time`` read at a time by :func:`_store_lengths` (32 MB of float64).
_LENGTH_SLAB = 1 << 22


@functools.lru_cache(maxsize=4)
def _store_lengths(path: str, stamp: tuple, tdim: str) -> np.ndarray:
    """Every contact's length in a store with a 2-D ``time`` (the last finite instant + 1, 0
    without one), read once, in slabs of whole rows: the client asked for each contact's row in
    turn, which for a Zarr store chunked across contacts (xarray's default chunks) decompressed
    whole chunks for one row (3.4 ms a contact, 17 s for 5 000 before any task started)."""
    ds = _cached_store(path, stamp)
    time = ds["time"].transpose(CONTACT_DIM, tdim)
    count, samples = time.shape
    lengths = np.zeros(count, dtype=np.int64)
    if samples == 0:
        return lengths
    step = max(1, _LENGTH_SLAB // samples)
    for a in range(0, count, step):
        finite = np.isfinite(np.asarray(time.isel({CONTACT_DIM: slice(a, a + step)}).values,
                                        dtype=float))
        last = samples - np.argmax(finite[:, ::-1], axis=1)
        lengths[a:a + step] = np.where(finite.any(axis=1), last, 0)
    return lengths


def frame_of(arrays: dict[str, np.ndarray]) -> pd.DataFrame:
    """The arrays of one contact as a table (columns in the store's order)."""
    return pd.DataFrame(arrays)
