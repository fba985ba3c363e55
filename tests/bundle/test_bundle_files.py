"""The bundle's own files: CSV reals in the table layer's one float format (exact), and Parquet
without pyarrow refused by fretwear._optional naming the extra (issue 10)."""

from __future__ import annotations

import sys

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.manifest import read_manifest
from fretwear.bundle.store import read_frame, write_frame
from fretwear.errors import MissingDependencyError
from fretwear.table.schema import FLOAT_FORMAT


def test_csv_outputs_use_the_table_float_format_and_round_trip(tmp_path):
    # 0.1 + 0.2 and 1/3 need all 17 significant digits to come back
    frame = pd.DataFrame({"contact": ["a", "b"], "depth": [0.1 + 0.2, 1.0 / 3.0]})
    path = write_frame(frame, tmp_path / "t.csv", "csv")
    rows = path.read_text(encoding="utf-8").splitlines()
    assert rows[1] == "a," + FLOAT_FORMAT % (0.1 + 0.2)
    back = read_frame(path)
    assert np.array_equal(back["depth"].to_numpy(), frame["depth"].to_numpy())


def test_parquet_without_pyarrow_names_the_formats_extra(tmp_path, monkeypatch):
    manifest = tmp_path / "manifest.parquet"
    pd.DataFrame({"contact": ["a"], "history": ["a.csv"]}).to_parquet(manifest, index=False)
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    with pytest.raises(MissingDependencyError, match=r"pip install 'fretwear\[formats\]'"):
        read_manifest(manifest)
    with pytest.raises(MissingDependencyError, match=r"csv table format .*fretwear\[formats\]"):
        write_frame(pd.DataFrame({"x": [1.0]}), tmp_path / "t.parquet", "parquet")
    assert not (tmp_path / "t.parquet").exists()
