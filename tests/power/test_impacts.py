"""Impacts one by one (fretwear.power.impacts): the same impacts as the contact statistics, and
values computed by hand.

Independent computations: contact_statistics (the streaming reduction) gives the count, the
mean and largest durations, the mean peak and the contact time of the same impacts; a triangle
pulse of height F over a base w has ∫Fn dt = F·w/2 and crosses F_s at F_s/F of its rise.
"""

from __future__ import annotations

import numpy as np
import pytest

from fretwear import ContactHistory
from fretwear.power import channel_statistics, contact_statistics, impacts


@pytest.mark.parametrize("threshold, rest, window", [
    (0.0, 0.0, (None, None)), (2.0, 0.0, (None, None)), (0.0, 0.15, (None, None)),
    (1.0, 0.1, (3.003, 28.98))])
def test_impacts_are_the_contact_statistics_impacts(threshold, rest, window):
    rng = np.random.default_rng(3)
    n = 600
    t = np.cumsum(rng.uniform(0.01, 0.1, n))
    fn = np.maximum(0, rng.normal(0, 1, n)) * 10
    h = ContactHistory(time=t, normal_force=fn, vt1=np.ones(n), vt2=np.zeros(n))
    lo, hi = window
    s = contact_statistics(h, t_start=lo, t_end=hi, force_threshold=threshold,
                           minimum_rest_time=rest)
    table = impacts(h, t_start=lo, t_end=hi, force_threshold=threshold, minimum_rest_time=rest)
    assert len(table) == s.impact_count > 10
    assert table["duration"].mean() == pytest.approx(s.impact_duration_mean, rel=1e-12)
    assert table["duration"].max() == pytest.approx(s.impact_duration_max, rel=1e-12)
    assert table["peak_force"].mean() == pytest.approx(s.impact_peak_force_mean, rel=1e-12)
    assert table["contact_time"].sum() == pytest.approx(s.contact_time, rel=1e-12)
    assert (table["episodes"] >= 1).all() and (table["end"] >= table["start"]).all()


def test_triangle_pulses_by_hand():
    # two triangles of height 8 N and 4 N, base 2 s, 1 s apart; vn = 0.5 m/s constant
    t = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    fn = np.array([0.0, 8.0, 0.0, 0.0, 4.0, 0.0, 0.0])
    h = ContactHistory(time=t, normal_force=fn, vt1=np.ones(7), vt2=np.zeros(7),
                       vn=np.full(7, 0.5))
    table = impacts(h)
    assert table["impulse"].tolist() == [8.0, 4.0]
    assert table["peak_time"].tolist() == [1.0, 4.0]
    assert table["impact_velocity"].tolist() == [0.5, 0.5]
    # threshold 2 N: crossings at 2/8 and 2/4 of the rise and fall
    table = impacts(h, force_threshold=2.0)
    assert table["start"].tolist() == [0.25, 3.5] and table["end"].tolist() == [1.75, 4.5]
    # impulse over the contact part: trapezoids (2 → 8 → 2 over 1.5 s; 2 → 4 → 2 over 1 s)
    assert table["impulse"].tolist() == pytest.approx([7.5, 3.0], rel=1e-14)
    # a rest of 1.75 s: one impact of two episodes (Code_Aster's rebounds)
    one = impacts(h, force_threshold=2.0, minimum_rest_time=2.0)
    assert one["episodes"].tolist() == [2] and one["duration"].tolist() == [4.25]
    assert one["contact_time"].tolist() == [2.5]
    # no contact: an empty table with the columns
    empty = impacts(h, force_threshold=10.0)
    assert len(empty) == 0 and "impulse" in empty.columns


def test_channel_statistics_blocks():
    # x = t on [0, 2]: mean 1, mean square 4/3; two blocks: means 0.5 and 1.5, variances 1/12
    s = channel_statistics([0.0, 2.0], [0.0, 2.0], blocks=2)
    assert s["mean"] == pytest.approx(1.0) and s["rms"] == pytest.approx(np.sqrt(4 / 3))
    assert s["std"] == pytest.approx(np.sqrt(1 / 12))
    # the window cuts the linear pieces exactly
    w = channel_statistics([0.0, 2.0], [0.0, 2.0], t_start=0.5, t_end=1.5)
    assert w["mean"] == pytest.approx(1.0) and w["min"] == 0.5 and w["max"] == 1.5
