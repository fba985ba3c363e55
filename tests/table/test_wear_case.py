"""fretwear.table.WearCase: one validated, immutable description of a wear computation.

The tables are checked bit for bit against :func:`fretwear.table.wear_table` on every shipped
example (one per contact type: Archard, EDF_MZ, KWU_EPRI, a database pair, sectors, a restart
from a Code_Aster table, a tube replacement), whose values are themselves pinned by the
snapshots of tests/workflows; the Archard volumes of the hand-made cases are V = K·P·t
(docs/theory.md §4).
"""

from __future__ import annotations

import dataclasses
import json
import pickle
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import fretwear
from fretwear import ContactHistory
from fretwear.errors import InputError, KeywordError, LawWarning
from fretwear.io import read_history
from fretwear.table import Coefficient, WearCase, wear_table, wear_table_from_case
from fretwear.workflows.case_files import case_arguments, history_options, load_case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CONTACT_EXAMPLES = ("tube_bav", "tube_tube", "tube_alesage", "tube_3_enco", "tube_4_enco",
                    "grappe_alesage", "grappe_1_enco", "grappe_2_enco")
BAV = {"mobile_radius": 0.0111, "obstacle_width": 0.0127}
P = 0.012  # [W]
YEAR = 31_536_000.0


def base(**changes):
    kw = dict(contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0, 2.0],
              coefficients={"COEF_USURE": 1.2e-13}, time_scale=YEAR)
    kw.update(changes)
    return kw


def sector_history(n=4001, seed=3):
    """An impact-sliding history turning round the contact (every sector is visited)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 8.0, n)
    angle = 2 * np.pi * 0.37 * t
    return ContactHistory(time=t, normal_force=np.abs(20 + 5 * rng.standard_normal(n)),
                          vt1=0.05 * np.sin(7 * t), vt2=0.05 * np.cos(5 * t),
                          dy=1e-4 * np.cos(angle), dz=1e-4 * np.sin(angle))


def example(name):
    """(wear_table keywords, source) of a shipped example case."""
    case = load_case(EXAMPLES / f"{name}.toml")
    args = case_arguments(case)
    spec = case.get("history", {})
    if "file" in spec:
        source = read_history(Path(case["_directory"]) / spec["file"], **history_options(spec))
    else:
        source = float(case["power"]["value_W"])
    return args, source


def assert_same_table(a: pd.DataFrame, b: pd.DataFrame):
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    for column in a.columns:  # bit for bit, NaN at the same places
        assert np.array_equal(a[column].to_numpy(), b[column].to_numpy(), equal_nan=True)
    assert a.attrs == b.attrs


# --------------------------------------------------------------------------- equal tables
@pytest.mark.filterwarnings("ignore::fretwear.errors.FretwearWarning")
@pytest.mark.parametrize("name", CONTACT_EXAMPLES)
def test_wear_table_is_wear_table_from_case_on_every_contact_type(name):
    args, source = example(name)
    direct = wear_table(source, **args)
    case = WearCase.from_keywords(**args)
    assert_same_table(wear_table_from_case(case, source), direct)
    assert direct.attrs["case"] == case.to_dict()


@pytest.mark.filterwarnings("ignore::fretwear.errors.FretwearWarning")
@pytest.mark.parametrize("name", CONTACT_EXAMPLES)
def test_json_and_pickle_round_trips_give_equal_cases_and_identical_tables(name):
    args, source = example(name)
    case = WearCase.from_keywords(**args)
    table = wear_table_from_case(case, source)
    text = json.dumps(case.to_dict(), allow_nan=False)  # strict JSON: a worker elsewhere reads it
    for copy in (WearCase.from_dict(json.loads(text)), WearCase.from_json(case.to_json()),
                 pickle.loads(pickle.dumps(case))):
        assert copy == case and hash(copy) == hash(case)
        assert_same_table(wear_table_from_case(copy, source), table)


def test_round_trip_of_a_sector_restart_keeps_the_initial_rows_exactly():
    """The restart rows (an int sector column, NaN obstacle sector depths of TUBE_BAV) travel
    through JSON: the continued table is the same bit for bit."""
    h = sector_history()
    kw = base(sectors=4, obstacle_coefficients={"COEF_USURE": 3e-14}, time_scale=3600.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # TUBE_BAV: no obstacle sector depth (RangeWarning)
        first = wear_table(h, **kw)
        case = WearCase.from_keywords(**{**kw, "instants": [1.0, 3.0]}, initial_state=first)
        again = WearCase.from_json(case.to_json())
        a, b = wear_table_from_case(case, h), wear_table_from_case(again, h)
    assert first["depth_obstacle_sector"].isna().any()
    assert case.restart.table.rows["sector"].dtype == again.restart.table.rows["sector"].dtype
    assert again == case
    assert_same_table(a, b)
    assert a["instant"].tolist()[-4:] == [5.0] * 4  # origin 2 + 3


def test_a_case_is_frozen():
    case = WearCase.from_keywords(**base())
    with pytest.raises(dataclasses.FrozenInstanceError):
        case.law = "EDF_MZ"
    with pytest.raises(TypeError):
        case.dimensions["mobile_radius"] = 1.0
    with pytest.raises(TypeError):
        case.coefficients["coefficient"] = Coefficient(1.0, "user")
    changed = case.replace(instants=(1.0, 5.0))
    assert changed.instants == (1.0, 5.0) and case.instants == (1.0, 2.0)


def test_from_dict_names_unknown_keys():
    data = WearCase.from_keywords(**base()).to_dict()
    data["instant"] = [1.0]
    with pytest.raises(KeywordError, match=r"unknown wear-case key\(s\) \['instant'\]"):
        WearCase.from_dict(data)


def test_from_keywords_takes_exactly_the_keywords_of_wear_table():
    # both read the one keyword table (tests/table/test_keywords.py checks the docstrings)
    kw = {"contact_type": "TUBE_ALESAGE", "instants": [1.0], "dimensions": BAV,
          "coefficients": {"COEF_USURE": 1e-14}, "wall_thickness": 1e-3}
    assert wear_table_from_case(WearCase.from_keywords(**kw), 0.01).equals(wear_table(0.01, **kw))


def test_fretwear_exports_the_case():
    assert fretwear.WearCase is WearCase
    assert fretwear.wear_table_from_case is wear_table_from_case


# --------------------------------------------------------------------------- sources
def test_coefficient_sources_user_default_database_history():
    """EDF_MZ with A given: A is the user's, b, n, S the law's defaults; a database pair names
    its row; KWU-EPRI's intensity comes from the history's class statistics."""
    edf = WearCase.from_keywords(**base(law="EDF_MZ", coefficients={"COEF_USURE": 2e-15}))
    sources = edf.coefficient_sources
    assert sources["mobile.rate_coefficient"] == "user"
    assert {sources[f"mobile.{k}"] for k in ("power_exponent", "decay_constant",
                                              "asymptotic_rate")} == {"default"}
    db = WearCase.from_keywords(**base(coefficients=None, materials=("I600", "A405")))
    assert db.coefficients["coefficient"].value == 6.2e-14  # R7.20.01 §3 TUBE_BAV I600/A405
    assert db.coefficients["coefficient"].source.startswith("database I600/A405 (TUBE_BAV, "
                                                            "ARCHARD): ")
    assert "built-in" in db.coefficient_sources["mobile.coefficient"]
    t = wear_table_from_case(db, P)
    assert t.attrs["coefficient_sources"] == db.coefficient_sources
    kwu = WearCase.from_keywords(**base(law="KWU_EPRI", time_scale=3600.0))
    table = wear_table_from_case(kwu, sector_history())
    assert table.attrs["coefficient_sources"]["mobile.intensity"].startswith("history")
    assert table.attrs["coefficient_sources"]["mobile.reference_coefficient"] == "user"


def test_law_warnings_name_the_body():
    """EDF_MZ with S > A·P^b warns (theory §4) for each body that wears, naming it."""
    kw = base(law="EDF_MZ", coefficients={"COEF_USURE": 1e-20, "COEF_B": 1.0},
              obstacle_coefficients={"COEF_USURE": 1e-20, "COEF_B": 1.0})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        wear_table(P, **kw)
    messages = [str(w.message) for w in caught if issubclass(w.category, LawWarning)]
    assert any(m.startswith("mobile: ") for m in messages)
    assert any(m.startswith("obstacle: ") for m in messages)


def test_attrs_carry_the_case_and_the_wall():
    t = wear_table(P, **base(wall_thickness=1e-2, depth_limit=0.5, name="N12",
                             time_unit="year"))
    assert t.attrs["wall_thickness"] == 1e-2 and t.attrs["depth_limit"] == 0.5
    assert t.attrs["title"] == "N12" and t.attrs["time_unit"] == "year"
    np.testing.assert_allclose(t["volume_mobile"], 1.2e-13 * P * YEAR * np.array([1.0, 2.0]),
                               rtol=1e-15)
    assert WearCase.from_dict(t.attrs["case"]) == WearCase.from_keywords(
        **base(wall_thickness=1e-2, depth_limit=0.5, name="N12", time_unit="year"))


# --------------------------------------------------------------------------- validation
@pytest.mark.parametrize("changes, error, match", [
    (dict(law="EDF_MZ", sectors=4),
     KeywordError, r"SECTEUR belongs to LOI_USURE='ARCHARD'.*use law='ARCHARD' or remove"),
    (dict(force_max=40.0),
     KeywordError, r"FNOR_MAXI belongs to LOI_USURE='KWU_EPRI', not ARCHARD: remove force_max"),
    (dict(speed_max=0.1),
     KeywordError, r"VTAN_MAXI belongs to LOI_USURE='KWU_EPRI'.*remove speed_max"),
    (dict(coefficient_files=[__file__]), KeywordError, "coefficient_files .* give materials too"),
    (dict(obstacle_wear=True), KeywordError, r"obstacle_wear \(USURE_OBST\).*give materials"),
    (dict(materials=("I600", "A405")), KeywordError, "coefficients .* or materials .* not both"),
    (dict(coefficients=None, materials=("I600",)),
     KeywordError, r"materials \(MATER_USURE\) must be a \(mobile, obstacle\) pair"),
    (dict(coefficients=None, materials=("I600", "A405"),
          obstacle_coefficients={"COEF_USURE": 1e-14}),
     KeywordError, "excludes obstacle_coefficients .* obstacle_wear"),
    (dict(initial_instant=1.0), KeywordError, r"initial_instant .* needs an initial_state"),
    (dict(sector_coefficients=[(1e-13, None)]),
     KeywordError, r"sector_coefficients .* need sectors: give sectors="),
    (dict(sectors=4, sector_coefficients=[(1e-13, None)] * 3),
     InputError, r"3 entries for 4 sectors"),
    (dict(sectors=4, coefficients=None),
     KeywordError, r"give sector_coefficients .* or coefficients"),
    (dict(sectors=[-180, 0, 90]), InputError, "180"),
    (dict(law="COULOMB"), KeywordError, "unknown wear law 'COULOMB'"),
    (dict(time_scale=0.0), InputError, r"time_scale \(COEF_INST\) must be > 0"),
    (dict(instants=[2.0, 1.0]), InputError, "strictly increasing"),
    (dict(blocks=0), InputError, r"blocks \(NB_BLOC\) must be a whole number >= 1"),
    (dict(t_start=2.0, t_end=1.0), InputError, r"t_end \(INST_FIN\) = 1 s must be after"),
    (dict(wall_thickness=-1e-3), InputError, r"wall_thickness must be > 0 \[m\]"),
    (dict(depth_limit=40.0), InputError, r"depth_limit is a fraction .* got 40"),
    (dict(contact_type="TUBE"), KeywordError, "TUBE"),
    (dict(coefficients={"COEF_USRE": 1e-13}), KeywordError, "mobile coefficients: .*COEF_USRE"),
])
def test_validation_errors_name_the_keyword_and_the_fix(changes, error, match):
    with pytest.raises(error, match=match):
        WearCase.from_keywords(**base(**changes))


def test_coefficient_files_go_with_materials(tmp_path):
    """A user row overrides the built-in one (R7.20.01 §3 TUBE_BAV I600/A405: 6.2e-14 Pa⁻¹)."""
    mine = tmp_path / "mine.csv"
    mine.write_text("contact_type,mobile_material,obstacle_material,law,parameter,value,unit\n"
                    "TUBE_BAV,I600,A405,ARCHARD,COEF_USURE,3e-14,1/Pa\n", encoding="utf-8")
    case = WearCase.from_keywords(**base(coefficients=None, materials=("I600", "A405"),
                                         coefficient_files=[mine]))
    assert case.coefficients["coefficient"].value == 3e-14
    assert str(mine) in case.coefficients["coefficient"].source
    assert case.coefficient_files == (str(mine),)
    with pytest.raises(KeywordError, match="coefficient_files .* give materials too"):
        WearCase.from_keywords(**base(coefficient_files=[mine]))


def test_rules_that_need_the_source_are_checked_by_the_builder():
    with pytest.raises(InputError, match="sectors need a contact history"):
        wear_table_from_case(WearCase.from_keywords(**base(sectors=4)), P)
    with pytest.raises(KeywordError, match="KWU_EPRI law needs the contact history"):
        wear_table_from_case(WearCase.from_keywords(**base(law="KWU_EPRI")), P)
    with pytest.raises(InputError, match="case must be a WearCase"):
        wear_table_from_case(base(), P)


def test_restart_rules_are_checked_with_the_case():
    first = wear_table(P, **base())
    with pytest.raises(InputError, match="tube_replacement.*before the origin 2"):
        WearCase.from_keywords(**base(initial_state=first, tube_replacement=1.0))
    with pytest.raises(InputError, match="has 0 sectors and this run has 4"):
        WearCase.from_keywords(**base(initial_state=first, sectors=4))
    case = WearCase.from_keywords(**base(initial_state=first))
    assert case.origin == 2.0 and case.restart.source == "(DataFrame)"


def test_sectors_need_a_contact_type_with_an_obstacle_width():
    """Sector depths fill the sector's arc over the obstacle's width l (docs/theory.md §3).
    TUBE_TUBE, two crossed tubes, has none (SPEC §6 gives its depth from R_m and the crossing
    angle alone): asked with sectors, one error says so, and no warning says first that the
    width given for the sectors is unused (found by a user's trial: the warning, then an error
    asking for the width just given). Every type with a width still takes sectors."""
    from fretwear.geometry import CONTACT_TYPES

    dimensions = {"mobile_radius": 9.525e-3, "obstacle_radius": 9.525e-3, "tilt_angle": 45.0,
                  "obstacle_width": 12.7e-3}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning would fail the test
        with pytest.raises(KeywordError, match=r"TUBE_TUBE \(CONTACT\).*LARGEUR_OBST.*remove "
                                               r"sectors"):
            WearCase.from_keywords(contact_type="TUBE_TUBE", dimensions=dimensions, law="ARCHARD",
                     coefficients={"COEF_USURE": 1e-17}, sectors=4, instants=[1.0])
    refused = []
    for name, cls in CONTACT_TYPES.items():
        dims = {**cls.example, "obstacle_width": 12.7e-3}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                WearCase.from_keywords(contact_type=name, dimensions=dims, law="ARCHARD",
                         coefficients={"COEF_USURE": 1e-17}, sectors=4, instants=[1.0])
        except KeywordError:
            refused.append(name)
    assert refused == ["TUBE_TUBE"]
    # without sectors, TUBE_TUBE is as before: the width is unused, said by a warning
    with pytest.warns(fretwear.errors.UnusedKeywordWarning, match="obstacle_width"):
        WearCase.from_keywords(contact_type="TUBE_TUBE", dimensions=dimensions, law="ARCHARD",
                 coefficients={"COEF_USURE": 1e-17}, instants=[1.0])


def test_sector_edges_made_once_per_case_read_only_and_remade_on_replace():
    """Every table of a case reads its sector edges [deg] (issue 28: validation once, where
    the case is built): the same read-only array each time; a replaced case has its own; a
    pickled case (a bundle's worker) carries none and makes them again."""
    case = WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0], sectors=4,
                                  dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
                                  coefficients={"COEF_USURE": 1e-14})
    edges = case.sector_edges
    assert edges is case.sector_edges and edges.tolist() == [-180.0, -90.0, 0.0, 90.0, 180.0]
    with pytest.raises(ValueError, match="read-only"):
        edges[0] = 0.0
    assert case.replace(sectors=2).sector_edges.tolist() == [-180.0, 0.0, 180.0]
    assert "sector_edges" not in pickle.loads(pickle.dumps(case)).__dict__
    assert case.replace(sectors=None).sector_edges is None
