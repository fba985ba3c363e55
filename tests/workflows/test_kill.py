"""SIGKILL during `fretwear run -o`, `obstacle` and `iterate` (issue 15): nothing half-written.

Each command first writes its outputs once (the "old" outputs, configuration A), then is run
again with configuration B over them and killed with SIGKILL at delays spread over its whole
run time (stratified random delays from a fixed seed). After every kill each output file must
be the old one (same bytes) or the complete new one (the same content as an uninterrupted run
of B), and an `iterate` cycle folder must be entirely old or entirely new. Temporary files left
by a kill are hidden (``.name.*.tmp``) and removed by the next write (tested apart).

Budget: ``FRETWEAR_KILLS`` kills per command (default 4 for run and obstacle, 3 for iterate),
about 20 s on two idle cores; FRETWEAR_KILLS=20 for a deep run (60 kills passed, 2 min).
"""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.io import read_history, write_history
from fretwear.io.atomic import STALE_SECONDS, atomic_folder, atomic_path

EXAMPLES = Path(__file__).parents[2] / "examples"
KILLS = int(os.environ.get("FRETWEAR_KILLS", "0"))


def _launch(argv: list[str], cwd: Path) -> subprocess.Popen:
    code = "import sys; from fretwear.cli import main; sys.exit(main(sys.argv[1:]))"
    return subprocess.Popen([sys.executable, "-c", code, *argv], cwd=cwd,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def _complete(argv: list[str], cwd: Path) -> float:
    start = time.perf_counter()
    proc = _launch(argv, cwd)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err.decode()
    return time.perf_counter() - start


def _files(root: Path) -> dict[str, Path]:
    return {str(p.relative_to(root)): p for p in sorted(root.rglob("*"))
            if p.is_file() and not any(part.startswith(".") for part in p.relative_to(root).parts)}


def _content(path: Path):
    """What must equal between two complete runs (provenance lines carry the date)."""
    if path.suffix == ".csv":
        return pd.read_csv(path, comment="#")
    if path.suffix == ".parquet":
        return pd.read_parquet(path)
    if path.suffix == ".json":
        return sorted(json.loads(path.read_text()))  # timings and paths differ: keys only
    return [ln for ln in path.read_text().splitlines() if not ln.startswith("#")]


def _same(a, b) -> bool:
    if isinstance(a, pd.DataFrame):
        return a.shape == b.shape and list(a.columns) == list(b.columns) and all(
            np.array_equal(a[c].to_numpy(), b[c].to_numpy()) or a[c].equals(b[c])
            for c in a.columns)
    return a == b


def _generation(path: Path, old: dict[str, bytes], new: dict[str, object], rel: str) -> str:
    data = path.read_bytes()
    if rel in old and data == old[rel]:
        return "old"
    try:
        content = _content(path)
    except Exception as exc:  # noqa: BLE001 - a half-written file fails to parse
        raise AssertionError(f"{rel}: neither the old file nor a readable new one ({exc})"
                             ) from exc
    assert rel in new and _same(content, new[rel]), f"{rel}: neither the old nor the new one"
    return "new"


def _kill_many(argv_b, cwd, out_root, old, new, seconds, kills, folders=False):
    rng = random.Random(15)
    leftovers = 0
    for k in range(kills):
        proc = _launch(argv_b, cwd)
        time.sleep((k + rng.random()) / kills * seconds * 1.05)  # stratified over the run
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=60)
        now = _files(out_root)
        assert set(old) <= set(now), f"lost: {sorted(set(old) - set(now))}"
        generations = {rel: _generation(p, old, new, rel) for rel, p in now.items()}
        if folders:  # a cycle folder is all old or all new, with the files of that generation
            for cycle in {rel.split("/")[0] for rel in now if rel.startswith("cycle_")}:
                inside = {rel: g for rel, g in generations.items() if rel.startswith(cycle + "/")}
                kinds = set(inside.values())
                assert len(kinds) == 1, f"kill {k}: {cycle} mixes old and new files: {inside}"
                expected = old if kinds == {"old"} else new
                assert set(inside) == {r for r in expected if r.startswith(cycle + "/")}
        leftovers += sum(1 for p in out_root.rglob(".*") if p.name.endswith((".tmp", ".old")))
    return leftovers


def _budget(default: int) -> int:
    return KILLS or default


@pytest.fixture(scope="module")
def history(tmp_path_factory):
    d = tmp_path_factory.mktemp("kill")
    return write_history(read_history(EXAMPLES / "data" / "oscillator_gap.csv"), d / "h.csv")


def test_kill_run_output(tmp_path, history, grappe_case):
    a = grappe_case(tmp_path / "a.toml", history, sectors=6)
    b = grappe_case(tmp_path / "b.toml", history, instants="[1000, 5000, 20000]", sectors=6)
    out = tmp_path / "out"
    out.mkdir()
    ref = tmp_path / "ref"
    ref.mkdir()
    _complete(["run", str(a), "-q", "-o", str(out / "table.csv")], tmp_path)
    seconds = _complete(["run", str(b), "-q", "-o", str(ref / "table.csv")], tmp_path)
    old = {rel: p.read_bytes() for rel, p in _files(out).items()}
    new = {rel: _content(p) for rel, p in _files(ref).items()}
    _kill_many(["run", str(b), "-q", "-o", str(out / "table.csv")], tmp_path, out, old, new,
               seconds, _budget(4))


def test_kill_obstacle_outputs(tmp_path, history, grappe_case):
    table = tmp_path / "wear.csv"
    _complete(["run", str(grappe_case(tmp_path / "a.toml", history, sectors=6)), "-q", "-o",
               str(table)], tmp_path)
    common = ["obstacle", "--table", str(table), "--mobile-radius", "4.85e-3",
              "--wall-thickness", "0.47e-3", "--width", "20e-3", "-q"]

    def argv(root: Path, gap: str) -> list[str]:
        return [*common, "--gap", gap, "-o", str(root / "profile.csv"), "--write-discret",
                str(root / "worn.txt")]

    out, ref = tmp_path / "out", tmp_path / "ref"
    out.mkdir()
    ref.mkdir()
    _complete(argv(out, "0.4e-3"), tmp_path)
    seconds = _complete(argv(ref, "0.3e-3"), tmp_path)
    old = {rel: p.read_bytes() for rel, p in _files(out).items()}
    new = {rel: _content(p) for rel, p in _files(ref).items()}
    _kill_many(argv(out, "0.3e-3"), tmp_path, out, old, new, seconds, _budget(4))


ITERATE = """[law]
name = "ARCHARD"
mobile = {{ COEF_USURE = 2e-14 }}
obstacle = {{ COEF_USURE = 1e-14 }}
[geometry]
contact_type = "TUBE_ALESAGE"
mobile_radius_m = 9.5e-3
obstacle_radius_m = 9.7e-3
obstacle_width_m = 0.02
[sectors]
count = 8
[time]
instants = [0.5, 1.0]
unit = "year"
[obstacle]
type = "circle"
gap_m = 2e-4
wall_thickness_m = 1.1e-3
[dynamics]
duration_s = 0.2
time_step_s = 2e-5
archive_step_s = 1e-4
[dynamics.modes]
frequencies_Hz = [30.0, 30.0]
damping_ratios = 0.02
masses_kg = 0.5
shock_shapes = [[[1.0, 0.0], [0.0, 1.0]]]
forcing_shapes = [[[1.0, 0.0], [0.0, 1.0]]]
[[dynamics.shocks]]
name = "bore"
obstacle = "case"
normal_stiffness_N_per_m = 1e6
normal_damping_N_s_per_m = 20.0
friction = 0.3
tangential_stiffness_N_per_m = 1e6
[[dynamics.forces]]
point = 0
direction = "y"
kind = "harmonic"
amplitude = {amplitude}
frequency_Hz = 25.0
[[dynamics.forces]]
point = 0
direction = "z"
kind = "harmonic"
amplitude = 6.0
frequency_Hz = 25.0
phase_deg = 90.0
[iterate]
cycles = 2
plot = false
"""


def test_kill_iterate_cycle_folders(tmp_path):
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    a.write_text(ITERATE.format(amplitude=12.0))
    b.write_text(ITERATE.format(amplitude=10.0))
    out, ref = tmp_path / "out", tmp_path / "ref"
    _complete(["iterate", str(a), "-o", str(out), "-q"], tmp_path)
    seconds = _complete(["iterate", str(b), "-o", str(ref), "-q"], tmp_path)
    old = {rel: p.read_bytes() for rel, p in _files(out).items()}
    new = {rel: _content(p) for rel, p in _files(ref).items()}
    assert any(rel.startswith("cycle_02/histories/") for rel in old)
    _kill_many(["iterate", str(b), "-o", str(out), "-q"], tmp_path, out, old, new, seconds,
               _budget(3), folders=True)


def test_leftovers_of_a_killed_run_are_removed_by_the_next_write(tmp_path):
    target = tmp_path / "table.csv"
    stale = tmp_path / ".table.csv.abc123.tmp"
    stale.write_text("half")
    fresh = tmp_path / ".table.csv.def456.tmp"  # perhaps another writer's, right now
    fresh.write_text("busy")
    old_folder = tmp_path / ".cycle_01.x1y2.tmp"
    (old_folder / "histories").mkdir(parents=True)
    past = time.time() - 2 * STALE_SECONDS
    for p in (stale, old_folder):
        os.utime(p, (past, past))
    with atomic_path(target) as tmp:
        tmp.write_text("new")
    with atomic_folder(tmp_path / "cycle_01") as folder:
        (folder / "wear_table.csv").write_text("new")
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == [".table.csv.def456.tmp", "cycle_01", "table.csv"]
