"""A wear table or a case file given where a contact history is expected is named as what it
is (a new user's trial: the error listed the table's columns, or the TOML's words, only)."""

from __future__ import annotations

import pytest

from fretwear.errors import FormatError
from fretwear.io import read_history
from fretwear.table import wear_table, write_wear_table


@pytest.mark.parametrize("suffix", [".csv", ".tab"])
def test_a_wear_table_is_named_as_one(tmp_path, suffix):
    table = wear_table(0.01, contact_type="TUBE_BAV", instants=[1.0, 2.0],
                       dimensions={"mobile_radius": 0.0095, "obstacle_width": 0.02},
                       coefficients={"COEF_USURE": 1e-14}, time_scale=31_536_000.0)
    path = write_wear_table(table, tmp_path / f"t{suffix}")
    with pytest.raises(FormatError, match=r"is a wear table \(POST_USURE's output.*\[restart\]"
                                          r".*not a contact history"):
        read_history(path)


def test_a_case_file_is_named_as_one(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text('title = "SG tube"\n[law]\nname = "ARCHARD"\n')
    with pytest.raises(FormatError, match=r"is a TOML file \(a case file\? run it with "
                                          r"fretwear run CASE.toml\), not a contact history"):
        read_history(path)
