"""fretwear.bundle.end_scan.scan: the one pass over the final records at a bundle's end gives
what the six passes it replaced gave (commit 140fc7c's outputs._assemble, kept below as the
reference), for records done, failed, stale and skipped, with and without warnings, rows and
two passes; and the digest made from its rows is outputs_digest's from the records."""

from __future__ import annotations

import pandas as pd

from fretwear.bundle.end_scan import scan
from fretwear.bundle.outputs import outputs_digest

RECORDS = {
    "a": {"status": "done", "key": "k1", "part": "p1", "rows_file": "p1.parquet",
          "samples": 100, "passes": 1, "warnings": []},
    "b": {"status": "done", "key": "k2", "part": "p1", "rows_file": "p1.parquet",
          "samples": 50, "passes": 2, "warnings": [["RangeWarning", "beyond"]]},
    "c": {"status": "failed", "key": "k3", "samples": 0, "error": ["InputError", "gone"],
          "warnings": None},
    "d": {"status": "skipped", "key": "k4", "part": "p0", "rows_file": "p0.parquet",
          "samples": 70, "passes": 2},
    "e": {"status": "stale", "key": "k5", "part": "p0", "rows_file": "p0.parquet",
          "error": ["InputError", "moved"], "warnings": []},
    "f": {"status": "done", "key": "k6", "part": "p2", "rows_file": None, "samples": 9,
          "table": {"columns": [], "arrays": []}},
}


def reference(order, records, built):
    cases = {c: built[c] for c in order
             if c in built and records[c]["status"] in ("done", "skipped")}
    tables = any(records[c].get("table") is not None for c in order)
    computed = samples = two_pass = 0
    for c in order:
        rec = records[c]
        if rec["status"] in ("done", "failed"):
            computed += 1
            samples += rec.get("samples", 0)
            two_pass += rec.get("passes") == 2
    news = [c for c in order if records[c].get("warnings")
            or records[c]["status"] not in ("done", "skipped")]
    parts = {r.get("part") for r in records.values() if r.get("part")}
    return cases, tables, (computed, samples, two_pass), news, parts


def test_scan_is_the_passes_it_replaced():
    built = {"a": "case-a", "b": "case-b", "c": "case-c", "d": "case-d", "e": "case-e"}
    for order in (list(RECORDS), ["e", "d", "c", "b", "a"], ["a"]):
        records = {c: RECORDS[c] for c in order}
        seen = scan(order, records, built)
        cases, tables, counts, news, parts = reference(order, records, built)
        assert seen.cases == cases
        assert seen.tables == tables
        assert (seen.computed, seen.samples, seen.two_pass) == counts
        assert seen.news == news
        assert seen.parts == parts
        skipped = {"skipped": "done"}  # 140fc7c's outputs_digest rows
        assert seen.digest_rows == [
            [c, records[c].get("key"), skipped.get(records[c]["status"], records[c]["status"]),
             records[c].get("part"), records[c].get("rows_file")] for c in order]
        identity = pd.DataFrame({"contact": order, "tube_row": range(len(order))})
        options = ("parquet", "zarr", 0.4)
        assert outputs_digest(identity, order, records, *options, rows=seen.digest_rows) \
            == outputs_digest(identity, order, records, *options)
    assert scan(["a", "f"], RECORDS, None).tables  # f holds its rows
    assert scan([], {}, None).digest_rows == []
