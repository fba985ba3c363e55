"""The rules between a wear case's values: each checked once, where the case is built.

:meth:`fretwear.table.WearCase.__post_init__` calls these in order on the values it was given
(by :meth:`~fretwear.table.WearCase.from_keywords`, :meth:`~fretwear.table.WearCase.from_dict`
or the constructor): each function checks one group of rules and returns the group's values
normalised (plain floats and tuples), which the case keeps; a rule broken raises an
:class:`~fretwear.errors.InputError` or :class:`~fretwear.errors.KeywordError` naming the
keyword and the fix. The case's outputs (its tables' depths) are never checked again.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from typing import Any

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.io.geometry_units import check_absolute_sizes, check_wall_thickness
from fretwear.sectors import sector_edges
from fretwear.table._serial import FrozenMap
from fretwear.table.case_values import _real
from fretwear.table.coefficients import (
    USER,
    Coefficient,
    laws_with,
    material_pair,
    plain,
    sector_parameter,
)
from fretwear.table.restart import InitialState
from fretwear.timeunits import TIME_UNITS, time_unit_name, unit_seconds

#: The Code_Aster names of the KWU-EPRI class ranges given as separate keywords.
HISTORY_KEYWORDS = {"force_max": "FNOR_MAXI", "speed_max": "VTAN_MAXI"}


def instants(values, restart: bool) -> tuple[float, ...]:
    """The instants (INST) [user time unit] as a tuple of floats: finite, at least one,
    strictly increasing, >= 0 (> 0 with a ``restart``: they count from its origin).

    >>> instants([0, 1, 2.5], restart=False)
    (0.0, 1.0, 2.5)
    """
    try:
        arr = np.atleast_1d(np.asarray(values, dtype=float)).ravel()
    except OverflowError:  # a 400-digit integer
        raise InputError(f"instants must be finite numbers, got one beyond the float range "
                         f"({str(values)[:40]}...)") from None
    except (TypeError, ValueError):
        raise InputError(f"instants must be numbers (user time unit), got {values!r}") from None
    if arr.size == 0 or not np.isfinite(arr).all():
        raise InputError(f"instants must be finite numbers and at least one, got {arr.tolist()}")
    if (arr < 0).any() or (restart and (arr <= 0).any()):
        low = "> 0 (they count from the restart origin)" if restart else ">= 0"
        raise InputError(f"instants (INST) must be {low}, got {arr.tolist()}")
    if (np.diff(arr) <= 0).any():
        raise InputError(f"instants (INST) must be strictly increasing, got {arr.tolist()}")
    return tuple(arr.tolist())


def coefficient_map(value, body: str) -> FrozenMap:
    """The coefficients of ``body`` as an immutable name -> :class:`Coefficient` map (SI values;
    a bare value or a ``{"value", "source"}`` mapping is the user's)."""
    if not isinstance(value, Mapping):
        raise InputError(f"{body} coefficients must be a mapping name -> Coefficient, got "
                         f"{type(value).__name__}")
    out = {}
    for name, c in value.items():
        if isinstance(c, Mapping):
            c = Coefficient(plain(c.get("value")), str(c.get("source", USER)))
        elif not isinstance(c, Coefficient):
            c = Coefficient(plain(c), USER)
        out[str(name)] = c
    return FrozenMap(out)


def sector_pairs(pairs, n: int) -> tuple[tuple[float, float | None], ...]:
    """(mobile, obstacle or None) Archard coefficients [1/Pa] of each of the ``n`` sectors."""
    pairs = list(pairs)
    if len(pairs) == 1 and n > 1:
        pairs = pairs * n
    if len(pairs) != n:
        raise InputError(f"sector_coefficients has {len(pairs)} entries for {n} sectors; give "
                         "one (mobile, obstacle) pair [1/Pa] per sector, or one for all")
    out = []
    for j, pair in enumerate(pairs):
        if np.isscalar(pair):
            pair = (pair, None)
        if len(pair) != 2:
            raise InputError(f"sector_coefficients[{j}] must be a (mobile, obstacle) pair "
                             f"[1/Pa], got {pair!r}")
        out.append((float(pair[0]), None if pair[1] is None else float(pair[1])))
    return tuple(out)


def time_values(case) -> dict[str, Any]:
    """``time_scale`` [s per user time unit] as a float > 0 (COEF_INST); ``time_unit`` a name."""
    try:
        scale = float(case.time_scale)
    except (TypeError, ValueError):
        scale = math.nan
    if not math.isfinite(scale) or scale <= 0:
        raise InputError(f"time_scale (COEF_INST) must be > 0 [s per unit], got "
                         f"{case.time_scale!r}")
    if case.time_unit is not None and not isinstance(case.time_unit, str):
        raise InputError(f"time_unit must be the name of the unit, got {case.time_unit!r}")
    return {"time_scale": scale}


def check_restart_unit(case, state: InitialState | None) -> None:
    """A restart's table counts time in the case's unit (its header's ``time_unit``)."""
    seconds = None if state is None else unit_seconds(state.time_unit)
    if seconds is None or math.isclose(seconds, case.time_scale, rel_tol=1e-2) or (
            case.time_unit is not None
            and time_unit_name(case.time_unit) == time_unit_name(state.time_unit)):
        return  # the same unit (a year of 365 or 365.25 days alike): only a slip is refused
    table = f" {case.restart.source}" if case.restart.source else ""
    name = time_unit_name(state.time_unit)
    key = (f'unit = "{name}"' if name in TIME_UNITS
           else f"seconds_per_unit = {seconds:g}")
    raise InputError(
        f"the initial wear table{table} counts time in {state.time_unit!r} ({seconds:g} s, "
        f"its header's time_unit) and this case in {case.time_label!r} ({case.time_scale:g} "
        "s): its instants would be read in the wrong unit. Give the case the table's unit "
        f"({key} in a case file's [time], time_scale={seconds:g} in Python), or restart "
        "from a table written in the case's unit")


def material_values(case) -> dict[str, Any]:
    """``materials`` (MATER_USURE), ``obstacle_wear`` (USURE_OBST) and ``coefficient_files``
    normalised, and the keywords they need given."""
    out: dict[str, Any] = {}
    if case.materials is not None:
        out["materials"] = material_pair(case.materials)
    if not isinstance(case.obstacle_wear, bool | np.bool_):
        raise InputError(f"obstacle_wear (USURE_OBST) must be True or False, got "
                         f"{case.obstacle_wear!r}")
    out["obstacle_wear"] = bool(case.obstacle_wear)
    if out["obstacle_wear"] and case.materials is None:
        raise KeywordError("obstacle_wear (USURE_OBST) takes the obstacle coefficient from "
                           "the database: give materials (MATER_USURE) too")
    if case.coefficient_files is not None:
        files = out["coefficient_files"] = \
            tuple(os.fspath(f) for f in case.coefficient_files) or None
        if files and case.materials is None:
            raise KeywordError("coefficient_files extend the coefficient database, which is "
                               "read for materials (MATER_USURE) only: give materials too, "
                               "or the coefficients directly")
    return out


def history_values(case, law) -> dict[str, float]:
    """The class ranges FNOR_MAXI [N] / VTAN_MAXI [m/s] given, as floats: they belong to laws
    with history statistics."""
    out = {}
    for name, keyword in HISTORY_KEYWORDS.items():
        value = getattr(case, name)
        if value is None:
            continue
        if name not in law.accepted:
            owners = laws_with(lambda lw, n=name: n in lw.accepted)
            raise KeywordError(f"{keyword} belongs to LOI_USURE={owners}, not {law.name}: "
                               f"remove {name} ({keyword}), a class range of the history "
                               "statistics")
        out[name] = _real(value, f"{name} ({keyword})")
    return out


def sector_values(case, law, geometry, state: InitialState | None) -> dict[str, Any]:
    """``sectors`` (SECTEUR: a count or edges [deg]) and ``sector_coefficients`` [1/Pa]
    normalised; checked against the law (Archard coefficients only), the geometry (a mobile
    radius and an obstacle width) and a restart's table (the same sectors)."""
    if case.sectors is None:
        if case.sector_coefficients is not None:
            raise KeywordError("sector_coefficients (SECTEUR COEF_USUR_MOBILE/COEF_USUR_OBST) "
                               "need sectors: give sectors= (a count or edges [deg])")
        if state is not None and state.sector_count:
            raise InputError(f"the initial wear table has {state.sector_count} sectors and "
                             "this run has none; the number of sectors must match")
        return {}
    spec = case.sectors
    if isinstance(spec, int | np.integer) and not isinstance(spec, bool):
        spec = int(spec)
    elif not isinstance(spec, bool):
        try:
            spec = tuple(float(v) for v in np.asarray(spec, dtype=float).ravel())
        except (TypeError, ValueError):
            pass  # sector_edges names the problem
    edges = sector_edges(spec)
    out: dict[str, Any] = {"sectors": spec}
    if sector_parameter(law) is None:
        raise KeywordError(
            f"law {law.name!r} with sectors: SECTEUR belongs to LOI_USURE="
            f"{laws_with(lambda lw: sector_parameter(lw) is not None)} (sector tables take "
            "Archard coefficients only: V_j = k_j·P_j·t); use law='ARCHARD' or remove sectors")
    m = edges.size - 1
    if state is not None:
        if state.sector_count != m:
            raise InputError(f"the initial wear table has {state.sector_count} sectors and "
                             f"this run has {m}; the number of sectors must match")
        if not np.allclose(state.edges, edges, atol=1e-6):
            raise InputError(f"the initial wear table's sector edges {state.edges.tolist()} "
                             f"differ from this run's {edges.tolist()} [deg]; use the same")
    if case.sector_coefficients is not None:
        out["sector_coefficients"] = sector_pairs(case.sector_coefficients, m)
    elif case.coefficients.get(sector_parameter(law)) is None or \
            case.coefficients[sector_parameter(law)].value is None:
        raise KeywordError("sector mode needs Archard coefficients: give "
                           "sector_coefficients (SECTEUR COEF_USUR_MOBILE) or coefficients")
    if getattr(geometry, "mobile_radius", None) is None or \
            getattr(geometry, "obstacle_width", None) is None:
        raise KeywordError("sector depths need mobile_radius (RAYON_MOBILE) and "
                           "obstacle_width (LARGEUR_OBST); give them in the dimensions")
    return out


def check_wall(case) -> None:
    """The wall is checked by :class:`~fretwear.table.case_values.Wall`; here against the tube
    it belongs to: a wall in mm typed into a metre key is thicker than the tube (issue 29)."""
    check_wall_thickness(case.wall.thickness, case.dimensions.get("mobile_radius"),
                         key="wall_thickness (wall_thickness_m in a case file or manifest)")
    check_absolute_sizes(case.dimensions, case.wall.thickness)
