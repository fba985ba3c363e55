"""Where a bundle run's client memory goes, phase by phase (issue 28).

Runs ``--contacts`` contacts of ``--samples`` samples (the bundle of
``benchmarks/bench_bundle_scale.py``) on a LocalCluster of 2 workers with an output directory,
and samples this process's resident memory (psutil, every 20 ms; the process holds the client,
the local cluster's scheduler and their event loop). The phases are marked by wrapping the
engine's steps: the run (tasks built, results arriving, parts written), the final table's
assembly (``outputs._table``) or its streaming from the parts (``stream_table``), the summary,
the dataset's build (or its writing by groups of contacts) and the final files. Prints, for
each phase in order, the memory at its start and its peak over the memory before the run, in
kB a contact (the table itself is printed beside them for scale).

Usage::

    .venv/bin/python benchmarks/bench_bundle_memory.py --contacts 3000
"""

from __future__ import annotations

import argparse
import gc
import os
import shutil
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_bundle import CASE, local_cluster  # noqa: E402
from bench_bundle_scale import make_bundle  # noqa: E402

from fretwear.bundle import engine, outputs, result, run_bundle, store  # noqa: E402


class Phases:
    """The resident memory [bytes] at the start of each phase and its peak during it."""

    def __init__(self):
        import psutil

        self.me = psutil.Process()
        self.marks: list[list] = []  # [name, seconds, start bytes, peak bytes]
        self.stop = threading.Event()
        threading.Thread(target=self._watch, daemon=True).start()

    def mark(self, name: str) -> None:
        rss = self.me.memory_info().rss
        self.marks.append([name, time.perf_counter(), rss, rss])

    def _watch(self):
        while not self.stop.wait(0.02):
            if self.marks:
                self.marks[-1][3] = max(self.marks[-1][3], self.me.memory_info().rss)

    def wrap(self, module, name: str, label: str, after: str) -> None:
        f = getattr(module, name)

        def marked(*args, **kwargs):
            self.mark(label)
            try:
                return f(*args, **kwargs)
            finally:
                self.mark(after)

        setattr(module, name, marked)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=3000)
    parser.add_argument("--samples", type=int, default=1000)
    args = parser.parse_args(argv)
    import distributed

    n = args.contacts
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    phases = Phases()
    for module, name, label in [
            (engine, "open_engine", "run: tasks submitted, results arriving, parts written"),
            (outputs, "_table", "final table assembled"),
            (store.OutputDirectory, "stream_table", "table.parquet written from the parts"),
            (result, "summarize", "summary"),
            (outputs, "build_dataset", "dataset built"),
            (store.OutputDirectory, "write_dataset", "dataset written"),
            (store.OutputDirectory, "write_zarr_by_regions", "dataset written by groups"),
            (store.OutputDirectory, "write_table", "table written")]:
        if hasattr(module, name):
            phases.wrap(module, name, label, "between phases")
    directory = Path(tempfile.mkdtemp(prefix="bench_bundle_memory_"))
    try:
        case = directory / "base.toml"
        case.write_text(CASE)
        manifest = make_bundle(directory, n, args.samples, 50)
        warm = make_bundle(directory, 4, args.samples, 50)
        with local_cluster(2) as cluster, distributed.Client(cluster) as client:
            run_bundle(warm, case, scheduler=client)
            gc.collect()
            phases.marks.clear()
            phases.mark("read the manifest, build the tasks")
            base, t0 = phases.marks[0][2], phases.marks[0][1]
            res = run_bundle(manifest, case, scheduler=client, output=directory / "out")
            phases.mark("returned")
        phases.stop.set()
        table = res.table.memory_usage(deep=True).sum()  # read after: not in the peak
        print(f"{n} contacts of {args.samples} samples: {res.stats['done']} done; memory before "
              f"the run {base / 2**20:.0f} MiB; the table {table / n / 1e3:.1f} kB a contact")
        for name, t, start, peak in phases.marks:
            if name != "between phases":
                print(f"  {t - t0:7.1f} s  {name:55s} start {(start - base) / n / 1e3:6.1f}, "
                      f"peak {(peak - base) / n / 1e3:6.1f} kB a contact")
        top = max(m[3] for m in phases.marks)
        print(f"peak {top / 2**20:.0f} MiB: {(top - base) / n / 1e3:.1f} kB a contact")
    finally:
        shutil.rmtree(directory, ignore_errors=True)
        print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
