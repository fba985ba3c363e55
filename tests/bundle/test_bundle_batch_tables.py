"""A worker's group makes the tables of a case's contacts together (tasks._batch_tables,
fretwear.table.batch.sector_tables; issue 28) and every record equals the contact's computed
alone (tasks.run_contact, the reference) bit for bit: the table's arrays, the attrs, the
warnings in their order, the samples. A batch whose tables warn (one contact worn beyond the
relation's range) is made one contact at a time: the warning goes to that contact only."""

from __future__ import annotations

import numpy as np
import pytest
from bundle_helpers import manifest_tasks, oscillator, write_bundle

from fretwear.bundle import tasks

pytest.importorskip("pyarrow")


def _tasks(tmp_path, extra):
    count = len(next(iter(extra.values())))
    return manifest_tasks(*write_bundle(tmp_path, oscillator(), count, extra=extra))


def _same(records, alone):
    assert len(records) == len(alone)
    for a, b in zip(records, alone, strict=True):
        assert {k: a[k] for k in a if k not in ("table", "seconds", "attrs")} \
            == {k: b[k] for k in b if k not in ("table", "seconds", "attrs")}
        assert a["attrs"] == b["attrs"]
        assert a["table"]["columns"] == b["table"]["columns"]
        for x, y in zip(a["table"]["arrays"], b["table"]["arrays"], strict=True):
            assert x.dtype == y.dtype and x.tobytes() == y.tobytes()


def test_a_case_s_tables_made_together_equal_each_alone(tmp_path, monkeypatch):
    # two cases (8 and 3 sectors) mixed in the group, a StationarityWarning of the power in
    # some contacts (the power step's warnings kept in their records)
    sectors = [8 if k % 3 else 3 for k in range(12)]
    group = _tasks(tmp_path, {"sectors.count": sectors,
                              "power.stationarity_threshold": [1e-6 if k % 4 == 1 else None
                                                               for k in range(12)],
                              "power.blocks": [4 if k % 4 == 1 else None for k in range(12)]})
    alone = [tasks.run_contact(t) for t in group]
    made = []
    real = tasks.sector_tables
    monkeypatch.setattr(tasks, "sector_tables", lambda case, results, **k: (
        made.append(len(results)), real(case, results, **k))[1])
    monkeypatch.setattr(tasks, "READ_AHEAD", 6)
    records = tasks.run_contacts(group)
    assert sum(made) >= 8  # most tables made together
    assert any(r["warnings"] for r in records)
    _same(records, alone)


def test_a_batch_that_warns_is_made_one_contact_at_a_time(tmp_path):
    # the last contact (the largest power) wears the tube beyond the relation's range
    group = _tasks(tmp_path, {"law.mobile.COEF_USURE": [3e-12] * 8})
    alone = [tasks.run_contact(t) for t in group]
    assert [len(r["warnings"]) for r in alone] == [0] * 7 + [1]
    records = tasks.run_contacts(group)
    _same(records, alone)
    assert np.isnan(np.asarray(records[-1]["table"]["arrays"][
        records[-1]["table"]["columns"].index("depth_mobile_sector")])).any()


def test_a_worker_group_really_uses_the_batched_tables(tmp_path, monkeypatch):
    """Every contact of a group of one case takes its table from its batch (_table_step's
    ``made``), not made again alone: counting the calls of sector_tables passed with every
    batch thrown away (review of issue 28's afternoon round)."""
    group = manifest_tasks(*write_bundle(tmp_path, oscillator(), 8))
    used = []
    real = tasks._table_step

    def step(task, value, made=None):
        used.append(made is not None)
        return real(task, value, made)

    monkeypatch.setattr(tasks, "_table_step", step)
    tasks.run_contacts(group)
    assert sum(used) == 8
