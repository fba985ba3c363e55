"""POST_DYNA_MODA_T(RESU_GENE=..., CHOC=_F(OPTION='USURE' or 'IMPACT')) with Code_Aster's columns
(Code_Aster ``statch.F90``, ``statim.F90``, ``impact.F90``; issue 14).

The history is piecewise linear, so every value is exact by hand: two triangular pulses of the
normal force, 8 N over [0, 2] s (peak at 1 s) and 4 N over [3, 5] s, free over [5, 6] s;
sliding at vt1 = 0.1 m/s; vn = 0.5 m/s; ft1 = −0.3·Fn; dy a triangle wave of amplitude A = 1e-4 m
and period 2 s, dz = 0. Over T = 6 s: ∫Fn dt = 8 + 4 = 12 N·s, ∫Fn² dt = 2·(8² + 4²)/3 N²·s,
contact time 4 s, P = 0.1·12/6 = 0.2 W (theory §2); a triangle wave has mean 0 and mean square
A²/3.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear import ContactHistory
from fretwear.errors import KeywordError, StationarityWarning
from fretwear.power import channel_statistics
from fretwear.workflows.aster import _F, POST_DYNA_MODA_T

A = 1e-4


def history(name="N12"):
    t = np.arange(0.0, 6.01, 0.5)
    fn = np.interp(t, [0, 1, 2, 3, 4, 5, 6], [0, 8, 0, 0, 4, 0, 0])
    dy = np.interp(t, [0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0],
                   [0, A, 0, -A, 0, A, 0, -A, 0, A, 0, -A, 0])
    n = t.size
    return ContactHistory(time=t, normal_force=fn, vt1=np.full(n, 0.1), vt2=np.zeros(n),
                          vn=np.full(n, 0.5), ft1=-0.3 * fn, dy=dy, dz=np.zeros(n), name=name)


def row(table, calcul, node="N12"):
    return table[(table["CALCUL"] == calcul) & (table["NOEUD"] == node)].iloc[0]


def test_usure_statistics_by_hand():
    # TABCHOC = POST_DYNA_MODA_T(RESU_GENE=TRAN_GE, CHOC=_F(OPTION='USURE', INST_INIT=0.,
    #                            INST_FIN=6., NB_BLOC=1, SEUIL_FORCE=0., DUREE_REPOS=0.))
    t = POST_DYNA_MODA_T(RESU_GENE=history(), CHOC=_F(OPTION="USURE", INST_INIT=0.0,
                                                        INST_FIN=6.0, NB_BLOC=1,
                                                        SEUIL_FORCE=0.0, DUREE_REPOS=0.0))
    assert list(t.columns) == [
        "INTITULE", "NOEUD", "CALCUL", "MOYEN", "ECART_TYPE", "RMS", "MAXI", "MINI",
        "MOYEN_T_TOTAL", "MOYEN_T_CHOC", "RMS_T_TOTAL", "RMS_T_CHOC", "NB_CHOC_S",
        "NB_REBON_CHOC", "T_CHOC_MOYEN", "T_CHOC_MAXI", "T_CHOC_MINI", "T_REBON_MOYEN",
        "%_T_CHOC", "PUIS_USURE"]
    assert t["CALCUL"].tolist() == ["DEPL_X", "DEPL_Y", "DEPL_Z", "DEPL_RADIAL", "DEPL_ANGULAIRE",
                                    "FORCE_NORMALE", "FORCE_TANG_1", "FORCE_TANG_2", "STAT_CHOC",
                                    "PUIS_USURE"]
    y = row(t, "DEPL_Y")
    assert y["MOYEN"] == pytest.approx(0.0, abs=1e-20)
    assert y["RMS"] == pytest.approx(A / math.sqrt(3), rel=1e-12)
    assert y["ECART_TYPE"] == pytest.approx(A / math.sqrt(3), rel=1e-12)
    assert (y["MAXI"], y["MINI"]) == (A, -A)
    radial = row(t, "DEPL_RADIAL")  # |dy|: mean A/2, mean square A²/3
    assert radial["MOYEN"] == pytest.approx(A / 2, rel=1e-12)
    assert radial["RMS"] == pytest.approx(A / math.sqrt(3), rel=1e-12)
    angle = row(t, "DEPL_ANGULAIRE")
    assert (angle["MAXI"], angle["MINI"]) == (180.0, 0.0)
    assert np.isnan(row(t, "DEPL_X")[["MOYEN", "RMS"]].astype(float)).all()  # no axial channel
    fn = row(t, "FORCE_NORMALE")
    i2 = 2 * (8.0**2 + 4.0**2) / 3
    assert fn["MOYEN_T_TOTAL"] == pytest.approx(12 / 6, rel=1e-14)
    assert fn["MOYEN_T_CHOC"] == pytest.approx(12 / 4, rel=1e-14)
    assert fn["RMS_T_TOTAL"] == pytest.approx(math.sqrt(i2 / 6), rel=1e-14)
    assert fn["RMS_T_CHOC"] == pytest.approx(math.sqrt(i2 / 4), rel=1e-14)
    assert fn["MAXI"] == 8.0
    ft = row(t, "FORCE_TANG_1")  # −0.3·Fn
    assert ft["MOYEN"] == pytest.approx(-0.3 * 2, rel=1e-14)
    assert ft["RMS"] == pytest.approx(0.3 * math.sqrt(i2 / 6), rel=1e-14)
    assert ft["ECART_TYPE"] == pytest.approx(math.sqrt(0.09 * i2 / 6 - 0.36), rel=1e-12)
    assert (ft["MAXI"], ft["MINI"]) == (0.0, -2.4)
    assert np.isnan(float(row(t, "FORCE_TANG_2")["MOYEN"]))  # no ft2 channel
    stat = row(t, "STAT_CHOC")
    assert stat["NB_CHOC_S"] == pytest.approx(2 / 6)
    assert stat[["T_CHOC_MOYEN", "T_CHOC_MAXI", "T_CHOC_MINI", "T_REBON_MOYEN"]].tolist() == \
        pytest.approx([2.0, 2.0, 2.0, 2.0])
    assert stat["NB_REBON_CHOC"] == 1.0 and stat["%_T_CHOC"] == pytest.approx(100 * 4 / 6)
    assert row(t, "PUIS_USURE")["PUIS_USURE"] == pytest.approx(0.1 * 12 / 6, rel=1e-14)
    assert t.attrs["missing"]["N12"] == ["DEPL_X (axial)", "ft2"]


def test_usure_rest_blocks_window_and_nodes():
    # a rest of 1.5 s joins the two pulses (1 s apart): one impact of two episodes (rebounds)
    t = POST_DYNA_MODA_T(RESU_GENE=history(), CHOC=_F(DUREE_REPOS=1.5))
    stat = row(t, "STAT_CHOC")
    assert stat["NB_CHOC_S"] == pytest.approx(1 / 6) and stat["NB_REBON_CHOC"] == 2.0
    assert stat["T_CHOC_MOYEN"] == pytest.approx(5.0) and stat["T_REBON_MOYEN"] == 2.0
    assert stat["%_T_CHOC"] == pytest.approx(100 * 5 / 6)
    # blocks: the block statistics of channel_statistics
    h = history()
    with pytest.warns(StationarityWarning):  # the two blocks' powers differ by 2/3
        two = POST_DYNA_MODA_T(RESU_GENE=h, CHOC=_F(NB_BLOC=2))
    s = channel_statistics(h.time, h.dy, blocks=2)
    assert row(two, "DEPL_Y")["ECART_TYPE"] == pytest.approx(s["std"], rel=1e-14)
    # a window (INST_FIN beyond the record is clipped, as Code_Aster does) and two nodes
    w = POST_DYNA_MODA_T(RESU_GENE={"N12": h, "N13": history("N13")},
                         CHOC=_F(INST_INIT=2.5, INST_FIN=999.0))
    assert set(w["NOEUD"]) == {"N12", "N13"}
    assert row(w, "FORCE_NORMALE", "N13")["MAXI"] == 4.0
    assert row(w, "PUIS_USURE", "N13")["PUIS_USURE"] == pytest.approx(0.1 * 4 / 3.5, rel=1e-14)
    with pytest.raises(KeywordError, match="INST_INIT = 7 s is not before INST_FIN"):
        POST_DYNA_MODA_T(RESU_GENE=h, CHOC=_F(INST_INIT=7.0))


def test_impact_table_by_hand():
    # TABIMP = POST_DYNA_MODA_T(RESU_GENE=TRAN_GE, CHOC=_F(OPTION='IMPACT', NB_CLASSE=2))
    t = POST_DYNA_MODA_T(RESU_GENE=history(), CHOC=_F(OPTION="IMPACT", NB_CLASSE=2))
    imp = t[t["CALCUL"] == "IMPACT"]
    assert imp["CHOC"].tolist() == [1, 2]
    assert imp["INSTANT"].tolist() == [1.0, 4.0] and imp["F_MAX"].tolist() == [8.0, 4.0]
    assert imp["IMPULSION"].tolist() == [8.0, 4.0] and imp["T_CHOC"].tolist() == [2.0, 2.0]
    assert imp["V_IMPACT"].tolist() == [0.5, 0.5] and imp["NB_IMPACT"].tolist() == [1, 1]
    glob = row(t, "GLOBAL")
    assert (glob["F_MAX_ABS"], glob["F_MAX_MOY"], glob["F_MAX_ETYPE"]) == (8.0, 6.0, 2.0)
    proba = t[t["CALCUL"] == "PROBA"]
    assert proba["CLASSE"].tolist() == [1, 2] and proba["PROBA"].tolist() == [0.5, 0.5]
    assert proba["DEBUT"].tolist() == [4.0, 6.0] and proba["FIN"].tolist() == [6.0, 8.0]


def test_no_contact_gives_zeros_as_code_aster():
    h = history()
    free = h.replace(normal_force=np.zeros(len(h)), ft1=np.zeros(len(h)))
    stat = row(POST_DYNA_MODA_T(RESU_GENE=free, CHOC=_F()), "STAT_CHOC")
    assert stat[["NB_CHOC_S", "NB_REBON_CHOC", "T_CHOC_MOYEN", "T_CHOC_MAXI", "T_CHOC_MINI",
                 "T_REBON_MOYEN", "%_T_CHOC"]].tolist() == [0.0] * 7
    imp = POST_DYNA_MODA_T(RESU_GENE=free, CHOC=_F(OPTION="IMPACT"))
    first = row(imp, "IMPACT")
    assert first["CHOC"] == 0 and first["F_MAX"] == 0.0
    assert row(imp, "GLOBAL")["F_MAX_MOY"] == 0.0


def test_catalogue_of_post_dyna_moda_t_and_the_old_path():
    with pytest.raises(KeywordError, match=r"exactly one of CHOC, RELA_EFFO_DEPL"):
        POST_DYNA_MODA_T(RESU_GENE=history())
    with pytest.raises(KeywordError, match="RELA_EFFO_DEPL is not available"):
        POST_DYNA_MODA_T(RESU_GENE=history(), RELA_EFFO_DEPL=_F(NOEUD="N1", NOM_CMP="DX"))
    with pytest.raises(KeywordError, match=r"OPTION='CHOC' is not allowed"):
        POST_DYNA_MODA_T(RESU_GENE=history(), CHOC=_F(OPTION="CHOC"))
    with pytest.raises(KeywordError, match="RESU_GENE is required"):
        POST_DYNA_MODA_T(CHOC=_F())
