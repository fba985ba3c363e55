"""TUBE_TUBE (tube against tube at a crossing angle), theory §6 and Code_Aster R7.20.01 §4.8.

Sources: R7.20.01's closed form d = (1/(2R))^(1/5)·(15θV/8)^(2/5) typed in here; the oracle
integrating exact circular segments along an unbounded wedge, which must agree with the
parabolic relation to its first-order error 1 − (3/28)·d/R (∫u^{3/2}(1 − 3u/(20R))du over
∫u^{3/2}du = 1 − (3/(20R))·(5/7)d).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from oracle import flat_cut_area, wedge_volume

from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.geometry import contact_geometry
from fretwear.geometry.tube_tube import TubeTube

RM, RO, ANGLE = 9.525e-3, 11.1e-3, 5.0
THETA = math.radians(ANGLE)


def manual_depth(volume, radius):
    return (1 / (2 * radius)) ** (1 / 5) * (15 * THETA * volume / 8) ** (2 / 5)


@pytest.fixture
def geometry():
    return TubeTube(mobile_radius=RM, tilt_angle=ANGLE, obstacle_radius=RO)


def test_closed_form_matches_the_manual_for_each_tube(geometry):
    vm, vo = np.geomspace(1e-13, 1e-8, 6), np.geomspace(1e-12, 3e-9, 6)
    dm, do = geometry.depth_from_volume(vm, vo)
    assert np.allclose(dm, manual_depth(vm, RM), rtol=1e-13, atol=0)
    assert np.allclose(do, manual_depth(vo, RO), rtol=1e-13, atol=0)


@pytest.mark.parametrize("ratio", [1e-4, 1e-3, 1e-2])
def test_against_integrated_exact_segments(geometry, ratio):
    depth = ratio * RM
    exact = wedge_volume(lambda u: flat_cut_area(RM, u), depth, math.inf, THETA)
    model = geometry.volume_from_depth(depth)[0]
    assert exact / model - 1 == pytest.approx(-3 / 28 * ratio, abs=0.02 * ratio**2)


def test_round_trip_and_independence(geometry):
    dm = np.geomspace(1e-9, 0.9 * RM, 30)
    do = dm[::-1] * 0.5
    vm, vo = geometry.volume_from_depth(dm, do)
    dm2, do2 = geometry.depth_from_volume(vm, vo)
    assert np.allclose(dm2, dm, rtol=1e-10, atol=0) and np.allclose(do2, do, rtol=1e-10, atol=0)
    alone = geometry.depth_from_volume(vm)[0]
    assert np.array_equal(alone, dm2)  # the obstacle's wear does not change the mobile's depth


def test_needs_a_positive_angle_and_the_obstacle_radius_for_obstacle_wear():
    with pytest.raises(InputError, match=r"ANGL_INCLI"):
        contact_geometry("TUBE_TUBE", mobile_radius=RM, tilt_angle=0.0)
    with pytest.raises(KeywordError, match=r"tilt_angle \(ANGL_INCLI"):
        contact_geometry("TUBE_TUBE", mobile_radius=RM)
    lonely = contact_geometry("TUBE_TUBE", mobile_radius=RM, tilt_angle=ANGLE)
    assert lonely.depth_from_volume(1e-10)[1] == 0.0
    with pytest.raises(KeywordError, match=r"RAYON_OBST"):
        lonely.depth_from_volume(1e-10, 1e-10)


def test_range(geometry):
    with pytest.warns(RangeWarning, match=r"TUBE_TUBE.*R_o = 0.0111"):
        dm, do = geometry.depth_from_volume(1e-10, 1e-3)
    assert np.isfinite(dm) and np.isnan(do)
