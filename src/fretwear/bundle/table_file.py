"""A bundle's ``table.parquet`` written from its Parquet parts without the whole table in memory.

The parts hold the contacts' rows in the order they arrived; the table holds them in the
manifest's order. Where each part holds a consecutive run of the manifest's contacts (a run
computing every contact, its groups consecutive slices of the manifest: the usual case),
:class:`PrefixTable` appends each part to the table while the results arrive, as soon as
every contact before it is resolved. Otherwise (a restart mixing earlier parts, stale rows,
parts of interleaved contacts) :func:`stream_table` sorts them out of core at the end in two
passes over the parts:

1. each part is read once and its rows dealt into *buckets* of consecutive manifest positions
   (about :data:`ROWS_PER_GROUP` rows each), appended to one temporary Arrow file per bucket;
2. each bucket is read back, put in the manifest's order (a stable sort: a contact's rows stay
   in its part's order), given the identity columns, and written as one row group.

The client holds one part and one bucket at a time (issue 28: at 10^5 contacts the table,
1.2 GB, was held whole, then copied to be written). The file read back is the table the
in-memory assembly gives, row for row and dtype for dtype (test_bundle_table_stream.py).
:func:`read_columns` reads some columns of the written table (the summary's).
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.datasets import require
from fretwear.bundle.manifest import IDENTITY
from fretwear.io.atomic import atomic_path
from fretwear.table import COLUMNS

#: Rows of a bucket, the table's row group (a bucket's Arrow and pandas copies: some 50 MB
#: at the benchmark's 250 bytes a row).
ROWS_PER_GROUP = 1 << 17

#: The table's columns :func:`fretwear.bundle.result.summarize` reads.
SUMMARY_COLUMNS = ("contact", "instant", "sector", "depth_mobile", "power",
                   "depth_mobile_sector", "limit_instant", "origin", "volume_mobile",
                   "volume_obstacle", "sector_power")


def read_part_file(pq, path: Path, columns: list[str] | None = None):
    """A part's Arrow table (``columns``, or all): ``ParquetFile.read`` on the calling thread,
    the table ``pq.read_table`` gives, at half its cost a part of 100 contacts (no dataset
    discovery, no thread pool contending with the workers for the machine's cores); without
    pre-buffering (coalesced reads into a cache, for remote files: a part is a small local
    file read whole; 3.8 us a contact instead of 4.7 on this machine)."""
    with pq.ParquetFile(path, pre_buffer=False) as handle:
        return handle.read(columns=columns, use_threads=False)


def _by_file(records: Iterable[Mapping[str, Any]]) -> dict[str, set[str]]:
    """``{rows file: the contacts whose latest rows it holds}``."""
    out: dict[str, set[str]] = {}
    for r in records:
        if r.get("rows_file"):
            out.setdefault(r["rows_file"], set()).add(str(r["contact"]))
    return out


def _positions(pq, path: Path, contacts: set[str], position: dict[str, int]) -> np.ndarray:
    """Each row's manifest position in the part ``path`` (-1: a row that is not its contact's
    latest), from its ``contact`` column alone."""
    codes = read_part_file(pq, path, ["contact"]).column("contact")
    codes = codes.combine_chunks().dictionary_encode()
    ids = codes.dictionary.to_pylist()
    where = np.array([position.get(c, -1) if c in contacts else -1 for c in map(str, ids)]
                     + [-1], dtype=np.int64)
    return where[codes.indices.fill_null(len(ids)).to_numpy(zero_copy_only=False)]


def with_identity(table: pd.DataFrame, identity: pd.DataFrame, gaps: bool | None = None,
                  rows: np.ndarray | None = None) -> pd.DataFrame:
    """The table with the manifest's identity columns in front (each contact's values taken to
    its rows), ``sector`` as Int64 where it has gaps (``gaps``: where the whole table has them,
    for a bucket of it; None: where this table has them). ``rows``: each row's row of
    ``identity`` where the caller knows it (None: found from the ``contact`` column, an index
    of the whole manifest built: 0.12 s a part at 10^5 contacts)."""
    if "sector" in table.columns and (table["sector"].isna().any() if gaps is None else gaps):
        table["sector"] = table["sector"].astype("Int64")
    # what ``identity.merge(table, on="contact", how="right")`` gives, without the merge's
    # copies of the whole table (a merge, then the columns' reorder: the table held three times)
    where = pd.Index(identity["contact"]).get_indexer(table["contact"]) if rows is None \
        else rows
    for k, name in enumerate(IDENTITY):
        if name != "contact":
            table.insert(k, name, identity[name].take(where).set_axis(table.index))
    return table


def stream_table(parts: Path, target: Path, records: Iterable[Mapping[str, Any]],
                 order: list[str], identity: pd.DataFrame) -> bool:
    """Write ``target`` (``table.parquet``, atomically) from the Parquet parts in ``parts``
    holding the ``records``' rows, contacts in ``order``'s order, the ``identity`` columns in
    front (:func:`with_identity`). False (nothing written) where the parts differ in their
    columns or types, or hold no row: the caller assembles the table in memory."""
    pa = require("pyarrow", purpose="writing a bundle's Parquet table")
    import pyarrow.compute  # noqa: F401 - pa.compute
    import pyarrow.parquet as pq

    files = _by_file(records)
    position = {c: i for i, c in enumerate(order)}
    schema = None
    rows = {}
    for name, contacts in files.items():
        part_schema = pq.read_schema(parts / name)
        if schema is not None and not part_schema.equals(schema, check_metadata=False):
            return False
        schema = part_schema
        rows[name] = _positions(pq, parts / name, contacts, position)
    counts = np.zeros(len(order) + 1, dtype=np.int64)
    for where in rows.values():
        counts += np.bincount(where + 1, minlength=len(order) + 1)
    bucket_of = np.cumsum(counts[1:]) // ROWS_PER_GROUP  # per manifest position
    if schema is None or not counts[1:].any():
        return False
    gaps = _sector_gaps(pq, parts, files, rows)
    scratch = target.parent / f".{target.name}.buckets"
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir()
    try:
        buckets = _deal(pa, pq, parts, rows, bucket_of, scratch)
        kept = identity[identity["contact"].isin([c for f in files.values() for c in f])]
        types = pa.Schema.from_pandas(kept[list(IDENTITY)], preserve_index=False)
        with atomic_path(target) as tmp:
            _write_buckets(pa, buckets, tmp, identity, gaps, types)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return True


def pa_float(kind) -> bool:
    """Whether an Arrow type is a floating-point one."""
    import pyarrow as pa

    return pa.types.is_floating(kind)


def _any_nan(array) -> bool:
    """Whether a floating-point Arrow column holds a NaN (a null is not one). Without nulls,
    by numpy on the column's buffers (0.3 us a contact of a part's 17 float columns, against
    1.2 for pyarrow's ``is_nan`` and ``any``: two kernels a column)."""
    if array.null_count == 0:
        return bool(np.isnan(array.to_numpy()).any())
    import pyarrow.compute as pc

    return bool(pc.any(pc.is_nan(array)).as_py())


def _has_gaps(pa, table) -> bool:
    """Whether an Arrow table has a ``sector`` column with a missing value (null or NaN)."""
    if "sector" not in table.column_names:
        return False
    sector = table.column("sector")
    return sector.null_count > 0 or (pa_float(sector.type) and _any_nan(sector))


def _sector_gaps(pq, parts: Path, files, rows) -> bool:
    """Whether a kept row of the parts has no ``sector`` (the whole table's ``sector`` is then
    Int64, as :func:`fretwear.bundle.outputs._with_identity` makes it)."""
    for name in files:
        if "sector" not in pq.read_schema(parts / name).names:
            return False
        sector = read_part_file(pq, parts / name, ["sector"]).column("sector")
        kept = rows[name] >= 0
        missing = ~sector.is_valid().to_numpy(zero_copy_only=False)
        if pa_float(sector.type):
            missing |= np.isnan(sector.to_numpy())
        if (missing & kept).any():
            return True
    return False


def _deal(pa, pq, parts: Path, rows, bucket_of: np.ndarray, scratch: Path) -> list[Path]:
    """Pass 1: every part's kept rows appended to its bucket's Arrow file, with their manifest
    position (``__position``); the buckets' files in order."""
    writers: dict[int, Any] = {}
    try:
        for name, where in rows.items():
            kept = np.flatnonzero(where >= 0)
            if not kept.size:
                continue
            table = read_part_file(pq, parts / name)
            table = table.take(pa.array(kept)).append_column(
                "__position", pa.array(where[kept]))
            bucket = bucket_of[where[kept]]
            for b in np.unique(bucket):
                piece = table.filter(pa.array(bucket == b))
                if b not in writers:
                    sink = pa.OSFile(str(scratch / f"b{b:06d}.arrow"), "wb")
                    writers[b] = (sink, pa.ipc.new_file(sink, piece.schema))
                writers[b][1].write_table(piece)
            del table
    finally:
        for sink, writer in writers.values():
            writer.close()
            sink.close()
    return [scratch / f"b{b:06d}.arrow" for b in sorted(writers)]


def _write_buckets(pa, buckets: list[Path], tmp: Path, identity: pd.DataFrame, gaps: bool,
                   types) -> None:
    """Pass 2: each bucket in the manifest's order, its identity columns put in front, written
    as a row group of ``tmp`` (the schema, pandas' metadata included, of the first bucket; an
    identity column without a value there is typed as in the whole table: ``types``)."""
    import pyarrow.parquet as pq

    writer = None
    try:
        for path in buckets:
            with pa.memory_map(str(path)) as source:
                table = pa.ipc.open_file(source).read_all()
            take = pa.compute.sort_indices(table.column("__position"))  # stable
            table = table.take(take).drop_columns(["__position"])
            frame = with_identity(table.to_pandas(split_blocks=True, self_destruct=True),
                                  identity, gaps)
            del table
            if writer is None:
                schema = pa.Schema.from_pandas(frame, preserve_index=False)
                schema = _typed(pa, schema, types)
                writer = pq.ParquetWriter(tmp, schema)
            writer.write_table(pa.Table.from_pandas(frame, schema=writer.schema,
                                                    preserve_index=False))
            del frame
            os.unlink(path)
    finally:
        if writer is not None:
            writer.close()


def _typed(pa, schema, types):
    """``schema`` with its null-typed fields (an identity column without a value in the first
    bucket) typed as ``types`` types them (the whole table's identity)."""
    for i, f in enumerate(schema):
        if pa.types.is_null(f.type) and f.name in types.names:
            schema = schema.set(i, f.with_type(types.field(f.name).type))
    return schema


def read_columns(path: Path, columns: Iterable[str] | None = None, *,
                 categorical: Iterable[str] = ()) -> pd.DataFrame:
    """The given columns of a written Parquet table that it has, every column for None
    (pandas' dtypes, as ``pandas.read_parquet`` gives them); the ``categorical`` columns read
    as categories (pyarrow's ``read_dictionary``: a contact's id once, not once a row: the
    summary of 10^5 contacts reads 4.8 million rows)."""
    require("pyarrow", purpose="reading a bundle's Parquet table")
    if columns is None:
        return pd.read_parquet(path)
    import pyarrow.parquet as pq

    names = set(pq.read_schema(path).names)
    wanted = [c for c in columns if c in names]
    coded = [c for c in categorical if c in wanted]
    if coded:
        return pd.read_parquet(path, columns=wanted, read_dictionary=coded)
    return pd.read_parquet(path, columns=wanted)


#: Rows of a piece of the table the summary reads at a time (:func:`contact_pieces`: some
#: 20 MB of its columns; the whole table's were 0.7 GB at 10^5 contacts).
PIECE_ROWS = 1 << 18


def contact_pieces(path: Path, columns: Iterable[str], *, rows: int = PIECE_ROWS):
    """The given columns of a written Parquet table that it has, ``contact`` as categories,
    in pieces of about ``rows`` rows each holding whole contacts, in the table's order: the
    frames :func:`read_columns` gives of the whole table, cut between two contacts (an
    iterator, the file opened here). None where a contact's rows are not consecutive, a row
    has no contact, or there is no row (read the table whole)."""
    pq = require("pyarrow.parquet", purpose="reading a bundle's Parquet table")
    handle = pq.ParquetFile(path, read_dictionary=["contact"])
    wanted = [c for c in columns if c in handle.schema_arrow.names]
    ids = handle.read(columns=["contact"], use_threads=False).column("contact") \
        if "contact" in wanted else None
    codes = None if ids is None or ids.null_count or not len(ids) else \
        ids.to_pandas().cat.codes.to_numpy()
    del ids
    bounds = None if codes is None else np.flatnonzero(codes[1:] != codes[:-1]) + 1
    if bounds is None or bounds.size + 1 != np.count_nonzero(np.bincount(codes)):
        handle.close()  # bounds: where a contact's rows start; else one in two runs of rows
        return None
    cuts = []
    while True:
        i = np.searchsorted(bounds, (cuts[-1] if cuts else 0) + rows)
        if i == bounds.size:
            break
        cuts.append(int(bounds[i]))
    return _pieces(handle, wanted, [*cuts, codes.size])


def _pieces(handle, columns: list[str], cuts: list[int]):
    """The frames of rows ``[0, cuts[0])``, ``[cuts[0], cuts[1])`` ... of ``handle``."""
    pa = require("pyarrow")
    with handle:
        batches = handle.iter_batches(batch_size=1 << 16, columns=columns, use_threads=False)
        held, start = [], 0
        for cut in cuts:
            while sum(b.num_rows for b in held) < cut - start:
                held.append(next(batches))
            table = pa.Table.from_batches(held)
            held = table.slice(cut - start).to_batches()
            # on this thread: pyarrow's pool took more CPU and wall for these columns (the
            # summary's pieces at 10^5 contacts 0.63-0.72 -> 0.29-0.50 s of CPU, issue 28)
            yield table.slice(0, cut - start).to_pandas(use_threads=False)
            start = cut


#: A manifest position whose contact has no final record yet (:class:`PrefixTable`).
_UNRESOLVED = object()


class PrefixTable:
    """``table.parquet`` written while a run's results arrive: each part's rows appended, the
    identity columns put in front (:func:`with_identity`), once every contact before the part's
    first one in the manifest is resolved (its rows in an earlier part, or none: failed). The
    client then copies the table part by part as the workers compute, one pass, no bucket or
    sort (issue 28: the copy after the last result took 1.4 s of 5.2 at 10^4 contacts).

    The route gives up (:meth:`abort`: its temporary file removed, ``finish`` False, the caller
    writes the table by :func:`stream_table`) where its table could differ from that one: a
    part holding contacts that are not consecutive in the manifest (interleaved with another
    part's), a contact whose rows are an earlier run's (skipped, stale), parts of different
    columns or types, a ``sector`` with gaps after a first part without. Its file is the table
    :func:`stream_table` writes of the same parts, row for row and dtype for dtype
    (test_bundle_table_prefix.py). Written as ``.table.parquet.<random>.tmp`` beside the table
    (the name :func:`fretwear.io.atomic.atomic_path` gives, whose next write removes one a
    killed run left) and renamed over it by :meth:`finish` only once whole.

    Parameters
    ----------
    parts : Path
        The ``parts/`` folder of the output directory.
    target : Path
        ``table.parquet``.
    order : list of str
        The manifest's contacts, in order.
    identity : DataFrame
        The manifest's identity columns, ``contact`` as text.
    """

    def __init__(self, parts: Path, target: Path, order: list[str], identity: pd.DataFrame,
                 dataset=None):
        self.parts, self.target, self.identity = parts, target, identity
        #: The dataset written with it (:class:`fretwear.bundle.result_dataset.GridZarr`, or
        #: None): given each row group's rows.
        self.dataset = dataset
        self.arrow_identity = None  # the identity columns as Arrow (False: pandas' route only)
        self.position = {str(c): i for i, c in enumerate(order)}
        # the identity row of each manifest position, found once (None: the same position)
        ids = identity["contact"].astype(str).tolist()
        self.identity_row = None if ids == [str(c) for c in order] else \
            pd.Index(ids).get_indexer(pd.Index([str(c) for c in order], dtype=object))
        self.where: list[Any] = [_UNRESOLVED] * len(order)
        self.files: dict[str, list[int]] = {}
        self.cursor = 0
        self.aborted = False
        self.tmp: Path | None = None
        self.writer = None
        self.schema = None  # the parts' Arrow schema (the first part's)
        self.gaps: bool | None = None  # whether the first part's sector has gaps
        self.batch: list = []  # Arrow tables of the next row group

    def resolve(self, records: Iterable[Mapping[str, Any]]) -> None:
        """Take the final records of some contacts (a failed one: no rows; a done one whose
        part is written: its rows in ``rows_file``; a done one not written yet is left for a
        later call), then append every part whose turn has come."""
        if self.aborted:
            return
        try:
            for r in records:
                status = r["status"]
                if status == "done" and not r.get("rows_file"):
                    continue  # in the client's buffer: resolved when its part is written
                where = None if status == "failed" else r.get("rows_file")
                pos = self.position.get(str(r["contact"]))
                if status not in ("done", "failed") or pos is None:
                    return self.abort()  # an earlier run's rows (skipped, stale)
                if self.where[pos] is not _UNRESOLVED:
                    if self.where[pos] != where:
                        return self.abort()
                    continue
                self.where[pos] = where
                if where is not None:
                    self.files.setdefault(where, []).append(pos)
            self._advance()
        except Exception:  # noqa: BLE001 - this route is a shortcut: stream_table decides
            self.abort()

    def _advance(self) -> None:
        """Append the parts whose contacts come next in the manifest, all resolved."""
        n = len(self.where)
        while self.cursor < n:
            name = self.where[self.cursor]
            if name is _UNRESOLVED:
                return
            if name is None:
                self.cursor += 1
                continue
            positions = sorted(self.files[name])
            if positions[0] != self.cursor:
                return self.abort()
            span = self.where[self.cursor:positions[-1] + 1]
            if any(w is _UNRESOLVED for w in span):
                return
            if any(w is not None and w != name for w in span):
                return self.abort()  # another part's contacts among this one's
            self._append(name, positions)
            self.cursor = positions[-1] + 1

    def _append(self, name: str, positions: list[int]) -> None:
        """The part ``name`` (its contacts at the manifest ``positions``) added to the table."""
        pa = require("pyarrow", purpose="writing a bundle's Parquet table")
        import pyarrow.parquet as pq

        table = read_part_file(pq, self.parts / name)
        if self.schema is None:
            self.schema = table.schema
        elif not table.schema.equals(self.schema, check_metadata=False):
            return self.abort()  # stream_table refuses these parts too: in memory then
        where = self._rows(table, positions)
        if where is None:
            return self.abort()
        if (np.diff(where) < 0).any():  # a contact's rows stay in the part's order
            order = np.argsort(where, kind="stable")
            table, where = table.take(pa.array(order)), where[order]
        gaps = _has_gaps(pa, table)
        if self.gaps is None:
            self.gaps = gaps
        elif gaps and not self.gaps:
            return self.abort()  # the whole table's sector would be Int64 from the start
        rows = where if self.identity_row is None else self.identity_row[where]
        out = None if self.writer is None else self._arrow_rows(pa, table, rows)
        if out is None:  # the first part (its pandas schema the file's), or a part it differs
            frame = with_identity(table.to_pandas(split_blocks=True, self_destruct=True),
                                  self.identity, self.gaps, rows)
            del table
            if self.writer is None:
                self._open(pa, pq, frame)
            out = pa.Table.from_pandas(frame, schema=self.writer.schema, preserve_index=False)
        self.batch.append(out)
        if sum(t.num_rows for t in self.batch) >= ROWS_PER_GROUP:
            self._write_batch()

    def _open(self, pa, pq, frame: pd.DataFrame) -> None:
        """The temporary file's writer, of the schema pandas gives the first part's rows."""
        schema = pa.Schema.from_pandas(frame, preserve_index=False)
        types = pa.Schema.from_pandas(self.identity[list(IDENTITY)], preserve_index=False)
        fd, tmp = tempfile.mkstemp(prefix=f".{self.target.name}.", suffix=".tmp",
                                   dir=self.target.parent)
        os.close(fd)
        self.tmp = Path(tmp)
        self.writer = pq.ParquetWriter(self.tmp, _typed(pa, schema, types))

    def _arrow_rows(self, pa, table, rows: np.ndarray):
        """The part's rows with the identity columns in front (:func:`with_identity`'s
        columns and values) built in Arrow, without the part's trip through pandas and back
        (0.2 ms a contact at 10^4 contacts: the client's largest share); None where an Arrow
        column is not of the type the file holds (a sector with gaps made Int64, an identity
        column of mixed types) or a float column holds NaN, which pandas' route writes as
        null: the caller goes through pandas."""
        if self.arrow_identity is None:
            try:
                self.arrow_identity = pa.Table.from_pandas(
                    self.identity[list(IDENTITY)], preserve_index=False)
            except Exception:  # noqa: BLE001 - pandas' route decides, part by part
                self.arrow_identity = False
        if self.arrow_identity is False:
            return None
        names, arrays = list(table.column_names), list(table.columns)
        taken = self.arrow_identity.take(pa.array(rows, type=pa.int64()))
        for k, name in enumerate(IDENTITY):
            if name != "contact":
                names.insert(k, name)
                arrays.insert(k, taken.column(name))
        schema = self.writer.schema
        if names != schema.names or any(a.type != f.type
                                        for a, f in zip(arrays, schema, strict=True)):
            return None
        if any(pa_float(a.type) and _any_nan(a) for a in table.columns):
            return None
        return pa.Table.from_arrays(arrays, schema=schema)

    def _rows(self, table, positions: list[int]) -> np.ndarray | None:
        """Each row's manifest position, from the part's ``contact`` column; None where a row
        is not one of the part's contacts at ``positions``."""
        codes = table.column("contact").combine_chunks().dictionary_encode()
        ids = [self.position.get(str(c), -1) for c in codes.dictionary.to_pylist()]
        where = np.array(ids + [-1], dtype=np.int64)[
            codes.indices.fill_null(len(ids)).to_numpy(zero_copy_only=False)]
        if not np.isin(where, positions).all():
            return None
        return where

    def _write_batch(self) -> None:
        """The batch written as a row group, and given to the dataset as the pandas frame the
        table reads back (its wear columns: those the dataset takes)."""
        import pyarrow as pa

        if not self.batch:
            return
        group = pa.concat_tables(self.batch)
        self.batch = []
        self.writer.write_table(group)
        if self.dataset is not None and not self.dataset.aborted:
            names = [c for c in group.column_names if c == "contact" or c in COLUMNS]
            self.dataset.add(group.select(names).to_pandas(use_threads=False))

    def finish(self) -> bool:
        """Write what is left and rename the file over ``table.parquet``: True where every
        contact is resolved and some have rows; False otherwise (nothing written: the caller
        writes the table by :func:`stream_table`)."""
        if self.aborted or self.cursor < len(self.where) or self.writer is None:
            self.abort()
            return False
        try:
            self._write_batch()
            self.writer.close()
            self.writer = None
            os.chmod(self.tmp, _mode(self.target))
            os.replace(self.tmp, self.target)
        except BaseException:
            self.abort()
            raise
        return True

    def abort(self) -> None:
        """Give up this route: the temporary file removed, nothing kept."""
        self.aborted = True
        self.batch = []
        if self.dataset is not None:
            self.dataset.abort()
        writer, self.writer = self.writer, None
        if writer is not None:
            with contextlib.suppress(Exception):
                writer.close()
        if self.tmp is not None:
            with contextlib.suppress(FileNotFoundError):
                self.tmp.unlink()
            self.tmp = None


def _mode(target: Path) -> int:
    """The mode of the file ``target`` replaces, or an ordinary ``open()``'s (0666 less the
    umask), as :func:`fretwear.io.atomic.atomic_path` gives it."""
    with contextlib.suppress(OSError):
        return target.stat().st_mode & 0o7777
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask
