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
same load.

Usage::

    .venv/bin/python benchmarks/bench_simulate.py
    .venv/bin/python benchmarks/bench_simulate.py --duration 2 --tubes 6
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
    specs = [dataclasses.replace(s, duration=args.duration)
             for s in read_description(EXAMPLE)][:args.tubes]
    work = len(specs) * args.duration
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        simulate_tube(specs[0], Path(tmp) / "warmup")
        t = time.perf_counter()
        for s in specs:
            simulate_tube(s, Path(tmp) / "serial" / "tubes" / s.tube)
        single = work / (time.perf_counter() - t)

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
            t = time.perf_counter()
            run_simulate(specs, Path(tmp) / "bundle", scheduler=client, force=True)
            bundle = work / (time.perf_counter() - t)
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


if __name__ == "__main__":
    main()
