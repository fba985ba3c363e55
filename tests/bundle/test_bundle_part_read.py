"""A part read back by the client (table_file.read_part_file: ParquetFile.read on the calling
thread) is the table ``pyarrow.parquet.read_table`` gives of it (the reader before, pyarrow's
own: the independent computation): values, types and schema metadata, whole or by columns.
Same process: compared exactly."""

import numpy as np
import pytest

from fretwear.bundle.table_file import read_part_file

pd = pytest.importorskip("pandas")
pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")


def test_a_part_read_is_read_tables(tmp_path):
    frame = pd.DataFrame({"contact": np.repeat(["c0", "c1", "c2"], 4),
                          "instant": np.tile([0.0, 1.0, 2.0, 40.0], 3),
                          "sector": pd.array([1, 2, None, 4] * 3, dtype="Int64"),
                          "depth_mobile": np.linspace(0.0, 1e-4, 12)})
    frame["contact"] = frame["contact"].astype("category")
    path = tmp_path / "part.parquet"
    frame.to_parquet(path, row_group_size=5)  # three row groups
    for columns in (None, ["contact"], ["sector", "instant"]):
        got, want = read_part_file(pq, path, columns), pq.read_table(path, columns=columns)
        assert got.equals(want)
        assert got.schema.equals(want.schema, check_metadata=True)
    assert read_part_file(pq, path).to_pandas().equals(frame)
