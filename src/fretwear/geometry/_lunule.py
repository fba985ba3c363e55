"""The lunule: the lens shared between a worn mobile and a worn bore (theory §6).

The r, α, β, γ system of Code_Aster R7.20.01 §4.1, corrected (segment area ρ²(φ − ½ sin 2φ)): the
new common surface is an arc of radius r, R_m ≤ r ≤ R_o, through the ends of the lens chord of
half-length x, so that V_m/l = seg(R_m, x) − seg(r, x), V_o/l = seg(r, x) − seg(R_o, x), d_m =
s(R_m, x) − s(r, x) and d_o = s(r, x) − s(R_o, x). Vectorised, SI units (lengths [m], areas [m²]);
derivation in ``docs/geometry.md``.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._lazy import compiled_when_used
from fretwear.geometry._shapes import (  # noqa: F401 - lens_area is used by the doctests
    _SERIES_LIMIT,
    _SERIES_TUPLE,
    _out,
    lens_area,
    lens_area_grid,
    lens_depth_limit,
    lens_half_chord,
    sagitta,
    segment_area,
    solve_monotone,
    solve_on_grid,
)

__all__ = ["lunule_areas", "lunule_depths", "lunule_mobile_depth"]


def _interface_segment(half_chord, interface_sagitta):
    """Segment area under the arc through the chord ends with the given sagitta [m²]."""
    x = np.asarray(half_chord, dtype=float)
    s = np.asarray(interface_sagitta, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        radius = (s * s + x * x) / (2.0 * s)
        area = segment_area(radius, np.minimum(x, radius))
    return np.where(x == 0.0, 0.0, area)


def _mobile_area(x, s_m, seg_m):
    """The mobile's area of a lunule of half-chord ``x`` as a function of d_m [m] -> [m²],
    max(seg(R_m, x) − seg(r, x), 0) with r the common arc of sagitta s(R_m, x) − d_m
    (``s_m``, ``seg_m`` of the mobile given), for :func:`lunule_mobile_depth`'s solver: with
    numba its arithmetic compiled around NumPy's own arcsin and sin, the same bits."""

    def area(dm):
        return np.maximum(seg_m - _interface_segment(x, s_m - dm), 0.0)

    kernels = _kernels()
    if kernels is None:
        return area
    ratios_of, areas_of = kernels
    shape = np.shape(x)
    xs, sms, segs = (np.ascontiguousarray(a if np.shape(a) == shape else
                                          np.broadcast_to(a, shape), dtype=float).ravel()
                     for a in (x, s_m, seg_m))

    def compiled_area(dm):
        d = np.asarray(dm, dtype=float)
        if d.shape != shape:  # (broadcast_to costs more than the rest of a small call)
            d = np.broadcast_to(d, shape)
        d = np.ascontiguousarray(d).ravel()
        radius = np.empty(d.size)
        ratio = np.empty(d.size)
        ratios_of(xs, sms, d, radius, ratio)
        # the ratios are in [0, 1] or NaN: NumPy's arcsin and sin raise nothing on them
        u = 2.0 * np.arcsin(ratio)
        out = np.empty(d.size)
        areas_of(u, np.sin(u), radius, xs, segs, out)
        return out.reshape(shape)

    return compiled_area


def _interface_ratios(x, s_m, dm, radius, ratio):
    """The common arc's radius r = (s² + x²)/(2s), s = s_m − d_m, and min(x, r)/r (NaN outside
    [0, 1]), as :func:`_interface_segment` and :func:`segment_area` make them."""
    for i in range(x.size):
        xi = x[i]
        s = s_m[i] - dm[i]
        r = (s * s + xi * xi) / (2.0 * s)
        radius[i] = r
        if xi != xi:  # np.minimum(x, r), NaN kept
            chord = xi
        else:
            chord = xi if xi < r else r
        q = chord / r
        ratio[i] = q if (q >= 0.0 and q <= 1.0) else math.nan


def _mobile_areas(u, sine, radius, x, seg_m, out):
    """max(seg_m − seg(r, x), 0) from u = 2φ of the common arc's segment, as
    :func:`segment_area`, :func:`_u_minus_sin`, :func:`_interface_segment` and np.maximum
    make them (``sine``: sin u, used where |u| is not below the series limit)."""
    for i in range(out.size):
        ui = u[i]
        if abs(ui) < _SERIES_LIMIT:
            u2 = ui * ui
            series = 0.0
            power = ui * u2
            for coefficient in _SERIES_TUPLE:
                series = series + coefficient * power
                power = power * u2
            value = series
        else:
            value = ui - sine[i]
        rho = radius[i]
        segment = 0.0 if x[i] == 0.0 else 0.5 * rho * rho * value
        a = seg_m[i] - segment
        out[i] = a if (a != a or a > 0.0) else 0.0  # np.maximum(a, 0.0)


#: (:func:`_interface_ratios`, :func:`_mobile_areas`) compiled at the first call, None without
#: numba.
_kernels = compiled_when_used(_interface_ratios, _mobile_areas)


def lunule_areas(mobile_radius, obstacle_radius, depth_mobile, depth_obstacle):
    """Worn section areas of mobile and bore in a lunule, from their worn depths [m²].

    Parameters
    ----------
    mobile_radius : float or array_like
        Mobile outer radius R_m [m].
    obstacle_radius : float or array_like
        Bore radius R_o [m], > R_m.
    depth_mobile, depth_obstacle : float or array_like
        Worn depths d_m, d_o [m], ≥ 0, with d_m + d_o ≤ :func:`lens_depth_limit`.

    Returns
    -------
    area_mobile, area_obstacle : numpy.ndarray or float
        A_m = V_m/l and A_o = V_o/l [m²] (NaN beyond the lens range).

    Notes
    -----
    The mobile protrudes by D = d_m + d_o beyond the original bore; the lens S(D) (chord
    half-length x from :func:`lens_half_chord`) is split by the new common surface, an arc
    through the chord ends whose apex lies d_m below the mobile's apex, i.e. of sagitta
    σ = s(R_m, x) − d_m and radius r = (σ² + x²)/(2σ), R_m ≤ r ≤ R_o:

    .. math:: A_m = \\mathrm{seg}(R_m, x) - \\mathrm{seg}(r, x), \\qquad
              A_o = \\mathrm{seg}(r, x) - \\mathrm{seg}(R_o, x)

    This is the r, α, β, γ system of [2]_ with R_m sin α = r sin β = R_o sin γ = x and the
    segment area ρ²(φ − ½ sin 2φ).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 (lunule).
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.1 and §4.5 case 2
           (corrected as in theory §6).

    Examples
    --------
    >>> am, ao = lunule_areas(3.0, 5.0, 2.0, 0.0)  # bore not worn: the whole lens
    >>> bool(np.isclose(am, lens_area(3.0, 5.0, 2.0), rtol=1e-13)), float(ao)
    (True, 0.0)
    """
    rm = np.asarray(mobile_radius, dtype=float)
    ro = np.asarray(obstacle_radius, dtype=float)
    dm = np.asarray(depth_mobile, dtype=float)
    do = np.asarray(depth_obstacle, dtype=float)
    depth = dm + do
    x = lens_half_chord(rm, ro, depth)
    limit = lens_depth_limit(rm, ro)
    x = np.where(depth <= limit * (1.0 + 1e-12), np.minimum(x, rm), np.nan)
    seg_m = segment_area(rm, x)
    seg_o = segment_area(ro, x)
    with np.errstate(invalid="ignore"):
        seg_r = _interface_segment(x, sagitta(rm, x) - dm)
        seg_r = np.where(do == 0.0, seg_o, np.where(dm == 0.0, seg_m, seg_r))
        area_m = np.maximum(seg_m - seg_r, 0.0)
        area_o = np.maximum(seg_r - seg_o, 0.0)
    area_m = np.where(np.isnan(x), np.nan, area_m)
    area_o = np.where(np.isnan(x), np.nan, area_o)
    return _out(area_m), _out(area_o)


def lunule_mobile_depth(mobile_radius, obstacle_radius, depth, share):
    """Mobile's part d_m of a lunule of total depth D holding a share of its area [m].

    Parameters
    ----------
    mobile_radius : float
        Mobile outer radius R_m [m].
    obstacle_radius : float
        Bore radius R_o [m], > R_m.
    depth : float or array_like
        Total depth D = d_m + d_o of the lunule [m].
    share : float or array_like
        Mobile's share A_m/(A_m + A_o) of the lunule's area, in [0, 1].

    Returns
    -------
    numpy.ndarray or float
        d_m [m] (d_o = D − d_m); share 1 gives D, share 0 gives 0.

    Notes
    -----
    Solves A_m(d_m; D) = share · S(D) for d_m in [0, D] (A_m of :func:`lunule_areas`, increasing
    in d_m: a deeper mobile share flattens the common arc, r grows from R_m to R_o) with
    :func:`solve_monotone`. The target is formed from the same function at d_m = D, so that the
    bracket holds it exactly. Where every share is 0 or 1, no solve: D or 0 (NaN beyond the lens
    range, where the chord is not defined).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 (lunule, and the split at the deepest section of
           TUBE_ALESAGE with tilt).

    Examples
    --------
    >>> dm = lunule_mobile_depth(3.0, 5.0, 1.0, 0.5)
    >>> am, ao = lunule_areas(3.0, 5.0, dm, 1.0 - dm)
    >>> bool(np.isclose(am, ao, rtol=1e-11))
    True
    """
    depth = np.asarray(depth, dtype=float)
    share = np.asarray(share, dtype=float)
    depth, share = np.broadcast_arrays(depth, share)
    # The chord depends on D only: computed once, the solver varies the common arc.
    x = lens_half_chord(mobile_radius, obstacle_radius, depth)
    limit = lens_depth_limit(mobile_radius, obstacle_radius)
    x = np.where(depth <= limit * (1.0 + 1e-12), np.minimum(x, mobile_radius), np.nan)
    if ((share >= 1.0) | (share <= 0.0)).all():  # no split: D or 0 within the lens range
        dm = np.where(share >= 1.0, depth, 0.0)
        return _out(np.where(np.isnan(x), np.nan, dm))
    seg_m = segment_area(mobile_radius, x)
    s_m = sagitta(mobile_radius, x)

    mobile_area = _mobile_area(x, s_m, seg_m)

    with np.errstate(invalid="ignore"):
        whole = mobile_area(depth)
        # f(0) is 0 up to rounding: the target is kept inside [f(0), f(D)] so that a tiny
        # share returns d_m = 0 rather than NaN.
        none = mobile_area(np.zeros_like(depth))
        target = np.clip(np.clip(share, 0.0, 1.0) * whole, none, whole)
        # a share of 0 or 1 is answered below: the solver (element-wise) runs on the others,
        # from the bracket's values f(0) and f(D) computed here
        split = ~((share >= 1.0) | (share <= 0.0))
        if depth.ndim == 0 or split.all():
            dm = solve_monotone(mobile_area, target, np.zeros_like(depth), depth,
                                bound_values=(none, whole))
        else:
            dm = np.zeros(depth.shape)
            if split.any():
                dm[split] = solve_monotone(
                    _mobile_area(x[split], s_m[split], seg_m[split]), target[split],
                    np.zeros(int(split.sum())), depth[split],
                    bound_values=(none[split], whole[split]))
    dm = np.where(share >= 1.0, depth, np.where(share <= 0.0, 0.0, dm))
    dm = np.where(np.isnan(whole), np.nan, dm)
    return _out(dm)


def lunule_depths(mobile_radius, obstacle_radius, area_mobile, area_obstacle):
    """Worn depths of mobile and bore in a lunule from their worn section areas [m].

    Parameters
    ----------
    mobile_radius : float
        Mobile outer radius R_m [m].
    obstacle_radius : float
        Bore radius R_o [m], > R_m.
    area_mobile, area_obstacle : float or array_like
        A_m = V_m/l, A_o = V_o/l [m²], ≥ 0.

    Returns
    -------
    depth_mobile, depth_obstacle : numpy.ndarray or float
        d_m, d_o [m]; NaN where A_m + A_o exceeds the lens at :func:`lens_depth_limit`.

    Notes
    -----
    Solve S(D) = A_m + A_o for D on [0, D_max] (S of :func:`lens_area`, increasing; each
    element from the two points of a grid of S around it, :func:`solve_on_grid`), then split
    D with :func:`lunule_mobile_depth` (share A_m/(A_m + A_o)). With A_o = 0, d_m = D.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6 (lunule).

    Examples
    --------
    >>> dm, do = lunule_depths(3.0, 5.0, lens_area(3.0, 5.0, 1.5), 0.0)
    >>> round(float(dm), 12), float(do)
    (1.5, 0.0)
    """
    am = np.asarray(area_mobile, dtype=float)
    ao = np.asarray(area_obstacle, dtype=float)
    am, ao = np.broadcast_arrays(am, ao)
    total = am + ao
    # lens_area bit for bit, and its grid on [0, D_max], kept for the radii: each element
    # starts from the grid points around its area (about 5 evaluations instead of 13 to 37)
    lens, grid = lens_area_grid(mobile_radius, obstacle_radius)
    with np.errstate(invalid="ignore", divide="ignore"):
        depth = solve_on_grid(lambda d: lens(d.ravel()).reshape(d.shape), total, grid)
        share = np.where(total > 0.0, am / total, 1.0)
    dm = lunule_mobile_depth(mobile_radius, obstacle_radius, depth, share)
    dm = np.asarray(dm, dtype=float)
    do = np.where(np.isnan(depth), np.nan, np.maximum(depth - dm, 0.0))
    return _out(dm), _out(do)
