"""A bundle worker's CPU per small Parquet contact, against a pyarrow read of the same files.

``--contacts`` contacts (default 1 000) of ``--samples`` samples (default 1 000) each, Parquet,
the base case of ``bench_bundle.py`` (TUBE_BAV, 8 sectors, 6 instants; the files as
``bench_bundle_scale.py`` makes them: ``--distinct`` files hard-linked under one name a
contact), are computed in one process by :func:`fretwear.bundle.tasks.run_contacts` (what a
Dask worker runs: the file read and checked, its wear power, the wear table and the record),
in groups of 100 contacts. Printed, in milliseconds of **CPU** (``time.process_time``: a shared
machine's other load moves it less than wall time) a contact, the best of ``--repeat`` passes
over every contact:

* ``run_contacts``: the whole worker's cost;
* ``wear_power``: the part from the file to the :class:`~fretwear.power.PowerResult` the
  table takes (``wear_power(path, ...)`` as the worker calls it, with the geometry check of
  the first block);
* the floor ``read``: ``pyarrow.parquet.ParquetFile(path).read(columns=...)`` of the columns
  the contact reads (the six channels), in the same process: no contact costs less;
* ``read 1t``: the same read on one thread (``use_threads=False``), as the worker reads a
  small file (pyarrow's threads cost a 1 000-sample file more than they save: the floor
  above is about twice this one);

and the ratios ``run_contacts / read``, ``wear_power / read`` and ``wear_power / read 1t``.

Before and after in one run: ``--base DIR`` runs the timings in child processes taking turns
(``--rounds`` times each), one importing fretwear from ``DIR/src`` (a clone of the base commit),
the other this checkout's; the best of each side is printed with the ratio after / before,
then the medians of the rounds.
The load average is printed before and after.

Usage::

    .venv/bin/python benchmarks/bench_contact.py
    .venv/bin/python benchmarks/bench_contact.py --base /tmp/base --rounds 4
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GROUP = 100  # contacts a run_contacts call (a task of the bundle)


def _timings(src: str, directory: Path, repeat: int) -> dict:
    """CPU seconds a contact of the three timings, with the fretwear of ``src``."""
    sys.path.insert(0, src)
    import pyarrow.parquet as pq

    import fretwear
    from fretwear.bundle.cases import build_task
    from fretwear.bundle.engine import _base_case
    from fretwear.bundle.manifest import read_manifest
    from fretwear.bundle.tasks import _geometry_check, run_contacts
    from fretwear.power import wear_power

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_bundle import CASE

    warnings.simplefilter("ignore")
    case = directory / "base.toml"
    case.write_text(CASE)
    manifest = read_manifest(next(directory.glob("bundle*/manifest.csv")))
    base = _base_case(case)
    base["_directory"] = str(manifest.directory)
    cache: dict = {}
    tasks = [build_task(base, r, manifest.source, chunk_size=1_000_000, cache=cache)
             for r in manifest.rows]
    groups = [tasks[i:i + GROUP] for i in range(0, len(tasks), GROUP)]
    paths = [t.history.path for t in tasks]
    columns = pq.ParquetFile(paths[0]).schema_arrow.names

    def power(task):
        wear_power(task.history.path, **task.wear_case().power_options, chunk_size=1_000_000,
                   name=task.contact, first_block=_geometry_check(task),
                   **dict(task.read_options))

    def best(run) -> float:
        run()  # warm: compiled kernels, imports, the page cache
        times = []
        for _ in range(repeat):
            t0 = time.process_time()
            run()
            times.append(time.process_time() - t0)
        return min(times) / len(tasks)

    failed = [r for g in groups[:1] for r in run_contacts(g) if r["status"] != "done"]
    assert not failed, failed[0]
    return {"module": fretwear.__file__, "contacts": len(tasks), "columns": columns,
            "run_contacts": best(lambda: [run_contacts(g) for g in groups]),
            "wear_power": best(lambda: [power(t) for t in tasks]),
            "read": best(lambda: [pq.ParquetFile(p).read(columns=columns) for p in paths]),
            "read1": best(lambda: [pq.ParquetFile(p).read(columns=columns, use_threads=False)
                                   for p in paths])}


def _child(src: str, directory: Path, repeat: int) -> dict:
    out = subprocess.run([sys.executable, __file__, "--child", src, "--directory",
                          str(directory), "--repeat", str(repeat)],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _line(label: str, t: dict) -> str:
    ms = {k: 1e3 * t[k] for k in _TIMED}
    return (f"{label:>8} {ms['run_contacts']:>13.3f} {ms['wear_power']:>11.3f} "
            f"{ms['read']:>8.3f} {ms['read1']:>8.3f} {ms['run_contacts'] / ms['read']:>10.2f} "
            f"{ms['wear_power'] / ms['read']:>10.2f} {ms['wear_power'] / ms['read1']:>11.2f}")


_TIMED = ("run_contacts", "wear_power", "read", "read1")


def _load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--contacts", type=int, default=1000)
    p.add_argument("--samples", type=int, default=1000)
    p.add_argument("--distinct", type=int, default=50, help="distinct files, hard-linked")
    p.add_argument("--repeat", type=int, default=3, help="passes; the best is kept")
    p.add_argument("--base", help="a checkout of the code before (its src/): before and after")
    p.add_argument("--rounds", type=int, default=3, help="turns of each side with --base")
    p.add_argument("--child", help=argparse.SUPPRESS)
    p.add_argument("--directory", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        print(json.dumps(_timings(args.child, Path(args.directory), args.repeat)))
        return
    sys.path.insert(0, str(ROOT / "src"))
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_bundle_scale import make_bundle

    with tempfile.TemporaryDirectory() as tmp:
        directory = Path(tmp)
        make_bundle(directory, args.contacts, args.samples, args.distinct)
        print(f"load average {_load()}; {args.contacts} contacts x {args.samples} samples, "
              f"Parquet; ms of CPU a contact, best of {args.repeat} passes"
              + (f", best of {args.rounds} rounds taking turns" if args.base else ""))
        print(f"{'':>8} {'run_contacts':>13} {'wear_power':>11} {'read':>8} {'read 1t':>8} "
              f"{'run / read':>10} {'power/read':>10} {'power/read1':>11}")
        after = str(ROOT / "src")
        if not args.base:
            new = _child(after, directory, args.repeat)
            print(_line("", new))
        else:
            before = str(Path(args.base).resolve() / "src")
            olds, news = [], []
            for _ in range(args.rounds):
                olds.append(_child(before, directory, args.repeat))
                news.append(_child(after, directory, args.repeat))
            assert olds[0]["module"].startswith(before), olds[0]["module"]
            assert news[0]["module"].startswith(after), news[0]["module"]
            old, new = ({k: min(t[k] for t in side) if k in _TIMED else side[0][k]
                         for k in side[0]} for side in (olds, news))
            print(_line("before", old))
            print(_line("after", new))
            print(f"{'ratio':>8} {new['run_contacts'] / old['run_contacts']:>13.2f} "
                  f"{new['wear_power'] / old['wear_power']:>11.2f}")
            # the rounds' medians: a shared machine moves single rounds by 10 % both ways
            med = {k: [statistics.median(t[k] for t in side) for side in (olds, news)]
                   for k in ("run_contacts", "wear_power")}
            print(f"{'medians':>8} " + "; ".join(
                f"{k} {1e3 * b:.3f} -> {1e3 * a:.3f} ms ({a / b:.2f})"
                for k, (b, a) in med.items()))
            # and of each child's own ratios to its one-thread read (the same machine state)
            rel = {k: [statistics.median(t[k] / t["read1"] for t in side)
                       for side in (olds, news)] for k in ("run_contacts", "wear_power")}
            print(f"{'/ read1':>8} " + "; ".join(
                f"{k} {b:.2f} -> {a:.2f} ({a / b:.2f})" for k, (b, a) in rel.items()))
        print(f"columns read: {new['columns']}")
        print(f"load average after {_load()}")


if __name__ == "__main__":
    main()
