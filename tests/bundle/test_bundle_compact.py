"""The client's record metadata kept once per part (``OutputDirectory.compact`` through
``record_part``): every record keeps metadata equal to what the worker sent; equal values of
different contacts become one object, whether they arrived as one object (one task's pickle)
or as equal copies; the power stays each contact's own. Independent check: ``==`` against a
deep copy taken before the part was recorded."""

from __future__ import annotations

import copy
import json
import pickle

from fretwear.bundle.part_json import records_of
from fretwear.bundle.store import OutputDirectory


def _records(n: int, shared: bool):
    geometry = {"mobile_radius": 0.0095, "obstacle_radius": 0.0105}
    edges = [-180.0, -90.0, 0.0, 90.0, 180.0]
    out = []
    for i in range(n):
        out.append({"contact": f"C{i}", "status": "done", "table": None,
                    "attrs": {"dimensions": geometry if shared else dict(geometry),
                              "sector_edges": edges if shared else list(edges),
                              "law": "ARCHARD",
                              "power": {"total": 0.1 * i, "sectors": [0.1 * i, 0.0]}}})
    return out


def test_compacted_metadata_equals_what_arrived_and_is_shared(tmp_path):
    out = OutputDirectory(tmp_path / "o")
    sent = _records(6, shared=True)
    # one task's records arrive through one pickle (shared objects stay shared) ...
    first = pickle.loads(pickle.dumps(sent[:3]))
    # ... another task's as equal copies
    second = [pickle.loads(pickle.dumps(r)) for r in sent[3:]]
    expected = copy.deepcopy(first + second)
    out.record_part(first, "part-a", None)
    out.record_part(second, "part-b", None)
    records = first + second
    assert [r["attrs"] for r in records] == [e["attrs"] for e in expected]
    dims = {id(r["attrs"]["dimensions"]) for r in records}
    edges = {id(r["attrs"]["sector_edges"]) for r in records}
    assert len(dims) == 1 and len(edges) == 1
    powers = {id(r["attrs"]["power"]) for r in records}
    assert len(powers) == len(records)


def test_a_value_changed_between_parts_is_not_taken_for_the_old_one(tmp_path):
    """The memo is by object within one part: a different value in the next part (even at an
    address the old object once had) is compared by its text."""
    out = OutputDirectory(tmp_path / "o")
    a = _records(2, shared=True)
    out.record_part(a, "part-a", None)
    b = _records(2, shared=False)
    for r in b:
        r["attrs"]["dimensions"] = {"mobile_radius": 0.01, "obstacle_radius": 0.011}
    out.record_part(b, "part-b", None)
    assert all(r["attrs"]["dimensions"]["mobile_radius"] == 0.0095 for r in a)
    assert all(r["attrs"]["dimensions"]["mobile_radius"] == 0.01 for r in b)


def test_the_part_json_holds_every_contact_whole(tmp_path):
    out = OutputDirectory(tmp_path / "o")
    recs = pickle.loads(pickle.dumps(_records(3, shared=True)))
    expected = copy.deepcopy(recs)
    out.record_part(recs, "part-a", None)
    data = json.loads((out.parts / "part-a.json").read_text(encoding="utf-8"))
    assert [c["attrs"] for c in records_of(data)] == [e["attrs"] for e in expected]
    previous = out.previous()
    assert [previous[f"C{i}"]["attrs"] for i in range(3)] == [e["attrs"] for e in expected]
