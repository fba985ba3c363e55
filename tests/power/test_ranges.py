"""Wear power at the ends of the floating-point range (issue 15): no silent inf, no lost speed.

The property: the wear power equals the trapezoid rule of Fn·‖Vt‖ computed independently with
``numpy.hypot`` (theory §2), for random histories whose velocities include 8e-270 and 1e160 m/s
(whose squares underflow or overflow: before, √(Vt1²+Vt2²) gave 0 or inf and the total differed
from the trapezoid sum: the failing case was vt = 8.4e-270 m/s, P = 0 instead of 8.4e-270 W).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fretwear.errors import HistoryError, UnitsWarning
from fretwear.history import ContactHistory
from fretwear.io import write_history
from fretwear.power import wear_power

SPEEDS = st.one_of(st.floats(-1e3, 1e3), st.sampled_from([8e-270, -3e-200, 1e160, -2e170,
                                                          1e-310, 0.0]))


@st.composite
def histories(draw):
    n = draw(st.integers(2, 30))
    dt = draw(arrays(float, n - 1, elements=st.floats(1e-6, 5.0)))
    t = draw(st.sampled_from([0.0, -3.0, 1e6])) + np.concatenate([[0.0], np.cumsum(dt)])
    fn = draw(arrays(float, n, elements=st.one_of(st.floats(0.0, 1e3), st.just(0.0))))
    tiny = draw(st.booleans())  # every speed tiny, or a mix of ordinary and extreme speeds
    values = st.sampled_from([8e-270, -3e-200, 0.0]) if tiny else SPEEDS
    return (t, fn, draw(arrays(float, n, elements=values)),
            draw(arrays(float, n, elements=values)))


# random forces on 2 to 30 samples split in up to 3 blocks: the block powers spread far beyond
# the stationarity threshold, which is expected here (the property is about the float range)
@pytest.mark.filterwarnings("ignore::fretwear.errors.StationarityWarning")
@settings(max_examples=150, deadline=None, derandomize=True, database=None,
          suppress_health_check=list(HealthCheck))
@given(h=histories(), backend=st.sampled_from(["numba", "numpy"]), blocks=st.integers(1, 3))
def test_power_is_the_trapezoid_sum_over_the_whole_float_range(h, backend, blocks):
    t, fn, v1, v2 = h
    if not np.all(np.diff(t) > 0):
        return
    g = fn * np.hypot(v1, v2)
    if not np.isfinite(g).all():
        return
    expected = np.sum(np.diff(t) * (g[1:] + g[:-1]) / 2) / (t[-1] - t[0])
    if not np.isfinite(expected):
        return
    r = wear_power(ContactHistory(time=t, normal_force=fn, vt1=v1, vt2=v2), blocks=blocks,
                   backend=backend)
    # a speed component below 1e-154 m/s next to ordinary ones, or below 5e-305 of the largest
    # (here 2e170 m/s), counts as 0 (fretwear.power.ranges): an absolute error under
    # 1e-130 m/s × max Fn
    assert r.total == pytest.approx(expected, rel=1e-9, abs=1e-130 * max(fn.max(), 1.0))
    assert r.blocks.mean() == pytest.approx(r.total, rel=1e-9, abs=1e-300)


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_failing_case_found_by_the_property(backend):
    h = ContactHistory(time=[0.0, 1.0], normal_force=[1.0, 1.0], vt1=[0.0, 0.0],
                       vt2=[8.38677994e-270, 8.38677994e-270])
    assert wear_power(h, backend=backend).total == 8.38677994e-270
    h = ContactHistory(time=[0.0, 1.0], normal_force=[2.0, 2.0], vt1=[1e160, 1e160],
                       vt2=[1e160, 1e160])
    assert wear_power(h, backend=backend).total == pytest.approx(2 * np.hypot(1e160, 1e160))


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_overflowing_products_name_the_instant_and_values(backend):
    h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[0.0, 1e200, 0.0],
                       vt1=[0.0, 1e200, 0.0], vt2=[0.0, 0.0, 0.0], name="N12")
    with pytest.raises(HistoryError, match=r"'N12': the wear power overflows at t = 1.0 s: "
                                           r"normal_force 1e\+200 N × sliding speed 1e\+200 m/s"
                                           r".*check the units"):
        wear_power(h, backend=backend)
    h = h.replace(vt1=[0.0, 0.1, 0.0])  # Fn·Vt fits, Fn² of the statistics does not
    with pytest.raises(HistoryError, match=r"channel 'normal_force' = 1e\+200 N at t = 1.0 s: "
                                           r"its square \(force statistics\)"):
        wear_power(h, backend=backend)


def test_overflow_is_reported_when_streaming_a_file(tmp_path):
    t = np.linspace(0.0, 1e-3, 50)  # a plausible sampling step: only Fn and Vt are implausible
    fn = np.full(50, 1e200)
    path = write_history(ContactHistory(time=t, normal_force=fn, vt1=fn, vt2=0 * t, name="N1"),
                         tmp_path / "h.csv")
    with pytest.warns(UnitsWarning) as seen, pytest.raises(
            HistoryError, match=r"wear power overflows at t = 0.0 s"):
        wear_power(path, chunk_size=7)
    # the streamed file's values are also flagged as a likely unit mistake, once each
    assert sorted(str(w.message).split(": ")[2].split(" (")[0] for w in seen) == [
        "largest normal force 1e+200 N", "largest sliding speed ‖Vt‖ 1e+200 m/s"]
