"""Audit: every volume -> depth relation of theory §3 and §6 evaluated literally, against fretwear.

Source of every expected value: the formulas of theory §6 (and §3 for the sector depths) typed in
here as written there, independently of ``fretwear.geometry`` (the lens in its arcsine form R_m²
asin(x/R_m) − R_o² asin(x/R_o) + x·c with the x² of theory §6, not the library's factorised form;
the lunule split by solving for the arc radius r, not for the sagitta; the notch cubic in mm / mm²),
and inverted with scipy's brentq. Realistic dimensions: 22.22 mm SG tube (R_m = 11.11 mm), 20 mm
bar/plate, 1° tilt; control rod R_m = 4.85 mm in a 5.25 mm bore, l = 10 mm. Both branches of the
tilted relations (D < lθ and D ≥ lθ, θ in radians) are exercised.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from fretwear.errors import RangeWarning
from fretwear.geometry import contact_geometry, sector_depth_mobile, sector_depth_obstacle

MM = 1e-3
RTOL = 1e-9


def _solve(func, target, lower, upper):
    return brentq(lambda x: func(x) - target, lower, upper, xtol=1e-22, rtol=1e-15, maxiter=500)


def _seg(rho, x):
    """Theory §6: seg(ρ, x) = ρ²·asin(x/ρ) − x·√(ρ² − x²)."""
    return rho**2 * math.asin(x / rho) - x * math.sqrt(rho**2 - x**2)


def _sag(rho, x):
    """Theory §6: s(ρ, x) = ρ − √(ρ² − x²)."""
    return rho - math.sqrt(rho**2 - x**2)


def _half_chord(d, rm, ro):
    """Theory §6: x² = R_m² − (R_o² − R_m² − c²)²/(4c²), c = R_o − R_m + D."""
    c = ro - rm + d
    return math.sqrt(max(rm**2 - (ro**2 - rm**2 - c**2) ** 2 / (4 * c**2), 0.0))


def _lens(d, rm, ro):
    """Theory §6: S = R_m²·asin(x/R_m) − R_o²·asin(x/R_o) + x·c."""
    if d == 0.0:
        return 0.0
    x = _half_chord(d, rm, ro)
    return rm**2 * math.asin(x / rm) - ro**2 * math.asin(x / ro) + x * (ro - rm + d)


def _d_max(rm, ro):
    """Chord through the mobile's centre: c² = R_o² − R_m²."""
    return math.sqrt(ro**2 - rm**2) - (ro - rm)


def _frustum(area, d, width, theta):
    """Theory §6 frustum rule: (d/θ)·A(d)/3 while d < lθ, else (l/3)(A1 + √(A1·A2) + A2)."""
    if theta == 0.0:
        return width * area(d)
    if d < width * theta:
        return (d / theta) * area(d) / 3
    a1, a2 = area(d), area(d - width * theta)
    return width / 3 * (a1 + math.sqrt(a1 * a2) + a2)


def _lunule_split(d, mobile_area, rm, ro):
    """Theory §6 lunule: seg(R_m, x) − seg(r, x) = V_m/l for r in [R_m, R_o]; depths by sagittas."""
    x = _half_chord(d, rm, ro)
    if mobile_area <= 0.0:
        return 0.0, d
    if mobile_area >= _seg(rm, x) - _seg(ro, x):
        return d, 0.0
    r = _solve(lambda r: _seg(rm, x) - _seg(r, x), mobile_area, rm, ro)
    return _sag(rm, x) - _sag(r, x), _sag(r, x) - _sag(ro, x)


def _check(geometry, vm, vo, expected):
    dm, do = geometry.depth_from_volume(vm, vo)
    np.testing.assert_allclose([dm, do], expected, rtol=RTOL, atol=1e-18)
    back = geometry.volume_from_depth(*expected)
    np.testing.assert_allclose(back, [vm, vo], rtol=RTOL, atol=1e-24)


# ---------------------------------------------------------------- TUBE_BAV
R_TUBE, L_BAR = 11.11 * MM, 20 * MM


def _tube_bav(vm, vo, tilt_deg, impact_deg):
    """Theory §6 TUBE_BAV: D from (V_m + V_o)·cos α; d_m = D·V_m/V, d_o = D − d_m."""
    v = (vm + vo) * math.cos(math.radians(impact_deg))
    theta = math.radians(tilt_deg)
    if theta == 0.0:
        d = (1 / (2 * R_TUBE)) ** (1 / 3) * (3 * v / (4 * L_BAR)) ** (2 / 3)
    else:
        d = (1 / (2 * R_TUBE)) ** (1 / 5) * (15 * theta * v / 8) ** (2 / 5)
        if d >= L_BAR * theta:
            def volume(d):
                return (8 * math.sqrt(2 * R_TUBE) / (15 * theta)
                        * (d**2.5 - (d - L_BAR * theta) ** 2.5))
            d = _solve(volume, v, L_BAR * theta, R_TUBE)
    dm = d * vm / (vm + vo)
    return dm, d - dm


@pytest.mark.parametrize("vm, vo, tilt, impact", [
    (1e-9, 0.0, 0.0, 0.0), (1e-9, 0.4e-9, 0.0, 0.0), (1e-9, 0.0, 1.0, 0.0),
    (1e-9, 0.4e-9, 1.0, 0.0), (1e-9, 0.4e-9, 1.0, 30.0), (1e-9, 0.4e-9, 0.0, 20.0),
    (50e-9, 0.0, 1.0, 0.0),            # D = 0.71 mm > lθ = 0.35 mm: solved branch
    (1e-9, 0.0, 0.01, 0.0),            # lθ = 3.5 µm: solved branch at small tilt
    (1e-11, 3e-12, 1.0, 20.0),
])
def test_tube_bav(vm, vo, tilt, impact):
    g = contact_geometry("TUBE_BAV", RAYON_MOBILE=R_TUBE, LARGEUR_OBST=L_BAR, ANGL_INCLI=tilt,
                         ANGL_IMPACT=impact)
    _check(g, vm, vo, _tube_bav(vm, vo, tilt, impact))


def test_tube_bav_tilt_is_in_radians():
    """1 mm³ at 1°: D = 0.137 mm by the closed form with θ = π/180 (degrees would give 1.37 mm)."""
    g = contact_geometry("TUBE_BAV", RAYON_MOBILE=R_TUBE, LARGEUR_OBST=L_BAR, ANGL_INCLI=1.0)
    assert float(g.depth_from_volume(1e-9)[0]) == pytest.approx(1.3696280599661e-4, rel=1e-12)


# ---------------------------------------------------------------- TUBE_TUBE
@pytest.mark.parametrize("vm, vo, tilt", [(1e-9, 0.0, 5.0), (1e-9, 2e-9, 5.0),
                                          (1e-10, 1e-11, 30.0)])
def test_tube_tube(vm, vo, tilt):
    ro = 9.0 * MM
    theta = math.radians(tilt)
    expected = ((1 / (2 * R_TUBE)) ** 0.2 * (15 * theta * vm / 8) ** 0.4,
                (1 / (2 * ro)) ** 0.2 * (15 * theta * vo / 8) ** 0.4)
    g = contact_geometry("TUBE_TUBE", RAYON_MOBILE=R_TUBE, RAYON_OBST=ro, ANGL_INCLI=tilt)
    _check(g, vm, vo, expected)


# ---------------------------------------------------------------- TUBE_ALESAGE
R_HOLE = 11.5 * MM


def test_tube_alesage_uniform():
    g = contact_geometry("TUBE_ALESAGE", RAYON_MOBILE=R_TUBE, LARGEUR_OBST=L_BAR)
    _check(g, 1e-9, 0.0, (1e-9 / (2 * math.pi * L_BAR * R_TUBE), 0.0))


def _tube_alesage(vm, vo, tilt_deg):
    """Theory §6 TUBE_ALESAGE with R_o: two lunules of half the volumes; tilted: frustum of S."""
    theta = math.radians(tilt_deg)
    limit = _d_max(R_TUBE, R_HOLE)

    def lens(d):
        return _lens(d, R_TUBE, R_HOLE)

    if theta == 0.0:
        d = _solve(lens, (vm + vo) / (2 * L_BAR), 0.0, limit)
        return _lunule_split(d, vm / (2 * L_BAR), R_TUBE, R_HOLE)
    d = _solve(lambda d: _frustum(lens, d, L_BAR, theta), (vm + vo) / 2, 0.0, limit)
    return _lunule_split(d, vm / (vm + vo) * lens(d), R_TUBE, R_HOLE)


@pytest.mark.parametrize("vm, vo, tilt", [
    (1e-9, 0.0, 0.0), (1e-9, 0.5e-9, 0.0), (1e-9, 0.0, 1.0), (1e-9, 0.5e-9, 1.0),
    (3e-9, 1e-9, 0.05),                # D = 29.6 µm ≥ lθ = 17.5 µm: second frustum branch
    (20e-9, 5e-9, 0.5),
])
def test_tube_alesage_lunules(vm, vo, tilt):
    g = contact_geometry("TUBE_ALESAGE", RAYON_MOBILE=R_TUBE, RAYON_OBST=R_HOLE,
                         LARGEUR_OBST=L_BAR, ANGL_INCLI=tilt)
    _check(g, vm, vo, _tube_alesage(vm, vo, tilt))


# ---------------------------------------------------------------- GRAPPE_ALESAGE
R_ROD, R_BORE, L_CARD = 4.85 * MM, 5.25 * MM, 10 * MM


@pytest.mark.parametrize("vm, vo", [(1e-10, 0.0), (1e-9, 0.0), (1e-9, 1.4e-9), (1e-11, 1e-9)])
def test_grappe_alesage(vm, vo):
    d = _solve(lambda d: _lens(d, R_ROD, R_BORE), (vm + vo) / L_CARD, 0.0, _d_max(R_ROD, R_BORE))
    g = contact_geometry("GRAPPE_ALESAGE", RAYON_MOBILE=R_ROD, RAYON_OBST=R_BORE,
                         LARGEUR_OBST=L_CARD)
    _check(g, vm, vo, _lunule_split(d, vm / L_CARD, R_ROD, R_BORE))


# ---------------------------------------------------------------- TUBE_3_ENCO / TUBE_4_ENCO
R_M_E, R_O_E, L_E, ALPHA_I = 9.525 * MM, 9.75 * MM, 30 * MM, 30.0


def _enco(vm, vo, tilt_deg, kappa, per_edge):
    """Theory §6: S' = S + tan(α_i)·D²; V = (l/2)S' or D·S'/(6θ) or (l/6)(S'1 + √(S'1S'2) + S'2);
    V = V_m + V_o (× 1/2 per edge for TUBE_4_ENCO), V_o = κ·π·l·R_o·d_o, d_m = D − d_o."""
    theta = math.radians(tilt_deg)
    tan_a = math.tan(math.radians(ALPHA_I))

    def s_prime(d):
        return _lens(d, R_M_E, R_O_E) + tan_a * d * d

    def volume(d):
        if theta == 0.0:
            return L_E / 2 * s_prime(d)
        if d < L_E * theta:
            return d * s_prime(d) / (6 * theta)
        s1, s2 = s_prime(d), s_prime(d - L_E * theta)
        return L_E / 6 * (s1 + math.sqrt(s1 * s2) + s2)

    d = _solve(volume, per_edge * (vm + vo), 0.0, _d_max(R_M_E, R_O_E))
    do = vo / (kappa * math.pi * L_E * R_O_E)
    return d - do, do


@pytest.mark.parametrize("contact, kappa, per_edge", [("TUBE_3_ENCO", 1.41, 1.0),
                                                      ("TUBE_4_ENCO", 1.88, 0.5)])
@pytest.mark.parametrize("vm, vo, tilt", [
    (1e-9, 0.0, 0.0), (1e-9, 0.0, 1.0), (1e-9, 0.2e-9, 0.0), (1e-9, 0.2e-9, 1.0),
    (1e-11, 1e-12, 1.0),
    (1e-8, 1e-9, 0.2),                 # D ≈ 0.13 mm ≥ lθ = 0.105 mm: second frustum branch
])
def test_broached_hole(contact, kappa, per_edge, vm, vo, tilt):
    g = contact_geometry(contact, RAYON_MOBILE=R_M_E, RAYON_OBST=R_O_E, LARGEUR_OBST=L_E,
                         ANGL_ISTHME=ALPHA_I, ANGL_INCLI=tilt)
    _check(g, vm, vo, _enco(vm, vo, tilt, kappa, per_edge))


# ---------------------------------------------------------------- GRAPPE_1_ENCO / GRAPPE_2_ENCO
@pytest.mark.parametrize("contact, coefficients, kappa", [
    ("GRAPPE_1_ENCO", (-2.76, 10.30, 0.83), 0.47), ("GRAPPE_2_ENCO", (-5.52, 20.60, 1.66), 0.94)])
@pytest.mark.parametrize("vm, vo", [(1e-9, 0.0), (1e-8, 2e-9), (1e-7, 0.0), (1e-12, 1e-12)])
def test_guide_card_notch(contact, coefficients, kappa, vm, vo):
    a, b, c = coefficients
    d_top = (-b - math.sqrt(b * b - 3 * a * c)) / (3 * a)            # [mm], rising branch end
    area_mm2 = vm / L_CARD / MM**2                                    # V_m/l in mm²
    d_mm = _solve(lambda d: a * d**3 + b * d**2 + c * d, area_mm2, 0.0, d_top)
    g = contact_geometry(contact, RAYON_MOBILE=R_ROD, RAYON_OBST=R_BORE, LARGEUR_OBST=L_CARD)
    _check(g, vm, vo, (d_mm * MM, vo / (kappa * math.pi * L_CARD * R_BORE)))


@pytest.mark.parametrize("contact, top_mm2", [("GRAPPE_1_ENCO", 23.333), ("GRAPPE_2_ENCO", 46.666)])
def test_guide_card_notch_beyond_maximum(contact, top_mm2):
    """Past the cubic's maximum (23.333 / 46.666 mm² at d = 2.5276 mm): NaN and a RangeWarning."""
    g = contact_geometry(contact, LARGEUR_OBST=L_CARD)
    with pytest.warns(RangeWarning, match=contact):
        dm, _ = g.depth_from_volume(np.array([0.999, 1.001]) * top_mm2 * MM**2 * L_CARD)
    assert np.isfinite(dm[0]) and np.isnan(dm[1])


# ---------------------------------------------------------------- sector depths (theory §3)
@pytest.mark.parametrize("volume, radius, arc", [(1e-9, R_TUBE, 36.0), (5e-9, R_TUBE, 10.0),
                                                 (1e-10, R_HOLE, 90.0)])
def test_sector_depths(volume, radius, arc):
    dtheta = math.radians(arc)
    a = 2 * volume / (L_BAR * dtheta)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert sector_depth_mobile(volume, radius, L_BAR, arc) == pytest.approx(
            radius - math.sqrt(radius**2 - a), rel=1e-10)
        assert sector_depth_obstacle(volume, radius, L_BAR, arc) == pytest.approx(
            math.sqrt(radius**2 + a) - radius, rel=1e-10)
