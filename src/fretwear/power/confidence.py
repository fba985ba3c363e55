"""Confidence intervals of the wear power: batch means over blocks, ensembles of runs.

The wear power of a window is the mean of its B block powers (theory §2). When the blocks are
long compared with the correlation time of the contact, the block powers are nearly independent
and nearly normal (they are themselves averages), and the batch-means interval

    P̄ ± t_{B−1, (1+level)/2} · s / √B,   s² = Σ (P_b − P̄)² / (B − 1)

holds ``level`` of the probability. Two checks guard it: with fewer than
:data:`MINIMUM_BLOCKS` blocks the interval is wide and the correlation cannot be tested; a lag-1
autocorrelation of the block powers above its 5 % one-sided threshold under independence,
z₀.₉₅/√B, says the blocks are too short (the interval is then too narrow). Either raises a
:class:`~fretwear.errors.ConfidenceWarning`.

An ensemble of independent runs (different random seeds, gaps perturbed by a rounding error: a
rattling tube is chaotic) gives R estimates of the same power; their mean and Student interval
with R − 1 degrees of freedom combine them (:func:`ensemble_interval`).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fretwear.errors import ConfidenceWarning, InputError
from fretwear.keys import check_level

__all__ = ["MINIMUM_BLOCKS", "PowerInterval", "TruncatedStudent", "batch_means_interval",
           "ensemble_interval", "format_interval"]

#: Below this many blocks (or runs) an interval carries a ConfidenceWarning.
MINIMUM_BLOCKS = 10


def format_interval(estimate: float, half_width: float, level: float, unit: str = "W",
                    symbol: str = "P") -> str:
    """``P = 0.184 ± 0.012 W (95 %)``: the half-width to two significant digits, the estimate
    to the same decimal.

    Examples
    --------
    >>> format_interval(0.18417, 0.01234, 0.95)
    'P = 0.184 ± 0.012 W (95 %)'
    >>> format_interval(2.5e-4, 3.1e-6, 0.9)
    'P = 2.500e-04 ± 3.1e-06 W (90 %)'
    """
    pct = f"{100 * level:.3g} %"
    if not math.isfinite(half_width):
        return f"{symbol} = {estimate:.4g} {unit} ({pct}: no interval)"
    if half_width <= 0:
        return f"{symbol} = {estimate:.4g} ± 0 {unit} ({pct})"
    exponent = math.floor(math.log10(half_width))
    if -4 <= exponent <= 4:
        decimals = max(0, 1 - exponent)
        return (f"{symbol} = {estimate:.{decimals}f} ± {half_width:.{decimals}f} {unit} "
                f"({pct})")
    digits = 1
    if estimate:
        digits = min(6, max(1, int(math.floor(math.log10(abs(estimate)))) - exponent + 1))
    return f"{symbol} = {estimate:.{digits}e} ± {half_width:.1e} {unit} ({pct})"


@dataclass(frozen=True)
class TruncatedStudent:
    """Scaled Student distribution loc + scale·T_df restricted to x ≥ 0 (a power is ≥ 0).

    Parameters
    ----------
    df : float
        Degrees of freedom.
    loc : float
        Location (the estimate) [W].
    scale : float
        Scale (the standard error) [W], ≥ 0.

    Examples
    --------
    >>> d = TruncatedStudent(df=9, loc=1.0, scale=0.1)
    >>> round(float(d.ppf(0.5)), 6)
    1.0
    >>> float(TruncatedStudent(df=3, loc=0.01, scale=1.0).ppf(1e-9)) >= 0
    True
    """

    df: float
    loc: float
    scale: float

    def _base(self):
        from scipy import stats  # scipy.stats costs 0.6-0.9 s to import: only when used

        return stats.t(self.df, loc=self.loc, scale=self.scale)

    def _floor(self) -> float:
        return float(self._base().cdf(0.0)) if self.scale > 0 else 0.0

    def ppf(self, u) -> np.ndarray:
        """Quantile function [W] of u in (0, 1)."""
        u = np.asarray(u, dtype=float)
        if self.scale == 0:
            return np.full(u.shape, self.loc)
        f0 = self._floor()
        return np.maximum(self._base().ppf(f0 + u * (1.0 - f0)), 0.0)

    def cdf(self, x) -> np.ndarray:
        """P(X ≤ x)."""
        x = np.asarray(x, dtype=float)
        if self.scale == 0:
            return (x >= self.loc).astype(float)
        f0 = self._floor()
        return np.where(x < 0, 0.0, (self._base().cdf(x) - f0) / (1.0 - f0))

    def pdf(self, x) -> np.ndarray:
        """Density [1/W]."""
        x = np.asarray(x, dtype=float)
        return np.where(x < 0, 0.0, self._base().pdf(x) / (1.0 - self._floor()))

    def __str__(self) -> str:
        return f"student(df={self.df:g}, loc={self.loc:.4g} W, scale={self.scale:.3g} W, ≥ 0)"


@dataclass(frozen=True)
class PowerInterval:
    """A wear power with its confidence interval.

    Attributes
    ----------
    estimate : float
        The power [W] (mean of the block powers, or of the runs).
    half_width : float
        Half-width of the interval [W]; NaN when there is none (one block).
    level : float
        Confidence level [-].
    standard_error : float
        s/√n [W].
    dof : int
        Degrees of freedom of the Student quantile (n − 1).
    count : int
        Number of blocks (or runs) n.
    autocorrelation : float
        Lag-1 autocorrelation of the block powers (NaN below 3 blocks or for runs) [-].
    method : str
        ``"batch means"`` or ``"ensemble"``.
    name : str
        What the power is of (``"total"``, ``"sector 3"``, a history's name).
    values : numpy.ndarray
        The block powers (or run powers) [W].
    warnings : tuple of str
        Why the interval may be unreliable (also issued as ConfidenceWarning).

    Examples
    --------
    >>> iv = batch_means_interval([0.18, 0.19, 0.17, 0.19, 0.18, 0.185, 0.175, 0.19, 0.18, 0.19])
    >>> str(iv)
    'P = 0.1830 ± 0.0051 W (95 %)'
    """

    estimate: float
    half_width: float
    level: float
    standard_error: float
    dof: int
    count: int
    autocorrelation: float = math.nan
    method: str = "batch means"
    name: str = "total"
    values: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    warnings: tuple[str, ...] = ()

    @property
    def low(self) -> float:
        """Lower end of the interval [W] (not below 0)."""
        return max(0.0, self.estimate - self.half_width)

    @property
    def high(self) -> float:
        """Upper end of the interval [W]."""
        return self.estimate + self.half_width

    @property
    def relative_half_width(self) -> float:
        """half_width / estimate [-] (NaN for a zero power)."""
        return self.half_width / self.estimate if self.estimate > 0 else math.nan

    def distribution(self) -> TruncatedStudent:
        """The distribution of the power for a Monte Carlo propagation: loc + se·T_{n−1},
        truncated at 0 (the Bayesian posterior of a normal mean with unknown variance under a
        flat prior, [W])."""
        if not math.isfinite(self.standard_error):
            raise InputError(f"the power {self.name!r} has no interval ({self.count} block): "
                             "compute it in blocks >= 2 to propagate its uncertainty")
        return TruncatedStudent(df=self.dof, loc=self.estimate, scale=self.standard_error)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary; powers [W]."""
        def num(x):
            return None if not math.isfinite(x) else float(x)
        return {"estimate": num(self.estimate), "half_width": num(self.half_width),
                "low": num(self.low), "high": num(self.high), "level": self.level,
                "standard_error": num(self.standard_error), "dof": self.dof,
                "count": self.count, "autocorrelation": num(self.autocorrelation),
                "method": self.method, "name": self.name,
                "values": [float(v) for v in self.values], "warnings": list(self.warnings)}

    def __str__(self) -> str:
        return format_interval(self.estimate, self.half_width, self.level)


def _level(level: float) -> float:
    return check_level(level)


def lag1_autocorrelation(values) -> float:
    """r₁ = Σ (x_i − x̄)(x_{i+1} − x̄) / Σ (x_i − x̄)² [-] (NaN below 3 values or no spread).

    Examples
    --------
    >>> round(lag1_autocorrelation([1.0, 2.0, 3.0, 4.0]), 3)
    0.25
    """
    x = np.asarray(values, dtype=float)
    if x.size < 3:
        return math.nan
    d = x - x.mean()
    den = float(np.dot(d, d))
    return math.nan if den <= 0 else float(np.dot(d[:-1], d[1:]) / den)


def _student(values, level: float, method: str, name: str, unit_name: str,
             check_correlation: bool, stacklevel: int) -> PowerInterval:
    x = np.asarray(values, dtype=float).ravel()
    p = _level(level)
    if x.size == 0 or not np.isfinite(x).all():
        raise InputError(f"the {unit_name} powers of {name!r} must be finite numbers [W]")
    n = x.size
    if n < 2:
        raise InputError(f"a confidence interval of {name!r} needs at least 2 {unit_name}s, got "
                         f"{n}; compute the power in blocks >= 2 (NB_BLOC, [power] blocks, "
                         "--blocks), ideally >= 10")
    mean = float(x.mean())
    se = float(x.std(ddof=1)) / math.sqrt(n)
    # scipy.special's stdtrit and ndtri are what scipy.stats.t.ppf and norm.ppf evaluate, without
    # scipy.stats' 0.6-0.9 s import (and scipy.special's 0.15 s only when an interval is asked)
    from scipy import special

    half = float(special.stdtrit(n - 1, 0.5 * (1.0 + p))) * se
    notes = []
    if n < MINIMUM_BLOCKS:
        unchecked = (f" and the independence of the {unit_name}s cannot be checked"
                     if check_correlation else "")
        notes.append(f"{name}: only {n} {unit_name}s: the interval is wide (Student, {n - 1} "
                     f"degrees of freedom){unchecked}; use >= {MINIMUM_BLOCKS}")
    r1 = lag1_autocorrelation(x) if check_correlation else math.nan
    if check_correlation and n >= 3 and math.isfinite(r1):
        threshold = float(special.ndtri(0.95)) / math.sqrt(n)
        if r1 > threshold:
            notes.append(f"{name}: the block powers are correlated (lag-1 autocorrelation "
                         f"{r1:.2f} > {threshold:.2f}, its 5 % threshold under independence): "
                         "the interval is too narrow; use a longer window or fewer, longer "
                         "blocks")
    for note in notes:
        warnings.warn(note, ConfidenceWarning, stacklevel=stacklevel)
    return PowerInterval(estimate=mean, half_width=half, level=p, standard_error=se, dof=n - 1,
                         count=n, autocorrelation=r1, method=method, name=name, values=x.copy(),
                         warnings=tuple(notes))


def batch_means_interval(block_powers, level: float = 0.95, *, name: str = "total"
                         ) -> PowerInterval:
    """Batch-means confidence interval of a power from its block powers.

    Parameters
    ----------
    block_powers : array_like
        Powers of B ≥ 2 equal blocks [W].
    level : float
        Confidence level in (0, 1) [-].
    name : str
        What the power is of, for messages.

    Returns
    -------
    PowerInterval

    Raises
    ------
    InputError
        Fewer than 2 blocks, a non-finite power, a level outside (0, 1).

    Warns
    -----
    ConfidenceWarning
        Fewer than :data:`MINIMUM_BLOCKS` blocks, or correlated blocks.

    Notes
    -----
    .. math:: \\bar P \\pm t_{B-1,\\,(1+\\ell)/2}\\,\\frac{s}{\\sqrt B}, \\qquad
              s^2 = \\frac{1}{B-1}\\sum_b (P_b - \\bar P)^2

    References
    ----------
    .. [1] G. S. Fishman, *Monte Carlo: Concepts, Algorithms, and Applications*, Springer
       (1996), §6.6 "Batch means".
    .. [2] C. Alexopoulos, A. F. Seila, "Output data analysis", in *Handbook of Simulation*,
       J. Banks ed., Wiley (1998), ch. 7.

    Examples
    --------
    >>> iv = batch_means_interval([1.0, 1.2, 0.8, 1.1, 0.9, 1.0, 1.05, 0.95, 1.0, 1.0])
    >>> round(iv.half_width, 4)  # t(9, 0.975)·s/√10 = 2.2622 × 0.10801/3.1623
    0.0773
    """
    return _student(block_powers, level, "batch means", name, "block", True, 4)


def ensemble_interval(results: Sequence, level: float = 0.95, *, sector: int | None = None
                      ) -> PowerInterval:
    """One wear power and its interval from an ensemble of independent runs.

    Parameters
    ----------
    results : sequence of PowerResult (or of floats [W])
        The runs: the same contact computed with different random seeds or slightly
        perturbed gaps (``fretwear.dynamics``), each a PowerResult of its own window.
    level : float
        Confidence level [-].
    sector : int, optional
        1-based sector whose power to combine (default the total).

    Returns
    -------
    PowerInterval
        ``method="ensemble"``: the mean of the run powers and a Student interval with R − 1
        degrees of freedom; one run only: that run's batch-means interval.

    Notes
    -----
    The runs are independent by construction, so no correlation check is needed; their
    spread holds both the sampling error of each run and the chaotic sensitivity of the
    power to the initial state. Runs of different durations are weighted alike (a warning
    says so when they differ by more than 10 %).

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:  # 5 runs < 10: a warning
    ...     iv = ensemble_interval([0.181, 0.190, 0.176, 0.188, 0.185], level=0.9)
    >>> str(iv), len(caught)
    ('P = 0.1840 ± 0.0054 W (90 %)', 1)
    """
    items = list(results)
    if not items:
        raise InputError("ensemble_interval needs at least one run")
    values, durations = [], []
    for k, item in enumerate(items):
        if hasattr(item, "total"):
            if sector is None:
                values.append(float(item.total))
            else:
                if item.sectors is None or not 1 <= sector <= len(item.sectors):
                    raise InputError(f"run {k} has no sector {sector}")
                values.append(float(item.sectors[sector - 1]))
            durations.append(float(item.duration))
        else:
            try:
                values.append(float(item))
            except (TypeError, ValueError):
                raise InputError(f"run {k}: give a PowerResult or a power [W], got "
                                 f"{type(item).__name__}") from None
    name = "total" if sector is None else f"sector {sector}"
    if len(items) == 1:
        if not hasattr(items[0], "blocks"):
            raise InputError("one run given as a number has no interval: give >= 2 runs")
        return items[0].confidence_interval(level, sector=sector)
    if durations and max(durations) > 1.1 * min(durations):
        warnings.warn(f"ensemble: the runs last from {min(durations):g} to {max(durations):g} s; "
                      "they are weighted alike", ConfidenceWarning, stacklevel=2)
    return _student(values, level, "ensemble", name, "run", False, 4)
