"""Sector depths of mobile and obstacle (theory §3; R7.20.01 §5): geometry.sectors.

(Named test_sector_depths.py, not test_sectors.py, so that its module name does not collide
with tests/test_sectors.py: the test directories have no __init__.py.)

Sources: the area of an annular sector as a polygon (shoelace oracle, many vertices) and the
thin-shell limit d → V/(l·R·Δθ) with Δθ in radians; Code_Aster's degrees give 180/π smaller
depths, which must not be reproduced.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from oracle import polygon_area

from fretwear.errors import InputError, RangeWarning
from fretwear.geometry.sectors import (
    sector_depth_mobile,
    sector_depth_obstacle,
    sector_volume_mobile,
    sector_volume_obstacle,
)

R, L = 9.525e-3, 12.7e-3


def annular_sector_area(inner, outer, arc_deg, vertices=200_001):
    """Polygon area of the annular sector inner < r < outer, 0 < φ < arc (shoelace)."""
    phi = np.linspace(0.0, math.radians(arc_deg), vertices)
    # chords of 2e5 vertices: relative area error ~ (Δφ)²/6 < 1e-10
    x = np.concatenate([outer * np.cos(phi), inner * np.cos(phi[::-1])])
    y = np.concatenate([outer * np.sin(phi), inner * np.sin(phi[::-1])])
    return polygon_area(x, y)


@pytest.mark.parametrize("arc_deg", [36.0, 90.0, 360.0])
def test_mobile_and_obstacle_slices_against_polygons(arc_deg):
    depth = 2e-4
    mobile = L * annular_sector_area(R - depth, R, arc_deg)
    obstacle = L * annular_sector_area(R, R + depth, arc_deg)
    assert sector_volume_mobile(depth, R, L, arc_deg) == pytest.approx(mobile, rel=1e-8)
    assert sector_volume_obstacle(depth, R, L, arc_deg) == pytest.approx(obstacle, rel=1e-8)
    assert sector_depth_mobile(mobile, R, L, arc_deg) == pytest.approx(depth, rel=1e-7)
    assert sector_depth_obstacle(obstacle, R, L, arc_deg) == pytest.approx(depth, rel=1e-7)


def test_thin_wear_limit_uses_radians():
    """d → V/(l·R·Δθ) with Δθ in radians (not degrees: Code_Aster's 57× error)."""
    volume, arc = 1e-13, 36.0
    thin = volume / (L * R * math.radians(arc))
    assert sector_depth_mobile(volume, R, L, arc) == pytest.approx(thin, rel=1e-8)
    assert sector_depth_obstacle(volume, R, L, arc) == pytest.approx(thin, rel=1e-8)
    assert sector_depth_mobile(volume, R, L, arc) > 50 * volume / (L * R * arc)


def test_round_trips_vectorised_over_sectors_and_instants():
    arcs = np.array([36.0, 72.0, 252.0])  # three sectors
    depth = np.geomspace(1e-9, 0.9 * R, 12)[:, None] * np.ones(3)
    volume = sector_volume_mobile(depth, R, L, arcs)
    assert np.allclose(sector_depth_mobile(volume, R, L, arcs), depth, rtol=1e-12, atol=0)
    volume = sector_volume_obstacle(depth, R, L, arcs)
    assert np.allclose(sector_depth_obstacle(volume, R, L, arcs), depth, rtol=1e-12, atol=0)
    assert sector_depth_mobile(0.0, R, L, 10.0) == 0.0


def test_beyond_the_sector_and_bad_input():
    whole = L * math.radians(90.0) * R**2 / 2
    with pytest.warns(RangeWarning, match="whole sector"):
        depth = sector_depth_mobile([whole, 1.01 * whole], R, L, 90.0)
    assert depth[0] == pytest.approx(R, rel=1e-12) and np.isnan(depth[1])
    with pytest.raises(InputError, match="arc_deg"):
        sector_depth_mobile(1e-10, R, L, 0.0)
    with pytest.raises(InputError, match="volume"):
        sector_depth_obstacle(-1e-10, R, L, 10.0)
    with pytest.raises(InputError, match="mobile_radius"):
        sector_depth_mobile(1e-10, -R, L, 10.0)


def test_beyond_the_sector_exactly_where_twice_the_density_exceeds_r_squared():
    """The volumes beyond the whole sector are those with 2V/(l·Δθ) > R² (the definition,
    evaluated here as written), counted in the warning; NaN volumes pass without a warning."""
    arcs = np.array([30.0, 45.0, 90.0, 195.0])
    whole = L * np.radians(arcs) * R**2 / 2
    near = np.stack([np.nextafter(whole, 0.0), whole, np.nextafter(whole, np.inf),
                     1.5 * whole, 0.5 * whole])
    density = near / (L * np.radians(arcs))
    expected = 2.0 * density > R * R
    assert 0 < expected.sum() < expected.size
    with pytest.warns(RangeWarning, match=f"{int(expected.sum())} volume"):
        depth = sector_depth_mobile(near, R, L, arcs)
    assert np.array_equal(np.isnan(depth), expected)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isnan(sector_depth_mobile(np.array([np.nan, 0.0]), R, L, arcs[:2])).tolist() \
            == [True, False]


@pytest.mark.parametrize("arc", [np.nan, np.inf, -np.inf, -10.0, 360.5])
def test_arcs_outside_the_range_are_refused(arc):
    for depth in (sector_depth_mobile, sector_depth_obstacle):
        with pytest.raises(InputError, match="arc_deg"):
            depth(1e-10, R, L, np.array([10.0, arc]))


def test_radius_width_and_shapes_are_checked():
    for bad in (np.nan, np.inf, 0.0, np.array([R, -R])):
        with pytest.raises(InputError, match="mobile_radius"):
            sector_depth_mobile(np.array([1e-10, 1e-10]), bad, L, 10.0)
        with pytest.raises(InputError, match="width"):
            sector_depth_obstacle(np.array([1e-10, 1e-10]), R, bad, 10.0)
    with pytest.raises(InputError, match="do not broadcast"):
        sector_depth_mobile(np.zeros((2, 3)), R, L, np.full(4, 10.0))
    with pytest.raises(InputError, match="do not broadcast"):
        sector_depth_mobile(np.zeros(3), np.full(2, R), L, 10.0)
    assert sector_depth_mobile(np.zeros(3), R, L, np.full((2, 3), 10.0)).shape == (2, 3)
