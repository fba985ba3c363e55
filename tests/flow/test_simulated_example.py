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
