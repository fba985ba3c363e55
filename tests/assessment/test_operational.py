"""Operational assessment against closed forms and brute force.

Sources: P(any) = 1 − (1 − p)ⁿ for n independent identical contacts (the complement of all
surviving); with a shared factor, the law of total probability over the factor's nodes,
computed here contact by contact with plain Python floats; the fewest tubes to plug by trying
every set; the logistic POD's defining equation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from fretwear.assessment import (
    LogisticPOD,
    SizingModel,
    bundle_risk,
    inspection_sample,
    longest_interval,
    plugging_list,
)
from fretwear.assessment.operational import plugging_list_brute_force
from fretwear.errors import InputError


@pytest.mark.parametrize("n, p", [(1, 0.3), (10, 0.01), (100_000, 1e-9), (9727, 2e-6)])
def test_independent_identical_contacts(n, p):
    risk = bundle_risk(np.full(n, p), tubes=np.arange(n))
    assert risk.probability_any() == pytest.approx(-math.expm1(n * math.log1p(-p)), rel=1e-12)


def test_contacts_of_one_tube_combine_and_tubes_combine():
    # two tubes of two contacts each: tube A fails if either contact does
    risk = bundle_risk([0.1, 0.2, 0.05, 0.0], tubes=["A", "A", "B", "B"])
    assert risk.tube_probabilities() == pytest.approx([1 - 0.9 * 0.8, 0.05], rel=1e-14)
    assert risk.probability_any() == pytest.approx(1 - 0.9 * 0.8 * 0.95, rel=1e-14)
    assert risk.probability_any(without=["A"]) == pytest.approx(0.05, rel=1e-14)


def test_shared_factor_by_total_probability():
    """Given the factor the contacts are independent; over the factor they are not: P_any is
    the nodes' weighted mean of 1 − Π(1 − p_ik), not 1 − Π(1 − mean p)."""
    rng = np.random.default_rng(3)
    p = np.outer(rng.uniform(0.2, 1.0, 6), [0.01, 0.1, 0.4, 0.8])  # rises with the factor
    w = np.array([0.1, 0.2, 0.3, 0.4])
    tubes = [0, 0, 1, 2, 2, 2]
    expected = 0.0
    for k in range(4):
        survive = 1.0
        for i in range(6):
            survive *= 1.0 - float(p[i, k])
        expected += float(w[k]) * (1.0 - survive)
    risk = bundle_risk(p, tubes, weights=w * 3.0)  # weights are normalised
    assert risk.probability_any() == pytest.approx(expected, rel=1e-13)
    independent = 1 - np.prod(1 - p @ w)
    assert abs(risk.probability_any() - independent) > 1e-3  # the sharing matters


@pytest.mark.parametrize("seed", range(6))
def test_greedy_plugging_is_the_fewest(seed):
    """Independent tubes, and a shared lognormal factor scaling every contact's wear (tubes
    ordered alike at every node): the greedy list is as short as brute force's, and meets the
    target."""
    rng = np.random.default_rng(seed)
    n = 9
    tubes = rng.integers(0, 7, size=n)
    independent = bundle_risk(rng.uniform(0, 0.15, n), tubes)
    # shared factor: contact i exceeds when f·r_i > 1, r_i its nominal ratio; f lognormal
    nodes, weights = np.polynomial.hermite_e.hermegauss(9)
    f = np.exp(0.4 * nodes)
    ratio = rng.uniform(0.2, 0.8, n)
    p = stats.norm.cdf((np.log(f[None, :] * ratio[:, None])) / 0.3)
    shared = bundle_risk(p, tubes, weights=weights)
    for risk in (independent, shared):
        for target in (0.2, 0.05, 0.01):
            greedy = plugging_list(risk, target)
            assert risk.probability_any(greedy) <= target
            assert len(greedy) == len(plugging_list_brute_force(risk, target))


def test_plugging_starts_from_the_tubes_past_the_limit():
    risk = bundle_risk([0.3, 0.01, 0.2, 0.001], tubes=["A", "B", "C", "D"])
    assert plugging_list(risk, 0.05, always=["D"]) == ["D", "A", "C"]
    with pytest.raises(InputError, match="not in the bundle"):
        plugging_list(risk, 0.05, always=["Z"])


def test_longest_interval_inverts_the_closed_form():
    """n contacts of p(T) = 1 − exp(−λT) (a constant hazard): P_any(T) = 1 − exp(−nλT), so
    T* = −ln(1 − target)/(nλ)."""
    n, lam, target = 50, 1e-10, 0.05
    t = longest_interval(lambda T: bundle_risk(np.full(n, -math.expm1(-lam * T)), range(n)),
                         target, upper=1e12)
    assert t == pytest.approx(-math.log1p(-target) / (n * lam), rel=1e-9)
    assert longest_interval(lambda T: bundle_risk([0.0], [0]), 0.05, upper=7.0) == 7.0
    with pytest.raises(InputError, match="missed already"):
        longest_interval(lambda T: bundle_risk([0.5], [0]), 0.05, upper=1.0)


def test_inspection_sample_covers_the_share_with_the_fewest():
    rng = np.random.default_rng(1)
    p = rng.uniform(0, 0.05, 40)
    risk = bundle_risk(p, range(40))
    sample = inspection_sample(risk, 0.5)
    pt = dict(zip(range(40), p, strict=True))
    covered = sum(pt[t] for t in sample)
    assert covered >= 0.5 * p.sum()
    assert covered - min(pt[t] for t in sample) < 0.5 * p.sum()  # one fewer would not do


@pytest.mark.parametrize("bad", [1.5, 0.0, -0.1, float("nan"), "x"])
def test_bad_levels_are_input_errors(bad):
    risk = bundle_risk([0.1], [0])
    with pytest.raises(InputError, match="target"):
        plugging_list(risk, bad)
    with pytest.raises(InputError, match="share"):
        inspection_sample(risk, bad)


@pytest.mark.parametrize("bad", [1.5, -0.1, float("nan"), float("inf")])
def test_bad_contact_probabilities_are_input_errors(bad):
    with pytest.raises(InputError, match="contact 1"):
        bundle_risk([0.1, bad], [0, 1])


def test_logistic_pod_and_sizing():
    pod = LogisticPOD.from_depths(a50=2e-4, a90=4e-4)
    d = np.array([1e-4, 2e-4, 4e-4, 8e-4])
    # the defining equation: logit POD = β0 + β1 ln d
    logit = np.log(pod(d) / pod.miss(d))
    assert logit == pytest.approx(pod.beta0 + pod.beta1 * np.log(d), rel=1e-12)
    assert pod(d) + pod.miss(d) == pytest.approx(np.ones(4), rel=1e-15)
    assert float(pod(0.0)) == 0.0
    linear = LogisticPOD.from_depths(2e-4, 4e-4, log_depth=False)
    assert float(linear(3e-4)) == pytest.approx(1 / (1 + 3 ** -1), rel=1e-12)  # midway: √9
    s = SizingModel(intercept=1e-5, slope=0.9, sigma=5e-5)
    grid = np.linspace(-1e-3, 2e-3, 200_001)
    assert np.trapezoid(s.likelihood(grid, 5e-4), grid) == pytest.approx(1.0, rel=1e-9)
    assert s.true_depth(1e-5 + 0.9 * 5e-4) == pytest.approx(5e-4, rel=1e-12)
    for make in (lambda: LogisticPOD(0.0, -1.0), lambda: LogisticPOD.from_depths(4e-4, 2e-4),
                 lambda: SizingModel(sigma=0.0), lambda: SizingModel(slope=float("nan"))):
        with pytest.raises(InputError):
            make()
