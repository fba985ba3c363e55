"""The old fuzz findings issue 29 left open, one test each, with the input that showed it.

Each input used to end in a Python exception (exit 3, a traceback), a silent wrong number or a
stream of 20-70 s; each now ends in a fretwear error naming the culprit and the fix, a warning,
or the right number.
"""

from __future__ import annotations

import copy
import warnings

import numpy as np
import pandas as pd
import pytest
from test_fuzz_cases import base_cases, obstacle_base

from fretwear.errors import FretwearWarning, InputError, KeywordError
from fretwear.history import ContactHistory
from fretwear.io import delimited, iter_history_chunks, read_history
from fretwear.obstacle.update import sector_volumes
from fretwear.power import wear_power
from fretwear.table import WearCase
from fretwear.table.replace import replace_tube
from fretwear.table.restart import initial_state
from fretwear.table.schema import to_aster_names
from fretwear.workflows.case_files import run_case
from fretwear.workflows.loop import load_iterate_case


@pytest.mark.parametrize("meta", ['{"metadata": [1], "units": 3, "name": 5}',
                                  '{"metadata": "abc"}', "[1, 2]"])
def test_npz_metadata_that_is_not_a_dict(tmp_path, meta):
    """A list or a text as the stored metadata raised TypeError/ValueError from dict()."""
    t = np.linspace(0.0, 1e-3, 11)
    path = tmp_path / "h.npz"
    np.savez(path, time=t, normal_force=t + 1.0, vt1=0 * t, vt2=0 * t,
             __fretwear__=np.array(meta))
    history = read_history(path)
    np.testing.assert_array_equal(history.time, t)   # the arrays are read; the odd entries
    assert history.metadata["format"] == "npz"       # dropped (never the user's file changed)


def test_a_top_level_power_in_an_iterate_case(tmp_path):
    """``power = 1.0`` above the sections: TypeError ('float' is not iterable), exit 3."""
    case = tmp_path / "it.toml"
    text = open("examples/iterate_tube_support.toml", encoding="utf-8").read()
    case.write_text("power = 1.0\n" + text.replace("[power]\nt_start_s = 0.2", ""),
                    encoding="utf-8")
    with pytest.raises(KeywordError, match="power"):
        load_iterate_case(case)


@pytest.mark.parametrize("value", [[1e-14, 2e-14], "1e-14", True])
def test_a_coefficient_given_as_a_list(value):
    """COEF_USURE = [1e-14, 2e-14] on 8 sectors: numpy's 'could not broadcast', exit 3."""
    with pytest.raises(KeywordError, match=r"COEF_USURE = .* is not a number.*per-sector"):
        WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0], sectors=8,
                               dimensions={"mobile_radius": 9.525e-3, "obstacle_width": 0.0127},
                               coefficients={"COEF_USURE": value})


@pytest.fixture(scope="module")
def sector_table():
    return obstacle_base()[0]


@pytest.mark.parametrize("column", ["volume_mobile_cumulated", "instant", "sector"])
def test_a_text_cell_in_a_wear_table_given_to_obstacle(sector_table, column):
    """'abc' in a cell: ValueError 'could not convert string to float', exit 3."""
    table = sector_table.astype({column: object})
    table.loc[table.index[-1], column] = "abc"
    with pytest.raises(InputError, match=rf"column '{column}', row {len(table)}: 'abc' is not"):
        sector_volumes(table)


def test_a_text_cell_in_a_restart_table_is_not_read_as_zero(sector_table):
    """A text volume of an initial (restart) table was read as 0 m³: wear lost silently."""
    table = sector_table.astype({"volume_mobile_cumulated": object})
    table.loc[table.index[-1], "volume_mobile_cumulated"] = "abc"
    with pytest.raises(InputError, match=r"volume_mobile_cumulated.*'abc' is not a number"):
        initial_state(table)


def test_wall_thickness_nan():
    """wall_thickness_m = nan: KeyError 'obstacle' (nan != nan), exit 3."""
    case = copy.deepcopy(base_cases()[0])
    case["geometry"]["wall_thickness_m"] = float("nan")
    with pytest.raises(InputError, match="wall_thickness.*nan"):
        run_case(case)


def test_tube_replacement_far_from_the_end_warns_of_its_nan_depths():
    """TUBE_NEUF='OUI' on a Code_Aster table (no geometry) at an early INST: NaN depths said
    only in attrs."""
    table = run_case({**base_cases()[2], "time": {"instants": [1000, 5000, 9000],
                                                   "unit": "h"}}).table
    old = to_aster_names(table)
    old.attrs = {}   # read from Code_Aster's file: no geometry
    with pytest.warns(FretwearWarning, match=r"TUBE_NEUF at INST = 1000: .* 2 later instants "
                                             r"of the table \(5000 \.\. 9000\) are NaN"):
        new = replace_tube(old, 1000.0)
    assert new.loc[new["INST"] > 1000, "P_USUR_TUBE_SECT"].isna().all()


@pytest.mark.parametrize("time", [[0.0, 5e-324, 1e-323], [0.0, 1e-310, 2e-310]])
def test_a_subnormal_window_is_refused(time):
    """A window of 1e-323 s gave P = 0.0 W (blocks NaN) for 1e100 N at 1 m/s: the division by
    a subnormal duration loses every digit."""
    h = ContactHistory(time=time, normal_force=[1e100] * 3, vt1=[1.0] * 3, vt2=[0.0] * 3)
    with pytest.raises(InputError, match="smallest normal floating-point number"):
        wear_power(h, blocks=4)


def test_a_wide_csv_streamed_in_tiny_chunks_is_parsed_in_few_blocks(tmp_path, monkeypatch):
    """250 rows and 2 000 extra columns in chunks of 2 rows: 125+ pandas blocks of 2 000
    column objects each took 20-70 s; parsed in one block, 0.5 s. Counted, not timed: the
    number of blocks pandas parses."""
    n = 250
    t = np.linspace(0.0, 0.025, n)
    frame = pd.DataFrame({"time": t, "normal_force": np.ones(n), "vt1": np.full(n, 0.01),
                          "vt2": np.zeros(n)})
    extra = pd.DataFrame(np.zeros((n, 2000)), columns=[f"x{i}" for i in range(2000)])
    path = tmp_path / "wide.csv"
    pd.concat([frame, extra], axis=1).to_csv(path, index=False)
    parsed = []
    columns = delimited._columns
    monkeypatch.setattr(delimited, "_columns", lambda f, *a: parsed.append(len(f)) or
                        columns(f, *a))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        chunks = list(iter_history_chunks(path, chunk_size=2))
    assert parsed == [n]
    assert len(chunks) == n - 1 and all(len(c) == 2 for c in chunks)
    np.testing.assert_array_equal(np.concatenate([c.time[:1] for c in chunks] + [t[-1:]]), t)


# ---- found by the flow and assessment families (tests/fuzz/test_fuzz_flow_assessment.py)
DESCRIPTION = "examples/bundle/bundle_geometry.toml"


@pytest.mark.parametrize("old, new, match", [
    ('parameters = { long_cor = 3.0, kinematic_viscosity = 1.2e-7 }', 'parameters = ""',
     r"\[flow\].parameters: expected a table"),                        # TypeError from **
    ('ends = ["clamped", "clamped"]', "ends = 0508-08-20", r"\[tubes\].ends: expected two"),
    ("grid_points = 241", "grid_points = " + "4" * 400,                # numpy's MemoryError
     r"grid_points: expected an integer in \[1, 100000\], got an integer of 400 digits"),
    ('type = "AVB"                      #', "type = []  #", r"type: \[\]; choose one"),
    ("span_lengths_m = 1.2", "span_lengths_m = " + "2" * 400,          # OverflowError
     r"span_lengths_m: expected a finite number, got an integer of 400 digits"),
    ("duration_s = 0.7", "duration_s = 1e12", r"2e\+15 samples per tube"),
    ("duration_s = 0.7", "duration_s = 5e-324",                        # NaN modal forces
     r"the duration must hold at least two archive steps"),
    ('spectrum = "SPEC_LONG_COR_1"', "spectrum = []",                   # unhashable list
     r"\[flow\].spectrum: unknown \[\]; choose one of"),
])
def test_odd_values_of_a_bundle_description(tmp_path, old, new, match):
    from fretwear.flow.description import read_description

    text = open(DESCRIPTION, encoding="utf-8").read()
    assert old in text
    path = tmp_path / "bundle.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(InputError, match=match):
        read_description(path)


def test_a_utf16_bundle_description_reads(tmp_path):
    """A description saved as UTF-16 (a Windows editor): UnicodeDecodeError before."""
    from fretwear.flow.description import read_description

    text = open(DESCRIPTION, encoding="utf-8").read()
    path = tmp_path / "bundle.toml"
    path.write_bytes(text.encode("utf-16"))
    assert [s.tube for s in read_description(path)] == \
        [s.tube for s in read_description(DESCRIPTION)]


def test_sizing_and_pod_models_at_the_float_range():
    """A slope of 9e307 overflowed b·d in the likelihood (a numpy RuntimeWarning, inf - inf);
    a POD slope of 1e308 overflowed β₁·ln d. The slope is now refused (a technique's slope is
    near 1); the POD saturates at 0 or 1, its exact limit, without a warning."""
    from fretwear.assessment import LogisticPOD, SizingModel

    with pytest.raises(InputError, match=r"slope = 8.98846567431158e\+307"):
        SizingModel(intercept=0.0, slope=8.98846567431158e307, sigma=1.0)
    with pytest.raises(InputError, match=r"sigma = 2.0 \[m\]: outside"):
        SizingModel(sigma=2.0)   # 2 m: depths not in metres
    model = SizingModel(intercept=0.0, slope=1.0, sigma=1e-4)
    pod = LogisticPOD(beta0=0.0, beta1=1e308)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert model.likelihood(1e300, 0.0) == 0.0   # z² = inf: the density's limit, 0
        assert pod([1e-4, 2.0]).tolist() == [0.0, 1.0]
        assert pod.miss([1e-4, 2.0]).tolist() == [1.0, 0.0]


def test_a_tube_diameter_beyond_the_float_range_of_its_fourth_power(tmp_path):
    """outer_diameter_m = 1.157920892373162e+77 (FRETWEAR_FUZZ_SCALE=20): OverflowError from
    d**4 in the second moment of area."""
    from fretwear.flow.description import read_description

    text = open(DESCRIPTION, encoding="utf-8").read()
    path = tmp_path / "bundle.toml"
    path.write_text(text.replace("outer_diameter_m = 19.05e-3",
                                 "outer_diameter_m = 1.157920892373162e+77"), encoding="utf-8")
    with pytest.raises(InputError, match=r"outer_diameter_m: 1.157920892373162e\+77 is beyond"):
        read_description(path)


@pytest.mark.parametrize("rows", ["{}", "[1.0]", "true"])
def test_a_flow_region_row_that_is_not_an_integer(tmp_path, rows):
    """rows = {} (FRETWEAR_FUZZ_SCALE=20): TypeError 'unhashable type: dict'; a row 1.0 was
    taken for row 1 and failed as a list index; true was taken for row 1."""
    from fretwear.flow.description import read_description

    text = open(DESCRIPTION, encoding="utf-8").read()
    path = tmp_path / "bundle.toml"
    path.write_text(text.replace("rows = [1]\n", f"rows = {rows}\n", 1), encoding="utf-8")
    with pytest.raises(InputError, match=r"\[\[flow.regions\]\] #1: row .* is not one of"):
        read_description(path)
