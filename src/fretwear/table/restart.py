"""Restarts of the wear table: reading previous tables, the initial state, tube replacement.

Theory §7: a previous table (ours, or a Code_Aster one read from its text file) gives the origin
ORIG_INST (its last instant, or INST_INIT) and the cumulated volumes there; TUBE_NEUF replaces
the tube (its volumes and depths restart from zero, the obstacle's are kept). Used by
:func:`fretwear.table.wear_table` (``initial_state=``) and
:func:`fretwear.workflows.aster.POST_USURE`.
"""

from __future__ import annotations

import copy
import math
import os
import stat
import threading
import warnings
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FretwearWarning, InputError
from fretwear.geometry.sectors import SectorGeometry, sector_depth_mobile
from fretwear.sectors import sector_edges as _validated_edges
from fretwear.table.files import read_aster_wear_table, read_wear_table
from fretwear.table.schema import _TIME_TOL, COLUMNS, from_aster_names, to_aster_names

__all__ = ["InitialState", "initial_state", "read_wear_table", "replace_tube"]


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
    """

    origin: float
    volume_mobile: float
    volume_obstacle: float
    sector_volume_mobile: np.ndarray | None
    sector_volume_obstacle: np.ndarray | None
    edges: np.ndarray | None
    rows: pd.DataFrame

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


def _memo_bytes(path) -> bytes | None:
    """The bytes of ``path`` when its state may be kept (a regular file of at most _MEMO_BYTES
    that :func:`read_wear_table` reads as a Code_Aster text table), else None: it is then read
    as usual, which words any problem."""
    if not isinstance(path, str | os.PathLike):
        return None
    try:
        name = os.fsdecode(os.fspath(path))
        if os.path.splitext(name)[1].lower() in (".csv", ".parquet", ".pq"):
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
    return InitialState(state.origin, state.volume_mobile, state.volume_obstacle, *arrays, rows)


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


def replace_tube(table: pd.DataFrame | str | os.PathLike, instant: float | None = None
                 ) -> pd.DataFrame:
    """The wear table with the tube replaced by a new one at ``instant`` (TUBE_NEUF, theory §7).

    Rows before ``instant`` are unchanged. From ``instant`` on the tube is the new one: its
    cumulated volumes (global and per sector) are the old ones minus their value at ``instant``
    (zero at ``instant``, then what the new tube wears since, for a law linear in time), the
    volume worn in a sector by the tube in place (``volume_mobile_sector``) is the new tube's
    cumulated volume, and the depths are computed again from those volumes with the table's
    geometry (of the case the table carries, :func:`fretwear.table.carried_case`; sector
    depths theory §3). The
    obstacle's volumes are kept. Code_Aster's TUBE_NEUF keeps the later rows too, but sets the
    tube's values to zero on every one of them (``motubn``): a tube that no longer wears.

    The result seeds a restart (:func:`fretwear.table.wear_table` ``initial_state=``) of the new
    tube against the worn obstacle, from the table's last instant, or from ``instant`` with
    ``initial_instant=instant`` (ETAT_INIT INST_INIT).

    Parameters
    ----------
    table : DataFrame or path-like
        A wear table, native or Code_Aster names (the result keeps the names given).
    instant : float, optional
        Instant of the replacement [user time unit]; an instant of the table. Default: the last.

    Returns
    -------
    pandas.DataFrame
        A new table (the one given is not modified); ``attrs`` gain ``tube_replacement`` and,
        when the table carries no geometry (a Code_Aster table read from its file), the note
        ``tube_replacement_depths``: the new tube's depths after ``instant`` are then NaN.

    Raises
    ------
    InputError
        ``instant`` is not an instant of the table; rows after it in a table of a law that is
        not linear in time (EDF_MZ: the new tube's run-in starts again, compute it with
        ``tube_replacement=`` / ``[time] tube_replacement`` instead).

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0, 2.0, 3.0], "volume_mobile": [1e-9, 2e-9, 3e-9],
    ...                   "volume_obstacle": [3e-10, 6e-10, 9e-10]})
    >>> replace_tube(t, 2.0)["volume_mobile"].tolist()
    [1e-09, 0.0, 1e-09]
    """
    if not isinstance(table, pd.DataFrame):
        table = read_wear_table(table)
    aster = "INST" in table.columns
    native = from_aster_names(table)
    attrs = dict(table.attrs)
    from fretwear.table.depth_build import carried_case  # (depth_build reads restarts)

    case = carried_case(table)  # the case it was computed from, rebuilt once; None: none
    inst = _column(native, ["instant"], "the instant (INST)", "(DataFrame)")
    if instant is not None and len(inst) and not np.any(
            np.abs(inst - float(instant)) <= _TIME_TOL * max(1.0, float(np.abs(inst).max()))):
        raise InputError(f"TUBE_NEUF at INST = {float(instant):g}: not an instant of the wear "
                         f"table (TABL_USURE), whose instants are {sorted(set(inst.tolist()))}; "
                         "replace the tube at one of them (the new tube's volumes are the old "
                         "ones minus their value there), or compute the table with "
                         "tube_replacement= (case file [time] tube_replacement) for another "
                         "instant")
    state = initial_state(native, instant)
    at = state.origin
    tol = _TIME_TOL * max(1.0, abs(at))
    on, after = np.abs(inst - at) <= tol, inst > at + tol
    law = None if case is None else case.wear_law
    if after.any() and law is not None and not law.linear_in_time:
        raise InputError(f"TUBE_NEUF at {at:g} before the table's last instant with "
                         f"LOI_USURE='{law.name}': the new tube's wear is not the old one's "
                         "minus its value at the replacement (the law is not linear in time); "
                         "compute the table with tube_replacement= (case file [time] "
                         "tube_replacement) instead")
    out = native.copy()
    new = on | after
    keys = _sector_keys(native)
    for col in ("volume_mobile", "volume_mobile_cumulated"):
        if col in out.columns:
            out[col] = _restarted(native[col], keys, inst, at, tol, new)
    if "volume_mobile_sector" in out.columns:
        if "volume_mobile_cumulated" in out.columns:
            out.loc[new, "volume_mobile_sector"] = out.loc[new, "volume_mobile_cumulated"]
        else:
            out["volume_mobile_sector"] = _restarted(native["volume_mobile_sector"], keys, inst,
                                                     at, tol, new)
    geometry = None if case is None else _geometry(case)
    _restarted_depths(out, new, on, geometry, keys)
    if geometry is None and after.any():
        attrs["tube_replacement_depths"] = (
            "the table carries no geometry (no wear case: attrs['case'], or its file's "
            "provenance): the new tube's depths after the replacement are NaN; recompute them "
            "with the contact geometry")
        later = sorted(set(inst[after].tolist()))
        warnings.warn(
            f"TUBE_NEUF at INST = {at:g}: the new tube's depths at the {len(later)} later "
            f"instant{'s' if len(later) > 1 else ''} of the table ({later[0]:g} .. "
            f"{later[-1]:g}) are NaN, not computed: the table carries no contact geometry (a "
            "Code_Aster table read from its file). Its volumes are right; for the depths, "
            "replace the tube at the table's last instant and continue with ETAT_INIT, or "
            "compute the table with tube_replacement= ([time] tube_replacement) and the "
            "geometry", FretwearWarning, stacklevel=2)
    attrs["tube_replacement"] = at
    if case is not None and at >= case.origin:  # the case that computes the table now
        attrs["case"] = case.replace(tube_replacement=at).to_dict()
    else:  # replaced among a restart's earlier rows: no case computes this table
        attrs.pop("case", None)
    out.attrs = attrs
    return to_aster_names(out) if aster else out


def _sector_keys(frame: pd.DataFrame) -> np.ndarray:
    """A key per row: its sector number, or -1 for a global row (no sector)."""
    if "sector" not in frame.columns:
        return np.full(len(frame), -1.0)
    sector = pd.to_numeric(frame["sector"], errors="coerce").to_numpy(dtype=float)
    return np.where(np.isnan(sector), -1.0, sector)


def _restarted(values: pd.Series, keys: np.ndarray, inst: np.ndarray, at: float, tol: float,
               new: np.ndarray) -> np.ndarray:
    """A cumulated column minus its value at ``at`` (per sector key) on the ``new`` rows."""
    out = pd.to_numeric(values, errors="coerce").to_numpy(dtype=float).copy()
    for key in np.unique(keys[new]):
        group = keys == key
        base_rows = np.flatnonzero(group & (inst <= at + tol))
        base = 0.0 if base_rows.size == 0 else out[base_rows[-1]]
        rows = group & new
        out[rows] = np.maximum(out[rows] - (0.0 if np.isnan(base) else base), 0.0)
    return out


def _geometry(case):
    """The geometry of a table's wear case: its contact's, or the sector dimensions alone."""
    if case.contact_type is None:
        return SectorGeometry(**{k: v for k, v in case.dimensions.items() if k in
                                 ("mobile_radius", "obstacle_width", "obstacle_radius")})
    return case.geometry


def _restarted_depths(out: pd.DataFrame, new: np.ndarray, on: np.ndarray, geometry,
                      keys: np.ndarray) -> None:
    """Depths of the new tube (and the obstacle's, which may depend on both volumes)."""
    if geometry is None:
        for col in ("depth_mobile", "depth_mobile_sector"):
            if col in out.columns:
                values = out[col].to_numpy(dtype=float).copy()
                values[new] = np.nan
                values[on] = 0.0
                out[col] = values
        return
    if "depth_mobile" in out.columns and "volume_mobile" in out.columns:
        vm = out.loc[new, "volume_mobile"].to_numpy(dtype=float)
        vo = (np.nan_to_num(out.loc[new, "volume_obstacle"].to_numpy(dtype=float))
              if "volume_obstacle" in out.columns else np.zeros_like(vm))
        dm, do = geometry.depth_from_volume(vm, vo)
        out.loc[new, "depth_mobile"] = dm
        if "depth_obstacle" in out.columns:
            out.loc[new, "depth_obstacle"] = np.where(vo == 0, 0.0, do)
    if "depth_mobile_sector" in out.columns and "volume_mobile_cumulated" in out.columns:
        rows = new & (keys >= 0)
        arc = (out.loc[rows, "angle_end"].to_numpy(dtype=float)
               - out.loc[rows, "angle_start"].to_numpy(dtype=float))
        out.loc[rows, "depth_mobile_sector"] = sector_depth_mobile(
            out.loc[rows, "volume_mobile_cumulated"].to_numpy(dtype=float),
            geometry.mobile_radius, geometry.obstacle_width, arc)
