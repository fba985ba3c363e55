"""``fretwear power``: table and JSON output, streaming options, errors with exit codes.

Expected values come from the analytic cases of tests/power/test_wear_power.py: a ramp force
Fn = a + b·t at constant sliding speed V gives block powers V·(a + b·t_mid) exactly (closed-form
integral).
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
    # (the ramp is not a physical contact: its 1 m displacements and 1 s steps get UnitsWarnings)
    assert [w for w in out["warnings"] if "plausibility limit" not in w] == []


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
    assert "none.csv' does not exist" in capsys.readouterr().err
    assert main(["power", str(tmp_path)]) == 2
    assert "is a directory, not a file" in capsys.readouterr().err


# --------------------------------------------------------------------------- reading options
FIXTURES = __import__("pathlib").Path(__file__).parents[1] / "io" / "fixtures"


def _trapezoid_power(t, fn, vt1, vt2):
    """Independent computation: P = (1/T) ∫ Fn·‖Vt‖ dt by numpy's trapezoid rule (theory §2)."""
    t = np.asarray(t, dtype=float)
    g = np.asarray(fn) * np.hypot(vt1, vt2)
    return float(np.trapezoid(g, t) / (t[-1] - t[0]))


# The literals printed in fixtures/fonction_{fn,vt1,vt2}.txt (IMPR_FONCTION TABLEAU, one per file)
FUNCTION_T = [0.0, 1e-3, 2e-3, 3e-3]
FUNCTION_P = _trapezoid_power(FUNCTION_T, [0.0, 5.0, 10.0, 5.0], [0.01, 0.02, 0.03, 0.04],
                              [-0.01, 0.0, 0.01, 0.0])


def test_function_files_as_a_list_or_channel_equals_file(capsys):
    files = [FIXTURES / f"fonction_{c}.txt" for c in ("fn", "vt1", "vt2")]
    out = _json(capsys, *files)
    assert out["total"] == pytest.approx(FUNCTION_P, rel=1e-12)
    assert out["duration"] == pytest.approx(3e-3, rel=1e-12)
    assert out["name"] == "fonction_fn"
    keyed = _json(capsys, f"normal_force={files[0]}", f"VT1={files[1]}", f"vt2={files[2]}",
                  "--units", "force=kN")
    assert keyed["total"] == pytest.approx(1e3 * FUNCTION_P, rel=1e-12)


def test_function_files_errors(capsys, tmp_path):
    files = [FIXTURES / f"fonction_{c}.txt" for c in ("fn", "vt1", "vt2")]
    assert main(["power", f"fn={files[0]}", str(files[1]), str(files[2])]) == 2
    assert "mix of CHANNEL=FILE" in capsys.readouterr().err
    assert main(["power", f"fn={tmp_path / 'none.txt'}", str(files[1])]) == 2
    assert "none.txt" in capsys.readouterr().err
    # value columns that are not channel names (RECU_FONCTION's default): the hint says how
    for k in range(3):
        (tmp_path / f"f{k}.txt").write_text(
            "#\n#FONCTION\n INST         TOUTRESU\n 0.00000E+00  1.00000E+00\n"
            " 1.00000E-03  2.00000E+00\n")
    assert main(["power", *(str(tmp_path / f"f{k}.txt") for k in range(3))]) == 2
    err = capsys.readouterr().err
    assert "TOUTRESU" in err and "CHANNEL=FILE" in err


def test_aster_table_choice_and_units(capsys):
    """Second table of fixtures/impr_table_aster.resu: lengths in mm (FN in N, VT in mm/s)."""
    path = FIXTURES / "impr_table_aster.resu"
    expected = _trapezoid_power([0.0, 5e-4, 1e-3, 1.5e-3], [0.0, 4.0, 8.0, 0.0],
                                [0.0, 12e-3, 11e-3, 0.0], [0.0, -5e-3, -4e-3, 0.0])
    by_title = _json(capsys, path, "--read-option", "title=CHOC", "--units", "length=mm")
    by_index = _json(capsys, path, "--read-option", "index=1", "--units", "length=mm")
    assert by_title["total"] == pytest.approx(expected, rel=1e-12)
    assert by_index["total"] == by_title["total"]
    assert main(["power", str(path)]) == 2
    assert "--read-option index=<n>" in capsys.readouterr().err
    assert main(["power", str(path), "--units", "length"]) == 2
    assert "--units" in capsys.readouterr().err


def test_headerless_file_with_columns_and_units(capsys, tmp_path):
    # time in ms, Fn in kN, velocities in mm/ms (= m/s): a constant Fn·V = 2 kN · 0.5 m/s
    path = tmp_path / "raw.dat"
    path.write_text("".join(f"{k};2,0;0,3;0,4;0\n" for k in range(5)))
    out = _json(capsys, path, "--column", "0=time,1=fn", "--column", "2=vt1", "--column",
                "3=vt2", "--column", "4=none", "--units", "time=ms,force=kN,length=mm")
    assert out["total"] == pytest.approx(2e3 * 0.5, rel=1e-12)
    assert out["duration"] == pytest.approx(4e-3, rel=1e-12)
