"""Calls written as in a Code_Aster command file, found in the review of issue 14.

* EDF_MZ with every coefficient at the catalogue's default (``MOBILE=_F()``), as a code_aster
  test command file calls it; expected V = ((A·P^b − S)/n)(1 − e^(−n·t)) + S·t with the defaults
  of code_aster's catalogue (A = 1e-13, b = 1.2, n = 2.44e-8, S = 1.14e-16; theory §4),
  written out here.
* A MATER_USURE pair the database lacks: the message reads as sentences and lists the pairs.
* TUBE_NEUF at an instant the table does not hold: the error names TUBE_NEUF's INST.
* POST_DYNA_MODA_T on one IMPR_TABLE holding several shock points (a NOEUD column): every shock
  point, as Code_Aster's does for a tran_gene; the second node (its force doubled) has twice the
  wear power and the same impacts with doubled peaks.
* POST_USURE on such a file without NOEUD: the error says to give NOEUD.
* OBSTACLE next to SECTEUR (the catalogue allows it; Code_Aster's usuvu2 uses only the sectors'
  COEF_USUR_OBST): not used, with a warning. TITRE with TUBE_NEUF titles the table.

The two-node file is ``tests/io/fixtures/impr_table_tableau.txt`` (hand-written IMPR_TABLE of
N12) with its rows repeated for N13, VINT1 doubled.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import DatabaseError, FormatError, InputError, UnusedKeywordWarning
from fretwear.workflows.aster import _F, POST_DYNA_MODA_T, POST_USURE

TABLEAU = Path(__file__).parents[1] / "io" / "fixtures" / "impr_table_tableau.txt"


def _two_nodes(tmp_path: Path) -> Path:
    lines = TABLEAU.read_text().splitlines()
    header, rows = lines[:4], lines[4:]
    doubled = []
    for r in rows:
        cells = r.split()
        cells[0], cells[2] = "N13", f"{2 * float(cells[2]):12.5E}"
        doubled.append(" " + "  ".join(cells))
    path = tmp_path / "tabchoc.tab"
    path.write_text("\n".join(header + rows + doubled) + "\n")
    return path


def test_edf_mz_with_the_catalogue_defaults():
    # T1 = POST_USURE(PUIS_USURE=0.5, LOI_USURE='EDF_MZ', MOBILE=_F(), CONTACT='TUBE_BAV',
    #                 RAYON_MOBILE=1., LARGEUR_OBST=10., INST=(1., 2., ..., 7.),
    #                 COEF_INST=31536000.)
    inst = (1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0)
    t1 = POST_USURE(PUIS_USURE=0.5, LOI_USURE="EDF_MZ", MOBILE=_F(), CONTACT="TUBE_BAV",
                    RAYON_MOBILE=1.0, LARGEUR_OBST=10.0, INST=inst, COEF_INST=31536000.0)
    a, b, n, s = 1.0e-13, 1.2, 2.44e-8, 1.14e-16
    t = np.array(inst) * 31536000.0
    expected = (a * 0.5**b - s) / n * (1.0 - np.exp(-n * t)) + s * t
    np.testing.assert_allclose(t1["V_USUR_TUBE"], expected, rtol=1e-13)
    assert t1["INST"].tolist() == list(inst)
    # OBSTACLE=_F() with the same defaults wears the obstacle by the same law
    t2 = POST_USURE(PUIS_USURE=0.5, LOI_USURE="EDF_MZ", MOBILE=_F(), OBSTACLE=_F(),
                    CONTACT="TUBE_BAV", RAYON_MOBILE=1.0, LARGEUR_OBST=10.0, INST=inst,
                    COEF_INST=31536000.0)
    np.testing.assert_allclose(t2["V_USUR_OBST"], expected, rtol=1e-13)


def test_a_pair_without_coefficients_reads_as_sentences():
    # Code_Aster's usuban has KWU_EPRI values for TUBE_BAV I600_I600 only (docs/laws.md)
    with pytest.raises(DatabaseError, match=r"--database\)\. MATER_USURE in Code_Aster's form "
                                            r"for TUBE_BAV/KWU_EPRI: I600_I600$"):
        POST_USURE(PUIS_USURE=0.01, LOI_USURE="KWU_EPRI", MATER_USURE="I600_A405",
                   CONTACT="TUBE_BAV", RAYON_MOBILE=9.525e-3, LARGEUR_OBST=12.7e-3, INST=(1.0,))


def test_tube_neuf_at_an_instant_the_table_does_not_hold():
    tab = POST_USURE(PUIS_USURE=0.01, LOI_USURE="ARCHARD", MOBILE=_F(COEF_USURE=1e-13),
                     CONTACT="TUBE_BAV", RAYON_MOBILE=9.525e-3, LARGEUR_OBST=12.7e-3,
                     INST=(1.0, 2.0, 3.0), COEF_INST=31536000.0)
    # TAB = POST_USURE(reuse=TAB, TUBE_NEUF='OUI', TABL_USURE=TAB, INST=10.)
    with pytest.raises(InputError, match=r"TUBE_NEUF at INST = 10: not an instant of the wear "
                                         r"table \(TABL_USURE\), whose instants are \[1\.0, 2\.0, "
                                         r"3\.0\]"):
        POST_USURE(reuse=tab, TUBE_NEUF="OUI", TABL_USURE=tab, INST=10.0)
    assert len(tab) == 3


def test_post_dyna_moda_t_on_a_table_of_several_shock_points(tmp_path):
    path = _two_nodes(tmp_path)
    # TABCHOC = POST_DYNA_MODA_T(RESU_GENE=TRAN_GE, CHOC=_F(OPTION='USURE', NB_BLOC=1))
    both = POST_DYNA_MODA_T(RESU_GENE=str(path), CHOC=_F(OPTION="USURE", NB_BLOC=1))
    assert both["NOEUD"].unique().tolist() == ["N12", "N13"]
    assert both["INTITULE"].unique().tolist() == ["N12", "N13"]
    # each shock point's rows are the ones of that point alone
    for node in ("N12", "N13"):
        alone = POST_DYNA_MODA_T(RESU_GENE={node: str(path)}, CHOC=_F(OPTION="USURE"))
        mine = both[both["NOEUD"] == node].reset_index(drop=True)
        pd.testing.assert_frame_equal(mine.drop(columns="INTITULE"),
                                      alone.drop(columns="INTITULE"))
    power = both.loc[both["CALCUL"] == "PUIS_USURE"].set_index("NOEUD")["PUIS_USURE"]
    assert power["N13"] == pytest.approx(2 * power["N12"], rel=1e-12)
    # impacts: the same ones, peaks doubled
    imp = POST_DYNA_MODA_T(RESU_GENE=str(path), CHOC=_F(OPTION="IMPACT"))
    peaks = imp[imp["CALCUL"] == "IMPACT"].groupby("NOEUD")["F_MAX"].apply(list)
    assert peaks["N12"] == [25.0] and peaks["N13"] == [50.0]


def test_post_usure_on_several_shock_points_asks_for_noeud(tmp_path):
    with pytest.raises(FormatError, match=r"choose one with node='N12' \(POST_USURE's "
                                          r"NOEUD='N12' or GROUP_NO"):
        POST_USURE(RESU_GENE=str(_two_nodes(tmp_path)), LOI_USURE="ARCHARD",
                   MOBILE=_F(COEF_USURE=1e-13), CONTACT="TUBE_BAV", RAYON_MOBILE=9.525e-3,
                   LARGEUR_OBST=12.7e-3, INST=1.0)
    assert math.isfinite(POST_USURE(
        RESU_GENE=str(_two_nodes(tmp_path)), NOEUD="N13", LOI_USURE="ARCHARD",
        MOBILE=_F(COEF_USURE=1e-13), CONTACT="TUBE_BAV", RAYON_MOBILE=9.525e-3,
        LARGEUR_OBST=12.7e-3, INST=1.0)["V_USUR_TUBE"].iloc[0])


def test_obstacle_with_secteur_is_not_used_and_says_so():
    # Code_Aster's catalogue accepts OBSTACLE next to SECTEUR; its usuvu2 uses only the sectors'
    # COEF_USUR_OBST: with none given the obstacle does not wear
    secteur = (_F(COEF_USUR_MOBILE=1e-14, ANGL_INIT=-180.0, ANGL_FIN=0.0),
               _F(COEF_USUR_MOBILE=1e-14, ANGL_FIN=180.0))
    with pytest.warns(UnusedKeywordWarning, match="OBSTACLE is not used"):
        t = POST_USURE(RESU_GENE=str(TABLEAU), NOEUD="N12", LOI_USURE="ARCHARD",
                       RAYON_MOBILE=9.525e-3, RAYON_OBST=9.75e-3, LARGEUR_OBST=12.7e-3,
                       OBSTACLE=_F(COEF_USURE=5e-15), SECTEUR=secteur, INST=(1.0,))
    assert (t["V_USUR_OBST_CUMU"] == 0.0).all()


def test_tube_neuf_keeps_titre():
    tab = POST_USURE(PUIS_USURE=0.01, LOI_USURE="ARCHARD", MOBILE=_F(COEF_USURE=1e-13),
                     CONTACT="TUBE_BAV", RAYON_MOBILE=9.525e-3, LARGEUR_OBST=12.7e-3,
                     INST=(1.0, 2.0))
    new = POST_USURE(reuse=tab, TUBE_NEUF="OUI", TABL_USURE=tab, INST=1.0, TITRE="tube neuf")
    assert new.attrs["title"] == "tube neuf"
