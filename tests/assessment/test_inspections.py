"""The field inspection reader (issue 26, point 1): units, NDD, not inspected, plugged, dates,
tube locations, Parquet, and errors naming the file, the line and the fix."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from fretwear.assessment import (
    LogisticPOD,
    LogSizingModel,
    SizingModel,
    Technique,
    read_field_inspections,
)
from fretwear.errors import FormatError, InputError

ECT = Technique(SizingModel(0.0, 1.0, 1e-4), LogisticPOD.from_depths(2e-4, 4e-4), name="bobbin")


def _csv(tmp_path, text, name="ins.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_units_and_statuses(tmp_path):
    path = _csv(tmp_path, "# outage 2024\ncontact,instant,technique,depth_mm,plugged\n"
                          "A,10,bobbin,0.30,\nB,10,bobbin,NDD,\nC,10,bobbin,0.5,yes\n")
    ins = read_field_inspections(path, {"bobbin": ECT})
    t = ins.table
    assert list(t.columns)[:4] == ["contact", "tube_row", "tube_column", "support"]
    assert t["status"].tolist() == ["sized", "ndd", "sized"]
    # 0.30 mm and 0.5 mm are 3e-4 m and 5e-4 m (mm -> m: 1e-3)
    assert t["depth"].iloc[0] == pytest.approx(3e-4, rel=1e-15)
    assert math.isnan(t["depth"].iloc[1])
    assert t["plugged"].tolist() == [False, False, True]
    assert t["line"].tolist() == [3, 4, 5]
    assert ins.counts() == {"sized": 2, "ndd": 1, "not inspected": 0, "plugged": 1}
    assert ins.techniques["bobbin"] is ECT
    assert "2 sized, 1 NDD" in str(ins)


def test_percent_through_wall_and_metres_give_one_depth(tmp_path):
    wall = 1.09e-3
    pct = read_field_inspections(pd.DataFrame({"contact": ["A"], "instant": [5.0],
                                               "depth_pct": [40.0]}), wall_thickness=wall)
    per_row = read_field_inspections(pd.DataFrame({"contact": ["A"], "instant": [5.0],
                                                   "depth_pct": ["40"],
                                                   "wall_thickness": [wall]}))
    metres = read_field_inspections(pd.DataFrame({"contact": ["A"], "instant": [5.0],
                                                  "depth": [0.4 * wall]}))
    # 40 % of the wall is 0.4·wall [m], whichever column gives it
    for ins in (pct, per_row):
        assert ins.table["depth"].iloc[0] == pytest.approx(metres.table["depth"].iloc[0],
                                                           rel=1e-14)


def test_dates_become_instants_in_the_time_unit():
    frame = pd.DataFrame({"tube_row": [1, 1], "tube_column": [2, 3], "support": ["AVB1", ""],
                          "date": ["2022-01-01", "2012-01-01"], "depth_mm": ["NDD", "0.2"]})
    ins = read_field_inspections(frame, origin_date="2012-01-01", time_unit="years")
    # 2012-01-01 to 2022-01-01 is 3653 days (three leap years): 3653/365 years
    assert ins.table["instant"].tolist() == pytest.approx([3653 / 365, 0.0], rel=1e-14)
    assert ins.table["support"].tolist() == ["AVB1", ""]
    assert ins.table["tube_row"].tolist() == [1.0, 1.0]
    with pytest.raises(InputError, match="origin_date"):
        read_field_inspections(frame)


def test_not_inspected_gives_no_depth_and_a_depth_there_is_refused(tmp_path):
    ins = read_field_inspections(pd.DataFrame({"contact": ["A"], "instant": [1.0],
                                               "depth": [""], "inspected": ["no"],
                                               "plugged": ["yes"]}))
    assert ins.table["status"].tolist() == ["not inspected"]
    path = _csv(tmp_path, "contact,instant,depth_mm,inspected\nA,1,0.3,no\n")
    with pytest.raises(InputError, match=r"ins\.csv'.*line 2.*not inspected"):
        read_field_inspections(path)


def test_parquet_reads_like_csv(tmp_path):
    pytest.importorskip("pyarrow")
    frame = pd.DataFrame({"contact": ["A", "B"], "instant": [10.0, 10.0],
                          "depth_mm": ["0.3", "NDD"], "technique": ["bobbin", "bobbin"]})
    frame.to_parquet(tmp_path / "ins.parquet")
    ins = read_field_inspections(tmp_path / "ins.parquet", ECT)
    assert ins.table["status"].tolist() == ["sized", "ndd"]
    assert ins.table["depth"].iloc[0] == pytest.approx(3e-4)


@pytest.mark.parametrize(("text", "match"), [
    ("contact,instant,depth_mm\nA,1,-0.3\n", r"line 2: depth_mm must be a finite number > 0"),
    ("contact,instant,depth_mm\nA,1,\n", r"line 2: an inspected tube with no depth"),
    ("contact,instant,depth_pct\nA,1,30\n", r"line 2: depth_pct needs the tube's wall"),
    ("contact,instant,depth_mm,plugged\nA,1,0.3,maybe\n", r"plugged must be yes or no"),
    ("contact,instant,depth_mm,colour\nA,1,0.3,red\n", r"unknown column\(s\) \['colour'\]"),
    ("instant,depth_mm\n1,0.3\n", r"a contact column, or tube_row and tube_column"),
    ("contact,depth_mm\nA,0.3\n", r"instant \[time unit\] or date"),
    ("contact,instant,depth,depth_mm\nA,1,3e-4,0.3\n", r"in one column"),
    ("contact,date,depth_mm\nA,yesterday,0.3\n", r"line 2: date must be an ISO 8601 date"),
    ("contact,instant,depth_mm,result\nA,1,0.3,NDD\n", r"NDD with a depth"),
])
def test_bad_input_names_the_file_the_line_and_the_fix(tmp_path, text, match):
    with pytest.raises(InputError, match=match):
        read_field_inspections(_csv(tmp_path, text), origin_date="2012-01-01")


def test_guard_layer_errors_name_the_file(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_bytes(b"contact,instant\x00,depth_mm\nA,1,0.3\n")
    with pytest.raises(FormatError, match="bad.csv"):
        read_field_inspections(path)
    with pytest.raises(InputError, match="no rows"):
        read_field_inspections(_csv(tmp_path, "contact,instant,depth_mm\n"))


def test_techniques_must_cover_the_file():
    frame = pd.DataFrame({"contact": ["A"], "instant": [1.0], "depth_mm": [0.3],
                          "technique": ["rotating"]})
    with pytest.raises(InputError, match=r"\['rotating'\] have no model"):
        read_field_inspections(frame, {"bobbin": ECT})
    one = read_field_inspections(frame.drop(columns="technique"), ECT)
    assert one.table["technique"].tolist() == ["bobbin"]


def test_user_frame_is_not_modified():
    frame = pd.DataFrame({"contact": [" A "], "instant": ["1"], "depth_mm": ["ndd"]})
    before = frame.copy()
    read_field_inspections(frame)
    pd.testing.assert_frame_equal(frame, before)


def test_log_sizing_density_integrates_to_one():
    # ∫ p(m | d) dm = 1 (trapezoid on a fine grid of m, independent of the closed form)
    s = LogSizingModel(0.2)
    m = np.linspace(1e-7, 3e-3, 200001)
    assert np.trapezoid(s.likelihood(m, 3e-4), m) == pytest.approx(1.0, abs=1e-6)
