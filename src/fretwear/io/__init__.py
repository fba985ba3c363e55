"""Reading and writing contact histories (theory §1): CSV, Parquet, HDF5, NetCDF, NPZ, Code_Aster.

``read_history`` opens a file in any supported format, maps its columns to the channels of a
:class:`~fretwear.history.ContactHistory` through case-insensitive aliases (Code_Aster's INST,
FN, VINT1 ...), converts units to SI and validates. ``iter_history_chunks`` does the same chunk by
chunk with bounded memory. ``write_history`` writes the native formats. The families of formats
are the explicit registry :data:`FORMATS`; see ``docs/formats.md`` for the layouts.
"""

from __future__ import annotations

import gzip
import os
import zipfile
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from fretwear._optional import optional
from fretwear.errors import FormatError, InputError, KeywordError
from fretwear.history import CHANNELS, DEFAULT_CHUNK_SIZE, ContactHistory
from fretwear.io import aster as _aster
from fretwear.io import binary as _binary
from fretwear.io import delimited as _delimited
from fretwear.io.aster_source import open_aster as _open_aster
from fretwear.io.aster_source import open_functions as _open_functions
from fretwear.io.channels import (
    ALIASES,
    Source,
    build_history,
    channel_of,
    check_lengths,
    fast_history,
    resolve_columns,
    resolve_units,
)
from fretwear.io.guard import HDF5_MAGIC, probe, readable_file, reading, warn_whole_read
from fretwear.io.plausibility import StreamPlausibility, check_plausibility

__all__ = ["FORMATS", "ALIASES", "FileFormat", "read_history", "write_history",
           "iter_history_chunks", "guess_format", "open_source", "units_read"]

#: Code_Aster parameter names used when a history is written as a Code_Aster table.
ASTER_NAMES: Mapping[str, str] = MappingProxyType({
    "time": "INST", "normal_force": "FN", "ft1": "FT1", "ft2": "FT2", "vn": "VN", "vt1": "VT1",
    "vt2": "VT2", "dy": "DYLOC", "dz": "DZLOC", "stick": "VINT13"})


def _write_aster(history: ContactHistory, path: str | os.PathLike, *,
                 table_format: str = "TABLEAU", float_format: str = "%.16E") -> Path:
    frame = history.to_frame().rename(columns=dict(ASTER_NAMES))
    return _aster.write_aster_table(frame, path, format=table_format, title=history.name or None,
                                    float_format=float_format)


@dataclass(frozen=True)
class FileFormat:
    """One family of files: suffixes, reader (``path, **options -> Source``), writer, options."""

    name: str
    suffixes: tuple[str, ...]
    open: Callable[..., Source]
    write: Callable[..., Path] | None
    read_options: tuple[str, ...]
    write_options: tuple[str, ...]
    description: str


#: The registry of formats, keyed by the names accepted by ``format=``.
FORMATS: Mapping[str, FileFormat] = MappingProxyType({
    "csv": FileFormat("csv", (".csv", ".txt", ".dat", ".tsv"), _delimited.open_csv,
                      _delimited.write_csv, ("delimiter", "decimal", "comment", "header",
                                             "encoding"), ("float_format", "delimiter"),
                      "delimited text (any delimiter, '#' comments, header guessed)"),
    "parquet": FileFormat("parquet", (".parquet", ".pq"), _binary.open_parquet,
                          _binary.write_parquet, (), ("row_group_size",),
                          "Apache Parquet (pyarrow), units in field metadata"),
    "hdf5": FileFormat("hdf5", (".h5", ".hdf5", ".hdf"), _binary.open_hdf5, _binary.write_hdf5,
                       ("group",), ("group",),
                       "HDF5 (h5py), one dataset per channel in a group, 'units' attributes"),
    "netcdf": FileFormat("netcdf", (".nc", ".nc4", ".cdf"), _binary.open_netcdf,
                         _binary.write_netcdf, (), (),
                         "NetCDF (netCDF4), dimension 'time', 'units' attributes"),
    "npz": FileFormat("npz", (".npz",), _binary.open_npz, _binary.write_npz, (), (),
                      "NumPy .npz archive, one array per channel"),
    "aster": FileFormat("aster", (".resu", ".tab", ".table"), _open_aster, _write_aster,
                        ("index", "title", "select", "node", "functions"),
                        ("table_format", "float_format"),
                        "Code_Aster IMPR_TABLE text table (FORMAT='TABLEAU' or 'ASTER') or "
                        "IMPR_FONCTION file"),
    "aster-function": FileFormat("aster-function", (), _open_functions, None, ("functions",),
                                 (), "Code_Aster IMPR_FONCTION TABLEAU files (functions of one "
                                     "history)"),
})

_FORMAT_ALIASES = {"h5": "hdf5", "hdf": "hdf5", "nc": "netcdf", "pq": "parquet", "txt": "csv",
                   "dat": "csv", "tsv": "csv", "tableau": "aster", "aster-table": "aster",
                   "impr_table": "aster", "impr_fonction": "aster-function",
                   "function": "aster-function", "aster_function": "aster-function"}


def _format_name(format: str) -> str:
    key = str(format).strip().lower().lstrip(".")
    key = _FORMAT_ALIASES.get(key, key)
    if key not in FORMATS:
        raise FormatError(f"unknown format {format!r}; known formats: {list(FORMATS)} "
                          f"(also {sorted(_FORMAT_ALIASES)})")
    return key


def guess_format(path: str | os.PathLike) -> str:
    """Name of a file's format, from its content (magic bytes, Code_Aster markers), else suffix.

    Binary formats are recognised by their signature whatever the suffix; a text file is a
    Code_Aster table when its content says so (whatever the suffix), else delimited text.

    Raises
    ------
    FormatError
        The content matches no known format (the message lists them).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (d / "a.txt").write_text("#DEBUT_TABLE\\n#TITRE x\\nINST\\nR\\n0.0\\n#FIN_TABLE\\n")
    >>> _ = (d / "b.out").write_text("t,fn,vt1,vt2\\n0,1,0,0\\n")
    >>> guess_format(d / "a.txt"), guess_format(d / "b.out")
    ('aster', 'csv')
    """
    path = readable_file(path, "history file")
    with reading(path, "history", "history file"), open(path, "rb") as handle:
        head = handle.read(65536)
    suffix = path.suffix.lower()
    if not head:
        raise FormatError(f"{path}: the file is empty")
    if head.startswith(b"PAR1"):
        return "parquet"
    if head.startswith(HDF5_MAGIC):
        if suffix in FORMATS["netcdf"].suffixes:
            return "netcdf"
        if optional("h5py") is None:
            return "hdf5"
        # the structure is walked in a child process: a damaged file cannot crash this one
        return "netcdf" if probe(path, "hdf5").get("netcdf") else "hdf5"
    if head[:4] in (b"CDF\x01", b"CDF\x02", b"CDF\x05"):
        return "netcdf"
    if head.startswith(b"PK\x03\x04"):
        with reading(path, "npz"), zipfile.ZipFile(path) as zf:
            if any(n.endswith(".npy") for n in zf.namelist()):
                return "npz"
        raise FormatError(f"{path}: a zip archive without .npy arrays; known formats: "
                          f"{list(FORMATS)}")
    if head.startswith(b"\x93NUMPY"):
        raise FormatError(f"{path}: a single .npy array has no column names; save the channels "
                          "with numpy.savez(path, time=..., normal_force=..., ...) instead")
    if head.startswith(_aster.GZIP_MAGIC):  # compressed text: CSV or a Code_Aster table
        with reading(path, "gzip-compressed text"), gzip.open(path, "rb") as handle:
            head = handle.read(65536)
        if not head:
            raise FormatError(f"{path}: the file is empty (once decompressed)")
    if head[:2] in _delimited.UTF16_BOMS:  # UTF-16 text (a spreadsheet's "Unicode text")
        return "aster" if _aster.looks_like_aster(head.decode("utf-16", errors="replace")) \
            else "csv"
    if b"\x00" in head:
        raise FormatError(f"{path}: binary content of no known format; known formats: "
                          f"{list(FORMATS)}; give format= if it is one of them")
    text = head.decode("utf-8-sig", errors="replace")  # a BOM is dropped
    if _aster.looks_like_aster(text):
        return "aster"
    return "csv"


def _is_path(value: Any) -> bool:
    return isinstance(value, (str, os.PathLike))


def _require_file(path: str | os.PathLike) -> None:
    readable_file(path, "history file")


def _guarded(source: Source, path: Any, format: str) -> Source:
    """``source`` whose column readers turn a damaged file's exceptions into fretwear errors."""
    read, blocks = source.read, source.iter_blocks

    def guarded_read(positions: list[int]) -> list[np.ndarray]:
        with reading(path, format, "history file"):
            return read(positions)

    def guarded_blocks(positions: list[int], size: int) -> Iterator[list[np.ndarray]]:
        with reading(path, format, "history file"):
            yield from blocks(positions, size)  # type: ignore[misc]

    source.read = guarded_read
    if blocks is not None:
        source.iter_blocks = guarded_blocks
    return source


def _frame_source(table: Any) -> Source:
    names = [str(c) for c in table.keys()]
    values = (list(table.values()) if isinstance(table, Mapping)
              else [table[c] for c in table.columns])
    return Source(label="<in-memory table>", format="frame", columns=names,
                  read=lambda positions: [np.asarray(values[p], dtype=float) for p in positions])


def open_source(path: Any, format: str | None = None, **options: Any) -> Source:
    """Open ``path`` with the reader of its format (given or guessed) as a :class:`Source`.

    ``path`` may also be a mapping ``{channel: file}`` or a list of IMPR_FONCTION files
    (format ``aster-function``), or an in-memory table (a DataFrame or a mapping of arrays).
    """
    if not _is_path(path):
        if isinstance(path, ContactHistory):
            raise InputError("got a ContactHistory where a file is expected: it is already read")
        is_table = hasattr(path, "columns") or (
            isinstance(path, Mapping) and not all(_is_path(v) for v in path.values()))
        if is_table:
            if options or format is not None:
                given = sorted(options) + ([] if format is None else ["format"])
                raise KeywordError(f"option(s) {given} do not apply to an in-memory table")
            return _frame_source(path)
        if not isinstance(path, (Mapping, list, tuple)):
            raise InputError(f"cannot read a history from a {type(path).__name__}; give a file "
                             "path, a list or mapping of IMPR_FONCTION files, or a table")
        if format is None:
            format = "aster-function"
        if _format_name(format) != "aster-function":
            raise FormatError(f"a list or mapping of files is read with format='aster-function', "
                              f"not {format!r}; read other formats one file at a time")
        for f in (path.values() if isinstance(path, Mapping) else path):
            _require_file(f)
    else:
        _require_file(path)
    name = _format_name(format) if format is not None else guess_format(path)
    fmt = FORMATS[name]
    unknown = sorted(set(options) - set(fmt.read_options))
    if unknown:
        raise KeywordError(f"option(s) {unknown} unknown for the {name!r} reader; its options "
                           f"are {list(fmt.read_options)} (common: units=, columns=, name=)")
    label = source_label(path)
    with reading(label, name, "history file"):
        source = fmt.open(path, **options)
    return _guarded(source, label, name)


def source_label(path: Any) -> str:
    """The file (or files) a history is read from, as quoted in messages."""
    if _is_path(path):
        return os.fspath(path) if isinstance(path, os.PathLike) else str(path)
    files = path.values() if isinstance(path, Mapping) else path
    return ", ".join(str(f) for f in files)


def _stem(path: Any) -> str:
    """Default history name: the file's stem (``n12.csv.gz`` -> ``n12``), else the first
    function file's stem for a set of IMPR_FONCTION files."""
    if isinstance(path, Mapping) and path and all(_is_path(v) for v in path.values()):
        path = next(iter(path.values()))
    elif isinstance(path, (list, tuple)) and path and all(_is_path(v) for v in path):
        path = path[0]
    if _is_path(path):
        p = Path(path)
        return Path(p.stem).stem if p.suffix.lower() == ".gz" else p.stem
    return ""


def _takes_node(path: Any, format: str | None) -> bool:
    """Whether the reader of ``path`` selects a shock point (``node=``): Code_Aster tables."""
    if format is not None:
        return "node" in FORMATS[_format_name(format)].read_options
    return _is_path(path) and Path(path).is_file() and guess_format(path) == "aster"


def _check_stored_node(source: Source, node: str) -> None:
    """Check ``node`` against the node a native file stores (its metadata), else record it as
    unchecked."""
    stored = source.metadata.get("node")
    if stored is None:
        source.metadata.update(node=node, node_checked=False)
    elif str(stored).strip().upper() != node.upper():
        raise KeywordError(f"{source.label}: the shock point {node!r} (NOEUD/GROUP_NO) is not "
                           f"in this file: it holds the history of {stored!r}")
    else:
        source.metadata.update(node=str(stored), node_checked=True)


def _prepare(path: Any, format: str | None, units: Mapping[str, str] | None,
             columns: Mapping[Any, str | None] | None, name: str | None,
             options: Mapping[str, Any]) -> tuple[Source, dict[str, int], dict[str, float], str,
                                                  dict[str, Any]]:
    options = dict(options)
    node = options.get("node")
    own = node is not None and not _takes_node(path, format)
    if own:  # one shock point per file in these formats: nothing to select
        options.pop("node")
    source = open_source(path, format, **options)
    if own:
        _check_stored_node(source, str(node).strip())
    mapping = resolve_columns(source.columns, columns, label=source.label, hint=source.hint)
    unit_of, factors = resolve_units(mapping, source.units, units, label=source.label)
    used = {ch: source.columns[p] for ch, p in mapping.items()}
    ignored = [c for i, c in enumerate(source.columns) if i not in mapping.values()]
    metadata = dict(source.metadata)
    metadata.update(source=source.label, format=source.format, columns=used, units=unit_of,
                    unit_factors=factors, ignored_columns=ignored)
    label = name if name is not None else (source.name if source.name else _stem(path))
    return source, mapping, factors, label, metadata


def read_history(path: Any, format: str | None = None, *, units: Mapping[str, str] | None = None,
                 columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                 **options: Any) -> ContactHistory:
    """Read a contact history from a file, mapping its columns to channels and converting to SI.

    Parameters
    ----------
    path : path-like, mapping, list or table
        The file. For Code_Aster IMPR_FONCTION files, a mapping ``{channel: file}`` (one function
        per file) or a list of files (channels from the value-column names). A DataFrame or a
        mapping of arrays is read as an in-memory table (aliases and units apply).
    format : str, optional
        A key of :data:`FORMATS` (``csv``, ``parquet``, ``hdf5``, ``netcdf``, ``npz``, ``aster``,
        ``aster-function``); default guessed from the content, then the suffix.
    units : mapping, optional
        Units of the file's values, converted to SI: per quantity (``{"length": "mm",
        "force": "kN", "time": "ms", "velocity": "mm/s"}``) or per channel (``{"dy": "mm"}``).
        Without a velocity unit, velocities are in ``<length>/<time>`` of the units given.
        Default: the units the file declares (header ``"Fn [kN]"``, attributes), else SI.
    columns : mapping, optional
        ``{column: channel}`` overrides (channel name or alias, or None to ignore the column);
        they win over the aliases. Columns of a file without header are named ``0``, ``1`` ...
    name : str, optional
        Name of the history; default the name stored in the file, else the file's stem.
    **options
        Options of the format's reader: csv ``delimiter``, ``decimal``, ``comment``,
        ``header``, ``encoding``; hdf5 ``group``; aster ``index``, ``title`` (which table of
        the file), ``select`` (rows where a column equals a value: ``{"NOEUD": "N12"}`` or
        ``"NOEUD=N12"``), ``node`` (the shock point, POST_USURE's NOEUD / GROUP_NO: its rows or
        tables; an error when the file's node column does not hold it) and ``functions``
        (channel names of an IMPR_FONCTION file's functions, in order). ``node`` is accepted
        for every format: the other formats hold one shock point, recorded as unchecked
        (``metadata["node_checked"]`` False).

    Returns
    -------
    ContactHistory
        In SI units. ``metadata`` records ``source``, ``format``, ``columns`` (channel -> column),
        ``units`` (channel -> unit read), ``unit_factors`` and ``ignored_columns``.

    Raises
    ------
    FormatError
        Unknown or unreadable format, a required channel missing (columns found and aliases
        accepted are listed), two columns for one channel (both named), a non-numeric cell.
    KeywordError
        Unknown option, unknown unit (known ones listed), bad ``columns=`` entry.
    HistoryError
        Invalid values (NaN, non-increasing time, negative normal force ...), naming the column
        and the row.

    Notes
    -----
    Conversion: ``x_SI = x_file · f_unit`` (e.g. ``f = 1e-3`` for mm, ``1e3`` for kN).
    Column aliases follow theory §1 (see :data:`fretwear.io.channels.ALIASES`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "shock.txt"
    >>> _ = p.write_text("# N1\\nINST  VINT1  VINT11  VINT12\\n0.0 0.0 0.0 0.0\\n"
    ...                  "1.0 2.5 10.0 0.0\\n")
    >>> h = read_history(p, units={"time": "ms", "force": "kN", "length": "mm"})
    >>> h.time.tolist(), h.normal_force.tolist(), h.vt1.tolist()
    ([0.0, 0.001], [0.0, 2500.0], [0.0, 10.0])
    >>> h.metadata["columns"]["normal_force"], h.metadata["units"]["vt1"]
    ('VINT1', 'mm/ms')
    """
    source, mapping, factors, label, metadata = _prepare(path, format, units, columns, name,
                                                         options)
    arrays = source.read(list(mapping.values()))
    history = build_history(dict(zip(mapping, arrays, strict=True)), columns=source.columns,
                            mapping=mapping, factors=factors, label=source.label, name=label,
                            metadata=metadata)
    check_plausibility(history)  # UnitsWarning for values implausible in SI (mm, ms ...)
    return history


def _slices(arrays: list[np.ndarray], size: int) -> Iterator[list[np.ndarray]]:
    n = min((a.size for a in arrays), default=0)
    for start in range(0, n, size):
        yield [a[start:start + size] for a in arrays]


def _files(path: Any) -> list:
    if _is_path(path):
        return [path]
    if isinstance(path, Mapping):
        return list(path.values())
    return list(path) if isinstance(path, (list, tuple)) else []


def units_read(path: Any, format: str | None = None, *, units: Mapping[str, str] | None = None,
               columns: Mapping[Any, str | None] | None = None, **options: Any
               ) -> dict[str, str]:
    """The unit each channel of a history file is read in (``{channel: unit}``), without
    reading its values; arguments as :func:`read_history`. Printed by the command line's
    summaries.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv"
    >>> _ = p.write_text("t [ms],Fn [kN],vt1,vt2\\n0,1,0,0\\n1,1,0,0\\n")
    >>> units_read(p, units={"length": "mm"})
    {'time': 'ms', 'normal_force': 'kN', 'vt1': 'mm/s', 'vt2': 'mm/s'}
    """
    return dict(_prepare(path, format, units, columns, None, options)[4]["units"])


def _reader_blocks(path, chunk_size, format, units, columns, name, options):
    """The checked chunk size, the opened source and its column mapping, and the reader's
    own blocks of at most ``chunk_size`` rows (a format read whole is sliced, with a warning
    above the size limit): what both chunk iterators start from."""
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) \
            or chunk_size < 2:
        raise KeywordError(f"chunk_size={chunk_size!r}: give an integer >= 2 (samples per chunk)")
    size = int(chunk_size)
    source, mapping, factors, label, metadata = _prepare(path, format, units, columns, name,
                                                         options)
    positions = list(mapping.values())
    if source.iter_blocks is not None:
        blocks = source.iter_blocks(positions, size)
    else:
        warn_whole_read(_files(path), source.label, source.format)
        whole = source.read(positions)
        check_lengths([a.size for a in whole], [source.columns[p] for p in positions],
                      source.label)
        blocks = _slices(whole, size)
    return size, source, mapping, factors, label, metadata, blocks


def iter_history_chunks(path: Any, chunk_size: int = DEFAULT_CHUNK_SIZE,
                        format: str | None = None, *, units: Mapping[str, str] | None = None,
                        columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                        **options: Any) -> Iterator[ContactHistory]:
    """Read a history chunk by chunk, with bounded memory; consecutive chunks share one sample.

    Parameters
    ----------
    path, format, units, columns, name, **options
        As :func:`read_history`.
    chunk_size : int
        Samples per chunk, at least 2 (default 10⁶, about 80 MB for ten channels).

    Yields
    ------
    ContactHistory
        Chunk ``k`` holds the rows ``[k·(m−1), k·(m−1) + m)`` of the file, ``m = chunk_size``
        (the last chunk may be shorter, never a single sample): **the last sample of chunk k is
        the first sample of chunk k+1**. Every interval between consecutive samples therefore
        lies in exactly one chunk, so a reduction over intervals (the trapezoid rule of the
        wear power) summed over the chunks equals the one-shot reduction, and the time
        validation sees every pair of neighbours. ``metadata`` adds ``chunk`` (k) and
        ``first_row`` (file row of the chunk's first sample).

    Notes
    -----
    Bounded memory: Parquet is read by record batches, HDF5 and NetCDF by slices, CSV by pandas
    chunks. NPZ and Code_Aster text files are read whole and then sliced.
    With ``m`` samples per chunk, ``n`` samples give ``ceil((n − 1)/(m − 1))`` chunks.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv"
    >>> _ = p.write_text("t [ms],fn,vt1,vt2\\n" + "".join(f"{i},1,1,0\\n" for i in range(7)))
    >>> [(1e3 * c.time).tolist() for c in iter_history_chunks(p, chunk_size=3)]
    [[0.0, 1.0, 2.0], [2.0, 3.0, 4.0], [4.0, 5.0, 6.0]]
    """
    size, source, mapping, factors, label, metadata, blocks = _reader_blocks(
        path, chunk_size, format, units, columns, name, options)
    channels = list(mapping)
    pending: list[list[np.ndarray]] = []
    pending_rows = 0
    carry: list[np.ndarray] | None = None
    row = 0  # file row of the next sample not yet in a chunk

    def emit(parts: list[list[np.ndarray]], k: int, first_row: int) -> ContactHistory:
        arrays = {ch: np.concatenate([p[j] for p in parts]) for j, ch in enumerate(channels)}
        meta = dict(metadata, chunk=k, first_row=first_row)
        chunk = build_history(arrays, columns=source.columns, mapping=mapping, factors=factors,
                              label=source.label, name=label, metadata=meta,
                              first_row=first_row)
        plausibility.update(chunk, check=True)  # each check warns once per file
        return chunk

    plausibility = StreamPlausibility()

    k = 0
    for block in blocks:
        if not block or block[0].size == 0:
            continue
        pending.append(block)
        pending_rows += block[0].size
        need = size - (0 if carry is None else 1)
        while pending_rows >= need:
            merged = (pending[0] if len(pending) == 1 else
                      [np.concatenate([p[j] for p in pending]) for j in range(len(channels))])
            take = [a[:need] for a in merged]
            rest = [a[need:] for a in merged]
            parts = [take] if carry is None else [carry, take]
            first = row - (0 if carry is None else 1)
            yield emit(parts, k, first)
            k += 1
            row += need
            carry = [a[-1:] for a in take]
            pending = [rest] if rest[0].size else []
            pending_rows = rest[0].size
            need = size - 1
    if pending_rows or k == 0:
        parts = ([] if carry is None else [carry]) + pending
        if not parts:
            raise FormatError(f"{source.label}: no data rows (a header only?); a history "
                              "needs at least two instants")
        yield emit(parts, k, row - (0 if carry is None else 1))
    plausibility.finish()  # the file's largest force (a chunk's says nothing of the file)


def history_time_range(path: Any, format: str | None = None, *,
                       units: Mapping[str, str] | None = None,
                       columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                       **options: Any) -> tuple[float, float] | None:
    """First and last instant [s] of a history file without reading it through, or None.

    Parquet: the time column's statistics in the first and last row groups (else the values at
    their ends); HDF5 and NetCDF: the time dataset's first and last values. Other formats
    (text, NPZ) give None: the caller then needs a pass. Arguments as :func:`read_history`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0.5, 1.0, 2.5], normal_force=[1, 1, 1], vt1=[0, 0, 0],
    ...                    vt2=[0, 0, 0])
    >>> p = write_history(h, pathlib.Path(tempfile.mkdtemp()) / "h.parquet")
    >>> history_time_range(p), history_time_range(p, units={"time": "ms"})
    ((0.5, 2.5), (0.0005, 0.0025))
    """
    source, mapping, factors, _, _ = _prepare(path, format, units, columns, name, options)
    if source.ends is None:
        return None
    first, last = source.ends(mapping["time"])
    factor = factors.get("time", 1.0)
    return (first * factor, last * factor) if factor != 1.0 else (first, last)


def iter_history_blocks(path: Any, chunk_size: int = DEFAULT_CHUNK_SIZE,
                        format: str | None = None, *, units: Mapping[str, str] | None = None,
                        columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                        **options: Any) -> Iterator[ContactHistory]:
    """Read a history block by block as the file gives them: no shared sample, no copy.

    The streaming reader of the wear power (:class:`fretwear.power.PowerAccumulator` bridges
    the interval between two blocks). Unlike :func:`iter_history_chunks`, the blocks are the
    reader's own (Parquet record batches of at most ``chunk_size`` rows, HDF5/NetCDF slices,
    slices of a whole read for the text formats), consecutive without overlap, and each is
    checked by :func:`fretwear.io.channels.fast_history`: its arrays go into the history
    without a copy when they pass (the same errors otherwise, row numbers of the file). The
    instants must also increase across blocks. A block of one row is joined to the next (the
    last one comes with the previous block's last sample). The plausibility of the values in
    SI (:func:`fretwear.io.plausibility.check_plausibility`) is checked on the first block: a
    wrong unit shows there; the smallest plausible largest force, on the whole file's largest
    force after the last block (:class:`fretwear.io.plausibility.StreamPlausibility`).

    Parameters
    ----------
    path, format, units, columns, name, **options
        As :func:`read_history`.
    chunk_size : int
        Largest block [samples] (>= 2).

    Yields
    ------
    ContactHistory
        Consecutive blocks; ``metadata`` adds ``chunk`` and ``first_row``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv"
    >>> _ = p.write_text("t [ms],fn,vt1,vt2\\n" + "".join(f"{i},1,1,0\\n" for i in range(7)))
    >>> [(1e3 * c.time).tolist() for c in iter_history_blocks(p, chunk_size=3)]
    [[0.0, 1.0, 2.0], [3.0, 4.0, 5.0], [5.0, 6.0]]
    """
    size, source, mapping, factors, label, metadata, blocks = _reader_blocks(
        path, chunk_size, format, units, columns, name, options)
    channels = list(mapping)
    row = 0
    k = 0
    last: list[np.ndarray] | None = None  # the previous block's last sample
    pending: list[np.ndarray] | None = None  # a single-row block waiting for the next one
    plausibility = StreamPlausibility()
    build = dict(columns=source.columns, mapping=mapping, factors=factors, label=source.label,
                 name=label)
    for block in blocks:
        if not block or block[0].size == 0:
            continue
        if pending is not None:
            block = [np.concatenate((a, b)) for a, b in zip(pending, block, strict=True)]
            pending = None
        if block[0].size < 2:
            pending = block
            continue
        if last is not None and not float(block[0][0]) > float(last[0][0]):
            # the instants do not increase across the blocks: the history of the two samples
            # raises the error with their rows
            build_history({ch: np.concatenate((last[j], block[j][:1]))
                           for j, ch in enumerate(channels)}, metadata=metadata,
                          first_row=row - 1, **build)
        chunk = fast_history(dict(zip(channels, block, strict=True)),
                             metadata=dict(metadata, chunk=k, first_row=row), first_row=row,
                             **build)
        plausibility.update(chunk, check=k == 0)
        yield chunk
        last = [a[-1:] for a in block]
        row += block[0].size
        k += 1
    if pending is not None:
        if last is None:  # the whole file is one row
            build_history(dict(zip(channels, pending, strict=True)), metadata=metadata, **build)
        chunk = build_history({ch: np.concatenate((last[j], pending[j]))
                               for j, ch in enumerate(channels)},
                              metadata=dict(metadata, chunk=k, first_row=row - 1),
                              first_row=row - 1, **build)
        plausibility.update(chunk, check=False)
        yield chunk
    elif k == 0:
        raise FormatError(f"{source.label}: no data rows (a header only?); a history "
                          "needs at least two instants")
    plausibility.finish()  # the file's largest force (a block's says nothing of the file)


def write_history(history: ContactHistory, path: str | os.PathLike, format: str | None = None,
                  **options: Any) -> Path:
    """Write a history in a native format, atomically, with the units documented in the file.

    Parameters
    ----------
    history : ContactHistory
        The history (SI units).
    path : path-like
        Output file.
    format : str, optional
        A key of :data:`FORMATS` with a writer (``csv``, ``parquet``, ``hdf5``, ``netcdf``,
        ``npz``, ``aster``); default from the suffix.
    **options
        csv ``float_format`` (default: shortest exact text), ``delimiter``; parquet
        ``row_group_size``; hdf5 ``group`` (default ``history``); aster ``table_format``
        (``TABLEAU``/``ASTER``) and ``float_format`` (default ``%.16E``, exact) with Code_Aster
        names (INST, FN, FT1, FT2, VN, VT1, VT2, DYLOC, DZLOC, VINT13).

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 1e-4], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0],
    ...                    name="n1")
    >>> out = write_history(h, pathlib.Path(tempfile.mkdtemp()) / "n1.h5")
    >>> read_history(out).normal_force.tolist()
    [2.0, 3.0]
    """
    if not isinstance(history, ContactHistory):
        raise InputError(f"write_history needs a ContactHistory, got {type(history).__name__}; "
                         "build one with fretwear.ContactHistory(...) or read_history(...)")
    if format is None:
        suffix = Path(path).suffix.lower()
        if suffix == ".gz":  # h.csv.gz, t.resu.gz: the format of the inner suffix, compressed
            suffix = Path(Path(path).stem).suffix.lower()
        hits = [f.name for f in FORMATS.values() if suffix in f.suffixes and f.write]
        if not hits:
            known = sorted(s for f in FORMATS.values() if f.write for s in f.suffixes)
            raise FormatError(f"{path}: cannot tell the format from the suffix {suffix!r}; use "
                              f"one of {known} or give format= among "
                              f"{[f.name for f in FORMATS.values() if f.write]}")
        name = hits[0]
    else:
        name = _format_name(format)
    if Path(path).suffix.lower() == ".gz" and name not in ("csv", "aster"):
        raise FormatError(f"{path}: gzip (.gz) is for the text formats csv and aster; the "
                          f"{name!r} format compresses internally, drop the .gz")
    fmt = FORMATS[name]
    if fmt.write is None:
        raise FormatError(f"format {name!r} is read-only; writable formats: "
                          f"{[f.name for f in FORMATS.values() if f.write]}")
    unknown = sorted(set(options) - set(fmt.write_options))
    if unknown:
        raise KeywordError(f"option(s) {unknown} unknown for the {name!r} writer; its options "
                           f"are {list(fmt.write_options)}")
    return fmt.write(history, path, **options)


def _check_channel_names() -> None:  # keeps the alias table and the history in step
    assert set(ALIASES) == set(CHANNELS)
    assert all(channel_of(ch) == ch for ch in CHANNELS)


_check_channel_names()
