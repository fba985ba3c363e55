"""Fuzz the bundle manifests and the inspection files of ``calibrate`` (issue 29, point 5).

Manifests: a valid CSV or TOML manifest mutated byte by byte (cuts, flips, NULs, BOMs, nasty
tokens) is read by :func:`fretwear.bundle.read_manifest`; a TOML manifest with one cell replaced
by a value of another type or an extreme one runs through :func:`fretwear.bundle.run_bundle`
(serial, given powers: no history to read). Inspections: a valid file mutated the same way is
read by :func:`fretwear.uncertainty.calibration.read_inspections`. Only fretwear errors may come
out, no example may last over 20 s, and what is returned holds no NaN or inf where a number is
required (instants finite, depths finite and > 0; a bundle's table without NaN depth unless a
warning says why). Derandomized (the same inputs on every run); FRETWEAR_FUZZ_SCALE scales the
number of examples.
"""

from __future__ import annotations

import datetime
import itertools

import numpy as np
from fuzzhelpers import examples, mutated, only_fretwear, workdir
from hypothesis import given, settings
from hypothesis import strategies as st

from fretwear.bundle import read_manifest, run_bundle
from fretwear.uncertainty.calibration import read_inspections

_COUNTER = itertools.count()

CSV_MANIFEST = (b"contact,tube_row,tube_column,support,power.value_W,wall_thickness_m\n"
                b"R1C1,1,1,AVB1,1e-3,0.00109\nR1C2,1,2,AVB1,2e-3,0.00109\n")
TOML_MANIFEST = (b'[[contacts]]\ncontact = "R1C1"\ntube_row = 1\n"power.value_W" = 1e-3\n'
                 b'[[contacts]]\ncontact = "R1C2"\ntube_row = 1\n"power.value_W" = 2e-3\n'
                 b'"time.instants" = [1, 2]\n')
INSPECTIONS = (b"# campaign 2024\ncontact,instant,depth_mm,measurement_sigma\n"
               b"R1C1,10,0.30,0.1\nR1C2,10,0.25,0.1\n")
BASE = ('[law]\nmobile = { COEF_USURE = 1e-14 }\n[geometry]\ncontact_type = "TUBE_BAV"\n'
        'mobile_radius_m = 9.525e-3\nobstacle_width_m = 12.7e-3\n[time]\ninstants = [1, 5]\n'
        'unit = "year"\n')

#: values of the wrong type or out of range, as TOML gives them
ODD = st.one_of(
    st.text(max_size=8), st.integers(-10**400, 10**400), st.sampled_from([0, -1, 2**63]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-300, 1e300, 5e-324]), st.booleans(), st.dates(),
    st.just(datetime.datetime(2024, 1, 1, 12, 0)),
    st.lists(st.one_of(st.floats(), st.text(max_size=3), st.integers()), max_size=3),
    st.dictionaries(st.sampled_from(["a", "COEF_USURE"]), st.integers(), max_size=2))
CELLS = ["tube_row", "tube_column", "support", "wall_thickness_m", "power.value_W",
         "time.instants", "law.mobile.COEF_USURE", "geometry.mobile_radius_m", "history",
         "contact", "sectors.count"]


def deterministic(n: int) -> settings:
    """The suite's budget (:func:`fuzzhelpers.examples`), always derandomized."""
    return settings(examples(n), derandomize=True)


def _file(data: bytes, suffix: str):
    path = workdir() / f"fuzz-{next(_COUNTER)}{suffix}"
    path.write_bytes(data)
    return path


@deterministic(60)
@given(data=st.one_of(mutated(CSV_MANIFEST).map(lambda b: (b, ".csv")),
                      mutated(TOML_MANIFEST).map(lambda b: (b, ".toml"))))
def test_a_mutated_manifest_reads_or_says_why(data):
    manifest, _ = only_fretwear(read_manifest, _file(*data))
    if manifest is not None:
        assert len({r.contact for r in manifest.rows}) == len(manifest.rows)


def _toml_value(value) -> str:
    """``value`` written as TOML (tomllib reads back the same value)."""
    import json

    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return ("nan" if value != value else "inf" if value == float("inf")
                else "-inf" if value == float("-inf") else repr(value))
    if isinstance(value, int):
        return str(value)
    if isinstance(value, datetime.datetime | datetime.date):
        return value.isoformat()
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{json.dumps(k)} = {_toml_value(v)}"
                                for k, v in value.items()) + " }"
    return json.dumps(str(value))


@deterministic(30)
@given(cell=st.sampled_from(CELLS), value=ODD)
def test_an_odd_manifest_cell_fails_its_contact_or_says_why(cell, value):
    case = workdir() / "fuzz-base.toml"
    if not case.exists():
        case.write_text(BASE)
    text = (f'[[contacts]]\ncontact = "A"\n"power.value_W" = 1e-3\n'
            f'"{cell}" = {_toml_value(value)}\n'
            f'[[contacts]]\ncontact = "B"\n"power.value_W" = 1e-3\n')
    result, said = only_fretwear(run_bundle, _file(text.encode(), ".toml"), case,
                                 scheduler="serial")
    if result is None:
        return
    depth = result.table["depth_mobile"].to_numpy(dtype=float)
    bad = ~np.isfinite(depth) | (depth < 0)
    assert not bad.any() or len(result.warnings) or said, (cell, value)


@deterministic(80)
@given(data=mutated(INSPECTIONS))
def test_a_mutated_inspection_file_reads_or_says_why(data):
    table, _ = only_fretwear(read_inspections, _file(data, ".csv"))
    if table is not None:
        assert np.isfinite(table["instant"].to_numpy(dtype=float)).all()
        depth = table["depth"].to_numpy(dtype=float)
        assert (np.isfinite(depth) & (depth > 0)).all()


FIELD_INSPECTIONS = (b"# outage 2024\ntube_row,tube_column,support,date,technique,depth_pct,"
                     b"inspected,plugged,wall_thickness\n"
                     b"1,1,AVB1,2022-05-01,bobbin,32,yes,no,0.00109\n"
                     b"1,2,AVB1,2022-05-01,bobbin,NDD,yes,no,0.00109\n"
                     b"1,3,,2022-05-01,bobbin,,no,yes,0.00109\n")


@deterministic(80)
@given(data=mutated(FIELD_INSPECTIONS))
def test_a_mutated_field_inspection_file_reads_or_says_why(data):
    """The field reader (issue 26): a result or a fretwear error, never another exception."""
    from fretwear.assessment import read_field_inspections

    ins, _ = only_fretwear(read_field_inspections, _file(data, ".csv"),
                           origin_date="2012-01-01")
    if ins is not None:
        table = ins.table
        assert np.isfinite(table["instant"].to_numpy(dtype=float)).all()
        sized = table["status"] == "sized"
        depth = table.loc[sized, "depth"].to_numpy(dtype=float)
        assert (np.isfinite(depth) & (depth > 0)).all()
        assert table.loc[~sized, "depth"].isna().all()
