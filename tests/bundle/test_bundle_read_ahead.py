"""fretwear.bundle.read_ahead.ReadAhead (the summary's pieces read in a thread, issue 28): the
items in order, made ahead in another thread, errors raised where their item is asked for,
the source closed when stopped early; and the bundle end's column-wise shortcuts against
the code they replaced: result_dataset._contact_coordinates (one indexer, was
``info.loc[order, col]`` per column) and summary_quantities.ContactQuantities' neighbours
test of repeated instants (was ``DataFrame.duplicated``)."""

from __future__ import annotations

import threading

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.read_ahead import ReadAhead
from fretwear.bundle.result_dataset import _CONTACT_COORDINATES, _contact_coordinates
from fretwear.bundle.summary_quantities import ContactQuantities


def test_items_in_order_made_in_another_thread():
    made = []

    def items():
        for k in range(7):
            made.append(threading.get_ident())
            yield k

    ahead = ReadAhead(items(), depth=3)
    assert list(ahead) == list(range(7))
    assert made and threading.get_ident() not in made


def test_an_error_is_raised_where_its_item_is_asked_for():
    def items():
        yield 1
        raise OSError("piece 2 unreadable")

    ahead = ReadAhead(items())
    assert next(ahead) == 1
    with pytest.raises(OSError, match="piece 2"):
        next(ahead)
    with pytest.raises(StopIteration):
        next(ahead)


def test_closed_early_the_source_is_closed():
    closed = []

    def items():
        try:
            yield from range(100)
        finally:
            closed.append(True)

    with ReadAhead(items(), depth=2) as ahead:
        assert next(ahead) == 0
    assert closed == [True]
    with pytest.raises(ValueError, match="depth"):
        ReadAhead([], depth=0)


def test_contact_coordinates_are_those_of_loc():
    rng = np.random.default_rng(28)
    ids = [f"c{k}" for k in range(50)]
    info = pd.DataFrame({"contact": ids, "tube_row": rng.integers(1, 9, 50),
                         "tube_column": rng.integers(1, 9, 50).astype(float),
                         "support": ["AVB"] * 49 + [None], "wall_thickness": np.nan,
                         "time_unit": "year"}).set_index("contact")
    for order in (ids, list(rng.permutation(ids)), ids[::3]):
        got = _contact_coordinates(info, order)
        expected = _contact_coordinates_by_loc(info, order)
        assert list(got) == list(expected)
        for name, (dim, values) in got.items():
            assert dim == "contact" and values.dtype == expected[name][1].dtype
            np.testing.assert_array_equal(values, expected[name][1])
    with pytest.raises(KeyError):
        _contact_coordinates(info, ["nobody"])


def _contact_coordinates_by_loc(info, order):
    """The coordinates as _contact_coordinates found them before (a .loc per column)."""
    from fretwear.bundle.result_dataset import _coordinate

    return {col: ("contact", _coordinate(info.loc[order, col] if col in info.columns
                                         else pd.Series([None] * len(order), dtype=object),
                                         col))
            for col in _CONTACT_COORDINATES}


@pytest.mark.parametrize("instants", [[0.0, -0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 2.0],
                                      [1.0, 0.0, 1.0, 1.0], [0.0, np.nan, 1.0, 1.0]])
def test_repeated_instants_are_those_of_duplicated(instants):
    """Two contacts of 4 sector rows each: the global rows kept are the first of each
    (contact, instant) as DataFrame.duplicated says (-0.0 is 0.0), rows in order or not."""
    table = pd.DataFrame({"contact": ["a"] * 4 + ["b"] * 4, "instant": instants * 2,
                          "sector": [1, 2, 1, 2] * 2, "depth_mobile": np.arange(8.0),
                          "power": 1.0})
    per = ContactQuantities(table, given=False)
    repeated = table[["contact", "instant"]].duplicated().to_numpy()
    kept = np.flatnonzero(~repeated)
    expected = kept[np.lexsort((table["instant"].to_numpy()[kept],
                                pd.factorize(table["contact"])[0][kept]))]
    np.testing.assert_array_equal(per.pos, expected)
