"""What a bundle manifest's columns mean: its own columns, and the case keys they override.

The names a manifest accepts (:data:`BUNDLE_COLUMNS`, ``wall_thickness_m``, any case-file key
bare when unique or as ``section.key``, entries of inline tables as ``section.key.entry``), the
case key each column overrides (:func:`column_key`), and the messages of unknown or ambiguous
columns with the closest valid name (:func:`column_meanings`). Used by
:mod:`fretwear.bundle.manifest` for tables, TOML manifests and Datasets alike.
"""

from __future__ import annotations

from typing import Any

from fretwear.errors import KeywordError
from fretwear.keys import keyword_hint
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
#: Per-contact wall thickness [m], a manifest column while the case files have no such key.
WALL_COLUMN = "wall_thickness_m"
#: Case keys the manifest gives through its own columns (history <- file, contact <- name).
_SUPPLIED = {("history", "file"): "history", ("history", "name"): "contact",
             ("history", "node"): "node"}


def _case_keys() -> dict[str, dict[str, tuple[Any, str]]]:
    return KEYS


def _wall_is_case_key() -> bool:
    return any(WALL_COLUMN in keys for keys in _case_keys().values())


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
        The column itself for :data:`BUNDLE_COLUMNS` (and ``wall_thickness_m`` while it is not
        a case key); else ``(section, key)`` or ``(section, key, entry)`` (an entry of an inline
        table such as ``law.mobile.COEF_USURE``), ``("", "title")`` for the top-level title.

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
    if column in BUNDLE_COLUMNS or (column == WALL_COLUMN and not _wall_is_case_key()):
        return column
    parts = column.split(".")
    if len(parts) > 1 and parts[0] in keys and parts[0]:
        section, key = parts[0], parts[1]
        if key in keys[section] and (section, key) not in _SUPPLIED:
            if len(parts) == 2:
                return (section, key)
            if len(parts) >= 3 and keys[section][key][0] is dict:  # the entry may hold dots
                return (section, key, ".".join(parts[2:]))
    elif len(parts) == 1:
        found = [s for s, ks in keys.items() if column in ks and (s, column) not in _SUPPLIED]
        if len(found) == 1:
            return (found[0], column)
        if len(found) > 1:
            return found
    return None


def identity_columns() -> list[str]:
    """The manifest's documented columns: :data:`BUNDLE_COLUMNS` and ``wall_thickness_m`` (a
    case key's bare name, or the manifest's own column while the case files have none)."""
    return [*BUNDLE_COLUMNS, WALL_COLUMN]


def _unknown_message(names: list[str], source: str, noun: str) -> str:
    """The message of unknown manifest columns (or TOML keys), each with its closest name."""
    valid = valid_columns()
    listed = ", ".join(f"{n!r}{keyword_hint(n, valid)}" for n in names)
    where = "a manifest has the columns" if noun == "column" else \
        "a [[contacts]] table of a TOML manifest has the keys"
    hint = ""
    if any(sep in n for n in names for sep in (";", "\t")):
        hint = (" (the names hold ';' or tabs: the file looks ;-separated but was not read so; "
                "save it with one separator throughout)")
    return (f"{source}: unknown {noun}{'s' if len(names) > 1 else ''} {listed}{hint}; "
            f"{where} {', '.join(identity_columns())}, and any case key as an override (bare "
            "when unique, else section.key; entries of inline tables as section.key.entry, "
            "e.g. law.mobile.COEF_USURE): fretwear bundle --help lists them")


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
    if not _wall_is_case_key():
        names.append(WALL_COLUMN)
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
