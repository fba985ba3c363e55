"""Shared plane-geometry helpers of the volume/depth relations (theory §6).

All functions are vectorised with numpy (any broadcastable shapes) and work in SI units:
lengths [m], areas [m²], angles [rad]. They never modify their arguments.

- :func:`segment_area`, :func:`sagitta`: circular segment of radius ρ cut by a chord.
- :func:`lens_half_chord`, :func:`lens_area`, :func:`lens_depth_limit`: the lens (lunule) of a
  mobile disk of radius R_m that protrudes by D beyond a bore of radius R_o > R_m.
- the lens shared between a worn mobile and a worn bore (the lunule) is in
  :mod:`fretwear.geometry._lunule`.
- :func:`frustum_volume`: the frustum (prismatoid) rule of a tilted contact.
- :func:`solve_monotone`: vectorised bracketed solver for increasing functions.
- :func:`stacked_lens_area`: :func:`lens_area` of given radii for a solver's many calls.

The closed forms are written so that they keep full relative precision at small depth: the
segment uses a series of u − sin u for small angles, the sagitta is ``x²/(ρ + √(ρ² − x²))``
and the lens half-chord uses the factorised (Heron-like) form derived in ``docs/geometry.md``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import numpy as np

from fretwear._lazy import compiled_when_used
from fretwear.geometry._solve import (  # noqa: F401 - re-exported
    _out,
    monotone_grid,
    solve_monotone,
    solve_on_grid,
)

__all__ = [
    "frustum_volume",
    "lens_area",
    "lens_depth_limit",
    "lens_half_chord",
    "sagitta",
    "segment_area",
    "solve_monotone",
    "stacked_lens_area",
]

# Taylor coefficients of u - sin(u) = u³/3! - u⁵/5! + u⁷/7! - ...  (used for |u| < 0.5, where the
# truncation after u¹⁵ leaves a relative error below 1e-17).
_SERIES_LIMIT = 0.5
_SERIES = [(-1.0) ** k / float(np.prod(np.arange(1, 2 * k + 4))) for k in range(7)]


def _u_minus_sin(u: np.ndarray) -> np.ndarray:
    """u − sin(u) with full relative precision for small u (u ≥ 0)."""
    u = np.asarray(u, dtype=float)
    small = np.abs(u) < _SERIES_LIMIT
    every = bool(small.all())
    if not every and not small.any():  # the direct form only (the series would be dropped)
        with np.errstate(invalid="ignore"):
            return np.asarray(u - np.sin(u))
    u2 = u * u
    series = np.zeros_like(u)
    power = u * u2
    for coefficient in _SERIES:
        series = series + coefficient * power
        power = power * u2
    if every:  # the series only (the direct form would be dropped)
        return np.asarray(series)
    with np.errstate(invalid="ignore"):
        direct = u - np.sin(u)
    return np.where(small, series, direct)


def segment_area(radius, half_chord):
    """Area of the circular segment of radius ρ cut off by a chord of half-length x [m²].

    Parameters
    ----------
    radius : float or array_like
        Circle radius ρ [m], > 0.
    half_chord : float or array_like
        Half-length x of the chord [m], 0 ≤ x ≤ ρ (NaN outside).

    Returns
    -------
    numpy.ndarray or float
        Area of the minor segment [m²] (NaN where x > ρ or x < 0).

    Notes
    -----
    .. math:: \\mathrm{seg}(\\rho, x) = \\rho^2 \\arcsin(x/\\rho) - x\\sqrt{\\rho^2 - x^2}
              = \\tfrac{\\rho^2}{2}\\,(2\\varphi - \\sin 2\\varphi),\\quad \\sin\\varphi = x/\\rho

    The second form, with a series of u − sin u for small u = 2φ, keeps full relative precision
    for chords much shorter than the radius (seg ≈ 2x³/(3ρ)). Theory §6 [1]_ (Code_Aster R7.20.01
    [2]_ writes ρ²(φ − sin 2φ), a typo).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.1 (corrected as in theory
           §6).

    Examples
    --------
    >>> round(float(segment_area(1.0, 1.0)), 12)  # half disk: π/2
    1.570796326795
    >>> round(float(segment_area(2.0, 1e-4)) / (2 * 1e-12 / 6), 9)  # small chord: 2x³/(3ρ)
    1.0
    """
    rho = np.asarray(radius, dtype=float)
    x = np.asarray(half_chord, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = x / rho
        valid = (ratio >= 0.0) & (ratio <= 1.0)
        phi = np.arcsin(np.where(valid, ratio, np.nan))
        area = 0.5 * rho * rho * _u_minus_sin(2.0 * phi)
    return _out(area)


def sagitta(radius, half_chord):
    """Height of the circular segment of radius ρ cut by a chord of half-length x [m].

    Parameters
    ----------
    radius : float or array_like
        Circle radius ρ [m], > 0.
    half_chord : float or array_like
        Half-length x of the chord [m], 0 ≤ x ≤ ρ (NaN outside).

    Returns
    -------
    numpy.ndarray or float
        Sagitta s [m].

    Notes
    -----
    .. math:: s(\\rho, x) = \\rho - \\sqrt{\\rho^2 - x^2}
              = \\frac{x^2}{\\rho + \\sqrt{\\rho^2 - x^2}}

    The second form is used (no cancellation for x ≪ ρ).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.

    Examples
    --------
    >>> float(sagitta(5.0, 3.0))
    1.0
    >>> float(sagitta(1.0, 1e-6))  # x²/(2ρ)
    5e-13
    """
    rho = np.asarray(radius, dtype=float)
    x = np.asarray(half_chord, dtype=float)
    with np.errstate(invalid="ignore"):
        valid = (x >= 0.0) & (x <= rho)
        root = np.sqrt(np.where(valid, rho * rho - x * x, np.nan))
        s = x * x / (rho + root)
    return _out(s)


def lens_half_chord(mobile_radius, obstacle_radius, depth):
    """Half-chord x of the lens of a mobile disk protruding by D beyond a bore [m].

    The mobile disk (radius R_m) has its centre offset by c = R_o − R_m + D from the centre of
    the bore (radius R_o > R_m), so that it reaches a depth D beyond the bore's surface.
    The two circles cross at the ends of a chord of half-length x.

    Parameters
    ----------
    mobile_radius : float or array_like
        Mobile outer radius R_m [m].
    obstacle_radius : float or array_like
        Bore radius R_o [m], > R_m.
    depth : float or array_like
        Depth D of the mobile beyond the bore [m], D ≥ 0.

    Returns
    -------
    numpy.ndarray or float
        Half-chord x [m] (NaN where D < 0 or D > 2 R_m).

    Notes
    -----
    Theory §6 writes x² = R_m² − (R_o² − R_m² − c²)²/(4c²). Factorising the difference of squares
    gives the form used here, exact and free of cancellation at small D:

    .. math:: x^2 = \\frac{D\\,(2R_o + D)\\,(2R_m - D)\\,(2(R_o - R_m) + D)}{4c^2},
              \\qquad c = R_o - R_m + D

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6 (same x).

    Examples
    --------
    >>> float(lens_half_chord(3.0, 5.0, 0.0))
    0.0
    >>> round(float(lens_half_chord(3.0, 5.0, 2.0)), 12)  # c = 4: circles cross at x = 3
    3.0
    """
    rm = np.asarray(mobile_radius, dtype=float)
    ro = np.asarray(obstacle_radius, dtype=float)
    d = np.asarray(depth, dtype=float)
    c = ro - rm + d
    with np.errstate(invalid="ignore", divide="ignore"):
        product = d * (2.0 * ro + d) * (2.0 * rm - d) * (2.0 * (ro - rm) + d)
        x = np.sqrt(np.where((d >= 0.0) & (product >= 0.0), product, np.nan)) / (2.0 * c)
        x = np.where(d == 0.0, 0.0, x)
    return _out(x)


def lens_depth_limit(mobile_radius, obstacle_radius):
    """Largest depth D of the lens relation: the chord reaches the mobile's centre [m].

    Parameters
    ----------
    mobile_radius : float or array_like
        Mobile outer radius R_m [m].
    obstacle_radius : float or array_like
        Bore radius R_o [m], > R_m.

    Returns
    -------
    numpy.ndarray or float
        D_max [m]; there x = R_m (the lens holds half the mobile's disk minus a bore segment).

    Notes
    -----
    The chord passes through the mobile's centre when c² = R_o² − R_m², so

    .. math:: D_{max} = \\sqrt{R_o^2 - R_m^2} - (R_o - R_m)

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 ("valid while the chord stays beyond the mobile's
           centre").

    Examples
    --------
    >>> float(lens_depth_limit(3.0, 5.0))
    2.0
    """
    rm = np.asarray(mobile_radius, dtype=float)
    ro = np.asarray(obstacle_radius, dtype=float)
    with np.errstate(invalid="ignore"):
        # sqrt(ro² - rm²) written as sqrt((ro - rm)·(ro + rm)): no cancellation when ro ≈ rm.
        g = ro - rm
        limit = np.sqrt(g * (ro + rm)) - g
    return _out(limit)


def lens_area(mobile_radius, obstacle_radius, depth):
    """Area S(D) of the mobile's disk outside the bore (the lens, or lunule) [m²].

    Parameters
    ----------
    mobile_radius : float or array_like
        Mobile outer radius R_m [m].
    obstacle_radius : float or array_like
        Bore radius R_o [m], > R_m.
    depth : float or array_like
        Depth D of the mobile beyond the bore [m], 0 ≤ D ≤ :func:`lens_depth_limit`.

    Returns
    -------
    numpy.ndarray or float
        S [m²] (NaN beyond the limit or for D < 0).

    Notes
    -----
    .. math:: S(D) = R_m^2\\arcsin\\frac{x}{R_m} - R_o^2\\arcsin\\frac{x}{R_o} + x\\,c
              = \\mathrm{seg}(R_m, x) - \\mathrm{seg}(R_o, x)

    with x from :func:`lens_half_chord` and c = R_o − R_m + D (the two forms are equal because
    √(R_m² − x²) + c = √(R_o² − x²)); the segment difference is used.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6.

    Examples
    --------
    >>> import numpy as np
    >>> s = float(lens_area(3.0, 5.0, 2.0))  # half disk of radius 3 minus a segment of radius 5
    >>> bool(np.isclose(s, np.pi * 9 / 2 - (25 * np.arcsin(0.6) - 3 * 4), rtol=1e-14))
    True
    """
    rm = np.asarray(mobile_radius, dtype=float)
    ro = np.asarray(obstacle_radius, dtype=float)
    d = np.asarray(depth, dtype=float)
    x = lens_half_chord(rm, ro, d)
    limit = lens_depth_limit(rm, ro)
    tolerance = 1e-12 * np.maximum(limit, 0.0)
    with np.errstate(invalid="ignore"):
        x = np.where(d <= limit + tolerance, np.minimum(x, rm), np.nan)
        area = segment_area(rm, x) - segment_area(ro, x)
    area = np.asarray(area, dtype=float)
    return _out(area)


def lens_area_on_range(mobile_radius: float, obstacle_radius: float):
    """(:func:`stacked_lens_area` of the radii, its values at depth 0 and at
    :func:`lens_depth_limit`, the limit) [m², m], made once per pair of radii (kept for the
    last 256 pairs): a solver on [0, D_max] starts from them."""
    return _lens_area_on_range(float(mobile_radius), float(obstacle_radius))


@functools.lru_cache(maxsize=256)
def _lens_area_on_range(mobile_radius: float, obstacle_radius: float):
    area = stacked_lens_area(mobile_radius, obstacle_radius)
    limit = float(lens_depth_limit(mobile_radius, obstacle_radius))
    with np.errstate(invalid="ignore"):
        at_zero, at_limit = area(np.array([0.0, limit]))
    return area, float(at_zero), float(at_limit), limit


def lens_area_grid(mobile_radius: float, obstacle_radius: float):
    """(:func:`lens_area_on_range`'s area function, its
    :func:`~fretwear.geometry._solve.monotone_grid` on [0, D_max]) [m², m], made once per
    pair of radii (the last 256 kept): a solver of S(D) = A starts each element from the grid
    points around its area
    (:func:`~fretwear.geometry._solve.solve_on_grid`)."""
    return _lens_area_grid(float(mobile_radius), float(obstacle_radius))


@functools.lru_cache(maxsize=256)
def _lens_area_grid(mobile_radius: float, obstacle_radius: float):
    area, at_zero, at_limit, limit = _lens_area_on_range(mobile_radius, obstacle_radius)
    return area, monotone_grid(area, limit, (at_zero, at_limit))


def lens_range(mobile_radius, obstacle_radius) -> float:
    """The largest depth :func:`lens_area` accepts [m]: :func:`lens_depth_limit` and its
    tolerance of 1e-12 relative."""
    limit = lens_depth_limit(mobile_radius, obstacle_radius)
    return limit + 1e-12 * np.maximum(limit, 0.0)


def stacked_lens_area(mobile_radius, obstacle_radius) -> Callable:
    """:func:`lens_area` of these radii as a function of a 1-d array of depths [m] -> [m²], bit
    for bit, for a solver that calls it many times: the two circular segments (R_m and R_o) in
    one :func:`segment_area` call on the stacked chords, the radii's constants once.

    The same element-wise operations in the same order as :func:`lens_area`; with numba the
    arithmetic is compiled (:func:`_lens_kernels`) around NumPy's own arcsin and sin.

    Examples
    --------
    >>> d = np.array([0.5, 1.0, 2.0])
    >>> bool(np.array_equal(stacked_lens_area(3.0, 5.0)(d), lens_area(3.0, 5.0, d)))
    True
    """
    rm = np.asarray(mobile_radius, dtype=float)
    ro = np.asarray(obstacle_radius, dtype=float)
    within = lens_range(rm, ro)
    radii: dict[int, np.ndarray] = {}

    def area(d: np.ndarray) -> np.ndarray:
        x = lens_half_chord(rm, ro, d)
        with np.errstate(invalid="ignore"):
            x = np.where(d <= within, np.minimum(x, rm), np.nan)
        n = d.size
        if n not in radii:
            radii[n] = np.concatenate([np.full(n, float(rm)), np.full(n, float(ro))])
        segments = np.asarray(segment_area(radii[n], np.concatenate([x, x])), dtype=float)
        return segments[:n] - segments[n:]

    kernels = _lens_kernels()
    if kernels is None:
        return area
    ratios_of, lens_of = kernels
    r_m, r_o, top = float(rm), float(ro), float(within)

    def compiled_area(d: np.ndarray) -> np.ndarray:
        # the operations of ``area`` in their order: the arithmetic compiled, NumPy's own
        # arcsin and sin (their results differ from the C library's in the last bit)
        d = np.ascontiguousarray(d, dtype=float)
        ratio = np.empty(2 * d.size)
        ratios_of(d, r_m, r_o, top, ratio)
        # the ratios are in [0, 1] or NaN: NumPy's arcsin and sin raise nothing on them
        u = 2.0 * np.arcsin(ratio)
        out = np.empty(d.size)
        lens_of(u, np.sin(u), r_m, r_o, out)
        return out

    return compiled_area


def _lens_ratios(d, rm, ro, within, ratio):
    """x/R_m, then x/R_o (NaN outside [0, 1]) of the lens half-chord x of each depth, as
    :func:`lens_half_chord`, the range of :func:`lens_area` and :func:`segment_area` make
    them (compiled with numba: :func:`_lens_kernels`)."""
    n = d.size
    gap = ro - rm
    for i in range(n):
        di = d[i]
        c = gap + di
        product = di * (2.0 * ro + di) * (2.0 * rm - di) * (2.0 * gap + di)
        if di >= 0.0 and product >= 0.0:
            x = math.sqrt(product) / (2.0 * c)
        else:
            x = math.nan
        if di == 0.0:
            x = 0.0
        if di <= within:
            x = x if (x != x or x < rm) else rm  # np.minimum(x, R_m)
        else:
            x = math.nan
        for j, rho in ((i, rm), (n + i, ro)):
            r = x / rho
            ratio[j] = r if (r >= 0.0 and r <= 1.0) else math.nan


def _lens_of_angles(u, sine, rm, ro, out):
    """seg(R_m) − seg(R_o) of each depth from u = 2φ of both segments (first the R_m ones), as
    :func:`segment_area` and :func:`_u_minus_sin` make them (``sine``: sin u, used where |u|
    is not below the series limit)."""
    n = out.size
    for i in range(n):
        seg_m = 0.0
        seg_o = 0.0
        for j, rho in ((i, rm), (n + i, ro)):
            uj = u[j]
            if abs(uj) < _SERIES_LIMIT:
                u2 = uj * uj
                series = 0.0
                power = uj * u2
                for coefficient in _SERIES_TUPLE:
                    series = series + coefficient * power
                    power = power * u2
                value = series
            else:
                value = uj - sine[j]
            segment = 0.5 * rho * rho * value
            if j == i:
                seg_m = segment
            else:
                seg_o = segment
        out[i] = seg_m - seg_o


_SERIES_TUPLE = tuple(_SERIES)
#: (:func:`_lens_ratios`, :func:`_lens_of_angles`) compiled at the first call, None without
#: numba.
_lens_kernels = compiled_when_used(_lens_ratios, _lens_of_angles)


def frustum_volume(area: Callable, depth, width, tilt):
    """Volume of a tilted trace by the frustum (prismatoid) rule [m³].

    Parameters
    ----------
    area : callable
        A(d): cross-section area [m²] of the trace at depth d [m] (vectorised, A(0) = 0).
    depth : float or array_like
        Depth d at the deepest end of the trace [m], ≥ 0.
    width : float or array_like
        Obstacle width l [m] (length of the trace along the mobile's axis when d ≥ l·θ).
    tilt : float or array_like
        Tilt angle θ [rad], ≥ 0 (θ = 0 gives l·A(d)).

    Returns
    -------
    numpy.ndarray or float
        Volume [m³].

    Notes
    -----
    The trace is a wedge whose depth falls linearly from d by θ per unit length along the axis:

    .. math:: V = \\frac{d}{\\theta}\\,\\frac{A(d)}{3} \\quad (d < l\\theta), \\qquad
              V = \\frac{l}{3}\\left(A_1 + \\sqrt{A_1 A_2} + A_2\\right) \\quad (d \\ge l\\theta)

    with A1 = A(d), A2 = A(d − lθ). Both branches agree at d = lθ. The rule is exact when A
    grows as d² (pyramid); for A ∝ d^{3/2} it gives 5/6 of the exact wedge integral
    (1/θ)∫A(u)du (see docs/geometry.md). Theory §6 prescribes it.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.6 case 2.

    Examples
    --------
    >>> float(frustum_volume(lambda d: d**2, 1.0, 10.0, 0.5))  # pyramid: (d/θ)·d²/3
    0.6666666666666666
    >>> float(frustum_volume(lambda d: d**2, 1.0, 2.0, 0.0))  # no tilt: l·A(d)
    2.0
    """
    d = np.asarray(depth, dtype=float)
    l = np.asarray(width, dtype=float)
    theta = np.asarray(tilt, dtype=float)
    reach = l * theta
    short = d < reach
    a1 = np.asarray(area(d), dtype=float)
    a2 = np.asarray(area(np.where(short, 0.0, np.maximum(d - reach, 0.0))), dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        wedge = np.where(short, d / np.where(short, theta, 1.0) * a1 / 3.0, 0.0)
        frustum = l / 3.0 * (a1 + np.sqrt(a1 * a2) + a2)
    volume = np.where(short, wedge, frustum)
    return _out(volume)
