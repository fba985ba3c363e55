"""The coupled loop said honestly: each cycle's wear power with its confidence interval, and
whether a change from one cycle to the next stands out of that noise.

A rattling tube is chaotic: two computations of the same cycle whose sums round differently (two
processors, two SIMD code paths) follow different trajectories after a few hundred impacts. What
they share is their statistics: the wear power of a cycle is an estimate, known to within the
batch-means interval of its history (:func:`fretwear.power.batch_means_interval`). This module
gives every cycle that interval, compares cycles through it, and judges convergence and the
``max_depth_m`` stop against it, so that no conclusion is drawn from a difference smaller than
the noise.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from fretwear.errors import ConfidenceWarning, KeywordError

__all__ = ["DEFAULT_CONFIDENCE_BLOCKS", "DEFAULT_CONFIDENCE_LEVEL", "change_interval",
           "convergence_verdict", "cycle_interval", "ensemble_power", "largest_depth",
           "max_depth_noise", "noise_columns", "reseeded", "warn_if_noisy"]

#: Blocks of the batch-means interval of a cycle's power when [power] blocks is below 2 [-].
DEFAULT_CONFIDENCE_BLOCKS = 10
#: Confidence level of a cycle's power interval [-].
DEFAULT_CONFIDENCE_LEVEL = 0.95


def cycle_interval(power, level: float, *, interval_power=None):
    """The confidence interval of a cycle's wear power (batch means over its history).

    Parameters
    ----------
    power : PowerResult
        The power that feeds the cycle's wear table [W].
    level : float
        Confidence level in (0, 1) [-].
    interval_power : PowerResult, optional
        The same window reduced in more blocks, when ``power`` has fewer than 2 (the table's
        power is left as the user asked; its total is the same mean over the window).

    Returns
    -------
    PowerInterval
        Centred on ``power.total`` [W]; the ConfidenceWarnings of the blocks (too few,
        correlated) are issued as usual.
    """
    source = power if len(np.atleast_1d(power.blocks)) >= 2 else interval_power
    iv = source.confidence_interval(level)
    # the table's power is the estimate: the block split may round its mean differently
    return replace(iv, estimate=float(power.total))


def change_interval(current, previous) -> tuple[float, float]:
    """(ΔP, its half-width) [W] between two cycles' power intervals.

    Notes
    -----
    The two cycles' estimates come from separate dynamics computations, so they are taken as
    independent: the half-width of the difference is :math:`\\sqrt{h_k^2 + h_{k-1}^2}`, the
    half-widths combined in quadrature (exact for normal estimates of equal level; the two
    Student intervals have equal degrees of freedom here).

    Examples
    --------
    >>> from fretwear.power.confidence import batch_means_interval
    >>> a = batch_means_interval([1.0, 1.2, 0.8, 1.1, 0.9, 1.0, 1.05, 0.95, 1.0, 1.0])
    >>> d, h = change_interval(a, a)
    >>> d, round(h / a.half_width, 6)   # √2 times one half-width
    (0.0, 1.414214)
    """
    return (float(current.estimate - previous.estimate),
            float(math.hypot(current.half_width, previous.half_width)))


def noise_columns(interval, previous, depth_increment: float) -> dict[str, Any]:
    """The summary columns of one cycle's noise (see :class:`IterationResult`)."""
    row: dict[str, Any] = {
        "power_low": interval.low, "power_high": interval.high,
        "power_half_width": float(interval.half_width), "power_level": interval.level,
        "power_interval_count": int(interval.count),
        "power_interval_method": interval.method,
        "power_change": math.nan, "power_change_half_width": math.nan,
        "power_change_significant": None}
    if previous is not None:
        change, half = change_interval(interval, previous)
        row.update(power_change=change, power_change_half_width=half,
                   power_change_significant=bool(abs(change) > half))
    rel = interval.relative_half_width
    row["depth_increment_half_width"] = (float(abs(depth_increment) * rel)
                                         if math.isfinite(rel) else math.nan)
    return row


def convergence_verdict(summary, tolerance: float | None) -> tuple[str, str]:
    """(verdict, sentence) on whether the loop's power converged beyond the noise.

    Parameters
    ----------
    summary : DataFrame
        The loop's summary (``power``, ``power_change``, ``power_change_half_width``).
    tolerance : float or None
        ``[iterate] convergence_tolerance``: the relative change of the power [-] below which
        two cycles count as converged.

    Returns
    -------
    verdict : str
        ``"converged"`` (the interval of the last change lies inside ±tolerance·P),
        ``"not converged"`` (the change is beyond the noise, and beyond the tolerance when one
        is given), ``"undecided"`` (the change is within the noise: the interval is too wide to
        tell, or, without a tolerance, no change can be claimed either way) or
        ``"one cycle"``.
    sentence : str
        What the terminal and ``summary.json`` say.

    Examples
    --------
    >>> import pandas as pd
    >>> s = pd.DataFrame({"power": [1.0, 1.02], "power_change": [float("nan"), 0.02],
    ...                   "power_change_half_width": [float("nan"), 0.01]})
    >>> convergence_verdict(s, 0.05)[0], convergence_verdict(s, 0.005)[0]
    ('converged', 'not converged')
    >>> convergence_verdict(s, 0.02)[0], convergence_verdict(s, None)[0]
    ('undecided', 'not converged')
    """
    if len(summary) < 2:
        return "one cycle", "one cycle: no change between cycles to judge convergence by"
    last = summary.iloc[-1]
    change, half, power = (float(last["power_change"]), float(last["power_change_half_width"]),
                           float(last["power"]))
    k = int(last["cycle"]) if "cycle" in summary.columns else len(summary)
    said = (f"power change from cycle {k - 1} to {k}: {change:+.3g} ± {half:.2g} W "
            f"({_percent(change, power)} ± {_percent(half, power)} of P)")
    if not math.isfinite(half):
        return "undecided", f"{said}: no interval, convergence cannot be judged"
    if tolerance is None:
        if abs(change) > half:
            return "not converged", f"{said}: beyond the noise, the power still changes"
        return "undecided", (f"{said}: within the noise; convergence is not claimed from a "
                             "change smaller than the noise (set [iterate] "
                             "convergence_tolerance to judge it against a tolerance)")
    band = tolerance * abs(power)
    if abs(change) + half <= band:
        return "converged", (f"{said}: inside ±{100 * tolerance:.3g} % beyond the noise: "
                             "converged")
    if abs(change) - half > band:
        return "not converged", (f"{said}: beyond ±{100 * tolerance:.3g} % and beyond the "
                                 "noise: not converged")
    return "undecided", (f"{said}: the noise is too wide to tell whether the change is inside "
                         f"±{100 * tolerance:.3g} % (a longer [dynamics] duration_s narrows "
                         "it)")


def max_depth_noise(row: Mapping[str, Any], columns, max_depth: float) -> bool:
    """Whether the ``max_depth_m`` decision of a cycle is inside the noise: the compared depth's
    interval (its value ± the cycle's ``depth_increment_half_width`` [m]) straddles
    ``max_depth`` [m]."""
    half = float(row.get("depth_increment_half_width", math.nan))
    if not math.isfinite(half):
        return False
    depth = largest_depth(row, columns)
    return depth is not None and depth - half < max_depth <= depth + half


def largest_depth(row: Mapping[str, Any], columns) -> float | None:
    """The largest finite value of ``row`` among ``columns`` [m], None when none is finite
    (the depth the ``max_depth_m`` criterion compares)."""
    values = [float(row[c]) for c in columns if np.isfinite(row[c])]
    return max(values) if values else None


def _percent(value: float, reference: float) -> str:
    if not (math.isfinite(value) and reference):
        return "n/a"
    return f"{100 * value / reference:.2g} %"


def warn_if_noisy(k: int, interval, threshold: float = 0.5) -> None:
    """A ConfidenceWarning when a cycle's power is known to worse than ±``threshold`` [-]."""
    rel = interval.relative_half_width
    if math.isfinite(rel) and rel > threshold:
        warnings.warn(f"cycle {k}: the wear power is known to ±{100 * rel:.0f} % only "
                      f"({interval}); a longer [dynamics] duration_s narrows it",
                      ConfidenceWarning, stacklevel=3)


def reseeded(excitations, run: int, step: int = 1000):
    """The excitations of ensemble run ``run`` (0-based): every random signal's seed moved by
    ``run · step``; run 0 is the case as written.

    Raises
    ------
    KeywordError
        ``run`` > 0 and no excitation is random: every run would be the same computation.
    """
    if run == 0:
        return list(excitations)
    out, moved = [], False
    for e in excitations:
        signal = getattr(e, "signal", None)
        if signal is not None and signal.kind == "random":
            e = replace(e, signal=replace(signal, seed=int(signal.seed) + run * step))
            moved = True
        out.append(e)
    if not moved:
        raise KeywordError("[iterate] ensemble > 1 needs a random excitation ([[dynamics.forces]] "
                           "or [[dynamics.base]] with kind = \"random\"): with harmonic or table "
                           "signals every run is the same computation; use ensemble = 1 (the "
                           "batch-means interval)")
    return out


def ensemble_power(powers):
    """The wear power of an ensemble of runs of one cycle: the mean of the runs' powers.

    Parameters
    ----------
    powers : sequence of PowerResult
        The runs' powers over the same window [W].

    Returns
    -------
    PowerResult
        ``total``, ``sectors``, ``blocks`` and ``block_sectors`` the means over the runs [W]
        (the sector and block layouts are the same in every run); ``statistics`` and the other
        fields those of the first run.
    """
    first = powers[0]
    if len(powers) == 1:
        return first

    def mean(name):
        values = [getattr(p, name) for p in powers]
        return None if values[0] is None else np.mean(np.stack(
            [np.asarray(v, dtype=float) for v in values]), axis=0)

    return replace(first, total=float(np.mean([p.total for p in powers])),
                   sectors=mean("sectors"), blocks=mean("blocks"),
                   block_sectors=mean("block_sectors"))
