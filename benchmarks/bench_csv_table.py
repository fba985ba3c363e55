"""The bundle's CSV table: :func:`fretwear.bundle.csv_table.write_csv` against pandas' ``to_csv``
(``float_format=FLOAT_FORMAT``), the same bytes, in the same run (issue 28: the CSV table of
20 000 contacts, 506 MB, took 57 s).

A table shaped as a bundle's (``--contacts`` contacts of 6 instants x 8 sectors: identity
columns, instants, durations, origins, sector numbers and angles repeated from contact to
contact) whose wear columns (powers, volumes, depths) are all distinct random reals: the case
least favourable to ``write_csv``, which formats each column's distinct values once (a real
bundle of identical histories repeats its wear values too, and goes faster). Prints both
times, their ratio, the size, whether the bytes are the same, and the load average.

Usage::

    .venv/bin/python benchmarks/bench_csv_table.py
    .venv/bin/python benchmarks/bench_csv_table.py --contacts 20000
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.bundle.csv_table import write_csv
from fretwear.table.schema import FLOAT_FORMAT

WEAR = ("power", "volume_mobile", "volume_obstacle", "depth_mobile", "depth_obstacle",
        "sector_power", "volume_mobile_sector", "volume_obstacle_sector", "depth_mobile_sector",
        "depth_obstacle_sector", "volume_mobile_cumulated", "volume_obstacle_cumulated")


def bundle_table(contacts: int, instants: int = 6, sectors: int = 8) -> pd.DataFrame:
    """A table of the bundle's columns (see the module's docstring)."""
    rows = instants * sectors
    n = contacts * rows
    k = np.arange(n)
    contact = np.repeat([f"R{c // 100 + 1}C{c % 100 + 1}-AVB" for c in range(contacts)], rows)
    rng = np.random.default_rng(28)
    frame = pd.DataFrame({
        "contact": contact, "tube_row": np.repeat(np.arange(contacts) // 100 + 1, rows),
        "tube_column": np.repeat(np.arange(contacts) % 100 + 1, rows),
        "support": np.nan, "node": None,
        "history": np.repeat([f"h/c{c:06d}.parquet" for c in range(contacts)], rows),
        "instant": np.tile(np.repeat([0.5, 1.0, 2.0, 5.0, 10.0, 20.0][:instants], sectors),
                           contacts),
        "duration": 3.15576e7, "origin": 0.0,
        "sector": k % sectors + 1,
        "angle_start": (k % sectors) * 360.0 / sectors,
        "angle_end": (k % sectors + 1) * 360.0 / sectors})
    for name in WEAR:
        frame[name] = rng.random(n) * 1e-6
    return frame


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=2_000)
    args = parser.parse_args(argv)
    frame = bundle_table(args.contacts)
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        theirs, ours = Path(tmp) / "pandas.csv", Path(tmp) / "ours.csv"
        t0 = time.perf_counter()
        frame.to_csv(theirs, index=False, float_format=FLOAT_FORMAT)
        t1 = time.perf_counter()
        assert write_csv(frame, ours)
        t2 = time.perf_counter()
        same = theirs.read_bytes() == ours.read_bytes()
        size = theirs.stat().st_size / 1e6
    print(f"{args.contacts} contacts, {len(frame)} rows, {size:.0f} MB: pandas to_csv "
          f"{t1 - t0:.2f} s, write_csv {t2 - t1:.2f} s ({(t1 - t0) / (t2 - t1):.1f}x); same "
          f"bytes: {same}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
