"""A case file's ``[history]`` picks the shock point of a file holding several (``node``,
POST_USURE's NOEUD) and passes any reader option (``options``), as
POST_USURE(RESU_GENE=..., NOEUD=...) does.

The file: ``tests/io/fixtures/impr_table_tableau.txt`` (IMPR_TABLE of the shock N12, hand-written)
with its rows repeated for N13 with the normal force doubled. Expected power: the trapezoid rule of
theory §2 on the printed samples, computed independently below.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fretwear.errors import KeywordError
from fretwear.io import read_history
from fretwear.workflows.case_files import history_options, run_case

TABLEAU = Path(__file__).parents[1] / "io" / "fixtures" / "impr_table_tableau.txt"


def _two_nodes(tmp_path: Path) -> Path:
    lines = TABLEAU.read_text().splitlines()
    rows = lines[4:]
    doubled = []
    for r in rows:
        cells = r.split()
        cells[0], cells[2] = "N13", f"{2 * float(cells[2]):12.5E}"  # VINT1 doubled
        doubled.append(" ".join(cells))
    path = tmp_path / "choc.tab"
    path.write_text("\n".join(lines[:4] + rows + doubled) + "\n")
    return path


def _power(t, fn, vt1, vt2, stick):
    p = np.asarray(fn) * np.hypot(vt1, vt2)
    keep = np.asarray(stick[:-1]) == 0
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(t) * keep) / (t[-1] - t[0]))


def _case(tmp_path, **history):
    return {"history": {"file": str(_two_nodes(tmp_path)), **history},
            "law": {"name": "ARCHARD", "mobile": {"COEF_USURE": 1e-14}},
            "geometry": {"contact_type": "TUBE_BAV", "mobile_radius_m": 0.0111,
                         "obstacle_width_m": 0.0127},
            "time": {"instants": [1.0]}}


def test_case_history_node_selects_the_shock_point(tmp_path):
    t = [0.0, 1e-3, 2e-3, 3e-3, 4e-3]
    vt1, vt2 = [0.0, 0.02, 0.03, 0.0, -0.01], [0.0, -0.01, -0.02, 0.0, 0.005]
    stick = [0, 0, 0, 1, 0]
    case = _case(tmp_path, node="N13")
    r = run_case(case)  # streams the file: the history itself is not kept (issue 13)
    fn13 = [0.0, 25.0, 50.0, 25.0, 0.0]
    assert r.power.statistics.force_max == 50.0
    assert r.total_power == pytest.approx(_power(t, fn13, vt1, vt2, stick), rel=1e-12)
    h = read_history(case["history"]["file"], **history_options(case["history"]))
    assert h.normal_force.tolist() == fn13
    assert h.metadata["node"] == "N13" and h.metadata["node_checked"]
    # any reader option: select= does the same through [history] options
    r = run_case(_case(tmp_path, options={"select": "NOEUD=N12"}))
    fn12 = [0.0, 12.5, 25.0, 12.5, 0.0]
    assert r.power.statistics.force_max == 25.0
    assert r.total_power == pytest.approx(_power(t, fn12, vt1, vt2, stick), rel=1e-12)
    # a node the file does not hold is an error naming those it holds
    with pytest.raises(KeywordError, match=r"'N14' \(NOEUD/GROUP_NO\) is not in this file: its "
                                           r"node column holds \['N12', 'N13'\]"):
        run_case(_case(tmp_path, node="N14"))


def test_history_options_refuses_a_key_given_twice():
    assert history_options({"file": "f", "format": "aster", "options": {"index": 2}}) == {
        "format": "aster", "index": 2}
    with pytest.raises(KeywordError, match=r"options = \{node = \.\.\.\}: give node as "
                                           r"\[history\] keys"):
        history_options({"file": "f", "node": "N1", "options": {"node": "N2"}})
