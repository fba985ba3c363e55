"""``fretwear run`` end to end on a long Parquet history, for each wear law, against pyarrow.

A Parquet file of ``--samples`` samples (default 10⁸; written once under ``--dir`` and kept) holds
a ``fretwear.dynamics`` rattling tube tiled end to end (``benchmarks/_signals.py``: time,
normal_force, vt1, vt2, dy, dz, stick; row groups of 2²⁰ rows). Each command runs in a fresh
interpreter; measured:

* **wall** [s]: the command from start to exit (interpreter start, imports and the compiled
  kernels' cache load included, about 1 s);
* **peak RSS** [MB]: the process's ``ru_maxrss``;
* **CPU** [s]: the process's user + system time, all threads (on a shared machine the wall
  also holds the time spent waiting for a core; the CPU time does not);
* **passes**: how many times the file's data were read (calls of pyarrow's
  ``ParquetFile.iter_batches`` and ``read_table``);
* **ratio**: wall / the wall of a plain pyarrow read of the same columns (record batches of 2²⁰
  rows turned into numpy arrays, in a fresh interpreter too).

Commands: the pyarrow read; ``fretwear power FILE --blocks 4 --sectors 10`` (the streaming
ratio); ``fretwear run`` of a case per law on the file: ARCHARD (10 sectors, 4 blocks),
KWU_EPRI without FNOR_MAXI/VTAN_MAXI (the class counts need the window's maxima: two passes),
KWU_EPRI with them (one pass), EDF_MZ. Each ``--runs`` times, the commands taking turns
within a run (median printed, with the min-max of the wall: the machine may be shared; the load
average is printed before and after).

Before and after in one run: ``--base DIR`` adds ``fretwear power`` run by the fretwear of
``DIR/src`` (e.g. a clone of the base commit), taking its turn with the others; its ratio to
the pyarrow read is printed beside this checkout's.

Usage::

    .venv/bin/python benchmarks/bench_run.py                     # 1e8 samples (5.6 GB file)
    .venv/bin/python benchmarks/bench_run.py --samples 1e7 --runs 1
    .venv/bin/python benchmarks/bench_run.py --laws --base /tmp/base   # fretwear power only
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _signals  # noqa: E402 - the benchmark's own helper module

COLUMNS = ("time", "normal_force", "vt1", "vt2", "dy", "dz", "stick")
UNITS = {"time": "s", "normal_force": "N", "vt1": "m/s", "vt2": "m/s", "dy": "m", "dz": "m",
         "stick": "1"}
ROW_GROUP = 1 << 20

#: Run in the child: count the passes over Parquet data, run the command, report.
_CHILD = textwrap.dedent("""
    import json, resource, sys, time
    import pyarrow.parquet as pq
    passes = [0]
    _batches, _table = pq.ParquetFile.iter_batches, pq.read_table
    def iter_batches(self, *a, **k):
        passes[0] += 1
        return _batches(self, *a, **k)
    def read_table(*a, **k):
        passes[0] += 1
        return _table(*a, **k)
    pq.ParquetFile.iter_batches, pq.read_table = iter_batches, read_table
    args = json.loads(sys.argv[1])
    start = time.perf_counter()
    if args[0] == "pyarrow":
        handle = pq.ParquetFile(args[1], pre_buffer=False, buffer_size=1 << 20)
        n = 0
        for batch in handle.iter_batches(batch_size=1 << 20, columns=args[2:]):
            arrays = [batch.column(i).to_numpy() for i in range(batch.num_columns)]
            n += len(arrays[0])
        code = 0
    else:
        from fretwear.cli import main
        code = main(args)
    inner = time.perf_counter() - start
    usage = resource.getrusage(resource.RUSAGE_SELF)
    print("BENCH " + json.dumps({"passes": passes[0], "rss_mb": usage.ru_maxrss / 1024,
                                 "inner": inner, "cpu": usage.ru_utime + usage.ru_stime,
                                 "code": code}), file=sys.stderr)
""")


def write_file(path: Path, samples: int, chunk: int = 1_000_000) -> None:
    """The tiled rattling tube, ``samples`` rows, streamed to Parquet (atomic rename)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    gen = _signals.generator("dynamics")
    schema = pa.schema([pa.field(c, pa.float64(), metadata={"units": UNITS[c]})
                        for c in COLUMNS])
    tmp = path.with_suffix(".tmp")
    with pq.ParquetWriter(tmp, schema) as writer:
        for start in range(0, samples, chunk):
            arrays = gen(start, min(chunk, samples - start))
            writer.write_table(pa.Table.from_arrays([pa.array(arrays[c]) for c in COLUMNS],
                                                    schema=schema), row_group_size=ROW_GROUP)
    os.replace(tmp, path)


def case_text(path: Path, law: str) -> str:
    """A TOML case on the history file for ``law``."""
    laws = {
        "ARCHARD": 'name = "ARCHARD"\nmobile = { COEF_USURE = 5.2e-14 }',
        "KWU_EPRI": 'name = "KWU_EPRI"\nmobile = { COEF_USURE = 5.2e-14, '
                    'reference_intensity = 1.0e-7 }',
        "KWU_EPRI_MAXI": 'name = "KWU_EPRI"\nmobile = { COEF_USURE = 5.2e-14, '
                         'reference_intensity = 1.0e-7 }\nforce_max_N = 60.0\n'
                         'speed_max_m_per_s = 0.5',
        "EDF_MZ": 'name = "EDF_MZ"\nmobile = { COEF_USURE = 2.6e-15, COEF_B = 1.0, '
                  'COEF_N = 2.44e-8, COEF_S = 1.14e-16 }',
    }
    sectors = "\n[sectors]\ncount = 10\n" if law == "ARCHARD" else ""
    return (f'title = "bench_run {law}"\n[history]\nfile = "{path}"\n[power]\nblocks = 4\n'
            f"[law]\n{laws[law]}\n[geometry]\ncontact_type = \"TUBE_ALESAGE\"\n"
            "mobile_radius_m = 9.525e-3\nobstacle_radius_m = 9.725e-3\n"
            f"obstacle_width_m = 20e-3\n{sectors}[time]\ninstants = [1, 10]\nunit = \"year\"\n")


def measure(args: list[str], src: Path | None = None) -> dict:
    """Run one command in a fresh interpreter (importing fretwear from ``src`` when given);
    wall [s] and the child's report."""
    env = dict(os.environ)
    if src is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(src), env.get("PYTHONPATH", "")])
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _CHILD, json.dumps(args)],
                          capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    lines = [x for x in proc.stderr.splitlines() if x.startswith("BENCH ")]
    if proc.returncode or not lines:
        raise RuntimeError(f"{args[:2]} failed ({proc.returncode}):\n{proc.stderr[-2000:]}")
    report = json.loads(lines[-1][6:])
    if report["code"]:
        raise RuntimeError(f"{args[:2]} exited {report['code']}:\n{proc.stderr[-2000:]}")
    return {"wall": wall, **report}


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--samples", type=float, default=1e8)
    p.add_argument("--dir", type=Path, default=Path(tempfile.gettempdir()),
                   help="where the Parquet file is written once and kept")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--laws", nargs="*",
                   default=["ARCHARD", "KWU_EPRI", "KWU_EPRI_MAXI", "EDF_MZ"])
    p.add_argument("--base", type=Path, default=None,
                   help="a checkout whose src/ gives the 'before' of fretwear power")
    args = p.parse_args(argv)
    n = int(args.samples)
    args.dir.mkdir(parents=True, exist_ok=True)  # a folder given that does not exist yet
    path = args.dir / f"fretwear_bench_run_{n}.parquet"
    if not path.is_file():
        print(f"writing {path} ({n:.0e} samples) ...", flush=True)
        write_file(path, n)
    size = path.stat().st_size / 1e9
    commands = {"pyarrow read": ["pyarrow", str(path), *COLUMNS],
                "fretwear power": ["power", str(path), "--blocks", "4", "--sectors", "10"]}
    with tempfile.TemporaryDirectory() as tmp:
        for law in args.laws:
            case = Path(tmp) / f"{law}.toml"
            case.write_text(case_text(path, law))
            commands[f"run {law}"] = ["run", str(case), "-o", str(Path(tmp) / f"{law}.csv"),
                                      "--quiet"]
        srcs = {name: None for name in commands}
        if args.base is not None:
            commands["power (base)"] = commands["fretwear power"]
            srcs["power (base)"] = args.base.resolve() / "src"
        load = os.getloadavg()
        for name in ("fretwear power", "power (base)"):  # warm the page and numba caches
            if name in commands:
                measure(commands[name], srcs[name])
        results = {name: [] for name in commands}
        for _ in range(args.runs):  # the commands take turns: a change of load hits all
            for name, cmd in commands.items():
                results[name].append(measure(cmd, srcs[name]))
    base = float(np.median([r["wall"] for r in results["pyarrow read"]]))
    base_cpu = float(np.median([r["cpu"] for r in results["pyarrow read"]]))
    print(f"{n:.0e} samples, {len(COLUMNS)} columns, {size:.2f} GB, page cache warm; medians "
          f"of {args.runs} runs (wall min-max); load average (1, 5, 15 min) "
          f"{'/'.join(f'{x:.1f}' for x in load)} before, "
          f"{'/'.join(f'{x:.1f}' for x in os.getloadavg())} after")
    print(f"{'command':>22} {'wall [s]':>9} {'min-max':>13} {'ratio':>6} {'peak RSS [MB]':>14} "
          f"{'passes':>7} {'CPU [s]':>8} {'ratio':>6}")
    for name, runs in results.items():
        wall = float(np.median([r["wall"] for r in runs]))
        lo, hi = min(r["wall"] for r in runs), max(r["wall"] for r in runs)
        rss = float(np.median([r["rss_mb"] for r in runs]))
        cpu = float(np.median([r["cpu"] for r in runs]))
        print(f"{name:>22} {wall:>9.2f} {lo:>6.2f}-{hi:<6.2f} {wall / base:>6.2f} "
              f"{rss:>14.0f} {runs[0]['passes']:>7d} {cpu:>8.2f} {cpu / base_cpu:>6.2f}")


if __name__ == "__main__":
    main()
