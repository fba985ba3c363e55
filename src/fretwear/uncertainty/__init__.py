"""Uncertainty of wear predictions: Monte Carlo propagation and calibration on inspections.

Engineers decide whether a tube reaches the plugging limit (commonly 40 % through the wall)
before the next outage, knowing that wear coefficients scatter by a factor of several, that the
wear power of a rattling tube is chaotic, and that inspections measure real depths.

- :func:`monte_carlo`: propagate distributions of the wear coefficients, the wear power and the
  dimensions to the worn depth (quantiles, probability of exceeding the limit, time to reach
  it, Sobol' indices) -> :class:`UncertaintyResult`;
- :func:`calibrate`: Bayesian update of a factor on the wear coefficients from measured depths,
  and the posterior predictive depth and exceedance probability of every contact;
- :class:`LogNormal`: the usual distribution of a wear coefficient (median and σ_ln or a
  scatter factor);
- the forward model is :class:`fretwear.table.DepthModel` (depth as a vectorised function of
  the inputs and time, and its inverse).

The model and how to read the outputs: docs/uncertainty.md.
"""

from fretwear.uncertainty.calibration import (
    CalibrationResult,
    GridPosterior,
    calibrate,
    read_inspections,
)
from fretwear.uncertainty.distributions import LogNormal, lognormal_sigma
from fretwear.uncertainty.monte_carlo import UncertaintyResult, Variable, monte_carlo
from fretwear.uncertainty.sampling import index_intervals, sobol_indices, uniform_points

__all__ = [
    "CalibrationResult",
    "GridPosterior",
    "LogNormal",
    "UncertaintyResult",
    "Variable",
    "lognormal_sigma",
    "calibrate",
    "monte_carlo",
    "read_inspections",
    "index_intervals",
    "sobol_indices",
    "uniform_points",
]
