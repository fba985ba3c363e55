"""Throughput of a bundle on Dask against the serial loop over the single-contact API.

A bundle of ``--contacts`` (default 500) contacts × ``--samples`` (default 10⁵) samples is
generated as Parquet files in a temporary directory (the ``smooth`` signal of
``benchmarks/_signals.py``: an oscillator impacting a gap, each contact its own stretch of the
record and its own force scale), with a CSV manifest and a base case (TUBE_BAV, Archard,
8 sectors, 6 instants). Then:

* **serial**: ``fretwear.table.wear_table(path, **keywords)`` for every contact in a loop (the
  keywords built once from the base case): the single-contact API; pyarrow decodes Parquet on
  every core, so the loop is run again with one decoding thread, as in a Dask worker;
* **bundle**: :func:`fretwear.bundle.run_bundle` on a LocalCluster of ``--workers`` worker
  processes (one thread each, no scheduler-side queuing: the cluster ``run_bundle`` starts),
  joined through its client (cluster start excluded; workers warmed up by a small run first,
  then a full garbage collection in them as in this process before its loop: the warm-up's
  imports would otherwise leave a 0.1 s collector pass to the next run), without and with an
  output directory;
* **rounds**: the serial loop, the machine's scaling and the bundle are measured in turn
  ``--rounds`` times (a fresh cluster each round, started after the loop), and the medians
  reported with the range of the rounds' speed-ups: a shared machine drifts by 10-20 % within
  minutes, so one loop and one bundle measured minutes apart can be 10 % off either way;
* **grouping**: the same bundle with one contact per Dask task instead of
  the tasks of ``engine.task_sizes``;
* **the machine's scaling**: the serial loop split over ``--workers`` plain processes
  (multiprocessing, no Dask): what the cores, caches and memory bandwidth allow this workload,
  the ceiling of the bundle's speed-up;
* **per-contact overhead**: (workers × T_bundle − T_serial)/N, the worker time a contact costs
  beyond the single-contact computation, measured on this bundle and on one of tiny contacts
  (100 samples, where the computation is almost nothing);
* **CPU**: the CPU seconds of the worker processes and of this process (client, scheduler and
  their event loop) during the timed bundle, against the loop's own CPU seconds: their sum
  over ``--workers`` is the least time the bundle could take on that many cores perfectly
  shared, and gives the highest speed-up this machine allows it;
* **memory**: peak resident memory of each worker process (sampled every 20 ms with psutil, in
  a run of its own: the sampling thread stays out of the timed run), idle, during this
  bundle, and during one contact of ``--long`` samples read in chunks of ``--chunk`` samples
  (chunk tasks merged in a tree) against the same contact in one task: the peak follows the
  chunk, not the bundle or the history.

The bundle's tables are checked equal to the serial ones bit for bit: both run in this
benchmark, on this machine, in this environment (the workers are its child processes), which
is where bit for bit is promised; across machines only to rounding. Prints contacts/s,
samples/s, the speed-up (goal >= 1.7 on 2 cores), the overhead (goal < 20 ms) and the memory.

Usage::

    .venv/bin/python benchmarks/bench_bundle.py
    .venv/bin/python benchmarks/bench_bundle.py --contacts 100 --samples 1e4 --long 1e6
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

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _signals import smooth  # noqa: E402

from fretwear.bundle import engine as engine_module  # noqa: E402
from fretwear.bundle import run_bundle  # noqa: E402
from fretwear.history import ContactHistory  # noqa: E402
from fretwear.io import write_history  # noqa: E402
from fretwear.table import wear_table  # noqa: E402
from fretwear.workflows.case_files import case_arguments, load_case  # noqa: E402

CASE = """\
[law]
mobile = { COEF_USURE = 1e-17 }
[geometry]
contact_type = "TUBE_BAV"
mobile_radius_m = 9.525e-3
obstacle_width_m = 12.7e-3
[sectors]
count = 8
[time]
instants = [1, 2, 5, 10, 20, 40]
unit = "year"
"""


def make_bundle(directory: Path, contacts: int, samples: int, name: str) -> Path:
    """``contacts`` Parquet histories and their manifest under ``directory/name``."""
    folder = directory / name
    folder.mkdir(parents=True)
    rows = []
    for k in range(contacts):
        arrays = smooth(k * samples, samples)
        arrays["time"] = arrays["time"] - arrays["time"][0]
        arrays["normal_force"] = arrays["normal_force"] * (0.5 + (k % 17) / 16)
        path = folder / f"c{k:05d}.parquet"
        write_history(ContactHistory(**arrays), path)
        rows.append({"contact": f"c{k:05d}", "history": path.name,
                     "tube_row": k // 25 + 1, "tube_column": k % 25 + 1})
    manifest = folder / "manifest.csv"
    pd.DataFrame(rows).to_csv(manifest, index=False)
    return manifest


def serial(manifest: Path, case: Path) -> tuple[float, dict[str, pd.DataFrame]]:
    """Seconds of the loop over fretwear.table.wear_table, and the tables."""
    keywords = case_arguments(load_case(case), history_elsewhere=True)
    frame = pd.read_csv(manifest)
    tables = {}
    t0 = time.perf_counter()
    for row in frame.itertuples():
        tables[row.contact] = wear_table(manifest.parent / row.history, **keywords)
    return time.perf_counter() - t0, tables


def _loop_part(manifest: Path, case: Path, part: int, parts: int) -> float:
    """Seconds of the serial loop over every ``parts``-th contact from ``part`` on (run in a
    pool process, after one warm-up contact)."""
    import warnings

    warnings.simplefilter("ignore")
    keywords = case_arguments(load_case(case), history_elsewhere=True)
    rows = list(pd.read_csv(manifest).itertuples())[part::parts]
    wear_table(manifest.parent / rows[0].history, **keywords)
    t0 = time.perf_counter()
    for row in rows:
        wear_table(manifest.parent / row.history, **keywords)
    return time.perf_counter() - t0


def machine_scaling(manifest: Path, case: Path, workers: int) -> float:
    """What the machine itself gives: the serial loop split over ``workers`` plain processes
    (multiprocessing, no Dask), T(one process) / max T(each of them) [-]."""
    import multiprocessing

    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        one = pool.apply(_loop_part, (manifest, case, 0, 1))
        many = pool.starmap(_loop_part, [(manifest, case, k, workers) for k in range(workers)])
    return one / max(many)


class CpuTime:
    """CPU seconds (user + system) of the worker processes, and of this process (the client,
    the scheduler of a local cluster, their event loop), while in use [s]."""

    def __init__(self, client) -> None:
        import psutil

        self.processes = [psutil.Process(pid) for pid in client.run(os.getpid).values()]
        self.me = psutil.Process()
        self.workers = self.client = 0.0

    @staticmethod
    def _seconds(process) -> float:
        t = process.cpu_times()
        return t.user + t.system

    def __enter__(self) -> CpuTime:
        self._start = [self._seconds(p) for p in self.processes], self._seconds(self.me)
        return self

    def __exit__(self, *exc) -> None:
        workers, me = self._start
        self.workers = sum(self._seconds(p) - s for p, s in zip(self.processes, workers,
                                                                strict=True))
        self.client = self._seconds(self.me) - me


class PeakMemory:
    """Samples the resident memory of the worker processes every 20 ms while in use [MB]."""

    def __init__(self, client) -> None:
        import psutil

        self.processes = [psutil.Process(pid) for pid in client.run(os.getpid).values()]
        self.peaks = [0.0] * len(self.processes)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._sample, daemon=True)

    def _sample(self) -> None:
        while not self._stop.is_set():
            for i, p in enumerate(self.processes):
                try:
                    self.peaks[i] = max(self.peaks[i], p.memory_info().rss / 2**20)
                except Exception:  # noqa: BLE001 - a worker restarting
                    pass
            time.sleep(0.02)

    def __enter__(self) -> PeakMemory:
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join()

    def text(self) -> str:
        return ", ".join(f"{p:.0f}" for p in sorted(self.peaks)) + " MB"


def bundle_time(manifest: Path, case: Path, client, **options) -> tuple[float, object]:
    t0 = time.perf_counter()
    result = run_bundle(manifest, case, scheduler=client, **options)
    return time.perf_counter() - t0, result


def identical(result, tables: dict[str, pd.DataFrame]) -> bool:
    from fretwear.bundle import IDENTITY

    for contact, expected in tables.items():
        got = result.table[result.table["contact"] == contact].drop(columns=list(IDENTITY))
        for c in expected.columns:
            if not np.array_equal(got[c].to_numpy(dtype=float), expected[c].to_numpy(dtype=float),
                                  equal_nan=True):
                return False
    return True


def local_cluster(workers: int):
    """A LocalCluster as run_bundle starts one: single-threaded worker processes, every task
    sent to a worker's queue at once, the workers' malloc as in a plain process
    (fretwear.bundle.cluster.LOCAL_CLUSTER_CONFIG)."""
    import dask
    import distributed

    from fretwear.bundle.cluster import LOCAL_CLUSTER_CONFIG

    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        return distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                        dashboard_address=":0")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=500)
    parser.add_argument("--samples", type=float, default=1e5)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--long", type=float, default=4e6,
                        help="samples of the long contact of the memory check (0: skip)")
    parser.add_argument("--chunk", type=float, default=2.5e5,
                        help="chunk of the long contact [samples]")
    parser.add_argument("--rounds", type=int, default=3,
                        help="rounds of (serial loop, bundle) measured in turn; medians shown")
    parser.add_argument("--keep", type=Path, help="generate the bundle here and keep it")
    args = parser.parse_args(argv)
    if args.rounds < 1:
        parser.error("--rounds must be at least 1")
    import distributed

    n, samples = args.contacts, int(args.samples)
    directory = args.keep or Path(tempfile.mkdtemp(prefix="bench_bundle_"))
    directory.mkdir(parents=True, exist_ok=True)
    try:
        case = directory / "base.toml"
        case.write_text(CASE)
        t0 = time.perf_counter()
        manifest = make_bundle(directory, n, samples, "bundle")
        tiny = make_bundle(directory, n, 100, "tiny")
        warm = make_bundle(directory, 2 * args.workers, samples, "warm")
        print(f"generated {n} contacts x {samples:.0e} samples (+ {n} tiny) as Parquet in "
              f"{time.perf_counter() - t0:.1f} s under {directory}")
        serial(warm, case)  # compile / load the kernels in this process
        import pyarrow

        threads = pyarrow.cpu_count()
        w = args.workers
        rounds = []  # (serial, one-thread serial, machine scaling, bundle) [s, s, -, s]
        for k in range(args.rounds):
            # the loop and the bundle measured in turn, so that both see the machine in the
            # same state (a shared 2-vCPU machine drifts by 10-20 % within minutes)
            gc.collect()  # both sides measured after a full collection (below: the workers)
            c0 = time.process_time()
            t_serial, tables = serial(manifest, case)
            t_cpu = time.process_time() - c0
            # pyarrow decodes a large Parquet block on all cores by default, so the loop is
            # partly parallel already; a Dask worker decodes on one thread (distributed sets
            # OMP_NUM_THREADS=1). The same loop with one decoding thread isolates the scaling.
            pyarrow.set_cpu_count(1)
            t_one, _ = serial(manifest, case)
            pyarrow.set_cpu_count(threads)
            scaling = machine_scaling(manifest, case, w)
            with local_cluster(w) as cluster, distributed.Client(cluster) as client:
                run_bundle(warm, case, scheduler=client)  # workers import fretwear, kernels
                # the warm-up's imports leave the workers' collector due a full pass (0.1 s)
                # early in the next run: collected now, as this process is before its loop
                client.run(gc.collect)
                # timed alone: the memory sampler (a thread of this process) runs in a run
                # of its own below, not in the timed one
                with CpuTime(client) as cpu:
                    t_bundle, result = bundle_time(manifest, case, client)
                same = identical(result, tables)
                rounds.append((t_serial, t_one, scaling, t_bundle, cpu.workers, cpu.client,
                               t_cpu))
                print(f"round {k + 1}: serial loop {t_serial:.2f} s (one decoding thread "
                      f"{t_one:.2f} s), machine's own scaling {scaling:.2f}x, bundle "
                      f"{t_bundle:.2f} s: speed-up {t_serial / t_bundle:.2f}x; CPU: workers "
                      f"{cpu.workers:.2f} s, client and scheduler {cpu.client:.2f} s (the "
                      f"loop's own {t_cpu:.2f} s); tables bit-identical to the loop: {same}",
                      flush=True)
                if k == 0:
                    with PeakMemory(client) as idle:
                        time.sleep(0.2)
                    client.run(gc.collect)
                    with PeakMemory(client) as peaks:
                        bundle_time(manifest, case, client)
                    memory = (peaks.text(), idle.text())
                    t_tiny_serial, _ = serial(tiny, case)
                    t_out, _ = bundle_time(manifest, case, client, output=directory / "out")
                    t_tiny, _ = bundle_time(tiny, case, client)
                    saved = engine_module.TASKS_PER_WORKER
                    engine_module.TASKS_PER_WORKER = n + 1  # one contact per task
                    try:
                        t_single, _ = bundle_time(manifest, case, client)
                    finally:
                        engine_module.TASKS_PER_WORKER = saved
        t_serial, t_one, scaling, t_bundle, cpu_workers, cpu_client, t_cpu = np.median(
            np.array(rounds), axis=0).tolist()
        ratios = [r[0] / r[3] for r in rounds]
        print(f"serial loop over wear_table (median of {len(rounds)}): {t_serial:.2f} s, "
              f"{n / t_serial:.1f} contacts/s, {n * samples / t_serial:.3g} samples/s; with "
              f"one decoding thread {t_one:.2f} s")
        print(f"the machine's own scaling of the loop on {w} plain processes "
              f"(multiprocessing, no Dask), median: {scaling:.2f}x "
              f"({min(r[2] for r in rounds):.2f}-{max(r[2] for r in rounds):.2f}x)")
        print(f"bundle on {w} workers (median): {t_bundle:.2f} s, {n / t_bundle:.1f} "
              f"contacts/s, {n * samples / t_bundle:.3g} samples/s; speed-up "
              f"{t_serial / t_bundle:.2f}x over the loop (goal >= 1.7x; rounds "
              f"{min(ratios):.2f}-{max(ratios):.2f}x), {t_one / t_bundle:.2f}x over the "
              f"one-thread loop")
        floor = (cpu_workers + cpu_client) / w
        print(f"CPU of the bundle (median): workers {cpu_workers:.2f} s in all, against "
              f"{t_cpu:.2f} s for the same contacts in the loop (x{cpu_workers / t_cpu:.2f}: "
              f"the cores slow each other down, as in the machine's own scaling), client and "
              f"scheduler {cpu_client:.2f} s; on {w} cores perfectly shared the bundle takes at "
              f"least {floor:.2f} s, a speed-up of at most {t_serial / floor:.2f}x")
        print(f"  with the output directory (parts, table, dataset, summary): {t_out:.2f} s, "
              f"{n / t_out:.1f} contacts/s")
        print(f"  one contact per task instead of {len(engine_module.task_sizes(n, w))} "
              f"tasks: {t_single:.2f} s (grouping gains {t_single / rounds[0][3]:.2f}x)")
        over = (w * t_bundle - t_serial) / n * 1e3
        over_tiny = (w * t_tiny - t_tiny_serial) / n * 1e3
        print(f"per-contact overhead (workers x T_bundle - T_serial)/N: {over:.1f} ms on "
              f"this bundle, {over_tiny:.1f} ms on 100-sample contacts (goal < 20 ms); "
              f"tiny bundle {t_tiny:.2f} s vs serial {t_tiny_serial:.2f} s")
        print(f"peak memory per worker during the {n}-contact bundle: {memory[0]} "
              f"(idle warmed-up workers: {memory[1]})")
        if args.long:  # fresh workers for each: ru_maxrss is the peak of a process's life
            long_manifest = make_bundle(directory, 1, int(args.long), "long")
            for label, chunk in (("chunks of", int(args.chunk)),
                                 ("one task of", int(args.long) + 1)):
                with local_cluster(args.workers) as cluster, \
                        distributed.Client(cluster) as client:
                    run_bundle(warm, case, scheduler=client)
                    with PeakMemory(client) as peaks:
                        t_long, r = bundle_time(long_manifest, case, client, chunk_size=chunk)
                    print(f"one contact of {args.long:.0e} samples in {label} {chunk:.0e} "
                          f"samples: {t_long:.2f} s, peak memory per worker {peaks.text()} "
                          f"(errors: {len(r.errors)})")
    finally:
        if args.keep is None:
            shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
