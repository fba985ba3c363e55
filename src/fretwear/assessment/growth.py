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

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import special

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
        λ_k = ln f at the nodes [-].
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
        if lam.shape != w.shape or not np.isfinite(lam).all() or (w < 0).any() or w.sum() <= 0:
            raise InputError("FactorNodes: one finite log-factor and one weight >= 0 per node")
        for name in ("contact_sigma", "power_sigma"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InputError(f"{name} must be a standard deviation of ln >= 0, got {v!r}")
        object.__setattr__(self, "log_factor", lam)
        object.__setattr__(self, "weights", w / w.sum())

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

    def quantiles(self, q) -> np.ndarray:
        """Quantiles of ln g, the mixture Σ w_k N(λ_k, s²) [-]."""
        from scipy.optimize import brentq

        s, lam, w = self.sigma, self.log_factor, self.weights
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
class Family:
    """The contacts grouped by what makes their nominal models one up to the rate: the same
    law, geometry, coefficients, limit, time scale and origin, unworn at the origin (no
    restart, no replacement, one term). Contact i's state after t at the factor g is its
    group's representative's after g·t·r_i/r_rep (the volumes linear in time and in the rate
    r, :attr:`DepthModel.rates`), so one :meth:`DepthModel.time_to` and one
    :meth:`DepthModel.depth` call serve a whole group (10⁵ contacts in a few calls).
    """

    reps: list            # representative DepthModel of each group
    group: np.ndarray     # group of each contact
    ratio: np.ndarray     # r_i / r_rep [-]
    origin: np.ndarray    # each contact's origin [time unit]

    @classmethod
    def of(cls, models) -> Family:
        keys: dict = {}
        members: list[list[int]] = []
        group = np.zeros(len(models), int)
        for i, m in enumerate(models):
            alike = (len(m.powers) == 1 and m.sector_arc is None and m.rows is None
                     and m.replacement is None and m.initial_mobile == 0
                     and m.initial_obstacle == 0 and m.law.linear_in_time)
            key = (id(m.law), id(m.geometry), _items(m.coefficients_mobile[0]),
                   _items(m.coefficients_obstacle[0]), m.limit_depth, m.time_scale,
                   m.origin) if alike else ("own", i)
            if key not in keys:
                keys[key] = len(members)
                members.append([])
            group[i] = keys[key]
            members[group[i]].append(i)
        reps, ratio = [], np.ones(len(models))
        for idx in members:  # one law call per group: the rates of its members
            first = models[idx[0]]
            power = np.array([models[i].powers[0] for i in idx], float)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                c = first.coefficients_mobile[0]
                rate = (np.zeros(len(idx)) if c is None else np.broadcast_to(np.asarray(
                    first.law.volume(power, 1.0, **c), float), (len(idx),)))
            best = int(np.argmax(rate))
            reps.append(models[idx[best]])
            ratio[idx] = rate / rate[best] if rate[best] > 0 else 1.0
        return cls(reps, group, ratio, np.array([m.origin for m in models], float))

    def subset(self, rows) -> Family:
        rows = np.asarray(rows, int)
        return Family(self.reps, self.group[rows], self.ratio[rows], self.origin[rows])

    def nominal_time(self, depth, rows) -> np.ndarray:
        """τ: the contacts' (``rows``) nominal times to ``depth`` [m] (rows x k) after their
        origins [time unit]; 0 where depth <= 0, inf where never reached."""
        depth = np.asarray(depth, float)
        rows = np.asarray(rows, int)
        out = np.zeros(depth.shape)
        for g in np.unique(self.group[rows]):
            mine = self.group[rows] == g
            d = depth[mine]
            worn = d > 0
            if worn.any():
                rep = self.reps[g]
                t = np.zeros(d.shape)
                t[worn] = np.asarray(rep.time_to(d[worn])) - rep.origin
                with np.errstate(divide="ignore", invalid="ignore"):
                    out[mine] = np.where(t > 0, t / self.ratio[rows[mine]][:, None], t)
        return out

    def depth(self, tau, rows) -> np.ndarray:
        """The contacts' (``rows``) depths [m] at the nominal times ``tau`` (rows x k) after
        their origins [time unit] (NaN beyond the geometry's range)."""
        tau = np.asarray(tau, float)
        rows = np.asarray(rows, int)
        out = np.full(tau.shape, np.nan)
        for g in np.unique(self.group[rows]):
            mine = self.group[rows] == g
            rep = self.reps[g]
            t = np.minimum(tau[mine] * self.ratio[rows[mine]][:, None], 1e300)
            with np.errstate(invalid="ignore", over="ignore"):
                out[mine] = rep.depth(t * rep.time_scale, warn=False)
        return out


def _items(coefficients):
    return None if coefficients is None else tuple(sorted(coefficients.items()))


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

    @classmethod
    def build(cls, models, found, kind, measured, nodes: FactorNodes, *, sizing, pod
              ) -> GrowthModel:
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
        """
        kind = np.asarray(kind, int)
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
        s, lam = nodes.sigma, nodes.log_factor
        tails = np.zeros((ndd.size, lam.size, _U_POINTS))
        grids = np.zeros((ndd.size, _U_POINTS))
        misses = np.zeros((ndd.size, _U_POINTS))
        if s > 0 and ndd.size:
            u = np.linspace(lam.min() - _U_HALF * s, lam.max() + _U_HALF * s, _U_POINTS)
            depth = family.depth(a[ndd, None] * np.exp(u)[None, :], ndd)
            misses = pod.miss(np.where(np.isnan(depth), np.inf, depth))
            grids = np.broadcast_to(u, misses.shape).copy()
            seg = _segments(grids[:, None, :-1], grids[:, None, 1:], misses[:, None, :-1],
                            misses[:, None, 1:], lam[None, :, None], s)
            tails[:, :, :-1] = np.cumsum(seg[:, :, ::-1], axis=2)[:, :, ::-1]
        return cls(nodes=nodes, found=a, tau_limit=tau_l, kind=kind, tau_d0=tau_d0,
                   h_d0=h, d0_nodes=d0, ndd_tail=tails, u_grid=grids, ndd_miss=misses,
                   family=family)

    def probabilities(self, interval: float) -> np.ndarray:
        """p_ik, the probability that contact i exceeds its limit by the end of ``interval``
        [time unit] after its inspection, given the factor's node k; shape (contacts, nodes)."""
        T = float(interval)
        if not (math.isfinite(T) and T >= 0):
            raise InputError(f"the interval must be a time >= 0, got {interval!r}")
        lam, s = self.nodes.log_factor, self.nodes.sigma
        with np.errstate(divide="ignore", invalid="ignore"):
            c = np.log(self.tau_limit / (self.found + T))  # ln of the g that reaches L
        p = _step_or_sf(c[:, None], lam[None, :], s)
        sized = np.flatnonzero(self.kind == 1)
        if sized.size:
            with np.errstate(divide="ignore", invalid="ignore"):
                gap = (self.tau_limit[sized, None] - self.tau_d0) / T if T > 0 else \
                    np.where(self.tau_limit[sized, None] > self.tau_d0, np.inf, -np.inf)
                cj = np.where(gap > 0, np.log(gap), -np.inf)
            pj = _step_or_sf(cj[:, :, None], lam[None, None, :], s)
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
                             lam[None, :], s)
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
        lam, s, w = self.nodes.log_factor, self.nodes.sigma, self.nodes.weights
        g = np.exp(self.nodes.quantiles(q))
        out = (self.found + interval)[:, None] * g[None, :]
        z, hz = np.polynomial.hermite_e.hermegauss(16)
        hz = hz / hz.sum()
        growth = np.exp(lam[:, None] + s * z[None, :]).ravel()       # (K·Z,)
        wg = (w[:, None] * hz[None, :]).ravel()
        for row, i in enumerate(np.flatnonzero(self.kind == 1)):
            tau = self.tau_d0[row][:, None] + interval * growth[None, :]
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
            "family": None if model.family is None else model.family.subset(rows)}


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
