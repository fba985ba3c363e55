"""Benchmark of the outage assessment (issue 26): ``assess`` on a synthetic steam generator of
10⁵ contacts (10 supports on each of 10⁴ tubes), 20 % of the tubes inspected (2 % of the
contacts sized, the rest of the inspected tubes NDD).

Prints the wall time of :func:`fretwear.assessment.outage.assess` (goal < 60 s on 2 cores),
the process's peak resident memory (goal < 4 GB) and the machine's load (``uptime``), and the
time per contact against a floor measured in the same run: one ``DepthModel.time_to`` call per
contact (the root every contact needs), so the ratio says what the assessment costs beyond it.

Run: ``python benchmarks/bench_assess.py [--contacts 100000]``.
"""

from __future__ import annotations

import argparse
import math
import resource
import subprocess
import time
from types import SimpleNamespace

import numpy as np
import pandas as pd

from fretwear.assessment import LogisticPOD, SizingModel
from fretwear.assessment.contacts import bundle_models
from fretwear.assessment.outage import assess

YEAR = 31536000.0


def synthetic_bundle(contacts: int, seed: int = 2026):
    """``contacts`` TUBE_BAV contacts (Archard, 19.05 mm tube, 1.09 mm wall, 12.7 mm bar) on
    ``contacts // 10`` tubes, lognormal wear powers (median 1 mW, σ_ln 0.6), 30 years run."""
    rng = np.random.default_rng(seed)
    tubes = max(contacts // 10, 1)
    side = int(math.ceil(math.sqrt(tubes)))
    k = np.arange(contacts)
    tube = k % tubes
    power = rng.lognormal(math.log(1e-3), 0.6, contacts)
    dims = {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3, "tilt_angle": 0.0,
            "impact_angle": 0.0}
    frame = pd.DataFrame({
        "contact": [f"c{i}" for i in k], "tube_row": tube // side + 1,
        "tube_column": tube % side + 1, "support": [f"AVB{i // tubes + 1}" for i in k],
        "status": "done", "power": power, "time_unit": "year", "origin": 0.0,
        "wall_thickness": 1.09e-3, "depth_limit": 0.4, "contact_type": "TUBE_BAV",
        "dimensions": [dims] * contacts, "law": "ARCHARD",
        "coefficients_mobile": [{"coefficient": 4.1e-16}] * contacts,
        "coefficients_obstacle": None, "time_scale": YEAR})
    table = pd.DataFrame({"contact": frame["contact"], "instant": 30.0, "depth_mobile": 0.0})
    return SimpleNamespace(contacts=frame, table=table, output="(synthetic)"), rng


def inspections(bundle, rng, share: float = 0.2, sized: float = 0.02,
                factor: float = 1.5) -> pd.DataFrame:
    """The tubes of ``share`` of the bundle inspected at 30 years: the deepest ``sized`` share
    of all contacts sized (true depth from the model at a true factor ``factor`` with a
    contact scatter of σ_ln 0.3, plus a sizing error of 0.05 mm), the other contacts of the
    inspected tubes NDD."""
    c = bundle.contacts
    tube = c["tube_row"].astype(str) + "-" + c["tube_column"].astype(str)
    chosen = rng.choice(tube.unique(), int(share * tube.nunique()), replace=False)
    rows = c[tube.isin(chosen)].reset_index(drop=True)
    models = bundle_models(SimpleNamespace(contacts=rows, table=bundle.table))["model"]
    true = np.array([float(m.depth(30 * YEAR, factor=factor * rng.lognormal(0.0, 0.3)))
                     for m in models])
    n_sized = min(int(sized * len(c)), len(rows))
    deepest = np.argsort(-true)[:n_sized]
    depth = np.full(len(rows), np.nan)
    depth[deepest] = np.maximum(true[deepest] + rng.normal(0.0, 5e-5, n_sized), 1e-5)
    return pd.DataFrame({"contact": rows["contact"].to_numpy(), "instant": 30.0,
                         "depth": depth,
                         "result": np.where(np.isnan(depth), "NDD", "")})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=100_000)
    args = parser.parse_args()
    bundle, rng = synthetic_bundle(args.contacts)
    insp = inspections(bundle, rng)
    # the floor: one time_to per contact (the root each contact needs), same models
    models = bundle_models(bundle)["model"]
    t0 = time.perf_counter()
    for m in models:
        m.time_to(m.limit_depth)
    floor = time.perf_counter() - t0
    t0, cpu0 = time.perf_counter(), time.process_time()
    result = assess(bundle, insp, interval=2.0, sizing=SizingModel(0.0, 1.0, 5e-5),
                    pod=LogisticPOD.from_depths(1.5e-4, 3e-4), contact_sigma_ln=0.3,
                    power_sigma_ln=0.2, target=0.05)
    wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024 ** 2  # [GB] (Linux: kB)
    b = result.bundle
    load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    print(f"contacts {args.contacts}, tubes {b['tubes']}, inspected contacts {len(insp)} "
          f"({int(insp['depth'].notna().sum())} sized)")
    print(f"assess: {wall:.1f} s wall, {cpu:.1f} s CPU (goal < 60 s), peak memory "
          f"{peak:.2f} GB (goal < 4 GB)")
    print(f"floor (one DepthModel.time_to per contact): {floor:.1f} s; assess / floor = "
          f"{wall / floor:.1f}")
    print(f"calibration: {result.inputs['calibration'].get('method')}, bundle factor "
          f"{result.inputs['calibration'].get('factor_median', float('nan')):.3g}")
    print(f"P(any) {b['p_any']:.3g}, longest interval {b['longest_interval']:.3g} year after "
          f"plugging ({b['longest_interval_before_plugging']:.3g} before), "
          f"plugging {len(b['plugging'])} tube(s), sample {len(b['inspection_sample'])} tube(s)")
    print(f"uptime: {load}")


if __name__ == "__main__":
    main()
