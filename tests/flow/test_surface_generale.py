"""GENERALE integrated on the tube's surface (Code_Aster's accept.F90 with coegen: the coherence
e^{−d/L} cos(ωd/U_c) of the distance d in space between two points of the interface).

Checks:
- against the four-fold integral reduced exactly to a double integral over the two separations
  (Δs, Δθ) for a pinned mode (closed-form autocorrelations of the mode along and around, below),
  evaluated by scipy's adaptive dblquad: an independent evaluation, to the sums' error;
- the closed-form limit L → ∞ at f → 0: the pressure is the same all around, which gives no
  force: S → 0 against (∬|w| dA)².
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

from fretwear.errors import InputError
from fretwear.flow.spectra import make_spectrum
from fretwear.flow.surface import generale_surface_coherence
from fretwear.flow.tube import TubeFlow

R, SPAN, LC = 0.01, 0.01, 1e-3   # [m] radius, span, a correlation length L
U = 10.0                          # [m/s]: U_c = 6.5 m/s


def pinned(points=21):
    s = np.linspace(0.0, SPAN, points)
    shapes = np.zeros((points, 2, 1))
    shapes[:, 0, 0] = np.sin(np.pi * s / SPAN)
    return TubeFlow(s, shapes, 2 * R, U, 1000.0)


def spectrum(length, points=126):
    return make_spectrum("SPEC_CORR_CONV_2", function=lambda w: np.ones_like(w), velocity=U,
                         long_cor_1=length, circumferential_points=points)


def reduced(length, kl):
    """The four-fold surface integral for the pinned y-mode reduced exactly to two separations:
    with φ = sin(πs/S) and w = φ cos θ, ∬ φ(s₁)φ(s₂) g(s₁ − s₂) ds₁ds₂ = ∫ A(Δs) g(Δs) dΔs,
    A(Δs) = ((S − |Δs|)/2) cos(πΔs/S) + (S/2π) sin(π|Δs|/S), and over the full circle
    ∬ cos θ₁ cos θ₂ h(θ₁ − θ₂) dθ₁dθ₂ = ∫ π cos Δθ h(Δθ) dΔθ; the kernel is even in both, so
    S_Q = 4πR² ∫₀^S ∫₀^π A cos Δθ C dΔθ dΔs, by scipy's adaptive dblquad (the cusp of C at
    the origin a corner of the domain)."""
    k = kl / length

    def integrand(dth, ds):
        a = (SPAN - ds) / 2 * np.cos(np.pi * ds / SPAN) + SPAN / (2 * np.pi) * np.sin(
            np.pi * ds / SPAN)
        d = np.hypot(ds, 2 * R * np.sin(dth / 2))
        return a * np.cos(dth) * np.exp(-d / length) * np.cos(k * d)

    value, _ = integrate.dblquad(integrand, 0.0, SPAN, 0.0, np.pi, epsabs=0, epsrel=1e-8)
    return 4 * np.pi * R**2 * value


@pytest.mark.parametrize("kl", [0.0, 0.5])
def test_surface_sum_matches_the_integral_reduced_to_two_separations(kl):
    """21 points along and 126 around (h = 0.5 mm = L/4): the sums' error on the kernel's cusp
    is about (h/L)²/12 = 0.5 % per direction (measured: 0.1 %, falling with h)."""
    length = 2e-3
    tube = pinned()
    f = max(kl / length * 0.65 * U / (2 * np.pi), 1e-9)   # k = ω/U_c
    got = spectrum(length).modal_spectrum([f], tube)[0, 0, 0]
    assert got == pytest.approx(reduced(length, kl), rel=0.01)


def test_a_pressure_correlated_all_around_gives_no_force():
    tube = pinned()
    got = spectrum(100.0, points=32).modal_spectrum([1e-9], tube)[0, 0, 0]
    full = (np.trapezoid(tube.shapes[:, 0, 0], tube.positions) * 4 * R) ** 2  # (∬|w| dA)²
    assert abs(got) < 1e-3 * full


def test_coherence_uses_the_distance_in_space():
    c = generale_surface_coherence(0.03, 0.5, 0.0, -0.5, 0.0, radius=R, velocity=U,
                                   length=0.02)
    d = np.hypot(0.03, 2 * R * np.sin(0.5))
    assert float(c) == pytest.approx(np.exp(-d / 0.02), rel=1e-14)


def test_corcos_on_the_surface_is_refused():
    with pytest.raises(InputError, match="circumferential_points integrates GENERALE"):
        make_spectrum("SPEC_CORR_CONV_2", function=lambda w: np.ones_like(w), velocity=U,
                      long_cor_1=LC, method="CORCOS",
                      circumferential_points=8).modal_spectrum([10.0], pinned())
