"""Table files: one schema, one exact float format, one provenance header in every format.

Round trips are checked bit for bit: ``%.16E`` (17 significant digits) round-trips every
float64 (IEEE 754: 17 digits identify a double), Parquet stores the binary values.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

import fretwear
from fretwear.obstacle import CircleObstacle, Mobile, update_obstacle
from fretwear.table import read_wear_table, wear_table, write_wear_table
from fretwear.table.files import read_profile_table, write_profile_table
from fretwear.table.provenance import header_lines, parse_header
from fretwear.table.schema import FLOAT_FORMAT, PROFILE_COLUMNS

FORMATS = [(".csv", {}), (".parquet", {}), (".tab", {"aster_format": "TABLEAU"}),
           (".resu", {"aster_format": "ASTER"})]


@pytest.fixture(scope="module")
def table():
    """A restartable EDF_MZ table: A given (user), b, n, S the law's defaults; awkward reals."""
    return wear_table(0.0123456789, contact_type="TUBE_BAV", instants=[1 / 3, 1.0, 7.0],
                      dimensions={"mobile_radius": 0.0111, "obstacle_width": 0.0127},
                      law="EDF_MZ", coefficients={"COEF_USURE": 1.1e-13}, time_scale=31_536_000.0,
                      time_unit="year", name="N12 span 3")


def assert_bits(a: pd.Series, b: pd.Series):
    assert np.array_equal(a.to_numpy(dtype=float), b.to_numpy(dtype=float), equal_nan=True)


@pytest.mark.parametrize("suffix, options", FORMATS, ids=[s for s, _ in FORMATS])
def test_every_format_round_trips_exactly_with_its_provenance(table, tmp_path, suffix, options):
    back = read_wear_table(write_wear_table(table, tmp_path / f"t{suffix}", **options))
    assert list(back.columns) == list(table.columns)
    for column in table.columns:
        assert_bits(back[column], table[column])
    prov = back.attrs["provenance"]
    assert prov["version"] == fretwear.__version__
    assert prov["kind"] == "wear table" and prov["name"] == "N12 span 3"
    assert prov["law"] == "EDF_MZ" and prov["contact_type"] == "TUBE_BAV"
    assert prov["time_unit"] == "year" and prov["float_format"] == FLOAT_FORMAT == "%.16E"
    assert prov["date"].endswith("+00:00")
    coefficients = prov["coefficients"]
    assert coefficients["mobile.rate_coefficient"] == {"value": 1.1e-13, "source": "user"}
    assert coefficients["mobile.asymptotic_rate"]["source"] == "default"
    assert set(coefficients) == {f"mobile.{k}" for k in table.attrs["coefficients_mobile"]}


def test_the_header_is_where_each_format_keeps_it(table, tmp_path):
    csv = write_wear_table(table, tmp_path / "t.csv")
    lines = csv.read_text(encoding="utf-8").splitlines()
    assert lines[0].startswith("# fretwear.kind = ")
    assert lines[len([x for x in lines if x.startswith("#")])].startswith("instant,duration")
    # an ordinary CSV reader that skips comments reads the same numbers
    assert_bits(pd.read_csv(csv, comment="#")["volume_mobile"], table["volume_mobile"])
    aster = write_wear_table(table, tmp_path / "t.resu", aster_format="ASTER").read_text()
    head = aster.splitlines()
    # LIRE_TABLE (FORMAT='ASTER') reads '#TITRE' lines as the title: every header line is one
    assert head[0] == "#DEBUT_TABLE" and head[1] == "#TITRE N12 span 3"
    assert all(x.startswith("#TITRE fretwear.") for x in head[2:head.index(
        next(x for x in head if x.startswith("INST")))])
    assert aster.isascii()
    import pyarrow.parquet as pq

    meta = pq.read_schema(write_wear_table(table, tmp_path / "t.parquet")).metadata
    assert json.loads(meta[b"fretwear"])["law"] == "EDF_MZ"


def test_header_lines_parse_back():
    prov = {"kind": "wear table", "version": "9.9", "name": "a = b # c",
            "coefficients": {"obstacle.coefficient": {"value": 3e-14,
                                                      "source": "database I600/A405 §3"}}}
    lines = header_lines(prov)
    assert all(line.isascii() for line in lines)
    assert parse_header([f"# {x}" for x in ["a user title", *lines]]) == prov


def test_restart_from_every_format_continues_exactly(table, tmp_path):
    """theory §7: continuing a written table equals continuing the table in memory."""
    kw = dict(contact_type="TUBE_BAV", instants=[2.0],
              dimensions={"mobile_radius": 0.0111, "obstacle_width": 0.0127}, law="EDF_MZ",
              coefficients={"COEF_USURE": 1.1e-13}, time_scale=31_536_000.0)
    expected = wear_table(0.0123456789, initial_state=table, **kw)
    for suffix, options in FORMATS:
        path = write_wear_table(table, tmp_path / f"r{suffix}", **options)
        again = wear_table(0.0123456789, initial_state=path, **kw)
        for column in ("instant", "volume_mobile", "depth_mobile"):
            assert_bits(again[column], expected[column])


@pytest.mark.parametrize("suffix, fmt", [(".csv", None), (".parquet", None), (".tab", None),
                                         (".txt", "ASTER")])
def test_obstacle_profile_uses_the_same_writer(tmp_path, suffix, fmt):
    vm = np.zeros(10)
    vm[1] = 1e-9
    r = update_obstacle(CircleObstacle(9.5e-3, 10e-3), Mobile(9.5e-3, 1.09e-3),
                        np.linspace(-180.0, 180.0, 11), vm, width=0.02, resolution=0.5,
                        instant=5.0)
    back = read_profile_table(r.write(tmp_path / f"p{suffix}", format=fmt))
    frame = r.to_frame()
    assert list(back.columns) == list(PROFILE_COLUMNS) == list(frame.columns)
    for column in frame.columns:
        assert_bits(back[column], frame[column])
    prov = back.attrs["provenance"]
    assert prov["kind"] == "obstacle profile" and prov["instant"] == 5.0
    if suffix == ".tab":
        text = (tmp_path / "p.tab").read_text()
        assert "THETA" in text and "JEU_USE" in text


def test_profile_format_errors_name_the_choices(tmp_path):
    with pytest.raises(Exception, match="csv, parquet, TABLEAU or ASTER"):
        write_profile_table(pd.DataFrame({"angle": [0.0]}), tmp_path / "p.x", format="xls")


@pytest.mark.parametrize("suffix, options", FORMATS)
def test_restart_in_another_time_unit_is_refused_naming_both_units(table, tmp_path, suffix,
                                                                   options):
    """A table whose header counts time in years, continued by a case in hours, would have its
    instants read as hours (a new user's trial: 20 year became 20 h and the limit 1.458e5 h
    instead of about 3.2e5 h). The units are compared, the error names both and the fix; the
    same unit by another spelling ("years", its scale in seconds) continues."""
    path = write_wear_table(table, tmp_path / f"u{suffix}", **options)
    kw = dict(contact_type="TUBE_BAV", instants=[2.0],
              dimensions={"mobile_radius": 0.0111, "obstacle_width": 0.0127}, law="EDF_MZ",
              coefficients={"COEF_USURE": 1.1e-13})
    assert table.attrs["time_unit"] == "year"
    with pytest.raises(fretwear.InputError, match=r"'year' \(3\.1536e\+07 s.*'h' \(3600 s\).*"
                                                  r"unit = \"year\" in a case file's \[time\], "
                                                  r"time_scale=3\.1536e\+07 in Python"):
        wear_table(0.0123456789, initial_state=path, time_scale=3600.0, time_unit="h", **kw)
    with pytest.raises(fretwear.InputError, match=r"'86400 s'.*unit = \"year\""):  # by scale
        wear_table(0.0123456789, initial_state=path, time_scale=86400.0, **kw)
    again = wear_table(0.0123456789, initial_state=path, time_scale=31_536_000.0, **kw)
    assert again["instant"].iloc[-1] > table["instant"].iloc[-1]
    with pytest.raises(fretwear.InputError, match=r"counts time in 'year'"):  # in memory too
        wear_table(0.0123456789, initial_state=table, time_scale=3600.0, time_unit="h", **kw)
    hours = wear_table(0.0123456789, time_scale=3600.0, **kw)  # no unit name
    with pytest.raises(fretwear.InputError, match=r"'3600 s'.*seconds_per_unit = 3600 in a case"):
        wear_table(0.0123456789, initial_state=hours, time_scale=1.0, **{**kw, "instants": [3.0]})
