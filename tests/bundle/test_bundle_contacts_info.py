"""fretwear.bundle.contacts_info (its rows made while the results arrive, or at the end) and
the errors and warnings of a bundle, taken a column at a time (issue 28: a dict per contact
took 0.4 s at 10^5 contacts), against the per-contact code they replaced (commit 7171c2a's
outputs._contact_info and assemble's loops, kept below as the reference): the same frames,
column for column and value for value, for contacts done, failed, stale (an earlier run's rows
kept) and skipped, with and without warnings, records replaced after their row was made."""

from __future__ import annotations

import math
from typing import Any

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

import fretwear.bundle.engine as engine
from fretwear.bundle import run_bundle
from fretwear.bundle.result import ERROR_COLUMNS
from fretwear.geometry.base import GLOBAL_RANGE

pytest.importorskip("pyarrow")


def reference_contact_info(contact: str, rec: dict[str, Any], case) -> dict[str, Any]:
    """A contact's row as outputs._contact_info made it (commit 7171c2a), no cache."""
    attrs = rec.get("attrs") or {}
    info = {"contact": contact, "status": rec["status"], "samples": rec.get("samples", 0),
            "seconds": rec.get("seconds", 0.0),
            "power": (attrs.get("power") or {}).get("total"), "time_unit": attrs.get("time_unit")}
    carried = case is not None and bool(attrs)
    if carried:
        info.update(origin=case.origin, tube_replacement=case.restart.tube_replacement,
                    wall_thickness=case.wall.thickness, depth_limit=case.wall.limit,
                    contact_type=case.contact_type, dimensions=dict(case.dimensions),
                    law=case.law)
    else:
        info.update({k: attrs.get(k) for k in ("origin", "tube_replacement", "wall_thickness",
                                               "depth_limit", "contact_type", "dimensions",
                                               "law")})
    info.update(coefficients_mobile=attrs.get("coefficients_mobile"),
                coefficients_obstacle=attrs.get("coefficients_obstacle"),
                time_scale=case.time_scale if carried else attrs.get("time_scale"),
                sector_coefficients=attrs.get("sector_coefficients"))
    return info


def reference_frames(man, records, built, identity):
    """contacts, errors and warnings as assemble made them (commit 7171c2a)."""
    order = [r.contact for r in man.rows]
    cases = {c: (built or {})[c] for c in order
             if c in (built or {}) and records[c]["status"] in ("done", "skipped")}
    info = [reference_contact_info(c, records[c], cases.get(c)) for c in order]
    contacts = identity.merge(pd.DataFrame(info), on="contact", how="right")
    errors, warns = [], []
    for c in order:
        rec = records[c]
        for category, message in rec.get("warnings") or []:
            warns.append({"contact": c, "category": category, "message": message})
        if rec["status"] == "failed":
            errors.append({"contact": c, "error": rec["error"][0], "message": rec["error"][1],
                           "rows_kept": False})
        elif rec["status"] == "stale":
            errors.append({"contact": c, "error": rec["error"][0],
                           "message": f"{rec['error'][1]} (this run could not recompute it: "
                                      f"its rows are the earlier run's, {rec['part']})",
                           "rows_kept": True})
        elif rec["status"] in ("done", "skipped"):
            ranged = [m for cat, m in rec.get("warnings") or [] if cat == "RangeWarning"]
            if ranged:
                message = next((m for m in ranged if GLOBAL_RANGE in m), ranged[0])
                errors.append({"contact": c, "error": "RangeWarning", "message": message,
                               "rows_kept": True})
    errors = pd.DataFrame(errors, columns=list(ERROR_COLUMNS)).merge(
        identity.drop(columns=["history"]), on="contact", how="left")
    return contacts, errors, pd.DataFrame(warns, columns=["contact", "category", "message"])


def assert_same(got: pd.DataFrame, expected: pd.DataFrame) -> None:
    """Same columns, dtypes and values (dicts and None compared as objects)."""
    pd.testing.assert_frame_equal(got, expected, check_exact=True)
    for column in got.columns:  # NaN and None told apart, each dict its own
        for a, b in zip(got[column].tolist(), expected[column].tolist(), strict=True):
            assert type(a) is type(b), (column, a, b)
            assert a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))


def test_contacts_errors_and_warnings_are_the_per_contact_codes(tmp_path, monkeypatch):
    seen = []
    assemble = engine.assemble

    def spy(man, records, *args, **kwargs):
        # warnings as a task catches them (category, message): a sector's and the global
        # depth's RangeWarning (the error is the global one's), a sector's alone, another kind
        order = [r.contact for r in man.rows]
        records[order[0]]["warnings"] = [("RangeWarning", "sector 3 beyond"),
                                         ("UnitsWarning", "orbit too large"),
                                         ("RangeWarning", f"{GLOBAL_RANGE} beyond")]
        records[order[2]]["warnings"] = [("RangeWarning", "sector 1 beyond")]
        records[order[4]]["warnings"] = [("ResolutionWarning", "coarse")]
        # a record replaced after its row was made while the results arrived (a copy), and
        # another's attrs: their rows made again at the end (ContactRows.frame)
        records[order[1]] = {**records[order[1]]}
        if records[order[3]].get("attrs"):
            records[order[3]]["attrs"] = {**records[order[3]]["attrs"], "time_unit": "day"}
        result = assemble(man, records, *args, **kwargs)
        seen.append((man, records, kwargs.get("built"), result))
        return result

    monkeypatch.setattr(engine, "assemble", spy)
    # 5 contacts: one history file missing (failed), one a low-frequency case whose warnings
    # are kept; then a rerun with another file gone (stale) and the rest skipped
    manifest, case = write_bundle(tmp_path, oscillator(), 5)
    (tmp_path / "histories" / "t4.parquet").unlink()
    out = tmp_path / "out"
    run_bundle(manifest, case, scheduler="serial", output=out)
    (tmp_path / "histories" / "t1.parquet").rename(tmp_path / "t1.parquet")
    run_bundle(manifest, case, scheduler="serial", output=out)
    run_bundle(manifest, case, scheduler="serial")  # no output: no table file
    statuses = set()
    for man, records, built, result in seen:
        identity = man.identity_frame()
        identity["contact"] = identity["contact"].astype(str)
        contacts, errors, warns = reference_frames(man, records, built, identity)
        assert_same(result.contacts, contacts)
        assert_same(result.errors, errors)
        assert_same(result.warnings, warns)
        statuses |= set(contacts["status"])
        # a dimensions dict is each row's own (a change to one is not another's)
        dims = [d for d in result.contacts["dimensions"] if isinstance(d, dict)]
        assert len({id(d) for d in dims}) == len(dims)
    assert statuses == {"done", "failed", "skipped", "stale"}
    assert [len(r.warnings) for *_, r in seen] == [5, 5, 5]
    assert [len(r.errors) for *_, r in seen] == [3, 4, 4]


def test_the_identity_share_of_the_digest_taken_ahead_gives_the_same_digest():
    """outputs.identity_hash taken by the engine while the workers compute, then given to
    outputs_digest, makes the digest it makes itself from the identity frame."""
    from fretwear.bundle.outputs import identity_hash, outputs_digest

    identity = pd.DataFrame({"contact": ["a", "b"], "tube_row": [1, 2], "support": ["AVB", None]})
    records = {"a": {"key": "k1", "status": "done", "part": "p", "rows_file": "p.parquet"},
               "b": {"key": "k2", "status": "skipped", "part": "q", "rows_file": "q.parquet"}}
    options = ("parquet", "zarr", 0.4)
    alone = outputs_digest(identity, ["a", "b"], records, *options)
    assert outputs_digest(identity, ["a", "b"], records, *options,
                          identity_bytes=identity_hash(identity)) == alone
    other = identity.assign(tube_row=[1, 3])
    assert outputs_digest(other, ["a", "b"], records, *options) != alone
