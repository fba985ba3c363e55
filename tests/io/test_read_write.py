"""Round trips through every reader and writer, units documented in the files, format sniffing.

Reference values: the analytic history of ``iohelpers.analytic_history`` (closed-form signals);
every native writer stores doubles exactly, so a read-back must be bit-identical.
"""

from __future__ import annotations

import json
import shutil
import sys

import numpy as np
import pandas as pd
import pytest
from iohelpers import FIXTURES, analytic_history, assert_same_history

from fretwear.errors import FormatError, InputError, KeywordError, UnitsWarning
from fretwear.history import UNITS, ContactHistory
from fretwear.io import FORMATS, guess_format, read_history, write_history
from fretwear.io.aster import read_aster_table

NATIVE = {"csv": "h.csv", "parquet": "h.parquet", "hdf5": "h.h5", "netcdf": "h.nc",
          "npz": "h.npz", "aster": "h.resu"}


@pytest.mark.parametrize("fmt", sorted(NATIVE))
def test_round_trip_every_writer_and_reader(tmp_path, history, fmt):
    path = write_history(history, tmp_path / NATIVE[fmt])
    assert guess_format(path) == fmt
    back = read_history(path)
    assert_same_history(history, back)  # exact: shortest repr / %.16E / binary doubles
    assert back.metadata["format"] == fmt
    # Code_Aster tables keep their name in the title only (the stem names the history)
    assert back.name == ("h" if fmt == "aster" else "N12")
    assert back.metadata["unit_factors"] == {ch: 1.0 for ch in history.channels}
    if fmt != "aster":  # Code_Aster tables carry the name in the title only
        assert back.metadata["case"] == "analytic" and back.metadata["node"] == "N12"


def test_round_trip_required_channels_only(tmp_path):
    h = ContactHistory(time=[0.0, 5e-4, 1e-3], normal_force=[0.0, 1.0, 0.0], vt1=[1.0, 2.0, 3.0],
                       vt2=[0.0, 0.0, 0.0])  # a plausible 0.5 ms step (no UnitsWarning)
    for fmt, fname in NATIVE.items():
        back = read_history(write_history(h, tmp_path / fname))
        assert back.channels == ("time", "normal_force", "vt1", "vt2"), fmt
        assert_same_history(h, back)


def test_units_are_documented_in_every_native_file(tmp_path, history):
    import h5py
    import netCDF4
    import pyarrow.parquet as pq

    csv_text = write_history(history, tmp_path / "h.csv").read_text()
    assert "#   normal_force [N]:" in csv_text and "#   vt1 [m/s]:" in csv_text
    schema = pq.read_schema(write_history(history, tmp_path / "h.parquet"))
    assert schema.field("dy").metadata[b"units"] == b"m"
    with h5py.File(write_history(history, tmp_path / "h.h5"), "r") as f:
        assert f["history/time"].attrs["units"] == "s"
        assert f["history"].attrs["name"] == "N12"
    with netCDF4.Dataset(write_history(history, tmp_path / "h.nc")) as ds:
        assert ds.variables["ft1"].units == "N"
        assert ds.dimensions["time"].size == len(history)
    with np.load(write_history(history, tmp_path / "h.npz")) as f:
        assert json.loads(str(f["__fretwear__"]))["units"] == {
            ch: UNITS[ch] for ch in history.channels}


def test_hdf5_group_option_and_aster_table_format(tmp_path, history):
    path = write_history(history, tmp_path / "h.hdf5", group="shocks/N12")
    assert_same_history(history, read_history(path, group="shocks/N12"))
    assert_same_history(history, read_history(path))  # the only group with datasets
    path = write_history(history, tmp_path / "h.tab", table_format="ASTER")
    frame = read_aster_table(path)
    assert frame.attrs["format"] == "ASTER" and frame.attrs["title"] == "N12"
    assert list(frame.columns) == ["INST", "FN", "FT1", "FT2", "VN", "VT1", "VT2", "DYLOC",
                                   "DZLOC", "VINT13"]
    assert_same_history(history, read_history(path))


def test_csv_float_format_rounds_to_the_printed_precision(tmp_path, history):
    back = read_history(write_history(history, tmp_path / "h.csv", float_format="%.6e"))
    expected = np.array([float("%.6e" % v) for v in history.normal_force])  # noqa: UP031
    np.testing.assert_array_equal(back.normal_force, expected)


def test_csv_default_is_exact_without_pyarrow(tmp_path, history, monkeypatch):
    """The pandas fallback writes the same exact values as the pyarrow writer."""
    fast = write_history(history, tmp_path / "fast.csv").read_text()
    for module in ("pyarrow", "pyarrow.csv"):
        monkeypatch.setitem(sys.modules, module, None)
    slow = write_history(history, tmp_path / "slow.csv")
    assert_same_history(history, read_history(slow))
    assert fast.splitlines()[:15] == slow.read_text().splitlines()[:15]  # same header


def test_units_declared_by_binary_files_are_converted(tmp_path):
    """A file written in mm and kN (units attributes) is read back in SI."""
    import h5py
    import netCDF4

    t = np.array([0.0, 1.0, 2.0])
    with h5py.File(tmp_path / "mm.h5", "w") as f:
        for name, values, unit in [("INST", t, "ms"), ("FN", [0.0, 2.0, 4.0], "kN"),
                                   ("VT1", [1.0, 2.0, 3.0], "mm/s"),
                                   ("VT2", [0.0, 0.0, 0.0], "mm/s")]:
            f.create_dataset(name, data=values).attrs["units"] = unit
    h = read_history(tmp_path / "mm.h5")
    np.testing.assert_allclose(h.time, t * 1e-3, rtol=1e-15)
    np.testing.assert_allclose(h.normal_force, [0.0, 2000.0, 4000.0], rtol=1e-15)
    np.testing.assert_allclose(h.vt1, [1e-3, 2e-3, 3e-3], rtol=1e-15)
    assert h.metadata["units"] == {"time": "ms", "normal_force": "kN", "vt1": "mm/s",
                                   "vt2": "mm/s"}
    with netCDF4.Dataset(tmp_path / "cf.nc", "w") as ds:
        ds.createDimension("time", 3)
        for name, values, unit in [("time", t, "seconds since 2026-01-01"),
                                   ("fn", [0.0, 2.0, 4.0], "daN"), ("vt1", [1.0, 2.0, 3.0], "m/s"),
                                   ("vt2", [0.0, 0.0, 0.0], "m/s")]:
            var = ds.createVariable(name, "f8", ("time",))
            var.units = unit
            var[:] = values
    # CF "seconds since ...": read in s, so the 1 s step is flagged under its declared unit
    with pytest.warns(UnitsWarning, match=r".*median sampling step 1 s \(read in 'seconds'\)"):
        h = read_history(tmp_path / "cf.nc")
    np.testing.assert_array_equal(h.time, t)
    np.testing.assert_allclose(h.normal_force, [0.0, 20.0, 40.0], rtol=1e-15)


def test_sniffing_binary_formats_whatever_the_suffix(tmp_path, history):
    for fmt, fname in NATIVE.items():
        if fmt in ("csv", "aster"):
            continue
        path = write_history(history, tmp_path / fname)
        odd = tmp_path / f"{fmt}.bin"
        shutil.copy(path, odd)
        assert guess_format(odd) == fmt
        assert_same_history(history, read_history(odd))


@pytest.mark.parametrize("suffix", [".resu", ".txt", ".tab", ".csv", ".dat", ""])
def test_code_aster_tables_recognised_by_content(tmp_path, suffix):
    for fixture in ("impr_table_tableau.txt", "impr_table_aster.resu"):
        path = tmp_path / f"table{suffix}"
        shutil.copy(FIXTURES / fixture, path)
        assert guess_format(path) == "aster", fixture


@pytest.mark.parametrize("suffix", [".txt", ".csv"])
def test_tableau_with_a_user_title_and_a_node_column_is_recognised(tmp_path, suffix):
    # IMPR_TABLE(FORMAT='TABLEAU', TITRE='...'): no Code_Aster words in the '#' block, a K8
    # column of node names; the values are the literals of fixtures/impr_table_tableau.txt.
    lines = (FIXTURES / "impr_table_tableau.txt").read_text().splitlines()
    path = tmp_path / f"choc{suffix}"
    path.write_text("\n".join(["#", "#Choc du noeud N12", "#", *lines[3:]]) + "\n")
    assert guess_format(path) == "aster"
    h = read_history(path)
    assert h.normal_force.tolist() == [0.0, 12.5, 25.0, 12.5, 0.0]
    assert h.metadata["ignored_columns"] == ["NOEUD"]
    # read as blank-separated text, the unused node column is ignored too
    assert read_history(path, format="csv").normal_force.tolist() == h.normal_force.tolist()


# samples 1 s apart: the coarse step is flagged (likely ms), irrelevant to the format guess
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_numeric_text_with_a_comment_block_stays_delimited_text(tmp_path):
    # numpy.savetxt(..., fmt="%.5E", header="t fn vt1 vt2"): the names are in the comment, the
    # line after it is data, so it is not a Code_Aster table.
    path = tmp_path / "saved.txt"
    np.savetxt(path, [[0.0, 1.0, 0.5, 0.0], [1.0, 1.0, 0.5, 0.0], [2.0, 1.0, 0.5, 0.0]],
               fmt="%.5E", header="t fn vt1 vt2")
    assert guess_format(path) == "csv"
    h = read_history(path, columns={0: "time", 1: "fn", 2: "vt1", 3: "vt2"})
    assert h.time.tolist() == [0.0, 1.0, 2.0]


# the first frame's samples are 1 s apart: the coarse step is flagged (likely ms), irrelevant
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_in_memory_tables_use_aliases_and_units_without_modifying_them():
    frame = pd.DataFrame({"INST": [0.0, 1.0], "FN": [1.0, 2.0], "VT1": [3.0, 4.0],
                          "VT2": [0.0, 0.0]})
    before = frame.copy()
    h = read_history(frame, units={"force": "kN", "velocity": "mm/s"})
    pd.testing.assert_frame_equal(frame, before)
    np.testing.assert_array_equal(h.normal_force, [1000.0, 2000.0])
    np.testing.assert_allclose(h.vt1, [3e-3, 4e-3], rtol=1e-15)
    arrays = {"t": np.array([0.0, 1.0]), "fn": np.array([1.0, 2.0]), "vt1": np.zeros(2),
              "vt2": np.zeros(2)}
    h = read_history(arrays, units={"time": "ms"})
    np.testing.assert_array_equal(arrays["t"], [0.0, 1.0])
    np.testing.assert_array_equal(h.time, [0.0, 1e-3])


def test_write_errors_name_the_culprit(tmp_path, history):
    with pytest.raises(FormatError, match=r"suffix '\.xyz'.*'\.csv'"):
        write_history(history, tmp_path / "h.xyz")
    with pytest.raises(FormatError, match="'aster-function' is read-only"):
        write_history(history, tmp_path / "h.txt", format="aster-function")
    with pytest.raises(KeywordError, match=r"\['compression'\] unknown for the 'csv' writer"):
        write_history(history, tmp_path / "h.csv", compression="gzip")
    with pytest.raises(FormatError, match="unknown format 'xlsx'"):
        write_history(history, tmp_path / "h.csv", format="xlsx")


def test_failed_write_leaves_the_previous_file(tmp_path, history):
    """Atomic output: a writer failing midway does not truncate the existing file."""
    path = write_history(history, tmp_path / "h.csv")
    before = path.read_bytes()
    with pytest.raises(Exception, match="float_format"):
        write_history(analytic_history(n=5), path, float_format="%q")
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["h.csv"]


def test_registry_lists_every_family():
    assert set(FORMATS) == {"csv", "parquet", "hdf5", "netcdf", "npz", "aster", "aster-function"}
    assert {s for f in FORMATS.values() for s in f.suffixes} >= {
        ".csv", ".txt", ".dat", ".parquet", ".pq", ".h5", ".hdf5", ".nc", ".npz"}


def test_gzip_text_formats_round_trip_and_are_sniffed(tmp_path, history):
    """Compressed CSV and Code_Aster tables are written by suffix and read by content."""
    import gzip

    for fname in ("h.csv.gz", "h.resu.gz"):
        path = write_history(history, tmp_path / fname)
        assert path.read_bytes()[:2] == b"\x1f\x8b"
        assert_same_history(history, read_history(path))
        odd = tmp_path / f"{fname}.bin"
        shutil.copy(path, odd)
        assert guess_format(odd) == ("csv" if "csv" in fname else "aster")
    # a gzipped Code_Aster fixture, and chunked reading of a gzipped CSV
    gz = tmp_path / "table.gz"
    gz.write_bytes(gzip.compress((FIXTURES / "impr_table_tableau.txt").read_bytes()))
    assert read_history(gz).normal_force.tolist() == [0.0, 12.5, 25.0, 12.5, 0.0]
    from fretwear.io import iter_history_chunks

    chunks = list(iter_history_chunks(tmp_path / "h.csv.gz", chunk_size=50))
    assert [len(c) for c in chunks] == [50, 50, 50, 50, 5]
    with pytest.raises(FormatError, match=r"gzip \(.gz\) is for the text formats"):
        write_history(history, tmp_path / "h.parquet.gz")


def test_default_name_is_the_stem_without_gz(tmp_path, history):
    # A Code_Aster table keeps no history name: the file's stem is used, '.gz' dropped too.
    for suffix in (".resu", ".resu.gz"):
        out = write_history(history.replace(name=""), tmp_path / f"n12{suffix}")
        assert read_history(out).name == "n12"


@pytest.mark.parametrize("codec, stored", [("lz4", "LZ4"), ("snappy", "SNAPPY"),
                                           ("zstd", "ZSTD"), (None, "UNCOMPRESSED")])
def test_parquet_codec_and_plain_pages(tmp_path, history, codec, stored):
    """Every codec reads back the same doubles (binary, lossless); the pages are plain float64
    (no dictionary: the samples of a signal seldom repeat); lz4 is the default."""
    import pyarrow.parquet as pq

    options = {} if codec == "lz4" else {"compression": codec}
    path = write_history(history, tmp_path / "h.parquet", **options)
    assert_same_history(history, read_history(path))
    meta = pq.ParquetFile(path).metadata
    for i in range(meta.num_columns):
        column = meta.row_group(0).column(i)
        assert column.compression == stored
        assert "RLE_DICTIONARY" not in column.encodings and column.dictionary_page_offset is None


def test_parquet_unknown_codec_is_refused_before_writing(tmp_path, history):
    target = tmp_path / "h.parquet"
    with pytest.raises(InputError, match=r"compression='lzma'.*'lz4', 'snappy'"):
        write_history(history, target, compression="lzma")
    assert not target.exists() and list(tmp_path.iterdir()) == []
