"""The client's side of a bundle run while the results arrive: every contact's final record.

:class:`Arrivals` takes each task's records as :func:`fretwear.bundle.engine.run_bundle`
receives them, whoever wrote their rows (the worker, as its group's part; or the client, from
its buffer of ``part_size`` records), with one bookkeeping for both: the record kept in
``records`` (a failure of a contact an earlier run computed keeps that run's rows, status
``stale``: :func:`kept`), the part written or recorded, the count said to ``progress``, and the
records handed to the table written meanwhile
(:class:`fretwear.bundle.table_file.PrefixTable`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from fretwear.bundle.cases import ContactTask
from fretwear.bundle.store import OutputDirectory
from fretwear.bundle.table_file import PrefixTable
from fretwear.bundle.worker_parts import PartTarget, written_by_worker

#: Contacts per part file written by the client (a part is also written every PART_SECONDS),
#: and the most a worker's part holds (:data:`fretwear.bundle.engine.GROUP_SIZE`).
PART_SIZE = 250
PART_SECONDS = 10.0


def failed(task: ContactTask, exc: BaseException) -> dict[str, Any]:
    """The record of a contact whose task raised ``exc``."""
    return {"contact": task.contact, "key": task.key, "status": "failed", "table": None,
            "warnings": [list(w) for w in task.warnings],
            "error": [type(exc).__name__, str(exc)], "samples": 0,
            "seconds": 0.0, "attrs": None, "state": None}


def kept(rec: dict[str, Any], old: dict[str, Any] | None) -> dict[str, Any]:
    """A contact failing this run (its history moved, unreadable, a case now invalid) whose
    earlier run in the output directory computed it: its earlier record and rows kept, status
    ``"stale"``, this run's error beside them. A stale record is never written to a part, so the
    earlier good record stays the contact's latest (a later run with the input back skips it);
    any other record is returned as it is."""
    if rec["status"] != "failed" or not old or old.get("status") != "done" \
            or not old.get("rows_file"):
        return rec
    said = [list(w) for w in old.get("warnings") or []]
    said += [list(w) for w in rec.get("warnings") or [] if list(w) not in said]
    return {**old, "status": "stale", "error": rec["error"], "warnings": said, "table": None,
            "state": None}


def flush(store: OutputDirectory, buffer: list[dict[str, Any]]) -> None:
    """Write the records of ``buffer`` as a part, then drop their rows from the client: the
    part file holds them, and the final table is assembled from the parts (issue 28: the
    client held every contact's rows until the end, some 12 kB a contact)."""
    store.write_part(buffer)
    for rec in buffer:
        rec["table"] = rec["state"] = None


class Arrivals:
    """Every contact's final record as the results arrive (see the module's docstring).

    Parameters
    ----------
    store : OutputDirectory or None
        The output directory (None: nothing written).
    records : dict
        ``{contact: its latest record}``, filled here (the contacts failed or skipped before
        any task are in it already).
    earlier : dict
        The records of the output directory's earlier runs (:func:`kept`).
    total : int
        Contacts of the manifest.
    progress : callable or None
        ``progress(done, total, record)`` after each contact.
    part_size : int
        Contacts per part written by the client.
    table : PrefixTable or None
        The table written while the results arrive.
    """

    def __init__(self, store: OutputDirectory | None, records: dict[str, dict[str, Any]],
                 earlier: dict[str, dict[str, Any]], total: int,
                 progress: Callable[[int, int, dict], None] | None, part_size: int,
                 table: PrefixTable | None = None) -> None:
        self.store, self.records, self.earlier = store, records, earlier
        self.total, self.progress, self.part_size, self.table = total, progress, part_size, table
        self.buffer: list[dict[str, Any]] = []  # this run's records not written yet
        self.done = 0
        self.last_flush = time.perf_counter()

    def start(self) -> None:
        """The records made before any task (failed or skipped): counted, said, resolved."""
        self.done = sum(1 for r in self.records.values() if r["status"] == "skipped")
        if self.progress is not None:
            for r in self.records.values():
                self.progress(0, self.total, r)
        self._resolve(list(self.records.values()))
        self.last_flush = time.perf_counter()

    def receive(self, group: list[ContactTask], value: Any, target: PartTarget | None
                ) -> None:
        """A task's result ``value`` (a record, a list of one per contact of ``group``, or the
        exception that lost the task), its rows in the part ``target`` when its worker wrote
        them there."""
        values = value if isinstance(value, list) else [value] * len(group)
        part = [kept(one if isinstance(one, dict) else failed(task, one),
                     self.earlier.get(task.contact))
                for task, one in zip(group, values, strict=True)]
        by_worker = target is not None and any(written_by_worker(v, target) for v in values)
        if by_worker:  # the rows in the worker's file: the part's records written at once
            self.store.record_part([r for r in part if r["status"] != "stale"],
                                   target.stem, target.rows_file)
        for task, rec in zip(group, part, strict=True):
            self.records[task.contact] = rec
            self.done += 1
            if not by_worker and self.store is not None and rec["status"] != "stale":
                self._buffer(rec)
            if self.progress is not None:
                self.progress(self.done, self.total, rec)
        self._resolve(part)  # the failed ones; the done ones once their part is written

    def close(self) -> None:
        """Write this run's last records, and the failures of the client-side checks."""
        if self.store is None:
            return
        queued = {id(b) for b in self.buffer}
        self.buffer += [r for r in self.records.values() if r["status"] == "failed"
                        and "part" not in r and id(r) not in queued]
        if self.buffer:
            self._flush()

    def _buffer(self, rec: dict[str, Any]) -> None:
        self.buffer.append(rec)
        now = time.perf_counter()
        if len(self.buffer) >= self.part_size or now - self.last_flush >= PART_SECONDS:
            self._flush()
            self.last_flush = now

    def _flush(self) -> None:
        flush(self.store, self.buffer)
        written, self.buffer = self.buffer, []
        self._resolve(written)

    def _resolve(self, records: list[dict[str, Any]]) -> None:
        if self.table is not None:
            self.table.resolve(records)

    def abort(self) -> None:
        """The run stops: the table written meanwhile is given up (its temporary file
        removed)."""
        if self.table is not None:
            self.table.abort()
