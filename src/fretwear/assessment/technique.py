"""An inspection technique's model: its sizing error and its probability of detection (POD).

An eddy-current or ultrasonic inspection of a worn tube gives either a sized indication (a
measured depth) or no detectable degradation (NDD). What either says of the true depth d
depends on the technique:

* sizing: the measured depth m = a + b·d + e, e normal with standard deviation σ
  (:class:`SizingModel`);
* detection: a flaw of depth d is detected with the probability POD(d), logistic in d or in
  ln d (:class:`LogisticPOD`).

The user supplies both for their technique (from its qualification, e.g. the EPRI
examination technique specification sheets); fretwear ships no qualified values. Depths are in
metres [m] everywhere.

References
----------
.. [1] MIL-HDBK-1823A, *Nondestructive Evaluation System Reliability Assessment* (2009), §3.2:
   the hit/miss POD model POD(a) = F((g(a) − μ)/σ), logistic F, g = identity or ln.
.. [2] EPRI, *Steam Generator Integrity Assessment Guidelines*, 1019038 (2009), §5: sizing
   error as a linear regression of measured on true depth with a normal residual.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fretwear.errors import InputError
from fretwear.keys import check_level

__all__ = ["LogSizingModel", "LogisticPOD", "SizingModel", "from_record"]


def _finite(name: str, value, *, positive: bool = False) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(x) or (positive and x <= 0):
        need = "a finite number > 0" if positive else "a finite number"
        raise InputError(f"{name} must be {need}, got {value!r}")
    return x


@dataclass(frozen=True)
class SizingModel:
    """Sizing error of a technique: measured = a + b·true + e, e ~ N(0, σ²).

    Parameters
    ----------
    intercept : float
        a [m].
    slope : float
        b [-], > 0.
    sigma : float
        σ, the standard deviation of the residual [m], > 0.

    Examples
    --------
    A technique that reads 0.05 mm deep with a 1.0 slope and σ = 0.1 mm:

    >>> s = SizingModel(intercept=5e-5, slope=1.0, sigma=1e-4)
    >>> round(float(s.true_depth(4.05e-4)) * 1e3, 3)   # [mm]
    0.355
    >>> round(float(s.likelihood(4.05e-4, 3.55e-4)), 1)   # the normal peak 1/(σ√(2π)) [1/m]
    3989.4
    """

    intercept: float = 0.0
    slope: float = 1.0
    sigma: float = 1e-4

    def __post_init__(self) -> None:
        a = _finite("SizingModel intercept [m]", self.intercept)
        b = _finite("SizingModel slope [-]", self.slope, positive=True)
        sigma = _finite("SizingModel sigma [m]", self.sigma, positive=True)
        # beyond these no technique sizes a tube's wall (a few mm): depths not in metres, or
        # a slope that overflows b·d (9e307 did)
        for name, value, low, high, unit in (("intercept", abs(a), 0.0, 1.0, "m"),
                                             ("slope", b, 1e-3, 1e3, "-"),
                                             ("sigma", sigma, 1e-9, 1.0, "m")):
            if not low <= value <= high:
                raise InputError(
                    f"SizingModel {name} = {getattr(self, name)!r} [{unit}]: outside "
                    f"{'|a| <= 1 m' if name == 'intercept' else f'[{low:g}, {high:g}] {unit}'}"
                    "; depths are in metres (0.3 mm is 3e-4) and a technique's slope is near 1")

    def describe(self) -> str:
        """The model in engineering units, with the units named (for reports and terminals).

        >>> print(SizingModel(intercept=5e-5, slope=1.0, sigma=1e-4).describe())
        sizing: measured = 0.05 mm + 1 × true + e, sizing error σ = 0.1 mm
        """
        return (f"sizing: measured = {self.intercept * 1e3:.4g} mm + {self.slope:.4g} × true "
                f"+ e, sizing error σ = {self.sigma * 1e3:.4g} mm")

    def to_record(self) -> dict:
        """Explicit fields with units (as ``assessment.json`` keeps them; :func:`from_record`
        reads them back).

        >>> SizingModel(intercept=5e-5, slope=1.0, sigma=1e-4).to_record()
        {'model': 'normal', 'intercept_m': 5e-05, 'slope': 1.0, 'sigma_m': 0.0001}
        """
        return {"model": "normal", "intercept_m": float(self.intercept),
                "slope": float(self.slope), "sigma_m": float(self.sigma)}

    def true_depth(self, measured):
        """The true depth whose expected measurement is ``measured``: (m − a)/b [m]."""
        return (np.asarray(measured, dtype=float) - self.intercept) / self.slope

    def true_depth_sigma(self) -> float:
        """The standard deviation of :meth:`true_depth` given one measurement: σ/b [m]."""
        return self.sigma / self.slope

    def likelihood(self, measured, true):
        """The density of measuring ``measured`` [m] on a flaw of depth ``true`` [m], [1/m].

        Notes
        -----
        .. math:: p(m \\mid d) = \\frac{1}{\\sigma\\sqrt{2\\pi}}
                  \\exp\\left(-\\frac{(m - a - b d)^2}{2\\sigma^2}\\right)
        """
        with np.errstate(over="ignore"):   # a depth of 1e300 m: z² = inf, the density 0
            z = (np.asarray(measured, float) - self.intercept
                 - self.slope * np.asarray(true, float))
            z = z / self.sigma
            return np.exp(-0.5 * z * z) / (self.sigma * math.sqrt(2.0 * math.pi))


@dataclass(frozen=True)
class LogSizingModel:
    """Sizing error proportional to the depth: ln(measured) = ln(true) + e, e ~ N(0, σ_ln²).

    The error model of :func:`fretwear.uncertainty.calibrate` (``measurement_sigma``); with a
    depth that is a power law of the factor it keeps the calibration conjugate.

    Parameters
    ----------
    sigma_ln : float
        σ_ln, the standard deviation of ln(measured) [-], > 0 (0.1: about 10 % of the depth).

    Examples
    --------
    >>> s = LogSizingModel(sigma_ln=0.1)
    >>> round(float(s.likelihood(3e-4, 3e-4) * 3e-4), 4)   # 1/(σ√(2π)) on ln m [-]
    3.9894
    """

    sigma_ln: float = 0.1

    def __post_init__(self) -> None:
        _finite("LogSizingModel sigma_ln [-]", self.sigma_ln, positive=True)

    def describe(self) -> str:
        """The model with its units named.

        >>> print(LogSizingModel(0.1).describe())
        sizing: ln(measured) = ln(true) + e, σ_ln = 0.1 (about 11 % of the depth)
        """
        return (f"sizing: ln(measured) = ln(true) + e, σ_ln = {self.sigma_ln:.4g} (about "
                f"{100 * math.expm1(self.sigma_ln):.2g} % of the depth)")

    def to_record(self) -> dict:
        """Explicit fields (``sigma_ln`` [-]); :func:`from_record` reads them back.

        >>> LogSizingModel(0.1).to_record()
        {'model': 'lognormal', 'sigma_ln': 0.1}
        """
        return {"model": "lognormal", "sigma_ln": float(self.sigma_ln)}

    def true_depth(self, measured):
        """The true depth whose median measurement is ``measured`` [m]."""
        return np.asarray(measured, dtype=float)

    def likelihood(self, measured, true):
        """The density of measuring ``measured`` [m] on a flaw of depth ``true`` [m], [1/m].

        Notes
        -----
        .. math:: p(m \\mid d) = \\frac{1}{m\\,\\sigma\\sqrt{2\\pi}}
                  \\exp\\left(-\\frac{(\\ln m - \\ln d)^2}{2\\sigma^2}\\right)
        """
        m = np.asarray(measured, float)
        with np.errstate(divide="ignore", invalid="ignore"):
            z = (np.log(m) - np.log(np.asarray(true, float))) / self.sigma_ln
            out = np.exp(-0.5 * z * z) / (m * self.sigma_ln * math.sqrt(2.0 * math.pi))
        return np.where(np.isfinite(out), out, 0.0)


@dataclass(frozen=True)
class LogisticPOD:
    """Probability of detecting a flaw of depth d: POD(d) = 1 / (1 + exp(−(β₀ + β₁·x))),
    x = ln(d / 1 m) (``log_depth=True``, the usual hit/miss model) or x = d [m].

    Parameters
    ----------
    beta0 : float
        β₀ [-].
    beta1 : float
        β₁ [-] (log depth) or [1/m] (depth), > 0: deeper flaws are found more often.
    log_depth : bool
        Logistic in ln d (default) or in d.

    Examples
    --------
    From the depths of 50 % and 90 % detection (0.2 and 0.4 mm):

    >>> pod = LogisticPOD.from_depths(a50=2e-4, a90=4e-4)
    >>> round(float(pod(2e-4)), 6), round(float(pod(4e-4)), 6)
    (0.5, 0.9)
    >>> round(pod.depth_at(0.9) * 1e3, 6)   # [mm]
    0.4
    """

    beta0: float
    beta1: float
    log_depth: bool = True

    def __post_init__(self) -> None:
        _finite("LogisticPOD beta0", self.beta0)
        _finite("LogisticPOD beta1", self.beta1, positive=True)

    @classmethod
    def from_depths(cls, a50: float, a90: float, *, log_depth: bool = True) -> LogisticPOD:
        """The POD detecting a depth ``a50`` [m] half the time and ``a90`` [m] 90 % of it."""
        a50 = _finite("a50 [m]", a50, positive=True)
        a90 = _finite("a90 [m]", a90, positive=True)
        if a90 <= a50:
            raise InputError(f"a90 ({a90:g} m) must be deeper than a50 ({a50:g} m): a deeper "
                             "flaw is detected more often")
        g = math.log if log_depth else (lambda x: x)
        beta1 = math.log(9.0) / (g(a90) - g(a50))      # logit(0.9) = ln 9
        return cls(beta0=-beta1 * g(a50), beta1=beta1, log_depth=log_depth)

    def describe(self) -> str:
        """The POD in engineering units: its depths of 50 % and 90 % detection in mm.

        >>> print(LogisticPOD.from_depths(a50=2e-4, a90=4e-4).describe())
        POD: logistic in ln depth, a50 = 0.2 mm, a90 = 0.4 mm (detected 50 %, 90 % of the time)
        """
        return (f"POD: logistic in {'ln depth' if self.log_depth else 'depth'}, "
                f"a50 = {self.depth_at(0.5) * 1e3:.4g} mm, a90 = {self.depth_at(0.9) * 1e3:.4g}"
                " mm (detected 50 %, 90 % of the time)")

    def to_record(self) -> dict:
        """Explicit fields with units: the depths of 50 % and 90 % detection ``a50_m``,
        ``a90_m`` [m], and the coefficients ``beta0`` [-], ``beta1`` ([-] in ln depth, [1/m] in
        depth) that :func:`from_record` reads back exactly.

        >>> r = LogisticPOD.from_depths(a50=1.5e-4, a90=3e-4).to_record()
        >>> r["model"], round(r["a50_m"] * 1e3, 9), round(r["a90_m"] * 1e3, 9)
        ('logistic', 0.15, 0.3)
        """
        return {"model": "logistic", "log_depth": bool(self.log_depth),
                "a50_m": self.depth_at(0.5), "a90_m": self.depth_at(0.9),
                "beta0": float(self.beta0), "beta1": float(self.beta1)}

    def _x(self, depth):
        d = np.asarray(depth, dtype=float)
        if not self.log_depth:
            return d
        with np.errstate(divide="ignore"):
            return np.log(np.where(d > 0, d, 0.0))

    def _z(self, depth):
        with np.errstate(over="ignore"):   # β₁·x beyond the float range: z = ±inf, tanh ±1
            return self.beta0 + self.beta1 * self._x(depth)

    def __call__(self, depth):
        """POD at ``depth`` [m] (0 at a depth of 0 in the log model) [-]."""
        return 0.5 * (1.0 + np.tanh(0.5 * self._z(depth)))   # 1/(1 + e^{-z}), no overflow

    def miss(self, depth):
        """1 − POD(depth) [-]: the likelihood of 'no detectable degradation' on a flaw."""
        return 0.5 * (1.0 - np.tanh(0.5 * self._z(depth)))

    def depth_at(self, probability: float) -> float:
        """The depth detected with ``probability`` in (0, 1) [m] (a90 for 0.9)."""
        p = check_level(probability, "a detection probability")
        x = (math.log(p / (1.0 - p)) - self.beta0) / self.beta1
        return math.exp(x) if self.log_depth else x


def from_record(record: dict):
    """The sizing model or POD of a record of ``to_record`` (``assessment.json``'s inputs).

    Parameters
    ----------
    record : dict
        ``model`` ``"normal"`` (``intercept_m``, ``slope``, ``sigma_m``), ``"lognormal"``
        (``sigma_ln``) or ``"logistic"`` (``beta0``, ``beta1``, ``log_depth``; or ``a50_m``,
        ``a90_m`` [m] without the coefficients).

    Returns
    -------
    SizingModel, LogSizingModel or LogisticPOD

    Examples
    --------
    >>> pod = LogisticPOD.from_depths(a50=1.5e-4, a90=3e-4)
    >>> from_record(pod.to_record()) == pod
    True
    >>> from_record({"model": "normal", "intercept_m": 0.0, "slope": 1.0, "sigma_m": 5e-5})
    SizingModel(intercept=0.0, slope=1.0, sigma=5e-05)
    """
    if not isinstance(record, dict):
        raise InputError(f"a technique record is a mapping with a 'model' key, got {record!r}")
    model = record.get("model")
    fields = {"normal": ("intercept_m", "slope", "sigma_m"), "lognormal": ("sigma_ln",),
              "logistic": ("beta0", "beta1") if "beta0" in record else ("a50_m", "a90_m")}
    if model not in fields:
        raise InputError(f"technique record: model {model!r} is not one of "
                         f"{sorted(fields)} (what to_record writes)")
    missing = [k for k in fields[model] if k not in record]
    if missing:
        raise InputError(f"technique record ({model}): missing {missing}; give "
                         f"{list(fields[model])}")
    if model == "normal":
        return SizingModel(record["intercept_m"], record["slope"], record["sigma_m"])
    if model == "lognormal":
        return LogSizingModel(record["sigma_ln"])
    log_depth = bool(record.get("log_depth", True))
    if "beta0" in record:
        return LogisticPOD(record["beta0"], record["beta1"], log_depth=log_depth)
    return LogisticPOD.from_depths(record["a50_m"], record["a90_m"], log_depth=log_depth)
