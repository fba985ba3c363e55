"""TUBE_3_ENCO / TUBE_4_ENCO: tube against an isthmus edge of a broached hole (theory §6).

A steam-generator tube (radius R_m) passes through a trefoil (three lobes) or quatrefoil (four
lobes) broached hole of a support plate: the tube bears on the lands ("isthmuses") between the
lobes, on the arc of radius R_o, and wears against the edge where a land meets a lobe flank. With
the tube pushed by D beyond the bore circle, the worn section at one edge is half the lens S(D)
(the land side) plus the material wedge over the lobe side, bounded by the flank, which makes the
angle α_i (ANGL_ISTHME) with the radius through the edge:

    S'(D) = S(D) + tan(α_i)·D²,   worn section at one edge A(D) = S'(D)/2.

The wedge term is the flat-front approximation: it counts the right triangle of legs D and
D·tan α_i, and overestimates the exact wedge by (D·tan α_i)³/(6 R_m) (the tube's curvature over
the triangle), see ``docs/geometry.md``.

Volumes: no tilt V = n·(l/2)·S'(D); tilt θ: the frustum rule with A = S'/2,
V = n·D·S'(D)/(6θ) while D < lθ, else n·(l/6)·(S'1 + √(S'1·S'2) + S'2). n = 1 edge for the
trefoil, n = 2 for the quatrefoil (the tube bears on the two edges of a lobe, each carrying half
the volumes). V is V_m, or V_m + V_o with D = d_m + d_o and V_o = κ·π·l·R_o·d_o (κ = 1.41
trefoil, 1.88 quatrefoil).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import ClassVar

import numpy as np

from fretwear._lazy import compiled_when_used
from fretwear.geometry._shapes import (
    _lens_kernels,
    _out,
    frustum_volume,
    lens_area,
    lens_depth_limit,
    lens_range,
    monotone_grid,
    solve_on_grid,
    stacked_lens_area,
)
from fretwear.geometry.base import ContactGeometry

__all__ = [
    "ENCO_TYPES",
    "Tube3Enco",
    "Tube4Enco",
    "enco_depth",
    "enco_obstacle_volume",
    "enco_volume",
    "isthmus_section_area",
]

#: Broached-hole families, keyed by Code_Aster contact type: obstacle factor κ [-] of
#: V_o = κ·π·l·R_o·d_o (Code_Aster R7.20.01 §4.6-§4.7), number of isthmus edges the tube bears on
#: (theory §6), number of lobes of the hole.
ENCO_TYPES: dict[str, dict] = {
    "TUBE_3_ENCO": {"kappa": 1.41, "edges": 1, "lobes": 3},
    "TUBE_4_ENCO": {"kappa": 1.88, "edges": 2, "lobes": 4},
}


def isthmus_section_area(depth, mobile_radius, obstacle_radius, isthmus_angle):
    """S'(D) = S(D) + tan(α_i)·D²: twice the worn section at one isthmus edge [m²].

    Parameters
    ----------
    depth : float or array_like
        Total depth D of the tube beyond the bore circle [m], 0 ≤ D ≤ √(R_o² − R_m²) − (R_o − R_m).
    mobile_radius : float
        Tube outer radius R_m [m].
    obstacle_radius : float
        Radius R_o of the bore circle of the lands [m], > R_m.
    isthmus_angle : float
        Isthmus angle α_i [deg]: angle between the lobe flank and the radius through the edge.

    Returns
    -------
    numpy.ndarray or float
        S'(D) [m²]; NaN beyond the lens range (chord past the tube's centre).

    Notes
    -----
    .. math:: S'(D) = R_m^2\\arcsin\\frac{x}{R_m} - R_o^2\\arcsin\\frac{x}{R_o}
              + x\\,(R_o - R_m + D) + D^2\\tan\\alpha_i

    (Code_Aster R7.20.01 §4.6 case 1). Half of it is the worn section at the edge: half lens on
    the land side plus the triangle of legs D and D·tan α_i over the lobe side.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6-§4.7.

    Examples
    --------
    >>> import numpy as np
    >>> s = isthmus_section_area(1e-4, 9.525e-3, 9.75e-3, 45.0)
    >>> bool(np.isclose(s - lens_area(9.525e-3, 9.75e-3, 1e-4), 1e-8, rtol=1e-12))
    True
    """
    d = np.asarray(depth, dtype=float)
    wedge = math.tan(math.radians(isthmus_angle)) * d * d
    area = lens_area(mobile_radius, obstacle_radius, d) + wedge
    area = np.asarray(area, dtype=float)
    return _out(area)


def enco_volume(depth, mobile_radius, obstacle_radius, width, isthmus_angle, tilt_angle=0.0,
                edges=1):
    """Total worn volume V (V_m, or V_m + V_o) of a broached-hole contact at total depth D [m³].

    Parameters
    ----------
    depth : float or array_like
        Total depth D = d_m + d_o at the deepest section [m], ≥ 0.
    mobile_radius : float
        Tube outer radius R_m [m].
    obstacle_radius : float
        Radius R_o of the bore circle of the lands [m], > R_m.
    width : float
        Plate thickness l (worn height) [m].
    isthmus_angle : float
        Isthmus angle α_i [deg].
    tilt_angle : float
        Tilt θ of the tube in the hole [deg], ≥ 0.
    edges : int
        Number of isthmus edges the tube bears on: 1 (TUBE_3_ENCO) or 2 (TUBE_4_ENCO).

    Returns
    -------
    numpy.ndarray or float
        V [m³]; NaN beyond the lens range.

    Notes
    -----
    Frustum rule with the section A = S'/2 of one edge, times the number of edges n:

    .. math:: V = n\\,\\frac{l}{2} S'(D)\\ (\\theta = 0), \\quad
              V = n\\,\\frac{D\\,S'(D)}{6\\theta}\\ (D < l\\theta), \\quad
              V = n\\,\\frac{l}{6}\\left(S'_1 + \\sqrt{S'_1 S'_2} + S'_2\\right)\\ (D \\ge l\\theta)

    with S'1 = S'(D), S'2 = S'(D − lθ). Continuous at D = lθ (S'2 = 0 there).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 (typos of R7.20.01 resolved).
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6-§4.7, cases 1-4.

    Examples
    --------
    >>> import numpy as np
    >>> v = enco_volume(1e-4, 9.525e-3, 9.75e-3, 0.03, 30.0)
    >>> bool(np.isclose(v, 0.03 / 2 * isthmus_section_area(1e-4, 9.525e-3, 9.75e-3, 30.0)))
    True
    """
    theta = math.radians(tilt_angle)

    def section(d):
        return 0.5 * np.asarray(isthmus_section_area(d, mobile_radius, obstacle_radius,
                                                     isthmus_angle), dtype=float)

    volume = edges * np.asarray(frustum_volume(section, depth, width, theta), dtype=float)
    return _out(volume)


def enco_depth(volume, mobile_radius, obstacle_radius, width, isthmus_angle, tilt_angle=0.0,
               edges=1, rtol=1e-13):
    """Total depth D from the total worn volume V (inverse of :func:`enco_volume`) [m].

    Parameters
    ----------
    volume : float or array_like
        Total worn volume V = V_m + V_o [m³], ≥ 0.
    mobile_radius, obstacle_radius, width : float
        R_m, R_o, l [m] as in :func:`enco_volume`.
    isthmus_angle, tilt_angle : float
        α_i, θ [deg].
    edges : int
        1 (TUBE_3_ENCO) or 2 (TUBE_4_ENCO).
    rtol : float
        Relative tolerance on D [-].

    Returns
    -------
    numpy.ndarray or float
        D [m] in [0, D_max], D_max = √(R_o² − R_m²) − (R_o − R_m); NaN where V exceeds V(D_max).

    Notes
    -----
    V(D) is increasing (S' is), so the root is bracketed by [0, D_max] and found by the
    vectorised Chandrupatla solver (:func:`~fretwear.geometry._shapes.solve_monotone`), each
    element from the two points around its volume of a grid of V on [0, D_max] made once per
    dimensions (:func:`~fretwear.geometry._solve.solve_on_grid`).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6-§4.7 ("a solver
           integrated into POST_USURE").

    Examples
    --------
    >>> d = enco_depth(1e-9, 9.525e-3, 9.75e-3, 0.03, 30.0, tilt_angle=1.0)
    >>> v = enco_volume(d, 9.525e-3, 9.75e-3, 0.03, 30.0, tilt_angle=1.0)
    >>> bool(np.isclose(v, 1e-9, rtol=1e-12))
    True
    """
    v = np.asarray(volume, dtype=float)
    func, grid = _enco_volume_grid(
        float(mobile_radius), float(obstacle_radius), float(width), float(isthmus_angle),
        float(tilt_angle), int(edges))
    depth = solve_on_grid(func, v, grid, rtol=rtol)
    depth = np.where(v == 0.0, 0.0, np.asarray(depth, dtype=float))
    return _out(depth)


@functools.lru_cache(maxsize=256)
def _enco_volume_on_range(mobile_radius: float, obstacle_radius: float, width: float,
                          isthmus_angle: float, tilt_angle: float, edges: int):
    """(:func:`_stacked_enco_volume` of the dimensions, its values at depth 0 and at the lens
    limit D_max, D_max) [m³, m], made once per dimensions (the last 256 kept): enco_depth's
    solver on [0, D_max] starts from them."""
    func = _stacked_enco_volume(mobile_radius, obstacle_radius, width, isthmus_angle,
                                tilt_angle, edges)
    limit = float(lens_depth_limit(mobile_radius, obstacle_radius))
    with np.errstate(invalid="ignore"):
        at_zero, at_limit = func(np.array([0.0, limit]))
    return func, float(at_zero), float(at_limit), limit


@functools.lru_cache(maxsize=256)
def _enco_volume_grid(mobile_radius: float, obstacle_radius: float, width: float,
                      isthmus_angle: float, tilt_angle: float, edges: int):
    """(:func:`_stacked_enco_volume` of the dimensions, its
    :func:`~fretwear.geometry._solve.monotone_grid` on [0, D_max]) [m³, m], made once per
    dimensions (the last 256 kept): enco_depth's solver starts each element from the grid
    points around its volume (:func:`~fretwear.geometry._solve.solve_on_grid`)."""
    func, at_zero, at_limit, limit = _enco_volume_on_range(
        mobile_radius, obstacle_radius, width, isthmus_angle, tilt_angle, edges)
    return func, monotone_grid(func, limit, (at_zero, at_limit))


def _stacked_enco_volume(mobile_radius, obstacle_radius, width, isthmus_angle, tilt_angle=0.0,
                         edges=1):
    """:func:`enco_volume` of these dimensions as a function of the depth [m] -> [m³], bit for
    bit, with the solver's trial depths stacked: the two frustum sections S'(D)/2 and
    S'(D − lθ)/2 in one lens computation, the four circular segments (R_m and R_o of each) in one
    :func:`~fretwear.geometry._shapes.segment_area` call
    (:func:`~fretwear.geometry._shapes.stacked_lens_area`), the dimensions' constants once.

    The same element-wise operations in the same order as :func:`enco_volume` (through
    :func:`~fretwear.geometry._shapes.frustum_volume`, :func:`isthmus_section_area`,
    :func:`~fretwear.geometry._shapes.lens_area`), on arrays four times longer: the solver
    (:func:`enco_depth`) calls it some twenty times per table.
    """
    lens = stacked_lens_area(mobile_radius, obstacle_radius)
    l = np.asarray(width, dtype=float)
    theta = np.asarray(math.radians(tilt_angle), dtype=float)
    reach = l * theta
    slope = math.tan(math.radians(isthmus_angle))

    def sections(d):  # S'(d)/2 (isthmus_section_area / 2) of a 1-d array of depths
        return 0.5 * (lens(d) + slope * d * d)

    def volume(depth):
        d = np.asarray(depth, dtype=float)
        shape = d.shape
        d = d.ravel()
        short = d < reach
        n = d.size
        both = sections(np.concatenate([d, np.where(short, 0.0, np.maximum(d - reach, 0.0))]))
        a1, a2 = both[:n], both[n:]
        with np.errstate(invalid="ignore", divide="ignore"):
            wedge = np.where(short, d / np.where(short, theta, 1.0) * a1 / 3.0, 0.0)
            frustum = l / 3.0 * (a1 + np.sqrt(a1 * a2) + a2)
        return _out((edges * np.where(short, wedge, frustum)).reshape(shape))

    kernels, lens_kernels = _enco_kernels(), _lens_kernels()
    if kernels is None or lens_kernels is None:
        return volume
    stack_of, volumes_of = kernels
    ratios_of, lens_of = lens_kernels
    r_m, r_o = float(mobile_radius), float(obstacle_radius)
    top = float(lens_range(np.asarray(r_m), np.asarray(r_o)))
    constants = (slope, float(l), float(theta), float(reach), float(edges))

    def compiled_volume(depth):
        # the operations of ``volume`` in their order: the arithmetic compiled, NumPy's own
        # arcsin and sin (their results differ from the C library's in the last bit)
        d = np.asarray(depth, dtype=float)
        shape = d.shape
        d = np.ascontiguousarray(d).ravel()
        stacked = np.empty(2 * d.size)
        stack_of(d, float(reach), stacked)
        ratio = np.empty(2 * stacked.size)
        ratios_of(stacked, r_m, r_o, top, ratio)
        # the ratios are in [0, 1] or NaN: NumPy's arcsin and sin raise nothing on them
        u = 2.0 * np.arcsin(ratio)
        lens = np.empty(stacked.size)
        lens_of(u, np.sin(u), r_m, r_o, lens)
        out = np.empty(d.size)
        volumes_of(stacked, lens, *constants, out)
        return _out(out.reshape(shape))

    return compiled_volume


def _enco_stack(d, reach, stacked):
    """The depths of both frustum sections, [D, then max(D − lθ, 0) or 0 where D < lθ], as
    ``_stacked_enco_volume``'s ``volume`` stacks them (np.maximum keeps a NaN)."""
    n = d.size
    for i in range(n):
        di = d[i]
        stacked[i] = di
        if di < reach:
            stacked[n + i] = 0.0
        else:
            e = di - reach
            stacked[n + i] = e if (e != e or e > 0.0) else 0.0


def _enco_volumes(stacked, lens, slope, l, theta, reach, edges, out):
    """n·(wedge or frustum) of each depth from the lens areas of its two sections (``lens``:
    :func:`~fretwear.geometry._shapes._lens_of_angles` of the stacked depths, D's then the
    second section's), with the operations of ``_stacked_enco_volume``'s ``volume`` in their
    order."""
    n = out.size
    third = l / 3.0
    for i in range(n):
        d = stacked[i]
        e = stacked[n + i]
        a1 = 0.5 * (lens[i] + slope * d * d)
        a2 = 0.5 * (lens[n + i] + slope * e * e)
        if d < reach:
            value = d / theta * a1 / 3.0
        else:
            value = third * (a1 + math.sqrt(a1 * a2) + a2)
        out[i] = edges * value


#: (:func:`_enco_stack`, :func:`_enco_volumes`) compiled at the first call, None without numba.
_enco_kernels = compiled_when_used(_enco_stack, _enco_volumes)


def enco_obstacle_volume(depth_obstacle, obstacle_radius, width, kappa):
    """Worn volume of the broached plate from its depth: V_o = κ·π·l·R_o·d_o [m³].

    Parameters
    ----------
    depth_obstacle : float or array_like
        Worn depth of the plate d_o [m].
    obstacle_radius : float
        Radius R_o of the bore circle of the lands [m].
    width : float
        Plate thickness l [m].
    kappa : float
        κ [-]: 1.41 trefoil, 1.88 quatrefoil.

    Returns
    -------
    numpy.ndarray or float
        V_o [m³].

    Notes
    -----
    V_o = κ·π·l·R_o·d_o. Code_Aster R7.20.01 [2]_ writes V_o = κ·R_o·d_o·π, without the width,
    which the dimensions need (theory §6). κ = 0.47 per isthmus (1.41 = 3 × 0.47,
    1.88 = 4 × 0.47), the same factor as one guide-card notch (GRAPPE_1_ENCO).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6-§4.7, cases 3-4.

    Examples
    --------
    >>> round(float(enco_obstacle_volume(1e-5, 9.75e-3, 0.03, 1.41)) * 1e9, 6)  # [mm³]
    12.956714
    """
    volume = kappa * math.pi * width * obstacle_radius * np.asarray(depth_obstacle, dtype=float)
    return _out(volume)


@dataclasses.dataclass(frozen=True)
class _BroachedHole(ContactGeometry):
    """Common relations of TUBE_3_ENCO and TUBE_4_ENCO (see the module docstring)."""

    mobile_radius: float
    obstacle_radius: float
    obstacle_width: float
    isthmus_angle: float
    tilt_angle: float = 0.0

    required: ClassVar[tuple[str, ...]] = (
        "mobile_radius", "obstacle_radius", "obstacle_width", "isthmus_angle")
    optional: ClassVar[tuple[str, ...]] = ("tilt_angle",)
    example: ClassVar[dict[str, float]] = {
        "mobile_radius": 9.525e-3, "obstacle_radius": 9.75e-3, "obstacle_width": 30e-3,
        "isthmus_angle": 30.0, "tilt_angle": 0.5}

    def __post_init__(self) -> None:
        super().__post_init__()
        self._check_room("the radius of the lands", "the tube radius")

    @property
    def kappa(self) -> float:
        """Obstacle factor κ [-] of V_o = κ·π·l·R_o·d_o."""
        return ENCO_TYPES[self.contact_type]["kappa"]

    @property
    def edges(self) -> int:
        """Number of isthmus edges the tube bears on (each carries V/edges)."""
        return ENCO_TYPES[self.contact_type]["edges"]

    @property
    def max_depth(self) -> float:
        return float(lens_depth_limit(self.mobile_radius, self.obstacle_radius))

    @property
    def range_limit(self) -> str:
        return (f"total depth d_m + d_o up to {self.max_depth:.6g} m, where the chord of the "
                "lens reaches the tube's axis; and d_m >= 0, i.e. the obstacle depth "
                f"V_o/(κ·π·l·R_o) (κ = {self.kappa}) not beyond the total depth")

    def _total_volume(self, depth):
        return np.asarray(enco_volume(depth, self.mobile_radius, self.obstacle_radius,
                                      self.obstacle_width, self.isthmus_angle, self.tilt_angle,
                                      self.edges), dtype=float)

    def _depth_from_volume(self, volume_mobile, volume_obstacle):
        total = volume_mobile + volume_obstacle
        depth = np.asarray(enco_depth(total, self.mobile_radius, self.obstacle_radius,
                                      self.obstacle_width, self.isthmus_angle, self.tilt_angle,
                                      self.edges), dtype=float)
        depth_obstacle = volume_obstacle / (self.kappa * math.pi * self.obstacle_width
                                            * self.obstacle_radius)
        depth_mobile = depth - depth_obstacle
        # d_m < 0: V_o too large for V_m under the κ relation of theory §6 (inconsistent input).
        # A relative tolerance absorbs the solver's rounding when V_m = 0 gives d_m ≈ 0.
        consistent = depth_mobile >= -1e-12 * depth
        depth_mobile = np.where(consistent, np.maximum(depth_mobile, 0.0), np.nan)
        depth_obstacle = np.where(consistent & ~np.isnan(depth), depth_obstacle, np.nan)
        return depth_mobile, depth_obstacle

    def _volume_from_depth(self, depth_mobile, depth_obstacle):
        depth = depth_mobile + depth_obstacle
        total = self._total_volume(depth)
        volume_obstacle = np.asarray(enco_obstacle_volume(
            depth_obstacle, self.obstacle_radius, self.obstacle_width, self.kappa), dtype=float)
        volume_mobile = total - volume_obstacle
        consistent = volume_mobile >= -1e-12 * total
        volume_mobile = np.where(consistent, np.maximum(volume_mobile, 0.0), np.nan)
        volume_obstacle = np.where(consistent, volume_obstacle, np.nan)
        return volume_mobile, volume_obstacle


@dataclasses.dataclass(frozen=True)
class Tube3Enco(_BroachedHole):
    """TUBE_3_ENCO: tube against an isthmus edge of a trefoil broached hole.

    Parameters
    ----------
    mobile_radius : float
        Tube outer radius R_m [m] (RAYON_MOBILE).
    obstacle_radius : float
        Radius R_o of the bore circle of the lands [m] (RAYON_OBST), > R_m.
    obstacle_width : float
        Plate thickness l (worn height) [m] (LARGEUR_OBST).
    isthmus_angle : float
        Isthmus angle α_i [deg] (ANGL_ISTHME): angle between the lobe flank and the radius
        through the edge, in [0, 90).
    tilt_angle : float
        Tilt θ of the tube in the hole [deg] (ANGL_INCLI), default 0.

    Notes
    -----
    One edge: V = (l/2)·S'(D) (no tilt) or the frustum rule with A = S'/2 (tilt), with
    S'(D) = S(D) + tan(α_i)·D², V = V_m + V_o, D = d_m + d_o, V_o = 1.41·π·l·R_o·d_o.
    Range: D ≤ √(R_o² − R_m²) − (R_o − R_m) and d_m ≥ 0. See docs/geometry.md.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6.

    Examples
    --------
    >>> g = Tube3Enco(mobile_radius=9.525e-3, obstacle_radius=9.75e-3, obstacle_width=0.03,
    ...               isthmus_angle=30.0)
    >>> dm, do = g.depth_from_volume(1e-9)
    >>> round(float(dm) * 1e6, 4), float(do)  # [µm], obstacle not worn
    (14.7281, 0.0)
    >>> bool(np.isclose(g.volume_from_depth(dm)[0], 1e-9, rtol=1e-12))
    True
    """

    contact_type: ClassVar[str] = "TUBE_3_ENCO"


@dataclasses.dataclass(frozen=True)
class Tube4Enco(_BroachedHole):
    """TUBE_4_ENCO: tube against the two isthmus edges of a lobe of a quatrefoil broached hole.

    Parameters
    ----------
    mobile_radius : float
        Tube outer radius R_m [m] (RAYON_MOBILE).
    obstacle_radius : float
        Radius R_o of the bore circle of the lands [m] (RAYON_OBST), > R_m.
    obstacle_width : float
        Plate thickness l (worn height) [m] (LARGEUR_OBST).
    isthmus_angle : float
        Isthmus angle α_i [deg] (ANGL_ISTHME), in [0, 90).
    tilt_angle : float
        Tilt θ of the tube in the hole [deg] (ANGL_INCLI), default 0.

    Notes
    -----
    Two edges, each carrying half the volumes and worn as the trefoil edge:
    V/2 = (l/2)·S'(D), i.e. V = l·S'(D) (no tilt), or V/2 = frustum rule with A = S'/2 (tilt),
    with V = V_m + V_o, D = d_m + d_o (the depth at each edge) and V_o = 1.88·π·l·R_o·d_o.
    See docs/geometry.md.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.7.

    Examples
    --------
    >>> g = Tube4Enco(mobile_radius=9.525e-3, obstacle_radius=9.75e-3, obstacle_width=0.03,
    ...               isthmus_angle=30.0)
    >>> g3 = Tube3Enco(mobile_radius=9.525e-3, obstacle_radius=9.75e-3, obstacle_width=0.03,
    ...                isthmus_angle=30.0)
    >>> bool(np.isclose(g.depth_from_volume(2e-9)[0], g3.depth_from_volume(1e-9)[0]))
    True
    """

    contact_type: ClassVar[str] = "TUBE_4_ENCO"
