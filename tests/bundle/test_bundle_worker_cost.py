"""A worker's fixed costs per contact (issue 28, point 2): what a bundle does once a contact."""

from __future__ import annotations

import collections

import pytest
from bundle_helpers import oscillator, write_bundle

import fretwear.io.sources as sources
import fretwear.io.streaming as streaming
from fretwear.bundle import run_bundle


def test_each_history_file_is_opened_once(tmp_path, monkeypatch):
    """A contact's file is opened by one reader (the stream of the wear power), its units
    checked against the geometry on the block that stream reads: the probe that read the
    first chunk apart opened every file twice (fails before: 2 opens a file). A file of a
    layout already known is opened by the stream's lean lane instead (one pyarrow open,
    :func:`fretwear.io.parquet.read_known_block`): counted with the reader's. The first file
    of a layout is opened by both (the lane finds the layout unknown, the full path learns
    it): once a layout and worker process."""
    pytest.importorskip("pyarrow")
    manifest, case = write_bundle(tmp_path, oscillator(), count=3)
    opened = collections.Counter()
    original = sources.open_source

    def counting(path, *args, **kwargs):
        opened[str(path)] += 1
        return original(path, *args, **kwargs)

    monkeypatch.setattr(sources, "open_source", counting)
    monkeypatch.setattr(sources, "_LAYOUTS", collections.OrderedDict())  # no layout known
    lean = streaming.read_known_block

    def counting_lean(path, *args, **kwargs):
        opened[str(path)] += 1
        return lean(path, *args, **kwargs)

    monkeypatch.setattr(streaming, "read_known_block", counting_lean)
    result = run_bundle(manifest, case, scheduler="serial")
    assert result.stats["done"] == 3
    assert len(opened) == 3 and sorted(opened.values()) == [1, 1, 2], opened
