"""The shipped example bundle (examples/bundle): the output of
``fretwear simulate examples/bundle/bundle_geometry.toml -o examples/bundle``.

Checked: it is the output of the shipped description as it reads today (every tube's inputs'
signature in its tube.json), ``fretwear bundle`` reads its manifest as it is, the contacts' wear
power grows toward the faster rows, and the stability ratios follow Connors' form independently
of the code: the rows differ only by their uniform velocity (same tube, same density 350 kg/m³,
same added mass), so U_eff = U and U_c is the same, and ratio/U is one constant.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.bundle import run_bundle
from fretwear.flow.description import read_description

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"
SIMULATED = EXAMPLE  # the simulation writes into the example directory itself
VELOCITY = {1: 2.0, 2: 2.5, 3: 3.0, 4: 3.5}   # bundle_geometry.toml's [[flow.regions]]


def test_shipped_outputs_are_those_of_the_shipped_description():
    specs = read_description(EXAMPLE / "bundle_geometry.toml")
    for spec in specs:
        record = json.loads((SIMULATED / "tubes" / spec.tube / "tube.json").read_text())
        assert record["signature"] == spec.signature(), (
            f"{spec.tube}: examples/bundle is stale; rerun fretwear simulate "
            "examples/bundle/bundle_geometry.toml -o examples/bundle --force")
    assert pd.read_csv(SIMULATED / "errors.csv").empty


def test_stability_ratio_is_proportional_to_the_row_velocity():
    tubes = pd.read_csv(SIMULATED / "tubes.csv")
    per_velocity = tubes["max_stability_ratio"] / tubes["row"].map(VELOCITY)
    np.testing.assert_allclose(per_velocity, per_velocity.iloc[0], rtol=1e-5)  # 6 digits
    assert tubes["flagged"].tolist() == (tubes["max_stability_ratio"] > 1.0).tolist()


def test_bundle_reads_the_manifest_and_wear_grows_toward_the_fast_rows():
    result = run_bundle(SIMULATED / "manifest.csv", EXAMPLE / "bundle.toml", scheduler="serial")
    assert result.errors.empty
    by_row = result.summary().groupby("tube_row")["power"].median()
    assert (np.diff(by_row.to_numpy()) > 0).all(), by_row


def test_bundle_terminal_says_the_unstable_tubes_first(tmp_path, capsys):
    """The tubes whose largest per-mode stability ratio (stability.csv, U_eff/U_c) exceeds
    the description's margin (1.0) lead fretwear bundle's output; a hand-written manifest
    with no simulation beside it says nothing of stability."""
    from fretwear.cli import main
    from fretwear.flow.bundle import unstable_tubes

    modes = pd.read_csv(SIMULATED / "stability.csv")
    worst = modes.groupby("tube")["stability_ratio"].max()
    expected = sorted(worst[worst > 1.0].index)           # the margin of bundle_geometry.toml
    found = unstable_tubes(SIMULATED / "manifest.csv")
    assert sorted(found["tube"]) == expected and expected
    np.testing.assert_allclose(found["max_stability_ratio"], worst[found["tube"]], rtol=1e-5)
    hand = tmp_path / "hand"
    hand.mkdir()
    pd.read_csv(EXAMPLE / "manifest.csv").to_csv(hand / "manifest.csv", index=False)
    assert unstable_tubes(hand / "manifest.csv") is None  # no tubes.csv beside it

    code = main(["bundle", str(SIMULATED / "manifest.csv"), "--case",
                 str(EXAMPLE / "bundle.toml"), "--scheduler", "serial",
                 "-o", str(tmp_path / "out"), "-q"])
    output = capsys.readouterr().out
    first = output.splitlines()[0]
    assert code == 0 and first.startswith("FLUID-ELASTICALLY UNSTABLE: 3 tube(s)"), output
    assert all(t in first for t in expected) and "NOT valid" in first


def test_the_ranking_marks_the_unstable_tubes_rows(tmp_path, capsys):
    """Every row of the terminal's ranking whose tube (tube_row, tube_column of the manifest)
    the simulation flagged (tubes.csv: flagged) says UNSTABLE, and no other row does (a new
    user read a flagged tube's forecast in the ranking with no mark beside it)."""
    from fretwear.cli import main

    tubes = pd.read_csv(SIMULATED / "tubes.csv")
    flagged = {f"R{r}C{c}" for r, c, f in zip(tubes["row"], tubes["column"], tubes["flagged"],
                                               strict=True) if f}
    assert flagged
    assert main(["bundle", str(SIMULATED / "manifest.csv"), "--case",
                 str(EXAMPLE / "bundle.toml"), "--scheduler", "serial", "--top", "24",
                 "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    manifest = pd.read_csv(SIMULATED / "manifest.csv")
    rows = [line for line in out.splitlines()
            if any(f" {c} " in line for c in manifest["contact"].astype(str))
            and "UNSTABLE:" not in line]
    assert len(rows) == len(manifest)
    for line in rows:
        contact = next(c for c in manifest["contact"].astype(str) if f" {c} " in line)
        tube = manifest.loc[manifest["contact"] == contact].iloc[0]
        name = f"R{tube['tube_row']}C{tube['tube_column']}"
        assert ("UNSTABLE" in line) == (name in flagged), line


def test_the_bundle_output_keeps_the_unstable_tubes(tmp_path):
    """fretwear bundle keeps the flagged tubes in OUT/unstable_tubes.csv (what assess and
    calibrate --bundle read without the manifest): the same tubes and ratios as
    unstable_tubes of the manifest; a header-only file reads back as an empty list."""
    from fretwear.cli import main
    from fretwear.flow.bundle import record_unstable, recorded_unstable, unstable_tubes

    out = tmp_path / "out"
    assert main(["bundle", str(SIMULATED / "manifest.csv"), "--case",
                 str(EXAMPLE / "bundle.toml"), "--scheduler", "serial", "-o", str(out),
                 "-q"]) == 0
    kept = recorded_unstable(out)
    pd.testing.assert_frame_equal(kept, unstable_tubes(SIMULATED / "manifest.csv"),
                                  check_exact=False, rtol=1e-12)
    record_unstable(out, kept.iloc[:0])
    assert recorded_unstable(out).empty


def test_assess_calibrate_and_reports_say_the_unstable_tubes_first(tmp_path, capsys):
    """The tubes fretwear bundle kept in OUT/unstable_tubes.csv lead fretwear assess (terminal,
    assessment.json, report.html), fretwear calibrate --bundle and fretwear report OUT (a new
    user saw a normal outage decision on a bundle with 3 unstable tubes and no word of it)."""
    import json

    from fretwear.cli import main
    from fretwear.flow.bundle import unstable_tubes

    expected = list(unstable_tubes(SIMULATED / "manifest.csv")["tube"])
    assert expected
    out = tmp_path / "out"
    assert main(["bundle", str(SIMULATED / "manifest.csv"), "--case",
                 str(EXAMPLE / "bundle.toml"), "--scheduler", "serial", "-o", str(out),
                 "-q"]) == 0
    capsys.readouterr()
    oa = tmp_path / "oa"
    assert main(["assess", str(out), str(EXAMPLE / "inspections.csv"), "--interval", "4",
                 "-o", str(oa), "--report"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("FLUID-ELASTICALLY UNSTABLE: 3 tube(s)") and "NOT valid" in first
    assert all(t in first for t in expected)
    kept = json.loads((oa / "assessment.json").read_text(encoding="utf-8"))
    assert [t["tube"] for t in kept["inputs"]["unstable_tubes"]] == expected
    page = (oa / "report.html").read_text(encoding="utf-8")
    assert "FLUID-ELASTICALLY UNSTABLE" in page
    assert page.index("FLUID-ELASTICALLY UNSTABLE") < page.index("P(any")
    assert main(["calibrate", str(EXAMPLE / "inspections.csv"), "--bundle", str(out),
                 "--pod-a50-mm", "0.15", "--pod-a90-mm", "0.3"]) == 0
    assert capsys.readouterr().out.splitlines()[0].startswith("FLUID-ELASTICALLY UNSTABLE")
    assert main(["report", str(out)]) == 0
    assert "FLUID-ELASTICALLY UNSTABLE" in (out / "report.html").read_text(encoding="utf-8")
