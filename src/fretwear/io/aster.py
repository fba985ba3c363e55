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
import math
import os
import re
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FormatError, InputError
from fretwear.io._aster_plain import plain_frame
from fretwear.io.atomic import atomic_write
from fretwear.io.guard import readable_file, reading

#: First bytes of a gzip stream: text tables may be compressed (read transparently).
GZIP_MAGIC = b"\x1f\x8b"
#: The two layouts of IMPR_TABLE that LIRE_TABLE reads (its FORMAT keyword).
TABLE_FORMATS: tuple[str, ...] = ("TABLEAU", "ASTER")
_TOKEN = re.compile(r"'[^']*'|\"[^\"]*\"|\S+")
_TYPES = ("R", "I", "K8", "K16", "K24", "K32", "K80")
_STRING_WIDTHS = (8, 16, 24, 32, 80)


def _text_of(path_or_text: str | os.PathLike, data: bytes | None = None) -> tuple[str, str]:
    """(text, label): a path is read (``data``: its bytes, already read); a string holding a
    newline is the table itself."""
    if isinstance(path_or_text, str) and "\n" in path_or_text:
        return path_or_text, "<text>"
    if data is None:
        path = readable_file(path_or_text, "Code_Aster table file")
    else:
        name = os.fspath(path_or_text)
        path = Path(os.fsdecode(name) if isinstance(name, bytes) else name)
    with reading(path, "Code_Aster table", "Code_Aster table file"):
        if data is None:
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
    columns = [frame[j].to_numpy() for j in range(frame.shape[1])]
    # a row shorter than the first is padded with empty strings (no cell is empty otherwise)
    if any(c.dtype == object and (c == "").any() for c in columns):
        return None
    return columns


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


def _convert(raw: dict, label: str, rename: Mapping[str, str] | None = None) -> pd.DataFrame:
    """The frame of a raw table; ``rename`` (old -> new) renames some of its columns (the
    messages name the file's)."""
    names: list[str] = raw["names"]
    columns = [rename.get(n, n) for n in names] if rename else list(names)
    plain = plain_frame(raw, columns)  # a table of numbers only: numpy, the same frame
    if plain is not None:
        return plain
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
    frame.columns = columns
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
                     title: str | None = None, rename: Mapping[str, str] | None = None,
                     data: bytes | None = None) -> pd.DataFrame:
    """Read a table printed by Code_Aster's IMPR_TABLE (FORMAT 'TABLEAU' or 'ASTER').

    Parameters
    ----------
    path_or_text : str or path-like
        The file, or the text of the table itself (a string holding a newline).
    index : int, optional
        Which table (0-based) when the file holds several.
    title : str, optional
        Choose the table whose title contains this text (case-insensitive).
    rename : mapping, optional
        Columns renamed as the frame is made (old -> new; e.g. native names, without a copy).
    data : bytes, optional
        The file's bytes, already read (a caller keyed on them parses those bytes).

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
    text, label = _text_of(path_or_text, data)
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
    return _convert(raw[chosen], label, rename)


def _format_cell(value, kind: str, float_format: str) -> str:
    if value is None or (not isinstance(value, str) and pd.isna(value)):
        return "-"
    if kind == "R":
        value = float(value)
        # no infinity in a Code_Aster table: LIRE_TABLE's ASTER-format reals match
        # [0-9.,+-eEdD]+ only; an empty cell, like NaN
        return float_format % value if math.isfinite(value) else "-"
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
        for i in np.flatnonzero(~np.isfinite(values)).tolist():  # NaN and ±inf: empty cell
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
