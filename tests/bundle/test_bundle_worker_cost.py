"""A worker's fixed costs per contact (issue 28, point 2): what a bundle does once a contact."""

from __future__ import annotations

import collections

import pytest
from bundle_helpers import oscillator, write_bundle

import fretwear.io.sources as sources
from fretwear.bundle import run_bundle


def test_each_history_file_is_opened_once(tmp_path, monkeypatch):
    """A contact's file is opened by one reader (the stream of the wear power), its units
    checked against the geometry on the block that stream reads: the probe that read the
    first chunk apart opened every file twice (fails before: 2 opens a file)."""
    pytest.importorskip("pyarrow")
    manifest, case = write_bundle(tmp_path, oscillator(), count=3)
    opened = collections.Counter()
    original = sources.open_source

    def counting(path, *args, **kwargs):
        opened[str(path)] += 1
        return original(path, *args, **kwargs)

    monkeypatch.setattr(sources, "open_source", counting)
    result = run_bundle(manifest, case, scheduler="serial")
    assert result.stats["done"] == 3
    assert len(opened) == 3 and set(opened.values()) == {1}, opened
