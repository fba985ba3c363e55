"""The near-critical band of the fluid-elastic stability ratio: tubes not flagged unstable whose
U_eff/U_c exceeds the design threshold (0.75 by default: a 25 % margin on Connors' critical
velocity) are named after the bad news of ``fretwear simulate``, ``bundle``, ``assess`` and the
reports (a new user's trial: the example's row 3 at U/Uc = 0.957 was not flagged).

Independent source: the per-mode table ``stability.csv`` the simulation writes (each mode's
ratio), reduced here by hand to each tube's largest ratio and compared with the band's bounds;
the band's definition threshold < ratio <= margin on explicit ratios.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.cli import main
from fretwear.errors import InputError
from fretwear.flow.bundle import NEAR_CRITICAL_FILE, near_critical_tubes, recorded_unstable
from fretwear.flow.stability import NEAR_CRITICAL, near_critical

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


def _largest_ratio_per_tube() -> pd.Series:
    modes = pd.read_csv(EXAMPLE / "stability.csv")
    return modes.groupby("tube")["stability_ratio"].max()


def test_the_band_is_above_the_threshold_up_to_the_margin():
    ratios = np.array([0.5, 0.75, 0.7500001, 0.957, 1.0, 1.0000001, np.nan])
    assert near_critical(ratios).tolist() == [False, False, True, True, True, False, False]
    assert near_critical(ratios, threshold=0.9, margin=0.95).tolist() == [
        False, False, False, False, False, False, False]
    assert NEAR_CRITICAL == 0.75
    for bad in (0.0, -0.5, float("nan"), float("inf")):
        with pytest.raises(InputError, match="threshold must be a stability ratio"):
            near_critical(ratios, threshold=bad)


def test_the_examples_near_critical_tubes_are_those_of_its_per_mode_table():
    worst = _largest_ratio_per_tube()
    for threshold in (0.75, 0.9, 0.6):
        expected = set(worst[(worst > threshold) & (worst <= 1.0)].index)  # margin 1.0
        found = near_critical_tubes(EXAMPLE / "manifest.csv", threshold)
        assert set(found["tube"]) == expected, threshold
        np.testing.assert_allclose(found["max_stability_ratio"], worst[found["tube"]],
                                   rtol=1e-5)  # tubes.csv keeps 6 digits
        assert (np.diff(found["max_stability_ratio"]) <= 0).all()  # largest first
        assert (found["threshold"] == threshold).all()
    assert {"R3C1", "R2C3"} <= set(near_critical_tubes(EXAMPLE / "manifest.csv")["tube"])


def test_bundle_and_assess_say_the_near_critical_tubes_after_the_bad_news(tmp_path, capsys):
    worst = _largest_ratio_per_tube()
    out = tmp_path / "wear"
    args = ["bundle", str(EXAMPLE / "manifest.csv"), "--case", str(EXAMPLE / "bundle.toml"),
            "--scheduler", "serial", "-o", str(out), "-q"]
    assert main(args) == 0
    lines = capsys.readouterr().out.splitlines()
    near = [i for i, line in enumerate(lines) if line.startswith("NEAR-CRITICAL")]
    assert len(near) == 1, lines
    expected = worst[(worst > 0.75) & (worst <= 1.0)].sort_values(ascending=False)
    line = lines[near[0]]
    assert f"{len(expected)} tube(s)" in line and "threshold 0.75" in line
    assert all(f"{t} ({r:.3g})" in line for t, r in expected.head(5).items()), line
    assert lines[0].startswith("FLUID-ELASTICALLY UNSTABLE")  # bad news stays first
    assert near[0] == len(lines) - 2  # after every bad-news line, before the final line
    assert set(recorded_unstable(out, NEAR_CRITICAL_FILE)["tube"]) == set(expected.index)

    from fretwear.bundle import load
    from fretwear.report.assessment import render_bundle_report

    page = render_bundle_report(load(out))  # the bundle's report: after the bad news too
    assert page.index("FLUID-ELASTICALLY") < page.index("NEAR-CRITICAL")

    assert main([*args, "--near-critical", "0.9"]) == 0  # user-set: only row 3 (0.957)
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("NEAR-"))
    row3 = worst[(worst > 0.9) & (worst <= 1.0)]
    assert f"{len(row3)} tube(s)" in line and "threshold 0.9" in line
    assert all(t in line for t in row3.index) and "R2C1" not in line

    code = main(["assess", str(out), str(EXAMPLE / "inspections.csv"), "--interval", "4",
                 "-o", str(tmp_path / "oa"), "--sizing-sigma-mm", "0.05", "--pod-a50-mm",
                 "0.15", "--pod-a90-mm", "0.30", "--report"])
    text = capsys.readouterr().out.splitlines()
    assert code == 0
    at = [i for i, x in enumerate(text) if x.startswith("NEAR-CRITICAL")]
    bad = [i for i, x in enumerate(text) if x.startswith(("FLUID-ELASTICALLY", "PREDICTED"))]
    assert len(at) == 1 and bad and max(bad) < at[0], text
    kept = json.loads((tmp_path / "oa" / "assessment.json").read_text())["inputs"]
    assert {t["tube"] for t in kept["near_critical_tubes"]} == set(row3.index)
    page = (tmp_path / "oa" / "report.html").read_text(encoding="utf-8")
    assert page.index("FLUID-ELASTICALLY") < page.index("PREDICTED AGAINST") \
        < page.index("NEAR-CRITICAL") < page.index("P(any")  # the report: the same order


def test_a_bad_threshold_is_a_usage_error(tmp_path, capsys):
    code = main(["bundle", str(EXAMPLE / "manifest.csv"), "--case", str(EXAMPLE / "bundle.toml"),
                 "--near-critical", "0", "-o", str(tmp_path)])
    assert code == 2 and "--near-critical" in capsys.readouterr().err


def test_simulate_says_the_stability_news_even_quiet(tmp_path, capsys):
    """fretwear simulate -q keeps the unstable line and the NEAR-CRITICAL line (before: -q
    silenced both with the table); the tubes named are the per-mode table's. The unstable line
    is the one ``bundle``, ``assess`` and the reports say (before: simulate said "N tube(s)
    fluid-elastically unstable: a mode's stability ratio exceeds the margin", naming none)."""
    worst = _largest_ratio_per_tube()
    assert main(["simulate", str(EXAMPLE / "bundle_geometry.toml"), "-o", str(tmp_path / "h"),
                 "--scheduler", "serial", "-q"]) == 0
    lines = capsys.readouterr().out.splitlines()
    flagged = worst[worst > 1.0].sort_values(ascending=False)
    assert lines[0].startswith(f"FLUID-ELASTICALLY UNSTABLE: {len(flagged)} tube(s) flagged "
                               "by the simulation"), lines
    assert all(f"{t} ({r:.3g})" in lines[0] for t, r in flagged.head(5).items()), lines[0]
    assert lines[0].endswith("these tubes' wear and forecasts below are NOT valid.")
    near = worst[(worst > 0.75) & (worst <= 1.0)]
    assert lines[1].startswith(f"NEAR-CRITICAL (fluid-elastic): {len(near)} tube(s)"), lines
    assert lines[2].startswith("done 12, reused 0, failed 0 of 12 tubes") and len(lines) == 3
