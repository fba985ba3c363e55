"""fretwear.assessment.assess against closed forms (issue 26, point 4).

Sources: the uniform-wear contact's time to a depth in closed form (tests/assessment/
synthetic.py); n independent identical contacts: P(any) = 1 − (1 − p)ⁿ; a sized contact's
probability as a scipy.integrate.quad over its true depth; an NDD contact's as a quad over
the factor weighted by 1 − POD; the greedy plugging list against every set of tubes.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
import synthetic
from scipy import integrate, stats

from fretwear.assessment import LogisticPOD, SizingModel
from fretwear.assessment.growth import FactorNodes
from fretwear.assessment.operational import plugging_list_brute_force
from fretwear.assessment.outage import assess

SIZING = SizingModel(intercept=0.0, slope=1.0, sigma=5e-5)
POD = LogisticPOD.from_depths(1.5e-4, 3e-4)
LIMIT = 0.4 * synthetic.WALL


def _run(powers, inspections=None, mu=0.0, s=0.3, **kw):
    nodes = FactorNodes([mu], [1.0], contact_sigma=s)
    return assess(synthetic.bundle(powers), inspections, interval=kw.pop("interval", 2.0),
                  sizing=SIZING, pod=POD, posterior=nodes, **kw)


@pytest.mark.parametrize("n", [1, 7, 50])
def test_identical_independent_contacts_give_one_minus_q_to_the_n(n):
    power = 0.1
    a = _run([power] * n)
    t_l = synthetic.tau(LIMIT, power)
    p = stats.norm.sf((math.log(t_l / 12.0) - 0.0) / 0.3)  # as found at 10, end at 12
    assert a.contacts["p_exceed"].to_numpy() == pytest.approx(np.full(n, p), rel=1e-10)
    assert a.bundle["p_any"] == pytest.approx(1 - (1 - p) ** n, rel=1e-10)


def test_longest_interval_is_the_closed_form_root():
    n, power, target = 20, 0.05, 0.05
    a = _run([power] * n, target=target, horizon=60.0)
    p_star = 1 - (1 - target) ** (1 / n)
    t_l = synthetic.tau(LIMIT, power)
    expected = t_l / math.exp(0.3 * stats.norm.isf(p_star)) - 10.0
    assert a.bundle["longest_interval"] == pytest.approx(expected, rel=1e-5)


def test_a_sized_contact_integrates_its_true_depth():
    power, measured = 0.1, 3.5e-4
    insp = pd.DataFrame({"contact": ["c0"], "instant": [10.0], "depth": [measured]})
    a = _run([power], insp)
    t_l = synthetic.tau(LIMIT, power)

    def integrand(d0):  # the growth after the as-found depth d0, over 2 years
        gap = (t_l - synthetic.tau(max(d0, 0.0), power)) / 2.0
        p = 1.0 if gap <= 0 else stats.norm.sf(math.log(gap) / 0.3)
        return p * stats.norm.pdf(d0, measured, 5e-5)

    expected = integrate.quad(integrand, measured - 10 * 5e-5, measured + 10 * 5e-5,
                              points=[LIMIT], limit=200, epsabs=1e-13)[0]
    assert a.contacts["p_exceed"].iloc[0] == pytest.approx(expected, rel=1e-6)


def test_an_ndd_contact_weighs_the_factor_by_the_miss():
    power = 0.1
    insp = pd.DataFrame({"contact": ["c0"], "instant": [10.0], "result": ["NDD"],
                         "depth": [None]})
    a = _run([power], insp, s=0.8)
    t_l = synthetic.tau(LIMIT, power)
    rate = power * synthetic.K * synthetic.YEAR / (2 * math.pi * synthetic.L_W * synthetic.R)

    def weight(u):  # density of u = ln g times the miss of the depth it gives at 10 years
        return stats.norm.pdf(u, 0.0, 0.8) * float(POD.miss(math.exp(u) * 10.0 * rate))

    cut = math.log(t_l / 12.0)
    num = integrate.quad(weight, cut, 8.0, epsabs=1e-14)[0]
    den = integrate.quad(weight, -8.0, 8.0, points=[cut], epsabs=1e-14)[0]
    # ln(1 − POD) linear between the 129 nodes of the u grid (step 0.1): 0.1 % of it
    assert a.contacts["p_exceed"].iloc[0] == pytest.approx(num / den, rel=2e-3)
    # the miss lowers it below the not-inspected contact's
    assert a.contacts["p_exceed"].iloc[0] < stats.norm.sf(cut / 0.8)


def test_contact_and_power_spreads_add_in_quadrature():
    nodes = FactorNodes([0.1], [1.0], contact_sigma=0.3, power_sigma=0.4)
    b = assess(synthetic.bundle([0.1]), None, interval=2.0, sizing=SIZING, pod=POD,
               posterior=nodes)
    t_l = synthetic.tau(LIMIT, 0.1)
    assert b.contacts["p_exceed"].iloc[0] == pytest.approx(
        stats.norm.sf((math.log(t_l / 12.0) - 0.1) / 0.5), rel=1e-10)


def test_greedy_plugging_matches_brute_force_with_a_shared_factor():
    rng = np.random.default_rng(26)
    powers = rng.lognormal(math.log(0.1), 0.5, 10)
    nodes = FactorNodes.from_posterior(stats.lognorm(0.4, scale=1.2), count=8,
                                       contact_sigma=0.2)
    a = assess(synthetic.bundle(list(powers)), None, interval=3.0, sizing=SIZING, pod=POD,
               posterior=nodes, target=0.01)
    brute = plugging_list_brute_force(a.risk, 0.01)
    assert len(a.bundle["plugging"]) == len(brute) > 0
    assert a.risk.probability_any(a.bundle["plugging"]) <= 0.01
    # the next inspection's sample leaves the plugged tubes out (a new user saw R4C2 both to be
    # plugged and to be inspected): the fewest of the other tubes covering the share of their
    # own risk, by brute force over the tubes in service
    plugged = set(a.bundle["plugging"])
    sample = a.bundle["inspection_sample"]
    assert plugged.isdisjoint(sample)
    p = dict(zip(a.risk.tubes, a.risk.tube_probabilities(), strict=True))
    live = sorted((v for t, v in p.items() if t not in plugged), reverse=True)
    need = a.bundle["share"] * sum(live) * (1 - 1e-12)
    fewest = next(k for k in range(1, len(live) + 1) if sum(live[:k]) >= need)
    assert len(sample) == fewest


def test_a_tube_past_the_limit_as_measured_is_plugged_and_said_first():
    insp = pd.DataFrame({"contact": ["c0", "c1"], "instant": [10.0, 10.0],
                         "depth": [1.2e-3, 5.0e-4]})
    a = _run([0.01, 0.01, 0.01], insp)
    assert a.bundle["must_plug"] == ["R1C1", "R1C2"]
    assert set(a.bundle["must_plug"]) <= set(a.bundle["plugging"])
    news = a.bad_news()
    assert "THROUGH THE WALL" in news[0] and "AT OR PAST" in news[1]
    assert a.tubes.set_index("tube").loc["R1C1", "reason"].startswith("at or past")


def test_plugged_tubes_leave_the_risk():
    insp = pd.DataFrame({"contact": ["c0"], "instant": [10.0], "depth": [None],
                         "result": ["NDD"], "plugged": ["true"]})
    a = _run([0.05, 0.01], insp)
    assert a.bundle["plugged_already"] == ["R1C1"]
    assert "R1C1" not in a.risk.tubes.tolist()


def test_the_hierarchical_calibration_feeds_the_nodes():
    from fretwear.assessment import Technique
    from fretwear.assessment.calibration import calibrate_bundle
    from fretwear.assessment.contacts import bundle_models

    bundle = synthetic.bundle([0.05, 0.06, 0.07, 0.08])
    models = dict(zip(*(bundle_models(bundle)[c] for c in ("contact", "model")), strict=True))
    insp = pd.DataFrame({"contact": ["c0", "c1", "c2"], "instant": [10.0] * 3,
                         "depth": ["3e-4", "3.5e-4", "NDD"]})
    cal = calibrate_bundle(models, insp, techniques=Technique(sizing=SIZING, pod=POD),
                           power_sigma_ln=0.2)
    a = assess(bundle, insp, interval=2.0, sizing=SIZING, pod=POD, posterior=cal)
    assert a.nodes.contact_sigma == cal.prior.contact_sigma_ln
    assert a.nodes.power_sigma == pytest.approx(0.2, rel=1e-12)
    # the nodes' distribution is the bundle-level posterior's: its median at the 0.5 quantile
    # (s = 0 for the check: the nodes alone; a discrete median of 16 nodes, within 10 %)
    alone = FactorNodes(a.nodes.log_factor, a.nodes.weights)
    assert math.exp(alone.quantiles([0.5])[0]) == pytest.approx(cal.bundle_factor()[0],
                                                                rel=0.1)


# ---------------------------------------------------------------- the hierarchical default
# An independent quadrature of the hierarchical censored posterior, written here: the
# likelihood of each inspected contact on a grid of its λ = ln f (sized: the additive sizing
# error's normal density of the depth f·t·r; NDD: 1 - POD), its evidence on its group's factor
# M_i(c) = ∫ L_i(λ) N(λ; c, s²) dλ (trapezoid on a fine grid), and the factor's levels
# integrated on grids: p(μ) ∝ N(μ; ln 1, τ0²) Π_g ∫ N(c; μ, τ_g²) Π_{i∈g} M_i(c) dc.
LAM = np.linspace(-7.0, 7.0, 2801)
S_C, S_P = 0.35, 0.2
S = math.hypot(S_C, S_P)


def _rate(power):
    """Depth per year at f = 1 [m/year] (TUBE_ALESAGE's closed form, synthetic.py)."""
    return power * synthetic.K * synthetic.YEAR / (2 * math.pi * synthetic.L_W * synthetic.R)


def _evidence(power, measured=None):
    """M_i(c) on LAM, of a contact sized (``measured`` [m]) or NDD (None) at 10 years."""
    depth = np.exp(LAM) * 10.0 * _rate(power)
    lik = stats.norm.pdf(measured, depth, 5e-5) if measured is not None else POD.miss(depth)
    kern = stats.norm.pdf(LAM[None, :], LAM[:, None], S)           # [c, λ]
    return np.trapezoid(kern * lik[None, :], LAM, axis=1)


def _survival(power, interval):
    """1 - P(contact not inspected exceeds the limit | its group's factor c), on LAM."""
    x = math.log(synthetic.tau(LIMIT, power) / (10.0 + interval))
    return 1.0 - stats.norm.sf((x - LAM) / S)


def _hierarchical_case(supports):
    powers = [0.05, 0.05, 0.05, 0.08, 0.1, 0.12, 0.09]
    bundle = synthetic.bundle(powers)
    bundle.contacts["support"] = supports
    insp = pd.DataFrame({"contact": ["c0", "c1", "c2"], "instant": [10.0] * 3,
                         "depth": ["1.9e-4", "2.0e-4", "NDD"]})
    evidence = {"c0": _evidence(0.05, 1.9e-4), "c1": _evidence(0.05, 2.0e-4),
                "c2": _evidence(0.05)}
    return bundle, insp, powers, evidence


def test_the_default_calibration_is_the_hierarchical_one_against_a_quadrature():
    """One level (no groups): the contacts not inspected are independent given μ, so
    P(any of them) = 1 - ∫ p(μ|D) Π_i (1 - p_i(μ)) dμ, against the OA's nodes (16
    Gauss-Hermite nodes through the grid posterior's quantiles: within 1e-3)."""
    from fretwear.assessment.calibration import FactorPrior

    bundle, insp, powers, evidence = _hierarchical_case("TSP1")
    a = assess(bundle, insp, interval=2.0, sizing=SIZING, pod=POD)  # the defaults
    assert a.inputs["calibration"]["method"] == "hierarchical"
    assert (a.inputs["contact_sigma_ln"], a.inputs["power_sigma_ln"]) == (S_C, S_P)
    tau0 = FactorPrior().bundle.sigma_ln
    post = stats.norm.pdf(LAM, 0.0, tau0) * np.prod(list(evidence.values()), axis=0)
    post /= np.trapezoid(post, LAM)
    survive = [_survival(p, 2.0) for p in powers[3:]]
    for k, q in enumerate(survive, start=3):
        p_k = a.contacts.set_index("contact").loc[f"c{k}", "p_exceed"]
        assert p_k == pytest.approx(1.0 - np.trapezoid(post * q, LAM), rel=1e-3)
    p_any = 1.0 - np.trapezoid(post * np.prod(survive, axis=0), LAM)
    assert a.risk.probability_any(["R1C1", "R1C2", "R1C3"]) == pytest.approx(p_any, rel=1e-3)


def test_the_group_level_is_carried_into_the_assessment_against_a_quadrature():
    """Two support types (τ_g = 0.3): contacts of one type share its factor c_g, the types
    independent given μ, so P(none of the contacts not inspected) =
    ∫ N(μ) Π_g [∫ N(c; μ, τ_g²) M_g(c) Q_g(c) dc] dμ / ∫ N(μ) Π_g [∫ N(c; μ, τ_g²) M_g(c) dc] dμ
    (M_g the product of the group's evidences, Q_g of its uninspected survivals), against the
    OA's 8 × 5² joint nodes (within 1e-3; they agree to 1e-4 here, while treating the
    contacts of a group as independent given μ would give 0.732 against 0.706)."""
    from fretwear.assessment.calibration import FactorPrior

    supports = ["AVB1", "TSP2", "AVB1", "AVB2", "AVB3", "TSP1", "TSP3"]
    bundle, insp, powers, evidence = _hierarchical_case(supports)
    a = assess(bundle, insp, interval=2.0, sizing=SIZING, pod=POD, group_sigma_ln=0.3)
    assert a.inputs["calibration"]["groups"] == ["AVB", "TSP"]
    assert a.nodes.table.shape == (2, 8 * 5 * 5)
    tau0 = FactorPrior().bundle.sigma_ln
    kern = stats.norm.pdf(LAM[None, :], LAM[:, None], 0.3)        # [μ, c]
    members = {"AVB": [0, 2, 3, 4], "TSP": [1, 5, 6]}
    top, bottom = stats.norm.pdf(LAM, 0.0, tau0), stats.norm.pdf(LAM, 0.0, tau0)
    for idx in members.values():
        m_g = np.prod([evidence[f"c{i}"] for i in idx if f"c{i}" in evidence], axis=0)
        q_g = np.prod([_survival(powers[i], 2.0) for i in idx if i >= 3], axis=0)
        top = top * np.trapezoid(kern * (m_g * q_g)[None, :], LAM, axis=1)
        bottom = bottom * np.trapezoid(kern * m_g[None, :], LAM, axis=1)
    p_any = 1.0 - np.trapezoid(top, LAM) / np.trapezoid(bottom, LAM)
    assert a.risk.probability_any(["R1C1", "R1C2", "R1C3"]) == pytest.approx(p_any, rel=1e-3)


def test_the_longest_interval_is_taken_after_the_plugging_list():
    """n cold contacts and 3 hot ones, one factor node (independent contacts): the greedy
    list plugs the hot tubes, and the longest interval then solves 1 - (1 - p(T))ⁿ = target
    over the n cold ones alone, p(T) = Φ̄(ln(τ_L/(10 + T))/σ), in closed form; before
    plugging it is the root with every tube in service (brentq here)."""
    from scipy.optimize import brentq

    n, cold, hot, target = 20, 0.05, 0.3, 0.05
    a = _run([hot] * 3 + [cold] * n, target=target, horizon=60.0)
    assert a.bundle["plugging"] == ["R1C1", "R1C2", "R1C3"]
    t_cold, t_hot = synthetic.tau(LIMIT, cold), synthetic.tau(LIMIT, hot)
    p_star = 1 - (1 - target) ** (1 / n)
    expected = t_cold / math.exp(0.3 * stats.norm.isf(p_star)) - 10.0
    assert a.bundle["longest_interval"] == pytest.approx(expected, rel=1e-5)

    def p_any(t):
        p_c = stats.norm.sf(math.log(t_cold / (10 + t)) / 0.3)
        p_h = stats.norm.sf(math.log(t_hot / (10 + t)) / 0.3)
        return 1 - (1 - p_c) ** n * (1 - p_h) ** 3 - target

    before = brentq(p_any, 0.0, 60.0, xtol=1e-12) if p_any(0.0) < 0 else 0.0
    assert a.bundle["longest_interval_before_plugging"] == pytest.approx(before, abs=1e-4)
    assert a.bundle["longest_interval_before_plugging"] < a.bundle["longest_interval"]
    # the curve is the plugged bundle's: the target crossed at the longest interval
    assert a.bundle["p_any_after_plugging"] == pytest.approx(
        1 - (1 - stats.norm.sf(math.log(t_cold / 12.0) / 0.3)) ** n, rel=1e-10)
