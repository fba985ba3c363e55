"""TUBE_BAV (tube against an anti-vibration bar), theory §6 and Code_Aster R7.20.01 §4.4.

Sources: R7.20.01's closed forms (cases 1-2) typed in independently here; the exact circular
segment cut by the bar (oracle quadrature) and its numerical integration along the width for
the tilted bar; the parabolic approximation's known error: exact/parabolic section
= 1 − (3/20)·D/R + O(D²/R²) (Taylor of R²(α − sin α cos α) with D = R(1 − cos α)), hence for a
tilted wedge whose depths run over [E, D] (E = max(D − lθ, 0)) the volume ratio is
1 − (3/(20R))·(5/7)·(D^{7/2} − E^{7/2})/(D^{5/2} − E^{5/2}) + O(D²/R²).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from oracle import flat_cut_area, wedge_volume

from fretwear.errors import RangeWarning
from fretwear.geometry import contact_geometry
from fretwear.geometry.tube_bav import TubeBav, flat_trace_depth

R, L = 9.525e-3, 12.7e-3  # 3/4" SG tube, 1/2" anti-vibration bar
TILT_DEG = 1.0
THETA = math.radians(TILT_DEG)
REACH = L * THETA


def manual_depth_no_tilt(volume):
    """R7.20.01 §4.4 case 1: d = (1/(2R))^(1/3)·(3V/(4l))^(2/3)."""
    return (1 / (2 * R)) ** (1 / 3) * (3 * volume / (4 * L)) ** (2 / 3)


def manual_depth_tilt_short(volume):
    """R7.20.01 §4.4 case 2, d < lθ: d = (1/(2R))^(1/5)·(15θV/8)^(2/5)."""
    return (1 / (2 * R)) ** (1 / 5) * (15 * THETA * volume / 8) ** (2 / 5)


def manual_volume_tilt_long(depth):
    """R7.20.01 §4.4 case 2, d ≥ lθ: V = 8√(2R)/(15θ)·[d^(5/2) − (d − θl)^(5/2)]."""
    return 8 * math.sqrt(2 * R) / (15 * THETA) * (depth**2.5 - (depth - THETA * L) ** 2.5)


@pytest.fixture
def straight():
    return TubeBav(mobile_radius=R, obstacle_width=L)


@pytest.fixture
def tilted():
    return TubeBav(mobile_radius=R, obstacle_width=L, tilt_angle=TILT_DEG)


def test_closed_forms_match_the_manual(straight, tilted):
    volumes = np.geomspace(1e-14, 1e-8, 7)
    assert np.allclose(straight.depth_from_volume(volumes)[0], manual_depth_no_tilt(volumes),
                       rtol=1e-13, atol=0)
    short = volumes[manual_depth_tilt_short(volumes) < REACH]
    assert short.size >= 3
    assert np.allclose(tilted.depth_from_volume(short)[0], manual_depth_tilt_short(short),
                       rtol=1e-13, atol=0)
    deep = np.array([1.01, 2.0, 5.0, 40.0]) * REACH
    assert np.allclose(tilted.volume_from_depth(deep)[0], manual_volume_tilt_long(deep),
                       rtol=1e-11, atol=0)
    assert np.allclose(tilted.depth_from_volume(manual_volume_tilt_long(deep))[0], deep,
                       rtol=1e-11, atol=0)


@pytest.mark.parametrize("ratio", [1e-4, 1e-3, 1e-2])
def test_parabolic_section_against_exact_segment(straight, ratio):
    """Oracle: exact segment area × l; agrees to the parabola's known first-order error."""
    depth = ratio * R
    exact = L * flat_cut_area(R, depth)
    model = straight.volume_from_depth(depth)[0]
    assert exact / model - 1 == pytest.approx(-0.15 * ratio, abs=0.02 * ratio**2)


@pytest.mark.parametrize("ratio", [1e-4, 1e-3, 1e-2, 0.05])
def test_tilted_wedge_against_integrated_exact_segments(tilted, ratio):
    """Oracle: exact segments integrated along the width; first-order error as derived above."""
    depth = ratio * R
    exact = wedge_volume(lambda u: flat_cut_area(R, u), depth, L, THETA)
    model = tilted.volume_from_depth(depth)[0]
    shallow = max(depth - REACH, 0.0)
    first_order = (3 / (20 * R)) * (5 / 7) * (depth**3.5 - shallow**3.5) / (
        depth**2.5 - shallow**2.5)
    assert exact / model - 1 == pytest.approx(-first_order, abs=0.02 * ratio**2)


def test_round_trip_and_continuity_at_switch(tilted, straight):
    depths = np.concatenate([np.geomspace(1e-9, 0.5 * R, 40), [REACH]])
    for geometry in (straight, tilted):
        volumes = geometry.volume_from_depth(depths)[0]
        back = geometry.depth_from_volume(volumes)[0]
        assert np.allclose(back, depths, rtol=1e-10, atol=0)
    v_switch = tilted.volume_from_depth(REACH)[0]
    below = tilted.depth_from_volume(v_switch * (1 - 1e-12))[0]
    above = tilted.depth_from_volume(v_switch * (1 + 1e-12))[0]
    assert below == pytest.approx(REACH, rel=1e-11) and above == pytest.approx(REACH, rel=1e-11)


def test_tilt_to_zero_and_long_trace_tend_to_straight(straight):
    """θ → 0: the wedge becomes the straight flat (relative difference O(lθ/D))."""
    depth = 1e-4
    nearly = TubeBav(mobile_radius=R, obstacle_width=L, tilt_angle=1e-7)
    assert nearly.volume_from_depth(depth)[0] == pytest.approx(
        straight.volume_from_depth(depth)[0], rel=1e-7)


def test_obstacle_wear_shares_the_depth(tilted):
    """d_m = D·V_m/V, d_o = D − d_m, D from the total volume; V_o → 0 is the bar-intact case."""
    vm, vo = 3e-10, 1e-10
    dm, do = tilted.depth_from_volume(vm, vo)
    total = tilted.depth_from_volume(vm + vo)[0]
    assert dm == pytest.approx(0.75 * total, rel=1e-14)
    assert do == pytest.approx(0.25 * total, rel=1e-14)
    dm_small, do_small = tilted.depth_from_volume(vm, 1e-22)
    assert dm_small == pytest.approx(tilted.depth_from_volume(vm)[0], rel=1e-11)
    assert do_small < 1e-15
    vm2, vo2 = tilted.volume_from_depth(dm, do)
    assert vm2 == pytest.approx(vm, rel=1e-11) and vo2 == pytest.approx(vo, rel=1e-11)


def test_impact_angle_multiplies_volumes_by_cosine():
    alpha = 30.0
    impact = TubeBav(mobile_radius=R, obstacle_width=L, tilt_angle=TILT_DEG, impact_angle=alpha)
    plain = TubeBav(mobile_radius=R, obstacle_width=L, tilt_angle=TILT_DEG)
    vm, vo = np.array([1e-11, 4e-10]), np.array([0.0, 1e-10])
    c = math.cos(math.radians(alpha))
    dm, do = impact.depth_from_volume(vm, vo)
    dm_ref, do_ref = plain.depth_from_volume(vm * c, vo * c)
    assert np.allclose(dm, dm_ref, rtol=1e-13, atol=0)
    assert np.allclose(do, do_ref, rtol=1e-13, atol=0)
    assert np.allclose(impact.volume_from_depth(dm, do)[0], vm, rtol=1e-10, atol=0)


def test_range_beyond_tube_radius():
    geometry = contact_geometry("TUBE_BAV", RAYON_MOBILE=R, LARGEUR_OBST=L)
    with pytest.warns(RangeWarning, match=r"TUBE_BAV.*R_m = 0.009525"):
        depth = geometry.depth_from_volume([1e-10, 2 * geometry.max_volume])[0]
    assert np.isfinite(depth[0]) and np.isnan(depth[1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert geometry.depth_from_volume(geometry.max_volume)[0] == pytest.approx(R, rel=1e-12)


def test_bar_without_wear_has_exactly_zero_depth():
    """Theory §6 TUBE_BAV: d_m = D·V_m/V, d_o = D − d_m; with V_o = 0 the share is exactly 1, so
    d_m = D and d_o = 0 exactly (no rounding residue such as 3e-21 m in a service-life table)."""
    import numpy as np

    from fretwear.geometry import contact_geometry

    for tilt in (0.0, 1.0):
        g = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3,
                             tilt_angle=tilt)
        v = np.array([1e-12, 3.7e-10, 1.1e-9, 5.3e-9])
        d_m, d_o = g.depth_from_volume(v, 0.0)
        assert np.all(d_o == 0.0)
        d_total, _ = g.depth_from_volume(v)
        np.testing.assert_array_equal(d_m, d_total)
        v_m, v_o = g.volume_from_depth(d_m, 0.0)
        assert np.all(v_o == 0.0)


@pytest.mark.parametrize("dims", [{}, {"tilt_angle": 1.0},
                                  {"tilt_angle": 2.0, "impact_angle": 30.0}])
def test_unworn_bar_is_the_shared_formula_bit_for_bit(dims):
    """An obstacle volume of 0 (or −0) everywhere takes a shortcut: the shares of theory §6
    written out here (d_m = D·V_m/V where V > 0, d_o = max(D − d_m, 0), NaN where D is), bit
    for bit; zeros, NaN volumes and volumes beyond the range included."""
    g = TubeBav(mobile_radius=R, obstacle_width=L, **dims)
    vm = np.array([0.0, -0.0, 1e-300, 1e-12, 3.7e-10, 1.1e-9, np.nan, 2 * g.max_volume,
                   10 * g.max_volume])
    for vo in (np.zeros(vm.size), np.full(vm.size, -0.0)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            got = g._depth_from_volume(vm, vo)
        total = vm + vo
        depth = flat_trace_depth(total * math.cos(math.radians(g.impact_angle)), R, L,
                                 math.radians(g.tilt_angle))  # D of V
        depth = np.where(depth <= R, depth, np.nan)
        with np.errstate(invalid="ignore", divide="ignore"):
            dm = np.where(total > 0.0, depth * (vm / total), 0.0)
        dm = np.where(np.isnan(depth), np.nan, dm)
        do = np.where(total > 0.0, depth - dm, 0.0)
        do = np.where(np.isnan(depth), np.nan, np.maximum(do, 0.0))
        for a, b in zip(got, (dm, do), strict=True):
            assert np.array_equal(a, b, equal_nan=True)
            assert np.array_equal(np.signbit(a), np.signbit(b))
        assert np.isnan(got[0][-3:]).all() and np.isfinite(got[0][:-3]).all()
