"""How a bundle's cost grows with its number of contacts: the client's share at the scale of a
steam generator (tens of thousands of contacts).

Bundles of ``--small`` and ``--large`` contacts (defaults 2 000 and 20 000) of short histories
(``--samples``, default 100: the computation is almost nothing, what is left is the cost of a
contact's bookkeeping) are run through :func:`fretwear.bundle.run_bundle` on a LocalCluster of
``--workers`` workers with an output directory, then run again into the same directory (a
restart: every contact unchanged, skipped). The histories are ``--distinct`` Parquet files (the
``smooth`` signal of ``benchmarks/_signals.py``) hard-linked under one name per contact.

Prints, for each size, the seconds of the whole run, of the part after the last result
(assembling the table and the dataset, writing the final files) and of the restart, per
contact; then the ratio of the large bundle's cost per contact to the small one's for each: 1
when the cost grows in proportion to the contacts, 10 when it grows with their square (as the
dataset's assembly did: 28 s for 20 000 contacts).

A whole steam generator (issue 28): ``--contacts N`` runs ``N / 10`` and ``N`` contacts of
``--samples`` (default 1 000 with ``--contacts``) samples, and for each size also prints:

* the wall time of the run against **a pyarrow read of the same files on as many processes as
  workers** (``pyarrow.parquet.read_table`` of the four channels of every file, the files
  dealt to a ``multiprocessing`` pool in the manifest's order; the floor of any Parquet
  bundle: the run's goal is within 1.5x of it);
* **the client's peak memory** (resident memory of this process, which holds the client, the
  local cluster's scheduler and their event loop, sampled every 50 ms with psutil during the
  run and the restart; goal under 2 GB at 10^5 contacts), and its rise over the process's
  memory before the run;
* the cost per contact (goal at 10^5 no more than 1.1x that at 10^4) and the restart's seconds
  (goal under 30 s at 10^5);
* the CPU this process (the client and the local cluster's scheduler) used during the run, per
  contact until the last result and in seconds after it: what the client takes from the
  workers' cores on a small machine;
* the CPU the workers used (every child process of this one: the cluster's nannies and
  workers), and the run's whole CPU (workers + this process) divided by the workers' cores:
  the least time this design could take on the machine, a bound set by the CPU the contacts
  cost and not by how the work is shared out, printed against the read;
* the workers' CPU split between their task threads (the contacts, the parts' writes, the
  pickles) and the rest of their processes (event loops: messages, heartbeats, Dask's timers).

The machine's load average is printed before and after: on a shared machine the two sizes
can be run at different loads.

Usage::

    .venv/bin/python benchmarks/bench_bundle_scale.py
    .venv/bin/python benchmarks/bench_bundle_scale.py --small 1000 --large 10000
    .venv/bin/python benchmarks/bench_bundle_scale.py --contacts 100000
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import sys
import tempfile
import threading
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _signals import smooth  # noqa: E402
from bench_bundle import CASE, local_cluster  # noqa: E402  (the same base case and cluster)

from fretwear.bundle import engine as engine_module  # noqa: E402
from fretwear.bundle import run_bundle  # noqa: E402
from fretwear.history import ContactHistory  # noqa: E402
from fretwear.io import write_history  # noqa: E402


def make_bundle(directory: Path, contacts: int, samples: int, distinct: int) -> Path:
    """A manifest of ``contacts`` contacts whose histories are ``distinct`` files hard-linked
    (copied where links are refused) under one name each."""
    sources = directory / "sources"
    if not sources.is_dir():
        sources.mkdir(parents=True)
        for k in range(distinct):
            arrays = smooth(k * samples, samples)
            arrays["time"] = arrays["time"] - arrays["time"][0]
            arrays["normal_force"] = arrays["normal_force"] * (0.5 + (k % 17) / 16)
            write_history(ContactHistory(**arrays), sources / f"s{k:03d}.parquet")
    folder = directory / f"bundle{contacts}"
    folder.mkdir()
    rows = []
    for k in range(contacts):
        name = f"c{k:05d}.parquet"
        source = sources / f"s{k % distinct:03d}.parquet"
        try:
            os.link(source, folder / name)
        except OSError:
            shutil.copyfile(source, folder / name)
        rows.append({"contact": f"c{k:05d}", "history": name,
                     "tube_row": k // 100 + 1, "tube_column": k % 100 + 1})
    manifest = folder / "manifest.csv"
    pd.DataFrame(rows).to_csv(manifest, index=False)
    return manifest


class PeakMemory:
    """Peak resident memory [bytes] of this process while the block runs (psutil, 50 ms)."""

    def __enter__(self):
        import psutil

        self.me = psutil.Process()
        self.start = self.me.memory_info().rss
        self.peak = self.start
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._watch, daemon=True)
        self.thread.start()
        return self

    def _watch(self):
        while not self.stop.wait(0.05):
            self.peak = max(self.peak, self.me.memory_info().rss)

    def __exit__(self, *exc):
        self.stop.set()
        self.thread.join()
        self.peak = max(self.peak, self.me.memory_info().rss)


def _read_files(paths: list[str]) -> int:
    """Rows of the four channels of each Parquet file, read with pyarrow (a pool process)."""
    import pyarrow.parquet as pq

    rows = 0
    for p in paths:
        rows += pq.read_table(p, columns=["time", "normal_force", "vt1", "vt2"]).num_rows
    return rows


def pyarrow_read(manifest: Path, processes: int) -> float:
    """Seconds of a pyarrow read of the manifest's files on ``processes`` processes (the pool
    started and warmed up first, not counted)."""
    import multiprocessing

    paths = [str(manifest.parent / name) for name in pd.read_csv(manifest)["history"]]
    parts = [paths[k::processes] for k in range(processes)]
    with multiprocessing.get_context("spawn").Pool(processes) as pool:
        pool.map(_read_files, [p[:2] for p in parts])
        t0 = time.perf_counter()
        pool.map(_read_files, parts)
        return time.perf_counter() - t0


def breakdown(manifest: Path, case: Path, count: int = 500) -> dict[str, float]:
    """Seconds a contact of the manifest costs in this process, by step, each the best of 3
    passes over its first ``count`` contacts: a pyarrow read of the four channels, the wear
    power streamed from the file (fretwear.power.wear_power, as a worker calls it), the wear
    table's columns from that power, and the worker's whole path for a group of contacts
    (tasks.run_contacts and the pickle of its records); then pyarrow's direct read of the six
    channels (ParquetFile) and the worker's read with its checks (warnings captured,
    plausibility, units against the geometry) and power. What bounds the run against the read."""
    import warnings

    import pyarrow.parquet as pq

    from fretwear.bundle.cases import build_task
    from fretwear.bundle.engine import _base_case
    from fretwear.bundle.manifest import read_manifest
    from fretwear.bundle.tasks import captured, pickled, run_contacts
    from fretwear.io.geometry_units import check_against_geometry
    from fretwear.power import wear_power
    from fretwear.table import wear_table_columns

    warnings.simplefilter("ignore")
    man = read_manifest(manifest)
    base = _base_case(case)
    base["_directory"] = str(man.directory)
    cache: dict = {}
    tasks = [build_task(base, r, man.source, chunk_size=1_000_000, cache=cache)
             for r in man.rows[:count]]
    wear = tasks[0].wear_case()
    powers = [wear_power(t.history.path, **wear.power_options) for t in tasks]

    def read():
        for t in tasks:
            pq.read_table(t.history.path, columns=["time", "normal_force", "vt1", "vt2"])

    def power():
        for t in tasks:
            wear_power(t.history.path, **wear.power_options)

    def parquet_file():  # pyarrow's direct read of the six channels the case needs
        for t in tasks:
            handle = pq.ParquetFile(t.history.path, pre_buffer=False)
            handle.read(columns=["time", "normal_force", "vt1", "vt2", "dy", "dz"],
                        use_threads=False)
            handle.close()

    dims = wear.dimensions

    def geometry(first):  # the worker's check of the first block's units against the tube
        check_against_geometry(first, mobile_radius=dims.get("mobile_radius"),
                               obstacle_radius=dims.get("obstacle_radius"))

    def checked_power():  # as tasks._file_table calls it: the checks a worker runs, then power
        for t in tasks:
            with captured():
                wear_power(t.history.path, **wear.power_options, name=t.contact,
                           first_block=geometry, **t.read_options)

    def table():
        for p in powers:
            wear_table_columns(wear, p)

    def worker():
        pickled(run_contacts, tasks)

    out = {}
    for name, step in (("pyarrow read", read), ("wear power", power),
                       ("wear table from the power", table), ("worker's whole path", worker),
                       ("ParquetFile read of 6 channels", parquet_file),
                       ("worker's read + checks + power", checked_power)):
        best = math.inf
        for _ in range(3):
            t0 = time.perf_counter()
            step()
            best = min(best, time.perf_counter() - t0)
        out[name] = best / len(tasks)
    return out


def _cpu_seconds() -> float:
    """CPU seconds (user + system) this process has used: the client, the local cluster's
    scheduler and their event loop, every thread (not the worker processes, its children)."""
    times = os.times()
    return times.user + times.system


def _children_cpu() -> float:
    """CPU seconds (user + system) used so far by this process's children and their children:
    the local cluster's nannies and workers (psutil; a process gone meanwhile counts 0)."""
    import psutil

    total = 0.0
    for child in psutil.Process().children(recursive=True):
        try:
            times = child.cpu_times()
        except psutil.Error:
            continue
        total += times.user + times.system
    return total


def _task_thread_cpu() -> float:
    """CPU seconds (user + system) used so far by this worker's threads that run tasks (Dask's
    ``Dask-Default-Threads``: the contacts, the part's write, the pickle); the rest of the
    process is the event loop (messages, heartbeats, Dask's timers) (run in a worker)."""
    import threading

    import psutil

    ids = {t.native_id for t in threading.enumerate() if "Dask-Default-Threads" in t.name}
    return sum(t.user_time + t.system_time for t in psutil.Process().threads() if t.id in ids)


def measure(manifest: Path, case: Path, client, output: Path
            ) -> tuple[float, float, float, PeakMemory]:
    """Seconds of (the run, its part after the last result, the restart), and the client's
    memory during both."""
    marks = {}
    assemble = engine_module.assemble

    def timed(*args, **kwargs):
        marks["assemble"] = time.perf_counter()
        marks["cpu"] = _cpu_seconds()
        return assemble(*args, **kwargs)

    engine_module.assemble = timed
    try:
        with PeakMemory() as memory:
            cpu0, workers0 = _cpu_seconds(), _children_cpu()
            tasks0 = sum(client.run(_task_thread_cpu).values())
            t0 = time.perf_counter()
            result = run_bundle(manifest, case, scheduler=client, output=output)
            end = time.perf_counter()
            memory.cpu = (_cpu_seconds() - cpu0, marks["cpu"] - cpu0)
            memory.workers_cpu = _children_cpu() - workers0
            memory.task_threads = sum(client.run(_task_thread_cpu).values()) - tasks0
            if result.stats["done"] != result.stats["contacts"]:
                raise SystemExit(f"{result.stats['failed']} contacts failed: "
                                 f"{result.errors.head()}")
            del result
            tail = end - marks["assemble"]
            t1 = time.perf_counter()
            again = run_bundle(manifest, case, scheduler=client, output=output)
            restart = time.perf_counter() - t1
    finally:
        engine_module.assemble = assemble
    if again.stats["skipped"] != again.stats["contacts"]:
        raise SystemExit("the restart recomputed contacts")
    return end - t0, tail, restart, memory


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", type=int, default=2_000)
    parser.add_argument("--large", type=int, default=20_000)
    parser.add_argument("--contacts", type=int,
                        help="a steam generator: contacts/10 and contacts (e.g. 100000), with "
                             "the pyarrow read and the client's memory")
    parser.add_argument("--samples", type=int, help="default 100, 1000 with --contacts")
    parser.add_argument("--distinct", type=int, default=50, help="distinct history files")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    if args.contacts:
        args.small, args.large = args.contacts // 10, args.contacts
    if args.samples is None:
        args.samples = 1000 if args.contacts else 100
    import distributed

    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    directory = Path(tempfile.mkdtemp(prefix="bench_bundle_scale_"))
    try:
        case = directory / "base.toml"
        case.write_text(CASE)
        manifests = {n: make_bundle(directory, n, args.samples, args.distinct)
                     for n in (args.small, args.large)}
        warm = make_bundle(directory, 4, args.samples, args.distinct)
        if args.contacts:
            steps = breakdown(manifests[args.small], case)
            ratio = steps["worker's whole path"] / steps["pyarrow read"]
            checked = steps["worker's read + checks + power"] / steps["pyarrow read"]
            print("a contact in one process (best of 3 over 500): " + ", ".join(
                f"{name} {1e3 * t:.3f} ms" for name, t in steps.items())
                + f"; the worker's path is {ratio:.1f}x the read (its read + checks + power "
                f"{checked:.2f}x)", flush=True)
        costs = {}
        for n, manifest in manifests.items():
            # a fresh cluster per size: the scheduler's memory of the first size is not the
            # second's; the pyarrow read right before, on the same cores
            floor = pyarrow_read(manifest, args.workers) if args.contacts else None
            with local_cluster(args.workers) as cluster, distributed.Client(cluster) as client:
                run_bundle(warm, case, scheduler=client)
                run, tail, restart, memory = measure(manifest, case, client,
                                                     directory / f"out{n}")
            costs[n] = (run / n, tail / n, restart / n)
            print(f"{n} contacts of {args.samples} samples on {args.workers} workers: run "
                  f"{run:.2f} s ({n / run:.0f} contacts/s, {1e3 * run / n:.3f} ms a contact), "
                  f"of which {tail:.2f} s after the last result (table, dataset, files); "
                  f"restart (all skipped) {restart:.2f} s", flush=True)
            if floor is not None:
                print(f"  pyarrow read of the same files on {args.workers} processes "
                      f"{floor:.2f} s: the run is {run / floor:.2f}x that read (goal 1.5x); "
                      f"client's peak memory {memory.peak / 2**30:.2f} GB "
                      f"({memory.start / 2**30:.2f} GB before the run; "
                      f"{(memory.peak - memory.start) / n / 1e3:.1f} kB a contact; goal under "
                      "2 GB)", flush=True)
            cpu, to_tail = memory.cpu
            print(f"  this process (client + scheduler) used {cpu:.2f} s of CPU during the run "
                  f"({100 * cpu / run:.0f} % of a core; {1e3 * to_tail / n:.3f} ms a contact "
                  f"until the last result, {cpu - to_tail:.2f} s after it)", flush=True)
            least = (cpu + memory.workers_cpu) / args.workers
            print(f"  the workers used {memory.workers_cpu:.2f} s of CPU "
                  f"({1e3 * memory.workers_cpu / n:.3f} ms a contact); all the run's CPU shared "
                  f"perfectly over {args.workers} cores: {least:.2f} s, the least this design "
                  "takes on this machine" + (f" = {least / floor:.2f}x the read" if floor
                                             else ""), flush=True)
            rest = memory.workers_cpu - memory.task_threads
            print(f"  of the workers' CPU, their task threads (the contacts, the parts' writes, "
                  f"the pickles) {1e3 * memory.task_threads / n:.3f} ms a contact, the rest "
                  f"(event loops: messages, heartbeats, Dask's timers) {1e3 * rest / n:.3f} ms",
                  flush=True)
            shutil.rmtree(directory / f"out{n}", ignore_errors=True)
        small, large = costs[args.small], costs[args.large]
        names = ("run", "after the last result", "restart")
        print(f"cost per contact at {args.large} / at {args.small} contacts (1: proportional, "
              f"{args.large / args.small:.0f}: quadratic; goal for the run <= 1.1): " + ", ".join(
                  f"{name} {b / a:.2f}" for name, a, b in zip(names, small, large, strict=True)))
    finally:
        shutil.rmtree(directory, ignore_errors=True)
        print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
