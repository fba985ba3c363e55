"""Each contact's depth at the end of an operating interval, as a probability: from its
as-found state at the outage, plus the growth of the calibrated model.

Notation (per contact; times in the bundle's time unit, counted from the contact's origin):

* g = f·π, the contact's growth factor: f its wear factor (the bundle's posterior, a node
  λ_k of weight w_k, times the contact's own scatter, σ_c in ln) and π the factor on its wear
  power (its interval, σ_P in ln). Given the node, ln g ~ N(λ_k, s²), s² = σ_c² + σ_P².
* The law is linear in time (Archard, KWU-EPRI): the worn volume is V₀ + g·r·t, so the
  state reached at the factor g after t is the nominal model's state after g·t (the
  nominal-time equivalent, τ). τ(d), the nominal time to the depth d, is
  :meth:`fretwear.table.depth.DepthModel.time_to` (one root per contact, no new inversion)
  and τ_L = τ(L) that of the plugging limit L.

The contact exceeds L by the end of the interval (as found at a, interval T):

* not inspected: g·(a + T) > τ_L, P = Φ̄((ln(τ_L/(a + T)) − λ_k)/s);
* sized (measured m; true depth d₀ ~ N((m − a_s)/b, (σ/b)²) by the sizing model, independent
  of the growth): τ(d₀) + g·T > τ_L, P = E_d₀[Φ̄((ln((τ_L − τ(d₀))/T) − λ_k)/s)] by
  Gauss-Hermite in d₀ (1 where d₀ ≥ L);
* inspected and nothing detected (NDD): the prediction's posterior given the miss, the
  density of u = ln g ∝ φ((u − λ_k)/s)·(1 − POD(d(e^u, a))), and g·(a + T) > τ_L.

Every case is monotone in g, so the probability is one threshold per contact and node: no
sampling. With s = 0 (no contact scatter, no power interval), Φ̄ is the step 1[λ_k > ·].
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from fretwear.assessment.family import Family
from fretwear.errors import InputError

__all__ = ["FactorNodes", "GrowthModel"]

_U_HALF = 8.0     # the NDD grid of u = ln g spans λ ± 8 s around the nodes
_U_POINTS = 129
_D0_NODES = 48


def _sf(x) -> np.ndarray:
    """Φ̄(x), the standard normal tail."""
    return 0.5 * special.erfc(np.asarray(x, float) / math.sqrt(2.0))


@dataclass(frozen=True)
class FactorNodes:
    """The calibrated factor: the bundle's shared log-factor at quadrature nodes, and the
    spread each contact keeps of its own.

    Attributes
    ----------
    log_factor : numpy.ndarray
        λ_k = ln f at the nodes [-], shape (nodes,); or (groups, nodes) with a group level
        (support type, region): λ_gk, group g's log-factor at the joint node k, each
        contact taking its group's row (:meth:`GrowthModel.build`'s ``group_of``).
    weights : numpy.ndarray
        w_k [-], summing to 1.
    contact_sigma : float
        σ_c, the standard deviation of ln f of one contact about the bundle's [-].
    power_sigma : float
        σ_P, the standard deviation of ln of the factor on each contact's power [-].
    """

    log_factor: np.ndarray
    weights: np.ndarray
    contact_sigma: float = 0.0
    power_sigma: float = 0.0

    def __post_init__(self) -> None:
        lam = np.atleast_1d(np.asarray(self.log_factor, float))
        w = np.atleast_1d(np.asarray(self.weights, float))
        if lam.ndim not in (1, 2) or lam.shape[-1:] != w.shape or not np.isfinite(lam).all() \
                or (w < 0).any() or w.sum() <= 0:
            raise InputError("FactorNodes: one finite log-factor (per group) and one weight "
                             ">= 0 per node")
        for name in ("contact_sigma", "power_sigma"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InputError(f"{name} must be a standard deviation of ln >= 0, got {v!r}")
        object.__setattr__(self, "log_factor", lam)
        object.__setattr__(self, "weights", w / w.sum())

    @property
    def table(self) -> np.ndarray:
        """λ_gk, shape (groups, nodes) [-] (one row without a group level)."""
        return np.atleast_2d(self.log_factor)

    @property
    def sigma(self) -> float:
        """s = √(σ_c² + σ_P²) [-]."""
        return math.hypot(self.contact_sigma, self.power_sigma)

    @classmethod
    def from_posterior(cls, posterior, *, count: int = 16, contact_sigma: float = 0.0,
                       power_sigma: float = 0.0) -> FactorNodes:
        """Nodes of a factor's distribution (anything with ``ppf``: a LogNormal, a calibration's
        GridPosterior): λ_k = ln F⁻¹(Φ(x_k)) at the probabilists' Gauss-Hermite nodes x_k
        (exact for a lognormal).

        Examples
        --------
        >>> from fretwear.uncertainty.distributions import LogNormal
        >>> n = FactorNodes.from_posterior(LogNormal(2.0, sigma_ln=0.3), count=8)
        >>> round(float(np.dot(n.weights, n.log_factor)), 12) == round(math.log(2.0), 12)
        True
        """
        x, w = np.polynomial.hermite_e.hermegauss(int(count))
        u = np.clip(0.5 * special.erfc(-x / math.sqrt(2.0)), 1e-300, 1 - 1e-16)
        lam = np.log(np.asarray(posterior.ppf(u), float))
        return cls(lam, w, contact_sigma=float(contact_sigma), power_sigma=float(power_sigma))

    @classmethod
    def from_levels(cls, grid, bundle, log_groups=None, group_sigma: float = 0.0, *,
                    count: int = 16, per_group: int | None = None, contact_sigma: float = 0.0,
                    power_sigma: float = 0.0) -> FactorNodes:
        """Nodes of a hierarchical posterior on a grid of λ = ln f
        (:mod:`fretwear.assessment.posterior`).

        The bundle level μ is taken at ``count`` nodes, λ = F⁻¹(Φ(x_k)) at the probabilists'
        Gauss-Hermite nodes x_k. With a group level (``log_groups``, τ_g = ``group_sigma`` > 0)
        the groups are independent given μ, each with the posterior

        .. math:: p(c_g \\mid \\mu, D) \\propto N(c_g; \\mu, \\tau_g^2)\\,
                  \\prod_{i \\in g} M_i(c_g)

        (M_i a contact's evidence, ``GridLevels.log_evidence``; a group with no inspected
        contact keeps N(μ, τ_g²), taken in closed form), at ``per_group`` nodes given each μ
        node: the joint nodes are their tensor product, count·per_group^G of them, so that
        contacts of one group share their group's factor at every node (the dependence
        P(any) needs). Default per_group: 8 for one group, 5 for two, 3 beyond.

        Parameters
        ----------
        grid : array_like
            Uniform grid of λ [-], shape (N,).
        bundle : array_like
            Density of μ on the grid, shape (N,).
        log_groups : array_like, optional
            log Π_{i∈g} M_i(c) of each group on the grid, shape (G, N) (zeros: no data).
        group_sigma : float
            τ_g [-].
        count, per_group : int
            Nodes of μ, and of each group's factor given μ.
        contact_sigma, power_sigma : float
            σ_c and σ_P [-] (the class's attributes).

        Examples
        --------
        >>> grid = np.linspace(-6, 6, 2401)
        >>> n = FactorNodes.from_levels(grid, np.exp(-0.5 * (grid / 0.5) ** 2),
        ...                             np.zeros((2, grid.size)), 0.3, count=8)
        >>> n.table.shape, round(float(n.weights @ n.table[1] ** 2), 3)   # 0.5² + 0.3²
        ((2, 200), 0.34)
        """
        from fretwear.assessment.posterior import ppf_rows

        grid = np.asarray(grid, float)
        x, w = np.polynomial.hermite_e.hermegauss(int(count))
        u = np.clip(0.5 * special.erfc(-x / math.sqrt(2.0)), 1e-300, 1 - 1e-16)
        mu = ppf_rows(grid, np.asarray(bundle, float), u)[0]
        sig = {"contact_sigma": float(contact_sigma), "power_sigma": float(power_sigma)}
        if log_groups is None or not group_sigma > 0:
            return cls(mu, w, **sig)
        log_groups = np.atleast_2d(np.asarray(log_groups, float))
        groups = log_groups.shape[0]
        m = int(per_group or (8 if groups == 1 else 5 if groups == 2 else 3))
        xm, wm = np.polynomial.hermite_e.hermegauss(m)
        um = 0.5 * special.erfc(-xm / math.sqrt(2.0))
        cond = np.empty((groups, mu.size, m))
        for g in range(groups):
            if not np.any(log_groups[g]):
                cond[g] = mu[:, None] + group_sigma * xm[None, :]
                continue
            log_p = -0.5 * ((grid[None, :] - mu[:, None]) / group_sigma) ** 2 + log_groups[g]
            top = np.max(log_p, axis=1, keepdims=True)
            cond[g] = ppf_rows(grid, np.exp(log_p - np.where(np.isfinite(top), top, 0.0)), um)
        pick = np.array(list(itertools.product(range(m), repeat=groups))).reshape(-1, groups)
        table = np.stack([cond[g][:, pick[:, g]].ravel() for g in range(groups)])
        weights = (w[:, None] * np.prod((wm / wm.sum())[pick], axis=1)[None, :]).ravel()
        return cls(table, weights, **sig)

    def quantiles(self, q, group: int = 0) -> np.ndarray:
        """Quantiles of ln g, the mixture Σ w_k N(λ_gk, s²) [-] (of ``group``'s contacts)."""
        from scipy.optimize import brentq

        s, lam, w = self.sigma, self.table[group], self.weights
        out = []
        for level in np.atleast_1d(q):
            if s == 0:
                order = np.argsort(lam)
                cum = np.cumsum(w[order])
                out.append(lam[order][min(int(np.searchsorted(cum, level)), lam.size - 1)])
                continue
            cdf = lambda x: float(np.dot(w, 1 - _sf((x - lam) / s))) - level  # noqa: E731,B023
            out.append(brentq(cdf, lam.min() - 12 * s, lam.max() + 12 * s, xtol=1e-12))
        return np.asarray(out)


@dataclass
class GrowthModel:
    """Each contact's probability of exceeding its limit by the end of an interval
    (module notes), precomputed once and evaluated at any interval T.

    Built by :meth:`build`; :meth:`probabilities` gives p_ik(T), shape (contacts, nodes).
    """

    nodes: FactorNodes
    found: np.ndarray       # a, the as-found instant after the origin [time unit]
    tau_limit: np.ndarray   # τ_L [time unit]
    kind: np.ndarray        # 0 not inspected, 1 sized, 2 NDD
    tau_d0: np.ndarray      # (sized, J) τ(d₀_j) [time unit]
    h_d0: np.ndarray        # (sized, J) weights of d₀ (sum 1 per contact)
    d0_nodes: np.ndarray    # (sized, J) d₀_j [m]
    ndd_tail: np.ndarray    # (ndd, nodes, U) normalised tail of u = ln g
    u_grid: np.ndarray      # (ndd, U)
    ndd_miss: np.ndarray    # (ndd, U) 1 − POD of the depth at the inspection, on the grid
    family: Family | None = None
    group_of: np.ndarray | None = None  # each contact's row of nodes.table (None: row 0)

    def log_factors(self, rows=None) -> np.ndarray:
        """λ of the contacts at positions ``rows`` (all: None) at every node, shape
        (contacts, nodes), or (1, nodes) when every contact shares it [-]."""
        table = self.nodes.table
        if table.shape[0] == 1 or self.group_of is None:
            return table[:1]
        return table[self.group_of if rows is None else self.group_of[rows]]

    def factor_quantile(self, q: float) -> np.ndarray:
        """The quantile ``q`` of each contact's growth factor g [-] (its group's mixture)."""
        per_group = np.exp([self.nodes.quantiles([q], group=k)[0]
                            for k in range(self.nodes.table.shape[0])])
        return per_group[self.group_of] if self.group_of is not None and per_group.size > 1 \
            else np.full(self.found.size, per_group[0])

    @classmethod
    def build(cls, models, found, kind, measured, nodes: FactorNodes, *, sizing, pod,
              group_of=None) -> GrowthModel:
        """Precompute τ_L, τ(d₀) and the NDD posteriors.

        Parameters
        ----------
        models : sequence of DepthModel
            Each contact's global depth (its ``limit_depth`` the plugging limit [m]).
        found : array_like
            As-found instant of each contact [time unit, absolute].
        kind : array_like of int
            0 not inspected, 1 sized, 2 NDD.
        measured : array_like
            The sized depth [m] (NaN elsewhere).
        nodes : FactorNodes
        sizing : SizingModel
        pod : LogisticPOD
        group_of : array_like of int, optional
            Each contact's group, its row of ``nodes.table`` (with a group level).
        """
        kind = np.asarray(kind, int)
        if nodes.table.shape[0] > 1:
            group_of = np.asarray(group_of, int) if group_of is not None else None
            if group_of is None or group_of.shape != kind.shape or group_of.min() < 0 \
                    or group_of.max() >= nodes.table.shape[0]:
                raise InputError("nodes with a group level need each contact's group "
                                 f"(group_of, integers in [0, {nodes.table.shape[0]}))")
        else:
            group_of = None
        family = Family.of(models)
        a = np.asarray(found, float) - family.origin
        if (a < 0).any():
            bad = int(np.flatnonzero(a < 0)[0])
            raise InputError(f"contact {models[bad].name!r}: inspected before its origin")
        limits_all = np.array([m.limit_depth for m in models])
        tau_l = family.nominal_time(limits_all[:, None], np.arange(len(models)))[:, 0]
        sized = np.flatnonzero(kind == 1)
        d0, h = _depth_nodes(np.asarray(sizing.true_depth(np.asarray(measured, float)[sized])),
                             sizing.true_depth_sigma(), limits_all[sized])
        tau_d0 = family.nominal_time(d0, sized)  # τ(d₀) = 0 for d₀ <= 0 (unworn)
        ndd = np.flatnonzero(kind == 2)
        s, lam = nodes.sigma, nodes.table
        lam_ndd = lam[:1] if group_of is None else lam[group_of[ndd]]
        tails = np.zeros((ndd.size, lam.shape[1], _U_POINTS))
        grids = np.zeros((ndd.size, _U_POINTS))
        misses = np.zeros((ndd.size, _U_POINTS))
        if s > 0 and ndd.size:
            u = np.linspace(lam.min() - _U_HALF * s, lam.max() + _U_HALF * s, _U_POINTS)
            depth = family.depth(a[ndd, None] * np.exp(u)[None, :], ndd)
            misses = pod.miss(np.where(np.isnan(depth), np.inf, depth))
            grids = np.broadcast_to(u, misses.shape).copy()
            seg = _segments(grids[:, None, :-1], grids[:, None, 1:], misses[:, None, :-1],
                            misses[:, None, 1:], lam_ndd[:, :, None], s)
            tails[:, :, :-1] = np.cumsum(seg[:, :, ::-1], axis=2)[:, :, ::-1]
        return cls(nodes=nodes, found=a, tau_limit=tau_l, kind=kind, tau_d0=tau_d0,
                   h_d0=h, d0_nodes=d0, ndd_tail=tails, u_grid=grids, ndd_miss=misses,
                   family=family, group_of=group_of)

    def probabilities(self, interval: float) -> np.ndarray:
        """p_ik, the probability that contact i exceeds its limit by the end of ``interval``
        [time unit] after its inspection, given the factor's node k; shape (contacts, nodes)."""
        T = float(interval)
        if not (math.isfinite(T) and T >= 0):
            raise InputError(f"the interval must be a time >= 0, got {interval!r}")
        s = self.nodes.sigma
        with np.errstate(divide="ignore", invalid="ignore"):
            c = np.log(self.tau_limit / (self.found + T))  # ln of the g that reaches L
        p = _step_or_sf(c[:, None], self.log_factors(), s)
        sized = np.flatnonzero(self.kind == 1)
        if sized.size:
            with np.errstate(divide="ignore", invalid="ignore"):
                gap = (self.tau_limit[sized, None] - self.tau_d0) / T if T > 0 else \
                    np.where(self.tau_limit[sized, None] > self.tau_d0, np.inf, -np.inf)
                cj = np.where(gap > 0, np.log(gap), -np.inf)
            pj = _step_or_sf(cj[:, :, None], self.log_factors(sized)[:, None, :], s)
            p[sized] = np.einsum("ij,ijk->ik", self.h_d0, pj)
        ndd = np.flatnonzero(self.kind == 2)
        if ndd.size and s > 0:  # the tail from the cut: its partial segment, then whole ones
            u, miss = self.u_grid, self.ndd_miss
            step = u[:, 1] - u[:, 0]
            cut = np.clip(c[ndd], u[:, 0], u[:, -1])
            j = np.clip(((cut - u[:, 0]) // step).astype(int), 0, u.shape[1] - 2)
            rows = np.arange(ndd.size)
            u0, u1 = u[rows, j], u[rows, j + 1]
            m0, m1 = miss[rows, j], miss[rows, j + 1]
            with np.errstate(divide="ignore"):
                m_cut = np.exp(np.log(np.maximum(m0, 1e-300)) + (cut - u0) / step
                               * (np.log(np.maximum(m1, 1e-300)) - np.log(np.maximum(m0, 1e-300))))
            part = _segments(cut[:, None], u1[:, None], m_cut[:, None], m1[:, None],
                             self.log_factors(ndd), s)
            total = self.ndd_tail[:, :, 0]
            tail = part + self.ndd_tail[rows, :, j + 1]
            p[ndd] = np.where(total > 0, tail / np.where(total > 0, total, 1.0), 0.0)
        return np.clip(p, 0.0, 1.0)

    def _subset(self, rows) -> GrowthModel:
        """The model of the contacts at positions ``rows`` only."""
        return GrowthModel(**_subset_fields(self, rows))

    def end_nominal_times(self, interval: float, q, rows=None) -> np.ndarray:
        """Quantiles ``q`` of each contact's nominal-time equivalent at the end of the
        interval [time unit] (the depth's quantiles through the nominal model: depth grows
        with it), shape (contacts, len(q)); ``rows``: only these contacts (positions)."""
        if rows is not None:
            return self._subset(rows).end_nominal_times(interval, q)
        q = np.atleast_1d(np.asarray(q, float))
        table, s, w = self.nodes.table, self.nodes.sigma, self.nodes.weights
        g = np.exp([self.nodes.quantiles(q, group=k) for k in range(table.shape[0])])
        own = np.zeros(self.found.size, int) if self.group_of is None else self.group_of
        out = (self.found + interval)[:, None] * g[own]
        z, hz = np.polynomial.hermite_e.hermegauss(16)
        hz = hz / hz.sum()
        growth = np.exp(table[:, :, None] + s * z[None, None, :]).reshape(table.shape[0], -1)
        wg = (w[:, None] * hz[None, :]).ravel()                       # (K·Z,)
        for row, i in enumerate(np.flatnonzero(self.kind == 1)):
            tau = self.tau_d0[row][:, None] + interval * growth[own[i]][None, :]
            out[i] = _weighted_quantiles(tau.ravel(), np.outer(self.h_d0[row], wg).ravel(), q)
        for row, i in enumerate(np.flatnonzero(self.kind == 2)):
            if s == 0:
                continue
            u = self.u_grid[row]
            mass = -np.diff(self.ndd_tail[row], axis=1)                # (K, U-1)
            mass = mass / self.ndd_tail[row][:, :1]
            pts = 0.5 * (u[1:] + u[:-1])
            weight = (w[:, None] * mass).sum(axis=0)
            out[i] = (self.found[i] + interval) * np.exp(
                _weighted_quantiles(pts, weight, q))
        return out


def _pick(kind, rows, which):
    """Positions, among the contacts of ``which`` kind, of the ``rows`` of that kind."""
    of_kind = np.flatnonzero(kind == which)
    return np.searchsorted(of_kind, [r for r in rows if kind[r] == which])


def _depth_nodes(mean, sigma, limit):
    """Nodes and weights of the true depth d₀ ~ N(mean, σ²) of each sized contact [m]:
    Gauss-Legendre on [mean − 8σ, min(L, mean + 8σ)] weighted by the normal density, and one
    node at E[d₀ | d₀ ≥ L] carrying P(d₀ ≥ L) (the step at the limit kept out of the
    quadrature). Shapes (contacts, J + 1)."""
    x, h = np.polynomial.legendre.leggauss(_D0_NODES)
    lo = mean - 8 * sigma
    hi = np.maximum(np.minimum(limit, mean + 8 * sigma), lo)
    half = 0.5 * (hi - lo)
    nodes = (0.5 * (hi + lo))[:, None] + half[:, None] * x[None, :]
    w = h[None, :] * half[:, None] * np.exp(-0.5 * ((nodes - mean[:, None]) / sigma) ** 2) \
        / (sigma * math.sqrt(2 * math.pi))
    alpha = (limit - mean) / sigma
    past = _sf(alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        tail_mean = np.where(past > 0, mean + sigma * np.exp(-0.5 * alpha ** 2)
                             / math.sqrt(2 * math.pi) / past, limit)
    nodes = np.concatenate([nodes, np.maximum(tail_mean, limit)[:, None]], axis=1)
    w = np.concatenate([w, past[:, None]], axis=1)
    w = w / np.where(w.sum(axis=1, keepdims=True) > 0, w.sum(axis=1, keepdims=True), 1.0)
    return nodes, w


def _segments(a, b, m_a, m_b, lam, s):
    """∫_a^b φ((u − λ)/s)/s · m(u) du with ln m linear from ln m_a to ln m_b (the miss of a
    logistic POD is nearly exponential piecewise): in closed form, completing the square,
    exp(ln m_a + c(λ − a) + c²s²/2)·[Φ((b − λ')/s) − Φ((a − λ')/s)], λ' = λ + c·s²."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        la, lb = np.log(np.maximum(m_a, 1e-300)), np.log(np.maximum(m_b, 1e-300))
        width = np.where(b > a, b - a, 1.0)
        c = (lb - la) / width
        shifted = lam + c * s * s
        mass = _sf((a - shifted) / s) - _sf((b - shifted) / s)
        scale = np.exp(np.minimum(la + c * (lam - a) + 0.5 * (c * s) ** 2, 700.0))
        return np.where(b > a, scale * np.maximum(mass, 0.0), 0.0)


def _subset_fields(model: GrowthModel, rows) -> dict:
    rows = np.asarray(rows, int)
    sized, ndd = _pick(model.kind, rows, 1), _pick(model.kind, rows, 2)
    return {"nodes": model.nodes, "found": model.found[rows], "tau_limit": model.tau_limit[rows],
            "kind": model.kind[rows], "tau_d0": model.tau_d0[sized], "h_d0": model.h_d0[sized],
            "d0_nodes": model.d0_nodes[sized], "ndd_tail": model.ndd_tail[ndd],
            "u_grid": model.u_grid[ndd], "ndd_miss": model.ndd_miss[ndd],
            "family": None if model.family is None else model.family.subset(rows),
            "group_of": None if model.group_of is None else model.group_of[rows]}


def _step_or_sf(c, lam, s):
    if s > 0:
        return _sf((c - lam) / s)
    return (lam > c).astype(float)


def _weighted_quantiles(values, weights, q) -> np.ndarray:
    order = np.argsort(values)
    v, w = values[order], weights[order]
    cum = np.cumsum(w)
    cum = cum / cum[-1]
    return np.interp(q, cum, v)
