"""Modal model and uniform-beam modes against closed forms (Blevins 1979, Table 8-1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.dynamics.modal import ModalModel, beam_eigenvalues, uniform_beam_modes
from fretwear.errors import InputError, KeywordError

E, I, RA, L = 2.0e11, 2.0e-9, 0.8, 1.2  # steel tube-like beam [Pa, m^4, kg/m, m]
C = math.sqrt(E * I / RA)


def test_eigenvalues_blevins_table_8_1():
    # Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1 (λ_i = β_i L).
    assert beam_eigenvalues(("clamped", "free"), 3) == pytest.approx(
        [1.87510407, 4.69409113, 7.85475744], rel=1e-8)
    assert beam_eigenvalues(("clamped", "clamped"), 3) == pytest.approx(
        [4.73004074, 7.85320462, 10.9956078], rel=1e-8)
    assert beam_eigenvalues(("clamped", "pinned"), 2) == pytest.approx(
        [3.92660231, 7.06858275], rel=1e-8)
    assert beam_eigenvalues(("pinned", "pinned"), 2) == pytest.approx([math.pi, 2 * math.pi])


def test_pinned_pinned_frequencies_masses_participation():
    # f_n = (nπ)²/(2π L²)·√(EI/ρA); φ = sin(nπx/L): modal mass ρAL/2, Γ_1 = 2ρAL/π.
    m = uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=3, shock_positions=[L / 2, L / 4])
    f = np.array([(n * math.pi) ** 2 / (2 * math.pi * L**2) * C for n in (1, 2, 3)])
    assert m.frequencies[:3] == pytest.approx(f, rel=1e-12)
    assert m.frequencies[3:] == pytest.approx(f, rel=1e-12)  # z plane
    assert m.masses[0] == pytest.approx(RA * L / 2, rel=1e-6)
    assert m.participation[0, 0] == pytest.approx(2 * RA * L / math.pi, rel=1e-6)
    assert m.participation[1, 0] == 0.0 and m.participation[1, 3] == pytest.approx(
        2 * RA * L / math.pi, rel=1e-6)
    # shapes: sin(π/2) = 1 in y for mode 1, sin(π/4) at L/4; z component zero for y modes
    assert m.shock_shapes[0, 0, 0] == pytest.approx(1.0)
    assert m.shock_shapes[1, 0, 0] == pytest.approx(math.sin(math.pi / 4))
    assert m.shock_shapes[0, 1, 0] == 0.0 and m.shock_shapes[0, 1, 3] == pytest.approx(1.0)


@pytest.mark.parametrize("ends", [("clamped", "clamped"), ("clamped", "free"),
                                  ("clamped", "pinned"), ("pinned", "pinned")])
def test_fe_matches_analytic(ends):
    # Independent computations: FE eigen-solve vs the characteristic-equation roots.
    kw = dict(young_modulus=E, second_moment=I, mass_per_length=RA, length=L, n_modes=4,
              shock_positions=[0.3, 0.9], ends=ends)
    a = uniform_beam_modes(method="analytic", **kw)
    f = uniform_beam_modes(method="fe", n_elements=120, **kw)
    assert f.frequencies == pytest.approx(a.frequencies, rel=1e-6)
    assert f.masses == pytest.approx(a.masses, rel=1e-4)
    # same shapes up to sign at the shock points
    sa, sf = a.shock_shapes[:, 0, :4], f.shock_shapes[:, 0, :4]
    sign = np.sign(np.sum(sa * sf, axis=0))
    assert sf * sign == pytest.approx(sa, abs=1e-5)


def test_intermediate_support_two_equal_spans():
    # Pinned-pinned beam with a pinned support at mid-span: the first mode is that of one
    # pinned-pinned span of length L/2 (antisymmetric mode, Blevins Table 8-2), f = 4 f_1(L).
    m = uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=2, shock_positions=[L / 4], supports=[L / 2])
    f1 = math.pi**2 / (2 * math.pi * L**2) * C
    assert m.frequencies[0] == pytest.approx(4 * f1, rel=1e-6)
    # second mode: one span clamped-pinned (λ = 3.9266 on L/2), symmetric mode of the pair
    f2 = 3.92660231**2 / (2 * math.pi * (L / 2) ** 2) * C
    assert m.frequencies[1] == pytest.approx(f2, rel=1e-6)
    assert m.metadata["beam"]["method"] == "fe"


def test_free_free_keeps_rigid_modes():
    m = uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=3, shock_positions=[0.0], ends=("free", "free"))
    # two rigid-body modes (translation, rotation) then λ = 4.73004 (Blevins Table 8-1)
    assert m.frequencies[:2] == pytest.approx([0.0, 0.0], abs=1e-9)
    assert m.frequencies[2] == pytest.approx(4.73004074**2 / (2 * math.pi * L**2) * C, rel=1e-6)


def test_modal_model_errors():
    with pytest.raises(InputError, match="masses"):
        ModalModel(frequencies=[1.0, 2.0], damping_ratios=0.0, masses=[1.0, 2.0, 3.0],
                   shock_shapes=np.zeros((1, 2, 2)))
    with pytest.raises(InputError, match="shock_shapes"):
        ModalModel(frequencies=[1.0], damping_ratios=0.0, masses=1.0, shock_shapes=[1.0])
    with pytest.raises(InputError, match="damping_ratios"):
        ModalModel(frequencies=[1.0], damping_ratios=1.5, masses=1.0,
                   shock_shapes=np.zeros((1, 2, 1)))
    with pytest.raises(KeywordError, match="ends"):
        uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=1, shock_positions=[0.1], ends=("welded", "pinned"))
    with pytest.raises(InputError, match="supports"):
        uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=1, shock_positions=[0.1], supports=[2.0])
    with pytest.raises(InputError, match="n_modes"):
        uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=0, shock_positions=[0.1])
    with pytest.raises(InputError, match="n_elements"):
        uniform_beam_modes(young_modulus=E, second_moment=I, mass_per_length=RA, length=L,
                           n_modes=4, shock_positions=[0.1], method="fe", n_elements=3)
    with pytest.raises(KeywordError, match="unknown shock point"):
        ModalModel(frequencies=[1.0], damping_ratios=0.0, masses=1.0,
                   shock_shapes=np.zeros((1, 2, 1))).shock_index("AVB9")
