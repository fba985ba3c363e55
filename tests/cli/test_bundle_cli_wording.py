"""Wording of ``fretwear bundle`` on the shipped example bundle (examples/bundle, 24 contacts,
run serially): --top's range and singular, the options named in the --workers/--scheduler
error, what -q leaves (the bad news and the final line, as its help says), and a run with
nothing to compute saying that no cluster was started. Expected values: the option values
given, the example's 24 contacts, and the bad news computed from the files (tubes.csv's flags,
summary.csv's depths against the limit)."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("xarray")

from fretwear.cli import main  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"
ARGS = ["bundle", str(EXAMPLE / "manifest.csv"), "--case", str(EXAMPLE / "bundle.toml")]


def test_top_must_be_at_least_one_and_one_is_singular(tmp_path, capsys):
    assert main([*ARGS, "--scheduler", "serial", "-o", str(tmp_path), "--top", "0"]) == 2
    assert "--top" in capsys.readouterr().err
    assert main([*ARGS, "--scheduler", "serial", "-o", str(tmp_path), "--top", "1"]) == 0
    out = capsys.readouterr().out
    assert "the deepest contact (" in out
    assert "the 1 deepest" not in out


def test_workers_with_a_scheduler_names_the_options(tmp_path, capsys):
    code = main([*ARGS, "--scheduler", "tcp://127.0.0.1:1", "--workers", "2",
                 "-o", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2
    assert "--workers applies to the local cluster" in err and "--scheduler" in err
    assert main([*ARGS, "--scheduler", "serial", "--workers", "2", "-o", str(tmp_path)]) == 2
    assert "--scheduler serial runs in this process: --workers" in capsys.readouterr().err


def test_quiet_keeps_only_the_bad_news_and_the_final_line_a_skipped_run_starts_no_cluster(
        tmp_path, capsys):
    out_dir = tmp_path / "out"
    assert main([*ARGS, "--scheduler", "serial", "-o", str(out_dir), "-q"]) == 0
    lines = capsys.readouterr().out.splitlines()
    # bad news stays with -q, first (issue 26): the tubes the simulation flagged unstable
    # (tubes.csv beside the manifest), then any contact past the limit (summary.csv's depth
    # fraction against the limit)
    import pandas as pd

    from fretwear.flow.bundle import near_critical_tubes, unstable_tubes

    unstable = unstable_tubes(EXAMPLE / "manifest.csv")
    near = near_critical_tubes(EXAMPLE / "manifest.csv")  # said after the bad news
    summary = pd.read_csv(out_dir / "summary.csv")
    past = int((summary["depth"] >= summary["limit_depth"]).sum())
    kinds = set(pd.read_csv(out_dir / "warnings.csv")["category"])  # one line a kind said
    said = {"PerforationWarning", "UnitsWarning", "ResolutionWarning"} & kinds
    bad = lines[:-1]
    assert len(bad) == (len(unstable) > 0) + (past > 0) + len(said) + (len(near) > 0), lines
    assert bad[-1].startswith("NEAR-CRITICAL") == (len(near) > 0), lines
    assert all(any(b.startswith(f"{kind}: ") for b in bad) for kind in said), lines
    assert bad[0].startswith(f"FLUID-ELASTICALLY UNSTABLE: {len(unstable)} tube(s)"), lines
    assert all(t in bad[0] for t in unstable["tube"])
    assert any(b.startswith("PAST THE PLUGGING LIMIT at ") and f": {past} contact" in b
               for b in bad) == (past > 0)
    assert lines[-1].startswith("done 24, failed 0, skipped 0 of 24 contacts")
    # again: every contact unchanged, nothing computed, no cluster (not "on 1 worker(s)")
    assert main([*ARGS, "-o", str(out_dir), "-q"]) == 0
    *news, line = capsys.readouterr().out.splitlines()
    assert news == bad
    assert line.startswith("done 0, failed 0, skipped 24 of 24 contacts")
    assert "no cluster started" in line
    said = line.split("; results in ")[0]
    assert "worker(s)" not in said and "(cluster start" not in said


def test_the_forecast_column_shows_for_the_contacts_own_limit_only(tmp_path, capsys):
    """The terminal table's forecast (the summary's limit_forecast) for the case's own limit:
    the shallowest contact that wears, its limit not reached by the last instant, has no time
    to limit and its forecast printed as summary.csv has it (4 significant digits;
    tests/bundle/test_bundle_time_to_limit.py checks the value); with another --limit there is
    no forecast, and no empty column."""
    import math

    import pandas as pd

    assert main([*ARGS, "--scheduler", "serial", "-o", str(tmp_path / "a"), "--top", "24"]) == 0
    out = capsys.readouterr().out
    assert "forecast [year]" in out
    summary = pd.read_csv(tmp_path / "a" / "summary.csv")
    worn = summary[summary["power"] > 0]
    shallow = worn.loc[worn["depth"].idxmin()]
    assert math.isnan(shallow["time_to_limit"]) and shallow["limit_forecast"] > 40
    line = next(x for x in out.splitlines() if f" {shallow['contact']} " in x)
    assert f"{shallow['limit_forecast']:.4g}" in line, line
    assert main([*ARGS, "--scheduler", "serial", "-o", str(tmp_path / "b"), "--limit", "0.3"]) \
        == 0
    out = capsys.readouterr().out
    assert "forecast [" not in out and "forecast:" not in out


def test_letter_rows_leave_out_the_map_not_the_other_figures(tmp_path, capsys):
    """A manifest numbering its rows with letters: --plot says why there is no tube-sheet map
    and still writes the power and worst-depth figures and the final line, exit 0 (the map's
    error stopped the command with exit 2 and no figure)."""
    import pandas as pd

    pytest.importorskip("matplotlib")
    frame = pd.read_csv(EXAMPLE / "manifest.csv")
    frame["history"] = [str(EXAMPLE / h) for h in frame["history"]]
    frame["tube_row"] = [chr(ord("A") + int(r) - 1) for r in frame["tube_row"]]
    manifest = tmp_path / "letters.csv"
    frame.to_csv(manifest, index=False)
    figures = tmp_path / "figures"
    code = main(["bundle", str(manifest), "--case", str(EXAMPLE / "bundle.toml"), "--scheduler",
                 "serial", "-o", str(tmp_path / "out"), "--plot", str(figures)])
    out = capsys.readouterr().out
    assert code == 0
    assert "no tube-sheet map: the tube-sheet map needs tube_row and tube_column as numbers" \
        in " ".join(out.split())
    assert sorted(p.name for p in figures.iterdir()) == [
        "bundle_power.png", "bundle_power.svg", "bundle_worst_depths.png",
        "bundle_worst_depths.svg"]
    assert out.splitlines()[-1].startswith("done 24, failed 0, skipped 0 of 24 contacts")


KWU = """[law]
name = "KWU_EPRI"
mobile = { COEF_USURE = 5.2e-14, reference_intensity = 1.0e-7 }
[geometry]
contact_type = "TUBE_ALESAGE"
mobile_radius_m = 9.525e-3
obstacle_radius_m = 9.725e-3
obstacle_width_m = 20e-3
[time]
instants = [10, 100]
unit = "hour"
"""


def test_the_final_lines_say_how_many_contacts_were_read_twice(tmp_path, capsys):
    """issue 28: KWU-EPRI contacts without both class ranges are read twice, which the run
    says with the keys that read them once; a contact given both (manifest columns) is not
    counted. Expected: 1 of the 2 contacts of this manifest."""
    history = Path(__file__).resolve().parents[2] / "examples" / "data" / "oscillator_gap.csv"
    (tmp_path / "kwu.toml").write_text(KWU)
    (tmp_path / "m.csv").write_text(f"contact,history,force_max_N,speed_max_m_per_s\n"
                                    f"a,{history},,\nb,{history},400,0.5\n")
    assert main(["bundle", str(tmp_path / "m.csv"), "--case", str(tmp_path / "kwu.toml"),
                 "--scheduler", "serial", "-o", str(tmp_path / "out"), "-q"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[-1] == ("1 KWU-EPRI contact(s) read twice (the class bounds from the "
                         "window's maxima); give force_max_N and speed_max_m_per_s (FNOR_MAXI, "
                         "VTAN_MAXI) in the case or the manifest to read them once")
