"""`fretwear run` end to end on every example case file, outputs and errors.

Checks against independent computations: the table written equals run_case's (the library
call) and the Code_Aster table written reads back with the same values (theory §7 names).
"""

import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.cli import main
from fretwear.io.aster import read_aster_table
from fretwear.table import read_wear_table
from fretwear.workflows.case_files import run_case

# the example cases of `fretwear run` (those with an [iterate] section belong to `fretwear iterate`)
EXAMPLES = [p for p in sorted((Path(__file__).parents[2] / "examples").glob("*.toml"))
            if "iterate" not in tomllib.loads(p.read_text(encoding="utf-8"))]


@pytest.mark.parametrize("case", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_every_example_runs(case, tmp_path, capsys):
    out = tmp_path / "table.csv"
    assert main(["run", str(case), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "wear power P" in printed and "table written" in printed
    table = read_wear_table(out)
    expected = run_case(case).table
    np.testing.assert_allclose(table["volume_mobile"], expected["volume_mobile"], rtol=1e-11)
    assert np.isfinite(table["depth_mobile"]).all()
    assert (np.diff(table.drop_duplicates("instant")["instant"]) > 0).all()


def test_demo_outputs_plots_and_aster_table(tmp_path, capsys):
    case = Path(__file__).parents[2] / "examples" / "tube_bav.toml"
    tab = tmp_path / "wear.tab"
    assert main(["run", str(case), "-o", str(tab), "--plot", str(tmp_path / "fig")]) == 0
    printed = capsys.readouterr().out
    assert "sectors at instant 20 " in printed and "StationarityWarning" in printed
    names = sorted(p.name for p in (tmp_path / "fig").iterdir())
    assert names == ["wear_history.png", "wear_history.svg", "wear_sectors.png",
                     "wear_sectors.svg"]
    back = read_aster_table(tab)
    assert {"INST", "SECTEUR", "V_USUR_TUBE_CUMU", "P_USUR_TUBE_SECT"} <= set(back.columns)
    expected = run_case(case).table
    np.testing.assert_allclose(back["V_USUR_TUBE_CUMU"], expected["volume_mobile_cumulated"],
                               rtol=1e-10)
    # the bar does not wear (no obstacle coefficient in R7.20.01's table): no depth, exactly
    assert back["V_USUR_OBST"].eq(0.0).all() and back["P_USUR_OBST"].eq(0.0).all()
    pq = tmp_path / "wear.parquet"
    assert main(["run", str(case), "-q", "-o", str(pq), "--aster-names"]) == 0
    assert "PUIS_USUR_SECT" in pd.read_parquet(pq).columns


def test_help_documents_every_key(capsys):
    """Every key of fretwear.workflows.case_files.KEYS and every output column of
    fretwear.table.COLUMNS (with its Code_Aster name and unit) is in `fretwear run --help`."""
    from fretwear.table import COLUMNS
    from fretwear.workflows.case_files import KEYS

    assert main(["run", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())  # undo click's line wrapping
    for section, keys in KEYS.items():
        if section:
            assert f"[{section}]" in text
        for key in keys:
            assert f"{key}:" in text, key
    for native, (aster, unit, _) in COLUMNS.items():
        # a time column names the case's unit ([time] unit), not the schema's placeholder
        unit = ("time unit of [time] unit, e.g. year" if unit == COLUMNS["instant"][1]
                else unit)
        assert f"{native} ({aster}) [{unit}]" in text
    for option in ("--output", "--plot", "--aster-names", "--aster-format", "--database",
                   "--quiet"):
        assert option in text


def test_typo_in_case_is_a_clean_error(tmp_path, capsys):
    case = tmp_path / "bad.toml"
    case.write_text('[geometry]\ncontact_typ = "TUBE_BAV"\n', encoding="utf-8")
    assert main(["run", str(case)]) == 2
    err = capsys.readouterr().err
    assert "unknown key [geometry] contact_typ" in err and "contact_type" in err


def test_unknown_output_suffix(tmp_path, capsys):
    case = Path(__file__).parents[2] / "examples" / "tube_tube.toml"
    assert main(["run", str(case), "-q", "-o", str(tmp_path / "t.xlsx")]) == 2
    assert "unknown suffix '.xlsx'" in capsys.readouterr().err
    assert not (tmp_path / "t.xlsx").exists()


@pytest.mark.parametrize("suffix, options", [(".csv", []), (".parquet", []), (".tab", []),
                                             (".resu", ["--aster-format", "ASTER"])])
def test_sector_restart_through_each_output_format(tmp_path, capsys, suffix, options):
    """Two CLI runs chained by [restart] equal one long run (Archard, 8 sectors, theory §7):
    V_j(2 + 3 years) = V_j(2) + k·P_j·3 years; the table file of the first run, in each output
    format, seeds the second (read back by fretwear.table.read_wear_table)."""
    examples = Path(__file__).parents[2] / "examples"
    text = (examples / "tube_bav.toml").read_text(encoding="utf-8")
    text = text.replace('file = "data/oscillator_gap.csv"',
                        f'file = "{(examples / "data" / "oscillator_gap.csv").as_posix()}"')
    first_case = tmp_path / "first.toml"
    first_case.write_text(text.replace("instants = [0.5, 1, 2, 5, 10, 20]", "instants = [1, 2]"),
                          encoding="utf-8")
    long_case = tmp_path / "long.toml"
    long_case.write_text(text.replace("instants = [0.5, 1, 2, 5, 10, 20]",
                                      "instants = [1, 2, 5]"), encoding="utf-8")
    first = tmp_path / f"first{suffix}"
    assert main(["run", str(first_case), "-q", "-o", str(first), *options]) == 0
    second_case = tmp_path / "second.toml"
    second_case.write_text(text.replace("instants = [0.5, 1, 2, 5, 10, 20]", "instants = [3]")
                           + f'\n[restart]\ntable = "{first.name}"\n', encoding="utf-8")
    out = tmp_path / "second.csv"
    assert main(["run", str(second_case), "-q", "-o", str(out)]) == 0
    chained, long = read_wear_table(out), run_case(long_case).table
    assert chained["instant"].tolist() == long["instant"].tolist()
    assert chained["origin"].tolist() == [0.0] * 16 + [2.0] * 8
    rtol = 1e-9 if suffix in (".tab", ".resu") else 1e-14  # %.10E in Code_Aster files
    for col in ("volume_mobile_cumulated", "volume_mobile", "depth_mobile_sector"):
        np.testing.assert_allclose(chained[col], long[col], rtol=rtol)
    if suffix == ".resu":
        assert first.read_text(encoding="utf-8").startswith("#DEBUT_TABLE")


def test_example_continuing_a_code_aster_table(capsys):
    """examples/grappe_2_enco.toml restarts from a hand-written Code_Aster TABLEAU file at
    10 000 h: V = V(10 000 h) + k·P·Δt with the R7.20.01 §3 pair A316L/A304L (40e-15, 29e-15 Pa⁻¹),
    P = 2 mW (theory §4, §7)."""
    case = Path(__file__).parents[2] / "examples" / "grappe_2_enco.toml"
    t = run_case(case).table
    assert t["instant"].tolist() == [5000.0, 10000.0, 15000.0, 20000.0]
    assert t["origin"].tolist() == [0.0, 0.0, 10000.0, 10000.0]
    hours = np.array([5000.0, 10000.0]) * 3600.0
    np.testing.assert_allclose(t["volume_mobile"].iloc[2:], 2.88e-9 + 40e-15 * 2e-3 * hours,
                               rtol=1e-12)
    np.testing.assert_allclose(t["volume_obstacle"].iloc[2:], 2.088e-9 + 29e-15 * 2e-3 * hours,
                               rtol=1e-12)
    assert main(["run", str(case)]) == 0
    assert "continues data/grappe_2_enco_10000h.tab from instant 10000" in capsys.readouterr().out


def test_database_option_adds_to_the_case_list(tmp_path, capsys):
    """R7.20.01 §3: TUBE_BAV I600/A405 K = 6.2e-14 Pa⁻¹. `--database` files come after the case's
    `[law] database` (later wins); V = K·P·t (theory §4) scales by the ratio of the K's."""
    header = "contact_type,mobile_material,obstacle_material,law,parameter,value,unit\n"
    (tmp_path / "case_file.csv").write_text(
        header + "TUBE_BAV,I600,A405,ARCHARD,COEF_USURE,3.1e-14,1/Pa\n", encoding="utf-8")
    (tmp_path / "cli_file.csv").write_text(
        header + "TUBE_BAV,I600,A405,ARCHARD,COEF_USURE,1.24e-14,1/Pa\n", encoding="utf-8")
    case = tmp_path / "case.toml"
    case.write_text('[power]\nvalue_W = 0.01\n[law]\nmaterials = ["I600", "A405"]\n'
                    'database = ["case_file.csv"]\n[geometry]\ncontact_type = "TUBE_BAV"\n'
                    'mobile_radius_m = 0.0111\nobstacle_width_m = 0.0127\n'
                    '[time]\ninstants = [1, 2]\nunit = "year"\n', encoding="utf-8")
    year = 31_536_000.0
    out = tmp_path / "case.csv"
    assert main(["run", str(case), "-o", str(out)]) == 0
    np.testing.assert_allclose(read_wear_table(out)["volume_mobile"],
                               3.1e-14 * 0.01 * year * np.array([1, 2]), rtol=1e-15)
    capsys.readouterr()
    assert main(["run", str(case), "-o", str(out), "--database",
                 str(tmp_path / "cli_file.csv")]) == 0
    printed = "".join(capsys.readouterr().out.split())  # wherever rich wraps the path
    assert "cli_file.csv" in printed  # the summary names the coefficient's file
    np.testing.assert_allclose(read_wear_table(out)["volume_mobile"],
                               1.24e-14 * 0.01 * year * np.array([1, 2]), rtol=1e-15)
    assert case.read_text(encoding="utf-8").count("database") == 1  # the case file untouched
    assert main(["run", str(case), "--database", str(tmp_path / "absent.csv")]) == 2
    assert "absent.csv" in capsys.readouterr().err
