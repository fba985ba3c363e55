"""A whole tube bundle: the wear tables of thousands of contacts, on Dask.

A steam generator has thousands of tubes, each touching several anti-vibration bars and support
plates: an assessment is tens of thousands of contact histories. :func:`run_bundle` takes them
all in one call, from a manifest (one row per contact: its history file and what differs from
the base case), on a laptop (a local Dask cluster, one worker process per core) or on a cluster
(a scheduler address), and gives every contact the same numbers as the single-contact
:func:`fretwear.table.wear_table`.

- :mod:`fretwear.bundle.manifest`: reading manifests, multi-node Code_Aster tables, stores;
- :mod:`fretwear.bundle.datasets`: bundles held in one xarray Dataset / Zarr / NetCDF store;
- :mod:`fretwear.bundle.cases`: one contact's case (base case + overrides) and its task;
- :mod:`fretwear.bundle.tasks`: what a worker runs (whole contact, time chunk, merge, finish);
- :mod:`fretwear.bundle.engine`: :func:`run_bundle` (Dask orchestration, restarts);
- :mod:`fretwear.bundle.store`: the output directory (parts, final files), :func:`load`
  (a finished run's results read back, without its history files);
- :mod:`fretwear.bundle.result`: :class:`BundleResult` (table, dataset, errors, summary).

Needs the ``bundle`` extra: ``pip install 'fretwear[bundle]'`` (dask.distributed, xarray, zarr).
See docs/bundle.md.
"""

from fretwear.bundle.cases import ContactTask
from fretwear.bundle.engine import run_bundle
from fretwear.bundle.manifest import BUNDLE_COLUMNS, IDENTITY, Manifest, read_manifest
from fretwear.bundle.result import BundleResult
from fretwear.bundle.store import load

__all__ = [
    "BUNDLE_COLUMNS",
    "IDENTITY",
    "BundleResult",
    "ContactTask",
    "load",
    "Manifest",
    "read_manifest",
    "run_bundle",
]
