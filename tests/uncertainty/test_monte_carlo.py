"""Monte Carlo propagation (fretwear.uncertainty.monte_carlo) against closed forms.

Analytic case (docs/uncertainty.md §5): Archard, TUBE_BAV without tilt, bar not worn, fixed
power P, K lognormal (median K₀, σ). The depth relation of docs/theory.md §6 is exactly

    D = c·V^(2/3),  c = (1/(2R_m))^(1/3)·(3/(4l))^(2/3),  V = K·P·t,

a monotone map of K, so ln D ~ N(ln c + (2/3)·ln(K₀·P·t), (2σ/3)²): the depth quantiles, the
probability of exceeding a limit L and the time to reach it, t_L = (L/c)^(3/2)/(K·P), are in
closed form. The Monte Carlo estimates must agree within their own sampling error.
"""

import math
import warnings

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.history import ContactHistory
from fretwear.table import wear_table
from fretwear.table.depth import DepthModel
from fretwear.table.depth_build import model_from_table
from fretwear.uncertainty import LogNormal, monte_carlo

R, L_BAR = 9.525e-3, 12.7e-3
K0, SIGMA, P = 9.2e-15, 0.7, 0.01
YEAR = 3.15576e7
WALL = 1.09e-3
C = (1 / (2 * R)) ** (1 / 3) * (3 / (4 * L_BAR)) ** (2 / 3)
CASE = {"contact_type": "TUBE_BAV", "instants": [1.0, 5.0, 10.0, 20.0], "time_scale": YEAR,
        "dimensions": {"mobile_radius": R, "obstacle_width": L_BAR},
        "coefficients": {"COEF_USURE": K0}, "wall_thickness": WALL}
INSTANTS = np.array(CASE["instants"])


def _exact_quantile(q, t_years):
    median = C * (K0 * P * t_years * YEAR) ** (2 / 3)
    return median * np.exp(2 * SIGMA / 3 * stats.norm.ppf(q))


def _exact_cdf(depth, t_years):
    median = C * (K0 * P * t_years * YEAR) ** (2 / 3)
    return stats.norm.cdf((np.log(depth) - np.log(median)) / (2 * SIGMA / 3))


@pytest.fixture(scope="module", params=["sobol", "random"])
def result(request):
    return monte_carlo(CASE, P, coefficients={"coefficient": LogNormal(sigma_ln=SIGMA)},
                       samples=8192, method=request.param, seed=11)


def test_nominal_depth_is_the_wear_table_and_the_closed_form(result):
    kw = {k: v for k, v in CASE.items() if k != "wall_thickness"}
    table = wear_table(P, **kw)
    np.testing.assert_allclose(result.nominal_depth, table["depth_mobile"], rtol=1e-14)
    np.testing.assert_allclose(result.nominal_depth, _exact_quantile(0.5, INSTANTS), rtol=1e-12)


def test_depth_quantiles_match_closed_form_within_sampling_error(result):
    """The estimated q-quantile x̂ has F(x̂) within q ± 4·√(q(1−q)/N) (order statistics)."""
    n = result.samples
    levels = [0.05, 0.25, 0.5, 0.75, 0.95]
    est = result.quantiles(levels)
    for j, t in enumerate(INSTANTS):
        for q in levels:
            achieved = _exact_cdf(est.iloc[j][q], t)
            assert abs(achieved - q) < 4 * math.sqrt(q * (1 - q) / n), (t, q, achieved)


def test_exceedance_matches_closed_form_within_sampling_error(result):
    limit = 0.4 * WALL
    ex = result.exceedance()
    assert result.limit == pytest.approx(limit)
    for j, t in enumerate(INSTANTS):
        p = 1 - _exact_cdf(limit, t)
        se = math.sqrt(p * (1 - p) / result.samples)
        assert abs(ex["probability"].iloc[j] - p) <= 4 * se + 1e-12, (t, p)
        assert ex["standard_error"].iloc[j] == pytest.approx(
            math.sqrt(ex["probability"].iloc[j] * (1 - ex["probability"].iloc[j])
                      / result.samples))


def test_time_to_limit_is_exact_per_sample_and_its_quantiles_match(result):
    limit = 0.4 * WALL
    times = result.time_to_limit()  # years (user unit)
    k = result.inputs["mobile coefficient"].to_numpy()
    exact = (limit / C) ** 1.5 / (k * P) / YEAR
    np.testing.assert_allclose(times, exact, rtol=1e-10)
    # the time quantile q is the one of K at 1 − q
    tq = result.time_to_limit_quantiles([0.1, 0.5, 0.9])
    for q, value in tq.items():
        k_level = 1 - q
        achieved = stats.norm.cdf(np.log((limit / C) ** 1.5 / (value * YEAR * P) / K0) / SIGMA)
        assert abs(achieved - k_level) < 4 * math.sqrt(q * (1 - q) / result.samples)


def test_sobol_is_closer_than_random_on_the_mean_depth():
    """Scrambled Sobol' estimates of E[min(D, R)] scatter less than random ones over 12 seeds
    (exact: the lognormal's partial expectation m·e^(s²/2)·Φ(z − s) + R·(1 − Φ(z)),
    z = ln(R/m)/s; past R the depth leaves the relation's range). Rates:
    benchmarks/bench_uncertainty.py."""
    m, s_d = _exact_quantile(0.5, 20.0), 2 * SIGMA / 3
    z = math.log(R / m) / s_d
    exact = m * math.exp(s_d ** 2 / 2) * stats.norm.cdf(z - s_d) + R * stats.norm.sf(z)
    errors = {}
    for method in ("sobol", "random"):
        e = [np.minimum(monte_carlo(CASE, P, coefficients={"coefficient": LogNormal(
            sigma_ln=SIGMA)}, samples=1024, method=method, seed=s).depth[:, -1], R).mean()
            - exact for s in range(12)]
        errors[method] = math.sqrt(np.mean(np.square(e)))
    assert errors["sobol"] < 0.25 * errors["random"]


def test_sobol_indices_of_a_product_of_lognormals():
    """TUBE_ALESAGE without bore radius: d = K·P·t/(2π·l·R_m), linear in K·P. For independent
    lognormal K (σ₁) and P (σ₂): S_K = (e^{σ₁²} − 1)/(e^{σ₁²+σ₂²} − 1), S_T,K = 1 − S_P."""
    s1, s2 = 0.5, 0.3
    case = {"contact_type": "TUBE_ALESAGE", "instants": [1.0], "time_scale": YEAR,
            "dimensions": {"mobile_radius": R, "obstacle_width": L_BAR},
            "coefficients": {"coefficient": K0}}
    r = monte_carlo(case, P, coefficients={"coefficient": LogNormal(sigma_ln=s1)},
                    power_scatter=LogNormal(sigma_ln=s2), samples=2 ** 15, seed=2)
    total = math.exp(s1 ** 2 + s2 ** 2) - 1
    first = {"mobile coefficient": (math.exp(s1 ** 2) - 1) / total,
             "wear power": (math.exp(s2 ** 2) - 1) / total}
    s = r.sensitivity(resamples=50)
    for name, value in first.items():
        other = next(v for k, v in first.items() if k != name)
        assert s.loc[name, "first"] == pytest.approx(value, abs=0.03)
        assert s.loc[name, "total"] == pytest.approx(1 - other, abs=0.03)


def test_power_from_a_power_interval_and_its_share():
    from fretwear.power.confidence import batch_means_interval

    iv = batch_means_interval(np.random.default_rng(0).normal(P, 0.1 * P, 20))
    r = monte_carlo(CASE, iv, samples=4096)
    assert [v.label for v in r.variables] == ["wear power"]
    powers = r.inputs["wear power"]
    assert powers.median() == pytest.approx(iv.estimate, rel=0.01)
    # depth ∝ P^(2/3): the 95 % depth quantile is that of the power's 95 % quantile
    d95 = r.quantiles([0.95]).iloc[-1, 0]
    p95 = float(iv.distribution().ppf(0.95))
    assert d95 == pytest.approx(C * (K0 * p95 * 20 * YEAR) ** (2 / 3), rel=0.01)


def test_errors_name_the_fix():
    with pytest.raises(InputError, match="no uncertain input"):
        monte_carlo(CASE, P, samples=64)
    with pytest.raises(KeywordError, match="no coefficient 'k'"):
        monte_carlo(CASE, P, coefficients={"k": LogNormal(sigma_ln=0.1)}, samples=64)
    with pytest.raises(KeywordError, match="no dimension 'obstacle_radius'"):
        monte_carlo(CASE, P, dimensions={"obstacle_radius": LogNormal(sigma_ln=0.1)},
                    samples=64)
    r = monte_carlo({k: v for k, v in CASE.items() if k != "wall_thickness"}, P,
                    factor=LogNormal(1.0, sigma_ln=0.3), samples=64)
    with pytest.raises(InputError, match="wall_thickness"):
        r.exceedance()


def test_uncertain_dimensions_are_evaluated_sample_by_sample():
    width = stats.uniform(loc=0.9 * L_BAR, scale=0.2 * L_BAR)
    r = monte_carlo(CASE, P, dimensions={"obstacle_width": width}, samples=256, seed=3)
    w = r.inputs["dimension obstacle_width"].to_numpy()
    expected = (1 / (2 * R)) ** (1 / 3) * (3 * K0 * P * 20 * YEAR / (4 * w)) ** (2 / 3)
    np.testing.assert_allclose(r.depth[:, -1], expected, rtol=1e-12)


@pytest.mark.parametrize("contact", ["TUBE_BAV", "TUBE_ALESAGE", "TUBE_3_ENCO", "TUBE_4_ENCO",
                                     "TUBE_TUBE", "GRAPPE_ALESAGE", "GRAPPE_1_ENCO",
                                     "GRAPPE_2_ENCO"])
def test_every_contact_type_matches_its_wear_table(contact):
    """The model's depth at sampled factors equals wear_table's with the coefficient scaled."""
    from fretwear.geometry import CONTACT_TYPES

    cls = CONTACT_TYPES[contact]
    dims = dict(cls.example)
    case = {"contact_type": contact, "dimensions": dims, "instants": [0.5, 1.0, 2.0],
            "time_scale": YEAR, "coefficients": {"coefficient": 1e-15},
            "obstacle_coefficients": {"coefficient": 5e-16}}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        r = monte_carlo(case, 0.005, factor=LogNormal(1.0, sigma_ln=0.5), samples=16,
                        method="random", seed=5)
        for i in (0, 7, 15):
            f = r.inputs["wear-coefficient factor"].iloc[i]
            table = wear_table(0.005, **{**case, "coefficients": {"coefficient": f * 1e-15},
                                         "obstacle_coefficients": {"coefficient": f * 5e-16}})
            expected = table["depth_mobile"].to_numpy()
            got = r.depth[i]
            assert np.allclose(np.where(np.isnan(expected), np.inf, expected), got, rtol=1e-12)


def test_restart_and_edf_mz_continue_from_the_previous_volume():
    """A restart of an EDF_MZ table: the model at factor 1 equals wear_table's restart rows."""
    base = {"contact_type": "TUBE_ALESAGE", "law": "EDF_MZ", "time_scale": YEAR,
            "dimensions": {"mobile_radius": R, "obstacle_width": L_BAR}}
    first = wear_table(0.01, instants=[0.0, 2.0], **base)
    second = wear_table(0.01, instants=[1.0, 3.0], initial_state=first, **base)
    model = model_from_table(second)
    assert isinstance(model, DepthModel) and model.origin == 2.0
    np.testing.assert_allclose(model.depth(np.array([1.0, 3.0]) * YEAR),
                               second["depth_mobile"].iloc[-2:], rtol=1e-13)
    # the factor scales the new wear only: V(t) = f·V_law(τ_f + t), f·V_law(τ_f) = V₀
    vm, _ = model.volumes(np.array([0.0, 3.0 * YEAR]), factor=2.0)
    assert vm[0] == pytest.approx(model.initial_mobile, rel=1e-12)


def test_sector_tables_give_sector_models():
    t = np.linspace(0, 2, 2001)
    angle = np.radians(150 * np.sin(3 * t))
    h = ContactHistory(time=t, normal_force=np.full(t.size, 2.0), vt1=np.full(t.size, 0.1),
                       vt2=np.zeros(t.size), dy=np.cos(angle), dz=np.sin(angle))
    kw = {"contact_type": "TUBE_BAV", "instants": [1.0, 10.0], "time_scale": YEAR,
          "dimensions": {"mobile_radius": R, "obstacle_width": L_BAR}, "sectors": 4,
          "coefficients": {"coefficient": K0},
          "sector_coefficients": [(K0, None), (2 * K0, None), (K0, None), (3 * K0, None)]}
    table = wear_table(h, **kw)
    from fretwear.table import models_from_table

    models = models_from_table(table, sector_coefficients=kw["sector_coefficients"])
    last = table[table["instant"] == 10.0]
    assert models["global"].depth(10 * YEAR) == pytest.approx(last["depth_mobile"].iloc[0],
                                                              rel=1e-13)
    for j in range(4):
        m = models[f"sector {j + 1}"]
        assert m.depth(10 * YEAR) == pytest.approx(last["depth_mobile_sector"].iloc[j],
                                                   rel=1e-13)
    r = monte_carlo(kw, h, factor=LogNormal(1.0, sigma_ln=0.2), sector=4, samples=64)
    assert isinstance(r.quantiles(), pd.DataFrame)


def test_a_wear_case_and_a_history_give_the_same_as_the_keywords():
    """WearCase (fretwear.table) and a KWU-EPRI history: the propagation is the same whether the
    case comes as keywords or as the validated object."""
    from fretwear.table import WearCase

    t = np.linspace(0.0, 2.0, 4001)
    h = ContactHistory(
        time=t, normal_force=np.abs(np.sin(20 * t)) * 5, vt1=0.05 * np.cos(7 * t),
        vt2=np.zeros(t.size))
    kw = {"contact_type": "TUBE_BAV", "instants": [10.0], "time_scale": YEAR, "law": "KWU_EPRI",
          "dimensions": {"mobile_radius": R, "obstacle_width": L_BAR},
          "coefficients": {"reference_coefficient": 1e-14}, "blocks": 4}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = monte_carlo(kw, h, factor=LogNormal(1.0, sigma_ln=0.4), samples=128)
        b = monte_carlo(WearCase.from_keywords(**kw), h, factor=LogNormal(1.0, sigma_ln=0.4),
                        samples=128)
    assert [v.label for v in a.variables] == ["wear-coefficient factor", "wear power"]
    np.testing.assert_array_equal(a.depth, b.depth)
