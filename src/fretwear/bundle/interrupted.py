"""A bundle run interrupted (Ctrl-C): what it says, once what arrived is written
(:func:`interrupted`)."""

from __future__ import annotations

import contextlib
from pathlib import Path


class BundleInterrupted(KeyboardInterrupt):
    """A bundle run interrupted (Ctrl-C): the contacts whose results are in the output directory.

    A :class:`KeyboardInterrupt`, so that code catching that still sees the interrupt.

    Attributes
    ----------
    written : int
        Contacts of the manifest done and in the output directory's parts (this run's and the
        earlier runs' kept ones): a run with the same inputs skips them (0 without output).
    total : int
        Contacts of the manifest.
    output : Path or None
        The output directory.
    """

    def __init__(self, written: int, total: int, output: Path | None):
        self.written, self.total, self.output = written, total, output
        super().__init__(f"interrupted: {written} of {total} contacts written to {output}"
                         if output is not None
                         else f"interrupted: none of {total} contacts written (no output)")


def interrupted(store, records, buffer, total, previous, man, tasks) -> BundleInterrupted:
    """The :class:`BundleInterrupted` of an interrupted run, the records received but not yet
    written saved first as a part (a second interrupt during that write leaves it out)."""
    if store is not None and buffer:
        with contextlib.suppress(OSError, KeyboardInterrupt):
            store.write_part(buffer)
    # a record is in a part once its part's JSON is written (write_part sets "part" then); a
    # row made a task (``tasks``) counts only once computed this run; a row not reached yet
    # (interrupted while the tasks were built) counts by the earlier runs' parts
    written = sum(1 for row in man.rows
                  if (row.contact in records and records[row.contact].get("part")
                      and records[row.contact]["status"] in ("done", "skipped"))
                  or (row.contact not in records and row.contact not in tasks
                      and (previous.get(row.contact) or {}).get("status") == "done"))
    if store is None:  # nothing written: the contacts computed before the interrupt
        written = 0
    return BundleInterrupted(written, total, None if store is None else store.path)
