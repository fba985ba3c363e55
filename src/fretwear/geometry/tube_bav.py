"""TUBE_BAV: tube against a flat anti-vibration bar (theory §6; Code_Aster R7.20.01 §4.4).

The bar wears a flat on the tube. Its cross-section at depth D is the tube's circular segment,
taken in the parabolic approximation A(D) = (4/3)·√(2R_m)·D^{3/2} (the closed forms of
Code_Aster R7.20.01, as theory §6 prescribes; the exact segment is smaller by a factor
1 − 3D/(20R_m) + O(D²/R_m²)). A bar tilted by θ along the tube wears a wedge; the total depth D
comes from the total volume V = (V_m + V_o)·cos α (α = ANGL_IMPACT) and is shared in proportion
to the volumes: d_m = D·V_m/(V_m + V_o), d_o = D − d_m.
"""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np

from fretwear.geometry._shapes import _out, solve_monotone
from fretwear.geometry.base import ContactGeometry

__all__ = ["TubeBav", "flat_trace_depth", "flat_trace_volume"]


def _power_difference_52(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a^{5/2} − b^{5/2} for a ≥ b ≥ 0 without cancellation when a ≈ b."""
    ra, rb = np.sqrt(a), np.sqrt(b)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(ra + rb > 0.0, (a - b) / (ra + rb), 0.0)
    return ratio * (a * a + a * ra * rb + a * b + ra * rb * b + b * b)


def flat_trace_volume(depth, mobile_radius, width, tilt=0.0):
    """Volume of a flat worn on a cylinder, parabolic section, straight or tilted [m³].

    Parameters
    ----------
    depth : float or array_like
        Depth D of the flat at its deepest section [m], ≥ 0.
    mobile_radius : float
        Cylinder (tube) radius R [m].
    width : float
        Width l of the flat body (bar) along the cylinder's axis [m] (``inf`` for an unbounded
        wedge, as for TUBE_TUBE).
    tilt : float
        Tilt θ of the flat relative to the cylinder's axis [rad], ≥ 0.

    Returns
    -------
    numpy.ndarray or float
        Volume V [m³].

    Notes
    -----
    Section of the flat (parabolic approximation of the circular segment, half-chord √(2RD)):
    A(D) = (4/3)·√(2R)·D^{3/2}. Without tilt V = l·A(D). With tilt the depth falls by θ per
    unit length, V = (1/θ)∫A(u)du over the depths of the trace:

    .. math:: V = \\frac{8\\sqrt{2R}}{15\\,\\theta}\\left[D^{5/2} - (D - l\\theta)_+^{5/2}\\right]

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 (TUBE_BAV, TUBE_TUBE).
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.4, cases 1-2.

    Examples
    --------
    >>> round(float(flat_trace_volume(1e-4, 0.01, 0.02)) / (0.02 * 4 / 3 * (2e-2)**0.5 * 1e-6), 12)
    1.0
    """
    d = np.asarray(depth, dtype=float)
    r = float(mobile_radius)
    l = float(width)
    theta = float(tilt)
    root = math.sqrt(2.0 * r)
    if theta == 0.0:
        volume = l * 4.0 / 3.0 * root * d * np.sqrt(d)
    else:
        reach = l * theta
        shallow = np.maximum(d - reach, 0.0) if math.isfinite(reach) else np.zeros_like(d)
        volume = 8.0 * root / (15.0 * theta) * _power_difference_52(d, shallow)
    return _out(volume)


def flat_trace_depth(volume, mobile_radius, width, tilt=0.0):
    """Depth D of a flat worn on a cylinder from its volume (inverse of flat_trace_volume) [m].

    Parameters
    ----------
    volume : float or array_like
        Volume V [m³], ≥ 0.
    mobile_radius : float
        Cylinder radius R [m].
    width : float
        Flat width l along the axis [m] (``inf`` for an unbounded wedge).
    tilt : float
        Tilt θ [rad], ≥ 0.

    Returns
    -------
    numpy.ndarray or float
        Depth D [m].

    Notes
    -----
    .. math:: D = \\left(\\frac{1}{2R}\\right)^{1/3}\\left(\\frac{3V}{4l}\\right)^{2/3}
              \\quad(\\theta = 0), \\qquad
              D = \\left(\\frac{1}{2R}\\right)^{1/5}\\left(\\frac{15\\theta V}{8}\\right)^{2/5}
              \\quad(D < l\\theta)

    and for D ≥ lθ the tilted relation is solved by a bracketed solver on
    [max(lθ, D₀), lθ + D₀] with D₀ the untilted depth (the wedge lies between the sections
    A(D − lθ) and A(D) along its width).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.4, cases 1-2.

    Examples
    --------
    >>> d = flat_trace_depth([1e-9, 1e-8], 0.01, 0.02, math.radians(1.0))
    >>> v = flat_trace_volume(d, 0.01, 0.02, math.radians(1.0))
    >>> np.allclose(v, [1e-9, 1e-8], rtol=1e-11, atol=0)
    True
    """
    v = np.asarray(volume, dtype=float)
    r = float(mobile_radius)
    l = float(width)
    theta = float(tilt)
    untilted = (np.cbrt(0.75 * v / l) ** 2) / np.cbrt(2.0 * r) if math.isfinite(l) else None
    if theta == 0.0:
        depth = untilted
    else:
        depth = (15.0 * theta * v / 8.0) ** 0.4 / (2.0 * r) ** 0.2
        reach = l * theta
        long = depth >= reach
        if np.any(long):
            lower = np.maximum(reach, untilted)
            upper = reach + untilted
            solved = solve_monotone(
                lambda x: flat_trace_volume(x, r, l, theta), np.where(long, v, 0.0),
                np.where(long, lower, 0.0), np.where(long, upper, 0.0))
            depth = np.where(long, solved, depth)
    depth = np.asarray(depth, dtype=float)
    return _out(depth)


def _unshared(depth: np.ndarray, total: np.ndarray, nan_free: bool = False):
    """(d_m, d_o) [m] of :meth:`TubeBav._depth_from_volume` when V_o is 0 (or −0) everywhere:
    where V > 0, V_m/V is exactly 1 (V = V_m + 0 is V_m), so d_m = D and d_o = D − D = 0; 0
    where V is not > 0; NaN where D is (``nan_free``: D known to hold none)."""
    if nan_free:
        return np.where(total > 0.0, depth, 0.0), np.zeros(depth.shape)
    nan = np.isnan(depth)
    return (np.where(nan, np.nan, np.where(total > 0.0, depth, 0.0)),
            np.where(nan, np.nan, 0.0))


@dataclasses.dataclass(frozen=True)
class TubeBav(ContactGeometry):
    """TUBE_BAV: tube against an anti-vibration bar (flat trace, parabolic section).

    Parameters
    ----------
    mobile_radius : float
        Tube outer radius R_m [m] (RAYON_MOBILE).
    obstacle_width : float
        Bar width l [m] (LARGEUR_OBST).
    tilt_angle : float
        Tilt θ of the bar relative to the tube [deg] (ANGL_INCLI), default 0.
    impact_angle : float
        Impact angle α [deg] (ANGL_IMPACT), default 0: volumes are multiplied by cos α.

    Notes
    -----
    D from V = (V_m + V_o)·cos α by :func:`flat_trace_depth`; d_m = D·V_m/(V_m + V_o),
    d_o = D − d_m. Range: D ≤ R_m (the flat reaches the tube's axis; the parabolic section is
    meaningless beyond). See docs/geometry.md.

    Examples
    --------
    >>> g = TubeBav(mobile_radius=0.0111, obstacle_width=0.0127)
    >>> dm, do = g.depth_from_volume(1e-9, 1e-9)
    >>> bool(np.isclose(dm, do)), bool(np.isclose(g.volume_from_depth(dm, do)[0], 1e-9))
    (True, True)
    """

    mobile_radius: float
    obstacle_width: float
    tilt_angle: float = 0.0
    impact_angle: float = 0.0

    contact_type: ClassVar[str] = "TUBE_BAV"
    required: ClassVar[tuple[str, ...]] = ("mobile_radius", "obstacle_width")
    optional: ClassVar[tuple[str, ...]] = ("tilt_angle", "impact_angle")
    example: ClassVar[dict[str, float]] = {
        "mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3, "tilt_angle": 1.0}

    @property
    def max_depth(self) -> float:
        return float(self.mobile_radius)

    @property
    def range_limit(self) -> str:
        return (f"total depth d_m + d_o up to the tube radius R_m = {self.mobile_radius:.6g} m, "
                "where the worn flat reaches the tube's axis")

    def _depth_from_volume(self, volume_mobile, volume_obstacle):
        cos_impact = math.cos(self.angle("impact_angle"))
        total = volume_mobile + volume_obstacle
        depth = flat_trace_depth(total if cos_impact == 1.0 else total * cos_impact,  # (V·1 = V)
                                 self.mobile_radius, self.obstacle_width,
                                 self.angle("tilt_angle"))
        # no NaN and none beyond the range: the mask below would change nothing
        nan_free = bool(depth.ndim and depth.size and depth.max() <= self.max_depth)
        if not nan_free:
            depth = np.where(depth <= self.max_depth, depth, np.nan)
        if not volume_obstacle.any():  # the bar does not wear: the tube's share is 1 exactly
            return _unshared(depth, total, nan_free)
        with np.errstate(invalid="ignore", divide="ignore"):
            # the share first: exactly 1 when the bar does not wear, so d_o is exactly 0
            depth_mobile = np.where(total > 0.0, depth * (volume_mobile / total), 0.0)
        depth_mobile = np.where(np.isnan(depth), np.nan, depth_mobile)
        depth_obstacle = np.where(total > 0.0, depth - depth_mobile, 0.0)
        depth_obstacle = np.where(np.isnan(depth), np.nan, np.maximum(depth_obstacle, 0.0))
        return depth_mobile, depth_obstacle

    def _volume_from_depth(self, depth_mobile, depth_obstacle):
        cos_impact = math.cos(self.angle("impact_angle"))
        depth = depth_mobile + depth_obstacle
        valid = depth <= self.max_depth
        total = flat_trace_volume(np.where(valid, depth, 0.0), self.mobile_radius,
                                  self.obstacle_width, self.angle("tilt_angle")) / cos_impact
        with np.errstate(invalid="ignore", divide="ignore"):
            volume_mobile = np.where(depth > 0.0, total * (depth_mobile / depth), 0.0)
            volume_obstacle = np.where(depth > 0.0, total * (depth_obstacle / depth), 0.0)
        return (np.where(valid, volume_mobile, np.nan), np.where(valid, volume_obstacle, np.nan))
