"""The hierarchical calibration and forecast of a bundle's contacts (issue 26, point 2).

``--contacts`` (default 2,150, the issue's bundle) Archard TUBE_BAV contacts, powers drawn from
a seeded lognormal, ``--inspected`` of them (default 300) inspected at 10 years from a true
bundle factor 1.7 with a contact scatter σ_ln 0.35: sized through an additive sizing error
(σ 0.05 mm) where a logistic POD (a50 0.15 mm, a90 0.3 mm) detects them, NDD otherwise. Prints
the time of :func:`fretwear.assessment.calibrate_bundle`, of its forecast at 30 years and of its
node decomposition, each with the ratio to a floor measured in the same run: one vectorised
``DepthModel.depth`` call per contact on the posterior's grid (what any grid method must at least
evaluate). The issue's single-factor ``calibrate --forecast`` took 183 s for 2,150 contacts.

Usage: python benchmarks/bench_calibrate_bundle.py [--contacts 2150] [--inspected 300]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
import pandas as pd

from fretwear.assessment import LogisticPOD, SizingModel, Technique, calibrate_bundle
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import Wall
from fretwear.table.depth import DepthModel

YEAR = 31536000.0


def bundle(n: int, inspected: int, seed: int = 26):
    rng = np.random.default_rng(seed)
    g = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)
    models = {f"C{i}": DepthModel(law=get_law("ARCHARD"), geometry=g, powers=(float(p),),
                                  coefficients_mobile=({"coefficient": 1e-14},),
                                  coefficients_obstacle=(None,), time_scale=YEAR,
                                  name=f"C{i}", wall=Wall(1.09e-3))
              for i, p in enumerate(rng.lognormal(np.log(5e-3), 0.8, n))}
    pod = LogisticPOD.from_depths(1.5e-4, 3e-4)
    sizing = SizingModel(0.0, 1.0, 5e-5)
    rows = []
    for c in list(models)[:inspected]:
        d = float(models[c].depth(10 * YEAR, factor=1.7 * np.exp(0.35 * rng.standard_normal())))
        sized = rng.random() < pod(d)
        rows.append((c, 10.0, f"{max(d + 5e-5 * rng.standard_normal(), 1e-6) * 1e3:.4f}"
                     if sized else "NDD"))
    frame = pd.DataFrame(rows, columns=["contact", "instant", "depth_mm"])
    return models, frame, Technique(sizing, pod)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=2150)
    parser.add_argument("--inspected", type=int, default=300)
    args = parser.parse_args()
    models, frame, tech = bundle(args.contacts, args.inspected)
    t0 = time.perf_counter()
    cal = calibrate_bundle(models, frame, techniques=tech)
    t1 = time.perf_counter()
    fc = cal.forecast(30.0)
    t2 = time.perf_counter()
    cal.node_exceedance(30.0)
    t3 = time.perf_counter()
    grid = np.exp(cal.levels.grid)
    for m in models.values():
        m.depth(np.full(grid.size, 10 * YEAR), factor=grid, warn=False)
    floor = time.perf_counter() - t3
    median, (low, high) = cal.bundle_factor()
    print(f"{args.contacts} contacts, {args.inspected} inspected, grid {grid.size} points; "
          f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(f"floor (one depth call per contact on the grid): {floor:.2f} s")
    print(f"calibrate_bundle: {t1 - t0:.2f} s ({(t1 - t0) / floor:.1f} x floor)")
    print(f"forecast at 30 y: {t2 - t1:.2f} s ({(t2 - t1) / floor:.1f} x floor)")
    print(f"node decomposition: {t3 - t2:.2f} s ({(t3 - t2) / floor:.1f} x floor)")
    print(f"bundle factor: median {median:.3f}, 90 % [{low:.3f}, {high:.3f}] (true 1.7); "
          f"{int((fc['exceedance'] > 0.5).sum())} contacts more likely than not past the limit")


if __name__ == "__main__":
    main()
