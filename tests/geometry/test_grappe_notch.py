"""Tests of GRAPPE_1_ENCO / GRAPPE_2_ENCO (fretwear.geometry.grappe_notch).

The notch relation is empirical (Code_Aster R7.20.01 §4.2-§4.3, from Lina & Zbinden 1995): the
expected values are R7.20.01's coefficients evaluated independently (numpy.polynomial), the roots of
the cubic from numpy's companion-matrix eigenvalues (numpy.roots), the maximum from the derivative's
roots, and R7.20.01's obstacle relation V_o = κ·π·l·R_o·d_o (κ = 0.47 / 0.94; its h is the width l).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from fretwear.errors import KeywordError, RangeWarning, UnusedKeywordWarning
from fretwear.geometry import CONTACT_TYPES, contact_geometry
from fretwear.geometry.grappe_notch import (
    NOTCH_LAWS,
    Grappe1Enco,
    Grappe2Enco,
    notch_area,
    notch_depth,
    notch_depth_limit,
)

# R7.20.01 §4.2-§4.3: V_m/l = A d³ + B d² + C d + D (d in mm, V_m/l in mm²), D = 0.
SEED = {"GRAPPE_1_ENCO": (-2.76, 10.30, 0.83, 0.47), "GRAPPE_2_ENCO": (-5.52, 20.60, 1.66, 0.94)}
WIDTH = 0.02
CLASSES = {"GRAPPE_1_ENCO": Grappe1Enco, "GRAPPE_2_ENCO": Grappe2Enco}


def manual_polynomial(name):
    a, b, c, _ = SEED[name]
    return np.polynomial.Polynomial([0.0, c, b, a])  # coefficients in increasing degree


def rising_root(name, area_mm2):
    """Smallest non-negative real root of P(d) = area (numpy.roots, companion matrix)."""
    a, b, c, _ = SEED[name]
    roots = np.roots([a, b, c, -area_mm2])
    real = roots[np.abs(roots.imag) < 1e-9].real
    return real[real >= -1e-15].min()


@pytest.mark.parametrize("name", SEED)
def test_coefficients_are_the_manual_values(name):
    a, b, c, kappa = SEED[name]
    assert NOTCH_LAWS[name]["coefficients"] == (a, b, c)
    assert NOTCH_LAWS[name]["kappa"] == kappa


@pytest.mark.parametrize("name", SEED)
def test_area_is_the_manual_polynomial(name):
    depth_mm = np.array([0.0, 0.1, 1.0, 2.0, 2.5])
    expected = manual_polynomial(name)(depth_mm) * 1e-6  # mm² -> m²
    np.testing.assert_allclose(notch_area(depth_mm * 1e-3, name), expected, rtol=1e-14)
    g = CLASSES[name](obstacle_width=WIDTH)
    np.testing.assert_allclose(g.volume_from_depth(depth_mm * 1e-3)[0], WIDTH * expected,
                               rtol=1e-14)


def test_two_notches_are_twice_one():
    """Seed: the double-notch coefficients are exactly twice the single-notch ones."""
    depth = np.linspace(0.0, 2.5e-3, 11)
    np.testing.assert_allclose(notch_area(depth, "GRAPPE_2_ENCO"),
                               2.0 * notch_area(depth, "GRAPPE_1_ENCO"), rtol=1e-15)
    area = notch_area(depth, "GRAPPE_1_ENCO")
    np.testing.assert_allclose(notch_depth(2.0 * area, "GRAPPE_2_ENCO"),
                               notch_depth(area, "GRAPPE_1_ENCO"), rtol=1e-12, atol=1e-18)


@pytest.mark.parametrize("name", SEED)
def test_maximum_of_the_polynomial(name):
    """d_max is the positive root of P'(d); P'' < 0 there; the area there is the largest."""
    p = manual_polynomial(name)
    critical = p.deriv().roots()
    d_max = critical[critical > 0].max()
    assert notch_depth_limit(name) * 1e3 == pytest.approx(d_max, rel=1e-14)
    assert d_max == pytest.approx(2.5276, abs=5e-5)
    assert p.deriv(2)(d_max) < 0
    g = CLASSES[name](obstacle_width=WIDTH)
    assert g.max_depth == notch_depth_limit(name)
    assert g.max_volume == pytest.approx(WIDTH * p(d_max) * 1e-6, rel=1e-14)


@pytest.mark.parametrize("name", SEED)
def test_inverse_is_the_rising_branch_root(name):
    """notch_depth returns the smallest non-negative root (rising branch), not the other one."""
    p = manual_polynomial(name)
    areas_mm2 = p(np.array([1e-6, 0.01, 0.3, 1.0, 1.9, 2.5]))
    got = notch_depth(areas_mm2 * 1e-6, name) * 1e3
    expected = [rising_root(name, y) for y in areas_mm2]
    np.testing.assert_allclose(got, expected, rtol=1e-11)
    # the cubic has a second positive root beyond the maximum: never returned
    a, b, c, _ = SEED[name]
    other = np.roots([a, b, c, -p(1.0)]).real
    assert other.max() > notch_depth_limit(name) * 1e3 and got[3] == pytest.approx(1.0)


@pytest.mark.parametrize("name", SEED)
def test_round_trips(name):
    g = CLASSES[name](obstacle_width=WIDTH)
    depth = np.concatenate([[0.0], np.geomspace(1e-9, 0.999 * g.max_depth, 12)])
    do = np.linspace(0.0, 1e-4, depth.size)
    vm, vo = g.volume_from_depth(depth, do)
    dm_back, do_back = g.depth_from_volume(vm, vo)
    np.testing.assert_allclose(dm_back, depth, rtol=1e-12, atol=1e-21)
    np.testing.assert_allclose(do_back, do, rtol=1e-14)
    volumes = np.geomspace(1e-15, 0.999 * g.max_volume, 12)
    back = g.volume_from_depth(g.depth_from_volume(volumes)[0])[0]
    np.testing.assert_allclose(back, volumes, rtol=1e-12)


@pytest.mark.parametrize("name", SEED)
def test_small_depth_is_linear(name):
    """P(d) = C·d·(1 + (B/C)·d + ...): V_m/l ≈ C·d for d → 0."""
    _, b, c, _ = SEED[name]
    g = CLASSES[name](obstacle_width=WIDTH)
    depth_mm = 1e-6
    dm, _ = g.depth_from_volume(WIDTH * c * depth_mm * 1e-6)
    assert dm * 1e3 == pytest.approx(depth_mm, rel=2 * abs(b / c) * depth_mm)


@pytest.mark.parametrize("name", SEED)
def test_obstacle_relation(name):
    """V_o = κ·π·l·R_o·d_o (R7.20.01, h = l), with R_o the fitted 5.25 mm unless given."""
    kappa = SEED[name][3]
    vo = np.array([0.0, 1e-12, 1e-9])
    for radius, kwargs in ((5.25e-3, {}), (5.25e-3, {"obstacle_radius": 5.25e-3})):
        g = CLASSES[name](obstacle_width=WIDTH, **kwargs)
        dm, do = g.depth_from_volume(2e-9, vo)
        np.testing.assert_allclose(do, vo / (kappa * math.pi * WIDTH * radius), rtol=1e-15)
        # the rod's depth does not depend on the card's wear (separate relations)
        np.testing.assert_allclose(dm, g.depth_from_volume(2e-9)[0], rtol=0)


@pytest.mark.parametrize("name", SEED)
def test_beyond_the_maximum_is_nan_with_warning(name):
    g = CLASSES[name](obstacle_width=WIDTH)
    with pytest.warns(RangeWarning, match=f"{name}.*maximum of the notch polynomial"):
        dm, do = g.depth_from_volume([0.5 * g.max_volume, 1.001 * g.max_volume], 1e-10)
    assert np.isfinite(dm[0]) and np.isnan(dm[1])
    assert np.isfinite(do).all()  # the card's depth has its own relation
    with pytest.warns(RangeWarning, match=name):
        vm, _ = g.volume_from_depth([2.0e-3, 2.6e-3])
    assert np.isfinite(vm[0]) and np.isnan(vm[1])
    assert g.volume_from_depth(g.max_depth)[0] == pytest.approx(g.max_volume, rel=1e-14)


def test_keywords_and_radius_warnings():
    assert CONTACT_TYPES["GRAPPE_1_ENCO"] is Grappe1Enco
    assert CONTACT_TYPES["GRAPPE_2_ENCO"] is Grappe2Enco
    with pytest.raises(KeywordError, match="LARGEUR_OBST"):
        contact_geometry("GRAPPE_1_ENCO", RAYON_OBST=5.25e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the fitted radii: no warning
        contact_geometry("GRAPPE_2_ENCO", LARGEUR_OBST=WIDTH, RAYON_MOBILE=4.85e-3,
                         RAYON_OBST=5.25e-3)
    with pytest.warns(RangeWarning, match="9.7 mm rod in a 10.5 mm.*RAYON_OBST"):
        g = contact_geometry("GRAPPE_1_ENCO", LARGEUR_OBST=WIDTH, RAYON_OBST=6e-3)
    assert g.card_radius == 6e-3
    with pytest.warns(RangeWarning, match="RAYON_MOBILE"):
        contact_geometry("GRAPPE_1_ENCO", LARGEUR_OBST=WIDTH, RAYON_MOBILE=5e-3)
    with pytest.warns(UnusedKeywordWarning, match="ANGL_INCLI"):
        contact_geometry("GRAPPE_1_ENCO", LARGEUR_OBST=WIDTH, ANGL_INCLI=1.0)


def test_vectorised_and_inputs_untouched():
    g = Grappe2Enco(obstacle_width=WIDTH)
    vm = np.array([[1e-8, 2e-7], [0.0, 5e-7]])
    keep = vm.copy()
    dm, do = g.depth_from_volume(vm)
    assert dm.shape == do.shape == (2, 2)
    np.testing.assert_array_equal(vm, keep)
    np.testing.assert_allclose(dm.ravel(), [g.depth_from_volume(v)[0] for v in vm.ravel()],
                               rtol=1e-15)


@pytest.mark.parametrize("name", SEED)
@pytest.mark.parametrize("rtol", [1e-13, 1e-6])
def test_few_areas_element_by_element_are_the_vectorised_iterations_bit_for_bit(name, rtol):
    """notch_depth of a few areas (element by element in Python floats) against the same areas
    among many (the vectorised iterations): the same bits, zero, the maximum, tiny areas and
    the out-of-range ones included; both against numpy.roots' rising root."""
    from fretwear.geometry import grappe_notch

    p = manual_polynomial(name)
    d_max = notch_depth_limit(name) * 1e3
    rng = np.random.default_rng(11)
    depths = np.concatenate([[0.0, 1e-300, 1e-12, 1e-6, d_max, d_max * (1 - 1e-12)],
                             rng.uniform(0.0, d_max, 40)])
    areas = np.concatenate([p(depths) * 1e-6, [np.nan, np.inf, -1e-9, 2 * p(d_max) * 1e-6]])
    many = notch_depth(areas, name, rtol=rtol)  # the vectorised iterations
    assert areas.size > grappe_notch._SCALAR_AREAS
    chunk = 5  # a table's instants: element by element
    assert chunk <= grappe_notch._SCALAR_AREAS
    few = np.concatenate([notch_depth(areas[i:i + chunk], name, rtol=rtol)
                          for i in range(0, areas.size, chunk)])
    assert np.array_equal(few, many, equal_nan=True)
    assert [notch_depth(x, name, rtol=rtol).shape for x in (areas[0], areas[:3])] == [(), (3,)]
    assert np.isnan(many[-4:]).all() and many[0] == 0.0
    expected = [rising_root(name, y) for y in p(depths[6:])]
    np.testing.assert_allclose(many[6:-4] * 1e3, expected, rtol=max(rtol, 1e-11) * 10)
