"""wear_table(power, **keywords) validates the same keywords once (issue 28 point 5): the table
of a repeated call, of changed keywords, of a rewritten coefficient file, and the warnings of the
validation at every call.

Expected values from the closed form of docs/theory.md §4 (Archard, V = K·P·t) and, for the
reused case, from ``wear_table_from_case(WearCase.from_keywords(**keywords), power)`` of a case
made afresh (the same process: compared bit for bit).
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import UnitsWarning
from fretwear.table import WearCase, wear_table, wear_table_from_case, write_wear_table

P = 0.01  # [W]
HOUR = 3.6e3  # [s]


def keywords(**changes):
    base = dict(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
                dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
                coefficients={"COEF_USURE": 1e-14}, time_scale=HOUR)
    return {**base, **changes}


def test_repeated_keywords_give_the_table_of_a_fresh_case():
    kw = keywords(wall_thickness=1e-3)
    fresh = wear_table_from_case(WearCase.from_keywords(**kw), P)
    for _ in range(3):  # the first call makes the case, the others reuse it
        table = wear_table(P, **kw)
        pd.testing.assert_frame_equal(table, fresh, check_exact=True)
        assert table.attrs["case"] == fresh.attrs["case"]
        table.attrs["case"]["instants"].append(99.0)  # a table's metadata is its own
    np.testing.assert_allclose(table["volume_mobile"], 1e-14 * P * HOUR * np.array([1.0, 2.0]),
                               rtol=1e-15)


def test_changed_keywords_make_a_new_case():
    """The same dict object changed between calls: its new content decides (K·P·t)."""
    kw = keywords()
    first = wear_table(P, **kw)
    kw["coefficients"]["COEF_USURE"] = 3e-14
    kw["instants"].append(4.0)
    second = wear_table(P, **kw)
    np.testing.assert_allclose(first["volume_mobile"], 1e-14 * P * HOUR * np.array([1.0, 2.0]),
                               rtol=1e-15)
    np.testing.assert_allclose(second["volume_mobile"],
                               3e-14 * P * HOUR * np.array([1.0, 2.0, 4.0]), rtol=1e-15)
    # 1 and 1.0 are other values (an int instant is not a float one): both valid, both exact
    third = wear_table(P, **keywords(instants=[1, 2]))
    np.testing.assert_array_equal(third["volume_mobile"], first["volume_mobile"])


def test_a_rewritten_coefficient_file_is_read_again(tmp_path):
    """A file may change between calls: the case of coefficient_files is made again when the
    file's content changes."""
    pytest.importorskip("fretwear.database")
    path = tmp_path / "mine.csv"

    def write(k):
        path.write_text("contact_type,mobile_material,obstacle_material,law,parameter,value,"
                        f"unit\nTUBE_BAV,I600,A405,ARCHARD,COEF_USURE,{k!r},1/Pa\n",
                        encoding="utf-8")

    kw = dict(contact_type="TUBE_BAV", instants=[1.0], law="ARCHARD",
              dimensions={"mobile_radius": 0.0111, "obstacle_width": 0.0127},
              materials=("I600", "A405"), coefficient_files=str(path), time_scale=HOUR)
    write(3.1e-15)
    first = wear_table(P, **kw)
    write(6.2e-15)
    second = wear_table(P, **kw)
    np.testing.assert_allclose(first["volume_mobile"], 3.1e-15 * P * HOUR, rtol=1e-15)
    np.testing.assert_allclose(second["volume_mobile"], 6.2e-15 * P * HOUR, rtol=1e-15)


def test_a_restart_file_case_is_made_once_per_content(tmp_path):
    """wear_table(power, initial_state=<file>) again with the same file: the table of a case
    made afresh (bit for bit, one process); the file rewritten with other volumes: the table
    continues the new ones (Archard, V = V0 + K·P·t, theory §7); the file removed: the error
    of a missing file, not a remembered case."""
    kw = keywords(instants=[1.0])
    path = tmp_path / "first.tab"

    def write(hours):  # a Code_Aster text table of hours [h] of wear at P
        write_wear_table(wear_table(P, **keywords(instants=[hours])), path)

    write(2.0)
    restart = dict(kw, initial_state=str(path))
    fresh = wear_table_from_case(WearCase.from_keywords(**restart), P)
    for _ in range(3):
        pd.testing.assert_frame_equal(wear_table(P, **restart), fresh, check_exact=True)
    write(5.0)
    table = wear_table(P, **restart)
    assert table["volume_mobile"].iloc[-1] == pytest.approx(1e-14 * P * HOUR * 6.0, rel=1e-12)
    path.unlink()
    with pytest.raises(Exception, match="first.tab"):
        wear_table(P, **restart)


def test_the_validations_warnings_at_every_call():
    """A radius of 10 m (in mm?) warns when the case is made, and again at each call with the
    same keywords, at the same file and line; a user's "error" filter still raises."""
    kw = keywords(dimensions={"mobile_radius": 10.0, "obstacle_width": 0.02})
    seen = []
    for _ in range(3):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            wear_table(P, **kw)
        seen.append([(w.category, w.filename, w.lineno) for w in caught
                     if issubclass(w.category, UnitsWarning)])
    assert len(seen[0]) == 1 and seen[1] == seen[0] and seen[2] == seen[0]
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitsWarning)
        with pytest.raises(UnitsWarning):
            wear_table(P, **kw)
