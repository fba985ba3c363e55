"""Shock definitions: obstacle geometry (gap in a direction), offsets, preload, input errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.dynamics import ModalModel, Shock, circle_profile, simulate
from fretwear.errors import InputError, KeywordError


def test_gap_in_a_direction():
    # plane at g along 30°: distance along direction φ is g/cos(φ − 30°) (inf when moving away)
    p = Shock(point=0, obstacle="plane", gap=1e-3, angle=30.0, normal_stiffness=1.0)
    assert p.gap_at([30.0, 90.0]) == pytest.approx([1e-3, 1e-3 / math.cos(math.radians(60))])
    assert np.isinf(p.gap_at(210.0))
    two = Shock(point=0, obstacle="two_planes", gap=1e-3, angle=0.0, normal_stiffness=1.0)
    assert two.gap_at([0.0, 180.0, 45.0]) == pytest.approx([1e-3, 1e-3, 1e-3 * math.sqrt(2)])
    # 721-point circle: between vertices the chord is inside the circle by g(1 − cos 0.25°)
    a, g = circle_profile(5e-4)
    prof = Shock(point=0, obstacle="profile", profile_angles=a, profile_gaps=g,
                 normal_stiffness=1.0)
    assert prof.gap_at([0.0, 90.5]) == pytest.approx([5e-4, 5e-4], rel=1e-12)
    assert prof.gap_at(0.25)[()] == pytest.approx(5e-4 * math.cos(math.radians(0.25)), rel=1e-12)


def test_origin_and_preload_static_equilibrium():
    # A mass on a soft mode k_m pushed by a preload P into a plane at gap g, obstacle centre
    # shifted by o along the normal: static balance P = k_m x + k_n (x − g − o) once in contact.
    m, km, kn, g, o, pre = 1.0, 1e3, 1e5, 1e-3, 5e-4, 10.0
    model = ModalModel(frequencies=[math.sqrt(km / m) / (2 * math.pi)], damping_ratios=0.5,
                       masses=m, shock_shapes=[[[1.0], [0.0]]])
    s = Shock(point=0, obstacle="plane", gap=g, origin=(o, 0.0), normal_stiffness=kn,
              normal_damping=2 * math.sqrt(kn * m), preload=pre)
    r = simulate(model, [s], duration=1.0, time_step=5e-5, archive_step=1e-3)
    x = (pre + kn * (g + o)) / (km + kn)
    h = r.history(0)
    assert h.dy[-1] + o == pytest.approx(x, rel=1e-6)  # dy is measured from the obstacle centre
    assert h.normal_force[-1] == pytest.approx(kn * (x - g - o), rel=1e-5)
    assert r.energy["preload_work"] > 0


def test_shock_errors():
    with pytest.raises(KeywordError, match="unknown obstacle"):
        Shock(point=0, obstacle="cone", normal_stiffness=1.0)
    with pytest.raises(InputError, match="tangential_stiffness"):
        Shock(point=0, obstacle="circle", gap=1e-4, normal_stiffness=1.0, friction=0.3)
    with pytest.raises(InputError, match="normal_stiffness"):
        Shock(point=0, obstacle="circle", gap=1e-4, normal_stiffness=0.0)
    with pytest.raises(KeywordError, match="profile_angles"):
        Shock(point=0, obstacle="profile", normal_stiffness=1.0)
    with pytest.raises(InputError, match="row 1"):
        Shock(point=0, obstacle="profile", normal_stiffness=1.0, profile_angles=[0, 90, 180],
              profile_gaps=[1e-4, 0.0, 1e-4])
    with pytest.raises(InputError, match="gap"):
        Shock(point=0, obstacle="circle", gap=-1e-4, normal_stiffness=1.0)


# ----------------------------------------------------------------- Code_Aster's DIS_CHOC defaults
# Code_Aster's validation test SDND100A (astest/sdnd100a.comm): one degree of freedom (M = 1 kg,
# K = 1e4 N/m, no modal damping) sliding along the diagonal of a plane PLAN_Z pressed with
# Fn = RIGI_NOR·(1 − JEU) = 20·0.5 = 10 N = M·G, COULOMB = 0.1, RIGI_TAN = 4e5 N/m, no AMOR_TAN,
# DIFF_CENTRE with PAS = 5e-4 s, U0 = 0.85e-3 m. Analytic (Coulomb-damped oscillator, C = μMG/K):
# DY(kπ/ω) = ±(U0 − 2kC)·cos 45°, the VALE_REFE of its TEST_RESU with PRECISION 1e-3, 1e-3, 1e-3,
# 5e-3.
SDND100A_REFE = [-4.596e-4, 3.182e-4, -1.768e-4, 3.536e-05]
SDND100A_PRECISION = [1e-3, 1e-3, 1e-3, 5e-3]


def _sdnd100a(tangential_damping):
    w0 = 100.0  # √(K/M) [rad/s]
    model = ModalModel(frequencies=[w0 / (2 * math.pi)], damping_ratios=0.0, masses=1.0,
                       shock_shapes=[[[1.0], [0.0]]])
    # DYNA_VIBRA(..., COMPORTEMENT=_F(RELATION='DIS_CHOC', OBSTACLE=PLANZ, JEU=0.5,
    #            RIGI_NOR=20., RIGI_TAN=400000., FROTTEMENT='COULOMB', COULOMB=0.1))
    shock = Shock(point=0, obstacle="plane", angle=90.0, gap=-0.5, normal_stiffness=20.0,
                  tangential_stiffness=4e5, friction=0.1, tangential_damping=tangential_damping)
    result = simulate(model, [shock], duration=0.3, time_step=5e-4, archive_step=5e-4,
                      initial_displacement=[0.85e-3])
    h = result.history(0)
    instants = [k * math.pi / w0 for k in (1, 2, 3, 4)]
    dy = np.interp(instants, h.time, h.dy) * math.cos(math.pi / 4)  # INTERPOL='LIN', DY
    return np.abs(dy - SDND100A_REFE) / np.abs(SDND100A_REFE), h


def test_code_aster_tangential_damping_passes_sdnd100a():
    # AMOR_TAN absent: dtmprep_noli_choc's c_t = 2√(m(k + k_t)) − 2ξ√(km) = 2√4.1e5
    errors, h = _sdnd100a(None)
    assert h.metadata["tangential_damping"] == pytest.approx(2 * math.sqrt(4.1e5), rel=1e-14)
    assert np.all(errors < SDND100A_PRECISION), errors
    # with no tangential damping the stuck phases ring on the tangential spring: SDND100A's last
    # check misses its 0.5 % tolerance (by about 4 %)
    errors0, _ = _sdnd100a(0.0)
    assert errors0[3] > 0.03


def test_code_aster_tangential_damping_cases():
    from fretwear.dynamics.shocks import code_aster_tangential_damping

    # two modes: the one moving the point most along the plane's tangent (y for a plane of
    # normal z) decides; its effective mass m_r/φ² and damping ratio enter
    model = ModalModel(frequencies=[10.0, 50.0], damping_ratios=[0.02, 0.05], masses=[2.0, 3.0],
                       shock_shapes=[[[0.1, 2.0], [1.0, 0.0]]])
    s = Shock(point=0, obstacle="plane", angle=90.0, normal_stiffness=1e5,
              tangential_stiffness=1e6, friction=0.2)
    m = 3.0 / 2.0**2
    k = (2 * math.pi * 50.0) ** 2 * m
    expected = 2 * math.sqrt(m * (k + 1e6)) - 2 * 0.05 * math.sqrt(k * m)
    assert code_aster_tangential_damping(model, s) == pytest.approx(expected, rel=1e-14)
    # normalisation of the modes does not matter (mode 2 scaled by 10: mass ×100)
    scaled = ModalModel(frequencies=[10.0, 50.0], damping_ratios=[0.02, 0.05],
                        masses=[2.0, 300.0], shock_shapes=[[[0.1, 20.0], [1.0, 0.0]]])
    assert code_aster_tangential_damping(scaled, s) == pytest.approx(expected, rel=1e-14)
    # no tangential stiffness: 0 (Code_Aster leaves AMOR_TAN at 0)
    assert code_aster_tangential_damping(model, Shock(point=0, obstacle="plane",
                                                      normal_stiffness=1.0)) == 0.0


def test_static_and_dynamic_friction():
    """COULOMB_STAT / COULOMB_DYNA: a spring force between μ_d·Fn and μ_s·Fn does not break the
    contact free; once free, the block slides at μ_d·Fn (Coulomb-damped oscillator, amplitude
    decrement 2μ_d·Fn/K per half period)."""
    w0, fn = 100.0, 10.0
    model = ModalModel(frequencies=[w0 / (2 * math.pi)], damping_ratios=0.0, masses=1.0,
                       shock_shapes=[[[1.0], [0.0]]])

    def run(u0, **friction):
        shock = Shock(point=0, obstacle="plane", angle=90.0, gap=-0.5, normal_stiffness=2 * fn,
                      tangential_stiffness=4e7, tangential_damping=None, **friction)
        r = simulate(model, [shock], duration=0.05, time_step=2e-5, archive_step=2e-5,
                     initial_displacement=[u0])
        return r.history(0)

    # K·U0 = 1.2 N: held by μ_s·Fn = 1.5 N (only the tangential spring's 1.2/4e7 m gives way)
    held = run(1.2e-4, friction=0.1, static_friction=0.15)
    assert np.max(np.abs(held.dy - 1.2e-4)) < 1e-7 and held.stick[1:].min() == 1.0
    # one coefficient 0.1: the same spring force slides (1.2 N > 1 N)
    assert np.min(run(1.2e-4, friction=0.1).dy) < 1.0e-4
    # K·U0 = 3 N breaks free, slides at μ_d = 0.1: at π/ω the block is at −(U0 − 2μ_d·Fn/K)
    free = run(3e-4, friction=0.1, static_friction=0.15)
    at = float(np.interp(math.pi / w0, free.time, free.dy))
    assert at == pytest.approx(-(3e-4 - 2 * 0.1 * fn / 1e4), rel=0.01)
    # then held for good: 1 N < μ_s·Fn
    assert np.ptp(free.dy[free.time > 1.2 * math.pi / w0]) < 1e-7


def test_static_friction_errors_and_config():
    with pytest.raises(InputError, match="'static_friction' must be >= 0"):
        Shock(point=0, obstacle="plane", normal_stiffness=1.0, tangential_stiffness=1.0,
              friction=0.1, static_friction=-0.1)
    s = Shock(point=0, obstacle="plane", normal_stiffness=1.0, tangential_stiffness=1.0,
              friction=0.1)
    assert s.static_friction == 0.1
    from fretwear.dynamics.config import dynamics_from_config

    section = {"duration_s": 0.01,
               "modes": {"frequencies_Hz": [15.0], "damping_ratios": 0.0, "masses_kg": 1.0,
                         "shock_shapes": [[[1.0], [0.0]]]},
               "shocks": [{"obstacle": "plane", "normal_stiffness_N_per_m": 20.0,
                           "tangential_stiffness_N_per_m": 4e5, "friction": 0.1,
                           "static_friction": 0.15}]}
    setup = dynamics_from_config(section)
    shock = setup.shocks[0]
    # AMOR_TAN absent in the case file: Code_Aster's default, resolved by simulate
    assert shock.tangential_damping is None and shock.static_friction == 0.15
    section["shocks"][0]["tangential_damping_N_s_per_m"] = 0.0
    assert dynamics_from_config(section).shocks[0].tangential_damping == 0.0
