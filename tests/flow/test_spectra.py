"""Turbulence spectra (DEFI_SPEC_TURB) and their projection onto the modes (PROJ_SPEC_BASE).

Sources: the catalogue code_aster/Cata/Commands/defi_spec_turb.py (defaults), the Fortran
routines spect1/spect4 (projection), coesp1/coesp4 (coefficients), sfifj/dspprs/accept/coegen/
corcos (convected), specep (GRAPPE_2), all of code_aster (GitHub ehmoussi/code_aster). Closed
forms of the joint acceptance of a pinned-pinned mode sin(πs/L) under uniform flow:
λ → ∞: (∫φ ds)² = (2L/π)²; λ → 0: 2λ∫φ² ds = λL; otherwise checked against an independent
adaptive double quadrature (scipy.integrate.dblquad).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from fretwear.errors import InputError, KeywordError
from fretwear.flow import SPECTRA, TubeFlow, beam_tube_flow, exponential_acceptance, make_spectrum
from fretwear.flow.grappe2 import GRAPPE_2_COEFFICIENTS, grappe_2_spectra
from fretwear.flow.spectra import convected_coherence, long_cor_1_coefficients, long_cor_4_phi0

L, D = 1.2, 0.019


def pinned_tube(n_grid=2001, velocity=2.0, density=1000.0, modes=1):
    s = np.linspace(0.0, L, n_grid)
    shapes = np.zeros((n_grid, 2, modes))
    for r in range(modes):
        shapes[:, 0, r] = np.sin((r + 1) * np.pi * s / L)
    return TubeFlow(s, shapes, D, velocity, density, 0.3)


#: one set of parameters per family (the contract test evaluates each).
PARAMETERS = {
    "SPEC_LONG_COR_1": {"long_cor": 3.0, "kinematic_viscosity": 1e-6},
    "SPEC_LONG_COR_2": {"long_cor": 3.0},
    "SPEC_LONG_COR_3": {"long_cor": 3.4},
    "SPEC_LONG_COR_4": {"long_cor": 3.0, "void_fraction": 0.6},
    "SPEC_CORR_CONV_1": {"long_cor_1": 0.05, "velocity": 2.0, "density": 1000.0,
                         "hydraulic_diameter": 0.01},
    "SPEC_CORR_CONV_2": {"function": lambda w: 1.0 / (1.0 + (w / 200.0) ** 2),
                         "velocity": 2.0, "long_cor_1": 0.05, "method": "CORCOS"},
    "SPEC_CORR_CONV_3": {"function": lambda s1, t1, s2, t2, f: np.exp(-np.abs(s1 - s2) / 0.05)
                         * np.exp(-np.abs(t1 - t2)) * np.cos(2 * np.pi * f * (s1 - s2) / 1.3),
                         "circumferential_points": 8, "axial_points": 101},
    "GRAPPE_1": {"flow_rate": "DEBIT_300", "position": 0.6},
    "GRAPPE_2": {"configuration": "ASC_EXC", "density": 1000.0, "velocity": 3.0,
                 "position": 0.3},
}


#: the families' variants the contract also holds (a coherence of their own).
VARIANTS = {
    "SPEC_CORR_CONV_1/AU_YANG": ("SPEC_CORR_CONV_1", {
        **PARAMETERS["SPEC_CORR_CONV_1"], "method": "AU_YANG", "long_cor_2": 0.004,
        "coef_vite_flui_a": 0.65, "coef_vite_flui_o": 0.55}),
    "SPEC_CORR_CONV_2/AU_YANG": ("SPEC_CORR_CONV_2", {
        **PARAMETERS["SPEC_CORR_CONV_2"], "method": "AU_YANG", "long_cor_2": 0.004,
        "coef_vite_flui_a": 0.65, "coef_vite_flui_o": 0.55}),
    # on the surface the points must resolve the convected wavelength U_c/f (here ≥ 43 mm
    # against 6 mm steps); 2 m/s would alias it (4 mm at 300 Hz) into indefinite matrices
    "SPEC_CORR_CONV_1/GENERALE on the surface": ("SPEC_CORR_CONV_1", {
        **PARAMETERS["SPEC_CORR_CONV_1"], "velocity": 20.0, "circumferential_points": 8,
        "axial_points": 201}),
}
CASES = {**{name: (name, parameters) for name, parameters in PARAMETERS.items()}, **VARIANTS}


def test_every_family_has_parameters_here():
    assert set(PARAMETERS) == set(SPECTRA)


@pytest.mark.parametrize("case", sorted(CASES))
def test_contract(case):
    """Shared contract: (n_f, n, n), finite, Hermitian, positive semi-definite (or flagged
    ``positive_semidefinite = False`` and then truly not), quadratic in the mode shapes, and
    positive somewhere in a band of interest."""
    name, parameters = CASES[case]
    spectrum = make_spectrum(name, **parameters)
    tube = pinned_tube(n_grid=401, modes=3)
    f = np.linspace(2.0, 300.0, 40)
    s = spectrum.modal_spectrum(f, tube)
    assert s.shape == (40, 3, 3)
    assert np.all(np.isfinite(s))
    np.testing.assert_allclose(s, np.conj(np.swapaxes(s, 1, 2)), rtol=1e-12, atol=0)
    lowest = min(np.linalg.eigvalsh(s[k]).min() / max(abs(np.linalg.eigvalsh(s[k])).max(),
                                                      1e-300) for k in range(f.size))
    if getattr(spectrum, "positive_semidefinite", True):
        assert lowest >= -1e-9
    else:  # the flag is only for a family whose data are not (GRAPPE_1's measured matrix)
        assert lowest < -1e-6
    assert np.all(np.diagonal(s, axis1=1, axis2=2).real >= 0)
    assert np.max(np.abs(s)) > 0
    doubled = tube.__class__(tube.positions, 2 * tube.shapes, tube.diameter, tube.velocity,
                             tube.density, tube.void_fraction)
    np.testing.assert_allclose(spectrum.modal_spectrum(f, doubled), 4 * s, rtol=1e-12)


def test_catalogue_defaults():
    """The defaults of code_aster/Cata/Commands/defi_spec_turb.py."""
    assert (make_spectrum("SPEC_LONG_COR_2", long_cor=1).freq_coup,
            make_spectrum("SPEC_LONG_COR_2", long_cor=1).phi0,
            make_spectrum("SPEC_LONG_COR_2", long_cor=1).beta) == (0.1, 1.5e-3, 2.7)
    s3 = make_spectrum("SPEC_LONG_COR_3", long_cor=1)
    assert (s3.freq_coup, s3.phi0_1, s3.beta_1, s3.phi0_2, s3.beta_2) == (0.2, 5e-3, 0.5, 4e-5,
                                                                          3.5)
    s4 = make_spectrum("SPEC_LONG_COR_4", long_cor=1, TAUX_VIDE=0.5)
    assert (s4.beta, s4.gamma, s4.void_fraction) == (2.0, 4.0, 0.5)
    c1 = make_spectrum("SPEC_CORR_CONV_1", long_cor_1=1, vite_flui=1, rho_flui=1, d_flui=1)
    assert (c1.k, c1.method) == (5.8e-3, "GENERALE")


def test_unknown_names_say_what_exists():
    with pytest.raises(KeywordError, match="SPEC_LONG_COR_1"):
        make_spectrum("SPEC_LONG_COR_9")
    with pytest.raises(KeywordError, match="long_cor"):
        make_spectrum("SPEC_LONG_COR_2", longcor=3.0)
    with pytest.raises(KeywordError, match="surface"):
        convected_coherence("AU_YANG", 0.0, 1.0, 1.0, 1.0)
    with pytest.raises(InputError, match="long_cor_2"):
        make_spectrum("SPEC_CORR_CONV_1", **{**PARAMETERS["SPEC_CORR_CONV_1"],
                                             "method": "AU_YANG"}).modal_spectrum(
            [1.0], pinned_tube())
    with pytest.raises(InputError, match="> 0"):
        make_spectrum("SPEC_LONG_COR_2", long_cor=3.0).modal_spectrum([0.0, 1.0], pinned_tube())


def test_coesp1_polynomial_joins_its_plateaus():
    """coesp1's fifth-degree polynomial meets its constant plateaus at Re = 1.5e4 and 5e4 (within
    1 %): an independent check of the transcription of its six coefficients."""
    low = long_cor_1_coefficients(1.5e4 + 1e-6)[0] / 1.3e-4
    high = long_cor_1_coefficients(5.0e4 - 1e-6)[0] / 1.3e-4
    assert low == pytest.approx(2.1808, rel=0.01)
    assert high == pytest.approx(38.6075, rel=0.01)
    assert long_cor_1_coefficients(6e4)[1:] == (0.6, 0.2, 4.0)
    assert long_cor_1_coefficients(4e4)[1:] == (0.3, 0.2, 4.0)


def test_coesp4_single_phase_and_formula():
    """coesp4: φ₀(α) = 10^(24.042√α − 50.421α^1.5 + 63.483α^2.5 − 33.284α^3.5)/0.068."""
    assert long_cor_4_phi0(0.0) == pytest.approx(1 / 6.8e-2)
    a = 0.8
    expected = 10 ** (24.042 * a**0.5 - 50.421 * a**1.5 + 63.483 * a**2.5 - 33.284 * a**3.5)
    assert long_cor_4_phi0(a) == pytest.approx(expected / 0.068, rel=1e-12)


def test_exponential_acceptance_limits_pinned_mode():
    tube = pinned_tube(n_grid=4001)
    full = exponential_acceptance(tube, math.inf)[0, 0]
    assert full == pytest.approx((2 * L / math.pi) ** 2, rel=1e-6)
    assert exponential_acceptance(tube, 1e6)[0, 0] == pytest.approx(full, rel=1e-5)
    lam = L / 400  # 10 grid spacings per λ; the boundary correction is O(λ/L)
    assert exponential_acceptance(tube, lam)[0, 0] == pytest.approx(lam * L, rel=0.01)


def _blevins(ends, x):
    """First mode of a uniform beam, Blevins (1979) Table 8-1, unit maximum."""
    if ends == ("pinned", "pinned"):
        return np.sin(np.pi * x / L)
    lam, sig = 4.730040745, 0.982502215
    z = lam * x / L
    shape = np.cosh(z) - np.cos(z) - sig * (np.sinh(z) - np.sin(z))
    return shape / 1.588150


@pytest.mark.parametrize("ends", [("clamped", "clamped"), ("pinned", "pinned")])
def test_exponential_acceptance_against_dblquad(ends):
    """The beam's first mode on the grid (fretwear's modes) against scipy's adaptive double
    quadrature of Blevins' closed-form shape (the kernel's kink on s₁ = s₂ on the border)."""
    _, tube = beam_tube_flow(young_modulus=2e11, second_moment=2.5e-9, mass_per_length=0.9,
                             length=L, n_modes=1, shock_positions=[0.5], diameter=D,
                             ends=ends, grid_points=1201, method="analytic")
    lam = 0.1

    def integrand(y, x):
        return math.exp(-(x - y) / lam) * _blevins(ends, x) * _blevins(ends, y)

    half, _ = integrate.dblquad(integrand, 0, L, 0, lambda x: x, epsabs=1e-12, epsrel=1e-9)
    assert exponential_acceptance(tube, lam, directions=("y",))[0, 0] == pytest.approx(
        2 * half, rel=1e-4)


def test_long_cor_spectrum_uniform_flow_closed_form():
    """SPEC_LONG_COR_2 on a pinned mode, uniform U and ρ, λ = LONG_COR·D ≪ L:
    S = ¼D³U³ · ρ²λL · φ₀/(1 + (fD/U/f_rc)^β) (spect1)."""
    u, rho = 2.0, 1000.0
    tube = pinned_tube(n_grid=6001, velocity=u, density=rho)
    spec = make_spectrum("SPEC_LONG_COR_2", long_cor=0.2)  # λ = 3.8 mm, 10 spacings
    f = np.array([5.0, 20.0, 80.0])
    got = spec.modal_spectrum(f, tube)[:, 0, 0]
    lam = 0.2 * D
    sr = 1.5e-3 / (1 + (f * D / u / 0.1) ** 2.7)
    expected = 0.25 * D**3 * u**3 * rho**2 * lam * L * sr
    np.testing.assert_allclose(got, expected, rtol=0.01)


def test_long_cor_profile_normalised_by_zone_mean():
    """Half the span in flow at U: Ū = U over the zone; doubling U multiplies S by U³ scaling
    at a fixed reduced frequency (f ∝ U)."""
    s = np.linspace(0, L, 1201)
    u = np.where(s <= L / 2, 2.0, 0.0)
    tube = pinned_tube(n_grid=1201).with_flow(velocity=u)
    assert tube.zone_velocity() == pytest.approx(2.0)
    spec = make_spectrum("SPEC_LONG_COR_3", long_cor=3.4)
    a = spec.modal_spectrum([10.0], tube)[0, 0, 0]
    b = spec.modal_spectrum([20.0], tube.with_flow(velocity=2 * u))[0, 0, 0]
    assert b == pytest.approx(8 * a, rel=1e-12)


def test_convected_generale_low_frequency_is_exponential():
    """GENERALE's coherence e^{−|Δ|/L}cos(ω|Δ|/U_c) → e^{−|Δ|/L} as ω → 0."""
    tube = pinned_tube(n_grid=801)
    spec = make_spectrum("SPEC_CORR_CONV_1", long_cor_1=0.1, velocity=5.0, density=1000.0,
                         hydraulic_diameter=0.01)
    got = spec.modal_spectrum([1e-6], tube)[0, 0, 0]
    level = 5.8e-3**2 * (1000.0 * 25.0) ** 2 * 0.01**3
    assert got == pytest.approx(level * exponential_acceptance(tube, 0.1)[0, 0], rel=1e-9)
    # cut-off: above 10·U/D_h (no FREQ_COUP) the pressure spectrum is zero (dspprs)
    assert spec.modal_spectrum([5001.0], tube)[0, 0, 0] == 0.0


def test_grappe_2_point_force_closed_form():
    """GRAPPE_2 at mid-span of a pinned mode (slope zero): the force term alone,
    S = ¼c₁³ρ²U³D³ c_D² S_F(fD/U) φ(L/2)² (specep)."""
    tube = pinned_tube(n_grid=2001)
    rho, u, f = 1000.0, 3.0, np.array([10.0, 100.0])
    spec = make_spectrum("GRAPPE_2", GRAPPE_2="DES_CEN", RHO_FLUI=rho, velocity=u, position=L / 2)
    got = spec.modal_spectrum(f, tube)[:, 0, 0]
    c1, cd = 282 / 890, D / 0.089
    s0, frc, beta = GRAPPE_2_COEFFICIENTS["DES_CEN"][0]
    expected = 0.25 * c1**3 * rho**2 * u**3 * D**3 * cd**2 * s0 / (1 + (f * D / u / frc) ** beta)
    np.testing.assert_allclose(got, expected, rtol=1e-9)
    force, moment = grappe_2_spectra("ASC_CEN", [0.19])
    assert force[0] == pytest.approx(1e-4, rel=1e-12)  # passes through S_ref at f_r,ref


def test_grappe_1_mode_equal_to_a_shape_function():
    """A tube whose y-shape on the window is ffgra1's first function (DEBIT_180) and z-shape its
    second: least squares give β = e₁ and e₈ exactly, so S₁₁ = 0.8/(1 + (f/15)^4.6) (specff's
    PLA180 first entry), S₂₂ the same, and the y-z cross term is zero (no correlation between
    the directions); the function spectra carry pha180's phases above the diagonal."""
    from fretwear.flow.grappe1 import function_spectra, shape_functions

    disc, g = shape_functions(180)
    s = disc[:101]
    shapes = np.zeros((101, 2, 2))
    shapes[:, 0, 0] = g[:101, 0]
    shapes[:, 1, 1] = g[101:, 7]
    tube = TubeFlow(s, shapes, D)
    spec = make_spectrum("GRAPPE_1", GRAPPE_1="DEBIT_180", position=0.971 / 2)
    beta = spec.projection(tube)
    np.testing.assert_allclose(beta[:, 0], np.eye(12)[0], atol=1e-9)
    np.testing.assert_allclose(beta[:, 1], np.eye(12)[7], atol=1e-9)
    f = np.array([5.0, 15.0, 40.0])
    got = spec.modal_spectrum(f, tube)
    np.testing.assert_allclose(got[:, 0, 0].real, 0.8 / (1 + (f / 15) ** 4.6), rtol=1e-9)
    np.testing.assert_allclose(got[:, 1, 1].real, 1.3 / (1 + (f / 15) ** 4.6), rtol=1e-9)
    np.testing.assert_allclose(got[:, 0, 1], 0.0, atol=1e-12)
    s6 = function_spectra(180, [50.0, 70.0, 130.0])
    np.testing.assert_allclose(np.angle(s6[:, 0, 2]), [0.0, -np.pi / 2, -np.pi / 4], atol=1e-12)
    with pytest.raises(InputError, match="window"):
        make_spectrum("GRAPPE_1", position=0.2).modal_spectrum(f, tube)
