"""Floating-point range of the wear-power reduction: no silent inf, no lost tiny speeds.

The kernels compute the sliding speed as ``√(Vt1² + Vt2²)``: the squares overflow for speeds
above about 1e154 m/s (the speed becomes inf) and underflow below about 1e-154 m/s (a speed of
8e-270 m/s becomes 0). Every speed-linear sum (the power, the sliding distance) is therefore
computed again on velocities scaled by an exact power of two, :func:`speed_scale`, and scaled
back, when the chunk's sums show it may be needed (:func:`out_of_range`): the result is the one
of the exact formula, bit for bit when no scaling is needed. A speed
component below 1e-154 m/s in a chunk whose largest one is ordinary counts as 0 (an absolute
error under 1e-154 m/s × Fn).

A product or a sum that still does not fit in a double (Fn·‖Vt‖ with Fn = Vt = 1e200, or Fn² of
the statistics with Fn = 1e200 N) is an error naming the channel, the instant and the values
(:func:`check_finite_sums`), never an infinite power: such values are never physical and come
from a unit or export mistake.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear.errors import HistoryError, InputError

#: Speeds [m/s] whose squares stay normal doubles: inside, no scaling (results bit for bit).
SAFE_SPEEDS = (1e-150, 1e150)
_FORCE_INTEGRAL = 3  # column "force_integral" of fretwear.power.reference.BLOCK_STATS


def speed_scale(vt1: np.ndarray, vt2: np.ndarray) -> float:
    """An exact power of two ``2^k`` such that ``2^k·max|Vt|`` lies in [2^499, 2^500) (``|k| <=
    1000``), or 1.0 when the largest speed component is 0 or inside :data:`SAFE_SPEEDS`.

    Components smaller than 2^-1011 of the largest one (a relative 5e-305) then count as 0.

    Examples
    --------
    >>> speed_scale(np.array([0.1, -2.0]), np.zeros(2))
    1.0
    >>> speed_scale(np.array([8e-270]), np.zeros(1)) > 1e268
    True
    """
    if vt1.size == 0:
        return 1.0
    top = max(float(vt1.max()), -float(vt1.min()), float(vt2.max()), -float(vt2.min()))
    if top == 0.0 or not math.isfinite(top) or SAFE_SPEEDS[0] < top < SAFE_SPEEDS[1]:
        return 1.0
    # the largest component to about 2^500: the squares of every component down to 2^-1011 of
    # it stay normal doubles, and |k| <= 1000 keeps the scale itself a normal double
    return math.ldexp(1.0, min(max(500 - math.frexp(top)[1], -1000), 1000))


def out_of_range(sums) -> bool:
    """Whether the partial sums of a chunk may suffer from the float range: not finite, or a
    power below 1e-100 J while the force integral is positive (a speed whose square
    underflowed). Ordinary chunks answer False after two reductions of small arrays, so the
    velocities are scanned (:func:`speed_scale`) only for the rare suspicious chunk.

    One sum of each array says whether all its values are finite (an inf or a NaN makes the
    sum inf or NaN; 13 -> 6 µs a chunk against ``isfinite().all()`` of both, issue 28): a sum of
    finite values that overflows (values near 1.8e308, never physical) only sends the chunk
    down the path of a suspicious one, which gives the same sums or the same error.

    Examples
    --------
    >>> from types import SimpleNamespace as sums
    >>> stats = np.array([[1.0, 2.0, 4.0, 2.0, 4.0, 0.5]])
    >>> out_of_range(sums(power=np.array([[1.0, 2.0]]), block_stats=stats))
    False
    >>> out_of_range(sums(power=np.array([[np.inf, -np.inf]]), block_stats=stats))
    True
    >>> out_of_range(sums(power=np.array([[0.0, 1e-300]]), block_stats=stats))  # underflow?
    True
    """
    power = float(sums.power.sum())
    if not math.isfinite(power + float(sums.block_stats.sum())):
        return True
    return bool(abs(power) < 1e-100 and sums.block_stats[:, _FORCE_INTEGRAL].sum() > 0.0)


def check_finite_sums(sums, t, fn, vt1, vt2, name: str) -> None:
    """Raise a :class:`HistoryError` naming the first overflowing product when the partial sums
    of a chunk (power and statistics) are not finite.

    Parameters
    ----------
    sums : ChunkSums
        The partial sums of the chunk.
    t, fn, vt1, vt2 : numpy.ndarray
        The chunk's instants [s], normal force [N], sliding velocities [m/s].
    name : str
        The history's name, for the message.
    """
    if np.isfinite(sums.power).all() and np.isfinite(sums.block_stats).all():
        return
    with np.errstate(over="ignore", invalid="ignore"):
        speed = np.hypot(vt1, vt2)
        product = fn * speed
        square = fn * fn
    hint = ("values this large are never physical: check the units and the export of the "
            "history (units = {...} in a case file, --units on the command line)")
    bad = np.flatnonzero(~np.isfinite(product))
    if bad.size:
        i = int(bad[0])
        raise HistoryError(
            f"contact history {name!r}: the wear power overflows at t = {float(t[i])!r} s: "
            f"normal_force {float(fn[i]):g} N × sliding speed {float(speed[i]):g} m/s (vt1 "
            f"{float(vt1[i]):g}, vt2 {float(vt2[i]):g}) exceeds the floating-point range; {hint}")
    bad = np.flatnonzero(~np.isfinite(square))
    if bad.size:
        i = int(bad[0])
        raise HistoryError(
            f"contact history {name!r}: channel 'normal_force' = {float(fn[i]):g} N at t = "
            f"{float(t[i])!r} s: its square (force statistics) exceeds the floating-point "
            f"range; {hint}")
    raise HistoryError(
        f"contact history {name!r}: the integral of Fn·‖Vt‖ over [{float(t[0])!r}, "
        f"{float(t[-1])!r}] s exceeds the floating-point range (largest force "
        f"{float(np.max(fn)):g} N, largest speed {float(np.max(speed)):g} m/s); {hint}")


#: The smallest normal float64 [s] (numpy.finfo(float).tiny, 2.2e-308).
_TINY = float(np.finfo(float).tiny)


def check_window_length(duration: float, blocks: int, name: str) -> None:
    """Refuse a window whose blocks last less than the smallest normal float [s].

    A block of ``duration / blocks`` seconds below ``numpy.finfo(float).tiny`` (2.2e-308 s)
    is a subnormal number: its sub-intervals and the division by it lose every digit (a power
    of 0 W or NaN came out of a 1e-323 s window). No contact is sampled that finely: the time
    channel is not in seconds.

    Parameters
    ----------
    duration : float
        Window length T [s].
    blocks : int
        Number of blocks (NB_BLOC).
    name : str
        The history's name, for the message.

    Raises
    ------
    InputError
        Naming the window, the block length and the fix.

    Examples
    --------
    >>> check_window_length(1.0, 4, "h")
    >>> try:
    ...     check_window_length(1e-310, 4, "h")
    ... except InputError as exc:
    ...     print(str(exc)[:64])
    history 'h': the window of 1e-310 s (4 blocks of 2.5e-311 s) is
    """
    tiny = _TINY
    if duration / blocks >= tiny:
        return
    raise InputError(
        f"history {name!r}: the window of {duration:g} s ({blocks} block"
        f"{'s' if blocks > 1 else ''} of {duration / blocks:g} s) is shorter than the smallest "
        f"normal floating-point number {tiny:g} s: its powers would lose every digit. No "
        "contact is sampled that finely: check the time channel's unit (units = {time = ...})")


def check_finite_power(total: float, blocks: np.ndarray, duration: float, name: str) -> None:
    """Raise a :class:`HistoryError` when the wear power [W] overflows where its integral [J]
    did not (a power above 1.8e308 W: the division by the window's ``duration`` [s]).

    Examples
    --------
    >>> check_finite_power(0.5, np.array([0.4, 0.6]), 2.0, "h")
    """
    if math.isfinite(total) and np.isfinite(blocks).all():
        return
    raise HistoryError(
        f"contact history {name!r}: the wear power over a window of {duration:g} s exceeds the "
        "floating-point range (its integral does not): values this large are never physical: "
        "check the units and the export of the history (units = {...} in a case file, --units "
        "on the command line)")
