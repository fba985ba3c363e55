"""The compiled (numba) pass of the plausibility checks (:mod:`fretwear.io.plausibility`), and
the checks of a streamed block (:func:`fretwear.io.channels.fast_history`: :func:`finite`,
:func:`increasing`, :func:`nonnegative_max`, :func:`flags`, one pass a channel; the numpy
expressions there remain the reference, used without numba).

Imported by :func:`fretwear.io.plausibility.check_plausibility` only when numba is installed
and the history is long (``plausibility._KERNEL_SAMPLES``). The numpy expressions of
``plausibility`` remain the reference; this pass computes the same numbers in four loops over
the channels (largest squares and force, dy/dz, time steps, contact episodes) instead of some
eight array passes and their temporaries (a 1e5-sample history with dy/dz, out of cache: 0.65
-> 0.23 ms; ``benchmarks/bench_read.py``).

Every quantity is computed as the reference computes it, operation for operation, so the
results are equal bit for bit: the squares ``a*a + b*b`` (no fused multiply-add: numba
compiles without fast-math contraction), exact maxima, the differences ``t[i+1] - t[i]``, and
the contact episodes' ``time[end] - time[start]``. The one exception is the sign of a zero:
when the forces are all zero, mixing 0.0 and -0.0, the largest force may be either (no check
can tell them apart). The inputs are a history's channels: finite (a
:class:`~fretwear.history.ContactHistory` holds no NaN or infinity), so a maximum taken by
comparison is the maximum numpy returns.
"""

from __future__ import annotations

import numpy as np

from fretwear._numba import njit


@njit(cache=True, nogil=True)
def statistics(t, fn, vt1, vt2, dy, dz, step_limit):  # pragma: no cover - compiled
    """Largest ``vt1² + vt2²`` [m²/s²], largest ``dy² + dz²`` [m²] (0 without dy), largest
    normal force [N], the number of time steps above ``step_limit`` [s] and the durations [s]
    of the complete contact episodes (Fn > 0 runs, open ends dropped), as
    :func:`fretwear.io.plausibility.impact_durations` gives them."""
    n = t.size
    speed2 = vt1[0] * vt1[0] + vt2[0] * vt2[0]
    fmax = fn[0]
    for i in range(1, n):
        s = vt1[i] * vt1[i] + vt2[i] * vt2[i]
        if s > speed2:
            speed2 = s
        if fn[i] > fmax:
            fmax = fn[i]
    radial2 = 0.0
    if dy is not None:
        radial2 = dy[0] * dy[0] + dz[0] * dz[0]
        for i in range(1, n):
            r = dy[i] * dy[i] + dz[i] * dz[i]
            if r > radial2:
                radial2 = r
    above = 0
    for i in range(n - 1):
        if t[i + 1] - t[i] > step_limit:
            above += 1
    # contact episodes: a start where Fn turns > 0, an end where it turns back to 0; an end
    # before the first start and a start never ended are dropped
    durations = np.empty(n // 2 + 1)
    count = 0
    start = -1
    was_on = fn[0] > 0.0
    for i in range(1, n):
        on = fn[i] > 0.0
        if on and not was_on:
            start = i
        elif was_on and not on and start >= 0:
            durations[count] = t[i] - t[start]
            count += 1
        was_on = on
    return speed2, radial2, fmax, above, durations[:count]


# ----------------------------------------------------------------------- a block's checks
# The checks of fretwear.io.channels.fast_history on one streamed block, one pass a channel
# (numpy's expressions take two to three passes and a temporary each). Finiteness is read from
# the bits (the exponent all ones: inf or NaN) and the largest force from the bits of
# non-negative floats (ordered as their values), so that the loops reduce integers: no
# floating-point reduction to keep in order, the compiler vectorises them.
_EXPONENT = np.uint64(0x7FF0000000000000)
_MAGNITUDE = np.uint64(0x7FFFFFFFFFFFFFFF)
_NEGATIVE_ZERO = np.uint64(0x8000000000000000)


@njit(cache=True, nogil=True)
def finite(a):  # pragma: no cover - compiled
    """Whether every value of the contiguous float64 array ``a`` is finite."""
    bits = a.view(np.uint64)
    bad = False
    for i in range(bits.size):
        bad |= (bits[i] & _EXPONENT) == _EXPONENT
    return not bad


@njit(cache=True, nogil=True)
def increasing(t):  # pragma: no cover - compiled
    """Whether the contiguous float64 array ``t`` is finite and strictly increasing."""
    bits = t.view(np.uint64)
    bad = (bits[0] & _EXPONENT) == _EXPONENT
    for i in range(1, bits.size):
        bad |= ((bits[i] & _EXPONENT) == _EXPONENT) | (not t[i] > t[i - 1])
    return not bad


@njit(cache=True, nogil=True)
def nonnegative_max(fn):  # pragma: no cover - compiled
    """``(ok, largest)``: whether the contiguous float64 array ``fn`` is finite and >= 0 (-0.0
    counts as 0), and its largest value [its unit] when it is (a largest zero may be 0.0 where
    numpy gives -0.0: no comparison tells them apart)."""
    bits = fn.view(np.uint64)
    bad = False
    top = np.uint64(0)
    for i in range(bits.size):
        b = bits[i]
        bad |= ((b & _EXPONENT) == _EXPONENT) | (b > _NEGATIVE_ZERO)
        top = max(top, b & _MAGNITUDE)
    return not bad, np.array([top]).view(np.float64)[0]


@njit(cache=True, nogil=True)
def flags(s):  # pragma: no cover - compiled
    """Whether every value of the contiguous float64 array ``s`` is 0.0 or 1.0 (-0.0 counts)."""
    bad = False
    for i in range(s.size):
        bad |= not ((s[i] == 0.0) | (s[i] == 1.0))
    return not bad


# ----------------------------------------------------------------- the units against a geometry
@njit(cache=True, nogil=True)
def motion(dy, dz, vt1, vt2, centre):  # pragma: no cover - compiled
    """The numbers :func:`fretwear.io.geometry_units.check_against_geometry` compares with the
    contact's geometry, in one pass: ``dy.max() - dy.min()`` and ``dz.max() - dz.min()`` [m],
    the sign changes of ``dy - centre`` (``numpy.signbit``, ``centre`` the median of ``dy``)
    and the largest ``vt1² + vt2²`` [m²/s²] (``inf`` when the squares overflow, as numpy's).
    The operations of the numpy expressions there, the same numbers (finite inputs: a
    history's channels)."""
    ylo = yhi = dy[0]
    zlo = zhi = dz[0]
    speed2 = vt1[0] * vt1[0] + vt2[0] * vt2[0]
    sign = np.signbit(dy[0] - centre)
    crossings = 0
    for i in range(1, dy.size):
        y, z = dy[i], dz[i]
        ylo, yhi = min(ylo, y), max(yhi, y)
        zlo, zhi = min(zlo, z), max(zhi, z)
        s = vt1[i] * vt1[i] + vt2[i] * vt2[i]
        if s > speed2:
            speed2 = s
        below = np.signbit(y - centre)
        crossings += below != sign
        sign = below
    return yhi - ylo, zhi - zlo, crossings, speed2
