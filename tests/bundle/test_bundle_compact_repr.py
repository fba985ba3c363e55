"""OutputDirectory.record_part shares the equal metadata values of a part's records (issue 28
point 2: the case's values, shared by the worker, compacted once per object, not once per
contact). The independent reference is ``compact`` without its ``seen`` memo: the values
keyed by their ``repr`` alone, as before the memo."""

from __future__ import annotations

import copy

from fretwear.bundle.store import OutputDirectory


def _records():
    geometry = {"mobile_radius": 0.01, "wall": [0.00109, -0.0]}  # one object, shared
    edges = [0.0, 90.0, 180.0]
    other = {"mobile_radius": 0.01, "wall": [0.00109, 0.0]}  # 0.0 is not -0.0: its own
    out = []
    for i in range(6):
        out.append({"contact": f"c{i}", "status": "done",
                    "attrs": {"geometry": geometry if i % 3 else other,
                              "sector_edges": edges if i < 4 else list(edges),
                              "power": {"total": float(i)}, "law": "archard"}})
    return out


def test_record_part_shares_as_the_repr_keyed_compact_does(tmp_path):
    ours, reference = _records(), _records()
    store = OutputDirectory(tmp_path / "a")
    store.record_part(ours, store.new_stem(), None)
    alone = OutputDirectory(tmp_path / "b")
    expected = [alone.compact(copy.deepcopy(r["attrs"])) for r in reference]
    for got, want in zip(ours, expected, strict=True):
        assert got["attrs"] == want
        # same sharing: -0.0 kept apart from 0.0 (repr differs), equal lists one object
        assert repr(got["attrs"]["geometry"]) == repr(want["geometry"])
    geometries = [r["attrs"]["geometry"] for r in ours]
    assert len({id(g) for g in geometries}) == 2
    assert repr(geometries[0]["wall"]) == "[0.00109, 0.0]"
    assert repr(geometries[1]["wall"]) == "[0.00109, -0.0]"
    assert len({id(r["attrs"]["sector_edges"]) for r in ours}) == 1
    assert len({id(r["attrs"]["power"]) for r in ours}) == 6  # each contact's own
