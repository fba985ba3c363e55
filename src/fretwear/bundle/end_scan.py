"""What a bundle's end reads of every contact's final record, in one pass over them.

The end (:func:`fretwear.bundle.outputs.assemble`) went over the records of 10^5 contacts six
times (the cases, whether one holds rows, the outputs' digest, the news, the run's counts, the
parts to keep): 0.5 s of the client's CPU after the last result (issue 28). :func:`scan` makes
all of it in one pass.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

#: A skipped contact's record is its earlier done one (:func:`digest_row`).
_AS_DONE = {"skipped": "done"}


def digest_row(contact: str, rec: dict[str, Any]) -> list:
    """A record's share of :func:`fretwear.bundle.outputs.outputs_digest`: its contact, input
    key, status (a skipped contact counts as the done one it was) and the part holding its
    rows."""
    status = rec["status"]
    return [contact, rec.get("key"), _AS_DONE.get(status, status), rec.get("part"),
            rec.get("rows_file")]


@dataclass
class Scan:
    """:func:`scan`'s answer.

    Attributes
    ----------
    digest_rows : list
        :func:`digest_row` of every contact, in order.
    news : list of str
        The contacts with something to say (warnings, failed, stale), in order.
    computed, samples, two_pass : int
        Contacts computed this run (done or failed), their history samples, and those whose
        history was read twice (KWU-EPRI without FNOR_MAXI and VTAN_MAXI).
    cases : dict
        ``{contact: its WearCase}`` of the contacts whose rows are its (done, or skipped: done
        before with the same inputs); a failed contact has none, a stale one the rows of an
        earlier case.
    parts : set of str
        The parts the records refer to.
    tables : bool
        Whether some record holds its rows (no output directory, or not written yet).
    """

    digest_rows: list = field(default_factory=list)
    news: list = field(default_factory=list)
    computed: int = 0
    samples: int = 0
    two_pass: int = 0
    cases: dict = field(default_factory=dict)
    parts: set = field(default_factory=set)
    tables: bool = False


def scan(order: list[str], records: dict[str, dict[str, Any]],
         built: dict[str, Any] | None) -> Scan:
    """One pass over the records of ``order`` (see :class:`Scan`); ``built``: the wear cases
    of this run's contacts."""
    out = Scan()
    built = built or {}
    rows, news, cases, parts = out.digest_rows, out.news, out.cases, out.parts
    computed = samples = two_pass = 0
    tables = False
    for c in order:
        rec = records[c]
        status = rec["status"]
        rows.append(digest_row(c, rec))
        if status == "done" or status == "skipped":
            if c in built:
                cases[c] = built[c]
            if rec.get("warnings"):
                news.append(c)
        else:
            news.append(c)
        if status == "done" or status == "failed":
            computed += 1
            samples += rec.get("samples", 0)
            two_pass += rec.get("passes") == 2
        part = rec.get("part")
        if part:
            parts.add(part)
        if not tables and rec.get("table") is not None:
            tables = True
    out.computed, out.samples, out.two_pass, out.tables = computed, samples, two_pass, tables
    return out
