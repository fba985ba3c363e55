"""Snapshots of every shipped example's results, for the regression check of refactors.

``python tests/workflows/example_snapshots.py`` (re)writes ``example_tables/*.csv`` from the
current code; ``python tests/workflows/example_snapshots.py DIR`` writes them into DIR (the
child process of the same-machine test). The CSVs are written with ``%.17g``, which
round-trips every float64 exactly.

The tables were first written by the code of commit 6de0b66 (before the layers refactor,
issue 10), on a machine with AVX-512: ``test_example_snapshots.py`` compares the wear tables
and the obstacle profile to them at a stated relative tolerance, and the coupled loop (a
chaotic rattling tube) within the confidence intervals of its powers. Do not rewrite them to
make a machine pass: a difference beyond those bounds is a change of the numbers.
"""

from __future__ import annotations

import tempfile
import warnings
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
SNAPSHOTS = Path(__file__).resolve().parent / "example_tables"
#: the wear-table examples (one per contact type); obstacle_grappe and the loop are separate
CASES = ("tube_bav", "tube_tube", "tube_alesage", "tube_3_enco", "tube_4_enco",
         "grappe_alesage", "grappe_1_enco", "grappe_2_enco")


def _run_case(path):
    from fretwear.workflows.case_files import run_case

    return run_case(path)


def _load_case(path):
    from fretwear.workflows.case_files import load_case

    return load_case(path)


def _iterate(path, output):
    from fretwear.workflows.loop import iterate_case

    return iterate_case(path, output=output, plot=False)


def compute() -> dict[str, pd.DataFrame]:
    """Every example's result tables, by snapshot name."""
    from fretwear.obstacle import obstacle_from_config

    out: dict[str, pd.DataFrame] = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in CASES:
            out[name] = _run_case(EXAMPLES / f"{name}.toml").table.reset_index(drop=True)
        case = _load_case(EXAMPLES / "obstacle_grappe.toml")
        setup = obstacle_from_config(case["obstacle"], geometry=case["geometry"],
                                     directory=case.get("_directory"))
        result = setup.update(_run_case(case).table)
        out["obstacle_grappe_profile"] = result.to_frame().reset_index(drop=True)
        with tempfile.TemporaryDirectory() as tmp:
            loop = _iterate(EXAMPLES / "iterate_tube_support.toml", Path(tmp) / "it")
            summary = loop.summary.reset_index(drop=True)
            out["iterate_summary"] = summary.select_dtypes("number")
            for k, table in enumerate(loop.tables, start=1):
                out[f"iterate_cycle{k}_table"] = table.reset_index(drop=True)
    return out


def write(directory: Path = SNAPSHOTS) -> None:
    directory = Path(directory)
    directory.mkdir(exist_ok=True)
    for name, frame in compute().items():
        frame.to_csv(directory / f"{name}.csv", index=False, float_format="%.17g")


if __name__ == "__main__":
    import sys

    write(Path(sys.argv[1]) if len(sys.argv) > 1 else SNAPSHOTS)
