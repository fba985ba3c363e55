"""A Parquet file's column names, units and stored name come from its own footer, though the
Arrow schema of the last files is remembered (``io.parquet._SCHEMAS``, by the footer's
key-value metadata and Parquet schema: a bundle's files share one). Each file is compared
with pyarrow's own reading of its schema (``pyarrow.parquet.read_schema``), the independent
source, after files of other units, names and metadata were opened in between."""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
import pytest

pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")

from fretwear.io import parquet  # noqa: E402
from fretwear.io.parquet import open_parquet  # noqa: E402


def _write(path, names, units, name=""):
    fields = [pa.field(n, pa.float64(), metadata=None if u is None else {"units": u})
              for n, u in zip(names, units, strict=True)]
    schema = pa.schema(fields, metadata={"fretwear": f'{{"name": "{name}", "metadata": {{}}}}'})
    table = pa.table([np.arange(3.0) + k for k in range(len(names))], schema=schema)
    pq.write_table(table, path)
    return path


def _expected(path):
    schema = pq.read_schema(path)
    units = {i: f.metadata[b"units"].decode() for i, f in enumerate(schema)
             if f.metadata and b"units" in f.metadata}
    return list(schema.names), units


def test_every_file_gets_its_own_names_units_and_name(tmp_path, monkeypatch):
    monkeypatch.setattr(parquet, "_SCHEMAS", OrderedDict())
    cols = ["time", "normal_force", "vt1", "vt2", "dy", "dz"]
    files = [
        _write(tmp_path / "a.parquet", cols, ["s", "N", "m/s", "m/s", "m", "m"], "A"),
        _write(tmp_path / "b.parquet", cols, ["ms", "N", "mm/s", "mm/s", "mm", "mm"], "A"),
        _write(tmp_path / "c.parquet", ["t", "fn", "v1", "v2", "y", "z"],
               ["s", "N", "m/s", "m/s", "m", "m"], "A"),
        _write(tmp_path / "d.parquet", cols, ["s", None, "m/s", "m/s", "m", "m"], "B"),
        _write(tmp_path / "e.parquet", cols, ["s", "N", "m/s", "m/s", "m", "m"], "A"),
    ]
    for path in files + files[::-1]:
        source = open_parquet(path)
        assert (source.columns, source.units) == _expected(path), path.name
        assert source.name == ("B" if path.name == "d.parquet" else "A")
        source.units[0] = "changed"  # a caller's change never reaches the next file
    assert len(parquet._SCHEMAS) == 4  # a.parquet and e.parquet share their schema


def test_a_file_without_key_value_metadata_is_read_as_before(tmp_path):
    path = tmp_path / "plain.parquet"
    pq.write_table(pa.table({"time": [0.0, 1.0], "normal_force": [1.0, 2.0],
                             "vt1": [0.0, 0.5], "vt2": [0.0, 0.0]}), path,
                   store_schema=False)
    assert pq.ParquetFile(path).metadata.metadata is None
    source = open_parquet(path)
    assert (source.columns, source.units) == _expected(path)
    assert source.read([1])[0].tolist() == [1.0, 2.0]


def test_the_oldest_schema_goes_beyond_sixteen(tmp_path, monkeypatch):
    monkeypatch.setattr(parquet, "_SCHEMAS", OrderedDict())
    files = [_write(tmp_path / f"f{k}.parquet", ["time", f"normal_force_{k}"], ["s", "N"])
             for k in range(20)]
    for path in files + files[:3]:
        source = open_parquet(path)
        assert (source.columns, source.units) == _expected(path), path.name
    assert len(parquet._SCHEMAS) == 16


def test_files_of_one_key_value_metadata_but_other_columns_get_their_own_names(
        tmp_path, monkeypatch):
    """Without a stored Arrow schema (``store_schema=False``) two files may hold the same
    key-value metadata and other columns: the remembered schema is the one of the same
    Parquet columns (the key holds their paths), never the other file's names."""
    monkeypatch.setattr(parquet, "_SCHEMAS", OrderedDict())
    meta = {"fretwear": '{"name": "A", "metadata": {}}'}
    files = []
    for k, names in enumerate((["time", "normal_force", "vt1", "vt2"],
                               ["t", "fn", "v1", "v2"])):
        table = pa.table({n: np.arange(3.0) + j for j, n in enumerate(names)})
        path = tmp_path / f"f{k}.parquet"
        with pq.ParquetWriter(path, table.schema, store_schema=False) as writer:
            writer.write_table(table)
            writer.add_key_value_metadata(meta)
        files.append(path)
    kv = [pq.ParquetFile(path).metadata.metadata for path in files]
    assert kv[0] == kv[1] == {b"fretwear": meta["fretwear"].encode()}
    for path in files + files[::-1]:
        source = open_parquet(path)
        assert (source.columns, source.units) == _expected(path), path.name
    assert len(parquet._SCHEMAS) == 2
