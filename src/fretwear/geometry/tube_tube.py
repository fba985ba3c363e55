"""TUBE_TUBE: two steam-generator tubes crossing at an angle θ (theory §6; R7.20.01 §4.8).

After a tube breaks, it may rub against a neighbour; each tube wears a flat (wear tests show
plane worn surfaces). Each flat is a wedge along its tube, with a parabolic section
A(d) = (4/3)·√(2R)·d^{3/2} whose depth falls by θ per unit length, unbounded in width:
V = 8√(2R)·d^{5/2}/(15θ). Mobile and obstacle are treated independently, each with its radius.
"""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.geometry.base import ContactGeometry
from fretwear.geometry.tube_bav import flat_trace_depth, flat_trace_volume

__all__ = ["TubeTube"]


@dataclasses.dataclass(frozen=True)
class TubeTube(ContactGeometry):
    """TUBE_TUBE: tube against tube at a crossing angle (one flat wedge on each).

    Parameters
    ----------
    mobile_radius : float
        Mobile tube outer radius R_m [m] (RAYON_MOBILE).
    tilt_angle : float
        Crossing angle θ of the two tubes [deg] (ANGL_INCLI), > 0.
    obstacle_radius : float, optional
        Outer radius R_o of the other tube [m] (RAYON_OBST); needed when it wears.

    Notes
    -----
    .. math:: d_m = \\left(\\frac{1}{2R_m}\\right)^{1/5}
              \\left(\\frac{15\\,\\theta V_m}{8}\\right)^{2/5},\\qquad
              d_o = \\left(\\frac{1}{2R_o}\\right)^{1/5}
              \\left(\\frac{15\\,\\theta V_o}{8}\\right)^{2/5}

    (Code_Aster R7.20.01 [2]_ writes d_t for d_m). Range: d_m ≤ R_m and d_o ≤ R_o (the flat
    reaches the axis).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.8.

    Examples
    --------
    >>> g = TubeTube(mobile_radius=0.0111, tilt_angle=5.0, obstacle_radius=0.0111)
    >>> dm, do = g.depth_from_volume(1e-9, 1e-9)
    >>> bool(np.isclose(dm, do)), round(float(dm) * 1e3, 6)
    (True, 0.260777)
    """

    mobile_radius: float
    tilt_angle: float
    obstacle_radius: float | None = None

    contact_type: ClassVar[str] = "TUBE_TUBE"
    required: ClassVar[tuple[str, ...]] = ("mobile_radius", "tilt_angle")
    optional: ClassVar[tuple[str, ...]] = ("obstacle_radius",)
    mobile_depth_alone: ClassVar[bool] = True  # each tube's flat from its own volume
    example: ClassVar[dict[str, float]] = {
        "mobile_radius": 9.525e-3, "obstacle_radius": 9.525e-3, "tilt_angle": 5.0}

    def __post_init__(self) -> None:
        super().__post_init__()
        if not self.tilt_angle > 0.0:
            raise InputError(
                "TUBE_TUBE needs a crossing angle tilt_angle (ANGL_INCLI) > 0 deg: the relation "
                f"V = 8√(2R)d^(5/2)/(15θ) has no meaning at θ = {self.tilt_angle:g}")

    @property
    def max_depth(self) -> float:
        return float(self.mobile_radius)

    @property
    def range_limit(self) -> str:
        text = f"d_m up to the mobile radius R_m = {self.mobile_radius:.6g} m"
        if self.obstacle_radius is not None:
            text += f", d_o up to R_o = {self.obstacle_radius:.6g} m"
        return text + ", where the worn flat reaches the tube's axis"

    def _need_obstacle(self, values: np.ndarray, what: str) -> None:
        if self.obstacle_radius is None and np.any(values > 0.0):
            raise KeywordError(
                f"TUBE_TUBE: the obstacle tube's {what} needs its radius obstacle_radius "
                "(RAYON_OBST) [m]; give it, or no obstacle wear")

    def _depth_from_volume(self, volume_mobile, volume_obstacle):
        self._need_obstacle(volume_obstacle, "depth")
        theta = self.angle("tilt_angle")
        dm = flat_trace_depth(volume_mobile, self.mobile_radius, math.inf, theta)
        dm = np.where(dm <= self.mobile_radius, dm, np.nan)
        if self.obstacle_radius is None:
            return dm, np.zeros_like(dm)
        do = flat_trace_depth(volume_obstacle, self.obstacle_radius, math.inf, theta)
        do = np.where(do <= self.obstacle_radius, do, np.nan)
        return dm, do

    def _volume_from_depth(self, depth_mobile, depth_obstacle):
        self._need_obstacle(depth_obstacle, "volume")
        theta = self.angle("tilt_angle")
        vm = flat_trace_volume(depth_mobile, self.mobile_radius, math.inf, theta)
        vm = np.where(depth_mobile <= self.mobile_radius, vm, np.nan)
        if self.obstacle_radius is None:
            return vm, np.zeros_like(vm)
        vo = flat_trace_volume(depth_obstacle, self.obstacle_radius, math.inf, theta)
        return vm, np.where(depth_obstacle <= self.obstacle_radius, vo, np.nan)
