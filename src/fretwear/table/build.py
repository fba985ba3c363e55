"""Building the service-life wear table of a :class:`~fretwear.table.WearCase` (theory §3, §6, §7).

:func:`wear_table_from_case` turns a wear power (or a contact history, from which the power is
computed) and a validated wear case into the table of worn volumes and depths at the instants of
service, optionally per angular sector, continuing the case's restart state and with the tube
replaced on the way. The steps, one function each:

1. :func:`_power_of`: the power [W] of the source (and the PowerResult, the history);
2. :func:`_body_coefficients`: each body's coefficients, the history's KWU-EPRI intensity added
   for a law whose registry entry says it ``needs_history``;
3. :class:`_Clock`: the elapsed seconds of each instant and the replacement;
4. :func:`_global_frame` or :func:`_sector_frame`: cumulated volumes (:func:`_cumulated`) and
   depths from them (:func:`_depths`; per sector :func:`~fretwear.geometry.sector_depth_mobile`);
5. the initial table's rows in front; with a wall thickness, the depth as a fraction of the wall
   and the instant of reaching the limit (:func:`_wall`, :mod:`fretwear.table.limit`);
6. the metadata in ``attrs`` (:func:`_attrs`).

Conventions of the table (one row per instant, or per instant and sector):

* ``instant`` is in the user's time unit; the laws use ``t = instant × time_scale`` [s].
* ``volume_mobile``/``volume_obstacle`` are the *cumulated* volumes of the bodies in place at
  that instant (initial state included; the tube's restart from zero at a replacement) [m³];
  ``depth_*`` are computed from them by the contact geometry (theory §6).
* In sector mode ``volume_*_sector`` is the volume worn in the sector over ``duration`` (since
  ``origin``, by the tube in place), ``volume_*_cumulated`` the sector's cumulated volume and
  ``depth_*_sector`` the sector depth from it (theory §3); ``volume_*`` is then the sum over
  sectors of the cumulated volumes.
"""

from __future__ import annotations

import functools
import os
import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd

from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.geometry.sectors import sector_depth_mobile, sector_depth_obstacle
from fretwear.history import ContactHistory
from fretwear.power import wear_power
from fretwear.table.case import WearCase
from fretwear.table.limit import time_to_depth, wall_columns
from fretwear.table.schema import GLOBAL_COLUMNS, SECTOR_COLUMNS

__all__ = ["wear_table_from_case"]

#: Source of a coefficient computed from the contact history (KWU-EPRI's intensity w).
HISTORY = "history (class statistics over the window)"


def wear_table_from_case(case: WearCase, source, *, history: ContactHistory | None = None
                         ) -> pd.DataFrame:
    """The service-life wear table of one contact (theory §7; Code_Aster's POST_USURE).

    Parameters
    ----------
    case : WearCase
        The validated description of the computation (:meth:`WearCase.from_keywords`).
    source : float, ContactHistory, PowerResult or path-like
        The wear power P [W] (PUIS_USURE), or a contact history (RESU_GENE) or its file, whose
        power is computed over the case's ``[t_start, t_end]`` [s] in ``blocks`` blocks
        (theory §2).
    history : ContactHistory, optional
        With a PowerResult ``source``, the history it was computed from: a law that needs the
        history's class statistics (KWU_EPRI) reads them over ``[t_start, t_end]`` without
        computing the power again.

    Returns
    -------
    pandas.DataFrame
        Native columns (:data:`fretwear.table.COLUMNS`), one row per instant (or instant and
        sector), preceded by the initial table's rows up to the origin on a restart. ``attrs``
        holds the run's metadata: ``case`` (``case.to_dict()``), ``coefficient_sources`` (where
        each coefficient came from), ``power``, ``dimensions``, ...

    Raises
    ------
    InputError
        Sectors without a history with contact angles, ``history`` without a PowerResult
        ``source``, a PowerResult whose sectors differ from the case's.
    KeywordError
        A law that needs the history's statistics given a power alone.

    Notes
    -----
    Per body, with ``t = duration × time_scale`` and ``V₀`` the volume at the origin:
    ``V(t) = V₀ + V_law(P, t)`` for a law linear in time, ``V(t) = V_law(P, τ₀ + t)`` with
    ``V_law(P, τ₀) = V₀`` otherwise (theory §7). Sectors: ``V_j = k_j·P_j·t`` (theory §3).
    Depths always come from the cumulated volumes (theory §6, §3).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3, §6, §7.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §6 ("actualisation du
           tableau": updating the table).

    Examples
    --------
    >>> case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...     coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> wear_table_from_case(case, 0.01)["volume_mobile"].tolist()  # K·P·t
    [3.6e-13, 7.2e-13]
    """
    if not isinstance(case, WearCase):
        raise InputError(f"case must be a WearCase (WearCase.from_keywords(...)), got "
                         f"{type(case).__name__}")
    result, history, power = _power_of(case, source, history)
    case = _with_run_sectors(case, result)
    mobile, obstacle, sources = _body_coefficients(case, history, result)
    geometry = case.geometry
    clock = _Clock(case)
    head = {"instant": case.origin + clock.durations, "duration": clock.durations,
            "origin": np.full(clock.n, case.origin), "power": np.full(clock.n, power)}
    if case.sectors is None:
        columns = _global_frame(case, head, power, mobile, obstacle, clock, geometry)
    else:
        columns = _sector_frame(case, head, result, mobile, obstacle, clock, geometry)
    state = case.initial_state
    frame = None
    if state is not None and len(state.rows):
        frame = pd.concat([state.rows.reindex(columns=list(columns)), _frame(columns)],
                          ignore_index=True)
    limit = None
    if case.wall_thickness is not None:
        wall, limit = _wall(case, columns if frame is None else frame, power, result, mobile,
                            obstacle, clock, geometry)
        if frame is None:
            columns.update(wall)
        else:
            frame = frame.assign(**wall)
    if frame is None:
        frame = _frame(columns)
    frame.attrs = _attrs(case, geometry, mobile, obstacle, sources, result)
    if limit is not None:
        frame.attrs.update(limit)
    return frame


# --------------------------------------------------------------------------- 1. the power
def _power_of(case: WearCase, source, history):
    """(PowerResult or None, history or None, total power [W]); ``history`` goes with a
    PowerResult only (the history it was computed from)."""
    is_result = hasattr(source, "total") and hasattr(source, "blocks")
    if history is not None and (not is_result or not isinstance(history, ContactHistory)):
        raise InputError("history is the ContactHistory a PowerResult source was computed from "
                         "(for the KWU_EPRI classes); give it with a PowerResult source only")
    if isinstance(source, str | os.PathLike):
        # streamed in one pass (two for KWU_EPRI without FNOR_MAXI/VTAN_MAXI): the law's class
        # counts come with the power (result.kwu), the history is never held whole
        kwu = (case.force_max, case.speed_max) if case.wear_law.needs_history else None
        result = wear_power(source, t_start=case.t_start, t_end=case.t_end, blocks=case.blocks,
                            sectors=case.sectors,
                            stationarity_threshold=case.stationarity_threshold, kwu=kwu)
        return result, None, float(result.total)
    if isinstance(source, ContactHistory):
        result = wear_power(source, t_start=case.t_start, t_end=case.t_end, blocks=case.blocks,
                            sectors=case.sectors,
                            stationarity_threshold=case.stationarity_threshold)
        return result, source, float(result.total)
    if is_result:
        return source, history, float(source.total)
    try:
        power = float(source)
    except (TypeError, ValueError):
        raise InputError(f"source must be a wear power [W], a ContactHistory, a PowerResult or "
                         f"the path of a history file, got {type(source).__name__}") from None
    if not np.isfinite(power) or power < 0:
        raise InputError(f"the wear power (PUIS_USURE) must be finite and >= 0 [W], got {power}")
    return None, None, power


def _with_run_sectors(case: WearCase, result) -> WearCase:
    """The case whose sectors are the run's: a PowerResult computed with sectors makes a
    sector table (checked as if the case had them); sectors need a power with sectors."""
    run_edges = None if result is None else getattr(result, "sector_edges", None)
    if getattr(result, "sectors", None) is None:
        run_edges = None
    if case.sectors is None:
        return case if run_edges is None else case.replace(
            sectors=tuple(np.asarray(run_edges, dtype=float).tolist()))
    if run_edges is None:
        raise InputError("sectors need a contact history with dy and dz (RESU_GENE): a power "
                         "alone (PUIS_USURE) has no contact angle")
    if not np.array_equal(np.asarray(run_edges, dtype=float), case.sector_edges):
        raise InputError(f"the PowerResult's sector edges {list(run_edges)} differ from the "
                         f"case's sectors {case.sector_edges.tolist()} [deg]; compute the power "
                         "with the same sectors")
    return case


# --------------------------------------------------------------------------- 2. coefficients
def _pass_counts(result, case: WearCase, coefs: dict):
    """The KWU-EPRI class counts of the power's pass (``result.kwu``) when they are those of
    ``coefs``'s maxima over the case's window, else None."""
    counts = getattr(result, "kwu", None)
    given = getattr(counts, "given", None)
    if given is None or given != (coefs.get("force_max"), coefs.get("speed_max")):
        return None
    # the case's window; a missing bound is the record's end (the power's window), which
    # selects the same samples as no bound at all
    for bound, power_bound, counted, open_end in (
            (case.t_start, result.t_start, counts.t_start, -np.inf),
            (case.t_end, result.t_end, counts.t_end, np.inf)):
        if counted != (power_bound if bound is None else bound) and not (
                bound is None and counted == open_end):
            return None
    return counts


def _body_coefficients(case: WearCase, history, result=None):
    """(mobile, obstacle or None, sources) coefficient dicts by native name; a law that needs
    the history's statistics gets each body's intensity from them (unless given)."""
    law = case.wear_law
    mobile = case.coefficient_values("mobile")
    obstacle = case.coefficient_values("obstacle")
    sources = case.coefficient_sources
    if law.needs_history:
        if history is None and getattr(result, "kwu", None) is None:
            raise KeywordError(f"the {law.name} law needs the contact history's force/speed "
                               "classes: give a history (RESU_GENE), or history= with a "
                               "PowerResult, not a power alone (PUIS_USURE)")
        for body, coefs in (("mobile", mobile), ("obstacle", obstacle)):
            if coefs is not None and coefs.get("intensity") is None:
                counts = _pass_counts(result, case, coefs) if history is None else None
                if counts is not None:
                    factors = law.resolve(**coefs)
                    stats = counts.result(**{k: factors[k] for k in
                                             ("impact_factor", "sliding_factor", "k", "c")})
                elif history is None:
                    raise KeywordError(
                        f"the PowerResult's KWU-EPRI class counts were made with the maxima "
                        f"{getattr(result.kwu, 'given', None)}, the {body}'s are "
                        f"{(coefs.get('force_max'), coefs.get('speed_max'))} (force_max, "
                        "speed_max): give the history too (history=)")
                else:
                    stats = law.statistics(history, t_start=case.t_start, t_end=case.t_end,
                                           **coefs)
                coefs["intensity"] = float(stats.intensity)
                sources[f"{body}.intensity"] = HISTORY
    return mobile, obstacle, sources


# --------------------------------------------------------------------------- 3. the clock
@dataclass(frozen=True)
class _Clock:
    """The run's durations [user unit], elapsed seconds [s] and the tube replacement."""

    case: WearCase

    @property
    def durations(self) -> np.ndarray:
        return np.asarray(self.case.instants, dtype=float)

    @property
    def n(self) -> int:
        return len(self.case.instants)

    @property
    def elapsed(self) -> np.ndarray:
        """Seconds since the origin at each instant [s]."""
        return self.durations * self.case.time_scale

    @property
    def fresh(self) -> float | None:
        """Seconds after the origin at which a new tube starts (None: no replacement) [s]."""
        at = self.case.tube_replacement
        return None if at is None else (at - self.case.origin) * self.case.time_scale

    @property
    def replaced(self) -> np.ndarray:
        """Instants at which the tube in place is the new one."""
        fresh = self.fresh
        return np.zeros(self.n, bool) if fresh is None else self.elapsed >= fresh


# --------------------------------------------------------------------------- 4. volumes, depths
def _cumulated(law, power: float, coefficients, elapsed_s: np.ndarray, previous: float,
               fresh_from_s: float | None, body: str) -> np.ndarray:
    """Cumulated volume of one body at ``elapsed_s`` seconds after the origin [m³].

    ``previous`` is the body's volume at the origin; a linear law adds ``V(P, Δt)``, another
    law continues from its equivalent time (theory §7). ``fresh_from_s`` (a replacement, seconds
    after the origin) restarts the body from zero there. The law's warnings name the body.
    """
    if coefficients is None:  # this body does not wear
        out = np.full(elapsed_s.shape, float(previous))
        if fresh_from_s is not None:
            out[elapsed_s >= fresh_from_s] = 0.0
        return out
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if previous == 0.0:
            out = np.asarray(law.volume(power, elapsed_s, **coefficients), dtype=float)
        else:  # linear: V0 + V(Δt); otherwise from the equivalent time of V0 (theory §7)
            out = np.asarray(law.cumulated_volume(previous, power, elapsed_s, **coefficients),
                             dtype=float)
        out = np.broadcast_to(out, elapsed_s.shape).copy()
        if fresh_from_s is not None:
            new = elapsed_s >= fresh_from_s
            out[new] = np.asarray(law.volume(power, elapsed_s[new] - fresh_from_s,
                                             **coefficients), dtype=float)
    for w in caught:
        warnings.warn(f"{body}: {w.message}", w.category, stacklevel=4)
    return out


def _depths(geometry, volume_mobile: np.ndarray, volume_obstacle: np.ndarray):
    """(mobile, obstacle) depths [m] from the cumulated volumes [m³] (theory §6).

    An obstacle without volume has no depth: exactly 0 where the mobile's depth is defined
    (the split d_o = D − D·V_m/V of a shared trace leaves a rounding residue otherwise).
    """
    dm, do = geometry.depth_from_volume(volume_mobile, volume_obstacle)
    dm = np.broadcast_to(dm, volume_mobile.shape).astype(float)
    do = np.broadcast_to(do, volume_mobile.shape).astype(float)
    return dm, np.where((volume_obstacle == 0) & np.isfinite(dm), 0.0, do)


def _global_frame(case, head, power, mobile, obstacle, clock, geometry) -> pd.DataFrame:
    """The table without sectors: one row per instant."""
    law, state = case.wear_law, case.initial_state
    prev_m = 0.0 if state is None else state.volume_mobile
    prev_o = 0.0 if state is None else state.volume_obstacle
    vm = _cumulated(law, power, mobile, clock.elapsed, prev_m, clock.fresh, "mobile")
    vo = _cumulated(law, power, obstacle, clock.elapsed, prev_o, None, "obstacle")
    dm, do = _depths(geometry, vm, vo)
    return {**head, "volume_mobile": vm, "volume_obstacle": vo, "depth_mobile": dm,
            "depth_obstacle": do}


def _sector_coefficients(case: WearCase, m: int, mobile, obstacle):
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


def _sector_frame(case, head, result, mobile, obstacle, clock, geometry) -> pd.DataFrame:
    """The sector table: one row per instant and sector (instant-major)."""
    law, state = case.wear_law, case.initial_state
    key = law.parameters[0]
    edges = np.asarray(result.sector_edges, dtype=float)
    powers = np.asarray(result.sectors, dtype=float)
    m, n = powers.size, clock.n
    k_m, k_o = _sector_coefficients(case, m, mobile, obstacle)
    r_m, r_o = geometry.mobile_radius, getattr(geometry, "obstacle_radius", None)
    width = geometry.obstacle_width
    elapsed, fresh, replaced = clock.elapsed, clock.fresh, clock.replaced
    cols = {c: [] for c in SECTOR_COLUMNS if c not in GLOBAL_COLUMNS}
    cum_m = np.zeros((n, m))
    cum_o = np.zeros((n, m))
    unradiused: list[int] = []
    for j in range(m):
        pm = 0.0 if state is None else float(state.sector_volume_mobile[j])
        po = 0.0 if state is None else float(state.sector_volume_obstacle[j])
        vm = _cumulated(law, powers[j], {key: k_m[j]}, elapsed, pm, fresh, "mobile")
        vo = _cumulated(law, powers[j], None if k_o is None else {key: k_o[j]}, elapsed, po,
                        None, "obstacle")
        cum_m[:, j], cum_o[:, j] = vm, vo
        arc = edges[j + 1] - edges[j]
        was_m = np.where(replaced, 0.0, pm)  # a replaced tube starts from zero
        cols["sector"].append(np.full(n, j + 1))
        cols["angle_start"].append(np.full(n, edges[j]))
        cols["angle_end"].append(np.full(n, edges[j + 1]))
        cols["sector_power"].append(np.full(n, powers[j]))
        cols["volume_mobile_sector"].append(vm - was_m)
        cols["volume_obstacle_sector"].append(vo - po)
        cols["depth_mobile_sector"].append(sector_depth_mobile(vm, r_m, width, arc))
        if r_o is None:
            if (vo > 0).any():
                unradiused.append(j + 1)
            cols["depth_obstacle_sector"].append(np.where(vo == 0, 0.0, np.nan))
        else:
            cols["depth_obstacle_sector"].append(sector_depth_obstacle(vo, r_o, width, arc))
        cols["volume_mobile_cumulated"].append(vm)
        cols["volume_obstacle_cumulated"].append(vo)
    if unradiused:
        warnings.warn(f"sectors {unradiused}: the obstacle wears but "
                      f"{geometry.contact_type or 'the sector geometry'} has no obstacle_radius "
                      "(RAYON_OBST): their obstacle sector depth is NaN", RangeWarning,
                      stacklevel=3)
    total_m, total_o = cum_m.sum(axis=1), cum_o.sum(axis=1)
    dm, do = _depths(geometry, total_m, total_o)
    glob = {"volume_mobile": total_m, "volume_obstacle": total_o,
            "depth_mobile": dm, "depth_obstacle": do}
    data = {k: np.repeat(np.asarray(v), m) for k, v in {**head, **glob}.items()}
    for c, parts in cols.items():  # instant-major order: row = i*m + j
        data[c] = np.column_stack(parts).ravel()
    return {c: data[c] for c in SECTOR_COLUMNS}


@functools.lru_cache(maxsize=64)
def _index(names: tuple[str, ...]) -> pd.Index:
    """The columns' index of a table (immutable: shared by the tables of those columns)."""
    return pd.Index(list(names))


def _frame(columns: dict) -> pd.DataFrame:
    """The DataFrame of ``columns`` (name -> 1-d array, one length), as
    ``pd.DataFrame(columns)`` gives it, built from one float block: the float columns
    stacked once, the others (the sector numbers) inserted at their place."""
    names = tuple(columns)
    floats = tuple(c for c in names if np.asarray(columns[c]).dtype == np.float64)
    block = np.stack([columns[c] for c in floats]) if floats else np.empty((0, 0))
    frame = pd.DataFrame(block.T, columns=_index(floats), copy=False)
    for at, name in enumerate(names):
        if name not in floats:
            frame.insert(at, name, columns[name])
    return frame


# --------------------------------------------------------------------------- 5. the wall
def _wall(case, table, power, result, mobile, obstacle, clock, geometry):
    """The wall columns (:func:`fretwear.table.limit.wall_columns`) of ``table`` (the columns,
    or the frame of a restart): the depth over the wall and the instant of reaching the limit,
    from depth(t) through the law and geometry.

    A law linear in time gives every term (the body, or each sector) V = V0 + r·t with its
    rate r = V(P, 1 s) computed once: depth(t) then costs a few array operations (the
    geometry's relation directly: the volumes are valid by construction), each sector's
    instant is the closed-form inverse (:class:`_SectorDepths`), and so is the global one
    when the obstacle's volume stays 0 (:class:`_GlobalDepth`); otherwise the global limit
    and through-wall instants are solved together.
    """
    law, state = case.wear_law, case.initial_state
    fresh = clock.fresh
    sectored = case.sectors is not None
    depths = (np.asarray(table["depth_mobile"], dtype=float),
              np.asarray(table["sector"], dtype=int) if sectored else None,
              np.asarray(table["depth_mobile_sector"], dtype=float) if sectored else None)
    options = {"wall": case.wall_thickness, "depth_limit": case.depth_limit,
               "origin": case.origin, "time_scale": case.time_scale, "fresh": fresh,
               "unit": case.time_unit, "stacklevel": 4}
    if case.sectors is None and not law.linear_in_time:
        terms = [(power, mobile, obstacle, 0.0 if state is None else state.volume_mobile,
                  0.0 if state is None else state.volume_obstacle)]
        return wall_columns(*depths, **options, global_depth=None if case.contact_type is None
                            else _law_depths(law, terms, fresh, geometry))
    if case.sectors is None:
        powers = np.array([power], dtype=float)
        rate_m = np.array([_rate(law, power, mobile)])
        rate_o = np.array([_rate(law, power, obstacle)])
        v0_m = np.array([0.0 if state is None else state.volume_mobile], dtype=float)
        v0_o = np.array([0.0 if state is None else state.volume_obstacle], dtype=float)
    else:
        key = law.parameters[0]
        powers = np.asarray(result.sectors, dtype=float)
        k_m, k_o = _sector_coefficients(case, powers.size, mobile, obstacle)
        rate_m = np.asarray(law.volume(powers, 1.0, **{key: k_m}), dtype=float)  # [m³/s]
        rate_o = (np.zeros(powers.size) if k_o is None
                  else np.asarray(law.volume(powers, 1.0, **{key: k_o}), dtype=float))
        zeros = np.zeros(powers.size)
        v0_m = zeros if state is None else np.asarray(state.sector_volume_mobile, dtype=float)
        v0_o = zeros if state is None else np.asarray(state.sector_volume_obstacle, dtype=float)
    zeros = np.zeros(powers.size)

    sectors = None
    if case.sectors is not None:
        arcs = np.diff(np.asarray(result.sector_edges, dtype=float))
        sectors = (_SectorDepths(v0_m, rate_m, geometry, arcs),
                   _SectorDepths(zeros, rate_m, geometry, arcs))
    glob = None
    if case.contact_type is not None:
        # the obstacle's volume stays 0 (old and new tube): the inverse is closed-form
        still = not (rate_o.any() or v0_o.any())
        glob = (_GlobalDepth(geometry, v0_m, rate_m, v0_o, rate_o, 0.0, still,
                             case.time_scale),
                _GlobalDepth(geometry, zeros, rate_m, v0_o, rate_o, fresh or 0.0, still,
                             case.time_scale))
    return wall_columns(*depths, **options, sector_depths=sectors, global_depth=glob,
                        vectorised=True)


def _rate(law, power: float, coefficients) -> float:
    """Volume per second [m³/s] of a body under a law linear in time (0 when it does not
    wear)."""
    if coefficients is None:
        return 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the table's own volumes already warned
        return float(np.asarray(law.volume(power, 1.0, **coefficients), dtype=float))


def _linear_volume(t, v0, rate):
    """V0 + r·t [m³] (exactly r·t where V0 = 0)."""
    v = rate * t
    return np.where(v0 == 0.0, v, v0 + v)


def _law_depths(law, terms, fresh, geometry):
    """(old, new) global depth functions of time through the law itself (a law not linear in
    time: each call continues the volumes from their equivalent times)."""

    def old(t):  # the tube in place at the origin, t seconds after it
        vm = sum(_cumulated(law, p, km, t, pm, None, "mobile") for p, km, _, pm, _ in terms)
        vo = sum(_cumulated(law, p, ko, t, po, None, "obstacle") for p, _, ko, _, po in terms)
        return _depths(geometry, np.asarray(vm, dtype=float), np.asarray(vo, dtype=float))[0]

    def new(tau):  # a new tube, tau seconds after its replacement
        vm = sum(_cumulated(law, p, km, tau, 0.0, None, "mobile") for p, km, _, _, _ in terms)
        vo = sum(_cumulated(law, p, ko, fresh + tau, po, None, "obstacle")
                 for p, _, ko, _, po in terms)
        return _depths(geometry, np.asarray(vm, dtype=float), np.asarray(vo, dtype=float))[0]

    return old, new


class _GlobalDepth:
    """The global mobile depth at the times t (an array, one depth per time) [m] of the terms
    V_j(t) = V0_j + r_j·t of a law linear in time, summed in the terms' order, for the mobile
    and the obstacle (the obstacle's clock ``shift`` seconds ahead: a new tube's).

    With ``still`` (the obstacle's volume is 0 at all times), :meth:`time_to` inverts it in
    closed form: the mobile volume of the target depth from the geometry's volume_from_depth
    relation, then t = (V − ΣV0)/Σr (the bracketed solver where that volume is out of range).
    """

    def __init__(self, geometry, v0_m, rate_m, v0_o, rate_o, shift: float, still: bool,
                 first_guess: float = 1.0):
        self.geometry, self.shift, self.first_guess = geometry, shift, first_guess
        self.v0_m, self.rate_m, self.v0_o, self.rate_o = v0_m, rate_m, v0_o, rate_o
        if still:
            self.time_to = self._time_to

    @staticmethod
    def _total(t, v0, rate):  # Σ_j V_j(t) at each time t, summed in the terms' order
        return np.cumsum(_linear_volume(t[..., None], v0, rate), axis=-1)[..., -1]

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        return self.geometry._depth_from_volume(
            self._total(t, self.v0_m, self.rate_m),
            self._total(t + self.shift, self.v0_o, self.rate_o))[0]

    def _time_to(self, targets) -> np.ndarray:
        """Seconds [s] at which the depth reaches ``targets`` [m] (obstacle volume 0): 0 when
        already there, inf when the mobile does not wear."""
        goal = np.asarray(targets, dtype=float)
        volume = np.asarray(self.geometry._volume_from_depth(goal, np.zeros_like(goal))[0],
                            dtype=float)
        if not np.isfinite(volume).all():  # a target beyond the relation's range
            return np.asarray(time_to_depth(self, goal, first_guess=self.first_guess), dtype=float)
        v0, rate = np.cumsum(self.v0_m)[-1], np.cumsum(self.rate_m)[-1]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (volume - v0) / rate
        return np.where(v0 >= volume, 0.0, np.where(rate > 0, t, np.inf))


class _SectorDepths:
    """The mobile depth of every sector at the times t (one per sector) [m], for a law linear
    in time, V_j(t) = V0_j + r_j·t; :meth:`time_to` inverts it in closed form through
    V = l·Δθ·d·(2R − d)/2 (:func:`~fretwear.geometry.sector_depth_mobile`), theory §3."""

    def __init__(self, v0, rate, geometry, arcs_deg):
        self.v0, self.rate = v0, rate
        self.radius, self.width = geometry.mobile_radius, geometry.obstacle_width
        self.arcs = arcs_deg

    def __call__(self, t):
        return sector_depth_mobile(_linear_volume(t, self.v0, self.rate), self.radius,
                                   self.width, self.arcs)

    def time_to(self, targets) -> np.ndarray:
        """Seconds [s] at which each sector's depth reaches ``targets`` [m]: 0 when already
        there, inf when it does not wear."""
        d = np.minimum(np.asarray(targets, dtype=float), self.radius)
        volume = self.width * np.radians(self.arcs) * d * (2.0 * self.radius - d) / 2.0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (volume - self.v0) / self.rate
        return np.where(self.v0 >= volume, 0.0, np.where(self.rate > 0, t, np.inf))


# --------------------------------------------------------------------------- 6. metadata
def _attrs(case: WearCase, geometry, mobile, obstacle, sources, result) -> dict:
    """The table's metadata: the run's description, the coefficients and their sources."""
    dimensions = dict(geometry.to_dict())
    dimensions.pop("contact_type", None)
    edges = case.sector_edges
    return {
        "title": case.name, "contact_type": case.contact_type, "dimensions": dimensions,
        "law": case.law, "coefficients_mobile": mobile, "coefficients_obstacle": obstacle,
        "coefficient_sources": sources,
        "materials": None if case.materials is None else list(case.materials),
        "coefficient_files": None if case.coefficient_files is None
        else list(case.coefficient_files),
        "sector_edges": None if edges is None else edges.tolist(),
        "sector_coefficients": None if case.sector_coefficients is None
        else [list(p) for p in case.sector_coefficients],
        "time_scale": case.time_scale,
        "time_unit": case.time_unit or f"{case.time_scale:g} s",
        "origin": case.origin, "tube_replacement": case.tube_replacement,
        "wall_thickness": case.wall_thickness, "depth_limit": case.depth_limit,
        "global_depth": getattr(geometry, "reason", None),  # why the global depths are NaN
        "power": None if result is None else _power_dict(result),
        "case": case.to_dict(),
    }


def _power_dict(result) -> dict:
    try:
        return dict(result.to_dict())
    except Exception:  # noqa: BLE001 - metadata only
        return {"total": float(result.total)}
