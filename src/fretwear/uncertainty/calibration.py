"""Calibration of the wear coefficients on inspections (Bayesian update of a factor).

Eddy-current inspections measure worn depths y_i of contacts (and sectors) at instants t_i.
The prediction of contact k is d_k(f, t), with f a factor on every wear coefficient, common to
the contacts calibrated together (:mod:`fretwear.table.depth`). With a lognormal prior
ln f ~ N(μ₀, τ₀²) and a lognormal measurement error ln y_i = ln d_k(f, t_i) + ε_i,
ε_i ~ N(0, σ_i²), the posterior of λ = ln f is

    p(λ | y) ∝ N(λ; μ₀, τ₀²) · Π_i N(ln y_i; ln d_k(e^λ, t_i), σ_i²).

Where every ln d_k(e^λ, t_i) is affine in λ, a_i + b_i·λ (Archard or KWU-EPRI from a new tube
with a power-law depth relation: TUBE_BAV without tilt b = 2/3, TUBE_TUBE b = 2/5, the uniform
TUBE_ALESAGE b = 1), the posterior is normal (conjugate update):

    1/τ² = 1/τ₀² + Σ b_i²/σ_i²,   μ = τ²·(μ₀/τ₀² + Σ b_i·(ln y_i − a_i)/σ_i²).

Otherwise (tilted contacts, lunules, restarts, EDF-MZ) the posterior is computed by quadrature
on a fine grid of λ. Because every depth grows with f, the posterior predictive quantiles of a
depth at a future instant are the depths at the posterior quantiles of f, and the probability
of exceeding a limit L is P(f > f_L) with d(f_L, T) = L: both are exact, without sampling.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, RangeWarning
from fretwear.geometry import solve_monotone
from fretwear.io.text_tables import number, read_text_table
from fretwear.keys import check_level, check_probabilities
from fretwear.table.case import WearCase
from fretwear.table.depth import DepthModel
from fretwear.table.depth_build import models_from_table
from fretwear.uncertainty.cases import prepare_case
from fretwear.uncertainty.distributions import LogNormal

__all__ = ["CalibrationResult", "GridPosterior", "calibrate", "read_inspections"]

#: Columns of an inspection table: name -> (unit, meaning).
INSPECTION_COLUMNS: dict[str, tuple[str, str]] = {
    "contact": ("-", "contact name (as in the predictions); optional with one contact"),
    "sector": ("1", "1-based sector of a sector depth; empty or absent: the global depth"),
    "instant": ("user time unit", "instant of the inspection (the case's time unit)"),
    "depth": ("m", "measured depth of the tube (or depth_mm [mm])"),
    "measurement_sigma": ("-", "standard deviation of ln(depth) of this measurement "
                               "(optional; default the measurement_sigma argument)"),
}

#: Default prior of the factor: median 1 (the coefficients as given), a factor 3 either way
#: at 95 % (σ_ln = ln 3 / 1.96 = 0.56).
DEFAULT_PRIOR = LogNormal(1.0, scatter=3.0)

#: Calibration methods (``calibrate(method=...)``, ``fretwear calibrate --method``): the
#: conjugate update where every prediction is a power law of the factor, grid quadrature.
CALIBRATION_METHODS = ("auto", "conjugate", "grid")

_GRID = 4001
_LINEAR_TOL = 1e-9
#: Largest λ = ln f searched for the factor that brings a depth to the limit (e^700 ≈ 1e304).
_LAMBDA_MAX = 700.0


# ---------------------------------------------------------------------- the posterior
@dataclass(frozen=True, eq=False)
class GridPosterior:
    """Distribution of the factor f = e^λ tabulated on a grid of λ = ln f.

    Attributes
    ----------
    log_factor : numpy.ndarray
        Grid of λ [-], increasing.
    density : numpy.ndarray
        Density of λ on the grid [-], integrating to 1 (trapezoid rule).
    """

    log_factor: np.ndarray
    density: np.ndarray

    @property
    def _cdf_table(self) -> np.ndarray:
        lam, p = self.log_factor, self.density
        cdf = np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(lam))])
        return cdf / cdf[-1]

    def cdf(self, f) -> np.ndarray:
        """P(factor ≤ f)."""
        with np.errstate(divide="ignore"):
            lam = np.log(np.asarray(f, dtype=float))
        return np.interp(lam, self.log_factor, self._cdf_table, left=0.0, right=1.0)

    def sf(self, f) -> np.ndarray:
        """P(factor > f), summed from the upper end of the grid (accurate in that tail)."""
        lam, p = self.log_factor, self.density
        segments = 0.5 * (p[1:] + p[:-1]) * np.diff(lam)
        tail = np.concatenate([np.cumsum(segments[::-1])[::-1], [0.0]])
        with np.errstate(divide="ignore"):
            x = np.log(np.asarray(f, dtype=float))
        return np.interp(x, lam, tail / tail[0], left=1.0, right=0.0)

    def ppf(self, u) -> np.ndarray:
        """Quantile function of the factor, u in (0, 1)."""
        cdf = self._cdf_table
        keep = np.concatenate([[True], np.diff(cdf) > 0])
        return np.exp(np.interp(np.asarray(u, dtype=float), cdf[keep], self.log_factor[keep]))

    def pdf(self, f) -> np.ndarray:
        """Density of the factor [1/-] (p_λ(ln f)/f)."""
        f = np.asarray(f, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            lam = np.log(f)
            return np.where(f > 0, np.interp(lam, self.log_factor, self.density, left=0.0,
                                             right=0.0) / f, 0.0)

    @property
    def median(self) -> float:
        """Median of the factor [-]."""
        return float(self.ppf(0.5))

    @property
    def mean_ln(self) -> float:
        """Mean of ln f [-]."""
        return float(np.trapezoid(self.log_factor * self.density, self.log_factor))

    @property
    def sigma_ln(self) -> float:
        """Standard deviation of ln f [-]."""
        m = self.mean_ln
        return float(math.sqrt(np.trapezoid((self.log_factor - m) ** 2 * self.density,
                                            self.log_factor)))

    def __str__(self) -> str:
        return f"grid posterior(median={self.median:.4g}, sigma_ln={self.sigma_ln:.3g})"


def _mean_ln(dist) -> float:
    return math.log(dist.median) if isinstance(dist, LogNormal) else dist.mean_ln


# ---------------------------------------------------------------------- inspections
def read_inspections(source) -> pd.DataFrame:
    """Inspection table (:data:`INSPECTION_COLUMNS`) from a CSV file or a DataFrame.

    Returns a new DataFrame with ``contact`` (str, "" when absent), ``sector`` (float, NaN for
    the global depth), ``instant``, ``depth`` [m] and ``measurement_sigma`` (NaN when absent).

    Raises
    ------
    InputError
        A missing column, a depth ≤ 0 or not finite, an unknown column.

    Examples
    --------
    >>> read_inspections(pd.DataFrame({"instant": [10.0], "depth_mm": [0.3]}))["depth"].tolist()
    [0.0003]
    """
    if isinstance(source, str | os.PathLike):
        # through the guard layer: encodings, empty or commented files, ragged rows,
        # duplicate labels, pipes: a fretwear error naming the file (issue 29)
        frame = read_text_table(source, "inspection file")
        where = f"inspection file {os.fspath(source)!r}"
        lines = frame.attrs.get("lines") or []
    elif isinstance(source, pd.DataFrame):
        frame = source.copy()
        where, lines = "inspections", []
    else:
        raise InputError(f"inspections must be a CSV path or a DataFrame, got "
                         f"{type(source).__name__}")
    frame.columns = [str(c).strip() for c in frame.columns]
    if len(set(frame.columns)) != len(frame.columns):
        raise InputError(f"{where}: a column is given twice ({list(frame.columns)}); keep one")
    known = set(INSPECTION_COLUMNS) | {"depth_mm"}
    unknown = [c for c in frame.columns if c not in known]
    if unknown:
        raise InputError(f"{where}: unknown column(s) {unknown}; the columns are "
                         f"{sorted(known)} (depth in m, or depth_mm in mm)")
    given = {"instant": "instant", "depth": "depth"}  # the user's column of each value
    if "depth" not in frame and "depth_mm" in frame:
        given["depth"] = "depth_mm"
    for col in ("instant", "depth"):
        if given[col] not in frame:
            raise InputError(f"{where}: the column {col!r} is missing "
                             f"({INSPECTION_COLUMNS[col][1]} [{INSPECTION_COLUMNS[col][0]}])")

    def numbers(name: str, scale: float = 1.0) -> np.ndarray:
        return np.array([number(v) for v in frame[name]], dtype=float) * scale

    out = pd.DataFrame({
        "contact": frame["contact"].fillna("").astype(str) if "contact" in frame else "",
        "sector": numbers("sector") if "sector" in frame else np.nan,
        "instant": numbers("instant"),
        "depth": numbers(given["depth"], 1e-3 if given["depth"] == "depth_mm" else 1.0),
        "measurement_sigma": numbers("measurement_sigma")
        if "measurement_sigma" in frame else np.nan}, index=range(len(frame)))
    if out.empty:
        raise InputError(f"{where}: the table has no rows")
    for col in ("instant", "depth"):
        bad = ~np.isfinite(out[col].to_numpy(dtype=float))
        if col == "depth":
            bad |= out[col].to_numpy(dtype=float) <= 0
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            name = given[col]
            unit = {"depth": " > 0 [m]", "depth_mm": " > 0 [mm]"}.get(name, "")
            at = (f"line {lines[row]}, " if lines else "") + f"row {row + 1}"
            cell = str(frame[name].iloc[row])
            raise InputError(f"{where}, {at}: {name} must be a finite number{unit}, got "
                             f"{cell if len(cell) <= 40 else cell[:37] + '...'!r}")
    return out


# ---------------------------------------------------------------------- predictions
def _contact_models(item, name: str) -> dict[str, DepthModel]:
    if isinstance(item, DepthModel):
        return {"global": item}
    if isinstance(item, pd.DataFrame):
        return models_from_table(item, name=name)
    table = getattr(item, "table", None)
    if isinstance(table, pd.DataFrame):  # a result: the case it carries
        case = getattr(item, "case", None)
        case = case if isinstance(case, WearCase) else getattr(item, "wear_case", None)
        return models_from_table(table, case=case if isinstance(case, WearCase) else None,
                                 name=name)
    if isinstance(item, tuple) and len(item) == 2:
        return prepare_case(item[0], item[1]).models
    raise InputError(f"prediction {name!r}: give a wear table (carrying its case), a run_case "
                     f"result, a DepthModel or a (case, power) pair, got "
                     f"{type(item).__name__}")


def _predictions(predictions) -> dict[str, dict[str, DepthModel]]:
    if isinstance(predictions, Mapping):
        return {str(k): _contact_models(v, str(k)) for k, v in predictions.items()}
    return {"": _contact_models(predictions, "")}


# ---------------------------------------------------------------------- the update
@dataclass(frozen=True, eq=False)
class _Observation:
    model: DepthModel
    elapsed: float  # [s]
    log_depth: float
    sigma: float


def _log_predicted(obs: Sequence[_Observation], lam: np.ndarray) -> np.ndarray:
    """ln d_i(e^λ, t_i), shape (n_obs, n_λ); +inf beyond the geometric range."""
    f = np.exp(lam)
    rows = []
    for o in obs:
        d = o.model.depth(np.full(lam.shape, o.elapsed), factor=f, warn=False)
        with np.errstate(divide="ignore"):
            rows.append(np.where(np.isnan(d), np.inf, np.log(d)))
    return np.array(rows)


def _affine(obs, mu0, tau0) -> tuple[np.ndarray, np.ndarray] | None:
    """(a_i, b_i) when every ln d_i(e^λ) is affine in λ over μ₀ ± 6τ₀, else None."""
    lam = mu0 + tau0 * np.linspace(-6.0, 6.0, 13) if tau0 > 0 else mu0 + np.linspace(-1, 1, 13)
    g = _log_predicted(obs, lam)
    if not np.isfinite(g).all():
        return None
    b = (g[:, -1] - g[:, 0]) / (lam[-1] - lam[0])
    a = g[:, 0] - b * lam[0]
    residual = np.abs(g - (a[:, None] + b[:, None] * lam[None, :]))
    if residual.max() > _LINEAR_TOL * max(1.0, float(np.abs(g).max())):
        return None
    return a, b


def _log_posterior(obs, lam, mu0, tau0) -> np.ndarray:
    g = _log_predicted(obs, lam)
    y = np.array([o.log_depth for o in obs])[:, None]
    s = np.array([o.sigma for o in obs])[:, None]
    with np.errstate(invalid="ignore"):
        loglik = -0.5 * np.sum(((y - g) / s) ** 2, axis=0)
    loglik = np.where(np.isnan(loglik), -np.inf, loglik)
    return loglik - 0.5 * ((lam - mu0) / tau0) ** 2


def _grid_posterior(obs, mu0, tau0) -> GridPosterior:
    """Posterior of λ on a grid that covers its mass (two passes: locate, then resolve)."""
    half = 20.0 * tau0
    for _ in range(6):
        lam = np.linspace(mu0 - half, mu0 + half, 1601)
        lp = _log_posterior(obs, lam, mu0, tau0)
        if not np.isfinite(lp).any():
            raise InputError("calibration: no factor explains the inspections (every predicted "
                             "depth is beyond the geometric range); check the units (depth [m])")
        # >=: at |lp| ~ 1e19 (inspections no factor fits, a tiny measurement sigma) the
        # spacing of doubles exceeds 60 and ``lp > max - 60`` kept nothing (an IndexError)
        keep = lp >= lp.max() - 60.0
        if not (keep[0] or keep[-1]):
            break
        half *= 4.0
    idx = np.flatnonzero(keep)
    lo, hi = lam[max(idx[0] - 1, 0)], lam[min(idx[-1] + 1, lam.size - 1)]
    fine = np.linspace(lo, hi, _GRID)
    lp = _log_posterior(obs, fine, mu0, tau0)
    p = np.exp(lp - lp.max())
    p /= np.trapezoid(p, fine)
    return GridPosterior(log_factor=fine, density=p)


# ---------------------------------------------------------------------- result
@dataclass(frozen=True, eq=False)
class CalibrationResult:
    """Posterior of the wear-coefficient factor and what it predicts.

    Attributes
    ----------
    prior : LogNormal
        Prior of the factor f [-].
    posterior : LogNormal or GridPosterior
        Posterior of f [-] (LogNormal for the conjugate update).
    method : str
        ``"conjugate"`` or ``"grid"``.
    observations : DataFrame
        The inspections with their predictions: ``contact``, ``sector``, ``instant``,
        ``depth`` [m], ``measurement_sigma`` [-], ``prior_depth`` (median prediction under the
        prior) and ``posterior_depth`` (under the posterior) [m].
    models : dict
        contact -> {"global"/"sector j" -> DepthModel}.
    predictive : DataFrame or None
        The forecast at ``calibrate(..., forecast=...)`` (:meth:`forecast`).
    """

    prior: LogNormal
    posterior: Any
    method: str
    observations: pd.DataFrame
    models: dict
    predictive: pd.DataFrame | None = None

    @property
    def factor_median(self) -> float:
        """Posterior median of the factor [-]."""
        return float(self.posterior.median)

    def factor_interval(self, level: float = 0.95) -> tuple[float, float]:
        """Central posterior interval of the factor [-] at ``level`` (a probability in
        (0, 1): 0.95 for 95 %; an InputError otherwise)."""
        level = check_level(level)
        return (float(self.posterior.ppf(0.5 * (1 - level))),
                float(self.posterior.ppf(0.5 * (1 + level))))

    def forecast(self, instant: float, *, limit: float | None = None,
                 q: Sequence[float] = (0.05, 0.5, 0.95)) -> pd.DataFrame:
        """Posterior predictive depth and exceedance of every contact (and sector) at
        ``instant``.

        Parameters
        ----------
        instant : float
            Future instant [user time unit of the cases] (e.g. the next outage).
        limit : float, optional
            Depth limit [m] (default each model's depth_limit × wall_thickness).
        q : sequence of float
            Quantile levels of the depth [-], probabilities in (0, 1).

        Returns
        -------
        DataFrame
            One row per contact and depth (global, sector j): ``contact``, ``sector``,
            ``instant``, ``depth_prior_q50``, ``depth_q..`` [m] (posterior quantiles),
            ``limit`` [m], ``exceedance_prior``, ``exceedance`` (posterior) [-],
            ``wall_fraction_q50`` [-].

        Notes
        -----
        d(f, T) grows with f, so the depth's q-quantile is d(F⁻¹(q), T) and
        P(d > L) = 1 − F(f_L) with d(f_L, T) = L, solved on λ = ln f (exact, no sampling).
        """
        q = check_probabilities(q, closed=False)
        rows = []
        for contact, models in self.models.items():
            for model in models.values():
                rows.append(_forecast_row(contact, model, float(instant), limit, q,
                                          self.prior, self.posterior))
        return pd.DataFrame(rows)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        low, high = self.factor_interval()
        return {"method": self.method, "prior": self.prior.to_dict(),
                "posterior": {"median": self.factor_median,
                              "sigma_ln": float(_sigma(self.posterior)),
                              "interval_95": [low, high]},
                "observations": self.observations.to_dict(orient="records"),
                "predictive": None if self.predictive is None
                else self.predictive.to_dict(orient="records")}


def _sigma(dist) -> float:
    return float(dist.sigma_ln)


def _exceed(model, elapsed, limit, dist, lam_lo, lam_hi) -> float:
    """P(d(f, T) > limit) under ``dist``: 1 − F(f_L), d(f_L, T) = limit."""

    def g(lam):
        d = model.depth(np.full(np.shape(lam), elapsed), factor=np.exp(lam), warn=False)
        return np.where(np.isnan(d), 2.0 * limit + 1.0, d)

    lo, hi = float(lam_lo), float(lam_hi)
    while g(np.array([hi]))[0] <= limit:  # f_L above the bracket: widen it upwards
        if hi >= _LAMBDA_MAX:
            return 0.0
        lo, hi = hi, min(_LAMBDA_MAX, hi + 2.0 * (hi - lo))
    if g(np.array([lo]))[0] > limit:
        return float(dist.sf(math.exp(lo)))
    lam_l = float(solve_monotone(g, np.array([limit]), np.array([lo]), np.array([hi]),
                                 rtol=1e-12, atol=1e-14)[0])
    return float(dist.sf(math.exp(lam_l)))  # sf, not 1 − cdf: small probabilities still rank


def _forecast_row(contact, model: DepthModel, instant, limit, q, prior, posterior) -> dict:
    if instant < model.origin:
        raise InputError(f"forecast instant {instant:g} is before the origin {model.origin:g} "
                         f"of contact {contact!r}")
    elapsed = (instant - model.origin) * model.time_scale
    value = model.limit_depth if limit is None else float(limit)
    row: dict[str, Any] = {"contact": contact, "sector": model.sector, "instant": instant}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        f_prior = float(prior.ppf(0.5))
        row["depth_prior_q50"] = float(model.depth(elapsed, factor=f_prior, warn=False))
        for level in q:
            f = float(posterior.ppf(level))
            row[f"depth_q{100 * level:g}"] = float(model.depth(elapsed, factor=f, warn=False))
        row["limit"] = value
        if value is not None:
            m, s = _mean_ln(posterior), _sigma(posterior)
            mp, sp = math.log(prior.median), prior.sigma_ln
            lo = min(m - 12 * s, mp - 12 * sp)
            hi = max(m + 12 * s, mp + 12 * sp)
            row["exceedance_prior"] = _exceed(model, elapsed, value, prior, lo, hi)
            row["exceedance"] = _exceed(model, elapsed, value, posterior, lo, hi)
        else:
            row["exceedance_prior"] = row["exceedance"] = math.nan
        if model.wall.thickness is not None:
            row["wall_fraction_q50"] = row["depth_q50"] / model.wall.thickness \
                if "depth_q50" in row else math.nan
    return row


def calibrate(predictions, inspections, *, prior: LogNormal = DEFAULT_PRIOR,
              measurement_sigma: float | None = 0.1, method: str = "auto",
              forecast: float | None = None, limit: float | None = None
              ) -> CalibrationResult:
    """Bayesian update of a factor on the wear coefficients from inspected depths.

    Parameters
    ----------
    predictions : wear table, run_case result, DepthModel, (case, power), or a mapping of
        contact name to one of them
        What predicts each contact's depth (a wear table must carry its case: wear_table's, or
        read back from a CSV or Parquet file fretwear wrote; a bundle's:
        :func:`fretwear.report.predictions.bundle_predictions`).
    inspections : DataFrame or path-like
        Measured depths (:func:`read_inspections`): ``contact``, ``sector`` (optional),
        ``instant`` [user time unit], ``depth`` [m] (or ``depth_mm``), ``measurement_sigma``
        (optional).
    prior : LogNormal
        Prior of the factor f [-] (default median 1, a factor 3 either way at 95 %).
    measurement_sigma : float
        Standard deviation of ln(measured depth) [-] (0.1: about 10 % of the depth), for rows
        without their own.
    method : str
        ``"auto"`` (conjugate when every prediction is a power law of f, else grid),
        ``"conjugate"`` (refused when it does not apply) or ``"grid"``.
    forecast : float, optional
        Instant [user time unit] of the posterior predictive (:meth:`CalibrationResult.forecast`).
    limit : float, optional
        Depth limit [m] for the forecast (default depth_limit × wall_thickness of each model).

    Returns
    -------
    CalibrationResult

    Raises
    ------
    InputError
        An inspection of an unknown contact or sector, before the origin of its prediction,
        a bad measurement sigma, ``method="conjugate"`` where the model is not a power law.

    Notes
    -----
    Module docstring: the likelihood, the conjugate update and the grid quadrature.

    References
    ----------
    .. [1] A. Gelman, J. B. Carlin, H. S. Stern, D. B. Dunson, A. Vehtari, D. B. Rubin,
       *Bayesian Data Analysis*, 3rd ed., CRC Press (2013), §2.5 (normal model with known
       variance) and §3.
    """
    if method not in CALIBRATION_METHODS:
        raise InputError(f"method must be one of {CALIBRATION_METHODS}, got {method!r}")
    if not isinstance(prior, LogNormal) or prior.median is None:
        raise InputError("prior must be a LogNormal with a median, e.g. LogNormal(1.0, "
                         "sigma_ln=0.5)")
    if prior.sigma_ln <= 0:
        raise InputError("the prior's sigma_ln must be > 0 (a prior of zero width cannot "
                         "be updated)")
    table = read_inspections(inspections)
    models = _predictions(predictions)
    observations = []
    for i, row in table.iterrows():
        contact = row["contact"]
        if contact not in models:
            if contact == "" and len(models) == 1:
                contact = next(iter(models))
            else:
                raise InputError(f"inspections row {i + 1}: unknown contact {contact!r}; the "
                                 f"predictions have {sorted(models)}")
        key = "global" if not np.isfinite(row["sector"]) else f"sector {int(row['sector'])}"
        if key not in models[contact]:
            raise InputError(f"inspections row {i + 1}: contact {contact!r} has no {key} "
                             f"(it has {sorted(models[contact])})")
        model = models[contact][key]
        if row["instant"] < model.origin:
            raise InputError(f"inspections row {i + 1}: instant {row['instant']:g} is before the "
                             f"origin {model.origin:g} of the prediction of {contact!r}")
        sigma = row["measurement_sigma"] if np.isfinite(row["measurement_sigma"]) \
            else measurement_sigma
        if sigma is None or not (math.isfinite(float(sigma)) and float(sigma) > 0):
            raise InputError(f"inspections row {i + 1}: the measurement sigma (of ln depth) must "
                             f"be > 0, got {sigma!r}")
        observations.append(_Observation(model, (row["instant"] - model.origin)
                                         * model.time_scale, math.log(row["depth"]),
                                         float(sigma)))
        table.loc[i, "contact"] = contact
        table.loc[i, "measurement_sigma"] = float(sigma)
    mu0, tau0 = math.log(prior.median), prior.sigma_ln
    affine = None if method == "grid" else _affine(observations, mu0, tau0)
    if method == "conjugate" and affine is None:
        raise InputError("method='conjugate' needs every predicted depth to be a power law of "
                         "the factor (Archard/KWU-EPRI from a new tube on TUBE_BAV without tilt, "
                         "TUBE_TUBE, uniform TUBE_ALESAGE); use method='grid'")
    if affine is not None:
        a, b = affine
        y = np.array([o.log_depth for o in observations])
        s2 = np.array([o.sigma for o in observations]) ** 2
        precision = 1 / tau0 ** 2 + np.sum(b ** 2 / s2)
        mean = (mu0 / tau0 ** 2 + np.sum(b * (y - a) / s2)) / precision
        posterior: Any = LogNormal(math.exp(mean), sigma_ln=math.sqrt(1 / precision))
        used = "conjugate"
    else:
        posterior = _grid_posterior(observations, mu0, tau0)
        used = "grid"
    f_prior, f_post = float(prior.median), float(posterior.median)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        table["prior_depth"] = [float(o.model.depth(o.elapsed, factor=f_prior, warn=False))
                                for o in observations]
        table["posterior_depth"] = [float(o.model.depth(o.elapsed, factor=f_post, warn=False))
                                    for o in observations]
    result = CalibrationResult(prior=prior, posterior=posterior, method=used,
                               observations=table, models=models)
    if forecast is not None:
        result = CalibrationResult(prior=prior, posterior=posterior, method=used,
                                   observations=table, models=models,
                                   predictive=result.forecast(forecast, limit=limit))
    return result

