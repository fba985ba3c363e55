"""Field inspections as they come from an outage: the reader of an inspection file.

An eddy-current campaign reports, per contact (or per tube location: row, column and support),
the date or instant of the inspection, the technique, and either a sized indication (a
measured depth in m, mm or % through-wall) or "no detectable degradation" (NDD), which is a
result, not a missing value: it says the flaw, if any, was too shallow for the technique to
see (:meth:`fretwear.assessment.technique.LogisticPOD.miss`). A tube that was not inspected
says nothing; a plugged tube is out of service.

:func:`read_field_inspections` reads a CSV (through the guard layer of
:mod:`fretwear.io.text_tables`: encodings, comments, ragged rows, duplicate labels, a pipe)
or a Parquet file, or takes a DataFrame, and returns an :class:`Inspections`: a table of
normalised columns in SI (:data:`FIELD_COLUMNS` for the output, :data:`INPUT_COLUMNS` for the
file) and the technique models that interpret it. Nothing the user gave is modified.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.assessment.technique import LogisticPOD
from fretwear.errors import InputError
from fretwear.io.guard import readable_file, reading
from fretwear.io.text_tables import number, read_text_table
from fretwear.timeunits import TIME_UNITS, time_unit_name

__all__ = ["DEPTH_WALLS_MAX", "FIELD_COLUMNS", "INPUT_COLUMNS", "Inspections", "Technique",
           "check_depths_within_walls", "read_field_inspections"]

DEPTH_WALLS_MAX = 5.0
"""The deepest measured depth taken as a real one, in walls [-]. The check is for a unit slip:
a value in mm in a metres column, or in µm in a mm column, is 1000 times too deep, so any
indication deeper than 5.5 µm (every technique's threshold is far above) typed so lands beyond
five walls of 1.09 mm. Below, a depth is kept, and past one wall said first, THROUGH THE WALL:
a tube worn through reads about one wall plus its sizing error, and a campaign drawn from the
depth model (whose scar goes on past the wall, into the tube: a bundle's forecast reports
130 %) reads more. Beyond five walls the depth is refused with the line, the column and the
likely unit."""

#: Columns of an inspection file: name -> (unit, meaning). A row names its contact (``contact``)
#: or its tube location (``tube_row``, ``tube_column``, optional ``support``); gives
#: ``instant`` or ``date``; a depth in one of ``depth``, ``depth_mm``, ``depth_pct``, or NDD.
INPUT_COLUMNS: dict[str, tuple[str, str]] = {
    "contact": ("-", "contact name as in the predictions (or tube_row/tube_column/support)"),
    "tube_row": ("-", "row of the tube in the tube sheet (integer)"),
    "tube_column": ("-", "column of the tube in the tube sheet (integer)"),
    "support": ("-", "support of the contact on that tube (e.g. AVB3); empty: every support"),
    "sector": ("1", "1-based sector of a sector depth; empty: the global depth"),
    "instant": ("time unit", "instant of the inspection (the predictions' time unit)"),
    "date": ("ISO 8601", "date of the inspection (needs origin_date=, the predictions' t = 0)"),
    "technique": ("-", "technique name (a key of techniques=); empty: the only one"),
    "depth": ("m", "measured depth; 'NDD' for no detectable degradation"),
    "depth_mm": ("mm", "measured depth in mm instead of depth; 'NDD' as well"),
    "depth_pct": ("% through-wall", "measured depth in % of the wall (needs the wall)"),
    "wall_thickness": ("m", "wall of the tube, for depth_pct (or the wall_thickness= argument)"),
    "result": ("-", "'NDD' (no detectable degradation) or 'sized'; default from the depth"),
    "inspected": ("yes/no", "whether the tube was inspected (default yes; no: no information)"),
    "plugged": ("yes/no", "whether the tube was already plugged (default no)"),
}

#: Columns of :attr:`Inspections.table`: name -> (unit, meaning).
FIELD_COLUMNS: dict[str, tuple[str, str]] = {
    "contact": ("-", "contact name ('' when the row gives a tube location)"),
    "tube_row": ("-", "tube row (NaN when not given)"),
    "tube_column": ("-", "tube column (NaN when not given)"),
    "support": ("-", "support ('' when not given)"),
    "sector": ("1", "1-based sector, NaN for the global depth"),
    "instant": ("time unit", "instant of the inspection (from date: (date − origin)/unit)"),
    "date": ("-", "date of the inspection (NaT when given as an instant)"),
    "technique": ("-", "technique name, a key of Inspections.techniques"),
    "status": ("-", "'sized', 'ndd' (no detectable degradation) or 'not inspected'"),
    "depth": ("m", "measured depth of a sized indication (NaN otherwise)"),
    "plugged": ("-", "the tube was plugged (bool)"),
    "line": ("-", "line of the file (row number for a DataFrame or Parquet)"),
}

STATUSES = ("sized", "ndd", "not inspected")
_YES = {"yes", "y", "true", "t", "1", "oui", "x"}
_NO = {"no", "n", "false", "f", "0", "non"}
_NDD = {"ndd", "nd", "no detectable degradation", "nodd"}


@dataclass(frozen=True)
class Technique:
    """An inspection technique: its sizing error and its probability of detection.

    Parameters
    ----------
    sizing : SizingModel or LogSizingModel
        measured = a + b·true + e (:class:`fretwear.assessment.technique.SizingModel`).
    pod : LogisticPOD, optional
        Probability of detection; needed where the inspections hold an NDD.
    name : str
        The technique's name in the inspection file.
    illustrative : bool
        True for values that are not a qualified technique's (shipped examples).
    """

    sizing: Any
    pod: LogisticPOD | None = None
    name: str = ""
    illustrative: bool = False

    def __post_init__(self) -> None:
        if not callable(getattr(self.sizing, "likelihood", None)):
            raise InputError(f"technique {self.name!r}: sizing must be a SizingModel (measured = "
                             f"a + b·true + e), got {type(self.sizing).__name__}")
        if self.pod is not None and not isinstance(self.pod, LogisticPOD):
            raise InputError(f"technique {self.name!r}: pod must be a LogisticPOD, e.g. "
                             f"LogisticPOD.from_depths(a50=2e-4, a90=4e-4), got "
                             f"{type(self.pod).__name__}")


@dataclass(frozen=True, eq=False)
class Inspections:
    """An inspection campaign read from the field's file.

    Attributes
    ----------
    table : DataFrame
        One row per inspection result, the columns of :data:`FIELD_COLUMNS` (SI: depth [m]).
    techniques : dict
        Technique name -> :class:`Technique` (every name in ``table['technique']`` is a key).
    source : str
        Where the table came from (a file name, or ``"DataFrame"``).
    depth_column : str
        The column the depths were read from (``depth`` [m], ``depth_mm``, ``depth_pct``).
    """

    table: pd.DataFrame
    techniques: Mapping[str, Technique] = field(default_factory=dict)
    source: str = "DataFrame"
    depth_column: str = "depth"

    def rows(self, status: str) -> pd.DataFrame:
        """The rows of one ``status`` ('sized', 'ndd' or 'not inspected')."""
        if status not in STATUSES:
            raise InputError(f"status must be one of {STATUSES}, got {status!r}")
        return self.table[self.table["status"] == status]

    def counts(self) -> dict[str, int]:
        """Number of rows of each status, and of plugged rows."""
        out = {s: int((self.table["status"] == s).sum()) for s in STATUSES}
        out["plugged"] = int(self.table["plugged"].sum())
        return out

    def __str__(self) -> str:
        c = self.counts()
        return (f"inspections from {self.source}: {c['sized']} sized, {c['ndd']} NDD, "
                f"{c['not inspected']} not inspected, {c['plugged']} plugged")


# ---------------------------------------------------------------------- cells
def _flag(cell, default: bool, where: str, name: str) -> bool:
    if cell is None or (isinstance(cell, float) and math.isnan(cell)):
        return default
    if isinstance(cell, bool | np.bool_):
        return bool(cell)
    text = str(cell).strip().lower()
    if not text:
        return default
    if text in _YES:
        return True
    if text in _NO:
        return False
    raise InputError(f"{where}: {name} must be yes or no, got {_short(cell)!r}")


def _short(cell) -> str:
    text = str(cell)
    return text if len(text) <= 40 else text[:37] + "..."


def _text(cell) -> str:
    if cell is None or (isinstance(cell, float) and math.isnan(cell)):
        return ""
    return str(cell).strip()


def _is_ndd(cell) -> bool:
    return _text(cell).lower() in _NDD


def _date(cell, where: str):
    if not _text(cell):
        return pd.NaT
    try:
        value = pd.Timestamp(cell) if not isinstance(cell, str) else pd.Timestamp(cell.strip())
    except (ValueError, TypeError, OverflowError):
        value = pd.NaT
    if value is pd.NaT or pd.isna(value):
        raise InputError(f"{where}: date must be an ISO 8601 date (2024-05-17), got "
                         f"{_short(cell)!r}")
    return value.tz_localize(None) if value.tzinfo is not None else value


# ---------------------------------------------------------------------- reading
def _load(source) -> tuple[pd.DataFrame, str, list]:
    if isinstance(source, pd.DataFrame):
        return source.copy(), "inspections (DataFrame)", []
    if not isinstance(source, str | os.PathLike):
        raise InputError(f"inspections must be a CSV or Parquet path or a DataFrame, got "
                         f"{type(source).__name__}")
    label = f"inspection file {os.fspath(source)!r}"
    if Path(os.fspath(source)).suffix.lower() in (".parquet", ".pq"):
        file = readable_file(source, "inspection file")
        with reading(file, "parquet", "inspection file"):
            frame = pd.read_parquet(file)
        return frame.astype(object), label, []
    frame = read_text_table(source, "inspection file")
    return frame, label, list(frame.attrs.get("lines") or [])


def _where(label: str, lines: list, row: int) -> str:
    return f"{label}, " + (f"line {lines[row]}" if lines else f"row {row + 1}")


def _check_columns(frame: pd.DataFrame, label: str) -> None:
    if len(set(frame.columns)) != len(frame.columns):
        raise InputError(f"{label}: a column is given twice ({list(frame.columns)}); keep one")
    unknown = [c for c in frame.columns if c not in INPUT_COLUMNS]
    if unknown:
        raise InputError(f"{label}: unknown column(s) {unknown}; the columns are "
                         f"{list(INPUT_COLUMNS)} (fretwear calibrate --help gives their units)")
    if "contact" not in frame and not {"tube_row", "tube_column"} <= set(frame):
        raise InputError(f"{label}: say where each inspection is: a contact column, or "
                         "tube_row and tube_column (and support)")
    if "instant" not in frame and "date" not in frame:
        raise InputError(f"{label}: the column instant [time unit] or date [ISO 8601] is "
                         "missing")
    depths = [c for c in ("depth", "depth_mm", "depth_pct") if c in frame]
    if len(depths) > 1:
        raise InputError(f"{label}: give the depth in one column, not {depths} (depth [m], "
                         "depth_mm [mm] or depth_pct [% through-wall])")
    if not len(frame):
        raise InputError(f"{label}: the table has no rows")


def _depth(value: float, column: str, wall: float, where: str) -> float:
    if column == "depth_pct":
        if not (math.isfinite(wall) and wall > 0):
            raise InputError(f"{where}: depth_pct needs the tube's wall: give a wall_thickness "
                             "column [m] or the wall_thickness= argument (--wall-mm)")
        if not (math.isfinite(value) and 0 < value <= 100):
            raise InputError(f"{where}: depth_pct must be in (0, 100] [% through-wall], got "
                             f"{value!r}; write NDD for no detectable degradation")
        return value / 100.0 * wall
    unit = {"depth": "m", "depth_mm": "mm"}[column]
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{where}: {column} must be a finite number > 0 [{unit}], got "
                         f"{value!r}; write NDD for no detectable degradation")
    depth = value * (1e-3 if column == "depth_mm" else 1.0)
    if math.isfinite(wall) and wall > 0:
        _within_walls(depth, value, column, wall, where)
    return depth


def _within_walls(depth: float, value, column: str, wall: float, where: str) -> None:
    """Refuse a depth [m] beyond :data:`DEPTH_WALLS_MAX` walls ``wall`` [m], guessing the
    unit."""
    if depth <= DEPTH_WALLS_MAX * wall:
        return
    guess = {"depth": f"a value in mm? ({value:g} mm is {value * 1e-3:g} m; or give the "
                      "column depth_mm)",
             "depth_mm": f"a value in µm? ({value:g} µm is {value * 1e-3:g} mm)"}[column]
    raise InputError(f"{where}: {column} = {value:g} [{'m' if column == 'depth' else 'mm'}] "
                     f"is {depth / wall:.3g} walls of {wall * 1e3:.4g} mm, deeper than any "
                     f"tube's wear (up to {DEPTH_WALLS_MAX:g} walls is taken as through the "
                     f"wall): {guess}")


def check_depths_within_walls(inspections: Inspections, contacts: pd.DataFrame) -> None:
    """Refuse a sized depth deeper than :data:`DEPTH_WALLS_MAX` walls of its tube.

    Parameters
    ----------
    inspections : Inspections
        The campaign (its depths [m], lines and source).
    contacts : DataFrame
        ``contact``, ``wall_thickness`` [m] and, for rows given by tube location,
        ``tube_row`` and ``tube_column`` (the tube's thinnest wall is used).

    Raises
    ------
    InputError
        Naming the file, the line, the column and the likely unit (a value in mm in a metres
        column). Rows whose contact or tube is not among ``contacts`` are left to the
        caller's own check.

    Examples
    --------
    >>> ins = read_field_inspections(pd.DataFrame({"contact": ["a"], "instant": [10],
    ...                                            "depth": [0.5]}))
    >>> check_depths_within_walls(ins, pd.DataFrame({"contact": ["a"],
    ...                                              "wall_thickness": [1.09e-3]}))
    Traceback (most recent call last):
    ...
    fretwear.errors.InputError: inspections (DataFrame), line 1: depth = 0.5 [m] is 459 walls
    of 1.09 mm, deeper than any tube's wear (up to 5 walls is taken as through the wall):
    a value in mm? (0.5 mm is 0.0005 m; or give the column depth_mm)
    """
    t = inspections.table
    sized = t[(t["status"] == "sized") & t["depth"].notna()]
    if sized.empty or inspections.depth_column == "depth_pct":
        return  # % through-wall is bounded by 100 when read
    walls = contacts.drop_duplicates("contact").set_index("contact")["wall_thickness"]
    by_tube = (contacts.groupby(["tube_row", "tube_column"])["wall_thickness"].min()
               if {"tube_row", "tube_column"} <= set(contacts) else None)
    label = inspections.source if inspections.source != "DataFrame" \
        else "inspections (DataFrame)"
    scale = 1e3 if inspections.depth_column == "depth_mm" else 1.0
    for r in sized.itertuples(index=False):
        if r.contact:
            wall = walls.get(r.contact, math.nan)
        elif by_tube is not None:
            wall = by_tube.get((r.tube_row, r.tube_column), math.nan)
        else:
            continue
        wall = float(wall) if wall is not None else math.nan
        if math.isfinite(wall) and wall > 0:
            _within_walls(float(r.depth), float(r.depth) * scale, inspections.depth_column,
                          wall, f"{label}, line {r.line}")


def _row(cols, i: int, where: str, depth_col: str | None, wall: float) -> dict[str, Any]:
    cell = {c: column[i] for c, column in cols.items()}
    inspected = _flag(cell.get("inspected"), True, where, "inspected")
    plugged = _flag(cell.get("plugged"), False, where, "plugged")
    raw = cell.get(depth_col) if depth_col else None
    result = _text(cell.get("result")).lower()
    if result and result not in _NDD and result != "sized":
        raise InputError(f"{where}: result must be NDD or sized, got {_short(result)!r}")
    ndd = result in _NDD or _is_ndd(raw)
    depth = math.nan
    if not inspected:
        if _text(raw) or result:
            raise InputError(f"{where}: a result on a tube not inspected (inspected = no); "
                             "leave the depth empty or set inspected = yes")
        status = "not inspected"
    elif ndd:
        if _text(raw) and not _is_ndd(raw):
            raise InputError(f"{where}: NDD with a depth {_short(raw)!r}; give one of them")
        status = "ndd"
    else:
        if depth_col is None or not _text(raw):
            raise InputError(f"{where}: an inspected tube with no depth; give the measured depth "
                             "or NDD (no detectable degradation), or inspected = no")
        row_wall = number(cell["wall_thickness"]) if "wall_thickness" in cell \
            and _text(cell["wall_thickness"]) else wall
        depth = _depth(number(raw), depth_col, row_wall, where)
        status = "sized"
    return {"status": status, "depth": depth, "plugged": plugged}


def _instant(cell_instant, cell_date, where: str, origin, seconds: float) -> tuple:
    date = _date(cell_date, where) if cell_date is not None else pd.NaT
    if _text(cell_instant):
        value = number(cell_instant)
        if not math.isfinite(value):
            raise InputError(f"{where}: instant must be a finite number [time unit], got "
                             f"{_short(cell_instant)!r}")
        return value, date
    if date is pd.NaT:
        raise InputError(f"{where}: no instant and no date; give one")
    if origin is None:
        raise InputError(f"{where}: a date needs the predictions' origin as a date: "
                         "origin_date='2012-01-01' (--origin-date), or give an instant column")
    return (date - origin).total_seconds() / seconds, date


def _location(cols, i: int, where: str) -> dict[str, Any]:
    out: dict[str, Any] = {"contact": _text(cols["contact"][i]) if "contact" in cols
                           else ""}
    for name in ("tube_row", "tube_column", "sector"):
        value = number(cols[name][i]) if name in cols and \
            _text(cols[name][i]) else math.nan
        if not math.isnan(value) and not (math.isfinite(value) and value == int(value)
                                          and (value >= 1 or name != "sector")):
            raise InputError(f"{where}: {name} must be an integer, got "
                             f"{_short(cols[name][i])!r}")
        out[name] = value
    out["support"] = _text(cols["support"][i]) if "support" in cols else ""
    if not out["contact"] and (math.isnan(out["tube_row"]) or math.isnan(out["tube_column"])):
        raise InputError(f"{where}: no contact and no tube location (tube_row, tube_column); "
                         "give one")
    return out


def _techniques(techniques, names: set[str], label: str) -> dict[str, Technique]:
    if isinstance(techniques, Technique):
        techniques = {techniques.name: techniques}
    techniques = dict(techniques or {})
    for key, value in techniques.items():
        if not isinstance(value, Technique):
            raise InputError(f"techniques[{key!r}] must be a Technique(sizing, pod), got "
                             f"{type(value).__name__}")
    missing = sorted(n for n in names if n not in techniques)
    if missing and not (missing == [""] and len(techniques) == 1):
        raise InputError(f"{label}: technique(s) {missing} have no model; give "
                         f"techniques={{name: Technique(SizingModel(...), LogisticPOD(...))}} "
                         f"(known: {sorted(techniques)})")
    return techniques


def read_field_inspections(source, techniques=None, *, origin_date=None,
                           time_unit: str = "year",
                           wall_thickness: float | None = None) -> Inspections:
    """Read an inspection campaign (CSV, Parquet or DataFrame) into an :class:`Inspections`.

    Parameters
    ----------
    source : path-like or DataFrame
        The file (columns :data:`INPUT_COLUMNS`; ``.parquet``/``.pq`` read as Parquet, any
        other name as delimited text) or a DataFrame (not modified).
    techniques : Technique or mapping of str to Technique, optional
        The model of each technique named in the file (one technique serves rows without a
        name). Optional only for reading; calibration needs them.
    origin_date : str or Timestamp, optional
        The date of the predictions' instant 0, to turn a ``date`` into an instant.
    time_unit : str
        The predictions' time unit for dates (a name of :data:`fretwear.timeunits.TIME_UNITS`).
    wall_thickness : float, optional
        Wall of the tubes [m] for ``depth_pct`` where the file has no wall_thickness column.

    Returns
    -------
    Inspections
        ``table`` with the columns of :data:`FIELD_COLUMNS`, in the file's order.

    Raises
    ------
    InputError, FormatError
        Naming the file, the line and the fix: an unknown column, a depth ≤ 0, a result on a
        tube not inspected, an inspected tube without a depth or NDD, an unknown technique.

    Examples
    --------
    >>> frame = pd.DataFrame({"tube_row": [4, 4, 5], "tube_column": [2, 3, 1],
    ...                       "support": ["AVB1", "AVB1", ""], "instant": [10, 10, 10],
    ...                       "depth_pct": ["32", "NDD", ""], "inspected": ["", "", "no"]})
    >>> ins = read_field_inspections(frame, wall_thickness=1.09e-3)
    >>> ins.table["status"].tolist()
    ['sized', 'ndd', 'not inspected']
    >>> round(float(ins.table["depth"].iloc[0]) * 1e3, 4)   # 32 % of 1.09 mm [mm]
    0.3488
    """
    frame, label, lines = _load(source)
    frame.columns = [str(c).strip() for c in frame.columns]
    _check_columns(frame, label)
    unit = time_unit_name(time_unit)
    if unit not in TIME_UNITS:
        raise InputError(f"time_unit must be one of {sorted(TIME_UNITS)}, got {time_unit!r}")
    origin = None if origin_date is None else _date(origin_date, "origin_date")
    wall = math.nan if wall_thickness is None else float(wall_thickness)
    depth_col = next((c for c in ("depth", "depth_mm", "depth_pct") if c in frame), None)
    rows = []
    cols = {c: frame[c].to_numpy() for c in frame.columns}  # read once, not a cell at a time
    for i in range(len(frame)):
        where = _where(label, lines, i)
        row = _location(cols, i, where)
        row["instant"], row["date"] = _instant(
            cols["instant"][i] if "instant" in cols else None,
            cols["date"][i] if "date" in cols else None, where, origin, TIME_UNITS[unit])
        row["technique"] = _text(cols["technique"][i]) if "technique" in cols else ""
        row.update(_row(cols, i, where, depth_col, wall))
        row["line"] = lines[i] if lines else i + 1
        rows.append(row)
    table = pd.DataFrame(rows)[list(FIELD_COLUMNS)]
    table["date"] = pd.to_datetime(table["date"])
    table["plugged"] = table["plugged"].astype(bool)
    names = set(table["technique"])
    models = _techniques(techniques, names, label) if techniques is not None else {}
    if len(models) == 1 and names == {""}:
        only = next(iter(models))
        table["technique"] = only
    return Inspections(table=table, techniques=models,
                       source=label if not isinstance(source, pd.DataFrame) else "DataFrame",
                       depth_column=depth_col or "depth")
