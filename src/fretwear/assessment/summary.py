"""Bad news first: the counts and the per-tube table of a bundle calibration's forecast.

:func:`summary_counts` gives the contacts and tubes at or past the limit and through the wall
(median forecast depth) and the worst contact; :func:`tube_summary` one row per tube, the
worst first (what ``fretwear calibrate --top N`` prints).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd

__all__ = ["COVERAGE_SIGNIFICANCE", "FACTOR_PLAUSIBLE", "PROBABILITY_FLOOR", "coverage_line",
           "factor_line", "probability_text", "summary_counts", "tube_summary"]

FACTOR_PLAUSIBLE = 10.0
"""A calibrated bundle factor beyond [1/10, 10] [-] is said with the bad news."""


PROBABILITY_FLOOR = 1e-6
"""Probabilities [-] below this are printed as "< 1e-6": the quadratures and the models' tails are
not meant to resolve smaller ones (a new user read 1.4e-229 as a result)."""


def probability_text(p: float) -> str:
    """A probability [-] for the terminal and the report: three significant digits, or
    ``"< 1e-6"`` below :data:`PROBABILITY_FLOOR`.

    >>> [probability_text(p) for p in (0.0963, 1.28e-23, 0.0, 1.0)]
    ['0.0963', '< 1e-06', '< 1e-06', '1']
    """
    return f"< {PROBABILITY_FLOOR:g}" if p < PROBABILITY_FLOOR else f"{p:.3g}"


def factor_line(median: float, bound: float = FACTOR_PLAUSIBLE) -> str | None:
    """The warning said with the bad news when the inspections put the model off by more
    than an order of magnitude.

    Parameters
    ----------
    median : float
        The calibrated bundle factor's median [-] (measured wear / predicted wear).
    bound : float
        The largest plausible factor [-] (and 1/bound the smallest); default 10. A wear
        coefficient's published scatter is a factor of 3-5 (docs/uncertainty.md); beyond 10
        the units of the inspection depths, the wear coefficients or the operating time are
        the likelier cause, and the forecasts rest on a model the inspections reject.

    Returns
    -------
    str or None
        The line, or None when the factor is within [1/bound, bound].

    Examples
    --------
    >>> factor_line(1.6) is None
    True
    >>> print(factor_line(274.0))  # doctest: +NORMALIZE_WHITESPACE
    CALIBRATED FACTOR 274 (outside [0.1, 10]): the inspections and the model disagree by
    more than an order of magnitude; check the inspection depths' units (depth [m], depth_mm,
    depth_pct), the wear coefficients and the operating time before using the forecasts
    """
    if not math.isfinite(median) or 1.0 / bound <= median <= bound:
        return None
    return (f"CALIBRATED FACTOR {median:.3g} (outside [{1 / bound:g}, {bound:g}]): the "
            "inspections and the model disagree by more than an order of magnitude; check the "
            "inspection depths' units (depth [m], depth_mm, depth_pct), the wear coefficients "
            "and the operating time before using the forecasts")


COVERAGE_SIGNIFICANCE = 0.01
"""A predicted-against-measured coverage as low as one a right model gives with a probability
below this [-] is said with the bad news."""


def coverage_line(inside: int, indications: int, level: float = 0.90,
                  significance: float = COVERAGE_SIGNIFICANCE) -> str | None:
    """The warning said with the bad news when too few sized indications fall inside their
    prediction's central interval.

    If the calibrated model were right, each indication would fall inside its ``level``
    interval with the probability ``level``, and the count inside would be binomial
    B(n, level) (taking the indications as independent). The line is said when a count as
    low as the one seen has a probability below ``significance`` (a one-sided binomial test):
    0 of 4 at 90 % has 1e-4, 1 of 4 3.7e-3 (both said), 2 of 4 0.052 (not said); one
    indication alone is never enough (0 of 1 has 0.1). It catches what the factor's median
    alone does not: a posterior split between the prior and the data, its median in between
    and near neither.

    Parameters
    ----------
    inside : int
        The indications inside their interval [-].
    indications : int
        The sized indications compared [-].
    level : float
        The interval's probability [-] (0.90).
    significance : float
        The largest probability of so few inside that is said [-] (default 0.01).

    Returns
    -------
    str or None

    Notes
    -----
    .. math:: P(K \\le k) = \\sum_{j=0}^{k} \\binom{n}{j} \\ell^j (1 - \\ell)^{n-j}

    Examples
    --------
    >>> coverage_line(2, 4) is None
    True
    >>> print(coverage_line(0, 4))  # doctest: +NORMALIZE_WHITESPACE
    PREDICTED AGAINST MEASURED: 0 of 4 sized indications inside their 90 % interval (3.6
    expected; as few has probability 0.0001 if the model were right): the calibrated model
    does not explain the inspections (a prior in conflict with the data, the depths' units,
    the wear coefficients or the operating time); check before using the forecasts
    """
    from scipy import stats

    n, k = int(indications), int(inside)
    if n <= 0:
        return None
    p = float(stats.binom.cdf(k, n, level))
    if p >= significance:
        return None
    return (f"PREDICTED AGAINST MEASURED: {k} of {n} sized indications inside their "
            f"{level * 100:g} % interval ({n * level:.3g} expected; as few has probability "
            f"{p:.2g} if the model were right): the calibrated model does not explain the "
            "inspections (a prior in conflict with the data, the depths' units, the wear "
            "coefficients or the operating time); check before using the forecasts")


def summary_counts(forecast: pd.DataFrame, identity=None) -> dict[str, Any]:
    """Bad news first: the contacts and tubes in service (not plugged) whose median forecast
    depth is at or past the limit, or through the wall, the worst contact in service (the
    first such row of the forecast), and the number of plugged tubes left out."""
    tubes_all = pd.Series(_tubes(forecast["contact"], identity))
    service = ~forecast["plugged"].to_numpy(bool) if "plugged" in forecast \
        else np.ones(len(forecast), bool)
    frame, tubes = forecast[service], tubes_all[service].reset_index(drop=True)
    past = (frame["depth_q50"] >= frame["limit"]).to_numpy()
    wall = (frame["wall_fraction_q50"] >= 1.0).to_numpy() \
        if "wall_fraction_q50" in frame else np.zeros(len(frame), bool)
    out = {"contacts_past_limit": int(past.sum()),
           "tubes_past_limit": int(tubes[past].nunique()),
           "contacts_through_wall": int(wall.sum()),
           "tubes_through_wall": int(tubes[wall].nunique()),
           "tubes_plugged": int(tubes_all[~service].nunique())}
    if len(frame):
        worst = frame.iloc[0]
        out.update(worst_contact=str(worst["contact"]), worst_tube=str(tubes.iloc[0]),
                   worst_exceedance=float(worst["exceedance"]),
                   worst_depth_q50=float(worst["depth_q50"]))
    return out


def tube_summary(forecast: pd.DataFrame, identity=None) -> pd.DataFrame:
    """One row per tube of a :meth:`BundleCalibration.forecast`, the worst first: ``tube``,
    ``contacts``, ``worst_contact`` (the largest probability of exceeding the limit, then the
    deepest median), ``exceedance_max`` [-] (its probability), ``worst_depth_q50`` [m] and
    ``worst_wall_fraction_q50`` [-] (its median depth: the worst contact's own, so that a row
    reads as one contact), ``inspected`` (any contact inspected), ``plugged``."""
    frame = forecast.copy()
    frame["tube"] = _tubes(frame["contact"], identity)
    frame = frame.sort_values(["exceedance", "depth_q50"], ascending=False, kind="stable")
    grouped = frame.groupby("tube", sort=False)
    out = pd.DataFrame({"contacts": grouped.size(),
                        "worst_contact": grouped["contact"].first(),
                        "exceedance_max": grouped["exceedance"].max(),
                        "worst_depth_q50": grouped["depth_q50"].first(),
                        "worst_wall_fraction_q50": grouped["wall_fraction_q50"].first(),
                        "inspected": grouped["inspected"].any(),
                        "plugged": grouped["plugged"].any() if "plugged" in frame
                        else False}).reset_index()
    return out.sort_values(["exceedance_max", "worst_depth_q50"], ascending=False,
                           kind="stable", ignore_index=True)


def _tubes(contacts: pd.Series, identity) -> list:
    if identity is None or not {"tube_row", "tube_column"} <= set(identity):
        return contacts.tolist()
    where = identity.drop_duplicates("contact").set_index("contact")
    out = []
    for c in contacts:
        r, k = (where.loc[c, "tube_row"], where.loc[c, "tube_column"]) if c in where.index \
            else (math.nan, math.nan)
        ok = all(isinstance(v, int | float | np.integer | np.floating) and math.isfinite(v)
                 for v in (r, k))
        out.append(f"R{int(r)}C{int(k)}" if ok else str(c))
    return out
