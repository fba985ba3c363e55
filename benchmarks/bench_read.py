"""Reading a contact history: the plausibility checks compiled against their numpy reference.

``--files`` (default 60) Parquet histories of ``--samples`` (default 10⁵) samples with dy/dz
(the ``smooth`` signal of ``benchmarks/_signals.py``, as ``bench_bundle.py`` writes them) are
generated in a temporary directory. Then, in turns over ``--rounds`` rounds (a shared machine
drifts within minutes; medians are printed):

* **checks**: :func:`fretwear.io.plausibility.check_plausibility` of every history (read
  beforehand; the files cycle, so the data come from memory, not from the CPU's cache), with the
  compiled pass (``fretwear.io._compiled``, from ``plausibility._KERNEL_SAMPLES`` samples on)
  and with the numpy expressions (the threshold raised above the history's length);
* **wear tables**: ``fretwear.table.wear_table(path, ...)`` of every file (TUBE_BAV, Archard,
  8 sectors, 6 instants: the single-contact API as a user calls it), both ways.

Prints milliseconds a history and the ratios numpy / compiled (above 1: the compiled pass is
faster). The messages of both ways are compared and must be the same.

Usage::

    .venv/bin/python benchmarks/bench_read.py
    .venv/bin/python benchmarks/bench_read.py --files 20 --samples 2e5 --rounds 5
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _signals import TUBE_BAV, smooth  # noqa: E402

from fretwear.history import ContactHistory  # noqa: E402
from fretwear.io import plausibility, read_history, write_history  # noqa: E402
from fretwear.table import wear_table  # noqa: E402

KEYWORDS = TUBE_BAV


def _per_item(fn, items) -> float:
    """Milliseconds per item of ``fn`` over ``items`` [ms]."""
    t0 = time.perf_counter()
    for item in items:
        fn(item)
    return (time.perf_counter() - t0) / len(items) * 1e3


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--files", type=int, default=60)
    parser.add_argument("--samples", type=float, default=1e5)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args(argv)
    samples = int(args.samples)
    if samples < plausibility._KERNEL_SAMPLES:
        parser.error(f"--samples must be at least {plausibility._KERNEL_SAMPLES} (below, the "
                     "numpy expressions run either way)")
    warnings.simplefilter("ignore")
    compiled_size = plausibility._KERNEL_SAMPLES
    with tempfile.TemporaryDirectory(prefix="bench_read_") as tmp:
        paths = []
        for k in range(args.files):
            arrays = smooth(k * samples, samples)
            arrays["time"] = arrays["time"] - arrays["time"][0]
            paths.append(write_history(ContactHistory(**arrays), Path(tmp) / f"c{k:03d}.parquet"))
        histories = [read_history(p) for p in paths]
        plausibility.check_plausibility(histories[0])  # compile or load the kernel
        wear_table(paths[0], **KEYWORDS)
        same = True
        timings: dict[str, list[float]] = {k: [] for k in ("checks compiled", "checks numpy",
                                                           "table compiled", "table numpy")}
        for _ in range(max(1, args.rounds)):
            for mode, size in (("compiled", compiled_size), ("numpy", 1 << 62)):
                plausibility._KERNEL_SAMPLES = size
                timings[f"checks {mode}"].append(
                    _per_item(plausibility.check_plausibility, histories))
                timings[f"table {mode}"].append(
                    _per_item(lambda p: wear_table(p, **KEYWORDS), paths))
            plausibility._KERNEL_SAMPLES = compiled_size
            messages = [plausibility.check_plausibility(h) for h in histories]
            plausibility._KERNEL_SAMPLES = 1 << 62
            same &= messages == [plausibility.check_plausibility(h) for h in histories]
            plausibility._KERNEL_SAMPLES = compiled_size
    med = {k: statistics.median(v) for k, v in timings.items()}
    print(f"{args.files} Parquet histories x {samples:.0e} samples with dy/dz, "
          f"{max(1, args.rounds)} rounds (medians)")
    checks = med["checks numpy"] / med["checks compiled"]
    tables = med["table numpy"] / med["table compiled"]
    print(f"plausibility checks: compiled {med['checks compiled']:.3f} ms, numpy "
          f"{med['checks numpy']:.3f} ms a history: ratio {checks:.2f}")
    print(f"wear_table(path): compiled {med['table compiled']:.2f} ms, numpy "
          f"{med['table numpy']:.2f} ms a history: ratio {tables:.2f} "
          f"({(1 - 1 / tables) * 100:.0f} % less time)")
    print(f"messages the same both ways: {same}")


if __name__ == "__main__":
    main()
