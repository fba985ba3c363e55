"""Read ahead: the next block of a file is decoded in a thread while this one is reduced.

A streamed history alternates two costs: decoding a block (pyarrow, which releases the GIL) and
reducing it (the power kernel, the block's checks). Run one after the other, their times add;
with the next block decoded by a background thread while the caller reduces the current one,
the slower of the two sets the pace. :func:`read_ahead` wraps a block iterator so: at most
``depth`` blocks wait decoded, so the memory stays bounded by ``depth + 2`` blocks (one being
reduced, ``depth`` waiting, one being decoded), whatever the length of the file.

The blocks and their order are those of the wrapped iterator: the values the caller computes
from them are unchanged. An exception raised while decoding is raised by the consumer at the
block where it happened; a consumer that stops early (an error in its own code, ``close()``, a
``break``) stops the thread and closes the wrapped iterator when it closes this generator or
drops it (a generator kept alive, e.g. by a traceback holding the frame that iterates it, keeps
its thread waiting: close it, as :mod:`fretwear.io.streaming` does in a ``finally``).

Examples
--------
>>> list(read_ahead(iter([[1], [2], [3]])))
[[1], [2], [3]]
>>> def failing():
...     yield [1]
...     raise OSError("disk")
>>> blocks = read_ahead(failing())
>>> next(blocks)
[1]
>>> next(blocks)
Traceback (most recent call last):
OSError: disk
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Iterator
from typing import TypeVar

T = TypeVar("T")

#: Blocks decoded ahead of the consumer.
DEPTH = 1
_POLL = 0.05  # [s] how often a blocked producer checks whether the consumer stopped
_END = object()


def read_ahead(blocks: Iterator[T], depth: int = DEPTH) -> Iterator[T]:
    """The items of ``blocks``, the next ones produced by a background thread.

    Parameters
    ----------
    blocks : iterator
        The blocks (e.g. a Parquet file's record batches as arrays); produced in a daemon
        thread, at most ``depth`` ahead of the consumer.
    depth : int
        Number of blocks waiting decoded (>= 1).

    Yields
    ------
    The items of ``blocks``, in order.

    Raises
    ------
    Exception
        Whatever producing a block raised, at that block.
    """
    if depth < 1:
        raise ValueError(f"depth must be >= 1, got {depth}")
    waiting: queue.Queue = queue.Queue(maxsize=depth)
    stop = threading.Event()

    def put(item) -> bool:
        while not stop.is_set():
            try:
                waiting.put(item, timeout=_POLL)
                return True
            except queue.Full:
                continue
        return False

    def produce() -> None:
        try:
            for block in blocks:
                if not put((block, None)):
                    return
            put((_END, None))
        except BaseException as exc:  # noqa: BLE001 - handed to the consumer
            put((_END, exc))
        finally:
            close = getattr(blocks, "close", None)
            if close is not None:
                close()

    thread = threading.Thread(target=produce, name="fretwear-read-ahead", daemon=True)
    thread.start()
    try:
        while True:
            block, error = waiting.get()
            if error is not None:
                raise error
            if block is _END:
                return
            yield block
    finally:
        stop.set()
        # unblock a producer waiting on a full queue, then join it; unless the cyclic GC
        # collected this generator in the producer thread itself, which cannot join itself: it
        # sees ``stop`` at its next put and closes the wrapped iterator
        while thread.is_alive() and threading.current_thread() is not thread:
            try:
                waiting.get_nowait()
            except queue.Empty:
                pass
            thread.join(timeout=_POLL)
