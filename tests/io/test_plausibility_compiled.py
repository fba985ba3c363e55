"""The compiled pass of the plausibility checks gives the numbers of the numpy reference.

:func:`fretwear.io._compiled.statistics` (one walk over the channels, used from
``plausibility._KERNEL_SAMPLES`` samples on when numba is installed) against the numpy
expressions of :mod:`fretwear.io.plausibility` (the reference, used below that size and
without numba): the largest squares, the largest force and the contact episodes' durations
equal bit for bit; the median sampling step, which the compiled path computes only when at
least half the steps exceed the limit, gives the same decision and, when computed, the same
value; and every message of :func:`check_plausibility` is the same on both paths.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.io import plausibility
from fretwear.io.plausibility import THRESHOLDS, check_plausibility

pytest.importorskip("numba")

LIMIT = THRESHOLDS["time_step"].limit


def _both(history, monkeypatch):
    """(compiled, numpy) results of ``plausibility._statistics``."""
    monkeypatch.setattr(plausibility, "_KERNEL_SAMPLES", 0)
    compiled = plausibility._statistics(history)
    monkeypatch.setattr(plausibility, "_KERNEL_SAMPLES", 1 << 62)
    return compiled, plausibility._statistics(history)


def _history(seed: int, n: int, *, radial: bool = True, scale: float = 1.0,
             force_at_ends: tuple[bool, bool] = (False, False)) -> ContactHistory:
    """Random impacts: a force of half-sine bursts and free flight, noisy velocities, an
    irregular time step; the force ``> 0`` at the first or last sample if asked."""
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.5e-5, 1.5e-5, n))
    fn = np.maximum(rng.normal(0.0, 20.0, n), 0.0) * (rng.random(n) < 0.3)
    fn[0] = 3.0 if force_at_ends[0] else 0.0
    fn[-1] = 4.0 if force_at_ends[1] else 0.0
    v = rng.normal(0.0, 0.05 * scale, (2, n))
    d = rng.normal(0.0, 1e-4 * scale, (2, n))
    return ContactHistory(time=t, normal_force=fn, vt1=v[0], vt2=v[1],
                          dy=d[0] if radial else None, dz=d[1] if radial else None)


@pytest.mark.parametrize("seed, n, radial, scale, ends", [
    (1, 20_000, True, 1.0, (False, False)),
    (2, 20_001, False, 1.0, (True, False)),
    (3, 5_000, True, 1e3, (False, True)),
    (4, 2, True, 1.0, (True, True)),
    (5, 3, False, 1e203, (True, False)),   # squares overflow: inf, numpy.hypot after
])
def test_compiled_statistics_equal_the_reference(monkeypatch, seed, n, radial, scale, ends):
    history = _history(seed, n, radial=radial, scale=scale, force_at_ends=ends)
    (s2, r2, fmax, step, durations), (s2_, r2_, fmax_, step_, durations_) = _both(
        history, monkeypatch)
    assert (s2, r2, fmax) == (s2_, r2_, fmax_)
    assert durations.dtype == durations_.dtype and np.array_equal(durations, durations_)
    assert (step > LIMIT) == (step_ > LIMIT)
    assert plausibility._root(s2, history.vt1, history.vt2) == plausibility._root(
        s2_, history.vt1, history.vt2)
    if scale > 1e200:
        assert s2 == np.inf and np.isfinite(plausibility._root(s2, history.vt1, history.vt2))


@pytest.mark.parametrize("steps", [10, 11])  # an even and an odd number of steps
@pytest.mark.parametrize("above", [-1, 0, 1])  # steps above the limit: half - 1, half, half + 1
@pytest.mark.parametrize("below, high", [(0.1, 10.0), (0.9, 1.05)])
def test_the_median_step_decision_at_the_half(monkeypatch, steps, above, below, high):
    """m steps of which m // 2 + ``above`` exceed the limit (value ``high`` × limit, the others
    ``below`` × limit), shuffled: the compiled path warns exactly when the median of numpy
    exceeds the limit. With m even and m / 2 above, the median is the mean of one step below
    and one above: 5.05 × limit (warns) or 0.975 × limit (does not)."""
    m = steps
    k = m // 2 + above
    dt = np.array([high * LIMIT] * k + [below * LIMIT] * (m - k))
    np.random.default_rng(m + k).shuffle(dt)
    t = np.concatenate([[0.0], np.cumsum(dt)])
    history = ContactHistory(time=t, normal_force=np.ones(m + 1), vt1=np.zeros(m + 1),
                             vt2=np.zeros(m + 1))
    (*_, step, _), (*_, step_, _) = _both(history, monkeypatch)
    median = float(np.median(np.diff(t)))
    assert step_ == median
    assert (step > LIMIT) == (median > LIMIT)
    if k >= m // 2:  # computed, not bounded
        assert step == median


@pytest.mark.parametrize("factors", [
    {},                                                   # plausible: no message
    {"vt1": 1e3, "vt2": 1e3, "dy": 1e3, "dz": 1e3},       # mm and mm/s
    {"time": 1e3, "vt1": 1e-3, "vt2": 1e-3},              # ms: step and impact duration
    {"normal_force": 1e5},                                # mN
    {"normal_force": 1e-4},                               # kN
])
def test_every_message_is_the_same_on_both_paths(monkeypatch, factors):
    base = _history(7, 20_000)
    history = base.replace(**{k: getattr(base, k) * f for k, f in factors.items()})
    found = []
    for size in (0, 1 << 62):
        monkeypatch.setattr(plausibility, "_KERNEL_SAMPLES", size)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            messages = check_plausibility(history)
        assert [str(w.message) for w in caught] == messages
        found.append(messages)
    assert found[0] == found[1]
    assert bool(found[0]) == bool(factors)
