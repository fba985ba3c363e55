"""Running a bundle on Dask: one task per contact, long histories split in time chunks.

:func:`run_bundle` reads the manifest, builds every contact's task on the client (the base case
plus the row's overrides, validated once), skips the contacts an earlier run already computed
with the same inputs, and submits the rest to a ``dask.distributed`` cluster: a local one (one
single-threaded worker process per core) unless a scheduler address is given. A history longer
than ``chunk_size`` samples in a file that can be read by row range (Parquet, a Zarr/NetCDF
store) is split into chunks: each chunk's :class:`~fretwear.power.PowerAccumulator` partial
state is computed by its own task, the states merge in a tree (``split_every`` per node) and a
last task builds the wear table, so one huge contact also spreads over the workers. Results are
written part by part as they arrive.
"""

from __future__ import annotations

import os
import stat
import time
import uuid
from collections.abc import Callable, Mapping
from typing import Any

from fretwear.bundle.arrivals import (  # noqa: F401 - PART_SECONDS: its home until now
    PART_SECONDS,
    PART_SIZE,
    Arrivals,
    failed,
    kept,
)
from fretwear.bundle.cases import ROW_ERRORS, ContactTask, build_task, check_base_case
from fretwear.bundle.cluster import (
    LOCAL_CLUSTER_CONFIG,  # noqa: F401 - its home until now
    DaskEngine,
    SerialEngine,
    open_engine,
)
from fretwear.bundle.contacts_info import ContactRows
from fretwear.bundle.datasets import require, store_length
from fretwear.bundle.frozen import gc_frozen
from fretwear.bundle.interrupted import BundleInterrupted, interrupted  # noqa: F401 - its home until now
from fretwear.bundle.manifest import Manifest, read_manifest
from fretwear.bundle.manifest_history import check_histories
from fretwear.bundle.outputs import assemble, identity_hash, outputs_digest  # noqa: F401
from fretwear.bundle.result import BundleResult, check_limit
from fretwear.bundle.store import (
    DATASET_FORMATS,
    TABLE_FORMATS,
    OutputDirectory,
)
from fretwear.bundle.tasks import (
    chunk_state,
    finish_contact,
    merge_states,
    needs_whole_history,
    run_contact,
    run_contacts,
    time_bounds,
)
from fretwear.bundle.worker_parts import PartTarget, run_contacts_into
from fretwear.errors import KeywordError
from fretwear.history import DEFAULT_CHUNK_SIZE
from fretwear.workflows.case_files import load_case, validate_case

#: Tasks per worker when contacts are grouped (:func:`task_sizes`; measured on 500 contacts ×
#: 1e5 samples, 2 workers: 4, 6, 8, 12, 16 per worker took 1.39, 1.40, 1.39, 1.51, 1.50 s).
TASKS_PER_WORKER = 8
#: Largest group of contacts in one task (:func:`task_sizes`): beyond 8 groups a worker of this
#: size, a larger bundle makes more groups, so that a task's results (progress, a part, what a
#: dead worker's retry recomputes, a worker's memory of finished records) stay about a part
#: (:data:`PART_SIZE`; never more than the run's ``part_size``) however large the bundle
#: (50 000 contacts on 2 workers: 3 125 a task without it). 250, not 100 (issue 28, 2x10^4
#: contacts of 10^3 samples, alternated: the client's CPU 0.209-0.246 -> 0.182-0.213 ms a
#: contact, the workers' 0.588-0.73 -> 0.55-0.69 ms: each task costs the scheduler, the client
#: and its worker some milliseconds, its part's file and messages among them; 500 and 1 000
#: measured as 250).
GROUP_SIZE = 250
#: Contacts to compute beyond which the results are fetched as each task finishes even when
#: nobody watches (no progress, no output directory): below, one gather at the end spares the
#: client some CPU (500 contacts: 0.18 -> 0.14 s); above, the workers would hold every finished
#: record until the end (some 12 kB a contact of 48 rows: 600 MB for 50 000), not a task's.
GATHER_AT_END = 2_000
#: Parquet files smaller than this many bytes per chunk sample are not inspected for splitting
#: (the time column alone, float64 strictly increasing, takes about 8 bytes per sample).
_BYTES_PER_SAMPLE = 6


def _base_case(case) -> dict[str, Any]:
    if case is None:
        return {}
    if isinstance(case, Mapping):
        directory = case.get("_directory")
        out = validate_case({k: v for k, v in case.items() if k != "_directory"},
                            source="base case")
        if directory is not None:
            out["_directory"] = directory
        return out
    return load_case(case)


def plan_chunks(task: ContactTask, chunk_size: int) -> list[tuple[int, int]] | None:
    """Row ranges ``[a, b)`` of a contact to be split (consecutive ranges share one sample, as
    :func:`fretwear.io.iter_history_chunks`), or None to compute it in one task.

    Only histories readable by row range are split (Parquet files, Zarr/NetCDF stores), and not
    for a law that needs the whole history (KWU-EPRI's classes without both FNOR_MAXI and
    VTAN_MAXI; with both, the class counts merge with the power's state).
    """
    ref = task.history
    n = None
    if ref.kind == "store":
        n = store_length(ref)
    elif ref.kind == "file" and ref.node is None \
            and task.read_options.get("format", "parquet") == "parquet" \
            and (_file_size(ref.path) if task.file_bytes is None else task.file_bytes) \
            > _BYTES_PER_SAMPLE * chunk_size:
        with open(ref.path, "rb") as handle:
            if handle.read(4) != b"PAR1":
                return None
        n = require("pyarrow.parquet").ParquetFile(ref.path).metadata.num_rows
    if n is None or n <= chunk_size or needs_whole_history(task):
        return None
    task.samples = n
    return [(a, min(a + chunk_size, n)) for a in range(0, n - 1, chunk_size - 1)]


def _file_size(path) -> int:
    """The size [bytes] of the regular file ``path``, -1 for anything else (missing, a
    directory, a name the system refuses): one ``os.stat`` a contact, no ``Path``."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return -1
    return st.st_size if stat.S_ISREG(st.st_mode) else -1


def _submit(engine, task: ContactTask, chunks, chunk_size: int, split_every: int,
            retries: int, tag: str):
    """The handle of a contact's final record (a tree of chunk tasks for a long contact)."""
    name = f"{task.contact}-{tag}"
    if chunks is None:
        return engine.submit(run_contact, task, chunk_size, key=f"contact-{name}",
                             retries=retries)
    try:
        bounds = time_bounds(task, task.samples)
    except Exception as exc:  # noqa: BLE001 - reading fails: let one task report it
        del exc
        return engine.submit(run_contact, task, chunk_size, key=f"contact-{name}",
                             retries=retries)
    level = [engine.submit(chunk_state, task, a, b, bounds, key=f"chunk-{name}-{k}",
                           retries=retries) for k, (a, b) in enumerate(chunks)]
    depth = 0
    while len(level) > 1:
        depth += 1
        level = [engine.submit(merge_states, *level[i:i + split_every],
                               key=f"merge-{name}-{depth}-{i}", retries=retries)
                 for i in range(0, len(level), split_every)]
    return engine.submit(finish_contact, task, level[0], key=f"finish-{name}", retries=retries)


def task_sizes(contacts: int, workers: int, largest: int | None = None) -> list[int]:
    """How many contacts each Dask task computes, in submission order.

    One contact per task for a bundle of fewer than :data:`TASKS_PER_WORKER` contacts per
    worker. Otherwise ``TASKS_PER_WORKER × workers`` groups, or more (a multiple of the
    workers) so that none holds more than ``largest`` contacts (default :data:`GROUP_SIZE`;
    :func:`run_bundle` gives the smaller of it and its ``part_size``, so that a group's rows
    make one part its worker writes), their sizes differing by
    one at most, the larger ones spread evenly along the order (:func:`_spread`): the cost of a
    task (the scheduler's and the client's CPU, shared with the workers on a small machine:
    about 4 ms a task) is spread over the group, and the scheduler, which gives each worker a
    consecutive run of the tasks before it knows their durations, gives every worker the same
    number of contacts within one (500 contacts on 2 workers: 250 each; with the larger groups
    first, 252 and 248). Each contact keeps its own record, warnings and failure. (A last group
    holding the remainder, 16 groups of 31 and one of 4, left one worker 31 contacts more when
    the groups were dealt in two batches; guided sizes, large first and single contacts last,
    were measured slower.)

    Examples
    --------
    >>> task_sizes(5, 2)
    [1, 1, 1, 1, 1]
    >>> sizes = task_sizes(500, 2)
    >>> len(sizes), sizes[:4], sum(sizes[:8]), sum(sizes[8:])
    (16, [31, 31, 31, 32], 250, 250)
    >>> sizes = task_sizes(50_000, 2)
    >>> len(sizes), max(sizes), sum(sizes)
    (200, 250, 50000)
    >>> sizes = task_sizes(50_000, 2, largest=100)
    >>> len(sizes), max(sizes), sum(sizes)
    (500, 100, 50000)
    """
    w = max(1, workers)
    if contacts < TASKS_PER_WORKER * w:
        return [1] * contacts
    most = max(1, GROUP_SIZE if largest is None else largest)
    groups = w * max(TASKS_PER_WORKER, -(-contacts // (most * w)))
    size, rest = divmod(contacts, groups)
    return [size + extra for extra in _spread(rest, groups)]


def _spread(rest: int, count: int) -> list[int]:
    """``count`` zeros and ones holding ``rest`` ones spread evenly (one where ``(g + 1) rest /
    count`` passes an integer): each run of ``count / k`` consecutive entries holds ``rest / k``
    ones within one.

    >>> _spread(4, 16)
    [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]
    """
    return [int((g + 1) * rest // count > g * rest // count) for g in range(count)]


def slices(items: list, sizes: list[int]) -> list[list]:
    """``items`` cut into consecutive groups of ``sizes`` items (:func:`task_sizes`).

    >>> slices(list(range(7)), [2, 3, 2])
    [[0, 1], [2, 3, 4], [5, 6]]
    """
    out, start = [], 0
    for size in sizes:
        out.append(items[start:start + size])
        start += size
    return out


def submitted_slices(items: list, sizes: list[int], order: list[int]) -> list[list]:
    """``items`` cut into consecutive slices, the ``k``-th in the manifest's order submitted
    ``order.index(k)``-th: the slices in submission order, the ``j``-th holding ``sizes[j]``
    items (:func:`task_sizes` spreads the larger ones along the submission, so that each
    worker's run holds the same number of contacts within one).

    >>> submitted_slices(list(range(7)), [2, 2, 3], [0, 2, 1])
    [[0, 1], [5, 6], [2, 3, 4]]
    """
    along = [0] * len(sizes)
    for size, k in zip(sizes, order, strict=True):
        along[k] = size
    cut = slices(items, along)
    return [cut[k] for k in order]


def worker_order(count: int, workers: int) -> list[int]:
    """The order in which ``count`` groups, consecutive slices of the manifest (:func:`slices`),
    are submitted to ``workers`` workers.

    Dask gives each worker a consecutive run of one map's tasks in submission order (the first
    ``count / workers`` to one worker, and so on; ``worker-saturation: inf``), each worker
    computing its run in that order. The groups are dealt to the workers as cards are dealt,
    back and forth (round ``r`` of ``workers`` groups to the workers 0, 1, ... when ``r`` is
    even, ..., 1, 0 when odd), each worker's groups in the manifest's order. Every worker's
    share then samples the whole manifest: when the cost grows along it (a manifest sorted by
    tube row, the rows toward the U-bend impacting more), the workers' shares are the same
    within a group's (consecutive halves gave one worker 0.625 of a cost growing linearly from
    1 to 2 against 0.875 to the other). And the workers compute the groups about in the
    manifest's order, each round's ``workers`` groups together: the parts arrive in the
    manifest's order within a round, so that the table is written as they arrive
    (:class:`fretwear.bundle.table_file.PrefixTable`). (Until issue 28 the contacts were dealt
    one by one into the groups, each group sampling the whole manifest: balanced too, but
    every part then held contacts from all along the manifest, and the table could only be
    sorted out of the parts once all had arrived.)

    Examples
    --------
    >>> worker_order(8, 2)
    [0, 3, 4, 7, 1, 2, 5, 6]
    >>> worker_order(6, 3)
    [0, 5, 1, 4, 2, 3]
    """
    w = max(1, workers)
    hands: list[list[int]] = [[] for _ in range(w)]
    for k in range(count):
        r, j = divmod(k, w)
        hands[j if r % 2 == 0 else w - 1 - j].append(k)
    return [k for hand in hands for k in hand]


def run_bundle(manifest, case=None, *, scheduler=None, workers: int | None = None,
               output: str | os.PathLike | None = None, force: bool = False,
               chunk_size: int = DEFAULT_CHUNK_SIZE, split_every: int = 8, retries: int = 2,
               table_format: str = "parquet", dataset_format: str | None = None,
               part_size: int = PART_SIZE,
               progress: Callable[[int, int, dict], None] | None = None,
               limit: float | None = None) -> BundleResult:
    """Compute the wear table of every contact of a bundle, on Dask.

    Parameters
    ----------
    manifest : path-like, DataFrame, xarray.Dataset or Manifest
        The contacts (:func:`fretwear.bundle.read_manifest`): a CSV/Parquet/TOML manifest, a
        Code_Aster table of several nodes, a Zarr/NetCDF store or Dataset ``(contact, time)``.
    case : path-like or mapping, optional
        The base case (TOML case file or its dict) every contact starts from; the manifest's
        columns override its keys per contact.
    scheduler : str or distributed.Client, optional
        None: a local cluster of ``workers`` single-threaded worker processes (default one per
        core); ``"tcp://host:port"``: join that cluster; a Client: use it; ``"serial"``: no
        Dask, in this process (debugging).
    workers : int, optional
        Worker processes of the local cluster.
    output : path-like, optional
        Output directory (parts as contacts finish, then ``table``, ``dataset``, ``errors.csv``,
        ``warnings.csv``, ``summary.csv``, ``run.json``). A run into a directory holding an
        earlier run's parts skips the contacts whose inputs did not change. None: nothing is
        written.
    force : bool
        Recompute every contact even if an earlier run has it.
    chunk_size : int
        Samples per chunk of a long history (>= 2): the memory of a task is bounded by it.
    split_every : int
        Partial states merged per node of the tree (>= 2).
    retries : int
        Dask retries of a task whose worker died (the scheduler's ``allowed-failures`` also
        applies).
    table_format : str
        ``"parquet"`` or ``"csv"`` (table and parts).
    dataset_format : str, optional
        ``"zarr"`` (default when zarr is installed) or ``"netcdf"``.
    part_size : int
        Contacts per part file (>= 1; default 250), and the most in one Dask task: a task's
        contacts are written by its worker as one part.
    progress : callable, optional
        ``progress(done, total, record)`` after each contact (done counts skipped ones too).
    limit : float, optional
        Depth limit as a fraction of the wall, 0 < limit <= 1 [-], of the ``summary.csv``
        written to ``output`` (as :meth:`BundleResult.summary`'s ``limit``; recorded as
        ``limit`` in ``run.json``). Default: each contact's ``depth_limit`` (``null`` in
        ``run.json``).

    Returns
    -------
    BundleResult

    Raises
    ------
    KeywordError, InputError
        A bad manifest (unknown column, duplicated id), base case or option; a contact's own
        problems never raise: they are rows of ``BundleResult.errors``.
    BundleInterrupted
        A :class:`KeyboardInterrupt` (Ctrl-C) during the run: the results received are written
        as a part first; ``written`` counts the contacts in the output directory, which a run
        with the same inputs skips.

    Notes
    -----
    A contact computed in one task gives the rows of :func:`fretwear.table.wear_table` (that is
    :func:`fretwear.table.wear_table_from_case`) on the same history and case bit for bit. A
    contact split into chunks sums its partial integrals in a different order (theory §2: the
    reduction is exact, the floating-point sum is reassociated), so its power agrees to rounding
    (~1e-16 relative), not bit for bit.
    """
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 2:
        raise KeywordError(f"chunk_size must be an integer >= 2 samples, got {chunk_size!r}")
    if isinstance(split_every, bool) or not isinstance(split_every, int) or split_every < 2:
        raise KeywordError(f"split_every must be an integer >= 2, got {split_every!r}")
    if isinstance(part_size, bool) or not isinstance(part_size, int) or part_size < 1:
        raise KeywordError(f"part_size must be an integer >= 1, got {part_size!r}")
    if table_format not in TABLE_FORMATS:
        raise KeywordError(f"table_format {table_format!r}: choose one of {TABLE_FORMATS}")
    if dataset_format is not None and dataset_format not in DATASET_FORMATS:
        raise KeywordError(f"dataset_format {dataset_format!r}: choose one of {DATASET_FORMATS}")
    check_limit(limit)
    with gc_frozen():
        return _run(manifest, case, scheduler, workers, output, force, chunk_size, split_every,
                    retries, table_format, dataset_format, part_size, progress, limit)


def _run(manifest, case, scheduler, workers, output, force, chunk_size, split_every, retries,
         table_format, dataset_format, part_size, progress, limit) -> BundleResult:
    """:func:`run_bundle` once its options are checked."""
    started = time.perf_counter()
    man = manifest if isinstance(manifest, Manifest) else read_manifest(manifest)
    base = _base_case(case)
    if "_directory" not in base:
        base["_directory"] = str(man.directory)
    cases: dict = {}
    # a base case that fails for every contact stops here, said once (the case it builds goes
    # into the cache the tasks use), before the output directory is made: a run that computes
    # nothing leaves nothing behind (an empty parts/ folder before, found by a user's trial)
    check_histories(man, base)  # no history and no power anywhere: one error, not one a contact
    check_base_case(base, man.rows, man.source, cases)
    store = None if output is None else OutputDirectory(output, table_format=table_format)
    # every contact's latest record in the directory: the ones to skip (unless force), and
    # the earlier rows a contact failing this run keeps (kept, even with force)
    earlier = {} if store is None else store.previous()
    previous = {} if force else earlier
    records: dict[str, dict[str, Any]] = {}
    pending: list[ContactTask] = []  # the rows made tasks (an interrupt counts them once done)
    built: dict[str, Any] = {}  # contact -> its WearCase, built once here
    arrivals = None
    engine = None
    try:
        try:
            # the rows built and submitted wave after wave (:func:`waves`): the workers
            # compute the first contacts while the client builds the others (issue 28: at
            # 10^5 contacts the tasks' build and submission, 2 s, left both workers idle)
            handles: dict[int, tuple[Any, list[ContactTask], PartTarget | None]] = {}
            startup = 0.0
            for k, (start, stop) in enumerate(waves(len(man.rows))):
                wave: list[ContactTask] = []
                _build_tasks(man.rows[start:stop], man.source, base, chunk_size, cases,
                             (earlier, previous), records, wave, built)
                pending += wave
                if not wave:
                    continue
                if engine is None:
                    before = time.perf_counter()
                    engine = open_engine(scheduler, workers)
                    startup = time.perf_counter() - before
                handles.update(_submit_all(engine, wave, store, chunk_size, split_every,
                                           retries, part_size,
                                           f"contacts{k}" if k else "contacts"))
            # what receives the results made once every wave is submitted, while the workers
            # compute (the identity frame and the table's writer: 0.2-0.4 s at 10^5 contacts,
            # before the first task earlier): the identity's share of the outputs' digest
            # too, and the rows of BundleResult.contacts made as the records are final, not
            # after the last one
            identity = man.identity_frame()
            identity["contact"] = identity["contact"].astype(str)
            hashed = None if store is None else identity_hash(identity)
            order = [r.contact for r in man.rows]
            made = ContactRows(order, built)
            arrivals = Arrivals(store, records, earlier, len(man.rows), progress, part_size,
                                None if store is None else store.table_writer(
                                    order, identity, dataset_format))
            arrivals.start()
            engine = engine or SerialEngine()
            streaming = (store is not None or progress is not None
                         or len(pending) > GATHER_AT_END)
            for handle, value in engine.results([h for h, _, _ in handles.values()], streaming):
                _, group, target = handles[id(handle)]
                arrivals.receive(group, value, target)
                # final once in a part (its attrs then shared with the others'), or at once
                made.add(r for r in map(records.get, (t.contact for t in group))
                         if store is None or r.get("part"))
            arrivals.close()
            workers_used = engine.workers
        finally:
            if engine is not None:
                engine.close()
        return assemble(man, records, store, (started, startup), workers_used,
                        dataset_format, limit, built, identity, arrivals.table, hashed, made)
    except KeyboardInterrupt as exc:  # Ctrl-C: keep what arrived, say what is written
        if arrivals is not None:
            arrivals.abort()
        raise interrupted(store, records, [] if arrivals is None else arrivals.buffer,
                           len(man.rows), previous, man, {t.contact for t in pending}) from exc
    except BaseException:
        if arrivals is not None:
            arrivals.abort()
        raise


#: Manifest rows of the first wave (:func:`waves`), and of the largest.
FIRST_WAVE = 1_000
LARGEST_WAVE = 16_000


def waves(rows: int) -> list[tuple[int, int]]:
    """The manifest's rows ``[start, stop)`` built and submitted together, in order: all at
    once up to :data:`FIRST_WAVE` rows; beyond, a first wave of that many and each next one
    twice the one before, up to :data:`LARGEST_WAVE` rows. Each wave's contacts are grouped
    and dealt to the workers as a whole bundle's are (:func:`task_sizes`,
    :func:`worker_order`): the workers start on the first wave while the client builds the
    next (building and submitting a row's task costs the client some 30 us: 3 s at 10^5
    contacts before any worker started), and every wave is shared evenly between them. (A
    task of the first waves holds fewer contacts than a whole bundle's would: 63 on 2
    workers.)

    Examples
    --------
    >>> waves(800)
    [(0, 800)]
    >>> waves(50_000)[:4], waves(50_000)[-2:]
    ([(0, 1000), (1000, 3000), (3000, 7000), (7000, 15000)], [(31000, 47000), (47000, 50000)])
    """
    out, start, size = [], 0, FIRST_WAVE
    while start < rows:
        stop = rows if rows - start <= size else start + size
        out.append((start, stop))
        start, size = stop, min(2 * size, LARGEST_WAVE)
    return out


def _build_tasks(rows: list, source: str, base: dict[str, Any], chunk_size: int, cases: dict,
                 directory: tuple[dict, dict], records: dict[str, dict[str, Any]],
                 pending: list[ContactTask], built: dict[str, Any]) -> None:
    """The task of every manifest row of ``rows`` into ``pending`` and its WearCase into
    ``built``; into ``records`` the rows whose case fails (their earlier rows kept where an
    earlier run computed them) and those skipped (``directory``: the earlier runs' records,
    and those to skip: none with force)."""
    earlier, previous = directory
    for row in rows:
        try:
            task = build_task(base, row, source, chunk_size=chunk_size, cache=cases)
        except ROW_ERRORS as exc:  # with the warnings its case raised before failing
            said = [list(w) for w in getattr(exc, "case_warnings", ())]
            records[row.contact] = kept(failed(
                ContactTask(row.contact, row.history, {}, warnings=said), exc),
                earlier.get(row.contact))
            continue
        built[row.contact] = task.wear_case()  # carried to the result (BundleResult.cases)
        old = previous.get(row.contact)
        if old is not None and old.get("status") == "done" and old.get("key") == task.key:
            records[row.contact] = {**old, "status": "skipped"}
        else:
            pending.append(task)


def _submit_all(engine, pending: list[ContactTask], store: OutputDirectory | None,
                chunk_size: int, split_every: int, retries: int, part_size: int,
                name: str = "contacts"
                ) -> dict[int, tuple[Any, list[ContactTask], PartTarget | None]]:
    """Submit every pending contact: a long one as its tree of chunk tasks (:func:`plan_chunks`),
    the others in groups, consecutive slices of the manifest (:func:`task_sizes`,
    :func:`slices`, submitted in :func:`worker_order`), their rows written by their workers
    where they see the output directory. Returns ``{id(handle): (handle, its contacts, the
    part its worker writes or None)}``. ``name`` begins the groups' keys: Dask's task group
    (each :func:`waves`' own: the scheduler deals a group's tasks to the workers in runs of
    its size over their number, counting the tasks of earlier waves still held in one group,
    which gave a whole wave to one worker)."""
    tag = uuid.uuid4().hex[:8]
    handles: dict[int, tuple[Any, list[ContactTask], PartTarget | None]] = {}
    whole = []
    for task in pending:
        try:
            chunks = plan_chunks(task, chunk_size)
        except Exception as exc:  # noqa: BLE001 - an unreadable file: one task reports it
            del exc
            chunks = None
        if chunks is None:
            whole.append(task)
            continue
        handle = _submit(engine, task, chunks, chunk_size, split_every, retries, tag)
        handles[id(handle)] = (handle, [task], None)
    # the contacts computed whole, in groups submitted in one map: one message to the
    # scheduler, which deals the groups out evenly by count (submitting each worker's first
    # group early, while the client built the others, left one worker 9 groups and the
    # other 7)
    sizes = task_sizes(len(whole), engine.workers, min(GROUP_SIZE, part_size)) \
        if isinstance(engine, DaskEngine) else [1] * len(whole)
    targets = None
    if all(size == 1 for size in sizes):
        groups = [[t] for t in whole]
        mapped = engine.map(run_contact, whole, chunk_size,
                            keys=[f"contact-{t.contact}-{tag}" for t in whole], retries=retries)
    else:
        order = worker_order(len(sizes), engine.workers)
        groups = submitted_slices(whole, sizes, order)
        keys = [f"{name}-{g[0].contact}-{len(g)}-{tag}" for g in groups]
        targets = _part_targets(store, groups, part_size)
        mapped = engine.map(run_contacts, groups, chunk_size, keys=keys,
                            retries=retries) if targets is None else \
            engine.map(run_contacts_into, list(zip(groups, targets, strict=True)),
                       chunk_size, keys=keys, retries=retries)
    for k, (handle, group) in enumerate(zip(mapped, groups, strict=True)):
        handles[id(handle)] = (handle, group, None if targets is None else targets[k])
    return handles


def _part_targets(store: OutputDirectory | None, groups: list[list[ContactTask]],
                  part_size: int) -> list[PartTarget] | None:
    """Each group's part, its rows written by its worker (:mod:`fretwear.bundle.worker_parts`),
    where there is an output directory and a group is no larger than ``part_size``; else
    None (the client writes the parts)."""
    if store is None or not groups or max(len(g) for g in groups) > part_size:
        return None
    token = store.share_with_workers()
    return [PartTarget(str(store.parts), store.new_stem(), store.table_format, token)
            for _ in groups]
