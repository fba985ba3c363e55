"""Small Parquet histories read ahead of their contacts (issue 28).

A bundle's worker computes a group of contacts one after the other: for each, the lean read of
its file (:func:`fretwear.io.parquet.read_known_block`), the checks, the wear power and the
wear table. Read in a row first, then computed in a row, the same contacts cost 20-30 % less
CPU (1 000-sample files, TUBE_BAV 8 sectors x 6 instants: 0.47-0.58 -> 0.34-0.38 ms a contact
in one process, whether 8 or 250 files are read ahead at a time): pyarrow's reader and
fretwear's computation each keep the processor's caches warm for the next contact instead of
evicting each other's.

:func:`prefetch` reads the files of a few contacts; the lean lane of
:func:`fretwear.io.iter_history_blocks` then takes each file's read (:func:`taken`) instead of
reading it again. Only a file the lean lane would read itself is read ahead (a ``.parquet`` file
of a column layout already resolved, :data:`fretwear.io.sources._LAYOUTS`, of at most
:data:`AHEAD_ROWS` rows): the values are those of the read it replaces, the same function on
the same bytes. A file that fails to read ahead is left to its contact, whose own read reports
it; one not taken is dropped at the end of the block.
"""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Iterable, Iterator
from typing import Any

from fretwear.io.parquet import read_known_block
from fretwear.io.sources import known_layout

#: Most rows of a file read ahead (a longer one is read when its contact comes), and the bytes
#: of columns held ahead past which no other file is (the one that passes them is held: at most
#: AHEAD_BYTES + 3 MB, 2^16 rows of 6 float64 channels).
AHEAD_ROWS = 1 << 16
AHEAD_BYTES = 1 << 25

_HELD = threading.local()  # each thread its own files: a worker's threads run their own groups


def layout_positions(names: list[str], units: dict[int, str]) -> list[int] | None:
    """The positions of the channels' columns in a file of these column ``names`` and
    ``{position: unit}``, where their layout is already resolved (what the lean lane reads),
    else None."""
    found = known_layout(names, units)
    return None if found is None else list(found[0].values())


@contextlib.contextmanager
def prefetch(paths: Iterable[Any], size: int) -> Iterator[int]:
    """Within the block, the files ``paths`` read ahead for the lean lane's reads of at most
    ``size`` rows (:func:`taken`), in this thread; yields how many were read.

    Parameters
    ----------
    paths : iterable of path-like
        The Parquet histories about to be read, in the order they will be (the first ones are
        read until :data:`AHEAD_BYTES` are held).
    size : int
        The block size of the reads that will take them [samples] (their ``chunk_size``).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from fretwear.history import ContactHistory
    >>> from fretwear.io import iter_history_blocks, write_history
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.parquet"
    >>> _ = write_history(ContactHistory(time=[0, 1e-5, 2e-5], normal_force=[20, 30, 25],
    ...                                  vt1=[0, 0.01, 0], vt2=[0, 0, 0]), p)
    >>> _ = list(iter_history_blocks(p))   # its column layout resolved by a first read
    >>> with prefetch([p], 1000) as count:
    ...     blocks = [b.normal_force.tolist() for b in iter_history_blocks(p, 1000)]
    ...     left = taken(p, 1000)          # the lane took the file read ahead
    >>> count, blocks, left
    (1, [[20.0, 30.0, 25.0]], None)
    """
    held: dict[str, tuple] = {}
    budget = AHEAD_BYTES
    limit = min(int(size), AHEAD_ROWS)
    for path in paths:
        if budget <= 0:
            break
        if os.fspath(path) in held:  # two contacts of one file: the second reads it itself
            continue
        try:
            read = read_known_block(path, limit, layout_positions)
        except Exception:  # noqa: BLE001 - its contact's own read says what is wrong
            continue
        if read is None:
            continue
        names, units, _, arrays = read
        held[os.fspath(path)] = (*read, layout_positions(names, units))
        budget -= sum(a.nbytes for a in arrays)
    previous = getattr(_HELD, "files", None)
    _HELD.files = held
    try:
        yield len(held)
    finally:
        _HELD.files = previous


def taken(path: Any, size: int) -> tuple | None:
    """The read of ``path`` held ahead in this thread (:func:`prefetch`), taken once:
    ``(names, units, stored metadata, arrays, positions)`` as
    :func:`~fretwear.io.parquet.read_known_block` gives them plus the columns' positions; None
    where none is held or it has more than ``size`` rows."""
    files = getattr(_HELD, "files", None)
    if not files:
        return None
    read = files.pop(os.fspath(path), None)
    if read is None or len(read[3][0]) > size:
        return None
    return read
