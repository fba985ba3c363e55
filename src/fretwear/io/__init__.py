"""Reading and writing contact histories (theory §1): CSV, Parquet, HDF5, NetCDF, NPZ, Code_Aster.

``read_history`` opens a file in any supported format, maps its columns to the channels of a
:class:`~fretwear.history.ContactHistory` through case-insensitive aliases (Code_Aster's INST,
FN, VINT1 ...), converts units to SI and validates. ``iter_history_chunks`` does the same chunk by
chunk with bounded memory. ``write_history`` writes the native formats. The families of formats
are the explicit registry :data:`FORMATS`; see ``docs/formats.md`` for the layouts.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from fretwear.errors import FormatError, InputError, KeywordError
from fretwear.history import CHANNELS, ContactHistory
from fretwear.io.channels import ALIASES, build_history, channel_of
from fretwear.io.plausibility import check_plausibility
from fretwear.io.sources import (  # noqa: F401 - re-exported
    ASTER_NAMES,
    FORMATS,
    FileFormat,
    _format_name,
    _prepare,
    guess_format,
    open_source,
    source_label,
)
from fretwear.io.streaming import (  # noqa: F401 - re-exported
    history_time_range,
    iter_history_blocks,
    iter_history_chunks,
)

__all__ = ["FORMATS", "ALIASES", "FileFormat", "read_history", "write_history",
           "iter_history_chunks", "iter_history_blocks", "history_time_range", "guess_format",
           "open_source", "units_read"]


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
        ``row_group_size``, ``compression`` (default ``"lz4"``, no dictionary pages); hdf5
        ``group`` (default ``history``); aster ``table_format`` (``TABLEAU``/``ASTER``) and
        ``float_format`` (default ``%.16E``, exact) with Code_Aster names (INST, FN, FT1, FT2,
        VN, VT1, VT2, DYLOC, DZLOC, VINT13).

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
