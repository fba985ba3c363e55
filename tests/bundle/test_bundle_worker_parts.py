"""A group of contacts whose worker writes its rows as the part file itself (issue 28: the
client wrote every part, 16 ms of its CPU a part of 100 contacts, and received every row).

The independent computation is the same bundle run in this process (``scheduler="serial"``,
the client writing every part as before): the table read back from the output directory, the
parts' records and a restart give the same on both paths. Both run on this machine and in this
environment (the workers are child processes of the test), so the tables compare exactly.
"""

from __future__ import annotations

import json

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import engine, run_bundle
from fretwear.bundle.store import MARKER, OutputDirectory, load
from fretwear.bundle.worker_parts import PartTarget

distributed = pytest.importorskip("distributed")
pytest.importorskip("pyarrow")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as local, \
            distributed.Client(local) as c:
        yield c


def _parts(out):
    return {p.name: json.loads(p.read_text()) for p in (out / "parts").glob("*.json")}


def test_workers_write_the_rows_and_the_result_is_the_client_written_one(tmp_path, client,
                                                                        monkeypatch):
    manifest, case = write_bundle(tmp_path, oscillator(), 6)
    frame = pd.read_csv(manifest)
    frame.loc[4, "history"] = "histories/missing.parquet"  # a failure inside a group
    frame.to_csv(manifest, index=False)
    monkeypatch.setattr(engine, "TASKS_PER_WORKER", 1)  # 2 groups of 3 contacts
    recorded = []
    real = OutputDirectory.record_part
    monkeypatch.setattr(OutputDirectory, "record_part", lambda self, records, stem, rows:
                        recorded.append((len(records), rows)) or real(self, records, stem, rows))
    written = []
    monkeypatch.setattr(OutputDirectory, "write_part", lambda self, records: written.append(
        len(records)))  # the client writes no part: a call would lose its rows here
    out = tmp_path / "out"
    result = run_bundle(manifest, case, scheduler=client, output=out)
    monkeypatch.undo()
    serial = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "serial")
    assert written == []
    assert sorted(n for n, _ in recorded) == [3, 3]
    assert all(rows and rows.endswith(".parquet") for _, rows in recorded)
    assert result.stats["done"] == 5 and result.errors["contact"].tolist() == ["R3C1-AVB"]
    pd.testing.assert_frame_equal(result.table, serial.table, check_exact=True)
    pd.testing.assert_frame_equal(load(out).table, load(tmp_path / "serial").table,
                                  check_exact=True)
    # every rows file has its JSON (a part is whole), the failed contact is in its group's
    # JSON, and the workers' marker is gone
    parts = _parts(out)
    assert {p["rows_file"] for p in parts.values()} == {r for _, r in recorded}
    assert sorted(c["contact"] for p in parts.values() for c in p["contacts"]) == \
        sorted(frame["contact"])
    assert not list((out / "parts").glob(".shared-*"))
    # a restart skips every contact, as after a client-written run
    again = run_bundle(manifest, case, scheduler=client, output=out)
    assert again.stats["skipped"] == 5
    pd.testing.assert_frame_equal(again.table, serial.table, check_exact=True)


def test_a_worker_that_does_not_see_the_directory_sends_its_rows_back(tmp_path):
    """A worker elsewhere (no marker with the client's token where it looks) writes nothing
    and returns the records with their rows: the client writes them. A rows file without its
    JSON (its worker wrote it, then the run died) is no part: ignored, then removed."""
    store = OutputDirectory(tmp_path / "out")
    token = store.share_with_workers()
    rec = {"contact": "A", "status": "done", "state": None,
           "table": {"columns": ["x"], "arrays": [pd.Series([1.0, 2.0]).to_numpy()]}}
    elsewhere = PartTarget(str(store.parts), store.new_stem(), "parquet", token + "-other")
    assert elsewhere.write([dict(rec)])[0]["table"] is not None
    assert not list(store.parts.glob("part-*"))
    here = PartTarget(str(store.parts), store.new_stem(), "parquet", token)
    back = here.write([dict(rec)])[0]
    assert back["table"] is None and back["rows_file"] == here.rows_file
    assert pd.read_parquet(store.parts / here.rows_file)["x"].tolist() == [1.0, 2.0]
    assert store.previous() == {}  # no JSON: not a part
    store.cleanup([])
    assert not list(store.parts.iterdir())


def test_the_marker_is_written_once_a_run_never_rewritten(tmp_path):
    """The engine asks for the marker at every wave while the workers read it for the groups
    of the earlier waves: it is written once, whole (its file, inode and time, the same after
    later asks), so that no worker reads it empty and sends its group's rows back (issue 28:
    one group of 62 contacts now and then, written by the client after the last result)."""
    store = OutputDirectory(tmp_path / "out")
    token = store.share_with_workers()
    marker = store.parts / f"{MARKER}{token}"
    first = marker.stat()
    for _ in range(5):
        assert store.share_with_workers() == token
    again = marker.stat()
    assert (again.st_ino, again.st_mtime_ns) == (first.st_ino, first.st_mtime_ns)
    assert marker.read_text(encoding="utf-8") == token
    assert sorted(p.name for p in store.parts.iterdir()) == [marker.name]  # no temporary left
    assert PartTarget(str(store.parts), store.new_stem(), "parquet", token).shared()
