"""Code_Aster text tables of plain numbers parsed with numpy: the fast path of
:mod:`fretwear.io.aster` for the small tables a restart reads (ETAT_INIT, theory §7).

A table whose cells are all decimal numbers or ``-`` (an empty cell) is split into tokens and
converted by numpy in one call; the frame is the one the general path (pandas' C parser, then a
column-by-column conversion) makes of the same text: the same values (numpy and pandas both
round a decimal to the nearest float64), dtypes (``R`` -> float64, ``I`` -> int64, or Int64 with
an empty cell), column names, index and ``attrs``. Anything else (strings, quotes, Fortran ``D``
exponents, ragged rows, long tables; pandas before 3.1, whose parser may round differently)
returns None and takes the general path, which also words every error. Values carry no unit
(Code_Aster tables carry none).
"""

from __future__ import annotations

import functools
import re

import numpy as np

from fretwear._lazy import pandas as pd

__all__ = ["PLAIN_MAX_CELLS", "plain_frame"]

#: A cell of a table of plain numbers (:func:`plain_frame`): ``-`` or a decimal number, with or
#: without a point and an exponent (no Fortran ``D``, no ``nan``/``inf`` words, no quotes).
_PLAIN_CELL = r"(?:-|[+-]?(?:\d+\.?\d*|\.\d+)(?:[Ee][+-]?\d+)?)"
_PLAIN_COLUMN = re.compile(rf"{_PLAIN_CELL}(?: {_PLAIN_CELL})*")
#: Cells up to which a table of plain numbers is parsed by :func:`plain_frame` (restart tables:
#: a few instants and sectors); larger tables (histories) take pandas' C parser, faster there
#: (measured: 8 columns, 50 rows 0.3 ms against 1.1 ms, 200 rows even).
PLAIN_MAX_CELLS = 1000


@functools.cache
def _same_rounding() -> bool:
    """Whether pandas' C parser rounds every decimal to the nearest float64 as numpy does:
    pandas >= 3.1 (one converter for every float_precision; checked on 300 000 random float64
    and 20 000 halfway cases printed with 6 to 31 digits). Before it, its default converter may
    differ in the last bit on long mantissas: the fast path is not taken."""
    import pandas  # (imported by now: the frame is made with it)

    match = re.match(r"(\d+)\.(\d+)", pandas.__version__)
    return match is not None and (int(match[1]), int(match[2])) >= (3, 1)


@functools.lru_cache(maxsize=64)
def _column_index(names: tuple[str, ...]) -> pd.Index:
    """The columns' index of these names (each frame gets a copy: its name stays its own)."""
    return pd.Index(list(names))


def plain_frame(raw: dict, names: list[str]) -> pd.DataFrame | None:
    """The frame of a table whose cells are all decimal numbers or ``-`` (a restart table),
    parsed with numpy, columns named ``names``: the frame the general path of
    :func:`fretwear.io.aster._convert` makes of it (the same values: numpy and pandas both
    round every decimal to the nearest float64; the same dtypes, types and attrs), or None for
    any other table (strings, quotes, Fortran ``D``, ragged rows, a column all ``-``, integers
    of 19 characters or more, declared types other than the cells' R / I, more than
    :data:`PLAIN_MAX_CELLS` cells, a pandas before 3.1), which takes the general path.
    """
    types, rows = raw["types"], raw["rows"]
    ncol = len(names)
    if not _same_rounding():
        return None
    if not rows or len(rows) * ncol > PLAIN_MAX_CELLS or (types is not None
                                                          and len(types) != ncol):
        return None
    split = [text.split() for _, text in rows]
    if any(len(cells) != ncol for cells in split):
        return None
    kinds = []
    for j, col in enumerate(zip(*split, strict=True)):
        text = " ".join(col)
        if _PLAIN_COLUMN.fullmatch(text) is None or col.count("-") == len(col):
            return None
        real = "." in text or "e" in text or "E" in text  # as _infer_type: digits, signs -> I
        if not real and max(map(len, col)) > 18:  # beyond int64: the general path decides
            return None
        kinds.append("R" if real else "I")
        if types is not None and types[j] != kinds[-1]:
            return None
    cells = np.array(split)
    values = np.where(cells == "-", "nan", cells).astype(float)
    if "I" not in kinds:
        frame = pd.DataFrame(values, columns=_column_index(tuple(names)).copy())
    else:  # integer columns as in _convert: int64, or Int64 with a missing value
        series = {}
        for j, kind in enumerate(kinds):
            col = values[:, j].copy()
            series[j] = pd.Series(col) if kind == "R" else (
                pd.Series(col).astype("Int64") if np.isnan(col).any()
                else pd.Series(col.astype(np.int64)))
        frame = pd.DataFrame(series)
        frame.columns = _column_index(tuple(names)).copy()
    frame.attrs.update(title="\n".join(raw["title"]), types=kinds, format=raw["format"])
    return frame
