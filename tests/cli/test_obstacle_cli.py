"""`fretwear obstacle`: the command wires the case file / options to the obstacle update.

Reference values: a single sector covering −180..180 keeps both bodies circular, so the worn
clearance is g + d_m + d_o in every direction, with the theory §3 depths (closed form).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from fretwear.cli import main
from fretwear.obstacle import read_discret
from fretwear.table.files import read_profile_table

RM, GAP, WALL, WIDTH = 9.5e-3, 0.5e-3, 1.09e-3, 20e-3


def _wear_table(path, vm, vo, instants=(1.0, 5.0)):
    """A sector-mode wear table with Code_Aster names: one sector −180..180."""
    rows = [{"INST": t, "SECTEUR": 1, "ANGLE_DEBUT": -180.0, "ANGLE_FIN": 180.0,
             "V_USUR_TUBE_CUMU": vm * t / instants[-1], "V_USUR_OBST_CUMU": vo * t / instants[-1]}
            for t in instants]
    pd.DataFrame(rows).to_csv(path, index=False)
    return path


def _expected_clearance(vm, vo):
    dm = RM - math.sqrt(RM**2 - 2 * vm / (WIDTH * 2 * math.pi))  # theory §3, Δθ = 2π
    do = math.sqrt((RM + GAP) ** 2 + 2 * vo / (WIDTH * 2 * math.pi)) - (RM + GAP)
    return GAP + dm + do


def test_table_mode_writes_profile_discret_and_plot(tmp_path, capsys):
    vm, vo = 2e-8, 1e-8
    table = _wear_table(tmp_path / "wear.csv", vm, vo)
    code = main(["obstacle", "--table", str(table), "--mobile-radius", str(RM),
                 "--wall-thickness", str(WALL), "--gap", str(GAP), "--width", str(WIDTH),
                 "--resolution", "0.25", "-o", str(tmp_path / "profile.csv"),
                 "--write-discret", str(tmp_path / "worn.txt"), "--plot",
                 str(tmp_path / "fig")])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "at instant 5" in out
    assert "profile d tube [mm]" in out  # the obstacle-profile depth, named as such
    profile = read_profile_table(tmp_path / "profile.csv")
    assert len(profile) == 721
    np.testing.assert_allclose(profile["clearance_worn"], _expected_clearance(vm, vo),
                               rtol=0, atol=1e-11)
    np.testing.assert_allclose(profile["clearance_initial"], GAP, rtol=0, atol=1e-11)
    worn = read_discret(tmp_path / "worn.txt")
    np.testing.assert_allclose(worn.gap(np.arange(0, 360, 7.5)), _expected_clearance(vm, vo),
                               rtol=0, atol=1e-11)
    for suffix in ("png", "svg"):
        assert (tmp_path / "fig" / f"obstacle_polar.{suffix}").stat().st_size > 1000


def test_case_mode_with_instant_and_aster_output(tmp_path, capsys):
    vm, vo = 2e-8, 0.0
    _wear_table(tmp_path / "wear.csv", vm, vo)
    (tmp_path / "case.toml").write_text(f"""
[geometry]
contact_type = "TUBE_ALESAGE"
mobile_radius_m = {RM}
obstacle_width_m = {WIDTH}
[obstacle]
gap_m = {GAP}
wall_thickness_m = {WALL}
table = "wear.csv"
instant = 1
resolution_deg = 0.5
output = "out/profile.tab"
""")
    code = main(["obstacle", str(tmp_path / "case.toml")])
    assert code == 0, capsys.readouterr()
    from fretwear.io.aster import read_aster_table

    t = read_aster_table(tmp_path / "out" / "profile.tab")
    np.testing.assert_allclose(t["JEU_USE"], _expected_clearance(vm / 5, 0.0), rtol=0,
                               atol=1e-11)


def test_perforation_and_errors_are_reported(tmp_path, capsys):
    deep = 0.5 * WIDTH * 2 * math.pi * (RM**2 - (RM - 0.8e-3) ** 2)  # 0.8 mm all round
    table = _wear_table(tmp_path / "wear.csv", deep, 0.0)
    args = ["obstacle", "--table", str(table), "--mobile-radius", str(RM), "--wall-thickness",
            str(WALL), "--gap", str(GAP), "--width", str(WIDTH), "--resolution", "1"]
    assert main(args + ["--perforation", "0.5"]) == 0
    err = capsys.readouterr().err
    assert "PerforationWarning" in err and "sector 1" in err
    assert main(args + ["--instant", "3"]) == 2
    assert "instant 3 is not in the wear table" in capsys.readouterr().err
    assert main(["obstacle", "--table", str(table), "--gap", str(GAP)]) == 2
    assert "--mobile-radius, --wall-thickness" in capsys.readouterr().err
    assert main(args + ["--gap", "-1e-4"]) == 2  # the last --gap wins
    assert "negative gap: -0.0001 m" in capsys.readouterr().err
    assert main(args + ["--bore-radius", "0.01"]) == 2
    assert "give one obstacle" in capsys.readouterr().err


def test_example_case_runs_the_wear_case_then_the_update(tmp_path, capsys):
    """examples/obstacle_grappe.toml: no table given, so the case is run (10 sectors). Wear
    only removes material (worn mobile ⊂ new mobile, worn obstacle ⊃ new obstacle), so the
    clearance can only open: worn >= initial in every direction."""
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "obstacle_grappe.toml"
    out = tmp_path / "profile.csv"
    assert main(["obstacle", str(example), "-o", str(out)]) == 0
    assert "10 sectors, smooth depth" in capsys.readouterr().out
    p = read_profile_table(out)
    assert (p["clearance_worn"] >= p["clearance_initial"] - 1e-15).all()
    assert p["clearance_worn"].max() > p["clearance_initial"].max()


def test_planes_options_step_and_closing_circle(tmp_path, capsys):
    """Two planes, normal at 30°, gaps 0.4 / 0.2 mm, closed by a circle of radius 50 mm, on a
    2° grid: the new clearance is g/|cos ψ| (closed form: the disk's normal travel reaches the
    gap) and, along the planes (ψ = ±90°), the disk touches the closing circle at
    s = R_c − R_m. Options that describe planes without --plane-gap are refused."""
    table = _wear_table(tmp_path / "wear.csv", 0.0, 0.0)
    args = ["obstacle", "--table", str(table), "--mobile-radius", str(RM), "--wall-thickness",
            str(WALL), "--width", str(WIDTH)]
    out = tmp_path / "planes.csv"
    assert main(args + ["--plane-gap", "4e-4", "--plane-gap-opposite", "2e-4", "--orientation",
                        "30", "--closing-radius", "0.05", "--step", "2", "-o", str(out)]) == 0
    p = read_profile_table(out)
    assert len(p) == 181 and p["angle"].iloc[1] == 2.0
    c = np.cos(np.radians(p["angle"] - 30.0))
    sel = np.abs(c) > 0.3
    expected = np.where(c > 0, 4e-4, 2e-4) / np.abs(c)
    np.testing.assert_allclose(p["clearance_initial"][sel], expected[sel], rtol=1e-9)
    along = p["angle"].isin([120.0, 300.0])
    np.testing.assert_allclose(p["clearance_initial"][along], 0.05 - RM, rtol=1e-6)
    np.testing.assert_array_equal(p["clearance_worn"], p["clearance_initial"])  # no wear
    capsys.readouterr()
    assert main(args + ["--gap", str(GAP), "--orientation", "30"]) == 2
    assert "--orientation describe two planes" in capsys.readouterr().err
