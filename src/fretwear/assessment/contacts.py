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
from fretwear.table.case_values import Wall
from fretwear.table.depth import DepthModel

__all__ = ["bundle_models", "field_inspections", "tube_label"]

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
    cases = getattr(result, "cases", None) or {}
    rows = []
    for c in done.itertuples(index=False):
        law = laws.get(c.law) or laws.setdefault(c.law, get_law(c.law))
        if not law.linear_in_time:
            raise InputError(f"contact {c.contact!r}: the law {c.law} is not linear in time; "
                             "the assessment's growth needs Archard or KWU-EPRI")
        wall = c.wall_thickness
        if wall is None or not math.isfinite(float(wall)):
            raise InputError(f"contact {c.contact!r} has no wall thickness: give the case's "
                             "wall_thickness_m [m] to assess it")
        key = (c.contact_type, tuple(sorted(dict(c.dimensions).items())))
        if key not in geometries:
            geometries[key] = contact_geometry(c.contact_type, **dict(c.dimensions))
        fraction = float(c.depth_limit if limit is None else limit)
        case = cases.get(str(c.contact))
        # the case's wall as the bundle built it (checked there), else one from the record
        its = case.wall if case is not None and case.wall.thickness == float(wall) \
            and case.wall.limit == fraction else Wall(float(wall), fraction)
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
                           wall=its)
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


def field_inspections(source, contacts: pd.DataFrame | None = None, *, origin_date=None,
                      time_unit: str = "year") -> pd.DataFrame:
    """One outage's inspections, read by
    :func:`fretwear.assessment.inspections.read_field_inspections` (CSV, Parquet or a
    DataFrame: per contact or tube location, sized depth in m, mm or % through-wall, NDD,
    inspected, plugged), one row per contact.

    Parameters
    ----------
    source : path-like or DataFrame
    contacts : DataFrame, optional
        ``contact``, ``tube_row``, ``tube_column``, ``support`` of the bundle: a row giving a
        tube location stands for the contacts of that tube (of its support when given).
    origin_date, time_unit
        The date of the predictions' instant 0 and their time unit, for a ``date`` column.

    Returns
    -------
    DataFrame
        ``contact`` (str), ``instant`` [time unit], ``depth`` [m] (NaN for NDD), ``ndd``,
        ``plugged`` (bools); a contact's latest inspection; rows 'not inspected' only mark
        a tube plugged.

    Examples
    --------
    >>> f = field_inspections(pd.DataFrame({"contact": ["a", "b"], "instant": [10, 10],
    ...                                     "depth_mm": ["0.3", "NDD"]}))
    >>> f["ndd"].tolist(), f["depth"].tolist()[0]
    ([False, True], 0.0003)
    """
    from fretwear.assessment.inspections import Inspections, read_field_inspections

    table = source.table if isinstance(source, Inspections) else \
        read_field_inspections(source, origin_date=origin_date, time_unit=time_unit).table
    located = table["contact"].astype(str).str.len() == 0
    if located.any():
        if contacts is None:
            raise InputError("inspections by tube location need the bundle's contacts")
        ident = contacts[["contact", "tube_row", "tube_column", "support"]].astype(
            {"contact": str})
        rows = table[located].drop(columns="contact").reset_index(names="_row")
        merged = rows.merge(ident, on=["tube_row", "tube_column"], how="left",
                            suffixes=("", "_bundle"))
        keep = (merged["support"].astype(str).isin(["", "nan"])
                | (merged["support"].astype(str) == merged["support_bundle"].astype(str)))
        merged = merged[keep & merged["contact"].notna()]
        missing = sorted(set(rows["_row"]) - set(merged["_row"]))
        if missing:
            r = rows.set_index("_row").loc[missing[0]]
            raise InputError(f"inspection line {r['line']}: no contact of the bundle at tube "
                             f"row {r['tube_row']}, column {r['tube_column']}"
                             f"{', support ' + str(r['support']) if r['support'] else ''}")
        table = pd.concat([table[~located], merged[table.columns]], ignore_index=True)
    status = table["status"].to_numpy()
    out = pd.DataFrame({"contact": table["contact"].astype(str).to_numpy(),
                        "instant": table["instant"].to_numpy(float),
                        "depth": np.where(status == "sized", table["depth"], np.nan),
                        "ndd": status == "ndd",
                        "plugged": table["plugged"].astype(bool).to_numpy(),
                        "inspected": status != "not inspected"})
    plugged = set(out.loc[out["plugged"], "contact"])
    out = out[out["inspected"] | out["plugged"]]
    out = out.sort_values("instant", kind="stable").drop_duplicates("contact", keep="last")
    out["plugged"] = out["contact"].isin(plugged)
    uninspected = ~out.pop("inspected")
    out.loc[uninspected, "instant"] = np.nan  # plugged, not inspected: no as-found state
    return out.reset_index(drop=True)
