"""The depth model as an openturns.Function (issue 26, point 7), checked against closed forms.

Archard on TUBE_BAV without tilt: D = A·(f·r)^(2/3) (docs/theory.md). With ln f ~ N(0, a²) and
ln r ~ N(0, b²) independent, Y = A·exp(c(X₁ + X₂)), c = 2/3, has the Sobol' indices

    S_f = (e^{c²a²} − 1)/(e^{c²(a²+b²)} − 1),   S_f^T = 1 − (e^{c²b²} − 1)/(e^{c²(a²+b²)} − 1)

(Var E[Y|X₁] = A²e^{c²b²}e^{c²a²}(e^{c²a²} − 1), lognormal moments). OpenTURNS' Saltelli and
Martinez estimators on the function are compared with them, and its random-walk
Metropolis-Hastings posterior with fretwear's conjugate calibration of the same contact.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table.depth import DepthModel
from fretwear.uncertainty import LogNormal, calibrate, sobol_indices
from fretwear.uncertainty.openturns_bridge import (
    depth_callable,
    depth_function,
    input_distribution,
)

ot = pytest.importorskip("openturns")

YEAR = 31536000.0


def _model(power=5e-3, name="A"):
    g = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)
    return DepthModel(law=get_law("ARCHARD"), geometry=g, powers=(power,),
                      coefficients_mobile=({"coefficient": 1e-14},),
                      coefficients_obstacle=(None,), time_scale=YEAR, name=name)


def test_the_function_is_the_depth_model():
    models = {"A": _model(5e-3, "A"), "B": _model(1e-2, "B")}
    f = depth_function(models, 10.0)
    assert f.getInputDimension() == 2 and f.getOutputDimension() == 2
    y = np.array(f(ot.Sample([[1.5, 0.8], [1.0, 1.0]])))
    for j, m in enumerate(models.values()):
        assert y[0, j] == pytest.approx(float(m.depth(10 * YEAR, factor=1.5 * 0.8)), rel=1e-12)
        assert y[1, j] == pytest.approx(float(m.depth(10 * YEAR)), rel=1e-12)
    assert np.allclose(depth_callable(models, 10.0)(np.array([[1.5, 0.8]])), y[:1], rtol=1e-14)


@pytest.mark.parametrize("algorithm", ["SaltelliSensitivityAlgorithm",
                                       "MartinezSensitivityAlgorithm"])
def test_openturns_sobol_estimators_on_the_function_match_the_closed_form(algorithm):
    a, b, c = 0.5, 0.3, 2.0 / 3.0
    ot.RandomGenerator.SetSeed(26)
    dist = input_distribution(LogNormal(1.0, sigma_ln=a), LogNormal(1.0, sigma_ln=b))
    size = 16384  # a power of two: fretwear's estimator (SciPy) asks for one
    design = ot.SobolIndicesExperiment(dist, size).generate()
    output = depth_function(_model(), 10.0)(design)
    est = getattr(ot, algorithm)(design, output, size)
    total = math.exp(c * c * (a * a + b * b)) - 1.0
    s_f = (math.exp(c * c * a * a) - 1.0) / total
    st_f = 1.0 - (math.exp(c * c * b * b) - 1.0) / total
    # Monte Carlo with 16 384 base points: 0.03 is several standard errors
    assert est.getFirstOrderIndices()[0] == pytest.approx(s_f, abs=0.03)
    assert est.getTotalOrderIndices()[0] == pytest.approx(st_f, abs=0.03)
    # fretwear's estimator on OpenTURNS' design (rows A, B, A with column i from B)
    y = np.array(output)[:, 0].reshape(-1, size)
    mine = sobol_indices(y[0], y[1], y[2:], resamples=0)
    assert mine["first"][0] == pytest.approx(s_f, abs=0.03)
    assert mine["total"][0] == pytest.approx(st_f, abs=0.03)


def test_metropolis_hastings_matches_the_conjugate_calibration():
    model = _model()
    measured = [2.2e-4, 2.6e-4, 2.4e-4]
    instants = [10.0, 12.0, 11.0]
    sigma, mu0, tau0 = 0.15, 0.0, 0.6
    table = pd.DataFrame({"instant": instants, "depth": measured})
    conj = calibrate(model, table, prior=LogNormal(1.0, sigma_ln=tau0),
                     measurement_sigma=sigma, method="conjugate")
    fns = [depth_function(model, t) for t in instants]

    def log_post(x):
        lam = x[0]
        out = -0.5 * ((lam - mu0) / tau0) ** 2
        for fn, m in zip(fns, measured, strict=True):
            d = fn([math.exp(lam), 1.0])[0]
            out += -0.5 * ((math.log(m) - math.log(d)) / sigma) ** 2
        return [out]

    ot.RandomGenerator.SetSeed(7)
    target = ot.PythonFunction(1, 1, log_post)
    sampler = ot.RandomWalkMetropolisHastings(target, ot.Interval([-5.0], [5.0]), [0.0],
                                              ot.Normal(0.0, 0.15))
    sample = np.array(sampler.getSample(4000))[500:, 0]
    # 3 500 correlated draws: the mean within 0.03 (several Monte Carlo standard errors)
    assert sample.mean() == pytest.approx(math.log(conj.posterior.median), abs=0.03)
    assert sample.std() == pytest.approx(conj.posterior.sigma_ln, rel=0.15)
