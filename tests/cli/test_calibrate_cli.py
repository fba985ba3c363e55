"""``fretwear calibrate``: the same posterior as the library, on a case file and on a bundle's
output directory (predictions rebuilt from its records), forecast written and figures drawn.

Oracle for the case: the conjugate closed form of docs/uncertainty.md §4 (TUBE_TUBE without
obstacle wear: d ∝ (f·K·P·t)^(2/5), so ln d is affine in ln f with slope 2/5).
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.cli import main
from fretwear.table import read_wear_table
from fretwear.uncertainty import LogNormal
from fretwear.workflows.case_files import load_case, run_case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
YEAR = 31536000.0


@pytest.fixture
def case_file(tmp_path):
    """The tube_tube example without obstacle wear (so the map is a power law of f)."""
    text = (EXAMPLES / "tube_tube.toml").read_text(encoding="utf-8")
    text = text.replace('obstacle = { COEF_USURE = 1.0e-12 }', "")
    path = tmp_path / "tt.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_case_calibration_matches_the_closed_form(case_file, tmp_path, capsys):
    insp = tmp_path / "insp.csv"
    insp.write_text("instant,depth_mm\n0.5,0.6\n1.0,0.75\n")
    out = tmp_path / "forecast.csv"
    assert main(["calibrate", str(insp), "--case", str(case_file), "--prior-sigma-ln", "0.5",
                 "--measurement-sigma", "0.2", "--forecast", "2", "-o", str(out),
                 "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["method"] == "conjugate"
    # closed form: ln d_i = a_i + (2/5)·λ, a_i = ln d_i(f = 1)
    table = run_case(load_case(case_file)).table
    d1 = dict(zip(table["instant"], table["depth_mobile"], strict=True))
    prec, num = 1 / 0.5 ** 2, 0.0
    for t, y in ((0.5, 0.6e-3), (1.0, 0.75e-3)):
        prec += 0.4 ** 2 / 0.2 ** 2
        num += 0.4 * (math.log(y) - math.log(d1[t])) / 0.2 ** 2
    assert math.log(payload["posterior"]["median"]) == pytest.approx(num / prec, rel=1e-9)
    assert payload["posterior"]["sigma_ln"] == pytest.approx(math.sqrt(1 / prec), rel=1e-9)
    forecast = pd.read_csv(out)
    f50 = math.exp(num / prec)
    assert forecast["depth_q50"].iloc[0] == pytest.approx(d1[2.0] * f50 ** 0.4, rel=1e-9)



@pytest.mark.parametrize("content", ["instant,depth_mm\n0.5,0.6\n1.0,NDD\n",
                                     "instant,depth,result\n0.5,6e-4,sized\n1.0,,NDD\n"])
def test_case_with_an_ndd_row_names_bundle(case_file, tmp_path, capsys, content):
    """A new user's trial: --case with an NDD row said only that the depth must be > 0 (or
    that 'result' is unknown); the message now names the fix, --bundle with a POD (fails
    before, passes after)."""
    insp = tmp_path / "insp.csv"
    insp.write_text(content, encoding="utf-8")
    assert main(["calibrate", str(insp), "--case", str(case_file)]) == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "NDD (no detectable degradation)" in err
    assert "--bundle RESULTS" in err and "--pod-a50-mm and --pod-a90-mm" in err
    insp.write_text("instant,depth_um\n0.5,600\n", encoding="utf-8")  # no NDD: no hint
    assert main(["calibrate", str(insp), "--case", str(case_file)]) == 2
    assert "--bundle" not in capsys.readouterr().err

def test_errors(case_file, tmp_path, capsys):
    insp = tmp_path / "insp.csv"
    insp.write_text("instant,depth_mm\n0.5,0.6\n")
    assert main(["calibrate", str(insp)]) == 2
    assert "exactly one of --case" in capsys.readouterr().err
    insp.write_text("instant,depth_um\n0.5,600\n")
    assert main(["calibrate", str(insp), "--case", str(case_file)]) == 2
    assert "unknown column(s) ['depth_um']" in capsys.readouterr().err


@pytest.fixture(scope="module")
def bundle_output(tmp_path_factory):
    from fretwear.bundle import run_bundle

    out = tmp_path_factory.mktemp("bundle") / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = run_bundle(EXAMPLES / "bundle" / "manifest.csv",
                            EXAMPLES / "bundle" / "bundle.toml", scheduler="serial",
                            output=out)
    return out, result


def test_bundle_calibration(bundle_output, tmp_path, capsys):
    out, result = bundle_output
    table = result.table
    at10 = table[table["instant"] == 10].drop_duplicates("contact")
    deepest = at10.sort_values("depth_mobile", ascending=False).head(3)
    contacts = deepest["contact"].tolist()
    rows = [{"contact": c, "instant": 10, "depth": 1.5 * d}
            for c, d in zip(contacts, deepest["depth_mobile"], strict=True)]
    insp = tmp_path / "insp.csv"
    pd.DataFrame(rows).to_csv(insp, index=False)
    forecast = tmp_path / "fc.csv"
    plots = tmp_path / "figs"
    assert main(["calibrate", str(insp), "--bundle", str(out), "--forecast", "30",
                 "--prior-sigma-ln", "0.5", "-o", str(forecast), "--plot", str(plots)]) == 0
    text = capsys.readouterr().out
    fc = pd.read_csv(forecast)
    assert {"tube_row", "tube_column", "support", "exceedance"} <= set(fc.columns)
    assert set(fc["contact"]) == set(table["contact"])
    assert np.all(np.diff(fc["exceedance"]) <= 0)  # ranked
    assert {p.name for p in plots.iterdir()} == {"exceedance_map.png", "exceedance_map.svg"}
    # the same posterior as the library's hierarchical calibration (issue 26) on the contacts'
    # own tables (bundle rows + records), and bad news first
    from fretwear.assessment import FactorPrior, LogSizingModel, Technique, calibrate_bundle
    from fretwear.report.predictions import bundle_predictions

    tables, identity = bundle_predictions(out)
    direct = calibrate_bundle(tables, insp, techniques=Technique(LogSizingModel(0.1)),
                              prior=FactorPrior(LogNormal(1.0, sigma_ln=0.5)),
                              identity=identity, power_sigma_ln=0.2)  # the option's default
    median, (low, high) = direct.bundle_factor()
    assert f"bundle factor: median {median:.4g}, 90 % [{low:.4g}, {high:.4g}]" in text
    assert text.index("at or past the limit") < text.index("bundle factor")
    assert f"the 10 worst of {identity.drop_duplicates(['tube_row', 'tube_column']).shape[0]}" \
        f" tubes" in text
    # the rows of one contact equal the bundle's table
    one = read_wear_table(out / "table.parquet") if (out / "table.parquet").exists() else None
    if one is not None:
        assert len(tables[contacts[0]]) == (one["contact"] == contacts[0]).sum()


def test_the_readmes_calibrate_line_runs_on_the_shipped_inspections(bundle_output, capsys):
    """README: ``fretwear calibrate examples/bundle/inspections.csv --bundle build/bundle``
    (issue 29: the line named a file nobody had)."""
    out, _ = bundle_output
    readme = (EXAMPLES.parent / "README.md").read_text(encoding="utf-8")
    assert "fretwear calibrate examples/bundle/inspections.csv --bundle build/bundle" in readme
    assert main(["calibrate", str(EXAMPLES / "bundle" / "inspections.csv"), "--bundle",
                 str(out)]) == 0
    assert "bundle factor: median" in capsys.readouterr().out
