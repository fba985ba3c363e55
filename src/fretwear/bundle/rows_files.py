"""The rows files of a bundle's output directory: parts (written by the client or by a
worker, :mod:`fretwear.bundle.worker_parts`) and the final CSV files, written atomically as
Parquet or CSV, and read back (:func:`read_frame`)."""

from __future__ import annotations

import functools
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.csv_table import write_csv
from fretwear.bundle.datasets import require
from fretwear.bundle.tasks import concat_packed, packed_columns
from fretwear.io.atomic import atomic_path
from fretwear.table.schema import FLOAT_FORMAT


def write_frame(frame: pd.DataFrame, path: Path, fmt: str, *, sweep: bool = True) -> Path:
    """Write a table atomically as Parquet or CSV (floats round-trip exactly in both);
    ``sweep``: as :func:`fretwear.io.atomic.atomic_path` (False for a part, whose name is
    never written twice: :meth:`OutputDirectory.cleanup` sweeps ``parts/`` once)."""
    if fmt == "parquet":
        require("pyarrow", purpose="writing Parquet (the csv table format does not need it)")
    with atomic_path(path, sweep=sweep) as tmp:
        if fmt == "parquet":
            frame.to_parquet(tmp, index=False)
        elif not write_csv(frame, tmp):
            frame.to_csv(tmp, index=False, float_format=FLOAT_FORMAT)
    return path


#: What pandas reads as missing in a CSV by default: kept for every column but ``contact``,
#: whose ids are text as written (a contact named ``NA`` or ``None`` read back as missing lost
#: its rows on a restart from CSV parts).
_CSV_MISSING = ("", "#N/A", "#N/A N/A", "#NA", "-1.#IND", "-1.#QNAN", "-NaN", "-nan", "1.#IND",
                "1.#QNAN", "<NA>", "N/A", "NA", "NULL", "NaN", "None", "n/a", "nan", "null")


def write_rows(records: list[dict[str, Any]], path: Path, fmt: str) -> list[dict[str, Any]]:
    """Write the rows of the records that carry a table (``table``, as
    :func:`fretwear.bundle.tasks.pack` lays it out) end to end as one rows file ``path``
    (:func:`write_frame`, or :func:`_write_arrow` for Parquet tables of one layout); returns
    those records (none: nothing written)."""
    kept = [r for r in records if r.get("table") is not None]
    if kept:
        contacts, tables = [r["contact"] for r in kept], [r["table"] for r in kept]
        if fmt != "parquet" or not _write_arrow(contacts, tables, path):
            write_frame(concat_packed(contacts, tables), path, fmt, sweep=False)
    return kept


def _write_arrow(contacts: list[str], tables: list[dict[str, Any]], path: Path) -> bool:
    """The Parquet file :func:`write_frame` writes of :func:`~fretwear.bundle.tasks.
    concat_packed`'s frame, built from the packed arrays in Arrow (no DataFrame: 0.03 ms a
    contact of a worker's CPU, two thirds of its part's write, issue 28): the same schema and
    pandas metadata (:func:`_arrow_schema`), the same values, the same writer options (pandas
    writes Snappy), so the same bytes. False, nothing written, where the tables differ in
    layout or a column is not a plain 1-D number array (``concat_packed`` aligns those)."""
    if not all(isinstance(a, np.ndarray) and a.ndim == 1 and a.dtype.kind in "fiub"
               for a in tables[0]["arrays"]):
        return False
    laid = packed_columns(tables)
    if laid is None:
        return False
    lengths, columns, arrays = laid
    pa = require("pyarrow", purpose="writing Parquet (the csv table format does not need it)")
    import pyarrow.parquet as pq

    schema = _arrow_schema(tuple(columns), tuple(a.dtype.str for a in arrays))
    ids = pa.array(contacts, type=schema.field(0).type)
    data = [ids.take(pa.array(np.repeat(np.arange(len(contacts)), lengths)))]
    # from_pandas: a NaN written as null, as pandas writes it (an obstacle sector's depth
    # without an obstacle radius is NaN)
    data += [pa.array(a, from_pandas=True) for a in arrays]
    table = pa.Table.from_arrays(data, schema=schema)
    with atomic_path(path, sweep=False) as tmp:
        pq.write_table(table, tmp, compression="snappy")
    return True


@functools.lru_cache(maxsize=16)
def _arrow_schema(columns: tuple[str, ...], dtypes: tuple[str, ...]):
    """The Arrow schema, pandas metadata included, that ``DataFrame.to_parquet(index=False)``
    gives a ``contact`` column of text and numeric ``columns`` of these numpy ``dtypes``: that
    of a frame of one row of them (the metadata holds names and types only, no row count)."""
    pa = require("pyarrow")
    one = {"contact": np.array(["c"], dtype=object)}
    one.update((c, np.zeros(1, dtype=d)) for c, d in zip(columns, dtypes, strict=True))
    return pa.Schema.from_pandas(pd.DataFrame(one), preserve_index=False)


def read_frame(path: Path) -> pd.DataFrame:
    """Read a table written by :func:`write_frame` (a CSV's ``contact`` ids as text, none of
    them missing)."""
    if path.suffix == ".parquet":
        require("pyarrow", purpose="reading a bundle's Parquet table")
        return pd.read_parquet(path)
    header = pd.read_csv(path, nrows=0).columns
    return pd.read_csv(path, dtype={"contact": str}, keep_default_na=False,
                       na_values={c: list(_CSV_MISSING) for c in header if c != "contact"})
