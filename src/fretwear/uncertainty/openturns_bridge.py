"""The depth model as an OpenTURNS function, with its inputs' distribution (the [openturns] extra).

OpenTURNS (EDF, Airbus, Phimeca; wheels on PyPI) holds the uncertainty toolbox of the nuclear
industry: Sobol' estimators (Saltelli, Martinez, Jansen ...), Markov-chain calibration,
reliability methods. :func:`depth_function` wraps the depth of one contact, or of a bundle's
contacts, at an instant as an ``openturns.Function`` of (factor, power ratio) — the factor f on
the wear coefficients [-] and the ratio r of the power to its nominal value [-], each
contact's depth being ``DepthModel.depth(t, factor=f, power=r·P)`` — and
:func:`input_distribution` their lognormal distributions as an ``openturns.Distribution``.
:func:`depth_callable` is the same model as a plain vectorised callable (SALib, SciPy).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping

import numpy as np

from fretwear._optional import require
from fretwear.errors import InputError, RangeWarning
from fretwear.table.depth import DepthModel
from fretwear.uncertainty.distributions import LogNormal

__all__ = ["INPUTS", "depth_callable", "depth_function", "input_distribution"]

#: The inputs of the function, in order: name -> (unit, meaning).
INPUTS = {"factor": ("-", "factor on the wear coefficients"),
          "power_ratio": ("-", "power over its nominal value")}


def _models(models) -> dict[str, DepthModel]:
    if isinstance(models, DepthModel):
        return {models.name or "contact": models}
    if isinstance(models, Mapping) and models and all(isinstance(m, DepthModel)
                                                      for m in models.values()):
        return dict(models)
    raise InputError("give a DepthModel or a mapping of contact name to DepthModel")


def depth_callable(models, instant: float):
    """A vectorised callable X (n, 2) -> depths (n, contacts) [m] at ``instant``
    [user time unit]: X[:, 0] the factor, X[:, 1] the power ratio (both [-], > 0).

    Examples
    --------
    >>> from fretwear.laws import get_law
    >>> from fretwear.geometry import contact_geometry
    >>> m = DepthModel(law=get_law("ARCHARD"), powers=(0.01,), time_scale=3.15e7,
    ...                geometry=contact_geometry("TUBE_BAV", mobile_radius=0.01,
    ...                                          obstacle_width=0.02),
    ...                coefficients_mobile=({"coefficient": 1e-14},),
    ...                coefficients_obstacle=(None,))
    >>> f = depth_callable(m, 1.0)
    >>> d = f(np.array([[1.0, 1.0], [2.0, 4.0]]))
    >>> round(float(d[1, 0] / d[0, 0]), 9)   # (2·4)^(2/3): Archard on TUBE_BAV
    4.0
    """
    items = _models(models)

    def evaluate(x) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, dtype=float))
        if x.shape[1] != 2 or not (np.isfinite(x) & (x > 0)).all():
            raise InputError("the inputs are (factor, power_ratio), finite and > 0")
        out = np.empty((x.shape[0], len(items)))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RangeWarning)
            for j, m in enumerate(items.values()):
                elapsed = (float(instant) - m.origin) * m.time_scale
                out[:, j] = m.depth(np.full(x.shape[0], elapsed), factor=x[:, 0],
                                    power=x[:, 1] * m.power, warn=False)
        return out

    return evaluate


def depth_function(models, instant: float):
    """``openturns.Function`` (factor, power_ratio) -> the depth [m] of each contact at
    ``instant`` [user time unit], evaluated a whole sample at once."""
    ot = require("openturns", purpose="the depth model as an openturns.Function")
    items = _models(models)
    evaluate = depth_callable(items, instant)
    function = ot.PythonFunction(2, len(items), func_sample=lambda x: evaluate(np.asarray(x)))
    function.setInputDescription(list(INPUTS))
    function.setOutputDescription([f"depth {name} [m]" for name in items])
    return function


def input_distribution(factor: LogNormal, power: LogNormal | None = None):
    """``openturns.Distribution`` of (factor, power_ratio): independent lognormals, the factor
    as given, the power ratio of median 1 and ``power.sigma_ln`` (default 0: a Dirac at 1)."""
    ot = require("openturns", purpose="the inputs' distribution")
    marginals = []
    for name, dist in (("factor", factor), ("power_ratio", power)):
        median = 1.0 if dist is None or name == "power_ratio" else dist.median
        sigma = 0.0 if dist is None else float(dist.sigma_ln or 0.0)
        if median is None or not median > 0:
            raise InputError(f"{name}: give a LogNormal with a median > 0")
        marginal = ot.LogNormal(math.log(median), sigma, 0.0) if sigma > 0 \
            else ot.Dirac(median)
        marginal.setDescription([name])
        marginals.append(marginal)
    return ot.JointDistribution(marginals) if hasattr(ot, "JointDistribution") \
        else ot.ComposedDistribution(marginals)
