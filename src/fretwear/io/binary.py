"""Binary formats: Parquet (pyarrow), HDF5 (h5py), NetCDF (netCDF4) and NumPy ``.npz``.

Layouts written (and read back):

* Parquet: one column per channel; field metadata ``units`` and ``description``; schema
  metadata ``fretwear`` = JSON ``{"name": ..., "metadata": ...}``. Read by row groups/batches.
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
from collections import OrderedDict
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._optional import require
from fretwear.errors import FormatError, InputError
from fretwear.history import DESCRIPTIONS, UNITS, ContactHistory
from fretwear.io.atomic import atomic_path, atomic_write
from fretwear.io.channels import Source, check_lengths
from fretwear.io.guard import probe
from fretwear.io.readahead import read_ahead

_NPZ_META = "__fretwear__"


def _decode(value: Any) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray):
        return str(value.item() if value.size == 1 else value.tolist())
    return str(value)


def _json_meta(history: ContactHistory) -> str:
    return json.dumps(dict(history.metadata), default=str)


def _loads(text: str | None) -> dict:
    if not text:
        return {}
    try:
        value = json.loads(text)
    except json.JSONDecodeError:
        return {}
    if not isinstance(value, dict):
        return {}
    # what the readers take from it, of the right type or dropped (a file written elsewhere
    # may hold anything under these keys: a list as metadata raised a TypeError)
    types = {"metadata": dict, "units": dict, "name": str}
    return {k: v for k, v in value.items() if k not in types or isinstance(v, types[k])}


# --------------------------------------------------------------------------- Parquet
#: float64, as numpy's frombuffer takes it at once (``dtype=np.float64`` costs it 1.5 µs a call
#: to convert: a tenth of a 1 000-sample Parquet block's six columns, issue 28).
_FLOAT64 = np.dtype(np.float64)


def _float_array(column) -> np.ndarray:
    """A pyarrow column as a float64 array: a float64 column without nulls is viewed in place
    (its values buffer, no copy; pyarrow's own ``to_numpy`` would also import pandas, 0.2 s),
    another is converted.

    Examples
    --------
    >>> import pyarrow as pa
    >>> column = pa.array([0.5, 1.5, 2.5]).slice(1)
    >>> _float_array(column).tolist(), _float_array(pa.array([1, None])).tolist()
    ([1.5, 2.5], [1.0, nan])
    """
    if column.null_count == 0 and str(column.type) == "double":
        values = np.frombuffer(column.buffers()[1], _FLOAT64, len(column), column.offset * 8)
        values.flags.writeable = False  # pyarrow's memory, as its to_numpy hands it out
        return values
    return column.to_numpy(zero_copy_only=False).astype(float, copy=False)


#: Values (rows × columns) from which a Parquet block is decoded on pyarrow's threads, when it
#: has more than one (measured, 6 float64 columns: below 5e4 rows the threads' hand-off costs
#: more than they save, 0.19 against 0.08 ms for 2 000 rows; a Dask worker has one thread).
_THREADED_VALUES = 1 << 18


def _one_chunk(column):
    """A pyarrow ChunkedArray as one Array (its chunks joined when there are several, as a file
    of several row groups gives them; none: an empty array of its type)."""
    if column.num_chunks == 1:
        return column.chunk(0)
    return column.combine_chunks()


#: Names, units and fretwear metadata of recent Arrow schemas, by the footer's key-value metadata
#: (its stored ``ARROW:schema``): ``schema_arrow`` decodes it at every call (50-60 µs, a sixth
#: of a 1 000-sample file's open and read), and the files of a bundle share it (issue 28).
_SCHEMAS: OrderedDict[tuple, tuple] = OrderedDict()


def _schema_of(handle) -> tuple[list[str], dict[int, bytes], bytes]:
    """Column names, ``{position: unit}`` and ``fretwear`` metadata (bytes: decoded by the
    caller) of an open ParquetFile's Arrow schema: a function of its Parquet schema and
    key-value metadata (pyarrow's conversion), remembered by both (:data:`_SCHEMAS`)."""
    kv, parquet_schema = handle.metadata.metadata, handle.metadata.schema
    key = None if kv is None else tuple(kv.items())
    cached = None if key is None else _SCHEMAS.get(key)
    if cached is not None and cached[0].equals(parquet_schema):
        return list(cached[1]), dict(cached[2]), cached[3]
    schema = handle.schema_arrow
    units = {i: f.metadata[b"units"] for i, f in enumerate(schema)
             if f.metadata and b"units" in f.metadata}
    stored = (schema.metadata or {}).get(b"fretwear", b"")
    if key is not None:
        if len(_SCHEMAS) >= 16:
            _SCHEMAS.popitem(last=False)  # the oldest (one call: safe beside other threads)
        _SCHEMAS[key] = (parquet_schema, tuple(schema.names), dict(units), stored)
    return list(schema.names), units, stored


def open_parquet(path: str | os.PathLike) -> Source:
    """Open a Parquet file; columns are read whole or by record batches (bounded memory).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0])
    >>> p = write_parquet(h, pathlib.Path(tempfile.mkdtemp()) / "h.parquet")
    >>> src = open_parquet(p)
    >>> src.columns, src.units[1], src.read([1])[0].tolist()
    (['time', 'normal_force', 'vt1', 'vt2'], 'N', [2.0, 3.0])
    """
    pq = require("pyarrow.parquet", purpose="reading Parquet")
    path = Path(path)
    stream = None
    try:
        # opened once: its schema here, its blocks by the first iter_blocks (a bundle opens
        # 10^5 small files: pq.read_schema then a second ParquetFile cost two opens and two
        # footer parses a file, a sixth of the wear power of a 1 000-sample file); from a
        # pyarrow file rather than a path, whose filesystem pyarrow would resolve again
        # (20 µs of a 1 000-sample file's 220 µs open and read, issue 28)
        stream = require("pyarrow").OSFile(str(path))
        first = pq.ParquetFile(stream, pre_buffer=False)
        names, unit_bytes, stored_bytes = _schema_of(first)
    except Exception as exc:  # pyarrow raises ArrowInvalid / OSError
        if stream is not None:
            stream.close()
        raise FormatError(f"{path}: not a readable Parquet file ({exc})") from None
    opened = [(first, stream)]
    units = {i: unit.decode("utf-8") for i, unit in unit_bytes.items()}
    stored = _loads(stored_bytes.decode("utf-8"))

    def read(positions: list[int]) -> list[np.ndarray]:
        table = pq.read_table(path, columns=[names[p] for p in positions])
        return [table.column(i).to_numpy().astype(float, copy=False) for i in range(len(positions))]

    def iter_blocks(positions: list[int], size: int) -> Iterator[list[np.ndarray]]:
        # no pre-buffering: pyarrow would otherwise cache every row group it is asked for
        # (measured: the whole 320 MB file); a file of one block is read unbuffered (one read
        # a column chunk, no longer than the chunk), a longer one through a 1 MiB read buffer
        # that keeps memory at O(chunk)
        handle, stream = opened.pop() if opened else (
            pq.ParquetFile(str(path), pre_buffer=False), None)
        if handle.metadata.num_rows <= size:  # one block: nothing to overlap
            return whole(handle, stream, positions)
        handle.close()
        if stream is not None:
            stream.close()
        handle = pq.ParquetFile(path, pre_buffer=False, buffer_size=1 << 20)
        # the next batch is decoded in a thread while the caller reduces this one (pyarrow
        # releases the GIL): decoding and reduction overlap; memory stays O(chunk)
        return read_ahead(batches(handle, positions, size))

    def whole(handle, stream, positions: list[int]) -> Iterator[list[np.ndarray]]:
        # a file of one block read as a table, each column chunk in one read: the values
        # iter_batches gives, without its record-batch reader (a 1e5-sample file of 6 channels
        # on one thread: 1.1 ms against 1.4 ms); on pyarrow's threads only when it has several
        # and the block is large (_THREADED_VALUES)
        threads = (handle.metadata.num_rows * len(positions) >= _THREADED_VALUES
                   and require("pyarrow").cpu_count() > 1)
        try:
            table = handle.read(columns=[names[p] for p in positions], use_threads=threads)
        finally:
            handle.close()
            if stream is not None:  # the file open_parquet opened (the handle leaves it open)
                stream.close()
        yield [_float_array(_one_chunk(table.column(i))) for i in range(len(positions))]

    def batches(handle, positions: list[int], size: int) -> Iterator[list[np.ndarray]]:
        try:
            wanted = [names[p] for p in positions]
            for batch in handle.iter_batches(batch_size=size, columns=wanted):
                yield [_float_array(batch.column(i)) for i in range(len(positions))]
        finally:
            handle.close()

    def ends(position: int) -> tuple[float, float]:
        # the row groups' statistics (min of the first, max of the last: the ends of an
        # increasing column), else the values at both ends of those two row groups
        handle = pq.ParquetFile(path)
        try:
            meta = handle.metadata
            if meta.num_rows == 0:
                raise FormatError(f"{path}: no data rows")
            first_rg, last_rg = 0, meta.num_row_groups - 1
            while meta.row_group(first_rg).num_rows == 0:
                first_rg += 1
            while meta.row_group(last_rg).num_rows == 0:
                last_rg -= 1
            stats = [meta.row_group(k).column(position).statistics for k in (first_rg, last_rg)]
            if all(st is not None and st.has_min_max for st in stats):
                return float(stats[0].min), float(stats[1].max)
            column = [names[position]]
            head = handle.read_row_group(first_rg, columns=column).column(0)
            tail = handle.read_row_group(last_rg, columns=column).column(0)
            return float(head[0].as_py()), float(tail[len(tail) - 1].as_py())
        finally:
            handle.close()

    return Source(label=str(path), format="parquet", columns=names, read=read, units=units,
                  name=stored.get("name"), metadata=stored.get("metadata", {}),
                  iter_blocks=iter_blocks, ends=ends)


#: Parquet compression of the histories fretwear writes (LZ4_RAW: read by pyarrow >= 9,
#: DuckDB, Spark >= 3.4, polars; measured on a 1e5-sample history of 6 channels: 4.1 MB read in
#: 1.1 ms, against 5.2 MB in 3.0 ms with pyarrow's default Snappy and dictionary pages).
PARQUET_COMPRESSION = "lz4"
_PARQUET_CODECS = ("lz4", "snappy", "zstd", "gzip", "brotli", "none")


def write_parquet(history: ContactHistory, path: str | os.PathLike, *,
                  row_group_size: int | None = None,
                  compression: str | None = PARQUET_COMPRESSION) -> Path:
    """Write a history as Parquet, units in each field's metadata (atomic).

    Parameters
    ----------
    history : ContactHistory
        The history (SI units: time [s], forces [N], velocities [m/s], displacements [m]).
    path : path-like
        Output file.
    row_group_size : int, optional
        Rows per row group (pyarrow's default, 1 Mi rows, when None); chunked reading decodes
        one row group at a time.
    compression : str or None
        Parquet codec of every column: ``"lz4"`` (default, LZ4_RAW), ``"snappy"`` (pyarrow's
        default, for older readers), ``"zstd"`` (smallest file, slowest to read), ``"gzip"``,
        ``"brotli"`` or None (uncompressed). Values are written as plain float64 pages without
        dictionary encoding (the samples of a signal seldom repeat: a dictionary makes the
        file larger and slower to read). The values read back are the same whatever the codec.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib, pyarrow.parquet as pq
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0])
    >>> p = write_parquet(h, pathlib.Path(tempfile.mkdtemp()) / "h.parquet")
    >>> pq.read_schema(p).field("vt1").metadata[b"units"]
    b'm/s'
    """
    pa = require("pyarrow", purpose="writing Parquet")
    pq = require("pyarrow.parquet", purpose="writing Parquet")
    codec = "none" if compression is None else str(compression).lower()
    if codec not in _PARQUET_CODECS or (codec != "none" and not pa.Codec.is_available(codec)):
        raise InputError(f"write_parquet: compression={compression!r} is not a Parquet codec "
                         "this pyarrow can write; give 'lz4', 'snappy', 'zstd', 'gzip', "
                         "'brotli' or None (uncompressed)")
    fields = [pa.field(ch, pa.float64(), metadata={"units": UNITS[ch],
                                                   "description": DESCRIPTIONS[ch]})
              for ch in history.channels]
    schema = pa.schema(fields, metadata={"fretwear": json.dumps(
        {"name": history.name, "metadata": dict(history.metadata)}, default=str)})
    table = pa.Table.from_arrays([pa.array(np.asarray(getattr(history, ch)))
                                  for ch in history.channels], schema=schema)
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp, row_group_size=row_group_size, use_dictionary=False,
                       compression=codec)
    return Path(path)


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
