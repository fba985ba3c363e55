"""Code_Aster compatibility: POST_USURE keywords, catalogue rules, table files (theory §1, §7).

The catalogue rules are those of Code_Aster's POST_USURE command (U4.84.05): exactly one of
PUIS_USURE / RESU_GENE / TUBE_NEUF, exactly one of MOBILE / MATER_USURE / SECTEUR, MATER_USURE
excludes OBSTACLE, exactly one of INST / LIST_INST, NOEUD excludes GROUP_NO. The fixtures in
tests/fixtures/aster_tables are written by hand (their README gives every value's computation).
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear import ContactHistory
from fretwear.errors import KeywordError
from fretwear.io.aster import read_aster_table, write_aster_table
from fretwear.table import from_aster_names, read_wear_table, wear_table
from fretwear.workflows.aster import _F, POST_USURE

FIXTURES = Path(__file__).parents[1] / "fixtures" / "aster_tables"
YEAR = 31_536_000.0
BASE = dict(LOI_USURE="ARCHARD", CONTACT="TUBE_BAV", RAYON_MOBILE=0.0111, LARGEUR_OBST=0.0127,
            COEF_INST=YEAR)


def call(**changes):
    kw = dict(BASE, PUIS_USURE=0.012, MOBILE=_F(COEF_USURE=1.2e-13), INST=(1.0, 2.0))
    kw.update(changes)
    return POST_USURE(**{k: v for k, v in kw.items() if v is not None})


def history():
    """Constant Fn = 20 N, ‖Vt‖ = 0.05 m/s: P = 1 W (theory §2); first 4 intervals at 45°
    (sector 2 of 2), the last 4 at −135° (sector 1): P_1 = P_2 = 0.5 W (theory §3)."""
    n = 9
    angle = np.where(np.arange(n) < 4, 45.0, -135.0)
    return ContactHistory(time=np.linspace(0, 8, n), normal_force=np.full(n, 20.0),
                          vt1=np.full(n, 0.03), vt2=np.full(n, 0.04),
                          dy=np.cos(np.radians(angle)) * 1e-4, dz=np.sin(np.radians(angle)) * 1e-4)


# --------------------------------------------------------------------------- values
def test_archard_power_values_and_column_names():
    t = call()
    v = 1.2e-13 * 0.012 * YEAR * np.array([1.0, 2.0])  # V = K·P·t, theory §4
    np.testing.assert_allclose(t["V_USUR_TUBE"], v, rtol=1e-15)
    assert t.columns.tolist() == ["INST", "DUREE", "ORIG_INST", "PUIS_USUR_GLOBAL", "V_USUR_TUBE",
                                 "V_USUR_OBST", "P_USUR_TUBE"]  # no obstacle depth: no column
    d = (1 / (2 * 0.0111)) ** (1 / 3) * (3 * v / (4 * 0.0127)) ** (2 / 3)  # theory §6 TUBE_BAV
    np.testing.assert_allclose(t["P_USUR_TUBE"], d, rtol=1e-9)
    with_obst = call(OBSTACLE=_F(COEF_USURE=1e-14))
    assert "P_USUR_OBST" in with_obst.columns and (with_obst["P_USUR_OBST"] > 0).all()


def test_list_inst_equals_inst_and_scalar_inst():
    a = call(INST=None, LIST_INST=[1.0, 2.0])
    pd.testing.assert_frame_equal(a, call())
    assert call(INST=2.0)["INST"].tolist() == [2.0]


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
def test_resu_gene_sectors_one_row_per_instant_and_sector():
    t = call(PUIS_USURE=None, RESU_GENE={"N12": history(), "N13": history()}, NOEUD="N12",
             MOBILE=None, COEF_INST=3600.0, INST=(1.0, 2.0),
             SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=1e-13,
                         COEF_USUR_OBST=1e-14, CONTACT="TUBE_BAV"),
                      _F(ANGL_INIT=0.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=2e-13)))
    assert t["SECTEUR"].tolist() == [1, 2, 1, 2]
    expected = np.array([1e-13, 2e-13]) * 0.5 * 3600.0 * 2.0  # V_j = k_j·P_j·t, theory §3
    np.testing.assert_allclose(t["V_USUR_TUBE_CUMU"].iloc[2:], expected, rtol=1e-12)
    np.testing.assert_allclose(t["V_USUR_OBST_CUMU"].iloc[2:], [1e-14 * 3600.0, 0.0], rtol=1e-12)
    assert {"P_USUR_TUBE_SECT", "ANGLE_DEBUT", "ANGLE_FIN", "P_USUR_OBST"} <= set(t.columns)
    # TUBE_BAV's bar is flat: no sector depth of the obstacle exists (theory §3 needs R_o)
    assert "P_USUR_OBST_SECT" not in t.columns


def test_sector_obstacle_depth_of_a_bore():
    """GRAPPE_ALESAGE sectors: P_USUR_OBST_SECT = √(R_o² + 2V/(l·Δθ)) − R_o and
    P_USUR_TUBE_SECT = R_m − √(R_m² − 2V/(l·Δθ)), Δθ = π rad (theory §3), V = k·P_j·t."""
    r_m, r_o, width = 4.84e-3, 5.25e-3, 0.02
    t = POST_USURE(RESU_GENE=history(), LOI_USURE="ARCHARD", CONTACT="GRAPPE_ALESAGE",
                   RAYON_MOBILE=r_m, RAYON_OBST=r_o, LARGEUR_OBST=width, INST=5.0,
                   COEF_INST=3600.0,
                   SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=2.6e-15,
                               COEF_USUR_OBST=3.7e-15),
                            _F(ANGL_INIT=0.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=2.6e-15)))
    vm = 2.6e-15 * 0.5 * 5 * 3600.0
    vo = np.array([3.7e-15 * 0.5 * 5 * 3600.0, 0.0])
    np.testing.assert_allclose(t["P_USUR_TUBE_SECT"], r_m - np.sqrt(r_m**2 - 2 * vm
                                                                   / (width * np.pi)), rtol=1e-9)
    np.testing.assert_allclose(t["P_USUR_OBST_SECT"], np.sqrt(r_o**2 + 2 * vo / (width * np.pi))
                               - r_o, rtol=1e-9, atol=1e-300)
    assert "P_USUR_OBST" in t.columns and (t["P_USUR_OBST"] > 0).all()
    # the metadata name the dimensions natively (what the obstacle update reads)
    assert t.attrs["dimensions"]["obstacle_width"] == width
    assert t.attrs["dimensions"]["obstacle_radius"] == r_o


def edf(power, t, a=1e-13, b=1.2, n=2.44e-8, s=1.14e-16):
    """Theory §4 EDF_MZ volume [m³]."""
    return (a * power**b - s) / n * (1 - np.exp(-n * t)) + s * t


def test_every_keyword_of_the_catalogue_is_accepted():
    """EDF_MZ with every coefficient keyword in MOBILE and OBSTACLE, a RESU_GENE window and
    blocks, GROUP_NO, a tilted TUBE_BAV, TITRE, INFO: V from theory §4 with P = 1 W (the
    history's constant power, theory §2), D = (1/(2R_m))^(1/5)·(15θV/8)^(2/5) (theory §6, tilt,
    D < l·θ) split d_m = D·V_m/V."""
    mob = dict(COEF_USURE=2e-16, COEF_B=1.1, COEF_N=3e-8, COEF_S=1e-17)
    obs = dict(COEF_USURE=5e-17, COEF_B=1.0, COEF_N=2e-8, COEF_S=2e-18)
    t = POST_USURE(RESU_GENE={"G1": history()}, GROUP_NO="G1", INST_INIT=1.0, INST_FIN=7.0,
                   NB_BLOC=3, LOI_USURE="EDF_MZ", MOBILE=_F(**mob), OBSTACLE=_F(**obs),
                   CONTACT="TUBE_BAV", RAYON_MOBILE=0.0111, LARGEUR_OBST=0.0127,
                   ANGL_INCLI=2.0, LIST_INST=np.array([0.5, 1.0]), COEF_INST=YEAR,
                   TITRE="wear", INFO=2)
    secs = np.array([0.5, 1.0]) * YEAR
    vm = edf(1.0, secs, mob["COEF_USURE"], mob["COEF_B"], mob["COEF_N"], mob["COEF_S"])
    vo = edf(1.0, secs, obs["COEF_USURE"], obs["COEF_B"], obs["COEF_N"], obs["COEF_S"])
    np.testing.assert_allclose(t["PUIS_USUR_GLOBAL"], 1.0, rtol=1e-12)
    np.testing.assert_allclose(t["V_USUR_TUBE"], vm, rtol=1e-10)
    np.testing.assert_allclose(t["V_USUR_OBST"], vo, rtol=1e-10)
    theta = np.radians(2.0)
    depth = (1 / (2 * 0.0111)) ** 0.2 * (15 * theta * (vm + vo) / 8) ** 0.4
    assert (depth < 0.0127 * theta).all()  # the first branch of the frustum rule
    np.testing.assert_allclose(t["P_USUR_TUBE"], depth * vm / (vm + vo), rtol=1e-8)
    np.testing.assert_allclose(t["P_USUR_OBST"], depth * vo / (vm + vo), rtol=1e-8)


@pytest.mark.parametrize("changes, match", [
    (dict(LOI_USURE="ARCHARDS"), "LOI_USURE='ARCHARDS' is not allowed; choose one of"),
    (dict(COEF_INST="year"), "COEF_INST must be a finite real"),
    (dict(RAYON_MOBILE="11 mm"), "RAYON_MOBILE must be a finite real"),
    (dict(PUIS_USURE="0.01"), "PUIS_USURE must be a finite real"),
    (dict(MOBILE=_F(COEF_USURE="1e-13")), "MOBILE COEF_USURE must be a finite real"),
    (dict(INST=(1.0, "2")), r"INST\[1\] must be a finite real"),
    (dict(PUIS_USURE=None, RESU_GENE=12.0), "RESU_GENE must be a ContactHistory"),
    (dict(PUIS_USURE=None, RESU_GENE=history(), NB_BLOC=2.5), "NB_BLOC must be a whole number"),
    (dict(PUIS_USURE=None, RESU_GENE=history(), MOBILE=None,
          SECTEUR=_F(ANGL_INIT=-180.0, ANGL_FIN="180", COEF_USUR_MOBILE=1e-13)),
     r"SECTEUR\[0\] ANGL_FIN must be a finite real"),
    (dict(ETAT_INIT=_F(TABL_USURE=FIXTURES / "post_usure_tableau.txt", INST_INIT="2")),
     "ETAT_INIT INST_INIT must be a finite real"),
])
def test_bad_values_name_the_keyword(changes, match):
    with pytest.raises(KeywordError, match=match):
        call(**changes)


# --------------------------------------------------------------------------- catalogue rules
@pytest.mark.parametrize("changes, match", [
    (dict(PUIS_USURE=None), "exactly one of TUBE_NEUF, RESU_GENE, PUIS_USURE.*got none"),
    (dict(RESU_GENE="x.csv"), "got RESU_GENE and PUIS_USURE"),
    (dict(TUBE_NEUF="OUI"), "got TUBE_NEUF and PUIS_USURE"),
    (dict(MOBILE=None), "exactly one of MOBILE, MATER_USURE, SECTEUR.*got none"),
    (dict(MATER_USURE="I600/I600"), "MOBILE and MATER_USURE"),
    (dict(SECTEUR=_F(ANGL_INIT=-180, ANGL_FIN=180, COEF_USUR_MOBILE=1e-13)),
     "MOBILE and SECTEUR"),
    (dict(MOBILE=None, MATER_USURE="I600/I600", OBSTACLE=_F(COEF_USURE=1e-14)),
     "MATER_USURE and OBSTACLE exclude each other"),
    (dict(INST=None), "exactly one of INST, LIST_INST.*got none"),
    (dict(LIST_INST=[3.0]), "INST and LIST_INST"),
    (dict(USURE_OBST="OUI"), "MOBILE and USURE_OBST exclude each other"),
    (dict(FNOR_MAXI=100.0), "FNOR_MAXI is accepted only when LOI_USURE='KWU_EPRI'"),
    (dict(NOEUD="N1"), "NOEUD is accepted only when RESU_GENE is given"),
    (dict(LOI_USURE=None), "exactly one of TUBE_NEUF, LOI_USURE is required"),
    (dict(CONTACT=None), "CONTACT is required"),
    (dict(COEF_USRE=1e-13), r"unknown keyword\(s\) \['COEF_USRE'\]"),
    (dict(MOBILE=_F(COEF_USURE=1e-13, COEF_X=1)), r"unknown keyword\(s\) \['COEF_X'\] in MOBILE"),
    (dict(MOBILE=_F(COEF_USURE=1e-13, COEF_B=1.0)),
     r"unknown keyword\(s\) \['COEF_B'\] in MOBILE; it accepts \['COEF_USURE'\]"),
    (dict(ETAT_INIT=_F(INST_INIT=1.0)), "ETAT_INIT needs TABL_USURE"),
    (dict(TABL_USURE="t.tab"), "TABL_USURE is accepted only when TUBE_NEUF='OUI'"),
])
def test_catalogue_rules(changes, match):
    with pytest.raises(KeywordError, match=match):
        call(**changes)


def test_catalogue_rules_of_resu_gene_and_sectors():
    with pytest.raises(KeywordError, match="NOEUD and GROUP_NO exclude each other"):
        call(PUIS_USURE=None, RESU_GENE=history(), NOEUD="N1", GROUP_NO="G1")
    with pytest.raises(KeywordError, match="'N9' is not in RESU_GENE"):
        call(PUIS_USURE=None, RESU_GENE={"N1": history()}, NOEUD="N9")
    with pytest.raises(KeywordError, match="pick one with NOEUD"):
        call(PUIS_USURE=None, RESU_GENE={"N1": history(), "N2": history()})
    with pytest.raises(KeywordError, match="SECTEUR is accepted only when LOI_USURE='ARCHARD'"):
        call(LOI_USURE="EDF_MZ", MOBILE=None,
             SECTEUR=_F(ANGL_INIT=-180, ANGL_FIN=180, COEF_USUR_MOBILE=1e-13))
    with pytest.raises(KeywordError, match=r"SECTEUR\[1\] ANGL_INIT = 10 deg must equal"):
        call(PUIS_USURE=None, RESU_GENE=history(), MOBILE=None,
             SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=1e-13),
                      _F(ANGL_INIT=10.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=1e-13)))
    with pytest.raises(KeywordError, match="give one CONTACT"):
        call(PUIS_USURE=None, RESU_GENE=history(), MOBILE=None, CONTACT=None,
             SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=1e-13,
                         CONTACT="TUBE_BAV"),
                      _F(ANGL_INIT=0.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=1e-13,
                         CONTACT="TUBE_ALESAGE")))


def test_tube_neuf_rules_and_result(tmp_path):
    with pytest.raises(KeywordError, match=r"TABL_USURE is required when TUBE_NEUF='OUI'"):
        POST_USURE(TUBE_NEUF="OUI")
    with pytest.raises(KeywordError, match=r"TUBE_NEUF='NON' is not allowed; choose one of "
                                           r"\['OUI'\]"):
        POST_USURE(TUBE_NEUF="NON", TABL_USURE=call())
    old = call(OBSTACLE=_F(COEF_USURE=1e-14))
    new = POST_USURE(TUBE_NEUF="OUI", TABL_USURE=old, INST=1.0)
    # the later row is kept, the tube restarted at INST 1 (Archard: K·P·1 year at INST 2)
    assert new["INST"].tolist() == [1.0, 2.0]
    assert new["V_USUR_TUBE"].iloc[0] == 0.0 and new["P_USUR_TUBE"].iloc[0] == 0.0
    np.testing.assert_allclose(new["V_USUR_TUBE"].iloc[1], 1.2e-13 * 0.012 * YEAR, rtol=1e-14)
    assert new["V_USUR_OBST"].tolist() == old["V_USUR_OBST"].tolist()
    # continue with the new tube against the worn obstacle, from the replacement
    cont = call(ETAT_INIT=_F(TABL_USURE=new, INST_INIT=1.0), OBSTACLE=_F(COEF_USURE=1e-14),
                INST=(1.0,))
    np.testing.assert_allclose(cont["V_USUR_TUBE"].iloc[-1], 1.2e-13 * 0.012 * YEAR, rtol=1e-14)
    np.testing.assert_allclose(cont["V_USUR_OBST"].iloc[-1], 1e-14 * 0.012 * 2 * YEAR,
                               rtol=1e-14)


# --------------------------------------------------------------------------- table files
def test_read_hand_written_tableau_fixture():
    frame = read_aster_table(FIXTURES / "post_usure_tableau.txt")
    assert frame["V_USUR_TUBE"].tolist() == [4.54118e-08, 9.08237e-08]
    assert frame["P_USUR_OBST"].isna().all()
    native = read_wear_table(FIXTURES / "post_usure_tableau.txt")
    assert {"instant", "volume_mobile", "depth_obstacle"} <= set(native.columns)


def test_etat_init_from_code_aster_tableau_file():
    """New rows: V = V_file(INST=2) + K·P·Δt (theory §7), from the file's printed value."""
    t = call(ETAT_INIT=_F(TABL_USURE=str(FIXTURES / "post_usure_tableau.txt")),
             INST=(1.0, 3.0))
    assert t["INST"].tolist() == [1.0, 2.0, 3.0, 5.0]
    assert t["ORIG_INST"].tolist() == [0.0, 0.0, 2.0, 2.0]
    np.testing.assert_allclose(t["V_USUR_TUBE"].iloc[2:],
                               9.08237e-08 + 1.2e-13 * 0.012 * YEAR * np.array([1.0, 3.0]),
                               rtol=1e-14)
    t1 = call(ETAT_INIT=_F(TABL_USURE=str(FIXTURES / "post_usure_tableau.txt"), INST_INIT=1.0),
              INST=(1.0,))
    assert t1["INST"].tolist() == [1.0, 2.0]
    np.testing.assert_allclose(t1["V_USUR_TUBE"].iloc[-1],
                               4.54118e-08 + 1.2e-13 * 0.012 * YEAR, rtol=1e-14)


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
def test_etat_init_from_code_aster_sector_file():
    """Cumulated sector volumes continue from the ASTER-format file's V_USUR_*_CUMU (theory §7)."""
    path = FIXTURES / "post_usure_secteurs.resu"
    sect = dict(PUIS_USURE=None, RESU_GENE=history(), MOBILE=None, COEF_INST=3600.0,
                SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=1e-13,
                            COEF_USUR_OBST=1e-14),
                         _F(ANGL_INIT=0.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=1e-13,
                            COEF_USUR_OBST=1e-14)))
    t = call(ETAT_INIT=_F(TABL_USURE=str(path)), INST=(2.0,), **sect)
    assert t["INST"].tolist() == [1.0, 1.0, 2.0, 2.0, 4.0, 4.0]
    np.testing.assert_allclose(t["V_USUR_TUBE_CUMU"].iloc[-2:],
                               np.array([2.88e-12, 5.76e-12]) + 1e-13 * 0.5 * 3600.0 * 2,
                               rtol=1e-14)
    np.testing.assert_allclose(t["V_USUR_OBST_CUMU"].iloc[-2:],
                               np.array([2.88e-13, 5.76e-13]) + 1e-14 * 0.5 * 3600.0 * 2,
                               rtol=1e-14)
    from fretwear.errors import InputError

    with pytest.raises(InputError, match="2 sectors and this run has none"):
        call(ETAT_INIT=_F(TABL_USURE=str(path)))
    with pytest.raises(InputError, match="2 sectors and this run has 1"):
        call(ETAT_INIT=_F(TABL_USURE=str(path)), **dict(
            sect, SECTEUR=_F(ANGL_INIT=-180.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=1e-13)))


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
@pytest.mark.parametrize("fmt", ["TABLEAU", "ASTER"])
def test_our_tables_round_trip_through_code_aster_files(tmp_path, fmt):
    ours = call(PUIS_USURE=None, RESU_GENE=history(), MOBILE=None, COEF_INST=3600.0,
                SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=1e-13),
                         _F(ANGL_INIT=0.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=3e-13,
                            COEF_USUR_OBST=1e-14)))
    path = write_aster_table(ours, tmp_path / "wear.tab", format=fmt, float_format="%.17E")
    back = read_aster_table(path)
    pd.testing.assert_frame_equal(back, ours, check_dtype=False, check_exact=True)
    # a continuation from the file equals a continuation from the frame
    a = call(ETAT_INIT=_F(TABL_USURE=str(path)), **dict(
        PUIS_USURE=None, RESU_GENE=history(), MOBILE=None, COEF_INST=3600.0,
        SECTEUR=(_F(ANGL_INIT=-180.0, ANGL_FIN=0.0, COEF_USUR_MOBILE=1e-13),
                 _F(ANGL_INIT=0.0, ANGL_FIN=180.0, COEF_USUR_MOBILE=3e-13,
                    COEF_USUR_OBST=1e-14))))
    b = from_aster_names(a)
    assert b["instant"].tolist() == [1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0]
    # default Code_Aster precision (%12.5E): values to 5 significant digits
    short = read_aster_table(write_aster_table(ours, tmp_path / "short.tab", format=fmt))
    np.testing.assert_allclose(short["V_USUR_TUBE_CUMU"], ours["V_USUR_TUBE_CUMU"], rtol=1e-5)


def test_wear_table_accepts_code_aster_file_path(tmp_path):
    t = wear_table(0.012, contact_type="TUBE_BAV", dimensions={"mobile_radius": 0.0111,
                                                               "obstacle_width": 0.0127},
                   coefficients={"COEF_USURE": 1.2e-13}, instants=[1.0], time_scale=YEAR,
                   initial_state=FIXTURES / "post_usure_tableau.txt")
    np.testing.assert_allclose(t["volume_mobile"].iloc[-1], 9.08237e-08 + 1.2e-13 * 0.012 * YEAR,
                               rtol=1e-14)


def test_mater_usure_and_usure_obst_from_the_database():
    """R7.20.01 §3: GRAPPE_ALESAGE A304L/A304L Archard 2.6e-15 (rod) and 3.7e-15 (guide)."""
    kw = dict(CONTACT="GRAPPE_ALESAGE", RAYON_MOBILE=4.84e-3, RAYON_OBST=5.25e-3,
              LARGEUR_OBST=0.02, COEF_INST=3600.0, MOBILE=None)
    t = call(MATER_USURE="A304L/A304L", USURE_OBST="OUI", **kw)
    np.testing.assert_allclose(t["V_USUR_TUBE"], 2.6e-15 * 0.012 * 3600.0 * np.array([1, 2]),
                               rtol=1e-15)
    np.testing.assert_allclose(t["V_USUR_OBST"], 3.7e-15 * 0.012 * 3600.0 * np.array([1, 2]),
                               rtol=1e-15)
    assert "P_USUR_OBST" in t.columns
    t2 = call(MATER_USURE=("A304L", "A304L"), **kw)
    assert "P_USUR_OBST" not in t2.columns and t2["V_USUR_OBST"].eq(0.0).all()
    with pytest.raises(KeywordError, match="USURE_OBST='NON' is not allowed"):
        call(MATER_USURE="A304L/A304L", USURE_OBST="NON", **kw)
    with pytest.raises(KeywordError, match="MATER_USURE must name the mobile and obstacle"):
        call(MATER_USURE="A304L", **kw)


def test_kwu_epri_keywords_reach_the_class_statistics():
    """K = COEF_USURE·w (w_r = 1, theory §4), w from kwu_epri_statistics with the same
    FNOR_MAXI, VTAN_MAXI, COEF_K, COEF_C (an independent call of the laws module)."""
    from fretwear.laws import kwu_epri_statistics

    h = history()
    t = call(PUIS_USURE=None, RESU_GENE=h, LOI_USURE="KWU_EPRI", COEF_INST=3600.0,
             MOBILE=_F(COEF_USURE=1e-13, COEF_K=4.0, COEF_C=12.0), FNOR_MAXI=40.0,
             VTAN_MAXI=0.1, INST=(1.0,))
    w = kwu_epri_statistics(h, force_max=40.0, speed_max=0.1, k=4.0, c=12.0).intensity
    w_default = kwu_epri_statistics(h).intensity
    assert w != pytest.approx(w_default)  # the keywords matter
    np.testing.assert_allclose(t["V_USUR_TUBE"], 1e-13 * w * 1.0 * 3600.0, rtol=1e-12)
    with pytest.raises(KeywordError, match="needs the contact history"):
        call(LOI_USURE="KWU_EPRI")


# history() is sampled every 1 s: as a file its step is flagged (likely ms), irrelevant here
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_resu_gene_as_a_file(tmp_path):
    """A history file gives the same table as the history itself (P = 1 W, theory §2)."""
    from fretwear.io import write_history

    path = tmp_path / "shock.csv"
    write_history(history(), path)
    a = call(PUIS_USURE=None, RESU_GENE=str(path), NOEUD="N12", COEF_INST=3600.0)
    b = call(PUIS_USURE=None, RESU_GENE=history(), COEF_INST=3600.0)
    pd.testing.assert_frame_equal(a, b)
    np.testing.assert_allclose(a["PUIS_USUR_GLOBAL"], 1.0, rtol=1e-12)
