"""A manifest's history paths (``fretwear.bundle.manifest_paths.HistoryPaths``) are the text
``(directory / cell).resolve()`` gives, whether a folder is listed or its files looked at one by
one: the independent computation is ``pathlib.Path.resolve`` itself."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import fretwear.bundle.manifest_paths as mp
from fretwear.bundle.manifest import read_manifest


@pytest.fixture
def tree(tmp_path: Path) -> tuple[Path, list[str]]:
    """A manifest folder with plain files, a link to a file elsewhere, a link to a folder, a
    subfolder, and cells naming a missing file, ``..``, an absolute path, a trailing slash."""
    (tmp_path / "far").mkdir()
    (tmp_path / "far" / "real.csv").write_text("x")
    (tmp_path / "sub").mkdir()
    for k in range(6):
        (tmp_path / f"h{k}.csv").write_text("x")
    (tmp_path / "sub" / "s.csv").write_text("x")
    os.symlink(tmp_path / "far" / "real.csv", tmp_path / "link.csv")
    os.symlink(tmp_path / "far", tmp_path / "linked")
    cells = [f"h{k}.csv" for k in range(6)] + [
        "link.csv", "linked/real.csv", "sub/s.csv", "missing.csv", "sub/../h0.csv", "../x.csv",
        str(tmp_path / "h1.csv"), "sub/", ".", "sub/missing.csv"]
    return tmp_path, cells


@pytest.mark.parametrize("listed_from", [1, 10**9])
def test_paths_are_resolve(tree, monkeypatch, listed_from):
    directory, cells = tree
    monkeypatch.setattr(mp, "LISTED_FROM", listed_from)  # every folder listed, or none
    path_of = mp.HistoryPaths(cells, directory)
    expected = [str((directory / c).resolve()) for c in cells]
    assert [path_of(c) for c in cells] == expected
    # the link to a file is its target, not the link's own path
    assert path_of("link.csv") == str(directory / "far" / "real.csv")


def test_listing_given_up_past_its_span(tree, monkeypatch):
    """A folder holding many more entries than the manifest's files in it is not listed (the
    listing stops), and the paths are the same."""
    directory, cells = tree
    monkeypatch.setattr(mp, "LISTED_FROM", 1)
    monkeypatch.setattr(mp, "LISTING_SPAN", 0)  # any entry is past the span
    path_of = mp.HistoryPaths(cells, directory)
    assert [path_of(c) for c in cells] == [str((directory / c).resolve()) for c in cells]
    assert path_of.links[str(directory.resolve())] is None


def test_file_made_after_listing(tree, monkeypatch):
    """A name the listing lacks (made since) is looked at alone: a link made after the listing
    is still followed."""
    directory, cells = tree
    monkeypatch.setattr(mp, "LISTED_FROM", 1)
    path_of = mp.HistoryPaths(["h0.csv", "late.csv"], directory)
    assert path_of("h0.csv") == str(directory.resolve() / "h0.csv")  # the folder listed
    os.symlink(directory / "far" / "real.csv", directory / "late.csv")
    assert path_of("late.csv") == str(directory / "far" / "real.csv")


def test_manifest_rows_use_resolved_paths(tree, monkeypatch):
    """read_manifest's history paths, through a listed folder, are Path.resolve's."""
    directory, cells = tree
    monkeypatch.setattr(mp, "LISTED_FROM", 2)
    rel = [c for c in cells if c not in ("sub/", ".")]
    text = "contact,history\n" + "".join(f"c{k},{c}\n" for k, c in enumerate(rel))
    (directory / "manifest.csv").write_text(text)
    man = read_manifest(directory / "manifest.csv")
    assert [r.history.path for r in man.rows] == [str((directory / c).resolve()) for c in rel]
