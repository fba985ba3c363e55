"""Operational assessment of a bundle: the probability that any tube exceeds its limit, the
longest operating interval under a target, the preventive-plugging list and the inspection
sample.

The contacts of a bundle share what the inspections calibrate (a bundle-level wear factor f),
so they are not independent: given f they are (each contact's own scatter and its power's
interval are in its conditional probability), and f is integrated over its posterior. The
inputs are therefore, for each contact i and each quadrature node k of the factor's
posterior (weight w_k, Σ w_k = 1), the conditional probability p_ik that the contact exceeds
the limit by the end of the interval. With one node of weight 1 the contacts are independent.

Notes
-----
A tube fails when any of its contacts does; given f_k its survival is
q_tk = Π_{i ∈ t} (1 − p_ik), and the bundle's

.. math:: P_{any} = \\sum_k w_k \\Big(1 - \\prod_t q_{tk}\\Big), \\qquad
          p_t = \\sum_k w_k (1 - q_{tk})

(the second: tube t's own probability). Products are summed as logarithms (log1p), so 10⁵
contacts of probability 1e-9 lose no digit. For n independent identical contacts,
P_any = 1 − (1 − p)ⁿ.

References
----------
.. [1] EPRI, *Steam Generator Integrity Assessment Guidelines*, 1019038 (2009), §6-§7
   (condition monitoring, operational assessment, the 0.05 probability target).
.. [2] NEI 97-06, *Steam Generator Program Guidelines*, Rev. 3 (2011).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fretwear.errors import InputError
from fretwear.keys import check_level

__all__ = ["BundleRisk", "bundle_risk", "longest_interval", "inspection_sample",
           "plugging_list"]


@dataclass(frozen=True)
class BundleRisk:
    """The risk of a bundle at one operating interval.

    Attributes
    ----------
    tubes : numpy.ndarray
        The tube labels, in order.
    log_survival : numpy.ndarray
        ln q_tk, shape (tubes, nodes) [-].
    weights : numpy.ndarray
        w_k, the factor's quadrature weights (sum 1) [-].
    """

    tubes: np.ndarray
    log_survival: np.ndarray
    weights: np.ndarray

    def probability_any(self, without=()) -> float:
        """P_any [-], the tubes ``without`` (labels) plugged."""
        keep = ~np.isin(self.tubes, np.asarray(list(without), dtype=self.tubes.dtype))
        total = self.log_survival[keep].sum(axis=0)
        return float(np.dot(self.weights, -np.expm1(total)))

    def tube_probabilities(self) -> np.ndarray:
        """p_t, each tube's probability of exceeding the limit [-]."""
        return -np.expm1(self.log_survival) @ self.weights


def bundle_risk(probabilities, tubes, weights=None) -> BundleRisk:
    """The bundle's risk from its contacts' conditional probabilities of exceeding the limit.

    Parameters
    ----------
    probabilities : array_like
        p_ik [-], shape (contacts,) (independent contacts) or (contacts, nodes): contact i's
        probability of exceeding the limit given the factor's node k.
    tubes : array_like
        The tube of each contact (any labels), length contacts.
    weights : array_like, optional
        w_k [-], the nodes' weights (default equal); normalised to sum 1.

    Examples
    --------
    Ten independent contacts of p = 0.01 on ten tubes: 1 − 0.99¹⁰.

    >>> r = bundle_risk([0.01] * 10, tubes=range(10))
    >>> round(r.probability_any(), 10) == round(1 - 0.99 ** 10, 10)
    True
    """
    p = np.asarray(probabilities, dtype=float)
    if p.ndim == 1:
        p = p[:, None]
    if p.ndim != 2 or p.shape[0] == 0:
        raise InputError("probabilities must be one value per contact, or one row per contact "
                         "and one column per factor node")
    if not np.all(np.isfinite(p)) or np.any((p < 0) | (p > 1)):
        bad = int(np.flatnonzero(~(np.isfinite(p) & (p >= 0) & (p <= 1)).any(axis=1))[0])
        raise InputError(f"contact {bad}: a probability must be in [0, 1], got {p[bad]}")
    labels = np.asarray(list(tubes))
    if labels.shape[0] != p.shape[0]:
        raise InputError(f"{labels.shape[0]} tube labels for {p.shape[0]} contacts")
    w = np.full(p.shape[1], 1.0 / p.shape[1]) if weights is None else np.asarray(weights, float)
    if w.shape != (p.shape[1],) or not np.all(np.isfinite(w)) or np.any(w < 0) or w.sum() <= 0:
        raise InputError(f"weights: {p.shape[1]} finite non-negative numbers, not all 0")
    names, index = np.unique(labels, return_inverse=True)
    log_q = np.zeros((names.size, p.shape[1]))
    with np.errstate(divide="ignore"):
        np.add.at(log_q, index, np.log1p(-p))
    return BundleRisk(tubes=names, log_survival=log_q, weights=w / w.sum())


def longest_interval(risk_at: Callable[[float], BundleRisk], target: float, *,
                     upper: float, lower: float = 0.0, xtol: float = 1e-6) -> float:
    """The longest operating interval T [s] whose P_any stays at or under ``target``.

    Parameters
    ----------
    risk_at : callable
        T [s] → :class:`BundleRisk` at the end of an interval T; P_any non-decreasing in T
        (wear only grows).
    target : float
        The probability target in (0, 1) (commonly 0.05).
    upper, lower : float
        The bracket [s]: ``lower`` must meet the target; ``upper`` is returned when it does too.
    xtol : float
        Tolerance of the root [s].

    Returns
    -------
    float
        T* [s] with P_any(T*) = target (Brent's method on the bracket), ``upper`` when the
        target holds over it.

    Raises
    ------
    InputError
        The target is already missed at ``lower``.
    """
    from scipy.optimize import brentq

    target = check_level(target, "target")
    gap = lambda t: risk_at(t).probability_any() - target  # noqa: E731
    if gap(lower) > 0:
        raise InputError(f"the target {target:g} is missed already at T = {lower:g} s: no "
                         "interval keeps the bundle under it (plug tubes first)")
    if gap(upper) <= 0:
        return float(upper)
    return float(brentq(gap, lower, upper, xtol=xtol))


def plugging_list(risk: BundleRisk, target: float, *, always=()) -> list:
    """The fewest tubes to plug so that P_any ≤ ``target``, after the tubes ``always`` (at or
    past the plugging limit as measured).

    Greedy: plug, one at a time, the tube whose plugging lowers P_any most. With independent
    tubes (one factor node) this is exact: P_any = 1 − Π q_t, and the fewest factors to remove
    for Π q_t ≥ 1 − target are the smallest q_t. With a shared factor it is exact when the
    tubes are ordered alike at every node (one tube's risk above another's at every f, as when
    the factor scales every contact's wear); ``tests/assessment`` checks it against brute force.

    Examples
    --------
    >>> r = bundle_risk([0.3, 0.01, 0.2, 0.001], tubes=["A", "B", "C", "D"])
    >>> plugging_list(r, 0.05)
    ['A', 'C']
    """
    target = check_level(target, "target")
    plugged = [t for t in always]
    unknown = [t for t in plugged if t not in set(risk.tubes.tolist())]
    if unknown:
        raise InputError(f"tubes to plug that are not in the bundle: {unknown[:5]}")
    # each step evaluates P_any without every tube left at once (one array operation over
    # tubes x nodes: 10⁴ tubes in milliseconds a step); the first of equal tubes is taken
    left = ~np.isin(risk.tubes, np.asarray(plugged, dtype=risk.tubes.dtype))
    log_q = np.maximum(risk.log_survival, -1e4)  # a sure tube (ln 0) removable: e^-1e4 = 0
    total = log_q[left].sum(axis=0)
    while float(np.dot(risk.weights, -np.expm1(total))) > target and left.any():
        with np.errstate(over="ignore"):  # the tubes plugged already: set to inf below
            after = -np.expm1(total[None, :] - log_q) @ risk.weights
        after[~left] = np.inf
        best = int(np.argmin(after))
        plugged.append(risk.tubes[best].item() if hasattr(risk.tubes[best], "item")
                       else risk.tubes[best])
        left[best] = False
        total = total - log_q[best]
    return plugged


def plugging_list_brute_force(risk: BundleRisk, target: float) -> list:
    """The fewest tubes whose plugging meets ``target``, by trying every set (small bundles
    only: 2ⁿ sets; the reference of :func:`plugging_list`'s tests)."""
    names = risk.tubes.tolist()
    if len(names) > 16:
        raise InputError("brute force is for bundles of at most 16 tubes")
    for size in range(len(names) + 1):
        best = min(itertools.combinations(names, size),
                   key=lambda s: risk.probability_any(s))
        if risk.probability_any(best) <= target:
            return list(best)
    return names


def inspection_sample(risk: BundleRisk, share: float, exclude=()) -> list:
    """The fewest tubes whose probabilities of exceeding the limit add up to ``share`` of the
    bundle's total (the tubes in decreasing order of p_t: a sum is covered by its largest terms
    first, so the list is the shortest).

    ``exclude``: tubes plugged (by the plugging list): out of service, they carry no risk and
    are not inspected; the share is of the other tubes' total.

    Examples
    --------
    >>> r = bundle_risk([0.3, 0.01, 0.2, 0.001], tubes=["A", "B", "C", "D"])
    >>> inspection_sample(r, 0.9)
    ['A', 'C']
    >>> inspection_sample(r, 0.9, exclude=["A"])
    ['C']
    """
    try:
        share = float(share)
    except (TypeError, ValueError):
        raise InputError(f"share must be a fraction in (0, 1], got {share!r}") from None
    if not 0.0 < share <= 1.0:
        raise InputError(f"share must be a fraction in (0, 1] of the bundle's risk (e.g. 0.9), "
                         f"got {share!r}")
    p = risk.tube_probabilities()
    p = np.where(np.isin(risk.tubes, list(exclude)), 0.0, p) if len(exclude) else p
    order = np.argsort(-p, kind="stable")
    total = float(p.sum())
    if total <= 0:
        return []
    cumulated = np.cumsum(p[order])
    count = int(np.searchsorted(cumulated, share * total * (1 - 1e-12))) + 1
    return risk.tubes[order[:count]].tolist()
