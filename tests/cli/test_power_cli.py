"""``fretwear power``: table and JSON output, streaming options, errors with exit codes.

Expected values come from the analytic cases of tests/test_power.py: a ramp force Fn = a + b·t at
constant sliding speed V gives block powers V·(a + b·t_mid) exactly (closed-form integral).
"""

import json

import numpy as np
import pytest

from fretwear.cli import main
from fretwear.history import ContactHistory
from fretwear.io import write_history

A, B, V = 2.0, 3.0, 0.1


@pytest.fixture(scope="module")
def ramp_file(tmp_path_factory):
    t = np.linspace(0.0, 10.0, 101)
    th = np.radians(-179.5 + 3.0 * np.arange(t.size))
    h = ContactHistory(time=t, normal_force=A + B * t, vt1=np.full_like(t, V),
                       vt2=np.zeros_like(t), dy=np.cos(th), dz=np.sin(th), name="ramp")
    path = tmp_path_factory.mktemp("power") / "ramp.csv"
    write_history(h, path)
    return path


def _json(capsys, *args):
    assert main(["power", *map(str, args), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_blocks_window_and_warning(capsys, ramp_file):
    out = _json(capsys, ramp_file, "--blocks", "3", "--t-start", "1.234", "--t-end", "8.765")
    edges = np.linspace(1.234, 8.765, 4)
    mids = 0.5 * (edges[1:] + edges[:-1])
    np.testing.assert_allclose(out["blocks"], V * (A + B * mids), rtol=1e-12)
    assert out["total"] == pytest.approx(V * (A + B * (1.234 + 8.765) / 2), rel=1e-12)
    assert out["units"]["total"] == "W" and out["sectors"] is None
    assert any("block powers spread" in w for w in out["warnings"])
    # a looser threshold: no warning
    out = _json(capsys, ramp_file, "--blocks", "3", "--threshold", "10")
    assert out["warnings"] == []


def test_sectors_and_small_chunks_match(capsys, ramp_file):
    one = _json(capsys, ramp_file, "--sectors", "-180,-90,0,90,180", "--blocks", "2")
    streamed = _json(capsys, ramp_file, "--sectors", "4", "--blocks", "2", "--chunk-size", "7")
    assert one["sector_edges"] == [-180.0, -90.0, 0.0, 90.0, 180.0]
    assert sum(one["sectors"]) == pytest.approx(one["total"], rel=1e-13)
    np.testing.assert_allclose(streamed["sectors"], one["sectors"], rtol=1e-12)
    assert streamed["statistics"]["contact_fraction"] == 1.0
    assert streamed["total"] == pytest.approx(V * (A + B * 5.0), rel=1e-12)


def test_table_output(capsys, ramp_file):
    assert main(["power", str(ramp_file), "--sectors", "2", "--blocks", "2"]) == 0
    out = capsys.readouterr().out
    for words in ("Wear power of ramp", "Blocks", "Angular sectors", "Contact statistics",
                  f"{V * (A + B * 5.0):.6g} W", "warning:"):
        assert words in out


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--sectors", "-170,0,180"], ["sectors", "-180..180"]),
        (["--sectors", "ten"], ["--sectors", "'ten'"]),
        (["--t-end", "11"], ["t_end = 11.0", "last instant 10.0"]),
        (["--blocks", "0"], ["--blocks"]),
        (["--format", "nosuch"], ["nosuch"]),
    ],
)
def test_errors_exit_2_and_name_the_culprit(capsys, ramp_file, args, words):
    assert main(["power", str(ramp_file), *args]) == 2
    err = capsys.readouterr().err
    for w in words:
        assert w in err


def test_missing_file(capsys, tmp_path):
    assert main(["power", str(tmp_path / "none.csv")]) == 2
    assert "none.csv" in capsys.readouterr().err
