"""The per-file cost of the HDF5/NetCDF pre-check (``fretwear.io.guard.probe``), before and after
issue 28, in one run.

``--files`` (default 200) small HDF5 histories (``--samples`` samples each, the ``smooth``
signal of ``benchmarks/_signals.py``, written by ``fretwear.io.write_history``) are:

* **a child per file** (before): the checking script ``guard._CHILD`` run by a new
  ``sys.executable`` for each file, given the file on its input, as ``probe`` did until issue 28
  (``subprocess.run`` per file: Python's start, h5py's import, the walk), plus
  ``guess_format``, which started another for a file named ``.h5`` (its answer was remembered,
  so the sum is one child a file);
* **one checker** (after): ``guard.probe`` on each file, its answers forgotten first: the
  process's long-lived checking child (started once, included) walks each file;
* **no check** (the floor): ``fretwear.io.read_history`` with ``probe`` replaced by a no-op:
  h5py opening and reading the file in this process;
* **read with the check**: ``read_history`` as the user calls it (after).

Then the same files run as a bundle (``run_bundle`` on ``--workers`` workers, a LocalCluster
started first, warmed up on 4 contacts of other files) against the same histories in Parquet:
the cost per contact of HDF5 over Parquet, where the checker is the only difference a contact
pays besides h5py against pyarrow.

Prints the seconds per file of each, the ratio before/after, and the machine's load average.

Usage::

    .venv/bin/python benchmarks/bench_probe.py
    .venv/bin/python benchmarks/bench_probe.py --files 100 --no-bundle
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _signals import smooth  # noqa: E402
from bench_bundle import CASE, local_cluster  # noqa: E402

import fretwear.io.binary as binary  # noqa: E402
import fretwear.io.guard as guard  # noqa: E402
from fretwear.history import ContactHistory  # noqa: E402
from fretwear.io import read_history, write_history  # noqa: E402


def make_files(directory: Path, count: int, samples: int, suffix: str) -> Path:
    """``count`` histories ``c00000<suffix>``... and their manifest ``manifest<suffix>.csv``."""
    rows = []
    for k in range(count):
        arrays = smooth(k * samples, samples)
        arrays["time"] = arrays["time"] - arrays["time"][0]
        path = directory / f"c{k:05d}{suffix}"
        write_history(ContactHistory(**arrays), path)
        rows.append({"contact": f"c{k:05d}", "history": path.name,
                     "tube_row": k // 25 + 1, "tube_column": k % 25 + 1})
    manifest = directory / f"manifest{suffix}.csv"
    pd.DataFrame(rows).to_csv(manifest, index=False)
    return manifest


def child_per_file(paths: list[Path]) -> float:
    """Seconds of the check as it was: a new interpreter per file."""
    t0 = time.perf_counter()
    for p in paths:
        done = subprocess.run([sys.executable, "-c", guard._CHILD], capture_output=True,
                              text=True, input=json.dumps([str(p), "hdf5"]) + "\n",
                              timeout=guard.PROBE_TIMEOUT)
        if done.returncode != 0 or "error" in done.stdout:
            raise SystemExit(f"{p}: {done.stdout} {done.stderr}")
    return time.perf_counter() - t0


def one_checker(paths: list[Path]) -> float:
    """Seconds of ``probe`` on each file (a fresh checker, its start included)."""
    guard._drop_checker()
    guard._PROBED.clear()
    t0 = time.perf_counter()
    for p in paths:
        guard.probe(p, "hdf5")
    return time.perf_counter() - t0


def reads(paths: list[Path], check: bool) -> float:
    """Seconds of ``read_history`` on each file, with or without the check."""
    guard._PROBED.clear()
    real = binary.probe
    if not check:
        binary.probe = lambda path, format: {}
    try:
        t0 = time.perf_counter()
        for p in paths:
            read_history(p)
        return time.perf_counter() - t0
    finally:
        binary.probe = real


def bundle_costs(directory: Path, manifests: dict[str, Path], workers: int) -> dict[str, float]:
    """Seconds of run_bundle per manifest on one LocalCluster (after a warm-up)."""
    import distributed

    from fretwear.bundle import run_bundle

    case = directory / "base.toml"
    case.write_text(CASE)
    warm = directory / "warm"
    warm.mkdir()
    warm_manifests = {s: make_files(warm, 4, 100, s) for s in manifests}
    out = {}
    with local_cluster(workers) as cluster, distributed.Client(cluster) as client:
        for suffix in manifests:
            run_bundle(warm_manifests[suffix], case, scheduler=client)
        for suffix, manifest in manifests.items():
            t0 = time.perf_counter()
            result = run_bundle(manifest, case, scheduler=client)
            out[suffix] = time.perf_counter() - t0
            if result.stats["failed"]:
                raise SystemExit(result.errors.head())
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--files", type=int, default=200)
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--no-bundle", action="store_true", help="the probe alone")
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    directory = Path(tempfile.mkdtemp(prefix="bench_probe_"))
    try:
        manifest = make_files(directory, args.files, args.samples, ".h5")
        paths = [directory / f"c{k:05d}.h5" for k in range(args.files)]
        print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
        reads(paths[:3], check=True)  # imports, numba
        before = child_per_file(paths)
        after = one_checker(paths)
        floor = reads(paths, check=False)
        checked = reads(paths, check=True)
        n = args.files
        print(f"{n} HDF5 files of {args.samples} samples: the check, a child per file (before) "
              f"{1e3 * before / n:.1f} ms a file; one checker (after, its start included) "
              f"{1e3 * after / n:.2f} ms a file: {before / after:.0f}x less")
        print(f"read_history: no check {1e3 * floor / n:.2f} ms a file, with the check "
              f"{1e3 * checked / n:.2f} ms a file ({checked / floor:.2f}x the unchecked read)")
        if not args.no_bundle:
            parquet = make_files(directory, args.files, args.samples, ".parquet")
            seconds = bundle_costs(directory, {".h5": manifest, ".parquet": parquet},
                                   args.workers)
            print(f"bundle of {n} contacts on {args.workers} workers: HDF5 "
                  f"{seconds['.h5']:.2f} s ({1e3 * seconds['.h5'] / n:.2f} ms a contact), "
                  f"Parquet {seconds['.parquet']:.2f} s ({1e3 * seconds['.parquet'] / n:.2f} ms "
                  f"a contact); HDF5 / Parquet {seconds['.h5'] / seconds['.parquet']:.2f}; the "
                  f"check as it was would add about {before / args.workers:.0f} s")
        print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    finally:
        guard._drop_checker()
        shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
