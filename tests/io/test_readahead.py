"""fretwear.io.readahead: blocks decoded ahead in a thread keep their order, their errors, a
bounded lead over the consumer, and stop with it."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.io import iter_history_blocks, read_history, write_history
from fretwear.io.readahead import read_ahead


def counting(n: int, produced: list, closed: threading.Event):
    try:
        for k in range(n):
            produced.append(k)
            yield k
    finally:
        closed.set()


def test_order_and_end():
    produced, closed = [], threading.Event()
    assert list(read_ahead(counting(50, produced, closed))) == list(range(50))
    assert closed.wait(1.0)


@pytest.mark.parametrize("depth", [1, 3])
def test_lead_over_the_consumer_is_bounded(depth):
    """The producer is at most depth + 1 blocks ahead (depth waiting, one being made): the
    memory of a streamed file is bounded by a few blocks."""
    produced, closed = [], threading.Event()
    blocks = read_ahead(counting(100, produced, closed), depth=depth)
    for consumed in range(1, 6):
        next(blocks)
        time.sleep(0.05)  # let the producer run as far as it can
        assert len(produced) <= consumed + depth + 1
    blocks.close()
    assert closed.wait(1.0)  # stopping early closes the wrapped iterator
    assert not any(t.name == "fretwear-read-ahead" for t in threading.enumerate())


def test_an_error_reaches_the_consumer_at_its_block():
    def failing():
        yield 1
        yield 2
        raise OSError("disk read failed")

    blocks = read_ahead(failing())
    assert [next(blocks), next(blocks)] == [1, 2]
    with pytest.raises(OSError, match="disk read failed"):
        next(blocks)


def test_parquet_blocks_equal_the_whole_read(tmp_path):
    """The Parquet reader's blocks (read ahead) are the whole file's rows from their first row
    on, bit for bit, and cover it."""
    rng = np.random.default_rng(7)
    t = np.cumsum(rng.uniform(1e-5, 2e-5, 10_001))
    h = ContactHistory(time=t, normal_force=np.abs(rng.normal(0, 5, t.size)),
                       vt1=rng.normal(0, 0.1, t.size), vt2=rng.normal(0, 0.1, t.size))
    path = write_history(h, tmp_path / "h.parquet", row_group_size=999)
    whole = read_history(path)
    chunks = list(iter_history_blocks(path, 1_000))
    assert len(chunks) > 5
    covered = np.zeros(len(whole), dtype=bool)
    for c in chunks:
        a = c.metadata["first_row"]
        covered[a:a + len(c)] = True
        for channel in ("time", "normal_force", "vt1", "vt2"):
            np.testing.assert_array_equal(getattr(c, channel),
                                          getattr(whole, channel)[a:a + len(c)])
    assert covered.all()


def _read_ahead_threads() -> int:
    return sum(t.name == "fretwear-read-ahead" for t in threading.enumerate())


def test_collected_in_its_own_producer_thread(monkeypatch):
    """The generator collected by the cyclic GC while it runs in the producer thread (any thread
    that allocates may run the GC): its clean-up must not try to join the thread it runs in.
    Oracle: no exception reaches sys.unraisablehook (before the fix: RuntimeError 'cannot join
    current thread'), the producer stops and closes the wrapped iterator."""
    import gc

    unraisable = []
    monkeypatch.setattr("sys.unraisablehook", unraisable.append)
    consumed, closed = threading.Event(), threading.Event()

    def blocks():
        try:
            yield 1
            consumed.wait(5.0)
            gc.collect()  # in the producer thread: collects the consumer's generator below
            yield 2
        finally:
            closed.set()

    gen = read_ahead(blocks())
    cycle: list = [gen]
    cycle.append(cycle)  # reachable only through a reference cycle: the GC's to collect
    assert next(gen) == 1
    del gen, cycle
    consumed.set()
    assert closed.wait(5.0)
    deadline = time.monotonic() + 5.0
    while _read_ahead_threads() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert _read_ahead_threads() == 0
    assert [str(u.exc_value) for u in unraisable] == []


@pytest.mark.parametrize("reader", ["blocks", "chunks"])
def test_an_error_in_a_later_block_stops_the_thread(tmp_path, reader):
    """A history error found in a later block of a Parquet file read ahead (instants not
    increasing at row 5500): the read-ahead thread is stopped and the file closed when the error
    leaves the iterator, not when its traceback (which holds the iterator's frame) is freed.
    Oracle: no 'fretwear-read-ahead' thread alive while the exception is still referenced."""
    from fretwear.errors import HistoryError
    from fretwear.io import iter_history_chunks

    n = 10_000
    t = np.arange(n) * 1e-4
    t[5500] = t[5499]
    h = ContactHistory(time=np.arange(n) * 1e-4, normal_force=np.full(n, 10.0),
                       vt1=np.full(n, 0.01), vt2=np.zeros(n))
    path = write_history(h, tmp_path / "h.parquet", row_group_size=1000)
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    table = table.set_column(0, "time", [t])
    pq.write_table(table, path, row_group_size=1000)
    iterate = iter_history_blocks if reader == "blocks" else iter_history_chunks
    with pytest.raises(HistoryError, match="not strictly increasing") as caught:
        for _ in iterate(path, 1000):
            pass
    assert caught.value.__traceback__ is not None  # the frames are still referenced
    time.sleep(0.1)
    assert _read_ahead_threads() == 0
