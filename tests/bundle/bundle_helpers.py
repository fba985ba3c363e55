"""Helpers of the bundle tests (imported as ``bundle_helpers``): small bundles cut from the
shipped oscillator history (examples/data/oscillator_gap.csv, a tube rattling in a support gap),
a base case, a manifest, and the single-contact reference (fretwear.table.wear_table on the same
history and case)."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.io import read_history, write_history
from fretwear.table import wear_table
from fretwear.workflows.case_files import case_arguments, load_case

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "data" / "oscillator_gap.csv"
SAMPLES = 3001
BASE_CASE = """\
title = "bundle test base case"
[law]
mobile = { COEF_USURE = 9.2e-15 }
[geometry]
contact_type = "TUBE_BAV"
mobile_radius_m = 9.525e-3
obstacle_width_m = 12.7e-3
[sectors]
count = 4
[time]
instants = [0.5, 1, 2, 5]
unit = "year"
"""


@functools.lru_cache(maxsize=1)
def oscillator():
    """The first 3001 samples (0.6 s) of the shipped history."""
    h = read_history(EXAMPLE)
    return h.replace(**{c: getattr(h, c)[:SAMPLES] for c in h.channels})


def scaled(history, k: int):
    """Contact k: the normal force scaled by 1 + 0.25 k (a different wear power per contact)."""
    return history.replace(normal_force=history.normal_force * (1.0 + 0.25 * k))


def write_bundle(directory: Path, history, count: int = 4, *, fmt: str = "parquet",
                 extra: dict | None = None) -> tuple[Path, Path]:
    """``count`` histories, the base case and a CSV manifest in ``directory``; returns the
    manifest and the case. ``extra``: more manifest columns (lists of ``count`` values)."""
    (directory / "histories").mkdir(parents=True, exist_ok=True)
    rows = []
    for k in range(count):
        name = f"histories/t{k}.{fmt}"
        write_history(scaled(history, k), directory / name)
        rows.append({"contact": f"R{k // 2 + 1}C{k % 2 + 1}-AVB", "history": name,
                     "tube_row": k // 2 + 1, "tube_column": k % 2 + 1, "support": "AVB"})
    frame = pd.DataFrame(rows)
    for column, values in (extra or {}).items():
        frame[column] = values
    manifest = directory / "manifest.csv"
    frame.to_csv(manifest, index=False)
    case = directory / "base.toml"
    case.write_text(BASE_CASE)
    return manifest, case


def manifest_tasks(manifest: Path, case: Path, chunk_size: int = 1_000_000) -> list:
    """The ContactTasks of a manifest's rows, built as the engine builds them (the base case
    loaded once, the rows sharing a case sharing it)."""
    from fretwear.bundle.cases import build_task
    from fretwear.bundle.manifest import read_manifest

    man = read_manifest(manifest)
    base = load_case(case)
    base["_directory"] = str(man.directory)
    cache: dict = {}
    return [build_task(base, row, man.source, chunk_size=chunk_size, cache=cache)
            for row in man.rows]


def reference(history_path, case_path, **read_options) -> pd.DataFrame:
    """The single-contact wear table: fretwear.table.wear_table on the history read with
    fretwear.io.read_history and the keywords of the case file (case-file layer)."""
    kw = case_arguments(load_case(case_path), history_elsewhere=True)
    return wear_table(read_history(history_path, **read_options), **kw)


def rows_of(result, contact: str) -> pd.DataFrame:
    """A contact's rows of a BundleResult, without the identity columns."""
    from fretwear.bundle import IDENTITY

    rows = result.table[result.table["contact"] == contact]
    return rows.drop(columns=list(IDENTITY)).reset_index(drop=True)


def assert_identical(got: pd.DataFrame, expected: pd.DataFrame) -> None:
    """Same columns, same values bit for bit (NaN where NaN).

    Bit for bit holds because both sides run on this machine in this environment: the bundle's
    Dask workers are child processes of the test, with its processor and its environment (the
    same numpy and numba SIMD code paths). It is not a promise across machines; there the
    results agree to rounding (tests/workflows/test_example_snapshots.py: 1e-12 relative)."""
    assert list(got.columns) == list(expected.columns)
    assert len(got) == len(expected)
    for c in expected.columns:
        a = got[c].to_numpy(dtype=float)
        b = expected[c].to_numpy(dtype=float)
        assert np.array_equal(a, b, equal_nan=True), c
