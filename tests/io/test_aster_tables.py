"""Code_Aster text tables: IMPR_TABLE TABLEAU / ASTER and IMPR_FONCTION TABLEAU.

Fixtures in ``fixtures/`` are written by hand from the format description of theory §1 and the
Code_Aster documentation of IMPR_TABLE (U4.91.03), LIRE_TABLE (U7.02.03) and IMPR_FONCTION
(U4.33.01); expected values are the literals printed in them.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from iohelpers import FIXTURES

from fretwear.errors import FormatError, InputError
from fretwear.io import read_history
from fretwear.io.aster import list_aster_tables, read_aster_table, write_aster_table

TABLEAU = FIXTURES / "impr_table_tableau.txt"
ASTER = FIXTURES / "impr_table_aster.resu"


def test_tableau_fixture():
    frame = read_aster_table(TABLEAU)
    assert list(frame.columns) == ["NOEUD", "INST", "VINT1", "VINT5", "VINT6", "VINT11",
                                   "VINT12", "VINT13"]
    assert frame.attrs["format"] == "TABLEAU"
    assert frame.attrs["title"].splitlines() == [
        "ASTER 16.04.00 CONCEPT TABCHOC CALCULE LE 21/11/2026 A 03:00:00 DE TYPE",
        "TABLE_SDASTER"]
    assert frame.attrs["types"] == ["K8", "R", "R", "R", "R", "R", "R", "R"]
    assert frame["NOEUD"].tolist() == ["N12"] * 5
    assert frame["VINT1"].tolist() == [0.0, 12.5, 25.0, 12.5, 0.0]
    assert frame["VINT12"].tolist() == [0.0, -0.01, -0.02, 0.0, 0.005]


def test_tableau_fixture_as_a_history():
    h = read_history(TABLEAU)
    assert h.metadata["format"] == "aster"
    assert h.time.tolist() == [0.0, 1e-3, 2e-3, 3e-3, 4e-3]
    assert h.normal_force.tolist() == [0.0, 12.5, 25.0, 12.5, 0.0]
    assert h.dy.tolist() == [1e-4, 2.05e-4, 2.1e-4, 2.05e-4, 1.5e-4]
    assert h.vt1.tolist() == [0.0, 0.02, 0.03, 0.0, -0.01]
    assert h.stick.tolist() == [0.0, 0.0, 0.0, 1.0, 0.0]
    assert h.metadata["ignored_columns"] == ["NOEUD"]


def test_aster_fixture_two_tables_choice_types_missing_cells_and_quotes():
    assert list_aster_tables(ASTER) == ["TABLE DE POST_USURE\nCALCULEE LE 21/11/2026",
                                        "CHOC N12 REPERE LOCAL"]
    with pytest.raises(FormatError, match=r"holds 2 tables \(0: TABLE DE POST_USURE / CALCULEE "
                                          r"LE 21/11/2026; 1: CHOC N12 REPERE LOCAL\); choose"):
        read_aster_table(ASTER)
    wear = read_aster_table(ASTER, index=0)
    assert wear.attrs["types"] == ["R", "R", "R", "I", "K16"]
    assert np.isnan(wear["INST"].iloc[2]) and wear["INST"].iloc[1] == 3.15360e7
    assert np.isnan(wear["V_USUR_TUBE"].iloc[0]) and wear["V_USUR_TUBE"].iloc[1] == 4.5678e-7
    assert str(wear["SECTEUR"].dtype) == "Int64" and wear["SECTEUR"].iloc[1] == 2
    assert pd.isna(wear["SECTEUR"].iloc[2])
    assert wear["COMMENTAIRE"].tolist() == ["etat initial", "fin", None]
    assert read_aster_table(ASTER, title="choc n12").shape == (4, 7)
    assert read_aster_table(ASTER, index=-1).attrs["title"] == "CHOC N12 REPERE LOCAL"
    with pytest.raises(FormatError, match="index=2 but the file holds 2 table"):
        read_aster_table(ASTER, index=2)
    with pytest.raises(FormatError, match="no table with a title containing 'absent'"):
        read_aster_table(ASTER, title="absent")


def test_aster_fixture_as_a_history_with_units():
    """The second table is in mm and mm/s (a model meshed in mm): converted to SI."""
    h = read_history(ASTER, title="CHOC", units={"length": "mm"})
    np.testing.assert_allclose(h.dy, [2e-4, 2.1e-4, 2.2e-4, -2e-4], rtol=1e-15)
    np.testing.assert_allclose(h.vt1, [0.0, 0.012, 0.011, 0.0], rtol=1e-15)
    np.testing.assert_allclose(h.vt2, [0.0, -0.005, -0.004, 0.0], rtol=1e-15)
    assert h.normal_force.tolist() == [0.0, 4.0, 8.0, 0.0]
    assert h.metadata["ignored_columns"] == ["DXLOC"]
    assert h.metadata["aster_title"] == "CHOC N12 REPERE LOCAL"


def test_fortran_exponents_and_text_input():
    frame = read_aster_table("#\n#t\nA B\n1.5D+00 2\n-2.0d-1 -\n")
    assert frame["A"].tolist() == [1.5, -0.2]
    assert frame.attrs["types"] == ["R", "I"]


@pytest.mark.parametrize("fmt", ["TABLEAU", "ASTER"])
def test_write_read_round_trip_to_printed_precision(tmp_path, fmt):
    rng = np.random.default_rng(7)
    x = rng.normal(scale=1e-3, size=50) * 10.0 ** rng.integers(-8, 8, size=50)
    frame = pd.DataFrame({"INST": np.arange(50) * 0.1, "V": x, "SECTEUR": np.arange(1, 51),
                          "NOM": ["a b", "", "-"] + ["s"] * 47})
    frame.loc[3, "V"] = np.nan
    path = write_aster_table(frame, tmp_path / "t.resu", format=fmt, title="ma table\nligne 2")
    back = read_aster_table(path)
    assert back.attrs["title"] == "ma table\nligne 2" and back.attrs["format"] == fmt
    expected = np.array([float("%12.5E" % v) for v in x])  # noqa: UP031 (what it prints)
    expected[3] = np.nan
    np.testing.assert_array_equal(back["V"].to_numpy(), expected)
    assert back["SECTEUR"].tolist() == list(range(1, 51))
    assert back["NOM"].tolist()[:4] == ["a b", "", "-", "s"]
    if fmt == "ASTER":
        assert back.attrs["types"] == ["R", "R", "I", "K8"]
    exact = read_aster_table(write_aster_table(frame, tmp_path / "e.resu", format=fmt,
                                               float_format="%.16E"))
    np.testing.assert_array_equal(exact["V"].to_numpy(), frame["V"].to_numpy())


def test_written_tableau_layout(tmp_path):
    """The layout LIRE_TABLE expects: '#' block, name line, %12.5E cells, '-' for NaN."""
    path = write_aster_table(pd.DataFrame({"INST": [0.0, 2.0], "FN": [np.nan, 12.5]}),
                             tmp_path / "t.txt", title="T")
    assert path.read_text().splitlines() == [
        "#", "#T", "INST         FN", " 0.00000E+00" + " " * 12 + "-", " 2.00000E+00  1.25000E+01"]


def test_append_adds_a_table(tmp_path):
    path = tmp_path / "two.resu"
    write_aster_table(pd.DataFrame({"A": [1.0]}), path, format="ASTER", title="one")
    write_aster_table(pd.DataFrame({"B": [2.0]}), path, format="ASTER", title="two", append=True)
    assert list_aster_tables(path) == ["one", "two"]
    assert read_aster_table(path, title="two")["B"].tolist() == [2.0]


def test_write_errors(tmp_path):
    with pytest.raises(InputError, match="'TABLEAU' or 'ASTER'"):
        write_aster_table(pd.DataFrame({"A": [1.0]}), tmp_path / "x", format="CSV")
    with pytest.raises(InputError, match="column name 'a b'"):
        write_aster_table(pd.DataFrame({"a b": [1.0]}), tmp_path / "x")
    assert not (tmp_path / "x").exists()


def test_malformed_tables_name_the_line(tmp_path):
    with pytest.raises(FormatError, match=r"line 4: 1 cells for 2 columns \['A', 'B'\]"):
        read_aster_table("#\n#t\nA B\n1.0\n")
    with pytest.raises(FormatError, match=r"line 4: column 'A' of type R holds 'x'"):
        read_aster_table("#DEBUT_TABLE\nA\nR\nx\n#FIN_TABLE\n")
    with pytest.raises(FormatError, match="never closed by #FIN_TABLE"):
        read_aster_table("#DEBUT_TABLE\nA\nR\n1.0\n")
    with pytest.raises(FormatError, match="unknown type 'Z9'"):
        read_aster_table("#DEBUT_TABLE\nA\nZ9\n1.0\n#FIN_TABLE\n")
    with pytest.raises(InputError, match="does not exist"):
        read_aster_table(tmp_path / "absent.resu")


# --------------------------------------------------------------------------- IMPR_FONCTION
def test_function_set_one_file_per_channel():
    files = {"normal_force": FIXTURES / "fonction_fn.txt", "VT1": FIXTURES / "fonction_vt1.txt",
             "vt2": FIXTURES / "fonction_vt2.txt"}
    h = read_history(files, format="aster-function")
    assert h.time.tolist() == [0.0, 1e-3, 2e-3, 3e-3]
    assert h.normal_force.tolist() == [0.0, 5.0, 10.0, 5.0]
    assert h.vt1.tolist() == [0.01, 0.02, 0.03, 0.04]
    assert h.vt2.tolist() == [-0.01, 0.0, 0.01, 0.0]
    assert h.metadata["format"] == "aster-function"
    # a mapping of files is recognised without format=, and units apply
    h = read_history(files, units={"force": "kN"})
    assert h.normal_force.tolist() == [0.0, 5000.0, 10000.0, 5000.0]


def test_function_list_and_pairs_file_use_the_column_names():
    h = read_history([FIXTURES / f"fonction_{c}.txt" for c in ("fn", "vt1", "vt2")])
    assert h.normal_force.tolist() == [0.0, 5.0, 10.0, 5.0]
    h = read_history(FIXTURES / "fonction_pairs.txt", format="aster-function")
    assert h.time.tolist() == [0.0, 1e-3]
    assert h.vt1.tolist() == [0.01, 0.02] and h.vt2.tolist() == [-0.01, 0.0]


def test_function_set_with_other_instants_is_refused():
    files = {"fn": FIXTURES / "fonction_fn.txt", "vt1": FIXTURES / "fonction_vt1.txt",
             "vt2": FIXTURES / "fonction_vt2_other_instants.txt"}
    with pytest.raises(FormatError, match=r"fonction_vt2_other_instants.txt: instant at row 2 is "
                                          r"0.0025 but .*fonction_fn.txt has 0.002"):
        read_history(files)


def test_function_file_with_several_functions_for_one_channel_is_refused():
    with pytest.raises(FormatError, match=r"holds 3 functions \['FN', 'VT1', 'VT2'\] but is "
                                          r"given for the single channel 'fn'"):
        read_history({"fn": FIXTURES / "fonction_pairs.txt", "vt1": FIXTURES / "fonction_vt1.txt",
                      "vt2": FIXTURES / "fonction_vt2.txt"})


def test_function_pairs_file_is_recognised_by_content(tmp_path):
    # (INST, value) pairs side by side: read as IMPR_FONCTION functions without format=
    # (values: the literals of fixtures/fonction_pairs.txt).
    h = read_history(FIXTURES / "fonction_pairs.txt")
    assert h.metadata["format"] == "aster-function"
    assert h.time.tolist() == [0.0, 1e-3]
    assert h.normal_force.tolist() == [0.0, 5.0] and h.vt1.tolist() == [0.01, 0.02]
    bad = tmp_path / "pairs.txt"
    bad.write_text("#\n#FONCTION\n INST  FN  INST  VT1\n 0.0  1.0  0.0  2.0\n"
                   " 1.0  1.0  1.5  2.0\n")
    with pytest.raises(FormatError, match=r"\(VT1\): instant at row 1 is 1.5 but .*\(FN\) has"):
        read_history(bad)


def test_table_of_several_shock_points_needs_a_selection(tmp_path):
    # fixtures/impr_table_tableau.txt with its rows repeated for a second node N13 (values x2):
    # without select= the mixed table is refused naming NOEUD; select= keeps one node's rows.
    from fretwear.errors import KeywordError

    lines = TABLEAU.read_text().splitlines()
    rows = lines[4:]
    doubled = []
    for r in rows:
        cells = r.split()
        cells[0], cells[2] = "N13", f"{2 * float(cells[2]):12.5E}"  # VINT1 doubled
        doubled.append(" ".join(cells))
    path = tmp_path / "two.txt"
    path.write_text("\n".join(lines[:4] + rows + doubled) + "\n")
    with pytest.raises(FormatError, match=r"column 'NOEUD' holds several values \['N12', 'N13'\]"
                                          r".*select=NOEUD=N12"):
        read_history(path)
    n12 = read_history(path, select={"NOEUD": "N12"})
    assert n12.normal_force.tolist() == [0.0, 12.5, 25.0, 12.5, 0.0]
    n13 = read_history(path, select="noeud=N13")
    assert n13.time.tolist() == [0.0, 1e-3, 2e-3, 3e-3, 4e-3]
    assert n13.normal_force.tolist() == [0.0, 25.0, 50.0, 25.0, 0.0]
    with pytest.raises(KeywordError, match=r"never equals 'N14'; its values: \['N12', 'N13'\]"):
        read_history(path, select="NOEUD=N14")
    with pytest.raises(KeywordError, match="give 'COLUMN=VALUE'"):
        read_history(path, select="NOEUD")


def test_infinite_reals_are_empty_cells(tmp_path):
    """No infinity in a Code_Aster table: LIRE_TABLE's ASTER-format reals match [0-9.,+-eEdD]+
    (code_aster MacroCommands/Utils/TableReader.FMT), so ±inf is written as an empty cell '-',
    like NaN, in both formats."""
    import numpy as np
    import pandas as pd

    from fretwear.io.aster import read_aster_table, write_aster_table

    frame = pd.DataFrame({"INST": [1.0, 2.0, 3.0], "T_LIMITE": [np.inf, 5.0, -np.inf]})
    for fmt in ("TABLEAU", "ASTER"):
        path = write_aster_table(frame, tmp_path / f"t_{fmt}.tab", format=fmt)
        assert "INF" not in path.read_text().upper()
        back = read_aster_table(path)
        assert np.isnan(back["T_LIMITE"].iloc[0]) and np.isnan(back["T_LIMITE"].iloc[2])
        assert back["T_LIMITE"].iloc[1] == 5.0
