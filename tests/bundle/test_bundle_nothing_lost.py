"""A rerun never loses a result (issue 29, point 1): a finished bundle opened again with
``run_bundle(..., output=OUT)`` after one history file moved keeps that contact's earlier rows,
reports it stale with this run's error, and rebuilds ``table.parquet`` from every part."""

from __future__ import annotations

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle

pytest.importorskip("pyarrow")


@pytest.mark.parametrize("force", [False, True])
def test_a_moved_history_keeps_the_contacts_earlier_rows(tmp_path, force):
    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    out = tmp_path / "out"
    first = run_bundle(manifest, case, scheduler="serial", output=out)
    before = pd.read_parquet(out / "table.parquet")
    assert first.stats["done"] == 4 and len(before)
    moved = tmp_path / "histories" / "t2.parquet"
    moved.rename(tmp_path / "elsewhere.parquet")

    again = run_bundle(manifest, case, scheduler="serial", output=out, force=force)

    after = pd.read_parquet(out / "table.parquet")
    # row for row: every earlier row is there, with the same values (same machine, same
    # process for both runs' arithmetic: the kept rows are the stored ones, read back)
    pd.testing.assert_frame_equal(after, before, check_exact=True)
    pd.testing.assert_frame_equal(again.table, first.table, check_exact=True)
    stale = again.contacts.set_index("contact")["status"]
    assert stale["R2C1-AVB"] == "stale"
    assert again.stats["stale"] == 1 and again.stats["failed"] == 0
    row = again.errors.set_index("contact").loc["R2C1-AVB"]
    assert bool(row["rows_kept"]) is True
    assert "t2.parquet" in row["message"] and "earlier run" in row["message"]
    # the summary still ranks the stale contact (its earlier rows), said in its note
    summary = again.summary()
    assert "R2C1-AVB" in set(summary["contact"])
    # the file back: the next run skips it again (its earlier record is still the latest)
    (tmp_path / "elsewhere.parquet").rename(moved)
    third = run_bundle(manifest, case, scheduler="serial", output=out)
    assert third.stats["skipped"] == 4 and third.stats["stale"] == 0
    pd.testing.assert_frame_equal(pd.read_parquet(out / "table.parquet"), before,
                                  check_exact=True)


def test_a_contact_that_fails_twice_still_keeps_its_rows(tmp_path):
    """Two reruns with the file gone: the rows survive both (the stale record is never written
    over the earlier good one)."""
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    out = tmp_path / "out"
    run_bundle(manifest, case, scheduler="serial", output=out)
    before = pd.read_parquet(out / "table.parquet")
    (tmp_path / "histories" / "t0.parquet").unlink()
    for _ in range(2):
        again = run_bundle(manifest, case, scheduler="serial", output=out)
        assert again.stats["stale"] == 1
    pd.testing.assert_frame_equal(pd.read_parquet(out / "table.parquet"), before,
                                  check_exact=True)
