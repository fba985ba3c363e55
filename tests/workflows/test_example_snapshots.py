"""Every shipped example gives bit-identical results to its stored snapshot.

The snapshots (``example_tables/*.csv``, ``%.17g``: exact float64) were written by the code
before the layers refactor (issue 10); see ``example_snapshots.py``. Columns added later
(e.g. depth as a fraction of the wall) are not in the snapshots and are not compared; every
snapshot column must still exist with the same values, bit for bit.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from example_snapshots import SNAPSHOTS, compute  # noqa: E402


@pytest.fixture(scope="module")
def current():
    return compute()


def test_every_snapshot_is_computed(current):
    stored = {p.stem for p in SNAPSHOTS.glob("*.csv")}
    assert stored == set(current)


@pytest.mark.parametrize("name", sorted(p.stem for p in SNAPSHOTS.glob("*.csv")))
def test_bit_identical(current, name):
    stored = pd.read_csv(SNAPSHOTS / f"{name}.csv")
    frame = current[name]
    missing = [c for c in stored.columns if c not in frame.columns]
    assert not missing, f"{name}: columns gone: {missing}"
    assert len(frame) == len(stored)
    for column in stored.columns:
        a = np.asarray(frame[column], dtype=float)
        b = np.asarray(stored[column], dtype=float)
        # bit for bit: equal values and NaN at the same places
        assert np.array_equal(a, b, equal_nan=True), f"{name}.{column} differs"
