"""Sampling designs and variance-based (Sobol') sensitivity indices.

:func:`uniform_points` draws the uniform points of a Monte Carlo design, pseudo-random or
scrambled Sobol' (quasi-Monte Carlo, ``scipy.stats.qmc``). :func:`sobol_indices` estimates the
first-order and total Sobol' indices of a model output from the Saltelli design: two
independent matrices A and B of inputs and, for each input i, the matrix A_B^(i) equal to A
with its column i taken from B.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats
from scipy.stats import norm, qmc

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.keys import check_level

__all__ = ["METHODS", "index_intervals", "sobol_indices", "uniform_points"]

#: Sampling methods of :func:`uniform_points`.
METHODS = ("sobol", "random")

# uniform points are kept this far from 0 and 1 so that unbounded quantile functions stay finite
_EDGE = 1e-12


def uniform_points(samples: int, dimension: int, *, method: str = "sobol",
                   seed: int | None = 0) -> np.ndarray:
    """``samples`` points of the unit cube (0, 1)^dimension.

    Parameters
    ----------
    samples : int
        Number of points N ≥ 2. For ``"sobol"`` it is rounded up to a power of two (Sobol'
        points keep their balance only in blocks of 2^m).
    dimension : int
        Dimension d ≥ 1.
    method : str
        ``"sobol"`` (scrambled Sobol' sequence, Owen scrambling) or ``"random"`` (independent
        uniform draws).
    seed : int, optional
        Seed of the generator (the scrambling for ``"sobol"``).

    Returns
    -------
    numpy.ndarray
        Shape (N, d), in (0, 1).

    Examples
    --------
    >>> uniform_points(1000, 2).shape  # 1000 -> 1024 Sobol' points
    (1024, 2)
    >>> uniform_points(10, 3, method="random").shape
    (10, 3)
    """
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 2:
        raise InputError(f"samples must be an integer >= 2, got {samples!r}")
    if method not in METHODS:
        raise InputError(f"method must be one of {METHODS}, got {method!r}")
    if dimension < 1:
        raise InputError("there is no uncertain input to sample: give at least one "
                         "distribution (coefficients, power_scatter or dimensions)")
    if method == "sobol":
        m = max(1, math.ceil(math.log2(int(samples))))
        points = qmc.Sobol(d=int(dimension), scramble=True, seed=seed).random_base2(m)
    else:
        points = np.random.default_rng(seed).random((int(samples), int(dimension)))
    return np.clip(points, _EDGE, 1.0 - _EDGE)


def sobol_indices(f_a, f_b, f_ab, *, resamples: int = 200, level: float = 0.95,
                  seed: int | None = 0) -> dict[str, np.ndarray]:
    """First-order and total Sobol' indices from the outputs of a Saltelli design.

    Parameters
    ----------
    f_a, f_b : array_like
        Model outputs on the matrices A and B, shape (N,).
    f_ab : array_like
        Outputs on A_B^(i) (A with column i from B), shape (d, N).
    resamples : int
        Bootstrap resamples for the confidence half-widths (0: none).
    level : float
        Confidence level of the half-widths [-].
    seed : int, optional
        Seed of the bootstrap.

    Returns
    -------
    dict
        ``first``, ``total`` (shape (d,)) and ``first_conf``, ``total_conf`` (bootstrap
        half-widths at ``level``, NaN without resamples).

    Notes
    -----
    Computed by :func:`scipy.stats.sobol_indices` (its ``saltelli_2010`` method, the outputs
    given as ``f_A``, ``f_B``, ``f_AB``), which needs N = 2^m (the balance of Sobol' points).
    With V the variance of the output over A and B together and f centred on the mean of the
    outputs of A and B [1]_ [2]_ [3]_:

    .. math:: S_i = \\frac{\\overline{f(B)\\,(f(A_B^{(i)}) - f(A))}}{V}, \\qquad
              S_{T,i} = \\frac{\\overline{(f(A) - f(A_B^{(i)}))^2}}{2V}

    (Saltelli 2010's first-order estimator, Jansen's total-effect estimator). For an additive
    function S_i = S_T,i. The half-widths: ``z·σ`` of the indices over ``resamples``
    bootstrap resamples of the N rows (the normal interval SALib gives).

    References
    ----------
    .. [1] A. Saltelli, P. Annoni, I. Azzini, F. Campolongo, M. Ratto, S. Tarantola,
       "Variance based sensitivity analysis of model output. Design and estimator for the total
       sensitivity index", Computer Physics Communications 181 (2010) 259-270.
    .. [2] M. J. W. Jansen, "Analysis of variance designs for model output", Computer Physics
       Communications 117 (1999) 35-43.
    .. [3] J. Herman, W. Usher, "SALib: An open-source Python library for Sensitivity
       Analysis", Journal of Open Source Software 2(9) (2017) 97.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> a, b = rng.random((4096, 2)), rng.random((4096, 2))
    >>> f = lambda x: x[:, 0] + 2 * x[:, 1]          # S = (1/5, 4/5)
    >>> ab = np.stack([np.where(np.arange(2) == i, b, a) for i in range(2)])
    >>> s = sobol_indices(f(a), f(b), np.stack([f(x) for x in ab]), resamples=0)
    >>> np.round(s["total"], 1).tolist()
    [0.2, 0.8]
    """
    level = check_level(level)
    fa = np.asarray(f_a, dtype=float)
    fb = np.asarray(f_b, dtype=float)
    fab = np.atleast_2d(np.asarray(f_ab, dtype=float))
    if fa.shape != fb.shape or fab.shape[1:] != fa.shape or fa.ndim != 1:
        raise InputError("sobol_indices: f_a and f_b must have shape (N,) and f_ab (d, N)")
    if not (np.isfinite(fa).all() and np.isfinite(fb).all() and np.isfinite(fab).all()):
        raise InputError("sobol_indices: the model outputs must be finite")

    n = fa.size
    if n & (n - 1):
        raise InputError(f"Sobol' indices need a Saltelli design of 2^m samples (the balance "
                         f"of Sobol' points, scipy.stats.sobol_indices), got {n}: use "
                         "method='sobol', or a power of two for samples")

    def estimate(idx):
        a, b, ab = fa[idx], fb[idx], fab[:, idx]
        if np.var(np.concatenate([a, b])) <= 0:
            return np.zeros(len(fab)), np.zeros(len(fab))
        d = len(ab)
        # one input given twice: scipy 1.17 squeezes one input's indices to a scalar and then
        # fails on it (each input's indices are computed alone, so the copy changes nothing)
        pages = np.concatenate([ab, ab]) if d == 1 else ab
        found = stats.sobol_indices(func={"f_A": a[None, :], "f_B": b[None, :],
                                          "f_AB": pages[:, None, :]}, n=a.size)
        return (np.asarray(found.first_order, dtype=float).reshape(-1)[:d],
                np.asarray(found.total_order, dtype=float).reshape(-1)[:d])

    first, total = estimate(np.arange(n))
    first_conf = np.full(first.shape, np.nan)
    total_conf = np.full(total.shape, np.nan)
    if resamples:
        rng = np.random.default_rng(seed)
        boot = [estimate(rng.integers(0, n, n)) for _ in range(int(resamples))]
        z = float(norm.ppf(0.5 * (1.0 + level)))
        first_conf = z * np.std([b[0] for b in boot], axis=0, ddof=1)
        total_conf = z * np.std([b[1] for b in boot], axis=0, ddof=1)
    return {"first": first, "total": total, "first_conf": first_conf, "total_conf": total_conf}


def index_intervals(table: pd.DataFrame) -> pd.DataFrame:
    """The confidence intervals of Sobol' indices, clipped to [0, 1], the range of an index.

    Parameters
    ----------
    table : DataFrame
        ``first``, ``total`` [-] and their half-widths ``first_conf``, ``total_conf`` [-] (the
        table of :meth:`fretwear.uncertainty.UncertaintyResult.sensitivity`); a missing
        half-width column counts as NaN.

    Returns
    -------
    DataFrame
        Same index: ``first_low``, ``first_high``, ``total_low``, ``total_high`` [-], the
        interval S ± h cut to [0, 1] (NaN without a half-width), and ``clipped`` (a bound of
        the row was cut).

    Notes
    -----
    An index is a fraction of the output's variance, 0 <= S_i <= S_T,i <= 1, but its
    estimators are ratios of sample moments (:func:`sobol_indices`) and the bootstrap
    interval S ± z·σ is symmetric: both can leave [0, 1] by their sampling error (a lone
    input, whose indices are exactly 1, gets 0.99 ± 0.20 with N = 256). The values outside
    [0, 1] are impossible, so the interval is shown cut to [max(0, S − h), min(1, S + h)];
    the estimates and half-widths themselves are left as computed (docs/uncertainty.md §3).

    Examples
    --------
    >>> t = pd.DataFrame({"first": [0.99, 0.01], "first_conf": [0.2, 0.02],
    ...                   "total": [1.0, 0.02], "total_conf": [0.13, 0.01]}, index=["f", "p"])
    >>> index_intervals(t).round(2).to_dict("list")  # doctest: +NORMALIZE_WHITESPACE
    {'first_low': [0.79, 0.0], 'first_high': [1.0, 0.03], 'total_low': [0.87, 0.01],
     'total_high': [1.0, 0.03], 'clipped': [True, True]}
    """
    out = pd.DataFrame(index=table.index)
    clipped = np.zeros(len(table), dtype=bool)
    for col in ("first", "total"):
        if col not in table.columns:
            raise InputError(f"index_intervals needs the column {col!r} (Sobol' indices)")
        value = table[col].to_numpy(dtype=float)
        half = (table[f"{col}_conf"].to_numpy(dtype=float) if f"{col}_conf" in table.columns
                else np.full(value.shape, np.nan))
        low, high = value - half, value + half
        clipped |= (low < 0) | (high > 1)
        out[f"{col}_low"] = np.clip(low, 0.0, 1.0)
        out[f"{col}_high"] = np.clip(high, 0.0, 1.0)
    out["clipped"] = clipped
    return out
