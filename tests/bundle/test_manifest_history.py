"""A manifest whose rows name no history and give no power, with a base case giving none:
one InputError before any work, naming the ``history`` column and the two fixes (a new user's
trial: one error per contact, 24 times the same message, before). Where a power is given (the
base case's ``[power] value_W``, or a ``power.value_W`` column) the same manifest runs, each
contact at that power (the given value, read back from the table: independent of the check)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle import run_bundle
from fretwear.cli import main
from fretwear.errors import InputError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"
BASE = """[law]
name = "ARCHARD"
materials = ["I690", "A405"]
[geometry]
contact_type = "TUBE_BAV"
mobile_radius_m = 9.525e-3
obstacle_width_m = 12.7e-3
[time]
instants = [1, 2]
unit = "year"
"""


def _no_history(tmp_path) -> Path:
    frame = pd.read_csv(EXAMPLE / "manifest.csv").drop(columns="history").head(4)
    path = tmp_path / "manifest.csv"
    frame.to_csv(path, index=False)
    return path


def test_no_history_and_no_power_is_one_error_before_any_work(tmp_path, capsys):
    manifest, case = _no_history(tmp_path), tmp_path / "base.toml"
    case.write_text(BASE)
    out = tmp_path / "out"
    with pytest.raises(InputError, match=r"none of its 4 contacts has a history") as info:
        run_bundle(manifest, case, scheduler="serial", output=out)
    assert "'history' column" in str(info.value) and "power.value_W" in str(info.value)
    assert not out.exists()  # nothing computed, nothing left behind
    assert main(["bundle", str(manifest), "--case", str(case), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("has a history") == 1 and "'history' column" in err


def test_a_given_power_still_runs_the_manifest_without_histories(tmp_path):
    manifest, case = _no_history(tmp_path), tmp_path / "base.toml"
    case.write_text(BASE + "[power]\nvalue_W = 1e-4\n")
    result = run_bundle(manifest, case, scheduler="serial")
    assert result.errors.empty
    np.testing.assert_allclose(result.summary()["power"], 1e-4, rtol=1e-12)
    frame = pd.read_csv(manifest).assign(**{"power.value_W": 2e-4})
    case.write_text(BASE)
    result = run_bundle(frame, case, scheduler="serial")
    assert result.errors.empty
    np.testing.assert_allclose(result.summary()["power"], 2e-4, rtol=1e-12)
