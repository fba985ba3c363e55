"""``table.parquet`` written while the results arrive (table_file.PrefixTable, issue 28): the
parts appended as soon as every contact before them is resolved give the table the bucket route
(table_file.stream_table) writes of the same parts, row for row and dtype for dtype, whatever
the order the parts arrive in and with failed contacts among them; where the parts interleave
contacts the route gives up and leaves nothing behind. The independent computation is
``stream_table`` on the same parts (itself checked against the in-memory assembly in
test_bundle_table_stream.py); both run in this process, so the tables are compared exactly."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle, table_file
from fretwear.bundle.manifest import IDENTITY
from fretwear.bundle.store import OutputDirectory
from fretwear.bundle.table_file import PrefixTable, stream_table

pytest.importorskip("pyarrow")

CONTACTS = [f"T{k:02d}" for k in range(10)]


def _packed(k: int) -> dict:
    """A contact's rows as tasks.pack lays them out: 3 instants x 2 sectors."""
    instant = np.repeat([1.0, 2.0, 5.0], 2)
    sector = np.tile(np.array([1, 2], dtype=np.int64), 3)
    return {"columns": ["instant", "sector", "depth_mobile"],
            "arrays": [instant, sector, 1e-6 * (k + 1) * instant * sector]}


def _identity() -> pd.DataFrame:
    frame = pd.DataFrame({"contact": CONTACTS, "tube_row": [k // 3 + 1 for k in range(10)],
                          "tube_column": [k % 3 + 1 for k in range(10)], "support": "AVB",
                          "node": None, "history": [f"h{k}.parquet" for k in range(10)]})
    return frame.reindex(columns=list(IDENTITY))


def _parts(store: OutputDirectory, runs: list[list[int]], failed: set[int]) -> list[list]:
    """Each run of contacts written as a part (the failed ones without rows); the parts'
    records."""
    out = []
    for run in runs:
        recs = [{"contact": CONTACTS[k], "key": str(k), "attrs": None,
                 "status": "failed" if k in failed else "done",
                 "table": None if k in failed else _packed(k)} for k in run]
        store.write_part(recs)
        out.append(recs)
    return out


@pytest.mark.parametrize("arrival", [[0, 1, 2, 3], [3, 1, 0, 2], [2, 3, 1, 0]],
                         ids=["in-order", "shuffled", "last-first"])
def test_parts_appended_as_they_arrive_give_the_bucket_routes_table(tmp_path, monkeypatch,
                                                                     arrival):
    """Four parts of consecutive contacts, a whole part failed in the middle (contacts 3-4) and
    one failed contact in another, resolved in the order ``arrival``: the table is the bucket
    route's; row groups of 7 rows (several parts a group, a part spanning groups)."""
    monkeypatch.setattr(table_file, "ROWS_PER_GROUP", 7)
    store = OutputDirectory(tmp_path / "out")
    parts = _parts(store, [[0, 1, 2], [3, 4], [5, 6, 7], [8, 9]], failed={3, 4, 6})
    writer = PrefixTable(store.parts, tmp_path / "prefix.parquet", CONTACTS, _identity())
    for k in arrival:
        writer.resolve(parts[k])
        assert not writer.aborted
    assert writer.finish()
    records = [r for part in parts for r in part if r["status"] == "done"]
    assert stream_table(store.parts, tmp_path / "buckets.parquet", records, CONTACTS,
                        _identity())
    got = pd.read_parquet(tmp_path / "prefix.parquet")
    expected = pd.read_parquet(tmp_path / "buckets.parquet")
    pd.testing.assert_frame_equal(got, expected, check_exact=True)  # values and dtypes
    assert list(got["contact"].unique()) == [CONTACTS[k] for k in (0, 1, 2, 5, 7, 8, 9)]
    assert not list(tmp_path.glob(".prefix.parquet.*"))  # the temporary file renamed


def test_an_identity_frame_in_another_order_is_matched_by_contact(tmp_path):
    """The identity rows reach their contacts by id where the identity frame is not in the
    manifest's order (PrefixTable finds each position's identity row once): the table equals
    the one of the identity frame in order (the bucket route's, found by id per row)."""
    store = OutputDirectory(tmp_path / "out")
    parts = _parts(store, [[0, 1, 2], [3, 4], [5, 6, 7], [8, 9]], failed={6})
    for name, identity in (("ordered", _identity()),
                           ("reversed", _identity().iloc[::-1].reset_index(drop=True))):
        writer = PrefixTable(store.parts, tmp_path / f"{name}.parquet", CONTACTS, identity)
        for part in parts:
            writer.resolve(part)
        assert writer.finish()
    got = pd.read_parquet(tmp_path / "reversed.parquet")
    pd.testing.assert_frame_equal(got, pd.read_parquet(tmp_path / "ordered.parquet"),
                                  check_exact=True)
    assert got.groupby("contact")["tube_column"].first().to_dict() == {
        c: k % 3 + 1 for k, c in enumerate(CONTACTS) if k != 6}


def test_parts_after_the_first_are_added_in_arrow_as_pandas_would_write_them(tmp_path,
                                                                              monkeypatch):
    """The parts after the first are given their identity columns in Arrow (no trip through
    pandas: with_identity runs for the first part only), and the file is the bucket route's
    Arrow table for Arrow table, schema and pandas metadata included; a part whose float column
    holds a NaN (written by pyarrow, not pandas: pandas' route writes a NaN as null) goes through
    pandas, so the NaN is null in both tables (compared in Arrow, where a NaN is not a null)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    monkeypatch.setattr(table_file, "ROWS_PER_GROUP", 7)
    store = OutputDirectory(tmp_path / "out")
    parts = _parts(store, [[0, 1, 2], [3, 4], [5, 6, 7], [8, 9]], failed={6})
    with_nan = store.parts / parts[2][0]["rows_file"]
    table = pq.read_table(with_nan)
    depth = table.column("depth_mobile").to_numpy().copy()
    depth[1] = np.nan
    pq.write_table(table.set_column(table.schema.get_field_index("depth_mobile"),
                                    "depth_mobile", pa.array(depth)), with_nan)
    real, through_pandas = table_file.with_identity, []
    monkeypatch.setattr(table_file, "with_identity",
                        lambda frame, *a: through_pandas.append(frame["contact"].iloc[0])
                        or real(frame, *a))
    writer = PrefixTable(store.parts, tmp_path / "prefix.parquet", CONTACTS, _identity())
    for part in parts:
        writer.resolve(part)
    assert writer.finish()
    assert through_pandas == [CONTACTS[0], CONTACTS[5]]  # the first part, the NaN part
    monkeypatch.setattr(table_file, "with_identity", real)
    records = [r for part in parts for r in part if r["status"] == "done"]
    assert stream_table(store.parts, tmp_path / "buckets.parquet", records, CONTACTS,
                        _identity())
    got = pq.read_table(tmp_path / "prefix.parquet")
    expected = pq.read_table(tmp_path / "buckets.parquet")
    assert got.equals(expected, check_metadata=True)
    assert got.column("depth_mobile").null_count == 1


def test_interleaved_parts_give_up_and_leave_nothing(tmp_path):
    """A part holding contacts 0 and 2 and another holding 1 (contacts dealt, not sliced):
    the route gives up, removes its temporary file, writes no table."""
    store = OutputDirectory(tmp_path / "out")
    parts = _parts(store, [[0, 2], [1, 3], list(range(4, 10))], failed=set())
    target = tmp_path / "prefix.parquet"
    writer = PrefixTable(store.parts, target, CONTACTS, _identity())
    writer.resolve(parts[2])
    writer.resolve(parts[0])
    writer.resolve(parts[1])
    assert writer.aborted and not writer.finish()
    assert not target.exists() and not list(tmp_path.glob(".prefix.parquet.*"))


def test_an_interrupted_route_leaves_no_half_table(tmp_path):
    """Parts appended (the temporary file written), then the run stops: abort removes it and no
    table appears; a run missing a contact does not finish either."""
    store = OutputDirectory(tmp_path / "out")
    parts = _parts(store, [[0, 1, 2], [3, 4, 5]], failed=set())
    target = tmp_path / "prefix.parquet"
    writer = PrefixTable(store.parts, target, CONTACTS, _identity())
    writer.resolve(parts[0])
    writer.resolve(parts[1])
    assert writer.tmp is not None and writer.tmp.exists()
    assert not writer.finish()  # contacts 6-9 never resolved
    assert not target.exists() and not list(tmp_path.glob(".prefix.parquet.*"))


def test_a_run_writes_its_table_while_the_results_arrive(tmp_path, monkeypatch):
    """A serial run (parts of 2 consecutive contacts, one contact failed) writes table.parquet
    by the prefix route (the bucket route is never called), and it is the table the bucket
    route writes in a second directory on the same inputs (the prefix route disabled)."""
    manifest, case = write_bundle(tmp_path, oscillator(), 5)
    (tmp_path / "histories" / "t2.parquet").unlink()  # fails: no rows, in the middle

    def refused(*args, **kwargs):
        raise AssertionError("the bucket route was called")

    with monkeypatch.context() as m:
        m.setattr(table_file, "stream_table", refused)
        m.setattr("fretwear.bundle.store.stream_table", refused)
        first = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "a",
                           part_size=2)
    assert first.stats["failed"] == 1
    with monkeypatch.context() as m:
        m.setattr(OutputDirectory, "finish_table", lambda self, writer: False)
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "b", part_size=2)
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "a" / "table.parquet"),
                                  pd.read_parquet(tmp_path / "b" / "table.parquet"),
                                  check_exact=True)
    assert not list((tmp_path / "a").glob(".table.parquet.*"))


@pytest.mark.parametrize("width", [False, True], ids=["same-ids", "longest-id-failed"])
def test_the_dataset_written_with_the_table_is_the_one_written_from_it(tmp_path, monkeypatch,
                                                                       width):
    """dataset.zarr appended a row group at a time while the table is written (GridZarr, row
    groups of 7 rows: several parts a group), its coordinates and attributes added at the end,
    is the Dataset written from the finished table (write_zarr_by_regions, the route before this
    change, forced in a second directory): the same variables, values, coordinates and
    attributes, compared exactly (same process). A failed contact in the middle has no row; where
    the failed one has the longest id (the ids' text width changes), the route gives up and the
    table's route writes it."""
    xr = pytest.importorskip("xarray")
    pytest.importorskip("zarr")
    from fretwear.bundle import result_dataset

    monkeypatch.setattr(table_file, "ROWS_PER_GROUP", 7)
    manifest, case = write_bundle(tmp_path, oscillator(), 5)
    if width:
        frame = pd.read_csv(manifest)
        frame.loc[2, "contact"] = "R2C1-AVB-LONGEST"
        frame.to_csv(manifest, index=False)
    (tmp_path / "histories" / "t2.parquet").unlink()  # failed: no rows, in the middle
    real = result_dataset.write_zarr_by_regions
    used = []
    monkeypatch.setattr(result_dataset, "write_zarr_by_regions",
                        lambda *a, **k: used.append(1) or real(*a, **k))
    first = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "a", part_size=2,
                       dataset_format="zarr")
    assert first.stats["failed"] == 1
    assert used == ([1] if width else [])  # the table's route only where the width changed
    with monkeypatch.context() as m:
        m.setattr(result_dataset.GridZarr, "finish", lambda self, *a: self.abort() or False)
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "b", part_size=2,
                   dataset_format="zarr")
    with xr.open_zarr(tmp_path / "a" / "dataset.zarr") as got, \
            xr.open_zarr(tmp_path / "b" / "dataset.zarr") as expected:
        xr.testing.assert_identical(got.load(), expected.load())
        assert got.sizes["contact"] == 4
    assert not list((tmp_path / "a").glob(".dataset.zarr*"))  # no temporary store left


def test_a_killed_runs_leftovers_are_removed_by_the_next_run(tmp_path):
    """A killed run leaves its table's temporary file and its Zarr store being written; the
    next finished run in the directory removes them (the temporary file once older than
    fretwear.io.atomic.STALE_SECONDS: mtime 0 here, as atomic_path's leftovers) and keeps the
    user's files."""
    import os

    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    out = tmp_path / "out"
    out.mkdir()
    old = out / ".table.parquet.abc123.tmp"
    old.write_bytes(b"PAR1")
    os.utime(old, (0, 0))
    store = out / ".dataset.zarr.00000000000000000001.parts"
    store.mkdir()
    (store / ".zgroup").write_text("{}")
    mine = out / "notes.txt"
    mine.write_text("kept")
    parts = out / "parts"
    parts.mkdir()
    half = parts / ".part-00000000000000000001-000001.parquet.x1y2.tmp"  # a killed write's
    half.write_bytes(b"PAR1")
    os.utime(half, (0, 0))
    busy = parts / ".part-00000000000000000002-000001.json.z3w4.tmp"  # being written now
    busy.write_text("{")
    run_bundle(manifest, case, scheduler="serial", output=out)
    assert not old.exists() and not store.exists() and mine.read_text() == "kept"
    assert not half.exists() and busy.exists()


def test_a_part_write_does_not_list_the_parts_folder(tmp_path, monkeypatch):
    """A part's rows and JSON are written atomically without the sweep of the folder for a
    killed write of the same name (fretwear.io.atomic.atomic_path(sweep=False)): a part's
    name is never written twice, and the listing of parts/ after every write grew with the
    parts (1.6 -> 3.1 ms a write over 2 000 parts). The run's cleanup sweeps parts/ once."""
    import fretwear.io.atomic as atomic

    swept = []
    real = atomic._remove_stale
    monkeypatch.setattr(atomic, "_remove_stale",
                        lambda target, *suffixes: (swept.append(target), real(target, *suffixes)))
    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out", part_size=1)
    assert len(list((tmp_path / "out" / "parts").glob("part-*.json"))) == 3
    assert [t for t in swept if t.parent.name == "parts"] == []
