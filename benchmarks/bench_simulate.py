"""Tube-seconds simulated per second by ``fretwear simulate`` on 2 Dask workers, against the
single-tube integrator in this process.

Model: the example bundle description (examples/bundle/bundle_geometry.toml: 12 tubes, 8 modes,
2 shocks each, SPEC_LONG_COR_1 turbulence) with ``--duration`` seconds simulated per tube. The
peer is the very same per-tube work (modes, projection, synthesis, shock dynamics, stability,
Parquet histories: :func:`fretwear.flow.bundle.simulate_tube`) run one tube after the other in
this process, after one warm-up tube (numba compilation). The bundle run joins a local 2-worker
cluster started beforehand (its start time is printed apart) and recomputes every tube
(``force=True``). Printed: tube-seconds per second of both and their ratio (2 is the ideal on 2
idle cores; the machine's other load and the per-task overhead lower it), with the machine's
load average (as ``uptime``) before and after: the two figures are comparable only under the
same load. Then where the time goes: a tube's time in a worker against in this process, the
workers' busy fraction, and the CPU time per tube of both (CPU time does not depend on the other
processes' load, so 2 x its ratio estimates the speed-up on 2 idle cores; measured at load 8-12
on a 2-core machine, where the wall-clock ratio says only how many cores the run obtained).

Usage::

    .venv/bin/python benchmarks/bench_simulate.py
    .venv/bin/python benchmarks/bench_simulate.py --duration 2 --tubes 6
    .venv/bin/python benchmarks/bench_simulate.py --duration 20 --tubes 48   # the example's
                                                                              # tubes 4 times
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import tempfile
import time
from pathlib import Path

from fretwear.bundle.cluster import LOCAL_CLUSTER_CONFIG
from fretwear.flow.bundle import run_simulate, simulate_tube
from fretwear.flow.description import read_description

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "bundle" / "bundle_geometry.toml"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=4.0, help="seconds per tube (default 4)")
    ap.add_argument("--tubes", type=int, default=12, help="tubes (default 12, the example's)")
    args = ap.parse_args()
    base = read_description(EXAMPLE)
    # more tubes than the example's 12: its tubes again, renamed (the same work per tube)
    specs = [dataclasses.replace(base[k % len(base)], duration=args.duration,
                                 tube=base[k % len(base)].tube + (f"_{k // len(base)}"
                                                                  if k >= len(base) else ""))
             for k in range(args.tubes)]
    work = len(specs) * args.duration
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        simulate_tube(specs[0], Path(tmp) / "warmup")
        t, cpu = time.perf_counter(), time.process_time()
        serial_tasks = [simulate_tube(s, Path(tmp) / "serial" / "tubes" / s.tube)["elapsed_s"]
                        for s in specs]
        single = work / (time.perf_counter() - t)
        serial_cpu = time.process_time() - cpu

        import dask
        import distributed

        t = time.perf_counter()
        with dask.config.set(LOCAL_CLUSTER_CONFIG):
            cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                               processes=True, dashboard_address=":0")
        client = distributed.Client(cluster)
        start = time.perf_counter() - t
        try:
            client.run(simulate_tube, specs[0], str(Path(tmp) / "warm_worker"))  # numba caches
            before = client.run(time.process_time)
            t = time.perf_counter()
            result = run_simulate(specs, Path(tmp) / "bundle", scheduler=client, force=True)
            wall = time.perf_counter() - t
            after = client.run(time.process_time)
            worker_cpu = sum(after[w] - before[w] for w in after)
            bundle = work / wall
            worker_tasks = [r["elapsed_s"] for r in result.records]
        finally:
            client.close()
            cluster.close()
    load_after = os.getloadavg()
    print(f"{len(specs)} tubes x {args.duration:g} s simulated on {os.cpu_count()} CPU(s)")
    print("load average (1, 5, 15 min) before: " + ", ".join(f"{v:.2f}" for v in load_before)
          + "; after: " + ", ".join(f"{v:.2f}" for v in load_after))
    print(f"single-tube integrator, this process: {single:8.2f} tube-s/s")
    print(f"fretwear simulate, 2 workers:         {bundle:8.2f} tube-s/s "
          f"(cluster start {start:.1f} s, not counted)")
    print(f"ratio 2 workers / single: {bundle / single:.2f} (ideal 2.00)")
    # where the time goes (robust to the load's level, not to its changes): a tube's own time
    # inside a worker against in this process (> 1: the workers' cores are shared, by each
    # other's memory traffic or by other processes), and the workers' busy fraction of the wall
    # time (< 1: per-task overhead, scheduling, the parent's writing of the tables)
    n = len(specs)
    print(f"per tube: {sum(serial_tasks) / n * 1e3:.1f} ms in this process, "
          f"{sum(worker_tasks) / n * 1e3:.1f} ms in a worker "
          f"(x{sum(worker_tasks) / sum(serial_tasks):.2f}); workers busy "
          f"{sum(worker_tasks) / (2 * wall):.0%} of the wall time; "
          f"other time per tube {(2 * wall - sum(worker_tasks)) / n * 1e3:.1f} ms")
    # CPU time does not depend on the other processes' load: the ratio on 2 idle cores would
    # be 2 x (CPU per tube in this process) / (CPU per tube in the workers, Dask included)
    print(f"CPU per tube: {serial_cpu / n * 1e3:.1f} ms in this process, "
          f"{worker_cpu / n * 1e3:.1f} ms in the workers (Dask's own work included); the "
          f"workers got {worker_cpu / wall:.2f} of the 2 cores (the rest: the machine's load); "
          f"ratio on 2 idle cores, from CPU time: {2 * serial_cpu / worker_cpu:.2f}")


if __name__ == "__main__":
    main()
