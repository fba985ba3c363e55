"""Code_Aster text tables: IMPR_TABLE (FORMAT='TABLEAU' and 'ASTER') and IMPR_FONCTION TABLEAU.

Generic: also used for wear tables (ETAT_INIT restarts) and for contact histories.

Formats (Code_Aster user documentation U4.91.03 IMPR_TABLE, U4.33.01 IMPR_FONCTION, U7.02.03
LIRE_TABLE; theory §1):

* ``TABLEAU``: a block of lines starting with ``#`` (title), a line of column names, then one
  line per row, cells separated by blanks, reals printed ``%12.5E``, ``-`` for an empty cell.
  Several tables may follow each other in one file, each with its own ``#`` block.
* ``ASTER``: each table between ``#DEBUT_TABLE`` and ``#FIN_TABLE``; ``#TITRE`` line(s), the
  column-name line, a line of types (``R`` real, ``I`` integer, ``K8``/``K16``/``K24``/``K32``/
  ``K80`` strings), then the rows. Strings may be quoted (``'a b'``).
* IMPR_FONCTION ``TABLEAU``: a TABLEAU table with two columns per function (abscissa, value).
"""

from __future__ import annotations

import gzip
import io
import os
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.errors import FormatError, InputError
from fretwear.io.atomic import atomic_write
from fretwear.io.guard import readable_file, reading

#: First bytes of a gzip stream: text tables may be compressed (read transparently).
GZIP_MAGIC = b"\x1f\x8b"
#: The two layouts of IMPR_TABLE that LIRE_TABLE reads (its FORMAT keyword).
TABLE_FORMATS: tuple[str, ...] = ("TABLEAU", "ASTER")
_TOKEN = re.compile(r"'[^']*'|\"[^\"]*\"|\S+")
_TYPES = ("R", "I", "K8", "K16", "K24", "K32", "K80")
_STRING_WIDTHS = (8, 16, 24, 32, 80)


def _text_of(path_or_text: str | os.PathLike) -> tuple[str, str]:
    """(text, label): a path is read; a string holding a newline is the table itself."""
    if isinstance(path_or_text, str) and "\n" in path_or_text:
        return path_or_text, "<text>"
    path = readable_file(path_or_text, "Code_Aster table file")
    with reading(path, "Code_Aster table", "Code_Aster table file"):
        data = path.read_bytes()
        if data[:2] == GZIP_MAGIC:
            data = gzip.decompress(data)
        if data[:2] in (b"\xff\xfe", b"\xfe\xff"):  # UTF-16 with its byte-order mark
            return data.decode("utf-16"), str(path)
    try:
        return data.decode("utf-8-sig"), str(path)  # a BOM is dropped
    except UnicodeDecodeError:
        return data.decode("latin-1"), str(path)


def _tokens(line: str) -> list[str]:
    return _TOKEN.findall(line)


def _unquote(token: str) -> str:
    if len(token) >= 2 and token[0] == token[-1] and token[0] in "'\"":
        return token[1:-1]
    return token


def _split_tables(text: str, label: str) -> list[dict]:
    """Cut a file into raw tables: dicts of format, title, names, types, rows (lineno, text)."""
    tables: list[dict] = []
    current: dict | None = None
    in_aster = False
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line[0] != "#" and current is not None and current["names"] is not None \
                and (current["types"] is not None or current["format"] == "TABLEAU"):
            current["rows"].append((lineno, line))  # the common case: a data line
            continue
        upper = line.upper()
        if upper.startswith("#DEBUT_TABLE"):
            current = {"format": "ASTER", "title": [], "names": None, "types": None, "rows": [],
                       "line": lineno}
            tables.append(current)
            in_aster = True
            continue
        if upper.startswith("#FIN_TABLE"):
            if not in_aster:
                raise FormatError(f"{label}, line {lineno}: #FIN_TABLE without #DEBUT_TABLE")
            in_aster = False
            current = None
            continue
        if in_aster:
            assert current is not None
            if upper.startswith("#TITRE"):
                current["title"].append(line[len("#TITRE"):].strip())
            elif line.startswith("#"):
                continue
            elif current["names"] is None:
                current["names"] = [_unquote(t) for t in _tokens(line)]
            elif current["types"] is None:
                current["types"] = [t.upper() for t in _tokens(line)]
            else:
                current["rows"].append((lineno, line))
            continue
        if line.startswith("#"):
            if current is None or current["names"] is not None:
                current = {"format": "TABLEAU", "title": [], "names": None, "types": None,
                           "rows": [], "line": lineno}
                tables.append(current)
            body = line.lstrip("#").strip()
            if body:
                current["title"].append(body)
            continue
        if current is None:  # a TABLEAU without '#' block
            current = {"format": "TABLEAU", "title": [], "names": None, "types": None,
                       "rows": [], "line": lineno}
            tables.append(current)
        if current["names"] is None:
            current["names"] = [_unquote(t) for t in _tokens(line)]
        else:
            current["rows"].append((lineno, line))
    if in_aster:
        raise FormatError(f"{label}: #DEBUT_TABLE at line {tables[-1]['line']} is never closed "
                          "by #FIN_TABLE; the file is truncated")
    return [t for t in tables if t["names"]]


def _numbers(col: np.ndarray) -> np.ndarray | None:
    """Float values of a column of tokens (``-`` -> NaN, Fortran ``D`` exponents); None if not."""
    missing = col == "-"
    filled = np.where(missing, "nan", col)
    try:
        return filled.astype(float)
    except ValueError:
        try:
            return np.array([c.replace("D", "E").replace("d", "e") for c in filled], dtype=float)
        except ValueError:
            return None


def _infer_type(col: np.ndarray, values: np.ndarray | None) -> str:
    present = col[col != "-"]
    if values is not None:
        if present.size and set("".join(present)) <= set("0123456789+-"):
            return "I"
        return "R"
    return _string_type(max((len(_unquote(c)) for c in present), default=1))


def _string_type(width: int) -> str:
    """The narrowest Code_Aster string type (K8 ... K80) holding ``width`` characters."""
    return f"K{next((w for w in _STRING_WIDTHS if width <= w), 80)}"


def _columns_fast(raw: dict) -> list[np.ndarray] | None:
    """Columns parsed by pandas' C parser, or None when the slow path must decide (quoted
    strings, ragged or short rows: the slow path names the line)."""
    texts = [text for _, text in raw["rows"]]
    if not texts or any("'" in t or '"' in t for t in texts):
        return None
    try:
        frame = pd.read_csv(io.StringIO("\n".join(texts)), sep=r"\s+", header=None,
                            keep_default_na=False, na_values=[], engine="c")
    except (pd.errors.ParserError, ValueError):
        return None
    if frame.shape != (len(texts), len(raw["names"])) or frame.isna().to_numpy().any():
        return None
    return [frame[j].to_numpy() for j in range(frame.shape[1])]


def _cells(raw: dict, label: str) -> np.ndarray:
    """The rows of a raw table as a 2-D object array of tokens, checking the count per line."""
    names: list[str] = raw["names"]
    ncol = len(names)
    texts = [text for _, text in raw["rows"]]
    quoted = any("'" in t or '"' in t for t in texts)
    split = [_tokens(t) if quoted else t.split() for t in texts]
    for (lineno, _), cells in zip(raw["rows"], split, strict=True):
        if len(cells) != ncol:
            raise FormatError(
                f"{label}, line {lineno}: {len(cells)} cells for {ncol} columns {names}; an empty "
                "cell must be written '-' and a string holding blanks must be quoted")
    table = np.empty((len(split), ncol), dtype=object)
    if split:
        table[:, :] = split
    return table


def _convert(raw: dict, label: str) -> pd.DataFrame:
    names: list[str] = raw["names"]
    ncol = len(names)
    fast = _columns_fast(raw)
    table = _cells(raw, label) if fast is None else None
    types = raw["types"]
    if types is not None and len(types) != ncol:
        raise FormatError(f"{label}, table at line {raw['line']}: {len(types)} types for "
                          f"{ncol} columns {names}")
    series = {}
    kinds = []
    for j in range(ncol):
        col = fast[j] if fast is not None else table[:, j]  # type: ignore[index]
        kind = types[j] if types is not None else None
        if kind is not None and not kind.startswith("K") and kind not in ("R", "I"):
            raise FormatError(f"{label}: column {names[j]!r} has unknown type {kind!r}; known "
                              f"types: {', '.join(_TYPES)}")
        if col.dtype == object and fast is not None:  # pandas keeps integers beyond 64 bits
            col = np.array([str(c) for c in col], dtype=object)  # as Python ints: tokens
        if col.dtype.kind in "iuf" and (kind is None or not kind.startswith("K")):
            values = col.astype(float)  # parsed by pandas: no '-' in this column
            if kind is None:
                kind = "I" if col.dtype.kind in "iu" else "R"
        else:
            if col.dtype.kind in "iuf":  # a string column (K) holding only numbers
                col = np.array([str(c) for c in col], dtype=object)
            values = None if kind is not None and kind.startswith("K") else _numbers(col)
            if kind is None:
                kind = _infer_type(col, values)
        kinds.append(kind)
        if kind.startswith("K"):
            series[j] = pd.Series([None if c == "-" else _unquote(c) for c in col], dtype=object)
            continue
        if values is None:  # a declared R/I column holding text: find the culprit
            for i, c in enumerate(col):
                if _numbers(np.array([c], dtype=object)) is None:
                    raise FormatError(f"{label}, line {raw['rows'][i][0]}: column {names[j]!r} "
                                      f"of type {kind} holds {c!r}, not a number")
        assert values is not None
        if kind == "I" and np.nanmax(np.abs(values), initial=0.0) >= 2.0 ** 63:
            if types is not None:  # a declared integer beyond 64 bits: not a Code_Aster integer
                i = int(np.flatnonzero(np.abs(values) >= 2.0 ** 63)[0])
                raise FormatError(f"{label}, line {raw['rows'][i][0]}: column {names[j]!r} of "
                                  f"type I holds {values[i]:.17g}, beyond 64-bit integers")
            kind = kinds[-1] = "R"  # digits only but too large for an integer: a real
        if kind == "I":
            series[j] = (pd.Series(values).astype("Int64") if np.isnan(values).any()
                         else pd.Series(values.astype(np.int64)))
        else:
            series[j] = pd.Series(values)
    frame = pd.DataFrame(series) if series else pd.DataFrame(index=range(0))
    frame.columns = list(names)
    frame.attrs.update(title="\n".join(raw["title"]), types=list(kinds), format=raw["format"])
    return frame


def _raw_tables(text: str, label: str) -> list[dict]:
    raw = _split_tables(text, label)
    if not raw:
        raise FormatError(f"{label}: no Code_Aster table found (expected a '#' header block and "
                          "a line of column names, or #DEBUT_TABLE ... #FIN_TABLE)")
    return raw


def read_aster_tables(path_or_text: str | os.PathLike) -> list[pd.DataFrame]:
    """Every table of a Code_Aster text file, in order (as :func:`read_aster_table` reads one).

    A file receives several tables when several IMPR_TABLE or IMPR_FONCTION commands print to
    the same unit (each appends its own ``#`` block and column names).

    Examples
    --------
    >>> text = "#\\n#a\\nINST FN\\n0 1\\n#\\n#b\\nINST VT1\\n0 2\\n"
    >>> [list(t.columns) for t in read_aster_tables(text)]
    [['INST', 'FN'], ['INST', 'VT1']]
    """
    text, label = _text_of(path_or_text)
    return [_convert(raw, label) for raw in _raw_tables(text, label)]


def list_aster_tables(path_or_text: str | os.PathLike) -> list[str]:
    """Titles of the tables of a Code_Aster text file, in order (index = position).

    Examples
    --------
    >>> text = "#\\n#first\\nA\\n1\\n#\\n#second\\nB\\n2\\n"
    >>> list_aster_tables(text)
    ['first', 'second']
    """
    text, label = _text_of(path_or_text)
    return ["\n".join(t["title"]) for t in _split_tables(text, label)]


def read_aster_table(path_or_text: str | os.PathLike, *, index: int | None = None,
                     title: str | None = None) -> pd.DataFrame:
    """Read a table printed by Code_Aster's IMPR_TABLE (FORMAT 'TABLEAU' or 'ASTER').

    Parameters
    ----------
    path_or_text : str or path-like
        The file, or the text of the table itself (a string holding a newline).
    index : int, optional
        Which table (0-based) when the file holds several.
    title : str, optional
        Choose the table whose title contains this text (case-insensitive).

    Returns
    -------
    pandas.DataFrame
        One column per parameter (duplicated names are kept, e.g. IMPR_FONCTION pairs). Reals
        and integers are numbers (``-`` is NaN, or a missing value of an ``Int64`` column);
        strings are str (``-`` is None). ``attrs``: ``title`` (str), ``types`` (list of
        ``R``/``I``/``K8``... per column, inferred for TABLEAU), ``format``.

    Raises
    ------
    FormatError
        No table, a row with a wrong number of cells (line number given), an unknown type, a
        non-number in a numeric column, an unclosed ``#DEBUT_TABLE``, or several tables and no
        choice (the message lists them).

    Notes
    -----
    Fortran ``D`` exponents (``1.0D+00``) are accepted. Values are not rescaled: Code_Aster
    tables carry no units.

    Examples
    --------
    >>> text = '''#DEBUT_TABLE
    ... #TITRE wear table
    ... INST         V_USUR_TUBE  NOEUD
    ... R            R            K8
    ... 0.00000E+00  -            N1
    ... 1.00000E+00  2.50000E-09  N1
    ... #FIN_TABLE
    ... '''
    >>> frame = read_aster_table(text)
    >>> frame.attrs["title"], frame.attrs["types"], frame["V_USUR_TUBE"].tolist()
    ('wear table', ['R', 'R', 'K8'], [nan, 2.5e-09])
    """
    text, label = _text_of(path_or_text)
    raw = _raw_tables(text, label)
    listing = "; ".join(f"{i}: {' / '.join(t['title']) or '(no title)'}"
                        for i, t in enumerate(raw))
    if title is not None:
        hits = [i for i, t in enumerate(raw) if title.lower() in "\n".join(t["title"]).lower()]
        if len(hits) != 1:
            what = "no table" if not hits else f"{len(hits)} tables"
            raise FormatError(f"{label}: {what} with a title containing {title!r}; tables: "
                              f"{listing}; choose with index=")
        chosen = hits[0]
    elif index is not None:
        if not -len(raw) <= index < len(raw):
            raise FormatError(f"{label}: index={index} but the file holds {len(raw)} table(s): "
                              f"{listing}")
        chosen = index
    elif len(raw) > 1:
        raise FormatError(f"{label} holds {len(raw)} tables ({listing}); choose one with "
                          "index=<n> or title='<text>' (command line: --read-option index=<n>)")
    else:
        chosen = 0
    return _convert(raw[chosen], label)


def _format_cell(value, kind: str, float_format: str) -> str:
    if value is None or (not isinstance(value, str) and pd.isna(value)):
        return "-"
    if kind == "R":
        return float_format % float(value)
    if kind == "I":
        return str(int(value))
    text = str(value)
    if text == "" or re.search(r"\s", text) or text == "-":
        if "'" in text:
            raise InputError(f"string {text!r} holds both a blank and a quote: it cannot be "
                             "written in a Code_Aster table")
        return f"'{text}'"
    return text


def _format_column(series: pd.Series, kind: str, float_format: str) -> list[str]:
    if kind == "R":
        values = series.to_numpy(dtype=float, na_value=np.nan)
        text = [float_format % v for v in values.tolist()]
        for i in np.flatnonzero(np.isnan(values)).tolist():
            text[i] = "-"
        return text
    return [_format_cell(v, kind, float_format) for v in series]


def _kind(series: pd.Series) -> str:
    if pd.api.types.is_bool_dtype(series) or pd.api.types.is_integer_dtype(series):
        return "I"
    if pd.api.types.is_float_dtype(series):
        return "R"
    return _string_type(max([len(str(v)) for v in series if v is not None] + [1]))


def format_aster_table(frame: pd.DataFrame, *, format: str = "TABLEAU", title: str | None = None,
                       float_format: str = "%12.5E") -> str:
    """The text of a Code_Aster table (parameters as in :func:`write_aster_table`).

    Raises
    ------
    InputError
        Unknown format, a float_format that is not a printf format, a column name empty or
        holding blanks, a string holding both a blank and a quote.

    Examples
    --------
    >>> print(format_aster_table(pd.DataFrame({"INST": [0.0, 1.5]}), title="demo"), end="")
    #
    #demo
    INST
     0.00000E+00
     1.50000E+00
    """
    fmt = str(format).upper()
    if fmt not in TABLE_FORMATS:
        raise InputError(f"format={format!r}: a Code_Aster table is written "
                         f"{' or '.join(map(repr, TABLE_FORMATS))}")
    try:
        float_format % 1.0
    except (TypeError, ValueError):
        raise InputError(f"float_format={float_format!r} is not a printf format such as "
                         "'%12.5E'") from None
    names = [str(c) for c in frame.columns]
    for name in names:
        if not name or re.search(r"\s", name):
            raise InputError(f"column name {name!r}: Code_Aster parameter names cannot be empty "
                             "or hold blanks; rename the column")
    kinds = [_kind(frame.iloc[:, j]) for j in range(frame.shape[1])]
    cells = [_format_column(frame.iloc[:, j], kinds[j], float_format)
             for j in range(frame.shape[1])]
    widths = [max([len(names[j])] + [len(c) for c in cells[j]]) for j in range(len(names))]
    lines: list[str] = []
    title_lines = (title if title is not None else "TABLE_SDASTER").splitlines() or [""]
    if fmt == "ASTER":
        lines.append("#DEBUT_TABLE")
        lines.extend(f"#TITRE {t}".rstrip() for t in title_lines)
    else:
        lines.append("#")
        lines.extend(f"#{t}" for t in title_lines)
    lines.append(" ".join(n.ljust(w) for n, w in zip(names, widths, strict=True)).rstrip())
    if fmt == "ASTER":
        lines.append(" ".join(k.ljust(w) for k, w in zip(kinds, widths, strict=True)).rstrip())
    padded = [[c.rjust(w) for c in column] for column, w in zip(cells, widths, strict=True)]
    lines.extend(map(" ".join, zip(*padded, strict=True)))
    if fmt == "ASTER":
        lines.append("#FIN_TABLE")
    return "\n".join(lines) + "\n"


def write_aster_table(frame: pd.DataFrame, path: str | os.PathLike, *, format: str = "TABLEAU",
                      title: str | None = None, float_format: str = "%12.5E",
                      append: bool = False) -> Path:
    """Write a DataFrame as a Code_Aster table that LIRE_TABLE and :func:`read_aster_table` read.

    Parameters
    ----------
    frame : pandas.DataFrame
        Columns are the parameters (names without blanks). Float columns are written as reals
        (``R``), integer and boolean columns as integers (``I``), others as strings (``K8`` ...
        by width); NaN and None are written ``-``.
    path : path-like
        Output file, written atomically.
    format : {"TABLEAU", "ASTER"}
        IMPR_TABLE format.
    title : str, optional
        Title line(s); default ``TABLE_SDASTER``.
    float_format : str
        printf format of reals, default Code_Aster's ``%12.5E``; ``"%.16E"`` keeps every digit.
    append : bool
        Keep the tables already in the file and add this one after them.

    A path ending in ``.gz`` is gzip-compressed (and read back transparently).

    Returns
    -------
    pathlib.Path
        The file written.

    Notes
    -----
    A read-back value equals ``float(float_format % x)``: exact to the printed precision.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "t.resu"
    >>> _ = write_aster_table(pd.DataFrame({"INST": [1.0], "FN": [1 / 3]}), out, format="ASTER")
    >>> read_aster_table(out)["FN"].tolist()
    [0.33333]
    """
    text = format_aster_table(frame, format=format, title=title, float_format=float_format)
    target = Path(path)
    previous = ""
    if append and target.is_file():
        previous, _ = _text_of(target)
        if previous and not previous.endswith("\n"):
            previous += "\n"
    if target.suffix.lower() == ".gz":
        with atomic_write(target, "wb") as handle:
            handle.write(gzip.compress((previous + text).encode("utf-8"), mtime=0))
        return target
    with atomic_write(target, "w", encoding="utf-8") as handle:
        handle.write(previous + text)
    return target


def function_pairs(frame: pd.DataFrame, label: str) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Split an IMPR_FONCTION TABLEAU table into functions: ``(name, abscissa, values)``.

    The columns come in pairs (abscissa, ordinate); the name is the ordinate's column name.

    Examples
    --------
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


def looks_like_aster(head: str) -> bool:
    """Whether the beginning of a text file is a Code_Aster table (content, not suffix).

    Recognised: ``#DEBUT_TABLE``; a ``#`` block naming Code_Aster (``#ASTER ... CONCEPT``,
    ``TABLE_SDASTER``, ``FONCTION``); or a ``#`` block, a line of names, and rows of
    blank-separated cells, each a ``%12.5E`` real, ``-`` or text that is not a number (a node
    name), with at least one real per row.

    Examples
    --------
    >>> looks_like_aster("#DEBUT_TABLE\\n"), looks_like_aster("t,fn\\n0,1\\n")
    (True, False)
    >>> looks_like_aster("#\\n#\\n INST  FN\\n 0.00000E+00 -\\n 1.00000E-04  1.20000E+01\\n")
    True
    >>> looks_like_aster("#\\n#my title\\nNOEUD INST\\nN12 0.00000E+00\\nN12 1.00000E-04\\n")
    True
    >>> looks_like_aster("# comment\\nt fn vt1 vt2\\n0 1.5 0.1 0\\n1 1.5 0.1 0\\n")
    False
    """
    lines = [ln.strip() for ln in head.splitlines() if ln.strip()]
    if any(ln.upper().startswith("#DEBUT_TABLE") for ln in lines[:50]):
        return True
    comments = []
    for ln in lines:
        if not ln.startswith("#"):
            break
        comments.append(ln.upper())
    if not comments:
        return False
    if any(("ASTER" in c and "CONCEPT" in c) or "TABLE_SDASTER" in c or "FONCTION_SDASTER" in c
           or re.match(r"^#\s*FONCTION\b", c) for c in comments):
        return True
    rest = lines[len(comments) + 1: len(comments) + 6]
    real = re.compile(r"^[+-]?\d\.\d+E[+-]\d{2,3}$")
    number = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([EeDd][+-]?\d+)?$")

    def row(line: str) -> bool:  # %12.5E reals, '-', and text cells (node names) that are
        cells = line.split()     # not numbers in another format; at least one real
        return (not line.startswith("#") and any(real.match(c) for c in cells)
                and all(real.match(c) or c == "-" or not number.match(c) for c in cells))

    names = lines[len(comments)].split() if len(lines) > len(comments) else []
    if not names or any(number.match(c) for c in names):  # the line after '#' names columns
        return False
    return bool(rest) and all(row(ln) for ln in rest)


def read_function_files(files: Sequence[tuple[str, str | os.PathLike]]
                        ) -> tuple[list[str], list[np.ndarray], dict]:
    """Read a set of IMPR_FONCTION TABLEAU files into one table of columns.

    Parameters
    ----------
    files : sequence of (key, path)
        ``key`` names the function held in the file (a channel or alias) or is None to use the
        value column's own name; a file may hold several functions when ``key`` is None.

    Returns
    -------
    (names, arrays, info)
        Column names (``time`` first, then one per function), their arrays, and ``{"files": ...}``.
    """
    functions = []
    for key, path in files:
        label = str(path)
        pairs = function_pairs(read_aster_table(path), label)
        if key is not None and len(pairs) != 1:
            raise FormatError(f"{label} holds {len(pairs)} functions {[p[0] for p in pairs]} "
                              f"but is given for the single channel {key!r}; give one file per "
                              "channel, or pass the file in a list to use its column names")
        functions += [(label, str(key) if key is not None else name, x, y)
                      for name, x, y in pairs]
    names, arrays = stack_functions(functions)
    return names, arrays, {"files": [str(p) for _, p in files]}


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
