"""Delimited text (CSV, TSV, blank-separated ``.txt``/``.dat``): reader, chunked reader, writer.

The reader finds by itself the leading comment lines (``#``), the delimiter (tab, ``;``, ``,``,
``|`` or blanks), whether the first line is a header (else columns are named ``0``, ``1`` ...),
a decimal comma (``1,5;2,5``), and units written in the header (``"Fn [kN]"``).
"""

from __future__ import annotations

import gzip
import json
import os
import re
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import optional
from fretwear.errors import FormatError, InputError
from fretwear.history import DESCRIPTIONS, UNITS, ContactHistory
from fretwear.io.aster import GZIP_MAGIC
from fretwear.io.atomic import atomic_write
from fretwear.io.channels import Source, split_unit

#: First line of the files written by :func:`write_csv` (their metadata lines are read back).
MAGIC = "# fretwear contact history"
_CANDIDATES = ("\t", ";", ",", "|")
#: byte-order marks of UTF-16 text (little and big endian)
UTF16_BOMS = (b"\xff\xfe", b"\xfe\xff")
_DECIMAL_COMMA = re.compile(r"^[+-]?\d+,\d+([eE][+-]?\d+)?$")


def is_gzip(path: Path) -> bool:
    """Whether a file is gzip-compressed (by its first bytes, whatever its suffix)."""
    with open(path, "rb") as handle:
        return handle.read(2) == GZIP_MAGIC


def _is_number(token: str, decimal: str) -> bool:
    try:
        float(token.replace(decimal, ".") if decimal != "." else token)
        return True
    except ValueError:
        return False


def _split(line: str, sep: str | None) -> list[str]:
    parts = line.split() if sep is None else line.split(sep)
    return [p.strip().strip("'\"") for p in parts]


def scan(path: Path, *, delimiter: str | None = None, decimal: str | None = None,
         comment: str = "#", header: bool | None = None, encoding: str | None = None) -> dict:
    """Inspect the head of a delimited file: comment lines, delimiter, decimal, header, names.

    Returns a dict with ``skip`` (lines before the header or first data line), ``sep`` (None
    for blanks), ``decimal``, ``header`` (bool), ``names``, ``units`` (position -> unit),
    ``comments`` (the leading comment lines).
    """
    compressed = is_gzip(path)
    opener = gzip.open if compressed else open
    if encoding is None:  # UTF-8 (a BOM is dropped), or UTF-16 when the file starts with its BOM
        with opener(path, "rb") as raw:
            encoding = "utf-16" if raw.read(2) in UTF16_BOMS else "utf-8-sig"
    try:
        with opener(path, "rt", encoding=encoding) as handle:
            head = [line.rstrip("\r\n") for _, line in zip(range(400), handle, strict=False)]
    except UnicodeDecodeError:
        raise FormatError(f"{path}: not a text file in {encoding!r}; give encoding='latin-1' "
                          "or format= for a binary file") from None
    skip = 0
    comments: list[str] = []
    while skip < len(head) and (not head[skip].strip()
                                or (comment and head[skip].lstrip().startswith(comment))):
        comments.append(head[skip])
        skip += 1
    sample = [ln for ln in head[skip:skip + 30] if ln.strip()
              and not (comment and ln.lstrip().startswith(comment))]
    if not sample:
        raise FormatError(f"{path}: no data lines (only comments or blank lines); is it the "
                          "right file?")
    sep = delimiter
    if sep is None:
        for cand in _CANDIDATES:  # the first separator found on every line (ragged rows are
            if all(ln.count(cand) > 0 for ln in sample):  # then reported by the parser)
                sep = cand
                break
    if sep is not None and sep.isspace() and sep != "\t":
        sep = None
    data_tokens = [t for ln in sample[1:] for t in _split(ln, sep)]
    if decimal is None:
        decimal = "," if sep != "," and any(_DECIMAL_COMMA.match(t) for t in data_tokens) else "."
    first = _split(sample[0], sep)
    if header is None:
        header = not all(_is_number(t, decimal) for t in first if t)
    if header:
        names = first
        units: dict[int, str] = {}
        for i, name in enumerate(names):
            _, unit = split_unit(name)
            if unit is not None:
                units[i] = unit
    else:
        names = [str(i) for i in range(len(first))]
        units = {}
    return {"skip": skip, "sep": sep, "decimal": decimal, "header": bool(header), "names": names,
            "units": units, "comments": comments, "comment": comment, "encoding": encoding,
            "compression": "gzip" if compressed else None}


def _stored_metadata(comments: list[str]) -> tuple[str | None, dict]:
    if not comments or comments[0].strip() != MAGIC:
        return None, {}
    name, meta = None, {}
    for line in comments[1:]:
        body = line.lstrip("#").strip()
        if body.startswith("name:"):
            name = body[len("name:"):].strip()
        elif body.startswith("metadata:"):
            try:
                meta = json.loads(body[len("metadata:"):].strip())
            except json.JSONDecodeError:
                meta = {}
    return name, meta


#: Rows pandas parses per block of a streamed text file, at least: each parsed block costs a
#: fixed time per column (a column object), so blocks of 2 rows of a file with 2 000 extra
#: columns took 68 s for 250 rows, one block 0.45 s (load 8.5). The blocks are sliced into the
#: chunks asked for; memory stays O(chunk) for a chunk of this many rows or more.
PARSE_ROWS = 256
#: Cells parsed per block at most when the chunk is smaller than PARSE_ROWS (8 MB of floats).
PARSE_CELLS = 1 << 20


def parse_rows(size: int, columns: int) -> int:
    """Rows pandas parses per block for chunks of ``size`` rows of a file of ``columns``
    columns: ``size``, raised to :data:`PARSE_ROWS` (or as many rows as fit in
    :data:`PARSE_CELLS` cells, if fewer).

    Examples
    --------
    >>> parse_rows(2, 2004), parse_rows(2, 100_000), parse_rows(5000, 4)
    (256, 10, 5000)
    """
    return max(int(size), min(PARSE_ROWS, PARSE_CELLS // max(1, int(columns))))


def _read_kwargs(info: dict, positions: list[int]) -> dict:
    # every column is parsed (no usecols): pandas would silently drop the extra cells of a
    # ragged row otherwise; only the columns used must be numbers (a node-name column is fine)
    return dict(sep=r"\s+" if info["sep"] is None else info["sep"], header=None,
                skiprows=info["skip"] + (1 if info["header"] else 0),
                comment=info["comment"] or None, decimal=info["decimal"],
                dtype={p: float for p in positions},
                encoding=info["encoding"], skip_blank_lines=True, engine="c",
                compression=info["compression"])


def _diagnose(path: Path, info: dict, positions: list[int], exc: ValueError) -> FormatError:
    """The error of a failed read: a ragged row (pandas' ParserError), else the first
    non-numeric cell among ``positions``."""
    if isinstance(exc, pd.errors.ParserError):
        return FormatError(f"{path}: {str(exc).strip()}; every row must have the same number of "
                           "cells as the header")
    kwargs = _read_kwargs(info, positions)
    kwargs["dtype"] = str  # every cell as text, whatever the columns found
    kwargs["keep_default_na"] = False
    frame = pd.read_csv(path, **kwargs)
    short = _short_rows(frame, positions, path, info)
    if short is not None:
        return short
    for pos in positions:
        col = frame[pos]
        text = col.str.strip()
        if info["decimal"] != ".":
            text = text.str.replace(info["decimal"], ".", regex=False)
        values = pd.to_numeric(text, errors="coerce")
        bad = values.isna() & (text != "") & ~text.str.lower().isin(["nan", "na", "n/a", "null"])
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            return FormatError(
                f"{path}: column {info['names'][pos]!r} holds {col.iloc[i]!r} at data row "
                f"{i} (0-based, header excluded), not a number; fix the cell (empty cells are "
                "read as missing)")
    return FormatError(f"{path}: could not read the columns as numbers")


def _columns(frame: pd.DataFrame, positions: list[int], path: Path, info: dict
             ) -> list[np.ndarray]:
    """The columns at ``positions`` as float arrays; rows shorter than the header are named."""
    short = _short_rows(frame, positions, path, info)
    if short is not None:
        raise short
    return [frame[pos].to_numpy(dtype=float) for pos in positions]


def _short_rows(frame: pd.DataFrame, positions: list[int], path: Path, info: dict
                ) -> FormatError | None:
    short = [p for p in positions if p not in frame.columns]
    if not short:
        return None
    return FormatError(f"{path}: the header names {len(info['names'])} columns "
                       f"{info['names']} but the data rows hold {frame.shape[1]} cells: no "
                       f"values for {[info['names'][p] for p in short]}; every row must have "
                       "the same number of cells as the header")


def open_csv(path: str | os.PathLike, *, delimiter: str | None = None,
             decimal: str | None = None, comment: str = "#", header: bool | None = None,
             encoding: str | None = None) -> Source:
    """Open a delimited text file as a :class:`~fretwear.io.channels.Source`.

    Parameters
    ----------
    path : path-like
        The file.
    delimiter : str, optional
        Column separator; default guessed among tab, ``;``, ``,``, ``|`` and blanks.
    decimal : str, optional
        Decimal mark; default ``.``, or ``,`` when the cells use a decimal comma.
    comment : str
        Lines starting with it are ignored (default ``#``).
    header : bool, optional
        Whether the first non-comment line names the columns; default guessed (it does unless
        every cell is a number). Without a header the columns are named ``0``, ``1`` ...
    encoding : str, optional
        Text encoding; default UTF-8 (with or without BOM), or UTF-16 when the file starts with
        a UTF-16 byte-order mark. Line ends may be ``\\n`` or ``\\r\\n``.

    Returns
    -------
    Source

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv"
    >>> _ = p.write_text("# test\\nt;Fn [kN]\\n0,0;1,5\\n1,0;2,5\\n")
    >>> src = open_csv(p)
    >>> src.columns, src.units, [a.tolist() for a in src.read([0, 1])]
    (['t', 'Fn [kN]'], {1: 'kN'}, [[0.0, 1.0], [1.5, 2.5]])
    """
    path = Path(path)
    info = scan(path, delimiter=delimiter, decimal=decimal, comment=comment, header=header,
                encoding=encoding)
    name, meta = _stored_metadata(info["comments"])

    def read(positions: list[int]) -> list[np.ndarray]:
        try:
            frame = pd.read_csv(path, **_read_kwargs(info, positions))
        except pd.errors.EmptyDataError:  # a header and no data rows
            return [np.empty(0) for _ in positions]
        except ValueError as exc:
            raise _diagnose(path, info, positions, exc) from None
        return _columns(frame, positions, path, info)

    def iter_blocks(positions: list[int], size: int) -> Iterator[list[np.ndarray]]:
        rows = parse_rows(size, len(info["names"]))
        try:
            with pd.read_csv(path, chunksize=rows, **_read_kwargs(info, positions)) as reader:
                for frame in reader:
                    arrays = _columns(frame, positions, path, info)
                    for start in range(0, len(frame), size):
                        yield [a[start:start + size] for a in arrays]
        except pd.errors.EmptyDataError:  # a header and no data rows: no blocks
            return
        except ValueError as exc:
            raise _diagnose(path, info, positions, exc) from None

    hint = ("" if info["header"] else "; the file has no header line: name the columns by "
            "position, e.g. columns={0: 'time', 1: 'normal_force', 2: 'vt1', 3: 'vt2'}")
    return Source(label=str(path), format="csv", columns=list(info["names"]), read=read,
                  units=dict(info["units"]), name=name, metadata=meta, iter_blocks=iter_blocks,
                  hint=hint)


def write_csv(history: ContactHistory, path: str | os.PathLike, *,
              float_format: str | None = None, delimiter: str = ",") -> Path:
    """Write a history as CSV: a commented header documenting every column, then the samples.

    Parameters
    ----------
    history : ContactHistory
        The history (SI units).
    path : path-like
        Output file, written atomically.
    float_format : str, optional
        printf format of the values (e.g. ``"%.8g"``). Default: the shortest text that reads
        back as the same double (exact round trip), written by pyarrow when it is installed
        (about 10x faster), else by pandas.
    delimiter : str
        Column separator (default ``,``).

    A path ending in ``.gz`` (``h.csv.gz``) is gzip-compressed; readers decompress
    transparently.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> h = ContactHistory(time=[0, 0.1], normal_force=[2, 3], vt1=[0, 1], vt2=[0, 0], name="n1")
    >>> out = write_csv(h, pathlib.Path(tempfile.mkdtemp()) / "n1.csv")
    >>> out.read_text().splitlines()[-3:]
    ['time,normal_force,vt1,vt2', '0,2,0,0', '0.1,3,1,0']
    """
    if float_format is not None:
        try:
            float_format % 1.0
        except (TypeError, ValueError):
            raise InputError(f"float_format={float_format!r} is not a printf format such as "
                             "'%.8g'") from None
    frame = history.to_frame()
    lines = [MAGIC, f"# name: {history.name}",
             f"# metadata: {json.dumps(dict(history.metadata), default=str)}",
             "# columns (SI units):"]
    lines += [f"#   {ch} [{UNITS[ch]}]: {DESCRIPTIONS[ch]}" for ch in history.channels]
    lines.append(delimiter.join(frame.columns))
    target = Path(path)
    if target.suffix.lower() == ".gz":  # compressed: pandas through a gzip stream
        with atomic_write(target, "wb") as raw, \
                gzip.open(raw, "wt", encoding="utf-8", newline="") as handle:
            handle.write("\n".join(lines) + "\n")
            frame.to_csv(handle, index=False, header=False, float_format=float_format,
                         sep=delimiter, lineterminator="\n")
        return target
    # pyarrow's CSV writer when installed (exact shortest round-trip), else pandas'
    pa = optional("pyarrow") if float_format is None else None
    pacsv = optional("pyarrow.csv") if pa is not None else None
    if pacsv is not None:
        with atomic_write(target, "wb") as handle:
            handle.write(("\n".join(lines) + "\n").encode("utf-8"))
            pacsv.write_csv(pa.Table.from_pandas(frame, preserve_index=False), handle,
                            pacsv.WriteOptions(include_header=False, delimiter=delimiter))
        return target
    with atomic_write(target, "w", encoding="utf-8", newline="") as handle:
        handle.write("\n".join(lines) + "\n")
        frame.to_csv(handle, index=False, header=False, float_format=float_format,
                     sep=delimiter, lineterminator="\n")
    return target
