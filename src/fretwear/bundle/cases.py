"""One contact's wear case: the base case with the manifest row's overrides, and its task.

The base case is a TOML case file (or the same content as a dict) read by the case-file layer
(:mod:`fretwear.workflows.case_files`); a manifest row overrides any of its keys. The merged case
is validated there and becomes a :class:`fretwear.table.WearCase` (validated once, on the
client: the database coefficients and a restart table are resolved into it), shipped to a worker
as ``WearCase.to_dict()`` inside a :class:`ContactTask` (picklable, ``to_dict``/``from_dict``
JSON-ready); the worker rebuilds it with ``WearCase.from_dict`` and calls
:func:`fretwear.table.wear_table_from_case`. :attr:`ContactTask.key` hashes everything the result
depends on (the wear case, the history file's size and modification time, the reader options,
the chunk size, the fretwear version), so a restarted run skips the contacts whose inputs did
not change.
"""

from __future__ import annotations

import copy
import functools
import hashlib
import json
import math
import os
import tomllib
import warnings
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._version import __version__
from fretwear.bundle.datasets import path_stamp
from fretwear.bundle.manifest import ContactRow, HistoryRef
from fretwear.errors import FretwearError, InputError, KeywordError
from fretwear.io.channels import channel_of, unknown_units_key
from fretwear.laws import get_law
from fretwear.table import WearCase
from fretwear.table.coefficients import laws_with, sector_parameter
from fretwear.workflows.case_files import KEYS, case_arguments, history_options, validate_case


def _coerce(kind: Any, value: Any, where: str) -> Any:
    """A manifest cell -> the type the case key expects (TOML text for lists and tables)."""
    kinds = kind if isinstance(kind, tuple) else (kind,)
    if isinstance(value, str) and (list in kinds or dict in kinds):
        text = value.strip()
        if text[:1] in "[{":
            try:
                return tomllib.loads(f"v = {text}")["v"]
            except tomllib.TOMLDecodeError as exc:
                raise KeywordError(f"{where} = {value!r}: not a TOML array or inline table "
                                   f"({exc}); write e.g. [1, 2, 5] or {{ COEF_USURE = 1e-14 }}"
                                   ) from None
        if str in kinds:
            return value
        if list in kinds:
            return [value]
    if bool in kinds and not isinstance(value, bool):
        text = str(value).strip().lower()
        if text in ("true", "1", "1.0", "yes"):
            return True
        if text in ("false", "0", "0.0", "no"):
            return False
        raise KeywordError(f"{where} = {value!r}: give true or false")
    if int in kinds and float not in kinds and isinstance(value, float) and value.is_integer():
        return int(value)
    if (int in kinds or float in kinds) and isinstance(value, str):
        try:
            number = float(value)
        except ValueError:
            raise KeywordError(f"{where} = {value!r}: not a number{_comma_hint(value)}"
                               ) from None
        return int(number) if float not in kinds and number.is_integer() else number
    if str in kinds and isinstance(value, int | float) and not isinstance(value, bool):
        return str(value)
    if list in kinds and not isinstance(value, list | tuple):
        return [value]
    return value


def _comma_hint(text: str) -> str:
    """The hint of a cell that is a number with a decimal comma (``"0,00109"``), else ""."""
    if "," not in text:
        return ""
    point = text.strip().replace(",", ".")
    try:
        float(point)
    except ValueError:
        return " (a decimal comma? a number's decimal mark is a point here)"
    return (f" (a decimal comma? write {point}: a ;- or tab-separated manifest's decimal "
            "commas are read where its numbers do not mix them with points)")


#: ``[law]`` keys of the two sources of a case's coefficients: given (the bodies' tables) or
#: the database (a pair of materials, and what reads it)
COEFFICIENT_KEYS = ("mobile", "obstacle")
DATABASE_KEYS = ("materials", "obstacle_wear", "database")


def _empty(value: Any) -> bool:
    return isinstance(value, list | tuple | Mapping) and not value


def _coefficient_source(law: dict[str, Any], given: Mapping[str, Any], where: str) -> None:
    """Make the row's coefficient source replace the base case's, in the base's ``[law]``.

    ``given``: the row's ``[law]`` overrides, ``{key: value}`` (an entry of ``law.mobile`` as
    ``mobile``). A row giving coefficients (``law.mobile``, ``law.obstacle``, or an entry of
    them) and no ``law.materials`` drops the base's ``materials``, ``obstacle_wear`` and
    ``database``; a row giving ``law.materials`` and no coefficients drops the base's
    ``mobile`` and ``obstacle``. An empty list or table (``law.materials = []``) gives nothing.
    What the base took from the database and the row does not replace is an error rather than
    a silent change: its ``law.mobile`` when the row gives only ``law.obstacle``, the
    obstacle's coefficient (``obstacle_wear``) unless the row gives ``law.obstacle`` or
    ``law.obstacle_wear``; and the base's own ``law.obstacle`` (a wearing obstacle) under the
    row's materials unless the row says ``law.obstacle_wear``. A row's ``law.obstacle_wear =
    false`` drops the base's ``law.obstacle`` (the obstacle does not wear); with the row's own
    ``law.obstacle`` it is an error.

    Raises
    ------
    KeywordError
        The row replaces the base's source but leaves one body's coefficient unsaid, or says
        both that the obstacle does not wear and how it wears.
    """
    coefficients = [k for k in COEFFICIENT_KEYS if k in given and not _empty(given[k])]
    materials = "materials" in given and not _empty(given["materials"])
    if given.get("obstacle_wear") is False:  # the obstacle does not wear, for this contact
        if "obstacle" in coefficients:
            raise KeywordError(f"{where}: law.obstacle_wear = false (the obstacle does not "
                               "wear) and law.obstacle (its coefficients) contradict each "
                               "other: keep one")
        law.pop("obstacle", None)
    if coefficients and not materials and "materials" in law:
        if "mobile" not in coefficients:
            raise KeywordError(f"{where}: law.obstacle replaces the base case's law.materials "
                               "for this contact, which gave the mobile's coefficient: give "
                               "law.mobile too (a case takes its coefficients either from "
                               "law.mobile and law.obstacle or from the database's materials)")
        if law.get("obstacle_wear") and "obstacle" not in coefficients \
                and "obstacle_wear" not in given:
            raise KeywordError(f"{where}: law.mobile replaces the base case's law.materials "
                               "for this contact, which also gave the obstacle's coefficient "
                               "(obstacle_wear = true): give law.obstacle too, or "
                               "law.obstacle_wear = false (the obstacle does not wear)")
        for key in DATABASE_KEYS:
            law.pop(key, None)
    if materials and not coefficients and any(k in law for k in COEFFICIENT_KEYS):
        if "obstacle" in law and "obstacle_wear" not in given:
            raise KeywordError(f"{where}: law.materials replaces the base case's coefficients "
                               "for this contact, and the base case's law.obstacle wears the "
                               "obstacle: say law.obstacle_wear = true (the database's "
                               "obstacle coefficient) or false (the obstacle does not wear)")
        for key in COEFFICIENT_KEYS:
            law.pop(key, None)


def _section_table(value: Any, where: str) -> dict[str, Any]:
    """A section given whole (a ``sectors`` cell): a table, in TOML syntax in a CSV cell."""
    if isinstance(value, str) and value.strip()[:1] == "{":
        value = _coerce(dict, value, where)
    if not isinstance(value, Mapping):
        raise KeywordError(f"{where} = {value!r}: give a table: {{}} drops the base case's "
                           "section for this contact, { count = 8 } replaces it")
    return dict(value)


def merge_case(base: Mapping[str, Any], row: ContactRow, source: str) -> dict[str, Any]:
    """The base case with the row's overrides, validated (not yet checked for consistency).

    A row giving the law's coefficients replaces the base case's coefficient source (its
    database materials), and a row giving materials replaces the base case's coefficients
    (:func:`_coefficient_source`). A row naming another law (``law.name``) does not inherit the
    base case's coefficient tables (``law.mobile``, ``law.obstacle``): their entries belong to
    the base's law; the row's own entries, or the new law's defaults, apply. A section given
    whole (``sectors``, :data:`fretwear.bundle.columns.WHOLE_SECTIONS`) replaces the base
    case's, ``{}`` drops it (a law other than Archard refuses sectors).

    Raises
    ------
    KeywordError
        An override of the wrong type, or a case that does not validate.
    """
    case = copy.deepcopy({k: v for k, v in base.items() if k != "_directory"})
    where = f"{source}: contact {row.contact!r}"
    given: list[tuple[tuple[str, ...], Any]] = []
    for key, value in row.overrides.items():
        if len(key) == 3:
            given.append((key, value.item() if isinstance(value, np.generic) else value))
            continue
        label = row.labels.get(key) or f"column {'.'.join(k for k in key if k)}"
        if len(key) == 1:  # a section given whole (sectors)
            given.append((key, _section_table(value, f"{where}: {label}")))
            continue
        given.append((key, _coerce(KEYS[key[0]][key[1]][0], value, f"{where}: {label}")))
    sections = {k[0] for k, _ in given if len(k) == 1}
    both = sorted({k[0] for k, _ in given if len(k) > 1 and k[0] in sections})
    if both:  # the result would depend on the columns' order
        raise KeywordError(f"{where}: {both[0]} is given whole and by key ({both[0]}.<key>) in "
                           "the same row: give the whole table, or its keys")
    wholes = {k for k, _ in given if len(k) == 2}
    both = sorted({".".join(k[:2]) for k, _ in given if len(k) == 3 and k[:2] in wholes})
    if both:  # the result would depend on the columns' order
        raise KeywordError(f"{where}: {both[0]} is given whole and by entry ({both[0]}.<entry>) "
                           "in the same row: give the whole table, or its entries")
    if isinstance(case.get("law"), dict):
        _coefficient_source(case["law"], {k[1]: v for k, v in given if k[0] == "law"}, where)
        # another law: the base law's coefficient tables mean other things (Archard's K is not
        # EDF-MZ's A): not inherited, the row's entries (or the new law's defaults) only
        new_law = next((v for k, v in given if k == ("law", "name")), None)
        if new_law is not None and str(new_law).strip().upper() != str(
                case["law"].get("name", "ARCHARD")).strip().upper():
            for table in ("mobile", "obstacle"):
                case["law"].pop(table, None)
    for key, value in given:
        if len(key) == 1:  # sectors = {}: none for this contact; a table replaces the base's
            if value:
                case[key[0]] = dict(value)
            else:
                case.pop(key[0], None)
            continue
        section, name = key[0], key[1]
        if len(key) == 3:
            case.setdefault(section, {}).setdefault(name, {})[key[2]] = value
        elif section == "law" and name in (*COEFFICIENT_KEYS, *DATABASE_KEYS) and _empty(value):
            case.get("law", {}).pop(name, None)  # law.materials = []: none for this contact
        elif section:
            case.setdefault(section, {})[name] = value
        else:
            case[name] = value
    case.get("history", {}).pop("file", None)
    case = validate_case(case, source=where)
    if "_directory" in base:
        case["_directory"] = base["_directory"]
    return case


def _jsonable(value: Any) -> Any:
    if isinstance(value, pd.DataFrame):
        digest = hashlib.blake2b(pd.util.hash_pandas_object(value, index=True).values.tobytes(),
                                 digest_size=16).hexdigest()
        return {"table": digest, "columns": [str(c) for c in value.columns]}
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return repr(value)
    return value


@dataclass
class ContactTask:
    """Everything a worker needs to compute one contact's wear table.

    Attributes
    ----------
    contact : str
        The contact id.
    history : HistoryRef
        Where the history is.
    case : dict
        The contact's :class:`fretwear.table.WearCase` as ``to_dict()`` (JSON-ready).
    read_options : dict
        Reader options of the history (``format``, ``units``, ``columns``, ``node`` ...).
    time_unit : str
        The table's time unit (``"year"``, or ``"<scale> s"``).
    key : str
        Hash of the inputs (case, history stamp, options, chunk size, version).
    samples : int or None
        Number of samples when known before reading (Parquet, stores).
    power : float or None
        A given wear power [W] (``power.value_W``) instead of a history.
    warnings : list
        ``[category, message]`` pairs of the warnings raised while the contact's case was
        built in the client (a dimension its contact type does not use, ...): its record
        starts with them, so they reach ``BundleResult.warnings`` with the contact's own.
    file_bytes : int or None
        The history file's size [bytes] when the task was built (the stat of its key), None
        where the history is not a file or that stat failed: whether the engine splits it
        into chunks is decided from it, not from a second stat.
    """

    contact: str
    history: HistoryRef
    case: dict[str, Any]
    read_options: dict[str, Any] = field(default_factory=dict)
    time_unit: str = "s"
    key: str = ""
    samples: int | None = None
    power: float | None = None
    warnings: list[list[str]] = field(default_factory=list)
    file_bytes: int | None = None

    def wear_case(self):
        """The :class:`fretwear.table.WearCase` (rebuilt once per process for equal cases)."""
        built = self.__dict__.get("_built")
        if built is None:
            built = _wear_case(json.dumps(self.case, sort_keys=True))
            self.__dict__["_built"] = built
        return built

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description."""
        out = asdict(self)
        out["history"] = {**out["history"],
                          "arrays": {k: np.asarray(v).tolist()
                                     for k, v in self.history.arrays.items()}}
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ContactTask:
        """Rebuild a task from :meth:`to_dict`."""
        h = dict(data["history"])
        h["arrays"] = {k: np.asarray(v, dtype=float) for k, v in h.get("arrays", {}).items()}
        return cls(**{**data, "history": HistoryRef(**h)})


@functools.lru_cache(maxsize=64)
def _wear_case(text: str):
    return WearCase.from_dict(json.loads(text))


def read_options(case: Mapping[str, Any], ref: HistoryRef) -> dict[str, Any]:
    """Reader options of a contact's history: the case's ``[history]`` options
    (:func:`fretwear.workflows.case_files.history_options`), the units a store declares, and
    the manifest's node (the shock point of a Code_Aster table, POST_USURE's NOEUD)."""
    options = history_options(case.get("history", {}))
    if ref.units:
        declared = {channel_of(v): u for v, u in ref.units.items() if channel_of(v)}
        options["units"] = {**declared, **options.get("units", {})}
    if ref.node is not None:
        options["node"] = ref.node
    return options


def build_task(base: Mapping[str, Any], row: ContactRow, source: str, *,
               chunk_size: int, cache: dict | None = None) -> ContactTask:
    """The task of one manifest row (client side: validated once, here).

    Parameters
    ----------
    base : mapping
        The validated base case.
    row : ContactRow
        The manifest row.
    source : str
        The manifest, for messages.
    chunk_size : int
        Samples per chunk (part of the task's key).
    cache : dict, optional
        Shared by the rows of one manifest: rows with the same overrides share one validated
        wear case (most rows of a bundle differ by their history only).

    Raises
    ------
    InputError, KeywordError
        The merged case is invalid, or the row has neither a history nor ``power.value_W``.
    """
    signature = _signature(row)
    cached = None if cache is None else cache.get(signature)
    if cached is None:
        cached = _wear_case_of(base, row, source)
        if cache is not None:
            cache[signature] = cached
    case, wear, payload, ident_case, caught = cached
    given_power = "value_W" in case.get("power", {})
    options, read_text = _options(case, row.history, signature, cache)
    stamp: Any = None
    if row.history.kind == "store" and row.history.stamp:
        stamp = list(row.history.stamp)
    elif row.history.kind in ("file", "store"):
        stamp = path_stamp(row.history.path)
    elif row.history.kind == "memory":
        h = hashlib.blake2b(digest_size=16)
        for name in sorted(row.history.arrays):
            h.update(name.encode())
            h.update(np.ascontiguousarray(row.history.arrays[name]).tobytes())
        stamp = h.hexdigest()
    power = float(case["power"]["value_W"]) if given_power else None
    key = _task_key(ident_case, signature, cache,
                    [row.history.kind, row.history.path, row.history.node, row.history.index,
                     stamp], read_text, chunk_size, power)
    samples = None
    if row.history.kind == "memory":
        samples = int(len(next(iter(row.history.arrays.values()), [])))
    # path_stamp's (size, mtime) of anything but a folder; a missing file is ("missing",)
    size = stamp[0] if row.history.kind == "file" and len(stamp) == 2 else None
    task = ContactTask(contact=row.contact, history=row.history, case=payload,
                       read_options=options, time_unit=wear.time_label, key=key,
                       samples=samples, power=power, warnings=[list(w) for w in caught],
                       file_bytes=size)
    if cache is not None:  # the rows sharing a case share its WearCase (wear_case's own)
        shared = cache.get(("built", signature))
        if shared is None:
            shared = cache[("built", signature)] = task.wear_case()
        task.__dict__["_built"] = shared
    return task


def _options(case: Mapping[str, Any], ref: HistoryRef, signature: str, cache: dict | None
             ) -> tuple[dict[str, Any], str]:
    """A row's reader options (:func:`read_options`) and their JSON in its key, made once for
    the rows sharing a case and a node (kept in ``cache``: most rows of a bundle), the options
    then one dict for all of them (read, never changed: the worker copies what it passes on)."""
    shared = ("options", signature, ref.node) if cache is not None and not ref.units else None
    known = None if shared is None else cache.get(shared)
    if known is None:
        options = read_options(case, ref)
        known = (options, _encode(_jsonable(options)))
        if shared is not None:
            cache[shared] = known
    return known


def _task_key(ident_case: Any, signature: str, cache: dict | None, history: list,
              read_text: str, chunk_size: int, power: float | None) -> str:
    """The hash of the JSON of a row's inputs: ``json.dumps({"case": ident_case, "chunk":
    chunk_size, "history": history, "power": power, "read": _jsonable(options), "version":
    __version__}, sort_keys=True, default=str)``, the same text made piece by piece (a value's
    JSON in a dict is its own JSON): the case's encoded once for the rows that share it (kept
    in ``cache``; encoding it again for each row was a third of the client's time a contact),
    the reader options' too (``read_text``, :func:`_options`); the key of a contact in an
    earlier run's output directory is this one for the same inputs."""
    text = None if cache is None else cache.get(("json", signature))
    if text is None:
        text = _encode(ident_case)
        if cache is not None:
            cache[("json", signature)] = text
    whole = "".join(('{"case": ', text, ', "chunk": ', _encode(chunk_size),
                     ', "history": ', _encode(history), ', "power": ', _encode(power),
                     ', "read": ', read_text, ', "version": ', _VERSION, "}"))
    return hashlib.blake2b(whole.encode(), digest_size=16).hexdigest()


#: ``json.dumps(value, sort_keys=True, default=str)`` without a new encoder made per call
#: (json.dumps makes one whenever an option is given)
_encode = json.JSONEncoder(sort_keys=True, default=str).encode
_VERSION = _encode(__version__)


class BaseCaseError(FretwearError, ValueError):
    """The base case fails for every contact, whatever the manifest's rows give: the run stops
    before any work (not an :class:`~fretwear.errors.InputError`: a contact's own problems are
    those, reported per contact)."""


def _signature(row: ContactRow) -> str:
    """What a row's wear case depends on besides the base case (rows equal here share it)."""
    if not row.overrides:  # most rows of a bundle: the same text, not encoded again
        return _NO_OVERRIDES[row.history.kind == "none"]
    return json.dumps([sorted((".".join(k), _jsonable(v)) for k, v in row.overrides.items()),
                       row.history.kind == "none"], default=str)


#: :func:`_signature` of a row without overrides, with a history (False) and without (True).
_NO_OVERRIDES = {flag: json.dumps([[], flag]) for flag in (False, True)}


def _message(exc: Exception, source: str, contact: str) -> str:
    text = str(exc)
    prefix = f"{source}: contact {contact!r}: "
    return text[len(prefix):] if text.startswith(prefix) else text


#: What building one row's task may raise, reported for that contact (the engine's loop over
#: the rows catches the same): a bad case, or a file the system refuses (a database path too
#: long, unreadable)
ROW_ERRORS = (InputError, OSError)


def check_base_case(base: Mapping[str, Any], rows, source: str, cache: dict | None = None
                    ) -> None:
    """Stop before any work when the base case fails for every row for its own reason.

    The base case with each distinct set of overrides of ``rows`` is built in turn (what a
    row's task builds anyway: the successes go into ``cache``) until one succeeds, which ends
    the check. The run stops only when the base case alone fails (with a history, without
    overrides) and every row fails with that same message: a base case missing a key that no
    row gives, say ``contact_type``. A row that gives the key, or fails otherwise (its own bad
    cell), leaves the failures to the contacts, each reported as usual.

    Raises
    ------
    BaseCaseError
        The base case's error, said once.
    """
    alone: str | None = None
    seen: set[str] = set()
    for row in rows:
        signature = _signature(row)
        if signature in seen:
            continue
        seen.add(signature)
        if cache is not None and signature in cache:
            return
        try:
            built = _wear_case_of(base, row, source)
        except ROW_ERRORS as exc:
            if alone is None:
                probe = ContactRow("base case", HistoryRef("file"), {}, {})
                try:
                    _wear_case_of(base, probe, source)
                    return
                except ROW_ERRORS as base_exc:
                    alone = _message(base_exc, source, probe.contact).removeprefix("case: ")
            if _message(exc, source, row.contact).removeprefix("case: ") != alone:
                return
            continue
        if cache is not None:
            cache[signature] = built
        return
    if alone is not None:
        if alone == BOTH_POWER_AND_HISTORY and "value_W" in base.get("power", {}):
            alone = ("its [power] value_W gives every contact a power, and the manifest's rows "
                     "give histories: remove value_W from the base case (a row without a "
                     "history may give power.value_W)")
        raise BaseCaseError(f"{source}: the base case fails for every contact: {alone}; no "
                            "row of the manifest changes that; nothing was computed")


BOTH_POWER_AND_HISTORY = "gives both a history and power.value_W; keep one"


def _check_sectors_law(row: ContactRow, case: Mapping[str, Any], where: str) -> None:
    """The base case's sectors under a row's law that refuses them (another law than Archard):
    the case layer's error, with how a manifest row drops them.

    Raises
    ------
    KeywordError
        The row's law takes no sectors and the row keeps the base case's.
    """
    if not case.get("sectors") or any(k[0] == "sectors" for k in row.overrides):
        return  # no sectors, or the row's own: the case layer's message says it
    try:
        law = get_law(str(case.get("law", {}).get("name", "ARCHARD")))
    except KeywordError:
        return  # an unknown law: the case layer names it
    if sector_parameter(law) is None:
        raise KeywordError(
            f"{where}: law {law.name!r} with the base case's [sectors]: sector tables take "
            f"Archard coefficients only (SECTEUR belongs to LOI_USURE="
            f"{laws_with(lambda lw: sector_parameter(lw) is not None)}); use law.name = "
            "ARCHARD, or drop the sectors for this contact: a sectors cell {} in its row (a "
            "TOML manifest: sectors = {})")


def _wear_case_of(base: Mapping[str, Any], row: ContactRow, source: str):
    """(merged case, WearCase, its to_dict, its JSON-ready form, the warnings raised while it
    was built as ``(category, message)`` pairs) of a row."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            built = _built_case(base, row, source)
        except ROW_ERRORS as exc:  # the contact fails: the warnings said before stay its own
            exc.case_warnings = _said(caught)
            raise
    return (*built, _said(caught))


def _said(caught) -> tuple:
    """``(category, message)`` pairs of recorded warnings, each once, in order."""
    return tuple(dict.fromkeys((w.category.__name__, str(w.message)) for w in caught))


def _built_case(base: Mapping[str, Any], row: ContactRow, source: str):
    case = merge_case(base, row, source)
    where = f"{source}: contact {row.contact!r}"
    given_power = "value_W" in case.get("power", {})
    if row.history.kind == "none" and not given_power:
        raise InputError(f"{where}: no history: give the history column (a file relative to "
                         "the manifest) or a power.value_W column")
    if row.history.kind != "none" and given_power:
        raise KeywordError(f"{where}: {BOTH_POWER_AND_HISTORY}")
    _check_sectors_law(row, case, where)
    units = case.get("history", {}).get("units")
    for key in units if isinstance(units, Mapping) else ():
        message = unknown_units_key(key, "[history]")
        if message is not None:  # said here once, not when each contact's file is read
            raise KeywordError(f"{where}: {message}")
    try:
        keywords = case_arguments(case, history_elsewhere=True)
        wear = WearCase.from_keywords(**keywords)
    except InputError as exc:
        raise type(exc)(f"{where}: {exc}") from None
    payload = wear.to_dict()
    return case, wear, payload, _jsonable(payload)
