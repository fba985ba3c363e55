"""Restarts from table files (issue 13): the restart state of a file, its memo, its errors.

Independent computations:

* the state of a file against the state of the same table given as a DataFrame read by
  ``read_wear_table`` (the DataFrame path never uses the memo), and against the rows selected
  by hand (the instants up to the origin) and the volumes of the printed literals;
* the memo (keyed on the file's content) against a file changed in place (same size, same
  modification time): the new content is read, never the old state;
* ``state_to_dict`` of float rows (one numpy pass) against the per-column
  ``jsonable(rows[c].tolist())`` it replaces, and against ``WearCase.from_dict`` round trips.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import FormatError, InputError
from fretwear.history import ContactHistory
from fretwear.table import WearCase, read_wear_table, restart, wear_table, write_wear_table
from fretwear.table._serial import jsonable, state_from_dict, state_to_dict
from fretwear.table.restart import InitialState, initial_state

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "data" / "grappe_2_enco_10000h.tab"
BAV = {"mobile_radius": 0.0111, "obstacle_width": 0.0127}


@pytest.fixture(autouse=True)
def empty_memo():
    restart._MEMO.clear()
    yield
    restart._MEMO.clear()


def same_state(a: InitialState, b: InitialState, attrs: bool = True) -> None:
    assert (a.origin, a.volume_mobile, a.volume_obstacle) == \
        (b.origin, b.volume_mobile, b.volume_obstacle)
    for name in ("sector_volume_mobile", "sector_volume_obstacle", "edges"):
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None) == (y is None)
        if x is not None:
            assert np.array_equal(x, y)
    pd.testing.assert_frame_equal(a.rows, b.rows, check_exact=True, check_column_type=True,
                                  check_index_type=True)
    assert a.rows.attrs == b.rows.attrs or not attrs


def sector_table(tmp_path: Path, suffix: str = ".tab") -> Path:
    t = np.linspace(0.0, 1.0, 2001)
    phase = 2 * np.pi * 20 * t
    history = ContactHistory(time=t, normal_force=np.maximum(0.0, 30 * np.sin(phase)),
                             vt1=0.02 * np.cos(phase), vt2=0.01 * np.sin(phase),
                             dy=1e-4 * np.cos(phase / 3), dz=1e-4 * np.sin(phase / 3))
    table = wear_table(history, contact_type="TUBE_ALESAGE", instants=[1.0, 2.0], sectors=4,
                       dimensions={**BAV, "obstacle_radius": 0.0115},
                       coefficients={"COEF_USURE": 1.1e-13}, time_scale=3.6e3)
    return write_wear_table(table, tmp_path / f"sectors{suffix}")


def test_the_example_file_state_is_its_printed_literals():
    state = initial_state(EXAMPLE)
    assert state.origin == 1e4 and state.volume_mobile == 2.88e-09
    assert state.volume_obstacle == 2.088e-09 and state.sector_count == 0
    frame = read_wear_table(EXAMPLE)
    pd.testing.assert_frame_equal(state.rows, frame, check_exact=True)
    same_state(state, initial_state(frame))  # the DataFrame path: no memo


def test_initial_instant_keeps_the_rows_up_to_it():
    state = initial_state(EXAMPLE, initial_instant=5000.0)
    frame = read_wear_table(EXAMPLE)
    expected = frame[frame["instant"] <= 5000.0].reset_index(drop=True)
    pd.testing.assert_frame_equal(state.rows, expected, check_exact=True)
    assert state.rows.attrs == frame.attrs
    assert (state.origin, state.volume_mobile, state.volume_obstacle) == (5000.0, 1.44e-09,
                                                                          1.044e-09)
    same_state(state, initial_state(EXAMPLE, initial_instant=5000))  # an int: the same key
    same_state(initial_state(EXAMPLE), initial_state(frame))  # the other key: the last


def test_a_frame_with_its_own_index_gets_rows_numbered_from_zero():
    frame = read_wear_table(EXAMPLE)
    frame.index = [10, 11]
    state = initial_state(frame)
    assert list(state.rows.index) == [0, 1] and isinstance(state.rows.index, pd.RangeIndex)
    assert frame.index.tolist() == [10, 11]  # the caller's frame is not touched
    assert "provenance" not in frame.attrs or frame.attrs == read_wear_table(EXAMPLE).attrs


@pytest.mark.parametrize("suffix", [".tab", ".resu", ".csv"])
def test_sector_file_state_equals_the_frame_state(tmp_path, suffix):
    path = sector_table(tmp_path, suffix)
    state = initial_state(path)
    same_state(state, initial_state(read_wear_table(path)))
    assert state.sector_count == 4 and state.edges.tolist() == [-180.0, -90.0, 0.0, 90.0, 180.0]
    same_state(state, initial_state(path))  # the second read (the memo for .tab, .resu)


def test_repeated_reads_are_remembered_and_each_caller_owns_its_state(tmp_path):
    path = sector_table(tmp_path)
    first = initial_state(path)
    assert len(restart._MEMO) == 1
    second = initial_state(path)
    assert len(restart._MEMO) == 1  # the same content: parsed once
    same_state(first, second)
    assert first.rows is not second.rows and first.edges is not second.edges
    reference = initial_state(read_wear_table(path))
    # a caller changing everything it can change in its state
    first.rows.iloc[0, 0] = -1.0
    first.rows["instant"] = 0.0
    first.rows.attrs["title"] = "changed"
    first.rows.attrs.setdefault("provenance", {})["law"] = "changed"
    first.rows.columns.name = "changed"
    first.sector_volume_mobile[:] = -1.0
    first.edges[0] = -5.0
    third = initial_state(path)
    for state in (second, third):
        same_state(state, reference)
        assert state.rows.columns.name is None


def test_a_file_changed_in_place_is_read_again(tmp_path):
    """Same path, same size, same modification time: only the content differs."""
    path = tmp_path / "restart.tab"
    shutil.copy(EXAMPLE, path)
    stamp = os.stat(path).st_mtime_ns
    before = initial_state(path)
    text = path.read_text()
    assert "2.88000E-09" in text
    path.write_text(text.replace("2.88000E-09", "2.99000E-09"))
    os.utime(path, ns=(stamp, stamp))
    after = initial_state(path)
    assert before.volume_mobile == 2.88e-09 and after.volume_mobile == 2.99e-09
    assert after.rows["volume_mobile"].tolist() == [1.44e-09, 2.99e-09]


def test_the_memo_is_bounded_and_big_or_csv_files_are_read_as_usual(tmp_path, monkeypatch):
    text = EXAMPLE.read_text()
    for i in range(restart._MEMO_SIZE + 5):
        path = tmp_path / f"r{i}.tab"
        path.write_text(text.replace("#TABLE_SDASTER", f"#TABLE_SDASTER {i}"))
        initial_state(path)
    assert len(restart._MEMO) == restart._MEMO_SIZE
    restart._MEMO.clear()
    csv = write_wear_table(read_wear_table(EXAMPLE), tmp_path / "r.csv")
    same_state(initial_state(csv), initial_state(EXAMPLE), attrs=False)  # (CSV provenance)
    assert len(restart._MEMO) == 1  # the .tab only
    monkeypatch.setattr(restart, "_MEMO_BYTES", 10)
    restart._MEMO.clear()
    same_state(initial_state(EXAMPLE), initial_state(read_wear_table(EXAMPLE)))
    assert not restart._MEMO


# --------------------------------------------------------------------------- errors
def write(tmp_path: Path, text: str, name: str = "bad.tab") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_errors_of_bad_restart_files_are_worded_and_never_remembered(tmp_path):
    missing = write(tmp_path, "#\n#t\nINST P_USUR_TUBE\n 1.00000E+00 2.00000E-05\n")
    for _ in range(2):  # the second time too: an error is not kept
        with pytest.raises(InputError, match=r"initial wear table '.*bad.tab': no column for the "
                                             r"tube's volume; expected one of "
                                             r"\['volume_mobile_cumulated', 'volume_mobile'\] "
                                             r"\(Code_Aster \['V_USUR_TUBE_CUMU', "
                                             r"'V_USUR_TUBE'\]\)"):
            initial_state(missing)
    assert not restart._MEMO
    gap = write(tmp_path, "#\n#t\nINST SECTEUR ANGLE_DEBUT ANGLE_FIN V_USUR_TUBE_CUMU "
                          "V_USUR_OBST_CUMU\n 1.0 1 0.0 90.0 1.0E-09 0.0\n"
                          " 1.0 2 100.0 360.0 2.0E-09 0.0\n", "gap.tab")
    with pytest.raises(InputError, match=r"its sectors are not contiguous \(ANGLE_DEBUT "
                                         r"\[0.0, 100.0\], ANGLE_FIN \[90.0, 360.0\]\)"):
        initial_state(gap)
    with pytest.raises(InputError, match=r"INST_INIT / initial_instant = 7000 is not an instant "
                                         r"of the initial wear table '.*'; its instants are "
                                         r"\[5000.0, 10000.0\]"):
        initial_state(EXAMPLE, initial_instant=7000.0)
    two = write(tmp_path, EXAMPLE.read_text() * 2, "two.tab")
    with pytest.raises(FormatError, match=r"holds 2 tables .*\[wear table: in a case file give "
                                          r"\[restart\] table_index = <n>"):
        initial_state(two)
    same_state(initial_state(read_wear_table(two, index=1)), initial_state(EXAMPLE))
    with pytest.raises(InputError, match="has no rows"):
        initial_state(write(tmp_path, "#\n#t\nINST V_USUR_TUBE V_USUR_OBST\n", "empty.tab"))
    with pytest.raises(InputError, match="wear table file .*nothing.tab.* does not exist"):
        initial_state(tmp_path / "nothing.tab")


def test_a_bad_file_fixed_in_place_is_read_again(tmp_path):
    path = write(tmp_path, EXAMPLE.read_text().replace("1.00000E+04", "1.0000OE+04"))
    with pytest.raises(Exception):  # noqa: B017 - a column of text: no INST number
        WearCase.from_keywords(contact_type="GRAPPE_2_ENCO", instants=[1.0], initial_state=path,
                               dimensions={"mobile_radius": 4.85e-3, "obstacle_radius": 5.25e-3,
                                           "obstacle_width": 20e-3},
                               coefficients={"COEF_USURE": 1e-14}, initial_instant=1e4)
    shutil.copy(EXAMPLE, path)
    assert initial_state(path, initial_instant=1e4).volume_mobile == 2.88e-09


# --------------------------------------------------------------------------- serialising
def test_state_to_dict_of_float_rows_is_the_per_column_serialisation():
    rows = pd.DataFrame({"instant": [1.0, 2.0, 3.0], "volume_mobile": [np.nan, -0.0, np.inf],
                         "depth_mobile": [1 / 3, 5e-324, 1e308]})
    state = InitialState(3.0, 1e-9, 0.0, None, None, None, rows)
    got = state_to_dict(state)
    assert got["rows"]["data"] == [jsonable(rows[c].tolist()) for c in rows.columns]
    assert got["rows"]["dtypes"] == [str(t) for t in rows.dtypes]
    assert got["rows"]["data"][1][0] is None and str(got["rows"]["data"][1][1]) == "-0.0"
    assert got == jsonable(got)  # JSON-ready as it is
    back = state_from_dict(json.loads(json.dumps(got)))
    pd.testing.assert_frame_equal(back.rows, rows, check_exact=True)


def test_state_to_dict_of_mixed_rows_and_case_round_trips(tmp_path):
    rows = pd.DataFrame({"instant": [1.0, 1.0], "sector": pd.array([1, None], dtype="Int64"),
                         "volume_mobile": [1e-9, np.nan]})
    got = state_to_dict(InitialState(1.0, 1e-9, 0.0, None, None, None, rows))
    assert got["rows"]["dtypes"] == ["float64", "Int64", "float64"]
    assert got["rows"]["data"] == [jsonable(rows[c].tolist()) for c in rows.columns]
    path = sector_table(tmp_path)
    case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0], sectors=4,
                                  dimensions={**BAV, "obstacle_radius": 0.0115},
                                  coefficients={"COEF_USURE": 1.1e-13}, initial_state=path,
                                  time_scale=3.6e3)  # the table's unit
    again = WearCase.from_json(case.to_json())
    assert again == case
    pd.testing.assert_frame_equal(again.restart.table.rows, case.restart.table.rows,
                                  check_exact=True)  # (the attrs of the file are not carried)
    assert np.array_equal(again.restart.table.sector_volume_mobile,
                          case.restart.table.sector_volume_mobile)


def test_rows_then_run_equal_the_pandas_concat():
    """build._after_rows (the restart rows then the run's, built from the float columns) is
    pandas.concat of the reindexed rows and the run's frame (its columns made a frame by
    _frame, when it gives them), exactly: values, dtypes, index and
    column order; rows lacking a column (NaN), holding extra ones (dropped), NaN cells; a run
    with an integer column (sectors) or rows with a text column take the concat itself."""
    from fretwear.table._columns import _frame
    from fretwear.table.build import _after_rows

    rng = np.random.default_rng(3)
    run = {c: rng.random(3) for c in ("instant", "duration", "volume_mobile", "depth_mobile")}
    rows = pd.DataFrame({"instant": [1.0, 2.0], "volume_mobile": [np.nan, 1e-9],
                         "depth_obstacle": [0.0, 1.0], "duration": [1.0, 2.0]})
    rows.attrs = {"title": "previous"}
    sectors = {"sector": np.array([1, 2, 1]), **run}
    texts = rows.assign(note=["a", "b"])
    for r, columns in ((rows, run), (rows.iloc[:, :0], run), (rows, sectors), (texts, run)):
        expected = pd.concat([r.reindex(columns=list(columns)), _frame(columns)],
                             ignore_index=True)
        got = _after_rows(r, columns)
        if isinstance(got, dict):  # the float columns of that frame
            got = _frame(got)
        pd.testing.assert_frame_equal(got, expected, check_exact=True)
        assert list(got.columns) == list(columns)
    assert rows.attrs == {"title": "previous"} and len(rows.columns) == 4  # not modified


# --------------------------------------------------------------------------- the memo's reads
def test_a_signed_zero_initial_instant_is_remembered_apart(tmp_path):
    """INST_INIT = 0.0 and -0.0 compare equal but give origins of their own sign (the origin
    column of the new rows); the memo must not hand one the other's. Expected: the DataFrame
    path, which has no memo."""
    path = write(tmp_path, "#\nINST V_USUR_TUBE V_USUR_OBST\n"
                 " -0.00000E+00 1.00000E-09 2.00000E-09\n 1.00000E+00 2.00000E-09 3.00000E-09\n")
    frame = read_wear_table(path)
    for first, second in ((0.0, -0.0), (-0.0, 0.0)):
        restart._MEMO.clear()
        for instant in (first, second):
            got = initial_state(path, instant).origin
            want = initial_state(frame, instant).origin
            assert (got, np.copysign(1.0, got)) == (want, np.copysign(1.0, want)) == \
                (0.0, np.copysign(1.0, instant))


def test_a_short_read_is_read_on_to_the_end(tmp_path, monkeypatch):
    """os.read may return fewer bytes than asked (FUSE and network file systems): the memo must
    read on to the end, not parse a truncated table. Expected: the state read by pandas' path
    (read_wear_table) before the reads were cut."""
    path = sector_table(tmp_path)
    reference = initial_state(read_wear_table(path))
    real = os.read
    monkeypatch.setattr(os, "read", lambda fd, n: real(fd, min(n, 97)))
    same_state(initial_state(path), reference)
    assert len(restart._MEMO) == 1


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes are POSIX")
def test_a_named_pipe_is_left_to_the_usual_reader(tmp_path):
    """A named pipe given as the restart table is read once, by read_wear_table: the memo does
    not open it (opening blocks until a writer comes, and closing it unread loses what the
    writer sent)."""
    import threading

    fifo = tmp_path / "pipe.tab"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(restart._memo_bytes(fifo)), daemon=True)
    reader.start()
    reader.join(5.0)
    if reader.is_alive():  # blocked in open(): let it go
        os.close(os.open(fifo, os.O_WRONLY))
        reader.join(5.0)
        pytest.fail("the memo opened the named pipe")
    assert got == [None]


def test_a_nan_volume_of_a_state_round_trips_through_json():
    """state_to_dict writes NaN as None (strict JSON); state_from_dict reads None back as NaN
    (IEEE 754: a missing volume stays NaN) for the scalars as for the arrays and rows."""
    rows = pd.DataFrame({"instant": [1.0], "volume_mobile": [np.nan]})
    state = InitialState(1.0, np.nan, np.nan, None, None, None, rows)
    back = state_from_dict(json.loads(json.dumps(state_to_dict(state))))
    assert back.origin == 1.0 and np.isnan(back.volume_mobile) and np.isnan(back.volume_obstacle)
    pd.testing.assert_frame_equal(back.rows, rows, check_exact=True)
    case = WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0], dimensions=BAV,
                                  coefficients={"COEF_USURE": 1.1e-13}, initial_state=state)
    assert np.isnan(WearCase.from_json(case.to_json()).restart.table.volume_mobile)
