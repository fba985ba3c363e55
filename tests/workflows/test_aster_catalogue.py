"""POST_USURE as pasted from a Code_Aster command file: the catalogue rule by rule, and the forms
Code_Aster's catalogue accepts (issue 14).

The catalogue is code_aster 16's ``code_aster/Cata/Commands/post_usure.py``; the behaviours
quoted are its operator's (``bibfor/op/op0153.F90``: ANGL_INIT read in the first SECTEUR only and
equal to -180, ANGL_FIN increasing and ending at 180, LARGEUR_OBST = 0.011 m by default, reuse of
TABL_USURE; ``usuban.F90``: MATER_USURE codes). Expected values: Archard V = K·P·t (theory §4),
sector volumes V_j = k_j·P_j·t and depths R_m − √(R_m² − 2V/(l·Δθ)) (theory §3), coefficients
from an independent ``fretwear.database.lookup``.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear import ContactHistory
from fretwear.database import lookup
from fretwear.errors import DatabaseError, FretwearWarning, KeywordError, UnusedKeywordWarning
from fretwear.laws import WEAR_LAWS
from fretwear.workflows.aster import _F, CATALOGUE, POST_USURE, SIMPLE_KEYWORDS
from fretwear.workflows.aster_catalogue import (
    AU_MOINS_UN,
    ENSEMBLE,
    EXCLUS,
    PRESENT_ABSENT,
    PRESENT_PRESENT,
    UN_PARMI,
    Fact,
)

YEAR = 31_536_000.0
ISSUE_KEYWORDS = (
    "TUBE_NEUF", "TABL_USURE", "ETAT_INIT", "RESU_GENE", "INST_FIN", "PUIS_USURE", "LOI_USURE",
    "NOEUD", "GROUP_NO", "MOBILE", "OBSTACLE", "SECTEUR", "MATER_USURE", "USURE_OBST",
    "FNOR_MAXI", "VTAN_MAXI", "CONTACT", "RAYON_MOBILE", "RAYON_OBST", "LARGEUR_OBST",
    "ANGL_INCLI", "ANGL_ISTHME", "ANGL_IMPACT", "INST_INIT", "NB_BLOC", "COEF_INST", "INST",
    "LIST_INST", "INFO", "TITRE")


def history():
    """Fn = 20 N, ‖Vt‖ = 0.05 m/s: P = 1 W (theory §2); 4 intervals at 45° (sector 2 of 2) then
    4 at −135° (sector 1): P_1 = P_2 = 0.5 W (theory §3)."""
    n = 9
    angle = np.where(np.arange(n) < 4, 45.0, -135.0)
    return ContactHistory(time=np.linspace(0, 8, n), normal_force=np.full(n, 20.0),
                          vt1=np.full(n, 0.03), vt2=np.full(n, 0.04), name="N12",
                          dy=np.cos(np.radians(angle)) * 1e-4,
                          dz=np.sin(np.radians(angle)) * 1e-4)


# --------------------------------------------------------------------------- rule kinds
@pytest.mark.parametrize("rule, present, ok", [
    (UN_PARMI("A", "B"), set(), False), (UN_PARMI("A", "B"), {"A"}, True),
    (UN_PARMI("A", "B"), {"A", "B"}, False),
    (AU_MOINS_UN("A", "B"), set(), False), (AU_MOINS_UN("A", "B"), {"A", "B"}, True),
    (EXCLUS("A", "B"), set(), True), (EXCLUS("A", "B"), {"B"}, True),
    (EXCLUS("A", "B"), {"A", "B"}, False),
    (ENSEMBLE("A", "B"), set(), True), (ENSEMBLE("A", "B"), {"A", "B"}, True),
    (ENSEMBLE("A", "B"), {"A"}, False),
    (PRESENT_PRESENT("A", "B", "C"), {"B"}, True), (PRESENT_PRESENT("A", "B", "C"), {"A", "B"},
                                                     False),
    (PRESENT_PRESENT("A", "B", "C"), {"A", "B", "C"}, True),
    (PRESENT_ABSENT("A", "B", "C"), {"B", "C"}, True), (PRESENT_ABSENT("A", "B"), {"A", "B"},
                                                         False),
])
def test_rule_kinds_as_code_aster_defines_them(rule, present, ok):
    if ok:
        rule.check(present, "CMD")
    else:
        with pytest.raises(KeywordError, match=rf"CMD.*\[{rule.kind}\]"):
            rule.check(present, "CMD")


# --------------------------------------------------------------------------- the catalogue
def test_every_keyword_of_code_aster_is_in_the_catalogue():
    assert set(ISSUE_KEYWORDS) <= set(CATALOGUE.all_keywords())
    assert "reuse" in CATALOGUE.all_keywords()
    # into-values from the registries, law coefficients and defaults as the laws' own
    assert CATALOGUE.keywords["LOI_USURE"].into == tuple(WEAR_LAWS)
    for bloc in CATALOGUE.blocs:
        law = bloc.text.removeprefix("LOI_USURE='").rstrip("'")
        if law not in WEAR_LAWS:
            continue
        wear_law = WEAR_LAWS[law]
        by_keyword = {k: p for p, k in wear_law.aster_keywords.items()}
        for key, simp in bloc.keywords["MOBILE"].keywords.items():
            assert key in by_keyword, (law, key)
            if simp.default is not None:
                assert wear_law.defaults[by_keyword[key]] == simp.default, (law, key)
    assert all(isinstance(v, str) and v for v in SIMPLE_KEYWORDS.values())


BASE = dict(LOI_USURE="ARCHARD", CONTACT="TUBE_BAV", RAYON_MOBILE=0.0111, LARGEUR_OBST=0.0127,
            COEF_INST=YEAR, PUIS_USURE=0.012, MOBILE=_F(COEF_USURE=1.2e-13), INST=(1.0, 2.0))


def call(**changes):
    kw = dict(BASE, **changes)
    return POST_USURE(**{k: v for k, v in kw.items() if v is not None})


# one Code_Aster call breaking each rule of the catalogue, with the rule's tag
RULE_CASES = [
    ("UN_PARMI TUBE_NEUF RESU_GENE PUIS_USURE", dict(PUIS_USURE=None), "UN_PARMI"),
    ("UN_PARMI TUBE_NEUF LOI_USURE", dict(LOI_USURE=None, MOBILE=None), "UN_PARMI"),
    ("PRESENT_ABSENT TUBE_NEUF ETAT_INIT INST_FIN",
     dict(TUBE_NEUF="OUI", PUIS_USURE=None, LOI_USURE=None, MOBILE=None, CONTACT=None,
          RAYON_MOBILE=None, LARGEUR_OBST=None, COEF_INST=None, INST=None, INST_FIN=1.0),
     "PRESENT_ABSENT"),
    ("PRESENT_ABSENT TUBE_NEUF RAYON_MOBILE ...",
     dict(TUBE_NEUF="OUI", PUIS_USURE=None, LOI_USURE=None, MOBILE=None, COEF_INST=None,
          INST=None), "PRESENT_ABSENT"),
    ("PRESENT_ABSENT TUBE_NEUF ANGL_INCLI ...",
     dict(TUBE_NEUF="OUI", PUIS_USURE=None, LOI_USURE=None, MOBILE=None, CONTACT=None,
          RAYON_MOBILE=None, LARGEUR_OBST=None, COEF_INST=None, INST=None, ANGL_IMPACT=1.0),
     "PRESENT_ABSENT"),
    ("PRESENT_PRESENT ANGL_INCLI CONTACT", dict(CONTACT=None, ANGL_INCLI=1.0), "PRESENT_PRESENT"),
    ("PRESENT_PRESENT ANGL_ISTHME CONTACT", dict(CONTACT=None, ANGL_ISTHME=1.0),
     "PRESENT_PRESENT"),
    ("PRESENT_PRESENT ANGL_IMPACT CONTACT", dict(CONTACT=None, ANGL_IMPACT=1.0),
     "PRESENT_PRESENT"),
    ("b_resu_gene EXCLUS NOEUD GROUP_NO",
     dict(PUIS_USURE=None, RESU_GENE=history(), NOEUD="N12", GROUP_NO="G"), "EXCLUS"),
    ("b_archard UN_PARMI MOBILE MATER_USURE SECTEUR", dict(MOBILE=None), "UN_PARMI"),
    ("b_archard EXCLUS MATER_USURE OBSTACLE",
     dict(MOBILE=None, MATER_USURE="I600_Z6C13", OBSTACLE=_F(COEF_USURE=1e-14)), "EXCLUS"),
    ("b_archard EXCLUS MOBILE USURE_OBST", dict(USURE_OBST="OUI"), "EXCLUS"),
    ("b_kwu_epri UN_PARMI MOBILE MATER_USURE", dict(LOI_USURE="KWU_EPRI", MOBILE=None),
     "UN_PARMI"),
    ("b_kwu_epri EXCLUS MATER_USURE OBSTACLE",
     dict(LOI_USURE="KWU_EPRI", MOBILE=None, MATER_USURE="I600_I600",
          OBSTACLE=_F(COEF_USURE=1e-14)), "EXCLUS"),
    ("b_kwu_epri EXCLUS MOBILE USURE_OBST", dict(LOI_USURE="KWU_EPRI", USURE_OBST="OUI"),
     "EXCLUS"),
    ("b_edf_mz UN_PARMI MOBILE MATER_USURE", dict(LOI_USURE="EDF_MZ", MOBILE=None), "UN_PARMI"),
    ("b_edf_mz EXCLUS MATER_USURE OBSTACLE",
     dict(LOI_USURE="EDF_MZ", MOBILE=None, MATER_USURE="I600_I600", OBSTACLE=_F()), "EXCLUS"),
    ("b_edf_mz EXCLUS MOBILE USURE_OBST", dict(LOI_USURE="EDF_MZ", MOBILE=_F(),
                                               USURE_OBST="OUI"), "EXCLUS"),
    ("b_not_tube_neuf UN_PARMI INST LIST_INST", dict(LIST_INST=[3.0]), "UN_PARMI"),
]


@pytest.mark.parametrize("label, changes, kind", RULE_CASES, ids=[c[0] for c in RULE_CASES])
def test_each_rule_of_the_catalogue(label, changes, kind):
    with pytest.raises(KeywordError, match=rf"\[{kind}\]"):
        call(**changes)


def test_every_rule_has_a_case():
    rules = list(CATALOGUE.rules) + [r for b in CATALOGUE.blocs for r in b.rules]
    assert len(rules) == len(RULE_CASES)


@pytest.mark.parametrize("changes, match", [
    (dict(FNOR_MAXI=100.0), "FNOR_MAXI is accepted only when LOI_USURE='KWU_EPRI'"),
    (dict(LOI_USURE="EDF_MZ", MOBILE=None,
          SECTEUR=_F(ANGL_INIT=-180.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=1e-13)),
     "SECTEUR is accepted only when LOI_USURE='ARCHARD'"),
    (dict(NOEUD="N12"), "NOEUD is accepted only when RESU_GENE is given"),
    (dict(TABL_USURE="t.tab"), "TABL_USURE is accepted only when TUBE_NEUF='OUI'"),
    (dict(MOBILE=_F(COEF_B=1.2)), r"unknown keyword\(s\) \['COEF_B'\] in MOBILE"),
    (dict(MOBILE=_F()), r"MOBILE needs COEF_USURE"),
    (dict(CONTACT="TUBE_PLAT"), r"CONTACT='TUBE_PLAT' is not allowed; choose one of"),
    (dict(INFO=3), r"INFO=3 is not allowed"),
    (dict(NB_BLOC=2.5, PUIS_USURE=None, RESU_GENE=history()), "NB_BLOC must be a whole number"),
])
def test_blocks_types_and_values(changes, match):
    with pytest.raises(KeywordError, match=match):
        call(**changes)


# --------------------------------------------------------------------------- MATER_USURE
def test_mater_usure_in_code_aster_form_and_codes():
    # TAB = POST_USURE(PUIS_USURE=0.012, LOI_USURE='ARCHARD', MATER_USURE='I600_Z6C13', ...)
    k = lookup("TUBE_BAV", "I600", "Z6C13", "ARCHARD").mobile["coefficient"]
    t = call(MOBILE=None, MATER_USURE="I600_Z6C13")
    np.testing.assert_allclose(t["V_USUR_TUBE"], k * 0.012 * YEAR * np.array([1.0, 2.0]),
                               rtol=1e-15)
    pd.testing.assert_frame_equal(call(MOBILE=None, MATER_USURE="I600/Z6C13"), t)
    # Code_Aster's code I690_Z6C13 is the reference manual's I690TT/Z6C13
    with pytest.warns(FretwearWarning, match=r"I690_Z6C13.*fretwear's pair I690TT/Z6C13"):
        t = call(MOBILE=None, MATER_USURE="I690_Z6C13")
    k = lookup("TUBE_BAV", "I690TT", "Z6C13", "ARCHARD").mobile["coefficient"]
    np.testing.assert_allclose(t["V_USUR_TUBE"].iloc[0], k * 0.012 * YEAR, rtol=1e-15)
    # a nitrided rod: NITRURE_A304L = A304LNI on A304L, obstacle wear from the database too
    grappe = dict(CONTACT="GRAPPE_ALESAGE", RAYON_MOBILE=4.84e-3, RAYON_OBST=5.25e-3,
                  LARGEUR_OBST=0.02, MOBILE=None, USURE_OBST="OUI")
    with pytest.warns(FretwearWarning, match="nitrided"):
        nitrided = call(MATER_USURE="NITRURE_A304L", **grappe)
    row = lookup("GRAPPE_ALESAGE", "A304LNI", "A304L", "ARCHARD", obstacle=True)
    np.testing.assert_allclose(nitrided["V_USUR_OBST"].iloc[0],
                               row.obstacle["coefficient"] * 0.012 * YEAR, rtol=1e-15)
    with pytest.warns(FretwearWarning, match="chromium"):
        call(MATER_USURE="CHROME_A304L", **grappe)


def test_an_unknown_pair_lists_the_database_in_code_aster_form():
    with pytest.raises(DatabaseError, match=r"MATER_USURE in Code_Aster's form for TUBE_BAV/"
                                            r"ARCHARD: I600_I600, .*I600_Z6C13.*; Code_Aster's "
                                            r"codes I690_Z6C13 \(= I690TT_Z6C13\)"):
        call(MOBILE=None, MATER_USURE="I600_A42")


# --------------------------------------------------------------------------- SECTEUR forms
SECT = dict(PUIS_USURE=None, RESU_GENE=history(), MOBILE=None, COEF_INST=3600.0,
            CONTACT=None, RAYON_MOBILE=4.84e-3)


def test_secteur_without_contact_gives_sector_depths():
    # TAB = POST_USURE(RESU_GENE=TRAN, NOEUD='N12', LOI_USURE='ARCHARD', RAYON_MOBILE=4.84e-3,
    #                  LARGEUR_OBST=0.01, SECTEUR=(_F(COEF_USUR_MOBILE=1e-13, ANGL_INIT=-180.,
    #                  ANGL_FIN=0.), _F(COEF_USUR_MOBILE=2e-13, ANGL_FIN=180.)), INST=(1., 2.))
    t = call(LARGEUR_OBST=0.01, NOEUD="N12", **dict(SECT, RESU_GENE={"N12": history()}),
             SECTEUR=(_F(COEF_USUR_MOBILE=1e-13, ANGL_INIT=-180.0, ANGL_FIN=0.0),
                      _F(COEF_USUR_MOBILE=2e-13, ANGL_FIN=180.0)))
    v = np.array([1e-13, 2e-13]) * 0.5 * 3600.0 * 2.0
    last = t[t["INST"] == 2.0]
    np.testing.assert_allclose(last["V_USUR_TUBE_CUMU"], v, rtol=1e-12)
    np.testing.assert_allclose(last["P_USUR_TUBE_SECT"],
                               4.84e-3 - np.sqrt(4.84e-3**2 - 2 * v / (0.01 * np.pi)), rtol=1e-9)
    assert t["P_USUR_TUBE"].isna().all()
    assert "no contact type (CONTACT)" in t.attrs["global_depth"]
    # ANGL_INIT given in every occurrence (consistent) is the same computation
    same = call(LARGEUR_OBST=0.01, **SECT,
                SECTEUR=(_F(COEF_USUR_MOBILE=1e-13, ANGL_INIT=-180.0, ANGL_FIN=0.0),
                         _F(COEF_USUR_MOBILE=2e-13, ANGL_INIT=0.0, ANGL_FIN=180.0)))
    pd.testing.assert_frame_equal(same, t)


def test_secteur_without_coefficient_or_width():
    with pytest.warns(UnusedKeywordWarning, match=r"LARGEUR_OBST = 0.011 m, Code_Aster's default"):
        t = call(LARGEUR_OBST=None, **SECT,
                 SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0),
                          _F(COEF_USUR_MOBILE=1e-13, ANGL_FIN=180.0)))
    last = t[t["INST"] == 2.0]
    assert last["V_USUR_TUBE_CUMU"].iloc[0] == 0.0  # no COEF_USUR_MOBILE: 0, as in Code_Aster
    v = 1e-13 * 0.5 * 3600.0 * 2.0
    np.testing.assert_allclose(last["P_USUR_TUBE_SECT"].iloc[1],
                               4.84e-3 - np.sqrt(4.84e-3**2 - 2 * v / (0.011 * np.pi)), rtol=1e-9)


@pytest.mark.parametrize("secteur, match", [
    ((_F(ANGL_INIT=-170.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=1e-13),),
     r"SECTEUR\[0\] ANGL_INIT = -170 deg: the first sector starts at -180 deg"),
    ((_F(ANGL_INIT=-180.0, ANGL_FIN=0.0), _F(ANGL_FIN=170.0)),
     r"SECTEUR\[1\] ANGL_FIN = 170 deg: the last sector ends at 180 deg"),
    ((_F(ANGL_FIN=180.0),), r"SECTEUR\[0\] needs ANGL_INIT = -180"),
    ((_F(ANGL_INIT=-180.0, ANGL_FIN=10.0), _F(ANGL_FIN=0.0)),
     r"SECTEUR\[1\] ANGL_FIN = 0 deg must exceed its start 10 deg"),
])
def test_sectors_must_cover_the_turn(secteur, match):
    with pytest.raises(KeywordError, match=match):
        call(LARGEUR_OBST=0.01, **SECT, SECTEUR=secteur)


# --------------------------------------------------------------------------- other forms
def test_reuse_with_etat_init_and_tube_neuf():
    # TAB = POST_USURE(...); TAB = POST_USURE(reuse=TAB, ETAT_INIT=_F(TABL_USURE=TAB), ...)
    tab = call()
    cont = call(reuse=tab, ETAT_INIT=_F(TABL_USURE=tab), INST=(1.0,))
    pd.testing.assert_frame_equal(cont, call(ETAT_INIT=_F(TABL_USURE=tab), INST=(1.0,)))
    np.testing.assert_allclose(cont["V_USUR_TUBE"].iloc[-1], 1.2e-13 * 0.012 * 3 * YEAR,
                               rtol=1e-14)
    assert len(tab) == 2  # the table given is not modified
    # TAB = POST_USURE(reuse=TAB, TUBE_NEUF='OUI', TABL_USURE=TAB, INST=1.)
    new = POST_USURE(reuse=tab, TUBE_NEUF="OUI", TABL_USURE=tab, INST=1.0)
    assert new["V_USUR_TUBE"].iloc[0] == 0.0
    with pytest.raises(KeywordError, match="reuse= must be the table given to TABL_USURE"):
        call(reuse=call(), ETAT_INIT=_F(TABL_USURE=tab))
    with pytest.raises(KeywordError, match="reuse= continues the table given to TABL_USURE"):
        call(reuse=tab)


def test_puis_usure_ignores_the_history_window():
    with pytest.warns(UnusedKeywordWarning, match=r"INST_INIT, INST_FIN, NB_BLOC apply to "
                                                  r"RESU_GENE.*ignored, as in Code_Aster"):
        t = call(INST_INIT=1.0, INST_FIN=2.0, NB_BLOC=4)
    pd.testing.assert_frame_equal(t, call())


def test_tube_neuf_before_the_last_instant_keeps_the_later_rows():
    # TAB = POST_USURE(reuse=TAB, TUBE_NEUF='OUI', TABL_USURE=TAB, INST=1.)
    tab = call(INST=(1.0, 2.0, 3.0))
    new = POST_USURE(reuse=tab, TUBE_NEUF="OUI", TABL_USURE=tab, INST=1.0)
    assert new["INST"].tolist() == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(new["V_USUR_TUBE"], 1.2e-13 * 0.012 * YEAR * np.array([0, 1, 2]),
                               rtol=1e-14, atol=1e-30)
    with pytest.raises(KeywordError, match="under TUBE_NEUF, INST is one instant"):
        POST_USURE(TUBE_NEUF="OUI", TABL_USURE=tab, INST=(1.0, 2.0))


# choc.tab is sampled every 1 s: the coarse step is flagged (likely ms), irrelevant to NOEUD
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_noeud_selects_in_a_file_and_is_checked(tmp_path):
    """RESU_GENE a Code_Aster table of two shock points (N12 and N13 with the force doubled):
    NOEUD picks one; a NOEUD the file does not hold is an error."""
    lines = ["#", "#TABLE_SDASTER", "NOEUD INST VINT1 VINT11 VINT12"]
    for node, f in (("N12", 20.0), ("N13", 40.0)):
        lines += [f"{node} {t:.17E} {f:.17E} {0.03:.17E} {0.04:.17E}" for t in range(9)]
    path = tmp_path / "choc.tab"
    path.write_text("\n".join(lines) + "\n")
    kw = dict(PUIS_USURE=None, RESU_GENE=str(path), INST=(1.0,), COEF_INST=3600.0)
    np.testing.assert_allclose(call(NOEUD="N13", **kw)["PUIS_USUR_GLOBAL"], 2.0, rtol=1e-14)
    np.testing.assert_allclose(call(GROUP_NO="N12", **kw)["PUIS_USUR_GLOBAL"], 1.0, rtol=1e-14)
    with pytest.raises(KeywordError, match=r"'N14' \(NOEUD/GROUP_NO\) is not in this file"):
        call(NOEUD="N14", **kw)
    # a history names its node: another NOEUD is an error
    with pytest.raises(KeywordError, match="RESU_GENE is the history of 'N12'"):
        call(PUIS_USURE=None, RESU_GENE=history().replace(metadata={"node": "N12"}),
             NOEUD="N13")


def test_every_catalogue_factor_keyword_lists_its_keywords():
    facts = {k: d for k, defs in CATALOGUE.all_keywords().items() for d in defs
             if isinstance(d, Fact)}
    assert set(facts) == {"ETAT_INIT", "MOBILE", "OBSTACLE", "SECTEUR"}
    assert set(facts["SECTEUR"].keywords) == {"COEF_USUR_MOBILE", "COEF_USUR_OBST", "ANGL_INIT",
                                              "ANGL_FIN", "CONTACT"}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        call(TITRE="wear of N12", INFO=2)  # accepted silently
