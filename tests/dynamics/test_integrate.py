"""Built-in dynamics against closed-form solutions.

Sources: free vibration and logarithmic decrement (S. S. Rao, *Mechanical Vibrations*, 5th ed.,
§2.6.4); restitution of a linear spring-dashpot contact without attractive force (T. Schwager,
T. Pöschel, "Coefficient of restitution and linear-dashpot model revisited", *Granular Matter* 9,
2007, 465-469); Coulomb friction under harmonic base motion (J. P. Den Hartog, "Forced vibrations
with combined Coulomb and viscous friction", *Trans. ASME* 53, 1931, 107-115; derivation below);
stability of central difference (Belytschko, Liu, Moran 2000, §6.3).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.dynamics import (
    BaseAcceleration,
    ModalModel,
    NodalForce,
    Shock,
    Signal,
    circle_profile,
    simulate,
    stability_limit,
)
from fretwear.errors import StabilityError


def one_mode(f=0.0, zeta=0.0, mass=1.0):
    return ModalModel(frequencies=[f], damping_ratios=zeta, masses=mass,
                      shock_shapes=[[[1.0], [0.0]]])


def test_free_vibration_frequency_and_log_decrement():
    # Rao §2.6.4: x(t) = X e^{-ζωt} cos(ω_d t), ω_d = ω√(1-ζ²); δ = ln(x_n/x_{n+1}) = 2πζ/√(1-ζ²).
    f, zeta = 5.0, 0.02
    m = one_mode(f, zeta, 3.0)
    far = Shock(point=0, obstacle="circle", gap=1.0, normal_stiffness=1e3)
    r = simulate(m, [far], duration=2.0, time_step=1e-4, initial_displacement=[1e-3])
    h = r.history(0)
    x, t = h.dy, h.time
    i = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1  # maxima
    # parabolic refinement of each maximum
    a, b, c = x[i - 1], x[i], x[i + 1]
    off = 0.5 * (a - c) / (a - 2 * b + c)
    peak = b - 0.25 * (a - c) * off
    tp = t[i] + off * (t[1] - t[0])
    fd = 1.0 / np.mean(np.diff(tp))
    delta = np.mean(np.log(peak[:-1] / peak[1:]))
    assert fd == pytest.approx(f * math.sqrt(1 - zeta**2), rel=1e-5)
    assert delta == pytest.approx(2 * math.pi * zeta / math.sqrt(1 - zeta**2), rel=1e-4)
    assert np.all(h.normal_force == 0.0) and np.all(h.stick == 0.0)


@pytest.mark.parametrize("zeta", [0.05, 0.3])
def test_impact_restitution_schwager_poschel(zeta):
    # Mass m hits a plane at v0; contact force F = max(0, kδ + cδ̇), δ(0) = 0, δ̇(0) = v0:
    # δ = (v0/ω) e^{−βt} sin ωt with ω0² = k/m, β = c/2m, ω² = ω0² − β². Schwager & Pöschel
    # (2007): the contact ends when F = 0, i.e. tan ω t_e = −2βω/(ω² − β²), so
    # ω t_e = π − atan(2βω/(ω² − β²)) and e = −δ̇(t_e)/v0 = −e^{−βt_e}(cos ωt_e − (β/ω) sin ωt_e).
    # The classical e = exp(−ζπ/√(1−ζ²)) holds only if the dashpot may pull (contact to δ = 0).
    m, k, v0 = 2.0, 1e6, 0.5
    c = 2 * zeta * math.sqrt(k * m)
    w0, beta = math.sqrt(k / m), c / (2 * m)
    w = math.sqrt(w0**2 - beta**2)
    te = (math.pi - math.atan2(2 * beta * w, w**2 - beta**2)) / w
    e_sp = -math.exp(-beta * te) * (math.cos(w * te) - beta / w * math.sin(w * te))
    e_classic = math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))
    s = Shock(point=0, obstacle="plane", gap=1e-4, normal_stiffness=k, normal_damping=c)
    r = simulate(one_mode(mass=m), [s], duration=8e-3, time_step=2e-7, archive_step=1e-5,
                 initial_velocity=[v0])
    e = -r.final_velocity[0] / v0
    assert e == pytest.approx(e_sp, rel=2e-4)
    if zeta > 0.1:
        assert abs(e - e_classic) > 0.05  # the no-pull rule matters
    h = r.history(0)
    assert h.normal_force.min() == 0.0 and h.normal_force.max() > 0
    # energy: ½ m v0² (1 − e²) dissipated in the contact dashpot
    assert r.energy["contact_damping_dissipation"] == pytest.approx(
        0.5 * m * v0**2 * (1 - e_sp**2), rel=1e-3)


def _friction_case(amplitude, *, kt=1e9, duration=0.5, h=5e-6, steady=True):
    """Mass m pressed by N on a plane (normal y), base moving along z with a = A sin ωt."""
    m, n_force, mu, kn, f = 1.0, 10.0, 0.3, 1e6, 10.0
    w = 2 * math.pi * f
    r = mu * n_force / (m * amplitude)
    xd0 = 0.0
    if steady:
        phi0 = math.acos(r * math.pi / 2)
        xd0 = amplitude / w * (math.cos(phi0) + 1 - r * (math.pi - phi0))
    model = ModalModel(frequencies=[0.0, 0.0], damping_ratios=0.0, masses=m,
                       shock_shapes=[[[1.0, 0.0], [0.0, 1.0]]],
                       participation=[[m, 0.0], [0.0, m]])
    shock = Shock(point=0, obstacle="plane", gap=0.0, angle=0.0, normal_stiffness=kn,
                  normal_damping=math.sqrt(kn * m), tangential_stiffness=kt,
                  tangential_damping=0.4 * math.sqrt(kt * m), friction=mu, preload=n_force)
    base = BaseAcceleration("z", Signal("harmonic", amplitude=amplitude, frequency=f))
    res = simulate(model, [shock], [base], duration=duration, time_step=h, archive_step=2e-5,
                   initial_displacement=[n_force / kn, 0.0], initial_velocity=[0.0, xd0])
    return res, n_force, mu, m, w


def _power(h):
    """Theory §2 wear power of a history, computed here independently (trapezoid, stick rule)."""
    p = h.normal_force * np.hypot(h.vt1, h.vt2)
    dt = np.diff(h.time)
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * dt * (h.stick[:-1] == 0)) / h.duration)


def test_coulomb_base_excitation_sliding_closed_form():
    # Relative motion x of the mass: ẍ = −A sin ωt − (μN/m) sgn ẋ; with y = −x and r = μN/(mA),
    # ÿ = A sin φ − rA sgn ẏ (φ = ωt). On the half period (φ0, φ0 + π) where ẏ > 0:
    # ẏ = (A/ω)(cos φ0 − cos φ − r(φ − φ0)); ẏ(φ0 + π) = 0 gives cos φ0 = πr/2, and
    # mean|ẏ| = (1/π)∫ẏ dφ = (2A/(πω)) sin φ0. The mass never stops while sin φ0 > r, i.e.
    # r < 1/√(1 + π²/4) ≈ 0.537 (Den Hartog 1931). Fn = N throughout, so the theory §2 wear power is
    # P = N·(2A/(πω))·√(1 − (πr/2)²). The run starts on this steady state: ẋ(0) = −ẏ(0).
    res, n_force, mu, m, w = _friction_case(10.0)
    amp = 10.0
    r = mu * n_force / (m * amp)
    p_exact = n_force * 2 * amp / (math.pi * w) * math.sqrt(1 - (math.pi * r / 2) ** 2)
    # regularisation: the stick spring k_t shifts P by O(√(μN/(k_t m A))); 0.1 % at k_t = 1e9
    assert res.wear_power[0] == pytest.approx(p_exact, rel=3e-3)
    assert _power(res.history(0)) == pytest.approx(p_exact, rel=3e-3)
    from fretwear.power import wear_power  # the library's theory §2 implementation agrees

    assert wear_power(res.history(0)).total == pytest.approx(_power(res.history(0)), rel=1e-9)
    h = res.history(0)
    assert h.normal_force == pytest.approx(np.full(len(h), n_force), rel=1e-9)
    assert np.max(np.abs(h.ft1)) == pytest.approx(mu * n_force, rel=1e-12)  # on the cone
    assert h.stick.mean() < 0.01


def test_coulomb_base_excitation_sticks_below_threshold():
    # Base displacement amplitude A/ω² below μN/(mω²): friction carries the mass, no sliding,
    # the stick flag is 1 and the wear power is exactly 0 (theory §2 stick rule).
    res, n_force, mu, m, w = _friction_case(2.0, kt=1e8, steady=False, duration=0.3, h=1e-5)
    h = res.history(0)
    assert np.all(h.stick[1:] == 1.0)
    assert res.wear_power[0] == 0.0 and _power(h) == 0.0
    assert np.max(np.abs(h.ft1)) == pytest.approx(m * 2.0, rel=1e-2)  # F = m·a_base


@pytest.mark.parametrize("friction, steps, min_ratio", [(0.0, (4e-5, 2e-5), 3.0),
                                                       (0.25, (8e-5, 2e-5), 8.0)])
def test_energy_balance_second_order(friction, steps, min_ratio):
    # Input work = dissipated + stored, from independent accumulators (external work, modal and
    # contact damping, friction work, stored energies at both ends). The scheme is second order:
    # the residual falls as h² (4x per halving without friction; stick/slip switches make it
    # irregular with friction, so there over a 4x step change, expecting ~16x).
    model = ModalModel(frequencies=[8.0, 23.0], damping_ratios=[0.02, 0.01], masses=[1.5, 0.7],
                       shock_shapes=[[[1.0, 0.6], [0.4, -0.8]]],
                       forcing_shapes=[[[1.0, 0.5], [0.0, 1.0]]])
    shock = Shock(point=0, obstacle="circle", gap=2e-4, normal_stiffness=2e5,
                  normal_damping=40.0, tangential_stiffness=2e5 if friction else 0.0,
                  friction=friction)
    loads = [NodalForce(0, "y", Signal("harmonic", amplitude=20.0, frequency=8.5)),
             NodalForce(0, "z", Signal("harmonic", amplitude=15.0, frequency=8.5, phase=80))]
    residual = []
    for h in steps:
        res = simulate(model, [shock], loads, duration=0.5, time_step=h, archive_step=8e-4)
        e = res.energy
        assert e["external_work"] > 0 and e["modal_damping_dissipation"] > 0
        assert e["contact_damping_dissipation"] > 0
        assert (e["friction_dissipation"] > 0) == (friction > 0)
        residual.append(abs(e["balance_residual"]) / e["external_work"])
    assert residual[0] < 1e-4
    assert residual[1] < residual[0] / min_ratio


def test_two_planes_period():
    # A free mass bouncing elastically between planes at ±g with speed v: period 4g/v plus two
    # half-periods of the contact spring π/ω_c each (ω_c = √(k/m)).
    g, v, k, m = 1e-3, 0.2, 1e6, 1.0
    s = Shock(point=0, obstacle="two_planes", gap=g, normal_stiffness=k)
    res = simulate(one_mode(mass=m), [s], duration=0.1, time_step=1e-6, archive_step=1e-5,
                   initial_velocity=[v])
    h = res.history(0)
    up = np.flatnonzero((h.dy[:-1] < 0) & (h.dy[1:] >= 0))
    tc = h.time[up] - h.dy[up] * (h.time[up + 1] - h.time[up]) / (h.dy[up + 1] - h.dy[up])
    assert np.mean(np.diff(tc)) == pytest.approx(4 * g / v + 2 * math.pi / math.sqrt(k / m),
                                                 rel=1e-4)


def test_profile_obstacle_matches_circle():
    # The discrete polar profile of a circle (721 points, Code_Aster's DISCRET) gives the same
    # motion as the circle, to the polygon's sagitta (1 − cos 0.25°) ≈ 1e-5 of the gap.
    model = ModalModel(frequencies=[10.0, 10.0], damping_ratios=0.01, masses=1.0,
                       shock_shapes=[[[1.0, 0.0], [0.0, 1.0]]])
    common = dict(normal_stiffness=1e5, normal_damping=20.0, friction=0.2,
                  tangential_stiffness=1e5)
    a, gp = circle_profile(1e-3)
    circ = Shock(point=0, obstacle="circle", gap=1e-3, **common)
    prof = Shock(point=0, obstacle="profile", profile_angles=a, profile_gaps=gp, **common)
    kw = dict(duration=0.3, time_step=2e-5, archive_step=2e-4,
              initial_displacement=[0.0, 0.0], initial_velocity=[0.3, 0.15])
    hc = simulate(model, [circ], **kw).history(0)
    hp = simulate(model, [prof], **kw).history(0)
    assert hc.normal_force.max() > 0
    assert hp.normal_force.max() == pytest.approx(hc.normal_force.max(), rel=2e-2)
    assert np.max(np.abs(hp.dy - hc.dy)) < 2e-2 * 1e-3


def test_stability_limit_and_error():
    # One mode, one shock: the bound is exact, h_crit = 2/√(ω² + k/m) (Belytschko §6.3).
    m = one_mode(f=20.0, mass=2.0)
    s = Shock(point=0, obstacle="plane", gap=-1e-4, normal_stiffness=5e5)
    lim = stability_limit(m, [s])["time_step_limit"]
    assert lim == pytest.approx(2 / math.sqrt((2 * math.pi * 20) ** 2 + 5e5 / 2.0), rel=1e-12)
    with pytest.raises(StabilityError, match=r"time_step = .* exceeds the stability limit"):
        simulate(m, [s], duration=0.01, time_step=1.01 * lim)
    # just below the limit the (permanently penetrating) oscillator stays bounded
    r = simulate(m, [s], duration=0.05, time_step=0.98 * lim)
    assert np.all(np.isfinite(r.history(0).dy)) and np.max(np.abs(r.history(0).dy)) < 1e-3


def test_adaptive_matches_fixed_and_saves_steps():
    # Coarse steps in free flight, fine ones near contact: same impacts, fewer steps.
    model = ModalModel(frequencies=[5.0], damping_ratios=0.01, masses=1.0,
                       shock_shapes=[[[1.0], [0.0]]], forcing_shapes=[[[1.0], [0.0]]])
    s = Shock(point=0, obstacle="plane", gap=5e-4, normal_stiffness=1e7, normal_damping=300.0)
    load = [NodalForce(0, "y", Signal("harmonic", amplitude=2.0, frequency=5.0))]
    kw = dict(duration=1.0, time_step=5e-6, archive_step=1e-3)
    fixed = simulate(model, [s], load, **kw)
    adapt = simulate(model, [s], load, adaptive=True, **kw)
    assert adapt.n_coarse_steps < fixed.n_coarse_steps / 5
    # the variable step keeps the energy balance (second-order residual, measured 4e-5)
    e = adapt.energy
    assert abs(e["balance_residual"]) < 1e-3 * e["external_work"]
    assert adapt.history(0).normal_force.max() > 0
    assert np.max(np.abs(adapt.history(0).dy - fixed.history(0).dy)) < 1e-2 * 5e-4


def test_streaming_to_parquet_equals_memory(tmp_path):
    model = one_mode(f=10.0, zeta=0.01)
    s = Shock(point=0, obstacle="plane", gap=5e-4, normal_stiffness=1e5, name="AVB")
    kw = dict(duration=0.2, time_step=1e-4, archive_step=1e-4, initial_displacement=[1e-3])
    mem = simulate(model, [s], **kw)
    disk = simulate(model, [s], output_dir=tmp_path, chunk_size=97, **kw)
    assert disk.files["AVB"].exists()
    a, b = mem.history("AVB"), disk.history("AVB")
    for ch in a.channels:
        np.testing.assert_array_equal(getattr(a, ch), getattr(b, ch))
    assert not list(tmp_path.glob("*.tmp"))


def test_plain_python_kernel_matches_compiled():
    # The benchmark's reference loop is the same code run by the interpreter.
    model = one_mode(f=10.0, zeta=0.01)
    s = Shock(point=0, obstacle="circle", gap=5e-4, normal_stiffness=1e5, friction=0.2,
              tangential_stiffness=1e5)
    kw = dict(duration=0.02, time_step=1e-4, initial_velocity=[0.1])
    a = simulate(model, [s], **kw).history(0)
    b = simulate(model, [s], compiled=False, **kw).history(0)
    np.testing.assert_allclose(a.dy, b.dy, rtol=1e-12, atol=1e-18)


def _coulomb_event_driven(amplitude, r, w, duration):
    """Exact stick-slip solution of ÿ = A sin φ − rA sgn ẏ (φ = ωt, y = −x as above), from rest.

    Independent of the integrator: piecewise closed form, events located with brentq. Slip with
    sign s from (φ0, ẏ0): ẏ(φ) = ẏ0 + (A/ω)(cos φ0 − cos φ − r s (φ − φ0)); the slip ends where
    ẏ = 0, then the mass sticks while |sin φ| <= r (friction holds it) and slips again, with
    the sign of sin φ, once |sin φ| > r (Den Hartog 1931, stick-slip regime r > 0.537).
    Returns (∫|ẏ| dt over [0, T] [m], time spent sticking [s]).
    """
    from scipy.optimize import brentq

    a_w = amplitude / w
    phi_end = w * duration
    phi, stick, s, p0, y0 = 0.0, True, 1.0, 0.0, 0.0
    travel, t_stick = 0.0, 0.0

    def vel(p):
        return y0 + a_w * (math.cos(p0) - math.cos(p) - r * s * (p - p0))

    while phi < phi_end:
        if stick:
            if abs(math.sin(phi)) <= r:  # held until |sin φ| rises through r
                j = math.floor(phi / math.pi)
                nxt = min(c for c in ((j + i) * math.pi + math.asin(r) for i in range(3))
                          if c > phi)
            else:
                nxt = phi
            nxt = min(nxt, phi_end)
            t_stick += (nxt - phi) / w
            phi = nxt
            if phi >= phi_end:
                break
            stick, s, p0, y0 = False, math.copysign(1.0, math.sin(phi)), phi, 0.0
            continue
        p = p0 + 1e-3
        while p < phi_end and vel(p) * s > 0:
            p += 1e-3
        p1 = min(p, phi_end)
        if vel(p1) * s <= 0:
            p1 = brentq(vel, p1 - 1e-3, p1, xtol=1e-14)
        d = p1 - p0
        travel += s * (y0 * d + a_w * (math.cos(p0) * d - (math.sin(p1) - math.sin(p0))
                                       - r * s * d * d / 2)) / w
        phi = p1
        if abs(math.sin(phi)) > r:  # reverses at once
            s, p0, y0 = math.copysign(1.0, math.sin(phi)), phi, 0.0
        else:
            stick = True
    return travel, t_stick


def test_coulomb_base_excitation_stick_slip_event_driven():
    # r = μN/(mA) = 0.75: the mass alternately sticks and slips (Den Hartog's regime with stops).
    # The wear power N·(1/T)∫|ẏ|dt (zero while sticking, theory §2) and the time spent sticking
    # are compared with the exact event-driven solution above, both from rest.
    amp, duration = 4.0, 0.5
    res, n_force, mu, m, w = _friction_case(amp, steady=False, duration=duration)
    travel, t_stick = _coulomb_event_driven(amp, mu * n_force / (m * amp), w, duration)
    p_exact = n_force * travel / duration
    h = res.history(0)
    assert 0.2 < t_stick / duration < 0.4  # both regimes present (measured 0.296)
    assert res.wear_power[0] == pytest.approx(p_exact, rel=1e-3)
    assert _power(h) == pytest.approx(p_exact, rel=2e-3)
    assert h.stick.mean() == pytest.approx(t_stick / duration, abs=5e-3)
    # while the flag says stick, the sliding speed is only the stick spring's creep (its force
    # changes by ~μN over a period: speed ~ μN·ω/k_t ≈ 2e-8 m/s here, plus the entry samples);
    # measured mean 8e-7 m/s against 8.5e-3 m/s while slipping
    speed = np.hypot(h.vt1, h.vt2)
    assert np.mean(speed[h.stick == 1]) < 1e-3 * np.mean(speed[h.stick == 0])
