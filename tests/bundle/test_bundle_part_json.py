"""A part's JSON writes what its contacts share once (fretwear.bundle.part_json, issue 28) and is
read back, in this form and in the one written until now (every record whole), as the same
records: the same values, keys in the same order. The references: the standard library's
``json.dumps`` of the whole records (the encoding before), a part JSON of that form written by
the code before (OLD_PART, a run's part cut to three contacts), and a run's output directory
whose parts are rewritten that way, then loaded and restarted."""

from __future__ import annotations

import copy
import json
import math
import pickle

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import load, run_bundle
from fretwear.bundle.part_json import records_of
from fretwear.bundle.store import OutputDirectory, _part_records

SKIP = ("table", "state", "rows_file", "part")

#: A part's JSON as fretwear wrote it before its shared entries (two contacts done, one failed).
OLD_PART = (
    '{"part": "part-01795939163433942248-000000", "rows_file": "part-0179593916343394'
    '2248-000000.parquet", "contacts": [{"contact": "c00000", "key": "4d8fc917bbdf671'
    '197e3b8f3c96b67b0", "status": "done", "warnings": [], "error": null, "samples": '
    '1000, "seconds": 0.138602234001155, "attrs": {"contact_type": "TUBE_BAV", "dimen'
    'sions": {"mobile_radius": 0.009525, "obstacle_width": 0.0127, "tilt_angle": 0.0,'
    ' "impact_angle": 0.0}, "law": "ARCHARD", "coefficients_mobile": {"coefficient": '
    '1e-17}, "coefficients_obstacle": null, "materials": null, "coefficient_sources":'
    ' {"mobile.coefficient": "user"}, "sector_edges": [-180.0, -135.0, -90.0, -45.0, '
    '0.0, 45.0, 90.0, 135.0, 180.0], "sector_coefficients": null, "time_scale": 31536'
    '000.0, "origin": 0.0, "tube_replacement": null, "wall_thickness": null, "depth_l'
    'imit": 0.4, "power": {"total": 0.22820974397058363, "blocks": [0.228209743970583'
    '63], "spread": 0.0, "t_start": 0.0, "t_end": 0.00999, "duration": 0.00999, "sect'
    'ors": [0.0, 0.0, 0.0, 0.08925961527673151, 0.13895012869385212, 0.0, 0.0, 0.0]},'
    ' "time_unit": "year"}, "passes": 1}, {"contact": "c00001", "key": "ecbd5a39b895e'
    'c0b87fd0ee03d12c27e", "status": "done", "warnings": [], "error": null, "samples"'
    ': 1000, "seconds": 0.0010548339996603318, "attrs": {"contact_type": "TUBE_BAV", '
    '"dimensions": {"mobile_radius": 0.009525, "obstacle_width": 0.0127, "tilt_angle"'
    ': 0.0, "impact_angle": 0.0}, "law": "ARCHARD", "coefficients_mobile": {"coeffici'
    'ent": 1e-17}, "coefficients_obstacle": null, "materials": null, "coefficient_sou'
    'rces": {"mobile.coefficient": "user"}, "sector_edges": [-180.0, -135.0, -90.0, -'
    '45.0, 0.0, 45.0, 90.0, 135.0, 180.0], "sector_coefficients": null, "time_scale":'
    ' 31536000.0, "origin": 0.0, "tube_replacement": null, "wall_thickness": null, "d'
    'epth_limit": 0.4, "power": {"total": 0.25795641517229717, "blocks": [0.257956415'
    '17229717], "spread": 0.0, "t_start": 0.0, "t_end": 0.00999, "duration": 0.00999,'
    ' "sectors": [0.0, 0.0, 0.0, 0.02696670926598931, 0.23098970590630785, 0.0, 0.0, '
    '0.0]}, "time_unit": "year"}, "passes": 1}, {"contact": "c00002", "key": "e0debe2'
    '7dc721e7d3a97d59cf519ee61", "status": "failed", "warnings": [["UnitsWarning", "o'
    'rbit too large"]], "error": ["InputError", "history missing"], "samples": 0, "se'
    'conds": 0.0, "attrs": null}]}')


def _old_text(stem, rows_file, records):
    """The part's JSON as written before (store.record_part until now)."""
    return json.dumps({"part": stem, "rows_file": rows_file,
                       "contacts": [{k: v for k, v in r.items() if k not in SKIP}
                                    for r in records]}, default=str)


def _records():
    shared = {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3}
    edges = [k * math.pi / 4 for k in range(9)]
    out = []
    for k in range(8):
        out.append({"contact": f"c{k}", "key": f"{k:032x}", "status": "done", "table": None,
                    "warnings": [["RangeWarning", f"power {k} W é"]] if k % 2 else [],
                    "error": None, "samples": 1000 + k, "seconds": 0.1 / (k + 1),
                    "attrs": {"dimensions": shared if k != 5 else dict(shared),
                              "sector_edges": edges, "law": "ARCHARD",
                              "power": {"total": 0.2 * k, "sectors": [0.0, 1e-300, -0.0]},
                              # written apart though == : -0.0 and 0.0, 1 and 1.0 and True
                              "origin": -0.0 if k == 3 else 0.0,
                              "depth_limit": [1, 1.0, True, 1][k % 4],
                              "time_scale": float("nan") if k == 6 else 3.15e7,
                              "when": __import__("numpy").float64(1.5)},  # default=str's
                    "state": None, "passes": 1})
    out.append({"contact": "f", "key": "0" * 32, "status": "failed", "table": None,
                "warnings": [], "error": ["InputError", "missing"], "samples": 0,
                "seconds": 0.0, "attrs": None, "state": None})
    out.append({"contact": "g", "status": "done", "attrs": {"law": "ARCHARD"}})  # no power
    return pickle.loads(pickle.dumps(out))  # as one task's records arrive


def test_a_part_reads_back_as_the_standard_encoders_records(tmp_path):
    store = OutputDirectory(tmp_path / "out")
    records = _records()
    want = json.loads(_old_text("part-x", "part-x.parquet", copy.deepcopy(records)))
    store.record_part(records, "part-x", "part-x.parquet")
    data = json.loads((store.parts / "part-x.json").read_text(encoding="utf-8"))
    assert len(data["shared_attrs"]) < len(records)  # shared: written once
    got = {k: v for k, v in data.items() if k != "shared_attrs"}
    got["contacts"] = records_of(data)
    # the same text once encoded alike: every value, type, sign and key order
    assert json.dumps(got, default=str) == json.dumps(want, default=str)
    assert [r["attrs"]["origin"] for r in got["contacts"][:4]] == [0.0, 0.0, 0.0, -0.0]
    assert [math.copysign(1, r["attrs"]["origin"]) for r in got["contacts"][2:4]] == [1, -1]
    assert [type(r["attrs"]["depth_limit"]) for r in got["contacts"][:4]] == [
        int, float, bool, int]


def test_a_part_written_before_reads_back_whole(tmp_path):
    store = OutputDirectory(tmp_path / "out")
    (store.parts / "part-01795939163433942248-000000.json").write_text(OLD_PART)
    old = json.loads(OLD_PART)["contacts"]
    previous = store.previous()
    assert list(previous) == ["c00000", "c00001", "c00002"]
    for rec in old:
        got = previous[rec["contact"]]
        assert {k: v for k, v in got.items() if k not in SKIP} == rec
        assert got["part"] == "part-01795939163433942248-000000"
        assert got["rows_file"] == "part-01795939163433942248-000000.parquet"
    assert _part_records(store.parts) == {r["contact"]: r for r in old}
    assert previous["c00000"]["attrs"]["power"]["total"] == 0.22820974397058363
    assert previous["c00001"]["attrs"]["sector_edges"] is \
        previous["c00000"]["attrs"]["sector_edges"]  # compacted as before


def test_an_output_directory_of_old_parts_loads_and_restarts(tmp_path):
    pytest.importorskip("zarr")
    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    out = tmp_path / "out"
    first = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    before = load(out)
    for js in (out / "parts").glob("part-*.json"):  # each part rewritten the old way
        data = json.loads(js.read_text(encoding="utf-8"))
        assert "shared_attrs" in data
        js.write_text(_old_text(data["part"], data["rows_file"], records_of(data)),
                      encoding="utf-8")
    again = load(out)
    pd.testing.assert_frame_equal(again.contacts, before.contacts, check_exact=True)
    pd.testing.assert_frame_equal(again.summary(), before.summary(), check_exact=True)
    restart = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    assert restart.stats["skipped"] == 4
    pd.testing.assert_frame_equal(restart.table, first.table, check_exact=True)
    assert (restart.contacts["status"] == "skipped").all()
    pd.testing.assert_frame_equal(restart.contacts.drop(columns="status"),
                                  first.contacts.drop(columns="status"), check_exact=True)
    pd.testing.assert_frame_equal(restart.summary(), first.summary(), check_exact=True)
