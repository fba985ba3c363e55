"""The rows of ``BundleResult.contacts`` but the identity: one per contact, from its final
record and its wear case, made while the results arrive (:class:`ContactRows`).

At 10^5 contacts these rows took 0.46 s of the client's CPU after the last result, the first
thing of the bundle's end, before the dataset's coordinates could be written (issue 28): a
contact's row is made when its record is final (its part written), while the workers
compute, and the end only checks that the record is still the one its row was made of.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from fretwear._lazy import pandas as pd

#: What a contact's wear case gives to its row (the record's ``attrs`` where it has no case):
#: the column and the case's attribute.
OF_CASE = (("origin", "origin"), ("tube_replacement", "restart.tube_replacement"),
           ("wall_thickness", "wall.thickness"), ("depth_limit", "wall.limit"),
           ("contact_type", "contact_type"), ("dimensions", "dimensions"), ("law", "law"),
           ("time_scale", "time_scale"))

#: The columns of a row, in order.
COLUMNS = ("contact", "status", "samples", "seconds", "power", "time_unit",
           *(name for name, _ in OF_CASE if name != "time_scale"),
           "coefficients_mobile", "coefficients_obstacle", "time_scale", "sector_coefficients")

_DIMENSIONS = [name for name, _ in OF_CASE].index("dimensions")


class ContactRows:
    """The contacts' rows (:data:`COLUMNS`): its record's status and computed values
    (``samples``, ``seconds`` [s], ``power`` [W], resolved coefficients), and what its wear
    case says (``cases[c]``, carried by the run; the record's metadata for a contact whose rows
    are an earlier run's or that failed).

    Parameters
    ----------
    order : list of str
        The manifest's contacts, in order.
    cases : dict
        ``{contact: its WearCase}`` of this run (filled as the tasks are built: read when a
        row is made).
    """

    def __init__(self, order: list[str], cases: dict[str, Any]) -> None:
        self.order, self.cases = order, cases
        self.position = {c: i for i, c in enumerate(order)}
        # per position: (the record, its attrs, its status, the row made of them) or None
        self.made: list[tuple | None] = [None] * len(order)
        self._of_case: dict[int, tuple] = {}  # id(case) -> (case, its values in OF_CASE's order)

    def add(self, records: Iterable[dict[str, Any]]) -> None:
        """Make the rows of these final records (their attrs as they will stay: after their
        part is written, which shares them with the other contacts')."""
        for rec in records:
            pos = self.position.get(rec["contact"])
            if pos is not None:
                attrs = rec.get("attrs")
                self.made[pos] = (rec, attrs, rec["status"], self._row(rec, attrs))

    def frame(self, records: dict[str, dict[str, Any]]) -> pd.DataFrame:
        """Every contact's row, as a DataFrame of :data:`COLUMNS`: those made by :meth:`add`
        whose record, attrs and status are still the contact's, the others made here."""
        rows = []
        for c, known in zip(self.order, self.made, strict=True):
            rec = records[c]
            attrs = rec.get("attrs")
            if known is None or known[0] is not rec or known[1] is not attrs \
                    or known[2] != rec["status"]:
                rows.append(self._row(rec, attrs))
            else:
                rows.append(known[3])
        columns = zip(*rows, strict=True) if rows else [()] * len(COLUMNS)
        return pd.DataFrame({name: list(values) for name, values
                             in zip(COLUMNS, columns, strict=True)})

    def _row(self, rec: dict[str, Any], attrs: dict | None) -> tuple:
        """One contact's row: its case's values where it has a case this run (done or
        skipped) and attrs, else its record's."""
        a = attrs or {}
        status = rec["status"]
        case = self.cases.get(rec["contact"]) if status in ("done", "skipped") and a else None
        if case is None:
            carried = [a.get(name) for name, _ in OF_CASE]
        else:
            carried = list(self._values(case))
            carried[_DIMENSIONS] = dict(carried[_DIMENSIONS])  # a row's dict is its own
        return (rec["contact"], status, rec.get("samples", 0), rec.get("seconds", 0.0),
                (a.get("power") or {}).get("total"), a.get("time_unit"), *carried[:-1],
                a.get("coefficients_mobile"), a.get("coefficients_obstacle"), carried[-1],
                a.get("sector_coefficients"))

    def _values(self, case) -> tuple:
        """The case's values in :data:`OF_CASE`'s order, taken once per case object (the
        contacts of a bundle share a few)."""
        known = self._of_case.get(id(case))
        if known is None or known[0] is not case:
            values = []
            for _, path in OF_CASE:
                value = case
                for name in path.split("."):
                    value = getattr(value, name)
                values.append(value)
            known = self._of_case[id(case)] = (case, tuple(values))
        return known[1]

