"""Binary formats: Parquet (pyarrow), HDF5 (h5py), NetCDF (netCDF4) and NumPy ``.npz``.

Layouts written (and read back):

* Parquet: :mod:`fretwear.io.parquet` (its reader and writer re-exported here).
* HDF5: a group (default ``/history``) holding one 1-D dataset per channel with attributes
  ``units`` and ``description``; group attributes ``name`` and ``metadata`` (JSON). Read by slices.
* NetCDF: dimension ``time``, a variable per channel with ``units`` and ``long_name``; global
  attributes ``title`` (the name) and ``fretwear_metadata`` (JSON).
* NPZ: one array per channel plus ``__fretwear__``, a JSON string with name, metadata, units.

pyarrow, h5py and netCDF4 are optional (``pip install fretwear[formats]``); they are imported
only when a file of theirs is read or written.
"""

from __future__ import annotations

import json
import os
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._optional import require
from fretwear.errors import FormatError
from fretwear.history import DESCRIPTIONS, UNITS, ContactHistory
from fretwear.io.atomic import atomic_path, atomic_write
from fretwear.io.channels import Source, check_lengths
from fretwear.io.guard import probe
from fretwear.io.parquet import PARQUET_COMPRESSION, _loads, open_parquet, write_parquet

__all__ = ["open_parquet", "write_parquet", "PARQUET_COMPRESSION", "open_hdf5", "write_hdf5",
           "open_netcdf", "write_netcdf", "open_npz", "npz_headers", "write_npz"]

_NPZ_META = "__fretwear__"


def _decode(value: Any) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray):
        return str(value.item() if value.size == 1 else value.tolist())
    return str(value)


def _json_meta(history: ContactHistory) -> str:
    return json.dumps(dict(history.metadata), default=str)


# --------------------------------------------------------------------------- HDF5
def _find_group(h5: Any, handle: Any, group: str | None, path: Path) -> Any:
    if group is not None:
        group = str(group)  # a numeric group name typed on the command line
        if group not in handle or not isinstance(handle[group], h5.Group):
            raise FormatError(f"{path}: no group {group!r}; groups: {_groups(h5, handle)}")
        return handle[group]
    candidates = [g for g in [handle, *_all_groups(h5, handle)]
                  if any(isinstance(v, h5.Dataset) and v.ndim == 1 for v in g.values())]
    if len(candidates) == 1:
        return candidates[0]
    if not candidates:
        raise FormatError(f"{path}: no group holds 1-D datasets (one per channel)")
    raise FormatError(f"{path}: several groups hold 1-D datasets "
                      f"{[g.name for g in candidates]}; choose one with group='<name>' "
                      "(command line: --read-option group=<name>)")


def _all_groups(h5: Any, handle: Any) -> list:
    found: list = []
    handle.visititems(lambda _, obj: found.append(obj) if isinstance(obj, h5.Group) else None)
    return found


def _groups(h5: Any, handle: Any) -> list[str]:
    return ["/"] + [g.name for g in _all_groups(h5, handle)]


def open_hdf5(path: str | os.PathLike, *, group: str | None = None) -> Source:
    """Open an HDF5 file: one 1-D dataset per column in a group (found when unique).

    Parameters
    ----------
    path : path-like
    group : str, optional
        The group holding the datasets; default the only group that holds 1-D datasets.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0], name="N1")
    >>> p = write_hdf5(h, pathlib.Path(tempfile.mkdtemp()) / "h.h5")
    >>> src = open_hdf5(p)
    >>> src.name, src.columns, src.units[0]
    ('N1', ['time', 'normal_force', 'vt1', 'vt2'], 's')
    """
    h5 = require("h5py", purpose="reading HDF5")
    path = Path(path)
    probe(path, "hdf5")  # a damaged file crashes or hangs the C library: check it apart first
    try:
        handle = h5.File(path, "r")
    except OSError as exc:
        raise FormatError(f"{path}: not a readable HDF5 file ({exc})") from None
    with handle:
        grp = _find_group(h5, handle, group, path)
        gname = grp.name
        names = [k for k, v in grp.items() if isinstance(v, h5.Dataset) and v.ndim == 1]
        units = {i: _decode(grp[k].attrs["units"]) for i, k in enumerate(names)
                 if "units" in grp[k].attrs}
        name = _decode(grp.attrs["name"]) if "name" in grp.attrs else None
        meta = _loads(_decode(grp.attrs["metadata"])) if "metadata" in grp.attrs else {}

    def read(positions: list[int]) -> list[np.ndarray]:
        with h5.File(path, "r") as f:
            return [np.asarray(f[gname][names[p]][()], dtype=float) for p in positions]

    def iter_blocks(positions: list[int], size: int) -> Iterator[list[np.ndarray]]:
        with h5.File(path, "r") as f:
            datasets = [f[gname][names[p]] for p in positions]
            n = check_lengths([d.shape[0] for d in datasets], [names[p] for p in positions],
                              str(path))
            for start in range(0, n, size):
                yield [np.asarray(d[start:start + size], dtype=float) for d in datasets]

    def ends(position: int) -> tuple[float, float]:
        with h5.File(path, "r") as f:
            d = f[gname][names[position]]
            if d.shape[0] == 0:
                raise FormatError(f"{path}: no data rows")
            return float(d[0]), float(d[d.shape[0] - 1])

    return Source(label=str(path), format="hdf5", columns=names, read=read, units=units,
                  name=name, metadata=meta, iter_blocks=iter_blocks, ends=ends)


def write_hdf5(history: ContactHistory, path: str | os.PathLike, *,
               group: str = "history") -> Path:
    """Write a history as HDF5: a dataset per channel in ``group``, units as attributes (atomic).

    Parameters
    ----------
    history : ContactHistory
        The history (SI units: time [s], forces [N], velocities [m/s], displacements [m]).
    path : path-like
        Output file.
    group : str
        Group holding the datasets (created; ``"/"`` for the root).

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib, h5py
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0])
    >>> p = write_hdf5(h, pathlib.Path(tempfile.mkdtemp()) / "h.h5")
    >>> with h5py.File(p) as f:
    ...     print(list(f["history"]), f["history/normal_force"].attrs["units"])
    ['time', 'normal_force', 'vt1', 'vt2'] N
    """
    h5 = require("h5py", purpose="writing HDF5")
    with atomic_path(path) as tmp, h5.File(tmp, "w", track_order=True) as f:
        grp = f.create_group(group, track_order=True) if group not in ("", "/") else f
        grp.attrs["name"] = history.name
        grp.attrs["metadata"] = _json_meta(history)
        for ch in history.channels:
            ds = grp.create_dataset(ch, data=np.asarray(getattr(history, ch)))
            ds.attrs["units"] = UNITS[ch]
            ds.attrs["description"] = DESCRIPTIONS[ch]
    return Path(path)


# --------------------------------------------------------------------------- NetCDF
def open_netcdf(path: str | os.PathLike) -> Source:
    """Open a NetCDF file: the 1-D variables along the time dimension, ``units`` attributes.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0], name="N1")
    >>> p = write_netcdf(h, pathlib.Path(tempfile.mkdtemp()) / "h.nc")
    >>> src = open_netcdf(p)
    >>> src.name, src.columns, src.units[3]
    ('N1', ['time', 'normal_force', 'vt1', 'vt2'], 'm/s')
    """
    nc = require("netCDF4", purpose="reading NetCDF")
    path = Path(path)
    probe(path, "netcdf")  # a damaged file crashes or hangs the C library: check it apart first
    try:
        ds = nc.Dataset(path, "r")
    except OSError as exc:
        raise FormatError(f"{path}: not a readable NetCDF file ({exc})") from None
    with ds:
        one_d = {k: v for k, v in ds.variables.items() if v.ndim == 1}
        dims = {v.dimensions[0] for v in one_d.values()}
        if "time" in dims:
            dim = "time"
        elif len(dims) == 1:
            dim = dims.pop()
        else:
            raise FormatError(f"{path}: 1-D variables along several dimensions {sorted(dims)} "
                              "and none is 'time'")
        names = [k for k, v in one_d.items() if v.dimensions[0] == dim]
        units = {i: str(one_d[k].getncattr("units")) for i, k in enumerate(names)
                 if "units" in one_d[k].ncattrs()}
        attrs = ds.ncattrs()
        name = str(ds.getncattr("title")) if "title" in attrs else None
        meta = (_loads(str(ds.getncattr("fretwear_metadata")))
                if "fretwear_metadata" in attrs else {})

    def _values(var: Any, sl: slice) -> np.ndarray:
        return np.ma.filled(np.ma.asarray(var[sl], dtype=float), np.nan)

    def read(positions: list[int]) -> list[np.ndarray]:
        with nc.Dataset(path, "r") as f:
            return [_values(f.variables[names[p]], slice(None)) for p in positions]

    def iter_blocks(positions: list[int], size: int) -> Iterator[list[np.ndarray]]:
        with nc.Dataset(path, "r") as f:
            n = len(f.dimensions[dim])
            for start in range(0, n, size):
                yield [_values(f.variables[names[p]], slice(start, start + size))
                       for p in positions]

    def ends(position: int) -> tuple[float, float]:
        with nc.Dataset(path, "r") as f:
            n = len(f.dimensions[dim])
            if n == 0:
                raise FormatError(f"{path}: no data rows")
            var = f.variables[names[position]]
            return (float(_values(var, slice(0, 1))[0]),
                    float(_values(var, slice(n - 1, n))[0]))

    return Source(label=str(path), format="netcdf", columns=names, read=read, units=units,
                  name=name, metadata=meta, iter_blocks=iter_blocks, ends=ends)


def write_netcdf(history: ContactHistory, path: str | os.PathLike) -> Path:
    """Write a history as NetCDF-4: dimension ``time``, one variable per channel with ``units``.

    Parameters
    ----------
    history : ContactHistory
        The history (SI units: time [s], forces [N], velocities [m/s], displacements [m]).
    path : path-like
        Output file (atomic).

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib, netCDF4
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0])
    >>> p = write_netcdf(h, pathlib.Path(tempfile.mkdtemp()) / "h.nc")
    >>> with netCDF4.Dataset(p) as ds:
    ...     print(ds.variables["time"].units, ds.dimensions["time"].size)
    s 2
    """
    nc = require("netCDF4", purpose="writing NetCDF")
    with atomic_path(path) as tmp:
        with nc.Dataset(tmp, "w", format="NETCDF4") as ds:
            ds.createDimension("time", len(history))
            ds.setncattr("title", history.name)
            ds.setncattr("fretwear_metadata", _json_meta(history))
            ds.setncattr("Conventions", "CF-1.8")
            for ch in history.channels:
                var = ds.createVariable(ch, "f8", ("time",))
                var.setncattr("units", UNITS[ch])
                var.setncattr("long_name", DESCRIPTIONS[ch])
                var[:] = np.asarray(getattr(history, ch))
    return Path(path)


# --------------------------------------------------------------------------- NPZ
def open_npz(path: str | os.PathLike) -> Source:
    """Open a NumPy ``.npz`` archive: every 1-D array is a column (whole reads only).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.npz"
    >>> np.savez(p, INST=[0.0, 1.0], FN=[1.0, 2.0])
    >>> open_npz(p).columns
    ['INST', 'FN']
    """
    path = Path(path)
    headers = npz_headers(path)  # shapes and types only: no array is decompressed here
    names = [k for k, (shape, _) in headers.items() if k != _NPZ_META and len(shape) == 1]
    stored: dict = {}
    if _NPZ_META in headers and headers[_NPZ_META][1].kind == "U":
        with np.load(path, allow_pickle=False) as archive:
            stored = _loads(str(archive[_NPZ_META]))
    units = {i: stored["units"][k] for i, k in enumerate(names)
             if isinstance(stored.get("units"), dict) and k in stored["units"]}

    def read(positions: list[int]) -> list[np.ndarray]:
        for p in positions:
            kind = headers[names[p]][1]
            if kind.kind not in "biuf":
                raise FormatError(f"{path}: array {names[p]!r} holds {kind} values, not numbers "
                                  "(object arrays are never unpickled); save float arrays")
        with np.load(path, allow_pickle=False) as f:
            return [np.asarray(f[names[p]], dtype=float) for p in positions]

    return Source(label=str(path), format="npz", columns=names, read=read, units=units,
                  name=stored.get("name"), metadata=stored.get("metadata", {}))


def npz_headers(path: str | os.PathLike) -> dict[str, tuple[tuple[int, ...], np.dtype]]:
    """Shape and dtype of every array of an ``.npz`` archive, read from the ``.npy`` headers
    (nothing is decompressed beyond them).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.npz"
    >>> np.savez(p, INST=[0.0, 1.0], N=np.array(["a"]))
    >>> {k: (s, str(d)) for k, (s, d) in npz_headers(p).items()}
    {'INST': ((2,), 'float64'), 'N': ((1,), '<U1')}
    """
    out = {}
    with zipfile.ZipFile(path) as zf:
        for info in zf.infolist():
            if not info.filename.endswith(".npy"):
                continue
            with zf.open(info) as handle:
                version = np.lib.format.read_magic(handle)
                if version == (1, 0):
                    shape, _, dtype = np.lib.format.read_array_header_1_0(handle)
                elif version == (2, 0):
                    shape, _, dtype = np.lib.format.read_array_header_2_0(handle)
                else:  # (3, 0): a UTF-8 header, no public reader: load that one array
                    with np.load(path, allow_pickle=False) as archive:
                        array = archive[info.filename[:-4]]
                    shape, dtype = array.shape, array.dtype
            out[info.filename[:-4]] = (tuple(shape), np.dtype(dtype))
    return out


def write_npz(history: ContactHistory, path: str | os.PathLike) -> Path:
    """Write a history as ``.npz`` (one array per channel, plus a JSON ``__fretwear__`` entry).

    Parameters
    ----------
    history : ContactHistory
        The history (SI units: time [s], forces [N], velocities [m/s], displacements [m]).
    path : path-like
        Output file (atomic; no ``.npz`` is appended).

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0])
    >>> p = write_npz(h, pathlib.Path(tempfile.mkdtemp()) / "h.npz")
    >>> sorted(np.load(p).files)
    ['__fretwear__', 'normal_force', 'time', 'vt1', 'vt2']
    """
    meta = json.dumps({"name": history.name, "metadata": dict(history.metadata),
                       "units": {ch: UNITS[ch] for ch in history.channels}}, default=str)
    arrays = {ch: np.asarray(getattr(history, ch)) for ch in history.channels}
    with atomic_write(path, "wb") as handle:
        np.savez(handle, **arrays, **{_NPZ_META: np.array(meta)})
    return Path(path)
