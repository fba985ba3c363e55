"""A worker's group of contacts reads the small Parquet files of every ``tasks.READ_AHEAD``
contacts in a row, then computes those contacts' powers in a row, then their tables (issue 28:
fretwear.io.prefetch, tasks._power_step), each file read once; every record equals the
contact's computed alone (tasks.run_contact), bit for bit: the same read of the same bytes,
the same computation, the same warnings in the same order (here a StationarityWarning from the
power and a RangeWarning from the table, alone and together) and the same failures."""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import manifest_tasks, oscillator, write_bundle

from fretwear.bundle import tasks
from fretwear.io import prefetch, sources, streaming

pytest.importorskip("pyarrow")


def _tasks(tmp_path, count):
    warned = [k % 4 in (1, 2) for k in range(count)]  # the power's StationarityWarning
    extra = {"law.obstacle.COEF_USURE": [1e-14 if k % 4 in (1, 3) else None  # the table's
                                         for k in range(count)],
             "power.blocks": [5 if w else None for w in warned],
             "power.stationarity_threshold": [1e-6 if w else None for w in warned]}
    manifest, case = write_bundle(tmp_path, oscillator(), count, extra=extra)
    frame = pd.read_csv(manifest)
    frame.loc[5, "history"] = "histories/missing.parquet"
    frame.to_csv(manifest, index=False)
    (tmp_path / "histories" / "t6.parquet").write_bytes(b"PAR1 garbage PAR1")
    return manifest_tasks(manifest, case)


def test_a_group_reads_ahead_then_computes_powers_then_tables(tmp_path, monkeypatch):
    monkeypatch.setattr(sources, "_LAYOUTS", OrderedDict())
    group = _tasks(tmp_path, 20)
    alone = [tasks.run_contact(t) for t in group]  # the layout resolved by the first
    events = []
    for module, where in ((prefetch, "ahead"), (streaming, "own")):
        real = module.read_known_block
        monkeypatch.setattr(module, "read_known_block", lambda path, *a, _r=real, _w=where: (
            events.append(_w), _r(path, *a))[1])
    for name in ("wear_power", "wear_table_columns"):
        real = getattr(tasks, name)
        monkeypatch.setattr(tasks, name, lambda *a, _r=real, _n=name, **k: (
            events.append(_n), _r(*a, **k))[1])
    real_tables = tasks.sector_tables

    def tables(case, results, **k):  # the tables of a case's contacts made together
        made = real_tables(case, results, **k)
        events.extend(["wear_table_columns"] * (0 if made is None else len(made)))
        return made

    monkeypatch.setattr(tasks, "sector_tables", tables)
    monkeypatch.setattr(tasks, "READ_AHEAD", 8)
    batched = tasks.run_contacts(group)
    # every file tried ahead (the missing one (5) and the broken one (6) fail there, then in
    # their contact's own read: its error, as alone), every power, then every table (those of
    # a case's contacts together, tasks._batch_tables, in another order)
    batch = ["ahead"] * 8 + ["wear_power"] * 8 + ["wear_table_columns"] * 8
    assert events == batch[:22] + batch + ["ahead"] * 4 + ["wear_power"] * 4 \
        + ["wear_table_columns"] * 4
    assert [r["status"] for r in batched] == [r["status"] for r in alone]
    assert [r["status"] for r in batched].count("failed") == 2
    assert {w[0] for r in batched for w in r["warnings"]} == {"StationarityWarning",
                                                              "RangeWarning"}
    for a, b in zip(batched, alone, strict=True):
        assert (a["warnings"], a["error"]) == (b["warnings"], b["error"])
        if b["table"] is None:
            assert a["table"] is None
            continue
        assert a["table"]["columns"] == b["table"]["columns"]
        for x, y in zip(a["table"]["arrays"], b["table"]["arrays"], strict=True):
            np.testing.assert_array_equal(x, y)
        assert a["attrs"]["power"] == b["attrs"]["power"]
