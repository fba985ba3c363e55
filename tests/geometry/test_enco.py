"""Tests of TUBE_3_ENCO / TUBE_4_ENCO (fretwear.geometry.enco).

Sources of the expected values:

- the worn-shape oracle: the worn section at an isthmus edge computed from the bodies' profiles
  (tube arc, bore arc, straight lobe flank through the edge at α_i from the radius) by adaptive
  quadrature with the crossing points found by brentq, using the primitives of
  ``tests/geometry/oracle.py`` and none of the closed forms of fretwear.geometry; tilted traces
  integrated numerically along the width (``oracle.wedge_volume``);
- the derivation in docs/geometry.md (TUBE_3_ENCO and TUBE_4_ENCO): the wedge term tan(α_i)·D²
  is the flat-front triangle, larger than the exact wedge by (D·tan α_i)³/(6R_m) at leading
  order; the frustum rule is exact for A ∝ d² and gives 5/6 of the wedge integral for
  A ∝ d^{3/2} (small-depth lens);
- analytic small-depth lens: S(D) ≈ (4/3)·√(2R_e)·D^{3/2}, R_e = R_m·R_o/(R_o − R_m) (the gap
  between two circles of curvatures 1/R_m − 1/R_o is t²/(2R_e));
- Code_Aster R7.20.01 §4.6-§4.7 for κ = 1.41 / 1.88 and the relations; theory §6 for the
  two-edge quatrefoil and the range limit √(R_o² − R_m²) − (R_o − R_m).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import QUAD as _QUAD
from oracle import arc, wedge_volume
from scipy.integrate import quad
from scipy.optimize import brentq

from fretwear.errors import InputError, KeywordError, RangeWarning, UnusedKeywordWarning
from fretwear.geometry import CONTACT_TYPES, contact_geometry
from fretwear.geometry.enco import (
    ENCO_TYPES,
    Tube3Enco,
    Tube4Enco,
    enco_depth,
    enco_volume,
    isthmus_section_area,
)

RM, RO, L = 9.525e-3, 9.75e-3, 30e-3   # 3/4" tube in a 19.5 mm broached hole, 30 mm plate
LIMIT = math.sqrt(RO**2 - RM**2) - (RO - RM)
# The profile differences cancel to ~1e-12 relative at the smallest depths: ask quad for 1e-11.
QUAD = dict(_QUAD, epsrel=1e-11)


def geometry(cls=Tube3Enco, alpha=30.0, tilt=0.0, rm=RM, ro=RO, width=L):
    return cls(mobile_radius=rm, obstacle_radius=ro, obstacle_width=width, isthmus_angle=alpha,
               tilt_angle=tilt)


# --------------------------------------------------------------------------- oracle
def edge_section_oracle(depth: float, alpha_deg: float, rm: float = RM, ro: float = RO) -> float:
    """Exact worn section [m²] of the tube at one isthmus edge, from the profiles.

    Bore centred at the origin, edge at (0, R_o); the tube, centre (0, R_o − R_m + D), protrudes
    by D. The plate's material lies outside the bore circle on the land side (t < 0) and, over
    the lobe (t > 0), between the radius t = 0 and the flank y = R_o + t·cot α_i. Valid for
    α_i ≤ 60° (the flank then stays below the bore arc on the lens's land side).
    """
    if depth <= 0.0:
        return 0.0
    tube, bore = arc(ro - rm + depth, rm), arc(0.0, ro)
    half_chord = brentq(lambda t: tube(t) - bore(t), 0.0, rm, xtol=1e-300, rtol=1e-15)
    land = quad(lambda t: tube(t) - bore(t), 0.0, half_chord, **QUAD)[0]   # by symmetry
    if alpha_deg == 0.0:
        return land
    cot = 1.0 / math.tan(math.radians(alpha_deg))
    flank = lambda t: ro + t * cot  # noqa: E731
    tip = brentq(lambda t: tube(t) - flank(t), 0.0, depth / cot, xtol=1e-300, rtol=1e-15)
    lobe = quad(lambda t: tube(t) - flank(t), 0.0, tip, **QUAD)[0]
    return land + lobe


def flat_front_excess(depth, alpha_deg, rm=RM):
    """Leading-order excess of the triangle term over the exact wedge: (D tan α)³/(6 R_m)."""
    return (depth * math.tan(math.radians(alpha_deg))) ** 3 / (6.0 * rm)


# --------------------------------------------------------------------------- sections
@pytest.mark.parametrize("depth", [1e-7, 1e-5, 1e-4, 1e-3, 0.999 * LIMIT])
def test_half_lens_matches_oracle(depth):
    """α_i = 0: the worn section at the edge is exactly half the lens, S/2 (oracle)."""
    formula = 0.5 * isthmus_section_area(depth, RM, RO, 0.0)
    assert formula == pytest.approx(edge_section_oracle(depth, 0.0), rel=1e-10)


@pytest.mark.parametrize("alpha", [20.0, 35.0, 45.0])
@pytest.mark.parametrize("depth", [1e-6, 1e-5, 3e-5])
def test_wedge_term_is_flat_front_triangle(alpha, depth):
    """S'/2 exceeds the exact section by (D tan α)³/(6R_m) at leading order (derivation)."""
    formula = 0.5 * isthmus_section_area(depth, RM, RO, alpha)
    excess = formula - edge_section_oracle(depth, alpha)
    # next order is 3/4·D·tan²α/R_m relative (≤ 0.3 % here); quadrature noise ≤ 1e-4 relative
    assert excess / flat_front_excess(depth, alpha) == pytest.approx(1.0, abs=5e-3)


def test_small_depth_asymptotics():
    """Small D: V = (l/2)·S(D) ≈ (l/2)(4/3)√(2R_e)·D^{3/2} with relative error O(D/(R_o−R_m))."""
    r_e = RM * RO / (RO - RM)
    depth = np.array([1e-9, 1e-8])
    volume = enco_volume(depth, RM, RO, L, 0.0)
    expected = 0.5 * L * 4.0 / 3.0 * math.sqrt(2.0 * r_e) * depth**1.5
    np.testing.assert_allclose(volume, expected, rtol=20 * depth.max() / (RO - RM))


# --------------------------------------------------------------------------- relations
def test_no_tilt_volume_is_half_width_times_section():
    """R7.20.01 §4.6 case 1: V_m = (l/2)·[S(d) + d² tan α]; the quatrefoil carries twice (two
    edges)."""
    depth = np.array([0.0, 2e-5, 4e-4])
    s_prime = isthmus_section_area(depth, RM, RO, 30.0)
    np.testing.assert_allclose(geometry().volume_from_depth(depth)[0], 0.5 * L * s_prime,
                               rtol=1e-15)
    np.testing.assert_allclose(geometry(Tube4Enco).volume_from_depth(depth)[0], L * s_prime,
                               rtol=1e-15)


@pytest.mark.parametrize("depth", [2e-5, 3e-4, 1.2e-3])
def test_tilt_frustum_rule_on_oracle_sections(depth):
    """Tilt: volume_from_depth equals the frustum rule on the oracle's sections A1 = A(D),
    A2 = A(D − lθ), to the flat-front excess; α_i = 0 makes the comparison exact."""
    tilt = 0.5
    reach = L * math.radians(tilt)
    for alpha in (0.0, 30.0):
        a1 = edge_section_oracle(depth, alpha)
        if depth < reach:
            expected = depth / math.radians(tilt) * a1 / 3.0
            bound = depth / math.radians(tilt) * flat_front_excess(depth, alpha) / 3.0
        else:
            a2 = edge_section_oracle(depth - reach, alpha)
            expected = L / 3.0 * (a1 + math.sqrt(a1 * a2) + a2)
            bound = L * flat_front_excess(depth, alpha)  # each section's excess ≤ the deepest
        got = float(geometry(alpha=alpha, tilt=tilt).volume_from_depth(depth)[0])
        assert abs(got - expected) <= 1.05 * bound + 1e-10 * expected


@pytest.mark.parametrize("depth", [3e-6, 2e-4, 1.2e-3])
def test_frustum_rule_against_exact_wedge_integral(depth):
    """The frustum rule approximates the exact tilted trace ∫A(D − θz)dz (oracle). For a section
    A ∝ d^p it gives (p + 1)/3 of the integral (D < lθ); the lens grows with p from 3/2
    (D ≪ R_o − R_m) down to 1 (D ≫ R_o − R_m, the chord saturates), the triangle with p = 2, so
    the ratio lies in [2/3, 1] and tends to 5/6 at small depth (derivation)."""
    tilt = math.radians(0.5)
    exact = wedge_volume(lambda d: edge_section_oracle(d, 0.0), depth, L, tilt)
    rule = float(geometry(alpha=0.0, tilt=0.5).volume_from_depth(depth)[0])
    assert 2.0 / 3.0 <= rule / exact <= 1.0 + 1e-9
    if depth < 1e-5:  # D/(R_o − R_m) ≈ 0.013: A ∝ d^{3/2} to ~1 %, ratio 5/6
        assert rule / exact == pytest.approx(5.0 / 6.0, rel=1e-2)


@pytest.mark.parametrize("cls", [Tube3Enco, Tube4Enco])
@pytest.mark.parametrize("alpha", [0.0, 30.0])
def test_continuous_at_width_times_tilt(cls, alpha):
    """Both branches of the frustum rule agree at D = lθ (S'2 = 0 there)."""
    g = geometry(cls, alpha=alpha, tilt=0.5)
    reach = L * math.radians(0.5)
    below, at, above = g.volume_from_depth(reach * np.array([1 - 1e-12, 1.0, 1 + 1e-12]))[0]
    assert below == pytest.approx(at, rel=1e-9) and above == pytest.approx(at, rel=1e-9)
    assert below <= at <= above
    # the inverse is continuous too: depths around the switch come back
    depths = reach * np.array([0.999, 1.0, 1.001])
    np.testing.assert_allclose(g.depth_from_volume(g.volume_from_depth(depths)[0])[0], depths,
                               rtol=1e-12)


# --------------------------------------------------------------------------- round trips
@pytest.mark.parametrize("cls", [Tube3Enco, Tube4Enco])
@pytest.mark.parametrize("tilt", [0.0, 0.5, 3.0])
def test_round_trip_volume_depth_volume(cls, tilt):
    g = geometry(cls, tilt=tilt)
    vm = np.geomspace(1e-13, 0.5 * g.max_volume, 9)
    for ratio in (0.0, 0.2, 1.0):
        vo = ratio * vm
        dm, do = g.depth_from_volume(vm, vo)
        assert np.isfinite(dm).all() and np.isfinite(do).all()
        back_m, back_o = g.volume_from_depth(dm, do)
        np.testing.assert_allclose(back_m, vm, rtol=1e-11)
        np.testing.assert_allclose(back_o, vo, rtol=1e-13)


@pytest.mark.parametrize("cls", [Tube3Enco, Tube4Enco])
@pytest.mark.parametrize("tilt", [0.0, 1.0])
def test_round_trip_depth_volume_depth(cls, tilt):
    g = geometry(cls, tilt=tilt)
    dm = np.array([1e-8, 1e-6, 5e-5, 3e-4, 1e-3])
    do = np.array([0.0, 1e-12, 1e-9, 1e-7, 2e-6])  # small enough to keep V_m > 0
    vm, vo = g.volume_from_depth(dm, do)
    assert (vm > 0).all()
    back_m, back_o = g.depth_from_volume(vm, vo)
    np.testing.assert_allclose(back_m, dm, rtol=1e-11)
    np.testing.assert_allclose(back_o, do, rtol=1e-13)


def test_solver_tolerance():
    """enco_depth solves V(D) = V to ~1e-13 relative in D (bracketed Chandrupatla)."""
    volume = np.geomspace(1e-14, 1e-7, 15)
    depth = enco_depth(volume, RM, RO, L, 30.0, tilt_angle=0.5)
    np.testing.assert_allclose(enco_volume(depth, RM, RO, L, 30.0, tilt_angle=0.5), volume,
                               rtol=5e-12)


# --------------------------------------------------------------------------- obstacle wear
def test_obstacle_relation_manual_kappa():
    """V_o = κ·π·l·R_o·d_o, κ = 1.41 (trefoil), 1.88 (quatrefoil), i.e. 0.47 per isthmus."""
    assert ENCO_TYPES["TUBE_3_ENCO"]["kappa"] == 1.41 == pytest.approx(3 * 0.47)
    assert ENCO_TYPES["TUBE_4_ENCO"]["kappa"] == 1.88 == pytest.approx(4 * 0.47)
    for cls, kappa in ((Tube3Enco, 1.41), (Tube4Enco, 1.88)):
        g = geometry(cls)
        vo = np.array([1e-12, 1e-10, 1e-9])
        _, do = g.depth_from_volume(2 * vo, vo)
        np.testing.assert_allclose(do, vo / (kappa * math.pi * L * RO), rtol=1e-15)


@pytest.mark.parametrize("cls", [Tube3Enco, Tube4Enco])
def test_total_depth_from_total_volume(cls):
    """D = d_m + d_o solves the relation with V = V_m + V_o (R7.20.01 cases 3-4)."""
    g = geometry(cls, tilt=0.5)
    dm, do = g.depth_from_volume(3e-10, 1e-10)
    d_alone, _ = g.depth_from_volume(4e-10)
    assert dm + do == pytest.approx(d_alone, rel=1e-12)


@pytest.mark.parametrize("cls", [Tube3Enco, Tube4Enco])
def test_obstacle_volume_to_zero(cls):
    g = geometry(cls, tilt=0.5)
    vm = 1e-9
    d_alone, do_alone = g.depth_from_volume(vm)
    assert do_alone == 0.0
    for eps in (1e-6, 1e-9):
        # D grows by ≤ eps·D/(p + 1) and d_o = eps·V_m/(κπlR_o) ≈ 0.05·eps·D here
        dm, do = g.depth_from_volume(vm, eps * vm)
        assert dm == pytest.approx(d_alone, rel=eps) and 0.0 < do < eps * d_alone


def test_quatrefoil_edges_carry_half():
    """TUBE_4_ENCO: each of the two edges carries half the volumes: the total depth of (2V_m,
    2V_o) on the quatrefoil equals that of (V_m, V_o) on one trefoil-like edge."""
    for tilt in (0.0, 0.5):
        d3 = sum(geometry(Tube3Enco, tilt=tilt).depth_from_volume(3e-10, 1e-10))
        d4 = sum(geometry(Tube4Enco, tilt=tilt).depth_from_volume(6e-10, 2e-10))
        assert d4 == pytest.approx(d3, rel=1e-12)


def test_inconsistent_depths_give_nan():
    """d_m = 0 with d_o > 0: the lens of depth d_o holds less than V_o = κπlR_o d_o (S ≤ 2R_m·D
    < κπR_o·D), so V_m would be negative: NaN and a RangeWarning."""
    g = geometry()
    do = 1e-4
    assert enco_volume(do, RM, RO, L, 30.0) < 1.41 * math.pi * L * RO * do
    with pytest.warns(RangeWarning, match="TUBE_3_ENCO"):
        vm, vo = g.volume_from_depth(0.0, do)
    assert np.isnan(vm) and np.isnan(vo)


def test_obstacle_depth_beyond_total_depth_gives_nan():
    """A steep flank (α_i = 89°): tan α·D²/2 > κπR_o·D for D > 2κπR_o/tan α ≈ 1.5 mm, so a
    V_o alone can give d_o > D (d_m < 0): NaN and a RangeWarning, not a negative depth."""
    g = geometry(alpha=89.0)
    d = 1.8e-3
    vo = 1.41 * math.pi * L * RO * d
    assert enco_volume(d, RM, RO, L, 89.0) > vo  # so D(vo) < d = d_o
    with pytest.warns(RangeWarning, match="d_m >= 0"):
        dm, do = g.depth_from_volume([0.0, 0.0], [1e-10, vo])
    assert np.isfinite(dm[0]) and np.isnan(dm[1]) and np.isnan(do[1])


# --------------------------------------------------------------------------- range
@pytest.mark.parametrize("cls", [Tube3Enco, Tube4Enco])
def test_range_limit(cls):
    """Limit: the lens chord reaches the tube's axis, D_max = √(R_o² − R_m²) − (R_o − R_m);
    there the oracle's half chord is R_m."""
    g = geometry(cls)
    assert g.max_depth == pytest.approx(LIMIT, rel=1e-14)
    tube, bore = arc(RO - RM + LIMIT, RM), arc(0.0, RO)
    assert tube(RM) - bore(RM) == pytest.approx(0.0, abs=1e-15)
    with pytest.warns(RangeWarning, match=f"{cls.contact_type}.*chord of the lens"):
        dm, _ = g.depth_from_volume([0.5 * g.max_volume, 1.01 * g.max_volume])
    assert np.isfinite(dm[0]) and np.isnan(dm[1])
    with pytest.warns(RangeWarning, match=cls.contact_type):
        vm, _ = g.volume_from_depth([0.5 * LIMIT, 1.01 * LIMIT])
    assert np.isfinite(vm[0]) and np.isnan(vm[1])


# --------------------------------------------------------------------------- API
def test_registry_and_keywords():
    assert CONTACT_TYPES["TUBE_3_ENCO"] is Tube3Enco and CONTACT_TYPES["TUBE_4_ENCO"] is Tube4Enco
    g = contact_geometry("TUBE_3_ENCO", RAYON_MOBILE=RM, RAYON_OBST=RO, LARGEUR_OBST=L,
                         ANGL_ISTHME=30.0, ANGL_INCLI=0.5)
    assert g == geometry(tilt=0.5)
    with pytest.raises(KeywordError, match="ANGL_ISTHME"):
        contact_geometry("TUBE_4_ENCO", RAYON_MOBILE=RM, RAYON_OBST=RO, LARGEUR_OBST=L)
    with pytest.raises(KeywordError, match="RAYON_OBST"):
        contact_geometry("TUBE_3_ENCO", RAYON_MOBILE=RM, LARGEUR_OBST=L, ANGL_ISTHME=30.0)
    with pytest.warns(UnusedKeywordWarning, match="ANGL_IMPACT"):
        contact_geometry("TUBE_3_ENCO", RAYON_MOBILE=RM, RAYON_OBST=RO, LARGEUR_OBST=L,
                         ANGL_ISTHME=30.0, ANGL_IMPACT=10.0)
    with pytest.raises(InputError, match="RAYON_OBST"):
        geometry(ro=RM)


def test_vectorised_shape_and_inputs_untouched():
    g = geometry(Tube4Enco, tilt=0.5)
    vm = np.array([[1e-10, 2e-10], [3e-10, 0.0]])
    vo = np.array([1e-11, 0.0])
    keep_m, keep_o = vm.copy(), vo.copy()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        dm, do = g.depth_from_volume(vm, vo)
    assert dm.shape == do.shape == (2, 2)
    np.testing.assert_array_equal(vm, keep_m)
    np.testing.assert_array_equal(vo, keep_o)
    assert dm[1, 1] == 0.0 and do[1, 1] == 0.0
    for i in range(2):
        for j in range(2):
            one = g.depth_from_volume(vm[i, j], vo[j])
            assert (dm[i, j], do[i, j]) == pytest.approx(one, rel=1e-14)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(rm=st.floats(2e-3, 15e-3), gap=st.floats(0.002, 0.3), width=st.floats(5e-3, 60e-3),
       alpha=st.floats(0.0, 60.0), tilt=st.floats(0.0, 5.0), fraction=st.floats(1e-6, 0.99),
       share=st.floats(0.0, 0.5), quatrefoil=st.booleans())
def test_round_trip_random_dimensions(rm, gap, width, alpha, tilt, fraction, share, quatrefoil):
    """Property: for any dimensions, volumes within the range come back through the depths."""
    g = geometry(Tube4Enco if quatrefoil else Tube3Enco, alpha=alpha, tilt=tilt, rm=rm,
                 ro=rm * (1.0 + gap), width=width)
    total = fraction * g.max_volume
    vm, vo = (1.0 - share) * total, share * total
    dm, do = g.depth_from_volume(vm, vo)
    assert 0.0 <= dm + do <= g.max_depth * (1 + 1e-12)
    back_m, back_o = g.volume_from_depth(dm, do)
    assert back_m == pytest.approx(vm, rel=1e-10) and back_o == pytest.approx(vo, rel=1e-12)


@pytest.mark.parametrize("dims", [
    (9.525e-3, 9.725e-3, 0.03, 20.0, 0.05, 1),   # the example: tilted trefoil
    (9.525e-3, 9.75e-3, 0.03, 30.0, 0.0, 2),     # quatrefoil, no tilt
    (9.525e-3, 9.75e-3, 0.03, 45.0, 1.0, 2),     # tilted: wedge and frustum branches
    (0.01, 0.0125, 0.02, 10.0, 3.0, 1),
])
def test_stacked_solver_function_is_enco_volume_bit_for_bit(dims):
    """The solver's function (sections and segments stacked in one computation) against the
    public enco_volume, element by element: the same bits, NaN and the scalar case included."""
    from fretwear.geometry.enco import _stacked_enco_volume
    volume = _stacked_enco_volume(*dims)
    rng = np.random.default_rng(7)
    limit = math.sqrt(dims[1] ** 2 - dims[0] ** 2) - (dims[1] - dims[0])
    cases = [rng.random(9) * limit, np.geomspace(1e-13, limit, 400),
             np.array([0.0, 1e-12, limit, limit * (1 + 1e-13), 2 * limit, np.nan]),
             np.array([[1e-5, 2e-5], [3e-4, 4e-3]]), np.array(2e-4)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for depth in cases:
            expected = enco_volume(depth, *dims)
            got = volume(depth)
            assert type(got) is type(expected) and np.shape(got) == np.shape(expected)
            assert np.array_equal(got, expected, equal_nan=True)
