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
