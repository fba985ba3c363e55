"""The wall and its limit: depth as a fraction of the wall, time to reach the limit.

A tube is plugged when its worn depth reaches a fraction of its wall thickness (commonly 40 %).
With the case's ``wall_thickness`` [m] and ``depth_limit`` [-] the wear table gains, for the
global depth and for every sector depth (docs/uncertainty.md §1):

* ``wall_fraction`` (``wall_fraction_sector``): the depth of the mobile over the wall [-];
* ``limit_instant`` (``limit_instant_sector``): the instant [user time unit] at which the tube
  in place first reaches ``depth_limit × wall_thickness``: the global depth's by
  :meth:`fretwear.table.DepthModel.time_to`, each sector's by
  :meth:`fretwear.table.DepthModel.sector_time_to` (the one meaning of the time to a limit,
  docs/uncertainty.md §1: a restart's earlier rows included, only the new tube after a
  replacement);
  ``inf`` when the law never gets there (no wear).

A depth beyond the wall (fraction > 1) is named by a :class:`~fretwear.errors.PerforationWarning`.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable

import numpy as np

from fretwear.errors import InputError, PerforationWarning
from fretwear.geometry import solve_monotone

__all__ = ["DEFAULT_DEPTH_LIMIT", "check_wall", "time_to_depth", "wall_columns"]

#: The depth limit of a tube by default, as a fraction of its wall [-]: the common plugging
#: criterion, 40 % through-wall.
DEFAULT_DEPTH_LIMIT = 0.4


def _finite(value, name: str) -> float:
    ok = not isinstance(value, bool | str | bytes) and value is not None
    try:
        out = float(value) if ok else math.nan
    except (TypeError, ValueError):
        out = math.nan
    if not math.isfinite(out):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return out


def check_wall(wall_thickness, depth_limit) -> tuple[float | None, float]:
    """The validated wall thickness [m] (None: unknown) and depth limit [-], as floats.

    The one check of the wall and its limit, for the wear case and the uncertainty models.

    Raises
    ------
    InputError
        A wall thickness that is not a finite number > 0 [m], or a depth limit that is not a
        fraction of the wall, 0 < depth_limit <= 1 [-].

    Examples
    --------
    >>> check_wall(1.09e-3, 0.4)
    (0.00109, 0.4)
    """
    wall = None
    if wall_thickness is not None:
        wall = _finite(wall_thickness, "wall_thickness [m]")
        if wall <= 0:
            raise InputError(f"wall_thickness must be > 0 [m], got {wall:g}")
    limit = _finite(depth_limit, "depth_limit")
    if not 0 < limit <= 1:
        raise InputError(f"depth_limit is a fraction of the wall thickness, 0 < depth_limit "
                         f"<= 1 [-], got {limit:g} (e.g. 0.4 for a plugging criterion)")
    return wall, limit


#: Bracket growth per step and number of steps (16⁸⁰ ≈ 10⁹⁶ times the first guess).
_GROWTH, _STEPS = 16.0, 80


def time_to_depth(depth_of_time: Callable[[np.ndarray], np.ndarray], target, *,
                  first_guess: float = 1.0, rtol: float = 1e-12,
                  narrow: str = "compiled") -> np.ndarray:
    """Times t ≥ 0 [s] at which a non-decreasing depth(t) reaches ``target`` [m]; vectorised.

    Parameters
    ----------
    depth_of_time : callable
        ``depth_of_time(t)`` for an array t [s] of the shape of ``target``, element-wise
        (element i may use parameters of its own); NaN means beyond the relation's range
        (deeper than any depth in it).
    target : float or array_like
        Depths to reach [m], > 0.
    first_guess : float
        A time scale to start the bracket from [s] (e.g. the user's time unit).
    rtol : float
        Relative tolerance on t.
    narrow : {"compiled", "scipy"}
        The solver that narrows the bracket: fretwear's Chandrupatla step compiled by numba
        (:func:`fretwear.geometry.solve_monotone`, the default: about twice as fast on Monte
        Carlo arrays, ``benchmarks/bench_time_to.py``), or
        ``scipy.optimize.elementwise.find_root`` (the same method).

    Returns
    -------
    numpy.ndarray or float
        t [s]: 0 where depth(0) ≥ target already, ``inf`` where the depth never reaches it.

    Notes
    -----
    ``scipy.optimize.elementwise.bracket_root`` [1]_ grows the bracket [0, first_guess] by ×16
    (at most 80 times) until depth(hi) ≥ target, each element on its own; Chandrupatla's
    method narrows it to ``rtol`` on t (``narrow``). ``depth_of_time`` is called with the
    full shape (the other elements at a time of theirs). A NaN depth counts as above the
    target.

    References
    ----------
    .. [1] SciPy, ``scipy.optimize.elementwise`` (SciPy >= 1.15).

    Examples
    --------
    >>> round(float(time_to_depth(lambda t: 1e-6 * np.sqrt(t), 1e-3)), 6)  # (1e-3/1e-6)²
    1000000.0
    """
    from scipy.optimize import elementwise

    if narrow not in ("compiled", "scipy"):
        raise InputError(f"narrow is 'compiled' or 'scipy', got {narrow!r}")
    goal = np.asarray(target, dtype=float)
    if not (np.isfinite(goal) & (goal > 0)).all():
        raise InputError(f"the depth to reach must be finite and > 0 [m], got {target!r}")
    shape = goal.shape
    above = 2.0 * goal + 1.0  # stands for "beyond the relation's range"
    flat_goal, flat_above = goal.ravel(), above.ravel()
    t_full = np.zeros(goal.size)  # the times of every element (converged ones keep theirs)

    def excess(t, at):  # depth(t) − target of the elements ``at`` (scipy's active ones)
        t_full[at] = t
        d = np.broadcast_to(np.asarray(depth_of_time(t_full.reshape(shape)), dtype=float),
                            shape).ravel()[at]
        return np.where(np.isnan(d), flat_above[at], d) - flat_goal[at]

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")  # range and law warnings of trial times
        index = np.arange(goal.size)
        done = excess(np.zeros(goal.size), index) >= 0
        out = np.where(done, 0.0, np.inf)
        active = np.flatnonzero(~done)
        if active.size:
            t_full[:] = 0.0
            bracket = elementwise.bracket_root(
                excess, np.zeros(active.size), np.full(active.size, float(first_guess)),
                xmin=0.0, factor=_GROWTH, args=(active,), maxiter=_STEPS)
            found = bracket.success
            active = active[found]
            if active.size and narrow == "scipy":
                t_full[:] = 0.0
                root = elementwise.find_root(
                    excess, (bracket.bracket[0][found], bracket.bracket[1][found]),
                    args=(active,), tolerances={"xrtol": rtol, "xatol": 0.0})
                out[active] = root.x
            elif active.size:
                lo = np.zeros(goal.size)
                hi = np.zeros(goal.size)
                lo[active], hi[active] = bracket.bracket[0][found], bracket.bracket[1][found]
                every = np.arange(goal.size)
                solved = solve_monotone(lambda t: excess(t.ravel(), every).reshape(shape),
                                        np.zeros(shape), lo.reshape(shape), hi.reshape(shape),
                                        rtol=rtol).ravel()
                out[active] = solved[active]
    out = out.reshape(shape)
    return out if out.ndim else float(out)


def _past_wall(fraction) -> np.ndarray:
    """Rows whose depth is past the wall: fraction > 1, or NaN (a volume beyond the geometric
    relation's range, deeper than any depth in it)."""
    # not (f <= 1): true exactly where f > 1 or f is NaN (a comparison with NaN is false)
    return ~(np.asarray(fraction, dtype=float) <= 1.0)


def wall_columns(depth_mobile: np.ndarray, sector: np.ndarray | None,
                 depth_mobile_sector: np.ndarray | None, *, wall: float, depth_limit: float,
                 global_depth, sector_depths=None, unit: str | None = None,
                 stacklevel: int = 3) -> tuple[dict, dict]:
    """The wall columns of a wear table from its depth columns, and the limit's metadata.

    Parameters
    ----------
    depth_mobile : numpy.ndarray
        The table's ``depth_mobile`` [m].
    sector, depth_mobile_sector : numpy.ndarray or None
        The table's ``sector`` numbers (1-based) and ``depth_mobile_sector`` [m] (sector mode).
    wall : float
        Wall thickness of the mobile [m].
    depth_limit : float
        Depth limit as a fraction of the wall [-].
    global_depth : DepthModel or None
        The global depth's model (None: no global depth): its
        :meth:`~fretwear.table.DepthModel.time_to` gives the limit and through-wall instants.
    sector_depths : DepthModel, optional
        The model of the sectors (sector mode): its
        :meth:`~fretwear.table.DepthModel.sector_time_to` gives each sector's instants.
    unit : str, optional
        Name of the user time unit, for the warning.

    Returns
    -------
    (dict, dict)
        ``{"wall_fraction", "limit_instant"[, "wall_fraction_sector", "limit_instant_sector"]}``
        as arrays of the table's length, and ``{"limit_depth", "limit_instant",
        "through_wall"[, "limit_instant_sector"]}``.
    """
    limit = depth_limit * wall
    depth_mobile = np.asarray(depth_mobile, dtype=float)

    fraction = depth_mobile / wall
    past = global_depth is not None and _past_wall(fraction).any()
    limit_at = wall_at = math.nan
    if global_depth is not None:  # the limit and the wall in one call
        found = np.atleast_1d(global_depth.time_to(np.array([limit, wall] if past
                                                            else [limit]))).tolist()
        limit_at, wall_at = found[0], found[-1]
    columns = {"wall_fraction": fraction, "limit_instant": np.full(fraction.shape, limit_at)}
    info = {"limit_depth": limit, "limit_instant": limit_at, "through_wall": {}}
    through = []
    if past:
        info["through_wall"]["global"] = wall_at
        through.append(f"its global depth from instant {wall_at:.6g}")
    if sector_depths is not None:
        sector = np.asarray(sector, dtype=int)
        fraction_sector = np.asarray(depth_mobile_sector, dtype=float) / wall
        columns["wall_fraction_sector"] = fraction_sector
        both = np.asarray(sector_depths.sector_time_to(np.array([limit, wall])), dtype=float)
        instants = both[0]
        columns["limit_instant_sector"] = instants[sector - 1]
        info["limit_instant_sector"] = instants.tolist()
        deep = sorted(set(sector[_past_wall(fraction_sector)].tolist()))
        walls = both[1]
        for j in deep:
            t = walls[j - 1]
            info["through_wall"][f"sector {j}"] = t
            through.append(f"sector {j}'s depth from instant {t:.6g}")
    if through:
        depths = np.concatenate([
            depth_mobile,
            np.asarray(depth_mobile_sector, dtype=float) if sector_depths else []])
        if np.isnan(depths).any():
            deepest = "beyond the geometric relation's range (NaN)"
        else:
            top = float(depths.max())
            deepest = f"{top * 1e3:.4g} mm ({top / wall:.0%} of the wall)"
        warnings.warn(f"the tube is worn through its wall ({wall * 1e3:.4g} mm): "
                      f"{'; '.join(through)} [{unit or 'user time unit'}]; deepest "
                      f"{deepest}. Depths past the wall are extrapolations of the geometry",
                      PerforationWarning, stacklevel=stacklevel)
    return columns, info
