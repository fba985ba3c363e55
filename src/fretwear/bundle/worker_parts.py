"""A group of contacts whose rows its worker writes as a part file itself (issue 28).

Written by the client, a part cost it some 0.16 ms a contact (the rows gathered from the
worker, unpickled, put end to end, converted and written: 16 ms a part of 100 contacts on an
idle core), CPU taken from the workers on a small machine, beside the rows' trip through
Dask. A worker that sees the output directory writes its group's rows as
``parts/<stem>.<format>`` (atomically, :func:`fretwear.bundle.rows_files.write_rows`) and sends
back the records without their rows; the client then writes the part's JSON
(:meth:`fretwear.bundle.store.OutputDirectory.record_part`). A part exists only once its
JSON is written, so a worker's rows file is never half-visible: one without its JSON (the
worker or the client died in between) is ignored by the next run and removed by its cleanup,
and the retry of a task whose worker died writes the same file again.

Whether a worker sees the directory is asked, not assumed (a cluster joined by its address
may run elsewhere): the client writes a marker file ``parts/.shared-<token>`` holding its
token, and a worker writes rows only where it reads that token there; elsewhere it sends them
back as before and the client writes them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fretwear.bundle.store import MARKER, write_rows
from fretwear.bundle.tasks import run_contacts


@dataclass(frozen=True)
class PartTarget:
    """Where a worker writes a group's rows: ``parts/<stem>.<table_format>``, when the marker
    ``parts/.shared-<token>`` holds ``token`` as the worker reads it."""

    parts: str
    stem: str
    table_format: str
    token: str

    @property
    def rows_file(self) -> str:
        """The rows file's name in ``parts/``."""
        return f"{self.stem}.{self.table_format}"

    def shared(self) -> bool:
        """Whether this process sees the client's output directory (its marker)."""
        try:
            return (Path(self.parts) / f"{MARKER}{self.token}").read_text(
                encoding="utf-8") == self.token
        except OSError:
            return False

    def write(self, records: list[Any]) -> list[Any]:
        """Write the rows of ``records`` (those with a table) as the part's rows file and take
        them out of the records (``table`` None, ``rows_file`` the file's name); the records
        as they are where the directory is not seen here or no record has rows."""
        dicts = [r for r in records if isinstance(r, dict)]
        if not any(r.get("table") is not None for r in dicts) or not self.shared():
            return records
        for r in write_rows(dicts, Path(self.parts) / self.rows_file, self.table_format):
            r["table"] = r["state"] = None
            r["rows_file"] = self.rows_file
        return records


def run_contacts_into(group: tuple[list, PartTarget], chunk_size: int = 1_000_000
                      ) -> list[dict[str, Any]]:
    """:func:`fretwear.bundle.tasks.run_contacts` of a group ``(tasks, target)``, its rows
    written by :meth:`PartTarget.write`."""
    tasks, target = group
    return target.write(run_contacts(tasks, chunk_size))


def written_by_worker(record: Any, target: PartTarget) -> bool:
    """Whether a record came back with its rows in ``target``'s file."""
    return isinstance(record, dict) and record.get("rows_file") == target.rows_file \
        and record.get("table") is None
