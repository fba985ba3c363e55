"""The engines a bundle runs on: a ``dask.distributed`` cluster (a local one started here, or
one joined by its address or Client) or, for debugging, this process (``scheduler="serial"``).

Each engine submits tasks (``submit``, ``map``: one graph for many), yields their results as
they finish or all at once (``results``) and closes what it started (``close``).
:func:`fretwear.bundle.engine.run_bundle` decides what to submit.
"""

from __future__ import annotations

import contextlib
import functools
import logging
import os
import signal
import threading
from typing import Any

from fretwear.bundle.datasets import require
from fretwear.bundle.tasks import pickled, unpickled
from fretwear.errors import InputError, KeywordError

#: Dask settings of the local cluster: tasks sent to the workers' queues at once; the workers'
#: malloc left to glibc's defaults (Dask sets MALLOC_TRIM_THRESHOLD_ before spawning them); no
#: statistical profiler in the workers (it samples the running task's stack every 10 ms for the
#: dashboard's profile page: the same contacts took 4-14 % longer in a worker with it than in a
#: plain process, 1-4 % without it; docs/bundle.md); and Dask's background timers slowed (issue
#: 28): the event-loop health check every 1 s (20 ms: it woke every worker 50 times a second), the
#: system monitor (the dashboard's CPU/memory/disk samples) every 5 s (500 ms), the memory
#: monitor (a worker's spill/pause, the nanny's terminate at 95 %) every 500 ms (100 ms). An idle
#: 2-worker cluster used 56 ms of CPU a second in the client's process (scheduler, nannies,
#: client) and 20 ms in each worker; with these 9 and 4 ms, each worker woken 4 times a second.
LOCAL_CLUSTER_CONFIG = {"distributed.scheduler.worker-saturation": "inf",
                        "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None,
                        "distributed.worker.profile.enabled": False,
                        "distributed.admin.tick.interval": "1s",
                        "distributed.admin.system-monitor.interval": "5s",
                        "distributed.worker.memory.monitor-interval": "500ms"}

@contextlib.contextmanager
def _sigint_ignored():
    """SIGINT ignored in this process (the main thread only; elsewhere nothing changes)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


class DeferredCall:
    """A call of the serial engine, run when its value is first asked for."""

    def __init__(self, fn, args) -> None:
        self._call: tuple | None = (fn, args)
        self._value: Any = None

    def value(self) -> Any:
        if self._call is not None:
            fn, args = self._call
            self._value = fn(*[a.value() if isinstance(a, DeferredCall) else a for a in args])
            self._call = None
        return self._value


class SerialEngine:
    """The engine without Dask: tasks run in this process, one contact after the other as the
    results are asked for (so parts are written as contacts finish) (``scheduler="serial"``)."""

    workers = 1

    def submit(self, fn, *args, key: str = "", retries: int = 0):
        return DeferredCall(fn, args)

    def map(self, fn, items, *args, keys, retries: int = 0):
        return [DeferredCall(fn, (item, *args)) for item in items]

    def results(self, handles, streaming: bool = True):
        for h in handles:
            yield h, h.value()

    def close(self):
        pass


class DaskEngine:
    """The engine on a dask.distributed cluster (local, or joined by its address)."""

    def __init__(self, scheduler, workers: int | None) -> None:
        dask = require("dask")
        distributed = require("distributed")
        self._cluster = None
        if scheduler is None:
            n = workers or os.cpu_count() or 1
            # every task goes to a worker's queue at once (no scheduler-side queuing): a short
            # task then starts without a round trip to the scheduler; and glibc's malloc keeps
            # its own mmap threshold: Dask's MALLOC_TRIM_THRESHOLD_ fixes it, so that every
            # block array is a fresh mmap whose pages fault in (a 1e5-sample contact took
            # 11 ms in a worker against 8.5 ms without it, 7 ms in a plain process;
            # docs/bundle.md)
            # (an earlier Dask nanny of this process put MALLOC_TRIM_THRESHOLD_ in os.environ,
            # which the workers would inherit: left out while they are spawned)
            trim = os.environ.pop("MALLOC_TRIM_THRESHOLD_", None)
            try:
                # Ctrl-C reaches the whole process group: the worker processes (spawned
                # ignoring SIGINT, as they inherit it) leave it to this client, which writes
                # what it received and closes them (without this each printed a traceback)
                with dask.config.set(LOCAL_CLUSTER_CONFIG), _sigint_ignored():
                    self._cluster = distributed.LocalCluster(
                        n_workers=n, threads_per_worker=1, processes=True,
                        dashboard_address=":0", silence_logs=logging.ERROR)
            finally:
                if trim is not None:
                    os.environ["MALLOC_TRIM_THRESHOLD_"] = trim
            self.client = distributed.Client(self._cluster)
        elif isinstance(scheduler, distributed.Client):
            self.client = scheduler
        else:
            if workers is not None:
                raise KeywordError("workers applies to the local cluster started when no "
                                   "scheduler is given; an existing cluster has its own workers")
            try:
                self.client = distributed.Client(scheduler, timeout="30s")
            except OSError as exc:
                raise InputError(f"cannot reach the Dask scheduler {scheduler!r} ({exc}); start "
                                 "it (dask scheduler, or a dask-jobqueue cluster) or leave "
                                 "--scheduler out for a local cluster") from None
        self._own_client = not isinstance(scheduler, distributed.Client)
        self._as_completed = distributed.as_completed
        self.workers = max(1, len(self.client.scheduler_info().get("workers", {})))

    def submit(self, fn, *args, key: str, retries: int = 2):
        return self.client.submit(fn, *args, key=key, pure=False, retries=retries)

    def map(self, fn, items, *args, keys, retries: int = 2):
        # one graph for many contacts: one message to the scheduler, not one per contact
        # the records come back pickled in one piece (transport.pickled; unpickled in results)
        if not items:
            return []
        return self.client.map(functools.partial(pickled, fn), items,
                               *[[a] * len(items) for a in args], key=keys, pure=False,
                               retries=retries)

    def results(self, handles, streaming: bool = True):
        # the futures finished since the last look, their results fetched in one gather (one
        # round trip per batch, not per contact); a task lost for good (its workers died too
        # often) gives its exception as the result. Not streaming (nobody watches the
        # progress, no part to write): every result fetched in one gather once all are done
        # (the client's CPU for 500 contacts in 16 tasks 0.18 -> 0.14 s, taken from the
        # workers' cores on a small machine)
        batches = self._as_completed(handles).batches() if streaming else \
            [self._wait(handles)]
        for batch in batches:
            finished = [f for f in batch if f.status == "finished"]
            values = self.client.gather(finished) if finished else []
            for future, value in zip(finished, values, strict=True):
                yield future, unpickled(value) if isinstance(value, bytes) else value
            for future in batch:
                if future.status != "finished":
                    try:
                        error = future.exception()
                    except Exception as exc:  # noqa: BLE001 - cancelled
                        error = exc
                    yield future, error
                future.release()

    def _wait(self, handles):
        require("distributed").wait(handles)
        return handles

    def close(self):
        if self._own_client:
            self.client.close()
        if self._cluster is not None:
            self._cluster.close()


def open_engine(scheduler, workers):
    if isinstance(scheduler, str) and scheduler.lower() == "serial":
        if workers not in (None, 1):
            raise KeywordError("scheduler='serial' runs in this process: workers must be 1")
        return SerialEngine()
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise KeywordError(f"workers must be an integer >= 1, got {workers!r}")
    return DaskEngine(scheduler, workers)
