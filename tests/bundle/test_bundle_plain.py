"""A record's per-contact values made one object when equal (``bundle.plain.interned``): equal
means the same JSON text (``json.dumps``, the independent reference), so a value is never
replaced by one that the part's JSON would write differently."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from fretwear.bundle import plain as p


@pytest.mark.parametrize("a, b", [
    ([0.0, 90.0], [-0.0, 90.0]),
    ([1, 2], [1.0, 2.0]),
    ({"K": 1e-15, "source": "db"}, {"source": "db", "K": 1e-15}),
    ({"K": 1e-15}, {"K": 1.0000000000000002e-15}),
    ([True], [1]),
    ([None, "x"], [None, "y"]),
])
def test_values_written_apart_stay_apart(a, b):
    assert json.dumps(a) != json.dumps(b)
    first = p.interned("k-apart", a)
    second = p.interned("k-apart", b)
    assert first is not second and json.dumps(second) == json.dumps(b)


def test_equal_values_become_one_object_and_keys_are_kept_apart():
    a = p.interned("sector_edges", [-180.0, 0.0, 180.0])
    b = p.interned("sector_edges", [-180.0, 0.0, 180.0])
    c = p.interned("other", [-180.0, 0.0, 180.0])
    assert a is b and c is not a and c == a


def test_nested_or_non_plain_values_are_returned_as_given():
    nested = [[1.0], [2.0]]
    assert p.interned("k-nested", nested) is nested
    assert p.interned("k-none", None) is None


def test_the_memo_is_bounded_and_stays_right_past_its_bound():
    values = [[float(i)] for i in range(p.INTERNED_MAX + 10)]
    out = [p.interned("k-bound", v) for v in values]
    assert [json.dumps(o) for o in out] == [json.dumps(v) for v in values]
    assert len(p._VALUES) <= p.INTERNED_MAX


@pytest.mark.parametrize("array", [
    np.array([0.25, -0.0, np.nan, np.inf, -np.inf, 1e308]),
    np.array([1.5, np.nan], dtype=np.float32),
    np.array([], dtype=float),
    np.array([[1.0, np.nan], [np.inf, 2.0]]),  # 2-d: nested lists
    np.array([1, 2]),  # integers: as they are
])
def test_arrays_are_made_plain_as_their_values_one_by_one(array):
    # the reference: each value made plain by itself (numpy's scalars as Python's, a number
    # not finite None), nested as tolist() nests them; compared as JSON text (signs of zeros)
    def each(v):
        if isinstance(v, np.ndarray):  # a row of a 2-d array
            return [each(x) for x in v]
        v = v.item() if isinstance(v, np.generic) else v
        return None if isinstance(v, float) and not math.isfinite(v) else v

    reference = each(array)
    got = p.plain(array)
    assert json.dumps(got) == json.dumps(reference)
    if array.ndim == 1:  # Python's numbers, not numpy's
        assert [type(v) for v in got] == [type(v) for v in reference]


def test_a_long_double_array_goes_the_general_way():
    """A 1-d array of long doubles is not taken by the float array's shortcut (its tolist()
    gives numpy long doubles, not Python floats): each value plain as on its own, text JSON
    can write."""
    values = np.array([1.5, np.inf], dtype=np.longdouble)
    assert p.plain(values) == [p.plain(v) for v in values]
    json.dumps(p.plain(values))
