"""Streaming a history file with bounded memory (theory §1): :func:`iter_history_chunks`
(validated chunks of a given size sharing their boundary sample), :func:`iter_history_blocks`
(the reader's own blocks, checked without copies: what :func:`fretwear.power.wear_power`
streams) and :func:`history_time_range` (the time range from the file's metadata).
Re-exported by :mod:`fretwear.io`.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from fretwear.errors import FormatError, KeywordError
from fretwear.history import DEFAULT_CHUNK_SIZE, ContactHistory
from fretwear.io.channels import build_history, check_lengths, fast_history
from fretwear.io.guard import warn_whole_read
from fretwear.io.parquet import read_known_block
from fretwear.io.plausibility import StreamPlausibility
from fretwear.io.prefetch import taken
from fretwear.io.sources import _files, _prepare, _stem, known_layout


def _slices(arrays: list[np.ndarray], size: int) -> Iterator[list[np.ndarray]]:
    n = min((a.size for a in arrays), default=0)
    for start in range(0, n, size):
        yield [a[start:start + size] for a in arrays]



def _close(blocks) -> None:
    """Close a reader's block iterator (a generator: its file, its read-ahead thread)."""
    close = getattr(blocks, "close", None)
    if close is not None:
        close()


def _reader_blocks(path, chunk_size, format, units, columns, name, options):
    """The checked chunk size, the opened source and its column mapping, and the reader's
    own blocks of at most ``chunk_size`` rows (a format read whole is sliced, with a warning
    above the size limit): what both chunk iterators start from."""
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) \
            or chunk_size < 2:
        raise KeywordError(f"chunk_size={chunk_size!r}: give an integer >= 2 (samples per chunk)")
    size = int(chunk_size)
    source, mapping, factors, label, metadata = _prepare(path, format, units, columns, name,
                                                         options)
    positions = list(mapping.values())
    if source.iter_blocks is not None:
        blocks = source.iter_blocks(positions, size)
    else:
        warn_whole_read(_files(path), source.label, source.format)
        whole = source.read(positions)
        check_lengths([a.size for a in whole], [source.columns[p] for p in positions],
                      source.label)
        blocks = _slices(whole, size)
    return size, source, mapping, factors, label, metadata, blocks


def _lean_block(path: Any, chunk_size: Any, name: str | None) -> ContactHistory | None:
    """The lean lane of :func:`iter_history_blocks`: a Parquet file (``.parquet``) of one block
    whose column layout was already resolved (:data:`fretwear.io.sources._LAYOUTS`: a bundle's
    files share one), read by one pyarrow call (:func:`fretwear.io.parquet.read_known_block`)
    and checked by the same functions as the full path (:func:`fast_history`,
    :class:`StreamPlausibility`): the same history, name and metadata. None when the file is
    another case, or when anything would raise or a check would warn (its messages gathered,
    not warned): the full path then reads it again and gives the very same errors and warnings
    (their text its own). Saves the full path's
    opening (file checks, format guess, Source, guarded generators): issue 28."""
    if not isinstance(path, (str, os.PathLike)) or isinstance(chunk_size, bool) \
            or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 2 \
            or not os.fspath(path).lower().endswith(".parquet"):
        return None
    try:
        return _known_parquet(path, int(chunk_size), name)
    except Exception:  # noqa: BLE001 - the full path raises it again, with its own message
        return None


def _known_parquet(path: Any, size: int, name: str | None) -> ContactHistory | None:
    layout: list[tuple] = []

    def positions_of(names: list[str], units: dict[int, str]) -> list[int] | None:
        found = known_layout(names, units)
        if found is None:
            return None
        layout.append(found)
        return list(found[0].values())

    ahead = taken(path, size)  # read ahead of its contact (fretwear.io.prefetch), or read now
    if ahead is not None and positions_of(ahead[0], ahead[1]) == ahead[4]:
        read = ahead[:4]
    else:
        layout.clear()
        read = read_known_block(path, size, positions_of)
    if read is None:
        return None
    names, _, stored, arrays = read
    mapping, unit_of, factors, used = (dict(d) for d in layout[0][:4])
    label = path_label(path)  # open_parquet's Source label
    metadata = dict(stored.get("metadata", {}))
    metadata.update(source=label, format="parquet", columns=used, units=unit_of,
                    unit_factors=factors, ignored_columns=list(layout[0][4]))
    chunk = fast_history(dict(zip(mapping, arrays, strict=True)),
                         metadata=dict(metadata, chunk=0, first_row=0), first_row=0,
                         columns=names, mapping=mapping, factors=factors, label=label,
                         name=name if name is not None else (stored.get("name") or _stem(path)))
    # the checks' messages gathered, not warned (no change to the process's warning state,
    # which other threads share): a history that would warn is read by the full path
    plausibility = StreamPlausibility(emit=False)
    plausibility.update(chunk, check=True)
    plausibility.finish()
    return None if plausibility.found else chunk


def path_label(path: Any) -> str:
    """``str(pathlib.Path(path))``, the label of a history file's Source, without making a
    Path where ``path`` is a string already in the form a Path gives it (POSIX: no empty
    component, no "." one, no trailing separator): a bundle's contact, 2 µs of its lean read
    (issue 28). Any other path goes through ``Path``.

    Examples
    --------
    >>> path_label("/data/c1.parquet"), path_label("./data//c1.parquet/")
    ('/data/c1.parquet', 'data/c1.parquet')
    """
    if (type(path) is str and os.sep == "/" and os.altsep is None and path and path != "."
            and "//" not in path and "/./" not in path and not path.startswith("./")
            and not path.endswith(("/", "/."))):
        return path
    return str(Path(path))


def iter_history_chunks(path: Any, chunk_size: int = DEFAULT_CHUNK_SIZE,
                        format: str | None = None, *, units: Mapping[str, str] | None = None,
                        columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                        **options: Any) -> Iterator[ContactHistory]:
    """Read a history chunk by chunk, with bounded memory; consecutive chunks share one sample.

    Parameters
    ----------
    path, format, units, columns, name, **options
        As :func:`read_history`.
    chunk_size : int
        Samples per chunk, at least 2 (default 10⁶, about 80 MB for ten channels).

    Yields
    ------
    ContactHistory
        Chunk ``k`` holds the rows ``[k·(m−1), k·(m−1) + m)`` of the file, ``m = chunk_size``
        (the last chunk may be shorter, never a single sample): **the last sample of chunk k is
        the first sample of chunk k+1**. Every interval between consecutive samples therefore
        lies in exactly one chunk, so a reduction over intervals (the trapezoid rule of the
        wear power) summed over the chunks equals the one-shot reduction, and the time
        validation sees every pair of neighbours. ``metadata`` adds ``chunk`` (k) and
        ``first_row`` (file row of the chunk's first sample).

    Notes
    -----
    Bounded memory: Parquet is read by record batches, HDF5 and NetCDF by slices, CSV by pandas
    chunks. NPZ and Code_Aster text files are read whole and then sliced.
    With ``m`` samples per chunk, ``n`` samples give ``ceil((n − 1)/(m − 1))`` chunks.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv"
    >>> _ = p.write_text("t [ms],fn,vt1,vt2\\n" + "".join(f"{i},1,1,0\\n" for i in range(7)))
    >>> [(1e3 * c.time).tolist() for c in iter_history_chunks(p, chunk_size=3)]
    [[0.0, 1.0, 2.0], [2.0, 3.0, 4.0], [4.0, 5.0, 6.0]]
    """
    size, source, mapping, factors, label, metadata, blocks = _reader_blocks(
        path, chunk_size, format, units, columns, name, options)
    try:
        channels = list(mapping)
        pending: list[list[np.ndarray]] = []
        pending_rows = 0
        carry: list[np.ndarray] | None = None
        row = 0  # file row of the next sample not yet in a chunk

        def emit(parts: list[list[np.ndarray]], k: int, first_row: int) -> ContactHistory:
            arrays = {ch: np.concatenate([p[j] for p in parts]) for j, ch in enumerate(channels)}
            meta = dict(metadata, chunk=k, first_row=first_row)
            chunk = build_history(arrays, columns=source.columns, mapping=mapping, factors=factors,
                                  label=source.label, name=label, metadata=meta,
                                  first_row=first_row)
            plausibility.update(chunk, check=True)  # each check warns once per file
            return chunk

        plausibility = StreamPlausibility()

        k = 0
        for block in blocks:
            if not block or block[0].size == 0:
                continue
            pending.append(block)
            pending_rows += block[0].size
            need = size - (0 if carry is None else 1)
            while pending_rows >= need:
                merged = (pending[0] if len(pending) == 1 else
                          [np.concatenate([p[j] for p in pending]) for j in range(len(channels))])
                take = [a[:need] for a in merged]
                rest = [a[need:] for a in merged]
                parts = [take] if carry is None else [carry, take]
                first = row - (0 if carry is None else 1)
                yield emit(parts, k, first)
                k += 1
                row += need
                carry = [a[-1:] for a in take]
                pending = [rest] if rest[0].size else []
                pending_rows = rest[0].size
                need = size - 1
        if pending_rows or k == 0:
            parts = ([] if carry is None else [carry]) + pending
            if not parts:
                raise FormatError(f"{source.label}: no data rows (a header only?); a history "
                                  "needs at least two instants")
            yield emit(parts, k, row - (0 if carry is None else 1))
        plausibility.finish()  # the file's largest force (a chunk's says nothing of the file)
    finally:
        # closed here, not when the generator is collected: a traceback holding this
        # frame would keep a read-ahead thread and the file open (io.readahead)
        _close(blocks)


def history_time_range(path: Any, format: str | None = None, *,
                       units: Mapping[str, str] | None = None,
                       columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                       **options: Any) -> tuple[float, float] | None:
    """First and last instant [s] of a history file without reading it through, or None.

    Parquet: the time column's statistics in the first and last row groups (else the values at
    their ends); HDF5 and NetCDF: the time dataset's first and last values. Other formats
    (text, NPZ) give None: the caller then needs a pass. Arguments as :func:`read_history`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from fretwear.io import write_history
    >>> h = ContactHistory(time=[0.5, 1.0, 2.5], normal_force=[1, 1, 1], vt1=[0, 0, 0],
    ...                    vt2=[0, 0, 0])
    >>> p = write_history(h, pathlib.Path(tempfile.mkdtemp()) / "h.parquet")
    >>> history_time_range(p)
    (0.5, 2.5)
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:  # the file declares seconds
    ...     warnings.simplefilter("always")
    ...     history_time_range(p, units={"time": "ms"})
    (0.0005, 0.0025)
    >>> caught[0].category.__name__
    'UnitsWarning'
    """
    source, mapping, factors, _, _ = _prepare(path, format, units, columns, name, options)
    if source.ends is None:
        return None
    first, last = source.ends(mapping["time"])
    factor = factors.get("time", 1.0)
    return (first * factor, last * factor) if factor != 1.0 else (first, last)


def iter_history_blocks(path: Any, chunk_size: int = DEFAULT_CHUNK_SIZE,
                        format: str | None = None, *, units: Mapping[str, str] | None = None,
                        columns: Mapping[Any, str | None] | None = None, name: str | None = None,
                        **options: Any) -> Iterator[ContactHistory]:
    """Read a history block by block as the file gives them: no shared sample, no copy.

    The streaming reader of the wear power (:class:`fretwear.power.PowerAccumulator` bridges
    the interval between two blocks). Unlike :func:`iter_history_chunks`, the blocks are the
    reader's own (Parquet record batches of at most ``chunk_size`` rows, or the whole file as
    one table when it holds no more; HDF5/NetCDF slices; slices of a whole read for the text
    formats), consecutive without overlap, and each is
    checked by :func:`fretwear.io.channels.fast_history`: its arrays go into the history
    without a copy when they pass (the same errors otherwise, row numbers of the file). The
    instants must also increase across blocks. A block of one row is joined to the next (the
    last one comes with the previous block's last sample). The plausibility of the values in
    SI (:func:`fretwear.io.plausibility.check_plausibility`) is checked on the first block: a
    wrong unit shows there; the smallest plausible largest force, on the whole file's largest
    force after the last block (:class:`fretwear.io.plausibility.StreamPlausibility`).
    A Parquet file of one block, of a column layout already read and without options, takes a
    lean lane (:func:`_lean_block`): one pyarrow read and the same checks, the full path
    again for anything that raises or warns (the same history, errors and warnings).

    Parameters
    ----------
    path, format, units, columns, name, **options
        As :func:`read_history`.
    chunk_size : int
        Largest block [samples] (>= 2).

    Yields
    ------
    ContactHistory
        Consecutive blocks; ``metadata`` adds ``chunk`` and ``first_row``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv"
    >>> _ = p.write_text("t [ms],fn,vt1,vt2\\n" + "".join(f"{i},1,1,0\\n" for i in range(7)))
    >>> [(1e3 * c.time).tolist() for c in iter_history_blocks(p, chunk_size=3)]
    [[0.0, 1.0, 2.0], [3.0, 4.0, 5.0], [5.0, 6.0]]
    """
    if format is None and units is None and columns is None and not options:
        lean = _lean_block(path, chunk_size, name)
        if lean is not None:  # the common case: silent, and what the full path would give
            yield lean
            return
    size, source, mapping, factors, label, metadata, blocks = _reader_blocks(
        path, chunk_size, format, units, columns, name, options)
    try:
        channels = list(mapping)
        row = 0
        k = 0
        last: list[np.ndarray] | None = None  # the previous block's last sample
        pending: list[np.ndarray] | None = None  # a single-row block waiting for the next one
        plausibility = StreamPlausibility()
        build = dict(columns=source.columns, mapping=mapping, factors=factors, label=source.label,
                     name=label)
        for block in blocks:
            if not block or block[0].size == 0:
                continue
            if pending is not None:
                block = [np.concatenate((a, b)) for a, b in zip(pending, block, strict=True)]
                pending = None
            if block[0].size < 2:
                pending = block
                continue
            if last is not None and not float(block[0][0]) > float(last[0][0]):
                # the instants do not increase across the blocks: the history of the two samples
                # raises the error with their rows
                build_history({ch: np.concatenate((last[j], block[j][:1]))
                               for j, ch in enumerate(channels)}, metadata=metadata,
                              first_row=row - 1, **build)
            chunk = fast_history(dict(zip(channels, block, strict=True)),
                                 metadata=dict(metadata, chunk=k, first_row=row), first_row=row,
                                 **build)
            plausibility.update(chunk, check=k == 0)
            yield chunk
            last = [a[-1:] for a in block]
            row += block[0].size
            k += 1
        if pending is not None:
            if last is None:  # the whole file is one row
                build_history(dict(zip(channels, pending, strict=True)), metadata=metadata, **build)
            chunk = build_history({ch: np.concatenate((last[j], pending[j]))
                                   for j, ch in enumerate(channels)},
                                  metadata=dict(metadata, chunk=k, first_row=row - 1),
                                  first_row=row - 1, **build)
            plausibility.update(chunk, check=False)
            yield chunk
        elif k == 0:
            raise FormatError(f"{source.label}: no data rows (a header only?); a history "
                              "needs at least two instants")
        plausibility.finish()  # the file's largest force (a block's says nothing of the file)
    finally:
        # closed here, not when the generator is collected: a traceback holding this
        # frame would keep a read-ahead thread and the file open (io.readahead)
        _close(blocks)

