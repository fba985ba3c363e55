"""An iterator's next items made in a thread while its caller works on the current one."""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Generic, TypeVar

T = TypeVar("T")


class ReadAhead(Iterator[T], Generic[T]):
    """The items of ``items`` in their order, the next ``depth`` ones made in a thread from
    the start (the first ones before the caller asks) and while the caller holds the current
    one: where making an item waits on files or releases the GIL (pyarrow reading Parquet,
    the columns made NumPy arrays), that time overlaps the caller's work (issue 28: the
    summary's pieces of the table read at 10^5 contacts were 1 s after the last result, alone
    on its core).

    ``items`` is advanced in one thread at a time, in order; an error making an item is
    raised where that item is asked for. Held at once: the caller's item and up to ``depth``
    made ahead. :meth:`close` (also at the end, on an error, and as a context manager)
    waits for the item being made, then closes ``items`` (a generator's ``finally`` and
    ``with`` blocks run).
    """

    def __init__(self, items: Iterable[T], depth: int = 1) -> None:
        if depth < 1:
            raise ValueError(f"depth must be >= 1 (items made ahead), got {depth!r}")
        self._source = iter(items)
        self._end = object()
        self._pool = ThreadPoolExecutor(1, thread_name_prefix="fretwear-read-ahead")
        self._ahead = deque(self._pool.submit(next, self._source, self._end)
                            for _ in range(depth))

    def __iter__(self) -> ReadAhead[T]:
        return self

    def __next__(self) -> T:
        if not self._ahead:
            raise StopIteration
        try:
            item = self._ahead.popleft().result()
        except BaseException:
            self.close()
            raise
        if item is self._end:
            self.close()
            raise StopIteration
        self._ahead.append(self._pool.submit(next, self._source, self._end))
        return item

    def close(self) -> None:
        """Stop: nothing more made (the item being made waited for), ``items`` closed."""
        for future in self._ahead:
            future.cancel()
        self._ahead.clear()
        self._pool.shutdown(wait=True)
        close = getattr(self._source, "close", None)
        if close is not None:
            close()

    def __enter__(self) -> ReadAhead[T]:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
