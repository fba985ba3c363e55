"""The bundle on a real dask.distributed cluster: a LocalCluster of 2 worker processes, shared by
the tests of this module and joined through its address (``scheduler=``), as a user joins a
cluster started elsewhere; plus one run that starts its own local cluster (no scheduler).

Checked: every contact equals the single-contact wear table bit for bit (both computed on this
machine in this environment: the workers are child processes with the test's processor and
environment, so the same SIMD code paths; across machines only to rounding); a corrupted and a
missing file land in ``errors`` while the rest complete; a chunked contact gives the same bits
on the cluster as in one process; a worker that dies is replaced and its task retried; a run
killed midway restarts without recomputing the contacts it had written; the CLI.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pandas as pd
import pytest
from bundle_helpers import assert_identical, oscillator, reference, rows_of, write_bundle

from fretwear.bundle import run_bundle
from fretwear.io import write_history

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as local:
        yield local


@pytest.fixture(scope="module")
def address(cluster):
    return cluster.scheduler_address


def test_cluster_rows_are_the_single_contact_tables_and_failures_are_rows(tmp_path, address):
    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 4)
    (tmp_path / "histories" / "corrupt.parquet").write_bytes(b"PAR1 garbage, not a table")
    frame = pd.concat([pd.read_csv(manifest), pd.DataFrame(
        {"contact": ["corrupt", "missing"],
         "history": ["histories/corrupt.parquet", "histories/missing.parquet"]})])
    frame.to_csv(manifest, index=False)
    result = run_bundle(manifest, case, scheduler=address)
    assert result.stats["workers"] == 2
    assert result.errors.set_index("contact")["error"].to_dict() == {
        "corrupt": "FormatError", "missing": "InputError"}
    assert result.stats["done"] == 4 and result.stats["failed"] == 2
    for k in range(4):
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.parquet", case))


def test_contacts_grouped_in_tasks_keep_their_own_rows_and_failures(tmp_path, address,
                                                                     monkeypatch):
    """Contacts grouped several per Dask task (engine.task_sizes, here 3 per task by asking one
    task per worker, consecutive slices) give each contact's single-contact table bit for bit, and
    a bad contact fails alone inside its group. The groups are submitted in one graph once
    every contact's task is built (the scheduler then deals them out evenly by count)."""
    from fretwear.bundle import engine

    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 6)
    frame = pd.read_csv(manifest)
    frame.loc[4, "history"] = "histories/missing.parquet"
    frame.to_csv(manifest, index=False)
    monkeypatch.setattr(engine, "TASKS_PER_WORKER", 1)
    assert engine.task_sizes(6, 2) == [3, 3]
    submitted = []
    dealt = []
    real_map = engine.DaskEngine.map
    monkeypatch.setattr(engine.DaskEngine, "map", lambda self, fn, items, *a, **k: submitted.append(
        (fn.__name__, [len(i) for i in items])) or dealt.extend(
        [t.contact for t in i] for i in items) or real_map(self, fn, items, *a, **k))
    real_build = engine.build_task
    monkeypatch.setattr(engine, "build_task", lambda base, row, *a, **k: submitted.append(
        ("build", row.contact)) or real_build(base, row, *a, **k))
    crossed = []
    real_gather = distributed.Client.gather

    def recording_gather(self, futures, *a, **k):
        values = real_gather(self, futures, *a, **k)
        crossed.extend(type(v) for v in values)
        return values

    monkeypatch.setattr(distributed.Client, "gather", recording_gather)
    result = run_bundle(manifest, case, scheduler=address)
    built = [("build", f"R{k // 2 + 1}C{k % 2 + 1}-AVB") for k in range(6)]
    assert submitted == [*built, ("run_contacts", [3, 3])]  # the groups in one graph
    # consecutive slices of the manifest (engine.submitted_slices; one per worker here)
    assert dealt == [[built[k][1] for k in (0, 1, 2)], [built[k][1] for k in (3, 4, 5)]]
    # each group's records cross to the client as one pickle (tasks.pickled), not as Dask's
    # frame per array
    assert crossed == [bytes, bytes]
    assert result.errors["contact"].tolist() == ["R3C1-AVB"]
    for k in (0, 1, 2, 3, 5):
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.parquet", case))


def test_groups_are_no_larger_than_a_part_so_their_workers_write_them(tmp_path, address,
                                                                      monkeypatch):
    """A run's ``part_size`` bounds its groups (engine.task_sizes' ``largest``): 12 contacts in
    one task per worker would make groups of 6, more than parts of 4, whose rows the client
    then gathered and wrote itself in parts of 4 (3 parts); bounded, 4 groups of 3, each
    written by its worker as one part (4 parts of 3). The rows are the single-contact tables
    either way."""
    from fretwear.bundle import engine

    monkeypatch.setattr(engine, "TASKS_PER_WORKER", 1)
    manifest, case = write_bundle(tmp_path, oscillator(), 12)
    result = run_bundle(manifest, case, scheduler=address, output=tmp_path / "out",
                        part_size=4)
    parts = [json.loads(p.read_text()) for p in sorted((tmp_path / "out" / "parts").glob(
        "*.json"))]
    assert sorted(len(p["contacts"]) for p in parts) == [3, 3, 3, 3]
    assert result.stats["done"] == 12
    for k in (0, 11):
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.parquet", case))


class _FirstAssignment(distributed.diagnostics.plugin.SchedulerPlugin):
    """The worker the scheduler first gives each task (before any work stealing moves it)."""

    def __init__(self, scheduler) -> None:
        self.scheduler, self.first = scheduler, {}

    def transition(self, key, start, finish, *args, **kwargs) -> None:
        if finish == "processing" and key not in self.first:
            self.first[key] = self.scheduler.tasks[key].processing_on.address


def test_a_large_bundle_is_submitted_in_waves_each_shared_evenly(tmp_path, monkeypatch):
    """Beyond engine.FIRST_WAVE rows (here 16, the largest wave 32: 80 contacts in waves of 16,
    32 and 32, engine.waves) the rows are built and submitted wave after wave, the workers
    computing one while the client builds the next; each wave is its own Dask task group, so
    the scheduler deals every wave's 8 groups to the 2 workers, 4 each (in one task group, it
    counted the earlier waves' tasks still held and dealt a whole wave to one worker: 8 and 0;
    where the tasks then ran is left to Dask's work stealing, not checked). Every contact
    equals its single-contact table bit for bit, and the run writes the table the serial
    engine writes. On a cluster set as run_bundle sets its own (cluster.LOCAL_CLUSTER_CONFIG:
    every task sent to a worker's queue at once; with Dask's default scheduler-side queuing, as
    this module's other cluster has, the scheduler hands the tasks out as workers free up)."""
    import dask

    from fretwear.bundle import engine
    from fretwear.bundle.cluster import LOCAL_CLUSTER_CONFIG

    monkeypatch.setattr(engine, "FIRST_WAVE", 16)
    monkeypatch.setattr(engine, "LARGEST_WAVE", 32)
    monkeypatch.setattr(engine, "TASKS_PER_WORKER", 4)
    manifest, case = write_bundle(tmp_path, oscillator(), 80)
    steps = []
    real_map = engine.DaskEngine.map
    monkeypatch.setattr(engine.DaskEngine, "map", lambda self, fn, items, *a, **k: steps.append(
        ("map", [len(i[0]) for i in items])) or real_map(self, fn, items, *a, **k))
    real_build = engine.build_task
    monkeypatch.setattr(engine, "build_task", lambda base, row, *a, **k: steps.append(
        ("build", row.contact)) or real_build(base, row, *a, **k))
    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=":0")
    with cluster:
        dealt = _FirstAssignment(cluster.scheduler)
        cluster.scheduler.add_plugin(dealt, name="first-assignment")
        result = run_bundle(manifest, case, scheduler=cluster.scheduler_address,
                            output=tmp_path / "out")
    kinds = [kind for kind, _ in steps]
    assert kinds == ["build"] * 16 + ["map"] + ["build"] * 32 + ["map"] + ["build"] * 32 + ["map"]
    assert [v for kind, v in steps if kind == "map"] == [[2] * 8, [4] * 8, [4] * 8]
    shares: dict = {}  # {a wave's tag (the key's end): {worker: its groups}}
    for key, worker in dealt.first.items():
        shares.setdefault(key.rsplit("-", 1)[1], {}).setdefault(worker, []).append(key)
    assert len(shares) == 3
    for wave, workers in shares.items():
        assert sorted(len(groups) for groups in workers.values()) == [4, 4], (wave, workers)
    assert sorted({key.split("-", 1)[0] for key in dealt.first}) == [
        "contacts", "contacts1", "contacts2"]
    assert result.errors.empty and result.stats["done"] == 80
    serial = run_bundle(manifest, case, scheduler="serial")
    pd.testing.assert_frame_equal(result.table, serial.table)
    for k in (0, 17, 79):
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.parquet", case))


def test_chunked_contact_same_bits_on_the_cluster_as_in_one_process(tmp_path, address):
    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 2)
    write_history(h, tmp_path / "histories" / "t0.parquet", row_group_size=300)
    options = dict(chunk_size=400, split_every=3)
    on_cluster = run_bundle(manifest, case, scheduler=address, **options)
    serial = run_bundle(manifest, case, scheduler="serial", **options)
    assert on_cluster.errors.empty
    pd.testing.assert_frame_equal(on_cluster.table, serial.table, check_exact=True)


def _kill_first_attempt(marker: str, contact: str):
    """Installed on the workers: the first task of ``contact`` kills its worker process."""
    import fretwear.bundle.tasks as tasks

    original = tasks.run_contact

    def run_contact(task, chunk_size=1_000_000):
        if task.contact == contact and not os.path.exists(marker):
            open(marker, "w").close()
            os._exit(1)  # the worker process dies: the nanny starts a new one
        return original(task, chunk_size)

    if getattr(tasks, "_original_run_contact", None) is None:
        tasks._original_run_contact = original
        tasks.run_contact = run_contact


def _restore():
    import fretwear.bundle.tasks as tasks

    if getattr(tasks, "_original_run_contact", None) is not None:
        tasks.run_contact = tasks._original_run_contact
        tasks._original_run_contact = None


def test_a_dead_worker_is_replaced_and_its_contact_retried(tmp_path, address):
    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    marker = tmp_path / "killed"
    with distributed.Client(address) as client:
        client.run(_kill_first_attempt, str(marker), "R1C2-AVB")
        try:
            result = run_bundle(manifest, case, scheduler=address)
        finally:
            client.run(_restore)
    assert marker.exists()  # a worker did die
    assert result.errors.empty, result.errors
    assert_identical(rows_of(result, "R1C2-AVB"),
                     reference(tmp_path / "histories/t1.parquet", case))


def _fails(x):
    raise ValueError(f"bad {x}")


def _workers_checking(client, crash_on: str | None, timeout: float | None):
    """In each worker: count the processes it starts (subprocess.Popen), make its checking child
    crash on the files named ``crash_on`` and time it out after ``timeout`` s; undone by
    ``_workers_checking(client, None, None)``, which returns each worker's count."""
    def setup(crash_on, timeout):
        import subprocess

        import fretwear.io.guard as guard
        real = getattr(subprocess, "_fretwear_real_popen", subprocess.Popen)
        if crash_on is None:
            started = len(getattr(subprocess, "_fretwear_started", []))
            subprocess.Popen = real
            guard._CHILD = getattr(guard, "_fretwear_child", guard._CHILD)
            guard.PROBE_TIMEOUT = getattr(guard, "_fretwear_timeout", guard.PROBE_TIMEOUT)
            return started
        guard._fretwear_child, guard._fretwear_timeout = guard._CHILD, guard.PROBE_TIMEOUT
        subprocess._fretwear_real_popen = real
        subprocess._fretwear_started = []

        def counted(*args, **kwargs):
            subprocess._fretwear_started.append(1)
            return real(*args, **kwargs)

        subprocess.Popen = counted
        guard._CHILD = guard._CHILD.replace(
            "def check(path, fmt):\n",
            f"def check(path, fmt):\n    if path.endswith({crash_on!r}):\n"
            "        import os\n        os._exit(139)\n")
        guard.PROBE_TIMEOUT = timeout
        guard._PROBED.clear()
        return 0

    return client.run(setup, crash_on, timeout)


def test_a_file_that_crashes_or_hangs_the_library_fails_its_contact_alone(tmp_path, address):
    """issue 28: in a bundle's worker, HDF5 files are checked by one long-lived child per worker
    (not a child per file: 0.2 s a file). A file that kills that child (simulated: the checking
    script patched in the workers to end its process on one file, as a segmentation fault of
    h5py would) and a real file that makes h5py loop forever (found by fuzzing; cut after the
    time limit) each fail their own contact with a message naming the file; the other contacts,
    in the same tasks, complete with the single-contact tables bit for bit (this machine)."""
    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 6, fmt="h5")
    loop = tmp_path / "histories" / "loop.h5"
    fixture = Path(__file__).parents[1] / "io" / "fixtures" / "damaged" / "hdf5_attribute_loop.h5"
    loop.write_bytes(fixture.read_bytes())
    frame = pd.concat([pd.read_csv(manifest), pd.DataFrame(
        {"contact": ["crash", "loop"], "history": ["histories/t2.h5", "histories/loop.h5"]})])
    crashing = tmp_path / "histories" / "t2.h5"
    frame.loc[frame["contact"] == "crash", "history"] = "histories/crash.h5"
    (tmp_path / "histories" / "crash.h5").write_bytes(crashing.read_bytes())
    frame.to_csv(manifest, index=False)
    with distributed.Client(address) as client:
        # a worker killed by an earlier test is replaced by now (an error, not a hang, if not)
        client.wait_for_workers(2, timeout=120)
        # the limit counts the checker's start (Python, h5py) as it did the child per file's:
        # 10 s, ample on a loaded machine, for a file that loops forever
        assert len(_workers_checking(client, "crash.h5", 10.0)) == 2
        try:
            result = run_bundle(manifest, case, scheduler=client)
        finally:
            started = _workers_checking(client, None, None)
    errors = result.errors.set_index("contact")["message"].to_dict()
    assert set(errors) == {"crash", "loop"}
    assert "crash.h5: the HDF5 library crashed (exit status 139) reading this file: it is " \
        "damaged" in errors["crash"]
    assert "loop.h5: the HDF5 library did not finish reading the file's structure in 10 s" \
        in errors["loop"] or "loop.h5: not a readable hdf5 file" in errors["loop"]
    assert result.stats["done"] == 6
    for k in range(6):
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.h5", case))
    # 8 files on 2 workers: a checker each, one more after the crash and after the hang at most
    assert sum(started.values()) <= 4, started


@pytest.mark.parametrize("streaming", [True, False])
def test_results_of_finished_and_failed_tasks(address, streaming):
    """The engine yields every task once: a finished task's records (unpickled when they came
    back pickled), a failed task's exception, whether the results are fetched as the tasks
    finish or all at once at the end (one gather, when nobody watches the progress)."""
    import pickle

    from fretwear.bundle.cluster import DaskEngine

    with distributed.Client(address) as client:
        engine = DaskEngine(client, None)
        good = [client.submit(pickle.dumps, [{"contact": f"c{k}"}], pure=False)
                for k in range(3)]
        bad = client.submit(_fails, 7, pure=False)
        plain = client.submit(dict, contact="p", pure=False)
        out = {id(h): v for h, v in engine.results([*good, bad, plain], streaming)}
    assert len(out) == 5
    assert [out[id(h)] for h in good] == [[{"contact": f"c{k}"}] for k in range(3)]
    assert isinstance(out[id(bad)], ValueError) and str(out[id(bad)]) == "bad 7"
    assert out[id(plain)] == {"contact": "p"}


def test_a_large_bundle_streams_its_results_even_when_nobody_watches(tmp_path, address,
                                                                    monkeypatch):
    """Without progress or output directory, the results come in one gather at the end only up
    to engine.GATHER_AT_END contacts (here lowered to 3 for a bundle of 4): beyond, as each task
    finishes, so that the workers do not hold every finished record until the end. Both ways
    give every contact's single-contact table bit for bit."""
    from fretwear.bundle import cluster, engine

    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    modes = []
    real_results = cluster.DaskEngine.results

    def recording_results(self, handles, streaming=True):
        modes.append(streaming)
        return real_results(self, handles, streaming)

    monkeypatch.setattr(cluster.DaskEngine, "results", recording_results)
    results = [run_bundle(manifest, case, scheduler=address)]
    monkeypatch.setattr(engine, "GATHER_AT_END", 3)
    results.append(run_bundle(manifest, case, scheduler=address))
    assert modes == [False, True]
    for result in results:
        assert result.errors.empty and result.stats["done"] == 4
        for k in range(4):
            contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
            assert_identical(rows_of(result, contact),
                             reference(tmp_path / f"histories/t{k}.parquet", case))


SLOW_RUN = """
import sys, time
import fretwear.bundle.engine as engine
from fretwear.bundle.tasks import run_contact

def slow(task, chunk_size):
    time.sleep(0.3)
    return run_contact(task, chunk_size)

engine.run_contact = slow
engine.run_bundle(sys.argv[1], sys.argv[2], scheduler=sys.argv[3], output=sys.argv[4],
                  part_size=1)
"""


def test_a_killed_run_restarts_where_it_stopped(tmp_path, address):
    manifest, case = write_bundle(tmp_path, oscillator(), 12)
    out = tmp_path / "out"
    script = tmp_path / "slow_run.py"
    script.write_text(textwrap.dedent(SLOW_RUN))
    proc = subprocess.Popen([sys.executable, str(script), str(manifest), str(case), address,
                             str(out)])
    try:
        deadline = time.monotonic() + 120
        while len(list((out / "parts").glob("*.json"))) < 3:
            assert proc.poll() is None, "the run ended before it could be killed"
            assert time.monotonic() < deadline
            time.sleep(0.05)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    finally:
        if proc.poll() is None:
            proc.kill()
    written = {c["contact"] for p in (out / "parts").glob("*.json")
               for c in json.loads(p.read_text())["contacts"]}
    assert 3 <= len(written) < 12
    assert not (out / "table.parquet").exists()
    restarted = run_bundle(manifest, case, scheduler=address, output=out)
    status = restarted.contacts.set_index("contact")["status"]
    assert set(status[status == "skipped"].index) == written
    assert set(status[status == "done"].index) == set(status.index) - written
    fresh = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "fresh")
    pd.testing.assert_frame_equal(restarted.table, fresh.table, check_exact=True)
    stored = pd.read_parquet(out / "table.parquet")
    pd.testing.assert_frame_equal(stored, fresh.table, check_dtype=False, check_exact=True)


def test_cli_joins_the_scheduler_and_exits_1_when_a_contact_failed(tmp_path, address, capsys):
    from fretwear.cli import main

    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    frame = pd.read_csv(manifest)
    frame.loc[1, "history"] = "histories/none.parquet"
    frame["wall_thickness_m"] = 1.09e-3
    frame.to_csv(manifest, index=False)
    out, figs = tmp_path / "out", tmp_path / "figs"
    code = main(["bundle", str(manifest), "--case", str(case), "--scheduler", address,
                 "-o", str(out), "--plot", str(figs)])
    printed = capsys.readouterr()
    assert code == 1, printed.err
    assert "done 2, failed 1, skipped 0 of 3 contacts" in printed.out
    assert "R1C2-AVB: InputError" in printed.out
    for name in ("table.parquet", "errors.csv", "warnings.csv", "summary.csv", "run.json",
                 "dataset.zarr"):
        assert (out / name).exists(), name
    assert pd.read_csv(out / "errors.csv")["contact"].tolist() == ["R1C2-AVB"]
    assert sorted(p.name for p in figs.glob("*.png")) == [
        "bundle_power.png", "bundle_tube_sheet.png", "bundle_worst_depths.png"]
    # a bad manifest: exit 2 with the message, before any cluster is joined
    frame.rename(columns={"tube_row": "tube_rw"}).to_csv(manifest, index=False)
    code = main(["bundle", str(manifest), "--case", str(case), "-o", str(out)])
    assert code == 2
    assert "did you mean 'tube_row'" in capsys.readouterr().err


def _environment(dask_worker) -> dict:
    import dask

    timers = {name: pc.callback_time for name, pc in dask_worker.periodic_callbacks.items()}
    return {**os.environ, "profile": dask.config.get("distributed.worker.profile.enabled"),
            "timers [ms]": timers}


def test_without_a_scheduler_a_local_cluster_is_started(tmp_path, monkeypatch):
    """... with single-threaded numerical libraries, glibc's own malloc thresholds (Dask's
    MALLOC_TRIM_THRESHOLD_ made every block array a fresh mmap: 1e5-sample contacts 11 ms
    instead of 8.5 ms in a worker) and no statistical profiler (docs/bundle.md)."""
    from fretwear.bundle import engine

    seen = []
    close = engine.DaskEngine.close

    def recording_close(self):
        seen.extend(self.client.run(_environment).values())
        close(self)

    monkeypatch.setattr(engine.DaskEngine, "close", recording_close)
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    result = run_bundle(manifest, case, workers=1)  # one process: the cheapest to start
    assert result.stats["workers"] == 1 and result.stats["done"] == 2
    assert len(seen) == 1
    assert "MALLOC_TRIM_THRESHOLD_" not in seen[0] and seen[0]["OMP_NUM_THREADS"] == "1"
    assert seen[0]["profile"] is False  # no stack sampling of the running contacts
    # Dask's background timers slowed (cluster.LOCAL_CLUSTER_CONFIG; Dask's defaults 20, 500
    # and 100 ms): the worker's own periodic callbacks, as it runs them [ms]
    timers = seen[0]["timers [ms]"]
    assert (timers["tick"], timers["monitor"], timers["memory_monitor"]) == (1000, 5000, 500)
    assert_identical(rows_of(result, "R1C1-AVB"),
                     reference(tmp_path / "histories/t0.parquet", case))
