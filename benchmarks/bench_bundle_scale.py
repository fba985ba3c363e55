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

Usage::

    .venv/bin/python benchmarks/bench_bundle_scale.py
    .venv/bin/python benchmarks/bench_bundle_scale.py --small 1000 --large 10000
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
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


def measure(manifest: Path, case: Path, client, output: Path) -> tuple[float, float, float]:
    """Seconds of (the run, its part after the last result, the restart)."""
    marks = {}
    assemble = engine_module._assemble

    def timed(*args, **kwargs):
        marks["assemble"] = time.perf_counter()
        return assemble(*args, **kwargs)

    engine_module._assemble = timed
    try:
        t0 = time.perf_counter()
        result = run_bundle(manifest, case, scheduler=client, output=output)
        end = time.perf_counter()
    finally:
        engine_module._assemble = assemble
    if result.stats["done"] != result.stats["contacts"]:
        raise SystemExit(f"{result.stats['failed']} contacts failed: {result.errors.head()}")
    t1 = time.perf_counter()
    again = run_bundle(manifest, case, scheduler=client, output=output)
    restart = time.perf_counter() - t1
    if again.stats["skipped"] != again.stats["contacts"]:
        raise SystemExit("the restart recomputed contacts")
    return end - t0, end - marks["assemble"], restart


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", type=int, default=2_000)
    parser.add_argument("--large", type=int, default=20_000)
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument("--distinct", type=int, default=50, help="distinct history files")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    import distributed

    directory = Path(tempfile.mkdtemp(prefix="bench_bundle_scale_"))
    try:
        case = directory / "base.toml"
        case.write_text(CASE)
        manifests = {n: make_bundle(directory, n, args.samples, args.distinct)
                     for n in (args.small, args.large)}
        warm = make_bundle(directory, 4, args.samples, args.distinct)
        costs = {}
        with local_cluster(args.workers) as cluster, distributed.Client(cluster) as client:
            run_bundle(warm, case, scheduler=client)
            for n, manifest in manifests.items():
                run, tail, restart = measure(manifest, case, client, directory / f"out{n}")
                costs[n] = (run / n, tail / n, restart / n)
                print(f"{n} contacts of {args.samples} samples on {args.workers} workers: run "
                      f"{run:.2f} s ({n / run:.0f} contacts/s), of which {tail:.2f} s after the "
                      f"last result (table, dataset, files); restart (all skipped) "
                      f"{restart:.2f} s", flush=True)
        small, large = costs[args.small], costs[args.large]
        names = ("run", "after the last result", "restart")
        print(f"cost per contact at {args.large} / at {args.small} contacts (1: proportional, "
              f"{args.large / args.small:.0f}: quadratic): " + ", ".join(
                  f"{name} {b / a:.2f}" for name, a, b in zip(names, small, large, strict=True)))
    finally:
        shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
