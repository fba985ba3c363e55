"""Coefficient database (theory §5) against the tables of Code_Aster R7.20.01 §3, lookups, user
files, CLI.

The reference is tests/fixtures/r7_20_01_tables.txt, a verbatim copy of R7.20.01's tables, parsed
here with its own small parser (independent of fretwear.database).
"""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from fretwear.database import (
    CONTACT_TYPE_NAMES,
    load_database,
    lookup,
    materials,
    read_coefficients,
    summary,
)
from fretwear.errors import DatabaseError, FormatError

FIXTURE = Path(__file__).parent / "fixtures" / "r7_20_01_tables.txt"
BUILTIN_CSV = Path(__file__).parents[1] / "src" / "fretwear" / "data" / "coefficients.csv"
EDF_NAMES = {"A": "rate_coefficient", "B": "power_exponent", "N": "decay_constant",
             "S": "asymptotic_rate"}


def parse_manual_tables() -> tuple[dict, dict]:
    """{(contact, mat1, mat2, law, body, parameter): (value text, references)}, {code: text}."""
    coefficients: dict = {}
    codes: dict = {}
    law = contacts = None
    for line in FIXTURE.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            continue
        if line.startswith("Tables of the coefficients"):
            law = "ARCHARD" if "ARCHARD" in line else "EDF_MZ" if "EDF-MZ" in line else None
            assert law, line
            continue
        if line.startswith("CONTACT :"):
            contacts = [c.replace("\\", "") for c in re.findall(r'"([^"]+)"', line)]
            continue
        fields = line.split("\t")
        if len(fields) == 5 and fields[0] not in ("mat1", "") and contacts:
            mat1, mat2, mobile, obstacle, refs = fields
            for body, text in (("mobile", mobile), ("obstacle", obstacle)):
                if not text.strip():
                    continue   # empty box: no row (theory §5)
                if law == "ARCHARD":
                    pairs = [("coefficient", text.strip())]
                else:
                    pairs = [(EDF_NAMES[k], v) for k, v in re.findall(r"([ABNS]) = (\S+)", text)]
                    assert len(pairs) == 4, text
                for parameter, value in pairs:
                    for contact in contacts:
                        key = (contact, mat1, mat2, law, body, parameter)
                        assert key not in coefficients
                        coefficients[key] = (value, refs.split())
    block = FIXTURE.read_text(encoding="utf-8").split("# ---- material codes")[1]
    for line in block.splitlines()[1:]:
        code, _, text = line.partition(":")
        codes[code.strip()] = text.strip().rstrip(",")
    return coefficients, codes


MANUAL, MANUAL_CODES = parse_manual_tables()


def test_fixture_parser_sanity():
    # counts by hand from R7.20.01 §3: ARCHARD GRAPPE 5 + 5 pairs (×2 bodies; ENCO table for 2
    # types), EDF_MZ 2 + 2 pairs × 2 bodies × 4 parameters (ENCO for 2 types), tubes
    # 13+6+2+10+2 mobiles
    assert len(MANUAL) == 10 + 2 * 10 + 16 + 2 * 16 + 33 == 111
    assert len(MANUAL_CODES) == 17


def test_every_builtin_value_matches_the_manual():
    db = load_database()
    # the rows of Code_Aster's usuban.F90 (tests/test_database_usuban.py) are not the manual's
    db = db[~db["source"].str.contains("usuban.F90")]
    got = {(r.contact_type, r.mobile_material, r.obstacle_material, r.law, r.body, r.parameter):
           r for r in db.itertuples()}
    assert set(got) == set(MANUAL)   # nothing missing, nothing added (empty boxes have no row)
    for key, (text, refs) in MANUAL.items():
        row = got[key]
        assert row.value == float(text), key
        for ref in refs:           # provenance names R7.20.01's references
            assert ref in row.source, key
        assert row.origin == "built-in"


def test_builtin_values_are_the_manuals_text_verbatim():
    with BUILTIN_CSV.open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        if "usuban.F90" in r["source"]:
            continue
        key = (r["contact_type"], r["mobile_material"], r["obstacle_material"], r["law"],
               r["body"], r["parameter"])
        assert r["value"] == MANUAL[key][0], key


def test_units():
    db = load_database()
    units = dict(zip(zip(db.law, db.parameter, strict=True), db.unit, strict=True))
    assert units == {("ARCHARD", "coefficient"): "Pa⁻¹",
                     ("EDF_MZ", "rate_coefficient"): "m³/(s·W^b)",
                     ("EDF_MZ", "power_exponent"): "1", ("EDF_MZ", "decay_constant"): "s⁻¹",
                     ("EDF_MZ", "asymptotic_rate"): "m³/s",
                     ("KWU_EPRI", "reference_coefficient"): "Pa⁻¹",
                     ("KWU_EPRI", "impact_factor"): "1", ("KWU_EPRI", "sliding_factor"): "1",
                     ("KWU_EPRI", "k"): "1", ("KWU_EPRI", "c"): "1"}


def test_material_codes_match_the_manual():
    m = materials().set_index("code")
    assert set(m.index) == set(MANUAL_CODES)
    used = {k[1] for k in MANUAL} | {k[2] for k in MANUAL}
    assert used <= set(m.index)
    for code, text in MANUAL_CODES.items():
        afnor = re.search(r"\((.*)\)", text)
        expected = afnor.group(1) if afnor else ""
        if code == "A316L":
            expected = "Z2 CND 17-12"   # the translation garbled CND (Cr-Ni-Mo) into "NDT"
        assert m.loc[code, "afnor"] == expected, code


def test_contact_types_match_geometry_registry():
    geometry = pytest.importorskip("fretwear.geometry")
    assert set(CONTACT_TYPE_NAMES) == set(geometry.CONTACT_TYPES)


# ----------------------------------------------------------------------------- lookup
def test_lookup_values():
    c = lookup("GRAPPE_ALESAGE", "A304L", "A304L", "ARCHARD", obstacle=True)
    # theory §5: R7.20.01's 2.6e-15 / 3.7e-15, not Code_Aster's current 10e-15 / 15e-15
    assert c.mobile == {"coefficient": 2.6e-15} and c.obstacle == {"coefficient": 3.7e-15}
    assert "[bib5]" in c.sources["mobile.coefficient"]
    assert c.units == {"coefficient": "Pa⁻¹"}
    e = lookup("grappe_2_enco", "a316l", "a304l", "edf_mz")      # codes are case-insensitive
    assert e.mobile == {"rate_coefficient": 500e-15, "power_exponent": 1.78,
                        "decay_constant": 2.44e-8, "asymptotic_rate": 1.14e-16}
    assert e.obstacle == {"rate_coefficient": 490e-15, "power_exponent": 1.91,
                          "decay_constant": 2.44e-8, "asymptotic_rate": 1.14e-16}
    # GRAPPE_1_ENCO and GRAPPE_2_ENCO share their table
    assert lookup("GRAPPE_1_ENCO", "A316L", "A304L", "EDF_MZ").mobile == e.mobile
    t = lookup("TUBE_4_ENCO", "I600TT", "I800", "ARCHARD")
    assert t.mobile == {"coefficient": 3.6e-16} and t.obstacle is None   # empty box
    assert t.to_dict()["obstacle"] is None


def test_lookup_errors_list_what_exists():
    with pytest.raises(DatabaseError,
                       match=r"mobile I690 on obstacle I600.*I600/I600 \(mobile only\)"):
        lookup("TUBE_BAV", "I690", "I600", "ARCHARD")
    with pytest.raises(DatabaseError, match=r"no obstacle coefficient.*empty box.*none"):
        lookup("TUBE_BAV", "I600", "I600", "ARCHARD", obstacle=True)
    # TUBE_BAV has EDF_MZ values for I600/I600 only (Code_Aster's usuban.F90)
    with pytest.raises(DatabaseError,
                       match=r"no coefficients for TUBE_BAV / EDF_MZ, mobile I690 on obstacle "
                             r"I600.*I600/I600"):
        lookup("TUBE_BAV", "I690", "I600", "EDF_MZ")
    with pytest.raises(DatabaseError,
                       match=r"no EDF_MZ coefficients for TUBE_ALESAGE.*ARCHARD: I690/Z10C13"):
        lookup("TUBE_ALESAGE", "I600", "I600", "EDF_MZ")
    with pytest.raises(DatabaseError, match=r"unknown contact type 'TUBE'.*TUBE_BAV"):
        lookup("TUBE", "I600", "I600", "ARCHARD")
    with pytest.raises(DatabaseError, match=r"unknown material code\(s\) \['I601'\]"):
        lookup("TUBE_BAV", "I601", "I600", "ARCHARD")
    with pytest.raises(DatabaseError, match=r"unknown law 'USURE'"):
        lookup("TUBE_BAV", "I600", "I600", "USURE")


# ----------------------------------------------------------------------------- user files
def write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


HEADER = "contact_type,mobile_material,obstacle_material,law,body,parameter,value,unit,source\n"


def test_user_file_extends_and_overrides_with_provenance(tmp_path):
    text = (HEADER
            + "TUBE_BAV,I690TT,A405,ARCHARD,mobile,COEF_USURE,3e-15,1/Pa,my test 2024\n"
            + "TUBE_BAV,I600,I600,ARCHARD,mobile,coefficient,1.0e-13,m3/J,lab B\n"
            + "TUBE_BAV,I600,I600,ARCHARD,obstacle,coefficient,2.0e-14,Pa^-1,lab B\n")
    extra = write(tmp_path / "mine.csv", text)
    new = lookup("TUBE_BAV", "I690TT", "A405", "ARCHARD", extra=extra)
    assert new.mobile == {"coefficient": 3e-15}
    assert new.sources["mobile.coefficient"] == f"my test 2024 ({extra})"
    over = lookup("TUBE_BAV", "I600", "I600", "ARCHARD", obstacle=True, extra=extra)
    assert over.mobile == {"coefficient": 1.0e-13} and over.obstacle == {"coefficient": 2.0e-14}
    assert lookup("TUBE_BAV", "I600", "I600", "ARCHARD").mobile == {"coefficient": 1.2e-13}
    db = load_database([extra])
    assert len(db) == 120 + 2       # one override, two new rows
    assert extra.read_text(encoding="utf-8") == text   # the user's file is untouched
    # later files win
    second = write(tmp_path / "second.csv",
                   HEADER + "TUBE_BAV,I600,I600,ARCHARD,mobile,coefficient,5e-14,Pa⁻¹,lab C\n")
    assert lookup("TUBE_BAV", "I600", "I600", "ARCHARD", extra=[extra, second]).mobile == \
        {"coefficient": 5e-14}


def test_user_file_optional_columns(tmp_path):
    p = write(tmp_path / "min.csv", "contact_type,mobile_material,obstacle_material,law,parameter,"
              "value,unit\nTUBE_TUBE,I800,I800,EDF_MZ,COEF_S,2e-16,m3/s\n")
    row = read_coefficients(p).iloc[0]
    assert (row.body, row.parameter, row.value, row.unit) == ("mobile", "asymptotic_rate", 2e-16,
                                                             "m³/s")
    assert row.source == f"{p}:2"


@pytest.mark.parametrize("line, message", [
    ("TUBE_BAV,I600,I600,ARCHARD,mobile,coefficient,1e-13,mm3/J,x", r"line 2: unit 'mm3/J'.*Pa⁻¹"),
    ("TUBE_BAV,I600,I600,ARCHARD,mobile,COEF_B,1,1,x",
     r"line 2: ARCHARD has no coefficient 'COEF_B'"),
    ("TUBE_BAV,I600,I600,ARCHARD,mobile,coefficient,-1e-13,Pa⁻¹,x", r"line 2: column 'value'"),
    ("TUBE_BAV,I600,I600,ARCHARD,wall,coefficient,1e-13,Pa⁻¹,x", r"line 2: body must be"),
    ("TUBE_XX,I600,I600,ARCHARD,mobile,coefficient,1e-13,Pa⁻¹,x", r"line 2: unknown contact_type"),
    ("TUBE_BAV,I600,I600,USURE,mobile,coefficient,1e-13,Pa⁻¹,x", r"line 2: unknown law 'USURE'"),
    ("TUBE_BAV,,I600,ARCHARD,mobile,coefficient,1e-13,Pa⁻¹,x", r"line 2: empty 'mobile_material'"),
])
def test_user_file_errors_name_file_and_line(tmp_path, line, message):
    p = write(tmp_path / "bad.csv", HEADER + line + "\n")
    with pytest.raises(FormatError, match=message) as info:
        load_database(p)
    assert str(p) in str(info.value)


def test_user_file_structural_errors(tmp_path):
    p = write(tmp_path / "cols.csv", "contact_type,law,value\nTUBE_BAV,ARCHARD,1e-13\n")
    with pytest.raises(FormatError, match=r"missing column\(s\) \['mobile_material'.*the file "
                                          r"has \['contact_type', 'law', 'value'\]"):
        read_coefficients(p)
    row = "TUBE_BAV,I600,I600,ARCHARD,mobile,coefficient,1e-13,Pa⁻¹,x\n"
    p = write(tmp_path / "dup.csv", HEADER + row + row.replace("coefficient", "COEF_USURE"))
    with pytest.raises(FormatError, match=r"lines \[2, 3\] give the same coefficient"):
        read_coefficients(p)


def test_summary_and_filters():
    s = summary(contact_type="GRAPPE_ALESAGE", law="EDF_MZ")
    assert s.mobile.tolist()[1] == ("A = 1.1e-14 m³/(s·W^b)  b = 1.61  n = 2.44e-08 s⁻¹  "
                                    "S = 1.14e-16 m³/s")
    # R7.20.01's boxes and usuban.F90's two TUBE_BAV I600/I600 boxes (KWU_EPRI, EDF_MZ)
    assert len(summary()) == 5 + 10 + 2 + 4 + 13 + 6 + 2 + 10 + 2 + 2
    with pytest.raises(DatabaseError, match="unknown contact type 'NOPE'.*TUBE_BAV"):
        summary(contact_type="NOPE")


# ----------------------------------------------------------------------------- CLI
def test_cli_table_and_json(tmp_path):
    from fretwear.cli.materials import command

    runner = CliRunner()
    out = runner.invoke(command, ["--contact", "TUBE_TUBE"], terminal_width=200)
    assert out.exit_code == 0, out.output
    assert "I690" in out.output and "1e-12" in out.output and "[bib6]" in out.output
    assert "Inconel 690" in out.output
    extra = write(tmp_path / "x.csv", HEADER + "TUBE_TUBE,I800,I800,ARCHARD,mobile,coefficient,"
                  "4e-14,Pa⁻¹,bench 7\n")
    out = runner.invoke(command, ["--contact", "tube_tube", "--law", "ARCHARD", "--json",
                                  "--database", str(extra)])
    assert out.exit_code == 0, out.output
    data = json.loads(out.output)
    records = {(r["mobile_material"], r["value"], r["origin"]) for r in data["coefficients"]}
    assert records == {("I600", 1.8e-13, "built-in"), ("I690", 1e-12, "built-in"),
                       ("I800", 4e-14, str(extra))}
    assert {m["code"] for m in data["materials"]} == {"I600", "I690", "I800"}
    out = runner.invoke(command, ["--law", "COULOMB"])
    assert out.exit_code != 0 and "unknown law 'COULOMB'" in str(out.exception)


# ----------------------------------------------------------------------------- review additions
def test_lookup_errors_point_at_swapped_materials_and_other_laws():
    """R7.20.01 §3: TUBE_BAV has I600/A405 (mobile I600), GRAPPE_ALESAGE has A304LNI/A304L for
    ARCHARD only (its EDF_MZ table holds A304L/A304L and A316L/A304L)."""
    with pytest.raises(DatabaseError, match=r"table has mobile I600 on obstacle A405.*order "
                                            r"mobile, obstacle"):
        lookup("TUBE_BAV", "A405", "I600", "ARCHARD")
    with pytest.raises(DatabaseError, match=r"A304LNI/A304L has ARCHARD coefficients for "
                                            r"GRAPPE_ALESAGE.*A304L/A304L \(mobile\+obstacle\), "
                                            r"A316L/A304L"):
        lookup("GRAPPE_ALESAGE", "A304LNI", "A304L", "EDF_MZ")


def test_spreadsheet_csv_semicolon_decimal_comma_and_bom(tmp_path):
    """A ';'-separated file with decimal commas (a spreadsheet with a comma decimal separator)
    and a UTF-8 file with a byte-order mark read the same values as the plain CSV."""
    semi = tmp_path / "semi.csv"
    semi.write_text("contact_type;mobile_material;obstacle_material;law;body;parameter;value;unit\n"
                    "TUBE_BAV;I690TT;A405;ARCHARD;mobile;COEF_USURE;3,5e-15;1/Pa\n"
                    "TUBE_BAV;I690TT;A405;ARCHARD;obstacle;COEF_USURE;1.2e-15;1/Pa\n",
                    encoding="utf-8")
    c = lookup("TUBE_BAV", "I690TT", "A405", "ARCHARD", obstacle=True, extra=semi)
    assert c.mobile == {"coefficient": 3.5e-15} and c.obstacle == {"coefficient": 1.2e-15}
    bom = tmp_path / "bom.csv"
    bom.write_bytes("contact_type,mobile_material,obstacle_material,law,parameter,value,unit\n"
                    "TUBE_TUBE,I800,I800,ARCHARD,coefficient,4e-14,Pa⁻¹\n".encode("utf-8-sig"))
    assert lookup("TUBE_TUBE", "I800", "I800", "ARCHARD", extra=bom).mobile == \
        {"coefficient": 4e-14}


def test_cli_filters_drop_constant_columns_and_explain_empty_results(tmp_path):
    from fretwear.cli.materials import command

    runner = CliRunner(env={"COLUMNS": "200"})   # rich reads the width from COLUMNS
    out = runner.invoke(command, ["--contact", "GRAPPE_ALESAGE", "--law", "edf_mz"])
    assert out.exit_code == 0, out.output
    header = next(line for line in out.output.splitlines() if "mobile" in line)
    assert "contact" not in header and "law" not in header
    # R7.20.01 §3, GRAPPE_ALESAGE EDF_MZ A316L/A304L: A = 11.E-15, B = 1.61; one parameter per line
    assert "A = 1.1e-14" in out.output and "b = 1.61" in out.output
    assert "HT.22/97-21A" in out.output              # [bib5] spelled out under the table
    out = runner.invoke(command, ["--contact", "GRAPPE_ALESAGE", "--law", "KWU_EPRI"])
    text = " ".join(out.output.split())     # rich wraps at the console width
    assert out.exit_code == 0
    # R7.20.01 §3, GRAPPE_ALESAGE: 5 ARCHARD boxes, 2 EDF_MZ; KWU_EPRI has usuban's TUBE_BAV
    # I600/I600 only
    assert "No KWU_EPRI coefficients for GRAPPE_ALESAGE" in text
    assert "ARCHARD (5 material pairs)" in text and "EDF_MZ (2 material pairs)" in text
    out = runner.invoke(command, ["--contact", "TUBE_ALESAGE", "--law", "EDF_MZ"])
    text = " ".join(out.output.split())
    assert "TUBE_ALESAGE has: ARCHARD (6 material pairs)" in text
    assert "at all" not in text  # EDF_MZ has rows (for other contact types)
    mine = write(tmp_path / "mine.csv", HEADER + "TUBE_TUBE,X12,I690,ARCHARD,mobile,coefficient,"
                 "1e-14,Pa⁻¹,bench\n")
    out = runner.invoke(command, ["--contact", "TUBE_TUBE", "--database", str(mine)])
    assert "X12" in out.output and "not a built-in code" in out.output
    assert f"bench [{mine}]" in out.output    # a user row shows its source and file
