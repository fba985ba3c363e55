"""The hierarchical calibration on field inspections (issue 26, point 2), against

* the conjugate closed form (every indication sized with a lognormal error, depth a power law of
  the factor: Archard on TUBE_BAV without tilt, D ∝ f^(2/3)): the normal-normal model, with and
  without contact scatter and groups (Gelman et al., *Bayesian Data Analysis*, 3rd ed., §5.4);
* an independent numeric quadrature of the same likelihood (Gauss-Legendre rules nested over
  the bundle and the contact levels), with an additive sizing error, an NDD and a tube not
  inspected; the depth there from the closed form D = (1/(2R))^(1/3)·(3V/(4l))^(2/3).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats
from scipy.special import expit

from fretwear.assessment import LogisticPOD, LogSizingModel, SizingModel, Technique
from fretwear.assessment.calibration import FactorPrior, calibrate_bundle
from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import Wall
from fretwear.table.depth import DepthModel
from fretwear.uncertainty import LogNormal, calibrate

YEAR = 31536000.0
R, L_BAR, K = 9.525e-3, 12.7e-3, 1e-14
GEOMETRY = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=L_BAR)


def _model(power: float, name: str) -> DepthModel:
    return DepthModel(law=get_law("ARCHARD"), geometry=GEOMETRY, powers=(power,),
                      coefficients_mobile=({"coefficient": K},), coefficients_obstacle=(None,),
                      time_scale=YEAR, name=name, wall=Wall(1.09e-3))


def _depth(power: float, years: float, f):
    """Independent closed form of TUBE_BAV (docs/theory.md): D = (1/2R)^(1/3)(3V/4l)^(2/3)."""
    v = np.asarray(f, float) * K * power * years * YEAR
    return (1 / (2 * R)) ** (1 / 3) * (3 * v / (4 * L_BAR)) ** (2 / 3)


POWERS = {"A": 4e-3, "B": 7e-3, "C": 2e-3, "D": 1.2e-2}
MEASURED_MM = {"A": 0.21, "B": 0.36, "C": 0.09, "D": 0.52}


def _sized_campaign():
    return pd.DataFrame({"contact": list(MEASURED_MM), "instant": [10.0] * 4,
                         "depth_mm": list(MEASURED_MM.values())})


def _normal_normal(sigma_meas, s, tau0, mu0=0.0, groups=None, tau_g=0.0):
    """Posterior (mean, sd) of μ with y_i = (ln m_i − a_i)/b = μ + γ_g + η_i + e_i/b,
    b = 2/3: a Gaussian vector per group, Σ_g = τ_g²·11ᵀ + diag(s² + (σ/b)²)."""
    b = 2.0 / 3.0
    a = {c: math.log(float(_depth(POWERS[c], 10.0, 1.0))) for c in POWERS}
    y = {c: (math.log(MEASURED_MM[c] * 1e-3) - a[c]) / b for c in POWERS}
    groups = groups or {c: "all" for c in POWERS}
    precision, weighted = 1 / tau0 ** 2, mu0 / tau0 ** 2
    for g in set(groups.values()):
        members = [c for c in POWERS if groups[c] == g]
        cov = tau_g ** 2 * np.ones((len(members),) * 2) \
            + np.diag([s ** 2 + (sigma_meas / b) ** 2] * len(members))
        inv = np.linalg.inv(cov)
        precision += inv.sum()
        weighted += inv.sum(axis=0) @ np.array([y[c] for c in members])
    return weighted / precision, 1 / math.sqrt(precision)


def _bundle_moments(cal):
    g = cal.levels
    mean = np.trapezoid(g.bundle * g.grid, g.grid)
    return mean, math.sqrt(np.trapezoid(g.bundle * (g.grid - mean) ** 2, g.grid))


def test_no_scatter_matches_the_conjugate_update_of_calibrate():
    models = {c: _model(p, c) for c, p in POWERS.items()}
    tech = Technique(LogSizingModel(0.1))
    prior = FactorPrior(LogNormal(1.0, sigma_ln=0.5), contact_sigma_ln=0.0)
    cal = calibrate_bundle(models, _sized_campaign(), techniques=tech, prior=prior,
                           power_sigma_ln=0.0)
    old = calibrate(models, _sized_campaign(), prior=LogNormal(1.0, sigma_ln=0.5),
                    measurement_sigma=0.1, method="conjugate")
    mean, sd = _bundle_moments(cal)
    assert mean == pytest.approx(math.log(old.posterior.median), abs=2e-4)
    assert sd == pytest.approx(old.posterior.sigma_ln, rel=2e-3)
    expected = _normal_normal(0.1, 0.0, 0.5)
    assert mean == pytest.approx(expected[0], abs=2e-4)


@pytest.mark.parametrize(("s", "tau_g"), [(0.35, 0.0), (0.2, 0.3)])
def test_contact_scatter_and_groups_match_the_normal_normal_closed_form(s, tau_g):
    models = {c: _model(p, c) for c, p in POWERS.items()}
    groups = {"A": "AVB", "B": "AVB", "C": "TSP", "D": "TSP"} if tau_g else None
    prior = FactorPrior(LogNormal(1.0, sigma_ln=0.6), contact_sigma_ln=s, group_sigma_ln=tau_g)
    cal = calibrate_bundle(models, _sized_campaign(), techniques=Technique(LogSizingModel(0.1)),
                           prior=prior, groups=groups, power_sigma_ln=0.0)
    mean, sd = _bundle_moments(cal)
    expected = _normal_normal(0.1, s, 0.6, groups=groups, tau_g=tau_g)
    assert mean == pytest.approx(expected[0], abs=5e-4)
    assert sd == pytest.approx(expected[1], rel=3e-3)


def test_a_contact_not_inspected_keeps_its_scatter_and_its_forecast_is_exact():
    models = {c: _model(p, c) for c, p in POWERS.items()}
    models["E"] = _model(5e-3, "E")               # never inspected
    s = 0.35
    prior = FactorPrior(LogNormal(1.0, sigma_ln=0.6), contact_sigma_ln=s)
    cal = calibrate_bundle(models, _sized_campaign(), techniques=Technique(LogSizingModel(0.1)),
                           prior=prior, power_sigma_ln=0.0)
    mu, tau = _normal_normal(0.1, s, 0.6)
    summary = cal.factor_summary().set_index("contact")
    # E: λ ~ N(μ_post, τ_post² + s²): the others' inspections cannot remove s
    assert summary.loc["E", "sigma_ln"] == pytest.approx(math.hypot(tau, s), rel=3e-3)
    assert not summary.loc["E", "inspected"]
    # P(D_E(30 y) > 0.4 mm) = P(λ > λ_L), f_L from the closed form D = A f^(2/3)
    limit = 4e-4
    f_limit = (limit / float(_depth(5e-3, 30.0, 1.0))) ** 1.5
    expected = stats.norm.sf(math.log(f_limit), mu, math.hypot(tau, s))
    fc = cal.forecast(30.0, limit=limit).set_index("contact")
    assert fc.loc["E", "exceedance"] == pytest.approx(expected, abs=2e-4)
    # the quantiles of the depth are the depths at the quantiles of the factor
    q95 = float(_depth(5e-3, 30.0, math.exp(mu + 1.6448536269514722 * math.hypot(tau, s))))
    assert fc.loc["E", "depth_q95"] == pytest.approx(q95, rel=2e-3)
    # the node decomposition sums back to each contact's exceedance (total probability; two
    # quadratures of one integral on the same grid: agreeing to 1e-3)
    p, w = cal.node_exceedance(30.0, limit=limit)
    assert p @ w == pytest.approx(cal.forecast(30.0, limit=limit).set_index("contact")
                                  .loc[cal.contacts, "exceedance"].to_numpy(), abs=1e-3)


def test_censored_likelihood_matches_an_independent_quadrature():
    models = {c: _model(POWERS[c], c) for c in ("A", "B", "C")}
    sizing = SizingModel(intercept=2e-5, slope=0.9, sigma=6e-5)
    pod = LogisticPOD.from_depths(a50=1.5e-4, a90=3e-4)
    campaign = pd.DataFrame({"contact": ["A", "B", "C"], "instant": [10.0, 10.0, 10.0],
                             "depth_mm": ["0.25", "NDD", ""], "inspected": ["", "", "no"]})
    mu0, tau0, s = 0.2, 0.5, 0.3
    cal = calibrate_bundle(models, campaign, techniques=Technique(sizing, pod),
                           prior=FactorPrior(LogNormal(math.exp(mu0), sigma_ln=tau0),
                                             contact_sigma_ln=s), power_sigma_ln=0.0)

    def lik_a(lam):     # sized 0.25 mm: N(m; a + b·D, σ²)
        return stats.norm.pdf(2.5e-4, 2e-5 + 0.9 * _depth(POWERS["A"], 10, np.exp(lam)), 6e-5)

    def lik_b(lam):     # NDD: 1 − POD(D), POD logistic in ln D
        d = _depth(POWERS["B"], 10, np.exp(lam))
        return 1.0 - expit(pod.beta0 + pod.beta1 * np.log(d))

    # Gauss-Legendre rules (400 nodes: exact to far below the tolerances for these smooth
    # integrands), nested: μ outside, λ = μ + s·u inside
    u, wu = np.polynomial.legendre.leggauss(400)
    lo, hi = mu0 - 8 * tau0, mu0 + 8 * tau0
    mu = 0.5 * (hi - lo) * u + 0.5 * (hi + lo)
    w_mu = 0.5 * (hi - lo) * wu
    lam = mu[:, None] + s * 9.0 * u[None, :]
    w_lam = 9.0 * s * wu[None, :] * stats.norm.pdf(lam, mu[:, None], s)

    def evidence(lik):
        return (lik(lam) * w_lam).sum(axis=1)

    post = stats.norm.pdf(mu, mu0, tau0) * evidence(lik_a) * evidence(lik_b)
    z = (post * w_mu).sum()
    mean = (mu * post * w_mu).sum() / z
    var = ((mu - mean) ** 2 * post * w_mu).sum() / z
    got_mean, got_sd = _bundle_moments(cal)
    assert got_mean == pytest.approx(mean, abs=1e-3)
    assert got_sd == pytest.approx(math.sqrt(var), rel=5e-3)
    # contact B (NDD): E[λ_B | D] = ∫∫ λ L_B(λ) N(λ; μ, s) p(μ|D)/M_B(μ) dλ dμ
    inner = (lam * lik_b(lam) * w_lam).sum(axis=1) / evidence(lik_b)
    mean_b = (inner * post * w_mu).sum() / z
    summary = cal.factor_summary().set_index("contact")
    assert summary.loc["B", "mean_ln"] == pytest.approx(mean_b, abs=2e-3)
    # an NDD pulls its contact's factor below the sized one's
    assert summary.loc["B", "median"] < summary.loc["A", "median"]


def test_ndd_needs_a_pod_and_unknown_contacts_are_named():
    models = {"A": _model(4e-3, "A")}
    ndd = pd.DataFrame({"contact": ["A"], "instant": [10.0], "depth_mm": ["NDD"]})
    # the fix named for both entry points (a new user on the command line read only Python)
    with pytest.raises(InputError, match=r"no POD.*--pod-a50-mm and --pod-a90-mm.*"
                                         r"LogisticPOD\.from_depths"):
        calibrate_bundle(models, ndd, techniques=Technique(SizingModel()))
    with pytest.raises(InputError, match="unknown contact 'Z'"):
        calibrate_bundle(models, ndd.assign(contact="Z"),
                         techniques=Technique(SizingModel(), LogisticPOD(0.0, 1.0)))


def test_bad_news_counts_leave_plugged_tubes_out():
    """summary_counts: contacts in service at or past the limit (median depth), the worst in
    service named, the plugged tubes counted apart; each contact its own tube here."""
    from fretwear.assessment.summary import summary_counts, tube_summary

    models = {c: _model(p, c) for c, p in POWERS.items()}
    campaign = _sized_campaign().assign(plugged=["", "", "", "yes"])
    cal = calibrate_bundle(models, campaign, techniques=Technique(LogSizingModel(0.1)),
                           power_sigma_ln=0.0)
    fc = cal.forecast(40.0, limit=4e-4)
    assert fc["contact"].iloc[-1] == "D" and fc["plugged"].iloc[-1]  # not in service: last
    counts = summary_counts(fc)
    past = fc[~fc["plugged"] & (fc["depth_q50"] >= 4e-4)]
    assert counts["contacts_past_limit"] == len(past) > 0
    assert counts["tubes_plugged"] == 1
    assert counts["worst_contact"] == fc[~fc["plugged"]]["contact"].iloc[0]
    assert tube_summary(fc).set_index("tube").loc["D", "plugged"]


def test_plugged_contacts_are_listed_not_forecast_and_leave_the_bundle_risk():
    """Issue 26: a plugged tube is out of service. Its contacts (every contact of the tube,
    a row naming one of them suffices) are listed as plugged with no depth and probability 0,
    and their rows of the node decomposition are 0, so P(any) = the in-service contacts'
    (1 - sum_k w_k prod_i (1 - p_ik) computed here without them)."""
    models = {c: _model(p, c) for c, p in POWERS.items()}
    identity = pd.DataFrame({"contact": list(POWERS), "tube_row": [1, 1, 2, 3],
                             "tube_column": [1, 1, 2, 3], "support": "AVB1"})  # A, B: one tube
    campaign = _sized_campaign().assign(plugged=["yes", "", "", ""])
    cal = calibrate_bundle(models, campaign, techniques=Technique(LogSizingModel(0.1)),
                           identity=identity, power_sigma_ln=0.0)
    assert cal.plugged.tolist() == [True, True, False, False]
    fc = cal.forecast(40.0, limit=4e-4).set_index("contact")
    for c in ("A", "B"):
        assert fc.loc[c, "plugged"] and fc.loc[c, "exceedance"] == 0.0
        assert fc.loc[c, "exceedance_prior"] == 0.0 and np.isnan(fc.loc[c, "depth_q50"])
    assert (fc.loc[["C", "D"], "exceedance"] > 0).all()
    p, w = cal.node_exceedance(40.0, limit=4e-4)
    assert not p[:2].any()
    # the same posterior with A and B unplugged: their rows were > 0, C and D's unchanged
    free = calibrate_bundle(models, _sized_campaign(), techniques=Technique(LogSizingModel(0.1)),
                            identity=identity, power_sigma_ln=0.0)
    p_free, w_free = free.node_exceedance(40.0, limit=4e-4)
    assert p_free[:2].any()
    np.testing.assert_array_equal(p[2:], p_free[2:])  # same process: the same floats
    np.testing.assert_array_equal(w, w_free)



def test_a_tube_row_reads_as_its_worst_contact():
    """A new user's trial: R4C3's row named AVB1 as its worst contact (the larger probability)
    beside AVB2's median depth (the larger depth). The row now gives the worst contact's own
    median depth and wall fraction; worst = largest probability, then deepest median."""
    from fretwear.assessment.summary import tube_summary

    fc = pd.DataFrame({"contact": ["R4C3-AVB1", "R4C3-AVB2", "R1C1-AVB1"],
                       "exceedance": [3e-5, 0.0, 0.0], "depth_q50": [2.0e-4, 2.45e-4, 1e-4],
                       "wall_fraction_q50": [0.18, 0.22, 0.09],
                       "inspected": [False, True, False], "plugged": [False, False, False]})
    ident = pd.DataFrame({"contact": fc["contact"], "tube_row": [4, 4, 1],
                          "tube_column": [3, 3, 1]})
    row = tube_summary(fc, ident).iloc[0]
    assert row["worst_contact"] == "R4C3-AVB1" and row["exceedance_max"] == 3e-5
    assert (row["worst_depth_q50"], row["worst_wall_fraction_q50"]) == (2.0e-4, 0.18)
    assert row["contacts"] == 2 and bool(row["inspected"])
