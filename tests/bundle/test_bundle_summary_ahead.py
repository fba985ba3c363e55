"""The summary of the run's limit made in a thread at a bundle's end (outputs.assemble,
result.summarize_ahead), beside the dataset and the CSV files: the ranking ``summary.csv``
holds and ``BundleResult.summary(limit)`` gives is the one ``summarize`` makes of the whole
table read back afterwards (the independent computation: the table in memory, one piece), for
the run's limit, another limit and the contacts' own."""

from __future__ import annotations

from concurrent.futures import Future

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.bundle.result import summarize

pytest.importorskip("pyarrow")


def fresh(result, limit):
    """The ranking of the result's table read whole (not the one made at the run's end)."""
    return summarize(result.table, result.contacts, limit=limit, limit_m=None,
                     wall_thickness=None)


@pytest.mark.parametrize("limit", [None, 0.3])
def test_the_summary_made_ahead_is_the_tables(tmp_path, limit):
    manifest, case = write_bundle(tmp_path, oscillator(), 6,
                                  extra={"wall_thickness_m": [1.09e-3] * 6})
    out = tmp_path / "out"
    result = run_bundle(manifest, case, scheduler="serial", output=out, limit=limit)
    assert result.table_file is not None  # the route whose summary is made ahead
    assert not any(isinstance(r, Future) for r in result._summaries.values())  # waited for
    expected = fresh(result, limit)
    got = result.summary(limit)
    pd.testing.assert_frame_equal(got, expected, check_exact=True)
    assert got.attrs == expected.attrs
    written = pd.read_csv(out / "summary.csv")
    assert list(written["contact"]) == list(expected["contact"])
    assert written["depth"].to_numpy() == pytest.approx(expected["depth"].to_numpy(),
                                                         rel=1e-15)
    # another limit: made on demand from the table file
    other = 0.5 if limit is None else None
    pd.testing.assert_frame_equal(result.summary(other), fresh(result, other), check_exact=True)
