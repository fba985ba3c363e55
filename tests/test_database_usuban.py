"""Code_Aster's own database values (issue 29, point 7): ``usuban.F90``, the routine POST_USURE
reads MATER_USURE from, has KWU_EPRI and EDF_MZ coefficients for TUBE_BAV I600/I600 that
R7.20.01's tables lack. The values below are typed from usuban.F90 (Code_Aster 2012,
bibfor/prepost), independently of the CSV."""

from __future__ import annotations

import math

import pytest

from fretwear.database import load_database, lookup

#: usuban.F90, TUBE_BAV, MATER_USURE='I600_I600', ISUPP = 1 (the tube): PARA(1..5) of KWU_EPRI
#: (COEF_USURE, the two class weights, CST_K, CST_C) and PARA(1..4) of EDF_MZ (COEF_USURE,
#: SEUIL, EXPOSANT_USURE, TAUX_RALENTISSEMENT).
KWU = {"reference_coefficient": 1.4e-15, "impact_factor": 1.4e-15, "sliding_factor": 1.4e-15,
       "k": 5.0, "c": 10.0}
MZ = {"rate_coefficient": 1e-13, "asymptotic_rate": 1.14e-16, "power_exponent": 1.2,
      "decay_constant": 2.44e-8}


def test_the_tube_bav_i600_pair_has_usubans_kwu_and_edf_mz_values():
    kwu = lookup("TUBE_BAV", "I600", "I600", "KWU_EPRI")
    assert kwu.mobile == KWU and kwu.obstacle is None
    mz = lookup("TUBE_BAV", "I600", "I600", "EDF_MZ")
    assert mz.mobile == MZ and mz.obstacle is None
    for found in (kwu, mz):
        assert all("usuban.F90" in s for s in found.sources.values()), found.sources


def test_usuban_rows_are_the_only_rows_not_from_the_manual():
    db = load_database()
    usuban = db[db["source"].str.contains("usuban.F90")]
    assert len(usuban) == 9
    assert set(usuban["law"]) == {"KWU_EPRI", "EDF_MZ"}
    assert (usuban["contact_type"] == "TUBE_BAV").all()


def test_a_pasted_post_usure_with_edf_mz_and_i600_i600_runs():
    """LOI_USURE='EDF_MZ', MATER_USURE='I600_I600' on TUBE_BAV: failed (no pair) before. The
    volume is EDF-MZ's closed form V = ((A P^b - S)/n)(1 - exp(-n t)) + S t (theory §4)."""
    from fretwear.workflows.aster import POST_USURE

    power, t = 0.01, 3.0e7
    table = POST_USURE(PUIS_USURE=power, LOI_USURE="EDF_MZ", MATER_USURE="I600_I600",
                       CONTACT="TUBE_BAV", RAYON_MOBILE=9.525e-3, LARGEUR_OBST=12.7e-3,
                       INST=(t,))
    a, s, b, n = (MZ[k] for k in ("rate_coefficient", "asymptotic_rate", "power_exponent",
                                  "decay_constant"))
    expected = (a * power**b - s) / n * (1.0 - math.exp(-n * t)) + s * t
    assert table["V_USUR_TUBE"].iloc[0] == pytest.approx(expected, rel=1e-12, abs=0)


#: usuban.F90's ARCHARD tube coefficients (ISUPP = 1; the obstacle's box is empty there too),
#: typed from the Fortran: Code_Aster's MATER_USURE code -> value [Pa⁻¹].
USUBAN_TUBES = {
    "TUBE_BAV": {"I600_I600": 1.2e-13, "I600TT_I600": 4.5e-14, "I600TT_I600TT": 1.4e-15,
                 "I600_I600CR": 7.2e-14, "I600TT_I600CR": 9.1e-16, "I690TT_I600CR": 1.2e-15,
                 "I600_Z10C13": 9.9e-14, "I600_A405": 6.2e-14, "I690_A405": 4.1e-16,
                 "I600TT_Z6C13": 9.2e-15, "I600_Z6C13": 7.1e-15, "I690_Z6C13": 7.7e-15,
                 "I600_A347": 1.0e-13},
    "TUBE_ALESAGE": {"I690_Z10C13": 6.0e-17, "I600_I600": 1.6e-13, "I690_I600": 5.2e-14,
                     "I600_I600CR": 2.2e-15, "I690_I600CR": 4.4e-15},
    "TUBE_4_ENCO": {"I600_Z10C13": 2.4e-16, "I690_Z10C13": 8.2e-17, "I600_A405": 6.5e-14,
                    "I600TT_A405": 1.4e-15, "I690_A405": 7.8e-15},
    "TUBE_3_ENCO": {"I600_Z10C13": 2.5e-16, "I690_Z10C13": 2.4e-16},
    "TUBE_TUBE": {"I600_I600": 1.8e-13, "I690_I690": 1.0e-12},
}
#: usuban.F90's ARCHARD GRAPPE coefficients, (mobile, obstacle) [Pa⁻¹].
USUBAN_GRAPPES = {
    "GRAPPE_ALESAGE": {"A304L_A304L": (10e-15, 15e-15), "A316L_A304L": (10e-15, 5e-15),
                       "NITRURE_A304L": (0.1e-15, 70e-15), "CHROME_A304L": (0.1e-15, 50e-15)},
    "GRAPPE_1_ENCO": {"A304L_A304L": (20e-15, 20e-15), "A316L_A304L": (30e-15, 20e-15)},
}


def test_docs_laws_list_of_the_differences_with_usuban_holds():
    """docs/laws.md: every tube pair both databases share has the same value (usuban's
    I690_Z6C13 is R7.20.01's I690TT/Z6C13), every GRAPPE pair they share differs (R7.20.01's
    values kept, theory §5)."""
    import warnings

    from fretwear.workflows.aster import materials_of

    def pair(code):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return materials_of(code)

    for contact, values in USUBAN_TUBES.items():
        for code, value in values.items():
            got = lookup(contact, *pair(code), "ARCHARD")
            assert got.mobile["coefficient"] == pytest.approx(value, rel=1e-12, abs=0), \
                (contact, code)
    for contact, values in USUBAN_GRAPPES.items():
        for code, (mobile, obstacle) in values.items():
            got = lookup(contact, *pair(code), "ARCHARD", obstacle=True)
            differ = (got.mobile["coefficient"] != pytest.approx(mobile, rel=1e-12, abs=0),
                      got.obstacle["coefficient"] != pytest.approx(obstacle, rel=1e-12, abs=0))
            # nitrided and chromium-plated rods: the same rod value, another bore value
            assert differ == ((code not in ("NITRURE_A304L", "CHROME_A304L")), True), code
