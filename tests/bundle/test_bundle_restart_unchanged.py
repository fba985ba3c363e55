"""A restart that skips every contact into a directory holding the final files of the same
records writes none of them again (issue 28: the restart of 10^5 contacts rewrote every output,
88 s), and returns the same result; anything that changes what the files hold writes them
again: a limit, a manifest's identity cell, a contact recomputed, a file removed or edited.
Issue 29's guarantee stands: no rerun drops a result."""

from __future__ import annotations

import json

import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle

FILES = ("table.parquet", "dataset.zarr", "errors.csv", "warnings.csv", "summary.csv")


def _stamps(out):
    return {name: (out / name).stat().st_mtime_ns for name in FILES}


@pytest.fixture
def bundle(tmp_path):
    pytest.importorskip("zarr")
    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    out = tmp_path / "out"
    first = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    assert first.stats["done"] == 3
    return manifest, case, out, first


def test_an_unchanged_restart_writes_no_final_file_and_returns_the_same_result(bundle):
    manifest, case, out, first = bundle
    before = _stamps(out)
    again = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    assert again.stats["skipped"] == 3
    assert _stamps(out) == before  # not one final file written again
    # the table read back from table.parquet is the one assembled from the parts (Parquet
    # keeps every value and dtype: exact, same machine)
    pd.testing.assert_frame_equal(again.table, first.table, check_exact=True)
    pd.testing.assert_frame_equal(again.summary(), first.summary(), check_exact=True)
    pd.testing.assert_frame_equal(again.errors, first.errors)
    run = json.loads((out / "run.json").read_text())
    assert run["skipped"] == 3 and run["outputs"][-1] == "run.json"
    assert set(run["stamps"]) == set(FILES)
    # and a third run again (run.json rewritten by the second keeps the digest and stamps)
    third = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    assert _stamps(out) == before and third.stats["skipped"] == 3


def test_a_changed_limit_or_identity_writes_the_files_again(bundle):
    manifest, case, out, first = bundle
    before = _stamps(out)
    run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr",
               limit=0.2)
    after = _stamps(out)
    assert all(after[name] != before[name] for name in FILES)
    assert json.loads((out / "run.json").read_text())["limit"] == 0.2
    # a tube row changed in the manifest: the contacts' keys are the same (skipped), the
    # table's identity is not
    frame = pd.read_csv(manifest)
    frame.loc[0, "tube_row"] = 99
    frame.to_csv(manifest, index=False)
    again = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr",
                       limit=0.2)
    assert again.stats["skipped"] == 3
    assert _stamps(out)["table.parquet"] != after["table.parquet"]
    assert 99 in set(pd.read_parquet(out / "table.parquet")["tube_row"])


def test_a_removed_or_edited_final_file_is_written_again(bundle):
    manifest, case, out, first = bundle
    (out / "summary.csv").unlink()
    run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    assert (out / "summary.csv").is_file()
    assert list(pd.read_csv(out / "summary.csv")["contact"]) == list(first.summary()["contact"])
    # a user's edit of the table (its size and time change): written again from the parts
    cut = pd.read_parquet(out / "table.parquet").iloc[:5]
    cut.to_parquet(out / "table.parquet", index=False)
    again = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    pd.testing.assert_frame_equal(again.table, first.table, check_exact=True)
    pd.testing.assert_frame_equal(pd.read_parquet(out / "table.parquet"), first.table,
                                  check_exact=True)


def test_a_recomputed_contact_writes_the_files_again_and_drops_nothing(bundle):
    manifest, case, out, first = bundle
    before = _stamps(out)
    again = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr",
                       force=True)
    assert again.stats["done"] == 3
    assert all(_stamps(out)[name] != before[name] for name in FILES)
    pd.testing.assert_frame_equal(pd.read_parquet(out / "table.parquet"), first.table,
                                  check_exact=True)
