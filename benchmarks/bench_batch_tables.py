"""A bundle worker's sector tables: one contact at a time against a case's contacts together.

``--contacts`` (default 2000) PowerResults of 1 000-sample histories with dy/dz (the ``smooth``
signal of ``benchmarks/_signals.py``, each force scaled differently) are computed first. Then,
in turns over ``--rounds`` rounds (a shared machine drifts; medians printed), their sector tables
(TUBE_BAV, Archard, 8 sectors, 6 instants: the case of ``bench_bundle.py``):

* **alone**: ``fretwear.table.wear_table_columns(case, result, attrs=...)`` of each contact (the
  worker's path before issue 28's batches);
* **together**: ``fretwear.table.batch.sector_tables(case, results, attrs=...)`` of each run of
  ``--batch`` (default 16, ``fretwear.bundle.tasks.READ_AHEAD``) contacts.

Prints CPU microseconds a contact and the ratio alone / together (above 1: the batch is
cheaper). The tables of both ways are compared and must be equal bit for bit.

Usage::

    .venv/bin/python benchmarks/bench_batch_tables.py
    .venv/bin/python benchmarks/bench_batch_tables.py --contacts 500 --batch 8 --rounds 3
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _signals import TUBE_BAV, smooth  # noqa: E402

from fretwear.history import ContactHistory  # noqa: E402
from fretwear.power import wear_power  # noqa: E402
from fretwear.table import WearCase, wear_table_columns  # noqa: E402
from fretwear.table.batch import sector_tables  # noqa: E402

KEYWORDS = TUBE_BAV
ATTRS = ("contact_type", "dimensions", "law", "coefficients_mobile", "coefficients_obstacle",
         "coefficient_sources", "sector_edges", "time_scale", "origin")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=2000)
    parser.add_argument("--batch", type=int, default=16)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args(argv)
    case = WearCase.from_keywords(**KEYWORDS)
    results = []
    for k in range(args.contacts):
        arrays = smooth(k * 1000, 1000)
        arrays["time"] = arrays["time"] - arrays["time"][0]
        arrays["normal_force"] = arrays["normal_force"] * (0.5 + (k % 17) / 16)
        results.append(wear_power(ContactHistory(**arrays), sectors=8))
    runs = [results[i:i + args.batch] for i in range(0, len(results), args.batch)]

    def alone():
        return [wear_table_columns(case, r, attrs=ATTRS) for r in results]

    def together():
        return [t for run in runs for t in sector_tables(case, run, attrs=ATTRS)]

    for (a, a_attrs), (b, b_attrs) in zip(alone(), together(), strict=True):
        assert list(a) == list(b) and a_attrs == b_attrs
        assert all(a[c].tobytes() == b[c].tobytes() for c in a)
    times: dict[str, list[float]] = {"alone": [], "together": []}
    for _ in range(args.rounds):
        for name, fn in (("alone", alone), ("together", together)):
            t0 = time.process_time()
            fn()
            times[name].append((time.process_time() - t0) / len(results) * 1e6)
    a, b = statistics.median(times["alone"]), statistics.median(times["together"])
    print(f"{args.contacts} sector tables (8 sectors x 6 instants), batches of {args.batch}")
    print(f"alone     {a:8.1f} us a contact")
    print(f"together  {b:8.1f} us a contact")
    print(f"ratio alone / together: {a / b:.2f}")


if __name__ == "__main__":
    main()
