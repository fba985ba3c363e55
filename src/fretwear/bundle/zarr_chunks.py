"""Whole chunks of a Zarr (format 2) array appended along its first axis without zarr's machinery.

:class:`fretwear.bundle.result_dataset.GridZarr` appends each row group of the table (some
2 800 contacts) to the arrays of ``dataset.zarr`` along ``contact``. zarr's ``Array.append``
cost 2-3 ms of the client's CPU an array a group (a resize, then the write through its
asynchronous codec pipeline and thread pool), where compressing the data takes some 0.1 ms;
and a group that does not end on a chunk's edge had its last chunk written padded, then read,
decoded, merged and encoded again by the next group (issue 28: 2.2 s of the client's CPU at
10^5 contacts, in zarr's threads). :class:`ChunkAppender` keeps the values past the last whole
chunk, encodes each whole chunk once with the array's own compressor and writes its file
under the array's key, and at the end writes the last chunk (padded with the fill value, as
zarr stores an edge chunk), then has zarr itself resize the array (its metadata).

The files are those zarr's ``append`` writes for the same values, byte for byte
(test_bundle_zarr_appender.py): the same chunks of the same values, the same compressor, a
chunk equal to the fill value everywhere not written (zarr's ``write_empty_chunks`` False,
its default). Only for an array this module knows the layout of (:func:`appender`): format 2,
no filter, C order, chunked along the first axis alone, its length a whole number of chunks;
None otherwise (the caller appends by zarr).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np


def appender(array: Any, folder: Path) -> ChunkAppender | None:
    """A :class:`ChunkAppender` of the zarr (>= 3) ``array`` stored in ``folder`` (the
    array's directory), or None where its layout is not the one this module writes."""
    try:
        import zarr
        from zarr.core.metadata.v2 import ArrayV2Metadata
    except ImportError:  # zarr 2: its own append
        return None
    meta = array.metadata
    if not isinstance(meta, ArrayV2Metadata) or meta.filters or meta.order != "C" \
            or not meta.chunks or tuple(meta.chunks[1:]) != tuple(meta.shape[1:]) \
            or meta.shape[0] % meta.chunks[0] or not folder.is_dir():
        return None
    fill = meta.fill_value if meta.fill_value is not None else meta.dtype.default_scalar()
    return ChunkAppender(array, folder, meta, fill,
                         bool(zarr.config.get("array.write_empty_chunks")))


class ChunkAppender:
    """Values appended along the first axis of one array, written a whole chunk at a time
    (see the module's docstring; made by :func:`appender`)."""

    def __init__(self, array: Any, folder: Path, meta: Any, fill: Any,
                 write_empty: bool) -> None:
        self.array, self.folder, self.meta = array, folder, meta
        self.fill, self.write_empty = fill, write_empty
        self.dtype = meta.dtype.to_native_dtype()
        self.size = int(meta.chunks[0])
        self.written = int(meta.shape[0]) // self.size  # whole chunks in the store
        self.tail = np.empty((0, *meta.shape[1:]), dtype=self.dtype)

    def add(self, data: np.ndarray) -> None:
        """Append ``data`` (the array's type and shape beyond the first axis): every chunk
        it completes written."""
        data = np.concatenate([self.tail, data]) if len(self.tail) else data
        whole = len(data) // self.size
        for k in range(whole):
            self._write(data[k * self.size:(k + 1) * self.size])
        self.tail = data[whole * self.size:].copy()  # not a view holding the group

    def close(self) -> None:
        """Write the last chunk (padded with the fill value) and set the array's length."""
        length = self.written * self.size + len(self.tail)
        if len(self.tail):
            self._write(self.tail)
        self.array.resize((length, *self.meta.shape[1:]))

    def _write(self, values: np.ndarray) -> None:
        """The next chunk, of ``values`` (at most a chunk's length; the rest the fill
        value), written as zarr writes it: not at all where it is the fill value all over."""
        if len(values) < self.size:
            chunk = np.full((self.size, *values.shape[1:]), self.fill, dtype=self.dtype)
            chunk[:len(values)] = values
        else:
            chunk = np.ascontiguousarray(values, dtype=self.dtype)
        key = self.meta.encode_chunk_key((self.written,) + (0,) * (chunk.ndim - 1))
        self.written += 1
        if not self.write_empty and _all_fill(chunk, self.fill):
            return
        from numcodecs.compat import ensure_bytes

        data = self.meta.compressor.encode(chunk) if self.meta.compressor else chunk
        path = self.folder / key
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(ensure_bytes(data))


def _all_fill(chunk: np.ndarray, fill: Any) -> bool:
    """Whether every value of ``chunk`` is ``fill``, as zarr decides a chunk is empty
    (``NDBuffer.all_equal``): a NaN equal to NaN in numbers, a zero fill compared bit for bit
    (-0.0 is not 0.0)."""
    kind = chunk.dtype.kind
    if kind in "USTOV":
        return bool(np.array_equal(chunk, np.broadcast_to(np.asarray(fill), chunk.shape)))
    other = np.asarray(fill)
    if other.dtype.kind == "f" and other == 0.0:
        zero = np.broadcast_to(np.asarray(fill, dtype=chunk.dtype), chunk.shape)
        void = f"V{chunk.dtype.itemsize}"
        return bool(np.array_equal(chunk.view(void), np.ascontiguousarray(zero).view(void)))
    return bool(np.array_equal(chunk, np.broadcast_to(other, chunk.shape), equal_nan=True))
