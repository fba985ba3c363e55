"""finalize_statistics against numpy's reductions of the same block sums, one block or
several.

The window's sums are numpy's ``block_stats.sum(axis=0)`` (one row: a -0.0 comes out +0.0),
the block arrays numpy's divisions by T/B; no RuntimeWarning for a NaN or an infinite sum, the
overflow of a division by a tiny block warned as numpy warns it.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from fretwear.power.statistics import GROUP_FIELDS, finalize_statistics

# contact time, force integral, force² integral, force·dt, force²·dt, sliding distance
ROWS = [
    [[1.0, 2.0, 4.0, 2.0, 4.0, 0.5]],
    [[-0.0, 0.0, -0.0, 0.0, 0.0, -0.0]],  # a -0.0 in every sum numpy makes +0.0
    [[0.25, 3.0, 9.5, 1.5, 7.25, 1e-3], [0.5, 1.0, 2.0, 0.75, 1.25, 2e-3]],  # two blocks
    [[math.nan, 1.0, 2.0, math.inf, 1.0, 0.0]],  # not finite: numbers only, no warning
]


@pytest.mark.parametrize("rows", ROWS)
def test_window_sums_are_numpys(rows):
    stats = np.array(rows)
    T = 2.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = finalize_statistics(stats, np.zeros(len(GROUP_FIELDS)), 3.0, T, 0.0, 0.0)
    tot = stats.sum(axis=0)  # numpy's, the reference
    tb = T / stats.shape[0]

    def same(a, b):  # bit for bit, signs of zeros and NaNs included
        return np.array_equal(np.asarray(a, dtype=float).view(np.uint64),
                              np.asarray(b, dtype=float).view(np.uint64))

    assert same(s.contact_time, tot[0]) and same(s.sliding_distance, tot[5])
    assert same(s.contact_fraction, tot[0] / T) and same(s.force_mean, tot[3] / T)
    assert same(s.force_rms, math.sqrt(max(float(tot[4]), 0.0) / T))
    if tot[0] > 0:
        assert same(s.force_mean_contact, tot[1] / tot[0])
    assert same(s.block_contact_fraction, stats[:, 0] / tb)
    assert same(s.block_force_mean, stats[:, 3] / tb)
    assert same(s.block_sliding_distance, stats[:, 5])


def test_division_by_a_tiny_block_still_warns_its_overflow():
    stats = np.array([[1e300, 0.0, 0.0, 0.0, 0.0, 0.0]])
    tiny = 1e-10
    with pytest.warns(RuntimeWarning, match="overflow"):
        expected = np.array([1e300]) / tiny
    with pytest.warns(RuntimeWarning, match="overflow"):
        s = finalize_statistics(stats, np.zeros(len(GROUP_FIELDS)), 1.0, tiny, 0.0, 0.0)
    assert s.block_contact_fraction.tolist() == expected.tolist() == [math.inf]
