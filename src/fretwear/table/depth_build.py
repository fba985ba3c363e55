"""Building a :class:`~fretwear.table.DepthModel`: from a wear case (:func:`case_model`, the
model the wear table is computed by) and from a wear table's rows and metadata
(:func:`models_from_table`, :func:`model_from_table`: the uncertainty propagation and the
calibration of tables read back). The few places that read a case or a table into a model.
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.laws import get_law
from fretwear.table.case import WearCase
from fretwear.table.case_values import Wall
from fretwear.table.depth import DepthModel, _geometry
from fretwear.table.depth_rows import EarlierRows
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT
from fretwear.table.provenance import provenance

__all__ = ["carried_case", "case_model", "model_from_table", "models_from_table", "record_model",
           "record_wall", "table_case", "table_record"]

_TIME_TOL = 1e-9


# ---------------------------------------------------------------------- from a wear case
def case_model(case, power: float, result, mobile, obstacle, fresh: float | None,
               geometry) -> DepthModel:
    """The :class:`DepthModel` of a wear case (the model the wear table's columns and limits
    are computed by): at its power [W] (``result``'s sector powers in sector mode: one term a
    sector), the bodies' coefficients ``mobile`` and ``obstacle`` (native names; None: it does
    not wear), a tube replaced ``fresh`` seconds after the origin (None: not), the case's
    ``geometry``; a restart's earlier rows and volumes at the origin from its initial state.

    Everything but the power is the case's (:func:`_case_parts`: made once per case and
    coefficients, kept on the case; a bundle's contacts of one case differ by their power).
    """
    if case.sectors is None:
        powers = (float(power),)
        edges = None
    else:
        powers = tuple(np.asarray(result.sectors, dtype=float).tolist())
        edges = tuple(np.asarray(result.sector_edges, dtype=float).tolist())
    parts = _case_parts(case, mobile, obstacle, len(powers), edges)
    return DepthModel(law=case.wear_law, geometry=geometry, powers=powers,
                      time_scale=case.time_scale, origin=case.origin, wall=case.wall,
                      replacement=fresh, **parts)


#: The most sets of coefficients whose model parts a case keeps (:func:`_case_parts`).
_PARTS_KEPT = 16


def _case_parts(case, mobile, obstacle, m: int, edges) -> dict[str, Any]:
    """The keywords of the case's :class:`DepthModel` but its power (:func:`case_model`):
    the coefficients of each term, the volumes at the origin, the sectors' arcs and earlier
    rows. Kept on the case (:meth:`WearCase.derived`: two cases never share them) by the
    coefficients' values, the number of terms and the sector ``edges`` [deg] (a KWU-EPRI
    intensity from each contact's history makes other coefficients; at most
    :data:`_PARTS_KEPT` kept). A new dict each call (the values shared: immutable)."""
    key = (None if mobile is None else tuple(mobile.items()),
           None if obstacle is None else tuple(obstacle.items()), m, edges)
    kept = case.derived("depth model parts", dict)
    try:
        found = kept.get(key)
    except TypeError:  # a coefficient that is not hashable (an array): made each time
        return _make_parts(case, mobile, obstacle, m, edges)
    if found is None:
        if len(kept) >= _PARTS_KEPT:
            kept.clear()
        found = kept[key] = _make_parts(case, mobile, obstacle, m, edges)
    return dict(found)


def _make_parts(case, mobile, obstacle, m: int, edges) -> dict[str, Any]:
    """:func:`_case_parts` made (the case's values read as :func:`case_model` always did)."""
    state = case.restart.table
    if case.sectors is None:
        parts = {"coefficients_mobile": (_copy(mobile),),
                 "coefficients_obstacle": (_copy(obstacle),),
                 "initial_mobile": 0.0 if state is None else state.volume_mobile,
                 "initial_obstacle": 0.0 if state is None else state.volume_obstacle}
    else:
        key = case.wear_law.parameters[0]
        k_m, k_o = _case_sector_coefficients(case, m, mobile, obstacle)
        pm = np.zeros(m) if state is None else np.asarray(state.sector_volume_mobile, float)
        po = np.zeros(m) if state is None else np.asarray(state.sector_volume_obstacle, float)
        parts = {"coefficients_mobile": _sector_dicts(key, k_m),
                 "coefficients_obstacle": (None,) * m if k_o is None
                 else _sector_dicts(key, k_o),
                 "initial_mobile": float(np.sum(pm)), "initial_obstacle": float(np.sum(po)),
                 "sector_arcs": tuple(np.diff(np.asarray(edges, dtype=float)).tolist()),
                 "term_initial": (tuple(pm.tolist()), tuple(po.tolist())),
                 # the bore radius of the sectors, also beside a type that has none (§3)
                 "sector_obstacle_radius": case.dimensions.get("obstacle_radius")}
        if state is not None and len(state.rows):  # read at their first use (a limit)
            parts["sector_rows"] = functools.partial(_earlier_sectors, state.rows,
                                                     case.origin, m)
    if state is not None and len(state.rows):  # read at their first use (a limit)
        parts["rows"] = functools.partial(EarlierRows.from_rows, state.rows, case.origin)
    return parts


def _sector_dicts(key: str, values: np.ndarray) -> tuple[dict, ...]:
    """Each sector's coefficients ``{key: value}`` (plain floats: WearLaw.rate), one dict for
    every sector when they all have the same value (the law's rates then in one call)."""
    values = values.tolist()
    if all(v == values[0] for v in values):
        return ({key: values[0]},) * len(values)
    return tuple({key: v} for v in values)


def _copy(coefficients: dict | None) -> dict | None:
    """A copy of a body's coefficients (the caller's dict stays the caller's)."""
    return None if coefficients is None else dict(coefficients)


def _earlier_sectors(rows, origin: float, m: int) -> tuple:
    """The earlier rows of each of the ``m`` sectors of a restart's rows."""
    return tuple(EarlierRows.from_rows(_sector_rows(rows, j + 1), origin,
                                       column="depth_mobile_sector",
                                       volumes=("volume_mobile_cumulated", None))
                 for j in range(m))


def _sector_rows(rows, sector: int):
    """The rows of one sector (1-based) of a table's rows; none without sector rows."""
    if "sector" not in rows.columns or "depth_mobile_sector" not in rows.columns:
        return rows.iloc[:0]
    return rows[np.asarray(rows["sector"], dtype=float) == sector]


def _case_sector_coefficients(case, m: int, mobile, obstacle):
    """(mobile [m], obstacle [m] or None) Archard coefficients [1/Pa] of the ``m`` sectors:
    the case's sector coefficients (a missing obstacle one is 0 when others wear), else the
    law's coefficient in every sector."""
    key = case.wear_law.parameters[0]
    if case.sector_coefficients is None:
        k_o = None if obstacle is None else obstacle.get(key)
        return np.full(m, mobile[key]), (None if k_o is None else np.full(m, k_o))
    km = np.array([p[0] for p in case.sector_coefficients])
    ko = np.array([np.nan if p[1] is None else p[1] for p in case.sector_coefficients])
    if np.isnan(ko).all():
        return km, None
    return km, np.nan_to_num(ko, nan=0.0)


# ---------------------------------------------------------------------- from a wear table
#: Where a wear table keeps the case it was computed from: ``attrs["case"]`` (the table of
#: :func:`~fretwear.table.wear_table`), or the provenance of a file fretwear wrote
#: (``attrs["provenance"]["case"]``, :func:`fretwear.table.read_wear_table`).
_NO_CASE = ("the wear table carries no wear case (neither attrs['case'], as wear_table "
            "returns it, nor a 'case' in the provenance of a CSV or Parquet file written by "
            "fretwear): {what}. Give the case it was computed from, models_from_table(table, "
            "case=WearCase.from_keywords(...)), or compute the table again with wear_table and "
            "write it as .parquet or .csv")


def table_record(table: pd.DataFrame) -> dict:
    """The record of the run a wear table carries: its provenance
    (:func:`fretwear.table.provenance.provenance`), read from the file it came from
    (``attrs["provenance"]``) or made from the ``attrs`` of :func:`~fretwear.table.wear_table`.

    Holds ``case`` (:meth:`WearCase.to_dict`), ``power`` (``total`` [W], ``sectors`` [W]) and
    ``coefficients`` (``"<body>.<name>"`` -> ``{"value", "source"}``: resolved, a history's
    KWU-EPRI intensity included) when the table has them.
    """
    attrs = getattr(table, "attrs", None) or {}
    if "case" in attrs:  # wear_table's own table
        return provenance(attrs)
    return dict(attrs.get("provenance") or {})


def carried_case(table: pd.DataFrame) -> WearCase | None:
    """The :class:`WearCase` a wear table carries (:func:`table_case`), or None where it
    carries none (a Code_Aster table, a file written before the case was kept)."""
    record = table_record(table)
    return table_case(table, record) if isinstance(record.get("case"), dict) else None


def table_case(table: pd.DataFrame, record: dict | None = None) -> WearCase:
    """The :class:`WearCase` a wear table was computed from, rebuilt once from its record
    (:func:`table_record`: ``attrs["case"]``, or the provenance of a file fretwear wrote).

    Raises
    ------
    InputError
        The table carries no case (a Code_Aster table, a file written before the case was
        kept, a table whose ``attrs`` a pandas operation dropped), naming the fix.
    """
    record = table_record(table) if record is None else record
    data = record.get("case")
    if not isinstance(data, dict):
        what = ("it was read from a file whose provenance has no case: a Code_Aster text "
                "table, or a file written before fretwear kept the case"
                if record else "its attrs are empty (a Code_Aster table, or attrs dropped by "
                "a pandas operation)")
        raise InputError(_NO_CASE.format(what=what))
    return WearCase.from_dict(data)


@dataclasses.dataclass(frozen=True)
class _Run:
    """What a table's models are built from: the case's values (law, geometry, time axis,
    tube replacement, wall, sectors) and the run's outputs the case does not hold (the power
    [W], per sector too; the coefficients resolved, a history's KWU-EPRI intensity included)."""

    law: Any
    geometry: Any
    time_scale: float
    origin: float
    replacement: float | None
    wall: Wall
    edges: np.ndarray | None
    sector_coefficients: Any
    mobile: dict
    obstacle: dict | None
    power: float
    sector_powers: np.ndarray | None


def _run(table: pd.DataFrame, case: WearCase | None) -> _Run:
    """The :class:`_Run` of a table: from ``case`` or the case the table carries; a bundle's
    contact table (:func:`fretwear.report.bundle_predictions`) from its record instead."""
    attrs = getattr(table, "attrs", None) or {}
    if case is None and _BUNDLE_RECORD in attrs:
        return _record_run(table, attrs[_BUNDLE_RECORD])
    record = table_record(table)
    if case is not None and not isinstance(case, WearCase):
        raise InputError(f"case must be a WearCase, got {type(case).__name__}")
    carried = record.get("case")
    if case is None or (case.sectors is None and isinstance(carried, dict)
                        and carried.get("sectors") is not None):
        case = table_case(table, record)  # (the run's sectors: a PowerResult with sectors)
    resolved = record.get("coefficients") or {}
    bodies = []
    for body in ("mobile", "obstacle"):
        coefs = case.coefficient_values(body)
        if coefs is not None and case.wear_law.needs_history and coefs.get("intensity") is None:
            value = (resolved.get(f"{body}.intensity") or {}).get("value")
            if value is None:
                raise InputError(f"the wear table has no {body} intensity of the "
                                 f"{case.law} law (computed from the history): give the "
                                 "table wear_table returned, or a file fretwear wrote of it")
            coefs["intensity"] = float(value)
        bodies.append(coefs)
    power = record.get("power") or {}
    sectors = power.get("sectors")
    return _Run(case.wear_law, _geometry(case.contact_type, case.dimensions),
                float(case.time_scale), case.origin, case.restart.tube_replacement,
                case.wall, case.sector_edges,
                case.sector_coefficients, bodies[0], bodies[1],
                _total_power(table, power.get("total")),
                None if sectors is None else np.asarray(sectors, dtype=float))


def _total_power(table: pd.DataFrame, total) -> float:
    """The run's total power [W]: its record's, else the table's power column."""
    if total is None:
        if "power" not in table.columns or not len(table):
            raise InputError("the wear table has neither a power column nor the power in "
                             "its provenance")
        total = table["power"].iloc[-1]
    return float(total)


#: The ``attrs`` key of a bundle contact's record (:func:`fretwear.report.bundle_predictions`).
_BUNDLE_RECORD = "bundle_record"


def _record_run(table: pd.DataFrame, record: dict) -> _Run:
    """The :class:`_Run` of a bundle contact's record (``parts/*.json``: the values of its
    table's run, :data:`fretwear.bundle.tasks._ATTRS`; the bundle's records keep no case)."""
    missing = [k for k in ("contact_type", "dimensions", "law", "coefficients_mobile",
                           "time_scale") if record.get(k) is None]
    if missing:
        raise InputError(f"the bundle contact's record lacks {', '.join(missing)}: run the "
                         "bundle again (fretwear bundle -o DIR)")
    power = record.get("power") or {}
    sectors = power.get("sectors")
    edges = record.get("sector_edges")
    obstacle = record.get("coefficients_obstacle")
    return _Run(get_law(record["law"]), _geometry(record["contact_type"], record["dimensions"]),
                float(record["time_scale"]), float(record.get("origin") or 0.0),
                record.get("tube_replacement"), record_wall(record),
                None if edges is None else np.asarray(edges, dtype=float),
                record.get("sector_coefficients"), dict(record["coefficients_mobile"]),
                None if obstacle is None else dict(obstacle),
                _total_power(table, power.get("total")),
                None if sectors is None else np.asarray(sectors, dtype=float))


def _origin_rows(table: pd.DataFrame, origin: float) -> pd.DataFrame:
    tol = _TIME_TOL * max(1.0, abs(origin))
    at = table[np.asarray(table["instant"], dtype=float) <= origin + tol]
    if at.empty:
        return at
    last = float(at["instant"].iloc[-1])
    return at[np.abs(np.asarray(at["instant"], dtype=float) - last) <= tol]


def models_from_table(table: pd.DataFrame, *, case: WearCase | None = None,
                      sector_coefficients=None, wall: Wall | None = None, name: str = ""
                      ) -> dict[str, DepthModel]:
    """The models of a wear table: ``"global"`` and, in sector mode, ``"sector 1"`` ...

    The law, geometry, time axis, wall, sectors and tube replacement are the case's; the
    volumes at the origin and a restart's earlier rows are the table's rows; the power and the
    coefficients computed from a history are the run's (:func:`table_record`).

    Parameters
    ----------
    table : DataFrame
        A wear table from :func:`fretwear.table.wear_table` (``attrs["case"]``), or read back
        by :func:`fretwear.table.read_wear_table` from a CSV or Parquet file fretwear wrote
        (the case in its provenance).
    case : WearCase, optional
        The case the table was computed from (default: the one it carries, rebuilt once by
        :meth:`WearCase.from_dict`).
    sector_coefficients : sequence of (float, float or None), optional
        Archard coefficients (mobile, obstacle) [Pa⁻¹] per sector, as given to wear_table
        (default the case's, else the law's coefficients).
    wall : Wall, optional
        The tube's wall (thickness [m], limit [-]; default the case's, as it carries it).
    name : str
        Contact name.

    Returns
    -------
    dict of str to DepthModel

    Raises
    ------
    InputError
        The table carries no case (:func:`table_case`), or the tube is replaced after the
        origin (not modelled).

    Examples
    --------
    >>> from fretwear.table import wear_table
    >>> t = wear_table(0.01, contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...                dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...                coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> m = models_from_table(t)["global"]
    >>> bool(abs(m.depth(7.2e3)[()] / t["depth_mobile"].iloc[-1] - 1) < 1e-12)
    True
    """
    run = _run(table, case)
    origin = run.origin
    if run.replacement is not None and \
            float(run.replacement) > origin + _TIME_TOL * max(1, origin):
        raise InputError("the wear table replaces the tube after its origin (TUBE_NEUF): the "
                         "uncertainty model continues one tube; compute from the replacement on "
                         "(a restart of replace_tube's table)")
    law = run.law
    common = {"law": law, "geometry": run.geometry, "time_scale": run.time_scale,
              "origin": origin, "wall": run.wall if wall is None else wall}
    earlier = None
    if "origin" in table.columns and origin > 0:  # a restart: the initial table's rows first
        earlier = EarlierRows.from_rows(
            table[np.asarray(table["origin"], dtype=float) != origin], origin)
    mobile, obstacle = run.mobile, run.obstacle
    at = _origin_rows(table, origin)
    if run.edges is None:
        v0m = float(at["volume_mobile"].iloc[0]) if len(at) else 0.0
        v0o = float(at["volume_obstacle"].iloc[0]) if len(at) else 0.0
        return {"global": DepthModel(powers=(run.power,), coefficients_mobile=(mobile,),
                                     coefficients_obstacle=(obstacle,), initial_mobile=v0m,
                                     initial_obstacle=v0o, name=name, rows=earlier, **common)}
    edges = np.asarray(run.edges, dtype=float)
    m = edges.size - 1
    sector_powers = run.sector_powers
    if sector_powers is None or sector_powers.size != m:
        raise InputError("the sector table's record of the run lacks the sector powers: give "
                         "the table wear_table returned, or a file fretwear wrote of it")
    pairs = sector_coefficients if sector_coefficients is not None else \
        run.sector_coefficients
    key = law.parameters[0]
    k_m, k_o = _sector_pairs(pairs, m, mobile.get(key),
                             None if obstacle is None else obstacle.get(key))
    coefs_m = tuple({key: k} for k in k_m)
    coefs_o = tuple(None if k is None else {key: k} for k in k_o)
    v0m_s = np.zeros(m)
    v0o_s = np.zeros(m)
    if len(at):
        by_sector = at.set_index("sector")
        for j in range(m):
            if j + 1 in by_sector.index:
                row = by_sector.loc[j + 1]
                v0m_s[j] = float(np.atleast_1d(row["volume_mobile_cumulated"])[-1])
                v0o_s[j] = float(np.atleast_1d(row["volume_obstacle_cumulated"])[-1])
    out = {"global": DepthModel(powers=tuple(float(p) for p in sector_powers),
                                  coefficients_mobile=coefs_m, coefficients_obstacle=coefs_o,
                                  initial_mobile=float(v0m_s.sum()),
                                  initial_obstacle=float(v0o_s.sum()), name=name,
                                  rows=earlier, **common)}
    for j in range(m):
        out[f"sector {j + 1}"] = DepthModel(
            powers=(float(sector_powers[j]),), coefficients_mobile=(coefs_m[j],),
            coefficients_obstacle=(coefs_o[j],), initial_mobile=float(v0m_s[j]),
            initial_obstacle=float(v0o_s[j]), sector_arc=float(edges[j + 1] - edges[j]),
            name=f"{name} sector {j + 1}".strip(), sector=j + 1, **common)
    return out


def _sector_pairs(pairs, m: int, mobile, obstacle):
    """(mobile, obstacle) Archard coefficients [Pa⁻¹] of each of ``m`` sectors: the pairs as
    wear_table reads them (one pair for all allowed; an obstacle None: it does not wear)."""
    if pairs is None:
        return [float(mobile)] * m, [None if obstacle is None else float(obstacle)] * m
    pairs = list(pairs)
    if len(pairs) == 1:
        pairs = pairs * m
    if len(pairs) != m:
        raise InputError(f"sector_coefficients has {len(pairs)} entries for {m} sectors")
    pairs = [(p, None) if np.isscalar(p) else tuple(p) for p in pairs]
    k_m = [float(p[0]) for p in pairs]
    k_o = [None if p[1] is None else float(p[1]) for p in pairs]
    if any(k is not None for k in k_o):  # wear_table: a missing one is 0 when others wear
        k_o = [0.0 if k is None else k for k in k_o]
    return k_m, k_o


def model_from_table(table: pd.DataFrame, *, sector: int | None = None, **options
                     ) -> DepthModel:
    """The model of a wear table's global depth (``sector=None``) or of one sector (1-based).

    Options as :func:`models_from_table`.
    """
    models = models_from_table(table, **options)
    key = "global" if sector is None else f"sector {int(sector)}"
    if key not in models:
        raise InputError(f"the wear table has no {key}; it has {sorted(models)}")
    return models[key]


# ---------------------------------------------------------------------- from a bundle record
def record_model(record: dict, *, instants, origins, depths, volume_mobile, volume_obstacle,
                 power: float, sector_powers=None, geometry=None,
                 wall: Wall | None = None) -> DepthModel:
    """The global :class:`DepthModel` of one bundle contact, from its record (the values of
    its wear case in :attr:`fretwear.bundle.BundleResult.contacts`, or ``parts/*.json`` read
    back by :func:`fretwear.bundle.load`) and its table's global rows: the model its table
    was computed by (:func:`case_model`), so that the summary's time to a limit is
    :meth:`DepthModel.time_to` (docs/uncertainty.md §1).

    Parameters
    ----------
    record : dict
        ``contact_type``, ``dimensions`` (lengths [m], angles [deg]), ``law``,
        ``coefficients_mobile``, ``coefficients_obstacle`` (None: it does not wear; native
        names, resolved: a history's KWU-EPRI intensity included), ``time_scale`` [s per
        unit]; optional ``origin`` and ``tube_replacement`` [user time unit],
        ``wall_thickness`` [m], ``depth_limit`` [-], ``sector_coefficients`` (pairs [Pa⁻¹]).
    instants, origins, depths, volume_mobile, volume_obstacle : array
        The contact's global rows, one per instant, increasing: ``instant`` and ``origin``
        [user time unit] (``origins`` None: 0), ``depth_mobile`` [m], the cumulated worn
        volumes [m³] (the obstacle's None: 0). A restart's rows before its origin are its
        earlier rows (:class:`~fretwear.table.depth_rows.EarlierRows`); its volumes at the
        origin are the last of them.
    power : float
        The run's total wear power [W].
    sector_powers : array, optional
        Each sector's wear power [W] (a sector table: one volume term a sector, a law linear
        in time).
    geometry : ContactGeometry, optional
        The record's geometry, when the caller built it already.
    wall : Wall, optional
        The contact's wall, when the caller holds its case's (``WearCase.wall``): default the
        record's ``wall_thickness`` and ``depth_limit`` (:func:`record_wall`, checked there).

    Raises
    ------
    InputError
        The record lacks what the model needs (:func:`_record_run`'s message), or its law is
        not linear in time with sectors.
    """
    if geometry is None:
        geometry = _geometry(record.get("contact_type"), record.get("dimensions") or {})
    missing = [k for k in ("law", "coefficients_mobile", "time_scale")
               if record.get(k) is None]
    if missing:
        raise InputError(f"the bundle contact's record lacks {', '.join(missing)}: run the "
                         "bundle again (fretwear bundle -o DIR)")
    law = get_law(record["law"])
    scale = float(record["time_scale"])
    t = np.asarray(instants, dtype=float)
    starts = np.zeros_like(t) if origins is None else np.asarray(origins, dtype=float)
    given = record.get("origin")
    origin = float(given) if given is not None and np.isfinite(given) else (
        float(starts[-1]) if starts.size else 0.0)
    vm = np.asarray(volume_mobile, dtype=float)
    vo = (np.zeros_like(t) if volume_obstacle is None
          else np.nan_to_num(np.asarray(volume_obstacle, dtype=float)))
    earlier = (starts != origin) if origin > 0 else np.zeros(t.size, dtype=bool)
    rows, v0m, v0o = None, 0.0, 0.0
    if earlier.any():  # a restart: the initial table's rows, then this run's
        keep = np.flatnonzero(earlier)
        if t[keep[-1]] < origin - _TIME_TOL * max(1.0, abs(origin)):
            raise InputError(f"the restart's earlier rows end at {t[keep[-1]]:g}, before its "
                             f"origin {origin:g}: its volumes at the origin are not known "
                             "(INST_INIT is an instant of the initial table)")
        rows = EarlierRows(t[keep], np.asarray(depths, dtype=float)[keep], vm[keep], vo[keep],
                           bool(starts[0] == 0))
        v0m, v0o = float(vm[keep[-1]]), float(vo[keep[-1]])
    mobile = dict(record["coefficients_mobile"])
    other = record.get("coefficients_obstacle")
    obstacle = None if other is None else dict(other)
    replaced = record.get("tube_replacement")
    fresh = (None if replaced is None or not np.isfinite(replaced)
             else (float(replaced) - origin) * scale)
    if sector_powers is None:
        powers, coefs_m, coefs_o = (float(power),), (mobile,), (obstacle,)
    else:
        powers = tuple(np.asarray(sector_powers, dtype=float).tolist())
        key = law.parameters[0]
        k_m, k_o = _sector_pairs(record.get("sector_coefficients"), len(powers),
                                 mobile.get(key), None if obstacle is None
                                 else obstacle.get(key))
        coefs_m = tuple({key: k} for k in k_m)
        coefs_o = tuple(None if k is None else {key: k} for k in k_o)
    return DepthModel(law=law, geometry=geometry, powers=powers, coefficients_mobile=coefs_m,
                      coefficients_obstacle=coefs_o, time_scale=scale, origin=origin,
                      initial_mobile=v0m, initial_obstacle=v0o,
                      wall=record_wall(record) if wall is None else wall,
                      replacement=fresh, rows=rows)


def record_wall(record: dict) -> Wall:
    """The :class:`Wall` of a bundle contact's record (``wall_thickness`` [m], ``depth_limit``
    [-]; missing or NaN: no thickness, the default limit): the one check of a wall read back
    from plain values (``parts/*.json``, the contacts frame)."""
    wall, limit = record.get("wall_thickness"), record.get("depth_limit")
    return Wall(None if wall is None or not np.isfinite(wall) else float(wall),
                DEFAULT_DEPTH_LIMIT if limit is None or not np.isfinite(limit)
                else float(limit))
