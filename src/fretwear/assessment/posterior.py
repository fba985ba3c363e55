"""The hierarchical posterior of the wear factor: bundle, group and contact levels on a grid.

The log-factor of contact i (a factor on its wear coefficients, times its power's error) is

    λ_i = c_g(i) + η_i,    c_g = μ + γ_g,
    μ ~ N(μ₀, τ₀²)  (the bundle),   γ_g ~ N(0, τ_g²)  (its group),   η_i ~ N(0, s_i²),

s_i² = s_c² + σ_P,i² (the contact scatter and the power's own log-spread). An inspection j of
contact i at time t_j says, given λ_i, through the depth d_ij = d_i(e^{λ_i}, t_j):

* a sized indication m_j: the sizing model's density p(m_j | d_ij);
* no detectable degradation: 1 − POD(d_ij);
* a tube not inspected: nothing (a likelihood of 1).

Given the levels above it the contacts are independent, so on a uniform grid of λ

    M_i(c)  = ∫ L_i(λ) N(λ; c, s_i²) dλ                  (contact i's evidence on its group)
    H_g(μ)  = ∫ N(c; μ, τ_g²) Π_{i∈g} M_i(c) dc          (group g's on the bundle)
    p(μ|D)  ∝ N(μ; μ₀, τ₀²) Π_g H_g(μ)
    p(c|D)  = Π_{i∈g} M_i(c) ∫ N(c; μ, τ_g²) p(μ|D)/H_g(μ) dμ
    p(λ_i|D) = L_i(λ_i) ∫ N(λ_i; c, s_i²) p(c|D)/M_i(c) dc

each a matrix product with a Gaussian kernel (trapezoid weights). Nothing is sampled.

References
----------
.. [1] A. Gelman et al., *Bayesian Data Analysis*, 3rd ed. (2013), §5.3-5.4 (hierarchical
   normal models, the marginal and conditional posteriors computed on a grid).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["GridLevels", "cdf_rows", "kernel", "mass_range", "moments_rows", "ppf_rows",
           "sf_rows", "solve_levels"]

_TINY = 1e-300


def kernel(grid: np.ndarray, sigma: float) -> np.ndarray:
    """K[a, b] ∝ N(grid[b]; grid[a], σ²), each row summing to 1 (σ > 0; the identity at 0)."""
    if sigma <= 0:
        return np.eye(grid.size)
    z = (grid[None, :] - grid[:, None]) / sigma
    k = np.exp(-0.5 * z * z)
    return k / k.sum(axis=1, keepdims=True)


def _normalise(log_p: np.ndarray, h: float) -> np.ndarray:
    """Densities (rows) from log-densities on a grid of spacing h."""
    log_p = np.atleast_2d(log_p)
    top = np.max(np.where(np.isfinite(log_p), log_p, -np.inf), axis=1, keepdims=True)
    p = np.exp(log_p - np.where(np.isfinite(top), top, 0.0))
    p = np.where(np.isfinite(p), p, 0.0)
    area = p.sum(axis=1, keepdims=True) * h
    return p / np.where(area > 0, area, 1.0)


@dataclass(frozen=True, eq=False)
class GridLevels:
    """Posterior densities of the three levels on one grid of λ = ln f [-].

    Attributes
    ----------
    grid : numpy.ndarray
        λ, uniform and increasing, shape (N,).
    bundle : numpy.ndarray
        Density of μ, shape (N,).
    groups : numpy.ndarray
        Density of c_g, shape (G, N).
    contacts : numpy.ndarray or None
        Density of λ_i, shape (n, N) (None: not computed, ``solve_levels(contacts=False)``).
    log_lik : numpy.ndarray
        log L_i(λ) of each contact, shape (n, N).
    log_evidence : numpy.ndarray
        log M_i(c), shape (n, N).
    """

    grid: np.ndarray
    bundle: np.ndarray
    groups: np.ndarray
    contacts: np.ndarray
    log_lik: np.ndarray
    log_evidence: np.ndarray


def _evidence(log_lik: np.ndarray, kernels: list[np.ndarray], which: np.ndarray):
    """log M_i(c) (n, N) from log L_i(λ) (n, N): each row smoothed by its contact's kernel
    (a row of zeros, a contact not inspected, stays 0 without a product)."""
    informative = np.any(log_lik != 0.0, axis=1)
    out = np.zeros_like(log_lik)
    if informative.any():
        out[informative] = _smoothed(log_lik[informative], kernels, which[informative])
    return out


def _smoothed(log_lik, kernels, which):
    top = np.max(log_lik, axis=1, keepdims=True)
    top = np.where(np.isfinite(top), top, 0.0)
    lik = np.exp(log_lik - top)
    out = np.empty_like(log_lik)
    for k, kern in enumerate(kernels):
        rows = which == k
        if rows.any():
            out[rows] = lik[rows] @ kern.T
    with np.errstate(divide="ignore"):
        return np.log(np.maximum(out, 0.0)) + top


def solve_levels(grid: np.ndarray, log_lik: np.ndarray, group_of: np.ndarray, n_groups: int,
                 scatter: np.ndarray, mu0: float, tau0: float, tau_group: float,
                 *, contacts: bool = True) -> GridLevels:
    """The posterior of every level (module docstring) on ``grid``.

    Parameters
    ----------
    grid : numpy.ndarray
        Uniform grid of λ [-], shape (N,).
    log_lik : numpy.ndarray
        log L_i(λ) of each contact on the grid, shape (n, N) (0 for a contact not inspected).
    group_of : numpy.ndarray
        Group index of each contact in [0, n_groups), shape (n,).
    n_groups : int
        G.
    scatter : numpy.ndarray
        s_i [-] of each contact, ≥ 0, shape (n,).
    mu0, tau0 : float
        Prior of μ: mean and standard deviation of ln f [-] (τ₀ > 0).
    tau_group : float
        τ_g [-], ≥ 0 (0: every group's factor is the bundle's).
    contacts : bool
        False: the bundle and group levels only (``GridLevels.contacts`` None), all the
        operational assessment reads.
    """
    h = float(grid[1] - grid[0])
    values, which = np.unique(np.round(scatter, 12), return_inverse=True)
    kernels = [kernel(grid, float(s)) for s in values]
    log_m = _evidence(log_lik, kernels, which)                       # log M_i(c)
    log_group = np.zeros((n_groups, grid.size))
    np.add.at(log_group, group_of, log_m)                             # log Π_{i∈g} M_i(c)
    k_group = kernel(grid, tau_group)
    log_h = _evidence(log_group, [k_group], np.zeros(n_groups, int))  # log H_g(μ)
    log_mu = -0.5 * ((grid - mu0) / tau0) ** 2 + log_h.sum(axis=0)
    bundle = _normalise(log_mu, h)[0]
    # p(c|D) = Π M_i(c) · Σ_μ K(μ, c) p(μ)/H_g(μ)
    with np.errstate(over="ignore", invalid="ignore"):
        top = np.max(np.where(np.isfinite(log_h), log_h, -np.inf), axis=1, keepdims=True)
        ratio = bundle[None, :] * np.exp(-(log_h - top))
        ratio = np.where(np.isfinite(ratio), ratio, 0.0)
    with np.errstate(divide="ignore"):
        log_c = log_group + np.log(np.maximum(ratio @ k_group, _TINY))
    groups = _normalise(log_c, h)
    if not contacts:
        return GridLevels(grid=grid, bundle=bundle, groups=groups, contacts=None,
                          log_lik=log_lik, log_evidence=log_m)
    # p(λ_i|D) = L_i(λ) · Σ_c K_i(c, λ) p(c)/M_i(c)
    with np.errstate(over="ignore", invalid="ignore"):
        top = np.max(np.where(np.isfinite(log_m), log_m, -np.inf), axis=1, keepdims=True)
        weight = groups[group_of] * np.exp(-(log_m - top))
        weight = np.where(np.isfinite(weight), weight, 0.0)
    # rows of contacts not inspected repeat per (group, scatter): one product each
    informative = np.any(log_lik != 0.0, axis=1)
    key = np.where(informative, -1, group_of * len(kernels) + which)
    spread = np.empty_like(weight)
    for k, kern in enumerate(kernels):
        rows = np.flatnonzero((which == k) & informative)
        if rows.size:
            spread[rows] = weight[rows] @ kern
        for g in np.unique(group_of[(which == k) & ~informative]):
            rows = np.flatnonzero(key == g * len(kernels) + k)
            spread[rows] = weight[rows[0]] @ kern
    with np.errstate(divide="ignore"):
        contacts = _normalise(log_lik + np.log(np.maximum(spread, _TINY)), h)
    return GridLevels(grid=grid, bundle=bundle, groups=groups, contacts=contacts,
                      log_lik=log_lik, log_evidence=log_m)


# ---------------------------------------------------------------------- grid statistics
def cdf_rows(grid: np.ndarray, density: np.ndarray) -> np.ndarray:
    """Cumulative distribution of each row (trapezoid), 0 at grid[0], 1 at grid[-1]."""
    d = np.atleast_2d(density)
    seg = 0.5 * (d[:, 1:] + d[:, :-1]) * np.diff(grid)
    cdf = np.concatenate([np.zeros((d.shape[0], 1)), np.cumsum(seg, axis=1)], axis=1)
    return cdf / np.where(cdf[:, -1:] > 0, cdf[:, -1:], 1.0)


def sf_rows(grid: np.ndarray, density: np.ndarray, x: np.ndarray) -> np.ndarray:
    """P(λ_i > x_i) of each row, summed from the upper end (small tails keep their digits)."""
    d = np.atleast_2d(density)
    seg = 0.5 * (d[:, 1:] + d[:, :-1]) * np.diff(grid)
    tail = np.concatenate([np.cumsum(seg[:, ::-1], axis=1)[:, ::-1],
                           np.zeros((d.shape[0], 1))], axis=1)
    tail = tail / np.where(tail[:, :1] > 0, tail[:, :1], 1.0)
    h = grid[1] - grid[0]
    pos = np.clip((np.asarray(x, float) - grid[0]) / h, 0.0, grid.size - 1.0)
    pos = np.where(np.isnan(pos), 0.0, pos)
    lo = np.minimum(np.floor(pos).astype(int), grid.size - 2)
    w = pos - lo
    rows = np.arange(d.shape[0])
    out = (1 - w) * tail[rows, lo] + w * tail[rows, lo + 1]
    out = np.where(np.asarray(x) <= grid[0], 1.0, out)
    return np.where(np.asarray(x) >= grid[-1], 0.0, out)


def ppf_rows(grid: np.ndarray, density: np.ndarray, q) -> np.ndarray:
    """Quantiles (n, len(q)) of each row's λ."""
    cdf = cdf_rows(grid, density)
    q = np.atleast_1d(np.asarray(q, float))
    out = np.empty((cdf.shape[0], q.size))
    for i, row in enumerate(cdf):
        keep = np.concatenate([[True], np.diff(row) > 0])
        out[i] = np.interp(q, row[keep], grid[keep])
    return out


def moments_rows(grid: np.ndarray, density: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(mean, standard deviation) of each row's λ (trapezoid)."""
    d = np.atleast_2d(density)
    mean = np.trapezoid(d * grid, grid, axis=1)
    var = np.trapezoid(d * (grid[None, :] - mean[:, None]) ** 2, grid, axis=1)
    return mean, np.sqrt(np.maximum(var, 0.0))


def mass_range(grid: np.ndarray, density: np.ndarray, drop: float = 35.0
               ) -> tuple[float, float]:
    """The λ range where any row's density is above its maximum × e^-drop."""
    d = np.atleast_2d(density)
    with np.errstate(divide="ignore"):
        keep = np.log(np.maximum(d, 0.0)) >= np.log(d.max(axis=1, keepdims=True)) - drop
    idx = np.flatnonzero(keep.any(axis=0))
    if idx.size == 0:
        return float(grid[0]), float(grid[-1])
    return float(grid[max(idx[0] - 1, 0)]), float(grid[min(idx[-1] + 1, grid.size - 1)])


def normal_log_pdf(x, mean: float, sigma: float):
    """ln N(x; mean, σ²)."""
    z = (np.asarray(x, float) - mean) / sigma
    return -0.5 * z * z - math.log(sigma * math.sqrt(2 * math.pi))
