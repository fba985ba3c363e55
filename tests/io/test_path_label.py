"""The lean lane's label of a history file (fretwear.io.streaming.path_label) is
``str(pathlib.Path(path))``, the label the full path's Source gives it (the reference), for
every path of up to four components among empty, ".", "..", names and dotted names, after
no, one, two or three leading separators, and for path objects."""

from __future__ import annotations

import itertools
from pathlib import Path, PurePosixPath

import pytest

from fretwear.io.streaming import path_label

PARTS = ("", ".", "..", "a", "c00001.parquet", " ", "...", ".x", "x.")


@pytest.mark.parametrize("lead", ["", "/", "//", "///"])
def test_the_label_is_the_path_s_own(lead):
    for k in range(1, 5):
        for combo in itertools.product(PARTS, repeat=k):
            text = lead + "/".join(combo)
            assert path_label(text) == str(Path(text)), text


def test_a_path_object_is_its_string():
    for path in (Path("/data/c1.parquet"), PurePosixPath("data//c1.parquet/"), Path(".")):
        assert path_label(path) == str(Path(path))
