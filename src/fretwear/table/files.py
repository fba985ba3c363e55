"""Reading and writing fretwear's tables in every format: CSV, Parquet and Code_Aster text
tables (IMPR_TABLE's TABLEAU and ASTER formats), native or Code_Aster column names (theory §7).

One schema (:mod:`fretwear.table.schema`: the wear table's :data:`COLUMNS`, the obstacle
profile's :data:`PROFILE_COLUMNS`), one float format for text (:data:`FLOAT_FORMAT`, exact) and
one provenance header (:mod:`fretwear.table.provenance`: version, date, law, coefficients and
their sources, case name) in every file; the readers skip the header and return it in
``attrs["provenance"]``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from fretwear._lazy import pandas as pd
from fretwear._optional import require
from fretwear.errors import FormatError, InputError
from fretwear.io.aster import TABLE_FORMATS, read_aster_table, write_aster_table
from fretwear.io.atomic import atomic_path, atomic_write
from fretwear.io.guard import readable_file, reading
from fretwear.table.provenance import PARQUET_KEY, header_lines, parse_header, provenance
from fretwear.table.schema import (
    COLUMNS,
    FLOAT_FORMAT,
    PROFILE_COLUMNS,
    from_aster_names,
    to_aster_names,
)

__all__ = ["read_profile_table", "read_wear_table", "write_profile_table", "write_wear_table"]

#: Suffixes of a wear table written as a Code_Aster text table (IMPR_TABLE, read by LIRE_TABLE).
ASTER_SUFFIXES = (".tab", ".resu", ".txt")
#: Code_Aster column name -> native name (a Code_Aster table is read with native names).
_NATIVE = {aster: native for native, (aster, _, _) in COLUMNS.items()}


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
    try:
        p = readable_file(path, "wear table file")
    except InputError as exc:
        raise InputError(f"{exc}; give the path of a table written by fretwear or by "
                         "Code_Aster's IMPR_TABLE") from None
    suffix = p.suffix.lower()
    if suffix == ".csv":
        with reading(p, "csv", "wear table file"):
            try:
                header, skip = _comment_lines(p)
                frame = pd.read_csv(p, encoding="utf-8-sig", skiprows=skip)
            except pd.errors.EmptyDataError:
                raise FormatError(f"{p}: empty wear table (no header line); give a table "
                                  "written by fretwear or by Code_Aster's IMPR_TABLE") from None
    elif suffix in (".parquet", ".pq"):
        require("pyarrow.parquet", purpose="reading a Parquet wear table")
        with reading(p, "parquet", "wear table file"):
            frame = pd.read_parquet(p)
            header = _parquet_provenance(p)
    else:
        return read_aster_wear_table(p, index=index)
    if index not in (None, 0):
        raise InputError(f"wear table file {str(p)!r} holds one table; table_index / index = "
                         f"{index} applies to Code_Aster text files only")
    return _with_provenance(from_aster_names(frame), header)


def read_aster_wear_table(path: Path, *, index: int | None = None, data: bytes | None = None
                          ) -> pd.DataFrame:
    """A wear table from a Code_Aster text file (:func:`read_wear_table` of a suffix other than
    CSV and Parquet), native names; ``data``: the file's bytes, already read (parsed instead of
    reading the file again: :func:`fretwear.table.restart.initial_state`'s memo)."""
    try:
        with reading(path, "aster", "wear table file"):  # native names as the frame is made
            frame = read_aster_table(path, index=index, rename=_NATIVE, data=data)
    except FormatError as exc:
        raise FormatError(f"{exc} [wear table: in a case file give [restart] table_index "
                          "= <n>; in Python read_wear_table(path, index=<n>)]") from None
    return _with_provenance(frame, str(frame.attrs.get("title", "")).splitlines())


def write_wear_table(table, path: Path, *, aster_names: bool = False, title: str | None = None,
                     aster_format: str = "TABLEAU") -> Path:
    """Write a wear table atomically; the suffix chooses CSV, Parquet or a Code_Aster table.

    Every format carries the provenance header (:mod:`fretwear.table.provenance`) and writes
    reals exactly (text: :data:`~fretwear.table.schema.FLOAT_FORMAT`, ``%.16E``). CSV and
    Parquet also carry the wear case and the power, so that the table read back
    (:func:`read_wear_table`) is rebuilt into its depth model
    (:func:`fretwear.table.models_from_table`: Monte Carlo, calibration); a Code_Aster text
    table does not (its title lines are LIRE_TABLE's).

    Parameters
    ----------
    table : pandas.DataFrame
        A wear table, native column names (:data:`fretwear.table.COLUMNS`); its ``attrs``
        give the provenance (law, coefficients and their sources, title).
    path : pathlib.Path
        ``.csv``, ``.parquet``/``.pq``, or ``.tab``/``.resu``/``.txt`` (Code_Aster IMPR_TABLE
        text, Code_Aster column names).
    aster_names : bool
        Code_Aster column names in CSV/Parquet too.
    title : str, optional
        Title of the table (default ``attrs["title"]``, else "POST_USURE fretwear"), the first
        title line of a Code_Aster table.
    aster_format : str
        ``"TABLEAU"`` or ``"ASTER"`` (``#DEBUT_TABLE`` ... with a line of types): the
        ``FORMAT`` of Code_Aster's IMPR_TABLE / LIRE_TABLE.

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> p = Path(tempfile.mkdtemp()) / "t.tab"
    >>> t = pd.DataFrame({"instant": [1.0], "volume_mobile": [1 / 3 * 1e-9]})
    >>> t.attrs = {"law": "ARCHARD"}
    >>> back = read_wear_table(write_wear_table(t, p))
    >>> back["volume_mobile"].tolist(), back.attrs["provenance"]["law"]
    ([3.333333333333333e-10], 'ARCHARD')
    """
    path = Path(path)
    fmt = _format_of(path, aster_format)
    attrs = dict(getattr(table, "attrs", {}) or {})
    native = to_aster_names(table) if aster_names and fmt in ("CSV", "PARQUET") else table
    return _write(native, to_aster_names(table), path, fmt,
                  title or attrs.get("title") or "POST_USURE fretwear", provenance(attrs))


def write_profile_table(frame: pd.DataFrame, path, *, format: str | None = None,
                        title: str | None = None, **extra) -> Path:
    """Write an obstacle profile table (:data:`~fretwear.table.schema.PROFILE_COLUMNS`).

    Parameters
    ----------
    frame : pandas.DataFrame
        The profile, native names (:meth:`fretwear.obstacle.ObstacleResult.to_frame`).
    path : path-like
        Output file, written atomically.
    format : str, optional
        ``"csv"``, ``"parquet"``, ``"TABLEAU"`` or ``"ASTER"`` (Code_Aster names THETA,
        JEU_INIT, JEU_USE, P_USUR_TUBE, P_USUR_OBST); default from the suffix (``.csv``,
        ``.parquet``, else TABLEAU).
    title : str, optional
        Title (first title line of a Code_Aster table).
    **extra
        More provenance items (JSON-ready), e.g. ``instant=5.0``.

    Returns
    -------
    pathlib.Path
    """
    target = Path(path)
    if format is None:
        suffix = target.suffix.lower()
        fmt = "CSV" if suffix == ".csv" else "PARQUET" if suffix in (".parquet", ".pq") \
            else "TABLEAU"
    else:
        fmt = str(format).upper()
        if fmt not in ("CSV", "PARQUET", *TABLE_FORMATS):
            raise InputError(f"unknown profile table format {format!r}; use csv, parquet, "
                             f"{' or '.join(TABLE_FORMATS)}")
    aster = frame.rename(columns={k: v for k, (v, _, _) in PROFILE_COLUMNS.items()})
    prov = provenance(frame.attrs, kind="obstacle profile", **extra)
    return _write(frame, aster, target, fmt, title or "fretwear obstacle profile", prov)


def read_profile_table(path, *, index: int | None = None) -> pd.DataFrame:
    """Read a profile table written by :func:`write_profile_table`, native names, its
    provenance in ``attrs["provenance"]``."""
    frame = read_wear_table(path, index=index)
    native = {aster: name for name, (aster, _, _) in PROFILE_COLUMNS.items()}
    return frame.rename(columns={c: native[c] for c in frame.columns if c in native})


# --------------------------------------------------------------------------- one writer
def _format_of(path: Path, aster_format: str) -> str:
    suffix = path.suffix.lower()
    if suffix in ASTER_SUFFIXES:
        fmt = str(aster_format).upper()
        if fmt not in TABLE_FORMATS:
            raise InputError(f"aster_format must be {' or '.join(TABLE_FORMATS)}, got "
                             f"{aster_format!r}")
        return fmt
    if suffix == ".csv":
        return "CSV"
    if suffix in (".parquet", ".pq"):
        return "PARQUET"
    raise InputError(f"output {str(path)!r}: unknown suffix {suffix!r}; use .csv, .parquet, "
                     f"or {', '.join(ASTER_SUFFIXES)} for a Code_Aster table")


def _write(frame: pd.DataFrame, aster: pd.DataFrame, path: Path, fmt: str, title: str,
           prov: dict) -> Path:
    """Write ``frame`` (CSV, Parquet) or ``aster`` (Code_Aster text) with the provenance."""
    if fmt in TABLE_FORMATS:  # the case (kB of JSON) stays out of LIRE_TABLE's title lines
        lines = [*str(title).splitlines(),
                 *header_lines({k: v for k, v in prov.items() if k != "case"})]
        return write_aster_table(aster, path, format=fmt, title="\n".join(lines),
                                 float_format=FLOAT_FORMAT)
    frame = frame.copy()
    frame.attrs = {}
    if fmt == "CSV":
        with atomic_write(path, "w", encoding="utf-8", newline="") as handle:
            handle.writelines(f"# {line}\n" for line in header_lines(prov))
            frame.to_csv(handle, index=False, float_format=FLOAT_FORMAT, lineterminator="\n")
        return path
    pa = require("pyarrow", purpose="writing a Parquet table")
    parquet = require("pyarrow.parquet", purpose="writing a Parquet table")
    arrow = pa.Table.from_pandas(frame, preserve_index=False)
    meta = {**(arrow.schema.metadata or {}), PARQUET_KEY: json.dumps(prov).encode("utf-8")}
    with atomic_path(path) as tmp:
        parquet.write_table(arrow.replace_schema_metadata(meta), tmp)
    return path


def _comment_lines(path: Path) -> tuple[list[str], int]:
    """The leading ``#`` lines of a CSV file (the provenance header) and their number."""
    lines: list[str] = []
    with open(path, encoding="utf-8-sig") as handle:
        for line in handle:
            if not line.lstrip("\ufeff").startswith("#"):
                break
            lines.append(line.rstrip("\n"))
    return lines, len(lines)


def _parquet_provenance(path: Path) -> list[str] | dict:
    parquet = require("pyarrow.parquet", purpose="reading a Parquet wear table")
    meta = parquet.read_schema(path).metadata or {}
    text = meta.get(PARQUET_KEY)
    return {} if text is None else json.loads(text.decode("utf-8"))


def _with_provenance(frame: pd.DataFrame, header) -> pd.DataFrame:
    """``frame`` with ``attrs["provenance"]`` from header lines (or a provenance dict)."""
    prov = dict(header) if isinstance(header, dict) else parse_header(header)
    if prov:
        frame.attrs["provenance"] = prov
    return frame


#: the former name (fretwear.cli.run.write_table)
write_table = write_wear_table
