"""A worker's group of contacts reads the small Parquet files of every ``tasks.READ_AHEAD``
contacts in a row, then computes those contacts in a row (issue 28: fretwear.io.prefetch), each
file read once; every record equals the contact's computed alone (tasks.run_contact), bit for
bit: the same read of the same bytes, the same computation."""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import tasks
from fretwear.bundle.cases import build_task
from fretwear.bundle.manifest import read_manifest
from fretwear.io import prefetch, sources, streaming
from fretwear.workflows.case_files import load_case

pytest.importorskip("pyarrow")


def _tasks(tmp_path, count):
    manifest, case = write_bundle(tmp_path, oscillator(), count)
    man = read_manifest(manifest)
    base = load_case(case)
    base["_directory"] = str(man.directory)
    cache: dict = {}
    return [build_task(base, row, man.source, chunk_size=1_000_000, cache=cache)
            for row in man.rows]


def test_a_group_reads_its_files_ahead_in_batches_with_the_same_records(tmp_path, monkeypatch):
    monkeypatch.setattr(sources, "_LAYOUTS", OrderedDict())
    monkeypatch.setattr(streaming, "_LAYOUTS", sources._LAYOUTS)
    group = _tasks(tmp_path, 20)
    alone = [tasks.run_contact(t) for t in group]  # the layout resolved by the first
    events = []
    for module, where in ((prefetch, "ahead"), (streaming, "own")):
        real = module.read_known_block
        monkeypatch.setattr(module, "read_known_block", lambda path, *a, _r=real, _w=where: (
            events.append(_w), _r(path, *a))[1])
    real_table = tasks.wear_table_columns
    monkeypatch.setattr(tasks, "wear_table_columns", lambda *a, **k: (
        events.append("table"), real_table(*a, **k))[1])
    monkeypatch.setattr(tasks, "READ_AHEAD", 8)
    batched = tasks.run_contacts(group)
    assert events == (["ahead"] * 8 + ["table"] * 8) * 2 + ["ahead"] * 4 + ["table"] * 4
    assert [r["status"] for r in batched] == ["done"] * 20
    for a, b in zip(batched, alone, strict=True):
        assert a["table"]["columns"] == b["table"]["columns"]
        for x, y in zip(a["table"]["arrays"], b["table"]["arrays"], strict=True):
            np.testing.assert_array_equal(x, y)
        assert (a["warnings"], a["attrs"]["power"]) == (b["warnings"], b["attrs"]["power"])
