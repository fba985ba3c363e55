"""The per-file work of reading a history is done once (issue 28: a bundle of 10⁵ small files
pays every repeated step 10⁵ times): a single file is checked readable once and its format
guessed from its first bytes; the errors of a bad path and of a file that is not Parquet are
the same as before."""

from __future__ import annotations

import pytest

from fretwear.errors import FormatError, InputError
from fretwear.history import ContactHistory
from fretwear.io import sources


def _parquet(tmp_path):
    pytest.importorskip("pyarrow")
    from fretwear.io import write_history

    h = ContactHistory(time=[0.0, 1e-4, 2e-4], normal_force=[0.0, 2.0, 1.0], vt1=[0.0, 0.1, 0.0],
                       vt2=[0.0, 0.0, 0.0])
    return write_history(h, tmp_path / "h.parquet")


def test_a_file_is_checked_readable_once_and_its_format_read_from_4_bytes(tmp_path,
                                                                          monkeypatch):
    path = _parquet(tmp_path)
    checked, reads = [], []
    readable = sources.readable_file
    monkeypatch.setattr(sources, "readable_file", lambda p, w: checked.append(p) or readable(p, w))
    real_read = sources.os.read
    monkeypatch.setattr(sources.os, "read", lambda fd, n: reads.append(n) or real_read(fd, n))
    monkeypatch.setattr(sources, "open", lambda *a: pytest.fail("opened again"), raising=False)
    source = sources.open_source(path)
    assert source.format == "parquet" and source.columns[:2] == ["time", "normal_force"]
    assert checked == [path]  # once (open_source, then guess_format, checked it twice)
    assert reads == [4]       # the signature only (65 536 bytes before)


def test_the_errors_of_a_bad_path_and_of_text_named_parquet_are_unchanged(tmp_path):
    with pytest.raises(InputError, match="does not exist|not found|No such"):
        sources.open_source(tmp_path / "missing.parquet")
    empty = tmp_path / "empty.parquet"
    empty.write_bytes(b"")
    with pytest.raises(FormatError, match="the file is empty"):
        sources.open_source(empty)
    text = tmp_path / "text.parquet"
    text.write_text("t,fn,vt1,vt2\n0,1,0,0\n1e-4,1,0,0\n")
    source = sources.open_source(text)  # read by its content, as csv, its name noted
    assert source.format == "csv" and "holds text, not Parquet" in source.hint
    assert sources.guess_format(text) == "csv"


def test_a_parquet_file_read_through_is_closed(tmp_path):
    """open_parquet opens the file itself (a pyarrow file, not a path pyarrow resolves again):
    each of 30 open sources holds one descriptor, and once read through, with the sources still
    alive, none is left open (Linux /proc); the arrays stay valid after the file is closed."""
    import os

    import numpy as np

    if not os.path.isdir("/proc/self/fd"):
        pytest.skip("counts the descriptors in /proc/self/fd")
    path = _parquet(tmp_path)
    before = len(os.listdir("/proc/self/fd"))
    opened = [sources.open_source(path) for _ in range(30)]
    assert len(os.listdir("/proc/self/fd")) == before + 30
    blocks = [b for src in opened for b in src.iter_blocks([0, 1], 1000)]
    assert len(os.listdir("/proc/self/fd")) == before
    assert all(np.array_equal(b[1], [0.0, 2.0, 1.0]) for b in blocks)
