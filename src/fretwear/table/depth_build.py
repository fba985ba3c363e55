"""Building a :class:`~fretwear.table.DepthModel`: from a wear case (:func:`case_model`, the
model the wear table is computed by) and from a wear table's rows and metadata
(:func:`models_from_table`, :func:`model_from_table`: the uncertainty propagation and the
calibration of tables read back). The few places that read a case or a table into a model.
"""

from __future__ import annotations

import functools

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.laws import get_law
from fretwear.table.depth import DepthModel, _dict, _geometry
from fretwear.table.depth_rows import EarlierRows
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT

__all__ = ["case_model", "model_from_table", "models_from_table"]

_TIME_TOL = 1e-9


# ---------------------------------------------------------------------- from a wear case
def case_model(case, power: float, result, mobile, obstacle, fresh: float | None,
               geometry) -> DepthModel:
    """The :class:`DepthModel` of a wear case (the model the wear table's columns and limits
    are computed by): at its power [W] (``result``'s sector powers in sector mode: one term a
    sector), the bodies' coefficients ``mobile`` and ``obstacle`` (native names; None: it does
    not wear), a tube replaced ``fresh`` seconds after the origin (None: not), the case's
    ``geometry``; a restart's earlier rows and volumes at the origin from its initial state.
    """
    law, state = case.wear_law, case.restart.table
    sectors = {}
    if case.sectors is None:
        powers = (float(power),)
        coefs_m, coefs_o = (mobile,), (obstacle,)
        v0_m = 0.0 if state is None else state.volume_mobile
        v0_o = 0.0 if state is None else state.volume_obstacle
    else:
        key = law.parameters[0]
        powers = tuple(np.asarray(result.sectors, dtype=float).tolist())
        m = len(powers)
        k_m, k_o = _case_sector_coefficients(case, m, mobile, obstacle)
        coefs_m = tuple({key: k} for k in k_m)
        coefs_o = (None,) * m if k_o is None else tuple({key: k} for k in k_o)
        pm = np.zeros(m) if state is None else np.asarray(state.sector_volume_mobile, float)
        po = np.zeros(m) if state is None else np.asarray(state.sector_volume_obstacle, float)
        v0_m, v0_o = float(np.sum(pm)), float(np.sum(po))
        sectors = {"sector_arcs": tuple(np.diff(np.asarray(result.sector_edges, dtype=float))
                                        .tolist()),
                   "term_initial": (tuple(pm.tolist()), tuple(po.tolist()))}
        if state is not None and len(state.rows):  # read at their first use (a limit)
            sectors["sector_rows"] = functools.partial(_earlier_sectors, state.rows,
                                                       case.origin, m)
    rows = None
    if state is not None and len(state.rows):  # read at their first use (a limit)
        rows = functools.partial(EarlierRows.from_rows, state.rows, case.origin)
    return DepthModel(law=law, geometry=geometry, powers=powers, coefficients_mobile=coefs_m,
                      coefficients_obstacle=coefs_o, time_scale=case.time_scale,
                      origin=case.origin, initial_mobile=v0_m, initial_obstacle=v0_o,
                      wall_thickness=case.wall.thickness, depth_limit=case.wall.limit,
                      replacement=fresh, rows=rows, **sectors)


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
def _attrs(table: pd.DataFrame) -> dict:
    attrs = dict(getattr(table, "attrs", {}) or {})
    missing = [k for k in ("contact_type", "dimensions", "law", "coefficients_mobile",
                           "time_scale") if k not in attrs]
    if missing:
        raise InputError(f"the wear table has no run metadata ({', '.join(missing)} missing "
                         "from DataFrame.attrs): give the table returned by wear_table / "
                         "run_case, or the case that computes it")
    return attrs


def _origin_rows(table: pd.DataFrame, origin: float) -> pd.DataFrame:
    tol = _TIME_TOL * max(1.0, abs(origin))
    at = table[np.asarray(table["instant"], dtype=float) <= origin + tol]
    if at.empty:
        return at
    last = float(at["instant"].iloc[-1])
    return at[np.abs(np.asarray(at["instant"], dtype=float) - last) <= tol]


def models_from_table(table: pd.DataFrame, *, sector_coefficients=None,
                      wall_thickness: float | None = None, depth_limit: float | None = None,
                      name: str = "") -> dict[str, DepthModel]:
    """The models of a wear table: ``"global"`` and, in sector mode, ``"sector 1"`` ...

    Parameters
    ----------
    table : DataFrame
        A wear table from :func:`fretwear.table.wear_table` (its ``attrs`` hold the run: law,
        coefficients, geometry, power, time scale).
    sector_coefficients : sequence of (float, float or None), optional
        Archard coefficients (mobile, obstacle) [Pa⁻¹] per sector, as given to wear_table
        (default ``attrs["sector_coefficients"]``, else the law's coefficients).
    wall_thickness : float, optional
        Wall thickness [m] (default ``attrs["wall_thickness"]``).
    depth_limit : float, optional
        Depth limit, fraction of the wall [-] (default ``attrs["depth_limit"]`` or
        :data:`~fretwear.table.DEFAULT_DEPTH_LIMIT`).
    name : str
        Contact name.

    Returns
    -------
    dict of str to DepthModel

    Raises
    ------
    InputError
        The table has no metadata, or the tube is replaced after the origin (not modelled).
    """
    a = _attrs(table)
    law = get_law(a["law"])
    geometry = _geometry(a["contact_type"], a["dimensions"])
    origin = float(a.get("origin") or 0.0)
    replacement = a.get("tube_replacement")
    if replacement is not None and float(replacement) > origin + _TIME_TOL * max(1, origin):
        raise InputError("the wear table replaces the tube after its origin (TUBE_NEUF): the "
                         "uncertainty model continues one tube; compute from the replacement on "
                         "(a restart of replace_tube's table)")
    wall = wall_thickness if wall_thickness is not None else a.get("wall_thickness")
    limit = depth_limit if depth_limit is not None else a.get("depth_limit")
    common = {"law": law, "geometry": geometry, "time_scale": float(a["time_scale"]),
              "origin": origin, "wall_thickness": None if wall is None else float(wall),
              "depth_limit": DEFAULT_DEPTH_LIMIT if limit is None else float(limit)}
    earlier = None
    if "origin" in table.columns and origin > 0:  # a restart: the initial table's rows first
        earlier = EarlierRows.from_rows(
            table[np.asarray(table["origin"], dtype=float) != origin], origin)
    mobile = _dict(a.get("coefficients_mobile"))
    obstacle = _dict(a.get("coefficients_obstacle"))
    power_info = a.get("power") or {}
    at = _origin_rows(table, origin)
    edges = a.get("sector_edges")
    if edges is None:
        total = float(power_info.get("total", table["power"].iloc[-1]))
        v0m = float(at["volume_mobile"].iloc[0]) if len(at) else 0.0
        v0o = float(at["volume_obstacle"].iloc[0]) if len(at) else 0.0
        return {"global": DepthModel(powers=(total,), coefficients_mobile=(mobile,),
                                     coefficients_obstacle=(obstacle,), initial_mobile=v0m,
                                     initial_obstacle=v0o, name=name, rows=earlier, **common)}
    edges = np.asarray(edges, dtype=float)
    m = edges.size - 1
    sector_powers = np.asarray(power_info.get("sectors"), dtype=float)
    if sector_powers.size != m:
        raise InputError("the sector table's attrs['power'] lacks the sector powers")
    pairs = sector_coefficients if sector_coefficients is not None else a.get(
        "sector_coefficients")
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
