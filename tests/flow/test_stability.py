"""Fluid-elastic stability: Connors' critical velocity and the mode-weighted effective velocity.

Sources: Connors (1970), U_c = K f D √(2πζ m/(ρD²)); the effective velocity of ASME III App. N-1330
(Pettigrew et al. 1978), U_eff² = ∫(ρ/ρ₀)U²φ² / ∫(m/m₀)φ²; closed forms for a pinned-pinned mode
sin(πs/L) in flow over [0, a]: ∫₀ᵃ sin² = a/2 − L sin(2πa/L)/(4π).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.dynamics import ModalModel
from fretwear.errors import InputError
from fretwear.flow import TubeFlow, beam_tube_flow
from fretwear.flow.stability import connors_velocity, effective_values, stability_ratios

L, D = 1.0, 0.019


def test_connors_closed_form():
    f, zeta, m, rho, k = 40.0, 0.02, 0.9, 750.0, 3.0
    expected = k * f * D * math.sqrt(2 * math.pi * zeta * m / (rho * D * D))
    assert float(connors_velocity(f, zeta, D, m, rho, k)) == pytest.approx(expected, rel=1e-14)
    with pytest.raises(InputError, match="constant"):
        connors_velocity(f, zeta, D, m, rho, 0.0)


def test_effective_velocity_partial_span():
    s = np.linspace(0, L, 4001)
    a = 0.3 * L
    tube = TubeFlow(s, np.sin(np.pi * s / L)[:, None, None] * [[1.0], [0.0]], D,
                    velocity=np.where(s <= a + 1e-12, 2.0, 0.0), density=1000.0)
    u, norm = effective_values(tube, 1.0, 1000.0, 1.0)
    part = a / 2 - L * math.sin(2 * math.pi * a / L) / (4 * math.pi)
    assert u[0] == pytest.approx(2.0 * math.sqrt(part / (L / 2)), rel=2e-3)
    assert norm[0] == pytest.approx(L / 2, rel=1e-6)


def test_ratio_uniform_flow_and_independent_of_references():
    model, tube = beam_tube_flow(young_modulus=2e11, second_moment=2.5e-9, mass_per_length=0.9,
                                 length=L, n_modes=2, shock_positions=[0.5], diameter=D,
                                 velocity=1.5, density=800.0, damping_ratio=0.015)
    r = stability_ratios(model, tube, mass_per_length=0.9, constant=3.0, margin=0.8)
    other = stability_ratios(model, tube, mass_per_length=0.9, constant=3.0, margin=0.8,
                             reference_density=1.0, reference_mass=123.0)
    np.testing.assert_allclose(r["stability_ratio"], other["stability_ratio"], rtol=1e-12)
    # uniform flow: U_eff = U; the lowest mode is the most critical
    np.testing.assert_allclose(r["effective_velocity_m_s"], 1.5, rtol=1e-9)
    first = r.iloc[0]
    uc = 3.0 * first["frequency_hz"] * D * math.sqrt(2 * math.pi * 0.015 * 0.9 / (800 * D * D))
    assert first["stability_ratio"] == pytest.approx(1.5 / uc, rel=1e-9)
    assert first["frequency_hz"] == pytest.approx(model.frequencies.min())
    assert list(r["flagged"]) == list(r["stability_ratio"] > 0.8)


def test_mode_count_mismatch_said():
    _, tube = beam_tube_flow(young_modulus=2e11, second_moment=2.5e-9, mass_per_length=0.9,
                             length=L, n_modes=2, shock_positions=[0.5], diameter=D, velocity=1.0)
    one = ModalModel(frequencies=[10.0], damping_ratios=0.01, masses=1.0,
                     shock_shapes=[[[1.0], [0.0]]])
    with pytest.raises(InputError, match="modes"):
        stability_ratios(one, tube, mass_per_length=0.9, constant=3.0)
