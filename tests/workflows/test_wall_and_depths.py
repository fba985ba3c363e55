"""The wall and its limit through the case files, the CLI and the Code_Aster facade.

Oracles: the TUBE_TUBE closed form d = (1/(2R))^(1/5)·(15θ·K·P·t/8)^(2/5) inverted for the limit
instant. The loop's choice of depth is tested in tests/dynamics/test_loop.py.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.cli import main
from fretwear.errors import KeywordError
from fretwear.workflows.aster import _F, POST_USURE
from fretwear.workflows.case_files import load_case, run_case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
YEAR = 31536000.0
R, WALL = 9.525e-3, 1.09e-3


def _tube_tube_limit(depth):
    theta = math.radians(5.0)
    return (depth * (2 * R) ** 0.2) ** 2.5 * 8 / (15 * theta * 1e-12 * 1e-3) / YEAR


def test_tube_tube_example_names_the_through_wall_depth():
    result = run_case(EXAMPLES / "tube_tube.toml")  # it collects the warnings
    t = result.table
    assert t["depth_mobile"].iloc[-1] == pytest.approx(1.411e-3, abs=1e-6)
    assert t["wall_fraction"].iloc[-1] > 1
    assert t["limit_instant"].iloc[0] == pytest.approx(_tube_tube_limit(0.4 * WALL), rel=1e-12)
    assert t.attrs["through_wall"]["global"] == pytest.approx(_tube_tube_limit(WALL), rel=1e-12)
    assert any("worn through its wall" in w for w in result.warnings)


def test_run_summary_prints_the_limit_and_through_wall(capsys):
    assert main(["run", str(EXAMPLES / "tube_tube.toml"), "--depth-limit", "0.6"]) == 0
    text = capsys.readouterr().out
    assert "limit: 60 % of the 1.09 mm wall = 0.654 mm; the global depth reaches it at " \
           f"instant {_tube_tube_limit(0.6 * WALL):.4g} [year]" in text
    assert "THROUGH THE WALL: the tube's global depth passes the 1.09 mm wall at instant " \
           f"{_tube_tube_limit(WALL):.4g} [year]" in text
    assert "129 THROUGH" in text  # the % wall column
    # bad news first: through the wall is said before the (less serious) limit
    assert text.index("THROUGH THE WALL: the tube's global") < text.index("limit: 60 % of the")


def test_run_wall_option_and_sector_limits(tmp_path, capsys):
    out = tmp_path / "t.csv"
    assert main(["run", str(EXAMPLES / "tube_bav.toml"), "--wall-thickness", "0.9e-3",
                 "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "limit: 40 % of the 0.9 mm wall = 0.36 mm" in text
    assert "the first sector to reach it is sector 5" in text
    table = pd.read_csv(out, comment="#")
    assert {"wall_fraction", "limit_instant", "wall_fraction_sector",
            "limit_instant_sector"} <= set(table.columns)
    np.testing.assert_allclose(table["wall_fraction_sector"],
                               table["depth_mobile_sector"] / 0.9e-3, rtol=1e-12)


def test_case_file_wall_keys_and_conflict(tmp_path):
    case = load_case(EXAMPLES / "tube_tube.toml")
    case["obstacle"] = {"wall_thickness_m": 1.2e-3}
    with pytest.raises(KeywordError, match="wall_thickness_m = 0.00109 and .*differ"):
        run_case(case)
    case["obstacle"] = {"wall_thickness_m": 1.09e-3}  # the same wall: fine
    assert run_case(case).table.attrs["wall_thickness"] == 1.09e-3


def test_post_usure_extras():
    t = POST_USURE(PUIS_USURE=1e-3, LOI_USURE="ARCHARD", MOBILE=_F(COEF_USURE=1e-12),
                   CONTACT="TUBE_TUBE", RAYON_MOBILE=R, RAYON_OBST=R, ANGL_INCLI=5.0,
                   INST=(0.1,), COEF_INST=YEAR, EPAIS_PAROI=WALL, LIMITE_PAROI=0.4)
    # the obstacle does not wear here: the mobile's depth alone, d(V_m)
    assert t["INST_LIMITE"].iloc[0] == pytest.approx(_tube_tube_limit(0.4 * WALL), rel=1e-12)
    assert t["FRAC_PAROI"].iloc[0] == pytest.approx(t["P_USUR_TUBE"].iloc[0] / WALL)
    plain = POST_USURE(PUIS_USURE=1e-3, LOI_USURE="ARCHARD", MOBILE=_F(COEF_USURE=1e-12),
                       CONTACT="TUBE_TUBE", RAYON_MOBILE=R, RAYON_OBST=R, ANGL_INCLI=5.0,
                       INST=(0.1,), COEF_INST=YEAR)
    assert "INST_LIMITE" not in plain.columns
