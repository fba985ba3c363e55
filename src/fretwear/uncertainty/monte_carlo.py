"""Monte Carlo propagation of the uncertain inputs of a wear prediction to the worn depth.

:func:`monte_carlo` draws the uncertain inputs of one contact (wear coefficients, a factor on
them, the wear power, dimensions) from their distributions with a pseudo-random or a
quasi-random (scrambled Sobol') design, evaluates the worn depth of the mobile at every instant
of the case for all samples at once, and returns an :class:`UncertaintyResult`: quantiles of
the depth, probability of exceeding a limit, quantiles of the time to reach it, and
variance-based (Sobol') sensitivity indices. docs/uncertainty.md explains the model.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.keys import check_probabilities
from fretwear.power import PowerResult
from fretwear.power.confidence import PowerInterval
from fretwear.table.depth import DepthModel, given_names
from fretwear.uncertainty.cases import prepare_case
from fretwear.uncertainty.distributions import (
    Scaled,
    as_distribution,
    describe,
    is_distribution,
    median_of,
)
from fretwear.uncertainty.sampling import sobol_indices, uniform_points

__all__ = ["UncertaintyResult", "Variable", "monte_carlo"]

#: Default quantiles of the summaries [-].
QUANTILES = (0.05, 0.5, 0.95)


@dataclass(frozen=True)
class Variable:
    """One uncertain input: its key, its label, its distribution.

    ``kind`` is ``"factor"``, ``"power"``, ``"mobile"`` / ``"obstacle"`` (a law coefficient
    ``name``) or ``"dimension"`` (a geometry dimension ``name``).
    """

    kind: str
    name: str
    distribution: Any
    unit: str = ""

    @property
    def label(self) -> str:
        """Display name, e.g. ``"mobile coefficient"``."""
        if self.kind in ("factor", "power"):
            return {"factor": "wear-coefficient factor", "power": "wear power"}[self.kind]
        return f"{self.kind} {self.name}"

    def describe(self) -> str:
        """The distribution in words."""
        return describe(self.distribution)


@dataclass(frozen=True, eq=False)
class _Propagation:
    """Evaluates the depth of a model for rows of input values (one column per variable)."""

    model: DepthModel
    variables: tuple[Variable, ...]
    elapsed: np.ndarray  # [s], shape (M,)

    def inputs(self, values: np.ndarray) -> tuple[dict, dict]:
        """(keyword arguments of DepthModel.depth, dimensions) for columns of values."""
        kw: dict[str, Any] = {}
        dims: dict[str, np.ndarray] = {}
        for j, var in enumerate(self.variables):
            col = values[:, j]
            if var.kind == "factor":
                kw["factor"] = col
            elif var.kind == "power":
                kw["power"] = col
            elif var.kind == "mobile":
                kw.setdefault("coefficients", {})[var.name] = col
            elif var.kind == "obstacle":
                kw.setdefault("obstacle_coefficients", {})[var.name] = col
            else:
                dims[var.name] = col
        return kw, dims

    def depth(self, values: np.ndarray, elapsed: np.ndarray | None = None) -> np.ndarray:
        """Depth [m], shape (N, M): NaN beyond the geometric range becomes +inf."""
        t = self.elapsed if elapsed is None else elapsed
        kw, dims = self.inputs(values)
        if not dims:
            column = {k: (v[:, None] if k in ("factor", "power") else
                          {n: c[:, None] for n, c in v.items()}) for k, v in kw.items()}
            out = self.model.depth(t[None, :], warn=False, **column)
        else:
            out = np.empty((values.shape[0], t.size))
            for i in range(values.shape[0]):
                model = self.model.with_dimensions(**{k: float(v[i]) for k, v in dims.items()})
                row = {k: (v[i] if k in ("factor", "power") else
                           {n: c[i] for n, c in v.items()}) for k, v in kw.items()}
                out[i] = model.depth(t, warn=False, **row)
        out = np.broadcast_to(out, (values.shape[0], t.size)).astype(float)
        return np.where(np.isnan(out), np.inf, out)

    def time_to(self, values: np.ndarray, depth: float) -> np.ndarray:
        """Instant [user time unit] at which the tube in place reaches ``depth`` [m], one per
        row of values (:meth:`DepthModel.time_to`)."""
        kw, dims = self.inputs(values)
        if not dims:
            return np.broadcast_to(np.asarray(self.model.time_to(depth, **kw), dtype=float),
                                   values.shape[:1]).astype(float)
        out = np.empty(values.shape[0])
        for i in range(values.shape[0]):
            model = self.model.with_dimensions(**{k: float(v[i]) for k, v in dims.items()})
            row = {k: (v[i] if k in ("factor", "power") else {n: c[i] for n, c in v.items()})
                   for k, v in kw.items()}
            out[i] = model.time_to(depth, **row)
        return out


@dataclass(frozen=True, eq=False)
class UncertaintyResult:
    """Samples of the worn depth of one contact and what they say.

    Attributes
    ----------
    instants : numpy.ndarray
        Instants [user time unit] (origin + durations), shape (M,).
    depth : numpy.ndarray
        Worn depth of the mobile [m] per sample and instant, shape (N, M); ``inf`` where the
        volume lies beyond the geometric relation's range (deeper than any depth in it).
    inputs : DataFrame
        The sampled inputs, one column per variable (units of each input).
    variables : tuple of Variable
        The uncertain inputs and their distributions.
    nominal_depth : numpy.ndarray
        Depth at the nominal inputs [m], shape (M,).
    method : str
        ``"sobol"`` or ``"random"``.
    seed : int or None
        Seed of the design.
    time_scale : float
        Seconds per user time unit [s].
    origin : float
        Origin of the run [user time unit].
    wall_thickness : float or None
        Wall thickness [m].
    depth_limit : float
        Depth limit as a fraction of the wall [-].
    name : str
        Contact name.
    depth_of : str
        Which depth of the mobile the samples are: ``"global"`` (the wear table's
        ``depth_mobile``, from the total volume) or ``"sector j"`` (``depth_mobile_sector`` of
        sector j, its volume spread over its arc).
    case : WearCase or None
        The wear case the samples were computed from (a wear table's: the case it carries;
        None: given a model).
    power_result : PowerResult or None
        The power computation of the case (None: a power given as a number or a distribution).
    """

    instants: np.ndarray
    depth: np.ndarray
    inputs: pd.DataFrame
    variables: tuple[Variable, ...]
    nominal_depth: np.ndarray
    method: str
    seed: int | None
    time_scale: float
    origin: float
    wall_thickness: float | None
    depth_limit: float
    name: str = ""
    depth_of: str = "global"
    case: Any = field(default=None, repr=False)
    power_result: Any = field(default=None, repr=False)
    _propagation: _Propagation | None = field(default=None, repr=False)
    _second: np.ndarray | None = field(default=None, repr=False)
    _cache: dict = field(default_factory=dict, repr=False)

    # ------------------------------------------------------------------ basic properties
    @property
    def samples(self) -> int:
        """Number of samples N."""
        return int(self.depth.shape[0])

    @property
    def limit(self) -> float | None:
        """The depth limit [m] = depth_limit × wall_thickness (None without a wall)."""
        return None if self.wall_thickness is None else self.depth_limit * self.wall_thickness

    def _limit(self, limit: float | None) -> float:
        value = self.limit if limit is None else float(limit)
        if value is None:
            raise InputError("no depth limit: give limit=... [m], or the wall_thickness [m] "
                             "(the limit is then depth_limit × wall_thickness)")
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"the depth limit must be finite and > 0 [m], got {value!r}")
        return value

    @property
    def beyond_range(self) -> np.ndarray:
        """Share of samples beyond the geometric relation's range, per instant [-]."""
        return np.mean(np.isinf(self.depth), axis=0)

    # ------------------------------------------------------------------ summaries
    def quantiles(self, q: Sequence[float] = QUANTILES) -> pd.DataFrame:
        """Quantiles of the depth [m] per instant: one row per instant, one column per q.

        ``inf`` where more than 1 − q of the samples lie beyond the relation's range.
        """
        q = check_probabilities(q)
        with np.errstate(invalid="ignore"):
            values = np.quantile(self.depth, q, axis=0, method="linear")
        frame = pd.DataFrame(values.T, columns=[float(x) for x in q])
        frame.index = pd.Index(self.instants, name="instant")
        return frame

    def exceedance(self, limit: float | None = None) -> pd.DataFrame:
        """Probability that the depth exceeds ``limit`` [m], per instant.

        Parameters
        ----------
        limit : float, optional
            Depth [m]; default depth_limit × wall_thickness.

        Returns
        -------
        DataFrame
            Index ``instant``; columns ``probability`` [-] and ``standard_error`` [-]
            (√(p(1−p)/N), the error of independent sampling; a Sobol' design does better).
        """
        value = self._limit(limit)
        p = np.mean(self.depth > value, axis=0)
        se = np.sqrt(p * (1 - p) / self.samples)
        return pd.DataFrame({"probability": p, "standard_error": se},
                            index=pd.Index(self.instants, name="instant"))

    def time_to_limit(self, limit: float | None = None) -> np.ndarray:
        """Instant [user time unit] at which each sample's depth reaches ``limit`` [m].

        :meth:`fretwear.table.DepthModel.time_to` of each sample (the one meaning of the time
        to a limit, docs/uncertainty.md §1): depth(t) inverted on the law and the geometry,
        a restart's earlier rows included (they are the tube's history: no sample changes
        them); ``inf`` where it is never reached.
        """
        value = self._limit(limit)
        key = ("time", value)
        if key not in self._cache:
            if self._propagation is None:
                raise InputError("this result has no model to invert (built without one)")
            self._cache[key] = self._propagation.time_to(self.inputs.to_numpy(), value)
        return self._cache[key]

    def time_to_limit_quantiles(self, q: Sequence[float] = QUANTILES,
                                limit: float | None = None) -> pd.Series:
        """Quantiles of the instant of reaching ``limit`` [user time unit] (inf: never)."""
        q = check_probabilities(q)
        t = self.time_to_limit(limit)
        with np.errstate(invalid="ignore"):
            values = np.quantile(t, q, method="linear")
        return pd.Series(values, index=pd.Index([float(x) for x in q], name="quantile"),
                         name="instant")

    def sensitivity(self, instant: float | None = None, *, resamples: int = 200
                    ) -> pd.DataFrame:
        """First-order and total Sobol' indices of the depth at ``instant``.

        Parameters
        ----------
        instant : float, optional
            One of :attr:`instants` [user time unit] (default the last).
        resamples : int
            Bootstrap resamples for the confidence half-widths (95 %).

        Returns
        -------
        DataFrame
            One row per variable (its label): ``first``, ``first_conf``, ``total``,
            ``total_conf`` [-].

        Notes
        -----
        The Saltelli design (:func:`fretwear.uncertainty.sampling.sobol_indices`) re-uses the
        N samples as its matrix A; the matrix B (drawn with A, independent of it) and the d
        matrices A_B^(i) cost (d + 1)·N more evaluations, done at the first call. Depths beyond
        the geometric range are counted at the relation's largest depth.
        """
        if self._propagation is None or self._second is None:
            raise InputError("this result has no design for sensitivity indices")
        j = self._instant_index(instant)
        key = ("sobol", j, resamples)
        if key not in self._cache:
            prop = self._propagation
            t = prop.elapsed[j:j + 1]
            a = self.inputs.to_numpy()
            b = self._second
            cap = _cap(prop.model)
            f_a = np.minimum(self.depth[:, j], cap)
            f_b = np.minimum(prop.depth(b, t)[:, 0], cap)
            f_ab = []
            for i in range(a.shape[1]):
                ab = a.copy()
                ab[:, i] = b[:, i]
                f_ab.append(np.minimum(prop.depth(ab, t)[:, 0], cap))
            s = sobol_indices(f_a, f_b, np.array(f_ab), resamples=resamples, seed=self.seed)
            self._cache[key] = pd.DataFrame(
                {"first": s["first"], "first_conf": s["first_conf"], "total": s["total"],
                 "total_conf": s["total_conf"]},
                index=pd.Index([v.label for v in self.variables], name="variable"))
        return self._cache[key]

    def _instant_index(self, instant: float | None) -> int:
        if instant is None:
            return self.instants.size - 1
        hits = np.flatnonzero(np.isclose(self.instants, float(instant), rtol=1e-9, atol=0))
        if hits.size == 0:
            raise InputError(f"instant {instant!r} is not one of the result's instants "
                             f"{self.instants.tolist()} [user time unit]")
        return int(hits[0])

    def summary(self, q: Sequence[float] = QUANTILES) -> pd.DataFrame:
        """Per instant: nominal depth ``depth_nominal`` and quantiles ``depth_q5`` ... [m] of
        the depth named by :attr:`depth_of` (also in the frame's ``attrs``), with a wall: the
        median's fraction of the wall ``wall_fraction_q50`` [-] and the probability of
        exceeding the limit ``exceedance`` [-]."""
        frame = self.quantiles(q).rename(columns=lambda x: f"depth_q{100 * x:g}")
        frame.attrs["depth_of"] = self.depth_of
        frame.insert(0, "depth_nominal", self.nominal_depth)
        if self.wall_thickness is not None:
            frame["wall_fraction_q50"] = np.quantile(self.depth, 0.5, axis=0) / self.wall_thickness
            frame["exceedance"] = self.exceedance()["probability"].to_numpy()
        return frame

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no samples): inputs, quantiles, exceedance, method."""
        out = {"name": self.name, "depth_of": self.depth_of, "method": self.method,
               "seed": self.seed,
               "samples": self.samples, "instants": self.instants.tolist(),
               "time_scale": self.time_scale, "origin": self.origin,
               "wall_thickness": self.wall_thickness, "depth_limit": self.depth_limit,
               "variables": [{"kind": v.kind, "name": v.name, "label": v.label,
                              "distribution": v.describe()} for v in self.variables],
               "nominal_depth": self.nominal_depth.tolist(),
               "quantiles": {str(k): [None if not np.isfinite(x) else float(x) for x in col]
                             for k, col in self.quantiles().items()}}
        if self.limit is not None:
            out["exceedance"] = self.exceedance()["probability"].tolist()
        return out


def _cap(model: DepthModel) -> float:
    """Largest depth of the relation's range [m] (the mobile's radius for a sector)."""
    if model.sector_arc is not None:
        return float(model.geometry.mobile_radius)
    return float(model.geometry.max_depth)


# ---------------------------------------------------------------------- the propagation
def _power_variable(power_scatter, uncertainty, nominal: float) -> Variable | None:
    if power_scatter is False or (isinstance(power_scatter, str) and power_scatter == "fixed"):
        return None
    absolute = uncertainty is not None and is_distribution(uncertainty)
    if absolute and power_scatter not in (None, "interval"):
        raise InputError("power= is already a distribution of the power [W]: power_scatter= "
                         "would compound a second scatter on it; give one of them")
    if absolute:
        return Variable("power", "power", uncertainty, "W")
    if power_scatter is None or (isinstance(power_scatter, str) and power_scatter == "interval"):
        if isinstance(uncertainty, PowerInterval):
            return Variable("power", "power", uncertainty.distribution(), "W")
        if isinstance(uncertainty, PowerResult) and len(uncertainty.blocks) >= 2:
            return Variable("power", "power",
                            uncertainty.confidence_interval().distribution(), "W")
        if power_scatter == "interval":
            raise InputError("power_scatter='interval' needs a PowerResult of >= 2 blocks or a "
                             "PowerInterval as the power")
        return None
    if isinstance(power_scatter, PowerInterval):
        return Variable("power", "power", power_scatter.distribution(), "W")
    dist = as_distribution(power_scatter, 1.0, "power_scatter")
    if dist is None:
        raise InputError("power_scatter: give a relative scatter of the power [-] (a factor "
                         "on the nominal power: LogNormal(sigma_ln=0.2), median 1), a "
                         "PowerInterval, 'interval' or 'fixed', got "
                         f"{power_scatter!r}; an absolute distribution [W] is power=")
    median = median_of(dist)
    if not 0.1 <= median <= 10.0:
        raise InputError(f"power_scatter is relative to the nominal power {nominal:g} W (a "
                         f"factor [-], median 1), but its median is {median:g}: a distribution "
                         f"of the power in W is given as power=, e.g. "
                         f"power=LogNormal({median:g}, sigma_ln=0.2)")
    return Variable("power", "power", Scaled(dist, nominal), "W")


def _coefficient_variables(spec, model: DepthModel, body: str) -> list[Variable]:
    if not spec:
        return []
    if not isinstance(spec, Mapping):
        raise InputError(f"{body} coefficients: give a mapping of coefficient name (or "
                         f"Code_Aster keyword) to distribution, got {spec!r}")
    law = model.law
    names = given_names(law, spec)
    out = []
    for (key, dist_spec), name in zip(spec.items(), names, strict=True):
        if name not in law.parameters:
            raise KeywordError(f"{law.name} has no coefficient {key!r} to vary; its "
                               f"coefficients: {list(law.parameters)}")
        if len(model.powers) > 1:
            raise KeywordError("the global depth of a sector table sums sectors of their own "
                               "coefficients: vary them through factor=LogNormal(...)")
        nominal = model.nominal(name, body)
        if nominal is None and (model.coefficients_mobile if body == "mobile"
                                else model.coefficients_obstacle)[0] is None:
            raise KeywordError(f"the {body} does not wear in this case: its coefficient "
                               f"{key!r} cannot vary")
        dist = as_distribution(dist_spec, nominal, f"{body} {name}")
        if dist is not None:
            out.append(Variable(body, name, dist, law.units.get(name, "")))
    return out


def _dimension_variables(spec, model: DepthModel) -> list[Variable]:
    if not spec:
        return []
    dims = model.geometry.dimensions()
    out = []
    for name, dist_spec in dict(spec).items():
        if name not in dims:
            raise KeywordError(f"{model.geometry.contact_type} has no dimension {name!r} to "
                               f"vary; its dimensions: {sorted(dims)}")
        dist = as_distribution(dist_spec, dims[name], f"dimension {name}")
        if dist is not None:
            out.append(Variable("dimension", name, dist,
                                "deg" if name.endswith("angle") else "m"))
    return out


def monte_carlo(case, power=None, *, coefficients: Mapping[str, Any] | None = None,
                obstacle_coefficients: Mapping[str, Any] | None = None, factor=None,
                power_scatter=None, dimensions: Mapping[str, Any] | None = None,
                samples: int = 10_000, seed: int | None = 0, method: str = "sobol",
                instants: Sequence[float] | None = None, sector: int | None = None,
                wall_thickness: float | None = None, depth_limit: float | None = None,
                name: str = "") -> UncertaintyResult:
    """Propagate the uncertain inputs of one contact to its worn depth.

    Parameters
    ----------
    case : mapping, WearCase, DataFrame or DepthModel
        The wear case: the keywords of :func:`fretwear.table.wear_table` (plus
        ``wall_thickness`` [m], ``depth_limit`` [-]), a wear-case object, a wear table with its
        metadata, or a model (:mod:`fretwear.uncertainty.cases`).
    power : float, PowerResult, PowerInterval, distribution, ContactHistory or path-like
        The wear power [W] or what gives it; a PowerResult of ≥ 2 blocks or a PowerInterval
        also gives the power's uncertainty; a distribution (``LogNormal(0.01,
        sigma_ln=0.2)``, a frozen scipy.stats one) is the power's own, absolute [W], its median
        the nominal power.
    coefficients, obstacle_coefficients : mapping, optional
        Distribution of law coefficients of the mobile / obstacle by name or Code_Aster keyword,
        e.g. ``{"coefficient": LogNormal(sigma_ln=0.7)}`` (median: the case's value) or
        ``{"COEF_USURE": LogNormal(9.2e-15, scatter=3)}`` [Pa⁻¹]; frozen scipy.stats
        distributions are accepted.
    factor : distribution, optional
        Distribution of a factor on every wear coefficient [-] (both bodies; e.g. the posterior
        of :func:`fretwear.uncertainty.calibrate`). Refused together with ``coefficients`` or
        ``obstacle_coefficients``: the two scatters would compound.
    power_scatter : None, "interval", "fixed", PowerInterval or distribution
        The power's scatter: None (default) takes the interval of a PowerResult or
        PowerInterval ``power`` (scaled Student truncated at 0), the distribution of a
        distribution ``power`` [W], and a number as exact; a distribution here is
        **relative**, a factor [-] on the nominal power (``LogNormal(sigma_ln=0.2)``, median
        1; a median outside [0.1, 10] is refused as a power in W given in the wrong place).
        An absolute distribution of the power [W] is ``power=LogNormal(0.01, sigma_ln=0.2)``.
    dimensions : mapping, optional
        Distributions of geometry dimensions [m] or [deg] (evaluated sample by sample: slower).
    samples : int
        Number of samples N (rounded up to a power of two for ``"sobol"``).
    seed : int, optional
        Seed of the design (same seed, same result).
    method : str
        ``"sobol"`` (scrambled Sobol' quasi-Monte Carlo) or ``"random"``.
    instants : sequence of float, optional
        Durations after the origin [user time unit] (default the case's instants).
    sector : int, optional
        1-based sector whose sector depth to propagate (default the global depth).
    wall_thickness : float, optional
        Wall thickness [m] (default the case's): gives the limit depth_limit × wall.
    depth_limit : float, optional
        Depth limit as a fraction of the wall [-] (default the case's, else 0.4).
    name : str
        Contact name.

    Returns
    -------
    UncertaintyResult

    Raises
    ------
    InputError
        No uncertain input, an unknown coefficient or dimension, a power of unknown scatter
        asked to scatter, a tube replaced during the run.

    Notes
    -----
    The inputs are independent; the design has 2d columns, the first d map to the inputs of
    the N samples (matrix A), the last d form the matrix B of the Sobol' indices
    (:meth:`UncertaintyResult.sensitivity`). A uniform point u maps to the input x = F⁻¹(u).
    All samples and instants are evaluated at once (the geometry's depth_from_volume on a flat
    array), except with uncertain dimensions.

    References
    ----------
    .. [1] A. B. Owen, "Scrambling Sobol' and Niederreiter-Xing points", Journal of
       Complexity 14 (1998) 466-489.
    .. [2] A. Saltelli et al., *Global Sensitivity Analysis. The Primer*, Wiley (2008).

    Examples
    --------
    >>> from fretwear.uncertainty import LogNormal
    >>> case = {"contact_type": "TUBE_BAV", "instants": [10.0], "time_scale": 3.15e7,
    ...         "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
    ...         "coefficients": {"COEF_USURE": 9.2e-15}, "wall_thickness": 1.09e-3}
    >>> r = monte_carlo(case, 0.01, coefficients={"coefficient": LogNormal(sigma_ln=0.7)},
    ...                 samples=4096)
    >>> round(float(r.quantiles([0.5]).iloc[0, 0] / r.nominal_depth[0]), 3)  # median = nominal
    1.0
    >>> round(float(r.exceedance()["probability"].iloc[0]), 2)  # P(depth > 0.4 × 1.09 mm)
    0.67
    """
    prepared = prepare_case(case, power, wall_thickness=wall_thickness,
                            depth_limit=depth_limit)
    key = "global" if sector is None else f"sector {int(sector)}"
    if key not in prepared.models:
        raise InputError(f"the case has no {key}; it has {sorted(prepared.models)}")
    model = prepared.models[key]
    if sector is None and model.geometry.contact_type is None:
        raise InputError("the case has no contact type (sector depths only): its global depth "
                         "is undefined; propagate a sector depth with sector=j")
    durations = prepared.durations if instants is None else np.asarray(instants, dtype=float)
    if durations is None or np.size(durations) == 0:
        raise InputError("give instants=[...] (durations after the origin, user time unit)")
    durations = np.atleast_1d(np.asarray(durations, dtype=float))
    if not (np.isfinite(durations).all() and (durations >= 0).all()):
        raise InputError(f"instants must be finite and >= 0, got {durations.tolist()}")

    if factor is not None and (coefficients or obstacle_coefficients):
        raise InputError("factor= and coefficients= both scale the wear coefficients: their "
                         "scatters would compound; give the coefficients' scatter either as one "
                         "factor on every coefficient (factor=) or coefficient by coefficient "
                         "(coefficients=, obstacle_coefficients=)")
    variables: list[Variable] = []
    if factor is not None:
        dist = as_distribution(factor, 1.0, "factor")
        if dist is not None:
            variables.append(Variable("factor", "factor", dist, "1"))
    variables += _coefficient_variables(coefficients, model, "mobile")
    variables += _coefficient_variables(obstacle_coefficients, model, "obstacle")
    pv = _power_variable(power_scatter, prepared.power, model.power)
    if pv is not None:
        variables.append(pv)
    variables += _dimension_variables(dimensions, model)
    d = len(variables)
    points = uniform_points(samples, 2 * d, method=method, seed=seed)
    values = np.column_stack([np.asarray(v.distribution.ppf(points[:, j]), dtype=float)
                              for j, v in enumerate(variables)])
    second = np.column_stack([np.asarray(v.distribution.ppf(points[:, d + j]), dtype=float)
                              for j, v in enumerate(variables)])
    for j, var in enumerate(variables):
        if not np.isfinite(values[:, j]).all() or (values[:, j] < 0).any():
            raise InputError(f"the distribution of {var.label} gives negative or infinite "
                             f"values ({var.describe()}); use one on [0, inf), e.g. LogNormal")
    elapsed = durations * model.time_scale
    prop = _Propagation(model, tuple(variables), elapsed)
    depth = prop.depth(values)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        nominal = np.asarray(model.depth(elapsed, warn=False), dtype=float)
    inputs = pd.DataFrame(values, columns=[v.label for v in variables])
    return UncertaintyResult(
        instants=model.origin + durations, depth=depth, inputs=inputs,
        variables=tuple(variables), nominal_depth=nominal, method=method, seed=seed,
        time_scale=model.time_scale, origin=model.origin, wall_thickness=model.wall.thickness,
        depth_limit=model.wall.limit, name=name or model.name, depth_of=key,
        case=prepared.case, power_result=prepared.power_result, _propagation=prop,
        _second=second)

