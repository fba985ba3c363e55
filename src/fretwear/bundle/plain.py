"""A bundle record's values made plain (JSON-ready) in the worker, and equal ones made one.

A contact's record goes back to the client pickled with the others of its task, and the client
writes it as JSON (:meth:`fretwear.bundle.store.OutputDirectory.record_part`): its values are
plain Python (:func:`plain`), and the equal lists and dicts of a case's contacts one object
(:func:`interned`), pickled once per task and compacted once per part.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def plain(value: Any) -> Any:
    """``value`` JSON-ready: dicts (string keys) and lists of plain numbers and strings, a
    number not finite None, numpy arrays and scalars as Python's, anything else its str."""
    kind = type(value)
    if kind is float:  # the commonest first (a record holds some fifty values)
        return value if math.isfinite(value) else None
    if value is None or kind is str or kind is int or kind is bool:
        return value
    if kind is np.ndarray and value.ndim == 1 and value.dtype.kind == "f" \
            and value.dtype.itemsize <= 8:  # tolist() gives Python floats (not long doubles)
        # a power's blocks and sectors: the list's floats checked in place, not one call each
        isfinite = math.isfinite
        return [v if isfinite(v) else None for v in value.tolist()]
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value if value is None or isinstance(value, bool | int | float | str) else str(value)


#: Equal plain values of contacts' records made one object in this process (:func:`interned`),
#: at most this many kept.
INTERNED_MAX = 256
_VALUES: dict[tuple, Any] = {}


def interned(key: str, value: Any) -> Any:
    """``value`` (plain: :func:`plain`), or the equal one this process already holds under
    ``key``: the coefficients and sector edges of a case's contacts are mostly equal, and as
    one object they are pickled once per task and compacted once per part by the client
    (``OutputDirectory.compact``: a ``repr`` per contact otherwise). Equal means the same
    JSON text: values are compared with their types (``1`` is not ``1.0``), signs (``-0.0``
    is not ``0.0``) and dict order.

    Examples
    --------
    >>> a = interned("sector_edges", [0.0, 90.0])
    >>> interned("sector_edges", [0.0, 90.0]) is a, interned("sector_edges", [-0.0, 90.0]) is a
    (True, False)
    """
    frozen = _frozen(value)
    if frozen is None:
        return value
    known = _VALUES.get((key, frozen))
    if known is not None:
        return known
    if len(_VALUES) >= INTERNED_MAX:
        _VALUES.clear()
    _VALUES[(key, frozen)] = value
    return value


def _frozen(value: Any) -> tuple | None:
    """A hashable image of a plain list or dict (its items' types and values, in order), or
    None for a value not worth it (a scalar, None) or not made of plain items."""
    if isinstance(value, list):
        pairs = [(None, v) for v in value]
    elif isinstance(value, dict):
        pairs = list(value.items())
    else:
        return None
    items = []
    for k, v in pairs:
        kind = type(v)
        if kind is float:  # -0.0 == 0.0, but JSON writes them apart
            items.append((k, kind, v, math.copysign(1.0, v)))
        elif v is None or kind is int or kind is str or kind is bool:
            items.append((k, kind, v))
        else:
            return None
    return (type(value), tuple(items))
