"""The depth limit of a bundle's summary given one way only, and carried to the output files:
``summary(limit, limit_m=...)`` refuses both at once, and ``run_bundle(limit=...)`` (the
command's ``--limit``) writes ``summary.csv`` at that limit and records it in ``run.json``; a
limit that is not a fraction of the wall in (0, 1] is refused before anything runs.

Expected values: the limit depth is the fraction times the wall thickness the manifest gives
(``limit_depth = limit × wall_thickness_m``, the definition in docs/bundle.md), and the file
holds what ``BundleResult.summary(limit)`` returns for the same contacts."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.cli import main
from fretwear.errors import KeywordError

pytest.importorskip("xarray")

WALL = 1.09e-3  # [m], the manifest's wall thickness of every tube below


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    """A manifest of 2 contacts (bundle_helpers: 0.6 s of the shipped oscillator history, the
    force scaled per contact) with a wall of 1.09 mm, and its base case."""
    directory = tmp_path_factory.mktemp("limit")
    manifest, case = write_bundle(directory, oscillator(), 2,
                                  extra={"wall_thickness_m": [WALL, WALL]})
    return manifest, case


def test_summary_refuses_a_fraction_and_a_depth_together(bundle):
    manifest, case = bundle
    result = run_bundle(manifest, case, scheduler="serial")
    with pytest.raises(KeywordError) as raised:
        result.summary(0.4, limit_m=1e-3)
    message = str(raised.value)
    assert "limit" in message and "limit_m" in message and "one" in message
    # each alone still works: 0.4 × 1.09 mm, and 1 mm as given
    assert np.allclose(result.summary(0.4)["limit_depth"], 0.4 * WALL, rtol=1e-15)
    assert (result.summary(limit_m=1e-3)["limit_depth"] == 1e-3).all()


def test_run_bundle_writes_summary_csv_at_the_limit_asked_and_records_it(bundle, tmp_path):
    manifest, case = bundle
    out = tmp_path / "out"
    result = run_bundle(manifest, case, scheduler="serial", output=out, limit=0.2)
    written = pd.read_csv(out / "summary.csv")
    # 0.2 × the manifest's 1.09 mm wall, not the case's default 0.4
    assert np.allclose(written["limit_depth"], 0.2 * WALL, rtol=1e-15)
    expected = result.summary(0.2)
    for column in ("contact", "limit_depth", "time_to_limit", "time_to_limit_method"):
        pd.testing.assert_series_equal(written[column], expected[column], check_dtype=False)
    assert json.loads((out / "run.json").read_text())["limit"] == 0.2
    # no limit: each contact's own depth_limit (0.4 here), and null in run.json
    run_bundle(manifest, case, scheduler="serial", output=out)
    assert np.allclose(pd.read_csv(out / "summary.csv")["limit_depth"], 0.4 * WALL, rtol=1e-15)
    assert json.loads((out / "run.json").read_text())["limit"] is None


@pytest.mark.parametrize("bad", [0, -0.2, 1.5, math.nan, math.inf, True, "0.2"])
def test_run_bundle_refuses_a_limit_that_is_not_a_fraction_before_running(bundle, tmp_path,
                                                                          bad):
    manifest, case = bundle
    with pytest.raises(KeywordError, match=r"limit must be a fraction of the wall"):
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out", limit=bad)
    assert not (tmp_path / "out").exists()  # refused up front: nothing computed or written


def test_the_command_passes_limit_to_summary_csv(tmp_path, capsys):
    """The shipped example bundle (examples/bundle, walls of 1.09 mm): --limit 0.2 gives the
    terminal table's header and summary.csv the same limit."""
    example = Path(__file__).resolve().parents[2] / "examples" / "bundle"
    out = tmp_path / "out"
    assert main(["bundle", str(example / "manifest.csv"), "--case",
                 str(example / "bundle.toml"), "--scheduler", "serial", "-o", str(out),
                 "--limit", "0.2"]) == 0
    assert "limit: 20% of the wall" in capsys.readouterr().out
    written = pd.read_csv(out / "summary.csv")
    assert len(written) == 24
    assert np.allclose(written["limit_depth"], 0.2 * 1.09e-3, rtol=1e-15)
    assert json.loads((out / "run.json").read_text())["limit"] == 0.2


@pytest.mark.parametrize("bad", [40, 1.5, 0])
def test_summary_refuses_a_limit_that_is_not_a_fraction(bundle, bad):
    """summary() takes the limits run_bundle and --limit take: 40 given for 40 % is a
    KeywordError saying what a fraction of the wall is, not a depth 40 walls deep that no
    contact reaches (summary() used to accept any positive fraction)."""
    manifest, case = bundle
    result = run_bundle(manifest, case, scheduler="serial")
    with pytest.raises(KeywordError, match=r"0 < limit <= 1 \[-\] \(0\.4: 40 % through-wall\)"):
        result.summary(bad)
    assert len(result.summary(1)) == len(result.contacts)  # through-wall: accepted


def test_numpy_numbers_are_limits_too(bundle):
    """A limit computed with numpy (np.float32(0.4), np.int64(1)) is a number like any other
    (refused after the (0, 1] check was added: a review); numpy's bool is not."""
    import numpy as np

    manifest, case = bundle
    result = run_bundle(manifest, case, scheduler="serial", limit=np.float64(0.2))
    for limit in (np.float32(0.4), np.int64(1)):
        got = result.summary(limit)
        expected = result.summary(float(limit))
        assert got["time_to_limit"].equals(expected["time_to_limit"])
    with pytest.raises(KeywordError, match="limit must be a fraction of the wall"):
        result.summary(np.bool_(True))
