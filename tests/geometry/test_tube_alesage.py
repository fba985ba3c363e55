"""TUBE_ALESAGE (tube in a drilled support-plate hole), theory §6 and Code_Aster R7.20.01 §4.5.

Sources: the annulus π(R² − (R − d)²)·l (elementary) for the uniform model, whose first-order
relation d = V/(2πlR) has relative error d/(2R); the oracle's lens and lunule (numerical
crossings, quadrature) for the two lunules; for the tilted traces the frustum rule of theory §6
applied to the oracle's sections, and the exact wedge integral of the oracle's sections, which
the frustum rule underestimates by the factor 5/6 at small depth (sections ∝ D^{3/2}).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from oracle import lens_oracle, lunule_oracle, wedge_volume

from fretwear.errors import InputError, KeywordError, RangeWarning, UnusedKeywordWarning
from fretwear.geometry import contact_geometry
from fretwear.geometry.tube_alesage import TubeAlesage

RM, RO, L, TILT = 9.525e-3, 9.7e-3, 20e-3, 0.5
THETA = math.radians(TILT)
REACH = L * THETA


def lens(depth):
    return lens_oracle(RM, RO, depth)[0] if depth > 0 else 0.0


@pytest.fixture
def straight():
    return TubeAlesage(mobile_radius=RM, obstacle_radius=RO, obstacle_width=L)


@pytest.fixture
def tilted():
    return TubeAlesage(mobile_radius=RM, obstacle_radius=RO, obstacle_width=L, tilt_angle=TILT)


# ----------------------------------------------------------------------------- uniform
def test_uniform_wear_against_annulus():
    geometry = contact_geometry("TUBE_ALESAGE", mobile_radius=RM, obstacle_width=L)
    for depth in (1e-7, 1e-5, 1e-4):
        annulus = math.pi * depth * (2 * RM - depth) * L  # π(R² − (R − d)²)·l
        model = geometry.volume_from_depth(depth)[0]
        assert annulus / model == pytest.approx(1 - depth / (2 * RM), rel=1e-12)
    volume = np.array([0.0, 1e-10, 1e-8])
    assert np.allclose(geometry.depth_from_volume(volume)[0], volume / (2 * math.pi * L * RM),
                       rtol=1e-15, atol=0)


def test_uniform_model_rejects_obstacle_wear_and_warns_on_tilt():
    geometry = contact_geometry("TUBE_ALESAGE", mobile_radius=RM, obstacle_width=L)
    with pytest.raises(KeywordError, match=r"RAYON_OBST"):
        geometry.depth_from_volume(1e-10, 1e-11)
    with pytest.warns(UnusedKeywordWarning, match=r"ANGL_INCLI"):
        contact_geometry("TUBE_ALESAGE", mobile_radius=RM, obstacle_width=L, tilt_angle=1.0)
    with pytest.raises(InputError, match=r"must exceed"):
        contact_geometry("TUBE_ALESAGE", mobile_radius=RM, obstacle_width=L,
                         obstacle_radius=0.9 * RM)


# ----------------------------------------------------------------------------- two lunules
@pytest.mark.parametrize(("dm", "do"), [(1e-6, 0.0), (3e-5, 2e-5), (4e-4, 6e-4)])
def test_two_lunules_against_oracle(straight, dm, do):
    vm, vo = straight.volume_from_depth(dm, do)
    om, oo = lunule_oracle(RM, RO, dm, do)
    assert vm == pytest.approx(2 * L * om, rel=1e-9)
    assert vo == pytest.approx(2 * L * oo, rel=1e-9, abs=1e-9 * vm)


def test_two_lunules_hold_half_the_volume_each(straight):
    """Each lunule holds half: the depth of (V_m, V_o) in TUBE_ALESAGE is that of one lunule
    holding (V_m/2, V_o/2), i.e. GRAPPE_ALESAGE with the same dimensions."""
    single = contact_geometry("GRAPPE_ALESAGE", mobile_radius=RM, obstacle_radius=RO,
                              obstacle_width=L)
    vm, vo = np.array([1e-12, 1e-9, 4e-8]), np.array([0.0, 5e-10, 1e-8])
    dm, do = straight.depth_from_volume(vm, vo)
    dm1, do1 = single.depth_from_volume(vm / 2, vo / 2)
    assert np.allclose(dm, dm1, rtol=1e-12, atol=0) and np.allclose(do, do1, rtol=1e-12, atol=0)


# ----------------------------------------------------------------------------- tilted
@pytest.mark.parametrize("depth", [0.3 * REACH, REACH, 4 * REACH])
@pytest.mark.parametrize("share", [1.0, 0.7])
def test_tilted_frustum_rule_on_oracle_sections(tilted, depth, share):
    """V_m + V_o = 2 × frustum rule of the oracle's lens sections; the split is the oracle
    lunule's share at the deepest section."""
    dm, do = share * depth, (1 - share) * depth
    s1, s2 = lens(depth), lens(depth - REACH)
    if depth < REACH:
        trace = depth / THETA * s1 / 3
    else:
        trace = L / 3 * (s1 + math.sqrt(s1 * s2) + s2)
    am, ao = lunule_oracle(RM, RO, dm, do)
    vm, vo = tilted.volume_from_depth(dm, do)
    assert vm + vo == pytest.approx(2 * trace, rel=1e-9)
    assert vm / (vm + vo) == pytest.approx(am / (am + ao), rel=1e-9)


def test_frustum_rule_bias_against_exact_wedge(tilted):
    """At small depth (lens ∝ D^{3/2}) the frustum rule is 5/6 of the exact wedge integral;
    far beyond lθ the two agree (documented in docs/geometry.md)."""
    small = 1e-9
    exact = 2 * wedge_volume(lens, small, L, THETA)
    assert tilted.volume_from_depth(small)[0] / exact == pytest.approx(5 / 6, rel=1e-5)
    deep = 0.9 * tilted.max_depth
    exact = 2 * wedge_volume(lens, deep, L, THETA)
    assert tilted.volume_from_depth(deep)[0] / exact == pytest.approx(1.0, abs=2e-3)


def test_tilted_round_trip_continuity_and_limits(tilted, straight):
    depth = np.concatenate([np.geomspace(1e-9, 0.99 * tilted.max_depth, 30), [REACH]])
    for share in (1.0, 0.5, 0.05):
        vm, vo = tilted.volume_from_depth(share * depth, (1 - share) * depth)
        dm, do = tilted.depth_from_volume(vm, vo)
        assert np.all(np.abs(dm - share * depth) <= 1e-10 * depth)
        assert np.all(np.abs(do - (1 - share) * depth) <= 1e-10 * depth)
    v_switch = tilted.volume_from_depth(REACH)[0]
    below, above = tilted.depth_from_volume(v_switch * np.array([1 - 1e-12, 1 + 1e-12]))[0]
    assert below == pytest.approx(REACH, rel=1e-11) and above == pytest.approx(REACH, rel=1e-11)
    nearly = TubeAlesage(mobile_radius=RM, obstacle_radius=RO, obstacle_width=L,
                         tilt_angle=1e-9)
    assert nearly.volume_from_depth(1e-4)[0] == pytest.approx(
        straight.volume_from_depth(1e-4)[0], rel=1e-7)
    vm = tilted.volume_from_depth(2e-4)[0]
    dm, do = tilted.depth_from_volume(vm, 1e-25)
    assert dm == pytest.approx(2e-4, rel=1e-10) and do < 1e-16


def test_range(tilted):
    with pytest.warns(RangeWarning, match=r"TUBE_ALESAGE.*0.00165922 m"):
        dm, do = tilted.depth_from_volume([1e-10, tilted.max_volume * 1.01])
    assert np.isfinite(dm[0]) and np.isnan(dm[1]) and np.isnan(do[1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert tilted.depth_from_volume(tilted.max_volume)[0] == pytest.approx(
            tilted.max_depth, rel=1e-9)


def test_lunule_split_solved_only_where_shared_is_the_whole_solve():
    """lunule_mobile_depth solves d_m only where the share is strictly between 0 and 1: the
    same bits as solving every element (the solver is element-wise), NaN shares included."""
    from fretwear.geometry._lunule import lunule_mobile_depth
    depth = np.array([1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 3e-4])
    for shares in ([0.0, 1.0, 0.5, 0.2, np.nan, 1.5], [0.3, 0.1, 0.9, 0.5, 0.7, 0.01]):
        shares = np.array(shares)
        got = lunule_mobile_depth(9.525e-3, 9.75e-3, depth, shares)
        # one element at a time: the whole-array solve of each
        one = [float(lunule_mobile_depth(9.525e-3, 9.75e-3, d, s))
               for d, s in zip(depth, shares, strict=True)]
        assert np.array_equal(got, one, equal_nan=True)
        inner = (shares > 0) & (shares < 1)
        assert np.isnan(got[np.isnan(shares)]).all()
        assert (got[shares >= 1] == depth[shares >= 1]).all() and (got[shares <= 0] == 0).all()
        assert (got[inner] > 0).all() and (got[inner] < depth[inner]).all()
