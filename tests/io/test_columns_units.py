"""Column aliases (theory §1: Code_Aster names and internal variables), overrides, unit conversion,
and the CSV dialects (delimiters, decimal comma, comments, header detection).

Reference values: the literal numbers written in each test file; unit factors are the SI
definitions (1 mm = 1e-3 m, 1 kN = 1e3 N, 1 daN = 10 N, 1 ms = 1e-3 s, 1 in = 0.0254 m,
1 lbf = 4.4482216152605 N, NIST SP 811).
"""

from __future__ import annotations

import numpy as np
import pytest

from fretwear.errors import FormatError, KeywordError, UnitsWarning
from fretwear.io import read_history
from fretwear.io.channels import ALIASES, channel_of, resolve_columns, unit_factor


@pytest.mark.parametrize("name, channel", [
    # theory §1: Code_Aster names
    ("INST", "time"), ("FN", "normal_force"), ("FT1", "ft1"), ("FT2", "ft2"), ("VN", "vn"),
    ("VT1", "vt1"), ("VT2", "vt2"), ("DYLOC", "dy"), ("DZLOC", "dz"),
    # theory §1: internal variables of a shock
    ("VINT1", "normal_force"), ("VINT2", "ft1"), ("VINT3", "ft2"), ("VINT5", "dy"),
    ("VINT6", "dz"), ("VINT10", "vn"), ("VINT11", "vt1"), ("VINT12", "vt2"), ("VINT13", "stick"),
    # canonical, case and separators, unit suffixes, French
    ("normal_force", "normal_force"), ("Normal Force [N]", "normal_force"), ("t (ms)", "time"),
    ("force-normale", "normal_force"), ("Vint13", "stick"), ("time", "time"), ("Temps", "time"),
])
def test_aliases(name, channel):
    assert channel_of(name) == channel


@pytest.mark.parametrize("name", ["VINT4", "DXLOC", "VINT7", "NOEUD", "x", "v"])
def test_names_that_are_not_channels(name):
    # VINT4/DXLOC is the local DX of node 1: not a channel of the history (theory §1)
    assert channel_of(name) is None


def test_every_channel_accepts_its_own_name():
    for channel, names in ALIASES.items():
        assert channel_of(channel) == channel
        assert all(channel_of(n.upper()) == channel for n in names)


# literal displacements of 1-2.5 m sampled every 0.1 s: flagged as a likely mm / ms export
# (the check is tested in test_plausibility.py); this test is about the column names
@pytest.mark.filterwarnings("ignore::fretwear.errors.UnitsWarning")
def test_vint_columns_give_the_right_channels(tmp_path):
    """A RECU_FONCTION export of the internal variables, as users do since 2016 (theory §1)."""
    path = tmp_path / "vint.csv"
    path.write_text("INST,VINT1,VINT2,VINT3,VINT4,VINT5,VINT6,VINT10,VINT11,VINT12,VINT13\n"
                    "0.0,0.0,0.0,0.0,9.0,1.0,2.0,0.5,0.0,0.0,0\n"
                    "0.1,3.0,-0.9,0.3,9.0,1.5,2.5,-0.5,0.2,-0.1,1\n")
    h = read_history(path)
    assert h.metadata["columns"] == {
        "time": "INST", "normal_force": "VINT1", "ft1": "VINT2", "ft2": "VINT3", "dy": "VINT5",
        "dz": "VINT6", "vn": "VINT10", "vt1": "VINT11", "vt2": "VINT12", "stick": "VINT13"}
    assert h.metadata["ignored_columns"] == ["VINT4"]
    assert h.normal_force.tolist() == [0.0, 3.0] and h.ft1.tolist() == [0.0, -0.9]
    assert h.dy.tolist() == [1.0, 1.5] and h.dz.tolist() == [2.0, 2.5]
    assert h.vn.tolist() == [0.5, -0.5] and h.vt2.tolist() == [0.0, -0.1]
    assert h.stick.tolist() == [0.0, 1.0]


# two samples 1 s apart: the coarse step is flagged (likely ms), irrelevant to the overrides
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_overrides_win_and_none_ignores(tmp_path):
    path = tmp_path / "o.csv"
    path.write_text("time,FN,load,u,w,stick\n0,1,10,1,0,7\n1,2,20,1,0,7\n")
    # 'stick' holds 7s (not a flag): ignored with None; 'load' is chosen over the alias 'FN'
    h = read_history(path, columns={"load": "normal_force", "u": "VT1", "w": "vt2",
                                    "stick": None})
    assert h.normal_force.tolist() == [10.0, 20.0]
    assert h.stick is None
    assert h.metadata["columns"]["normal_force"] == "load"
    assert sorted(h.metadata["ignored_columns"]) == ["FN", "stick"]


# samples 0.1 s apart: the coarse step is flagged (likely ms), irrelevant to the positions
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_resolve_columns_by_position_for_headerless_files(tmp_path):
    path = tmp_path / "nohead.dat"
    path.write_text("0.0 1.0 0.5 0.0\n0.1 2.0 0.5 0.0\n0.2 0.0 0.5 0.0\n")
    h = read_history(path, columns={0: "time", 1: "normal_force", 2: "vt1", 3: "vt2"})
    assert h.time.tolist() == [0.0, 0.1, 0.2] and h.normal_force.tolist() == [1.0, 2.0, 0.0]
    with pytest.raises(FormatError, match=r"no header line.*columns=\{0: 'time'"):
        read_history(path)


@pytest.mark.parametrize("unit, quantity, factor", [
    ("mm", "length", 1e-3), ("um", "length", 1e-6), ("µm", "length", 1e-6),
    ("in", "length", 0.0254), ("kN", "force", 1e3), ("daN", "force", 10.0),
    ("lbf", "force", 4.4482216152605), ("mN", "force", 1e-3), ("MN", "force", 1e6),
    ("ms", "time", 1e-3), ("us", "time", 1e-6), ("min", "time", 60.0),
    ("mm/s", "velocity", 1e-3), ("mm/ms", "velocity", 1.0), ("in/s", "velocity", 0.0254),
    ("KN", "force", 1e3), ("Mm", "length", 1e-3),
])
def test_unit_factors(unit, quantity, factor):
    assert unit_factor(unit, quantity) == pytest.approx(factor, rel=1e-15)


def _flagged(seen) -> list[str]:
    """The channels named by the UnitsWarnings recorded in ``seen``, sorted."""
    return sorted(str(w.message).split("channel '")[1].split("'")[0] for w in seen)


def test_units_option_per_quantity_per_channel_and_derived_velocity(tmp_path):
    path = tmp_path / "mm.csv"
    path.write_text("t,fn,vt1,vt2,dy,dz\n0,1.5,10,0,0.2,0\n2,0.5,20,5,0.1,-0.1\n")
    # the plausibility check sees the converted values and names the unit read (UnitsWarning)
    with pytest.warns(UnitsWarning, match=r"'vt1': largest sliding speed ‖Vt‖ 20.62 m/s "
                                          r"\(read in 'mm/ms'\)") as seen:
        h = read_history(path, units={"length": "mm", "force": "kN", "time": "ms"})
    assert _flagged(seen) == ["vt1"]
    np.testing.assert_allclose(h.time, [0.0, 2e-3], rtol=1e-15)
    np.testing.assert_allclose(h.normal_force, [1500.0, 500.0], rtol=1e-15)
    np.testing.assert_allclose(h.dy, [2e-4, 1e-4], rtol=1e-15)
    # velocity unit defaults to <length>/<time> = mm/ms = m/s
    np.testing.assert_array_equal(h.vt1, [10.0, 20.0])
    assert h.metadata["units"]["vt1"] == "mm/ms"
    with pytest.warns(UnitsWarning) as seen:  # 2 s between the samples
        h = read_history(path, units={"length": "mm", "vt2": "mm/s", "force": "N"})
    assert _flagged(seen) == ["time"]
    np.testing.assert_allclose(h.vt1, [1e-2, 2e-2], rtol=1e-15)  # mm/s derived
    np.testing.assert_allclose(h.vt2, [0.0, 5e-3], rtol=1e-15)
    with pytest.warns(UnitsWarning) as seen:  # lengths in m: 0.2 m is flagged too
        h = read_history(path, units={"FN": "daN", "velocity": "m/s"})  # alias as a key
    assert _flagged(seen) == ["dy", "time", "vt1"]
    np.testing.assert_array_equal(h.normal_force, [15.0, 5.0])
    np.testing.assert_array_equal(h.vt1, [10.0, 20.0])


def test_units_in_the_header_and_user_precedence(tmp_path):
    path = tmp_path / "hdr.csv"
    path.write_text("t [ms],Fn (kN),vt1 [mm/s],vt2 [mm/s]\n0,1,2,3\n1,2,4,6\n")
    h = read_history(path)
    np.testing.assert_allclose(h.time, [0.0, 1e-3], rtol=1e-15)
    np.testing.assert_allclose(h.normal_force, [1e3, 2e3], rtol=1e-15)
    np.testing.assert_allclose(h.vt2, [3e-3, 6e-3], rtol=1e-15)
    # the user's word wins over the header, with a warning naming the disagreement only
    with pytest.warns(UnitsWarning) as caught:
        h = read_history(path, units={"normal_force": "N", "time": "ms"})
    assert [str(w.message).split(": ", 1)[1] for w in caught] == [
        "the units given override the units the file declares for normal_force 'N' (the file: "
        "'kN'); the values are read in the units given. If the file is right, leave those "
        "units out"]  # time in 'ms' agrees with the header's [ms]: not named
    assert caught[0].filename == __file__  # points at the call
    np.testing.assert_array_equal(h.normal_force, [1.0, 2.0])
    assert h.metadata["unit_factors"]["time"] == 1e-3


@pytest.mark.parametrize("text", [
    "t;fn;vt1;vt2\n0,0;1,5;0,25;0\n0,5;2,5;0,75;0\n",           # French Excel: ; and decimal comma
    "t\tfn\tvt1\tvt2\n0.0\t1.5\t0.25\t0\n0.5\t2.5\t0.75\t0\n",   # tab
    "t|fn|vt1|vt2\n0.0|1.5|0.25|0\n0.5|2.5|0.75|0\n",            # pipe
    "# comment\n#\n   t   fn  vt1  vt2\n 0.0 1.5 0.25 0\n 0.5 2.5 0.75 0\n",  # blanks, comments
    "t, fn, vt1, vt2\n0.0, 1.5, 0.25, 0\n# a comment in the data\n0.5, 2.5, 0.75, 0\n",
    '"t","fn","vt1","vt2"\n0.0,1.5,0.25,0\n0.5,2.5,0.75,0\n',   # quoted header
])
# two samples 0.5 s apart: the coarse step is flagged (likely ms), irrelevant to the dialects
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_csv_dialects(tmp_path, text):
    path = tmp_path / "d.txt"
    path.write_text(text)
    h = read_history(path)
    assert h.time.tolist() == [0.0, 0.5]
    assert h.normal_force.tolist() == [1.5, 2.5] and h.vt1.tolist() == [0.25, 0.75]


# two samples 1 s apart: the coarse step is flagged (likely ms), irrelevant to the options
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_explicit_csv_options(tmp_path):
    path = tmp_path / "x.csv"
    path.write_text("% exported\nt:fn:vt1:vt2\n0:1:0:0\n1:2:0:0\n")
    h = read_history(path, delimiter=":", comment="%")
    assert h.normal_force.tolist() == [1.0, 2.0]


def test_resolve_columns_reports_ambiguity_with_both_names():
    with pytest.raises(FormatError, match=r"'FN' \(#2\) and 'VINT1' \(#5\) both stand for the "
                                          r"channel 'normal_force'"):
        resolve_columns(["INST", "FN", "VT1", "VT2", "VINT1"])
    # the override settles it
    assert resolve_columns(["INST", "FN", "VT1", "VT2", "VINT1"],
                           {"VINT1": None})["normal_force"] == 1


def test_bad_overrides_and_units_are_keyword_errors():
    with pytest.raises(KeywordError, match=r"'nope'.*not in the file; columns found"):
        resolve_columns(["t", "fn"], {"nope": "time"})
    with pytest.raises(KeywordError, match=r"unknown channel 'force'"):
        resolve_columns(["t", "fn"], {"fn": "force"})
    with pytest.raises(KeywordError, match=r"maps both 't' and 'u' to 'time'"):
        resolve_columns(["t", "u"], {"t": "time", "u": "time"})
    with pytest.raises(KeywordError, match=r"ambiguous between \['mN', 'MN'\]"):
        unit_factor("mn", "force")


def test_docs_list_every_alias():
    """docs/formats.md documents exactly the alias table of the code."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "docs" / "formats.md").read_text()
    for channel, names in ALIASES.items():
        assert f"| {channel} | {', '.join(names)} |" in text, channel
