"""The wall columns of the wear table: depth over the wall, instant of the limit.

Step 5 of :func:`~fretwear.table.wear_table_from_case`: the depth models that
:func:`fretwear.table.limit.wall_columns` inverts. The global depth is the case's
:class:`~fretwear.table.DepthModel` (:func:`case_model`: the law, the geometry, the volumes at
the origin, a restart's earlier rows, a tube replacement); each sector's depth of a law linear in
time, V = V0 + r·t, inverted in closed form (:class:`_SectorDepths`). SI units: volumes [m³],
depths [m], times [s].
"""

from __future__ import annotations

import numpy as np

from fretwear.geometry.sectors import sector_depth_mobile
from fretwear.table._columns import _sector_coefficients
from fretwear.table.depth import DepthModel
from fretwear.table.depth_rows import EarlierRows
from fretwear.table.limit import wall_columns


# --------------------------------------------------------------------------- 5. the wall
def _wall(case, table, power, result, mobile, obstacle, clock, geometry):
    """The wall columns (:func:`fretwear.table.limit.wall_columns`) of ``table`` (the columns,
    or the frame of a restart): the depth over the wall and the instant of reaching the limit,
    by the case's depth model (:meth:`DepthModel.time_to`; each sector's closed form).
    """
    sectored = case.sectors is not None
    depths = (np.asarray(table["depth_mobile"], dtype=float),
              np.asarray(table["sector"], dtype=int) if sectored else None,
              np.asarray(table["depth_mobile_sector"], dtype=float) if sectored else None)
    options = {"wall": case.wall.thickness, "depth_limit": case.wall.limit,
               "origin": case.origin, "time_scale": case.time_scale, "fresh": clock.fresh,
               "unit": case.time_unit, "stacklevel": 5}
    glob = None
    if case.contact_type is not None:
        glob = case_model(case, power, result, mobile, obstacle, clock.fresh, geometry)
    sectors = None
    if sectored:
        law, state = case.wear_law, case.restart.table
        powers = np.asarray(result.sectors, dtype=float)
        if glob is not None:  # the model's per-sector rates [m³/s], computed once
            rate_m = glob.term_rates[0]
        else:
            k_m, _ = _sector_coefficients(case, powers.size, mobile, obstacle)
            rate_m = np.asarray(law.volume(powers, 1.0, **{law.parameters[0]: k_m}),
                                dtype=float)  # [m³/s]
        zeros = np.zeros(powers.size)
        v0_m = zeros if state is None else np.asarray(state.sector_volume_mobile, dtype=float)
        arcs = np.diff(np.asarray(result.sector_edges, dtype=float))
        sectors = (_SectorDepths(v0_m, rate_m, geometry, arcs),
                   _SectorDepths(zeros, rate_m, geometry, arcs))
    return wall_columns(*depths, **options, sector_depths=sectors, global_depth=glob)


def case_model(case, power: float, result, mobile, obstacle, fresh: float | None,
               geometry) -> DepthModel:
    """The global :class:`DepthModel` of a case at its power [W] (``result``'s sector powers
    in sector mode), the bodies' coefficients ``mobile`` and ``obstacle`` (None: it does not
    wear), a tube replaced ``fresh`` seconds after the origin (None: not)."""
    law, state = case.wear_law, case.restart.table
    if case.sectors is None:
        powers = (float(power),)
        coefs_m, coefs_o = (mobile,), (obstacle,)
        v0_m = 0.0 if state is None else state.volume_mobile
        v0_o = 0.0 if state is None else state.volume_obstacle
    else:
        key = law.parameters[0]
        powers = tuple(np.asarray(result.sectors, dtype=float).tolist())
        k_m, k_o = _sector_coefficients(case, len(powers), mobile, obstacle)
        coefs_m = tuple({key: k} for k in k_m)
        coefs_o = (None,) * len(powers) if k_o is None else tuple({key: k} for k in k_o)
        v0_m = 0.0 if state is None else float(np.sum(state.sector_volume_mobile))
        v0_o = 0.0 if state is None else float(np.sum(state.sector_volume_obstacle))
    rows = None
    if state is not None and len(state.rows):
        rows = EarlierRows.from_rows(state.rows, case.origin)
    return DepthModel(law=law, geometry=geometry, powers=powers, coefficients_mobile=coefs_m,
                      coefficients_obstacle=coefs_o, time_scale=case.time_scale,
                      origin=case.origin, initial_mobile=v0_m, initial_obstacle=v0_o,
                      wall_thickness=case.wall.thickness, depth_limit=case.wall.limit,
                      replacement=fresh, rows=rows)


def _linear_volume(t, v0, rate):
    """V0 + r·t [m³] (exactly r·t where V0 = 0)."""
    v = rate * t
    return np.where(v0 == 0.0, v, v0 + v)


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
