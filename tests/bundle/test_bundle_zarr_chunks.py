"""The dataset's Zarr store is chunked by the groups of contacts the client appends
(result_dataset.contact_chunks, issue 28): every variable along ``contact`` in chunks of the
first group's contacts, whole along its instants and sectors, so that each group appended fills
about one chunk (zarr's own guess cut a group of 3 000 contacts x 6 instants x 8 sectors into a
dozen chunks and rewrote the partial ones). The values read back are the groups' own."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.result_dataset import GridZarr

zarr = pytest.importorskip("zarr")
pytest.importorskip("xarray")


def _group(first: int, count: int, instants: int = 6, sectors: int = 8) -> pd.DataFrame:
    rows = count * instants * sectors
    k = np.arange(rows)
    return pd.DataFrame({
        "contact": np.repeat([f"c{first + j:05d}" for j in range(count)], instants * sectors),
        "instant": np.tile(np.repeat(np.arange(1.0, instants + 1), sectors), count),
        "sector": np.tile(np.arange(1, sectors + 1), count * instants),
        "depth_mobile_sector": (first * instants * sectors + k) * 1e-9,
        "power": np.repeat(np.arange(first, first + count) * 1e-3, instants * sectors),
    })


def test_the_store_is_chunked_by_the_appended_groups(tmp_path):
    ids = [f"c{j:05d}" for j in range(6000)]
    store = GridZarr(tmp_path / "d.zarr", np.array(ids).dtype, {"zarr_format": 2}
                     if int(zarr.__version__.split(".")[0]) >= 3 else {})
    groups = [_group(0, 3000), _group(3000, 3000)]
    for frame in groups:
        store.add(frame)
    assert not store.aborted
    # the store whole once finished (the last chunk of an array is written then:
    # zarr_chunks.ChunkAppender)
    assert store.finish(pd.DataFrame({"contact": ids, "status": "done"}), tmp_path / "e.zarr")
    root = zarr.open_group(str(tmp_path / "e.zarr"), mode="r")
    sector = root["depth_mobile_sector"]
    assert sector.shape == (6000, 6, 8) and sector.chunks == (3000, 6, 8)
    assert root["power"].chunks == (3000, 6)
    expected = np.concatenate([g["depth_mobile_sector"].to_numpy() for g in groups])
    np.testing.assert_array_equal(sector[:].reshape(-1), expected)
