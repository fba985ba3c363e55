"""Small delimited text tables typed by users (inspections, lists): read through the guard layer.

:func:`read_text_table` reads a CSV a user wrote by hand or exported from a spreadsheet, every
cell as text, and says in fretwear's words (naming the file, the line and the fix) what pandas
would have raised as its own error or silently misread:

* the encoding: UTF-8 (with or without a byte-order mark) or UTF-16 with its mark; anything
  else is a :class:`~fretwear.errors.FormatError` asking for UTF-8;
* an empty file, or one of comments (``#``) and blank lines only;
* a row with more or fewer cells than the header (pandas took the first column as the index);
* a column label given twice (pandas renamed the second ``label.1``);
* a file larger than :data:`MAX_BYTES` (a table typed by a user is small: a wrong file).

Cells are left as text; numbers are the caller's (:func:`number`: a 400-digit integer is
``inf``, never an ``OverflowError``).
"""

from __future__ import annotations

import csv
import math
import os
from typing import Any

from fretwear._lazy import pandas as pd
from fretwear.errors import FormatError, InputError
from fretwear.io.guard import readable_file, reading

#: Largest text table read [bytes] (64 MiB).
MAX_BYTES = 64 << 20


def decode_text(raw: bytes, label: str) -> str:
    """UTF-8 (a BOM or none) or UTF-16 with its BOM, else a FormatError naming ``label``."""
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        return raw.decode("utf-16")
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise FormatError(f"{label}: not UTF-8 text (byte {exc.start + 1}: "
                          f"{raw[exc.start:exc.start + 1]!r}); save it as UTF-8 (a spreadsheet: "
                          "'CSV UTF-8')") from None


def read_text_table(path: Any, what: str = "table") -> pd.DataFrame:
    """A delimited text file (``,`` ``;`` or tab) as a DataFrame of text cells.

    Parameters
    ----------
    path : path-like
        The user's file.
    what : str
        What the file is, for the messages (``"inspection file"``).

    Returns
    -------
    DataFrame
        The header's labels (stripped) as columns, one row per data line, cells as ``str``
        (stripped); ``attrs['lines']`` the file's line number of each row.

    Raises
    ------
    InputError
        Not a readable file (missing, a directory, a pipe without a writer ...), too large.
    FormatError
        Not UTF-8/UTF-16 text, no header, a row of another length than the header, a label
        given twice: naming the file and the line.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
    >>> _ = p.write_text("# inspections\\ninstant;depth_mm\\n10;0.3\\n")
    >>> read_text_table(p).to_dict("list")
    {'instant': ['10'], 'depth_mm': ['0.3']}
    """
    file = readable_file(path, what)
    label = f"{what} {os.fspath(path)!r}"
    with reading(file, "csv", what):
        with open(file, "rb") as handle:
            raw = handle.read(MAX_BYTES + 1)
    if len(raw) > MAX_BYTES:
        raise InputError(f"{label} is larger than {MAX_BYTES >> 20} MiB: not a table typed by "
                         "hand; check the file name")
    if b"\x00" in raw and not raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise FormatError(f"{label}: binary data (a NUL byte), not a text table; give the CSV")
    text = decode_text(raw, label)
    lines = [(n, line) for n, line in enumerate(text.splitlines(), start=1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise FormatError(f"{label} is empty (no header line, only comments or blank lines); "
                          "the first line names the columns")
    header_line = lines[0][1]
    delimiter = max((",", ";", "\t"), key=header_line.count)
    # one row per line (a quote never joins lines: a row is what the user sees on one line)
    rows = [next(csv.reader([line], delimiter=delimiter), []) for _, line in lines]
    header = [c.strip() for c in rows[0]]
    seen: set[str] = set()
    for name in header:
        if not name:
            raise FormatError(f"{label}, line {lines[0][0]}: an empty column label; name every "
                              "column")
        if name in seen:
            raise FormatError(f"{label}, line {lines[0][0]}: the column {name!r} is given twice; "
                              "keep one")
        seen.add(name)
    for (number_, _), row in zip(lines[1:], rows[1:], strict=True):
        if len(row) != len(header):
            raise FormatError(f"{label}, line {number_}: {len(row)} cells for the "
                              f"{len(header)} columns {header} (separated by {delimiter!r}); "
                              "give one value per column")
    frame = pd.DataFrame([[c.strip() for c in row] for row in rows[1:]], columns=header,
                         dtype=object)
    if not len(frame):
        frame = pd.DataFrame({c: pd.Series([], dtype=object) for c in header})
    frame.attrs["lines"] = [n for n, _ in lines[1:]]
    return frame


def number(text: Any) -> float:
    """A cell as a float: NaN when empty or not a number, ``±inf`` beyond float range.

    >>> number("0.3"), number(""), number("9" * 400), number("abc")
    (0.3, nan, inf, nan)
    """
    if isinstance(text, int | float) and not isinstance(text, bool):
        try:
            return float(text)
        except OverflowError:
            return math.inf if text > 0 else -math.inf
    cell = str(text).strip()
    for candidate in (cell, cell.replace(",", ".") if cell.count(",") == 1 else ""):
        try:
            return float(candidate)  # a decimal comma (a ';' spreadsheet) read as the point
        except ValueError:
            continue
    return math.nan
