"""The fast path of Code_Aster text tables of plain numbers (fretwear.io._aster_plain).

Independent computation: the general path of ``fretwear.io.aster`` (pandas' C parser, then the
column-by-column conversion), taken by setting ``PLAIN_MAX_CELLS`` to 0, on the same text. The
fast path must give the same frame: values bit for bit (NaN where the general path has NaN),
dtypes, column names and their index type, row index, ``attrs``. Each case also states which
path the table takes (``plain_frame`` returns a frame, or None).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from iohelpers import FIXTURES

from fretwear.errors import FormatError
from fretwear.io import _aster_plain, aster
from fretwear.io.aster import format_aster_table, list_aster_tables, read_aster_table
from fretwear.table import read_wear_table, wear_table, write_wear_table

ROOT = Path(__file__).resolve().parents[2]


def same_frame(fast: pd.DataFrame, general: pd.DataFrame) -> None:
    """The two frames are the same: values bit for bit, dtypes, names, index, attrs."""
    pd.testing.assert_frame_equal(fast, general, check_exact=True, check_dtype=True,
                                  check_column_type=True, check_index_type=True,
                                  check_flags=True)
    assert list(fast.columns) == list(general.columns)
    assert fast.attrs == general.attrs
    for j in range(fast.shape[1]):
        a, b = fast.iloc[:, j], general.iloc[:, j]
        if a.dtype == np.float64:  # bit for bit: -0.0, NaN and every last bit
            assert np.array_equal(a.to_numpy().view(np.int64), b.to_numpy().view(np.int64))


def read_both(source, monkeypatch, **options) -> tuple[pd.DataFrame, pd.DataFrame]:
    fast = read_aster_table(source, **options)
    with monkeypatch.context() as m:
        m.setattr(_aster_plain, "PLAIN_MAX_CELLS", 0)
        general = read_aster_table(source, **options)
    return fast, general


def takes_fast_path(text: str, index: int = 0) -> bool:
    """Whether the table takes the fast path; a table meant for it takes it with a pandas that
    rounds as numpy does (>= 3.1), and the general path before."""
    raw = aster._split_tables(text, "<text>")[index]
    fast = _aster_plain.plain_frame(raw, list(raw["names"])) is not None
    return fast if _aster_plain._same_rounding() else _aster_plain_would_take(raw)


def _aster_plain_would_take(raw: dict) -> bool:
    with pytest.MonkeyPatch.context() as m:
        m.setattr(_aster_plain, "_same_rounding", lambda: True)
        return _aster_plain.plain_frame(raw, list(raw["names"])) is not None


def test_shipped_restart_table_takes_the_fast_path_and_gives_the_same_frame(monkeypatch):
    path = ROOT / "examples" / "data" / "grappe_2_enco_10000h.tab"
    assert takes_fast_path(path.read_text())
    fast, general = read_both(path, monkeypatch)
    same_frame(fast, general)
    assert fast["V_USUR_TUBE"].tolist() == [1.44e-09, 2.88e-09]  # the printed literals
    assert fast.attrs["types"] == ["R"] * 8


def test_shipped_shock_table_with_a_text_column_takes_the_general_path(monkeypatch):
    path = ROOT / "examples" / "data" / "shock_N12.tab"
    text = path.read_text()
    lines = text.splitlines()
    head = "\n".join(lines[:40]) + "\n"  # small enough for the fast path, were it numbers
    assert not takes_fast_path(head)  # NOEUD holds node names
    same_frame(*read_both(head, monkeypatch))
    same_frame(*read_both(path, monkeypatch))


@pytest.mark.parametrize("name", sorted(p.name for p in FIXTURES.glob("*")
                                        if p.is_file() and p.suffix in (".txt", ".resu")))
def test_every_fixture_table_gives_the_same_frame(name, monkeypatch):
    path = FIXTURES / name
    for index in range(len(list_aster_tables(path))):
        same_frame(*read_both(path, monkeypatch, index=index))


def test_multi_table_file_each_table_and_the_choice_error(monkeypatch):
    text = ("#\n#first\nINST V_USUR_TUBE\n 1.00000E+00  2.00000E-09\n"
            "#\n#second\nINST V_USUR_TUBE\n 2.00000E+00  -\n 3.00000E+00  4.00000E-09\n")
    assert takes_fast_path(text, 0) and takes_fast_path(text, 1)
    for index in (0, 1):
        same_frame(*read_both(text, monkeypatch, index=index))
    with pytest.raises(FormatError, match=r"holds 2 tables \(0: first; 1: second\); choose"):
        read_aster_table(text)


def test_sector_table_written_by_fretwear_exact_digits(tmp_path, monkeypatch):
    """A sector table (SECTEUR an integer column, every real %.16E: 17 digits) in both
    layouts, read as a wear table (native names)."""
    t = np.linspace(0.0, 1.0, 2001)
    from fretwear.history import ContactHistory
    phase = 2 * np.pi * 20 * t
    history = ContactHistory(time=t, normal_force=np.maximum(0.0, 30 * np.sin(phase)),
                             vt1=0.02 * np.cos(phase), vt2=0.01 * np.sin(phase),
                             dy=1e-4 * np.cos(phase / 3), dz=1e-4 * np.sin(phase / 3))
    table = wear_table(history, contact_type="TUBE_BAV", instants=[1 / 3, 1.0, 7.0],
                       sectors=4, dimensions={"mobile_radius": 0.0111, "obstacle_width": 0.0127},
                       coefficients={"COEF_USURE": 1.1e-13}, time_scale=3.6e3)
    for suffix, fmt in ((".tab", "TABLEAU"), (".resu", "ASTER")):
        path = write_wear_table(table, tmp_path / f"sectors{suffix}", aster_format=fmt)
        assert takes_fast_path(path.read_text())
        fast, general = read_both(path, monkeypatch)
        same_frame(fast, general)
        assert str(fast["SECTEUR"].dtype) == "int64"
        wear = read_wear_table(path)
        with monkeypatch.context() as m:
            m.setattr(_aster_plain, "PLAIN_MAX_CELLS", 0)
            same_frame(wear, read_wear_table(path))
        for column in ("volume_mobile", "volume_mobile_cumulated", "depth_mobile_sector"):
            assert np.array_equal(wear[column].to_numpy(), table[column].to_numpy(),
                                  equal_nan=True)  # %.16E round-trips every float64


def test_blank_cells_in_real_and_integer_columns(monkeypatch):
    text = ("#\n#blanks\nINST SECTEUR V_USUR_TUBE P_USUR_TUBE\n"
            " 1.00000E+00 1 - 2.00000E-05\n"
            " 1.00000E+00 - 3.00000E-09 -\n"
            " 2.00000E+00 2 4.00000E-09 -\n")
    assert takes_fast_path(text)
    fast, general = read_both(text, monkeypatch)
    same_frame(fast, general)
    assert str(fast["SECTEUR"].dtype) == "Int64" and pd.isna(fast["SECTEUR"].iloc[1])
    assert np.isnan(fast["V_USUR_TUBE"].iloc[0]) and fast.attrs["types"] == ["R", "I", "R", "R"]


def test_awkward_numbers_give_the_same_values(monkeypatch):
    """Random float64 of every exponent (subnormals included) printed with 17, 6 and 4
    significant digits, and the tokens a parser may treat apart: signed zeros, a leading point
    or sign, a trailing point, overflow and underflow, long mantissas, integers."""
    rng = np.random.default_rng(12)
    bits = rng.integers(0, 2 ** 63, 40, dtype=np.int64)
    x = bits.view(np.float64)
    x = x[np.isfinite(x)][:24]
    odd = ["-0.0", "0.0", "+.5", "5.", "1.e5", "00.1", "1e0005", "1E400", "-1E400", "1E-400",
           "9" * 30 + ".5", "0." + "1" * 40, "-0", "7", "+3", "-12"]
    columns = {
        "A": [f"{v:.16E}" for v in x], "B": [f"{v:12.5E}" for v in x],
        "C": [f"{v:.3e}" for v in x],
        "D": (odd + ["-"] * 24)[:24],  # reals with blanks
        "E": (odd[-4:] + [f"{v:.16E}" for v in x])[:24],  # integers and reals: reals
        "F": [str(int(v)) for v in rng.integers(-10 ** 17, 10 ** 17, 24)],  # 18-digit integers
    }
    text = "#\n#awkward\n" + " ".join(columns) + "\n" + "\n".join(
        " ".join(columns[c][i] for c in columns) for i in range(24)) + "\n"
    assert takes_fast_path(text)
    fast, general = read_both(text, monkeypatch)
    same_frame(fast, general)
    assert fast.attrs["types"] == ["R", "R", "R", "R", "R", "I"]
    assert np.array_equal(fast["A"].to_numpy(), x)  # %.16E: the float64 themselves


@pytest.mark.parametrize("body, why", [
    ("INST NOEUD\n 1.0 N1\n", "a text column"),
    ("INST NOEUD\n 1.0 'a b'\n", "a quoted string"),
    ("INST FN\n 1.0D+00 2.0\n", "a Fortran D exponent"),
    ("INST FN\n 1.0 nan\n", "a nan word"),
    ("INST FN\n 1.0 -\n 2.0 -\n", "a column all blank"),
    ("INST FN\n 1.0 12345678901234567890\n", "an integer beyond int64"),
])
def test_other_tables_take_the_general_path(body, why, monkeypatch):
    text = "#\n#t\n" + body
    assert not takes_fast_path(text), why
    same_frame(*read_both(text, monkeypatch))


def test_a_short_row_is_named_by_the_general_path():
    text = "#\n#t\nINST FN\n 1.0 2.0\n 3.0\n"
    assert not takes_fast_path(text)
    with pytest.raises(FormatError, match=r"<text>, line 5: 1 cells for 2 columns \['INST', "
                                          r"'FN'\]; an empty cell must be written '-'"):
        read_aster_table(text)


def test_declared_types_must_match_the_cells(monkeypatch):
    matching = ("#DEBUT_TABLE\n#TITRE t\nINST NUME_ORDRE FN\nR I R\n"
                "0.0 1 -\n1.0 2 3.5\n#FIN_TABLE\n")
    assert takes_fast_path(matching)
    same_frame(*read_both(matching, monkeypatch))
    for types in ("R R R", "R I K8", "I I R"):  # integers declared R, a string, reals as I
        text = matching.replace("R I R", types)
        assert not takes_fast_path(text)
        same_frame(*read_both(text, monkeypatch))


def test_repeated_names_and_large_tables(monkeypatch):
    pairs = "#\n#FONCTION\nINST FN INST VT1\n0 1 0 2.5\n1 3 1 4.5\n"
    assert takes_fast_path(pairs)
    same_frame(*read_both(pairs, monkeypatch))
    rng = np.random.default_rng(5)
    big = format_aster_table(pd.DataFrame(rng.random((200, 8)), columns=list("ABCDEFGH")))
    assert not takes_fast_path(big)  # 1600 cells > PLAIN_MAX_CELLS: pandas' parser
    small = format_aster_table(pd.DataFrame(rng.random((100, 8)), columns=list("ABCDEFGH")))
    assert takes_fast_path(small)
    same_frame(*read_both(small, monkeypatch))


def test_column_names_are_each_frames_own(monkeypatch):
    """The fast path shares one cached index of names between frames: a name set on one
    frame's columns stays with it."""
    text = "#\n#t\nINST FN\n 1.0 2.0\n"
    first = read_aster_table(text)
    first.columns.name = "mine"
    first.columns = ["X", "Y"]
    again = read_aster_table(text)
    assert list(again.columns) == ["INST", "FN"] and again.columns.name is None


def test_no_fast_path_with_a_pandas_that_may_round_otherwise(monkeypatch):
    """pandas before 3.1 may round a long mantissa otherwise than numpy: the general path."""
    text = "#\n#t\nINST FN\n 1.0000000000000001E+00 2.0\n"
    raw = aster._split_tables(text, "<text>")[0]
    monkeypatch.setattr(_aster_plain, "_same_rounding", lambda: False)
    assert _aster_plain.plain_frame(raw, ["INST", "FN"]) is None
    assert read_aster_table(text)["FN"].tolist() == [2.0]
