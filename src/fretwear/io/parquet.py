"""The Parquet reader and writer (pyarrow): a history as one float64 column per channel.

Layout written (and read back): one column per channel; field metadata ``units`` and
``description``; schema metadata ``fretwear`` = JSON ``{"name": ..., "metadata": ...}``. Read
whole (a file of one block: one table read) or by record batches (bounded memory). Split from
:mod:`fretwear.io.binary` (which re-exports :func:`open_parquet`, :func:`write_parquet` and
:data:`PARQUET_COMPRESSION`); :func:`_loads`, the fretwear JSON a file of any format stores,
is shared with the other binary readers.

pyarrow is optional (``pip install fretwear[formats]``); it is imported only when a Parquet
file is read or written.
"""

from __future__ import annotations

import inspect
import json
import os
import sys
from collections import OrderedDict
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from fretwear._optional import require
from fretwear.errors import FormatError, InputError
from fretwear.history import DESCRIPTIONS, UNITS, ContactHistory
from fretwear.io.atomic import atomic_path
from fretwear.io.channels import Source
from fretwear.io.readahead import read_ahead


def _loads(text: str | None) -> dict:
    """The dict of fretwear JSON a file stores (its name, metadata, units), the keys the readers
    take dropped when of the wrong type; ``{}`` for no text, bad JSON or not an object."""
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


#: Names, units, fretwear metadata and flatness of recent Arrow schemas, by the footer's
#: key-value metadata (its stored ``ARROW:schema``) and the Parquet schema's column paths:
#: ``schema_arrow`` decodes it at every call (50-60 µs, a sixth of a 1 000-sample file's open
#: and read), and the files of a bundle share it (issue 28).
_SCHEMAS: OrderedDict[tuple, tuple] = OrderedDict()


def _schema_of(reader) -> tuple[list[str], dict[int, bytes], bytes, bool]:
    """Column names, ``{position: unit}``, ``fretwear`` metadata (bytes: decoded by the caller)
    of an open ``pyarrow.parquet.ParquetReader``'s Arrow schema, and whether that schema is
    flat (one Parquet column a field, in order: a field's position is its column index).

    The names are the Parquet schema's (its column paths), the units and the fretwear metadata
    come from the footer's key-value metadata (the stored Arrow schema): remembered by both
    (:data:`_SCHEMAS`). The paths, not ``metadata.schema``: that object costs a file 8-10 µs
    (a reference cycle with the file's metadata, freed by the garbage collector), a tenth of
    a 1 000-sample file's read (issue 28). The column types are not remembered: the reader
    converts each column read by its own type (:func:`_float_array`)."""
    meta = reader.metadata
    kv = meta.metadata
    paths = reader.column_paths
    key = None if kv is None else (tuple(kv.items()), tuple(map(tuple, paths)))
    cached = None if key is None else _SCHEMAS.get(key)
    if cached is not None:
        return list(cached[0]), dict(cached[1]), cached[2], cached[3]
    schema = reader.schema_arrow
    units = {i: f.metadata[b"units"] for i, f in enumerate(schema)
             if f.metadata and b"units" in f.metadata}
    stored = (schema.metadata or {}).get(b"fretwear", b"")
    flat = len(paths) == len(schema) and all([n] == p for n, p in zip(schema.names, paths,
                                                                      strict=True))
    if key is not None:
        if len(_SCHEMAS) >= 16:
            _SCHEMAS.popitem(last=False)  # the oldest (one call: safe beside other threads)
        _SCHEMAS[key] = (tuple(schema.names), dict(units), stored, flat)
    return list(schema.names), units, stored, flat


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
        names, unit_bytes, stored_bytes, _ = _schema_of(first.reader)
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


def read_known_block(path: str | os.PathLike, size: int, positions_of
                     ) -> tuple[list[str], dict[int, str], dict, list[np.ndarray]] | None:
    """The lean read of a Parquet file of 2 to ``size`` rows (one block): its column names,
    ``{position: unit}``, stored fretwear metadata and the float64 columns at
    ``positions_of(names, units)``; None when the file has another number of rows or
    ``positions_of`` returns None (an unknown layout). The values :func:`open_parquet`'s
    ``iter_blocks`` gives for the same file (one table read, the same conversion), without its
    Source, generators and error guards: any failure here raises pyarrow's own exception,
    and the caller (:func:`fretwear.io.streaming.iter_history_blocks`) then reads the file
    through the full path, which names the culprit.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0])
    >>> p = write_parquet(h, pathlib.Path(tempfile.mkdtemp()) / "h.parquet")
    >>> names, units, stored, arrays = read_known_block(p, 10, lambda n, u: [1])
    >>> names[1], units[1], arrays[0].tolist()
    ('normal_force', 'N', [2.0, 3.0])
    >>> read_known_block(p, 1, lambda n, u: [1]) is None   # more rows than a block
    True
    """
    pa, pq, options = _pyarrow_modules()
    with pa.OSFile(os.fspath(path)) as stream:
        # pyarrow's reader itself, opened as ParquetFile(stream, pre_buffer=False) opens it,
        # without ParquetFile's Python around it (its source resolution, a map of the nested
        # column paths, the columns looked up by name: 5 µs of a 75 µs read, issue 28)
        reader = pq.ParquetReader()
        try:
            reader.open(stream, **options)
            rows = reader.metadata.num_rows
            if not 2 <= rows <= size:
                return None
            names, unit_bytes, stored_bytes, flat = _schema_of(reader)
            units = {i: unit.decode("utf-8") for i, unit in unit_bytes.items()}
            positions = positions_of(names, units)
            if positions is None or not flat:
                return None
            threads = (rows * len(positions) >= _THREADED_VALUES and pa.cpu_count() > 1)
            # a flat schema's field positions are its column indices
            table = reader.read_all(column_indices=positions, use_threads=threads)
        finally:
            reader.close()
    arrays = [_float_array(_one_chunk(table.column(i))) for i in range(len(positions))]
    return names, units, _loads(stored_bytes.decode("utf-8")), arrays


def _pyarrow_modules():
    """pyarrow, pyarrow.parquet (as :func:`require` gives them, from ``sys.modules`` once
    imported: ``require``'s ``import_module`` costs 2-3 µs a call, issue 28) and the options
    of ``ParquetReader.open`` that ``ParquetFile(source, pre_buffer=False)`` passes (but for
    their defaults): no pre-buffering, and ParquetFile's own default of the Arrow extension
    types where this pyarrow has them (the reader's default differs)."""
    global _OPEN_OPTIONS
    pa, pq = sys.modules.get("pyarrow"), sys.modules.get("pyarrow.parquet")
    if pa is None or pq is None:
        pq = require("pyarrow.parquet", purpose="reading Parquet")
        pa = require("pyarrow")
    if _OPEN_OPTIONS is None:
        extensions = inspect.signature(pq.ParquetFile).parameters.get("arrow_extensions_enabled")
        _OPEN_OPTIONS = {"pre_buffer": False} | (
            {} if extensions is None else {"arrow_extensions_enabled": extensions.default})
    return pa, pq, _OPEN_OPTIONS


_OPEN_OPTIONS: dict | None = None


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
