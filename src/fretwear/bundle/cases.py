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
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._version import __version__
from fretwear.bundle.datasets import path_stamp
from fretwear.bundle.manifest import ContactRow, HistoryRef
from fretwear.errors import InputError, KeywordError
from fretwear.io.channels import channel_of
from fretwear.table import WearCase
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
            raise KeywordError(f"{where} = {value!r}: not a number") from None
        return int(number) if float not in kinds and number.is_integer() else number
    if str in kinds and isinstance(value, int | float) and not isinstance(value, bool):
        return str(value)
    if list in kinds and not isinstance(value, list | tuple):
        return [value]
    return value


def merge_case(base: Mapping[str, Any], row: ContactRow, source: str) -> dict[str, Any]:
    """The base case with the row's overrides, validated (not yet checked for consistency).

    Raises
    ------
    KeywordError
        An override of the wrong type, or a case that does not validate.
    """
    case = copy.deepcopy({k: v for k, v in base.items() if k != "_directory"})
    where = f"{source}: contact {row.contact!r}"
    for key, value in row.overrides.items():
        section, name = key[0], key[1]
        column = ".".join(k for k in key if k)
        if len(key) == 3:
            table = case.setdefault(section, {}).setdefault(name, {})
            table[key[2]] = value.item() if isinstance(value, np.generic) else value
            continue
        coerced = _coerce(KEYS[section][name][0], value, f"{where}: column {column}")
        if section:
            case.setdefault(section, {})[name] = coerced
        else:
            case[name] = coerced
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
    """

    contact: str
    history: HistoryRef
    case: dict[str, Any]
    read_options: dict[str, Any] = field(default_factory=dict)
    time_unit: str = "s"
    key: str = ""
    samples: int | None = None
    power: float | None = None

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
    signature = json.dumps([sorted((".".join(k), _jsonable(v)) for k, v in
                                   row.overrides.items()), row.wall_thickness,
                            row.history.kind == "none"], default=str)
    cached = None if cache is None else cache.get(signature)
    if cached is None:
        cached = _wear_case_of(base, row, source)
        if cache is not None:
            cache[signature] = cached
    case, wear, payload, ident_case = cached
    given_power = "value_W" in case.get("power", {})
    options = read_options(case, row.history)
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
    ident = {"case": ident_case,
             "history": [row.history.kind, row.history.path, row.history.node,
                         row.history.index, stamp],
             "read": _jsonable(options), "chunk": chunk_size, "version": __version__,
             "power": power}
    key = hashlib.blake2b(json.dumps(ident, sort_keys=True, default=str).encode(),
                          digest_size=16).hexdigest()
    samples = None
    if row.history.kind == "memory":
        samples = int(len(next(iter(row.history.arrays.values()), [])))
    unit = wear.time_unit
    return ContactTask(contact=row.contact, history=row.history, case=payload,
                       read_options=options,
                       time_unit=unit if unit else f"{wear.time_scale:g} s", key=key,
                       samples=samples, power=power)


def _wear_case_of(base: Mapping[str, Any], row: ContactRow, source: str):
    """(merged case, WearCase, its to_dict, its JSON-ready form) of a row."""
    case = merge_case(base, row, source)
    where = f"{source}: contact {row.contact!r}"
    given_power = "value_W" in case.get("power", {})
    if row.history.kind == "none" and not given_power:
        raise InputError(f"{where}: no history: give the history column (a file relative to "
                         "the manifest) or a power.value_W column")
    if row.history.kind != "none" and given_power:
        raise KeywordError(f"{where}: gives both a history and power.value_W; keep one")
    try:
        keywords = case_arguments(case, history_elsewhere=True)
        if row.wall_thickness is not None:
            keywords["wall_thickness"] = row.wall_thickness
        wear = WearCase.from_keywords(**keywords)
    except InputError as exc:
        raise type(exc)(f"{where}: {exc}") from None
    payload = wear.to_dict()
    return case, wear, payload, _jsonable(payload)
