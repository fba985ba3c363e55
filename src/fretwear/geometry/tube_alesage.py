"""TUBE_ALESAGE: steam-generator tube in a drilled support-plate hole (theory §6; R7.20.01 §4.5).

Three situations:

- no bore radius given: a pure orbital motion wears the tube uniformly all round,
  d_m = V_m/(2π·l·R_m) (the obstacle's uniform depth d_o = V_o/(2π·l·R_o) needs R_o, so obstacle
  wear needs the bore radius);
- bore radius, no tilt: an elliptic impact-sliding motion wears two diametrically opposite
  lunules, each holding half of V_m and half of V_o;
- bore radius and tilt θ: each of the two traces is a wedge along the tube,
  (V_m + V_o)/2 = frustum rule with A = S (the lens of the total depth D at the deepest
  section); the arc r giving the tube the share V_m/(V_m + V_o) of that deepest section splits D
  into d_m and d_o.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings
from typing import ClassVar

import numpy as np

from fretwear.errors import KeywordError, UnusedKeywordWarning
from fretwear.geometry._lunule import lunule_areas, lunule_depths, lunule_mobile_depth
from fretwear.geometry._shapes import (
    frustum_volume,
    lens_area,
    lens_depth_limit,
    monotone_grid,
    solve_on_grid,
)
from fretwear.geometry.base import ContactGeometry

__all__ = ["TubeAlesage", "tilted_lunule_volume"]


def tilted_lunule_volume(depth, mobile_radius, obstacle_radius, width, tilt):
    """Volume of one tilted lunule trace by the frustum rule with A = S [m³].

    Parameters
    ----------
    depth : float or array_like
        Total depth D = d_m + d_o at the deepest section [m].
    mobile_radius : float
        Tube outer radius R_m [m].
    obstacle_radius : float
        Bore radius R_o [m], > R_m.
    width : float
        Bore width l [m].
    tilt : float
        Tilt θ [rad], ≥ 0.

    Returns
    -------
    numpy.ndarray or float
        Volume of the trace (mobile + obstacle) [m³]; NaN beyond the lens range.

    Notes
    -----
    .. math:: V = \\frac{D}{\\theta}\\frac{S(D)}{3}\\ (D < l\\theta), \\qquad
              V = \\frac{l}{3}\\left(S_1 + \\sqrt{S_1 S_2} + S_2\\right)\\ (D \\ge l\\theta)

    with S1 = S(D), S2 = S(D − lθ) (:func:`~fretwear.geometry._shapes.lens_area`).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 (TUBE_ALESAGE with tilt, frustum rule).

    Examples
    --------
    >>> v0 = tilted_lunule_volume(1e-4, 0.0111, 0.0115, 0.02, 0.0)
    >>> bool(np.isclose(v0, 0.02 * lens_area(0.0111, 0.0115, 1e-4), rtol=1e-14))
    True
    """
    return frustum_volume(lambda d: lens_area(mobile_radius, obstacle_radius, d),
                          depth, width, tilt)


@functools.lru_cache(maxsize=256)
def _tilted_grid(mobile_radius: float, obstacle_radius: float, width: float, tilt: float):
    """(:func:`tilted_lunule_volume` of the dimensions as a function of D, its
    :func:`~fretwear.geometry._solve.monotone_grid` on [0, D_max]) [m³, m], made once per
    dimensions (the last 256 kept): the depth solve starts each element from the grid points
    around its volume (:func:`~fretwear.geometry._solve.solve_on_grid`)."""
    def func(depth):
        return np.asarray(tilted_lunule_volume(depth, mobile_radius, obstacle_radius, width,
                                               tilt), dtype=float)

    limit = float(lens_depth_limit(mobile_radius, obstacle_radius))
    with np.errstate(invalid="ignore", divide="ignore"):
        ends = func(np.array([0.0, limit]))
    return func, monotone_grid(func, limit, (float(ends[0]), float(ends[1])))


@dataclasses.dataclass(frozen=True)
class TubeAlesage(ContactGeometry):
    """TUBE_ALESAGE: tube in a drilled hole (uniform wear, two lunules, or two tilted lunules).

    Parameters
    ----------
    mobile_radius : float
        Tube outer radius R_m [m] (RAYON_MOBILE).
    obstacle_width : float
        Plate thickness l (worn height) [m] (LARGEUR_OBST).
    obstacle_radius : float, optional
        Hole radius R_o [m] (RAYON_OBST), > R_m. Without it the wear is uniform all round.
    tilt_angle : float
        Tilt θ of the tube in the hole [deg] (ANGL_INCLI), default 0 (used with R_o).

    Notes
    -----
    Uniform: d_m = V_m/(2π l R_m). Two lunules: S(D) = (V_m + V_o)/(2l), split by the arc r
    with seg(R_m, x) − seg(r, x) = V_m/(2l). Tilted: (V_m + V_o)/2 = frustum rule of S, split
    at the deepest section. Range: D ≤ √(R_o² − R_m²) − (R_o − R_m) (lunules), d_m ≤ R_m
    (uniform). See docs/geometry.md.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.5.

    Examples
    --------
    >>> g = TubeAlesage(mobile_radius=0.0111, obstacle_width=0.02)
    >>> round(float(g.depth_from_volume(2 * np.pi * 0.02 * 0.0111 * 1e-5)[0]), 15)
    1e-05
    """

    mobile_radius: float
    obstacle_width: float
    obstacle_radius: float | None = None
    tilt_angle: float = 0.0

    contact_type: ClassVar[str] = "TUBE_ALESAGE"
    required: ClassVar[tuple[str, ...]] = ("mobile_radius", "obstacle_width")
    optional: ClassVar[tuple[str, ...]] = ("obstacle_radius", "tilt_angle")
    example: ClassVar[dict[str, float]] = {
        "mobile_radius": 9.525e-3, "obstacle_radius": 9.7e-3, "obstacle_width": 20e-3,
        "tilt_angle": 0.5}

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.obstacle_radius is None:
            if self.tilt_angle:
                warnings.warn(
                    "TUBE_ALESAGE without obstacle_radius (RAYON_OBST) is the uniform-wear "
                    f"model, which does not use tilt_angle (ANGL_INCLI) = {self.tilt_angle:g} "
                    "deg: ignored; give RAYON_OBST for the tilted lunule model",
                    UnusedKeywordWarning, stacklevel=3)
        else:
            self._check_room("the hole radius", "the tube radius")

    @property
    def uniform(self) -> bool:
        """True for the uniform-wear model (no bore radius given)."""
        return self.obstacle_radius is None

    @property
    def max_depth(self) -> float:
        if self.uniform:
            return float(self.mobile_radius)
        return float(lens_depth_limit(self.mobile_radius, self.obstacle_radius))

    @property
    def range_limit(self) -> str:
        if self.uniform:
            return (f"uniform depth up to the tube radius R_m = {self.mobile_radius:.6g} m")
        return (f"total depth d_m + d_o of a lunule up to {self.max_depth:.6g} m, where its "
                "chord reaches the tube's axis")

    def _uniform_obstacle(self, values: np.ndarray) -> None:
        if np.any(values > 0.0):
            raise KeywordError(
                "TUBE_ALESAGE without obstacle_radius (RAYON_OBST) is the uniform-wear model: "
                "the obstacle's depth d_o = V_o/(2π·l·R_o) needs the hole radius; give "
                "RAYON_OBST (two-lunule model) or no obstacle wear")

    def _depth_from_volume(self, volume_mobile, volume_obstacle):
        l = self.obstacle_width
        rm = self.mobile_radius
        if self.uniform:
            self._uniform_obstacle(volume_obstacle)
            dm = volume_mobile / (2.0 * math.pi * l * rm)
            return np.where(dm <= rm, dm, np.nan), np.zeros_like(dm)
        ro = self.obstacle_radius
        theta = self.angle("tilt_angle")
        if theta == 0.0:
            return lunule_depths(rm, ro, volume_mobile / (2.0 * l), volume_obstacle / (2.0 * l))
        total = volume_mobile + volume_obstacle
        func, grid = _tilted_grid(float(rm), float(ro), float(l), float(theta))
        depth = solve_on_grid(func, total / 2.0, grid)
        with np.errstate(invalid="ignore", divide="ignore"):
            share = np.where(total > 0.0, volume_mobile / total, 1.0)
        dm = np.asarray(lunule_mobile_depth(rm, ro, depth, share), dtype=float)
        do = np.where(np.isnan(depth), np.nan, np.maximum(depth - dm, 0.0))
        return dm, do

    def _volume_from_depth(self, depth_mobile, depth_obstacle):
        l = self.obstacle_width
        rm = self.mobile_radius
        if self.uniform:
            self._uniform_obstacle(depth_obstacle)
            vm = 2.0 * math.pi * l * rm * depth_mobile
            return np.where(depth_mobile <= rm, vm, np.nan), np.zeros_like(vm)
        ro = self.obstacle_radius
        theta = self.angle("tilt_angle")
        am, ao = lunule_areas(rm, ro, depth_mobile, depth_obstacle)
        am, ao = np.asarray(am, dtype=float), np.asarray(ao, dtype=float)
        if theta == 0.0:
            return 2.0 * l * am, 2.0 * l * ao
        depth = depth_mobile + depth_obstacle
        total = 2.0 * np.asarray(tilted_lunule_volume(depth, rm, ro, l, theta), dtype=float)
        section = am + ao
        with np.errstate(invalid="ignore", divide="ignore"):
            share = np.where(section > 0.0, am / section, 1.0)
        vm = total * share
        return vm, np.maximum(total - vm, 0.0)
