"""Time signals from a cross-spectral matrix (GENE_FONC_ALEA) against their target.

Sources: the Welch estimator's relative standard error 1/√K for K independent segments
(Bendat & Piersol, *Random Data*, 4th ed., §8.5.4); the mean square of a linear oscillator under
a stationary force, σ² = ∫|H(f)|² S(f) df with H = 1/(k − mω² + icω) (ibid. §6.2), the response
computed by fretwear.dynamics.simulate (an explicit integrator, independent of the synthesis).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate, signal

from fretwear.dynamics import ModalModel, NodalForce, Shock, Signal, simulate
from fretwear.errors import InputError
from fretwear.flow.synthesis import factor_matrices, synthesize


def two_channel(f):
    """A band-limited pair with a complex coherent part: S12 = 0.6·√(S11 S22)·e^{−iπf/100}."""
    s11 = np.where((f >= 20) & (f <= 150), 2.0, 0.0)
    s22 = np.where((f >= 20) & (f <= 150), 0.5 + f / 300.0, 0.0)
    s12 = 0.6 * np.sqrt(s11 * s22) * np.exp(-1j * np.pi * f / 100.0)
    return np.stack([np.stack([s11, s12], -1), np.stack([np.conj(s12), s22], -1)], -2)


def test_first_channel_mean_square_exact_over_the_period():
    """x₁ = Σ_k L₁₁(f_k)√(2Δf) cos(...): its mean square over the period is Σ S₁₁(f_k)Δf exactly
    (the other entries mix independent phases and are only right on average: next test)."""
    f = np.linspace(0.0, 200.0, 2001)
    s = two_channel(f)
    t, x = synthesize(f, s, duration=20.0, seed=7, sample_rate=1000.0)
    fk = np.arange(1, 4000) / 20.0
    target = np.sum(np.interp(fk[fk < 200.0], f, s[:, 0, 0].real)) / 20.0
    assert np.mean(x[:-1, 0] ** 2) == pytest.approx(target, rel=1e-9)


def test_psd_and_cross_psd_within_statistical_error():
    f = np.linspace(0.0, 200.0, 2001)
    s = two_channel(f)
    t, x = synthesize(f, s, duration=400.0, seed=3, sample_rate=800.0)
    nper = 1600  # 2 s segments, 0.5 Hz resolution: K = 200 independent segments (no overlap)
    k = (x.shape[0] - 1) // nper
    fw, p11 = signal.welch(x[:-1, 0], fs=800.0, nperseg=nper, noverlap=0, window="boxcar")
    _, p22 = signal.welch(x[:-1, 1], fs=800.0, nperseg=nper, noverlap=0, window="boxcar")
    _, p12 = signal.csd(x[:-1, 1], x[:-1, 0], fs=800.0, nperseg=nper, noverlap=0,
                        window="boxcar")
    band = (fw > 25) & (fw < 145)
    ref = two_channel(fw[band])
    # relative error of each bin 1/√K; over the n bins of the band the mean relative error has
    # standard error 1/√(K n): 5 of those
    tol = 5.0 / np.sqrt(k * band.sum())
    for got, want in ((p11[band], ref[:, 0, 0].real), (p22[band], ref[:, 1, 1].real)):
        assert np.mean(got / want) == pytest.approx(1.0, abs=tol)
    ratio = p12[band] / ref[:, 0, 1]
    assert np.mean(ratio.real) == pytest.approx(1.0, abs=tol / 0.6)
    assert abs(np.mean(ratio.imag)) < tol / 0.6


def test_seed_reproducible_and_rank_one():
    f = np.array([10.0, 100.0])
    s = np.ones((2, 2, 2))  # fully correlated: no Cholesky, the eigen factor
    _, a = synthesize(f, s, duration=5.0, seed=11)
    _, b = synthesize(f, s, duration=5.0, seed=11)
    np.testing.assert_array_equal(a, b)  # same process, same seed: bit for bit
    np.testing.assert_allclose(a[:, 0], a[:, 1], atol=1e-12 * np.abs(a).max())
    l = factor_matrices(s)
    np.testing.assert_allclose(l[0] @ l[0].conj().T, s[0], atol=1e-12)


def test_bad_matrices_said():
    f = np.array([1.0, 2.0])
    with pytest.raises(InputError, match="Hermitian"):
        synthesize(f, np.array([[[1, 2], [0, 1]]] * 2, float), duration=1, seed=0)
    with pytest.raises(InputError, match="semi-definite"):
        synthesize(f, np.array([[[1, 2], [2, 1]]] * 2, float), duration=1, seed=0)


@pytest.mark.parametrize("direction", ["y", "z"])
def test_linear_oscillator_rms_equals_integral_of_h2_s(direction):
    """A one-mode oscillator (f₀ = 20 Hz, ζ = 5 %, m = 2 kg) under a synthesised force; the
    steady state of the periodic record, integrated by fretwear.dynamics.simulate over its second
    period, has σ² = Σ|H(f_k)|²S(f_k)Δf ≈ ∫|H|²S df (Δf = 0.05 Hz ≪ ζf₀ = 1 Hz). In either
    transverse plane (fretwear simulate loads the z-plane modes along z)."""
    f0, zeta, m = 20.0, 0.05, 2.0
    f = np.linspace(0.0, 100.0, 1001)
    s = np.where((f >= 5) & (f <= 80), 3.0, 0.0)[:, None, None]
    period = 20.0
    t, x = synthesize(f, s, duration=period, seed=5, sample_rate=1000.0)
    times = np.concatenate([t[:-1], t[:-1] + period, [2 * period]])
    values = np.concatenate([x[:-1, 0], x[:-1, 0], x[:1, 0]])
    shape = [[[1.0], [0.0]]] if direction == "y" else [[[0.0], [1.0]]]
    model = ModalModel(frequencies=[f0], damping_ratios=zeta, masses=m,
                       shock_shapes=shape, forcing_shapes=shape)
    far = Shock(point=0, obstacle="plane", gap=1.0, normal_stiffness=1.0)  # never touched
    result = simulate(model, [far], [NodalForce(0, direction, Signal("table", times=times,
                                                                     values=values))],
                      duration=2 * period, time_step=1e-4, archive_step=1e-3)
    h = result.history(0)
    second = h.time >= period
    measured = np.mean(getattr(h, "d" + direction)[second][:-1] ** 2)
    w0 = 2 * np.pi * f0

    def h2(fr):
        w = 2 * np.pi * fr
        return 1.0 / (m**2 * ((w0**2 - w**2) ** 2 + (2 * zeta * w0 * w) ** 2))

    exact, _ = integrate.quad(lambda fr: h2(fr) * 3.0, 5.0, 80.0, points=[f0], limit=200)
    assert measured == pytest.approx(exact, rel=0.02)


def test_code_aster_zzzz180a_standard_deviations():
    """Code_Aster validation case zzzz180a (code_aster repository, astest/zzzz180a.comm;
    GENE_FONC_ALEA, REFERENCE='ANALYTIQUE'): S11 = 2 up to 100 Hz, linear to 0.01 at 200 Hz,
    0.01 to 300 Hz; S22 = 1; S12 = √(0.8 S11) e^{i2πf·0.025}; standard deviations √603 and
    √600. Code_Aster's spectra are two-sided (σ² = 2∫₀^∞ S df): fretwear's one-sided matrix is
    twice them. 70 s of signal as the case's 10 draws of 7 s; its precision 1e-3 on both (the
    first channel is exact over the period here, the second mixes two phases per bin: 1e-2)."""
    f = np.arange(0.0, 300.2, 0.2)
    c11 = np.where(f <= 100, 2.0, np.where(f <= 200, (1e-2 - 2.0) * f / 100 + 4.0 - 1e-2, 1e-2))
    c12 = np.sqrt(0.8 * c11) * np.exp(1j * 2 * np.pi * f * 0.025)
    aster = np.stack([np.stack([c11, c12], -1), np.stack([np.conj(c12), np.ones_like(f)], -1)],
                     -2)
    t, x = synthesize(f, 2.0 * aster, duration=70.0, seed=180, sample_rate=1000.0)
    std = x[:-1].std(axis=0)
    assert std[0] == pytest.approx(np.sqrt(603.0), rel=1e-3)
    assert std[1] == pytest.approx(np.sqrt(600.0), rel=1e-2)
