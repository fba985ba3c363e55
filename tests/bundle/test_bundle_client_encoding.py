"""The client's cheaper steps while a run's results arrive (issue 28) give what the steps before
gave, checked against the independent computation each replaced:

* a part's JSON (``OutputDirectory.record_part``, encoded without the check of circular
  references, what contacts share written once: ``part_json``) reads back as the records the
  standard library's ``json.dumps(meta, default=str)`` of the same records gives, the encoding
  before, encoded alike to the same text;
* ``table_file._any_nan`` (numpy on a column without nulls) says what pyarrow's
  ``pc.any(pc.is_nan(column))`` says, the test before: a null is not a NaN.
"""

import json
import math

import numpy as np
import pytest

from fretwear.bundle.part_json import records_of
from fretwear.bundle.store import OutputDirectory
from fretwear.bundle.table_file import _any_nan

pa = pytest.importorskip("pyarrow")
pc = pytest.importorskip("pyarrow.compute")


def _records():
    shared = {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3}
    edges = [k * math.pi / 4 for k in range(9)]
    out = []
    for k in range(5):
        out.append({"contact": f"c{k}", "key": f"{k:032x}", "status": "done", "table": None,
                    "warnings": [["RangeWarning", f"power {k} W é"]] if k % 2 else [],
                    "error": None, "samples": 1000 + k, "seconds": 0.1 / (k + 1),
                    "attrs": {"dimensions": shared, "sector_edges": edges,
                              "power": {"total": 0.2 * k, "sectors": [0.0, 1e-300, -0.0]},
                              "origin": float("nan") if k == 3 else 0.0,
                              "when": np.float64(1.5)},  # default=str's case
                    "state": None, "passes": 1})
    return out


def test_part_json_is_the_standard_encoders_text(tmp_path):
    store = OutputDirectory(tmp_path / "out")
    records = _records()
    skip = ("table", "state", "rows_file", "part")
    want = json.dumps({"part": "part-x", "rows_file": "part-x.parquet",
                       "contacts": [{k: v for k, v in r.items() if k not in skip}
                                    for r in records]}, default=str)
    store.record_part(records, "part-x", "part-x.parquet")
    data = json.loads((store.parts / "part-x.json").read_text(encoding="utf-8"))
    data["contacts"] = records_of(data)
    del data["shared_attrs"]
    assert json.dumps(data, default=str) == want


@pytest.mark.parametrize("values", [
    [0.0, 1.5, -2.0], [0.0, float("nan")], [None, 1.0], [None, float("nan")], [None, None],
    [float("inf"), -float("inf")], []])
@pytest.mark.parametrize("kind", ["float64", "float32"])
def test_any_nan_is_pyarrows_is_nan(values, kind):
    for column in (pa.array(values, type=kind),
                   pa.chunked_array([pa.array(values, type=kind)] * 2, type=kind),
                   pa.chunked_array([], type=kind)):
        assert _any_nan(column) is bool(pc.any(pc.is_nan(column)).as_py())
