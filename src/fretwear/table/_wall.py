"""The wall columns of the wear table: depth over the wall, instant of the limit.

Step 5 of :func:`~fretwear.table.wear_table_from_case`: the depth functions of time through
the law and the geometry that :func:`fretwear.table.limit.wall_columns` inverts. A law linear
in time gives every term V = V0 + r·t (:class:`_GlobalDepth`, :class:`_SectorDepths`, with
closed-form inverses); another law continues its volumes from their equivalent times
(:func:`_law_depths`). SI units: volumes [m³], depths [m], times [s].
"""

from __future__ import annotations

import warnings

import numpy as np

from fretwear.geometry.sectors import sector_depth_mobile
from fretwear.table._columns import _cumulated, _depths, _sector_coefficients
from fretwear.table.limit import time_to_depth, wall_columns


# --------------------------------------------------------------------------- 5. the wall
def _wall(case, table, power, result, mobile, obstacle, clock, geometry):
    """The wall columns (:func:`fretwear.table.limit.wall_columns`) of ``table`` (the columns,
    or the frame of a restart): the depth over the wall and the instant of reaching the limit,
    from depth(t) through the law and geometry.

    A law linear in time gives every term (the body, or each sector) V = V0 + r·t with its
    rate r = V(P, 1 s) computed once: depth(t) then costs a few array operations (the
    geometry's relation directly: the volumes are valid by construction), each sector's
    instant is the closed-form inverse (:class:`_SectorDepths`), and so is the global one
    when the obstacle's volume stays 0 or does not enter the mobile's depth
    (:class:`_GlobalDepth`); otherwise the global limit and through-wall instants are solved
    together.
    """
    law, state = case.wear_law, case.initial_state
    fresh = clock.fresh
    sectored = case.sectors is not None
    depths = (np.asarray(table["depth_mobile"], dtype=float),
              np.asarray(table["sector"], dtype=int) if sectored else None,
              np.asarray(table["depth_mobile_sector"], dtype=float) if sectored else None)
    options = {"wall": case.wall_thickness, "depth_limit": case.depth_limit,
               "origin": case.origin, "time_scale": case.time_scale, "fresh": fresh,
               "unit": case.time_unit, "stacklevel": 5}
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
        # the obstacle's volume stays 0 (old and new tube), or does not enter the mobile's
        # depth: the inverse is closed-form
        closed = geometry.mobile_depth_alone or not (rate_o.any() or v0_o.any())
        glob = (_GlobalDepth(geometry, v0_m, rate_m, v0_o, rate_o, 0.0, closed,
                             case.time_scale),
                _GlobalDepth(geometry, zeros, rate_m, v0_o, rate_o, fresh or 0.0, closed,
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

    With ``closed`` (the obstacle's volume is 0 at all times, or the geometry's
    ``mobile_depth_alone``: the obstacle's volume does not enter the mobile's depth),
    :meth:`time_to` inverts it in closed form: the mobile volume of the target depth from the
    geometry's volume_from_depth relation (obstacle depth 0), then t = (V − ΣV0)/Σr (the
    bracketed solver where that volume is out of range).
    """

    def __init__(self, geometry, v0_m, rate_m, v0_o, rate_o, shift: float, closed: bool,
                 first_guess: float = 1.0):
        self.geometry, self.shift, self.first_guess = geometry, shift, first_guess
        self.v0_m, self.rate_m, self.v0_o, self.rate_o = v0_m, rate_m, v0_o, rate_o
        if closed:
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
        """Seconds [s] at which the depth reaches ``targets`` [m] (the mobile's volume alone
        decides it): 0 when already there, inf when the mobile does not wear."""
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
