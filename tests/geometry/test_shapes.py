"""Shared shape helpers (fretwear.geometry._shapes) against independent computations.

Sources: the independent oracle of tests/geometry/oracle.py (profile quadrature, polygons),
elementary identities of the circle (s·(2ρ − s) = x², half disk = πρ²/2), the theory §6 forms of
x and S, and analytic pyramid volumes for the frustum rule.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from oracle import (
    circle_polygon,
    flat_cut_area,
    lens_oracle,
    lunule_oracle,
    polygon_outside_area,
    wedge_volume,
)
from scipy.optimize import brentq

from fretwear.geometry._lunule import lunule_areas, lunule_depths, lunule_mobile_depth
from fretwear.geometry._shapes import (
    frustum_volume,
    lens_area,
    lens_depth_limit,
    lens_half_chord,
    sagitta,
    segment_area,
    solve_monotone,
)

RM, RO = 4.85e-3, 5.25e-3  # control-rod rodlet in its guide bore (theory §6 GRAPPE dimensions)


# ----------------------------------------------------------------------------- segment, sagitta
@pytest.mark.parametrize("depth", [1e-7, 1e-5, 1e-3, 5e-3, 9.9e-3])
def test_segment_area_matches_flat_cut_quadrature(depth):
    """seg(ρ, x) equals the area of the disk beyond the chord, by quadrature (oracle)."""
    rho = 0.01
    x = math.sqrt(depth * (2 * rho - depth))
    assert segment_area(rho, x) == pytest.approx(flat_cut_area(rho, depth), rel=1e-11)


def test_segment_area_small_chord_asymptotics_and_series_switch():
    """seg ≈ 2x³/(3ρ)(1 + 3x²/(10ρ²)) for x ≪ ρ (Taylor of ρ²(φ − ½ sin 2φ)); the series
    branch (u = 2φ < 0.5) and the direct branch agree at the switch."""
    rho = 2.0
    x = np.array([1e-8, 1e-6, 1e-4])
    expected = 2 * x**3 / (3 * rho) * (1 + 3 * x**2 / (10 * rho**2))
    assert np.allclose(segment_area(rho, x), expected, rtol=1e-12, atol=0)
    phi_switch = 0.25  # u = 0.5
    xs = rho * math.sin(phi_switch) * np.array([1 - 1e-12, 1 + 1e-12])
    direct = rho**2 * np.arcsin(xs / rho) - xs * np.sqrt(rho**2 - xs**2)
    assert np.allclose(segment_area(rho, xs), direct, rtol=1e-13, atol=0)
    assert segment_area(rho, rho) == pytest.approx(math.pi * rho**2 / 2, rel=1e-15)
    assert np.isnan(segment_area(rho, 1.1 * rho))


def test_sagitta_identity_and_precision():
    """s·(2ρ − s) = x² (intersecting chords theorem), also for x ≪ ρ."""
    rho = 0.01
    x = np.geomspace(1e-9, rho, 25)
    s = sagitta(rho, x)
    assert np.allclose(s * (2 * rho - s), x**2, rtol=1e-14, atol=0)
    assert sagitta(rho, rho) == pytest.approx(rho, rel=1e-15)


# ----------------------------------------------------------------------------- lens
@pytest.mark.parametrize("depth", [1e-7, 1e-5, 1e-4, 1e-3, 1.6e-3])
def test_lens_matches_quadrature_oracle(depth):
    """S(D) and x against the oracle: crossing found numerically, area by quadrature."""
    area, half_chord = lens_oracle(RM, RO, depth)
    assert lens_half_chord(RM, RO, depth) == pytest.approx(half_chord, rel=1e-11)
    assert lens_area(RM, RO, depth) == pytest.approx(area, rel=1e-10)


@pytest.mark.parametrize("depth", [2e-4, 1e-3])
def test_lens_matches_polygon_clipping(depth):
    """S(D) against a polygon oracle: 360-gon of the mobile minus its part inside the bore."""
    mobile = circle_polygon(0.0, RO - RM + depth, RM, 360)
    bore = circle_polygon(0.0, 0.0, RO, 360)
    assert lens_area(RM, RO, depth) == pytest.approx(polygon_outside_area(mobile, bore),
                                                     rel=1e-5)


def test_lens_equals_spec_closed_forms():
    """The factorised x and the segment difference equal theory §6's written forms
    x² = R_m² − (R_o² − R_m² − c²)²/(4c²), S = R_m² asin(x/R_m) − R_o² asin(x/R_o) + x·c
    (evaluated where they do not suffer from cancellation)."""
    rm, ro = 0.0111, 0.0125
    d = np.linspace(2e-4, 0.98 * float(lens_depth_limit(rm, ro)), 9)  # asin is singular at x = R_m
    c = ro - rm + d
    x_spec = np.sqrt(rm**2 - (ro**2 - rm**2 - c**2) ** 2 / (4 * c**2))
    s_spec = rm**2 * np.arcsin(x_spec / rm) - ro**2 * np.arcsin(x_spec / ro) + x_spec * c
    assert np.allclose(lens_half_chord(rm, ro, d), x_spec, rtol=1e-10, atol=0)
    assert np.allclose(lens_area(rm, ro, d), s_spec, rtol=1e-9, atol=0)


def test_lens_limit_is_chord_through_mobile_centre():
    """At D_max the chord passes through the mobile's centre: x = R_m; beyond, NaN."""
    limit = lens_depth_limit(RM, RO)
    assert limit == pytest.approx(math.sqrt(RO**2 - RM**2) - (RO - RM), rel=1e-15)
    assert lens_half_chord(RM, RO, limit) == pytest.approx(RM, rel=1e-12)
    assert np.isnan(lens_area(RM, RO, 1.01 * limit))
    assert lens_area(RM, RO, 0.0) == 0.0


# ----------------------------------------------------------------------------- frustum rule
def test_frustum_rule_exact_for_pyramid_sections():
    """For A(d) = k·d² the frustum rule is exact: it equals the numerical wedge integral
    ∫_0^l A(d − θz) dz (oracle) in both branches, and is continuous at d = lθ."""
    def area(d):
        return 3.0 * np.maximum(d, 0.0) ** 2
    width, tilt = 0.02, math.radians(2.0)
    reach = width * tilt
    for d in (0.2 * reach, reach, 3.0 * reach):
        expected = wedge_volume(lambda u: float(area(u)), d, width, tilt)
        assert frustum_volume(area, d, width, tilt) == pytest.approx(expected, rel=1e-12)
    below = frustum_volume(area, reach * (1 - 1e-12), width, tilt)
    above = frustum_volume(area, reach * (1 + 1e-12), width, tilt)
    assert below == pytest.approx(above, rel=1e-10)
    assert frustum_volume(area, 1e-3, width, 0.0) == pytest.approx(width * 3e-6, rel=1e-15)


def test_frustum_rule_gives_five_sixths_for_three_halves_sections():
    """For A ∝ d^{3/2} (a lens at small depth, a flat trace) the rule gives (1/3)/(2/5) = 5/6
    of the exact wedge integral (1/θ)∫A: the known bias of the frustum rule of theory §6."""
    def area(d):
        return np.maximum(d, 0.0) ** 1.5
    width, tilt, d = 0.02, math.radians(2.0), 1e-4
    exact = wedge_volume(lambda u: float(area(u)), d, width, tilt)
    assert frustum_volume(area, d, width, tilt) / exact == pytest.approx(5 / 6, rel=1e-12)


# ----------------------------------------------------------------------------- solver
def test_solve_monotone_matches_brentq_elementwise():
    """Roots of x³ + x·p = target (p element-wise) against scipy's brentq one by one."""
    p = np.array([0.0, 1.0, 10.0, 1e-6])
    target = np.array([8.0, 2.0, 1e-3, 27.0])
    roots = solve_monotone(lambda x: x**3 + x * p, target, 0.0, 10.0)
    for r, pi, ti in zip(roots, p, target, strict=True):
        expected = brentq(lambda x, pi=pi, ti=ti: x**3 + x * pi - ti, 0.0, 10.0, xtol=1e-300,
                          rtol=1e-15)
        assert r == pytest.approx(expected, rel=2e-12)


def test_solve_monotone_outside_bracket_nan_and_endpoints():
    """NaN where the target is outside [f(lower), f(upper)] or NaN; exact endpoints kept."""
    roots = solve_monotone(np.exp, np.array([0.5, 1.0, math.e, 3.0, np.nan]), 0.0, 1.0)
    assert np.isnan(roots[0]) and np.isnan(roots[3]) and np.isnan(roots[4])
    assert roots[1] == 0.0 and roots[2] == 1.0


def test_solve_monotone_hard_functions():
    """Steep and flat functions (x^9 near 0, 1 − e^{−50x}): still converge to rtol 1e-12."""
    root = solve_monotone(lambda x: x**9, 1e-27, 0.0, 1.0)
    assert root == pytest.approx(1e-3, rel=1e-11)
    root = solve_monotone(lambda x: 1.0 - np.exp(-50 * x), 1.0 - math.exp(-50 * 0.1), 0.0, 1.0)
    assert root == pytest.approx(0.1, rel=1e-11)
    tiny = solve_monotone(lambda x: x, 1e-30, 0.0, 1.0)
    assert tiny == pytest.approx(1e-30, rel=1e-11)


# ----------------------------------------------------------------------------- lunule
@pytest.mark.parametrize(("dm", "do"), [(1e-4, 2e-4), (5e-4, 1e-5), (1e-6, 3e-6), (8e-4, 8e-4)])
def test_lunule_areas_match_oracle(dm, do):
    """A_m, A_o against the oracle's interface circle through the crossings and the apex."""
    am, ao = lunule_areas(RM, RO, dm, do)
    om, oo = lunule_oracle(RM, RO, dm, do)
    assert am == pytest.approx(om, rel=1e-9)
    assert ao == pytest.approx(oo, rel=1e-9)


def test_lunule_round_trip_and_limits():
    """Depths -> areas -> depths at 1e-10 of D; share 1 is the plain lens; share 0 gives 0."""
    limit = float(lens_depth_limit(RM, RO))
    depth = np.geomspace(1e-8, 0.999 * limit, 13)
    for share in (0.0, 0.2, 0.5, 0.97, 1.0):
        dm, do = share * depth, (1 - share) * depth
        am, ao = lunule_areas(RM, RO, dm, do)
        dm2, do2 = lunule_depths(RM, RO, am, ao)
        assert np.allclose(dm2, dm, rtol=0, atol=1e-10 * depth.max())
        assert np.all(np.abs(dm2 - dm) <= 1e-10 * depth)
        assert np.all(np.abs(do2 - do) <= 1e-10 * depth)
    am, ao = lunule_areas(RM, RO, depth, 0.0)
    assert np.allclose(am, lens_area(RM, RO, depth), rtol=1e-14, atol=0) and not ao.any()
    assert lunule_mobile_depth(RM, RO, 1e-4, 0.0) == 0.0
    assert lunule_mobile_depth(RM, RO, 1e-4, 1.0) == 1e-4
    beyond = lunule_depths(RM, RO, 1.01 * lens_area(RM, RO, limit), 0.0)
    assert np.isnan(beyond[0]) and np.isnan(beyond[1])


def test_lunule_split_of_shares_zero_and_one_alone_or_beside_a_split():
    """Shares of 0 and 1 only (no solve: D or 0) give what they give beside a share to split
    (the solved path), NaN beyond the lens range (1.01 D_max, NaN) included; and the whole lens
    is the mobile's at share 1 (lunule_areas, an independent relation)."""
    limit = float(lens_depth_limit(RM, RO))
    depth = np.array([0.0, 1e-9, 1e-6, 0.5 * limit, limit, 1.01 * limit, np.nan, 2e-5])
    share = np.array([1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 0.0])
    alone = lunule_mobile_depth(RM, RO, depth, share)
    beside = lunule_mobile_depth(RM, RO, np.append(depth, 1e-5), np.append(share, 0.5))
    assert np.array_equal(alone, beside[:-1], equal_nan=True)
    assert np.isnan(alone[5:7]).all() and alone[[0, 1, 4, 7]].tolist() == [0.0] * 4
    assert alone[[2, 3]].tolist() == depth[[2, 3]].tolist()
    am, ao = lunule_areas(RM, RO, alone[:5], depth[:5] - alone[:5])
    assert np.allclose(am + ao, lens_area(RM, RO, depth[:5]), rtol=1e-13, atol=0)
    assert not am[share[:5] == 0].any() and not ao[share[:5] == 1].any()


def test_stacked_lens_area_is_lens_area_bit_for_bit():
    """The solvers' lens area (both segments in one call) against the public lens_area."""
    from fretwear.geometry._shapes import lens_area, lens_depth_limit, stacked_lens_area
    rng = np.random.default_rng(5)
    for rm, ro in ((9.525e-3, 9.75e-3), (4.84e-3, 5.5e-3), (3.0, 5.0)):
        limit = float(lens_depth_limit(rm, ro))
        area = stacked_lens_area(rm, ro)
        for d in (rng.random(11) * limit, np.geomspace(1e-14, limit, 300),
                  np.array([0.0, limit, limit * (1 + 1e-13), 1.5 * limit, -1.0, np.nan])):
            with np.errstate(invalid="ignore"):
                assert np.array_equal(area(d), lens_area(rm, ro, d), equal_nan=True)


def test_solver_given_its_bound_values_is_the_solver():
    """solve_monotone(..., bound_values=(f(lower), f(upper))) skips two evaluations and gives
    the same bits; the values kept per radii are lens_area's at 0 and D_max."""
    from fretwear.geometry._shapes import lens_area, lens_area_on_range, solve_monotone
    rm, ro = 9.525e-3, 9.75e-3
    area, at_zero, at_limit, limit = lens_area_on_range(rm, ro)
    assert (at_zero, at_limit) == (float(lens_area(rm, ro, 0.0)), float(lens_area(rm, ro, limit)))
    assert lens_area_on_range(rm, ro)[0] is area  # made once
    calls = []

    def f(d):
        calls.append(d.size)
        return lens_area(rm, ro, d)

    targets = np.array([1e-12, 1e-9, 3e-8, at_limit, 2 * at_limit, np.nan])
    plain = solve_monotone(f, targets, 0.0, limit)
    n_plain = len(calls)
    given = solve_monotone(f, targets, 0.0, limit, bound_values=(at_zero, at_limit))
    assert np.array_equal(plain, given, equal_nan=True)
    assert len(calls) - n_plain == n_plain - 2
