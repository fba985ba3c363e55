"""Damaged, unreadable and oddly encoded files end in a fretwear error naming the file (issue 15).

Each test is one family of inputs that leaked a Python exception (a traceback for the user) or
crashed/hung the interpreter before fretwear.io.guard; the damage is made by hand from a good
file written by fretwear, so the expected failure is known.
"""

from __future__ import annotations

import gzip
import os
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest
from iohelpers import FIXTURES, analytic_history

import fretwear.io.guard as guard
from fretwear.errors import FormatError, HistoryError, InputError
from fretwear.io import iter_history_chunks, read_history, write_history
from fretwear.io.aster import read_aster_table
from fretwear.table.files import read_wear_table

GOOD = "INST,FN,VT1,VT2\n0.0,1.0,0.1,0.0\n0.1,2.0,0.1,0.0\n0.2,0.0,0.1,0.0\n"


def both(path, **kw):
    """Read whole and chunk by chunk: both paths must fail the same clean way."""
    read_history(path, **kw)
    list(iter_history_chunks(path, chunk_size=2, **kw))


def _read_both_fail(path, error=FormatError, match=None):
    with pytest.raises(error, match=match):
        read_history(path)
    with pytest.raises(error, match=match):
        list(iter_history_chunks(path, chunk_size=2))


# --------------------------------------------------------------------------- compressed text
@pytest.mark.parametrize("suffix", [".csv.gz", ".resu.gz"])
def test_truncated_gzip_names_the_file(tmp_path, suffix):
    good = write_history(analytic_history(n=400), tmp_path / f"h{suffix}")
    cut = tmp_path / f"cut{suffix}"
    cut.write_bytes(good.read_bytes()[: good.stat().st_size // 2])  # EOFError before
    _read_both_fail(cut, match=r"cut\.(csv|resu)\.gz: damaged or truncated .*EOFError")
    bad = bytearray(good.read_bytes())
    bad[-8] ^= 0xFF  # the CRC of the stream: BadGzipFile (an OSError) before
    crc = tmp_path / f"crc{suffix}"
    crc.write_bytes(bytes(bad))
    _read_both_fail(crc, match=r"crc\.(csv|resu)\.gz: damaged or truncated")


def test_truncated_gzip_wear_table_and_aster_table(tmp_path):
    text = "#\n#T\nINST V_USUR_TUBE\n 1.00000E+00 2.50000E-09\n" * 50
    cut = tmp_path / "t.tab"
    cut.write_bytes(gzip.compress(text.encode())[:-12])
    with pytest.raises(FormatError, match=r"t\.tab: damaged or truncated"):
        read_aster_table(cut)
    with pytest.raises(FormatError, match=r"t\.tab: damaged or truncated"):
        read_wear_table(cut)


# --------------------------------------------------------------------------- NPZ
def test_corrupt_npz_archives(tmp_path):
    good = write_history(analytic_history(n=50), tmp_path / "h.npz")
    data = bytearray(good.read_bytes())
    cut = tmp_path / "cut.npz"
    cut.write_bytes(bytes(data[: len(data) - 40]))  # central directory cut: BadZipFile
    _read_both_fail(cut, match=r"cut\.npz: .*(damaged|truncated|zip)")
    with zipfile.ZipFile(good) as zf:  # flip a byte inside the first stored array: bad CRC
        info = zf.infolist()[0]
    data[info.header_offset + 30 + len(info.filename) + 100] ^= 0xFF
    crc = tmp_path / "crc.npz"
    crc.write_bytes(bytes(data))
    _read_both_fail(crc, match=r"crc\.npz: damaged or truncated npz file \(BadZipFile")


def test_npz_holding_object_or_text_arrays(tmp_path):
    path = tmp_path / "obj.npz"
    np.savez(path, time=np.array([0.0, 1.0]), normal_force=np.array([1, "a"], dtype=object),
             vt1=np.zeros(2), vt2=np.zeros(2))
    _read_both_fail(path, match=r"obj\.npz: array 'normal_force' holds object values, not "
                                r"numbers \(object arrays are never unpickled\)")
    path = tmp_path / "text.npz"
    np.savez(path, time=np.array([0.0, 1.0]), normal_force=np.array(["1", "x"]),
             vt1=np.zeros(2), vt2=np.zeros(2))
    _read_both_fail(path, match=r"text\.npz: array 'normal_force' holds <U1 values, not "
                                r"numbers")


# --------------------------------------------------------------------------- Parquet
def test_corrupt_parquet(tmp_path):
    good = write_history(analytic_history(n=300), tmp_path / "h.parquet")
    data = bytearray(good.read_bytes())
    data[200:260] = b"\x7f" * 60  # inside the first column chunk's pages
    bad = tmp_path / "bad.parquet"
    bad.write_bytes(bytes(data))
    _read_both_fail(bad, match=r"bad\.parquet: (damaged or truncated parquet|not a readable)")
    cut = tmp_path / "cut.parquet"
    cut.write_bytes(good.read_bytes()[:-30])  # footer cut
    _read_both_fail(cut, match=r"cut\.parquet: (damaged or truncated|not a readable)")


# --------------------------------------------------------------------------- HDF5 / NetCDF
def test_truncated_hdf5_is_refused_before_the_library_opens_it(tmp_path):
    good = write_history(analytic_history(n=300), tmp_path / "h.h5")
    cut = tmp_path / "cut.h5"
    size = good.stat().st_size
    cut.write_bytes(good.read_bytes()[: size // 2])
    _read_both_fail(cut, match=rf"cut\.h5: truncated HDF5 file: it holds {size // 2} bytes "
                               rf"but its superblock says {size}")


@pytest.mark.parametrize("suffix", [".h5", ".nc"])
def test_a_library_crash_in_the_probe_is_an_error(tmp_path, monkeypatch, suffix):
    path = write_history(analytic_history(n=20), tmp_path / f"h{suffix}")
    monkeypatch.setattr(guard, "_CHILD", "import os, signal; os.kill(os.getpid(), "
                                         "signal.SIGSEGV)")
    monkeypatch.setattr(guard, "_PROBED", {})
    _read_both_fail(path, match=r"library crashed \(SIGSEGV\) reading this file: it is damaged")


def test_a_library_hang_in_the_probe_is_an_error(tmp_path, monkeypatch):
    path = write_history(analytic_history(n=20), tmp_path / "h.nc")
    monkeypatch.setattr(guard, "_CHILD", "import time; time.sleep(30)")
    monkeypatch.setattr(guard, "_PROBED", {})
    monkeypatch.setattr(guard, "PROBE_TIMEOUT", 0.5)
    with pytest.raises(FormatError, match=r"h\.nc: the NetCDF library did not finish reading "
                                          r"the file's structure in 0\.5 s"):
        read_history(path)


def test_hdf5_file_that_made_the_library_loop_forever(monkeypatch):
    """A file found by fuzzing (one corrupt attribute message in a file written by fretwear):
    h5py looped forever in ``attrs[...]``; the probe's time limit turns it into an error."""
    monkeypatch.setattr(guard, "PROBE_TIMEOUT", 3.0)
    monkeypatch.setattr(guard, "_PROBED", {})
    path = FIXTURES / "damaged" / "hdf5_attribute_loop.h5"
    with pytest.raises(FormatError, match=r"hdf5_attribute_loop\.h5: (the HDF5 library did not "
                                          r"finish|not a readable hdf5 file)"):
        read_history(path)


def test_probe_is_remembered_per_file(tmp_path, monkeypatch):
    path = write_history(analytic_history(n=25), tmp_path / "h.h5")  # steps <= 5 ms: plausible
    monkeypatch.setattr(guard, "_PROBED", {})
    read_history(path)
    assert len(guard._PROBED) == 1  # guess_format and open_hdf5 shared one child process
    write_history(analytic_history(n=30), path)  # a new file: probed again
    assert len(read_history(path)) == 30
    assert len(guard._PROBED) == 2


def test_text_file_named_like_hdf5_or_netcdf(tmp_path):
    path = tmp_path / "text.nc"
    path.write_text(GOOD)
    with pytest.raises(FormatError, match=r"text\.nc: not a readable"):
        read_history(path, format="netcdf")


@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
@pytest.mark.parametrize(("suffix", "named"), [(".parquet", "Parquet"), (".h5", "HDF5"),
                                              (".nc", "NetCDF"), (".npz", "NPZ")])
def test_text_named_like_a_binary_format_says_so_when_its_columns_fail(tmp_path, suffix, named):
    """A text file named like a binary format is read as text (its content decides); when its
    columns then fail, the message says it is not the binary file its name says (a user's
    trial: ``garbage.parquet`` gave only "no column for the required channel(s)"). A good CSV
    under that name is still read, with no note."""
    path = tmp_path / f"garbage{suffix}"
    path.write_text("not a parquet file\n1 2 3 4\n")
    for read in (lambda: read_history(path), lambda: list(iter_history_chunks(path))):
        with pytest.raises(FormatError, match=rf"no column for the required channel.*named "
                                              rf"\{suffix} but holds text, not {named}"):
            read()
    good = tmp_path / f"good{suffix}"
    good.write_text(GOOD)
    assert read_history(good).normal_force.tolist() == [1.0, 2.0, 0.0]
    plain = tmp_path / "plain.csv"  # the same column error in a file named as text: no note
    plain.write_text("not a parquet file\n1 2 3 4\n")
    with pytest.raises(FormatError, match="no column for the required channel") as err:
        read_history(plain)
    assert "holds text" not in str(err.value)
    # the mapping's fix in the three ways a user gives it (Python, command line, case file)
    assert "columns={'<column>': 'time'}" in str(err.value)
    assert "--column '<column>=time'" in str(err.value)
    assert "[history] columns = { '<column>' = 'time' }" in str(err.value)


# --------------------------------------------------------------------------- text files
def test_header_only_csv_says_no_instants(tmp_path):
    for text in ("INST,FN,VT1,VT2\n", "INST,FN,VT1,VT2\r\n"):
        path = tmp_path / "h.csv"
        path.write_text(text, newline="")
        with pytest.raises(HistoryError, match=r"at least two instants are needed, got 0"):
            read_history(path)
        with pytest.raises(FormatError, match=r"h\.csv: no data rows \(a header only\?\)"):
            list(iter_history_chunks(path))


def test_rows_shorter_than_the_header(tmp_path):
    path = tmp_path / "short.csv"
    path.write_text("INST,FN,VT1,VT2\n0,1,0\n1,2,0\n")
    _read_both_fail(path, match=r"short\.csv: the header names 4 columns .* data rows hold 3 "
                                r"cells: no values for \['VT2'\]")


# GOOD's samples are 0.1 s apart: the coarse step is flagged (likely ms), irrelevant to encodings
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-8-sig"])
def test_unicode_encodings_with_a_byte_order_mark(tmp_path, encoding):
    text = GOOD if encoding != "utf-16-le" else "\ufeff" + GOOD
    path = tmp_path / "h.csv"
    path.write_bytes(text.encode(encoding))
    h = read_history(path)
    assert h.normal_force.tolist() == [1.0, 2.0, 0.0]
    assert sum(len(c) for c in iter_history_chunks(path, chunk_size=2)) == 4  # 2 + 2, 1 shared
    table = ("#DEBUT_TABLE\n#TITRE x\nINST FN VT1 VT2\nR R R R\n0.0 1.0 0.1 0.0\n"
             "0.1 2.0 0.1 0.0\n#FIN_TABLE\n")
    aster = tmp_path / "h.resu"
    aster.write_bytes(table.encode(encoding) if encoding != "utf-16-le"
                      else ("\ufeff" + table).encode(encoding))
    assert read_history(aster).normal_force.tolist() == [1.0, 2.0]


# GOOD's samples are 0.1 s apart: the coarse step is flagged (likely ms), irrelevant to encodings
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_crlf_and_latin1(tmp_path):
    path = tmp_path / "crlf.csv"
    path.write_bytes(GOOD.replace("\n", "\r\n").encode())
    assert read_history(path).time.tolist() == [0.0, 0.1, 0.2]
    latin = tmp_path / "latin.csv"
    latin.write_bytes(("# essai à Chinon\n" + GOOD).encode("latin-1"))
    with pytest.raises(FormatError, match=r"latin\.csv: not a text file in 'utf-8-sig'; give "
                                          r"encoding='latin-1'"):
        read_history(latin)
    assert read_history(latin, encoding="latin-1").time.tolist() == [0.0, 0.1, 0.2]


def test_code_aster_integer_beyond_64_bits(tmp_path):
    path = tmp_path / "big.resu"
    path.write_text("#DEBUT_TABLE\n#TITRE x\nINST FN VT1 VT2\nI R R R\n0 1 0 0\n"
                    "99999999999999999999999 1 0 0\n#FIN_TABLE\n")
    with pytest.raises(FormatError, match=r"big\.resu, line 6: column 'INST' of type I holds "
                                          r"9\.99.*e\+22, beyond 64-bit integers"):
        read_history(path)
    # undeclared (TABLEAU): digits too large for an integer are read as a real, not wrapped
    tableau = read_aster_table("#\n#T\nN X\n1 2\n99999999999999999999999 3\n")
    assert tableau["N"].tolist() == [1.0, 1e23] and tableau.attrs["types"][0] == "R"


# --------------------------------------------------------------------------- paths
def test_paths_that_cannot_be_read(tmp_path, monkeypatch):
    long = tmp_path / ("x" * 300 + ".csv")
    with pytest.raises(InputError, match=r"history file '.*xxx\.csv' has a name too long"):
        read_history(long)
    with pytest.raises(InputError, match=r"wear table file '.*xxx\.csv' has a name too long"):
        read_wear_table(long)
    with pytest.raises(InputError, match=r"history file '.*' is a directory, not a file"):
        read_history(tmp_path)
    with pytest.raises(InputError, match=r"Code_Aster table file '.*' is a directory"):
        read_aster_table(tmp_path)
    path = tmp_path / "h.csv"
    path.write_text(GOOD)
    monkeypatch.setattr(os, "access", lambda *a, **k: False)  # as a user without the right
    with pytest.raises(InputError, match=r"history file '.*h\.csv' cannot be read \(permission "
                                         r"denied\)"):
        read_history(path)


def test_permission_error_while_reading_names_the_file(tmp_path, monkeypatch):
    """Root reads anything: simulate a file whose permission changes between check and read."""
    path = tmp_path / "h.csv"
    path.write_text(GOOD)
    real_open = open

    def deny(file, *args, **kwargs):
        if Path(file) == path:
            raise PermissionError(13, "Permission denied", str(path))
        return real_open(file, *args, **kwargs)

    monkeypatch.setattr("builtins.open", deny)
    with pytest.raises(InputError, match=r"history file '.*h\.csv' cannot be read \(permission "
                                         r"denied\)"):
        read_history(path)


# --------------------------------------------------------------------------- memory
@pytest.mark.parametrize("suffix", [".npz", ".resu"])
def test_streaming_a_format_read_whole_warns_above_a_size(tmp_path, monkeypatch, suffix):
    from fretwear.errors import WholeReadWarning

    path = write_history(analytic_history(n=200), tmp_path / f"h{suffix}")
    monkeypatch.setattr(guard, "WHOLE_READ_WARNING_BYTES", path.stat().st_size - 1)
    with pytest.warns(WholeReadWarning, match=rf"h\{suffix}: 0 MiB of .* data are read whole "
                                              r".*convert it once to Parquet"):
        list(iter_history_chunks(path, chunk_size=50))
    monkeypatch.setattr(guard, "WHOLE_READ_WARNING_BYTES", path.stat().st_size)
    with warnings.catch_warnings():
        warnings.simplefilter("error", WholeReadWarning)
        list(iter_history_chunks(path, chunk_size=50))
    csv = write_history(analytic_history(n=200), tmp_path / "h.csv")  # streamed: no warning
    monkeypatch.setattr(guard, "WHOLE_READ_WARNING_BYTES", 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error", WholeReadWarning)
        list(iter_history_chunks(csv, chunk_size=50))


# --------------------------------------------------------------------------- the per-file cost
def _count_processes(monkeypatch) -> list:
    """Every process started from now on (subprocess.Popen, which subprocess.run uses too)."""
    import subprocess

    started = []
    real = subprocess.Popen

    def counted(*args, **kwargs):
        started.append(args[0] if args else kwargs.get("args"))
        return real(*args, **kwargs)

    monkeypatch.setattr(subprocess, "Popen", counted)
    return started


def test_guess_format_starts_no_process(tmp_path, monkeypatch):
    """issue 28: guess_format tells NetCDF-4 from plain HDF5 by the header's bytes (the
    ``_NCProperties`` root attribute netCDF-C writes), without starting a process (a child
    walked each file before: 0.2 s a file); the formats are those the writers made."""
    from fretwear.io import guess_format

    h = analytic_history(n=25)
    netcdf4 = write_history(h, tmp_path / "n.nc")
    named_h5 = tmp_path / "netcdf4.h5"
    named_h5.write_bytes(netcdf4.read_bytes())  # a NetCDF-4 file under an HDF5 suffix
    plain = write_history(h, tmp_path / "p.h5")
    named_nc = tmp_path / "plain.hdf"
    named_nc.write_bytes(plain.read_bytes())
    monkeypatch.setattr(guard, "_PROBED", {})
    started = _count_processes(monkeypatch)
    assert [guess_format(p) for p in (netcdf4, named_h5, plain, named_nc)] == [
        "netcdf", "netcdf", "hdf5", "hdf5"]
    assert started == []
    assert read_history(named_h5).name == h.name  # read by netCDF4: its title is the name


def test_one_checking_process_for_many_files(tmp_path, monkeypatch):
    """issue 28: the files a process reads are walked by one long-lived child (a child per file
    before: 5 processes for 5 files), which the crash of one file replaces; the files after it
    are still checked and read."""
    paths = [write_history(analytic_history(n=25 + k), tmp_path / f"h{k}.h5") for k in range(5)]
    monkeypatch.setattr(guard, "_PROBED", {})
    guard._drop_checker()
    started = _count_processes(monkeypatch)
    assert [len(read_history(p)) for p in paths] == [25, 26, 27, 28, 29]
    assert len(started) == 1
    crash = guard._CHILD.replace(
        "def check(path, fmt):\n",
        "def check(path, fmt):\n    if path.endswith('h2.h5'):\n        import os, signal\n"
        "        os.kill(os.getpid(), signal.SIGSEGV)\n")
    monkeypatch.setattr(guard, "_CHILD", crash)
    monkeypatch.setattr(guard, "_PROBED", {})
    for p in paths[:2]:
        read_history(p)
    with pytest.raises(FormatError, match=r"h2\.h5: the HDF5 library crashed \(SIGSEGV\)"):
        read_history(paths[2])
    assert [len(read_history(p)) for p in paths[3:]] == [28, 29]
    assert len(started) == 3  # the patched script's child, and the one after its crash
