"""The formats of history files and how one is opened (theory §1): the registry
:data:`FORMATS`, :func:`guess_format` (by content), :func:`open_source` (a file as a
:class:`~fretwear.io.channels.Source`, its column readers guarded) and the preparation shared by
:func:`fretwear.io.read_history` and the streaming readers of :mod:`fretwear.io.streaming`
(columns mapped to channels, units resolved, metadata). Re-exported by :mod:`fretwear.io`.
"""

from __future__ import annotations

import gzip
import os
import zipfile
from collections import OrderedDict
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from fretwear.errors import FormatError, InputError, KeywordError
from fretwear.history import ContactHistory
from fretwear.io import aster as _aster
from fretwear.io import binary as _binary
from fretwear.io import delimited as _delimited
from fretwear.io.aster_source import open_aster as _open_aster
from fretwear.io.aster_source import open_functions as _open_functions
from fretwear.io.channels import Source, resolve_columns, resolve_units
from fretwear.io.guard import HDF5_MAGIC, readable_file, reading

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
                          _binary.write_parquet, (), ("row_group_size", "compression"),
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

#: The bytes of the root attribute netCDF-C writes into every NetCDF-4 file it creates
#: (:func:`guess_format`).
NETCDF4_MARK = b"_NCProperties"

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

    An HDF5 file is NetCDF-4 when its suffix says so (``.nc``, ``.nc4``, ``.cdf``) or when its
    first 64 KiB hold the root attribute ``_NCProperties`` that netCDF-C (4.4.1 and later)
    writes into every file it creates, in the root group's header near the start (at byte 606
    in a file written by :func:`fretwear.io.write_netcdf`). This reads bytes only: no library
    opens the file and no process is started, so that guessing the formats of 10⁴ files costs
    no more than reading their first blocks (a child process walked each file here, 0.2 s a
    file). Otherwise it is read as plain HDF5, which h5py can read whatever wrote it: a
    NetCDF-4 file under an HDF5 suffix from an older netCDF-C, or whose root attributes were
    rewritten past 64 KiB, gives its variables as HDF5 datasets (give ``format="netcdf"`` for
    its NetCDF title and metadata). The file's structure is checked when its reader opens it
    (:func:`fretwear.io.guard.probe`).

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
    return _guess_checked(readable_file(path, "history file"))


def _read_upto(fd: int, size: int, head: bytes = b"") -> bytes:
    """``head`` followed by the file's next bytes, ``size`` in all, or fewer at its end
    (``os.read`` may return less than asked)."""
    while len(head) < size:
        more = os.read(fd, size - len(head))
        if not more:
            break
        head += more
    return head


def _guess_checked(path: Path) -> str:
    """:func:`guess_format` of a path :func:`~fretwear.io.guard.readable_file` returned (a
    Parquet file by its first 4 bytes, without reading its first 64 KiB: a bundle of small
    Parquet files reads each file whole there, issue 28)."""
    with reading(path, "history", "history file"):
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_BINARY", 0))  # 5 µs, open() 20 µs
        try:
            head = _read_upto(fd, 4)
            if head == b"PAR1":
                return "parquet"
            head = _read_upto(fd, 65536, head)  # the first 64 KiB of another format
        finally:
            os.close(fd)
    suffix = path.suffix.lower()
    if not head:
        raise FormatError(f"{path}: the file is empty")
    if head.startswith(HDF5_MAGIC):
        # NetCDF-4 or plain HDF5, from the header's bytes (no process, no library: the file is
        # checked when its reader opens it, fretwear.io.guard.probe)
        return "netcdf" if suffix in FORMATS["netcdf"].suffixes or NETCDF4_MARK in head \
            else "hdf5"
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
        checked = readable_file(path, "history file")
    if format is not None:
        name = _format_name(format)
    else:  # a single file was checked above (a list of files has a format by now)
        name = _guess_checked(checked)
    fmt = FORMATS[name]
    unknown = sorted(set(options) - set(fmt.read_options))
    if unknown:
        raise KeywordError(f"option(s) {unknown} unknown for the {name!r} reader; its options "
                           f"are {list(fmt.read_options)} (common: units=, columns=, name=)")
    label = source_label(path)
    with reading(label, name, "history file"):
        source = fmt.open(path, **options)
    if format is None:
        source.hint += _suffix_hint(path, name)
    return _guarded(source, label, name)


#: Formats whose files carry a signature: a file named like one of them that holds text is
#: read as text (its content decides), and its column errors say so.
_BINARY_FORMATS = {"parquet": "Parquet", "hdf5": "HDF5", "netcdf": "NetCDF", "npz": "NPZ"}


def _suffix_hint(path: Any, guessed: str) -> str:
    """For a column error: a file named like a binary format that was read as text (a text file
    renamed, a failed export) is not the binary file its name says (found by a user's trial:
    ``garbage.parquet`` gave only "no column for the required channel(s)")."""
    if not _is_path(path) or guessed in _BINARY_FORMATS:
        return ""
    suffix = Path(path).suffix.lower()
    named = next((v for k, v in _BINARY_FORMATS.items() if suffix in FORMATS[k].suffixes), None)
    if named is None:
        return ""
    return (f"; note: the file is named {suffix} but holds text, not {named} (no {named} "
            f"signature), so it was read as {guessed}: re-export it as {named}, or rename it")


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
    key = _layout(source) if not columns and not units else None
    found = None if key is None else _LAYOUTS.get(key)
    if found is not None:  # copies: the caller's metadata may change
        mapping, unit_of, factors, used = (dict(d) for d in found[:4])
        ignored = list(found[4])
    else:  # resolve_units warns with the caller's line: called from here
        mapping = resolve_columns(source.columns, columns, label=source.label, hint=source.hint)
        unit_of, factors = resolve_units(mapping, source.units, units, label=source.label)
        used = {ch: source.columns[p] for ch, p in mapping.items()}
        ignored = [c for i, c in enumerate(source.columns) if i not in mapping.values()]
        if key is not None:
            _remember(key, (dict(mapping), dict(unit_of), dict(factors), dict(used),
                            list(ignored)))
    metadata = dict(source.metadata)
    metadata.update(source=source.label, format=source.format, columns=used, units=unit_of,
                    unit_factors=factors, ignored_columns=ignored)
    label = name if name is not None else (source.name if source.name else _stem(path))
    return source, mapping, factors, label, metadata


#: The channels of the last column layouts read without ``columns`` or ``units`` options
#: (:func:`_layout`), at most 16: a bundle's files share one.
_LAYOUTS: OrderedDict[tuple, tuple] = OrderedDict()


def _layout(source: Source) -> tuple | None:
    """The key of a source's column layout in :data:`_LAYOUTS` (its column names and declared
    units), or None when one of them is no hashable value (not remembered).

    Read without ``columns`` or ``units`` options, the channels of a file (column mapping,
    units, factors to SI, columns used and ignored) are a function of its layout alone, and
    nothing warns (a warning needs a unit given): they are remembered for the last layouts
    (15 µs of a bundle's 1 000-sample file, issue 28) and handed out as copies; an error is
    raised again at every file (nothing is remembered then)."""
    key = (tuple(source.columns), tuple(source.units.items()))
    try:
        hash(key)
    except TypeError:
        return None
    return key


def known_layout(names: list[str], units: dict[int, str]) -> tuple | None:
    """The channels remembered in :data:`_LAYOUTS` for a file of these column ``names`` and
    ``{position: unit}`` (:func:`_layout`'s key), or None: what the lean lane of
    :func:`fretwear.io.iter_history_blocks` and its read-ahead (:mod:`fretwear.io.prefetch`)
    read a file by."""
    return _LAYOUTS.get((tuple(names), tuple(units.items())))


def _remember(key: tuple, channels: tuple) -> None:
    if len(_LAYOUTS) >= 16:
        _LAYOUTS.popitem(last=False)  # the oldest (one call: safe beside other threads)
    _LAYOUTS[key] = channels


def _files(path: Any) -> list:
    if _is_path(path):
        return [path]
    if isinstance(path, Mapping):
        return list(path.values())
    return list(path) if isinstance(path, (list, tuple)) else []

