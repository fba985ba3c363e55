"""Confidence intervals of the wear power (fretwear.power.confidence, PowerResult methods).

Oracles: scipy.stats.t.interval on the same numbers (an independent computation of the
Student interval), the coverage of the interval on independent normal blocks (it must hold
its level), and the lag-1 autocorrelation of an AR(1) sequence.
"""

import math
import warnings

import numpy as np
import pytest
from scipy import stats

from fretwear.errors import ConfidenceWarning, InputError
from fretwear.history import ContactHistory
from fretwear.power import wear_power
from fretwear.power.confidence import (
    PowerInterval,
    batch_means_interval,
    ensemble_interval,
    format_interval,
    lag1_autocorrelation,
)


def test_interval_equals_scipy_student_interval():
    rng = np.random.default_rng(3)
    blocks = 0.184 + 0.02 * rng.standard_normal(16)
    iv = batch_means_interval(blocks, 0.9)
    low, high = stats.t.interval(0.9, 15, loc=blocks.mean(), scale=stats.sem(blocks))
    assert iv.estimate == pytest.approx(blocks.mean(), rel=1e-15)
    assert iv.estimate - iv.half_width == pytest.approx(low, rel=1e-13)
    assert iv.high == pytest.approx(high, rel=1e-13)
    assert iv.dof == 15 and iv.count == 16 and iv.warnings == ()


def test_coverage_on_independent_normal_blocks():
    """2000 sets of 12 independent normal blocks: the 95 % interval holds the true mean in
    95 % of them, within 4 binomial standard errors (0.0195)."""
    rng = np.random.default_rng(7)
    hits = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConfidenceWarning)  # a few sets look correlated
        for _ in range(2000):
            iv = batch_means_interval(1.0 + 0.1 * rng.standard_normal(12), 0.95)
            hits += iv.low <= 1.0 <= iv.high
    assert abs(hits / 2000 - 0.95) < 4 * math.sqrt(0.95 * 0.05 / 2000)


def test_correlated_blocks_warn():
    """AR(1) block powers x_k = 0.9 x_(k-1) + e_k: lag-1 autocorrelation near 0.9."""
    rng = np.random.default_rng(1)
    x = np.zeros(60)
    for k in range(1, 60):
        x[k] = 0.9 * x[k - 1] + rng.standard_normal()
    assert lag1_autocorrelation(x) > 0.6
    with pytest.warns(ConfidenceWarning, match="correlated"):
        iv = batch_means_interval(1.0 + 0.01 * x)
    assert any("correlated" in w for w in iv.warnings)


def test_few_blocks_warn_and_one_block_is_refused():
    with pytest.warns(ConfidenceWarning, match="only 4 blocks"):
        batch_means_interval([1.0, 1.1, 0.9, 1.0])
    with pytest.raises(InputError, match="blocks >= 2"):
        batch_means_interval([1.0])
    with pytest.raises(InputError, match="level"):
        batch_means_interval([1.0, 2.0], level=95)


def test_lag1_autocorrelation_by_hand():
    # x - mean = (-1.5, -0.5, 0.5, 1.5): numerator 0.75 - 0.25 + 0.75 = 1.25, denominator 5
    assert lag1_autocorrelation([1.0, 2.0, 3.0, 4.0]) == pytest.approx(0.25, rel=1e-15)


@pytest.mark.parametrize(("estimate", "half", "level", "text"), [
    (0.18417, 0.01234, 0.95, "P = 0.184 ± 0.012 W (95 %)"),
    (12.34, 1.26, 0.99, "P = 12.3 ± 1.3 W (99 %)"),
    (0.5, math.nan, 0.95, "P = 0.5 W (95 %: no interval)"),
])
def test_format(estimate, half, level, text):
    assert format_interval(estimate, half, level) == text


def _history(seed, n=40001, duration=40.0, sectors=False):
    """Rattling-like history: random force bursts with a drifting contact angle."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, duration, n)
    fn = np.maximum(0.0, rng.standard_normal(n).cumsum() * 0.05 % 3.0 - 1.0)
    vt1 = 0.1 * np.sin(7.0 * t) + 0.02 * rng.standard_normal(n)
    vt2 = 0.05 * np.cos(3.0 * t)
    angle = np.radians(170.0 * np.sin(0.37 * t))
    return ContactHistory(time=t, normal_force=fn, vt1=vt1, vt2=vt2,
                          dy=1e-4 * np.cos(angle), dz=1e-4 * np.sin(angle))


def test_power_result_interval_and_sector_intervals():
    h = _history(0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = wear_power(h, blocks=20, sectors=4, t_start=0.0, t_end=40.0,
                       stationarity_threshold=10.0)
        iv = r.confidence_interval(0.95)
        sector_ivs = r.sector_confidence_intervals(0.95)
    np.testing.assert_allclose(r.block_sectors.sum(axis=1), r.blocks, rtol=1e-12)
    np.testing.assert_allclose(r.block_sectors.mean(axis=0), r.sectors, rtol=1e-12)
    assert iv.estimate == pytest.approx(r.total, rel=1e-12)
    assert isinstance(iv, PowerInterval) and iv.count == 20
    assert [s.name for s in sector_ivs] == [f"power sector {j}" for j in range(1, 5)]
    for j, s in enumerate(sector_ivs):
        col = r.block_sectors[:, j]
        assert s.estimate == pytest.approx(r.sectors[j], rel=1e-12)
        expected = stats.t.ppf(0.975, 19) * col.std(ddof=1) / math.sqrt(20)
        assert s.half_width == pytest.approx(expected, rel=1e-12)
    with pytest.raises(InputError, match="1..4"):
        r.confidence_interval(sector=5)
    assert str(iv).startswith("P = ") and str(iv).endswith(" W (95 %)")
    assert r.to_dict()["block_sectors"][0] == pytest.approx(r.block_sectors[0].tolist())


def test_ensemble_of_runs():
    """Five runs of different seeds: the mean of their powers with a t(4) interval."""
    results = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for seed in range(5):
            results.append(wear_power(_history(seed, n=4001, duration=4.0), blocks=2,
                                      t_start=0.0, t_end=4.0, stationarity_threshold=10.0))
    totals = np.array([r.total for r in results])
    with pytest.warns(ConfidenceWarning, match="only 5 runs"):
        iv = ensemble_interval(results, 0.95)
    assert iv.method == "ensemble" and iv.dof == 4
    low, high = stats.t.interval(0.95, 4, loc=totals.mean(), scale=stats.sem(totals))
    assert (iv.estimate - iv.half_width, iv.high) == pytest.approx((low, high), rel=1e-12)
    # a single run falls back on its own block interval
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConfidenceWarning)
        single = ensemble_interval(results[:1])
    assert single.method == "batch means" and single.count == 2


def test_distribution_is_truncated_student():
    iv = batch_means_interval(np.random.default_rng(0).permutation(np.linspace(0.9, 1.1, 12)))
    d = iv.distribution()
    assert float(d.ppf(0.5)) == pytest.approx(iv.estimate, rel=1e-12)
    q = float(d.ppf(0.975))
    assert q - iv.estimate == pytest.approx(iv.half_width, rel=1e-6)  # truncation negligible
    wide = PowerInterval(estimate=0.01, half_width=1.0, level=0.95, standard_error=0.5, dof=3,
                         count=4).distribution()
    assert float(wide.ppf(1e-9)) >= 0.0 and float(wide.cdf(0.0)) == 0.0
