"""The final table of a run with an output directory is read from the parts in one pass
(issue 28: the client no longer holds every contact's rows until the end): it is the table
the contacts' own rows give, assembled as before (``concat_packed`` of each contact's latest
rows, the manifest's order), whatever order the parts were written in and whichever earlier
rows a later part superseded."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.bundle.store import OutputDirectory
from fretwear.bundle.tasks import concat_packed


def _rows(n: int, scale: float) -> dict:
    return {"columns": ["instant", "sector", "volume"],
            "arrays": [np.arange(n, dtype=float), np.arange(n, dtype=np.int64),
                       scale * np.linspace(0.0, 1.0, n)]}


def _record(contact: str, table: dict) -> dict:
    return {"contact": contact, "key": contact, "status": "done", "table": table,
            "warnings": [], "error": None, "samples": 1, "seconds": 0.0, "attrs": None,
            "state": None}


def test_the_parts_read_in_one_pass_give_the_latest_rows_in_the_manifests_order(tmp_path):
    pytest.importorskip("pyarrow")
    store = OutputDirectory(tmp_path / "out")
    a, b_old, b_new, c = _rows(2, 1.0), _rows(3, 2.0), _rows(3, 5.0), _rows(1, 7.0)
    store.write_part([_record("A", a), _record("B", b_old)])
    latest = [_record("B", b_new), _record("C", c)]
    store.write_part(latest)
    previous = store.previous()  # A in the first part, B (recomputed) and C in the second
    order = ["C", "A", "B"]
    got = store.ordered_rows([previous[k] for k in order], order)
    # the independent assembly: each contact's own rows, one under the other in that order
    expected = concat_packed(order, [c, a, b_new])
    pd.testing.assert_frame_equal(got, expected)
    assert got.loc[got["contact"] == "B", "volume"].tolist() == [0.0, 2.5, 5.0]  # not b_old


def test_csv_parts_are_left_to_the_packed_assembly(tmp_path):
    store = OutputDirectory(tmp_path / "out", table_format="csv")
    store.write_part([_record("A", _rows(2, 1.0))])
    assert store.ordered_rows(list(store.previous().values()), ["A"]) is None


@pytest.mark.parametrize("fmt", ["parquet", "csv"])
def test_a_run_with_an_output_directory_gives_the_table_of_a_run_without(tmp_path, fmt):
    """Same inputs, same process: the two tables are compared bit for bit (within one
    process and machine)."""
    pytest.importorskip("pyarrow")
    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    kept = run_bundle(manifest, case, scheduler="serial")
    written = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out",
                         table_format=fmt, part_size=1)
    pd.testing.assert_frame_equal(written.table, kept.table)
    assert list(written.table["contact"].unique()) == list(kept.table["contact"].unique())
