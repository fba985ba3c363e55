"""The wear-coefficient database (theory §5): the tables of Code_Aster R7.20.01 §3, plus user CSVs.

One row per coefficient, columns

============== ==================================================================================
contact_type   one of the eight Code_Aster contact types (``TUBE_BAV`` ... ``GRAPPE_2_ENCO``)
mobile_material, obstacle_material   material codes (``materials()``: A304L, I600TT, ...)
law            ``ARCHARD``, ``KWU_EPRI`` or ``EDF_MZ``
body           ``mobile`` or ``obstacle`` (optional in user files, default ``mobile``)
parameter      the law's coefficient by full name (``coefficient``, ``rate_coefficient``, ...) or
               Code_Aster keyword (``COEF_USURE``, ``COEF_B``, ...)
value          the number, in the unit of the ``unit`` column
unit           SI unit of the coefficient (checked): Archard K [Pa⁻¹]; EDF_MZ A [m³/(s·W^b)],
               b [1], n [s⁻¹], S [m³/s]
source         provenance (optional in user files, default ``<file>:<line>``)
============== ==================================================================================

The built-in values are those of the coefficient tables of Code_Aster's POST_USURE reference
manual (R7.20.01 §3), verbatim, even where Code_Aster's current source differs (theory §5), and
the KWU_EPRI and EDF_MZ values of TUBE_BAV I600/I600 that only Code_Aster's database routine
(``usuban.F90``) has, their ``source`` naming it (docs/laws.md lists where the two differ). An
empty box of those tables has no row: asking for it is a :class:`DatabaseError` that lists what
exists. User files extend the built-in rows and override a row with the same
(contact_type, mobile_material, obstacle_material, law, body, parameter); the ``source`` and
``origin`` (file) columns keep the provenance of every value.
"""

from __future__ import annotations

import dataclasses
import functools
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import DatabaseError, FormatError
from fretwear.geometry import CONTACT_TYPES
from fretwear.io.guard import readable_file, reading
from fretwear.laws.registry import WEAR_LAWS

#: The eight contact types of theory §6 (Code_Aster names), from the geometry registry.
CONTACT_TYPE_NAMES: tuple[str, ...] = tuple(CONTACT_TYPES)
#: Columns of a coefficient table, in order.
COLUMNS: tuple[str, ...] = ("contact_type", "mobile_material", "obstacle_material", "law", "body",
                            "parameter", "value", "unit", "source")
#: Columns a user file must have (``body``, ``source`` are optional).
REQUIRED_COLUMNS: tuple[str, ...] = ("contact_type", "mobile_material", "obstacle_material", "law",
                                     "parameter", "value", "unit")
#: The columns identifying one coefficient.
KEY: tuple[str, ...] = ("contact_type", "mobile_material", "obstacle_material", "law", "body",
                        "parameter")
BODIES: tuple[str, ...] = ("mobile", "obstacle")
#: The references quoted in the built-in ``source`` column: the bibliography of Code_Aster R7.20.01
#: (its §7; numbered 5 and 6 in docs/theory.md).
REFERENCES: dict[str, str] = {
    "[bib5]": "M. Zbinden, A. Lina et al.: rod cluster control assemblies and guides, "
              "synthesis of the wear tests on the ERABLE1 and ERABLE2 simulators 1995-1997, "
              "EDF-DER HT.22/97-21A, 1998",
    "[bib6]": "F. Guérout, M. Zbinden: bibliographic study of the wear models, review of the "
              "wear coefficients for steam generator tubes, EDF-DER HT.22/93-56A, 1993",
}

# Accepted spellings of each unit, compared after _canonical_unit().
_UNIT_SPELLINGS: dict[str, tuple[str, ...]] = {
    "Pa⁻¹": ("Pa^-1", "1/Pa", "m3/J", "m3*J^-1"),
    "m³/(s·W^b)": ("m3/(s*W^b)", "m3/s/W^b", "m3*s^-1*W^-b"),
    "1": ("1", "-", ""),
    "s⁻¹": ("s^-1", "1/s"),
    "m³/s": ("m3/s", "m3*s^-1"),
    "N": ("N",),
    "m/s": ("m/s", "m*s^-1"),
}


#: Where a user's own coefficient CSV goes, for error messages.
_EXTRA_HINT = ("your own CSV (lookup(extra=...), wear_table(coefficient_files=...), case file "
               "[law] database = [...], or fretwear run --database)")


def _canonical_unit(text: str) -> str:
    out = str(text).strip().replace(" ", "").replace("³", "3").replace("m^3", "m3")
    out = out.replace("⁻¹", "^-1").replace("⁻ᵇ", "^-b").replace("·", "*").replace("−", "-")
    return out


def _unit_ok(expected: str, given: str) -> bool:
    spellings = _UNIT_SPELLINGS.get(expected, (expected,))
    return _canonical_unit(given) in {_canonical_unit(s) for s in (expected, *spellings)}


def _data_path(name: str) -> Path:
    return Path(str(resources.files("fretwear") / "data" / name))


def _validate(frame: pd.DataFrame, where: str, *, builtin: bool) -> pd.DataFrame:
    """Checked, normalised copy of a coefficient table read from ``where``."""
    missing = [c for c in REQUIRED_COLUMNS if c not in frame.columns]
    if missing:
        raise FormatError(
            f"{where}: missing column(s) {missing} (the file has {list(frame.columns)}); a "
            f"coefficient file needs the columns {list(REQUIRED_COLUMNS)} (optional: body, "
            "source), one row per coefficient, separated by ',' (or ';')")
    out = pd.DataFrame({c: frame[c].astype(str).str.strip() for c in REQUIRED_COLUMNS
                        if c != "value"})
    out["body"] = (frame["body"].astype(str).str.strip().str.lower() if "body" in frame.columns
                   else "mobile")
    line = np.arange(len(frame)) + 2   # line 1 is the header
    if "source" in frame.columns:
        out["source"] = frame["source"].astype(str).str.strip()
    else:
        out["source"] = [f"{where}:{i}" for i in line]
    for col in ("contact_type", "mobile_material", "obstacle_material", "law", "parameter"):
        empty = out[col] == ""
        if empty.any():
            i = int(np.flatnonzero(empty)[0])
            raise FormatError(f"{where}, line {line[i]}: empty {col!r}; fill it in")
    for col in ("contact_type", "mobile_material", "obstacle_material", "law"):
        out[col] = out[col].str.upper()
    values = pd.to_numeric(frame["value"].astype(str).str.strip(), errors="coerce").to_numpy(float)
    bad = ~np.isfinite(values) | (values < 0)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise FormatError(f"{where}, line {line[i]}: column 'value' must be a finite number >= 0, "
                          f"got {frame['value'].iloc[i]!r}")
    out["value"] = values
    parameters, units = [], []
    for i, row in enumerate(out.itertuples(index=False)):
        at = f"{where}, line {line[i]}"
        if row.contact_type not in CONTACT_TYPE_NAMES:
            raise FormatError(f"{at}: unknown contact_type {row.contact_type!r}; one of "
                              f"{list(CONTACT_TYPE_NAMES)}")
        if row.law not in WEAR_LAWS:
            raise FormatError(f"{at}: unknown law {row.law!r}; one of {list(WEAR_LAWS)}")
        if row.body not in BODIES:
            raise FormatError(f"{at}: body must be 'mobile' or 'obstacle', got {row.body!r}")
        law = WEAR_LAWS[row.law]
        by_keyword = {kw: p for p, kw in law.aster_keywords.items()}
        name = by_keyword.get(row.parameter, row.parameter)
        storable = tuple(p for p in law.accepted if p != "intensity")
        if name not in storable:
            raise FormatError(
                f"{at}: {row.law} has no coefficient {row.parameter!r}; accepted: "
                + ", ".join(f"{p} ({law.aster_keywords[p]})" if p in law.aster_keywords else p
                            for p in storable))
        expected = law.units[name]
        if not _unit_ok(expected, row.unit):
            raise FormatError(
                f"{at}: unit {row.unit!r} for {row.law} {name}; expected {expected} (SI; also "
                f"written {', '.join(repr(s) for s in _UNIT_SPELLINGS.get(expected, ()))}): "
                "convert the value to SI")
        parameters.append(name)
        units.append(expected)
    out["parameter"] = parameters
    out["unit"] = units
    dup = out.duplicated(list(KEY), keep=False)
    if dup.any():
        rows = [int(x) for x in line[dup.to_numpy()]]
        raise FormatError(f"{where}: lines {rows} give the same coefficient (same contact_type, "
                          "materials, law, body, parameter); keep one")
    out["origin"] = "built-in" if builtin else where
    return out[[*COLUMNS, "origin"]].reset_index(drop=True)


def read_coefficients(path: str | os.PathLike) -> pd.DataFrame:
    """Read and check one coefficient CSV (UTF-8) of the form described in the module docstring.

    Parameters
    ----------
    path : path-like
        The CSV file: UTF-8 (a byte-order mark is accepted), comma-separated, or
        semicolon-separated with a decimal comma or point in ``value`` (as spreadsheets save it
        where the decimal separator is a comma).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS` plus ``origin`` (the file), parameters by full name, values SI.

    Raises
    ------
    FormatError
        Naming the file, the line and the column: missing column, unknown contact type, law,
        parameter or body, bad value, wrong unit, duplicated coefficient.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "mine.csv"
    >>> _ = p.write_text("contact_type,mobile_material,obstacle_material,law,parameter,value,"
    ...                  "unit\\nTUBE_BAV,I690TT,A405,ARCHARD,COEF_USURE,3e-15,1/Pa\\n")
    >>> read_coefficients(p)[["parameter", "value", "unit", "body"]].values.tolist()
    [['coefficient', 3e-15, 'Pa⁻¹', 'mobile']]
    """
    path = readable_file(path, "coefficient file")
    try:
        with reading(path, "CSV coefficient", "coefficient file"), \
                open(path, encoding="utf-8-sig") as stream:   # a spreadsheet's BOM is dropped
            header = stream.readline()
        # a spreadsheet with a decimal comma saves ';'-separated files: read those too
        semicolon = ";" in header and "," not in header
        with reading(path, "CSV coefficient", "coefficient file"):
            frame = pd.read_csv(path, dtype=str, keep_default_na=False, encoding="utf-8-sig",
                                sep=";" if semicolon else ",")
    except (UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise FormatError(f"{path}: not a readable UTF-8 CSV coefficient file ({exc})") from None
    frame.columns = [str(c).strip() for c in frame.columns]
    if semicolon and "value" in frame.columns:
        frame["value"] = frame["value"].str.replace(",", ".", regex=False)
    return _validate(frame, str(path), builtin=False)


@functools.lru_cache(maxsize=1)
def _builtin() -> pd.DataFrame:
    path = _data_path("coefficients.csv")
    frame = pd.read_csv(path, dtype=str, keep_default_na=False, encoding="utf-8")
    return _validate(frame, "fretwear/data/coefficients.csv", builtin=True)


def load_database(paths: str | os.PathLike | Iterable[str | os.PathLike] | None = None, *,
                  builtin: bool = True) -> pd.DataFrame:
    """The built-in coefficient table extended and overridden by user files, in order.

    Parameters
    ----------
    paths : path-like or iterable of path-like, optional
        User CSV files; a later file overrides an earlier one and the built-in rows.
    builtin : bool, optional
        Start from the built-in table (Code_Aster R7.20.01 §3). Default True.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS` and ``origin`` ("built-in" or the file path), one row per
        coefficient.

    Examples
    --------
    >>> db = load_database()
    >>> len(db), sorted(db.law.unique())
    (120, ['ARCHARD', 'EDF_MZ', 'KWU_EPRI'])
    """
    frames = [_builtin().copy()] if builtin else []
    if paths is not None:
        if isinstance(paths, (str, os.PathLike)):
            paths = [paths]
        frames += [read_coefficients(p) for p in paths]
    if not frames:
        return pd.DataFrame(columns=[*COLUMNS, "origin"])
    table = pd.concat(frames, ignore_index=True)
    return table.drop_duplicates(list(KEY), keep="last").reset_index(drop=True)


@functools.lru_cache(maxsize=1)
def _materials() -> pd.DataFrame:
    return pd.read_csv(_data_path("materials.csv"), dtype=str, keep_default_na=False,
                       encoding="utf-8")


def materials() -> pd.DataFrame:
    """Material codes with their names and AFNOR designations (Code_Aster R7.20.01 §3).

    Examples
    --------
    >>> m = materials().set_index("code")
    >>> m.loc["I690TT", "name"]
    'Inconel 690, thermally treated'
    """
    return _materials().copy()


@dataclass(frozen=True)
class DatabaseCoefficients:
    """Coefficients of one (contact type, material pair, law) box of the database.

    Attributes
    ----------
    contact_type, mobile_material, obstacle_material, law : str
        The key.
    mobile : mapping
        The mobile's coefficients by full parameter name (SI), ready for ``WearLaw.volume``.
    obstacle : mapping or None
        The obstacle's where the table has them (its box is not empty), else None. Whether the
        obstacle wears is the caller's choice (theory §4): having values does not imply using them.
    units : mapping
        Unit of each parameter.
    sources : mapping
        ``"mobile.<parameter>"`` / ``"obstacle.<parameter>"`` -> provenance ("source (origin)").
    """

    contact_type: str
    mobile_material: str
    obstacle_material: str
    law: str
    mobile: Mapping[str, float]
    obstacle: Mapping[str, float] | None
    units: Mapping[str, str] = field(default_factory=dict)
    sources: Mapping[str, str] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready copy."""
        return {"contact_type": self.contact_type, "mobile_material": self.mobile_material,
                "obstacle_material": self.obstacle_material, "law": self.law,
                "mobile": dict(self.mobile),
                "obstacle": None if self.obstacle is None else dict(self.obstacle),
                "units": dict(self.units), "sources": dict(self.sources)}


def _pairs_text(rows: pd.DataFrame) -> str:
    items = []
    for (m1, m2), grp in rows.groupby(["mobile_material", "obstacle_material"], sort=False):
        bodies = set(grp.body)
        tag = ("mobile+obstacle" if bodies == {"mobile", "obstacle"}
               else f"{'/'.join(sorted(bodies))} only")
        items.append(f"{m1}/{m2} ({tag})")
    return ", ".join(items) if items else "none"


def lookup(contact_type: str, mobile_material: str, obstacle_material: str, law: str, *,
           obstacle: bool = False, extra=None, database: pd.DataFrame | None = None
           ) -> DatabaseCoefficients:
    """Wear coefficients of a material pair for a contact type and a law.

    Parameters
    ----------
    contact_type : str
        Code_Aster contact type (``"TUBE_BAV"``, ``"GRAPPE_ALESAGE"``, ...); case-insensitive.
    mobile_material, obstacle_material : str
        Material codes (``"I600"``, ``"A405"``, ...; see :func:`materials`); case-insensitive.
    law : str
        ``"ARCHARD"``, ``"KWU_EPRI"`` or ``"EDF_MZ"``.
    obstacle : bool, optional
        Obstacle wear is asked for: the obstacle's coefficients must exist (else DatabaseError).
        Without it, they are returned where the table has them and None otherwise.
    extra : path-like or iterable of path-like, optional
        User coefficient CSV file(s) extending/overriding the built-in table.
    database : pandas.DataFrame, optional
        A table from :func:`load_database` to search instead (``extra`` is then added to it).

    Returns
    -------
    DatabaseCoefficients
        ``.mobile`` and ``.obstacle`` (None for an empty box) coefficient dicts by full parameter
        name, in SI units, with ``.units`` and ``.sources``.

    Raises
    ------
    DatabaseError
        Unknown contact type, law without rows for that contact type, unknown pair, or obstacle
        values asked for where the box of the reference tables is empty; the message lists what
        exists.

    Notes
    -----
    The values are the coefficient tables of Code_Aster R7.20.01 §3 (theory §5), with their
    references in the ``sources`` (``[bib5]``, ``[bib6]``: Zbinden et al. 1998, Guérout & Zbinden
    1993, the bibliography numbers of R7.20.01; full entries in :data:`REFERENCES`). For EDF_MZ,
    A is in m³/(s·W^b) (= Pa⁻¹ when b = 1), S in m³/s, n in s⁻¹.

    Examples
    --------
    >>> c = lookup("GRAPPE_ALESAGE", "A304L", "A304L", "ARCHARD", obstacle=True)
    >>> c.mobile["coefficient"], c.obstacle["coefficient"]
    (2.6e-15, 3.7e-15)
    >>> lookup("TUBE_BAV", "I600", "A405", "ARCHARD").mobile
    {'coefficient': 6.2e-14}
    """
    if database is None:  # the same question of the same files: answered once
        key = _lookup_key(contact_type, mobile_material, obstacle_material, law, obstacle, extra)
        if key is not None:
            found = _cached_lookup(*key)
            return dataclasses.replace(
                found, mobile=dict(found.mobile),
                obstacle=None if found.obstacle is None else dict(found.obstacle),
                units=dict(found.units), sources=dict(found.sources))
    table = load_database(extra) if database is None else (
        database if extra is None else pd.concat([database, load_database(extra, builtin=False)],
                                                 ignore_index=True)
        .drop_duplicates(list(KEY), keep="last"))
    ct, m1, m2, lw = (str(x).strip().upper() for x in (contact_type, mobile_material,
                                                       obstacle_material, law))
    if lw not in WEAR_LAWS:
        raise DatabaseError(f"unknown law {law!r}; one of {list(WEAR_LAWS)}")
    of_type = table[table.contact_type == ct]
    if of_type.empty:
        if ct not in CONTACT_TYPE_NAMES:
            raise DatabaseError(f"unknown contact type {contact_type!r}; one of "
                                f"{list(CONTACT_TYPE_NAMES)}")
        known = [c for c in CONTACT_TYPE_NAMES if c in set(table.contact_type)]
        raise DatabaseError(f"no coefficients for contact type {ct} in the database; it has "
                            f"{known}. Give the coefficients explicitly, or add rows with "
                            f"{_EXTRA_HINT}")
    of_law = of_type[of_type.law == lw]
    if of_law.empty:
        raise DatabaseError(
            f"no {lw} coefficients for {ct} in the database; {ct} has: "
            + "; ".join(f"{g}: {_pairs_text(r)}" for g, r in of_type.groupby("law", sort=False))
            + f". Give the {lw} coefficients explicitly, or add rows with {_EXTRA_HINT}")
    box = of_law[(of_law.mobile_material == m1) & (of_law.obstacle_material == m2)]
    mob = box[box.body == "mobile"]
    if mob.empty:
        what = "no coefficients" if box.empty else "no mobile coefficient (empty box)"
        known_codes = set(materials().code)
        in_table = set(table.mobile_material) | set(table.obstacle_material)
        unknown = [x for x in (m1, m2) if x not in known_codes and x not in in_table]
        hint = f" (unknown material code(s) {unknown}; see `fretwear materials`)" if unknown else ""
        swapped = of_law[(of_law.mobile_material == m2) & (of_law.obstacle_material == m1)]
        if len(swapped):
            hint += (f" (the table has mobile {m2} on obstacle {m1}: are the materials given in "
                     "the order mobile, obstacle?)")
        pair = of_type[(of_type.mobile_material == m1) & (of_type.obstacle_material == m2)]
        other_laws = [x for x in dict.fromkeys(pair.law) if x != lw]
        if other_laws:
            hint += f" ({m1}/{m2} has {' and '.join(other_laws)} coefficients for {ct})"
        raise DatabaseError(
            f"{what} for {ct} / {lw}, mobile {m1} on obstacle {m2}{hint}; {ct}/{lw} has "
            f"(mobile/obstacle): {_pairs_text(of_law)}. Give the coefficients explicitly, or add "
            f"rows with {_EXTRA_HINT}")
    obs = box[box.body == "obstacle"]
    if obstacle and obs.empty:
        with_obstacle = of_law[of_law.body == "obstacle"]
        why = (" (an empty box of the coefficient tables of Code_Aster's POST_USURE reference "
               "manual, R7.20.01 §3: its source, Guérout & Zbinden 1993, gives none for the "
               "antagonists of the tubes)" if ct.startswith("TUBE") else "")
        raise DatabaseError(
            f"no obstacle coefficient for {ct} / {lw}, {m1} on {m2}{why}; pairs of {ct}/{lw} with "
            f"obstacle values: {_pairs_text(with_obstacle)}. Leave the obstacle unworn (no "
            "USURE_OBST / obstacle_wear), or give both bodies' coefficients instead of the "
            "materials (POST_USURE: MOBILE=_F(...) and OBSTACLE=_F(...) without MATER_USURE; case "
            "file: [law] coefficients and obstacle_coefficients without materials)")

    def as_dict(rows: pd.DataFrame) -> dict[str, float]:
        return {r.parameter: float(r.value) for r in rows.itertuples()}

    used = pd.concat([mob, obs])
    return DatabaseCoefficients(
        contact_type=ct, mobile_material=m1, obstacle_material=m2, law=lw,
        mobile=as_dict(mob), obstacle=as_dict(obs) if len(obs) else None,
        units={r.parameter: r.unit for r in used.itertuples()},
        sources={f"{r.body}.{r.parameter}": f"{r.source} ({r.origin})" for r in used.itertuples()})


def _lookup_key(contact_type, mobile_material, obstacle_material, law, obstacle, extra):
    """The cache key of a lookup: its arguments and each extra file's (path, mtime, size); None
    when a file cannot be stat'ed (the lookup then reports it)."""
    if extra is None:
        files = ()
    else:
        items = [extra] if isinstance(extra, str | os.PathLike) else list(extra)
        try:
            files = tuple((os.fspath(f), os.stat(f).st_mtime_ns, os.stat(f).st_size)
                          for f in items)
        except (OSError, TypeError):
            return None
    return (str(contact_type), str(mobile_material), str(obstacle_material), str(law),
            bool(obstacle), files)


@functools.lru_cache(maxsize=256)
def _cached_lookup(contact_type, mobile_material, obstacle_material, law, obstacle, files):
    extra = [f[0] for f in files] or None
    return lookup(contact_type, mobile_material, obstacle_material, law, obstacle=obstacle,
                  extra=extra, database=load_database(extra))


def summary(database: pd.DataFrame | None = None, *, contact_type: str | None = None,
            law: str | None = None) -> pd.DataFrame:
    """One row per (contact type, material pair, law) box, mobile and obstacle values as text.

    Parameters
    ----------
    database : pandas.DataFrame, optional
        A table from :func:`load_database`; default the built-in one.
    contact_type, law : str, optional
        Keep only this contact type / law (any case).

    Returns
    -------
    pandas.DataFrame
        Columns ``contact_type, mobile_material, obstacle_material, law``, ``mobile`` and
        ``obstacle`` (e.g. ``"K = 2.6e-15 Pa⁻¹"``, SI units; ``""`` for an empty box), ``source``
        and ``origin``. Empty when nothing matches.

    Raises
    ------
    DatabaseError
        An unknown contact type or law (listing the known ones).

    Examples
    --------
    >>> s = summary(contact_type="TUBE_TUBE")
    >>> s[["mobile_material", "obstacle_material", "mobile", "obstacle"]].values.tolist()
    [['I600', 'I600', 'K = 1.8e-13 Pa⁻¹', ''], ['I690', 'I690', 'K = 1e-12 Pa⁻¹', '']]
    """
    table = load_database() if database is None else database
    if contact_type is not None:
        ct = contact_type.strip().upper()
        if ct not in CONTACT_TYPE_NAMES:
            raise DatabaseError(f"unknown contact type {contact_type!r}; one of "
                                f"{list(CONTACT_TYPE_NAMES)}")
        table = table[table.contact_type == ct]
    if law is not None:
        lw = law.strip().upper()
        if lw not in WEAR_LAWS:
            raise DatabaseError(f"unknown law {law!r}; one of {list(WEAR_LAWS)}")
        table = table[table.law == lw]
    symbols = {p: s for law_ in WEAR_LAWS.values() for p, s in law_.symbols.items()}
    order = {p: i for law_ in WEAR_LAWS.values() for i, p in enumerate(law_.accepted)}
    rows = []
    group_cols = ["contact_type", "mobile_material", "obstacle_material", "law"]
    for key, grp in table.groupby(group_cols, sort=False):
        text = {}
        for body in BODIES:
            part = grp[grp.body == body].sort_values("parameter", key=lambda s: s.map(order))
            text[body] = "  ".join(
                f"{symbols.get(r.parameter, r.parameter)} = {r.value:.4g}"
                + ("" if r.unit == "1" else f" {r.unit}") for r in part.itertuples())
        rows.append({**dict(zip(group_cols, key, strict=True)), **text,
                     "source": "; ".join(dict.fromkeys(grp.source)),
                     "origin": "; ".join(dict.fromkeys(grp.origin))})
    return pd.DataFrame(rows, columns=[*group_cols, "mobile", "obstacle", "source", "origin"])
