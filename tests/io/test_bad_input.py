"""Every bad input gives a clear error naming the culprit (file, column, row, option) and the fix.

Each file below is written by hand with one defect; the expected message quotes the defect.
"""

from __future__ import annotations

import sys
import warnings

import numpy as np
import pytest
from iohelpers import analytic_history

from fretwear.errors import (
    FormatError,
    HistoryError,
    InputError,
    KeywordError,
    MissingDependencyError,
    UnitsWarning,
)
from fretwear.io import guess_format, read_history, write_history

GOOD = "INST,FN,VT1,VT2\n0.0,1.0,0.1,0.0\n0.1,2.0,0.1,0.0\n0.2,0.0,0.1,0.0\n"


def csv(tmp_path, text, name="h.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_missing_required_column_lists_columns_and_aliases(tmp_path):
    path = csv(tmp_path, "INST,FN,VT1\n0,1,0\n1,2,0\n")
    with pytest.raises(FormatError) as err:
        read_history(path)
    msg = str(err.value)
    assert "h.csv" in msg and "required channel(s) ['vt2']" in msg
    assert "columns found: ['INST', 'FN', 'VT1']" in msg
    assert "vt2: vt2, v_t2, sliding_velocity_2, tangential_velocity_2" in msg and "vint12" in msg
    assert "columns={'<column>': 'vt2'}" in msg


def test_non_increasing_time_names_the_row_and_the_columns_used(tmp_path):
    path = csv(tmp_path, "INST,FN,VT1,VT2\n0.0,1,0,0\n0.2,1,0,0\n0.1,1,0,0\n")
    with pytest.raises(HistoryError, match=r"h.csv: .*'time' is not strictly increasing at row 2 "
                                           r".*\[columns used: time <- 'INST'"):
        read_history(path)


def test_nan_and_empty_cells_name_the_column_and_row(tmp_path):
    path = csv(tmp_path, "INST,FN,VT1,VT2\n0.0,1,0,0\n0.1,,0,0\n0.2,1,0,0\n")
    with pytest.raises(HistoryError, match=r"column 'FN' \(channel 'normal_force'\) has a missing "
                                           r"or non-finite value \(nan\) at data row 1"):
        read_history(path)
    path = csv(tmp_path, "INST,FN,VT1,VT2\n0.0,1,0,0\n0.1,1,nan,0\n", name="n.csv")
    with pytest.raises(HistoryError, match=r"column 'VT1' \(channel 'vt1'\).*data row 1"):
        read_history(path)


def test_non_numeric_cell_names_column_and_row(tmp_path):
    path = csv(tmp_path, "INST,FN,VT1,VT2\n0.0,1,0,0\n0.1,1,0,0\n0.2,abc,0,0\n")
    with pytest.raises(FormatError, match=r"column 'FN' holds 'abc' at data row 2"):
        read_history(path)


def test_negative_normal_force_names_row_time_and_sign_hint(tmp_path):
    path = csv(tmp_path, "INST,FN,VT1,VT2\n0.0,1,0,0\n0.1,-3.5,0,0\n")
    with pytest.raises(HistoryError, match=r"'normal_force' is negative \(-3.5 N\) at row 1 "
                                           r"\(t = 0.1 s\).*sign convention.*FN <- 'FN'|"
                                           r"normal_force <- 'FN'"):
        read_history(path)


def test_ambiguous_aliases_name_both_columns(tmp_path):
    path = csv(tmp_path, "INST,FN,VT1,VT2,VINT1\n0,1,0,0,1\n1,2,0,0,2\n")
    with pytest.raises(FormatError, match=r"columns 'FN' \(#2\) and 'VINT1' \(#5\) both stand "
                                          r"for the channel 'normal_force'"):
        read_history(path)
    path = csv(tmp_path, "t,fn,vt1,vt2,FN\n0,1,0,0,1\n1,2,0,0,2\n", name="dup.csv")
    with pytest.raises(FormatError, match=r"'fn' \(#2\) and 'FN' \(#5\)"):
        read_history(path)


# the last read (units given) has samples 1 s apart: flagged (likely ms), irrelevant here
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_unknown_units_list_the_known_ones(tmp_path):
    path = csv(tmp_path, GOOD)
    with pytest.raises(KeywordError, match=r"unknown force unit 'tonnes' for channel "
                                           r"'normal_force'.*known force units: 'N', 'mN'"):
        read_history(path, units={"force": "tonnes"})
    with pytest.raises(KeywordError, match=r"unknown velocity unit 'knots'.*'<length>/<time>'"):
        read_history(path, units={"velocity": "knots"})
    with pytest.raises(KeywordError, match=r"unknown key 'mass'.*'length', 'force'"):
        read_history(path, units={"mass": "kg"})
    path = csv(tmp_path, "t [fortnight],fn,vt1,vt2\n0,1,0,0\n1,1,0,0\n", name="hdr.csv")
    with pytest.raises(KeywordError, match=r"unknown time unit 'fortnight'.*known time units.*"
                                           r"declared by the file.*units=\{'time': 's'\}"):
        read_history(path)
    # the user's unit replaces the file's unreadable one, as the error asked: no warning
    with warnings.catch_warnings():
        warnings.filterwarnings("error", ".*override the units", UnitsWarning)
        assert read_history(path, units={"time": "s"}).time.tolist() == [0.0, 1.0]


def test_unknown_format_and_unknown_options(tmp_path):
    path = csv(tmp_path, GOOD)
    with pytest.raises(FormatError, match=r"unknown format 'excel'; known formats: \['csv', "
                                          r"'parquet', 'hdf5', 'netcdf', 'npz', 'aster'"):
        read_history(path, format="excel")
    with pytest.raises(KeywordError, match=r"\['sheet'\] unknown for the 'csv' reader; its "
                                           r"options are \['delimiter'"):
        read_history(path, sheet=1)
    binary = tmp_path / "blob.bin"
    binary.write_bytes(b"\x00\x01\x02garbage")
    with pytest.raises(FormatError, match=r"blob.bin: binary content of no known format"):
        read_history(binary)
    npy = tmp_path / "a.npy"
    np.save(npy, np.zeros(3))
    with pytest.raises(FormatError, match=r"single .npy array has no column names.*savez"):
        guess_format(npy)
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    with pytest.raises(FormatError, match="empty.csv: the file is empty"):
        read_history(empty)


def test_missing_file_or_wrong_content_for_the_format(tmp_path):
    with pytest.raises(InputError, match=r"file '.*absent.csv' does not exist"):
        read_history(tmp_path / "absent.csv")
    path = csv(tmp_path, GOOD, name="text.h5")
    with pytest.raises(FormatError, match=r"text.h5: not a readable HDF5 file"):
        read_history(path, format="hdf5")
    with pytest.raises(FormatError, match=r"text.h5: not a readable Parquet file"):
        read_history(path, format="parquet")


def test_ragged_rows_and_comment_only_files(tmp_path):
    path = csv(tmp_path, "t,fn,vt1,vt2\n0,1,0,0\n1,1,0,0,9,9\n")
    with pytest.raises(FormatError, match=r"h.csv: .*same number of cells as the header"):
        read_history(path)
    path = csv(tmp_path, "# only\n# comments\n", name="c.csv")
    with pytest.raises(FormatError, match=r"c.csv: no data lines"):
        read_history(path)


def test_hdf5_with_several_candidate_groups_asks_for_group(tmp_path):
    h = analytic_history(n=5)
    path = write_history(h, tmp_path / "two.h5", group="a")
    import h5py

    with h5py.File(path, "a") as f:
        f.create_dataset("b/time", data=h.time)
    with pytest.raises(FormatError, match=r"several groups hold 1-D datasets \['/a', '/b'\]; "
                                          r"choose one with group="):
        read_history(path)
    with pytest.raises(FormatError, match=r"no group 'c'; groups: \['/', '/a', '/b'\]"):
        read_history(path, group="c")


def test_missing_optional_dependency_names_the_extra(tmp_path, monkeypatch):
    path = write_history(analytic_history(n=5), tmp_path / "h.parquet")
    for module in ("pyarrow", "pyarrow.parquet"):
        monkeypatch.setitem(sys.modules, module, None)  # import now raises ImportError
    with pytest.raises(MissingDependencyError,
                       match=r"reading Parquet needs the optional package 'pyarrow.parquet': "
                             r"pip install 'fretwear\[formats\]'"):
        read_history(path)
    monkeypatch.setitem(sys.modules, "h5py", None)
    with pytest.raises(MissingDependencyError,
                       match=r"writing HDF5 needs the optional package 'h5py'"):
        write_history(analytic_history(n=5), tmp_path / "h.h5")
    assert not (tmp_path / "h.h5").exists()


# the arrays' samples are 1 s apart: the coarse step is flagged (likely ms), irrelevant here
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_user_inputs_are_not_modified(tmp_path):
    arrays = {"t": np.array([0.0, 1.0]), "fn": np.array([-1e-20, 2.0]), "vt1": np.ones(2),
              "vt2": np.zeros(2)}
    copies = {k: v.copy() for k, v in arrays.items()}
    columns = {"t": "time"}
    units = {"force": "kN"}
    h = read_history(arrays, columns=columns, units=units)
    assert h.normal_force.tolist() == [0.0, 2000.0]  # solver noise clipped in the copy only
    for k in arrays:
        np.testing.assert_array_equal(arrays[k], copies[k])
    assert columns == {"t": "time"} and units == {"force": "kN"}
    with pytest.raises(KeywordError, match=r"option\(s\) \['group'\] do not apply"):
        read_history(arrays, group="x")
    with pytest.raises(InputError, match="needs a ContactHistory, got dict"):
        write_history(arrays, tmp_path / "x.csv")


def test_wrong_kinds_of_input(tmp_path):
    h = analytic_history(n=5)
    with pytest.raises(InputError, match="got a ContactHistory where a file is expected"):
        read_history(h)
    with pytest.raises(InputError, match="cannot read a history from a int"):
        read_history(42)
    with pytest.raises(FormatError, match="list or mapping of files is read with "
                                          "format='aster-function', not 'csv'"):
        read_history([tmp_path / "a.csv"], format="csv")
    with pytest.raises(KeywordError, match=r"\['format'\] do not apply to an in-memory table"):
        read_history({"t": [0.0, 1.0]}, format="csv")


def test_columns_of_different_lengths_are_refused_also_when_streaming(tmp_path):
    # An HDF5 group or an NPZ archive can hold arrays of different lengths: reading whole or by
    # chunks of any size must refuse them (never silently truncate), naming the columns.
    import h5py

    from fretwear.io import iter_history_chunks

    arrays = {"time": np.arange(6.0), "fn": np.ones(5), "vt1": np.ones(6), "vt2": np.zeros(6)}
    with h5py.File(tmp_path / "h.h5", "w") as f:
        for k, v in arrays.items():
            f.create_dataset(f"shock/{k}", data=v)
    np.savez(tmp_path / "h.npz", **arrays)
    for name in ("h.h5", "h.npz"):
        with pytest.raises(HistoryError, match="'normal_force' has 5 samples but 'time' has 6"):
            read_history(tmp_path / name)
        for size in (2, 4, 100):
            with pytest.raises(FormatError, match="different lengths .*'fn': 5"):
                list(iter_history_chunks(tmp_path / name, chunk_size=size))
