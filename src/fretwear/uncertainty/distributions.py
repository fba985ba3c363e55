"""Distributions of the uncertain inputs of a wear prediction (docs/uncertainty.md §2).

An uncertain input is described by anything with a percent-point function ``ppf(u)`` (the
inverse of its cumulative distribution), so that a uniform point u ∈ (0, 1) of a Monte Carlo
or quasi-Monte Carlo design maps to a value x = F⁻¹(u). Frozen ``scipy.stats`` distributions
qualify as they are; :class:`LogNormal` is the usual description of a wear coefficient, given
by its median and either ``sigma_ln`` (the standard deviation of its logarithm) or a scatter
factor, and whose median may be left to the case's nominal value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import stats

from fretwear.errors import InputError

__all__ = ["LogNormal", "Scaled", "as_distribution", "is_distribution", "lognormal_sigma",
           "median_of"]


def lognormal_sigma(scatter: float, coverage: float = 0.95) -> float:
    """σ_ln of a lognormal whose central ``coverage`` interval is [median/F, median·F] [-].

    Parameters
    ----------
    scatter : float
        Scatter factor F > 1 [-] (a coefficient "known within a factor F").
    coverage : float
        Probability of the interval [median/F, median·F], in (0, 1) [-].

    Returns
    -------
    float
        σ_ln = ln F / z, z the standard normal quantile of (1 + coverage)/2 [-].

    Notes
    -----
    P(median/F ≤ X ≤ median·F) = P(|ln X − ln median| ≤ ln F) = 2Φ(ln F/σ) − 1 = coverage.

    Examples
    --------
    >>> round(lognormal_sigma(3.0), 4)  # a factor 3 either way, 95 %: ln 3 / 1.96
    0.5605
    """
    f = float(scatter)
    p = float(coverage)
    if not (math.isfinite(f) and f > 1.0):
        raise InputError(f"the scatter factor must be a finite number > 1 [-], got {scatter!r}")
    if not 0.0 < p < 1.0:
        raise InputError(f"coverage must lie in (0, 1) [-], got {coverage!r}")
    return math.log(f) / float(stats.norm.ppf(0.5 * (1.0 + p)))


@dataclass(frozen=True)
class LogNormal:
    """Lognormal distribution: ln X ~ N(ln median, sigma_ln²).

    Parameters
    ----------
    median : float or None
        Median of X, in the unit of the quantity it describes (e.g. [Pa⁻¹] for an Archard
        coefficient); None takes the case's nominal value (:meth:`with_median`).
    sigma_ln : float, optional
        Standard deviation of ln X [-], ≥ 0 (0: X is the median).
    scatter : float, optional
        Instead of ``sigma_ln``: the factor F > 1 such that [median/F, median·F] holds
        ``coverage`` of the probability (:func:`lognormal_sigma`).
    coverage : float
        Probability of the scatter interval, default 0.95 [-].

    Notes
    -----
    Mean = median·exp(σ²/2); quantile q: median·exp(σ·Φ⁻¹(q)).

    Examples
    --------
    >>> k = LogNormal(1e-14, scatter=3.0)
    >>> round(float(k.ppf(0.975)) / 1e-14, 6)
    3.0
    >>> LogNormal(sigma_ln=0.5).with_median(2e-14).median
    2e-14
    """

    median: float | None = None
    sigma_ln: float | None = None
    scatter: float | None = None
    coverage: float = 0.95

    def __post_init__(self) -> None:
        if (self.sigma_ln is None) == (self.scatter is None):
            raise InputError("LogNormal takes either sigma_ln (standard deviation of ln X) or "
                             "scatter (a factor F > 1), exactly one of them")
        if self.scatter is not None:
            object.__setattr__(self, "sigma_ln", lognormal_sigma(self.scatter, self.coverage))
        s = float(self.sigma_ln)
        if not (math.isfinite(s) and s >= 0.0):
            raise InputError(f"sigma_ln must be finite and >= 0 [-], got {self.sigma_ln!r}")
        object.__setattr__(self, "sigma_ln", s)
        if self.median is not None:
            m = float(self.median)
            if not (math.isfinite(m) and m > 0.0):
                raise InputError(f"the median of a lognormal must be finite and > 0, got "
                                 f"{self.median!r}")
            object.__setattr__(self, "median", m)

    def with_median(self, median: float) -> LogNormal:
        """This distribution with ``median`` where none was given (nominal value of a case)."""
        if self.median is not None:
            return self
        return LogNormal(median=median, sigma_ln=self.sigma_ln)

    def _checked(self) -> tuple[float, float]:
        if self.median is None:
            raise InputError("this LogNormal has no median: give median=..., or use it for an "
                             "input whose nominal value the case gives")
        return float(self.median), float(self.sigma_ln)

    def ppf(self, u) -> np.ndarray:
        """Quantile function x = median·exp(σ·Φ⁻¹(u)), u in (0, 1)."""
        m, s = self._checked()
        return m * np.exp(s * stats.norm.ppf(np.asarray(u, dtype=float)))

    def cdf(self, x) -> np.ndarray:
        """Cumulative distribution P(X ≤ x)."""
        m, s = self._checked()
        x = np.asarray(x, dtype=float)
        if s == 0.0:
            return (x >= m).astype(float)
        with np.errstate(divide="ignore"):
            return stats.norm.cdf((np.log(x) - math.log(m)) / s)

    def sf(self, x) -> np.ndarray:
        """Survival function P(X > x), exact in the upper tail (not 1 − cdf, which rounds to 0
        below 1e-16)."""
        m, s = self._checked()
        x = np.asarray(x, dtype=float)
        if s == 0.0:
            return (x < m).astype(float)
        with np.errstate(divide="ignore"):
            return stats.norm.sf((np.log(x) - math.log(m)) / s)

    def pdf(self, x) -> np.ndarray:
        """Probability density [1/unit of X]."""
        m, s = self._checked()
        return stats.lognorm.pdf(np.asarray(x, dtype=float), s, scale=m)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description."""
        return {"distribution": "lognormal", "median": self.median, "sigma_ln": self.sigma_ln}

    def __str__(self) -> str:
        median = "nominal" if self.median is None else f"{self.median:.4g}"
        return f"lognormal(median={median}, sigma_ln={self.sigma_ln:.3g})"


def as_distribution(spec, nominal: float | None, name: str):
    """An object with ``ppf`` for input ``name``, or None when the input is fixed.

    ``spec`` is a frozen ``scipy.stats`` distribution (anything with ``ppf``), a
    :class:`LogNormal` (its median defaults to ``nominal``), or a number (a fixed value: None
    is returned and the caller uses the number).

    Examples
    --------
    >>> as_distribution(LogNormal(sigma_ln=0.3), 2.0, "k").median
    2.0
    >>> as_distribution(1.5, 2.0, "k") is None
    True
    """
    if isinstance(spec, LogNormal):
        if spec.median is None and nominal is None:
            raise InputError(f"{name}: the lognormal has no median and the case gives no "
                             f"nominal value for it; give LogNormal(median=..., ...)")
        return spec.with_median(nominal) if spec.median is None else spec
    if hasattr(spec, "ppf"):
        return spec
    try:
        float(spec)
    except (TypeError, ValueError):
        raise InputError(f"{name}: give a distribution (fretwear.uncertainty.LogNormal or a "
                         f"frozen scipy.stats distribution, anything with ppf) or a number, "
                         f"got {spec!r}") from None
    return None


def describe(distribution) -> str:
    """One line naming a distribution (for tables and reports)."""
    if isinstance(distribution, LogNormal):
        return str(distribution)
    dist = getattr(distribution, "dist", None)
    if dist is not None:  # frozen scipy distribution
        args = ", ".join(f"{a:.4g}" for a in getattr(distribution, "args", ()))
        kwds = ", ".join(f"{k}={v:.4g}" for k, v in getattr(distribution, "kwds", {}).items())
        return f"{dist.name}({', '.join(p for p in (args, kwds) if p)})"
    return str(distribution)  # its own __str__ (e.g. TruncatedStudent with units), else repr


class Scaled:
    """``scale × X``: a relative distribution X [-] (a factor on a nominal value) made
    absolute, e.g. a relative scatter of the power on its nominal power [W].

    Examples
    --------
    >>> d = Scaled(LogNormal(1.0, sigma_ln=0.2), 0.01)
    >>> round(float(d.ppf(0.5)), 6), str(d)
    (0.01, '0.01 × lognormal(median=1, sigma_ln=0.2)')
    """

    def __init__(self, base, scale: float):
        self.base, self.scale = base, float(scale)

    def ppf(self, u):
        return self.scale * np.asarray(self.base.ppf(u), dtype=float)

    def cdf(self, x):
        return self.base.cdf(np.asarray(x, dtype=float) / self.scale)

    def median(self) -> float:
        return float(self.ppf(0.5))

    def __str__(self) -> str:
        return f"{self.scale:g} × {describe(self.base)}"


def median_of(distribution) -> float | None:
    """The median of a distribution (a LogNormal's, or ``ppf(0.5)``); None for a LogNormal
    without one."""
    if isinstance(distribution, LogNormal):
        return distribution.median
    return float(np.asarray(distribution.ppf(0.5), dtype=float))


def is_distribution(spec) -> bool:
    """Whether ``spec`` is a distribution (a LogNormal, or anything with ``ppf``)."""
    return isinstance(spec, LogNormal) or hasattr(spec, "ppf")
