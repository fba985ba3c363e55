"""KWU-EPRI streaming passes (issue 13): the compiled class and maxima passes give exactly what
the numpy implementation gives (sliding speed = numpy.hypot), on adversarial chunks: speeds and
forces exactly on the class bounds, speeds whose √(x² + y²) and hypot differ, tiny and huge
velocities, windows between and on samples, chunks with and without a shared sample."""

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.laws import KwuEpriAccumulator, KwuEpriMaxima, kwu_epri_statistics


def _adversarial(rng, n, fmax=50.0, vmax=0.4):
    t = np.cumsum(rng.uniform(0.5, 1.5, n)) * 1e-4
    fn = np.maximum(rng.normal(10.0, 20.0, n), 0.0)
    v1, v2 = rng.normal(0.0, 0.1, n), rng.normal(0.0, 0.1, n)
    k = rng.integers(0, 6, n)
    on = rng.uniform(size=n) < 0.2  # forces exactly on a force-class bound f·F_max/5
    fn[on] = k[on] * fmax / 5
    on = rng.uniform(size=n) < 0.2  # speeds on a speed-class bound, along an axis
    v1[on], v2[on] = k[on] * vmax / 5, 0.0
    on = rng.uniform(size=n) < 0.2  # on a bound with both components (3-4-5 triangles)
    v1[on], v2[on] = 0.6 * k[on] * vmax / 5, -0.8 * k[on] * vmax / 5
    v1[::97], v2[::97] = 1e-200, 3e-200  # √(x²+y²) underflows
    v1[::89], v2[::89] = 1e200, -1e200   # √(x²+y²) overflows
    fn[::53] = fmax
    return t, fn, v1, v2


def _split(n, rng, shared):
    cuts = np.sort(rng.choice(np.arange(2, n - 2), 6, replace=False))
    bounds = [0, *cuts, n]
    return [(a - (1 if shared and a else 0), b) for a, b in zip(bounds[:-1], bounds[1:],
                                                                    strict=True)]


@pytest.mark.parametrize("shared", [True, False])
@pytest.mark.parametrize("window", [(None, None), (0.05, 0.4)])
def test_class_pass_equals_numpy_hypot_counts(shared, window):
    rng = np.random.default_rng(4)
    t, fn, v1, v2 = _adversarial(rng, 5000)
    lo, hi = window
    if lo is not None:
        lo, hi = t[0] + lo * (t[-1] - t[0]), t[700]  # the end on a sample
    ref = KwuEpriAccumulator(50.0, 0.4, t_start=lo, t_end=hi)
    fast = KwuEpriAccumulator(50.0, 0.4, t_start=lo, t_end=hi)
    for a, b in _split(t.size, rng, shared):
        ref.update(t[a:b], fn[a:b], np.hypot(v1[a:b], v2[a:b]))
        fast.update_velocities(t[a:b], fn[a:b], v1[a:b], v2[a:b])
    np.testing.assert_array_equal(fast.class_time, ref.class_time)  # same sums, same order
    assert fast.time_above_max == pytest.approx(ref.time_above_max, rel=1e-12)
    assert fast.window_time == pytest.approx(ref.window_time, rel=1e-12)
    assert (fast.samples, fast.first_time, fast._last) == (ref.samples, ref.first_time, ref._last)
    assert ref.time_above_max > 0


def test_maxima_equal_numpy_hypot_maxima():
    rng = np.random.default_rng(8)
    t, fn, v1, v2 = _adversarial(rng, 8000)
    v1[::89], v2[::89] = 0.3, 0.4  # no overflow here: the largest speed is a 3-4-5 hypot
    v1[4000], v2[4000] = 0.5 * (1 + 1e-15), 0.5  # near-ties of the largest speed
    v1[4001], v2[4001] = 0.5, 0.5 * (1 + 2e-16)
    m = KwuEpriMaxima(t_start=t[10], t_end=t[7000])
    for a, b in _split(t.size, rng, True):
        m.update(t[a:b], fn[a:b], v1[a:b], v2[a:b])
    sel = slice(10, 7001)
    assert m.force_max == float(fn[sel].max())
    assert m.speed_max == float(np.hypot(v1[sel], v2[sel]).max())


def test_accumulated_statistics_equal_kwu_epri_statistics():
    # the default maxima, then the counts: the two passes of the streaming path give the
    # statistics of the whole history (kwu_epri_statistics), every field
    rng = np.random.default_rng(1)
    t, fn, v1, v2 = _adversarial(rng, 4000)
    v1[::89], v2[::89] = 0.1, 0.2
    h = ContactHistory(time=t, normal_force=fn, vt1=v1, vt2=v2)
    ref = kwu_epri_statistics(h, t_start=t[5])
    m = KwuEpriMaxima(t_start=t[5])
    m.update(t, fn, v1, v2)
    acc = KwuEpriAccumulator(m.force_max, m.speed_max, t_start=t[5])
    for a, b in _split(t.size, rng, False):
        acc.update_velocities(t[a:b], fn[a:b], v1[a:b], v2[a:b])
    got = acc.result()
    np.testing.assert_array_equal(got.class_time, ref.class_time)
    assert got.intensity == pytest.approx(ref.intensity, rel=1e-12)
    assert (got.force_max, got.speed_max, got.t_start, got.t_end) == (
        ref.force_max, ref.speed_max, ref.t_start, ref.t_end)
