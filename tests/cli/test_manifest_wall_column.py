"""A manifest whose wall column no contact can use is refused once, when it is read, naming
the column and the fix (a new user's trial: wall_thickness_m = 1.09 on every row gave one
identical error per contact, 24, and 'done 0, failed 24'). Oracle: the rows written here."""

from __future__ import annotations

import pandas as pd
import pytest

from fretwear.bundle.manifest import read_manifest
from fretwear.cli import main
from fretwear.errors import InputError


def _manifest(tmp_path, walls):
    path = tmp_path / "manifest.csv"
    pd.DataFrame({"contact": [f"c{i}" for i in range(len(walls))],
                  "history": [f"h{i}.csv" for i in range(len(walls))],
                  "wall_thickness_m": walls}).to_csv(path, index=False)
    return path


def test_a_wall_in_mm_is_one_error_naming_the_column(tmp_path, capsys):
    path = _manifest(tmp_path, [1.09, 1.09, 1.09])
    with pytest.raises(InputError) as err:
        read_manifest(path)
    text = " ".join(str(err.value).split())
    assert "column wall_thickness_m = 1.09 [m] on 3 of 3 rows (first: contact 'c0')" in text
    assert "a value in mm? Give metres: wall_thickness_m = 0.00109" in text
    case = tmp_path / "case.toml"
    case.write_text("", encoding="utf-8")
    assert main(["bundle", str(path), "--case", str(case), "-o", str(tmp_path / "out")]) == 2
    captured = capsys.readouterr()
    said = captured.out + captured.err
    assert said.count("wall_thickness_m = 1.09") == 1  # once, not once per contact
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_a_negative_column_and_one_bad_row(tmp_path):
    with pytest.raises(InputError, match="on 2 of 2 rows \\(first: contact 'c0'\\): a wall is > 0"):
        read_manifest(_manifest(tmp_path, [-0.00109, 0.0]))
    # one good wall: the column is not refused, the bad row fails its contact alone (as
    # tests/bundle/test_bundle_carries_cases.py checks); an empty cell is the case's wall
    rows = read_manifest(_manifest(tmp_path, [0.00109, 1.09, None])).rows
    assert [r.contact for r in rows] == ["c0", "c1", "c2"]
