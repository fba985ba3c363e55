"""A part's JSON (``parts/part-<run>-<n>.json``): its contacts' records, what they share once.

The records of a part's contacts repeat their case's table metadata (geometry, coefficients,
sector edges, time scale, depth limit ...: some 600 bytes a contact); only the power is each
contact's own. A part is written (:func:`part_text`) as::

    {"part": stem, "rows_file": name, "shared_attrs": [attrs, ...], "contacts": [record, ...]}

where a record whose ``attrs`` is a dict holds in ``attrs`` its own values alone
(:data:`OWN`: the power) and in ``shared`` the index of the entry of ``shared_attrs`` holding
the others, in the record's order (an own key there as null: the place it takes).
:func:`records_of` reads a part of either form back: this one, or the one written until now
(every record's whole ``attrs``, no ``shared_attrs``), giving the same records, their keys in
the same order. Encoding each case's values once per part, not once per contact, halves the
client's ``json.dumps`` of a part (issue 28: 2.35 s of the client's CPU at 10^5 contacts went
into the parts' JSON).
"""

from __future__ import annotations

import json
import math
from typing import Any

#: A record's keys not written: its rows (in the rows file), the worker's state, the part's
#: names (the part's own keys).
NOT_WRITTEN = frozenset(("table", "state", "rows_file", "part"))
#: The ``attrs`` values each contact has its own, written in its record.
OWN = ("power",)
#: Scalar types compared by value (with the type: 1, 1.0 and True are written apart) when
#: records' values are found the same; any other scalar by the object.
BY_VALUE = frozenset((str, int, float, bool, type(None)))


def signature(attrs: dict[str, Any]) -> tuple:
    """What makes two records' ``attrs`` the same once written, their own values (:data:`OWN`)
    aside: the keys in order; each dict or list by the object (the caller's compacted values:
    one object for equal ones); a str, int, float, bool or None by its type and value (a zero
    also by its sign: -0.0 is written apart); anything else by the object. Equal signatures:
    the same JSON text of the shared values."""
    sig: list[Any] = [tuple(attrs)]
    append = sig.append
    for key, value in attrs.items():
        kind = type(value)
        if kind in BY_VALUE:
            append(kind)
            append(value)
            if kind is float and value == 0.0:
                append(math.copysign(1.0, value))
        elif key not in OWN:
            append(id(value))  # an int where a value's entry starts with its type: apart
    return tuple(sig)


def part_text(stem: str, rows_file: str | None, records: list[dict[str, Any]]) -> str:
    """The part's JSON (see the module's docstring), one line, by ``json.dumps``'s C encoder
    (json.dump to a file, or any indent, takes the pure-Python one: 0.2 s for the records of
    500 contacts); without the check of circular references (an id kept for every dict and
    list: 10 % of the encoding), which a record, plain data from a worker's pickle, cannot
    hold. Each record's ``attrs`` should be compacted (equal dicts and lists one object:
    :meth:`fretwear.bundle.store.OutputDirectory.compact`), else each is its own entry."""
    index: dict[tuple, int] = {}
    shared: list[dict[str, Any]] = []
    contacts = []
    for r in records:
        rec = {k: v for k, v in r.items() if k not in NOT_WRITTEN}
        attrs = rec.get("attrs")
        if type(attrs) is dict:
            sig = signature(attrs)
            k = index.get(sig)
            if k is None:
                k = index[sig] = len(shared)
                shared.append({key: None if key in OWN else v for key, v in attrs.items()})
            rec["attrs"] = {key: attrs[key] for key in OWN if key in attrs}
            rec["shared"] = k
        contacts.append(rec)
    meta = {"part": stem, "rows_file": rows_file, "shared_attrs": shared, "contacts": contacts}
    return json.dumps(meta, default=str, check_circular=False)


def records_of(data: dict[str, Any]) -> list[dict[str, Any]]:
    """The records of a part's JSON (``json.loads`` of its text), of either form: each
    record's ``attrs`` whole, its keys in the written order (a record's shared values are the
    entry's objects: not to be changed in place)."""
    contacts = data.get("contacts", [])
    shared = data.get("shared_attrs")
    if shared is None:  # written before the shared entries: every record whole
        return contacts
    for rec in contacts:
        k = rec.pop("shared", None)
        if k is not None:
            rec["attrs"] = {**shared[k], **rec["attrs"]}
    return contacts
