"""A part's rows written from the packed arrays in Arrow (rows_files._write_arrow, issue 28)
give the very file pandas writes of the same rows (``concat_packed`` then
``DataFrame.to_parquet``, the route before): the same bytes, so the same schema, pandas
metadata, values and dtypes read back. Tables of different layouts (with and without sectors)
still go through pandas, which aligns them."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.rows_files import write_frame, write_rows
from fretwear.bundle.tasks import concat_packed

pytest.importorskip("pyarrow")


def _packed(rows: int, sectors: bool, seed: int) -> dict:
    rng = np.random.default_rng(seed)
    columns = ["instant", "duration", "power", "depth_mobile"] + (["sector"] if sectors else [])
    arrays = [rng.random(rows) for _ in range(4)]
    arrays[3][::5] = np.nan  # a depth without its radius: pandas writes it as null
    if sectors:
        arrays.append(np.arange(rows, dtype=np.int64) % 4 + 1)
    return {"columns": columns, "arrays": arrays}


@pytest.mark.parametrize("sectors", [True, False])
def test_the_arrow_part_is_the_file_pandas_writes(tmp_path, sectors):
    records = [{"contact": name, "table": _packed(rows, sectors, k)}
               for k, (name, rows) in enumerate([("R1C1-AVB", 12), ("NA", 8), ("é 2", 12)])]
    records.insert(1, {"contact": "failed", "table": None})
    kept = write_rows(records, tmp_path / "arrow.parquet", "parquet")
    assert [r["contact"] for r in kept] == ["R1C1-AVB", "NA", "é 2"]
    frame = concat_packed([r["contact"] for r in kept], [r["table"] for r in kept])
    write_frame(frame, tmp_path / "pandas.parquet", "parquet", sweep=False)
    assert (tmp_path / "arrow.parquet").read_bytes() == (tmp_path / "pandas.parquet").read_bytes()
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "arrow.parquet"), frame)
    import pyarrow.parquet as pq

    depth = pq.read_table(tmp_path / "arrow.parquet").column("depth_mobile")
    assert depth.null_count == frame["depth_mobile"].isna().sum() > 0


def test_tables_of_two_layouts_are_aligned_by_pandas(tmp_path):
    records = [{"contact": "a", "table": _packed(8, True, 0)},
               {"contact": "b", "table": _packed(2, False, 1)}]
    write_rows(records, tmp_path / "mixed.parquet", "parquet")
    got = pd.read_parquet(tmp_path / "mixed.parquet")
    expected = concat_packed(["a", "b"], [r["table"] for r in records])
    pd.testing.assert_frame_equal(got, expected)
    assert got["sector"].isna().sum() == 2
