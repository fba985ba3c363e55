"""`fretwear run` end to end on every example case file, outputs and errors.

Checks against independent computations: the table written equals run_case's (the library
call) and the Code_Aster table written reads back with the same values (SPEC §7 names).
"""

import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.case import run_case
from fretwear.cli import main
from fretwear.io.aster import read_aster_table

# the example cases of `fretwear run` (those with an [iterate] section belong to `fretwear iterate`)
EXAMPLES = [p for p in sorted((Path(__file__).parents[2] / "examples").glob("*.toml"))
            if "iterate" not in tomllib.loads(p.read_text(encoding="utf-8"))]


@pytest.mark.parametrize("case", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_every_example_runs(case, tmp_path, capsys):
    out = tmp_path / "table.csv"
    assert main(["run", str(case), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "wear power P" in printed and "table written" in printed
    table = pd.read_csv(out)
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
    pq = tmp_path / "wear.parquet"
    assert main(["run", str(case), "-q", "-o", str(pq), "--aster-names"]) == 0
    assert "PUIS_USUR_SECT" in pd.read_parquet(pq).columns


def test_help_documents_every_key(capsys):
    assert main(["run", "--help"]) == 0
    text = capsys.readouterr().out
    for key in ("mobile_radius_m", "seconds_per_unit", "tube_replacement", "edges_deg",
                "obstacle_coefficients_per_Pa", "value_W", "[restart]"):
        assert key in text


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
