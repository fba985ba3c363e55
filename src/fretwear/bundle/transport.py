"""How a task's records travel from a worker to the client: one pickle a task, its contacts'
tables laid end to end one array per column (:func:`pickled`, :func:`unpickled`; issue 28)."""

from __future__ import annotations

import pickle
from typing import Any

import numpy as np


def pickled(fn, *args) -> bytes:
    """``fn(*args)`` pickled in one piece, for a task whose result goes back to the client.

    A task's records hold a packed table each (some twenty small numpy arrays) and nested
    metadata; Dask would serialise every array of every record as a frame of its own (541
    frames for a task of 15 contacts: 3.3 ms to send, 2.1 ms to receive, 0.5 ms to size),
    where one pickle takes 0.4 ms and 0.25 ms (docs/bundle.md). The records of a group of
    contacts go with their tables laid end to end, one array per column (:func:`blocked`):
    unpickling an array costs the same whatever its length, and the client unpickled some
    twenty per contact (1 s of its CPU for 20 000 contacts, taken from the workers on a small
    machine). The client reads it with :func:`unpickled`
    (:class:`fretwear.bundle.cluster.DaskEngine`).
    """
    value = fn(*args)
    if isinstance(value, list):
        value = blocked(value)
    return pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)


def unpickled(data: bytes) -> Any:
    """The value :func:`pickled` pickled (a group's records as :func:`run_contacts` gave them,
    each table's arrays slices of its block)."""
    value = pickle.loads(data)
    if isinstance(value, tuple) and len(value) == 3 and isinstance(value[0], str) \
            and value[0] == _BLOCKS:
        return unblocked(value)
    return value


_BLOCKS = "fretwear-bundle-blocks"


def blocked(records: list[Any]) -> Any:
    """``(marker, records, blocks)``: the records with their packed tables taken out and laid
    end to end, one array per column, for each layout of columns and dtypes among them (a
    contact with sectors and one without have two); the records themselves otherwise the same.
    Records without a table, or a table that is not a set of equal-length 1-D arrays, stay
    as they are. :func:`unblocked` gives the records back with equal tables (bit for bit).

    Examples
    --------
    >>> a = {"contact": "A", "table": {"columns": ["x"], "arrays": [np.array([1.0, 2.0])]}}
    >>> b = {"contact": "B", "table": None}
    >>> c = {"contact": "C", "table": {"columns": ["x"], "arrays": [np.array([3.0])]}}
    >>> marker, light, blocks = blocked([a, b, c])
    >>> blocks
    [(['x'], [array([1., 2., 3.])], [0, 2], [2, 1])]
    >>> [r["table"]["arrays"][0].tolist() for r in unblocked((marker, light, blocks))
    ...  if r["table"] is not None]
    [[1.0, 2.0], [3.0]]
    """
    layouts: dict[tuple, list[int]] = {}
    for i, record in enumerate(records):
        table = record.get("table") if isinstance(record, dict) else None
        if table is None:
            continue
        arrays = table["arrays"]
        if not arrays or not all(isinstance(a, np.ndarray) and a.ndim == 1 for a in arrays) \
                or len({len(a) for a in arrays}) != 1:
            continue
        signature = (tuple(table["columns"]), tuple(a.dtype.str for a in arrays))
        layouts.setdefault(signature, []).append(i)
    if not layouts:
        return records
    light = [dict(r) if isinstance(r, dict) else r for r in records]
    blocks = []
    for (columns, _), members in layouts.items():
        tables = [records[i]["table"] for i in members]
        arrays = [np.concatenate([t["arrays"][j] for t in tables])
                  for j in range(len(columns))]
        for i in members:
            light[i]["table"] = None
        blocks.append((list(columns), arrays, members, [len(t["arrays"][0]) for t in tables]))
    return (_BLOCKS, light, blocks)


def unblocked(value: tuple) -> list[Any]:
    """The records of :func:`blocked` with their tables back (slices of the blocks)."""
    _, records, blocks = value
    for columns, arrays, members, lengths in blocks:
        start = 0
        for i, length in zip(members, lengths, strict=True):
            stop = start + length
            records[i]["table"] = {"columns": list(columns),
                                   "arrays": [a[start:stop] for a in arrays]}
            start = stop
    return records
