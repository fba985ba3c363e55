"""Restarts of the wear table: reading previous tables, the initial state (the tube
replacement is :mod:`fretwear.table.replace`).

Theory §7: a previous table (ours, or a Code_Aster one read from its text file) gives the origin
ORIG_INST (its last instant, or INST_INIT) and the cumulated volumes there; TUBE_NEUF replaces
the tube (its volumes and depths restart from zero, the obstacle's are kept). Used by
:func:`fretwear.table.wear_table` (``initial_state=``) and
:func:`fretwear.workflows.aster.POST_USURE`.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
import os
import stat
import threading
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.sectors import sector_edges as _validated_edges
from fretwear.table.files import read_aster_wear_table, read_wear_table
from fretwear.table.schema import _TIME_TOL, COLUMNS, from_aster_names

__all__ = ["InitialState", "initial_state", "read_wear_table"]


@dataclass(frozen=True)
class InitialState:
    """The state a restart continues from (theory §7, ETAT_INIT).

    Attributes
    ----------
    origin : float
        ORIG_INST of the new rows [user time unit].
    volume_mobile, volume_obstacle : float
        Cumulated global volumes at the origin [m³].
    sector_volume_mobile, sector_volume_obstacle : ndarray or None
        Cumulated sector volumes at the origin [m³] (sector tables only).
    edges : ndarray or None
        Sector edges of the table [deg].
    rows : DataFrame
        The table's rows up to the origin (native names), kept at the head of the new table.
    time_unit : str or None
        The time unit the table's header declares (its provenance's ``time_unit``: a name of
        :data:`fretwear.timeunits.TIME_UNITS` or ``"<number> s"``); None when it declares none
        (a Code_Aster table). A case continuing the table must count time in the same unit.
    """

    origin: float
    volume_mobile: float
    volume_obstacle: float
    sector_volume_mobile: np.ndarray | None
    sector_volume_obstacle: np.ndarray | None
    edges: np.ndarray | None
    rows: pd.DataFrame
    time_unit: str | None = None

    @functools.cached_property
    def row_dtypes(self) -> tuple:
        """The numpy dtypes of :attr:`rows`' columns, ``tuple(rows.dtypes)``, read once (a
        Series of dtypes costs about 40 µs; every table continuing the state asks)."""
        return tuple(self.rows.dtypes)

    @property
    def sector_count(self) -> int:
        """Number of sectors of the initial table (0 for a table without sectors)."""
        return 0 if self.edges is None else len(self.edges) - 1


def _numeric_columns(frame: pd.DataFrame) -> dict[str, np.ndarray]:
    """Name -> float values of every column when all are numbers (one ``to_numpy``, no column
    taken one by one): the values ``pd.to_numeric(column).to_numpy(dtype=float)`` gives; an
    empty dict otherwise (strings, missing integers, repeated names)."""
    if not frame.columns.is_unique:
        return {}
    values = frame.to_numpy()
    if values.dtype != np.float64:
        return {}
    return dict(zip(frame.columns.tolist(), values.T, strict=True))


def _column(frame: pd.DataFrame, names: Sequence[str], what: str, source: str,
            numeric: dict[str, np.ndarray] | None = None) -> np.ndarray:
    """The first of ``names`` in ``frame`` as floats, NaN as 0 (``numeric``: the frame's
    :func:`_numeric_columns`, when known)."""
    for name in names:
        if name in frame.columns:
            values = numeric.get(name) if numeric else None
            if values is None:
                values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
                text = frame[name].notna().to_numpy() & np.isnan(values)
                if text.any():  # a text cell was read as 0 (no wear) before
                    k = int(np.flatnonzero(text)[0])
                    raise InputError(
                        f"initial wear table {source}: column {name!r} ({what}), row {k + 1}: "
                        f"{frame[name].iloc[k]!r} is not a number; give the number (or leave "
                        "the cell empty)")
            return np.where(np.isnan(values), 0.0, values)
    aster = [COLUMNS[n][0] for n in names if n in COLUMNS]
    raise InputError(f"initial wear table {source}: no column for {what}; expected one of "
                     f"{list(names)} (Code_Aster {aster})")


def initial_state(table: pd.DataFrame | str | os.PathLike,
                  initial_instant: float | None = None) -> InitialState:
    """The restart state of a previous wear table (ours or Code_Aster's), theory §7.

    Parameters
    ----------
    table : DataFrame or path-like
        A previous table, native or Code_Aster column names, or its file.
    initial_instant : float, optional
        INST_INIT [user time unit]: an instant of the table to continue from (rows after it are
        dropped). Default: its last instant.

    Returns
    -------
    InitialState

    Examples
    --------
    >>> prev = pd.DataFrame({"INST": [1.0, 2.0], "V_USUR_TUBE": [1e-9, 2e-9],
    ...                      "V_USUR_OBST": [0.0, 0.0]})
    >>> s = initial_state(prev, initial_instant=1.0)
    >>> s.origin, s.volume_mobile, len(s.rows)
    (1.0, 1e-09, 1)
    """
    if not isinstance(table, pd.DataFrame):
        return _file_state(table, initial_instant)
    return _own_state(from_aster_names(table), initial_instant, "(DataFrame)")


# --------------------------------------------------------------------------- the memo of files
#: Restart states of Code_Aster text files, keyed on the file's bytes and INST_INIT: a table
#: read again (the same restart file for several contacts, a study run again) is parsed once.
#: The key is the content itself (the state is parsed from those very bytes), so it cannot be
#: stale; the states kept are never given out: each caller gets its own copy of their mutable
#: parts (rows and their attrs, sector arrays). Files of at most _MEMO_BYTES, the last
#: _MEMO_SIZE states.
_MEMO: OrderedDict[tuple, tuple[InitialState, dict]] = OrderedDict()
_MEMO_SIZE = 16
_MEMO_BYTES = 1 << 18
_MEMO_LOCK = threading.Lock()
_UNKEYED = object()


def _memo_bytes(path, *, tables_only: bool = True) -> bytes | None:
    """The bytes of ``path`` when its state may be kept (a regular file of at most _MEMO_BYTES
    that :func:`read_wear_table` reads as a Code_Aster text table; any such regular file when
    not ``tables_only``), else None: it is then read as usual, which words any problem."""
    if not isinstance(path, str | os.PathLike):
        return None
    try:
        name = os.fsdecode(os.fspath(path))
        if tables_only and os.path.splitext(name)[1].lower() in (".csv", ".parquet", ".pq"):
            return None
        # a named pipe or a device is never opened here (opening a pipe waits for a writer,
        # and closing it unread loses what the writer sent): read_wear_table reads it once
        if not stat.S_ISREG(os.stat(name).st_mode):
            return None
        fd = os.open(name, os.O_RDONLY | getattr(os, "O_BINARY", 0)
                     | getattr(os, "O_NONBLOCK", 0))  # (swapped for a pipe meanwhile)
        try:
            info = os.fstat(fd)
            if not stat.S_ISREG(info.st_mode) or info.st_size > _MEMO_BYTES:
                return None
            data = os.read(fd, info.st_size + 1)  # its size: the end (asked one byte more)
            chunks, size = [data], len(data)
            # fewer bytes than its size (a read cut short: FUSE, network file systems) or more
            # (grown meanwhile): read on to the end
            while chunks[-1] and size != info.st_size and size <= _MEMO_BYTES:
                chunks.append(os.read(fd, max(info.st_size + 1 - size, 1 << 16)))
                size += len(chunks[-1])
            if len(chunks) > 1:
                data = b"".join(chunks)
            return data if len(data) <= _MEMO_BYTES else None
        finally:
            os.close(fd)
    except (OSError, ValueError):
        return None


def _file_state(path, initial_instant) -> InitialState:
    """The state of a table file: remembered by content (see _MEMO), or read as usual."""
    source = repr(str(path))
    instant = (initial_instant if initial_instant is None
               else float(initial_instant) if isinstance(initial_instant, int | float)
               and not isinstance(initial_instant, bool) else _UNKEYED)
    data = None if instant is _UNKEYED else _memo_bytes(path)
    if data is None:
        return _own_state(read_wear_table(path), initial_instant, source)
    # -0.0 == 0.0 (one hash) but each gives an origin of its own sign: the sign in the key
    key = (data, instant, None if instant is None else math.copysign(1.0, instant))
    with _MEMO_LOCK:
        kept = _MEMO.get(key)
        if kept is not None:
            _MEMO.move_to_end(key)
    if kept is None:
        # parsed from the bytes of the key (the file may change meanwhile), named as
        # read_wear_table names it
        frame = read_aster_wear_table(Path(os.fsdecode(os.fspath(path))), data=data)
        state = _own_state(frame, initial_instant, source)
        kept = (state, state.rows.attrs)
        state.rows.attrs = {}  # kept aside: copied once per caller (see _handed_out)
        with _MEMO_LOCK:
            _MEMO[key] = kept
            while len(_MEMO) > _MEMO_SIZE:
                _MEMO.popitem(last=False)
    return _handed_out(*kept)


def _handed_out(state: InitialState, attrs: dict) -> InitialState:
    """A caller's own copy of a remembered state: its rows (attrs included) and arrays copied,
    so that changing them never changes the memo or another caller's state."""
    rows = state.rows.copy()
    rows.attrs = _copied(attrs)
    arrays = [None if a is None else a.copy() for a in
              (state.sector_volume_mobile, state.sector_volume_obstacle, state.edges)]
    out = InitialState(state.origin, state.volume_mobile, state.volume_obstacle, *arrays, rows,
                       state.time_unit)
    out.__dict__["row_dtypes"] = state.row_dtypes  # the copy's: the same (a tuple, immutable)
    return out


def _copied(value):
    """A deep copy of attrs (JSON-like: dicts, lists, strings, numbers; anything else by
    :func:`copy.deepcopy`)."""
    kind = type(value)
    if kind is dict:
        return {k: _copied(v) for k, v in value.items()}
    if kind is list:
        return [_copied(v) for v in value]
    if kind in (str, int, float, bool, type(None)):
        return value
    return copy.deepcopy(value)


def _own_state(table: pd.DataFrame, initial_instant, source: str) -> InitialState:
    """The state of ``table``, our own frame (read, or renamed: a copy), native names."""
    if len(table) == 0:
        raise InputError(f"initial wear table {source} has no rows")
    # pandas deep-copies a frame's attrs into every column and every slice taken from it: they
    # are set aside while the state is computed and given to its rows (which have them, as a
    # slice of ``table`` would)
    attrs = table.attrs
    table.attrs = {}
    state = _state(table, initial_instant, source)
    state.rows.attrs = attrs
    provenance = attrs.get("provenance")  # a file's header, or a table of this session
    unit = (provenance if isinstance(provenance, dict) else attrs).get("time_unit")
    if isinstance(unit, str) and unit.strip():
        state = dataclasses.replace(state, time_unit=unit.strip())
    return state


def _state(table: pd.DataFrame, initial_instant: float | None, source: str) -> InitialState:
    """The restart state of ``table`` (native names, at least one row); see initial_state."""
    numeric = _numeric_columns(table)
    inst = _column(table, ["instant"], "the instant (INST)", source, numeric)
    if initial_instant is None:
        origin = float(inst.max())
    else:
        origin = float(initial_instant)
        scale = max(1.0, float(np.abs(inst).max()))
        if not np.any(np.abs(inst - origin) <= _TIME_TOL * scale):
            raise InputError(
                f"INST_INIT / initial_instant = {origin:g} is not an instant of the initial wear "
                f"table {source}; its instants are {sorted(set(inst.tolist()))}")
    scale = max(1.0, abs(origin))
    keep = inst <= origin + _TIME_TOL * scale
    index = table.index
    if keep.all() and type(index) is pd.RangeIndex and index.start == 0 and index.step == 1 \
            and index.name is None:
        rows = table  # (our own copy) every row kept, already numbered 0..n-1
    else:
        rows = table.loc[keep].reset_index(drop=True)
    at = np.abs(inst[keep] - origin) <= _TIME_TOL * scale
    if "sector" in rows.columns and rows["sector"].notna().any():
        # rows without a sector number (a global row per instant) do not hold sector volumes
        last = rows.loc[at]
        last = last[pd.to_numeric(last["sector"], errors="coerce").notna()].sort_values("sector")
        sectors = pd.to_numeric(last["sector"]).to_numpy()
        if len(np.unique(sectors)) != len(sectors):
            raise InputError(f"initial wear table {source}: sector numbers repeat at instant "
                             f"{origin:g}; one row per sector is expected")
        starts = _column(last, ["angle_start"], "the sector start angle (ANGLE_DEBUT)", source)
        ends = _column(last, ["angle_end"], "the sector end angle (ANGLE_FIN)", source)
        edges = np.append(starts, ends[-1])
        if not np.allclose(starts[1:], ends[:-1]):
            raise InputError(f"initial wear table {source}: its sectors are not contiguous "
                             f"(ANGLE_DEBUT {starts.tolist()}, ANGLE_FIN {ends.tolist()})")
        svm = _column(last, ["volume_mobile_cumulated", "volume_mobile_sector"],
                      "the cumulated sector volume of the tube", source)
        svo = _column(last, ["volume_obstacle_cumulated", "volume_obstacle_sector"],
                      "the cumulated sector volume of the obstacle", source)
        return InitialState(origin, float(svm.sum()), float(svo.sum()), svm, svo,
                            _validated_edges(edges), rows)
    # the volumes of the last row at the origin (the rows are the table's ``keep`` rows)
    vm = _column(table, ["volume_mobile_cumulated", "volume_mobile"], "the tube's volume",
                 source, numeric)[keep]
    vo = _column(table, ["volume_obstacle_cumulated", "volume_obstacle"],
                 "the obstacle's volume", source, numeric)[keep]
    return InitialState(origin, float(vm[at][-1]), float(vo[at][-1]), None, None, None, rows)
