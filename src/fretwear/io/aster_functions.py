"""Code_Aster IMPR_FONCTION TABLEAU prints: the functions of a table, laid side by side.

IMPR_FONCTION ``FORMAT='TABLEAU'`` (Code_Aster ``MacroCommands/impr_fonction_ops.py``,
``Objects/table_graph.py`` ``TraceTableau``) prints, per command, one table: the abscissa of the
first function and one column per COURBE (every function interpolated on those abscissas),
labelled ``<NOM_RESU>_<curve number>``, the title listing ``Courbe i`` and each curve's legend.
Several commands printing to one unit append one table each; tables laid out as
``(abscissa, value)`` pairs side by side (files joined by hand, older prints) are read too.
The table itself is read by :func:`fretwear.io.aster.read_aster_table`.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FormatError

__all__ = ["function_pairs", "curve_legends", "is_function_table", "function_columns",
           "check_same_abscissa", "stack_functions"]


def function_pairs(frame: pd.DataFrame, label: str) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Split an IMPR_FONCTION TABLEAU table into functions: ``(name, abscissa, values)``.

    The columns come in pairs (abscissa, ordinate); the name is the ordinate's column name.

    Examples
    --------
    >>> from fretwear.io.aster import read_aster_table
    >>> f = read_aster_table("#\\n#FONCTION\\nINST FN INST VT1\\n0 1 0 2\\n1 3 1 4\\n")
    >>> [(n, x.tolist(), y.tolist()) for n, x, y in function_pairs(f, "x")]
    [('FN', [0.0, 1.0], [1.0, 3.0]), ('VT1', [0.0, 1.0], [2.0, 4.0])]
    """
    ncol = frame.shape[1]
    if ncol < 2 or ncol % 2:
        raise FormatError(f"{label}: an IMPR_FONCTION TABLEAU file has two columns per function "
                          f"(abscissa, value); found {ncol} columns {list(frame.columns)}")
    out = []
    for j in range(0, ncol, 2):
        try:
            x = frame.iloc[:, j].to_numpy(dtype=float)
            y = frame.iloc[:, j + 1].to_numpy(dtype=float)
        except (TypeError, ValueError):
            raise FormatError(f"{label}: function columns {list(frame.columns[j:j + 2])} are "
                              "not numeric") from None
        out.append((str(frame.columns[j + 1]), x, y))
    return out


_CURVE = re.compile(r"^courbe\s+(\d+)\b\s*(.*)$", re.IGNORECASE)


def curve_legends(title: str) -> list[str]:
    """Legends of the curves listed in the title of an IMPR_FONCTION TABLEAU table.

    IMPR_FONCTION writes, for curve ``i``, a line ``Courbe i`` followed by a line holding its
    LEGENDE (by default the function's concept name); older versions write ``Courbe i legend``
    on one line (Code_Aster ``Objects/table_graph.py``, ``TraceTableau``).

    Examples
    --------
    >>> curve_legends("Courbe 0\\nFN_N12\\nCourbe 1\\nVT1_N12")
    ['FN_N12', 'VT1_N12']
    >>> curve_legends("Courbe 0 FN"), curve_legends("TABLE_SDASTER")
    (['FN'], [])
    """
    lines = [ln.strip().lstrip("#").strip() for ln in str(title).splitlines()]
    lines = [ln for ln in lines if ln]
    legends = []
    for k, line in enumerate(lines):
        match = _CURVE.match(line)
        if match:
            legend = match.group(2).strip()
            if not legend and k + 1 < len(lines) and not _CURVE.match(lines[k + 1]):
                legend = lines[k + 1]
            legends.append(legend)
    return legends


def is_function_table(frame: pd.DataFrame) -> bool:
    """Whether a table is laid out as IMPR_FONCTION TABLEAU functions.

    True for ``(abscissa, value)`` pairs side by side that share one abscissa name (two or more
    functions), and for a table whose title lists ``Courbe i`` lines (one abscissa, then one
    column per function).

    Examples
    --------
    >>> from fretwear.io.aster import read_aster_table
    >>> is_function_table(read_aster_table("#\\n#x\\nINST FN INST VT1\\n0 1 0 2\\n"))
    True
    >>> is_function_table(read_aster_table("#\\n#Courbe 0\\n#FN\\nINST FN_0\\n0 1\\n"))
    True
    >>> is_function_table(read_aster_table("#\\n#x\\nINST FN VT1\\n0 1 2\\n"))
    False
    """
    names = [str(c) for c in frame.columns]
    pairs = (len(names) >= 4 and len(names) % 2 == 0 and len(set(names[0::2])) == 1
             and len(set(names[1::2])) == len(names) // 2)
    return pairs or bool(curve_legends(frame.attrs.get("title", "")))


def function_columns(frame: pd.DataFrame, label: str
                     ) -> list[tuple[str, str, np.ndarray, np.ndarray]]:
    """The functions of an IMPR_FONCTION TABLEAU table: ``(name, legend, abscissa, values)``.

    Two layouts (Code_Aster ``TraceTableau``): ``(abscissa, value)`` pairs side by side with one
    abscissa name repeated, or one abscissa column then one column per function (IMPR_FONCTION
    with several COURBE interpolates them all on the first one's abscissas). ``name`` is the
    value column's name (``VINT1_0``: IMPR_FONCTION appends ``_<curve number>``), ``legend`` the
    curve's legend from the title ('' when absent).

    Examples
    --------
    >>> from fretwear.io.aster import read_aster_table
    >>> f = read_aster_table("#\\n#Courbe 0\\n#FN\\n#Courbe 1\\n#VT\\nINST A_0 B_1\\n0 1 2\\n")
    >>> [(n, g, x.tolist(), y.tolist()) for n, g, x, y in function_columns(f, "x")]
    [('A_0', 'FN', [0.0], [1.0]), ('B_1', 'VT', [0.0], [2.0])]
    """
    names = [str(c) for c in frame.columns]
    legends = curve_legends(frame.attrs.get("title", ""))
    pairs = (len(names) >= 4 and len(names) % 2 == 0 and len(set(names[0::2])) == 1
             and len(set(names[1::2])) == len(names) // 2)
    if pairs:
        found = [(name, x, y) for name, x, y in function_pairs(frame, label)]
    else:
        if len(names) < 2:
            raise FormatError(f"{label}: an IMPR_FONCTION TABLEAU table has an abscissa column "
                              f"and at least one value column; found {names}")
        try:
            x = frame.iloc[:, 0].to_numpy(dtype=float)
            found = [(names[j], x, frame.iloc[:, j].to_numpy(dtype=float))
                     for j in range(1, len(names))]
        except (TypeError, ValueError):
            raise FormatError(f"{label}: function columns {names} are not all numeric") from None
    if legends and len(legends) != len(found):
        legends = []
    return [(name, legends[k] if legends else "", x, y) for k, (name, x, y) in enumerate(found)]


def check_same_abscissa(reference: tuple[str, np.ndarray], other: tuple[str, np.ndarray]) -> None:
    """Raise :class:`FormatError` unless two functions share their time column.

    The tolerance is 1e-9 of the largest |time|: files printed by the same run with the same
    format agree exactly; a different sampling does not.
    """
    (label_a, ta), (label_b, tb) = reference, other
    if ta.size != tb.size:
        raise FormatError(f"{label_b}: {tb.size} instants but {label_a} has {ta.size}; the "
                          "functions of one history must share their instants (same "
                          "LIST_INST / archiving)")
    scale = max(float(np.max(np.abs(ta), initial=0.0)), np.finfo(float).tiny)
    diff = np.abs(ta - tb) > 1e-9 * scale
    if diff.any():
        i = int(np.flatnonzero(diff)[0])
        raise FormatError(f"{label_b}: instant at row {i} is {float(tb[i])!r} but {label_a} "
                          f"has {float(ta[i])!r}; the functions of one history must share "
                          "their instants")


def stack_functions(functions: Sequence[tuple[str, str, np.ndarray, np.ndarray]]
                    ) -> tuple[list[str], list[np.ndarray]]:
    """Columns ``time, name...`` of functions ``(label, name, abscissa, values)`` that share
    their instants (checked with :func:`check_same_abscissa`, ``label`` naming each one).

    Examples
    --------
    >>> t = np.array([0.0, 1.0])
    >>> stack_functions([("a", "FN", t, t + 1), ("b", "VT1", t.copy(), t + 2)])[0]
    ['time', 'FN', 'VT1']
    """
    label, _, reference, _ = functions[0]
    for other, _, x, _ in functions[1:]:
        check_same_abscissa((label, reference), (other, x))
    return ["time", *(f[1] for f in functions)], [reference, *(f[3] for f in functions)]
