"""The identity columns of a bundle (``tube_row``, ``tube_column``, ``support``, ``node``) are
coordinates along ``contact`` of ``BundleResult.dataset``, as docs/bundle.md says: every one,
also when the manifest leaves it empty, integers kept as integers when none is missing, and the
same after a write to Zarr and to NetCDF (``OutputDirectory.write_dataset``) and a read back.

Expected values: the manifest's own cells, written by this test (bundle_helpers.write_bundle:
rows 1, 1, 2, columns 1, 2, 1, support "AVB", no node column), one tube column left empty."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.bundle.store import OutputDirectory

xr = pytest.importorskip("xarray")


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """(full, gap): 3 contacts with every row and column given (no node column), and the same
    with the second contact's tube column left empty."""
    directory = tmp_path_factory.mktemp("identity")
    manifest, case = write_bundle(directory, oscillator(), 3)
    full = run_bundle(manifest, case, scheduler="serial")
    gap_dir = tmp_path_factory.mktemp("identity_gap")
    manifest, case = write_bundle(gap_dir, oscillator(), 3, extra={"tube_column": [1, None, 1]})
    gap = run_bundle(manifest, case, scheduler="serial")
    return full, gap


def _check(ds, *, columns):
    for name in ("tube_row", "tube_column", "support", "node"):
        assert name in ds.coords, name
        assert ds[name].dims == ("contact",), name
    assert ds["tube_row"].dtype == np.int64
    assert ds["tube_row"].values.tolist() == [1, 1, 2]
    got = ds["tube_column"].values
    if columns is None:
        assert got.dtype == np.int64
        assert got.tolist() == [1, 2, 1]
    else:  # one missing: floats, NaN where empty
        assert got.dtype == np.float64
        assert [None if math.isnan(v) else v for v in got.tolist()] == columns
    assert [str(v) for v in ds["support"].values] == ["AVB"] * 3
    assert [str(v) for v in ds["node"].values] == ["", "", ""]  # no node in the manifest


@pytest.mark.parametrize("fmt", ["zarr", "netcdf"])
def test_every_identity_column_is_a_coordinate_of_its_dtype(results, tmp_path, fmt):
    pytest.importorskip("zarr" if fmt == "zarr" else "netCDF4")
    full, gap = results
    _check(full.dataset, columns=None)
    _check(gap.dataset, columns=[1.0, None, 1.0])
    for name, result in (("full", full), ("gap", gap)):
        path = OutputDirectory(tmp_path / name).write_dataset(result.dataset, fmt)
        engine = "zarr" if fmt == "zarr" else None
        with xr.open_dataset(path, engine=engine) as back:
            back = back.load()
        _check(back, columns=None if name == "full" else [1.0, None, 1.0])
