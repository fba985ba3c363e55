"""Condition monitoring: the as-found state against the plugging limit, and the model's
prediction against every sized indication.

* As found: a sized depth m is a true depth d ~ N((m − a)/b, (σ/b)²) (the technique's
  :class:`~fretwear.assessment.technique.SizingModel`); the contact is at or past its limit L
  as measured when (m − a)/b ≥ L, and P(d ≥ L) = Φ̄((L − (m − a)/b)/(σ/b)) says how sure.
* Predicted against measured: the prediction of a measurement at the inspection's instant t is
  m = a + b·d(g, t) + e, g the growth factor (:class:`~fretwear.assessment.growth.FactorNodes`)
  and e the sizing error; its 5 % and 95 % quantiles bound the 90 % interval, and the share
  of indications inside it is the coverage (0.90 when the model's spread is honest). The
  factor was calibrated on these indications: the check is in-sample.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special
from scipy.optimize import brentq

from fretwear._lazy import pandas as pd

__all__ = ["as_found", "predicted_vs_measured"]


def _phi_bar(x):
    return 0.5 * special.erfc(np.asarray(x, float) / math.sqrt(2.0))


def as_found(sized: pd.DataFrame, sizing) -> pd.DataFrame:
    """The sized indications against their limits.

    Parameters
    ----------
    sized : DataFrame
        ``contact``, ``tube``, ``depth`` (measured [m]), ``limit_depth`` [m],
        ``wall_thickness`` [m].
    sizing : SizingModel

    Returns
    -------
    DataFrame
        The columns given and ``true_depth`` [m] ((m − a)/b), ``true_depth_sigma`` [m] (σ/b),
        ``fraction`` [-] (true depth / wall), ``p_past_limit`` [-] (P(d ≥ L)),
        ``past_limit`` and ``through_wall`` (as measured), deepest first.

    Examples
    --------
    >>> from fretwear.assessment.technique import SizingModel
    >>> s = pd.DataFrame({"contact": ["a"], "tube": ["R1C1"], "depth": [4.4e-4],
    ...                   "limit_depth": [4.4e-4], "wall_thickness": [1.1e-3]})
    >>> float(as_found(s, SizingModel(sigma=1e-4))["p_past_limit"].iloc[0])   # at the limit
    0.5
    """
    out = sized.copy()
    out["true_depth"] = np.asarray(sizing.true_depth(out["depth"].to_numpy(float)))
    out["true_depth_sigma"] = sizing.true_depth_sigma()
    out["fraction"] = out["true_depth"] / out["wall_thickness"]
    out["p_past_limit"] = _phi_bar((out["limit_depth"] - out["true_depth"])
                                   / out["true_depth_sigma"])
    out["past_limit"] = out["true_depth"] >= out["limit_depth"]
    out["through_wall"] = out["true_depth"] >= out["wall_thickness"]
    return out.sort_values("true_depth", ascending=False, kind="stable").reset_index(drop=True)


def _measured_cdf(sizing, true):
    """P(measured <= x | each true depth) as a function of x [m], and a bracket of x holding
    every quantile: normal sizing (a + b·d, σ) or log-normal (ln m ~ N(ln d, σ_ln²))."""
    d = np.asarray(true, float)
    if hasattr(sizing, "sigma_ln"):
        s, d = sizing.sigma_ln, np.maximum(d, 1e-300)
        return (lambda x: 1 - _phi_bar((math.log(x) - np.log(d)) / s),
                (d.min() * math.exp(-10 * s), d.max() * math.exp(10 * s)))
    mean = sizing.intercept + sizing.slope * d
    return (lambda x: 1 - _phi_bar((x - mean) / sizing.sigma),
            (mean.min() - 10 * sizing.sigma, mean.max() + 10 * sizing.sigma))


def predicted_vs_measured(models, sized: pd.DataFrame, nodes, sizing, *,
                          level: float = 0.90, group_of=None) -> tuple[pd.DataFrame, dict]:
    """The prediction of every sized indication against its measurement.

    Parameters
    ----------
    models : mapping of contact to DepthModel
    sized : DataFrame
        ``contact``, ``instant`` [time unit], ``depth`` (measured [m]).
    nodes : FactorNodes
        The calibrated growth factor.
    sizing : SizingModel or LogSizingModel
        The technique's sizing error (normal, or log-normal as ``fretwear calibrate``'s
        default).
    level : float
        The central interval's probability [-].
    group_of : mapping of contact to int, optional
        Each contact's row of ``nodes.table`` (nodes with a group level).

    Returns
    -------
    (DataFrame, dict)
        Per indication ``predicted`` (median measurement [m]), ``low``, ``high`` (the
        interval [m]), ``residual`` (measured − predicted [m]), ``inside``; and
        ``{"indications", "coverage", "level", "rms_residual" [m]}``.
    """
    z, hz = np.polynomial.hermite_e.hermegauss(24)
    hz = hz / hz.sum()
    table, w, s = nodes.table, nodes.weights, nodes.sigma
    growth = np.exp(table[:, :, None] + s * z[None, None, :]).reshape(table.shape[0], -1)
    wg = (w[:, None] * hz[None, :]).ravel()
    rows = []
    for r in sized.itertuples(index=False):
        m = models[r.contact]
        g = growth[0 if group_of is None else group_of[r.contact]]
        elapsed = (float(r.instant) - m.origin) * m.time_scale
        d = np.nan_to_num(m.depth(elapsed, factor=g, warn=False), nan=m.geometry.mobile_radius)
        below, span = _measured_cdf(sizing, d)

        def cdf(x, q, below=below):
            return float(np.dot(wg, below(x))) - q

        low, mid, high = (brentq(cdf, *span, args=(q,), xtol=1e-12)
                          for q in (0.5 * (1 - level), 0.5, 0.5 * (1 + level)))
        rows.append({"contact": r.contact, "instant": float(r.instant),
                     "measured": float(r.depth), "predicted": mid, "low": low, "high": high,
                     "residual": float(r.depth) - mid,
                     "inside": bool(low <= float(r.depth) <= high)})
    frame = pd.DataFrame(rows, columns=["contact", "instant", "measured", "predicted", "low",
                                        "high", "residual", "inside"])
    stats = {"indications": len(frame), "level": level,
             "coverage": float(frame["inside"].mean()) if len(frame) else math.nan,
             "rms_residual": float(np.sqrt((frame["residual"] ** 2).mean()))
             if len(frame) else math.nan}
    return frame, stats
