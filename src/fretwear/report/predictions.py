"""What predicts the inspected contacts: a case file, or the results of a bundle run.

:func:`fretwear.uncertainty.calibrate` takes wear tables that carry their case (``attrs["case"]``,
or the provenance of a file fretwear wrote); a bundle keeps each contact's run (its power,
coefficients, geometry, wall) in the JSON records of its output directory
(:mod:`fretwear.bundle.store`), which :func:`bundle_predictions` joins back to its rows as
``attrs["bundle_record"]`` (read by :func:`fretwear.table.models_from_table`).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from fretwear._lazy import pandas as pd
from fretwear.bundle.manifest import IDENTITY
from fretwear.bundle.store import OutputDirectory, read_frame
from fretwear.errors import InputError
from fretwear.workflows.case_files import run_case

__all__ = ["bundle_predictions", "case_predictions"]


def case_predictions(case) -> dict[str, pd.DataFrame]:
    """``{name: wear table}`` of a case file (or its dict): one contact, named by its title or
    its history's name ("" when neither)."""
    result = run_case(case)
    table = result.table
    name = str(result.case.get("history", {}).get("name") or result.wear_case.name or "")
    return {name: table}


def bundle_predictions(results: Any) -> tuple[dict[str, pd.DataFrame], pd.DataFrame]:
    """The wear table (with its metadata) of every computed contact of a bundle run, and the
    contacts' identity columns.

    Parameters
    ----------
    results : BundleResult or path-like
        The results of :func:`fretwear.bundle.run_bundle` (run with an output directory) or that
        directory.

    Returns
    -------
    (dict of str to DataFrame, DataFrame)
        ``{contact: wear table}`` and one row per contact with ``contact, tube_row, tube_column,
        support, node, history``.

    Raises
    ------
    InputError
        Not a bundle output directory, or no computed contact in it.
    """
    path = getattr(results, "output", results)
    if path is None:
        raise InputError("these bundle results have no output directory: run the bundle with "
                         "output=... (fretwear bundle -o DIR) to calibrate on it")
    directory = Path(os.fspath(path))
    if not (directory / "parts").is_dir():
        raise InputError(f"{str(directory)!r} is not the output directory of a bundle run "
                         "(no parts/ folder): give the directory of fretwear bundle -o")
    store = OutputDirectory(directory)
    records = {c: r for c, r in store.previous().items()
               if r.get("status") in ("done", "skipped") and r.get("attrs")}
    if not records:
        raise InputError(f"the bundle output {str(directory)!r} has no computed contact")
    rows = store.rows(records.values())
    tables: dict[str, pd.DataFrame] = {}
    for contact, record in records.items():
        if contact in rows:
            table = rows[contact]
            # the run's values its record keeps (it keeps no case): models_from_table reads them
            table.attrs = {"bundle_record": dict(record["attrs"])}
            tables[contact] = table
    identity = pd.DataFrame({"contact": list(tables)})
    for name in ("table.parquet", "table.csv"):
        final = directory / name
        if final.is_file():
            frame = read_frame(final)
            cols = [c for c in IDENTITY if c in frame.columns]
            identity = frame[cols].drop_duplicates("contact").astype({"contact": str})
            break
    return tables, identity
