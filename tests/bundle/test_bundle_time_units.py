"""Contacts in different time units (the manifest's ``time.unit`` per contact): the summary,
summary.csv, the terminal table of ``fretwear bundle`` and the worst-depths figure say each
contact's unit; the dataset's time variables name the unit of ``instant``; docs/bundle.md lists
every column of the summary with its unit.

The bundle: three contacts of tests/bundle/bundle_helpers.py (base case in years, instants 0.5,
1, 2 and 5), the first given in hours by the manifest (the same instants: 4380, 8760, 17520 and
43800 h, a year being 8760 h in fretwear.timeunits). Expected values are the manifest's units.
"""

from __future__ import annotations

import re
from pathlib import Path

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

pytest.importorskip("xarray")

from fretwear.bundle import run_bundle  # noqa: E402
from fretwear.cli import main  # noqa: E402
from fretwear.plotting.bundle import plot_worst_depths  # noqa: E402

HOURS = "[4380, 8760, 17520, 43800]"
EXPECTED = {"R1C1-AVB": "h", "R1C2-AVB": "year", "R2C1-AVB": "year"}


def _bundle(directory, mixed=True):
    extra = {"wall_thickness_m": [1e-4] * 3}
    if mixed:
        extra.update({"time.unit": ["h", None, None], "time.instants": [HOURS, None, None]})
    return write_bundle(directory, oscillator(), 3, extra=extra)


def test_summary_and_summary_csv_carry_each_contacts_unit(tmp_path):
    manifest, case = _bundle(tmp_path)
    result = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    summary = result.summary()
    assert dict(zip(summary["contact"], summary["time_unit"], strict=True)) == EXPECTED
    # the hour contact's instants stay in hours (43800 h: 5 years of 8760 h)
    last = dict(zip(summary["contact"], summary["instant"], strict=True))
    assert last == {"R1C1-AVB": 43800.0, "R1C2-AVB": 5.0, "R2C1-AVB": 5.0}
    written = pd.read_csv(tmp_path / "out" / "summary.csv")
    assert dict(zip(written["contact"], written["time_unit"], strict=True)) == EXPECTED


def test_terminal_table_names_the_unit_per_row_when_they_differ(tmp_path, capsys):
    manifest, case = _bundle(tmp_path)
    assert main(["bundle", str(manifest), "--case", str(case), "--scheduler", "serial",
                 "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    # the summary table's rows (the bad-news lines above it name contacts too)
    lines = {c: next(line for line in out.splitlines() if c in line and "│" in line)
             for c in EXPECTED}
    assert lines["R1C1-AVB"].rstrip(" │").endswith(" h")
    assert lines["R1C2-AVB"].rstrip(" │").endswith(" year")
    assert "global depth [mm]" in out
    assert "time to limit [" not in out


def test_terminal_table_names_one_unit_in_the_header(tmp_path, capsys):
    manifest, case = _bundle(tmp_path, mixed=False)
    assert main(["bundle", str(manifest), "--case", str(case), "--scheduler", "serial",
                 "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "time to limit [year]" in out
    assert "global depth [mm]" in out
    row = next(line for line in out.splitlines() if "R1C1-AVB" in line and "│" in line)
    assert not row.rstrip(" │").endswith("year")


def test_worst_depths_figure_names_each_curves_unit_when_they_differ(tmp_path):
    manifest, case = _bundle(tmp_path / "mixed")
    fig = plot_worst_depths(run_bundle(manifest, case, scheduler="serial"))
    axis = fig.axes[0]
    labels = {t.get_text() for t in axis.get_legend().get_texts()}
    assert labels == {f"{c} [{u}]" for c, u in EXPECTED.items()}
    assert "legend" in axis.get_xlabel()
    manifest, case = _bundle(tmp_path / "years", mixed=False)
    fig = plot_worst_depths(run_bundle(manifest, case, scheduler="serial"))
    axis = fig.axes[0]
    assert axis.get_xlabel() == "instant [year]"
    assert {t.get_text() for t in axis.get_legend().get_texts()} == set(EXPECTED)


TIME_VARIABLES = ("duration", "origin", "limit_instant", "limit_instant_sector")


def test_dataset_time_variables_carry_the_instants_unit(tmp_path):
    """The table's schema says "user time unit" for these columns; the dataset names the unit
    (the base case's year), as it does on ``instant``."""
    manifest, case = _bundle(tmp_path / "years", mixed=False)
    ds = run_bundle(manifest, case, scheduler="serial").dataset
    assert ds["instant"].attrs["units"] == "year"
    for name in TIME_VARIABLES:
        assert ds[name].attrs["units"] == "year", name
    assert ds["depth_mobile"].attrs["units"] == "m"
    manifest, case = _bundle(tmp_path / "mixed")
    ds = run_bundle(manifest, case, scheduler="serial").dataset
    for name in ("instant", *TIME_VARIABLES):
        assert ds[name].attrs["units"] == "see the time_unit coordinate", name


def test_docs_list_every_summary_column_with_its_unit(tmp_path):
    """docs/bundle.md's table of the summary's columns names each column of summary() once."""
    docs = (Path(__file__).resolve().parents[2] / "docs" / "bundle.md").read_text()
    start = docs.index("The columns of `summary()` and of `OUT/summary.csv`")
    rows = [line for line in docs[start:].split("\n\n")[1].splitlines()
            if line.startswith("| `")]
    documented = []
    for row in rows:
        name, unit = row.split("|")[1:3]
        assert unit.strip(), row  # every column has a unit cell ("-" when none)
        documented += re.findall(r"`([a-z_]+)`", name)
    manifest, case = _bundle(tmp_path)
    summary = run_bundle(manifest, case, scheduler="serial").summary()
    assert sorted(documented) == sorted(summary.columns)


def test_power_histogram_has_integer_ticks_on_its_count_axis():
    """The y axis counts contacts: whole numbers only (3 contacts in 30 bins gave 0.25 steps)."""
    from fretwear.plotting.bundle import plot_power_distribution

    fig = plot_power_distribution(pd.DataFrame({"power": [1e-3, 2e-3, 5e-3]}))
    fig.canvas.draw()
    ticks = fig.axes[0].get_yticks()
    assert len(ticks) >= 2
    assert all(float(t).is_integer() for t in ticks), ticks
