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


def test_new_file_gets_umask_permissions_and_replaced_file_keeps_its_mode(tmp_path):
    # An ordinary open() creates 0666 & ~umask; mkstemp alone would give 0600.
    import os
    import stat

    mask = os.umask(0o022)
    try:
        new = tmp_path / "new.txt"
        with atomic_write(new) as fh:
            fh.write("x")
        assert stat.S_IMODE(new.stat().st_mode) == 0o644
        old = tmp_path / "old.txt"
        old.write_text("y")
        os.chmod(old, 0o640)
        with atomic_write(old) as fh:
            fh.write("z")
        assert stat.S_IMODE(old.stat().st_mode) == 0o640
    finally:
        os.umask(mask)
