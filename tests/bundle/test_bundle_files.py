"""The bundle's own files: CSV reals in the table layer's one float format (exact), and Parquet
without pyarrow refused by fretwear._optional naming the extra (issue 10)."""

from __future__ import annotations

import sys

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.manifest import read_manifest
from fretwear.bundle.store import read_frame, write_frame
from fretwear.errors import MissingDependencyError
from fretwear.table.schema import FLOAT_FORMAT


def test_csv_outputs_use_the_table_float_format_and_round_trip(tmp_path):
    # 0.1 + 0.2 and 1/3 need all 17 significant digits to come back
    frame = pd.DataFrame({"contact": ["a", "b"], "depth": [0.1 + 0.2, 1.0 / 3.0]})
    path = write_frame(frame, tmp_path / "t.csv", "csv")
    rows = path.read_text(encoding="utf-8").splitlines()
    assert rows[1] == "a," + FLOAT_FORMAT % (0.1 + 0.2)
    back = read_frame(path)
    assert np.array_equal(back["depth"].to_numpy(), frame["depth"].to_numpy())


def test_parquet_without_pyarrow_names_the_formats_extra(tmp_path, monkeypatch):
    manifest = tmp_path / "manifest.parquet"
    pd.DataFrame({"contact": ["a"], "history": ["a.csv"]}).to_parquet(manifest, index=False)
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    with pytest.raises(MissingDependencyError, match=r"pip install 'fretwear\[formats\]'"):
        read_manifest(manifest)
    with pytest.raises(MissingDependencyError, match=r"csv table format .*fretwear\[formats\]"):
        write_frame(pd.DataFrame({"x": [1.0]}), tmp_path / "t.parquet", "parquet")
    assert not (tmp_path / "t.parquet").exists()


def test_a_run_in_another_format_replaces_the_earlier_outputs(tmp_path):
    """The same output directory run again with --table-format csv and --dataset-format netcdf:
    the contacts are skipped (the formats are not part of a contact's key), the table and the
    dataset are written in the new formats, and the earlier table.parquet and dataset.zarr,
    now stale, are gone; the CSV table holds the rows of the Parquet one."""
    from bundle_helpers import oscillator, write_bundle

    from fretwear.bundle import run_bundle

    pytest.importorskip("xarray")
    pytest.importorskip("zarr")
    pytest.importorskip("netCDF4")
    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    out = tmp_path / "out"
    first = run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
    assert (out / "table.parquet").is_file() and (out / "dataset.zarr").is_dir()
    before = read_frame(out / "table.parquet")
    second = run_bundle(manifest, case, scheduler="serial", output=out, table_format="csv",
                        dataset_format="netcdf")
    assert first.stats["done"] == 3 and second.stats["skipped"] == 3
    assert sorted(p.name for p in out.iterdir() if p.name.startswith(("table", "dataset"))) \
        == ["dataset.nc", "table.csv"]
    after = read_frame(out / "table.csv")
    assert after.shape == before.shape and list(after.columns) == list(before.columns)
    np.testing.assert_allclose(after["depth_mobile"], before["depth_mobile"], rtol=1e-15)


def test_files_fretwear_did_not_write_are_never_removed(tmp_path):
    """A directory holding the user's own table.csv and dataset.nc (no earlier run.json says
    fretwear wrote them) keeps them when a bundle writes its Parquet table and Zarr dataset
    there; so does a directory whose run.json predates the record of outputs."""
    from bundle_helpers import oscillator, write_bundle

    from fretwear.bundle import run_bundle

    pytest.importorskip("zarr")
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    for name, run_json in (("user", None), ("older", '{"done": 2}')):
        out = tmp_path / name
        out.mkdir()
        (out / "table.csv").write_text("my own table\n")
        (out / "dataset.nc").write_bytes(b"my own data")
        if run_json is not None:
            (out / "run.json").write_text(run_json)
        run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="zarr")
        assert (out / "table.csv").read_text() == "my own table\n"
        assert (out / "dataset.nc").read_bytes() == b"my own data"
        assert (out / "table.parquet").is_file() and (out / "dataset.zarr").is_dir()
        import json

        assert json.loads((out / "run.json").read_text())["outputs"][:2] == [
            "table.parquet", "dataset.zarr"]


def test_a_run_without_rows_removes_the_earlier_runs_dataset(tmp_path):
    """A run whose every contact fails writes an empty table and no dataset: the dataset an
    earlier run wrote there (recorded in its run.json) is removed, not left beside it."""
    from bundle_helpers import oscillator, write_bundle

    from fretwear.bundle import run_bundle

    pytest.importorskip("netCDF4")
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    out = tmp_path / "out"
    run_bundle(manifest, case, scheduler="serial", output=out, dataset_format="netcdf")
    assert (out / "dataset.nc").is_file()
    # other contacts (an earlier contact failing now would keep its rows: stale)
    frame = pd.read_csv(manifest).assign(history="histories/missing.parquet")
    frame["contact"] = frame["contact"] + "-new"
    failed = run_bundle(frame, case, scheduler="serial", output=out, dataset_format="netcdf")
    assert failed.stats["failed"] == 2 and not len(failed.table)
    assert not (out / "dataset.nc").exists()


@pytest.mark.parametrize("name", ["NA", "None", "nan", "NULL"])
def test_a_restart_from_csv_parts_keeps_a_contact_named_like_a_missing_value(tmp_path, name):
    """Contact ids are text: one named NA (or None, nan, NULL) read back from CSV parts keeps
    its rows (pandas read it as missing: the restart counted it skipped and dropped its rows),
    and a missing number in the wear columns still reads as NaN."""
    from fretwear.bundle import run_bundle
    from fretwear.bundle.store import OutputDirectory

    frame = pd.DataFrame({"contact": [name, "B"], "power.value_W": [1e-3, 2e-3]})
    case = tmp_path / "base.toml"
    case.write_text('[law]\nmobile = { COEF_USURE = 1e-17 }\n[geometry]\ncontact_type = '
                    '"TUBE_BAV"\nmobile_radius_m = 9.525e-3\nobstacle_width_m = 12.7e-3\n'
                    '[time]\ninstants = [1, 2]\nunit = "year"\n')
    out = tmp_path / "out"
    first = run_bundle(frame, case, scheduler="serial", output=out, table_format="csv")
    again = run_bundle(frame, case, scheduler="serial", output=out, table_format="csv")
    assert again.stats["skipped"] == 2
    pd.testing.assert_frame_equal(again.table, first.table, check_exact=True)
    assert (again.table["contact"] == name).sum() == (first.table["contact"] == name).sum() == 2
    store = OutputDirectory(out, table_format="csv")
    part = read_frame(store.parts / store.previous()[name]["rows_file"])
    assert part["contact"].tolist().count(name) == 2
    assert part.drop(columns="contact").isna().any(axis=None) == \
        first.table.drop(columns=["contact", "tube_row", "tube_column", "support", "node",
                                  "history"]).isna().any(axis=None)


def test_the_csv_writer_writes_what_pandas_writes_byte_for_byte(tmp_path):
    """csv_table.write_csv (each column's distinct values formatted once, lines joined by pyarrow;
    issue 28: the CSV table of 20 000 contacts took 57 s) writes the bytes of
    ``DataFrame.to_csv(index=False, float_format=FLOAT_FORMAT)``: floats with NaN, inf, -0.0
    and 0.0 (distinct bits, distinct texts), 0.1 + 0.2 and 1/3 (17 digits), integers, nullable
    integers with <NA>, booleans, texts with a comma, a quote, a new line, empty and missing
    ones, a column of nothing; a column pandas formats its own way (dates, floats among
    objects) leaves the whole frame to pandas, with the same bytes."""
    from fretwear.bundle.csv_table import write_csv

    pytest.importorskip("pyarrow")
    frame = pd.DataFrame({
        "contact": ["a", "b,c", 'say "x"', "line\nbreak", "", None, "a"],
        "tube_row": np.arange(7, dtype=np.int64) - 3,
        "sector": pd.array([1, None, 3, 4, None, 2, 1], dtype="Int64"),
        "flag": [True, False, True, True, False, False, True],
        "depth": [0.1 + 0.2, 1.0 / 3.0, -0.0, 0.0, np.nan, np.inf, -np.inf],
        "volume": [1e-300, 5e-324, 1.0, 1.0, 2.5, -7.0, 1e300],
        "node": [None] * 7,
    })
    for k, part in enumerate((frame, frame.iloc[:0], frame.iloc[2:5], frame[["depth"]],
                              frame.assign(support=pd.to_datetime(["2020-01-01"] * 7)),
                              frame.assign(node=[1.5, None, "x", 2, 3, 4, 5]),
                              pd.DataFrame({"t": ["cr\rx", "a b", "q'", "\t", ","],
                                            "u": [1, 2, 3, 4, 5]}))):
        ours, theirs = tmp_path / f"ours{k}.csv", tmp_path / f"theirs{k}.csv"
        written = write_csv(part, ours)
        part.to_csv(theirs, index=False, float_format=FLOAT_FORMAT)
        if not written:  # dates, floats among objects: pandas writes them (write_frame)
            assert k in (4, 5)
            write_frame(part, ours, "csv")
        assert ours.read_bytes() == theirs.read_bytes(), k
    back = read_frame(tmp_path / "ours0.csv")
    assert np.array_equal(np.signbit(back["depth"].to_numpy()),
                          np.signbit(frame["depth"].to_numpy()))


def test_the_csv_writer_quotes_texts_as_pandas_does(tmp_path):
    """Texts that need quotes (a comma, a quote, CR, LF, several, quotes doubled) are written
    by csv_table.write_csv (quoting done without the csv module since issue 28 point 2) with
    the bytes of ``DataFrame.to_csv`` (the independent writer), in a column of one and of
    several."""
    from fretwear.bundle.csv_table import write_csv

    pytest.importorskip("pyarrow")
    texts = ["plain", "a,b", '"', '""', "cr\rhere", "crlf\r\n", 'x,"y"\nz', " sp ", "'q'",
             "tab\tx", "é,ü"]
    for k, part in enumerate((pd.DataFrame({"t": texts, "n": range(len(texts))}),
                              pd.DataFrame({"t": texts}))):
        ours, theirs = tmp_path / f"ours{k}.csv", tmp_path / f"theirs{k}.csv"
        assert write_csv(part, ours)
        part.to_csv(theirs, index=False, float_format=FLOAT_FORMAT)
        assert ours.read_bytes() == theirs.read_bytes(), k


def test_the_csv_writer_texts_made_by_pyarrow_are_pandas_bytes(tmp_path):
    """The texts csv_table.write_csv has pyarrow make (NumPy integers of every width and sign,
    extremes included; text columns of pandas' ``str`` and ``string`` dtypes, pyarrow or Python
    storage, none of whose values the csv module quotes: ids, paths, non-ASCII, empty and
    missing ones; issue 28: the summary's 10^5 ids, paths and ranks) have the bytes of
    ``DataFrame.to_csv`` (the independent writer); a column with one value to quote is
    written by the loop, same bytes."""
    from fretwear.bundle.csv_table import write_csv

    pytest.importorskip("pyarrow")
    n = 6
    frame = pd.DataFrame({
        "rank": np.arange(1, n + 1),
        "i8": np.array([-128, 127, 0, -1, 5, 5], dtype=np.int8),
        "u64": np.array([2**64 - 1, 0, 1, 7, 7, 9], dtype=np.uint64),
        "i64": np.array([-2**63, 2**63 - 1, 0, -10, 10, 3], dtype=np.int64),
        "contact": pd.array(["c1", "c2", None, "é日本", "", "c1"], dtype="str"),
        "path": pd.array(["/a/b.parquet", "C:\\x y.h5", "c", None, "d", "e"],
                         dtype="string[python]"),
        "note": pd.array(["", "depth beyond", None, "x", "y", "x"], dtype="string"),
        "quoted": pd.array(["a", "b,c", "d", None, "e", "a"], dtype="str"),
    })
    for k, part in enumerate((frame, frame.iloc[:0], frame.drop(columns="quoted"))):
        ours, theirs = tmp_path / f"ours{k}.csv", tmp_path / f"theirs{k}.csv"
        assert write_csv(part, ours)
        part.to_csv(theirs, index=False, float_format=FLOAT_FORMAT)
        assert ours.read_bytes() == theirs.read_bytes(), k
