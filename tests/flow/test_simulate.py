"""``fretwear simulate`` end to end: description → histories and manifest → ``fretwear bundle``.

Physics checked: two rows at 2.0 and 3.5 m/s with the same gaps; the SPEC_LONG_COR_1 force
spectrum grows as ρ²U³ at a given reduced frequency, so the faster row's tube rattles harder and
its contacts' wear power is larger; its stability ratio is U₂/U₁ times the slower row's (same
modes, same damping: Connors' U_c is the same, U_eff = U for a uniform flow).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.cli import main
from fretwear.errors import InputError, KeywordError
from fretwear.flow.bundle import MANIFEST_COLUMNS, run_simulate, simulate_tube
from fretwear.flow.description import read_description

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


def small_description(tmp_path: Path, **changes: str) -> Path:
    text = (EXAMPLE / "bundle_geometry.toml").read_text(encoding="utf-8")
    text = text.replace("rows = 4\n", "rows = 2\n").replace("columns = 3\n", "columns = 1\n")
    text = text.replace("duration_s = 0.7", "duration_s = 0.4")
    text = text.replace('gap_m = { distribution = "lognormal", median = 10e-6, sigma_ln = 0.8 }',
                        "gap_m = 5e-6")
    head, _, _ = text.partition("[[flow.regions]]")
    text = head + """[[flow.regions]]
rows = [1]
velocity_m_s = 2.0
density_kg_m3 = 350.0
void_fraction = 0.55

[[flow.regions]]
rows = [2]
velocity_m_s = 3.5
density_kg_m3 = 350.0
void_fraction = 0.55

[simulation]
duration_s = 0.4
archive_step_s = 5e-4
grid_points = 121
frequency_points = 200
"""
    for old, new in changes.items():
        text = text.replace(old, new)
    path = tmp_path / "bundle.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_simulate_then_bundle(tmp_path, capsys):
    desc = small_description(tmp_path)
    out = tmp_path / "histories"
    assert main(["simulate", str(desc), "-o", str(out), "--scheduler", "serial"]) == 0
    printed = capsys.readouterr().out
    assert "done 2, reused 0, failed 0 of 2 tubes" in printed
    manifest = pd.read_csv(out / "manifest.csv")
    assert tuple(manifest.columns) == MANIFEST_COLUMNS
    assert len(manifest) == 4 and all((out / h).exists() for h in manifest["history"])
    tubes = pd.read_csv(out / "tubes.csv").set_index("row")
    assert tubes.loc[2, "max_wear_power_w"] > 2 * tubes.loc[1, "max_wear_power_w"] > 0
    assert tubes.loc[2, "max_stability_ratio"] == pytest.approx(
        3.5 / 2.0 * tubes.loc[1, "max_stability_ratio"], rel=1e-5)  # tubes.csv: 6 digits
    # a rerun reuses both tubes, histories untouched
    stamp = (out / manifest["history"][0]).stat().st_mtime_ns
    assert main(["simulate", str(desc), "-o", str(out), "--scheduler", "serial"]) == 0
    assert "done 0, reused 2" in capsys.readouterr().out
    assert (out / manifest["history"][0]).stat().st_mtime_ns == stamp
    # fretwear bundle reads the manifest as it is
    wear = tmp_path / "wear"
    code = main(["bundle", str(out / "manifest.csv"), "--case", str(EXAMPLE / "bundle.toml"),
                 "-o", str(wear), "--scheduler", "serial", "-q"])
    assert code == 0
    assert (wear / "summary.csv").exists()


def test_changed_input_recomputes_only_that(tmp_path):
    desc = small_description(tmp_path)
    out = tmp_path / "h"
    first = run_simulate(desc, out, scheduler="serial")
    assert not first.reused and not first.errors
    changed = small_description(tmp_path, **{"velocity_m_s = 3.5": "velocity_m_s = 3.0"})
    second = run_simulate(changed, out, scheduler="serial")
    assert second.reused == ["R1C1"]


def test_description_errors_name_the_culprit(tmp_path):
    with pytest.raises(KeywordError, match=r"\[tubes\].*unknown key.*'colums'"):
        read_description(small_description(tmp_path, **{"columns = 1": "colums = 1"}))
    with pytest.raises(InputError, match=r"rows \[3\] have no \[\[flow.regions\]\]"):
        read_description(small_description(tmp_path, **{"rows = 2\n": "rows = 3\n"}))
    with pytest.raises(InputError, match="overlaps another region on row 1"):
        read_description(small_description(tmp_path, **{"rows = [2]": "rows = [1]"}))
    with pytest.raises(KeywordError, match="SPEC_LONG_COR_1"):
        read_description(small_description(tmp_path, **{'"SPEC_LONG_COR_1"': '"SPEC_X"'}))
    with pytest.raises(InputError, match="beyond the span"):
        read_description(small_description(tmp_path, **{"position_m = 0.8": "position_m = 1.3"}))


def test_example_description_gaps_are_seeded():
    a, b = read_description(EXAMPLE / "bundle_geometry.toml"), read_description(
        EXAMPLE / "bundle_geometry.toml")
    assert [s.supports for s in a] == [s.supports for s in b]
    gaps = [c["gap_m"] for s in a for c in s.supports]
    assert len(set(gaps)) == len(gaps) == 24


def test_a_failing_tube_is_isolated(tmp_path, capsys):
    """GRAPPE_2 at 1.0 m: inside row 1's 1.2 m span, beyond row 2's 0.9 m one. Row 2's tube fails
    in its task (the spectrum's own message), row 1's is written; exit status 1."""
    desc = small_description(tmp_path, **{
        'spectrum = "SPEC_LONG_COR_1"': 'spectrum = "GRAPPE_2"',
        "parameters = { long_cor = 3.0, kinematic_viscosity = 1.2e-7 }":
            'parameters = { configuration = "ASC_CEN", density = 700.0, velocity = 3.0, '
            "position = 1.0 }",
        "span_lengths_m = 1.2": "span_lengths_m = [1.2, 0.9]"})
    out = tmp_path / "h"
    assert main(["simulate", str(desc), "-o", str(out), "--scheduler", "serial"]) == 1
    printed = capsys.readouterr().out
    assert printed.index("1 tube(s) failed") < printed.index("R1C1")  # bad news first
    errors = pd.read_csv(out / "errors.csv")
    assert list(errors["tube"]) == ["R2C1"] and "outside the tube" in errors["error"][0]
    assert set(pd.read_csv(out / "manifest.csv")["contact"]) == {"R1C1-AVB1", "R1C1-AVB2"}


def test_a_tube_gaps_and_power_do_not_depend_on_the_bundle_size(tmp_path):
    """R4C1 is the same tube in a 4x3 and a 4x1 bundle with the same seed: its drawn gaps
    (per-contact streams default_rng([seed, row, column, k])) and so its simulated wear power
    are the same. Before the fix one shared stream drew the 4x3 bundle's 24 gaps in order, and
    R4C1's gaps were the 19th-20th draws in 4x3 but the 7th-8th in 4x1 (independent check: the
    same stream drawn by hand). Both runs are in one process on one machine: 1e-12 relative."""
    text = (EXAMPLE / "bundle_geometry.toml").read_text(encoding="utf-8")
    text = text.replace("duration_s = 0.7", "duration_s = 0.2")
    wide, narrow = tmp_path / "wide.toml", tmp_path / "narrow.toml"
    wide.write_text(text, encoding="utf-8")
    narrow.write_text(text.replace("columns = 3\n", "columns = 1\n"), encoding="utf-8")
    a = {s.tube: s for s in read_description(wide)}["R4C1"]
    b = {s.tube: s for s in read_description(narrow)}["R4C1"]
    gaps_a = [c["gap_m"] for c in a.supports]
    gaps_b = [c["gap_m"] for c in b.supports]
    np.testing.assert_allclose(gaps_a, gaps_b, rtol=1e-12)
    assert len(set(gaps_a)) == 2   # drawn, distinct
    median, sigma = 10e-6, 0.8     # bundle_geometry.toml's lognormal gaps
    by_hand = [median * np.exp(sigma * np.random.default_rng([2026, 4, 1, k]).standard_normal())
               for k in (1, 2)]
    np.testing.assert_allclose(gaps_a, by_hand, rtol=1e-12)
    power_a = simulate_tube(a, tmp_path / "a")["wear_power_w"]
    power_b = simulate_tube(b, tmp_path / "b")["wear_power_w"]
    assert power_a.keys() == power_b.keys()
    for name in power_a:
        assert power_a[name] > 0
        assert power_b[name] == pytest.approx(power_a[name], rel=1e-12)
