"""Immutable mappings and JSON-ready values for :class:`fretwear.table.WearCase`.

:class:`FrozenMap` is the read-only, hashable, picklable mapping of the case's dict-valued
fields; :func:`jsonable` turns nested values into JSON-ready ones (NaN written as None, so the
text is strict JSON); :func:`state_to_dict` / :func:`state_from_dict` carry a restart state
(:class:`~fretwear.table.restart.InitialState`, its table rows included) through JSON exactly
(``json`` writes floats with ``repr``, which round-trips every float64).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.table.restart import InitialState

__all__ = ["FrozenMap", "jsonable", "state_from_dict", "state_to_dict"]


class FrozenMap(Mapping):
    """A read-only, hashable, picklable mapping (the dict-valued fields of :class:`WearCase`).

    Examples
    --------
    >>> m = FrozenMap({"mobile_radius": 0.01})
    >>> m["mobile_radius"], m == {"mobile_radius": 0.01}
    (0.01, True)
    """

    __slots__ = ("_data",)

    def __init__(self, data: Mapping | None = None) -> None:
        object.__setattr__(self, "_data", dict(data or {}))

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def items(self):
        """The items' view of the underlying dict (read-only: a view has no setter)."""
        return self._data.items()

    def __hash__(self) -> int:
        return hash(tuple(self._data.items()))

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("FrozenMap is read-only")

    def __reduce__(self):
        return (FrozenMap, (self._data,))

    def __repr__(self) -> str:
        return repr(self._data)



_PLAIN = frozenset({str, int, bool, type(None)})


def jsonable(value: Any) -> Any:
    """Nested tuples/mappings/numpy values as JSON-ready lists/dicts/numbers; NaN -> None."""
    kind = type(value)
    if kind in _PLAIN:  # the common leaves first (the Mapping check below is slow)
        return value
    if kind is float:
        return None if math.isnan(value) else value
    if kind is dict or kind is FrozenMap:  # (before the slow abstract Mapping check)
        return {str(k): jsonable(v) for k, v in value.items()}
    if kind is tuple or kind is list:
        return [jsonable(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple | np.ndarray):
        return [jsonable(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


_FLOAT64 = np.dtype(np.float64)


def _rows(rows: pd.DataFrame, dtypes=None) -> dict[str, list]:
    """The rows' columns, dtype names and values as JSON-ready lists (NaN as None): the values
    of ``jsonable(rows[c].tolist())`` per column, in one numpy pass when every column is
    float64 (a restart table's rows). ``dtypes``: the columns' dtypes, when known."""
    dtypes = list(rows.dtypes if dtypes is None else dtypes)
    columns = [str(c) for c in rows.columns]
    if dtypes and all(t is _FLOAT64 for t in dtypes):  # (numpy's one float64 dtype)
        values = rows.to_numpy(dtype=float).T.tolist()
        if any(v != v for column in values for v in column):  # NaN
            values = [[None if v != v else v for v in column] for column in values]
        return {"columns": columns, "dtypes": ["float64"] * len(dtypes), "data": values}
    return {"columns": columns, "dtypes": [str(t) for t in dtypes],
            "data": [jsonable(rows[c].tolist()) for c in rows.columns]}


def state_to_dict(state: InitialState) -> dict[str, Any]:
    """The JSON-ready dict of a restart state (NaN as None; :func:`jsonable` keeps it as is)."""
    return {
        "origin": jsonable(float(state.origin)),
        "volume_mobile": jsonable(float(state.volume_mobile)),
        "volume_obstacle": jsonable(float(state.volume_obstacle)),
        "sector_volume_mobile": jsonable(state.sector_volume_mobile),
        "sector_volume_obstacle": jsonable(state.sector_volume_obstacle),
        "edges": jsonable(state.edges),
        "rows": _rows(state.rows, state.row_dtypes),
    }


def _number(value) -> float:
    """A number of :func:`state_to_dict` (None: NaN, as :func:`jsonable` wrote it)."""
    return math.nan if value is None else float(value)


def _array(values) -> np.ndarray | None:
    return None if values is None else np.array(
        [np.nan if v is None else v for v in values], dtype=float)


def state_from_dict(data: Mapping[str, Any]) -> InitialState:
    if isinstance(data, InitialState):
        return data
    rows = data["rows"]
    columns = {}
    for name, dtype, values in zip(rows["columns"], rows["dtypes"], rows["data"], strict=True):
        if dtype.startswith(("float", "Float")):
            values = [np.nan if v is None else v for v in values]
        columns[name] = pd.Series(values, dtype=dtype)
    frame = pd.DataFrame(columns, columns=list(rows["columns"]))
    return InitialState(_number(data["origin"]), _number(data["volume_mobile"]),
                        _number(data["volume_obstacle"]), _array(data["sector_volume_mobile"]),
                        _array(data["sector_volume_obstacle"]), _array(data["edges"]), frame)
