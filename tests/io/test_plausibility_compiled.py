"""The compiled pass of the plausibility checks gives the numbers of the numpy reference.

:func:`fretwear.io._compiled.statistics` (four loops over the channels, used from
``plausibility._KERNEL_SAMPLES`` samples on when numba is installed, at any size once imported)
against the numpy expressions of :mod:`fretwear.io.plausibility` (the reference, used below that
size before the module is imported, and without numba): the largest squares, the largest force
and the contact episodes' durations equal bit for bit (a largest force of zero may be -0.0 on
one path and 0.0 on the other when the forces mix both zeros: no check can tell them apart); the
median sampling step, which the compiled path computes only when at least half the steps exceed
the limit, gives the same decision and, when computed, the same value; every message of
:func:`check_plausibility` is the same on both paths.
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
    """(compiled, numpy) results of ``plausibility._statistics``; the compiled kernel is
    checked to have run for the first and not for the second."""
    from fretwear.io import _compiled

    calls = []
    kernel = _compiled.statistics
    monkeypatch.setattr(_compiled, "statistics", lambda *a: calls.append(1) or kernel(*a))
    monkeypatch.setattr(plausibility, "_KERNEL", False)
    monkeypatch.setattr(plausibility, "_KERNEL_SAMPLES", 0)
    compiled = plausibility._statistics(history)
    assert calls == [1]
    monkeypatch.setattr(plausibility, "_KERNEL", None)  # numpy at any size (the reference)
    reference = plausibility._statistics(history)
    assert calls == [1]
    return compiled, reference


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
    assert (s2, r2, fmax) == (s2_, r2_, fmax_)  # a zero largest force may differ in sign
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
    assert (step > LIMIT) == (median > LIMIT) == (step_ > LIMIT)
    if k >= m // 2:  # computed, not bounded
        assert step == median


@pytest.mark.parametrize("factors", [
    {},                                                   # plausible: no message
    {"vt1": 1e3, "vt2": 1e3, "dy": 1e3, "dz": 1e3},       # mm and mm/s
    {"time": 1e3, "vt1": 1e-3, "vt2": 1e-3},              # ms: the sampling step
    {"time": 1e5, "vt1": 1e-5, "vt2": 1e-5},              # step and impact duration
    {"normal_force": 1e5},                                # mN
    {"normal_force": 1e-4},                               # kN
])
def test_every_message_is_the_same_on_both_paths(monkeypatch, factors):
    base = _history(7, 20_000)
    history = base.replace(**{k: getattr(base, k) * f for k, f in factors.items()})
    found = []
    for kernel in (False, None):  # compiled (imported at the first use), then numpy
        monkeypatch.setattr(plausibility, "_KERNEL_SAMPLES", 0)
        monkeypatch.setattr(plausibility, "_KERNEL", kernel)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            messages = check_plausibility(history)
        assert [str(w.message) for w in caught] == messages
        found.append(messages)
    assert found[0] == found[1]
    # (the synthetic contacts last about one sample: said by ResolutionWarning, not a unit)
    units = [m for m in found[0] if "samples on average" not in m]
    assert bool(units) == bool(factors)
    if factors.get("time") == 1e5:
        assert any("mean impact duration" in m for m in found[0])


def test_each_square_as_numpy_computes_it(monkeypatch):
    """No fused multiply-add: on 300 histories of 2 samples, the largest ``a*a + b*b`` is
    numpy's bit for bit (a fused product would differ in about one value in eight)."""
    rng = np.random.default_rng(11)
    for _ in range(300):
        v, d = rng.normal(0.0, 1.0, (2, 2)), rng.normal(0.0, 1e-3, (2, 2))
        history = ContactHistory(time=[0.0, 1e-5], normal_force=[0.0, 1.0], vt1=v[0],
                                 vt2=v[1], dy=d[0], dz=d[1])
        (s2, r2, *_), _ = _both(history, monkeypatch)
        assert s2 == float((v[0] * v[0] + v[1] * v[1]).max())
        assert r2 == float((d[0] * d[0] + d[1] * d[1]).max())


@pytest.mark.parametrize("force", [
    [0, 5, 5, 0, 2, 0, 0, 3, 0],   # an episode from the second sample on
    [4, 0, 1, 0, 1, 1, 1, 0, 6],   # open at both ends: dropped
    [0, 1, 0, 1, 0, 1, 0, 1, 0],   # one-sample episodes
    [0, 0, 0, 0, 0, 0, 0, 0, 0],   # free flight
    [1, 1, 1, 1, 1, 1, 1, 1, 1],   # never ends
])
def test_contact_episodes_as_impact_durations_finds_them(monkeypatch, force):
    t = np.array([0.0, 1.0, 3.0, 4.0, 7.0, 8.0, 10.0, 13.0, 14.0]) * 1e-4
    history = ContactHistory(time=t, normal_force=np.array(force, dtype=float),
                             vt1=np.zeros(9), vt2=np.zeros(9))
    (*_, durations), _ = _both(history, monkeypatch)
    expected = plausibility.impact_durations(t, np.array(force, dtype=float))
    assert np.array_equal(durations, expected)
    if force[:4] == [0, 5, 5, 0]:
        assert durations.tolist() == [t[3] - t[1], t[5] - t[4], t[8] - t[7]]


def test_a_short_history_is_compiled_once_the_module_is_imported(monkeypatch):
    """Below ``_KERNEL_SAMPLES`` the numpy expressions run while the compiled module is not
    imported (reading a short history alone does not import numba); once it is (a streamed
    block's checks import it), a 1 000-sample history takes the compiled pass too (issue 28)."""
    import sys

    from fretwear.io import _compiled

    monkeypatch.setattr(plausibility, "_KERNEL", False)
    monkeypatch.delitem(sys.modules, "fretwear.io._compiled")
    assert plausibility._kernel_for(1000) is None
    assert plausibility._KERNEL is False  # nothing imported
    monkeypatch.setitem(sys.modules, "fretwear.io._compiled", _compiled)
    assert plausibility._kernel_for(1000) is _compiled
    monkeypatch.setattr(plausibility, "_KERNEL", None)  # no numba: numpy at every size
    assert plausibility._kernel_for(1 << 20) is None
