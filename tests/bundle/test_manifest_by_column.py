"""A table manifest's rows made column by column (``manifest._rows_from_frame``) equal the rows
made cell by cell from ``DataFrame.to_dict("records")`` through ``manifest._cells`` (the
per-cell reading the Dataset manifests still use, and the table manifests used before): the
independent computation here. Frames of every kind of column a manifest meets: integers,
floats with NaN and integral values, booleans, text with blanks, None and pd.NA, numpy scalars
in an object column, case-key overrides (numbers, paths), a list where one value is wanted."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle import manifest as m
from fretwear.bundle.columns import column_meanings
from fretwear.errors import InputError


def by_cells(frame: pd.DataFrame, directory: Path):
    meaning = column_meanings([str(c) for c in frame.columns], "t")
    out = []
    for record in frame.to_dict("records"):
        cid = str(m._identity_value(record["contact"]))
        identity, overrides, labels = m._cells(
            ((str(c), meaning[str(c)], v) for c, v in record.items()), cid, "t", directory)
        node = record.get("node")
        identity["node"] = None if m.empty_cell(node) else str(m._identity_value(node))
        out.append((cid, identity, overrides, labels))
    return out


def by_columns(frame: pd.DataFrame, directory: Path):
    return [(r.contact, r.identity, r.overrides, r.labels)
            for r in m._rows_from_frame(frame, "t", directory)]


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list | tuple) and isinstance(b, list | tuple):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    return type(a) is type(b) and a == b


FRAMES = {
    "numbers": pd.DataFrame({"contact": [1, 2, 3], "history": ["a.parquet"] * 3,
                             "tube_row": [1.0, np.nan, 2.5], "tube_column": [4, 5, 6],
                             "support": [True, False, True]}),
    "text": pd.DataFrame({"contact": ["A", "B", "C"], "history": ["a.csv", "", None],
                          "support": ["AVB1", "  ", None], "node": ["N1", np.nan, "N3"],
                          "tube_row": pd.array([1, pd.NA, 3], dtype="Int64")}),
    "overrides": pd.DataFrame({"contact": ["A", "B"], "history": ["a.csv", "b.csv"],
                               "mobile_radius_m": [0.0095, np.nan],
                               "wall_thickness_m": [1.09e-3, 1.2e-3],
                               "restart.table": ["prev.csv", None]}),
    "object numbers": pd.DataFrame({"contact": ["A", "B"], "history": ["a.csv", "b.csv"],
                                    "tube_row": pd.Series([np.int64(3), np.float64(4.0)],
                                                          dtype=object)}),
}


@pytest.mark.parametrize("name", list(FRAMES))
def test_rows_by_column_equal_rows_by_cell(name, tmp_path):
    frame = FRAMES[name]
    before = frame.copy(deep=True)
    got, want = by_columns(frame, tmp_path), by_cells(frame, tmp_path)
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert same(list(g), list(w)), (g, w)
    pd.testing.assert_frame_equal(frame, before)  # the user's frame untouched


def test_a_list_where_one_value_is_wanted_is_the_same_error(tmp_path):
    frame = pd.DataFrame({"contact": ["A", "B"], "history": ["a.csv", "b.csv"],
                          "support": ["AVB1", ["x", "y"]]})
    with pytest.raises(InputError) as by_column:
        m._rows_from_frame(frame, "t", tmp_path)
    with pytest.raises(InputError) as by_cell:
        by_cells(frame, tmp_path)
    assert str(by_column.value) == str(by_cell.value)
    assert "contact 'B'" in str(by_column.value) and "support" in str(by_column.value)


def test_columns_named_twice_read_as_to_dict_reads_them(tmp_path):
    frame = pd.DataFrame([["A", "a.csv", 1, 2]],
                         columns=["contact", "history", "tube_row", "tube_row"])
    with pytest.warns(UserWarning, match="not unique"):
        rows = m._rows_from_frame(frame, "t", tmp_path)
    assert rows[0].identity["tube_row"] == 2  # the last, as to_dict("records") kept it
