"""What a bundle manifest's columns mean: its own columns, and the case keys they override.

The names a manifest accepts (:data:`BUNDLE_COLUMNS`, ``wall_thickness_m``, any case-file key
bare when unique or as ``section.key``, entries of inline tables as ``section.key.entry``), the
case key each column overrides (:func:`column_key`), and the messages of unknown or ambiguous
columns with the closest valid name (:func:`column_meanings`). Used by
:mod:`fretwear.bundle.manifest` for tables, TOML manifests and Datasets alike.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, KeywordError
from fretwear.io import FORMATS
from fretwear.io.channels import CHANNELS, QUANTITIES, unknown_units_key
from fretwear.keys import keyword_hint
from fretwear.laws import WEAR_LAWS
from fretwear.workflows.case_files import KEYS

#: Columns of a manifest that are not case keys -> description (``fretwear bundle --help``).
BUNDLE_COLUMNS: dict[str, str] = {
    "contact": "unique id of the contact (required); also the history's name in messages",
    "history": "contact history file, relative to the manifest (required unless the row gives "
               "power.value_W)",
    "node": "shock point (NOEUD) to read from a Code_Aster table holding several, or the group "
            "of an HDF5 file",
    "tube_row": "row of the tube in the tube sheet (identity, used by the tube-sheet map)",
    "tube_column": "column of the tube in the tube sheet (identity)",
    "support": "support or anti-vibration bar of the contact (identity)",
}
#: Identity columns carried in front of every result row, in this order.
IDENTITY: tuple[str, ...] = ("contact", "tube_row", "tube_column", "support", "node", "history")
#: The per-contact wall thickness [m]: the case key [geometry] wall_thickness_m, by its bare name.
WALL_COLUMN = "wall_thickness_m"
#: Sections a row may give whole, as a table: ``{}`` drops the base case's section for the row
#: (a law other than Archard refuses sectors), a CSV cell ``{ count = 8 }`` replaces it.
WHOLE_SECTIONS: tuple[str, ...] = ("sectors",)
#: Case keys the manifest gives through its own columns (history <- file, contact <- name).
_SUPPLIED = {("history", "file"): "history", ("history", "name"): "contact",
             ("history", "node"): "node"}


def _case_keys() -> dict[str, dict[str, tuple[Any, str]]]:
    return KEYS


def entry_names(section: str, key: str) -> tuple[str, ...] | None:
    """The entries a case key's inline table accepts, when they are a known set; None for a
    table of free names (``history.columns``: the history file's own column names).

    ``law.mobile`` and ``law.obstacle``: the coefficients of every wear law, by name or
    Code_Aster keyword (a row may name its law); ``history.units``: the quantities and the
    channels (their aliases are accepted too, :func:`entry_known`); ``history.options``: the
    options of every format's reader.

    Examples
    --------
    >>> entry_names("law", "mobile")[:3]
    ('coefficient', 'COEF_USURE', 'reference_coefficient')
    >>> entry_names("history", "columns") is None
    True
    """
    if section == "law" and key in ("mobile", "obstacle"):
        names: list[str] = []
        for law in WEAR_LAWS.values():
            for name in law.accepted:
                names += [name, law.aster_keywords.get(name, name)]
        return tuple(dict.fromkeys(names))
    if (section, key) == ("history", "units"):
        return tuple(dict.fromkeys((*QUANTITIES, *CHANNELS)))
    if (section, key) == ("history", "options"):
        return tuple(dict.fromkeys(o for f in FORMATS.values() for o in f.read_options))
    return None


def entry_known(section: str, key: str, entry: str) -> bool:
    """Whether ``entry`` is an entry the table ``section.key`` accepts (any entry of a table of
    free names); a ``history.units`` key as the case layer takes it (an alias of a channel,
    a quantity in any case)."""
    names = entry_names(section, key)
    if names is None or entry in names:
        return True
    return (section, key) == ("history", "units") and unknown_units_key(entry, "") is None


def column_key(column: str, source: str, *, noun: str = "column") -> tuple[str, ...] | str:
    """What a manifest column means: a bundle column name, or the case key it overrides.

    Parameters
    ----------
    column : str
        The column's name (a TOML manifest's key, dotted).
    source : str
        The manifest, for messages.
    noun : str
        What the messages call it: ``"column"`` (a table, a Dataset's variable) or ``"key"``
        (a TOML manifest).

    Returns
    -------
    str or tuple
        The column itself for :data:`BUNDLE_COLUMNS`; else ``(section, key)`` or
        ``(section, key, entry)`` (an entry of an inline table such as
        ``law.mobile.COEF_USURE``), ``("", "title")`` for the top-level title,
        ``("sectors",)`` for a section given whole (:data:`WHOLE_SECTIONS`).

    Raises
    ------
    KeywordError
        Unknown or ambiguous column, with the closest valid name.

    Examples
    --------
    >>> column_key("mobile_radius_m", "manifest")
    ('geometry', 'mobile_radius_m')
    >>> column_key("law.mobile.COEF_USURE", "manifest")
    ('law', 'mobile', 'COEF_USURE')
    >>> try:
    ...     column_key("mobile_radus_m", "manifest")
    ... except KeywordError as exc:
    ...     print(str(exc).split(";")[0])
    manifest: unknown column 'mobile_radus_m' (did you mean 'mobile_radius_m'?)
    """
    key = _meaning(column)
    if isinstance(key, list):
        raise KeywordError(f"{source}: {noun} {column!r} is ambiguous: write it "
                           f"{' or '.join(f'{s}.{column}' for s in key)}")
    if key is None:
        raise KeywordError(_unknown_message([column], source, noun))
    return key


def _meaning(column: str) -> tuple[str, ...] | str | list[str] | None:
    """:func:`column_key`'s answer, the sections of an ambiguous bare name, or None."""
    keys = _case_keys()
    if column in BUNDLE_COLUMNS:
        return column
    if column in WHOLE_SECTIONS:
        return (column,)
    parts = column.split(".")
    if len(parts) > 1 and parts[0] in keys and parts[0]:
        section, key = parts[0], parts[1]
        if key in keys[section] and (section, key) not in _SUPPLIED:
            if len(parts) == 2:
                return (section, key)
            if len(parts) >= 3 and keys[section][key][0] is dict:  # the entry may hold dots
                entry = ".".join(parts[2:])
                return (section, key, entry) if entry_known(section, key, entry) else None
    elif len(parts) == 1:
        found = [s for s, ks in keys.items() if column in ks and (s, column) not in _SUPPLIED]
        if len(found) == 1:
            return (found[0], column)
        if len(found) > 1:
            return found
    return None


def identity_columns() -> list[str]:
    """The manifest's documented columns: :data:`BUNDLE_COLUMNS` and ``wall_thickness_m`` (the
    case key ``[geometry] wall_thickness_m``'s bare name, an override like any case key)."""
    return [*BUNDLE_COLUMNS, WALL_COLUMN]


def _unknown_message(names: list[str], source: str, noun: str) -> str:
    """The message of unknown manifest columns (or TOML keys), each with its closest name."""
    valid = valid_columns()
    listed = ", ".join(f"{n!r}{_closest(n, valid)}" for n in names)
    where = "a manifest has the columns" if noun == "column" else \
        "a [[contacts]] table of a TOML manifest has the keys"
    hint = ""
    if any(sep in n for n in names for sep in (";", "\t")):
        hint = (" (the names hold ';' or tabs: the file looks ;-separated but was not read so; "
                "save it with one separator throughout)")
    tables = dict.fromkeys(t for t in map(_table_of, names) if t is not None)
    entries = "".join(f"; the entries of {'.'.join(t)} are {_entries_text(*t)}" for t in tables)
    return (f"{source}: unknown {noun}{'s' if len(names) > 1 else ''} {listed}{hint}; "
            f"{where} {', '.join(identity_columns())}, and any case key as an override (bare "
            "when unique, else section.key; entries of inline tables as section.key.entry, "
            "e.g. law.mobile.COEF_USURE): fretwear bundle --help lists them" + entries)


def _table_of(name: str) -> tuple[str, str] | None:
    """``(section, key)`` of a dotted name ``section.key.entry`` under a table of known
    entries (:func:`entry_names`), else None."""
    parts = name.split(".")
    if len(parts) < 3 or parts[0] not in _case_keys() or not parts[0]:
        return None
    section, key = parts[0], parts[1]
    if _case_keys()[section].get(key, (None,))[0] is not dict or \
            entry_names(section, key) is None:
        return None
    return section, key


def _closest(name: str, valid: list[str]) -> str:
    """`` (did you mean 'x'?)`` for an unknown column: the closest entry of its table for
    ``section.key.entry`` (``law.mobile.COEF_USURE``), else the closest valid column."""
    table = _table_of(name)
    if table is None:
        return keyword_hint(name, valid)
    prefix = ".".join(table) + "."
    entry, names = name[len(prefix):], entry_names(*table)
    close = difflib.get_close_matches(entry, names, n=1) or \
        [n for n in names if n.lower() == entry.lower()][:1]
    return f" (did you mean {prefix + close[0]!r}?)" if close else ""


def _entries_text(section: str, key: str) -> str:
    """The entries of a table of known entries, for messages (a law's coefficients by law)."""
    if section == "law":
        return "the coefficients of the row's law, by name or Code_Aster keyword: " + "; ".join(
            f"{law.name}: " + ", ".join(f"{p} ({law.aster_keywords[p]})"
                                       if p in law.aster_keywords else p
                                       for p in law.accepted)
            for law in WEAR_LAWS.values())
    alias = " (or a channel's alias, e.g. FN)" if (section, key) == ("history", "units") else ""
    return ", ".join(entry_names(section, key)) + alias


def column_meanings(columns: list[str], source: str, *, noun: str = "column"
                    ) -> dict[str, tuple[str, ...] | str]:
    """:func:`column_key` of every column, the unknown ones reported together.

    Raises
    ------
    KeywordError
        Every unknown column at once (each with its closest valid name), or an ambiguous one.
    """
    meaning = {c: _meaning(c) for c in columns}
    unknown = [c for c, m in meaning.items() if m is None]
    if unknown:
        raise KeywordError(_unknown_message(unknown, source, noun))
    for c in columns:
        column_key(c, source, noun=noun)  # an ambiguous name raises
    return meaning  # type: ignore[return-value]


def valid_columns() -> list[str]:
    """Every column name a manifest accepts (bundle columns, bare and dotted case keys)."""
    keys = _case_keys()
    names = list(BUNDLE_COLUMNS)
    names += WHOLE_SECTIONS
    counts: dict[str, int] = {}
    for section, ks in keys.items():
        for k in ks:
            if (section, k) not in _SUPPLIED:
                counts[k] = counts.get(k, 0) + 1
    for section, ks in keys.items():
        for k in ks:
            if (section, k) in _SUPPLIED:
                continue
            if counts[k] == 1:
                names.append(k)
            if section:
                names.append(f"{section}.{k}")
    return list(dict.fromkeys(names))


def empty_cell(value: Any) -> bool:
    """Whether a manifest cell is empty: None, NaN, blank text, ``pd.NA`` or ``pd.NaT``."""
    if value is None:
        return True
    if isinstance(value, float | np.floating):
        return math.isnan(value)
    if isinstance(value, str):
        return value.strip() == ""
    return value is pd.NA or value is pd.NaT


def check_unique(ids: list[str], source: str) -> None:
    """Contact ids are unique, and no two differ only by surrounding whitespace (``'A'`` and
    ``'A '`` look alike in the terminal and in summary.csv); ids are never trimmed: a single
    id with surrounding whitespace is kept as written.

    Raises
    ------
    InputError
        An id given twice, or two ids that differ only by surrounding whitespace (both named).
    """
    seen: set[str] = set()
    for i, c in enumerate(ids):
        if c in seen:
            raise InputError(f"{source}: contact {c!r} appears twice (row {i + 1}); contact ids "
                             "must be unique")
        seen.add(c)
    trimmed: dict[str, int] = {}
    for i, c in enumerate(ids):
        j = trimmed.setdefault(c.strip(), i)
        if j != i:
            raise InputError(f"{source}: contact ids {ids[j]!r} (row {j + 1}) and {c!r} (row "
                             f"{i + 1}) differ only by surrounding whitespace: they look the "
                             "same in the terminal and in summary.csv; make them distinct or "
                             "trim them")


def check_wall_column(columns: Mapping[str, Any], meaning: Mapping[str, Any], source: str,
                      contacts=None, noun: str = "column") -> None:
    """One error up front for a wall column no contact can use (instead of one per contact
    when the bundle runs): every wall [m] given is a number not > 0, or above
    :data:`~fretwear.io.geometry_units.WALL_BOUND` (0.1 m: a value in mm). With one good wall
    in the column the bad rows are left to fail their own contacts.

    ``columns`` maps each column (or variable) name to its values, ``meaning`` to its key
    (:func:`column_meanings`); ``contacts`` names the rows in the message.

    Examples
    --------
    >>> check_wall_column({"wall_thickness_m": [1.09, 1.09]},
    ...                   {"wall_thickness_m": ("geometry", "wall_thickness_m")}, "m.csv")
    Traceback (most recent call last):
    ...
    fretwear.errors.InputError: m.csv: column wall_thickness_m = 1.09 [m] on 2 of 2 rows (first:
    row 1) is implausible for a tube's wall (above 0.1 m): a value in mm? Give metres:
    wall_thickness_m = 0.00109 (every length of a manifest is in metres)
    """
    from fretwear.io.geometry_units import WALL_BOUND

    for name, key in meaning.items():
        if key != ("geometry", "wall_thickness_m"):
            continue
        values = np.array([float(v) if isinstance(v, int | float | np.number) and not isinstance(
            v, bool | np.bool_) and abs(v) <= 1e308 else math.nan for v in columns[name]])
        # NaN: a text, a list, a date, a bool: the contact's own check says what is wrong
        given = np.isfinite(values)
        bad = given & ((values <= 0) | (values > WALL_BOUND))
        if not bad.any() or bad.sum() < given.sum():
            continue  # a good wall somewhere: the bad rows fail their contacts alone
        i = int(np.flatnonzero(bad)[0])
        first = f"contact {contacts[i]!r}" if contacts is not None \
            and not empty_cell(contacts[i]) else f"row {i + 1}"
        x = float(values[i])
        where = (f"{source}: {noun} {name} = {x:g} [m] on {int(bad.sum())} of {len(values)} "
                 f"rows (first: {first})")
        if x <= 0:
            raise InputError(f"{where}: a wall is > 0 [m]; give each tube's wall in metres "
                             "(1.09 mm is 0.00109) or leave the cell empty for the case's")
        raise InputError(f"{where} is implausible for a tube's wall (above {WALL_BOUND:g} m): "
                         f"a value in mm? Give metres: {name} = {x * 1e-3:g} (every length "
                         "of a manifest is in metres)")
