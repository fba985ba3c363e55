"""The end of a bundle run: its result and final files from every contact's latest record.

:func:`assemble` builds the :class:`~fretwear.bundle.result.BundleResult` (the table, the
per-contact information, the failures and warnings, the statistics) and writes the output
directory's final files (``table``, ``dataset``, ``errors.csv``, ``warnings.csv``,
``summary.csv``, ``run.json``). With an output directory the contacts' rows are in the parts,
written as they arrived: the table is read from them in one pass
(:meth:`~fretwear.bundle.store.OutputDirectory.ordered_rows`). A restart that changes nothing
(:func:`outputs_digest` unchanged, the files as recorded) writes only ``run.json``.
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from fretwear._lazy import pandas as pd
from fretwear._optional import optional
from fretwear._version import __version__
from fretwear.bundle.contacts_info import ContactRows
from fretwear.bundle.end_scan import digest_row, scan
from fretwear.bundle.frozen import collector_paused
from fretwear.bundle.manifest import Manifest
from fretwear.bundle.result import (
    ERROR_COLUMNS,
    BundleResult,
    summarize_ahead,
    summary_key,
    summary_rows,
)
from fretwear.bundle.result_dataset import build_dataset
from fretwear.bundle.store import OutputDirectory, write_frame
from fretwear.bundle.table_file import PrefixTable, with_identity
from fretwear.bundle.tasks import concat_packed
from fretwear.geometry.base import GLOBAL_RANGE
from fretwear.io.atomic import atomic_write


def assemble(man: Manifest, records: dict[str, dict[str, Any]], store,
              times: tuple[float, float], workers: int, dataset_format: str | None,
              limit: float | None = None, built: dict[str, Any] | None = None,
              identity: pd.DataFrame | None = None, written: PrefixTable | None = None,
              identity_bytes: bytes | None = None, made: ContactRows | None = None
              ) -> BundleResult:
    """The BundleResult (and the output files) from every contact's latest record and the
    wear cases ``built`` (contact -> WearCase) of this run; ``identity``: the manifest's
    identity columns (``contact`` as text), made here when None; ``written``: the table
    written while the results arrived, put in place when whole (else given up);
    ``identity_bytes``: :func:`identity_hash` of ``identity``, taken while the workers
    computed (made here when None); ``made``: the contacts' rows of ``BundleResult.contacts``
    made while the results arrived (made here when None)."""
    # the collector off until the end: at 10^5 contacts the records, cases and frames held
    # are millions of objects, each full collection a walk through them all, started again
    # and again by the objects made here (0.25-0.3 s of the end at 10^5, issue 28)
    with collector_paused():
        return _assemble(man, records, store, times, workers, dataset_format, limit, built,
                         identity, written, identity_bytes, made)


def _assemble(man, records, store, times, workers, dataset_format, limit, built, identity,
              written, identity_bytes=None, made=None) -> BundleResult:
    """:func:`assemble`, the collector paused."""
    order = [r.contact for r in man.rows]
    if identity is None:
        identity = man.identity_frame()
        identity["contact"] = identity["contact"].astype(str)
    # a restart that skips every contact into a directory whose final files are those of the
    # same records (outputs_digest, recorded in run.json with the files' stamps): the files
    # are not written again, the table is read back from its file (issue 28: a restart of
    # 10^5 contacts rewrote 4 final files, 88 s); else the digest is taken below, while the
    # dataset is being written
    options = (store.table_format, dataset_format or "default", limit, identity_bytes) \
        if store else None
    seen = scan(order, records, built)
    digest = None
    if store is not None and all(records[c]["status"] == "skipped" for c in order):
        digest = outputs_digest(identity, order, records, *options, rows=seen.digest_rows)
    unchanged = digest is not None and store.unchanged(digest)
    if dataset_format is None:
        dataset_format = "netcdf" if optional("zarr") is None else "zarr"
    # with Parquet parts, table.parquet is written from them while they arrived (table_file.
    # PrefixTable), else by buckets (table_file.stream_table), and the result reads it on
    # demand: the client never holds the whole table (issue 28: 1.3 GB at 10^5 contacts, then
    # its copies); an unchanged restart reads nothing
    table = None
    streamed = unchanged and _saved_table(store, order)
    if not streamed and store is not None and not seen.tables:
        kept = ("done", "skipped", "stale")  # the records with rows: listed where needed
        streamed = any(records[c]["status"] in kept for c in order) and (
            store.finish_table(written) or store.stream_table(
                [records[c] for c in order if records[c]["status"] in kept], order, identity))
    if written is not None:
        written.abort()  # not used: its temporary file removed (nothing once finished)
    if not streamed:
        table = _table(order, identity, records, store)
    table_file = store.table_path() if streamed else None
    if made is None:
        made = ContactRows(order, built or {})
    # after the last result the workers' cores are free (issue 28: the client's work there was
    # single-threaded while a core waited): the summary's columns read in a thread from now,
    # and from the contacts on, the dataset written in a thread and the summary of the run's
    # limit made in another, while this one makes the rest (outputs_digest, errors, the CSV
    # files)
    ahead = None if table_file is None or unchanged else summary_rows(table_file, AHEAD)
    result = None
    with ThreadPoolExecutor(2) as pool:
        try:
            contacts = identity.merge(made.frame(records), on="contact", how="right")
            regions = pool.submit(store.write_zarr_by_regions, contacts) \
                if ahead is not None and dataset_format == "zarr" else None
            summaries = {}
            if ahead is not None:  # the thread closes the rows it reads
                summaries[summary_key(limit)] = pool.submit(summarize_ahead, ahead, contacts,
                                                            limit)
                ahead = None
            if store is not None and digest is None:
                digest = outputs_digest(identity, order, records, *options,
                                        rows=seen.digest_rows)
            warns, errors = _news(seen.news, records)
            errors_frame = pd.DataFrame(errors, columns=list(ERROR_COLUMNS))
            errors_frame = errors_frame.merge(identity.drop(columns=["history"]), on="contact",
                                              how="left")
            statuses = contacts["status"].value_counts()
            started, startup = times
            stats = {"contacts": len(order), "done": int(statuses.get("done", 0)),
                     "failed": int(statuses.get("failed", 0)),
                     "skipped": int(statuses.get("skipped", 0)),
                     "stale": int(statuses.get("stale", 0)), "seconds": math.nan,
                     "startup_seconds": startup, "contacts_per_s": math.nan,
                     "samples": int(seen.samples), "samples_per_s": math.nan,
                     "workers": workers, "manifest": man.source,
                     "two_pass_contacts": int(seen.two_pass)}
            result = BundleResult(
                table=table, table_file=table_file, errors=errors_frame,
                warnings=pd.DataFrame(warns, columns=["contact", "category", "message"]),
                contacts=contacts, stats=stats,
                output=None if store is None else str(store.path), cases=seen.cases,
                _summaries=summaries)
            if store is not None:
                _write_outputs(result, store, seen.parts, dataset_format,
                               (started, seen.computed), limit, digest, unchanged,
                               (pool, regions))
            else:
                _times(result.stats, started, seen.computed)
        finally:
            if ahead is not None:  # not handed to the summary's thread: stopped
                ahead.close()
    return result


#: Pieces of the table (:func:`~fretwear.bundle.table_file.contact_pieces`, some 20 MB each)
#: the summary's reading may be ahead of it at the bundle's end: it starts before the result is
#: whole, and reading a piece took longer than summing it up (issue 28: 19 pieces at 10^5
#: contacts, 55 ms to read one, 35 ms to sum it up).
AHEAD = 4


def _news(order: list[str], records: dict[str, dict[str, Any]]) -> tuple[list, list]:
    """The rows of ``BundleResult.warnings`` (every warning of every contact) and
    ``BundleResult.errors`` (a failure, a stale contact's failure, a depth beyond its
    relation's range), contacts in ``order`` (those with news: :attr:`Scan.news`; any other
    says nothing)."""
    warns: list[dict] = []
    errors: list[dict] = []
    for c in order:
        rec = records[c]
        caught = rec.get("warnings")
        status = rec["status"]
        if not caught and status in ("done", "skipped"):
            continue  # most contacts: nothing to say
        for category, message in caught or []:
            warns.append({"contact": c, "category": category, "message": message})
        if status == "failed":
            errors.append({"contact": c, "error": rec["error"][0], "message": rec["error"][1],
                           "rows_kept": False})
        elif status == "stale":  # failed this run, its earlier run's rows kept
            errors.append({"contact": c, "error": rec["error"][0],
                           "message": f"{rec['error'][1]} (this run could not recompute it: "
                                      f"its rows are the earlier run's, {rec['part']})",
                           "rows_kept": True})
        elif status in ("done", "skipped"):
            ranged = [m for cat, m in caught if cat == "RangeWarning"]
            if ranged:  # the global depth's warning (the summary ranks by it), else a sector's
                message = next((m for m in ranged if GLOBAL_RANGE in m), ranged[0])
                errors.append({"contact": c, "error": "RangeWarning", "message": message,
                               "rows_kept": True})
    return warns, errors


def _times(stats: dict[str, Any], started: float, count: int) -> None:
    """The run's wall time [s] from the call to now (the results assembled, the files but
    run.json written) and its throughput without the cluster's start [1/s]."""
    elapsed = time.perf_counter() - started
    busy = elapsed - stats["startup_seconds"]
    stats["seconds"] = elapsed
    stats["contacts_per_s"] = count / busy if busy > 0 else math.nan
    stats["samples_per_s"] = stats["samples"] / busy if busy > 0 else math.nan


def _write_outputs(result: BundleResult, store: OutputDirectory, parts: set[str],
                   dataset_format: str, clock: tuple[float, int], limit: float | None,
                   digest: str, unchanged: bool, started: tuple):
    """The final files; ``summary.csv`` is ``result.summary(limit)``, and ``run.json`` records
    ``limit`` (None: each contact's depth_limit), the ``digest`` of what the files hold
    (:func:`outputs_digest`) and their stamps. ``unchanged``: the files of an earlier run are
    those of ``digest`` and still as written: only ``run.json`` is written (this run's stats).
    ``started``: the thread pool writing the dataset and the future of its Zarr store written
    by regions (None: not started). ``parts``: the parts the records refer to (the others
    removed)."""
    if unchanged:
        order = ("table.parquet", "table.csv", "dataset.zarr", "dataset.nc", "errors.csv",
                 "warnings.csv", "summary.csv")
        outputs = [o for o in order if o in store.written_before]
    else:
        pool, regions = started
        if result.table_file is None:  # else written from the parts already
            store.write_table(result.table)
        # the dataset written from the table file in a thread while this one writes the CSV
        # files and the summary; in memory, the table is the result's and the Dataset is
        # built here
        dataset = pool.submit(_write_dataset, result, store, dataset_format, regions) \
            if result.table_file is not None else None
        write_frame(result.errors, store.path / "errors.csv", "csv")
        write_frame(result.warnings, store.path / "warnings.csv", "csv")
        write_frame(result.summary(limit), store.path / "summary.csv", "csv")
        if dataset is None:
            _write_dataset(result, store, dataset_format)
        else:
            dataset.result()
        outputs = [*store.written, "errors.csv", "warnings.csv", "summary.csv"]
    # the final files written, so that a later run in another format removes only those
    stamps = store.stamps(outputs)
    _times(result.stats, *clock)
    with atomic_write(store.path / "run.json", encoding="utf-8") as handle:
        json.dump({**result.stats, "limit": limit, "outputs": [*outputs, "run.json"],
                   "digest": digest, "stamps": stamps}, handle, indent=1, default=str)
    store.cleanup(parts)


def _write_dataset(result: BundleResult, store: OutputDirectory, dataset_format: str,
                   regions=None) -> None:
    """``dataset.zarr`` (or ``.nc``) of the result's table, or the stale one removed where no
    contact has rows; ``regions``: the future of ``store.write_zarr_by_regions`` started
    already (its answer waited for), None to ask it here."""
    if regions is not None:
        if regions.result():
            return
    elif result.table_file is not None and dataset_format == "zarr" \
            and store.write_zarr_by_regions(result.contacts):
        return  # from the written table, a group of contacts at a time (issue 28)
    if len(result.table):
        # built, written and dropped: not kept on the result beside its table (the client's
        # memory at the end, issue 28); BundleResult.dataset builds it again when asked
        dataset = build_dataset(result.table, result.contacts)
        store.write_dataset(dataset, dataset_format)
        del dataset
    else:
        store.drop_dataset()


def outputs_digest(identity: pd.DataFrame, order: list[str], records: dict[str, dict],
                   table_format: str, dataset_format: str, limit: float | None,
                   identity_bytes: bytes | None = None, rows: list | None = None) -> str:
    """What a bundle's final files hold, as a hash: fretwear's version, the output options,
    the manifest's identity columns, and each contact's record: its input key, status and the
    part holding its rows (a part is never rewritten: a new run writes new parts; a skipped
    contact counts as the done one it was). Two runs of the same digest write the same
    files. ``identity_bytes``: :func:`identity_hash` of ``identity`` when already taken;
    ``rows``: the records' shares (:func:`~fretwear.bundle.end_scan.digest_row`, in
    ``order``) when already made."""
    h = hashlib.blake2b(digest_size=16)
    h.update(json.dumps([__version__, table_format, dataset_format, limit,
                         list(identity.columns)], default=str).encode())
    h.update(identity_hash(identity) if identity_bytes is None else identity_bytes)
    if rows is None:
        rows = [digest_row(c, records[c]) for c in order]
    h.update(json.dumps(rows, default=str).encode())
    return h.hexdigest()


def identity_hash(identity: pd.DataFrame) -> bytes:
    """The identity columns' share of :func:`outputs_digest` (each cell as text, hashed by
    pandas): taken by the engine while the workers compute, not after the last result (0.16 s
    of CPU at 10^5 contacts, issue 28)."""
    return pd.util.hash_pandas_object(identity.astype(str), index=False).to_numpy().tobytes()


def _table(order: list[str], identity: pd.DataFrame, records: dict[str, dict[str, Any]],
           store: OutputDirectory | None) -> pd.DataFrame:
    """The bundle's table from the records' rows (this run's, and the skipped or stale
    contacts' read back from the parts), identity columns in front."""
    if store is not None and all(records[c].get("table") is None for c in order):
        # every contact's rows in the parts (written as they arrived, then dropped): read
        # from there in one pass (store.ordered_rows), never held a contact at a time
        kept = [records[c] for c in order if records[c]["status"] in ("done", "skipped", "stale")]
        table = store.ordered_rows(kept, order) if kept else None
        if table is not None:
            return with_identity(table, identity)
    packed: dict[str, dict[str, Any]] = {c: records[c]["table"] for c in order
                                         if records[c].get("table") is not None}
    missing = [records[c] for c in order if c not in packed and records[c]["status"]
               in ("done", "skipped", "stale")]
    if missing and store is not None:  # a restart: the rows of skipped contacts from the parts
        packed.update(store.packed_rows(missing))
    kept = [c for c in order if c in packed]
    table = concat_packed(kept, [packed[c] for c in kept])
    del packed  # the contacts' rows, now in the table: freed before the identity's merge
    return with_identity(table, identity)


def _saved_table(store: OutputDirectory, order: list[str]) -> bool:
    """Whether the table an earlier run wrote as Parquet can be the result's, read on demand
    (Parquet keeps every column's dtype: the table :func:`_table` assembles; a CSV table is
    assembled again): readable, and its contacts ``order``'s (its ``contact`` column read
    alone)."""
    path = store.table_path()
    if store.table_format != "parquet" or not path.is_file():
        return False
    try:
        import pyarrow.compute as pc
        import pyarrow.parquet as pq

        ids = pc.unique(pq.read_table(path, columns=["contact"]).column("contact"))
    except Exception:  # noqa: BLE001 - unreadable, no contact: assembled again, written again
        return False
    wanted = set(order)
    return all(str(c) in wanted for c in ids.to_pylist())
