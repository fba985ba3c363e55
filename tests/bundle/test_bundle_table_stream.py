"""``table.parquet`` written from the Parquet parts by buckets, never the whole table in the
client (issue 28), is the table the in-memory assembly writes: row for row, dtype for dtype,
on a bundle with a failed contact, a contact recomputed into a later part and a stale one (its
earlier rows kept). The independent computation is the in-memory assembly itself
(``outputs._table`` then ``OutputDirectory.write_table``, the path before this change), forced
in a second output directory on the same inputs; both run in this process, so the tables are
compared exactly (same machine, same process)."""

from __future__ import annotations

import pandas as pd
import pytest
from bundle_helpers import oscillator, scaled, write_bundle

from fretwear.bundle import run_bundle, table_file
from fretwear.bundle.store import OutputDirectory, load
from fretwear.io import write_history

pytest.importorskip("pyarrow")


def _in_memory(*args, **kwargs):
    return False


@pytest.mark.parametrize("mixed", [False, True], ids=["sectors", "some-without-sectors"])
def test_the_streamed_table_is_the_in_memory_one(tmp_path, monkeypatch, mixed):
    monkeypatch.setattr(table_file, "ROWS_PER_GROUP", 7)  # many buckets: 16-row contacts
    extra = {"sectors.count": [None] * 5 + [1]} if mixed else None
    manifest, case = write_bundle(tmp_path, oscillator(), 6, extra=extra)
    histories = tmp_path / "histories"
    (histories / "t3.parquet").unlink()  # fails from the start: no rows

    def both(**options):
        streamed = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "a",
                              part_size=2, **options)
        with monkeypatch.context() as m:
            m.setattr(OutputDirectory, "stream_table", _in_memory)
            kept = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "b",
                              part_size=2, **options)
        return streamed, kept

    first, _ = both()
    assert first.stats["failed"] == 1 and first.table_file is not None
    write_history(scaled(oscillator(), 9), histories / "t1.parquet")  # recomputed: new part
    (histories / "t4.parquet").rename(tmp_path / "moved.parquet")  # stale: earlier rows kept
    streamed, kept = both()
    statuses = streamed.contacts.set_index("contact")["status"]
    assert list(statuses) == ["skipped", "done", "skipped", "failed", "stale", "skipped"]
    assert streamed.stats["stale"] == 1 and streamed.stats["failed"] == 1
    written = pd.read_parquet(tmp_path / "a" / "table.parquet")
    expected = pd.read_parquet(tmp_path / "b" / "table.parquet")
    pd.testing.assert_frame_equal(written, expected, check_exact=True)  # values and dtypes
    assert streamed._table is None or mixed  # not read until asked (mixed: the Dataset reads it)
    pd.testing.assert_frame_equal(streamed.table, kept.table, check_exact=True)
    pd.testing.assert_frame_equal(streamed.summary(), kept.summary(), check_exact=True)
    # the directory read back gives the run's summary
    pd.testing.assert_frame_equal(load(tmp_path / "a").summary(), streamed.summary(),
                                  check_exact=True)
    assert not list((tmp_path / "a").glob(".table.parquet.buckets*"))  # scratch removed


@pytest.mark.parametrize("mixed", [False, True], ids=["sectors", "some-without-sectors"])
def test_the_dataset_written_by_groups_of_contacts_is_the_whole_one(tmp_path, monkeypatch,
                                                                      mixed):
    """dataset.zarr appended a group of contacts at a time (the table's row groups of 7 rows:
    a contact's 16 rows span groups) is the Dataset built whole from the table (the path before
    this change, forced in a second directory); a bundle whose contacts do not all have sectors
    is built whole in both. Same process: compared exactly."""
    xr = pytest.importorskip("xarray")
    pytest.importorskip("zarr")
    monkeypatch.setattr(table_file, "ROWS_PER_GROUP", 7)
    extra = {"sectors.count": [None] * 4 + [1]} if mixed else None
    manifest, case = write_bundle(tmp_path, oscillator(), 5, extra=extra)
    (tmp_path / "histories" / "t2.parquet").unlink()  # a failed contact: not in the Dataset
    grouped = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "a",
                         dataset_format="zarr")
    with monkeypatch.context() as m:
        m.setattr(OutputDirectory, "write_zarr_by_regions", _in_memory)
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "b",
                   dataset_format="zarr")
    assert grouped._table is None or mixed  # the table was not read to write the Dataset
    with xr.open_zarr(tmp_path / "a" / "dataset.zarr") as a, \
            xr.open_zarr(tmp_path / "b" / "dataset.zarr") as b:
        assert a.sizes["contact"] == 4
        xr.testing.assert_identical(a.load(), b.load())
    xr.testing.assert_identical(grouped.dataset, xr.open_zarr(tmp_path / "a" / "dataset.zarr")
                                .load())


@pytest.mark.parametrize("sectors", [True, False], ids=["sectors", "no-sectors"])
def test_the_dataset_reshaped_from_the_grid_is_the_multiindex_one(tmp_path, monkeypatch,
                                                                  sectors):
    """A group of contacts laid out as the table writes them on a full grid is reshaped to
    ``(contact, instant[, sector])`` without pandas' MultiIndex (result_dataset._grid_dataset;
    issue 28: 0.85 s of the Dataset's 4 s at 10^4 contacts). The independent computation is
    the MultiIndex path (``set_index(...).to_xarray()``, the code before), forced in a second
    directory on the same inputs; same process: compared exactly. The reshape must be taken
    for every group here (counted), else this test would not test it."""
    xr = pytest.importorskip("xarray")
    pytest.importorskip("zarr")
    from fretwear.bundle import result_dataset

    monkeypatch.setattr(table_file, "ROWS_PER_GROUP", 7)  # contacts spanning row groups
    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    if not sectors:
        case.write_text(case.read_text().replace("[sectors]\ncount = 4\n", ""))
    taken = []
    real = result_dataset._grid_dataset
    monkeypatch.setattr(result_dataset, "_grid_dataset",
                        lambda *a: taken.append(real(*a) is not None) or real(*a))
    run_bundle(manifest, case, scheduler="serial", output=tmp_path / "a", dataset_format="zarr")
    monkeypatch.setattr(result_dataset, "_grid_dataset", lambda *a: None)
    run_bundle(manifest, case, scheduler="serial", output=tmp_path / "b", dataset_format="zarr")
    assert taken and all(taken)
    with xr.open_zarr(tmp_path / "a" / "dataset.zarr") as a, \
            xr.open_zarr(tmp_path / "b" / "dataset.zarr") as b:
        assert ("sector" in a.dims) == sectors
        xr.testing.assert_identical(a.load(), b.load())
