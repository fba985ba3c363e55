"""``fretwear assess BUNDLE_OUT INSPECTIONS``: the library's numbers (fretwear.assessment.assess
on fretwear.bundle.load of the same directory), bad news first, the tables written."""

from __future__ import annotations

import json

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.assessment import LogisticPOD, SizingModel
from fretwear.assessment.outage import assess
from fretwear.bundle import load, run_bundle
from fretwear.cli import main


@pytest.fixture(scope="module")
def bundle_out(tmp_path_factory):
    root = tmp_path_factory.mktemp("assess")
    manifest, case = write_bundle(root / "in", oscillator(), count=4,
                                  extra={"wall_thickness_m": [1.09e-3] * 4})
    run_bundle(manifest, case=case, output=root / "out", scheduler="serial")
    return root / "out"


def test_assess_prints_the_librarys_numbers_bad_news_first(bundle_out, tmp_path, capsys):
    summary = load(bundle_out).summary()
    worst = summary.iloc[0]
    # the deepest contact measured past its limit: said first
    insp = tmp_path / "insp.csv"
    pd.DataFrame({"contact": [worst["contact"], summary.iloc[1]["contact"]],
                  "instant": [5.0, 5.0],
                  "depth_mm": [0.5, None], "result": ["", "NDD"]}).to_csv(insp, index=False)
    out = tmp_path / "oa"
    code = main(["assess", str(bundle_out), str(insp), "--interval", "2", "-o", str(out),
                 "--sizing-sigma-mm", "0.05", "--pod-a50-mm", "0.1", "--pod-a90-mm", "0.2"])
    text = capsys.readouterr().out
    assert code == 0
    assert text.splitlines()[0].startswith("1 contact(s) on 1 tube(s) AT OR PAST")
    # the command's defaults are the library's (one default per option)
    lib = assess(load(bundle_out), insp, interval=2.0, sizing=SizingModel(0.0, 1.0, 5e-5),
                 pod=LogisticPOD.from_depths(1e-4, 2e-4))
    written = json.loads((out / "assessment.json").read_text(encoding="utf-8"))["bundle"]
    # same process and machine: the same floats
    assert written["p_any"] == lib.bundle["p_any"]
    assert f"{lib.bundle['p_any']:.3g}" in text
    # the interval is counted from the outage, the inspections' last instant (5): said so
    # (a new user read "by the end of 4 year" on a bundle inspected at year 10)
    assert lib.probability_line() in text
    assert f"within 2 {lib.bundle['unit']} after the outage at 5 " in lib.probability_line()
    assert written["must_plug"] == lib.bundle["must_plug"] and len(lib.bundle["must_plug"]) == 1
    assert lib.bundle["must_plug"][0] in text.splitlines()[0]
    tubes = pd.read_csv(out / "tubes.csv")
    assert len(tubes) == 4 and set(tubes.columns) >= {"tube", "p_exceed", "plug", "reason"}
    assert "illustrative" not in text  # every technique value given


def test_assess_says_the_technique_defaults_are_illustrative(bundle_out, tmp_path, capsys):
    insp = tmp_path / "insp.csv"
    insp.write_text("contact,instant,result\nR1C1-AVB,5,NDD\n", encoding="utf-8")
    code = main(["assess", str(bundle_out), str(insp), "--interval", "1", "-o",
                 str(tmp_path / "oa")])
    assert code == 0
    assert "illustrative technique values (not qualified)" in capsys.readouterr().out


def test_assess_and_calibrate_share_one_set_of_factor_options():
    """Issue 26: the same quantities under one name and one default in both commands (the old
    --contact-sigma/--power-sigma of assess are gone)."""
    import re

    from click.testing import CliRunner

    from fretwear.cli import cli

    texts = [CliRunner().invoke(cli, [name, "--help"], terminal_width=200).output
             for name in ("assess", "calibrate")]
    for text in texts:
        flat = re.sub(r"\s+", " ", text)
        for option, default in (("--contact-sigma-ln", "0.35"), ("--power-sigma-ln", "0.2"),
                                ("--group-sigma-ln", "0.0")):
            assert re.search(re.escape(option) + r" FLOAT RANGE .*?\[default: "
                             + re.escape(default) + r";", flat), option
        assert not re.search(r"--(contact|power)-sigma\b(?!-)", flat)


def test_assessment_json_keeps_the_technique_as_fields_with_units(bundle_out, tmp_path):
    """assessment.json's technique: explicit fields in metres (sizing σ, a50, a90 as given on
    the command line in mm, ×1e-3) read back into the same models (a new user's trial: a Python
    repr before); JSON keeps a float's repr, so the coefficients come back exactly (one
    process)."""
    from fretwear.assessment.technique import from_record

    summary = load(bundle_out).summary()
    insp = tmp_path / "insp.csv"
    pd.DataFrame({"contact": [summary.iloc[0]["contact"]], "instant": [5.0],
                  "depth_mm": [0.05]}).to_csv(insp, index=False)
    out = tmp_path / "oa"
    assert main(["assess", str(bundle_out), str(insp), "--interval", "2", "-o", str(out),
                 "--sizing-sigma-mm", "0.05", "--pod-a50-mm", "0.15",
                 "--pod-a90-mm", "0.3"]) == 0
    inputs = json.loads((out / "assessment.json").read_text(encoding="utf-8"))["inputs"]
    sizing, pod = inputs["sizing"], inputs["pod"]
    assert sizing["model"] == "normal" and pod["model"] == "logistic"
    assert sizing["sigma_m"] == pytest.approx(5e-5, rel=1e-12)
    assert sizing["intercept_m"] == 0.0 and sizing["slope"] == 1.0
    assert pod["a50_m"] == pytest.approx(1.5e-4, rel=1e-12)
    assert pod["a90_m"] == pytest.approx(3e-4, rel=1e-12)
    assert from_record(sizing) == SizingModel(0.0, 1.0, 5e-5)
    assert from_record(pod) == LogisticPOD.from_depths(1.5e-4, 3e-4)
