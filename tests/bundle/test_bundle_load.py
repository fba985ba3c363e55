"""fretwear.bundle.load: a finished bundle read back from its output directory without its
history files (issue 26, point 5), the same summary as the run's own result."""

from __future__ import annotations

import os
import shutil

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import load, run_bundle
from fretwear.errors import InputError


def _snapshot(root):
    return sorted((str(p.relative_to(root)), p.stat().st_mtime_ns) for p in root.rglob("*"))


def test_load_gives_the_runs_summary_without_the_histories(tmp_path):
    manifest, case = write_bundle(tmp_path / "in", oscillator(), count=4)
    out = tmp_path / "out"
    result = run_bundle(manifest, case=case, output=out, scheduler="serial")
    shutil.rmtree(tmp_path / "in" / "histories")  # the histories are gone
    before = _snapshot(out)
    back = load(out)
    assert _snapshot(out) == before  # read only: nothing written, nothing created
    # same process and machine: the files round-trip the floats exactly (Parquet)
    pd.testing.assert_frame_equal(back.summary().drop(columns=["history"]),
                                  result.summary().drop(columns=["history"]),
                                  check_dtype=False)
    assert back.stats["contacts"] == 4 and back.output == str(out)
    assert set(back.contacts["status"]) == {"done"}
    assert back.contacts["law"].tolist() == result.contacts["law"].tolist()


def test_load_names_what_is_missing(tmp_path):
    with pytest.raises(InputError, match="not a bundle output directory"):
        load(tmp_path / "nowhere")
    (tmp_path / "half").mkdir()
    with pytest.raises(InputError, match="no finished bundle run"):
        load(tmp_path / "half")
    assert os.listdir(tmp_path / "half") == []


def test_report_on_a_bundle_directory_reads_it_back(tmp_path, capsys):
    from fretwear.cli import main

    manifest, case = write_bundle(tmp_path / "in", oscillator(), count=4,
                                  extra={"wall_thickness_m": [1e-4] * 4})  # a thin wall
    out = tmp_path / "out"
    run_bundle(manifest, case=case, output=out, scheduler="serial")
    shutil.rmtree(tmp_path / "in" / "histories")
    assert main(["report", str(out), "-o", str(tmp_path / "r.html")]) == 0
    html = (tmp_path / "r.html").read_text(encoding="utf-8")
    assert main(["report", str(out)]) == 0  # without -o: the bundle's own report.html
    assert (out / "report.html").read_text(encoding="utf-8").count("data:image/png") == 2
    worst = load(out).summary().iloc[0]
    assert html.count("data:image/png;base64,") == 2
    if worst["depth_fraction"] >= 0.4:  # bad news first, the worst named
        assert html.index('class="alarm"') < html.index('id="inputs"')
        assert worst["contact"] in html
