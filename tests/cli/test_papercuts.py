"""New-user papercuts (issue 29, point 6): the report names the case file, the time unit is
named in headers and axes, ``unit = "years"`` is "year", ``fretwear power`` prints no "-0",
``fretwear iterate`` says where it writes (with -q too)."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

from fretwear.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_the_report_names_the_case_file_not_dict(tmp_path):
    from fretwear.report import analyse_case
    from fretwear.workflows.case_files import load_case, run_case

    path = EXAMPLES / "tube_tube.toml"
    case = load_case(path)
    analysis = analyse_case(case, result=run_case(case), source=path)
    assert analysis.source == str(path)


def test_report_headers_and_iteration_axes_name_the_time_unit():
    from fretwear.plotting.dynamics import plot_iteration
    from fretwear.report.html import _unit_label

    assert _unit_label("instant", "year") == "instant [year]"
    assert _unit_label("limit_instant", "h") == "limit_instant [h]"
    assert "user time unit" not in _unit_label("instant")
    s = pd.DataFrame({"cycle": [1, 2], "instant": [1.0, 2.0], "power": [0.1, 0.09],
                      "depth_mobile_max": [1e-5, 2e-5], "depth_obstacle_max": [0.0, 0.0]})
    s.attrs["time_unit"] = "year"
    a = np.linspace(0, 360, 9)
    fig = plot_iteration(s, [(a, np.full(9, 5e-4)), (a, np.full(9, 5.2e-4))])
    assert fig.axes[0].get_xlabel() == "instant [year]"
    from fretwear.cli.run import columns_help

    assert "user time unit" not in columns_help()


def test_years_is_the_unit_year():
    from fretwear.workflows.case_files import load_case, run_case, validate_case

    case = load_case(EXAMPLES / "tube_tube.toml")
    case["time"] = {**case["time"], "unit": "years"}
    given = dict(case["time"])
    table = run_case(validate_case({k: v for k, v in case.items() if k != "_directory"},
                                   source="test")).table
    assert table.attrs["time_unit"] == "year"
    assert given["unit"] == "years"  # the user's dict is not changed


def test_the_power_window_prints_no_minus_zero(tmp_path, capsys):
    path = tmp_path / "h.csv"
    t = np.linspace(0.0, 0.01, 101)
    frame = pd.DataFrame({"time": t, "normal_force": 5.0 + 0 * t, "vt1": 0.01 + 0 * t,
                          "vt2": 0 * t})
    frame.to_csv(path, index=False)
    text = path.read_text().splitlines()
    text[1] = "-0.0" + text[1][text[1].index(","):]  # the first instant written as -0.0
    path.write_text("\n".join(text) + "\n")
    assert main(["power", str(path)]) == 0
    out = capsys.readouterr().out
    assert "[0, 0.01] s" in out and "[-0" not in out


def test_iterate_says_where_it_writes_even_with_q(tmp_path, monkeypatch, capsys):
    import fretwear.cli.iterate as iterate_cli

    columns = ("cycle", "instant", "power", "depth_global_mobile", "depth_sector_mobile_max",
               "depth_mobile_max", "depth_obstacle_max", "clearance_min", "clearance_max",
               "contact_fraction")
    from fretwear.power.confidence import batch_means_interval

    fake = SimpleNamespace(stopped="cycles", max_depth_of=None, warnings=[],
                           summary=pd.DataFrame({**{c: [1.0] for c in columns},
                                                 "perforated": [False],
                                                 "power_change_significant": [None],
                                                 "power_change": [float("nan")]}),
                           directory=tmp_path / "loop_out",
                           intervals=[batch_means_interval([1.0, 1.1] * 5)],
                           convergence=("one cycle", "one cycle: no change to judge"),
                           tables=[pd.DataFrame()])
    fake.tables[0].attrs["time_unit"] = "year"
    monkeypatch.setattr(iterate_cli, "iterate_case", lambda *a, **k: fake)
    case = tmp_path / "c.toml"
    case.write_text("")
    assert main(["iterate", str(case), "-q"]) == 0
    assert f"outputs written to {tmp_path / 'loop_out'}" in capsys.readouterr().out
    # every column of the terminal table says its unit: the instant's is the case's time unit
    monkeypatch.setenv("COLUMNS", "400")
    assert main(["iterate", str(case)]) == 0
    out = capsys.readouterr().out
    for label in ("instant [year]", "global depth tube [mm]", "gap min [mm]", "gap max [mm]"):
        assert label in out, label
