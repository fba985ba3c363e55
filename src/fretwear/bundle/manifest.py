"""The manifest of a bundle: one row per contact, where its history is, and what differs.

Sources accepted by :func:`read_manifest`:

* a **table** (CSV, Parquet, or TOML ``[[contacts]]``), one row per contact: ``contact`` (unique
  id), ``history`` (path relative to the manifest), optional ``node`` (one shock point of a
  multi-node Code_Aster table, or the HDF5 group), identity columns ``tube_row``,
  ``tube_column``, ``support``, and any case-file key as a column overriding the base case for
  that row (``mobile_radius_m`` or ``geometry.mobile_radius_m``, ``law.mobile.COEF_USURE``);
* a **Code_Aster table holding many nodes** (IMPR_TABLE of a RESU_GENE with a ``NOEUD`` column):
  one contact per node;
* an **xarray Dataset** (in memory) or a **Zarr / NetCDF store** with dimensions
  ``(contact, time)`` and one variable per channel (names as in history files: ``time``,
  ``normal_force`` or ``FN`` ...; units in each variable's ``units`` attribute); 1-D variables
  along ``contact`` are identity columns or case-key overrides, as manifest columns.

Unknown columns are errors naming the closest valid name, as in case files.
"""

from __future__ import annotations

import os
import tomllib
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.columns import (  # noqa: F401 - re-exported
    BUNDLE_COLUMNS,
    IDENTITY,
    WALL_COLUMN,
    WHOLE_SECTIONS,
    _case_keys,
    check_unique,
    check_wall_column,
    column_key,
    column_meanings,
    empty_cell,
    identity_columns,
    valid_columns,
)
from fretwear.bundle.datasets import (
    CONTACT_DIM,
    channel_variables,
    open_store,
    path_stamp,
    require,
    time_dim,
    trim,
)
from fretwear.bundle.frozen import collector_paused
from fretwear.bundle.manifest_paths import HistoryPaths, absolute
from fretwear.errors import FormatError, InputError, KeywordError
from fretwear.io import guess_format
from fretwear.io.aster import read_aster_tables
from fretwear.io.aster_source import NODE_COLUMNS
from fretwear.io.delimited import UTF16_BOMS, scan
from fretwear.io.guard import readable_file, reading
from fretwear.io.text_tables import decode_text

#: Case keys holding paths (relative to the manifest when given in a manifest cell).
PATH_KEYS = {("restart", "table"), ("law", "database")}
TABLE_SUFFIXES = (".csv", ".tsv", ".parquet", ".pq", ".toml")
STORE_SUFFIXES = (".zarr", ".nc", ".nc4", ".netcdf", ".cdf")


@dataclass(frozen=True)
class HistoryRef:
    """Where one contact's history is.

    Attributes
    ----------
    kind : str
        ``"file"`` (a history file), ``"store"`` (one contact of a Zarr/NetCDF store),
        ``"memory"`` (arrays of an in-memory Dataset) or ``"none"`` (a given power).
    path : str
        Absolute path of the file or store ("" otherwise).
    node : str or None
        Shock point of a multi-node Code_Aster table (or HDF5 group).
    index : int
        Position of the contact along the store's ``contact`` dimension.
    arrays : dict
        ``{variable: 1-D array}`` of an in-memory contact, ``units`` per variable in ``units``.
    time_dim : str
        The time dimension of a store.
    stamp : tuple
        A store's :func:`~fretwear.bundle.datasets.path_stamp`, taken once for all its contacts.
    """

    kind: str
    path: str = ""
    node: str | None = None
    index: int = -1
    arrays: Mapping[str, np.ndarray] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)
    time_dim: str = "time"
    stamp: tuple = ()

    def label(self) -> str:
        """Short description for tables and messages."""
        if self.kind == "file":
            return self.path if self.node is None else f"{self.path} [{self.node}]"
        if self.kind == "store":
            return f"{self.path} [contact {self.index}]"
        return "<in-memory>" if self.kind == "memory" else ""


@dataclass
class ContactRow:
    """One contact of the manifest: id, history, identity and raw case overrides.

    ``labels`` names each override as the manifest wrote it (``column mobile_radius_m``, ``key
    law.mobile``) for messages.
    """

    contact: str
    history: HistoryRef
    identity: dict[str, Any]
    overrides: dict[tuple[str, ...], Any]
    labels: dict[tuple[str, ...], str] = field(default_factory=dict)


@dataclass
class Manifest:
    """The contacts of a bundle (:func:`read_manifest`)."""

    rows: list[ContactRow]
    source: str
    directory: Path
    kind: str

    def __len__(self) -> int:
        return len(self.rows)

    def identity_frame(self) -> pd.DataFrame:
        """One row per contact: the identity columns."""
        return pd.DataFrame([{**r.identity, "contact": r.contact, "history": r.history.label()}
                             for r in self.rows]).reindex(columns=list(IDENTITY))


def _plain(value: Any) -> Any:
    """numpy / pandas scalars and arrays -> plain Python values."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    return value


def _identity_value(value: Any) -> Any:
    value = _plain(value)
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return value


def _rows_from_frame(frame: pd.DataFrame, source: str, directory: Path, *,
                     noun: str = "column") -> list[ContactRow]:
    columns = [str(c) for c in frame.columns]
    if frame.empty:
        return []  # read_manifest says the manifest has no contacts
    meaning = column_meanings(columns, source, noun=noun)
    check_wall_column({c: frame[c].to_numpy() for c in frame.columns}, meaning, source,
                      frame["contact"].to_numpy() if "contact" in frame else None, noun)
    if "contact" not in columns:
        raise KeywordError(f"{source}: the manifest needs a 'contact' column (unique id of each "
                           f"contact); columns found: {columns}")
    if not frame.columns.is_unique:  # as DataFrame.to_dict("records") reads them: the last
        warnings.warn("DataFrame columns are not unique, some columns will be omitted.",
                      UserWarning, stacklevel=3)
        frame = frame.loc[:, ~frame.columns.duplicated(keep="last")]
    cells = [(str(col), meaning[str(col)], *_column_cells(frame[col], meaning[str(col)]))
             for col in frame.columns
             if meaning[str(col)] not in ("contact", "history", "node")]
    own = {k: frame[k].tolist() if k in frame else None for k in ("contact", "history", "node")}
    rows = []
    hists = [None] * len(frame) if own["history"] is None else \
        [None if empty_cell(h) else str(h) for h in own["history"]]
    path_of = HistoryPaths([h for h in hists if h is not None], directory)
    for i, cid in enumerate(own["contact"]):
        if empty_cell(cid):
            raise InputError(f"{source}: row {i + 1} has no contact id; give every row one")
        cid = cid if type(cid) is str else str(_identity_value(cid))
        identity, overrides, labels = _row_cells(cells, i, cid, source, directory, noun)
        node = None if own["node"] is None else own["node"][i]
        node = None if empty_cell(node) else str(_identity_value(node))
        hist = hists[i]
        if hist is None:
            ref = HistoryRef("none", node=node)
        else:
            ref = HistoryRef("file", path=path_of(hist), node=node)
        identity["node"] = node
        rows.append(ContactRow(cid, ref, identity, overrides, labels))
    check_unique([r.contact for r in rows], source)
    return rows


def _column_cells(series: pd.Series, key) -> tuple[list, list | None, list]:
    """(values, empty, raw) of one manifest column, by column (a 10^4-row manifest spent
    0.1 ms a row testing and converting its cells one by one): ``raw`` its cells as
    ``DataFrame.to_dict("records")`` gives them, ``empty`` whether each is empty
    (:func:`empty_cell`; None: none is), ``values`` the identity value of each
    (:func:`_identity_value`) for an identity column, else ``raw``."""
    raw = series.tolist()
    # numpy's own dtypes only: a nullable Int64 or boolean column has kind "i"/"b" and holds NA
    kind = series.dtype.kind if isinstance(series.dtype, np.dtype) else "O"
    if kind in "iub":  # numbers and booleans: never empty, already plain
        return raw, None, raw
    empty = np.isnan(series.to_numpy()).tolist() if kind == "f" else [empty_cell(v) for v in raw]
    if not isinstance(key, str):
        return raw, empty, raw
    if kind == "f":  # _identity_value of a float: an integral one becomes an int
        return [int(v) if v.is_integer() else v for v in raw], empty, raw
    return [None if e else _identity_value(v) for v, e in zip(raw, empty, strict=True)], \
        empty, raw


def _row_cells(cells, i: int, contact: str, source: str, directory: Path, noun: str
               ) -> tuple[dict[str, Any], dict[tuple[str, ...], Any], dict]:
    """(identity, overrides, labels) of row ``i`` from the columns of :func:`_column_cells`:
    :func:`_cells` of the row's cells."""
    identity: dict[str, Any] = {}
    overrides: dict[tuple[str, ...], Any] = {}
    labels: dict[tuple[str, ...], str] = {}
    for name, key, values, empty, raw in cells:
        if empty is not None and empty[i]:
            continue
        if isinstance(key, str):
            identity[key] = values[i]
            if not isinstance(identity[key], str | int | float | bool):
                raise InputError(f"{source}: contact {contact!r}: {noun} {name} = {raw[i]!r} is "
                                 f"not one value (a number or a name); give one {name} per "
                                 "contact")
        else:
            value = _plain(raw[i])
            overrides[key] = absolute(value, directory) if key in PATH_KEYS else value
            labels[key] = f"{noun} {name}"
    return identity, overrides, labels


def _cells(cells, contact: str, source: str, directory: Path, noun: str = "column"
           ) -> tuple[dict[str, Any], dict[tuple[str, ...], Any], dict]:
    """(identity, overrides, labels) of one row from its ``(name, meaning, value)`` cells
    (meaning from :func:`column_key`); empty cells are skipped, paths made absolute;
    ``labels`` names each override as the manifest wrote it (``column mobile_radius_m``)."""
    identity: dict[str, Any] = {}
    overrides: dict[tuple[str, ...], Any] = {}
    labels: dict[tuple[str, ...], str] = {}
    for name, key, value in cells:
        if empty_cell(value) or key in ("contact", "history", "node"):
            continue
        if isinstance(key, str):
            identity[key] = _identity_value(value)
            if not isinstance(identity[key], str | int | float | bool):
                raise InputError(f"{source}: contact {contact!r}: {noun} {name} = {value!r} is "
                                 f"not one value (a number or a name); give one {name} per "
                                 "contact")
        else:
            value = _plain(value)
            overrides[key] = absolute(value, directory) if key in PATH_KEYS else value
            labels[key] = f"{noun} {name}"
    return identity, overrides, labels


def _flatten(table: Mapping[str, Any], source: str, prefix: str = "") -> dict[str, Any]:
    """A TOML contact table -> manifest columns: nested tables become dotted names, down to
    the entries of dict-valued case keys (``law.mobile = { COEF_USURE = 6e-14 }`` and
    ``law.mobile.COEF_USURE = 6e-14``, which TOML reads alike, both give the column
    ``law.mobile.COEF_USURE``: the row updates that entry of the base case's table, as a CSV
    column of that name does). An empty table (``law.mobile = {}``, ``sectors = {}``) stays
    whole: that key, or that section, is dropped for the row
    (:func:`fretwear.bundle.cases.merge_case`).

    Raises
    ------
    KeywordError
        An empty table of a section that a row cannot drop (``geometry = {}``): it would
        change nothing.
    """
    keys = _case_keys()
    out: dict[str, Any] = {}
    for k, v in table.items():
        name = f"{prefix}{k}"
        parts = name.split(".")
        entries = (len(parts) == 2 and parts[0] in keys
                   and keys[parts[0]].get(parts[1], (None,))[0] is dict)
        if entries and isinstance(v, Mapping) and v:
            out.update({f"{name}.{entry}": value for entry, value in v.items()})
        elif isinstance(v, Mapping) and not v and name in WHOLE_SECTIONS:
            out[name] = {}  # the base case's section dropped for the row
        elif isinstance(v, Mapping) and not v and name in keys and name not in BUNDLE_COLUMNS:
            raise KeywordError(f"{source}: contact {table.get('contact', '?')!r}: {name} = {{}} "
                               f"would change nothing: an empty table drops a section of the "
                               f"base case only for {', '.join(WHOLE_SECTIONS)}; change "
                               f"[{name}] key by key ({name}.<key> = value)")
        elif isinstance(v, Mapping) and not entries:
            out.update(_flatten(v, source, prefix=f"{name}."))
        else:
            out[name] = v
    return out


def _read_toml(path: Path) -> pd.DataFrame:
    try:
        with reading(path, "toml", "manifest"):
            raw = tomllib.loads(decode_text(path.read_bytes(), f"manifest {str(path)!r}"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"manifest {str(path)!r} is not valid TOML: {exc}") from None
    extra = sorted(set(raw) - {"contacts"})
    if extra or not isinstance(raw.get("contacts"), list):
        raise KeywordError(f"manifest {str(path)!r}: a TOML manifest holds an array of tables "
                           f"[[contacts]] (one per contact) and nothing else; found keys "
                           f"{sorted(raw)}")
    return pd.DataFrame([_flatten(c, str(path)) for c in raw["contacts"]])


def _read_csv(path: Path, label: str) -> pd.DataFrame:
    """A CSV manifest: ``,``-separated, or ``;``- or tab-separated (a spreadsheet saved in a
    locale whose decimal mark is the comma; decimal commas are then read), the separator and
    the decimal mark found as the history reader finds them
    (:func:`fretwear.io.delimited.scan`). UTF-8 text (UTF-16 with its BOM); an empty or blank
    file has no contacts.

    Raises
    ------
    FormatError
        Not UTF-8 text (a spreadsheet saved in its locale's code page, e.g. Windows-1252),
        with how to save it; an unreadable table.
    """
    raw = path.read_bytes()
    encoding = "utf-16" if raw[:2] in UTF16_BOMS else "utf-8-sig"
    try:
        text = raw.decode(encoding)
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        raise FormatError(
            f"manifest {label!r} is not UTF-8 text (byte {raw[exc.start]:#04x} on line {line}: "
            "an accented character saved in the spreadsheet's code page, e.g. Windows-1252 by "
            "Excel's 'CSV (séparateur: point-virgule)'): save it as CSV UTF-8 (Excel: 'CSV "
            "UTF-8 (délimité par des virgules)'); ';' separators and decimal commas are "
            "read") from None
    if not text.strip():
        return pd.DataFrame()  # an empty or blank file: read_manifest says it has no contacts
    info = scan(path)  # only comments: its FormatError says so
    sep, decimal = (info["sep"], info["decimal"]) if info["sep"] in (";", "\t") else (",", ".")
    try:
        # only empty cells are missing: a contact may be called "NA" or "nan"
        return pd.read_csv(path, sep=sep, decimal=decimal,
                           dtype={"contact": str, "node": str, "history": str},
                           keep_default_na=False, na_values=[""], skipinitialspace=True,
                           encoding=info["encoding"])
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise FormatError(f"manifest {label!r} is not a readable CSV table: {exc}") from None


def _is_store(path: Path) -> bool:
    if path.suffix.lower() in STORE_SUFFIXES:
        return True
    return path.is_dir() and any((path / m).exists() for m in (".zgroup", "zarr.json",
                                                              ".zattrs"))


def read_manifest(source: Any) -> Manifest:
    """Read the contacts of a bundle from a manifest, a Code_Aster table or a Dataset.

    Parameters
    ----------
    source : path-like, DataFrame or xarray.Dataset
        A manifest table (``.csv`` or ``.tsv``, ``.parquet``, ``.toml``), a Code_Aster
        table of several shock points (one contact per ``NOEUD``), a Zarr or NetCDF store or
        an in-memory Dataset with dimensions ``(contact, time)``, or a DataFrame of manifest
        rows (paths relative to the current directory).

    Returns
    -------
    Manifest

    Raises
    ------
    KeywordError
        An unknown column (with the closest valid name), a missing ``contact`` column.
    InputError
        A missing file, a duplicated contact id, an unreadable table.

    Examples
    --------
    >>> m = read_manifest(pd.DataFrame({"contact": ["a", "b"], "history": ["a.csv", "b.csv"],
    ...                                 "tube_row": [1, 2], "mobile_radius_m": [0.0095, None]}))
    >>> [r.contact for r in m.rows], m.rows[0].overrides
    (['a', 'b'], {('geometry', 'mobile_radius_m'): 0.0095})
    """
    # the collector off while the rows are made: objects without cycles (a frozen dataclass,
    # dicts and text per row), whose young-generation passes over the growing list were a
    # sixth of a 10^5-row manifest's read (issue 28)
    with collector_paused():
        manifest = _read(source)
    if not manifest.rows:
        raise InputError(f"{manifest.source} has no contacts (a header only?); a manifest has "
                         "one row per contact")
    return manifest


def _read(source: Any) -> Manifest:
    """:func:`read_manifest` before the check that it has contacts."""
    if isinstance(source, pd.DataFrame):
        return Manifest(_rows_from_frame(source, "manifest", Path.cwd()), "<DataFrame>",
                        Path.cwd(), "table")
    if hasattr(source, "data_vars") and hasattr(source, "dims"):
        return Manifest(rows_from_dataset(source, None, "<Dataset>"), "<Dataset>", Path.cwd(),
                        "dataset")
    if not isinstance(source, str | os.PathLike):
        raise InputError(f"a manifest is a file path, a DataFrame or an xarray Dataset, got "
                         f"{type(source).__name__}")
    path = Path(source)
    if not path.exists():
        raise InputError(f"manifest {str(path)!r} does not exist")
    if not path.is_dir():  # a store is a directory; a file is read through the guard layer
        readable_file(path, "manifest")  # (a named pipe or a device refused, never read)
    directory = path.resolve().parent
    label = str(path)
    suffix = path.suffix.lower()
    if _is_store(path):
        return Manifest(rows_from_dataset(None, path.resolve(), label), label, directory,
                        "dataset")
    if suffix == ".toml":
        frame = _read_toml(path)
        return Manifest(_rows_from_frame(frame, label, directory, noun="key"), label, directory,
                        "table")
    if suffix in (".parquet", ".pq"):
        require("pyarrow", purpose="reading a Parquet manifest")
        with reading(readable_file(path, "manifest"), "parquet", "manifest"):
            frame = pd.read_parquet(path)
    elif suffix in (".csv", ".tsv"):  # the separator is found, not taken from the suffix
        frame = _read_csv(path, label)
    else:
        if path.is_file() and guess_format(path) == "aster":
            return Manifest(_rows_from_aster(path.resolve(), label), label, directory, "aster")
        raise InputError(f"{label!r} is not a manifest: give a .csv, .tsv, .parquet or .toml "
                         "table of contacts, a Code_Aster table of several nodes, or a "
                         "Zarr/NetCDF store with dimensions (contact, time)")
    return Manifest(_rows_from_frame(frame, label, directory), label, directory, "table")


def node_columns(frame: pd.DataFrame) -> list[str]:
    """The text columns of a Code_Aster table naming the shock point of each row (``NOEUD``,
    ``NOEUD_CHOC``, ``GROUP_NO`` ..., :data:`fretwear.io.aster_source.NODE_COLUMNS`)."""
    types = frame.attrs.get("types") or [None] * frame.shape[1]
    return [str(c) for c, kind in zip(frame.columns, types, strict=False)
            if (kind is None or str(kind).upper().startswith("K"))
            and (str(c).upper() in NODE_COLUMNS or str(c).upper().startswith(("NOEUD",
                                                                              "GROUP_NO")))]


def _rows_from_aster(path: Path, label: str) -> list[ContactRow]:
    nodes: list[str] = []
    for frame in read_aster_tables(path):
        for column in node_columns(frame):
            nodes += [str(v).strip() for v in pd.unique(frame[column].dropna())]
    nodes = list(dict.fromkeys(n for n in nodes if n))
    if not nodes:
        raise FormatError(f"{label}: a Code_Aster table used as a bundle needs a node column "
                          "(NOEUD, NOEUD_CHOC, GROUP_NO ...: one contact per node); none found. "
                          "For one contact, use fretwear run")
    return [ContactRow(n, HistoryRef("file", path=str(path), node=n), {"node": n}, {})
            for n in nodes]


def _declared(variable) -> str:
    """The ``units`` attribute of a store's variable, "" when absent or blank."""
    return str(variable.attrs.get("units", "")).strip()


def rows_from_dataset(ds, path: Path | None, label: str) -> list:
    """The :class:`ContactRow` of every contact of a Dataset or store (layout in
    :mod:`fretwear.bundle.datasets`)."""
    if ds is None:
        ds = open_store(path)
    tdim = time_dim(ds, label)
    channels = channel_variables(ds, tdim)
    n = ds.sizes[CONTACT_DIM]
    if CONTACT_DIM in ds.coords:
        ids = [str(_identity_value(v)) for v in ds[CONTACT_DIM].values]
    else:
        ids = [f"c{i}" for i in range(n)]
    columns = {}
    for name, var in ds.variables.items():
        if name == CONTACT_DIM or var.dims != (CONTACT_DIM,):
            continue
        columns[str(name)] = var.values
    meaning = column_meanings(list(columns), label)
    check_wall_column(columns, meaning, label, ids, "variable")
    # an empty units attribute (xarray and netCDF writers leave units="") declares nothing
    units = {c: _declared(ds[c]) for c in channels if _declared(ds[c])}
    if "time" in ds.coords and ds["time"].dims == (tdim,) and "time" not in channels:
        shared_time = np.asarray(ds["time"].values, dtype=float)
        if _declared(ds["time"]):
            units["time"] = _declared(ds["time"])
    else:
        shared_time = None
    directory = Path.cwd() if path is None else path.parent
    stamp = () if path is None else path_stamp(path)  # once: a Zarr store may hold many files
    rows = []
    for i, cid in enumerate(ids):
        identity, overrides, labels = _cells(
            ((name, meaning[name], values[i]) for name, values in columns.items()), cid, label,
            directory)
        if path is None:
            arrays = {c: np.asarray(ds[c].isel({CONTACT_DIM: i}).values, dtype=float)
                      for c in channels}
            if shared_time is not None:
                arrays["time"] = shared_time
            ref = HistoryRef("memory", arrays=trim(arrays), units=units, time_dim=tdim)
        else:
            ref = HistoryRef("store", path=str(path), index=i, units=units, time_dim=tdim,
                             stamp=stamp)
        node = columns["node"][i] if "node" in columns else None
        identity["node"] = None if empty_cell(node) else str(_identity_value(node))
        rows.append(ContactRow(cid, ref, identity, overrides, labels))
    check_unique(ids, label)
    return rows
