"""A contact's wear case (fretwear.bundle.cases): which coefficients a row's overrides give
against a base case that takes them from the database, and a base case that fails for every
contact.

References: the example manifest of docs/bundle.md run on the shipped example bundle
(examples/bundle) against the single-contact wear table of the same history with the row's
coefficient written in a case file (the case-file layer, an independent path); Archard's law
V = K·P·t (docs/theory.md §4) for given powers.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import pandas as pd
import pytest
from bundle_helpers import assert_identical, reference, rows_of

from fretwear.bundle import run_bundle
from fretwear.bundle.cases import BaseCaseError
from fretwear.cli import main
from fretwear.errors import KeywordError, PerforationWarning

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "bundle"
BASE = (EXAMPLE / "bundle.toml").read_text()
MATERIALS = 'materials = ["I690", "A405"]'
YEAR = 31536000.0  # [s], the case files' "year" (365 days)


def _docs_manifest() -> str:
    """The TOML manifest example of docs/bundle.md (the block starting '# manifest.toml')."""
    text = (ROOT / "docs" / "bundle.md").read_text(encoding="utf-8")
    blocks = re.findall(r"^```toml\n(# manifest\.toml\n.*?)^```", text, re.S | re.M)
    assert len(blocks) == 1
    return blocks[0]


def _example_dir(tmp_path: Path) -> Path:
    """A folder beside the example's histories (a link to them)."""
    (tmp_path / "tubes").symlink_to(EXAMPLE / "tubes", target_is_directory=True)
    return tmp_path


def _case_with(tmp_path: Path, name: str, coefficient: float, width: str = "") -> Path:
    """The example base case with a given coefficient instead of the database pair (and
    another bar width)."""
    assert BASE.count(MATERIALS) == 1
    text = BASE.replace(MATERIALS, f"mobile = {{ COEF_USURE = {coefficient!r} }}")
    text = text.replace("[geometry]\n", "[geometry]\nwall_thickness_m = 1.09e-3\n")
    if width:
        assert text.count("obstacle_width_m = 12.7e-3") == 1
        text = text.replace("obstacle_width_m = 12.7e-3", f"obstacle_width_m = {width}")
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_docs_toml_example_runs_on_the_example_bundle(tmp_path):
    folder = _example_dir(tmp_path)
    (folder / "manifest.toml").write_text(_docs_manifest())
    result = run_bundle(folder / "manifest.toml", EXAMPLE / "bundle.toml", scheduler="serial")
    assert result.errors.empty, result.errors.to_dict("records")
    expected = {"R4C3-AVB2": (2.0e-15, "10e-3"), "R4C3-AVB1": (4.0e-15, "")}
    assert sorted(result.contacts["contact"]) == sorted(expected)
    for contact, (k, extra) in expected.items():
        history = EXAMPLE / "tubes" / (contact.replace("-", "/") + ".parquet")
        case = _case_with(tmp_path, f"{contact}.toml", k, extra)
        rows = rows_of(result, contact)
        with warnings.catch_warnings():  # 5-10 times the database's K: may wear through
            warnings.simplefilter("ignore", PerforationWarning)
            assert_identical(rows, reference(history, case))
        # warned exactly when the table's depth reaches the wall by the last instant
        through = bool((rows["depth_mobile"] >= 1.09e-3).any())
        assert any("worn through its wall" in m for m in
                   result.warnings[result.warnings["contact"] == contact]["message"]) == through
        # Archard (theory §4): the mobile's volume is K·P·t with the row's K
        last = rows.iloc[-1]
        assert last["volume_mobile"] == pytest.approx(k * last["power"] * 40 * YEAR, rel=1e-12)
    # the base case's database coefficient (4.1e-16) was replaced, not used
    other = run_bundle(pd.DataFrame({"contact": ["x"], "history": [str(EXAMPLE / "tubes" /
                                                                        "R4C3/AVB1.parquet")]}),
                       EXAMPLE / "bundle.toml", scheduler="serial")
    a, b = rows_of(result, "R4C3-AVB1").iloc[-1], rows_of(other, "x").iloc[-1]
    assert a["power"] == b["power"]
    assert a["volume_mobile"] / b["volume_mobile"] == pytest.approx(4.0e-15 / 4.1e-16)


def test_csv_columns_give_the_coefficient_instead_of_the_materials(tmp_path):
    folder = _example_dir(tmp_path)
    frame = pd.DataFrame({"contact": ["a", "b", "c"],
                          "history": [f"tubes/R2C{i}/AVB1.parquet" for i in (1, 2, 3)],
                          "wall_thickness_m": [1.09e-3] * 3,
                          "law.mobile.COEF_USURE": [4.0e-15, None, None],
                          "law.materials": [None, "[]", None],
                          "law.mobile": [None, "{ COEF_USURE = 3.0e-15 }", None]})
    frame.to_csv(folder / "manifest.csv", index=False)
    result = run_bundle(folder / "manifest.csv", EXAMPLE / "bundle.toml", scheduler="serial")
    assert result.errors.empty, result.errors.to_dict("records")
    for contact, column, k in (("a", 1, 4.0e-15), ("b", 2, 3.0e-15)):
        case = _case_with(tmp_path, f"{contact}.toml", k)
        assert_identical(rows_of(result, contact),
                         reference(EXAMPLE / "tubes" / f"R2C{column}/AVB1.parquet", case))
    # the row without overrides keeps the base case's database pair
    case = tmp_path / "c.toml"
    case.write_text(BASE.replace("[geometry]\n", "[geometry]\nwall_thickness_m = 1.09e-3\n"))
    assert_identical(rows_of(result, "c"),
                     reference(EXAMPLE / "tubes" / "R2C3/AVB1.parquet", case))


POWERED = """\
[law]
{law}
[geometry]
contact_type = "GRAPPE_ALESAGE"
mobile_radius_m = 5e-3
obstacle_radius_m = 5.2e-3
obstacle_width_m = 1e-2
[time]
instants = [1]
unit = "year"
"""


def _given_power(tmp_path, law: str, **columns):
    """One contact of a given power 0.01 W, its row's columns, against a base case."""
    case = tmp_path / "base.toml"
    case.write_text(POWERED.format(law=law))
    frame = pd.DataFrame({"contact": ["x"], "power.value_W": [0.01],
                          **{k: [v] for k, v in columns.items()}})
    return run_bundle(frame, case, scheduler="serial")


def _volumes(result) -> tuple[float, float]:
    assert result.errors.empty, result.errors.to_dict("records")
    row = result.table.iloc[-1]
    return row["volume_mobile"], row["volume_obstacle"]


def test_what_a_row_replaces_of_the_base_coefficient_source(tmp_path):
    database = 'materials = ["A304L", "A304L"]\nobstacle_wear = true'  # 2.6e-15, 3.7e-15
    ptime = 0.01 * YEAR
    # base: the database pair for both bodies (GRAPPE_ALESAGE A304L/A304L, the shipped table)
    assert _volumes(_given_power(tmp_path, database)) == pytest.approx((2.6e-15 * ptime,
                                                                        3.7e-15 * ptime))
    # the row's coefficients for both bodies
    got = _given_power(tmp_path, database, **{"law.mobile.COEF_USURE": 1e-15,
                                              "law.obstacle.COEF_USURE": 2e-15})
    assert _volumes(got) == pytest.approx((1e-15 * ptime, 2e-15 * ptime))
    # the mobile's only, the obstacle said not to wear
    got = _given_power(tmp_path, database, **{"law.mobile.COEF_USURE": 1e-15,
                                              "law.obstacle_wear": False})
    assert _volumes(got) == pytest.approx((1e-15 * ptime, 0.0))
    # the mobile's only: the obstacle's database coefficient would be lost silently
    got = _given_power(tmp_path, database, **{"law.mobile.COEF_USURE": 1e-15})
    assert got.errors["error"].tolist() == ["KeywordError"]
    assert "give law.obstacle too, or law.obstacle_wear = false" in got.errors["message"][0]
    # the obstacle's only: the mobile's database coefficient would be lost
    got = _given_power(tmp_path, database, **{"law.obstacle.COEF_USURE": 2e-15})
    assert "give law.mobile too" in got.errors["message"][0]
    # both sources in one row: the case layer's refusal
    got = _given_power(tmp_path, database, **{"law.mobile.COEF_USURE": 1e-15,
                                              "law.materials": '["A304L", "A304L"]'})
    assert "not both" in got.errors["message"][0]

    given = "mobile = { COEF_USURE = 1e-15 }\nobstacle = { COEF_USURE = 2e-15 }"
    # materials instead of the base's coefficients: the row says whether the obstacle wears
    got = _given_power(tmp_path, given, **{"law.materials": '["A304L", "A304L"]',
                                           "law.obstacle_wear": True})
    assert _volumes(got) == pytest.approx((2.6e-15 * ptime, 3.7e-15 * ptime))
    got = _given_power(tmp_path, given, **{"law.materials": '["A304L", "A304L"]'})
    assert "say law.obstacle_wear = true" in got.errors["message"][0]
    # without an obstacle coefficient in the base, materials alone replace the mobile's
    got = _given_power(tmp_path, "mobile = { COEF_USURE = 1e-15 }",
                       **{"law.materials": '["A304L", "A304L"]'})
    assert _volumes(got) == pytest.approx((2.6e-15 * ptime, 0.0))


def test_a_bad_cell_is_named_as_the_manifest_wrote_it(tmp_path):
    result = _given_power(tmp_path, "mobile = { COEF_USURE = 1e-15 }", mobile_radius_m="abc")
    message = result.errors["message"][0]
    assert "column mobile_radius_m = 'abc'" in message, message
    toml = tmp_path / "m.toml"
    toml.write_text('[[contacts]]\ncontact = "x"\npower.value_W = 0.01\n'
                    'geometry.mobile_radius_m = "abc"\n')
    result = run_bundle(toml, tmp_path / "base.toml", scheduler="serial")
    assert "key geometry.mobile_radius_m = 'abc'" in result.errors["message"][0]


def test_a_base_case_failing_for_every_contact_stops_before_any_work(tmp_path):
    broken = POWERED.format(law="mobile = { COEF_USURE = 1e-15 }").replace(
        'contact_type = "GRAPPE_ALESAGE"\n', "")
    case = tmp_path / "base.toml"
    case.write_text(broken)
    frame = pd.DataFrame({"contact": [f"c{i}" for i in range(50)], "power.value_W": 0.01,
                          "mobile_radius_m": [5e-3 + 1e-5 * (i % 3) for i in range(50)]})
    with pytest.raises(BaseCaseError, match=r"base case fails for every contact: .*"
                                            r"\[geometry\] contact_type is required"):
        run_bundle(frame, case, scheduler="serial", output=tmp_path / "out")
    assert not (tmp_path / "out").exists()  # nothing computed, nothing left (an empty parts/)
    # a row that supplies the key runs; the others fail each on its own
    frame["contact_type"] = [None] * 49 + ["GRAPPE_ALESAGE"]
    result = run_bundle(frame, case, scheduler="serial")
    assert result.stats["done"] == 1 and len(result.errors) == 49
    # a row failing for its own reason (a bad cell) is not the base case's error: no stop
    frame = pd.DataFrame({"contact": ["a", "b"], "power.value_W": 0.01,
                          "mobile_radius_m": [5e-3, "abc"]})
    result = run_bundle(frame, case, scheduler="serial")
    assert len(result.errors) == 2
    # a base case that works with no row's overrides but fails with a row's is not stopped
    case.write_text(POWERED.format(law="mobile = { COEF_USURE = 1e-15 }"))
    frame = pd.DataFrame({"contact": ["a"], "power.value_W": 0.01, "blocks": ["two"]})
    assert run_bundle(frame, case, scheduler="serial").errors["error"].tolist() == [
        "KeywordError"]


def test_the_command_says_the_base_case_error_once_with_status_2(tmp_path, capsys):
    case = tmp_path / "base.toml"
    case.write_text(BASE.replace('contact_type = "TUBE_BAV"\n', ""))
    code = main(["bundle", str(EXAMPLE / "manifest.csv"), "--case", str(case), "-q",
                 "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.count("contact_type is required") == 1, err


def test_a_units_key_typo_is_named_with_the_closest_key(tmp_path):
    case = tmp_path / "base.toml"
    case.write_text(BASE + '\n[history]\nunits = { lenght = "mm" }\n')
    with pytest.raises(BaseCaseError, match=r"unknown key 'lenght' \(did you mean 'length'\?\)"):
        run_bundle(EXAMPLE / "manifest.csv", case, scheduler="serial")
    # in a row's history.units, that contact fails alone, with the hint
    frame = pd.DataFrame({"contact": ["a", "b"], "history": [
        str(EXAMPLE / "tubes" / "R1C1" / "AVB1.parquet")] * 2,
        "history.units": [None, '{ lenght = "mm" }']})
    result = run_bundle(frame, EXAMPLE / "bundle.toml", scheduler="serial")
    assert result.errors["contact"].tolist() == ["b"]
    assert "did you mean 'length'" in result.errors["message"][0]
    with pytest.raises(KeywordError, match="did you mean 'length'"):
        from fretwear.io import read_history
        read_history(EXAMPLE / "tubes" / "R1C1" / "AVB1.parquet", units={"lenght": "mm"})


def _kwu_bundle(tmp_path: Path, rows: str) -> tuple[Path, Path]:
    """A TOML manifest of the oscillator history (examples/data) against the KWU-EPRI base
    case examples/tube_alesage.toml (law.mobile = { COEF_USURE, reference_intensity })."""
    from bundle_helpers import oscillator

    from fretwear.io import write_history

    write_history(oscillator(), tmp_path / "h.parquet")
    manifest = tmp_path / "m.toml"
    manifest.write_text(rows)
    return manifest, ROOT / "examples" / "tube_alesage.toml"


@pytest.mark.filterwarnings("ignore::fretwear.errors.StationarityWarning")  # 0.6 s of history
def test_a_toml_row_updates_entries_of_the_base_case_law_table(tmp_path):
    from bundle_helpers import oscillator

    from fretwear.table import wear_table
    from fretwear.workflows.case_files import case_arguments, load_case

    manifest, base = _kwu_bundle(tmp_path, (
        '[[contacts]]\ncontact = "dotted"\nhistory = "h.parquet"\n'
        'law.mobile.COEF_USURE = 6.0e-14\n'
        '[[contacts]]\ncontact = "inline"\nhistory = "h.parquet"\n'
        'law.mobile = { COEF_USURE = 6.0e-14 }\n'
        '[[contacts]]\ncontact = "subtable"\nhistory = "h.parquet"\n'
        '[contacts.law.mobile]\nCOEF_USURE = 6.0e-14\n'))
    result = run_bundle(manifest, base, scheduler="serial")
    assert result.errors.empty, result.errors.to_dict("records")
    # reference: the single-contact wear_table with COEF_USURE changed, reference_intensity kept
    case = load_case(base)
    assert case["law"]["mobile"] == {"COEF_USURE": 5.2e-14, "reference_intensity": 1.0e-7}
    case["law"]["mobile"]["COEF_USURE"] = 6.0e-14
    expected = wear_table(oscillator(), **case_arguments(case, history_elsewhere=True))
    for contact in ("dotted", "inline", "subtable"):
        assert_identical(rows_of(result, contact), expected)
    # (before: the row's table replaced the base's, reference_intensity dropped, depth ~5e4
    # times smaller, no warning)
    depth = expected["depth_mobile"].iloc[-1]
    assert rows_of(result, "inline")["depth_mobile"].iloc[-1] == depth > 0
    # a row whose table holds every entry gives the base case's own table: same table
    manifest.write_text('[[contacts]]\ncontact = "all"\nhistory = "h.parquet"\n'
                        'law.mobile = { COEF_USURE = 5.2e-14, reference_intensity = 1.0e-7 }\n')
    same = run_bundle(manifest, base, scheduler="serial")
    plain = run_bundle(pd.DataFrame({"contact": ["all"],
                                     "history": [str(tmp_path / "h.parquet")]}),
                       base, scheduler="serial")
    assert_identical(rows_of(same, "all"), rows_of(plain, "all"))


@pytest.mark.filterwarnings("ignore::fretwear.errors.LawWarning")  # S > A·P^b: a short history
def test_a_toml_row_keeps_the_other_edf_mz_coefficients(tmp_path):
    from fretwear.bundle import read_manifest

    manifest, _ = _kwu_bundle(tmp_path, (
        '[[contacts]]\ncontact = "a"\nhistory = "h.parquet"\n'
        'law.obstacle = { COEF_USURE = 4.0e-15 }\n'
        '[[contacts]]\ncontact = "b"\nhistory = "h.parquet"\nlaw.obstacle = {}\n'))
    rows = read_manifest(manifest).rows
    assert rows[0].overrides == {("law", "obstacle", "COEF_USURE"): 4.0e-15}
    assert rows[1].overrides == {("law", "obstacle"): {}}  # {}: no obstacle coefficient
    base = ROOT / "examples" / "grappe_alesage.toml"
    result = run_bundle(manifest, base, scheduler="serial")
    assert result.errors.empty, result.errors.to_dict("records")
    edited = tmp_path / "edited.toml"
    text = base.read_text()
    old = "obstacle = { COEF_USURE = 3.7e-15,"
    assert text.count(old) == 1
    edited.write_text(text.replace(old, "obstacle = { COEF_USURE = 4.0e-15,"))
    assert_identical(rows_of(result, "a"), reference(tmp_path / "h.parquet", edited))
    dropped = tmp_path / "dropped.toml"
    lines = [ln for ln in text.splitlines() if not ln.startswith("obstacle = ")]
    dropped.write_text("\n".join(lines) + "\n")
    assert_identical(rows_of(result, "b"), reference(tmp_path / "h.parquet", dropped))


def test_a_file_the_system_refuses_in_the_first_row_fails_that_contact_only(tmp_path):
    # a law.database name of 300 characters: OSError 'File name too long' (ENAMETOOLONG, a
    # name component > 255 bytes) while building the case, which the base-case check must
    # leave to that contact as the engine's loop does
    result = _given_power(tmp_path, 'materials = ["A304L", "A304L"]',
                          **{"law.database": "d" * 300 + ".csv"})
    assert result.errors["error"].tolist() == ["OSError"]
    assert "File name too long" in result.errors["message"][0]
    case = tmp_path / "base.toml"
    frame = pd.DataFrame({"contact": ["long", "fine"], "power.value_W": [0.01, 0.01],
                          "law.database": ["d" * 300 + ".csv", None]})
    result = run_bundle(frame, case, scheduler="serial")
    assert result.errors["contact"].tolist() == ["long"]
    # the other row: Archard V = K·P·t with the shipped A304L/A304L coefficient 2.6e-15 1/Pa
    assert result.table["volume_mobile"].iloc[-1] == pytest.approx(2.6e-15 * 0.01 * YEAR)
    # a base case whose own database name is refused fails for every contact: said once
    case.write_text(POWERED.format(law='materials = ["A304L", "A304L"]\n'
                                       f'database = "{"d" * 300}.csv"'))
    with pytest.raises(BaseCaseError, match="File name too long"):
        run_bundle(frame.drop(columns="law.database"), case, scheduler="serial")


def test_obstacle_wear_false_on_a_row_drops_the_base_obstacle_coefficients(tmp_path):
    given = "mobile = { COEF_USURE = 1e-15 }\nobstacle = { COEF_USURE = 2e-15 }"
    ptime = 0.01 * YEAR
    # the base case: both bodies wear (Archard V = K·P·t, theory §4)
    assert _volumes(_given_power(tmp_path, given)) == pytest.approx((1e-15 * ptime,
                                                                     2e-15 * ptime))
    # the row says the obstacle does not wear: it does not (was: 2e-15·P·t, silently)
    got = _given_power(tmp_path, given, **{"law.obstacle_wear": False})
    assert _volumes(got) == (pytest.approx(1e-15 * ptime), 0.0)
    toml = tmp_path / "m.toml"
    toml.write_text('[[contacts]]\ncontact = "x"\npower.value_W = 0.01\n'
                    "law.obstacle_wear = false\n")
    assert _volumes(run_bundle(toml, tmp_path / "base.toml", scheduler="serial")) == (
        pytest.approx(1e-15 * ptime), 0.0)
    # true asks for the database's obstacle coefficient: the case layer wants materials
    got = _given_power(tmp_path, given, **{"law.obstacle_wear": True})
    assert "give materials (MATER_USURE) too" in got.errors["message"][0]
    # false with the row's own obstacle coefficients: contradictory, that contact fails
    got = _given_power(tmp_path, given, **{"law.obstacle_wear": False,
                                           "law.obstacle.COEF_USURE": 3e-15})
    assert got.errors["error"].tolist() == ["KeywordError"]
    assert "contradict each other" in got.errors["message"][0]


def test_the_base_case_error_names_the_base_case_key(tmp_path):
    # a base case giving [power] value_W, a manifest of histories: every row fails the same way
    case = tmp_path / "base.toml"
    case.write_text(POWERED.format(law="mobile = { COEF_USURE = 1e-15 }") +
                    "[power]\nvalue_W = 0.01\n")
    with pytest.raises(BaseCaseError) as caught:
        run_bundle(EXAMPLE / "manifest.csv", case, scheduler="serial")
    message = str(caught.value)
    assert ("the base case fails for every contact: its [power] value_W gives every contact a "
            "power, and the manifest's rows give histories: remove value_W from the base "
            "case") in message, message
    assert message.endswith("no row of the manifest changes that; nothing was computed")
    assert "gives what it lacks" not in message


def test_a_row_naming_another_law_does_not_inherit_the_base_laws_coefficients(tmp_path):
    """ARCHARD base (K = 2e-15 Pa⁻¹); a row switching to EDF_MZ with only its exponent b = 1:
    Archard's K must not become EDF-MZ's A (another quantity, m³/(s·W^b)). The row's volume is
    the one of a base case written for EDF_MZ with only COEF_B = 1 (its defaults otherwise),
    and a switch to ARCHARD from a KWU-EPRI base does not carry reference_intensity over
    (which ARCHARD would refuse)."""
    for sub in "abc":
        (tmp_path / sub).mkdir()
    archard = 'name = "ARCHARD"\nmobile = { COEF_USURE = 2e-15 }'
    switched = _given_power(tmp_path / "a", archard, **{"law.name": "EDF_MZ",
                                                        "law.mobile.COEF_B": 1.0})
    direct = _given_power(tmp_path / "b", 'name = "EDF_MZ"\nmobile = { COEF_B = 1.0 }')
    assert _volumes(switched) == _volumes(direct)
    assert _volumes(switched)[0] != pytest.approx(2e-15 * 0.01 * YEAR)
    kwu = 'name = "KWU_EPRI"\nmobile = { COEF_USURE = 5.2e-14, reference_intensity = 1.0e-7 }'
    back = _given_power(tmp_path / "c", kwu, **{"law.name": "ARCHARD",
                                                "law.mobile.COEF_USURE": 2e-15})
    assert _volumes(back) == pytest.approx((2e-15 * 0.01 * YEAR, 0.0))


def test_a_table_given_whole_and_by_entry_in_one_row_is_refused(tmp_path):
    """A CSV row with both law.mobile (a whole table) and law.mobile.COEF_USURE: the result
    depended on the columns' order (a volume of 5.1e-8 or 4.6e-7 m³ for the same cells); now
    that contact fails, in either order, naming both forms."""
    base = 'name = "ARCHARD"\nmobile = { COEF_USURE = 2e-15 }'
    cells = {"law.mobile": "{ COEF_USURE = 1e-15 }", "law.mobile.COEF_USURE": 3e-15}
    for order in (list(cells), list(reversed(cells))):
        got = _given_power(tmp_path, base, **{k: cells[k] for k in order})
        assert got.errors["error"].tolist() == ["KeywordError"]
        assert "law.mobile is given whole and by entry" in got.errors["message"][0]


@pytest.mark.parametrize("tilt", [45.0, 0.0])
def test_warnings_of_a_contacts_case_are_its_own(tmp_path, tilt):
    """A warning raised while a contact's case is built in the client (here: a row switching
    to TUBE_TUBE keeps the base's obstacle width, which crossed tubes do not use) lands in
    BundleResult.warnings for that contact, and only for it, where it reached the terminal
    alone before (a user's trial) and was missing from warnings.csv; the other contact, on the
    base case, has none. With a crossing angle of 0 the case then fails: the contact fails
    with its error and keeps the warning (it was lost, a review). Checked on the serial engine
    and through a warning filter that turns any escaping warning into an error."""
    case = tmp_path / "base.toml"
    case.write_text(POWERED.format(law="mobile = { COEF_USURE = 1e-15 }"))
    frame = pd.DataFrame({"contact": ["tube", "rod"], "power.value_W": [0.01, 0.01],
                          "contact_type": ["TUBE_TUBE", None], "tilt_angle_deg": [tilt, None]})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = run_bundle(frame, case, scheduler="serial", output=tmp_path / "out")
    assert result.errors["contact"].tolist() == ([] if tilt else ["tube"])
    assert result.stats["done"] == (2 if tilt else 1)
    said = result.warnings
    assert said["contact"].tolist() == ["tube"]
    assert said["category"].tolist() == ["UnusedKeywordWarning"]
    assert "TUBE_TUBE does not use obstacle_width" in said["message"][0]
    on_disk = pd.read_csv(tmp_path / "out" / "warnings.csv")
    assert on_disk["contact"].tolist() == ["tube"]
    assert on_disk["message"].tolist() == said["message"].tolist()


def test_task_key_is_the_hash_of_its_inputs_whether_the_case_is_shared_or_not(tmp_path):
    """issue 28: the client encodes a shared case's JSON once for all its rows; the key is
    still the blake2b hash of the JSON of every input, recomputed here independently as it
    was defined (so an output directory written before keeps its contacts on a restart), for
    rows sharing the case (cache) and alone (no cache), and differs when the history does."""
    import hashlib
    import json

    from bundle_helpers import oscillator, write_bundle

    from fretwear._version import __version__
    from fretwear.bundle.cases import _jsonable, build_task
    from fretwear.bundle.datasets import path_stamp
    from fretwear.bundle.engine import _base_case
    from fretwear.bundle.manifest import read_manifest
    from fretwear.io import write_history

    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    man = read_manifest(manifest)
    base = _base_case(case)
    base["_directory"] = str(man.directory)
    cache: dict = {}
    shared = [build_task(base, r, man.source, chunk_size=1000, cache=cache) for r in man.rows]
    alone = [build_task(base, r, man.source, chunk_size=1000) for r in man.rows]
    for task, row in zip(shared, man.rows, strict=True):
        ident = {"case": _jsonable(task.case),
                 "history": [row.history.kind, row.history.path, row.history.node,
                             row.history.index, path_stamp(row.history.path)],
                 "read": _jsonable(task.read_options), "chunk": 1000, "version": __version__,
                 "power": None}
        expected = hashlib.blake2b(json.dumps(ident, sort_keys=True, default=str).encode(),
                                   digest_size=16).hexdigest()
        assert task.key == expected
    assert [t.key for t in shared] == [t.key for t in alone]
    assert len({t.key for t in shared}) == 3
    # a node (in the reader options, made once per case and node) and a given power
    from fretwear.bundle.manifest import ContactRow, HistoryRef

    path = man.rows[1].history.path
    for row in (ContactRow("n", HistoryRef("file", path=path, node="N12"), {}, {}),
                ContactRow("n2", HistoryRef("file", path=path, node="N13"), {}, {}),
                ContactRow("p", HistoryRef("none"), {}, {("power", "value_W"): 1.5})):
        for where in (cache, None):
            task = build_task(base, row, man.source, chunk_size=1000, cache=where)
            power = 1.5 if row.history.kind == "none" else None
            ident = {"case": _jsonable(task.case),
                     "history": [row.history.kind, row.history.path, row.history.node,
                                 row.history.index,
                                 None if power else path_stamp(row.history.path)],
                     "read": _jsonable(task.read_options), "chunk": 1000,
                     "version": __version__, "power": power}
            assert task.read_options.get("node") == row.history.node
            assert task.key == hashlib.blake2b(
                json.dumps(ident, sort_keys=True, default=str).encode(),
                digest_size=16).hexdigest()
    write_history(oscillator(), man.rows[0].history.path)  # another history: another key
    again = build_task(base, man.rows[0], man.source, chunk_size=1000, cache=cache)
    assert again.key != shared[0].key


def test_task_carries_its_file_size_and_the_engine_splits_by_it(tmp_path):
    """A task built from a history file carries the size its key's stat read (os.stat, the
    independent value); a missing file none. plan_chunks decides from that size (no second
    stat): the same file said small is computed whole, said large it is split."""
    import dataclasses
    import os

    from bundle_helpers import oscillator, write_bundle

    from fretwear.bundle.cases import build_task
    from fretwear.bundle.engine import _base_case, plan_chunks
    from fretwear.bundle.manifest import ContactRow, HistoryRef, read_manifest

    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    man = read_manifest(manifest)
    base = _base_case(case)
    base["_directory"] = str(man.directory)
    task = build_task(base, man.rows[0], man.source, chunk_size=400)
    assert task.file_bytes == os.stat(man.rows[0].history.path).st_size
    missing = build_task(base, ContactRow("m", HistoryRef("file", path=str(tmp_path / "no")),
                                          {}, {}), man.source, chunk_size=400)
    assert missing.file_bytes is None
    assert plan_chunks(task, 400) is not None  # the oscillator's history: > 400 samples
    assert plan_chunks(dataclasses.replace(task, file_bytes=10), 400) is None
