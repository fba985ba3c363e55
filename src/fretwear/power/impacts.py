"""Impacts one by one, and statistics of any channel over a window (POST_DYNA_MODA_T-like).

:func:`impacts` lists every impact of a window with the definitions of the contact statistics
(:mod:`fretwear.power.statistics`, ``docs/power.md``): the normal force Fn is linear between
samples, *contact* is Fn > F_s (``force_threshold``, Code_Aster's SEUIL_FORCE), an *episode* is a
maximal time interval of contact (its ends are the interpolated crossings of F_s), and episodes
separated by a rest shorter than τ (``minimum_rest_time``, DUREE_REPOS) form one *impact*; the
first episode of the window starts an impact, an impact cut by a window bound keeps its part
inside. The count, durations and peaks are therefore those of
:func:`fretwear.power.contact_statistics` (tested); this module adds what a streaming reduction
does not keep: each impact's instant of peak, impulse, impact velocity and episodes (Code_Aster's
rebounds).

:func:`channel_statistics` gives the mean, standard deviation, RMS, maximum and minimum of a
channel over a window cut in blocks, on the same piecewise-linear reading (exact integrals of
x and x² on each linear piece).
"""

from __future__ import annotations

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.history import ContactHistory

__all__ = ["impacts", "channel_statistics", "IMPACT_UNITS"]

#: Unit of each column of :func:`impacts`.
IMPACT_UNITS: dict[str, str] = {
    "start": "s", "end": "s", "duration": "s", "peak_time": "s", "peak_force": "N",
    "impulse": "N·s", "impact_velocity": "m/s", "episodes": "1", "contact_time": "s",
}


def _window(time: np.ndarray, t_start: float | None, t_end: float | None) -> tuple[float, float]:
    lo = float(time[0]) if t_start is None else max(float(t_start), float(time[0]))
    hi = float(time[-1]) if t_end is None else min(float(t_end), float(time[-1]))
    if not hi > lo:
        raise InputError(f"the window [{t_start}, {t_end}] s does not overlap the record "
                         f"{float(time[0])} .. {float(time[-1])} s")
    return lo, hi


def _grid(time: np.ndarray, cuts: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """The samples of [lo, hi] and the cut instants inside it, sorted, without repeats."""
    inside = time[(time > lo) & (time < hi)]
    extra = cuts[(cuts > lo) & (cuts < hi)]
    return np.unique(np.concatenate(([lo, hi], inside, extra)))


def impacts(history: ContactHistory, *, t_start: float | None = None,
            t_end: float | None = None, force_threshold: float = 0.0,
            minimum_rest_time: float = 0.0) -> pd.DataFrame:
    """Every impact of a window of a contact history, one row each (in time order).

    Parameters
    ----------
    history : ContactHistory
        The contact history (SI units).
    t_start, t_end : float, optional
        Window [s]; default the whole record.
    force_threshold : float
        F_s [N]: contact is Fn > F_s (SEUIL_FORCE). Default 0.
    minimum_rest_time : float
        τ [s]: episodes separated by a shorter rest belong to one impact (DUREE_REPOS).

    Returns
    -------
    pandas.DataFrame
        Columns (units in :data:`IMPACT_UNITS`): ``start``, ``end`` (first up-crossing and last
        down-crossing of F_s) and ``duration`` [s]; ``peak_force`` [N] and ``peak_time`` [s] (its
        instant: a sample's, the first when it repeats); ``impulse`` ∫Fn dt over the impact's
        contact time [N·s]; ``impact_velocity`` the normal velocity vn at ``start`` [m/s]
        (NaN without a vn channel; > 0 when penetrating); ``episodes`` (contact episodes in the
        impact: Code_Aster's rebounds) and ``contact_time`` (their total duration) [s].

    Notes
    -----
    On a linear piece from (t_a, F_a) to (t_b, F_b) crossing F_s the crossing is at
    t_a + (F_a − F_s)/(F_a − F_b)·(t_b − t_a); ∫Fn dt over a piece's contact part is the
    trapezoid of the linear force there (exact).

    Examples
    --------
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0, 3.0, 4.0], normal_force=[0.0, 2.0, 0.0, 4.0, 0.0],
    ...                    vt1=[1.0] * 5, vt2=[0.0] * 5)
    >>> t = impacts(h)
    >>> t[["start", "end", "peak_force", "impulse"]].values.tolist()
    [[0.0, 2.0, 2.0, 2.0], [2.0, 4.0, 4.0, 4.0]]
    """
    if not isinstance(history, ContactHistory):
        raise InputError(f"impacts needs a ContactHistory, got {type(history).__name__}")
    threshold, rest = float(force_threshold), float(minimum_rest_time)
    if not np.isfinite(threshold) or threshold < 0 or not np.isfinite(rest) or rest < 0:
        raise InputError(f"force_threshold [N] and minimum_rest_time [s] must be >= 0, got "
                         f"{force_threshold!r} and {minimum_rest_time!r}")
    t = history.time
    lo, hi = _window(t, t_start, t_end)
    tg = _grid(t, np.zeros(0), lo, hi)
    fg = np.interp(tg, t, history.normal_force)
    pa, pb, fa, fb = tg[:-1], tg[1:], fg[:-1], fg[1:]
    above_a, above_b = fa > threshold, fb > threshold
    crossing = np.where(above_a != above_b,
                        pa + (fa - threshold) / np.where(fa != fb, fa - fb, 1.0) * (pb - pa), pa)
    ca = np.where(above_a, pa, crossing)
    cb = np.where(above_b, pb, crossing)
    part = (above_a | above_b) & (cb > ca)
    fca, fcb = np.interp(ca, tg, fg), np.interp(cb, tg, fg)
    area = np.where(part, 0.5 * (cb - ca) * (fca + fcb), 0.0)
    # episodes: runs of pieces whose contact parts touch (the shared sample is above F_s)
    inner_above = fg[1:-1] > threshold
    prev_above = np.concatenate(([False], inner_above))
    next_above = np.concatenate((inner_above, [False]))
    starts = np.flatnonzero(part & ~prev_above)
    ends = np.flatnonzero(part & ~next_above)
    columns = ["start", "end", "duration", "peak_time", "peak_force", "impulse",
               "impact_velocity", "episodes", "contact_time"]
    if starts.size == 0:
        return pd.DataFrame({c: pd.Series(dtype=int if c == "episodes" else float)
                             for c in columns})
    ep_start, ep_end = ca[starts], cb[ends]
    ep_area = np.add.reduceat(area, starts)
    # impacts: an episode after a rest >= τ starts one (the first always does)
    new = np.concatenate(([True], ep_start[1:] - ep_end[:-1] >= rest))
    first = np.flatnonzero(new)
    last = np.concatenate((first[1:] - 1, [starts.size - 1]))
    vn = history.vn
    rows = []
    for i, j in zip(first, last, strict=True):
        a, b = float(ep_start[i]), float(ep_end[j])
        within = (tg >= a) & (tg <= b)
        k = int(np.argmax(np.where(within, fg, -np.inf)))
        rows.append({
            "start": a, "end": b, "duration": b - a, "peak_time": float(tg[k]),
            "peak_force": float(fg[k]), "impulse": float(ep_area[i:j + 1].sum()),
            "impact_velocity": float("nan") if vn is None else float(np.interp(a, t, vn)),
            "episodes": int(j - i + 1),
            "contact_time": float(np.sum(ep_end[i:j + 1] - ep_start[i:j + 1]))})
    frame = pd.DataFrame(rows, columns=columns)
    frame.attrs["units"] = dict(IMPACT_UNITS)
    return frame


def channel_statistics(time, values, *, t_start: float | None = None,
                       t_end: float | None = None, blocks: int = 1) -> dict[str, float]:
    """Mean, standard deviation, RMS, maximum and minimum of a signal over a window in blocks.

    Parameters
    ----------
    time : array_like
        Instants [s], increasing.
    values : array_like
        The signal (any unit u), linear between samples.
    t_start, t_end : float, optional
        Window [s]; default the whole record.
    blocks : int
        Number of blocks of equal duration.

    Returns
    -------
    dict
        ``mean`` [u] (mean of the block means), ``std`` [u] (√ of the mean of the block
        variances), ``rms`` [u] (√ of the mean of the blocks' mean squares), ``max``, ``min``
        [u] (over the window).

    Notes
    -----
    Block b of length T_b: m_b = (1/T_b)∫x dt, q_b = (1/T_b)∫x² dt, v_b = q_b − m_b², exact for
    the piecewise-linear signal (∫x² = Δt(x_a² + x_a x_b + x_b²)/3 on a piece). With one block
    these are the time mean, the standard deviation and the RMS over the window. Code_Aster's
    POST_DYNA_MODA_T averages the samples of each block in the same way (``dstat0``).

    Examples
    --------
    >>> s = channel_statistics([0.0, 1.0, 2.0], [0.0, 2.0, 0.0])
    >>> s["mean"], round(s["rms"] ** 2, 12), s["max"], s["min"]
    (1.0, 1.333333333333, 2.0, 0.0)
    """
    t = np.asarray(time, dtype=float)
    x = np.asarray(values, dtype=float)
    if isinstance(blocks, bool) or not isinstance(blocks, int | np.integer) or blocks < 1:
        raise InputError(f"blocks (NB_BLOC) must be a whole number >= 1, got {blocks!r}")
    lo, hi = _window(t, t_start, t_end)
    edges = np.linspace(lo, hi, int(blocks) + 1)
    tg = _grid(t, edges, lo, hi)
    xg = np.interp(tg, t, x)
    dt = np.diff(tg)
    i1 = 0.5 * dt * (xg[:-1] + xg[1:])
    i2 = dt * (xg[:-1] ** 2 + xg[:-1] * xg[1:] + xg[1:] ** 2) / 3.0
    which = np.clip(np.searchsorted(edges, tg[:-1], side="right") - 1, 0, blocks - 1)
    length = np.diff(edges)
    mean_b = np.bincount(which, i1, blocks) / length
    ms_b = np.bincount(which, i2, blocks) / length
    var_b = np.maximum(ms_b - mean_b**2, 0.0)
    return {"mean": float(mean_b.mean()), "std": float(np.sqrt(var_b.mean())),
            "rms": float(np.sqrt(ms_b.mean())), "max": float(xg.max()), "min": float(xg.min())}
