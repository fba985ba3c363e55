"""Name lists come from their registries, never typed again: the help texts (case-file keys,
Code_Aster facade keywords, CLI options and choices) and the docs tables list exactly the names
of CONTACT_TYPES, WEAR_LAWS, fretwear.io.FORMATS, TIME_UNITS, CHANNELS and the table formats."""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner

from fretwear.bundle.store import DATASET_FORMATS
from fretwear.bundle.store import TABLE_FORMATS as BUNDLE_TABLE_FORMATS
from fretwear.cli import cli
from fretwear.geometry import CONTACT_TYPES
from fretwear.geometry.base import ASTER_KEYWORDS, DIMENSION_UNITS
from fretwear.history import CHANNELS
from fretwear.io import FORMATS
from fretwear.io.aster import TABLE_FORMATS
from fretwear.laws import WEAR_LAWS
from fretwear.obstacle.depth import DEPTH_SHAPES
from fretwear.obstacle.update import PROFILE_FORMATS
from fretwear.table.files import ASTER_SUFFIXES
from fretwear.timeunits import TIME_UNITS
from fretwear.uncertainty.calibration import CALIBRATION_METHODS
from fretwear.uncertainty.sampling import METHODS as SAMPLING_METHODS
from fretwear.workflows.aster import SIMPLE_KEYWORDS
from fretwear.workflows.case_files import KEYS, keys_help

DOCS = Path(__file__).resolve().parents[1] / "docs"
CONTACT = re.compile(r"\b(?:TUBE|GRAPPE)_[A-Z0-9_]+")
LAW = re.compile(r"\b(?:ARCHARD|KWU_EPRI|EDF_MZ|[A-Z]+_MZ|KWU\w*)\b")
NOT_CONTACT = {"TUBE_NEUF",  # a POST_USURE keyword, not a contact type
               # DEFI_SPEC_TURB's control-rod spectra (docs/flow.md), not contact types
               "GRAPPE_1", "GRAPPE_2", "GRAPPE_2_COEFFICIENTS"}


def contact_names(text: str) -> list[str]:
    return [n for n in CONTACT.findall(text) if n not in NOT_CONTACT]


def words(text: str) -> list[str]:
    return re.findall(r"[A-Za-z][\w-]*", text)


def test_case_file_key_help_lists_the_registries():
    assert contact_names(KEYS["geometry"]["contact_type"][1]) == list(CONTACT_TYPES)
    assert LAW.findall(KEYS["law"]["name"][1]) == [*WEAR_LAWS, "ARCHARD"]  # + the default
    assert set(words(KEYS["time"]["unit"][1])) - {"or", "days", "default"} == set(TIME_UNITS)
    text = keys_help()
    for name in (*CONTACT_TYPES, *WEAR_LAWS, *TIME_UNITS):
        assert re.search(rf"\b{re.escape(name)}\b", text), name


def test_case_file_geometry_and_history_keys_come_from_the_registries():
    dimensions = {k for k in KEYS["geometry"] if k.endswith(("_m", "_deg"))} - {"wall_thickness_m"}
    assert dimensions == {f"{n}_{DIMENSION_UNITS[n]}" for n in ASTER_KEYWORDS}
    for name, keyword in ASTER_KEYWORDS.items():
        assert f"({keyword})" in KEYS["geometry"][f"{name}_{DIMENSION_UNITS[name]}"][1]
    for key in ("file", "format"):
        assert ", ".join(FORMATS) in KEYS["history"][key][1]


def test_code_aster_facade_keyword_help_lists_the_registries():
    assert contact_names(SIMPLE_KEYWORDS["CONTACT"]) == list(CONTACT_TYPES)
    assert LAW.findall(SIMPLE_KEYWORDS["LOI_USURE"]) == list(WEAR_LAWS)


def _help(*argv: str) -> str:
    out = CliRunner().invoke(cli, [*argv, "--help"], terminal_width=10_000)
    assert out.exit_code == 0, out.output
    return out.output


def _option(text: str, option: str) -> str:
    """The help paragraph of one option (up to the next option)."""
    start = text.index(option)
    nxt = re.search(r"\n\s+-{1,2}\w", text[start + len(option):])
    return text[start:start + len(option) + (nxt.start() if nxt else len(text))]


def _choices(text: str, option: str) -> list[str]:
    """The choices click prints for an option (``[a|b]``; lower case when case-insensitive)."""
    return re.search(r"\[([^\]]+)\]", _option(text, option)).group(1).split("|")


def test_materials_help_lists_contact_types_and_laws():
    text = _help("materials")
    assert contact_names(_option(text, "--contact")) == list(CONTACT_TYPES)
    assert LAW.findall(_option(text, "--law")) == list(WEAR_LAWS)


def test_materials_help_gives_each_laws_coefficients_from_the_registry():
    text = " ".join(_help("materials").split())
    for law in WEAR_LAWS.values():
        user = [p for p in law.parameters if p in law.aster_keywords]
        assert all(p in law.symbols for p in user), law.name  # every user coefficient
        listed = ", ".join(f"{law.symbols[p]} [{law.units[p]}]" for p in user)
        assert f"{law.name} {listed}" in text, law.name


def test_power_help_lists_formats_and_channels():
    text = " ".join(_help("power").split())  # unwrapped
    formats = re.search(r"File format \(([^)]*)\)", text).group(1).split(", ")
    assert formats == list(FORMATS)
    channels = re.search(r"Map a column to a channel \(([^)]*)\)", text).group(1).split(", ")
    assert channels == list(CHANNELS)


def test_run_and_obstacle_choices_come_from_the_registries():
    run = _help("run")
    assert _choices(run, "--aster-format") == [f.lower() for f in TABLE_FORMATS]  # any case
    assert contact_names(run) == list(CONTACT_TYPES)
    assert "/".join(ASTER_SUFFIXES) in _option(run, "--output")  # table.files' suffixes
    obstacle = _help("obstacle")
    assert _choices(obstacle, "--format") == [f.lower() for f in PROFILE_FORMATS]
    assert _choices(obstacle, "--shape") == list(DEPTH_SHAPES)


def test_bundle_report_and_calibrate_choices_come_from_the_registries():
    bundle = _help("bundle")
    assert _choices(bundle, "--table-format") == list(BUNDLE_TABLE_FORMATS)
    assert _choices(bundle, "--dataset-format") == list(DATASET_FORMATS)
    assert _choices(_help("report"), "--method") == list(SAMPLING_METHODS)
    assert _choices(_help("calibrate"), "--method") == list(CALIBRATION_METHODS)


# ------------------------------------------------------------------------------ docs tables
def table_first_column(path: Path, header: str) -> list[str]:
    """First-column cells (comma-separated names, backticks removed) of the markdown table whose
    header row starts with ``| header |``."""
    lines = path.read_text(encoding="utf-8").splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(f"| {header} |"))
    names = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        cell = line.split("|")[1]
        names += [n.strip().strip("`") for n in cell.split(",")]
    return names


def test_docs_format_table_is_the_registry():
    assert table_first_column(DOCS / "formats.md", "name") == list(FORMATS)


def test_docs_law_tables_are_the_registry():
    assert table_first_column(DOCS / "laws.md", "law") == list(WEAR_LAWS)
    assert table_first_column(DOCS / "case_files.md", "law") == list(WEAR_LAWS)


def test_docs_contact_type_lists_are_the_registry():
    assert sorted(table_first_column(DOCS / "geometry.md", "type")) == sorted(CONTACT_TYPES)
    row = next(line for line in (DOCS / "case_files.md").read_text(encoding="utf-8").splitlines()
               if line.startswith("| `contact_type` |"))
    assert sorted(contact_names(row)) == sorted(CONTACT_TYPES)
    unit = next(line for line in (DOCS / "case_files.md").read_text(encoding="utf-8").splitlines()
                if line.startswith("| `unit` |"))
    assert set(re.findall(r"`(\w+)`", unit)) - {"unit"} == set(TIME_UNITS)


def test_docs_name_no_contact_type_or_law_that_does_not_exist():
    for path in [*sorted(DOCS.glob("*.md")), DOCS.parent / "README.md"]:
        text = path.read_text(encoding="utf-8")
        unknown = set(contact_names(text)) - set(CONTACT_TYPES)
        assert not unknown, f"{path.name} names contact types that do not exist: {unknown}"
