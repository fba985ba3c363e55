"""What the operational assessment needs of each contact of a bundle: its depth model, its
limit, and the field's inspection of it.

A bundle's results (:class:`fretwear.bundle.BundleResult` or :func:`fretwear.bundle.load`)
carry, per contact, the law, the geometry, the wear power and the wall: the depth model of
its global depth is built from them directly (:func:`bundle_models`, no table read per
contact: 10⁵ contacts in seconds). The inspections are one row per inspected contact
(:func:`field_inspections`): a sized depth, or no detectable degradation (NDD), or a tube
plugged already.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table.depth import DepthModel

__all__ = ["bundle_models", "field_inspections", "tube_label"]

#: Columns of a field inspection table (:func:`field_inspections`): name -> (unit, meaning).
FIELD_COLUMNS = {
    "contact": ("-", "contact (as in the bundle's manifest)"),
    "instant": ("time unit of the bundle", "instant of the inspection"),
    "depth": ("m", "sized depth of the tube (or depth_mm [mm]); empty with result NDD"),
    "result": ("-", "'NDD' (no detectable degradation) or empty (a sized depth)"),
    "plugged": ("-", "true: the tube is plugged already (out of the assessment)"),
}


def tube_label(row, column) -> str:
    """The tube's name on the tube sheet, ``R<row>C<column>`` (``R4C2``)."""
    def text(v):
        try:
            f = float(v)
            return str(int(f)) if f.is_integer() else str(v)
        except (TypeError, ValueError):
            return str(v)
    return f"R{text(row)}C{text(column)}"


def bundle_models(result: Any, *, limit: float | None = None) -> pd.DataFrame:
    """The global-depth :class:`~fretwear.table.depth.DepthModel` of every computed contact.

    Parameters
    ----------
    result : BundleResult
        A bundle's results (``contacts`` with law, geometry, power [W], wall [m], time scale
        [s per unit]; ``table`` for a restart's volume at its origin).
    limit : float, optional
        Plugging limit as a fraction of the wall [-] (default each contact's ``depth_limit``).

    Returns
    -------
    DataFrame
        One row per computed contact: ``contact``, ``tube`` (``R<row>C<col>``), ``tube_row``,
        ``tube_column``, ``support``, ``model`` (DepthModel), ``wall_thickness`` [m],
        ``limit_depth`` [m], ``time_unit``, ``time_scale`` [s per unit], ``origin`` and
        ``last_instant`` [time unit], ``depth_last`` [m] (the bundle's depth at its last
        instant).

    Raises
    ------
    InputError
        A contact without a wall thickness, or a law not linear in time (the assessment's
        growth is the law's volume linear in time: Archard, KWU-EPRI).
    """
    contacts = result.contacts
    done = contacts[contacts["status"].isin(["done", "skipped", "stale"])
                    & contacts["law"].notna()]
    if done.empty:
        raise InputError("the bundle has no computed contact to assess")
    table = result.table
    last = table.drop_duplicates(["contact", "instant"]).sort_values("instant", kind="stable") \
        .groupby("contact").tail(1)
    last = dict(zip(last["contact"].astype(str),
                    zip(last["instant"].to_numpy(float), last["depth_mobile"].to_numpy(float),
                        strict=True), strict=True))
    geometries: dict[Any, Any] = {}
    laws: dict[str, Any] = {}
    rows = []
    for c in done.itertuples(index=False):
        law = laws.get(c.law) or laws.setdefault(c.law, get_law(c.law))
        if not law.linear_in_time:
            raise InputError(f"contact {c.contact!r}: the law {c.law} is not linear in time; "
                             "the assessment's growth needs Archard or KWU-EPRI")
        wall = c.wall_thickness
        if wall is None or not math.isfinite(float(wall)):
            raise InputError(f"contact {c.contact!r} has no wall thickness: give the manifest's "
                             "wall_thickness_m (or the case's wall_thickness) to assess it")
        key = (c.contact_type, tuple(sorted(dict(c.dimensions).items())))
        if key not in geometries:
            geometries[key] = contact_geometry(c.contact_type, **dict(c.dimensions))
        fraction = float(c.depth_limit if limit is None else limit)
        origin = float(c.origin or 0.0)
        v0 = 0.0
        info = last.get(str(c.contact))
        if origin > 0 and "origin" in table.columns:  # a restart: the volume at its origin
            rows_c = table[(table["contact"] == c.contact) & (table["instant"] == origin)]
            v0 = float(rows_c["volume_mobile"].iloc[0]) if len(rows_c) else 0.0
        model = DepthModel(law=law, geometry=geometries[key], powers=(float(c.power),),
                           coefficients_mobile=(dict(c.coefficients_mobile),),
                           coefficients_obstacle=(None if c.coefficients_obstacle is None
                                                  else dict(c.coefficients_obstacle),),
                           time_scale=float(c.time_scale), origin=origin,
                           initial_mobile=v0, name=str(c.contact),
                           wall_thickness=float(wall), depth_limit=fraction)
        rows.append({"contact": str(c.contact), "tube": tube_label(c.tube_row, c.tube_column),
                     "tube_row": c.tube_row, "tube_column": c.tube_column,
                     "support": c.support, "model": model, "wall_thickness": float(wall),
                     "limit_depth": fraction * float(wall), "time_unit": c.time_unit,
                     "time_scale": float(c.time_scale), "origin": origin,
                     "last_instant": np.nan if info is None else info[0],
                     "depth_last": np.nan if info is None else info[1]})
    out = pd.DataFrame(rows)
    units = out["time_unit"].dropna().unique()
    if len(units) > 1:
        raise InputError(f"the bundle's contacts have different time units {list(units)}: an "
                         "interval needs one; give every contact the same [time] unit")
    return out


def _flag(value) -> bool:
    if isinstance(value, str):
        text = value.strip().lower()
        if text in ("", "0", "false", "no", "n", "nan"):
            return False
        if text in ("1", "true", "yes", "y"):
            return True
        raise InputError(f"plugged: {value!r} is not a yes/no value (true, false, 1, 0)")
    return bool(value) and not (isinstance(value, float) and math.isnan(value))


def field_inspections(source) -> pd.DataFrame:
    """One outage's inspections (:data:`FIELD_COLUMNS`) from a CSV file or a DataFrame.

    A row with a depth is a sized indication; ``result = NDD`` (or an empty depth) is an
    inspected contact where nothing was detected; ``plugged = true`` takes the tube out.
    A contact without a row was not inspected.

    Returns
    -------
    DataFrame
        ``contact`` (str), ``instant`` [time unit], ``depth`` [m] (NaN for NDD), ``ndd``,
        ``plugged`` (bools).

    Examples
    --------
    >>> f = field_inspections(pd.DataFrame({"contact": ["a", "b"], "instant": [10, 10],
    ...                                     "depth_mm": [0.3, None]}))
    >>> f["ndd"].tolist(), f["depth"].tolist()[0]
    ([False, True], 0.0003)
    """
    if isinstance(source, pd.DataFrame):
        frame, where = source.copy(), "inspections"
    else:
        from fretwear.io.text_tables import read_text_table

        frame, where = read_text_table(source, "inspection file"), f"inspection file {source!s}"
    frame.columns = [str(c).strip() for c in frame.columns]
    known = set(FIELD_COLUMNS) | {"depth_mm", "measurement_sigma", "sector"}
    unknown = [c for c in frame.columns if c not in known]
    if unknown:
        raise InputError(f"{where}: unknown column(s) {unknown}; the columns are {sorted(known)}")
    for need in ("contact", "instant"):
        if need not in frame.columns:
            raise InputError(f"{where}: the column {need!r} is missing "
                             f"({FIELD_COLUMNS[need][1]})")
    scale = 1e-3 if "depth" not in frame.columns and "depth_mm" in frame.columns else 1.0
    raw = frame.get("depth", frame.get("depth_mm", pd.Series(np.nan, index=frame.index)))
    depth = pd.to_numeric(raw.replace("", np.nan), errors="coerce").to_numpy(float) * scale
    result = frame.get("result", pd.Series("", index=frame.index)).fillna("").astype(str)
    ndd = result.str.strip().str.upper().eq("NDD").to_numpy() | np.isnan(depth)
    bad = ~ndd & ~(depth > 0)
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise InputError(f"{where}, row {row + 1}: a sized depth must be > 0 (or result NDD "
                         f"for no detectable degradation), got {raw.iloc[row]!r}")
    instant = pd.to_numeric(frame["instant"], errors="coerce").to_numpy(float)
    if not np.isfinite(instant).all():
        row = int(np.flatnonzero(~np.isfinite(instant))[0])
        raise InputError(f"{where}, row {row + 1}: instant must be a number, got "
                         f"{frame['instant'].iloc[row]!r}")
    plugged = frame.get("plugged", pd.Series(False, index=frame.index))
    out = pd.DataFrame({"contact": frame["contact"].astype(str).str.strip(),
                        "instant": instant, "depth": np.where(ndd, np.nan, depth),
                        "ndd": ndd, "plugged": [_flag(v) for v in plugged]})
    twice = out["contact"].duplicated(keep=False)
    if twice.any():  # the latest inspection of a contact is its as-found state
        out = out.sort_values("instant", kind="stable").drop_duplicates("contact", keep="last")
    return out.reset_index(drop=True)
