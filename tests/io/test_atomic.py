"""Atomic output: a failed write leaves the target as it was."""

import pytest

from fretwear.io.atomic import atomic_path, atomic_write


def test_failed_write_keeps_previous_file(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("previous")
    with pytest.raises(RuntimeError), atomic_write(target) as fh:
        fh.write("partial")
        raise RuntimeError("boom")
    assert target.read_text() == "previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_success_replaces_and_creates_parents(tmp_path):
    target = tmp_path / "a" / "b" / "out.txt"
    with atomic_path(target) as tmp:
        tmp.write_text("new")
        assert not target.exists()
    assert target.read_text() == "new"
