"""GridZarr's arrays appended a whole chunk at a time (fretwear.bundle.zarr_chunks, issue 28)
give the store zarr's own ``Array.append`` gives: the same files, byte for byte. The independent
reference is the same GridZarr with the chunk writer turned off (every group appended by zarr),
on groups that do not end on a chunk's edge, with NaN, -0.0, a variable NaN everywhere (its
chunks not written) and one NaN in a whole chunk only."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import fretwear.bundle.result_dataset as result_dataset
from fretwear.bundle.result_dataset import GridZarr

zarr = pytest.importorskip("zarr")
pytest.importorskip("xarray")
pytest.importorskip("numcodecs")


def _group(first: int, count: int, instants: int = 3, sectors: int = 4) -> pd.DataFrame:
    per = instants * sectors
    k = np.arange(count * per) + first * per
    depth = k * 1e-9
    depth[k % 7 == 0] = np.nan
    depth[k % 11 == 0] = -0.0
    power = np.repeat(np.arange(first, first + count) * 1e-3, per)
    power[(np.repeat(np.arange(first, first + count), per) // 50) == 2] = np.nan  # a chunk
    return pd.DataFrame({
        "contact": np.repeat([f"c{first + j:05d}" for j in range(count)], per),
        "instant": np.tile(np.repeat(np.arange(1.0, instants + 1), sectors), count),
        "sector": np.tile(np.arange(1, sectors + 1), count * instants),
        "depth_mobile_sector": depth,
        "volume_obstacle_sector": np.full(count * per, np.nan),  # no chunk written
        "angle_start": np.tile(np.arange(sectors) * 90.0 - 180.0, count * instants),
        "power": power,
    })


def _files(root):
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file()}


def _write(folder, target, sizes, ids, chunked):
    store = GridZarr(folder, np.array(ids).dtype, {"zarr_format": 2}
                     if int(zarr.__version__.split(".")[0]) >= 3 else {})
    first = 0
    for n in sizes:
        store.add(_group(first, n))
        first += n
    assert not store.aborted
    assert len(store.appenders) == 5  # contact and the 4 variables
    assert all((a is not None) == chunked for a in store.appenders.values())
    assert store.finish(pd.DataFrame({"contact": ids, "status": "done"}), target)
    return _files(target)


@pytest.mark.parametrize("sizes", [[50, 73, 50, 21, 130, 1], [50, 50, 50], [50, 10]])
def test_whole_chunks_written_are_zarrs_own_append(tmp_path, monkeypatch, sizes):
    ids = [f"c{j:05d}" for j in range(sum(sizes))]
    ours = _write(tmp_path / "a", tmp_path / "a.zarr", sizes, ids, True)
    monkeypatch.setattr(result_dataset, "appender", lambda array, folder: None)
    theirs = _write(tmp_path / "b", tmp_path / "b.zarr", sizes, ids, False)
    assert list(ours) == list(theirs)
    assert [k for k in ours if ours[k] != theirs[k]] == []
    assert not any(k.startswith("volume_obstacle_sector/") and k[-1].isdigit() for k in ours)
    assert "power/2.0" not in ours and "power/1.0" in ours  # the chunk of NaN only: none


def test_an_array_of_another_layout_is_appended_by_zarr(tmp_path):
    """An array not a whole number of chunks long (or chunked along another axis) is not
    this module's: None, zarr appends it."""
    from fretwear.bundle.zarr_chunks import appender

    if int(zarr.__version__.split(".")[0]) < 3:
        pytest.skip("zarr 2: its own append")
    root = zarr.open_group(str(tmp_path / "s"), mode="w", zarr_format=2)
    partial = root.create_array("p", shape=(10, 3), chunks=(4, 3), dtype="f8")
    across = root.create_array("q", shape=(8, 6), chunks=(4, 3), dtype="f8")
    whole = root.create_array("w", shape=(8, 3), chunks=(4, 3), dtype="f8")
    assert appender(partial, tmp_path / "s" / "p") is None
    assert appender(across, tmp_path / "s" / "q") is None
    assert appender(whole, tmp_path / "s" / "w") is not None
