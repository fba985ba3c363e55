"""Designs and Sobol' indices (fretwear.uncertainty.sampling) on functions with known indices.

- Additive f = Σ a_i·x_i, x_i ~ U(0, 1): S_i = S_T,i = a_i²/Σ a_j² (Var(x_i) = 1/12 each).
- Ishigami f = sin x₁ + a·sin² x₂ + b·x₃⁴·sin x₁, x_i ~ U(−π, π), a = 7, b = 0.1: V = a²/8 +
  bπ⁴/5 + b²π⁸/18 + 1/2, V₁ = (1 + bπ⁴/5)²/2, V₂ = a²/8, V₃ = 0, V_T3 = 8b²π⁸/225
  (Ishigami & Homma 1990; Sobol' & Levitan 1999).
- SALib (if installed): its Sobol' analysis of the same design gives the same estimates.
"""

import math

import numpy as np
import pytest

from fretwear.errors import InputError
from fretwear.uncertainty import LogNormal, lognormal_sigma, sobol_indices, uniform_points


def _saltelli(f, n, d, seed=0, method="sobol"):
    u = uniform_points(n, 2 * d, method=method, seed=seed)
    a, b = u[:, :d], u[:, d:]
    ab = []
    for i in range(d):
        m = a.copy()
        m[:, i] = b[:, i]
        ab.append(f(m))
    return f(a), f(b), np.array(ab)


def test_additive_function_indices():
    coef = np.array([1.0, 2.0, 3.0, 0.5])
    exact = coef ** 2 / np.sum(coef ** 2)
    s = sobol_indices(*_saltelli(lambda x: x @ coef, 2 ** 14, 4), resamples=100)
    np.testing.assert_allclose(s["first"], exact, atol=0.01)
    np.testing.assert_allclose(s["total"], exact, atol=0.01)
    assert (s["total_conf"] < 0.02).all() and (s["first_conf"] > 0).all()


def test_ishigami_indices():
    a, b = 7.0, 0.1

    def f(u):
        x = -math.pi + 2 * math.pi * u
        return np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])

    v = a ** 2 / 8 + b * math.pi ** 4 / 5 + b ** 2 * math.pi ** 8 / 18 + 0.5
    v1 = 0.5 * (1 + b * math.pi ** 4 / 5) ** 2
    v2 = a ** 2 / 8
    vt3 = 8 * b ** 2 * math.pi ** 8 / 225
    first = np.array([v1, v2, 0.0]) / v          # 0.3139, 0.4424, 0
    total = np.array([v1 + vt3, v2, vt3]) / v    # 0.5576, 0.4424, 0.2437
    s = sobol_indices(*_saltelli(f, 2 ** 15, 3), resamples=0)
    np.testing.assert_allclose(s["first"], first, atol=0.02)
    np.testing.assert_allclose(s["total"], total, atol=0.02)


def test_same_estimates_as_salib():
    salib_sample = pytest.importorskip("SALib.sample.sobol")
    salib_analyze = pytest.importorskip("SALib.analyze.sobol")
    problem = {"num_vars": 3, "names": ["x1", "x2", "x3"], "bounds": [[0, 1]] * 3}
    x = salib_sample.sample(problem, 1024, calc_second_order=False, seed=4)
    y = np.sin(6 * x[:, 0]) + 2 * x[:, 1] ** 2 + x[:, 0] * x[:, 2]
    ref = salib_analyze.analyze(problem, y, calc_second_order=False, num_resamples=10, seed=4)
    # SALib's layout: blocks of d + 2 rows: A, A_B^(1..d), B
    blocks = y.reshape(-1, 5)
    s = sobol_indices(blocks[:, 0], blocks[:, 4], blocks[:, 1:4].T, resamples=0)
    np.testing.assert_allclose(s["first"], ref["S1"], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(s["total"], ref["ST"], rtol=1e-10, atol=1e-12)


def test_designs():
    u = uniform_points(1000, 3, method="sobol", seed=1)
    assert u.shape == (1024, 3) and (u > 0).all() and (u < 1).all()
    # a balanced Sobol' block: each half of every axis holds exactly half of the points
    assert ((u < 0.5).sum(axis=0) == 512).all()
    assert np.array_equal(uniform_points(64, 2, seed=5), uniform_points(64, 2, seed=5))
    with pytest.raises(InputError, match="method"):
        uniform_points(64, 2, method="lhs")
    with pytest.raises(InputError, match="no uncertain input"):
        uniform_points(64, 0)


def test_lognormal():
    assert lognormal_sigma(3.0, 0.95) == pytest.approx(math.log(3) / 1.959963984540054)
    k = LogNormal(2e-14, scatter=3.0)
    assert float(k.ppf(0.025)) == pytest.approx(2e-14 / 3, rel=1e-12)
    assert float(k.cdf(2e-14)) == pytest.approx(0.5)
    with pytest.raises(InputError, match="exactly one"):
        LogNormal(1.0)
    with pytest.raises(InputError, match="no median"):
        LogNormal(sigma_ln=0.3).ppf(0.5)


def test_a_design_not_of_2_to_the_m_samples_is_refused():
    """scipy.stats.sobol_indices computes the indices: it needs N = 2^m (the balance of
    Sobol' points); another N is an InputError saying so, not scipy's ValueError."""
    rng = np.random.default_rng(3)
    fa, fb, fab = rng.random(1000), rng.random(1000), rng.random((2, 1000))
    with pytest.raises(InputError, match="2\\^m samples"):
        sobol_indices(fa, fb, fab, resamples=0)
    one = sobol_indices(fa[:512], fb[:512], fab[:1, :512], resamples=0)  # a single input
    assert one["first"].shape == (1,) and one["total"].shape == (1,)
