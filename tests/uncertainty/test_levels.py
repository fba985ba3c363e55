"""Bad confidence levels and quantile levels are a clear InputError everywhere (issue 25,
point 6): naming the argument and the value, on every posterior and every result, before any
computation (before: numpy's ValueError from np.quantile, (nan, nan) on a conjugate posterior
and the grid's ends on a grid one, a ``depth_q150`` column).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import InputError
from fretwear.keys import check_level, check_probabilities
from fretwear.power.confidence import batch_means_interval
from fretwear.table import wear_table
from fretwear.uncertainty import LogNormal, calibrate, monte_carlo, sobol_indices

R, W, K0, YEAR = 9.525e-3, 12.7e-3, 9.2e-15, 3.15576e7
BAD_LEVELS = [1.5, 0.0, 1.0, -0.1, 95, float("nan"), "0.9", None, True]
BAD_QUANTILES = [[1.5], [0.5, 95], [-0.01], [float("nan")], [], ["a"]]


def _table(**extra):
    kw = {"contact_type": "TUBE_BAV", "instants": [0.0, 10.0, 20.0], "time_scale": YEAR,
          "dimensions": {"mobile_radius": R, "obstacle_width": W},
          "coefficients": {"coefficient": K0}, "wall_thickness": 1.09e-3}
    kw.update(extra)
    return wear_table(0.01, **kw)


@pytest.fixture(scope="module")
def results():
    table = _table()
    tilted = _table(dimensions={"mobile_radius": R, "obstacle_width": W, "tilt_angle": 1.0})
    insp = pd.DataFrame({"instant": [8.0, 16.0], "depth": [0.30e-3, 0.42e-3]})
    conjugate = calibrate(table, insp, prior=LogNormal(1.0, sigma_ln=0.5))
    grid = calibrate(tilted, insp, prior=LogNormal(1.0, sigma_ln=0.5))
    assert (conjugate.method, grid.method) == ("conjugate", "grid")
    mc = monte_carlo(table, factor=LogNormal(1.0, sigma_ln=0.5), samples=64)
    return conjugate, grid, mc


@pytest.mark.parametrize("level", BAD_LEVELS)
def test_a_bad_level_is_an_input_error(results, level):
    conjugate, grid, _ = results
    for posterior in (conjugate, grid):
        with pytest.raises(InputError, match=r"level must be a probability in \(0, 1\)"):
            posterior.factor_interval(level=level)
    with pytest.raises(InputError, match="level must be a probability"):
        batch_means_interval([1.0, 1.1, 0.9, 1.05], level=level)
    with pytest.raises(InputError, match="level must be a probability"):
        sobol_indices(np.ones(4), np.ones(4), np.ones((1, 4)), level=level)


@pytest.mark.parametrize("q", BAD_QUANTILES)
def test_bad_quantile_levels_are_an_input_error(results, q):
    conjugate, grid, mc = results
    for posterior in (conjugate, grid):
        with pytest.raises(InputError, match=r"q must be probabilities in \(0, 1\)"):
            posterior.forecast(30.0, q=q)
    with pytest.raises(InputError, match=r"q must be probabilities in \[0, 1\]"):
        mc.time_to_limit_quantiles(q)
    with pytest.raises(InputError, match="q must be probabilities"):
        mc.quantiles(q)
    with pytest.raises(InputError, match="q must be probabilities"):
        mc.summary(q)


def test_the_named_value_and_good_levels(results):
    conjugate, grid, mc = results
    with pytest.raises(InputError, match=r"got \[95\]"):
        mc.time_to_limit_quantiles([0.5, 95])
    # the ends of a forecast's quantiles are refused (d(F⁻¹(0)) is no depth), not of Monte Carlo
    with pytest.raises(InputError, match=r"got \[0.0\]"):
        conjugate.forecast(30.0, q=[0.0, 0.5])
    assert mc.time_to_limit_quantiles([0.0, 1.0]).index.tolist() == [0.0, 1.0]
    lo, hi = grid.factor_interval(0.9)
    assert 0 < lo < grid.factor_median < hi
    assert check_level(np.float32(0.5)) == 0.5
    assert check_probabilities(0.5).tolist() == [0.5]
