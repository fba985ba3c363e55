"""Code_Aster files as users print them: IMPR_FONCTION units holding several functions, the
shock point of a file (NOEUD / GROUP_NO), and instants printed with too few digits.

Fixtures (hand-written, not printed by Code_Aster; the layout follows Code_Aster's
``Objects/table_graph.py`` ``TraceTableau`` and ``Objects/table_py.py`` ``ReprTable``: a
``#``/dashes header, ``## Courbe i`` and its legend, value columns labelled
``<NOM_RESU>_<curve number>``, reals ``%12.5E``):

* ``impr_fonction_courbes.txt``: ``IMPR_FONCTION(FORMAT='TABLEAU', UNITE=40,
  COURBE=(_F(FONCTION=FN), _F(FONCTION=VT1), _F(FONCTION=VT2)))`` — one table, one abscissa;
* ``impr_fonction_unite.txt``: five ``IMPR_FONCTION(FORMAT='TABLEAU', UNITE=40,
  COURBE=_F(FONCTION=...))`` commands printing VINT1, VINT5, VINT6, VINT11, VINT12 of the shock
  N12 to the same unit — five tables.

Values are the literals of ``impr_table_tableau.txt`` (the same shock printed by IMPR_TABLE).
"""

from __future__ import annotations

import os

import numpy as np
import pandas as pd
import pytest
from iohelpers import FIXTURES

from fretwear.errors import FormatError, HistoryError, KeywordError
from fretwear.io import iter_history_chunks, read_history

COURBES = FIXTURES / "impr_fonction_courbes.txt"
UNITE = FIXTURES / "impr_fonction_unite.txt"
TABLEAU = FIXTURES / "impr_table_tableau.txt"
FN = [0.0, 12.5, 25.0, 12.5, 0.0]
VT1 = [0.0, 0.02, 0.03, 0.0, -0.01]
VT2 = [0.0, -0.01, -0.02, 0.0, 0.005]


def test_one_impr_fonction_with_several_courbe_is_one_history():
    h = read_history(COURBES)  # format guessed from the content
    assert h.metadata["format"] == "aster-function"
    assert h.time.tolist() == [0.0, 1e-3, 2e-3, 3e-3, 4e-3]
    assert h.normal_force.tolist() == FN
    assert h.vt1.tolist() == VT1 and h.vt2.tolist() == VT2
    # the columns were VINT1_0, VINT11_1, VINT12_2: IMPR_FONCTION's curve numbers dropped
    assert h.metadata["columns"]["vt2"] == "VINT12"


def test_several_impr_fonction_to_one_unit_are_one_history():
    h = read_history(UNITE)
    assert h.metadata["format"] == "aster-function"
    assert h.normal_force.tolist() == FN
    assert h.dy.tolist() == [1e-4, 2.05e-4, 2.1e-4, 2.05e-4, 1.5e-4]
    assert h.dz.tolist() == [0.0, 1e-5, 2e-5, 3e-5, 2e-5]
    assert h.vt1.tolist() == VT1 and h.vt2.tolist() == VT2
    # the same history as the IMPR_TABLE print of the shock
    ref = read_history(TABLEAU)
    for ch in ("time", "normal_force", "dy", "dz", "vt1", "vt2"):
        assert getattr(h, ch).tolist() == getattr(ref, ch).tolist()
    # read in chunks too (the file is read whole, then sliced)
    chunks = list(iter_history_chunks(UNITE, chunk_size=3))
    assert [c.normal_force.tolist() for c in chunks] == [FN[:3], FN[2:]]
    # one table of the unit is still reachable with index=: its function alone
    with pytest.raises(FormatError, match=r"no column for the required channel\(s\) \['vt1', "
                                          r"'vt2'\]"):
        read_history(UNITE, index=0)


def test_functions_named_by_the_user_in_order(tmp_path):
    # legends and labels that are no channel names (LEGENDE='effort', NOM_RESU 'TOUTRESU')
    text = COURBES.read_text().replace("VINT1_0 ", "TOUTRESU_0").replace(
        "VINT11_1", "TOUTRESU_1").replace("VINT12_2", "TOUTRESU_2")
    path = tmp_path / "fort.40"
    path.write_text(text)
    # the legends (the concepts FN, VT1, VT2) name them
    assert read_history(path).vt2.tolist() == VT2
    text = text.replace("## FN\n", "## effort\n").replace("## VT1\n", "## g1\n").replace(
        "## VT2\n", "## g2\n")
    path.write_text(text)
    with pytest.raises(FormatError, match=r"columns found: \['time', 'TOUTRESU_0', .*name them "
                                          r"in order with functions=\[\.\.\.\]"):
        read_history(path, format="aster")
    h = read_history(path, format="aster", functions=["fn", "vt2", "vt1"])  # any order
    assert h.normal_force.tolist() == FN and h.vt1.tolist() == VT2 and h.vt2.tolist() == VT1
    # None skips a function (here the third: vt2 is then missing, and required)
    with pytest.raises(FormatError, match=r"required channel\(s\) \['vt2'\]"):
        read_history(path, format="aster", functions=["fn", "vt1", None])
    with pytest.raises(KeywordError, match=r"names 2 functions but the file holds 3"):
        read_history(path, format="aster", functions=["fn", "vt1"])
    # the command line's form: --read-option functions=fn,vt1,vt2
    assert read_history(path, functions="fn, vt1, vt2").vt2.tolist() == VT2
    # a set of files takes the same option
    h = read_history([path], functions=["normal_force", "vt1", "vt2"])
    assert h.vt2.tolist() == VT2


def test_a_unit_holding_several_shock_points_needs_a_choice(tmp_path):
    # the same function printed twice (N12 then N13): not one history
    text = UNITE.read_text()
    path = tmp_path / "two_nodes.txt"
    path.write_text(text + text.replace("_N12", "_N13").replace("1.25000E+01", "2.50000E+01"))
    with pytest.raises(FormatError, match=r"repeat the functions \['VINT1', 'VINT11', 'VINT12', "
                                          r"'VINT5', 'VINT6'\]: several shock points; choose "
                                          r"one with node="):
        read_history(path)
    # the legends (FN_N12 ... FN_N13) name the node: node= picks its tables
    assert read_history(path, node="N12").normal_force.tolist() == FN
    assert read_history(path, node="N13").normal_force.tolist() == [0.0, 25.0, 25.0, 25.0, 0.0]


def test_node_selects_the_rows_of_one_shock_point(tmp_path):
    lines = TABLEAU.read_text().splitlines()
    rows = lines[4:]
    n13 = [r.replace("N12", "N13", 1) for r in rows]
    path = tmp_path / "two.txt"
    path.write_text("\n".join(lines[:4] + rows + n13) + "\n")
    h = read_history(path, node="N13")
    assert h.normal_force.tolist() == FN
    assert h.metadata["node"] == "N13" and h.metadata["node_checked"] is True
    assert read_history(path, node="n12").time.tolist() == [0.0, 1e-3, 2e-3, 3e-3, 4e-3]
    # the mixed table without a choice names node= among the fixes
    with pytest.raises(FormatError, match=r"choose one with node='N12'"):
        read_history(path)


def test_a_node_not_in_a_single_node_file_is_an_error():
    with pytest.raises(KeywordError, match=r"shock point 'N13' \(NOEUD/GROUP_NO\) is not in this "
                                           r"file: its node column holds \['N12'\]"):
        read_history(TABLEAU, node="N13")
    h = read_history(TABLEAU, node="N12")
    assert h.metadata["node_checked"] is True
    # a file that names no node cannot confirm the choice: read, and recorded as unchecked
    h = read_history(COURBES, node="N12")
    assert h.metadata["node_checked"] is False and h.normal_force.tolist() == FN


def test_repeated_instants_explain_the_print_precision(tmp_path):
    # an archive step of 5e-5 s printed %12.5E around t = 20 s: every other instant repeats
    t = 19.999 + 5e-5 * np.arange(41)
    lines = ["#", "#TABLE_SDASTER", "INST         VINT1        VINT11       VINT12"]
    lines += [f"{x:12.5E} {1.0:12.5E} {0.1:12.5E} {0.0:12.5E}" for x in t]
    path = tmp_path / "n12.tab"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HistoryError, match=r"repeats the instant 1\.99991E\+01 at rows 1 and 2: "
                                           r"Code_Aster prints reals with FORMAT_R='E12\.5' "
                                           r"\(%12\.5E.*archive step is about 5e-05 s.*"
                                           r"IMPR_TABLE\(\.\.\., FORMAT_R='E16\.9'\)"):
        read_history(path)
    # printed with FORMAT_R='E16.9' the same instants are distinct and read
    lines[3:] = [f"{x:16.9E} {1.0:16.9E} {0.1:16.9E} {0.0:16.9E}" for x in t]
    path.write_text("\n".join(lines) + "\n")
    assert len(read_history(path)) == 41


# bare.csv's samples are 1 s apart: the coarse step is flagged (likely ms), irrelevant here
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_node_of_a_single_shock_file_of_another_format(tmp_path):
    """CSV, Parquet, HDF5 ... files hold one shock point: a node is checked against the one
    the file stores (fretwear writes its metadata), else recorded as unchecked."""
    from iohelpers import analytic_history

    from fretwear.io import write_history

    path = write_history(analytic_history(name="N12"), tmp_path / "n12.csv")
    assert read_history(path, node="N12").metadata["node_checked"] is True
    with pytest.raises(KeywordError, match=r"'N13' \(NOEUD/GROUP_NO\) is not in this file: it "
                                           r"holds the history of 'N12'"):
        read_history(path, node="N13")
    bare = tmp_path / "bare.csv"
    bare.write_text("t,fn,vt1,vt2\n0,1,0,0\n1,1,1,0\n")
    h = read_history(bare, node="N13")
    assert h.metadata["node"] == "N13" and h.metadata["node_checked"] is False


def _many_nodes(path, count: int, samples: int = 5) -> list[str]:
    """An IMPR_TABLE of ``count`` shock points (NOEUD and NOEUD_CHOC columns, node k's forces
    scaled by k + 1, the rows of the nodes interleaved sample by sample)."""
    nodes = [f"N{k}" for k in range(count)]
    lines = ["#", "#TABLE_SDASTER",
             "NOEUD    NOEUD_CHOC  INST         VINT1        VINT11       VINT12"]
    for i in range(samples):
        for k, node in enumerate(nodes):
            lines.append(f"{node:8s} {' ' + node.lower():10s} {i * 1e-3:12.5E} "
                         f"{(k + 1) * FN[i % len(FN)]:12.5E} {0.1:12.5E} {0.0:12.5E}")
    path.write_text("\n".join(lines) + "\n")
    return nodes


def test_the_nodes_of_one_file_are_read_from_one_parse(tmp_path, monkeypatch):
    """Reading the nodes of a multi-node IMPR_TABLE one after the other (a bundle's worker, a
    loop over wear_table(path, node=n)) parses the file once (aster_source.node_index): it was
    parsed and scanned for every node, quadratic (270 ms a node at 1 000 nodes). Each node's
    rows equal those of the file's table filtered by an independent pandas mask on its node
    column; the index is rebuilt when the file changes, and what a caller does to the frames it
    gets never reaches the next read."""
    from fretwear.io import aster as aster_module
    from fretwear.io import aster_source

    aster_source.forget_node_index()
    path = tmp_path / "nodes.tab"
    _many_nodes(path, 40)
    written = os.stat(path).st_mtime - 60
    os.utime(path, (written, written))  # a file written a minute ago (see the racy rule below)
    parses = []
    real = aster_module.read_aster_tables
    monkeypatch.setattr(aster_module, "read_aster_tables",
                        lambda p: parses.append(p) or real(p))
    whole = real(path)[0]
    for k in (0, 7, 39, 12):
        h = read_history(path, node=f" n{k} ")
        mask = whole["NOEUD"].astype(str).str.strip() == f"N{k}"
        np.testing.assert_array_equal(h.normal_force, whole.loc[mask, "VINT1"].to_numpy())
        np.testing.assert_array_equal(h.time, whole.loc[mask, "INST"].to_numpy())
        assert h.metadata["node"] == f"n{k}" and h.metadata["node_checked"] is True
    assert len(parses) == 1
    tables, _ = aster_source.node_index(path).select("N3", str(path))
    tables[0].loc[0, "VINT1"] = -1.0
    tables[0].attrs["title"] = "changed"
    tables[0].attrs["types"].append("changed")
    again, _ = aster_source.node_index(path).select("N3", str(path))
    assert again[0].loc[0, "VINT1"] == 4 * FN[0] and again[0].attrs["title"] != "changed"
    assert "changed" not in again[0].attrs["types"]
    with pytest.raises(KeywordError, match=r"'N40' \(NOEUD/GROUP_NO\) is not in this file: its "
                                           r"node column holds \['N0', 'N1', 'N2'"):
        read_history(path, node="N40")
    assert len(parses) == 1
    _many_nodes(path, 41)  # rewritten: another size, another index
    assert read_history(path, node="N40").normal_force.tolist() == [41 * f for f in FN]
    assert len(parses) == 2
    # rewritten in place with the same size and its modification time set back (cp -p,
    # rsync -t, or a coarse clock): the change time tells
    os.utime(path, (written, written))
    read_history(path, node="N40")
    assert len(parses) == 3  # the 41-node file written just now was not kept (racy rule)
    before = read_history(path, node="N40")
    assert len(parses) == 3
    text = path.read_text()
    path.write_text(text.replace(f"{41 * FN[1]:12.5E}", f"{41 * FN[1] + 1:12.5E}"))
    assert path.stat().st_size == len(text)
    os.utime(path, (written, written))
    after = read_history(path, node="N40")
    assert len(parses) == 4 and after.normal_force[1] == before.normal_force[1] + 1
    aster_source.forget_node_index()


def test_node_index_selects_as_the_scan_of_each_table_did(tmp_path):
    """NodeIndex(tables).select equals a scan of every table for the node (the code it
    replaced, written out here): rows matched through either node column, case-blind and
    stripped, tables without the node dropped, the tables' attributes kept, and a table
    without node column kept when its title names the node."""
    from fretwear.io.aster import read_aster_tables
    from fretwear.io.aster_source import NodeIndex

    path = tmp_path / "nodes.tab"
    _many_nodes(path, 6)
    table = read_aster_tables(path)[0]
    other = table.copy()
    other["NOEUD_CHOC"] = ["n5 "] * len(other)  # every row of this table names N5 too
    titled = pd.DataFrame({"INST": [0.0, 1e-3], "VINT1": [1.0, 2.0]})
    titled.attrs.update(title="FORCE DU CHOC N2", types=["R", "R"])
    tables = [table, other, titled]
    index = NodeIndex(tables)
    for node in ("N0", "n5", " N2 "):
        got, checked = index.select(node, "t")
        expected = []
        for frame in tables:
            if "NOEUD" in frame.columns:
                match = np.zeros(len(frame), dtype=bool)
                for column in ("NOEUD", "NOEUD_CHOC"):
                    match |= (frame[column].astype(str).str.strip().str.upper()
                              == node.strip().upper()).to_numpy()
                if match.any():
                    expected.append(frame.loc[match].reset_index(drop=True))
            elif node.strip().upper() in frame.attrs["title"]:
                expected.append(frame)
        assert checked is True and len(got) == len(expected)
        for g, e in zip(got, expected, strict=True):
            pd.testing.assert_frame_equal(g, e, check_exact=True)
            assert g.attrs == e.attrs
    assert index.held == [f"N{k}" for k in range(6)] + [f"n{k}" for k in range(6)]
