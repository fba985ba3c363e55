"""The vectorised bracketed solver of the geometry relations: :func:`solve_monotone`.

Chandrupatla's method on every element at once (theory §6: the depths of the relations without
a closed form). Each step's arithmetic is element-wise: with numba (the ``fast`` extra) one
compiled kernel makes the step of every element (:func:`_chandrupatla_advance`), otherwise numpy
array operations do (:func:`_numpy_steps`); the two make the same operations in the same order,
so the roots are the same to the bit. SI units are the caller's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from fretwear._lazy import compiled_when_used

__all__ = ["MonotoneGrid", "monotone_grid", "solve_monotone", "solve_on_grid"]


def _out(array):
    """A float array, or a float scalar for a 0-d result (scalars in, scalar out)."""
    array = np.asarray(array, dtype=float)
    return array[()] if array.ndim == 0 else array


_FOUR_TINY = 4.0 * np.finfo(float).tiny  # the solver's tolerance floor


def solve_monotone(func: Callable, target, lower, upper, rtol: float = 1e-12,
                   atol: float = 0.0, max_iter: int = 400, *, bound_values=None,
                   compiled: bool = True):
    """Solve func(x) = target for x in [lower, upper], func increasing; vectorised.

    Chandrupatla's method (inverse quadratic interpolation safeguarded by bisection), run on
    every element at once: ``func`` is called with an array of the broadcast shape of
    ``target``, ``lower`` and ``upper`` (converged elements keep their value), so it may use
    element-wise parameters of that same shape.

    Parameters
    ----------
    func : callable
        Vectorised, non-decreasing function of x.
    target : float or array_like
        Values to reach.
    lower, upper : float or array_like
        Bracket ends (broadcastable to ``target``), lower ≤ upper.
    rtol : float
        Relative tolerance on x (default 1e-12).
    atol : float
        Absolute tolerance on x (default 0).
    max_iter : int
        Iteration cap (the bracket then still holds the root; its best end is returned).
    bound_values : (array_like, array_like), optional
        ``(func(lower), func(upper))`` when known (e.g. kept for a geometry's dimensions): the
        solver then does not evaluate them.
    compiled : bool
        Make each step with the compiled kernel when numba is installed (default); False: with
        numpy array operations. The roots are the same to the bit.

    Returns
    -------
    numpy.ndarray or float
        The root x; NaN where ``target`` is NaN or lies outside [func(lower), func(upper)].

    Notes
    -----
    Each step keeps a bracket [x1, x2] with a sign change of f = func − target; the trial point
    is x1 + t·(x2 − x1), t from inverse quadratic interpolation when the three last points allow
    it, else t = 1/2; t is clipped so that each step shrinks the bracket by at least the
    tolerance. Stops when the bracket is shorter than 2·(rtol·|x| + atol) or f = 0.

    References
    ----------
    .. [1] Chandrupatla, T. R. (1997). A new hybrid quadratic/bisection algorithm for finding the
           zero of a nonlinear function without using derivatives. *Advances in Engineering
           Software* 28(3), 145-149.

    Examples
    --------
    >>> import numpy as np
    >>> x = solve_monotone(lambda x: x**3, np.array([8.0, 27.0, 100.0]), 0.0, 4.0)
    >>> np.round(x, 12).tolist()
    [2.0, 3.0, nan]
    """
    target = np.asarray(target, dtype=float)
    lo = np.asarray(lower, dtype=float)
    hi = np.asarray(upper, dtype=float)
    shape = target.shape
    if lo.shape != shape or hi.shape != shape:
        shape = np.broadcast_shapes(shape, lo.shape, hi.shape)
    # flat, of the full shape (broadcast only when needed: it costs more than a small call);
    # the solver never writes into them, so a view of the caller's array is enough
    target, lo, hi = (a.ravel() if a.shape == shape else np.broadcast_to(a, shape).ravel()
                      for a in (target, lo, hi))

    def evaluate(x_full: np.ndarray) -> np.ndarray:
        values = np.asarray(func(x_full.reshape(shape)), dtype=float)
        if values.shape != shape:
            values = np.broadcast_to(values, shape)
        return values.ravel()

    with np.errstate(all="ignore"):
        if bound_values is None:
            f_lo = evaluate(lo) - target
            f_hi = evaluate(hi) - target
        else:
            f_lo, f_hi = (_flat(v, shape) - target for v in bound_values)
        root = np.full(target.size, np.nan)
        root = np.where(f_lo == 0.0, lo, root)
        root = np.where((f_hi == 0.0) & np.isnan(root), hi, root)
        index = np.flatnonzero((f_lo < 0.0) & (f_hi > 0.0))
        # The state is kept for the unconverged elements only; ``func`` is always called on a
        # full-shape array (converged elements hold their root, or the lower bound).
        x_eval = np.where(np.isnan(root), lo, root)
        kernel = _step_kernel() if compiled else None
        step = None if kernel is None else kernel[0]
        if step is None:
            _numpy_steps(evaluate, x_eval, root, index, lo, hi, f_lo, f_hi, target[index], rtol,
                         atol, max_iter)
        else:
            _compiled_steps(step, evaluate, x_eval, root, index, lo, hi, f_lo, f_hi,
                            target[index], rtol, atol, max_iter)
    root = root.reshape(shape)
    return _out(root)


def _flat(value, shape) -> np.ndarray:
    """``value`` as a float array of ``shape``, flat (a scalar stays 0-d; broadcast only where
    its shape differs: broadcast_to costs more than the rest of a small solve's step)."""
    value = np.asarray(value, dtype=float)
    if value.ndim == 0:
        return value
    return value.ravel() if value.shape == shape else np.broadcast_to(value, shape).ravel()


def _numpy_steps(evaluate, x_eval, root, index, lo, hi, f_lo, f_hi, goal, rtol, atol,
                 max_iter):
    """Chandrupatla's steps with numpy array operations: ``root`` and ``x_eval`` filled in
    place (the elements of ``index`` are bracketed: f_lo < 0 < f_hi)."""
    # Chandrupatla's state: x1 (newest), x2 (other end of the bracket), x3 (dropped point).
    x1, f1 = hi[index], f_hi[index]
    x2, f2 = lo[index], f_lo[index]
    x3, f3 = x2.copy(), f2.copy()
    t = np.full(index.size, 0.5)
    for _ in range(max_iter):
        if index.size == 0:
            break
        xt = x1 + t * (x2 - x1)
        x_eval[index] = xt
        ft = evaluate(x_eval)[index] - goal
        same = np.sign(ft) == np.sign(f1)
        x3 = np.where(same, x1, x2)
        f3 = np.where(same, f1, f2)
        x2 = np.where(same, x2, x1)
        f2 = np.where(same, f2, f1)
        x1, f1 = xt, ft
        best_is_1 = np.abs(f1) < np.abs(f2)
        xm = np.where(best_is_1, x1, x2)
        fm = np.where(best_is_1, f1, f2)
        tol = 2.0 * (rtol * np.abs(xm) + atol) + _FOUR_TINY
        span = np.abs(x2 - x1)
        tl = tol / np.where(span > 0.0, span, 1.0)
        done = (tl > 0.5) | (fm == 0.0) | (span == 0.0) | ~np.isfinite(ft)
        if done.any():
            root[index[done]] = xm[done]
            x_eval[index[done]] = xm[done]
            keep = ~done
            index, goal = index[keep], goal[keep]
            x1, f1, x2, f2, x3, f3 = (a[keep] for a in (x1, f1, x2, f2, x3, f3))
            tl = tl[keep]
        xi = (x1 - x2) / (x3 - x2)
        phi = (f1 - f2) / (f3 - f2)
        iqi = (phi * phi < xi) & ((1.0 - phi) ** 2 < 1.0 - xi)
        t_iqi = (f1 / (f2 - f1) * f3 / (f2 - f3)
                 + (x3 - x1) / (x2 - x1) * f1 / (f3 - f1) * f2 / (f3 - f2))
        t = np.where(iqi & np.isfinite(t_iqi), t_iqi, 0.5)
        t = np.clip(t, np.minimum(tl, 0.5), np.maximum(1.0 - tl, 0.5))
    if index.size:
        root[index] = np.where(np.abs(f1) < np.abs(f2), x1, x2)


def _compiled_steps(step, evaluate, x_eval, root, index, lo, hi, f_lo, f_hi, goal, rtol, atol,
                    max_iter):
    """:func:`_numpy_steps` with each step made by :func:`_chandrupatla_advance` (compiled):
    the same operations element by element, without numpy's per-call cost on small arrays.
    The bracketed elements keep their place in the state arrays (``active`` marks those not
    converged), so a step costs one compiled call and the evaluation."""
    x1, f1 = hi[index], f_hi[index]
    x2, f2 = lo[index], f_lo[index]
    x3, f3 = x2.copy(), f2.copy()
    t = np.full(index.size, 0.5)
    xt = x1 + t * (x2 - x1)
    active = np.ones(index.size, dtype=np.bool_)
    x_eval[index] = xt
    remaining = index.size
    for _ in range(max_iter):
        if remaining == 0:
            break
        remaining = step(index, active, x1, f1, x2, f2, x3, f3, t, xt, evaluate(x_eval), goal,
                         float(rtol), float(atol), root, x_eval)
    if remaining:
        rest = index[active]
        root[rest] = np.where(np.abs(f1) < np.abs(f2), x1, x2)[active]


def _chandrupatla_advance(index, active, x1, f1, x2, f2, x3, f3, t, xt, values, goal, rtol,
                          atol, root, x_eval):
    """One step of every active element k (element ``index[k]`` of the full arrays), in place:
    the state (x1, f1, x2, f2, x3, f3) takes the trial point (xt, ft = values − goal); a
    converged element gets its best point in ``root`` and ``x_eval`` and leaves ``active``; the
    others get their next ``t`` and trial point ``xt`` (also put in ``x_eval``). Returns the
    count still active.

    The operations and their order are those of :func:`_numpy_steps` (np.clip, np.minimum,
    np.maximum as NumPy makes them, NaN included), element by element."""
    remaining = 0
    for k in range(index.size):
        if not active[k]:
            continue
        i = index[k]
        a = values[i] - goal[k]
        b = f1[k]  # np.sign(a) == np.sign(b) (a NaN equals nothing)
        if (a > 0.0 and b > 0.0) or (a < 0.0 and b < 0.0) or (a == 0.0 and b == 0.0):
            x3[k], f3[k] = x1[k], f1[k]
        else:
            x3[k], f3[k] = x2[k], f2[k]
            x2[k], f2[k] = x1[k], f1[k]
        x1[k], f1[k] = xt[k], a
        if abs(f1[k]) < abs(f2[k]):
            m, fm = x1[k], f1[k]
        else:
            m, fm = x2[k], f2[k]
        tol = 2.0 * (rtol * abs(m) + atol) + _FOUR_TINY
        span = abs(x2[k] - x1[k])
        tl = tol / (span if span > 0.0 else 1.0)
        if (tl > 0.5) or (fm == 0.0) or (span == 0.0) or not math.isfinite(a):
            active[k] = False
            root[i] = m
            x_eval[i] = m
            continue
        remaining += 1
        a1, b1, a2, b2, a3, b3 = x1[k], f1[k], x2[k], f2[k], x3[k], f3[k]
        xi = (a1 - a2) / (a3 - a2)
        phi = (b1 - b2) / (b3 - b2)
        rest = 1.0 - phi
        iqi = (phi * phi < xi) and (rest * rest < 1.0 - xi)
        t_iqi = (b1 / (b2 - b1) * b3 / (b2 - b3)
                 + (a3 - a1) / (a2 - a1) * b1 / (b3 - b1) * b2 / (b3 - b2))
        step = t_iqi if (iqi and math.isfinite(t_iqi)) else 0.5
        low = tl if (tl != tl or tl < 0.5) else 0.5  # np.minimum(tl, 0.5)
        high = 1.0 - tl
        high = high if (high != high or high > 0.5) else 0.5  # np.maximum(1 - tl, 0.5)
        # np.clip(step, low, high) = MIN(MAX(step, low), high), MAX(a, b) = a if a is NaN or
        # a > b else b (a NaN bound gives NaN, as in NumPy)
        step = step if (step != step or step > low) else low
        step = step if (step != step or step < high) else high
        t[k] = step
        xt[k] = a1 + step * (a2 - a1)
        x_eval[i] = xt[k]
    return remaining


#: (:func:`_chandrupatla_advance`,) compiled when a solve first asks, None without numba.
_step_kernel = compiled_when_used(_chandrupatla_advance)


class MonotoneGrid(NamedTuple):
    """Points of a non-decreasing function on its whole bracket, for :func:`solve_on_grid`:
    ``x`` from the lower to the upper end, ``f`` = func(x) strictly increasing (points where the
    function's rounding does not increase are left out). Units those of the function."""

    x: np.ndarray
    f: np.ndarray


def monotone_grid(func: Callable, upper: float, bound_values: tuple[float, float],
                  points: int = 128, smallest: float = 1e-10) -> MonotoneGrid:
    """The grid of a non-decreasing ``func`` on [0, ``upper``] for :func:`solve_on_grid`:
    0, then ``points`` depths log-spaced from ``smallest``·upper to ``upper`` (a ratio of
    about 1.2 between neighbours), ``func`` evaluated once on all of them; ``bound_values``
    (func(0), func(upper)) as the solver on [0, upper] would take them. Made once per set of
    dimensions (kept by the geometry's cache), it costs one call of ``func`` on its points:
    for the lens, about 0.04 ms, what one table's solve saves (5 evaluations from the grid
    against 13 to 37 on [0, D_max]), so that contacts of dimensions all their own pay no more
    than before.

    Examples
    --------
    >>> g = monotone_grid(lambda x: x**3, 4.0, (0.0, 64.0), points=8)
    >>> float(g.x[0]), float(g.x[-1]), float(g.f[-1]), g.x.size
    (0.0, 4.0, 64.0, 9)
    """
    x = np.concatenate([[0.0], upper * np.logspace(np.log10(smallest), 0.0, points)[:-1],
                        [upper]])
    with np.errstate(all="ignore"):
        f = np.asarray(func(x), dtype=float)
    f[0], f[-1] = bound_values
    keep = np.isfinite(f)
    keep[1:] &= f[1:] > np.maximum.accumulate(np.where(keep, f, -np.inf))[:-1]
    keep[[0, -1]] = True
    return MonotoneGrid(x[keep], f[keep])


def solve_on_grid(func: Callable, target, grid: MonotoneGrid, rtol: float = 1e-12,
                  atol: float = 0.0, *, compiled: bool = True):
    """:func:`solve_monotone` of func(x) = target on the grid's whole bracket [x₀, x_last],
    each element starting from the two neighbouring grid points around its target (found by
    ``np.searchsorted`` on the grid's values, their values known): a bracket about 20 % wide
    instead of the whole range: about 5 evaluations of ``func`` instead of 13 to 37.

    The root is the one :func:`solve_monotone` finds on the whole bracket to its tolerance
    (``rtol``, ``atol``): NaN where the target is NaN or outside [f(x₀), f(x_last)], the bracket's
    end where the target is its value.

    Examples
    --------
    >>> g = monotone_grid(lambda x: x**3, 4.0, (0.0, 64.0))
    >>> x = solve_on_grid(lambda x: x**3, np.array([8.0, 27.0, 100.0, 64.0]), g)
    >>> np.round(x, 11).tolist()
    [2.0, 3.0, nan, 4.0]
    """
    target = np.asarray(target, dtype=float)
    at = np.clip(np.searchsorted(grid.f, target, side="right"), 1, grid.f.size - 1)
    return solve_monotone(func, target, grid.x[at - 1], grid.x[at], rtol=rtol, atol=atol,
                          bound_values=(grid.f[at - 1], grid.f[at]), compiled=compiled)
