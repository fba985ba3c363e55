"""Wear laws (theory §4) and the restart equivalent time (theory §7).

Reference values come from the closed forms of theory §4 evaluated independently: by hand, or in
50-digit decimal arithmetic (Python's ``decimal``), never from fretwear itself.
"""

from __future__ import annotations

import warnings
from decimal import Decimal, getcontext

import numpy as np
import pytest

from fretwear.errors import InputError, KeywordError, LawWarning
from fretwear.laws import (
    WEAR_LAWS,
    archard,
    edf_mz,
    edf_mz_equivalent_time,
    edf_mz_rate,
    get_law,
    kwu_epri,
    linear_equivalent_time,
)

A, B, N, S = 1e-13, 1.2, 2.44e-8, 1.14e-16  # theory §4 EDF_MZ defaults
YEAR = 31_536_000.0


def edf_mz_decimal(p, t, a=A, b=B, n=N, s=S) -> float:
    """Theory §4 EDF_MZ formula in 50-digit decimal arithmetic (independent reference)."""
    getcontext().prec = 50
    P, T, Aa, Bb, Nn, Ss = (Decimal(repr(float(x))) for x in (p, t, a, b, n, s))
    s0 = Aa * (P ** Bb) if P > 0 else Decimal(0)
    return float((s0 - Ss) / Nn * (1 - (-Nn * T).exp()) + Ss * T)


# ----------------------------------------------------------------------------- Archard
def test_archard_value_and_linearity():
    # V = K·P·t (theory §4): 1e-13 Pa⁻¹ × 0.02 W × 1 year, by hand = 6.3072e-8 m³
    assert float(archard(0.02, YEAR, 1e-13)) == pytest.approx(6.3072e-8, rel=1e-15)
    p = np.array([0.0, 0.01, 0.02, 0.05])
    t = np.array([1.0, 10.0, 100.0])
    v = archard(p[:, None], t[None, :], 2e-14)
    assert v.shape == (4, 3)
    # linear in each argument: doubling P, t or K doubles V
    np.testing.assert_allclose(archard(2 * p[:, None], t, 2e-14), 2 * v, rtol=1e-15)
    np.testing.assert_allclose(archard(p[:, None], 2 * t, 2e-14), 2 * v, rtol=1e-15)
    np.testing.assert_allclose(archard(p[:, None], t, 4e-14), 2 * v, rtol=1e-15)
    # additive in time: V(t1 + t2) = V(t1) + V(t2)
    assert float(archard(0.03, 7.0 + 5.0, 1e-13)) == pytest.approx(
        float(archard(0.03, 7.0, 1e-13) + archard(0.03, 5.0, 1e-13)), rel=1e-15)


def test_archard_per_sector_coefficients_broadcast():
    # sector mode: V_j = k_j·P_j·t for each sector j (theory §3)
    k = np.array([1e-13, 2e-13, 3e-13])
    p = np.array([0.01, 0.02, 0.03])
    v = archard(p, np.array([[1.0], [2.0]]), k)
    np.testing.assert_allclose(v, [[1e-15, 4e-15, 9e-15], [2e-15, 8e-15, 18e-15]], rtol=1e-14)


@pytest.mark.parametrize("name, args", [
    ("power", (-0.1, 1.0, 1e-13)),
    ("duration", (0.1, np.nan, 1e-13)),
    ("coefficient", (0.1, 1.0, [1e-13, -1e-13])),
])
def test_archard_errors_name_the_argument(name, args):
    with pytest.raises(InputError, match=repr(name)):
        archard(*args)


def test_inputs_not_modified():
    p = np.array([0.01, 0.02])
    t = np.array([1.0, 2.0])
    p0, t0 = p.copy(), t.copy()
    edf_mz(p, t)
    archard(p, t, 1e-13)
    np.testing.assert_array_equal(p, p0)
    np.testing.assert_array_equal(t, t0)


# ----------------------------------------------------------------------------- KWU-EPRI law
def test_kwu_epri_volume():
    # K = k_r·w/w_r, V = K·P·t (theory §4): 1e-14 × 3/2 × 0.04 W × 100 s = 6e-14 m³ by hand
    v = kwu_epri(0.04, 100.0, reference_coefficient=1e-14, intensity=3.0, reference_intensity=2.0)
    assert float(v) == pytest.approx(6e-14, rel=1e-15)
    assert float(kwu_epri(0.04, 100.0, 1e-14, 3.0)) == pytest.approx(1.2e-13, rel=1e-15)
    with pytest.raises(InputError, match="reference_intensity"):
        kwu_epri(0.04, 100.0, 1e-14, 3.0, reference_intensity=0.0)


# ----------------------------------------------------------------------------- EDF_MZ
@pytest.mark.filterwarnings("ignore::fretwear.errors.LawWarning")   # P = 1e-3 W: S > A·P^b
@pytest.mark.parametrize("p", [1e-3, 0.01, 0.1, 1.0])
@pytest.mark.parametrize("t", [1e-6, 1.0, 3600.0, 1e6, YEAR, 10 * YEAR, 1e11])
def test_edf_mz_against_50_digit_reference(p, t):
    assert float(edf_mz(p, t)) == pytest.approx(edf_mz_decimal(p, t), rel=2e-14)


def test_edf_mz_small_nt_keeps_digits_when_s_dominates():
    # S > A·P^b with n·t ~ 1e-14: the naive formula cancels; ours keeps ~15 digits
    with pytest.warns(LawWarning):
        v = float(edf_mz(1e-5, 1e-6))
    assert v == pytest.approx(edf_mz_decimal(1e-5, 1e-6), rel=1e-13)


def test_edf_mz_initial_slope_is_a_p_b():
    # dV/dt(0) = A·P^b (theory §4): finite difference over h with n·h = 2.4e-8
    for p in (0.005, 0.05, 0.5):
        h = 1.0
        slope = float(edf_mz(p, h)) / h
        assert slope == pytest.approx(A * p ** B, rel=1e-7)
        assert float(edf_mz_rate(p, 0.0)) == pytest.approx(A * p ** B, rel=1e-15)


def test_edf_mz_asymptotic_slope_is_s():
    # dV/dt -> S for n·t >> 1, and V − S·t -> (A·P^b − S)/n
    p, t, dt = 0.05, 1e10, 1e6   # n·t = 244
    slope = float(edf_mz(p, t + dt) - edf_mz(p, t)) / dt
    assert slope == pytest.approx(S, rel=1e-6)
    offset = float(edf_mz(p, t)) - S * t
    assert offset == pytest.approx((A * p ** B - S) / N, rel=1e-9)


def test_edf_mz_zero_decay_is_linear():
    # n = 0: V = A·P^b·t (limit of (1 − e^{−nt})/n -> t)
    v = float(edf_mz(0.1, 1e7, decay_constant=0.0))
    assert v == pytest.approx(A * 0.1 ** B * 1e7, rel=1e-14)


def test_edf_mz_warns_when_s_exceeds_initial_rate():
    # A·P^b at P = 1e-3 W: 1e-13 × 1e-3^1.2 = 2.5e-17 < S = 1.14e-16 -> warning
    with pytest.warns(LawWarning, match="exceeds the initial rate"):
        edf_mz(1e-3, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", LawWarning)
        edf_mz(0.1, 1.0)   # 6.3e-15 > S: no warning


def test_restart_warns_once_at_the_callers_line():
    """A restart evaluates the law three times (t_eq, V(t_eq + Δt), V(t_eq)); S > A·P^b must give
    one LawWarning, attributed to this file (A·P^b = 1e-13 × 1e-4^1.2 = 1.6e-18 < S)."""
    law = WEAR_LAWS["EDF_MZ"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        law.cumulated_volume(1e-9, 1e-4, YEAR)
    rising = [w for w in caught if "exceeds the initial rate" in str(w.message)]
    assert len(rising) == 1 and rising[0].category is LawWarning
    assert rising[0].filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error", LawWarning)     # a user's filter still applies
        with pytest.raises(LawWarning):
            law.volume(1e-4, YEAR)


def test_edf_mz_monotone():
    t = np.geomspace(1e-3, 1e12, 400)
    for p in (0.0, 1e-3, 0.1, 10.0):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", LawWarning)
            v = edf_mz(p, t)
        assert np.all(np.diff(v) > 0)


# ----------------------------------------------------------------------------- equivalent time
def test_equivalent_time_round_trip_vectorised():
    p = np.array([0.0, 1e-4, 1e-3, 0.01, 0.1, 1.0, 100.0])[:, None]
    t = np.array([1e-3, 1.0, 1e5, 2e7, YEAR, 1e9])[None, :]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LawWarning)
        v = edf_mz(p, t)
        t_eq = edf_mz_equivalent_time(v, p)
    assert t_eq.shape == (7, 6)
    # the volume is reproduced to ~1e-12; the time too where V(t) is well conditioned
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LawWarning)
        np.testing.assert_allclose(edf_mz(p, t_eq), v, rtol=1e-13)
    np.testing.assert_allclose(t_eq[:, :5], np.broadcast_to(t, (7, 6))[:, :5], rtol=1e-11)


def test_equivalent_time_edge_cases():
    assert float(edf_mz_equivalent_time(0.0, 0.1)) == 0.0
    # S = 0: V saturates at A·P^b/n; a larger volume is never reached -> inf with a warning
    ceiling = A * 0.1 ** B / N
    with pytest.warns(LawWarning, match="never be reached"):
        t = edf_mz_equivalent_time([0.5 * ceiling, 2 * ceiling], 0.1, asymptotic_rate=0.0)
    # closed form for S = 0: t = −ln(1 − V·n/(A·P^b))/n = ln 2/n at half the ceiling
    assert t[0] == pytest.approx(np.log(2) / N, rel=1e-13)
    assert np.isinf(t[1])


def test_restart_continuity_edf_mz():
    # theory §7: V(t1), then continuing t2 from the equivalent time, equals V(t1 + t2)
    law = WEAR_LAWS["EDF_MZ"]
    coefficients = {"rate_coefficient": 2.6e-15, "power_exponent": 1.0}
    for p in (0.002, 0.05, 0.8):
        for t1, t2 in ((1e5, 3e6), (YEAR, 2 * YEAR), (5 * YEAR, 0.25 * YEAR)):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", LawWarning)
                v1 = law.volume(p, t1, **coefficients)
                v12 = law.cumulated_volume(v1, p, t2, **coefficients)
                direct = law.volume(p, t1 + t2, **coefficients)
            assert float(v12) == pytest.approx(float(direct), rel=1e-12)
    # restart with another power: the continuation starts at the equivalent time of the new power
    v1 = law.volume(0.05, YEAR)
    t_eq = float(law.equivalent_time(v1, 0.1))
    assert float(law.cumulated_volume(v1, 0.1, YEAR)) == pytest.approx(
        float(v1) + float(law.volume(0.1, t_eq + YEAR) - law.volume(0.1, t_eq)), rel=1e-14)


def test_linear_equivalent_time_and_restart():
    law = WEAR_LAWS["ARCHARD"]
    # t = V/(K·P): 6e-9 m³ / (1e-13 Pa⁻¹ × 0.02 W) = 3e6 s, by hand
    t_eq = float(law.equivalent_time(6e-9, 0.02, coefficient=1e-13))
    assert t_eq == pytest.approx(3e6, rel=1e-15)
    assert float(law.cumulated_volume(1e-9, 0.02, 1e6, coefficient=1e-13)) == pytest.approx(
        1e-9 + 2e-9, rel=1e-15)
    with pytest.warns(LawWarning):
        assert np.isinf(linear_equivalent_time(1e-9, 0.0))
    kwu = WEAR_LAWS["KWU_EPRI"]
    assert float(kwu.equivalent_time(6e-9, 0.02, reference_coefficient=1e-13, intensity=2.0)) == \
        pytest.approx(1.5e6, rel=1e-15)


# ----------------------------------------------------------------------------- registry
def test_registry_contents_follow_spec():
    assert list(WEAR_LAWS) == ["ARCHARD", "KWU_EPRI", "EDF_MZ"]
    edf = WEAR_LAWS["EDF_MZ"]
    assert dict(edf.defaults) == {"rate_coefficient": 1e-13, "power_exponent": 1.2,
                                  "decay_constant": 2.44e-8, "asymptotic_rate": 1.14e-16}
    assert dict(edf.aster_keywords) == {"rate_coefficient": "COEF_USURE",
                                        "power_exponent": "COEF_B", "decay_constant": "COEF_N",
                                        "asymptotic_rate": "COEF_S"}
    assert not edf.linear_in_time and not edf.needs_history
    kwu = WEAR_LAWS["KWU_EPRI"]
    assert kwu.defaults["k"] == 5.0 and kwu.defaults["c"] == 10.0
    assert kwu.defaults["reference_intensity"] == 1.0
    assert kwu.defaults["impact_factor"] == 1.0 and kwu.defaults["sliding_factor"] == 1.0
    assert kwu.aster_keywords["reference_coefficient"] == "COEF_USURE"
    assert kwu.aster_keywords["impact_factor"] == "COEF_FNOR"
    assert kwu.aster_keywords["sliding_factor"] == "COEF_VTAN"
    assert kwu.aster_keywords["k"] == "COEF_K" and kwu.aster_keywords["c"] == "COEF_C"
    assert kwu.linear_in_time and kwu.needs_history
    arch = WEAR_LAWS["ARCHARD"]
    assert arch.parameters == ("coefficient",)
    assert arch.aster_keywords["coefficient"] == "COEF_USURE"
    with pytest.raises(TypeError):
        arch.defaults["coefficient"] = 1.0   # read-only


def test_registry_volume_matches_functions():
    assert float(WEAR_LAWS["EDF_MZ"].volume(0.05, YEAR, COEF_B=1.0)) == pytest.approx(
        edf_mz_decimal(0.05, YEAR, b=1.0), rel=1e-13)
    assert float(WEAR_LAWS["KWU_EPRI"].volume(0.04, 100.0, COEF_USURE=1e-14, intensity=3.0)) == \
        pytest.approx(1.2e-13, rel=1e-15)


def test_registry_errors_name_the_culprit():
    with pytest.raises(KeywordError, match="'coefficient' \\(COEF_USURE\\).*missing"):
        WEAR_LAWS["ARCHARD"].volume(0.1, 1.0)
    with pytest.raises(KeywordError, match="'intensity'.*kwu_epri_statistics"):
        WEAR_LAWS["KWU_EPRI"].volume(0.1, 1.0, reference_coefficient=1e-14)
    with pytest.raises(KeywordError, match="unknown coefficient 'COEF_A'.*rate_coefficient"):
        WEAR_LAWS["EDF_MZ"].volume(0.1, 1.0, COEF_A=1e-13)
    with pytest.raises(KeywordError, match="given twice"):
        WEAR_LAWS["ARCHARD"].volume(0.1, 1.0, coefficient=1e-13, COEF_USURE=1e-13)
    with pytest.raises(KeywordError, match="unknown wear law 'COULOMB'.*ARCHARD"):
        get_law("COULOMB")
    assert get_law(" archard ") is WEAR_LAWS["ARCHARD"]   # any case, as the database lookup


# ----------------------------------------------------------------------------- properties
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=150, deadline=None, derandomize=True)   # deterministic CI
@given(p=st.floats(0.0, 100.0), t1=st.floats(1e-3, 1e10), t2=st.floats(0.0, 1e10),
       a=st.floats(1e-17, 1e-12), b=st.floats(0.5, 2.0),
       n=st.one_of(st.just(0.0), st.floats(1e-12, 1e-6)),
       s=st.one_of(st.just(0.0), st.floats(1e-20, 1e-15)))
def test_restart_continuity_property(p, t1, t2, a, b, n, s):
    # theory §7: continuing from the equivalent time reproduces the uninterrupted law (reference:
    # the law evaluated directly at t1 + t2), over wide ranges including n = 0 and S = 0
    law = WEAR_LAWS["EDF_MZ"]
    c = {"rate_coefficient": a, "power_exponent": b, "decay_constant": n, "asymptotic_rate": s}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LawWarning)
        v1 = law.volume(p, t1, **c)
        direct = float(law.volume(p, t1 + t2, **c))
        restarted = float(law.cumulated_volume(v1, p, t2, **c))
    assert restarted == pytest.approx(direct, rel=1e-11, abs=1e-300)
