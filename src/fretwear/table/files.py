"""Reading and writing wear tables in every format: CSV, Parquet and Code_Aster text tables
(IMPR_TABLE's TABLEAU and ASTER formats), native or Code_Aster column names (theory §7).
"""

from __future__ import annotations

import os
from pathlib import Path

import pandas as pd

from fretwear.errors import FormatError, InputError
from fretwear.io.aster import TABLE_FORMATS, read_aster_table, write_aster_table
from fretwear.io.atomic import atomic_path
from fretwear.table.schema import from_aster_names, to_aster_names

__all__ = ["read_wear_table", "write_wear_table"]

_ASTER_SUFFIXES = (".tab", ".resu", ".txt")


def read_wear_table(path: str | os.PathLike, *, index: int | None = None) -> pd.DataFrame:
    """Read a wear table file (CSV, Parquet or a Code_Aster text table) with native names.

    Parameters
    ----------
    path : path-like
        ``.csv`` and ``.parquet`` files written by fretwear, or an IMPR_TABLE file (TABLEAU or
        ASTER format; any other suffix) read by :func:`fretwear.io.aster.read_aster_table`.
    index : int, optional
        Which table (0-based) of a Code_Aster file holding several; needed then.

    Returns
    -------
    pandas.DataFrame
        The table with native column names (:data:`fretwear.table.COLUMNS`; volumes [m³],
        depths [m], instants in the user's time unit).

    Examples
    --------
    >>> import tempfile
    >>> p = Path(tempfile.mkdtemp()) / "t.tab"
    >>> _ = p.write_text("#\\nINST V_USUR_TUBE\\n 1.00000E+00 2.50000E-09\\n")
    >>> read_wear_table(p).columns.tolist()
    ['instant', 'volume_mobile']
    """
    p = Path(path)
    if not p.is_file():
        raise InputError(f"wear table file {str(p)!r} does not exist; give the path of a table "
                         "written by fretwear or by Code_Aster's IMPR_TABLE")
    suffix = p.suffix.lower()
    if suffix == ".csv":
        frame = pd.read_csv(p)
    elif suffix in (".parquet", ".pq"):
        frame = pd.read_parquet(p)
    else:
        try:
            frame = read_aster_table(p, index=index)
        except FormatError as exc:
            raise FormatError(f"{exc} [wear table: in a case file give [restart] table_index "
                              "= <n>; in Python read_wear_table(path, index=<n>)]") from None
        return from_aster_names(frame)
    if index not in (None, 0):
        raise InputError(f"wear table file {str(p)!r} holds one table; table_index / index = "
                         f"{index} applies to Code_Aster text files only")
    return from_aster_names(frame)


def write_wear_table(table, path: Path, *, aster_names: bool = False, title: str | None = None,
                aster_format: str = "TABLEAU") -> Path:
    """Write a wear table atomically; the suffix chooses CSV, Parquet or a Code_Aster table.

    Parameters
    ----------
    table : pandas.DataFrame
        A wear table, native column names (:data:`fretwear.table.COLUMNS`).
    path : pathlib.Path
        ``.csv``, ``.parquet``/``.pq``, or ``.tab``/``.resu``/``.txt`` (Code_Aster IMPR_TABLE
        text, Code_Aster column names, reals ``%.10E``).
    aster_names : bool
        Code_Aster column names in CSV/Parquet too.
    title : str, optional
        Title line of a Code_Aster table.
    aster_format : str
        ``"TABLEAU"`` or ``"ASTER"`` (``#DEBUT_TABLE`` ... with a line of types): the
        ``FORMAT`` of Code_Aster's IMPR_TABLE / LIRE_TABLE.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> p = Path(tempfile.mkdtemp()) / "t.tab"
    >>> _ = write_table(pd.DataFrame({"instant": [1.0], "volume_mobile": [2e-9]}), p)
    >>> p.read_text().splitlines()[2].split()
    ['INST', 'V_USUR_TUBE']
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in _ASTER_SUFFIXES:
        fmt = str(aster_format).upper()
        if fmt not in TABLE_FORMATS:
            raise InputError(f"aster_format must be {' or '.join(TABLE_FORMATS)}, got "
                             f"{aster_format!r}")
        return write_aster_table(to_aster_names(table), path, format=fmt,
                                 title=title or "POST_USURE fretwear", float_format="%.10E")
    frame = to_aster_names(table) if aster_names else table
    frame = frame.copy()
    frame.attrs = {}
    if suffix == ".csv":
        with atomic_path(path) as tmp:
            frame.to_csv(tmp, index=False)  # shortest repr: exact round trip
    elif suffix in (".parquet", ".pq"):
        with atomic_path(path) as tmp:
            frame.to_parquet(tmp, index=False)
    else:
        raise InputError(f"output {str(path)!r}: unknown suffix {suffix!r}; use .csv, .parquet, "
                         f"or {', '.join(_ASTER_SUFFIXES)} for a Code_Aster table")
    return path


#: the former name (fretwear.cli.run.write_table)
write_table = write_wear_table
