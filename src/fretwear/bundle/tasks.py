"""What a worker runs: one contact, or one time chunk of a long contact, and their merge.

Every function here takes plain picklable values and returns a *record* (a dict): the contact's
wear table or partial power state, its warnings (captured inside the task, one list per
contact) and, when it failed, the error class and message. Nothing raises out of a task for a
bad input: the batch goes on and the contact is reported in ``BundleResult.errors``.

Warnings are captured with :func:`warnings.catch_warnings`, whose state is global to a process;
a lock makes the tasks of one worker process take turns, so a worker running several threads
cannot mix two contacts' warnings (the local cluster runs one thread per worker process).
"""

from __future__ import annotations

import contextlib
import functools
import threading
import time
import warnings
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.cases import ContactTask
from fretwear.bundle.datasets import frame_of, require, store_arrays
from fretwear.bundle.plain import interned, plain
from fretwear.bundle.transport import (  # noqa: F401 - their home until now
    blocked,
    pickled,
    unblocked,
    unpickled,
)
from fretwear.io import open_source, read_history
from fretwear.io.channels import build_history, resolve_columns, resolve_units
from fretwear.io.geometry_units import check_against_geometry
from fretwear.io.prefetch import prefetch
from fretwear.laws import get_law
from fretwear.power import PowerAccumulator, PowerResult, wear_power
from fretwear.table import wear_table_columns
from fretwear.table.batch import batched, sector_tables

_LOCK = threading.Lock()
#: Table attributes kept in a contact's record (JSON-ready; the power statistics are dropped).
_ATTRS = ("contact_type", "dimensions", "law", "coefficients_mobile", "coefficients_obstacle",
          "materials", "coefficient_sources", "sector_edges", "sector_coefficients",
          "time_scale", "origin", "tube_replacement", "wall_thickness", "depth_limit")


#: The power's values kept in a contact's record (its statistics dropped).
_POWER = ("total", "blocks", "spread", "t_start", "t_end", "duration", "sectors")


def _attrs(attrs: dict[str, Any], task: ContactTask) -> dict[str, Any]:
    """A record's ``attrs``: the table's :data:`_ATTRS` and the power's :data:`_POWER`, JSON
    ready (:func:`plain`). ``attrs["power"]`` is the table's power dict, or the PowerResult
    itself (:func:`_wear_table`: its values read without its statistics' dict, the same once
    made plain). The case's own values (:func:`_case_attrs`) made plain once per case and
    shared by its contacts' records (the client shares them too, ``PartStore.compact``)."""
    out = dict(_case_attrs(attrs, task.wear_case()))
    for k in _CONTACT_ATTRS:
        out[k] = interned(k, plain(attrs.get(k)))
    power = attrs.get("power") or {}
    get = power.get if isinstance(power, dict) else functools.partial(getattr, power)
    out["power"] = {k: plain(get(k)) for k in _POWER}
    if not power and task.power is not None:  # a given power [W] (power.value_W): its total
        out["power"]["total"] = float(task.power)
    out["time_unit"] = task.time_unit
    return {k: out[k] for k in (*_ATTRS, "power", "time_unit")}


#: The table attributes that may differ between the contacts of one case: the coefficients
#: (a KWU-EPRI intensity from each contact's history, and its source) and the sector edges (the
#: power's, where the case has no sectors).
_CONTACT_ATTRS = ("coefficients_mobile", "coefficients_obstacle", "coefficient_sources",
                  "sector_edges")


def _case_attrs(attrs: dict[str, Any], case) -> dict[str, Any]:
    """The plain (:func:`plain`) values of the :data:`_ATTRS` a table of ``case`` takes from
    the case alone (its type, dimensions, law, materials, time scale, origin, replacement, wall;
    :func:`fretwear.table.wear_table_columns`), made from the first table of the case and kept
    on it (:meth:`fretwear.table.WearCase.derived`): shared by its contacts' records."""
    return case.derived("record attrs", lambda: {k: plain(attrs.get(k)) for k in _ATTRS
                                                 if k not in _CONTACT_ATTRS})


@contextlib.contextmanager
def captured():
    """Run a block with this process's warnings recorded (one task at a time per process)."""
    with _LOCK, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield caught


def _warning_list(caught) -> list[list[str]]:
    return [list(x) for x in dict.fromkeys(
        (w.category.__name__, str(w.message)) for w in caught)]


def _with_case_warnings(task: ContactTask, caught: list[list[str]]) -> list[list[str]]:
    """The warnings of the contact's case (raised in the client while it was built) first,
    then the task's own, each once."""
    return [list(w) for w in dict.fromkeys(tuple(w) for w in [*task.warnings, *caught])]


def _record(task: ContactTask, *, status: str, table=None, caught=(), error=None,
            samples: int = 0, seconds: float = 0.0, state=None) -> dict[str, Any]:
    """A task's record; ``table`` is ``(columns, attrs)`` of
    :func:`fretwear.table.wear_table_columns`, sent as :func:`pack` lays a table out."""
    columns, attrs = (None, None) if table is None else table
    record = {"contact": task.contact, "key": task.key, "status": status,
            "table": None if columns is None else {"columns": list(columns),
                                                    "arrays": list(columns.values())},
            "warnings": _with_case_warnings(task, _warning_list(caught)), "error": error,
            "samples": int(samples),
            "seconds": seconds, "attrs": None if attrs is None else _attrs(attrs, task),
            "state": state}
    if status == "done":  # how many times the history was read (BundleResult.stats)
        record["passes"] = history_passes(task)
    return record


def pack(table) -> dict[str, Any]:
    """A wear table as ``{"columns": names, "arrays": numpy arrays}``: what a task returns
    (cheaper to measure, send and store than a DataFrame carrying its metadata)."""
    attrs = table.attrs
    table.attrs = {}  # pandas deep-copies attrs into every column it hands out (5 ms a table)
    try:
        return {"columns": [str(c) for c in table.columns],
                "arrays": [table[c].to_numpy() for c in table.columns]}
    finally:
        table.attrs = attrs


def unpack(packed: dict[str, Any]) -> pd.DataFrame:
    """The DataFrame of :func:`pack` (same columns, same values and dtypes)."""
    return pd.DataFrame(dict(zip(packed["columns"], packed["arrays"], strict=True)))


def concat_packed(contacts: list[str], packed: list[dict[str, Any]]) -> pd.DataFrame:
    """The tables of :func:`pack` one under the other with a ``contact`` column in front, as
    ``pandas.concat`` of their :func:`unpack` with the contact inserted gives them: built column
    by column from the arrays (no DataFrame per contact) when the tables all have the same
    columns and dtypes, aligned by ``pandas.concat`` otherwise (tables with and without
    sectors); no tables: an empty frame with the ``contact`` column.

    Examples
    --------
    >>> a = {"columns": ["x"], "arrays": [np.array([1.0, 2.0])]}
    >>> b = {"columns": ["x"], "arrays": [np.array([3.0])]}
    >>> concat_packed(["A", "B"], [a, b]).to_dict("list")
    {'contact': ['A', 'A', 'B'], 'x': [1.0, 2.0, 3.0]}
    """
    if not packed:
        return pd.DataFrame(columns=["contact"])
    laid = packed_columns(packed)
    if laid is None:
        frames = []
        for contact, table in zip(contacts, packed, strict=True):
            frame = unpack(table)
            frame.insert(0, "contact", contact)
            frames.append(frame)
        return pd.concat(frames, ignore_index=True)
    lengths, columns, arrays = laid
    data = {"contact": np.repeat(np.array(contacts, dtype=object), lengths)}
    data.update(zip(columns, arrays, strict=True))
    return pd.DataFrame(data)


def packed_columns(packed: list[dict[str, Any]]
                   ) -> tuple[list[int], list[str], list[np.ndarray]] | None:
    """The tables of :func:`pack` (one at least) laid end to end a column at a time: (each
    table's rows, the columns, their arrays), where they all have the same columns and dtypes;
    None otherwise (:func:`concat_packed` aligns them by pandas)."""
    columns = packed[0]["columns"]
    dtypes = [a.dtype for a in packed[0]["arrays"]]
    if any(p["columns"] != columns or [a.dtype for a in p["arrays"]] != dtypes
           for p in packed[1:]):
        return None
    lengths = [len(p["arrays"][0]) if p["arrays"] else 0 for p in packed]
    return lengths, columns, [np.concatenate([p["arrays"][j] for p in packed])
                              for j in range(len(columns))]


def _error(exc: BaseException) -> list[str]:
    return [type(exc).__name__, str(exc)]


# ----------------------------------------------------------------------------- reading
def _read_in_memory(arrays: dict, task: ContactTask, first_row: int = 0):
    """A ContactHistory from raw arrays (aliases and units as for a file)."""
    options = {k: v for k, v in task.read_options.items() if k in ("units", "columns")}
    history = read_history(frame_of(arrays), name=task.contact, **options)
    return history


def _file_options(task: ContactTask) -> dict[str, Any]:
    """Reader options of a history file (the node is the reader's ``node=``)."""
    return dict(task.read_options)


def parquet_rows(task: ContactTask, start: int, stop: int):
    """Rows ``[start, stop)`` of a Parquet history, as a ContactHistory (only the row groups
    holding them are read); aliases and units as :func:`fretwear.io.read_history`."""
    pq = require("pyarrow.parquet")
    path = task.history.path
    options = {k: v for k, v in task.read_options.items() if k not in ("units", "columns")}
    source = open_source(path, **options)
    mapping = resolve_columns(source.columns, task.read_options.get("columns"),
                              label=source.label, hint=source.hint)
    unit_of, factors = resolve_units(mapping, source.units, task.read_options.get("units"),
                                     label=source.label)
    handle = pq.ParquetFile(path, pre_buffer=False)
    try:
        meta = handle.metadata
        sizes = [meta.row_group(g).num_rows for g in range(meta.num_row_groups)]
        bounds = np.cumsum([0] + sizes)
        groups = [g for g in range(len(sizes)) if bounds[g] < stop and bounds[g + 1] > start]
        names = [source.columns[p] for p in mapping.values()]
        table = handle.read_row_groups(groups, columns=names)
    finally:
        handle.close()
    offset = start - int(bounds[groups[0]])
    arrays = {ch: table.column(i).to_numpy().astype(float, copy=False)[offset:offset + stop - start]
              for i, ch in enumerate(mapping)}
    metadata = dict(source.metadata, source=source.label, format=source.format,
                    units=unit_of, unit_factors=factors, first_row=start)
    return build_history(arrays, columns=source.columns, mapping=mapping, factors=factors,
                         label=source.label, name=task.contact, metadata=metadata,
                         first_row=start)


def read_part(task: ContactTask, start: int, stop: int):
    """Samples ``[start, stop)`` of a contact whose length is known (Parquet, store)."""
    if task.history.kind == "store":
        return _read_in_memory(store_arrays(task.history, start, stop), task, start)
    return parquet_rows(task, start, stop)


# ----------------------------------------------------------------------------- computing
def _wear_table(source, task: ContactTask, history=None):
    """(columns, attrs) of the contact's wear table (:func:`fretwear.table.wear_table_columns`:
    the arrays the record sends, without a DataFrame in between), the attrs the record keeps
    only (:func:`_attrs`): with a PowerResult ``source`` its ``power`` is the result, whose
    values :func:`_attrs` reads (the dict of its statistics not made)."""
    if isinstance(source, PowerResult):
        columns, attrs = wear_table_columns(task.wear_case(), source, history=history,
                                            attrs=_ATTRS)
        attrs["power"] = source
        return columns, attrs
    return wear_table_columns(task.wear_case(), source, history=history,
                              attrs=(*_ATTRS, "power"))


def _power_options(task: ContactTask) -> dict[str, Any]:
    """The keywords of the contact's :class:`~fretwear.power.PowerAccumulator` (its window,
    blocks, sectors and, when the law counts KWU-EPRI classes, their maxima)."""
    options = task.wear_case().power_options
    del options["stationarity_threshold"]  # the result's, not the accumulator's
    return options


def _threshold(task: ContactTask) -> float:
    return task.wear_case().window.stationarity_threshold


def needs_whole_history(task: ContactTask) -> bool:
    """Whether a contact cannot be split in time chunks: KWU_EPRI without both FNOR_MAXI and
    VTAN_MAXI (its class bounds depend on the window's maxima, known only at the end: a second
    pass over the history; :mod:`fretwear.laws.kwu_stream`)."""
    return history_passes(task) == 2


def history_passes(task: ContactTask) -> int:
    """Passes over a contact's history: 0 without one (a given power), 2 for a law counting
    KWU-EPRI classes without both FNOR_MAXI and VTAN_MAXI (``force_max_N``,
    ``speed_max_m_per_s``, from the base case or the manifest: the pass of the power gives the
    window's maxima, a second the class counts), else 1 (read from the task's case, without
    building it: the client asks it of every contact).

    Examples
    --------
    >>> from fretwear.bundle.manifest import HistoryRef
    >>> task = ContactTask("c", HistoryRef("file", path="h.parquet"),
    ...                    {"law": "KWU_EPRI", "force_max": 400.0, "speed_max": None})
    >>> history_passes(task)
    2
    >>> task.case["speed_max"] = 0.5
    >>> history_passes(task)
    1
    """
    if task.history.kind == "none":
        return 0
    case = task.case
    if case.get("force_max") is not None and case.get("speed_max") is not None:
        return 1
    return 2 if _counts_classes(case.get("law")) else 1


@functools.cache
def _counts_classes(law: str | None) -> bool:
    return law is not None and get_law(law).needs_history


def _compute(task: ContactTask, chunk_size: int):
    """(table, samples) of one whole contact."""
    ref = task.history
    if ref.kind == "none":
        return _wear_table(task.power, task), 0
    if ref.kind == "memory":
        history = _read_in_memory(dict(ref.arrays), task)
    elif ref.kind == "store":
        history = _read_in_memory(store_arrays(ref), task)
    else:
        return _file_table(task, chunk_size)
    return _wear_table(history, task), len(history)


def _file_table(task: ContactTask, chunk_size: int):
    """(table, samples) of a history file, streamed by :func:`fretwear.power.wear_power` as
    ``wear_table(path)`` streams it: the reader's own blocks of at most ``chunk_size`` samples
    (memory bounded by a block), the time range of the blocks from the file's metadata (Parquet
    statistics, HDF5/NetCDF ends; a first pass for text only), the KWU_EPRI class counts in the
    same pass when FNOR_MAXI and VTAN_MAXI are given (one more pass otherwise); the units
    checked against the contact's geometry on the first block, as it is read
    (:func:`_geometry_check`)."""
    power, samples = _file_power(task, chunk_size)
    return _wear_table(power, task), samples


def _file_power(task: ContactTask, chunk_size: int):
    """(power, samples) of a history file: the first half of :func:`_file_table`."""
    read = [0]

    def progress(samples: int) -> None:
        read[0] = samples

    # the statistics not made: a record keeps the power's values only (_POWER)
    power = wear_power(task.history.path, **task.wear_case().power_options,
                       chunk_size=chunk_size, progress=progress, name=task.contact,
                       first_block=_geometry_check(task), statistics=False,
                       **_file_options(task))
    return power, read[0]


#: Samples of a streamed history's first block checked for its units against the contact's
#: geometry (:func:`fretwear.io.geometry_units.check_against_geometry`; a unit error shows in
#: the first block, as the plausibility checks assume).
PROBE_SAMPLES = 1 << 16


def _geometry_check(task: ContactTask):
    """The check of a streamed history's units against the contact's geometry, called by
    :func:`fretwear.power.wear_power` with the first block it reads (its first
    :data:`PROBE_SAMPLES` samples), or None for a contact without a tube radius. The file is
    read once: a probe reading the first chunk apart opened and read every file twice (1.2 ms
    of a 1 000-sample contact's 4.2 ms, issue 28)."""
    dims = task.wear_case().dimensions
    if not dims.get("mobile_radius"):
        return None

    def check(first) -> None:
        if len(first) > PROBE_SAMPLES:
            first = first.replace(**{ch: getattr(first, ch)[:PROBE_SAMPLES]
                                     for ch in first.channels})
        check_against_geometry(first, mobile_radius=dims.get("mobile_radius"),
                               obstacle_radius=dims.get("obstacle_radius"), name=task.contact)

    return check


def run_contact(task: ContactTask, chunk_size: int = 1_000_000) -> dict[str, Any]:
    """Compute one contact's wear table; a failure becomes an error record.

    Parameters
    ----------
    task : ContactTask
    chunk_size : int
        Samples per chunk when a history file is longer (streamed, memory bounded).

    Returns
    -------
    dict
        ``contact``, ``key``, ``status`` (``"done"`` or ``"failed"``), ``table`` (DataFrame or
        None), ``warnings`` (``[category, message]`` pairs), ``error`` (``[class, message]`` or
        None), ``samples``, ``seconds`` (compute time), ``attrs`` (the table's metadata).
    """
    value, caught, seconds, failure = _guarded(task, _compute, task, chunk_size)
    if failure is not None:
        return failure
    table, samples = value
    return _record(task, status="done", table=table, caught=caught, samples=samples,
                   seconds=seconds)


def _guarded(task: ContactTask, fn, *args, before=(), seconds: float = 0.0):
    """``fn(*args)`` with the process's warnings recorded: ``(value, warnings, seconds,
    None)``, or ``(None, warnings, seconds, the contact's failed record)`` when it raises; the
    warnings after ``before`` (a step's earlier ones), the seconds after ``seconds``."""
    start = time.perf_counter()
    with captured() as caught:
        try:
            value = fn(*args)
        except Exception as exc:  # noqa: BLE001 - a bad contact must not stop the batch
            failure = _record(task, status="failed", caught=[*before, *caught],
                              error=_error(exc), seconds=seconds + time.perf_counter() - start)
            return None, failure["warnings"], failure["seconds"], failure
    return value, [*before, *caught], seconds + time.perf_counter() - start, None


#: Contacts whose small Parquet files a worker reads in a row before computing them
#: (:func:`run_contacts`, :func:`fretwear.io.prefetch.prefetch`).
READ_AHEAD = 16


def run_contacts(tasks: list[ContactTask], chunk_size: int = 1_000_000) -> list[dict[str, Any]]:
    """:func:`run_contact` of several contacts in one task (one record each, in order): the
    scheduler's cost per task spread over them (:func:`fretwear.bundle.engine.task_sizes`).
    The small Parquet files of every :data:`READ_AHEAD` contacts are read in a row first, then
    those contacts' powers computed in a row, then their tables (:mod:`fretwear.io.prefetch`:
    the same reads, 20-30 % less CPU a contact of 1 000 samples; :func:`_power_step`), those of
    a case's contacts together (:func:`_batch_tables`: the same tables, 0.05-0.1 ms less CPU a
    contact of 8 sectors and 6 instants).
    """
    records = []
    for start in range(0, len(tasks), READ_AHEAD):
        batch = tasks[start:start + READ_AHEAD]
        with prefetch([t.history.path for t in batch if _lean_file(t)], chunk_size):
            powers = [_power_step(task, chunk_size) for task in batch]
        tables = _batch_tables(batch, powers)
        records += [_table_step(task, step, tables.get(k))
                    for k, (task, step) in enumerate(zip(batch, powers, strict=True))]
    return records


def _batch_tables(batch: list[ContactTask], steps: list) -> dict[int, tuple]:
    """The tables of a batch's contacts whose power step passed, made together per case
    (:func:`fretwear.table.batch.sector_tables`: the same columns and attrs as
    :func:`_wear_table` of each, a numpy call over all of them instead of one a contact), by
    their place in the batch: ``(table, seconds)``, the seconds the contact's share of the
    batch's. None of a case whose tables raise or warn (or that the batch does not take):
    those are made one by one (:func:`_table_step`), each with its own errors and warnings."""
    cases: dict[int, list[int]] = {}
    for k, (task, step) in enumerate(zip(batch, steps, strict=True)):
        if not isinstance(step, dict) and isinstance(step[0], PowerResult):
            cases.setdefault(id(task.wear_case()), []).append(k)
    out: dict[int, tuple] = {}
    for places in cases.values():
        if len(places) < 2 or not batched(batch[places[0]].wear_case()):
            continue
        start = time.perf_counter()
        with captured() as caught:
            try:
                tables = sector_tables(batch[places[0]].wear_case(),
                                       [steps[k][0] for k in places], attrs=_ATTRS)
            except Exception:  # noqa: BLE001 - one by one, each contact its own error
                tables = None
        if tables is None or caught:
            continue  # a warning belongs to one contact: its own table says it
        share = (time.perf_counter() - start) / len(places)
        for k, (columns, attrs) in zip(places, tables, strict=True):
            attrs["power"] = steps[k][0]  # as _wear_table: the record reads its values
            out[k] = ((columns, attrs), share)
    return out


def _power_step(task: ContactTask, chunk_size: int):
    """The first half of :func:`run_contact` of a history file (its power, samples, the
    warnings caught and the seconds taken), or the whole record of any other contact or of a
    failure; :func:`_table_step` then makes the record. A batch's powers, then its tables, each
    in a row: 5-8 % less CPU a contact than each contact's power and table in turn (the
    processor's caches, as for the files read ahead)."""
    if task.history.kind != "file":
        return run_contact(task, chunk_size)
    value, caught, seconds, failure = _guarded(task, _file_power, task, chunk_size)
    return failure if failure is not None else (*value, caught, seconds)


def _table_step(task: ContactTask, step, made: tuple | None = None) -> dict[str, Any]:
    """The record of :func:`run_contact` from :func:`_power_step`'s value: the same record
    (the warnings of both halves in the order raised, each once); ``made``: the table and its
    seconds already made with its batch's (:func:`_batch_tables`, which raised and warned
    nothing)."""
    if isinstance(step, dict):
        return step
    power, samples, before, seconds = step
    if made is not None:
        table, share = made
        return _record(task, status="done", table=table, caught=before, samples=samples,
                       seconds=seconds + share)
    table, caught, seconds, failure = _guarded(task, _wear_table, power, task, before=before,
                                               seconds=seconds)
    if failure is not None:
        return failure
    return _record(task, status="done", table=table, caught=caught, samples=samples,
                   seconds=seconds)


def _lean_file(task: ContactTask) -> bool:
    """Whether a contact's history is a file the lean lane of
    :func:`fretwear.io.iter_history_blocks` may read (a Parquet file without reader options)."""
    return task.history.kind == "file" and not task.read_options \
        and str(task.history.path).lower().endswith(".parquet")


def chunk_state(task: ContactTask, start: int, stop: int, bounds: tuple[float, float]
                ) -> dict[str, Any]:
    """The partial power state of samples ``[start, stop)`` of a long contact."""
    t0 = time.perf_counter()
    opts = _power_options(task)
    opts["t_start"] = bounds[0] if opts["t_start"] is None else opts["t_start"]
    opts["t_end"] = bounds[1] if opts["t_end"] is None else opts["t_end"]
    with captured() as caught:
        try:
            part = read_part(task, start, stop)
            if start == 0:  # the first chunk: units against the geometry (said once)
                dims = task.wear_case().dimensions
                check_against_geometry(part, mobile_radius=dims.get("mobile_radius"),
                                       obstacle_radius=dims.get("obstacle_radius"),
                                       name=task.contact)
            acc = PowerAccumulator(**opts).update(part)
        except Exception as exc:  # noqa: BLE001
            return _record(task, status="failed", caught=caught, error=_error(exc),
                           seconds=time.perf_counter() - t0)
    return _record(task, status="partial", caught=caught, state=acc,
                   seconds=time.perf_counter() - t0)


def merge_states(*records: dict[str, Any]) -> dict[str, Any]:
    """Merge partial records of consecutive chunks, left to right (a node of the tree)."""
    out = dict(records[0])
    out["warnings"] = [w for r in records for w in r["warnings"]]
    out["seconds"] = sum(r["seconds"] for r in records)
    failed = [r for r in records if r["status"] == "failed"]
    if failed:
        out.update(status="failed", error=failed[0]["error"], state=None)
        return out
    with captured() as caught:
        try:
            state = records[0]["state"]
            for r in records[1:]:
                state = state.merge(r["state"])
        except Exception as exc:  # noqa: BLE001
            out.update(status="failed", error=_error(exc), state=None)
            return out
    out["warnings"] += _warning_list(caught)
    out["state"] = state
    return out


def finish_contact(task: ContactTask, merged: dict[str, Any]) -> dict[str, Any]:
    """The wear table of a long contact from the merged power state of all its chunks."""
    t0 = time.perf_counter()
    if merged["status"] == "failed":
        rec = _record(task, status="failed", error=merged["error"], seconds=merged["seconds"])
        rec["warnings"] = merged["warnings"]
        return rec
    with captured() as caught:
        try:
            state = merged["state"]
            power = state.result(stationarity_threshold=_threshold(task))
            table = _wear_table(power, task)
        except Exception as exc:  # noqa: BLE001
            rec = _record(task, status="failed", caught=caught, error=_error(exc),
                          seconds=merged["seconds"] + time.perf_counter() - t0)
            rec["warnings"] = merged["warnings"] + rec["warnings"]
            return rec
    rec = _record(task, status="done", table=table, caught=caught, samples=state.samples,
                  seconds=merged["seconds"] + time.perf_counter() - t0)
    rec["warnings"] = [list(w) for w in dict.fromkeys(
        tuple(w) for w in merged["warnings"] + rec["warnings"])]
    return rec


def time_bounds(task: ContactTask, samples: int) -> tuple[float, float]:
    """First and last instant [s] of a contact of known length (two one-sample reads, on the
    client: their warnings are the chunks' own, which the chunk tasks capture and return with
    the contact; here they would only reach the terminal, twice a contact)."""
    with captured():  # recorded and dropped, under the process's lock as a task's are
        first = read_part(task, 0, 2).time[0]
        last = read_part(task, samples - 2, samples).time[-1]
    return float(first), float(last)
