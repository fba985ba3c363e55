"""Surface correlations (Au-Yang, SPEC_CORR_CONV_3) projected onto beam modes.

Sources: code_aster (GitHub ehmoussi/code_aster) bibfor/algorith/coyang.F90 (the coherence and
its R² factor), bibfor/modelisa/accept.F90, accep1.F90 (angles in (−π, π], |θ₁ − θ₂| on the
unrolled surface), sfifj.F90 (U_c = COEF_VITE_FLUI_A·U, U_ct = COEF_VITE_FLUI_O·U) and
evalis.F90 (SPEC_CORR_CONV_3: φᵀSφ over the surface). The checks are independent numerical
evaluations: scipy's adaptive dblquad of the circumferential double integral (split at the
kernel's kink θ₁ = θ₂), and the direct four-fold surface sum of SPEC_CORR_CONV_3 with the Au-Yang
coherence against the separable Au-Yang projection; and closed forms: a narrow circumferential
kernel gives 2πR·L_t, a uniform pressure no force, a pinned mode with L → ∞ at f → 0 the
product of (2L/π)² and the circumferential factor.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

from fretwear.errors import InputError
from fretwear.flow import TubeFlow, make_spectrum
from fretwear.flow.surface import (
    SpecCorrConv3,
    au_yang_acceptance,
    au_yang_coherence,
    circumferential_factors,
    resampled,
)

R, L = 0.0095, 1.2


def _dblquad_factor(f, lt, ut, normal):
    def g(a):
        return (np.exp(-R * abs(a) / lt) * np.cos(R * 2 * np.pi * f * abs(a) / ut) * R * R)

    def integrand(t2, t1):
        return g(t1 - t2) * normal(t1) * normal(t2)

    lower = integrate.dblquad(integrand, -np.pi, np.pi, -np.pi, lambda t1: t1,
                              epsabs=0, epsrel=1e-10)[0]
    upper = integrate.dblquad(integrand, -np.pi, np.pi, lambda t1: t1, np.pi,
                              epsabs=0, epsrel=1e-10)[0]
    return lower + upper


@pytest.mark.parametrize("f, lt, ut", [(0.0, 0.005, 1.3), (50.0, 0.005, 1.3),
                                       (300.0, 0.004, 0.5), (5.0, 1.0, 1.0)])
def test_circumferential_factors_match_dblquad(f, lt, ut):
    yy, zz = circumferential_factors(f, radius=R, circumferential_velocity=ut,
                                     circumferential_length=lt)
    assert yy == pytest.approx(_dblquad_factor(f, lt, ut, np.cos), rel=1e-6)
    assert zz == pytest.approx(_dblquad_factor(f, lt, ut, np.sin), rel=1e-6)


def test_circumferential_limits():
    """A narrow kernel integrates to 2L_t/R over the angle: Θ → R²·(2L_t/R)·π = 2πR·L_t; a
    uniform pressure (L_t → ∞ at f = 0) has no resultant."""
    lt = 1e-6
    yy, zz = circumferential_factors(1.0, radius=R, circumferential_velocity=1.0,
                                     circumferential_length=lt)
    assert yy == pytest.approx(2 * np.pi * R * lt, rel=1e-3)
    assert zz == pytest.approx(2 * np.pi * R * lt, rel=1e-3)
    yy, zz = circumferential_factors(0.0, radius=R, circumferential_velocity=1.0,
                                     circumferential_length=1e9)
    assert abs(yy) < 1e-9 * R * R and abs(zz) < 1e-9 * R * R


def pinned(n_grid=201):
    s = np.linspace(0.0, L, n_grid)
    shapes = np.zeros((n_grid, 2, 2))
    shapes[:, 0, 0] = np.sin(np.pi * s / L)
    shapes[:, 1, 1] = np.sin(2 * np.pi * s / L)
    shapes[:, 0, 1] = 0.3 * np.sin(2 * np.pi * s / L)
    return TubeFlow(s, shapes, 2 * R, 2.0, 1000.0)


KW = {"axial_velocity": 1.3, "circumferential_velocity": 1.1, "axial_length": 0.1,
      "circumferential_length": 0.004}


def test_au_yang_axial_limit_is_the_full_correlation():
    """L → ∞ at f → 0: J_11 = Θ_yy·(∫sin(πs/L) ds)² = Θ_yy·(2L/π)²."""
    tube = pinned(2001)
    kw = {**KW, "axial_length": 1e9}
    j = au_yang_acceptance(tube, [1e-9], **kw)
    yy, _ = circumferential_factors(1e-9, radius=R, circumferential_velocity=1.1,
                                    circumferential_length=0.004)
    assert j[0, 0, 0] == pytest.approx(yy * (2 * L / np.pi) ** 2, rel=1e-5)


def test_au_yang_separable_equals_the_surface_sum():
    """The separable Au-Yang projection against SPEC_CORR_CONV_3's direct sum over surface
    points with coyang's coherence (no reduction, no separation): the axial grids are the same,
    so the difference is the circumferential midpoint rule's, which falls as 1/n²."""
    tube = pinned(21)
    f = [5.0, 60.0]
    separable = au_yang_acceptance(tube, f, **KW)

    def coyang(s1, t1, s2, t2, fk):  # the coherence without its R² (the areas carry R dθ)
        return au_yang_coherence(s1 - s2, t1 - t2, fk, radius=R, **KW) / (R * R)

    errors = []
    for n in (32, 64):
        direct = SpecCorrConv3(function=coyang, circumferential_points=n).modal_spectrum(f, tube)
        diagonal = np.diagonal(direct / separable, axis1=1, axis2=2)
        errors.append(np.max(np.abs(diagonal - 1)))
    assert errors[1] < 0.02
    assert errors[1] < errors[0] / 3          # second order in the angular step


def test_spec_corr_conv_1_au_yang_scales_the_acceptance():
    """SPEC_CORR_CONV_1 with AU_YANG: the wall-pressure level K²(ρU²)²D_h³ times the surface
    acceptance with U_c = COEF_VITE_FLUI_A·U and U_ct = COEF_VITE_FLUI_O·U (sfifj)."""
    tube = pinned(201)
    spec = make_spectrum("SPEC_CORR_CONV_1", LONG_COR_1=0.1, LONG_COR_2=0.004, VITE_FLUI=2.0,
                         RHO_FLUI=1000.0, D_FLUI=0.01, METHODE="AU_YANG",
                         COEF_VITE_FLUI_A=0.65, COEF_VITE_FLUI_O=0.55)
    f = np.array([5.0, 60.0])
    level = 5.8e-3**2 * (1000.0 * 4.0) ** 2 * 0.01**3
    expected = level * au_yang_acceptance(tube, f, axial_velocity=1.3,
                                          circumferential_velocity=1.1, axial_length=0.1,
                                          circumferential_length=0.004)
    np.testing.assert_allclose(spec.modal_spectrum(f, tube), expected, rtol=1e-12)


def test_spec_corr_conv_3_refuses_bad_functions():
    tube = pinned(11)
    with pytest.raises(InputError, match="function"):
        SpecCorrConv3().modal_spectrum([1.0], tube)
    with pytest.raises(InputError, match="finite"):
        SpecCorrConv3(function=lambda *a: np.nan * a[0]).modal_spectrum([1.0], tube)
    with pytest.raises(InputError, match="circumferential_points"):
        SpecCorrConv3(function=lambda *a: 1.0, circumferential_points=2).modal_spectrum(
            [1.0], tube)


def test_resampled_keeps_linear_shapes():
    tube = pinned(11)
    linear = TubeFlow(tube.positions, np.stack([tube.positions] * 2, 1)[:, :, None], 2 * R)
    out = resampled(linear, 7)
    np.testing.assert_allclose(out.shapes[:, 0, 0], out.positions, rtol=0, atol=1e-15)
