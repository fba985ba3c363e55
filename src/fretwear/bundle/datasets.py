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
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from fretwear._optional import require as _require
from fretwear.errors import FormatError

CONTACT_DIM = "contact"


def require(module: str, purpose: str = "the bundle runner"):
    """Import an optional dependency, or a MissingDependencyError naming the extra to install
    (``fretwear[bundle]`` for dask, distributed, xarray, zarr)."""
    return _require(module, purpose=purpose)


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


def cached_store(path: str):
    """The store at ``path`` opened once per worker process (reopened when it changed)."""
    from fretwear.bundle.cases import path_stamp

    return _cached_store(path, path_stamp(path))


def _time_dim(ds, label: str) -> str:
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


def rows_from_dataset(ds, path: Path | None, label: str) -> list:
    """The :class:`~fretwear.bundle.manifest.ContactRow` of every contact of a Dataset/store."""
    from fretwear.bundle.manifest import (
        PATH_KEYS,
        WALL_COLUMN,
        ContactRow,
        HistoryRef,
        _absolute,
        _identity_value,
        _missing,
        _plain,
        _wall,
        column_key,
    )

    if ds is None:
        ds = open_store(path)
    tdim = _time_dim(ds, label)
    channels = channel_variables(ds, tdim)
    n = ds.sizes[CONTACT_DIM]
    if CONTACT_DIM in ds.coords:
        ids = [str(_identity_value(v)) for v in ds[CONTACT_DIM].values]
    else:
        ids = [f"c{i}" for i in range(n)]
    columns = {}
    for name, var in ds.variables.items():
        if name == CONTACT_DIM or var.dims != (CONTACT_DIM,):
            continue
        columns[str(name)] = (column_key(str(name), label), var.values)
    units = {c: str(ds[c].attrs["units"]) for c in channels if "units" in ds[c].attrs}
    if "time" in ds.coords and ds["time"].dims == (tdim,) and "time" not in channels:
        shared_time = np.asarray(ds["time"].values, dtype=float)
        if "units" in ds["time"].attrs:
            units["time"] = str(ds["time"].attrs["units"])
    else:
        shared_time = None
    directory = Path.cwd() if path is None else path.parent
    rows = []
    for i, cid in enumerate(ids):
        identity: dict[str, Any] = {}
        overrides: dict[tuple[str, ...], Any] = {}
        wall = None
        for key, values in columns.values():
            value = values[i]
            if _missing(value) or key in ("contact", "history"):
                continue
            if key == WALL_COLUMN:
                wall = _wall(value, cid, label)
            elif isinstance(key, str):
                identity[key] = _identity_value(value)
            else:
                value = _plain(value)
                overrides[key] = _absolute(value, directory) if key in PATH_KEYS else value
        if path is None:
            arrays = {c: np.asarray(ds[c].isel({CONTACT_DIM: i}).values, dtype=float)
                      for c in channels}
            if shared_time is not None:
                arrays["time"] = shared_time
            ref = HistoryRef("memory", arrays=_trim(arrays), units=units, time_dim=tdim)
        else:
            ref = HistoryRef("store", path=str(path), index=i, units=units, time_dim=tdim)
        identity.setdefault("node", None)
        rows.append(ContactRow(cid, ref, identity, overrides, wall))
    from fretwear.bundle.manifest import _check_unique

    _check_unique(ids, label)
    return rows


def _trim(arrays: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Drop the NaN padding at the end of a contact shorter than the store's time axis."""
    t = arrays.get("time")
    if t is None or t.size == 0 or np.isfinite(t[-1]):
        return arrays
    finite = np.flatnonzero(np.isfinite(t))
    stop = 0 if finite.size == 0 else int(finite[-1]) + 1
    return {k: v[:stop] for k, v in arrays.items()}


def store_arrays(ref, start: int = 0, stop: int | None = None) -> dict[str, np.ndarray]:
    """``{variable: samples [start, stop)}`` of one contact of a store (only that part is read)."""
    ds = cached_store(ref.path)
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
    return _trim(arrays)


def store_length(ref) -> int:
    """Number of samples of one contact of a store (its time axis without NaN padding)."""
    ds = cached_store(ref.path)
    tdim = ref.time_dim
    if "time" in ds.variables and ds["time"].ndim == 2:
        t = np.asarray(ds["time"].isel({CONTACT_DIM: ref.index}).values, dtype=float)
        return int(np.flatnonzero(np.isfinite(t))[-1]) + 1 if np.isfinite(t).any() else 0
    return int(ds.sizes[tdim])


def frame_of(arrays: dict[str, np.ndarray]) -> pd.DataFrame:
    """The arrays of one contact as a table (columns in the store's order)."""
    return pd.DataFrame(arrays)
