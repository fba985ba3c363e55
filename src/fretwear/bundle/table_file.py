"""A bundle's ``table.parquet`` written from its Parquet parts without the whole table in memory.

The parts hold the contacts' rows in the order they arrived; the table holds them in the
manifest's order. :func:`stream_table` sorts them out of core in two passes over the parts:

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

import os
import shutil
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.datasets import require
from fretwear.bundle.manifest import IDENTITY
from fretwear.io.atomic import atomic_path

#: Rows of a bucket, the table's row group (a bucket's Arrow and pandas copies: some 50 MB
#: at the benchmark's 250 bytes a row).
ROWS_PER_GROUP = 1 << 17

#: The table's columns :func:`fretwear.bundle.result.summarize` reads.
SUMMARY_COLUMNS = ("contact", "instant", "sector", "depth_mobile", "power",
                   "depth_mobile_sector", "limit_instant", "origin", "volume_mobile",
                   "volume_obstacle", "sector_power")


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
    codes = pq.read_table(path, columns=["contact"]).column("contact")
    codes = codes.combine_chunks().dictionary_encode()
    ids = codes.dictionary.to_pylist()
    where = np.array([position.get(c, -1) if c in contacts else -1 for c in map(str, ids)]
                     + [-1], dtype=np.int64)
    return where[codes.indices.fill_null(len(ids)).to_numpy(zero_copy_only=False)]


def with_identity(table: pd.DataFrame, identity: pd.DataFrame, gaps: bool | None = None
                  ) -> pd.DataFrame:
    """The table with the manifest's identity columns in front (each contact's values taken to
    its rows), ``sector`` as Int64 where it has gaps (``gaps``: where the whole table has them,
    for a bucket of it; None: where this table has them)."""
    if "sector" in table.columns and (table["sector"].isna().any() if gaps is None else gaps):
        table["sector"] = table["sector"].astype("Int64")
    # what ``identity.merge(table, on="contact", how="right")`` gives, without the merge's
    # copies of the whole table (a merge, then the columns' reorder: the table held three times)
    where = pd.Index(identity["contact"]).get_indexer(table["contact"])
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


def _sector_gaps(pq, parts: Path, files, rows) -> bool:
    """Whether a kept row of the parts has no ``sector`` (the whole table's ``sector`` is then
    Int64, as :func:`fretwear.bundle.outputs._with_identity` makes it)."""
    for name in files:
        if "sector" not in pq.read_schema(parts / name).names:
            return False
        sector = pq.read_table(parts / name, columns=["sector"]).column("sector")
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
            table = pq.read_table(parts / name)
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


def read_columns(path: Path, columns: Iterable[str] | None = None) -> pd.DataFrame:
    """The given columns of a written Parquet table that it has, every column for None
    (pandas' dtypes, as ``pandas.read_parquet`` gives them)."""
    require("pyarrow", purpose="reading a bundle's Parquet table")
    if columns is None:
        return pd.read_parquet(path)
    import pyarrow.parquet as pq

    names = set(pq.read_schema(path).names)
    return pd.read_parquet(path, columns=[c for c in columns if c in names])
