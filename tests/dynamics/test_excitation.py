"""Excitation signals: harmonic/table evaluation, seeded random signals from a one-sided PSD."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.dynamics import (
    ModalModel,
    NodalForce,
    Shock,
    Signal,
    random_signal_from_psd,
    simulate,
)
from fretwear.errors import InputError, KeywordError


def test_random_signal_reproducible_and_variance():
    # Shinozuka & Deodatis (1991): x = Σ √(2 S(f_k) Δf) cos(2π f_k t + φ_k); over one period
    # the mean square is exactly Σ_k S(f_k) Δf. Flat S = 2 N²/Hz on [5, 45] Hz, T = 20 s,
    # Δf = 0.05 Hz: 801 bins → 2 × 801 × 0.05 = 80.1 N².
    kw = dict(duration=20.0, seed=7)
    t1, x1 = random_signal_from_psd([5.0, 45.0], [2.0, 2.0], **kw)
    t2, x2 = random_signal_from_psd([5.0, 45.0], [2.0, 2.0], **kw)
    _, x3 = random_signal_from_psd([5.0, 45.0], [2.0, 2.0], duration=20.0, seed=8)
    np.testing.assert_array_equal(x1, x2)
    assert not np.allclose(x1, x3)
    assert np.mean(x1[:-1] ** 2) == pytest.approx(80.1, rel=1e-10)
    assert abs(np.mean(x1[:-1])) < 1e-12
    assert t1[-1] == 20.0 and x1[-1] == x1[0]
    # its periodogram sits on the PSD inside the band and vanishes outside (Welch-free check)
    n = x1.size - 1
    spec = np.abs(np.fft.rfft(x1[:-1])) ** 2 * 2 / (n * n) * 20.0  # one-sided S estimate
    f = np.fft.rfftfreq(n, 20.0 / n)
    assert np.allclose(spec[(f >= 5) & (f <= 45)], 2.0, rtol=1e-9)
    assert np.all(spec[(f > 45.5) | (f < 4.5)] < 1e-20)


def test_random_force_gives_reproducible_histories():
    model = ModalModel(frequencies=[12.0], damping_ratios=0.02, masses=1.0,
                       shock_shapes=[[[1.0], [0.0]]], forcing_shapes=[[[1.0], [0.0]]])
    shock = Shock(point=0, obstacle="two_planes", gap=2e-4, normal_stiffness=1e5)

    def run(seed):
        sig = Signal("random", psd_frequencies=[5, 30], psd=[0.5, 0.5], duration=1.0, seed=seed)
        return simulate(model, [shock], [NodalForce(0, "y", sig)], duration=1.0,
                        time_step=5e-5, archive_step=5e-4).history(0)

    a, b, c = run(3), run(3), run(4)
    for ch in a.channels:
        np.testing.assert_array_equal(getattr(a, ch), getattr(b, ch))
    assert not np.array_equal(a.dy, c.dy)


def test_signals_evaluate():
    h = Signal("harmonic", amplitude=3.0, frequency=2.0, phase=90.0)
    assert h.evaluate([0.0, 0.125]) == pytest.approx([3.0, 3 * math.cos(math.pi / 2)], abs=1e-12)
    t = Signal("table", times=[0.0, 1.0, 3.0], values=[0.0, 2.0, -2.0], scale=10.0)
    assert t.evaluate([-1.0, 0.5, 2.0, 9.0]) == pytest.approx([0.0, 10.0, 0.0, -20.0])


def test_tabulated_force_static_response():
    # A slowly ramped force F on one mode of stiffness k = m ω²: quasi-static q = F/k
    # (no contact). Ramp to 50 N over 2 s then hold; ω = 2π·20 rad/s.
    m, f = 2.0, 20.0
    k = m * (2 * math.pi * f) ** 2
    model = ModalModel(frequencies=[f], damping_ratios=0.3, masses=m,
                       shock_shapes=[[[1.0], [0.0]]], forcing_shapes=[[[1.0], [0.0]]])
    sig = Signal("table", times=[0.0, 2.0], values=[0.0, 50.0])
    far = Shock(point=0, obstacle="circle", gap=1.0, normal_stiffness=1.0)
    h = simulate(model, [far], [NodalForce(0, "y", sig)], duration=3.0, time_step=1e-4,
                 archive_step=1e-2).history(0)
    assert h.dy[-1] == pytest.approx(50.0 / k, rel=1e-4)


def test_signal_errors():
    with pytest.raises(KeywordError, match="seed"):
        Signal("random", psd_frequencies=[1, 2], psd=[1, 1], duration=1.0)
    with pytest.raises(InputError, match="Nyquist"):
        random_signal_from_psd([1, 100], [1, 1], duration=1.0, seed=0, sample_rate=150.0)
    with pytest.raises(InputError, match="strictly increasing"):
        Signal("table", times=[0, 1, 1], values=[0, 1, 2])
    with pytest.raises(KeywordError, match="direction"):
        NodalForce(0, "w", Signal("harmonic", amplitude=1.0, frequency=1.0))


def test_random_signal_must_cover_the_run():
    # Beyond its record a table signal stays constant: for a random excitation that would
    # silently turn the end of the run into a static load, so simulate refuses it.
    model = ModalModel(frequencies=[12.0], damping_ratios=0.02, masses=1.0,
                       shock_shapes=[[[1.0], [0.0]]], forcing_shapes=[[[1.0], [0.0]]])
    shock = Shock(point=0, obstacle="circle", gap=1e-3, normal_stiffness=1e5)
    short = Signal("random", psd_frequencies=[5, 30], psd=[0.5, 0.5], duration=0.5, seed=1)
    with pytest.raises(InputError, match=r"excitation 0: .* duration >= 1 s"):
        simulate(model, [shock], [NodalForce(0, "y", short)], duration=1.0, time_step=1e-4)
    # a case file whose duration is not a whole number of archive steps: the run ends at
    # round(0.1006 / 1e-3) = 101 archive steps, 0.101 s, and the record covers it
    from fretwear.dynamics.config import dynamics_from_config

    setup = dynamics_from_config({
        "duration_s": 0.1006, "archive_step_s": 1e-3, "time_step_s": 1e-4,
        "modes": {"frequencies_Hz": [12.0], "damping_ratios": 0.02, "masses_kg": 1.0,
                  "shock_shapes": [[[1.0], [0.0]]], "forcing_shapes": [[[1.0], [0.0]]]},
        "shocks": [{"obstacle": "circle", "gap_m": 1e-3, "normal_stiffness_N_per_m": 1e5}],
        "forces": [{"point": 0, "direction": "y", "kind": "random", "psd_frequencies_Hz": [5, 30],
                    "psd": [0.5, 0.5], "seed": 1}]})
    assert setup.excitations[0].signal.table[0][-1] == pytest.approx(0.101, rel=1e-12)
    r = simulate(setup.model, setup.shocks, setup.excitations, **setup.options)
    assert r.end_time == pytest.approx(0.101, rel=1e-12)
