"""Contact histories from Code_Aster text files: IMPR_TABLE tables and IMPR_FONCTION functions.

The readers behind ``read_history(..., format="aster")`` and ``format="aster-function"``
(:data:`fretwear.io.FORMATS`). They decide which rows of a file are the history:

* ``index=`` / ``title=``: one table of a file holding several;
* ``node=``: the shock point (POST_USURE's NOEUD / GROUP_NO): the rows whose node column
  (``NOEUD``, ``NOEUD_CHOC``, ``GROUP_NO``, ``INTITULE`` ...) holds it, or the tables whose title
  names it; a node that the file's node column does not hold is an error;
* ``select=``: rows where any column equals a value (``"NOEUD=N12"``);
* IMPR_FONCTION: the functions of a file (several IMPR_FONCTION commands printing to one unit,
  or one command with several COURBE) are the channels of one history, named from their column
  header, their legend, or by the user in order (``functions=``).

Instants printed with too few digits (Code_Aster's default ``FORMAT_R='E12.5'``) repeat: the
error says so and gives the FORMAT_R to print with (:func:`duplicated_instants_message`).
"""

from __future__ import annotations

import copy
import os
import re
import stat
import threading
import time
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FormatError, HistoryError, KeywordError
from fretwear.io import aster as _aster
from fretwear.io import aster_functions as _functions
from fretwear.io.channels import Source, channel_of

__all__ = ["open_aster", "open_functions", "select_rows", "select_node", "shock_nodes",
           "NodeIndex", "node_index", "forget_node_index", "NODE_COLUMNS",
           "duplicated_instants_message"]

#: Column names that hold the shock point of a row (compared case-blind); also any column
#: whose name starts with NOEUD or GROUP_NO.
NODE_COLUMNS = ("NOEUD", "NOEUD_CHOC", "GROUP_NO", "GROUP_NO_CHOC", "INTITULE", "NOM_CHOC")
_SUFFIX = re.compile(r"^(?P<base>.+)_\d+$")


def select_rows(frame: pd.DataFrame, select: Any, label: str) -> pd.DataFrame:
    """Rows of a table where every ``{column: value}`` matches (``"COL=VALUE"`` too).

    Examples
    --------
    >>> f = pd.DataFrame({"NOEUD": ["N1", "N2"], "INST": [0.0, 0.0]})
    >>> select_rows(f, "noeud=N2", "t")["NOEUD"].tolist()
    ['N2']
    """
    if isinstance(select, str):
        column, sep, value = select.partition("=")
        if not sep:
            raise KeywordError(f"select={select!r}: give 'COLUMN=VALUE' (e.g. 'NOEUD=N12') or "
                               "a mapping {column: value}")
        select = {column.strip(): value.strip()}
    if not isinstance(select, Mapping) or not select:
        raise KeywordError(f"select={select!r}: give a mapping {{column: value}} or "
                           "'COLUMN=VALUE'")
    keep = np.ones(len(frame), dtype=bool)
    names = [str(c) for c in frame.columns]
    for column, value in select.items():
        hits = [j for j, c in enumerate(names) if c.upper() == str(column).upper()]
        if len(hits) != 1:
            raise KeywordError(f"{label}: select={{{column!r}: ...}}: no single column of that "
                               f"name; columns: {names}")
        cells = frame.iloc[:, hits[0]]
        match = cells.astype(str).str.strip() == str(value).strip()
        if not match.any():
            raise KeywordError(f"{label}: select: column {names[hits[0]]!r} never equals "
                               f"{value!r}; its values: {[str(v) for v in cells.unique()[:10]]}")
        keep &= match.to_numpy()
    out = frame.loc[keep].reset_index(drop=True)
    out.attrs.update(frame.attrs)
    return out


def _node_columns(frame: pd.DataFrame) -> list[int]:
    types = frame.attrs.get("types") or [None] * frame.shape[1]
    out = []
    for j, (name, kind) in enumerate(zip(frame.columns, types, strict=False)):
        upper = str(name).upper()
        text = kind is None or str(kind).startswith("K")
        if text and (upper in NODE_COLUMNS or upper.startswith(("NOEUD", "GROUP_NO"))):
            out.append(j)
    return out


def _names(title: str, node: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9]){re.escape(node)}(?![A-Za-z0-9])", title,
                     re.IGNORECASE) is not None


def shock_nodes(path: str | os.PathLike) -> list[str]:
    """The shock points a Code_Aster table file names in its node columns, in file order.

    Parameters
    ----------
    path : str or path-like
        An IMPR_TABLE print (TABLEAU or ASTER layout).

    Returns
    -------
    list of str
        The distinct labels of its node columns (:data:`NODE_COLUMNS`); empty when it has none.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "choc.tab"
    >>> _ = p.write_text("#\\n#TABLE_SDASTER\\nNOEUD INST VINT1\\nN12 0.0 1.0\\nN13 0.0 2.0\\n")
    >>> shock_nodes(p)
    ['N12', 'N13']
    """
    held: list[str] = []
    seen: set[str] = set()
    for frame in _aster.read_aster_tables(path):
        for j in _node_columns(frame):
            cells = frame.iloc[:, j].dropna().astype(str).str.strip()
            fresh = [v for v in cells.unique().tolist() if v and v not in seen]
            held += fresh
            seen.update(fresh)
    return held


def select_node(tables: Sequence[pd.DataFrame], node: str, label: str
                ) -> tuple[list[pd.DataFrame], bool]:
    """The tables (or rows) of one shock point, and whether the file could confirm it.

    Parameters
    ----------
    tables : sequence of DataFrame
        The tables of a file (:func:`fretwear.io.aster.read_aster_tables`).
    node : str
        The node or group label (POST_USURE's NOEUD or GROUP_NO), compared case-blind.
    label : str
        The file, for messages.

    Returns
    -------
    (tables, checked)
        The rows whose node column holds ``node`` (tables without such rows dropped), or the
        tables whose title names it; ``checked`` is False when the file holds no node at all
        (no node column, no title naming a node): then every table is returned unchanged.

    Raises
    ------
    KeywordError
        The file's node columns never hold ``node`` (their values are listed), or several tables
        and none names it.

    Examples
    --------
    >>> f = pd.DataFrame({"NOEUD": ["N12", "N13"], "INST": [0.0, 0.0]})
    >>> f.attrs["types"] = ["K8", "R"]
    >>> [t["NOEUD"].tolist() for t in select_node([f], "n13", "t")[0]]
    [['N13']]
    """
    return NodeIndex(tables).select(node, label)


class NodeIndex:
    """The tables of one Code_Aster file with the rows of every shock point found in one pass:
    :func:`select_node`'s answer for any node at the cost of that node's rows.

    Scanning a file's node columns for each node made a bundle of the 1 000 nodes of one table
    quadratic (the file parsed and scanned 1 000 times: 270 ms a node, against 76 ms at 250
    nodes); :func:`open_aster` keeps the index of the last file it read by node
    (:func:`node_index`).

    Parameters
    ----------
    tables : sequence of DataFrame
        The tables of a file (:func:`fretwear.io.aster.read_aster_tables`); not modified, and
        never handed out: :meth:`select` returns new frames.

    Attributes
    ----------
    held : list of str
        The distinct labels of the node columns in file order (:func:`shock_nodes`).
    """

    def __init__(self, tables: Sequence[pd.DataFrame]) -> None:
        self.tables = list(tables)
        self.held: list[str] = []
        self._rows: list[dict[str, np.ndarray] | None] = []
        seen: set[str] = set()
        for frame in self.tables:
            columns = _node_columns(frame)
            if not columns:
                self._rows.append(None)
                continue
            where: dict[str, list[np.ndarray]] = {}
            for j in columns:
                cells = frame.iloc[:, j].astype(str).str.strip()
                for v in cells.unique().tolist():
                    if v not in seen:
                        seen.add(v)
                        self.held.append(v)
                groups = pd.Series(np.arange(len(frame))).groupby(
                    cells.str.upper().to_numpy(dtype=object), sort=False).indices
                for key, positions in groups.items():
                    where.setdefault(key, []).append(positions)
            self._rows.append({k: np.unique(np.concatenate(v)) for k, v in where.items()})

    def select(self, node: str, label: str) -> tuple[list[pd.DataFrame], bool]:
        """:func:`select_node` of these tables (new frames; the same rows, order, dtypes and
        attributes)."""
        wanted = str(node).strip()
        key = wanted.upper()
        kept: list[pd.DataFrame] = []
        for frame, rows in zip(self.tables, self._rows, strict=True):
            if rows is not None:
                positions = rows.get(key)
                if positions is not None:
                    taken = frame.iloc[positions].reset_index(drop=True)
                    taken.attrs.update(copy.deepcopy(frame.attrs))  # not the kept table's lists
                    kept.append(taken)
            elif _names(str(frame.attrs.get("title", "")), wanted):
                kept.append(frame.copy())
        if kept:
            return kept, True
        if self.held:
            raise KeywordError(f"{label}: the shock point {wanted!r} (NOEUD/GROUP_NO) is not in "
                               f"this file: its node column holds {self.held[:10]}; give one of "
                               "them, or the file of that shock point")
        tables = self.tables
        if len(tables) > 1 and not all(_functions.is_function_table(t) or _time_first(t)
                                       for t in tables):
            titles = "; ".join(f"{i}: {t.attrs.get('title', '') or '(no title)'}"
                               for i, t in enumerate(tables))
            raise KeywordError(f"{label}: no table of this file names the shock point "
                               f"{wanted!r} (tables: {titles}); choose one with index=<n> or "
                               "title='<text>'")
        return [t.copy() for t in tables], False


_LAST_INDEX: dict[tuple, NodeIndex] = {}
_INDEX_LOCK = threading.Lock()


#: A file whose modification time is less than this before its index is built is not kept
#: [s]: on a coarse clock (1-2 s on FAT, some NFS servers) it could be rewritten within the
#: same tick, keeping its size and times (git's "racy" rule).
_RACY_SECONDS = 2.0


def _file_key(path: str | os.PathLike) -> tuple:
    """(absolute path, device, inode, size, modification and change times [ns]) of a regular
    file, its attributes taken through an open handle: NFS revalidates them on open, where a
    plain ``stat`` may answer from its attribute cache. The change time moves on every write
    and also when a tool sets the modification time back (``cp -p``, ``rsync -t``)."""
    with open(path, "rb") as handle:
        info = os.fstat(handle.fileno())
    if not stat.S_ISREG(info.st_mode):
        raise OSError(f"{path}: not a regular file")
    return (os.path.abspath(os.fspath(path)), info.st_dev, info.st_ino, info.st_size,
            info.st_mtime_ns, info.st_ctime_ns)


def node_index(path: str | os.PathLike) -> NodeIndex:
    """The :class:`NodeIndex` of a Code_Aster file, kept for the last file asked for while it
    is unchanged (same device, inode, size, modification and change times, :func:`_file_key`):
    reading the nodes of one file one after the other (a bundle's worker, a loop over
    ``wear_table(path, node=n)``) parses and scans it once. A file modified within
    :data:`_RACY_SECONDS` of the moment its index is built is parsed again the next time. One
    file's tables are held at a time (about the size of its numbers);
    :func:`forget_node_index` lets them go."""
    try:
        key = _file_key(path)
    except (OSError, TypeError, ValueError):  # not a plain file: parsed (and its errors) as ever
        return NodeIndex(_aster.read_aster_tables(path))
    with _INDEX_LOCK:
        index = _LAST_INDEX.get(key)
    if index is None:
        index = NodeIndex(_aster.read_aster_tables(path))
        if time.time() - key[4] / 1e9 >= _RACY_SECONDS:
            with _INDEX_LOCK:
                _LAST_INDEX.clear()
                _LAST_INDEX[key] = index
    return index


def forget_node_index() -> None:
    """Drop the tables :func:`node_index` keeps."""
    with _INDEX_LOCK:
        _LAST_INDEX.clear()


def _time_first(frame: pd.DataFrame) -> bool:
    return frame.shape[1] >= 2 and channel_of(str(frame.columns[0])) == "time"


def _numeric(frame: pd.DataFrame) -> bool:
    types = frame.attrs.get("types") or []
    return bool(types) and all(str(k) in ("R", "I") for k in types)


def _function_name(column: str, legend: str) -> str:
    """The channel name of an IMPR_FONCTION function: its column, its column without the
    ``_<curve number>`` IMPR_FONCTION appends, or its legend; else the column as is."""
    if channel_of(column) is not None:
        return column
    match = _SUFFIX.match(column)
    if match and channel_of(match.group("base")) is not None:
        return match.group("base")
    if legend and channel_of(legend) is not None:
        return legend
    return column


def _named(functions: list[tuple[str, str, np.ndarray, np.ndarray, str]], names: Any,
           label: str) -> list[tuple[str, str, np.ndarray, np.ndarray]]:
    """Rename the functions in order with the user's ``functions=`` (None drops one)."""
    if names is None:
        return [(lab, _function_name(name, legend), x, y) for lab, name, x, y, legend
                in functions]
    if isinstance(names, str):  # the command line's --read-option functions=fn,vt1,none
        names = [None if n.strip().lower() in ("", "none", "-") else n.strip()
                 for n in names.split(",")]
    if not isinstance(names, Sequence):
        raise KeywordError(f"functions={names!r}: give a list of channel names, one per function "
                           "of the file in order (None to skip one), or 'fn,vt1,vt2'")
    if len(names) != len(functions):
        found = [f[1] for f in functions]
        raise KeywordError(f"{label}: functions= names {len(names)} functions but the file holds "
                           f"{len(functions)} ({found}); give one name per function, in order")
    out = [(f[0], str(n), f[2], f[3]) for f, n in zip(functions, names, strict=True)
           if n is not None]
    if not out:
        raise KeywordError(f"functions={list(names)}: every function is skipped")
    return out


def _function_source(functions: list, label: str, names: Any, metadata: dict) -> Source:
    chosen = _named(functions, names, label)
    columns, arrays = _functions.stack_functions(chosen)
    _check_instants(arrays[0], label, "time")
    hint = ("; the functions of an IMPR_FONCTION file are named from their columns or legends: "
            "name them in order with functions=[...] (e.g. functions=['fn', 'vt1', 'vt2'])")
    return Source(label=label, format="aster-function", columns=columns,
                  read=lambda positions: [arrays[p] for p in positions], metadata=metadata,
                  hint=hint)


def duplicated_instants_message(time: np.ndarray, label: str, column: str) -> str | None:
    """Why a printed time column repeats an instant, and the fix; None when it does not.

    Code_Aster prints reals with ``FORMAT_R='E12.5'`` (``%12.5E``: 6 significant digits) by
    default in IMPR_TABLE and IMPR_FONCTION: at ``t`` the printed instants are ``10^(e-5)``
    apart (``e = floor(log10 t)``), so an archive step smaller than that prints neighbouring
    instants equal (5e-5 s from t = 10 s on). Sorting and dropping the duplicates would lose
    samples; the fix is to print more digits with FORMAT_R.

    Examples
    --------
    >>> t = np.array([19.9999, 19.99995, 20.0, 20.0, 20.0001])
    >>> "FORMAT_R='E16.9'" in duplicated_instants_message(t, "f.tab", "INST")
    True
    >>> duplicated_instants_message(np.array([0.0, 1.0]), "f.tab", "INST") is None
    True
    """
    t = np.asarray(time, dtype=float)
    steps = np.diff(t)
    same = np.flatnonzero(steps == 0)
    if same.size == 0:
        return None
    i = int(same[0]) + 1
    step = float((t[-1] - t[0]) / (t.size - 1))  # the mean step: printing does not bias it
    top = float(np.max(np.abs(t[np.isfinite(t)]), initial=0.0))
    at = abs(float(t[i]))
    resolution = 10.0 ** (np.floor(np.log10(at)) - 5) if at > 0 else 0.0
    decimals = 9
    if step > 0 and top > 0:
        decimals = max(9, int(np.ceil(np.floor(np.log10(top)) - np.log10(step) + 1)))
    fix = f"E{decimals + 7}.{decimals}"
    about = (f"; the archive step is about {step:.3g} s while %12.5E resolves only "
             f"{resolution:.0e} s at t = {at:.6g} s" if step > 0 else "")
    return (f"{label}: column {column!r} repeats the instant {float(t[i]):.5E} at rows {i - 1} "
            f"and {i}: Code_Aster prints reals with FORMAT_R='E12.5' (%12.5E, 6 significant "
            f"digits) by default{about}, so neighbouring instants were printed equal. Print "
            f"with more digits: IMPR_TABLE(..., FORMAT_R='{fix}') or IMPR_FONCTION(..., "
            f"FORMAT_R='{fix}'). Sorting and dropping the duplicates would lose samples")


def _check_instants(time: np.ndarray, label: str, column: str) -> None:
    message = duplicated_instants_message(time, label, column)
    if message is not None:
        raise HistoryError(message)


def _functions_of(frame: pd.DataFrame, label: str) -> list:
    """(label, name, abscissa, values, legend) of every function of a table."""
    return [(f"{label} ({name})", name, x, y, legend)
            for name, legend, x, y in _functions.function_columns(frame, label)]


def open_aster(path: str | os.PathLike, *, index: int | None = None, title: str | None = None,
               select: Any = None, node: str | None = None, functions: Any = None) -> Source:
    """Open a Code_Aster text file (IMPR_TABLE or IMPR_FONCTION TABLEAU) as a history source.

    Parameters
    ----------
    path : path-like
        The file.
    index, title : optional
        Which table of a file holding several (:func:`fretwear.io.aster.read_aster_table`).
    select : mapping or str, optional
        Keep the rows where a column equals a value (``"NOEUD=N12"``).
    node : str, optional
        The shock point (NOEUD / GROUP_NO): see :func:`select_node`.
    functions : sequence of str, optional
        Channel names of the file's IMPR_FONCTION functions in order (None skips one); default
        their column names (without IMPR_FONCTION's ``_<n>`` suffix) or legends.

    Returns
    -------
    Source
        Format ``aster`` (a table with a column per channel) or ``aster-function`` (functions
        laid side by side: time first, then one column per function). ``metadata``: the title
        (``aster_title``), and with ``node=`` the ``node`` and ``node_checked`` (False when the
        file names no node, so the choice could not be confirmed).

    Raises
    ------
    FormatError
        Several tables that are not the functions of one history and no choice; functions with
        different instants; a table mixing shock points without a choice.
    HistoryError
        Repeated instants (the message explains Code_Aster's print precision and FORMAT_R).
    KeywordError
        A node the file does not hold, bad ``select=`` or ``functions=``.
    """
    label = str(path)
    metadata: dict[str, Any] = {}
    if index is not None or title is not None:
        tables = [_aster.read_aster_table(path, index=index, title=title)]
        if node is not None:
            tables, checked = select_node(tables, node, label)
    elif node is not None:  # the file's node index, kept while its nodes are read in turn
        tables, checked = node_index(path).select(node, label)
    else:
        tables = _aster.read_aster_tables(path)
    if node is not None:
        metadata.update(node=str(node).strip(), node_checked=checked)
    if select is not None:
        tables = [select_rows(t, select, label) for t in tables]
    metadata["aster_title"] = "\n".join(t.attrs.get("title", "") for t in tables)
    if len(tables) > 1:
        if not all(_time_first(t) and _numeric(t) for t in tables):
            _aster.read_aster_table(path)  # raises the standard "holds N tables" message
        found = [f for t in tables for f in _functions_of(t, label)]
        names = [_function_name(f[1], f[4]) for f in found]
        repeated = sorted({n for n in names if names.count(n) > 1})
        if repeated and functions is None:
            raise FormatError(
                f"{label} holds {len(tables)} tables that repeat the functions {repeated}: "
                "several shock points; choose one with node='<NOEUD>', index=<n> or "
                "title='<text>' (command line: --read-option index=<n>)")
        return _function_source(found, label, functions, metadata)
    frame = tables[0]
    if _functions.is_function_table(frame) or functions is not None:
        return _function_source(_functions_of(frame, label), label, functions, metadata)
    names = [str(c) for c in frame.columns]
    check_one_shock(frame, names, label)
    times = [j for j, c in enumerate(names) if channel_of(c) == "time"]
    if len(times) == 1:
        _check_instants(numeric_column(frame, times[0], label), label, names[times[0]])

    def read(positions: list[int]) -> list[np.ndarray]:
        out = []
        for p in positions:
            out.append(numeric_column(frame, p, label))
        return out

    return Source(label=label, format="aster", columns=names, read=read, metadata=metadata)


def numeric_column(frame: pd.DataFrame, j: int, label: str) -> np.ndarray:
    """Column ``j`` of a Code_Aster table as floats (``-`` is NaN), or a :class:`FormatError`
    naming the column, its type and the first cell that is not a number."""
    column = frame.iloc[:, j]
    try:
        return column.to_numpy(dtype=float, na_value=np.nan)
    except (TypeError, ValueError):
        pass
    kind = (frame.attrs.get("types") or ["?"] * frame.shape[1])[j]
    bad = next((i for i, v in enumerate(column) if v is not None
                and pd.isna(pd.to_numeric(v, errors="coerce"))), None)
    cell = "" if bad is None else f"; row {bad} holds {column.iloc[bad]!r}"
    raise FormatError(f"{label}: column {str(frame.columns[j])!r} is not numeric (type "
                      f"{kind}{cell}); fix the cell, or map another column to this channel")


def check_one_shock(frame: pd.DataFrame, names: list[str], label: str) -> None:
    """Refuse a table mixing several shock points (a text column such as NOEUD with several
    values while the instants restart), naming the column and a filter to use."""
    times = [j for j, c in enumerate(names) if channel_of(c) == "time"]
    if len(times) != 1:
        return
    t = numeric_column(frame, times[0], label)
    if t.size < 2 or bool(np.all(np.diff(t) > 0)):
        return
    for j, kind in enumerate(frame.attrs.get("types", [])):
        values = frame.iloc[:, j].dropna().unique() if str(kind).startswith("K") else []
        if len(values) > 1:
            shown = [str(v) for v in values[:5]]
            raise FormatError(
                f"{label}: column {names[j]!r} holds several values {shown} and the instants "
                f"of {names[times[0]]!r} restart: the table mixes several shock points; choose "
                f"one with node='{shown[0]}' (POST_USURE's NOEUD='{shown[0]}' or GROUP_NO, a "
                f"case file's [history] node) or select={{'{names[j]}': '{shown[0]}'}} (command "
                f"line: --read-option select={names[j]}={shown[0]}), or print one per table with "
                f"IMPR_TABLE(..., FILTRE=_F(NOM_PARA='{names[j]}', VALE_K='{shown[0]}'))")


def open_functions(files: Any, *, functions: Any = None) -> Source:
    """Open a set of IMPR_FONCTION TABLEAU files as one history source.

    Parameters
    ----------
    files : mapping, path or sequence of paths
        ``{channel: file}`` (one function per file), or files whose functions are named from
        their columns or legends; a file may hold several functions (several tables, or several
        columns) when it is not given for one channel.
    functions : sequence of str, optional
        Channel names of all the functions in order (None skips one).

    Returns
    -------
    Source
        Format ``aster-function``: ``time`` then one column per function.
    """
    if isinstance(files, Mapping):
        pairs = [(str(k), v) for k, v in files.items()]
    elif isinstance(files, (str, os.PathLike)):
        pairs = [(None, files)]
    else:
        pairs = [(None, v) for v in files]
    found = []
    for key, path in pairs:
        label = str(path)
        own = [f for t in _aster.read_aster_tables(path) for f in _functions_of(t, label)]
        if key is not None:
            if len(own) != 1:
                raise FormatError(
                    f"{label} holds {len(own)} functions {[f[1] for f in own]} but is given "
                    f"for the single channel {key!r}; give one file per channel, or pass the "
                    "file in a list to use its column names")
            own = [(label, key, own[0][2], own[0][3], "")]
        found += own
    labels = [str(p) for _, p in pairs]
    label = ", ".join(labels)
    source = _function_source(found, label, functions, {"files": labels})
    source.hint = ("; the value columns of IMPR_FONCTION files need not be channel names: give "
                   "the files as a mapping {channel: file} (command line: CHANNEL=FILE, e.g. "
                   "fn=fn.txt) or name the functions in order with functions=[...]")
    return source
