"""Streaming passes of the KWU-EPRI class statistics (theory §4), compiled when numba is there.

:class:`fretwear.laws.KwuEpriAccumulator` counts the contact time of each (speed, force) class
chunk by chunk; the classes need the window's largest normal force F_max and largest sliding
speed V_max. This module holds the two one-pass reductions over a chunk's raw channels
(time, Fn, Vt1, Vt2), so that the wear power's streaming pass can carry them
(:class:`fretwear.power.PowerAccumulator` with ``kwu=``):

* :func:`maxima_pass`: F_max and V_max over the window's samples (free flight included);
* :func:`class_pass`: the contact time per class with given maxima.

Both give exactly what the numpy implementation gives (sliding speed = ``numpy.hypot(Vt1,
Vt2)``): the speed is computed as √(Vt1² + Vt2²) and replaced by ``hypot`` wherever the two
could differ in a way that matters: near a class bound, near V_max, outside [1e-150, 1e150]
and for the candidates of the largest speed.

Why F_max and V_max cannot come from the same pass as the counts: a sample's class depends on
the final maxima, which a later sample can raise. With the data seen so far a single pass would
have to keep enough to classify every sample seen against any larger maximum, i.e. the sorted
forces and speeds themselves: memory proportional to the history (for a force record whose
first half peaks at F and whose second half brings one sample anywhere in [F, 5F], the class
time of the first class, Σ dt·[Fn ≤ F_max/5], is the first half's distribution at an arbitrary
point). Hence: with FNOR_MAXI and VTAN_MAXI given, the counts come in the power's pass; without
them, that pass gives the maxima and the counts take one more pass.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._numba import HAVE_NUMBA, njit

N_CLASSES = 5
#: Relative distance to a class bound (or to V_max) below which the exact hypot decides [-].
_NEAR = 1e-9
#: Relative margin under the largest Vt1² + Vt2² within which hypot is evaluated [-].
_CANDIDATE = 1e-12


@njit(nogil=True, error_model="numpy", inline="always")
def _speed(x, y):  # pragma: no cover - compiled
    """(√(x² + y²), exact): the sliding speed and whether it equals hypot(x, y) for sure."""
    q = x * x + y * y
    if q == 0.0:
        if x == 0.0 and y == 0.0:
            return 0.0, True
        return math.hypot(x, y), True
    if q < 1e-300 or q > 1e300:
        return math.hypot(x, y), True
    return math.sqrt(q), False


@njit(nogil=True, error_model="numpy", inline="always")
def _speed_class(x, y, speed_max):  # pragma: no cover - compiled
    """(speed class 1..5, speed) as speed_classes(hypot(x, y), speed_max)."""
    s, exact = _speed(x, y)
    if speed_max == 0.0:
        if not exact:
            s = math.hypot(x, y)
        return (N_CLASSES if s > 0.0 else 1), s
    r = s * N_CLASSES / speed_max
    if not exact:
        near = abs(r - math.floor(r + 0.5)) <= _NEAR * max(r, 1.0) or \
            abs(s - speed_max) <= _NEAR * speed_max
        if near:
            s = math.hypot(x, y)
            r = s * N_CLASSES / speed_max
    if r >= N_CLASSES:  # V_max and above (no float -> int overflow for huge speeds)
        return N_CLASSES, s
    return max(1, math.floor(r) + 1), s


@njit(cache=True, nogil=True, error_model="numpy")
def _class_pass(t, fn, v1, v2, lo, hi, force_max, speed_max, last, has_last, class_time,
                out):  # pragma: no cover - compiled
    """Contact time per class of the window's samples of one chunk, after ``last``.

    ``last`` = (t, Fn, Vt1, Vt2) of the previous chunk's last window sample when ``has_last``.
    ``out`` receives: status (0, or 1 when time does not increase: index in out[1]), window
    time, time above the maxima, window samples, first time, and the new last sample.
    """
    a = np.searchsorted(t, lo, side="left")
    b = np.searchsorted(t, hi, side="right")
    out[0] = 0.0
    out[2] = 0.0
    out[3] = 0.0
    out[4] = float(b - a) if b > a else 0.0
    if b <= a:
        return
    if has_last:
        if t[a] < last[0]:
            out[0] = 1.0
            out[1] = t[a]
            return
        pt, pf, p1, p2 = last[0], last[1], last[2], last[3]
        start = a + 1 if t[a] == last[0] else a
    else:
        out[5] = t[a]
        pt, pf, p1, p2 = t[a], fn[a], v1[a], v2[a]
        start = a + 1
    window = 0.0
    above = 0.0
    for i in range(start, b):
        dt = t[i] - pt
        if not dt > 0.0:
            out[0] = 1.0
            out[1] = t[i]
            return
        window += dt
        if pf > 0.0:
            x = pf * N_CLASSES / force_max
            f = N_CLASSES if x >= N_CLASSES else max(1, math.ceil(x))
            v, s = _speed_class(p1, p2, speed_max)
            class_time[v - 1, f - 1] += dt
            if pf > force_max or s > speed_max:
                above += dt
        pt, pf, p1, p2 = t[i], fn[i], v1[i], v2[i]
    out[2] = window
    out[3] = above
    out[6], out[7], out[8], out[9] = pt, pf, p1, p2


@njit(cache=True, nogil=True, error_model="numpy")
def _maxima_pass(t, fn, v1, v2, lo, hi, state):  # pragma: no cover - compiled
    """Update state = (F_max, V_max, largest Vt1² + Vt2², samples) over the window's samples."""
    a = np.searchsorted(t, lo, side="left")
    b = np.searchsorted(t, hi, side="right")
    fmax = state[0]
    best = state[1]
    qmax = state[2]
    for i in range(a, b):
        if fn[i] > fmax:
            fmax = fn[i]
        x = v1[i]
        y = v2[i]
        q = x * x + y * y
        if q >= qmax * (1.0 - _CANDIDATE) or q < 1e-300 or q > 1e300:
            h = math.hypot(x, y)
            if h > best:
                best = h
            if q > qmax:
                qmax = q
    state[0] = fmax
    state[1] = best
    state[2] = qmax
    state[3] += max(b - a, 0)


def _window_rows(t, lo, hi):
    return int(np.searchsorted(t, lo, side="left")), int(np.searchsorted(t, hi, side="right"))


def maxima_pass(state: np.ndarray, time, normal_force, vt1, vt2, lo: float, hi: float) -> None:
    """Fold a chunk into ``state`` = [F_max [N], V_max [m/s], max(Vt1² + Vt2²), samples].

    Samples with ``lo <= t <= hi`` count; V_max is ``max(hypot(Vt1, Vt2))`` exactly.

    Examples
    --------
    >>> s = np.array([0.0, 0.0, 0.0, 0.0])
    >>> maxima_pass(s, np.array([0.0, 1.0, 2.0]), np.array([1.0, 4.0, 2.0]),
    ...             np.array([3.0, 0.0, 1.0]), np.array([4.0, 0.0, 0.0]), 0.5, 2.0)
    >>> s[:2].tolist(), int(s[3])
    ([4.0, 1.0], 2)
    """
    t = np.ascontiguousarray(time, dtype=float)
    fn, x, y = (np.ascontiguousarray(a, dtype=float) for a in (normal_force, vt1, vt2))
    if HAVE_NUMBA:
        _maxima_pass(t, fn, x, y, float(lo), float(hi), state)
        return
    a, b = _window_rows(t, lo, hi)  # pragma: no cover - without numba
    if b > a:
        state[0] = max(state[0], float(fn[a:b].max()))
        state[1] = max(state[1], float(np.hypot(x[a:b], y[a:b]).max()))
        state[3] += b - a


def class_pass(class_time: np.ndarray, last: np.ndarray | None, time, normal_force, vt1, vt2,
               lo: float, hi: float, force_max: float, speed_max: float) -> np.ndarray:
    """Add a chunk's contact time per (speed, force) class to ``class_time`` [s] (5×5).

    ``last`` is (t, Fn, Vt1, Vt2) of the previous chunk's last window sample, or None; a chunk
    may repeat it as its first sample. Returns ``[status, t_bad, window time [s], time above the
    maxima [s], window samples, first time [s], t, Fn, Vt1, Vt2 of the last window sample]``
    (status 1: the instants do not increase at ``t_bad``).

    Examples
    --------
    >>> ct = np.zeros((5, 5))
    >>> out = class_pass(ct, None, np.array([0.0, 1.0, 2.0]), np.array([10.0, 0.0, 5.0]),
    ...                  np.zeros(3), np.array([0.0, 0.0, 1.0]), -np.inf, np.inf, 10.0, 1.0)
    >>> float(ct[0, 4]), float(out[2])
    (1.0, 2.0)
    """
    t = np.ascontiguousarray(time, dtype=float)
    fn, x, y = (np.ascontiguousarray(a, dtype=float) for a in (normal_force, vt1, vt2))
    out = np.full(10, np.nan)
    has_last = last is not None
    prev = np.zeros(4) if last is None else np.asarray(last, dtype=float)
    if HAVE_NUMBA:
        _class_pass(t, fn, x, y, float(lo), float(hi), float(force_max), float(speed_max),
                    prev, has_last, class_time, out)
        return out
    return _class_pass_numpy(t, fn, x, y, lo, hi, force_max, speed_max, prev, has_last,
                             class_time, out)  # pragma: no cover - without numba


def _class_pass_numpy(t, fn, x, y, lo, hi, force_max, speed_max, prev, has_last, class_time,
                      out):  # pragma: no cover - exercised only without numba
    a, b = _window_rows(t, lo, hi)
    out[0], out[2], out[3], out[4] = 0.0, 0.0, 0.0, float(max(b - a, 0))
    if b <= a:
        return out
    tt, ff, xx, yy = t[a:b], fn[a:b], x[a:b], y[a:b]
    if has_last:
        if tt[0] < prev[0]:
            out[0], out[1] = 1.0, tt[0]
            return out
        skip = 1 if tt[0] == prev[0] else 0
        tt, ff, xx, yy = (np.concatenate(([p], v[skip:])) for p, v in zip(prev, (tt, ff, xx, yy),
                                                                          strict=True))
    else:
        out[5] = tt[0]
    dt = np.diff(tt)
    if (dt <= 0).any():
        out[0], out[1] = 1.0, tt[1:][dt <= 0][0]
        return out
    s = np.hypot(xx, yy)
    contact = ff[:-1] > 0
    f = np.clip(np.ceil(ff[:-1][contact] * N_CLASSES / force_max), 1, N_CLASSES).astype(int)
    if speed_max == 0:
        v = np.where(s[:-1][contact] > 0, N_CLASSES, 1)
    else:
        v = np.clip(np.floor(s[:-1][contact] * N_CLASSES / speed_max) + 1, 1,
                    N_CLASSES).astype(int)
    np.add.at(class_time, (v - 1, f - 1), dt[contact])
    over = (ff[:-1][contact] > force_max) | (s[:-1][contact] > speed_max)
    out[2], out[3] = float(dt.sum()), float(dt[contact][over].sum())
    out[6:10] = tt[-1], ff[-1], xx[-1], yy[-1]
    return out


class KwuEpriMaxima:
    """Streaming F_max [N] and V_max [m/s] of a window's samples: the KWU-EPRI class ranges when
    FNOR_MAXI / VTAN_MAXI are not given (theory §4: the maxima in the window, free flight
    included). Mergeable (the largest of each).

    Examples
    --------
    >>> m = KwuEpriMaxima(t_start=0.5)
    >>> m.update([0.0, 1.0, 2.0], [9.0, 4.0, 2.0], [5.0, 0.0, 0.6], [0.0, 0.0, 0.8])
    >>> m.force_max, m.speed_max, m.samples
    (4.0, 1.0, 2)
    """

    def __init__(self, *, t_start: float | None = None, t_end: float | None = None) -> None:
        self.t_start = -np.inf if t_start is None else float(t_start)
        self.t_end = np.inf if t_end is None else float(t_end)
        self._state = np.zeros(4)  # F_max, V_max, max(Vt1² + Vt2²), samples

    @property
    def force_max(self) -> float:
        """Largest normal force of the window's samples so far [N] (0 without sample)."""
        return float(self._state[0])

    @property
    def speed_max(self) -> float:
        """Largest sliding speed hypot(Vt1, Vt2) of the window's samples so far [m/s]."""
        return float(self._state[1])

    @property
    def samples(self) -> int:
        """Window samples seen (a sample shared by two chunks counts twice)."""
        return int(self._state[3])

    def update(self, time, normal_force, vt1, vt2) -> None:
        """Fold a chunk in: time [s], normal force [N], sliding velocities [m/s]."""
        maxima_pass(self._state, time, normal_force, vt1, vt2, self.t_start, self.t_end)

    def merge(self, other: KwuEpriMaxima) -> KwuEpriMaxima:
        """Combine with the maxima of another stretch of the same window; returns ``self``."""
        self._state[:3] = np.maximum(self._state[:3], other._state[:3])
        self._state[3] += other._state[3]
        return self
