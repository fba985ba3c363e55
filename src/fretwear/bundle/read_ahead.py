"""An iterator's next items made in a thread while its caller works on the current one."""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

T = TypeVar("T")


def read_ahead(items: Iterable[T], depth: int = 1) -> Iterator[T]:
    """The items of ``items`` in their order, the next ``depth`` ones made in a thread while
    the caller holds the current one: where making an item waits on files or releases the
    GIL (pyarrow reading Parquet, the columns made NumPy arrays), that time overlaps the
    caller's work on the item before (issue 28: the summary's pieces of the table read at
    10^5 contacts were 1 s after the last result, alone on its core).

    ``items`` is advanced in one thread at a time, in order; an error making an item is
    raised where that item is asked for. Held at once: the caller's item and up to ``depth``
    made ahead. Closing the iterator early (or an error in the caller) waits for the item
    being made, then closes ``items`` (a generator's ``finally`` and ``with`` blocks run).
    """
    if depth < 1:
        raise ValueError(f"depth must be >= 1 (items made ahead), got {depth!r}")
    source = iter(items)
    end = object()
    try:
        with ThreadPoolExecutor(1, thread_name_prefix="fretwear-read-ahead") as pool:
            ahead = deque(pool.submit(next, source, end) for _ in range(depth))
            try:
                while True:
                    item = ahead.popleft().result()
                    if item is end:
                        return
                    ahead.append(pool.submit(next, source, end))
                    yield item
                    del item  # not held while the next one is waited for
            finally:
                for future in ahead:
                    future.cancel()
    finally:  # the pool's thread done: the source closed here
        close = getattr(source, "close", None)
        if close is not None:
            close()
