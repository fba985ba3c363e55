"""Calibration of a bundle's wear factor on field inspections, with censoring and honest spread.

:func:`calibrate_bundle` learns the factor on the wear coefficients (times the power's error) of
every contact from an :class:`~fretwear.assessment.inspections.Inspections` campaign:

* a sized indication through the technique's sizing model p(m | d);
* "no detectable degradation" on an inspected tube through 1 − POD(d);
* a tube not inspected gives nothing.

The factor is hierarchical (:mod:`fretwear.assessment.posterior`): a bundle-level lognormal, an
optional level per group (support type or region), and a contact-level scatter, so that one
contact keeps the spread that inspections of the others cannot remove; the power's own
log-spread σ_P adds to that scatter (the same power wore the tube before and after the
inspection). The depth of contact i is its :class:`~fretwear.table.depth.DepthModel`'s, the
one depth model: d_i(f, t) = ``model.depth(t, factor=f)``.

The forecast (:meth:`BundleCalibration.forecast`) uses the monotonicity of the depth in the
factor: the probability of exceeding a depth L at T is P(λ_i > λ_L,i) with
d_i(e^{λ_L,i}, T) = L, one root per contact. For a law linear in time the root is the model's
own inverse, f_L = (t_L(1) − t_r)/(T − t_r) with t_L(1) = ``model.time_to_depth(L)`` (t_r the
replacement, else 0); otherwise the crossing of ln d_i on the posterior's grid.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.assessment.calibration_inputs import (
    check_power_proportional,
    contact_scatter,
    group_index,
    prediction_models,
    resolve_inspections,
)
from fretwear.assessment.family import depths_at_factors
from fretwear.assessment.inspections import (
    Inspections,
    check_depths_within_walls,
    read_field_inspections,
)
from fretwear.assessment.posterior import (
    GridLevels,
    mass_range,
    moments_rows,
    ppf_rows,
    sf_rows,
    solve_levels,
)
from fretwear.errors import InputError, RangeWarning
from fretwear.keys import check_probabilities
from fretwear.table.depth import DepthModel
from fretwear.uncertainty.distributions import LogNormal

__all__ = ["CONTACT_SIGMA_LN", "POWER_SIGMA_LN", "BundleCalibration", "FactorPrior",
           "calibrate_bundle"]

CONTACT_SIGMA_LN = 0.35
"""The default σ of ln of one contact's factor about its group's [-] (a factor 2 either way at
95 %; an assumption to state, not a qualified value): :class:`FactorPrior`,
:func:`~fretwear.assessment.outage.assess` and the commands' ``--contact-sigma-ln``."""

POWER_SIGMA_LN = 0.2
"""The default σ_P, the log-spread of each contact's wear power [-] (about ±40 % at 90 %, a
power from a stationary vibration record of ordinary length; an assumption to state, not a
qualified value): :func:`calibrate_bundle`, :func:`~fretwear.assessment.outage.assess` and the
commands' ``--power-sigma-ln``. 0 takes the power as exact."""

_PASS1 = 801
_MAX_POINTS = 1601


@dataclass(frozen=True)
class FactorPrior:
    """Prior of the hierarchical factor.

    Parameters
    ----------
    bundle : LogNormal
        The bundle-level factor [-] (default median 1, a factor 3 either way at 95 %).
    group_sigma_ln : float
        τ_g, the standard deviation of a group's ln-factor around the bundle's [-] (0: no
        group level).
    contact_sigma_ln : float
        s_c, the standard deviation of one contact's ln-factor around its group's [-]
        (default :data:`CONTACT_SIGMA_LN`, 0.35: a factor 2 either way at 95 %; an assumption
        to state, not a qualified value).
    """

    bundle: LogNormal = field(default_factory=lambda: LogNormal(1.0, scatter=3.0))
    group_sigma_ln: float = 0.0
    contact_sigma_ln: float = CONTACT_SIGMA_LN

    def __post_init__(self) -> None:
        if not isinstance(self.bundle, LogNormal) or self.bundle.median is None \
                or not self.bundle.sigma_ln or self.bundle.sigma_ln <= 0:
            raise InputError("FactorPrior.bundle must be a LogNormal with a median and "
                             "sigma_ln > 0, e.g. LogNormal(1.0, scatter=3.0)")
        for name in ("group_sigma_ln", "contact_sigma_ln"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v >= 0):
                raise InputError(f"FactorPrior.{name} must be a finite number >= 0 [-], got "
                                 f"{v!r}")


@dataclass(frozen=True, eq=False)
class BundleCalibration:
    """The posterior of every contact's factor, and what it predicts.

    Attributes
    ----------
    contacts : list of str
        The contacts, in the order of every per-contact array.
    models : dict
        contact -> DepthModel (global depth).
    groups : list of str
        Group names; ``group_of[i]`` indexes it.
    group_of : numpy.ndarray
        Group index of each contact.
    scatter : numpy.ndarray
        s_i = sqrt(s_c² + σ_P,i²) [-] of each contact.
    levels : GridLevels
        The posterior densities on the grid of λ = ln f (bundle, groups, contacts).
    prior : FactorPrior
    observations : DataFrame
        The inspections used: the inspection table's columns, ``contact`` resolved, and
        ``elapsed_s`` [s]; ``prior_depth`` and ``posterior_depth`` [m], the depths at the
        prior's and the contact posterior's median factor.
    inspected : numpy.ndarray
        Whether each contact has a sized or NDD result (bool).
    plugged : numpy.ndarray
        Whether each contact's tube is plugged (an inspection row says so) (bool).
    """

    contacts: list
    models: dict
    groups: list
    group_of: np.ndarray
    scatter: np.ndarray
    levels: GridLevels
    prior: FactorPrior
    observations: pd.DataFrame
    inspected: np.ndarray
    plugged: np.ndarray

    # ------------------------------------------------------------------ the factor
    def factor_summary(self) -> pd.DataFrame:
        """Per contact: ``contact``, ``group``, ``inspected``, ``median`` [-] of the factor,
        ``mean_ln`` and ``sigma_ln`` [-] of its log, ``q05`` and ``q95`` [-]."""
        g = self.levels
        mean, sd = moments_rows(g.grid, g.contacts)
        q = np.exp(ppf_rows(g.grid, g.contacts, [0.05, 0.5, 0.95]))
        return pd.DataFrame({"contact": self.contacts,
                             "group": [self.groups[k] for k in self.group_of],
                             "inspected": self.inspected, "median": q[:, 1], "mean_ln": mean,
                             "sigma_ln": sd, "q05": q[:, 0], "q95": q[:, 2]})

    def contact_posterior(self, contact: str) -> tuple[np.ndarray, np.ndarray]:
        """(λ grid, density of λ = ln f) of one contact's factor [-] (the OA's input)."""
        try:
            i = self.contacts.index(contact)
        except ValueError:
            raise InputError(f"unknown contact {contact!r}") from None
        return self.levels.grid, self.levels.contacts[i]

    def bundle_factor(self) -> tuple[float, tuple[float, float]]:
        """Posterior median and central 90 % interval of the bundle-level factor [-]."""
        q = np.exp(ppf_rows(self.levels.grid, self.levels.bundle, [0.05, 0.5, 0.95])[0])
        return float(q[1]), (float(q[0]), float(q[2]))

    def group_factor(self, group: str) -> tuple[float, tuple[float, float]]:
        """Posterior median and central 90 % interval of one group's factor [-]."""
        k = self.groups.index(group)
        q = np.exp(ppf_rows(self.levels.grid, self.levels.groups[k], [0.05, 0.5, 0.95])[0])
        return float(q[1]), (float(q[0]), float(q[2]))

    # ------------------------------------------------------------------ the forecast
    def limit_log_factor(self, instant: float, limit: float | Sequence[float] | None = None
                         ) -> np.ndarray:
        """λ_L,i = ln f_L,i: the log-factor that brings each contact to ``limit`` at
        ``instant`` [-] (−inf: reached whatever the factor; +inf: never).

        Parameters
        ----------
        instant : float
            [user time unit of the predictions].
        limit : float or sequence, optional
            Depth [m] (default each model's depth_limit × wall thickness).
        """
        limits = self._limits(limit)
        out = np.empty(len(self.contacts))
        for i, contact in enumerate(self.contacts):
            out[i] = _limit_log_factor(self.models[contact], float(instant), limits[i],
                                       self.levels.grid)
        return out

    def node_exceedance(self, instant: float, limit=None) -> tuple[np.ndarray, np.ndarray]:
        """The exact node decomposition of the bundle's risk for
        :func:`fretwear.assessment.bundle_risk`: (p, weights).

        With one group, the contacts are independent given its factor c: at node c_k,
        P(λ_i > λ_L,i | c_k, D_i) = ∫_{λ>λ_L} L_i(λ) N(λ; c_k, s_i²) dλ / M_i(c_k).
        Returns p of shape (contacts, nodes) and the nodes' weights (summing to 1). With
        several groups, the nodes are the bundle-level μ and each group's factor is
        integrated given μ within a contact (contacts of one group then count as
        independent given μ: an approximation stated here).
        """
        from fretwear.assessment.posterior import kernel

        g = self.levels
        x = self.limit_log_factor(instant, limit)
        h = g.grid[1] - g.grid[0]
        with np.errstate(invalid="ignore"):  # the cell holding λ_L counted by its share
            above = np.clip((g.grid[None, :] - x[:, None]) / h + 0.5, 0.0, 1.0)
        above = np.where(np.isnan(above), (x[:, None] < g.grid[None, :]) * 1.0, above)
        top = np.max(g.log_lik, axis=1, keepdims=True)
        lik = np.exp(g.log_lik - np.where(np.isfinite(top), top, 0.0))
        p = np.empty((len(self.contacts), g.grid.size))
        for s in np.unique(self.scatter):
            rows = self.scatter == s
            k = kernel(g.grid, float(s))
            num = (lik[rows] * above[rows]) @ k.T
            den = lik[rows] @ k.T
            with np.errstate(invalid="ignore", divide="ignore"):
                p[rows] = np.where(den > 0, num / den, above[rows][:, -1:] * 1.0)
        if len(self.groups) == 1:
            weights = g.groups[0] * h
        else:
            weights = g.bundle * h
        keep = weights > 1e-16 * weights.max()
        p[self.plugged] = 0.0  # out of service: no part in the bundle's risk
        return np.clip(p[:, keep], 0.0, 1.0), weights[keep] / weights[keep].sum()

    def forecast(self, instant: float, *, limit=None,
                 q: Sequence[float] = (0.05, 0.5, 0.95)) -> pd.DataFrame:
        """Posterior predictive depth and probability of exceeding the limit of every contact
        at ``instant`` (vectorised over the contacts: one root each).

        Returns
        -------
        DataFrame
            ``contact``, ``group``, ``inspected``, ``plugged``, ``instant``, ``depth_q..``
            [m] (posterior quantiles), ``limit`` [m], ``wall_fraction_q50`` [-],
            ``exceedance`` [-] and ``exceedance_prior`` [-] (the same contact under the
            prior), ``factor_median``, ``factor_sigma_ln`` [-]; sorted by ``exceedance`` then
            ``depth_q50``, the worst first. A plugged contact (its tube plugged) is listed
            with ``plugged`` True, no depth (NaN) and exceedances 0: it is not in service.
        """
        q = check_probabilities(q, closed=False)
        g = self.levels
        limits = self._limits(limit)
        x = self.limit_log_factor(instant, limits)
        exceed = sf_rows(g.grid, g.contacts, x)
        exceed = np.where(np.isneginf(x), 1.0, np.where(np.isposinf(x), 0.0, exceed))
        prior = self.prior
        sd0 = np.sqrt(prior.bundle.sigma_ln ** 2 + prior.group_sigma_ln ** 2 + self.scatter ** 2)
        from scipy.stats import norm

        z = (x - math.log(prior.bundle.median)) / sd0
        exceed_prior = norm.sf(np.where(np.isfinite(z), z, np.sign(z) * np.inf))
        lam_q = ppf_rows(g.grid, g.contacts, q)
        depths = self._depths(float(instant), np.exp(lam_q))
        mean, sd = moments_rows(g.grid, g.contacts)
        out = pd.DataFrame({"contact": self.contacts,
                            "group": [self.groups[k] for k in self.group_of],
                            "inspected": self.inspected, "plugged": self.plugged,
                            "instant": float(instant)})
        for j, level in enumerate(q):
            out[f"depth_q{100 * level:g}"] = depths[:, j]
        out["limit"] = limits
        walls = np.array([self.models[c].wall.thickness or math.nan for c in self.contacts])
        if "depth_q50" in out:
            out["wall_fraction_q50"] = out["depth_q50"].to_numpy() / walls
        out["exceedance"] = np.where(self.plugged, 0.0, exceed)
        out["exceedance_prior"] = np.where(self.plugged, 0.0, exceed_prior)
        gone = [c for c in out.columns if c.startswith("depth_q") or c == "wall_fraction_q50"]
        out.loc[self.plugged, gone] = np.nan
        out["factor_median"] = np.exp(ppf_rows(g.grid, g.contacts, [0.5])[:, 0])
        out["factor_sigma_ln"] = sd
        key = "depth_q50" if "depth_q50" in out else out.columns[4]
        return out.sort_values(["exceedance", key], ascending=False, kind="stable",
                               ignore_index=True)

    def _limits(self, limit) -> np.ndarray:
        if limit is None:
            values = [self.models[c].limit_depth for c in self.contacts]
            if any(v is None for v in values):
                raise InputError("a contact has no wall thickness: give limit= [m]")
            return np.array(values, dtype=float)
        arr = np.broadcast_to(np.asarray(limit, dtype=float), (len(self.contacts),)).copy()
        if not (np.isfinite(arr) & (arr > 0)).all():
            raise InputError(f"limit must be depths > 0 [m], got {limit!r}")
        return arr

    def _depths(self, instant: float, factors: np.ndarray) -> np.ndarray:
        out = np.empty_like(factors)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RangeWarning)
            for i, c in enumerate(self.contacts):
                m = self.models[c]
                out[i] = m.depth(np.full(factors.shape[1], _elapsed(m, instant, c)),
                                 factor=factors[i], warn=False)
        return out


def _elapsed(model: DepthModel, instant: float, contact: str) -> float:
    if instant < model.origin:
        raise InputError(f"instant {instant:g} is before the origin {model.origin:g} of "
                         f"contact {contact!r}")
    return (instant - model.origin) * model.time_scale


def _limit_log_factor(model: DepthModel, instant: float, limit: float,
                      grid: np.ndarray) -> float:
    """ln f with d(f, T) = limit (module docstring)."""
    elapsed = _elapsed(model, instant, model.name)
    if elapsed <= 0:
        return -math.inf if model.depth(0.0, warn=False) >= limit else math.inf
    if model.law.linear_in_time:
        start = 0.0 if model.replacement is None else model.replacement
        if elapsed <= start:
            return math.inf  # the new tube is not in place yet: the old one's depth is known
        t_limit = float(model.time_to_depth(limit))
        if not math.isfinite(t_limit):
            return math.inf
        if t_limit <= start:
            return -math.inf
        return math.log((t_limit - start) / (elapsed - start))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        d = model.depth(np.full(grid.size, elapsed), factor=np.exp(grid), warn=False)
    d = np.where(np.isnan(d), np.inf, d)
    if d[0] >= limit:
        return -math.inf
    if d[-1] < limit:
        return math.inf
    k = int(np.argmax(d >= limit))
    lo, hi = math.log(max(d[k - 1], 1e-300)), math.log(d[k]) if math.isfinite(d[k]) else None
    if hi is None or hi == lo:
        return float(grid[k])
    return float(grid[k - 1] + (math.log(limit) - lo) / (hi - lo) * (grid[k] - grid[k - 1]))


def _log_likelihood(obs: pd.DataFrame, models, contacts, techniques, grid) -> np.ndarray:
    """log L_i(λ) on the grid (n, N): the sum over each contact's sized and NDD results (the
    depths of every result at every factor in one :func:`depths_at_factors` call)."""
    out = np.zeros((len(contacts), grid.size))
    used = obs[obs["status"] != "not inspected"]
    if used.empty:
        return out
    for name in set(used.loc[used["status"] == "ndd", "technique"]):
        if techniques[name].pod is None:
            line = used.loc[(used["status"] == "ndd") & (used["technique"] == name),
                            "line"].iloc[0]
            raise InputError(f"inspections line {line}: NDD with technique {name!r}, which "
                             "has no POD: give the technique's probability of detection "
                             "(command line --pod-a50-mm and --pod-a90-mm; Python "
                             "Technique(sizing, pod=LogisticPOD.from_depths(a50, a90)))")
    d = depths_at_factors([models[c] for c in used["contact"]], used["elapsed_s"].to_numpy(),
                          np.exp(grid))
    d = np.where(np.isnan(d), 1e300, d)  # beyond the geometry: through everything
    log_lik = np.empty(d.shape)
    status, technique = used["status"].to_numpy(), used["technique"].to_numpy()
    measured = used["depth"].to_numpy(float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for name in set(technique):
            tech = techniques[name]
            for sized in (True, False):
                rows = (technique == name) & ((status == "sized") == sized)
                if not rows.any():
                    continue
                lik = tech.sizing.likelihood(measured[rows, None], d[rows]) if sized \
                    else tech.pod.miss(d[rows])
                log_lik[rows] = np.log(np.maximum(lik, 0.0))
    index = used["index"].to_numpy(int)
    order = np.argsort(index, kind="stable")  # each contact's results summed (reduceat)
    first = np.flatnonzero(np.r_[True, np.diff(index[order]) != 0])
    out[index[order][first]] = np.add.reduceat(log_lik[order], first, axis=0)
    return out


def _grid_around(center: float, half: float, n: int) -> np.ndarray:
    return np.linspace(center - half, center + half, n)


def calibrate_bundle(predictions, inspections, *, techniques=None,
                     prior: FactorPrior | None = None, groups=None, identity=None,
                     power_sigma_ln=POWER_SIGMA_LN, origin_date=None, time_unit: str = "year",
                     levels_only: bool = False) -> BundleCalibration:
    """The hierarchical posterior of every contact's factor from a field campaign.

    Parameters
    ----------
    predictions : mapping of str to DepthModel or wear table
        Each contact's depth model (a bundle's: ``bundle_predictions(OUT)[0]``).
    inspections : Inspections, path-like or DataFrame
        The campaign (:func:`~fretwear.assessment.inspections.read_field_inspections`).
    techniques : Technique or mapping, optional
        The technique models, when ``inspections`` is a file or a DataFrame.
    prior : FactorPrior, optional
        Bundle prior, group and contact scatter (default :class:`FactorPrior`).
    groups : None, "support type" or mapping of contact to group name
        The optional group level (with ``prior.group_sigma_ln`` > 0).
    identity : DataFrame, optional
        ``contact, tube_row, tube_column, support`` of the contacts, to place inspections
        given by tube location and to group by support type.
    power_sigma_ln : float or mapping of contact to float
        σ_P, the log-spread of each contact's power [-] (from its confidence interval:
        ln(1 + half-width/power)/z); adds to the contact scatter. Default
        :data:`POWER_SIGMA_LN` (0.2), the commands' too; 0 takes the power as exact.
    origin_date, time_unit
        For an inspection file with dates (:func:`read_field_inspections`).
    levels_only : bool
        True: the bundle and group levels and each contact's evidence only, what
        :func:`fretwear.assessment.outage.assess` reads (no per-contact posterior: the
        forecast and the factor summary then need a full calibration).

    Returns
    -------
    BundleCalibration

    Raises
    ------
    InputError
        An unknown contact or location, an NDD without a POD, an inspection before the
        origin of its contact's prediction.

    Notes
    -----
    The posterior is computed on a uniform grid of λ = ln f in two passes: one over the
    prior's range (10 standard deviations), then one over the range where any level holds
    mass, with a spacing of a tenth of the narrowest posterior's standard deviation (at most
    1601 points). Module docstring of :mod:`fretwear.assessment.posterior`: the levels.
    """
    prior = prior or FactorPrior()
    models = prediction_models(predictions)
    contacts = list(models)
    if not isinstance(inspections, Inspections):
        inspections = read_field_inspections(inspections, techniques, origin_date=origin_date,
                                             time_unit=time_unit)
    elif techniques is not None:
        inspections = Inspections(inspections.table, dict(techniques) if isinstance(
            techniques, Mapping) else {techniques.name: techniques}, inspections.source,
            inspections.depth_column)
    sectors = inspections.table["sector"].notna()
    if sectors.any():
        raise InputError(f"inspections line {inspections.table.loc[sectors, 'line'].iloc[0]}: "
                         "a sector depth; calibrate_bundle takes global depths (sector depths: "
                         "fretwear.uncertainty.calibrate)")
    check_depths_within_walls(inspections, _walls(models, identity))
    obs = resolve_inspections(inspections.table, contacts, identity)
    used = set(obs.loc[obs["status"] != "not inspected", "technique"])
    missing = sorted(t for t in used if t not in inspections.techniques)
    if missing:
        raise InputError(f"technique(s) {missing} of the inspections have no model; give "
                         "techniques={name: Technique(SizingModel(...), LogisticPOD(...))}")
    obs["elapsed_s"] = [_elapsed(models[c], float(t), c)
                        for c, t in zip(obs["contact"], obs["instant"], strict=True)]
    names, group_of = group_index(contacts, groups, identity)
    scatter = contact_scatter(contacts, prior.contact_sigma_ln, power_sigma_ln)
    check_power_proportional(models, contacts, scatter ** 2 - prior.contact_sigma_ln ** 2)
    mu0, tau0 = math.log(prior.bundle.median), float(prior.bundle.sigma_ln)
    tau_g = prior.group_sigma_ln if groups is not None else 0.0
    half = 10.0 * math.sqrt(tau0 ** 2 + tau_g ** 2 + float(scatter.max()) ** 2)
    grid = _grid_around(mu0, half, _PASS1)
    levels = _solve(obs, models, contacts, inspections.techniques, grid, group_of, names,
                    scatter, mu0, tau0, tau_g)
    every = np.vstack([levels.bundle, levels.groups, levels.contacts])
    lo, hi = mass_range(grid, every)
    _, sd = moments_rows(grid, every)
    step = max(min(float(sd.min()) / 10.0, (hi - lo) / 200.0), (hi - lo) / (_MAX_POINTS - 1))
    grid = np.arange(lo, hi + step, step)
    levels = _solve(obs, models, contacts, inspections.techniques, grid, group_of, names,
                    scatter, mu0, tau0, tau_g, posteriors=not levels_only)
    inspected = np.zeros(len(contacts), bool)
    inspected[obs.loc[obs["status"] != "not inspected", "index"].to_numpy(int)] = True
    plugged = np.zeros(len(contacts), bool)
    plugged[obs.loc[obs["plugged"].astype(bool), "index"].to_numpy(int)] = True
    if identity is not None and plugged.any():  # a plugged tube: every contact of it
        where = identity.drop_duplicates("contact").set_index("contact")
        spot = [(where.at[c, "tube_row"], where.at[c, "tube_column"]) if c in where.index
                else (c, None) for c in contacts]
        gone = {spot[i] for i in np.flatnonzero(plugged)}
        plugged |= np.array([t in gone for t in spot])
    result = BundleCalibration(contacts=contacts, models=models, groups=names,
                               group_of=group_of, scatter=scatter, levels=levels, prior=prior,
                               observations=obs, inspected=inspected, plugged=plugged)
    return result if levels_only else _with_depths(result)


def _walls(models, identity) -> pd.DataFrame:
    """``contact``, ``wall_thickness`` [m] (NaN without a wall) and, with the identity table,
    ``tube_row``, ``tube_column`` of every contact."""
    walls = pd.DataFrame({"contact": list(models), "wall_thickness": [
        math.nan if m.wall.thickness is None else float(m.wall.thickness)
        for m in models.values()]})
    if identity is None or not {"tube_row", "tube_column"} <= set(identity):
        return walls
    spots = identity.drop_duplicates("contact")[["contact", "tube_row", "tube_column"]]
    return walls.merge(spots, on="contact", how="left")


def _solve(obs, models, contacts, techniques, grid, group_of, names, scatter, mu0, tau0,
           tau_g, posteriors: bool = True) -> GridLevels:
    log_lik = _log_likelihood(obs, models, contacts, techniques, grid)
    if not np.isfinite(log_lik.max(axis=1)).all():
        bad = contacts[int(np.flatnonzero(~np.isfinite(log_lik.max(axis=1)))[0])]
        raise InputError(f"calibration: no factor within {math.exp(grid[0]):.3g}..."
                         f"{math.exp(grid[-1]):.3g} explains the inspections of contact "
                         f"{bad!r}; check their units (depth [m], depth_mm [mm])")
    return solve_levels(grid, log_lik, group_of, len(names), scatter, mu0, tau0, tau_g,
                        contacts=posteriors)


def _with_depths(result: BundleCalibration) -> BundleCalibration:
    obs = result.observations.copy()
    median = np.exp(ppf_rows(result.levels.grid, result.levels.contacts, [0.5])[:, 0])
    f0 = float(result.prior.bundle.median)
    factors = np.column_stack([np.full(len(obs), f0),
                               median[obs["index"].to_numpy(int)] if len(obs) else []])
    d = depths_at_factors([result.models[c] for c in obs["contact"]],
                          obs["elapsed_s"].to_numpy(float), factors) if len(obs) \
        else np.empty((0, 2))
    obs["prior_depth"] = d[:, 0]
    obs["posterior_depth"] = d[:, 1]
    return BundleCalibration(**{**result.__dict__, "observations": obs})
