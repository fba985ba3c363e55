"""The client's CPU per contact while a bundle's results arrive (issue 28), two of its steps
against what they replaced, in the same run, as process CPU (every thread):

1. a part's JSON: ``OutputDirectory.record_part`` (what contacts share written once,
   ``bundle/part_json.py``) against the encoding before (``json.dumps`` of every record whole,
   then the records compacted), for parts of 250 records as one task's pickle delivers them
   (a case's geometry, coefficients and sector edges one object, each contact its power);
2. the dataset's row groups: ``GridZarr`` appending whole chunks itself
   (``bundle/zarr_chunks.py``) against zarr's ``Array.append`` (the chunk
   writer turned off), for groups of about 2 750 contacts x 6 instants x 8 sectors of distinct
   random reals, their sizes not a chunk's (as a run's parts make them); the store's files
   compared byte for byte.

Prints each pair's CPU, their ratio and the load average.

Usage::

    .venv/bin/python benchmarks/bench_bundle_client_parts.py
    .venv/bin/python benchmarks/bench_bundle_client_parts.py --parts 100 --groups 12
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

import fretwear.bundle.result_dataset as result_dataset
from fretwear.bundle.result_dataset import GridZarr
from fretwear.bundle.store import OutputDirectory
from fretwear.io.atomic import atomic_write

SKIP = ("table", "state", "rows_file", "part")


def task_records(first: int, n: int, rng) -> list[dict]:
    """``n`` records as one task's pickle delivers them."""
    case = {"contact_type": "TUBE_BAV",
            "dimensions": {"mobile_radius": 0.009525, "obstacle_width": 0.0127,
                           "tilt_angle": 0.0, "impact_angle": 0.0},
            "law": "ARCHARD", "coefficients_mobile": {"coefficient": 1e-17},
            "coefficients_obstacle": None, "materials": None,
            "coefficient_sources": {"mobile.coefficient": "user"},
            "sector_edges": [-180.0 + 45.0 * k for k in range(9)],
            "sector_coefficients": None, "time_scale": 31536000.0, "origin": 0.0,
            "tube_replacement": None, "wall_thickness": None, "depth_limit": 0.4}
    out = []
    for i in range(first, first + n):
        total = float(rng.random())
        power = {"total": total, "blocks": [total], "spread": 0.0, "t_start": 0.0,
                 "t_end": 0.00999, "duration": 0.00999,
                 "sectors": [float(v) for v in rng.random(8)]}
        out.append({"contact": f"c{i:06d}", "key": f"{i:032x}", "status": "done",
                    "table": None, "warnings": [], "error": None, "samples": 1000,
                    "seconds": float(rng.random()), "attrs": {**case, "power": power,
                                                               "time_unit": "year"},
                    "state": None, "rows_file": "x.parquet", "passes": 1})
    return pickle.loads(pickle.dumps(out))


def record_part_before(store: OutputDirectory, records: list[dict], stem: str) -> None:
    """The part's JSON as written before: every record whole, then compacted."""
    meta = {"part": stem, "rows_file": f"{stem}.parquet",
            "contacts": [{k: v for k, v in r.items() if k not in SKIP} for r in records]}
    text = json.dumps(meta, default=str, check_circular=False)
    with atomic_write(store.parts / f"{stem}.json", encoding="utf-8", sweep=False) as handle:
        handle.write(text)
    seen: dict = {}
    for r in records:
        r["part"], r["rows_file"] = stem, f"{stem}.parquet"
        r["attrs"] = store.compact(r.get("attrs"), seen)


def bench_json(parts: int, root: Path) -> tuple[float, float]:
    rng = np.random.default_rng(0)
    batches = [task_records(250 * k, 250, rng) for k in range(parts)]
    copies = [pickle.loads(pickle.dumps(b)) for b in batches]
    now = OutputDirectory(root / "now")
    t0 = time.process_time()
    for k, b in enumerate(batches):
        now.record_part(b, f"part-{k:06d}", f"part-{k:06d}.parquet")
    t1 = time.process_time()
    before = OutputDirectory(root / "before")
    for k, b in enumerate(copies):
        record_part_before(before, b, f"part-{k:06d}")
    t2 = time.process_time()
    assert [r["attrs"] for b in batches for r in b] == [r["attrs"] for b in copies for r in b]
    n = 250 * parts
    return (t1 - t0) / n, (t2 - t1) / n


def group(first: int, count: int, rng, instants: int = 6, sectors: int = 8) -> pd.DataFrame:
    per = instants * sectors
    rows = count * per
    frame = {"contact": np.repeat([f"c{first + j:06d}" for j in range(count)], per),
             "instant": np.tile(np.repeat(np.arange(1.0, instants + 1), sectors), count),
             "sector": np.tile(np.arange(1, sectors + 1), count * instants)}
    for name in ("power", "volume_mobile", "depth_mobile", "sector_power",
                 "volume_mobile_sector", "depth_mobile_sector", "volume_mobile_cumulated"):
        frame[name] = rng.random(rows)
    frame["volume_obstacle_sector"] = np.full(rows, np.nan)
    return pd.DataFrame(frame)


def bench_zarr(groups: int, root: Path) -> tuple[float, float, bool]:
    rng = np.random.default_rng(1)
    sizes = [2750] + [int(s) for s in rng.integers(2700, 2800, groups - 1)]
    frames, first = [], 0
    for n in sizes:
        frames.append(group(first, n, rng))
        first += n
    ids = [f"c{j:06d}" for j in range(first)]
    contacts = pd.DataFrame({"contact": ids, "status": "done"})
    import zarr

    options = {"zarr_format": 2} if int(zarr.__version__.split(".")[0]) >= 3 else {}

    def write(name: str) -> float:
        store = GridZarr(root / f"{name}.parts", np.array(ids).dtype, options)
        t0 = time.process_time()
        for frame in frames:
            store.add(frame)
        assert store.finish(contacts, root / f"{name}.zarr")
        return (time.process_time() - t0) / first

    warm = GridZarr(root / "warm.parts", np.array(ids).dtype, options)  # imports, first use
    for frame in frames[:2]:
        warm.add(frame)
    warm.abort()
    now = write("now")
    real = result_dataset.appender
    result_dataset.appender = lambda array, folder: None  # every array appended by zarr
    try:
        before = write("before")
    finally:
        result_dataset.appender = real

    def files(path: Path) -> dict:
        return {str(p.relative_to(path)): p.read_bytes() for p in sorted(path.rglob("*"))
                if p.is_file()}

    return now, before, files(root / "now.zarr") == files(root / "before.zarr")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--parts", type=int, default=60, help="parts of 250 records")
    parser.add_argument("--groups", type=int, default=8, help="row groups of ~2 750 contacts")
    args = parser.parse_args()
    root = Path(tempfile.mkdtemp(prefix="bench_client_parts_"))
    try:
        now, before = bench_json(args.parts, root)
        print(f"part JSON ({args.parts} parts of 250): {1e6 * now:.2f} us/contact now, "
              f"{1e6 * before:.2f} before: ratio {before / now:.2f}")
        now, before, same = bench_zarr(args.groups, root)
        print(f"dataset row groups ({args.groups} of ~2 750 contacts): {1e6 * now:.2f} "
              f"us/contact now, {1e6 * before:.2f} before: ratio {before / now:.2f}; "
              f"the same files: {same}")
    finally:
        shutil.rmtree(root, ignore_errors=True)
    print(f"load average {os.getloadavg()[0]:.2f} (1 min)")


if __name__ == "__main__":
    main()
