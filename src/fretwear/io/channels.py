"""Column aliases and unit conversion: from a file's columns to the channels of a history.

Every reader in :mod:`fretwear.io` turns a file into a :class:`Source` (column names, the units
the file declares, a way to read columns whole or by blocks). This module maps those columns to
the canonical channels of :class:`fretwear.history.ContactHistory` (theory §1), converts them to SI
and builds the history. Column names are matched case-insensitively, ignoring spaces, dashes and
dots, and a trailing unit in brackets (``"Fn [kN]"`` is the normal force in kilonewtons).

The alias table follows theory §1: Code_Aster's names ``INST, FN, FT1, FT2, VN, VT1, VT2, DYLOC,
DZLOC`` and its internal variables of a shock (``VINT1`` = FN, ``VINT2``/``VINT3`` = FT1/FT2,
``VINT5``/``VINT6`` = local DY/DZ of node 1, ``VINT10``-``VINT12`` = VN/VT1/VT2, ``VINT13`` =
stick flag).
"""

from __future__ import annotations

import functools
import re
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np

from fretwear.errors import FormatError, HistoryError, KeywordError, UnitsWarning
from fretwear.history import CHANNELS, REQUIRED, UNITS, ContactHistory
from fretwear.keys import keyword_hint

#: Accepted column names of each channel (normalised: lower case, ``_`` for spaces/dashes/dots).
ALIASES: Mapping[str, tuple[str, ...]] = MappingProxyType({
    "time": ("time", "t", "inst", "instant", "temps", "time_s"),
    "normal_force": ("normal_force", "fn", "f_n", "fnor", "force_normale", "normal_load",
                     "vint1"),
    "ft1": ("ft1", "f_t1", "tangential_force_1", "force_tangentielle_1", "vint2"),
    "ft2": ("ft2", "f_t2", "tangential_force_2", "force_tangentielle_2", "vint3"),
    "vn": ("vn", "v_n", "normal_velocity", "vitesse_normale", "vint10"),
    "vt1": ("vt1", "v_t1", "sliding_velocity_1", "tangential_velocity_1",
            "vitesse_tangentielle_1", "vint11"),
    "vt2": ("vt2", "v_t2", "sliding_velocity_2", "tangential_velocity_2",
            "vitesse_tangentielle_2", "vint12"),
    "dy": ("dy", "dyloc", "d_y", "vint5"),
    "dz": ("dz", "dzloc", "d_z", "vint6"),
    "stick": ("stick", "stick_flag", "sticking", "adherence", "vint13"),
})

_ALIAS_TO_CHANNEL: dict[str, str] = {a: ch for ch, names in ALIASES.items() for a in names}

#: Physical quantity of each channel (the keys accepted by the ``units`` option).
QUANTITY: Mapping[str, str] = MappingProxyType({
    "time": "time", "normal_force": "force", "ft1": "force", "ft2": "force",
    "vn": "velocity", "vt1": "velocity", "vt2": "velocity", "dy": "length", "dz": "length",
    "stick": "dimensionless",
})

#: Factor to SI of each known unit, per quantity (velocity units are ``<length>/<time>``).
UNIT_FACTORS: Mapping[str, Mapping[str, float]] = MappingProxyType({
    "length": MappingProxyType({
        "m": 1.0, "dm": 1e-1, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6,
        "micron": 1e-6, "nm": 1e-9, "in": 0.0254, "inch": 0.0254, "ft": 0.3048}),
    "force": MappingProxyType({
        "N": 1.0, "mN": 1e-3, "daN": 10.0, "kN": 1e3, "MN": 1e6, "lbf": 4.4482216152605,
        "kgf": 9.80665}),
    "time": MappingProxyType({
        "s": 1.0, "sec": 1.0, "second": 1.0, "seconds": 1.0, "ms": 1e-3, "us": 1e-6,
        "µs": 1e-6, "μs": 1e-6, "min": 60.0, "h": 3600.0}),
    "dimensionless": MappingProxyType({"1": 1.0, "-": 1.0, "": 1.0, "none": 1.0}),
})

_UNIT_SUFFIX = re.compile(r"^(?P<base>.*?)\s*[\[(](?P<unit>[^\])]*)[\])]\s*$")


def split_unit(column: str) -> tuple[str, str | None]:
    """Split a header such as ``"Fn [kN]"`` or ``"t (ms)"`` into its name and its unit.

    Examples
    --------
    >>> split_unit("Fn [kN]"), split_unit("t (ms)"), split_unit("VINT1")
    (('Fn', 'kN'), ('t', 'ms'), ('VINT1', None))
    """
    text = str(column).strip().strip("'\"")
    match = _UNIT_SUFFIX.match(text)
    if match and match.group("base"):
        return match.group("base").strip(), match.group("unit").strip()
    return text, None


def normalise(column: str) -> str:
    """Key used to compare column names: lower case, unit suffix dropped, ``_`` separators.

    Examples
    --------
    >>> normalise("Normal Force [N]"), normalise("force-normale"), normalise(" VINT13 ")
    ('normal_force', 'force_normale', 'vint13')
    """
    base, _ = split_unit(column)
    return re.sub(r"[\s\-.]+", "_", base.strip().lower())


def channel_of(column: str) -> str | None:
    """Canonical channel a column name stands for, or None.

    Examples
    --------
    >>> channel_of("INST"), channel_of("Vint11"), channel_of("DZLOC"), channel_of("NOEUD")
    ('time', 'vt1', 'dz', None)
    """
    if isinstance(column, str):  # the names of a bundle's files repeat: parsed once each
        return _channel_of_name(column)
    return _ALIAS_TO_CHANNEL.get(normalise(column))


@functools.lru_cache(maxsize=4096)
def _channel_of_name(column: str) -> str | None:
    return _ALIAS_TO_CHANNEL.get(normalise(column))


def unit_factor(unit: str, quantity: str, *, culprit: str = "") -> float:
    """Factor converting ``unit`` of ``quantity`` to SI (exact match first, then case-blind).

    Parameters
    ----------
    unit : str
        A unit name (``"mm"``, ``"kN"``, ``"ms"``, ``"mm/s"`` ...).
    quantity : str
        ``"length"``, ``"force"``, ``"time"``, ``"velocity"`` or ``"dimensionless"``.
    culprit : str
        What the unit was given for, quoted in the error message.

    Returns
    -------
    float
        SI value of one ``unit`` (``[m]``, ``[N]``, ``[s]``, ``[m/s]`` or 1).

    Raises
    ------
    KeywordError
        Unknown unit; the message lists the known ones.

    Notes
    -----
    A velocity unit is ``<length>/<time>``: its factor is ``f_length / f_time``.

    Examples
    --------
    >>> unit_factor("kN", "force"), unit_factor("mm/ms", "velocity"), unit_factor("MM", "length")
    (1000.0, 1.0, 0.001)
    """
    if type(unit) is str and type(quantity) is str and type(culprit) is str:
        return _unit_factor(unit, quantity, culprit)  # a bundle's files repeat their units
    return _unit_factor.__wrapped__(unit, quantity, culprit)


@functools.lru_cache(maxsize=1024)
def _unit_factor(unit: str, quantity: str, culprit: str) -> float:
    text = str(unit).strip()
    if quantity == "velocity":
        parts = text.split("/")
        if len(parts) == 2:
            return (unit_factor(parts[0], "length", culprit=culprit)
                    / unit_factor(parts[1], "time", culprit=culprit))
        raise KeywordError(f"unknown velocity unit {unit!r}{_for(culprit)}; give "
                           f"'<length>/<time>' (e.g. 'mm/s') with a length unit among "
                           f"{list(UNIT_FACTORS['length'])} and a time unit among "
                           f"{list(UNIT_FACTORS['time'])}")
    table = UNIT_FACTORS.get(quantity)
    if table is None:
        raise KeywordError(f"unknown quantity {quantity!r}; known: {sorted(UNIT_FACTORS)} "
                           "and 'velocity'")
    if text in table:
        return table[text]
    folded = [k for k in table if k.lower() == text.lower()]
    if len(folded) == 1:
        return table[folded[0]]
    hint = f" (ambiguous between {folded}: mind the case)" if folded else ""
    raise KeywordError(f"unknown {quantity} unit {unit!r}{_for(culprit)}{hint}; known "
                       f"{quantity} units: {', '.join(repr(k) for k in table)}")


def _for(culprit: str) -> str:
    return f" for {culprit}" if culprit else ""


# --------------------------------------------------------------------------- sources
@dataclass
class Source:
    """A tabular file opened by a reader: column names, declared units, readers of columns.

    Parameters
    ----------
    label : str
        The file (or files) for messages and metadata.
    format : str
        Registry name of the format.
    columns : list of str
        Column names as found (duplicates allowed; columns are addressed by position).
    read : callable
        ``read(positions) -> list of 1-D float arrays``, whole columns.
    units : dict
        Unit declared by the file for a column position (header suffix, attribute).
    name : str or None
        History name stored in the file.
    metadata : dict
        Metadata stored in the file.
    iter_blocks : callable or None
        ``iter_blocks(positions, size) -> iterator of lists of arrays`` reading consecutive blocks
        of at most ``size`` rows with bounded memory; None when the format cannot (then blocks are
        sliced from a whole read).
    hint : str
        Extra advice appended to column errors (e.g. for a file without header).
    ends : callable or None
        ``ends(position) -> (first, last)``: the first and last values of a column read from the
        file's metadata or its two ends, without a pass over it (the time range of a streamed
        history); None when the format cannot.
    """

    label: str
    format: str
    columns: list[str]
    read: Callable[[list[int]], list[np.ndarray]]
    units: dict[int, str] = field(default_factory=dict)
    name: str | None = None
    metadata: dict[str, Any] = field(default_factory=dict)
    iter_blocks: Callable[[list[int], int], Iterator[list[np.ndarray]]] | None = None
    ends: Callable[[int], tuple[float, float]] | None = None
    hint: str = ""


def _locate(key: Any, columns: Sequence[str], label: str) -> int:
    text = str(key)
    exact = [i for i, c in enumerate(columns) if c == text]
    if len(exact) == 1:
        return exact[0]
    hits = exact or [i for i, c in enumerate(columns) if normalise(c) == normalise(text)]
    if len(hits) == 1:
        return hits[0]
    if not hits:
        raise KeywordError(f"{label}: columns={{{key!r}: ...}} names a column that is not in the "
                           f"file; columns found: {list(columns)}")
    raise KeywordError(f"{label}: columns={{{key!r}: ...}} matches several columns "
                       f"{[f'{columns[i]} (#{i + 1})' for i in hits]}; rename them in the file")


def resolve_columns(columns: Sequence[str], overrides: Mapping[Any, str | None] | None = None,
                    *, label: str = "input", hint: str = "") -> dict[str, int]:
    """Map canonical channels to column positions, using aliases and user overrides.

    Parameters
    ----------
    columns : sequence of str
        Column names of the file, in order.
    overrides : mapping, optional
        ``{column name: channel}`` chosen by the user; the channel is a canonical name or an
        alias, or None to ignore the column. An override wins over the aliases of other columns.
    label : str
        The file, for messages.
    hint : str
        Extra advice appended to the missing-channel message.

    Returns
    -------
    dict
        ``{channel: position}`` for every channel found.

    Raises
    ------
    KeywordError
        An override names a column that does not exist or a channel that does not exist.
    FormatError
        Two columns stand for the same channel (both named), or a required channel is missing
        (the message lists the columns found and the aliases accepted).

    Examples
    --------
    >>> resolve_columns(["INST", "VINT1", "VINT11", "VINT12", "NOEUD"])
    {'time': 0, 'normal_force': 1, 'vt1': 2, 'vt2': 3}
    >>> resolve_columns(["t", "load", "u", "w"], {"load": "normal_force", "u": "vt1", "w": "VT2"})
    {'normal_force': 1, 'vt1': 2, 'vt2': 3, 'time': 0}
    """
    mapping: dict[str, int] = {}
    taken: set[int] = set()
    for key, target in (overrides or {}).items():
        pos = _locate(key, columns, label)
        taken.add(pos)
        if target is None:
            continue
        channel = target if target in CHANNELS else channel_of(str(target))
        if channel is None:
            raise KeywordError(f"{label}: columns={{{key!r}: {target!r}}}: unknown channel "
                               f"{target!r}; channels are {list(CHANNELS)} (or None to ignore)")
        if channel in mapping:
            raise KeywordError(f"{label}: columns= maps both {columns[mapping[channel]]!r} and "
                               f"{columns[pos]!r} to {channel!r}; keep one")
        mapping[channel] = pos
    forced = set(mapping)
    for pos, col in enumerate(columns):
        if pos in taken:
            continue
        channel = channel_of(col)
        if channel is None or channel in forced:
            continue
        if channel in mapping:
            other = mapping[channel]
            raise FormatError(
                f"{label}: columns {columns[other]!r} (#{other + 1}) and {col!r} (#{pos + 1}) both "
                f"stand for the channel {channel!r}; choose one with "
                f"columns={{{col!r}: None}} or columns={{{columns[other]!r}: None}}")
        mapping[channel] = pos
    missing = [ch for ch in REQUIRED if ch not in mapping]
    if missing and (kind := _not_a_history(label, columns)):
        raise FormatError(f"{label} is {kind}, not a contact history (no column for "
                          f"{missing}; columns found: {list(columns)[:8]}...). A contact "
                          "history has time, normal force and sliding velocities")
    if missing:
        accepted = "; ".join(f"{ch}: {', '.join(ALIASES[ch])}" for ch in missing)
        raise FormatError(
            f"{label}: no column for the required channel(s) {missing}; columns found: "
            f"{list(columns)}; accepted names (case-insensitive): {accepted}; or map a column "
            f"to it: Python columns={{'<column>': '{missing[0]}'}}, fretwear power --column "
            f"'<column>={missing[0]}', case file [history] columns = {{ '<column>' = "
            f"'{missing[0]}' }}{hint}")
    return mapping


def _not_a_history(label: str, columns) -> str | None:
    """What a file given as a history is instead, when it is one of fretwear's own kinds: a
    wear table (INST and V_USUR_TUBE, POST_USURE's columns) or a TOML case file."""
    names = {str(c).strip().upper() for c in columns}
    if {"INST", "V_USUR_TUBE"} <= names or {"INSTANT", "VOLUME_MOBILE"} <= names:
        return ("a wear table (POST_USURE's output; continue it with a case's [restart] "
                "table, or update an obstacle with fretwear obstacle)")
    if str(label).lower().rstrip("'\"").endswith(".toml"):
        return "a TOML file (a case file? run it with fretwear run CASE.toml)"
    return None


#: The quantities a ``units`` option may name (besides channels).
QUANTITIES = ("length", "force", "time", "velocity")


def unknown_units_key(key: Any, label: str) -> str | None:
    """The message of a ``units`` option's key that is neither a quantity nor a channel (with
    the closest of them), or None for a valid key.

    Examples
    --------
    >>> unknown_units_key("lenght", "h.csv")[:64]
    "h.csv: units={'lenght': ...}: unknown key 'lenght' (did you mean"
    >>> unknown_units_key("FN", "h.csv") is None
    True
    """
    k = str(key).strip()
    if k.lower() in QUANTITIES or k in CHANNELS or channel_of(k) is not None:
        return None
    return (f"{label}: units={{{key!r}: ...}}: unknown key {key!r}"
            f"{keyword_hint(k, (*QUANTITIES, *CHANNELS))}; give a quantity ('length', 'force', "
            f"'time', 'velocity') or a channel {list(CHANNELS)}")


def resolve_units(mapping: Mapping[str, int], declared: Mapping[int, str],
                  units: Mapping[str, str] | None, *, label: str = "input"
                  ) -> tuple[dict[str, str], dict[str, float]]:
    """Unit of every mapped channel and its factor to SI.

    Precedence: a unit the user gives for the channel (``units={"dy": "mm"}``), then for its
    quantity (``units={"length": "mm"}``), then the unit the file declares for the column, then
    for a velocity the user's ``<length>/<time>``, then SI. A unit given that differs from the
    one the file declares for the same column (another factor to SI) still wins, with one
    :class:`~fretwear.errors.UnitsWarning` naming every such column: the file and the option
    disagree, and one of them is wrong. A declared unit fretwear cannot read is replaced
    without a warning (the reader's error asks for the unit in that case).

    Parameters
    ----------
    mapping : mapping
        ``{channel: position}`` from :func:`resolve_columns`.
    declared : mapping
        ``{position: unit}`` declared by the file.
    units : mapping, optional
        The user's ``units`` option: keys are quantities (``length``, ``force``, ``time``,
        ``velocity``) or channels (canonical names or aliases).
    label : str
        The file, for messages.

    Returns
    -------
    (dict, dict)
        ``{channel: unit}`` and ``{channel: factor to SI}``.

    Examples
    --------
    >>> resolve_units({"time": 0, "vt1": 1, "dy": 2}, {}, {"length": "mm", "time": "ms"})
    ({'time': 'ms', 'vt1': 'mm/ms', 'dy': 'mm'}, {'time': 0.001, 'vt1': 1.0, 'dy': 0.001})
    """
    per_quantity: dict[str, str] = {}
    per_channel: dict[str, str] = {}
    for key, unit in (units or {}).items():
        k = str(key).strip()
        if k.lower() in ("length", "force", "time", "velocity"):
            per_quantity[k.lower()] = unit
        elif k in CHANNELS or channel_of(k) is not None:
            per_channel[k if k in CHANNELS else str(channel_of(k))] = unit
        else:
            raise KeywordError(unknown_units_key(key, label))
    derived = f"{per_quantity.get('length', 'm')}/{per_quantity.get('time', 's')}"
    chosen: dict[str, str] = {}
    factors: dict[str, float] = {}
    overridden: list[str] = []
    for channel, pos in mapping.items():
        quantity = QUANTITY[channel]
        if channel in per_channel:
            unit = per_channel[channel]
        elif quantity in per_quantity:
            unit = per_quantity[quantity]
        elif pos in declared and declared[pos] is not None:
            unit = declared[pos]
        elif quantity == "velocity":
            unit = derived
        else:
            unit = UNITS[channel]
        if channel == "time":
            unit = _without_epoch(unit)
        chosen[channel] = str(unit)
        from_file = channel not in per_channel and quantity not in per_quantity \
            and declared.get(pos) is not None
        try:
            factors[channel] = unit_factor(unit, quantity,
                                           culprit=f"channel {channel!r} ({label})")
        except KeywordError as exc:
            if not from_file:
                raise
            raise KeywordError(f"{exc}; this unit is declared by the file (header or "
                               f"attribute): override it with units={{{channel!r}: "
                               f"'{UNITS[channel]}'}}") from None
        if not from_file and declared.get(pos) is not None \
                and _differs(declared[pos], factors[channel], quantity):
            overridden.append(f"{channel} {unit!r} (the file: {declared[pos]!r})")
    if overridden:
        warnings.warn(f"{label}: the units given override the units the file declares for "
                      f"{', '.join(overridden)}; the values are read in the units given. If the "
                      "file is right, leave those units out", UnitsWarning, stacklevel=4)
    return chosen, factors


def _without_epoch(unit: Any) -> Any:
    """A CF time unit without its epoch (``"seconds since 2000-01-01"`` -> ``"seconds"``)."""
    return str(unit).split(" since ")[0].strip() if " since " in str(unit) else unit


def _differs(declared: str, factor: float, quantity: str) -> bool:
    """Whether the unit a file declares has another factor to SI than ``factor``. A declared
    unit fretwear cannot read (CF's ``m s-1``, say) is not said to differ: giving the unit is
    then what the reader's error asks for, and nothing tells the two apart."""
    try:
        read = unit_factor(_without_epoch(declared), quantity, culprit="the declared unit")
        return read != factor
    except KeywordError:
        return False


def check_lengths(sizes: list[int], names: list[str], label: str) -> int:
    """The common length of the columns read, or a :class:`FormatError` naming the culprits.

    Examples
    --------
    >>> check_lengths([3, 3], ["time", "fn"], "h.npz")
    3
    """
    if len(set(sizes)) > 1:
        detail = ", ".join(f"{n!r}: {k}" for n, k in zip(names, sizes, strict=True))
        raise FormatError(f"{label}: the columns used have different lengths ({detail}); every "
                          "channel needs one value per instant")
    return sizes[0] if sizes else 0


def build_history(arrays: Mapping[str, np.ndarray], *, columns: Sequence[str],
                  mapping: Mapping[str, int], factors: Mapping[str, float], label: str,
                  name: str, metadata: Mapping[str, Any], first_row: int = 0) -> ContactHistory:
    """Convert raw column arrays to SI and build a validated :class:`ContactHistory`.

    The errors of the history's validation are re-raised with the file and the columns used,
    and a missing or non-numeric value is reported with its column, channel and data row.
    ``first_row`` offsets the row numbers (chunked reading).
    """
    data: dict[str, np.ndarray] = {}
    for channel, raw in arrays.items():
        arr = np.asarray(raw, dtype=float)
        bad = ~np.isfinite(arr)
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            col = columns[mapping[channel]]
            raise HistoryError(
                f"{label}: column {col!r} (channel {channel!r}) has a missing or non-finite value "
                f"({arr[i]}) at data row {first_row + i} (0-based, header excluded); remove or "
                "fill it before reading")
        factor = factors.get(channel, 1.0)
        # no copy when factor == 1: ContactHistory copies its inputs (the user's stay untouched)
        data[channel] = arr * factor if factor != 1.0 else arr
    try:
        return ContactHistory(**data, name=name, metadata=dict(metadata), first_row=first_row)
    except HistoryError as exc:
        used = ", ".join(f"{ch} <- {columns[pos]!r}" for ch, pos in mapping.items())
        raise HistoryError(f"{label}: {exc} [columns used: {used}]") from None


def _checks(data: Mapping[str, np.ndarray]) -> tuple[bool, float]:
    """Whether the 1-D channels of equal length ``data`` pass the checks of a history (finite
    values, strictly increasing time, Fn >= 0, stick flags 0/1), and the largest force [N].

    One compiled pass a channel when numba is installed and the arrays are contiguous
    (:mod:`fretwear.io._compiled`; a 2**20-row block of 7 channels: 1-2 ms against 7-11 ms),
    else numpy's expressions, the reference.

    Examples
    --------
    >>> t = np.array([0.0, 1.0, 2.0])
    >>> _checks({"time": t, "normal_force": np.array([0.0, 2.0, 1.0])})
    (True, 2.0)
    >>> _checks({"time": t[::-1].copy(), "normal_force": np.zeros(3)})[0]
    False
    """
    from fretwear._numba import HAVE_NUMBA  # numba, imported by the stream's first block

    t, fn = data["time"], data["normal_force"]
    if HAVE_NUMBA and all(a.flags.c_contiguous for a in data.values()):
        from fretwear.io import _compiled

        ok, fmax = _compiled.nonnegative_max(fn)
        ok = (ok and _compiled.increasing(t)
              and all(_compiled.flags(a) if ch == "stick" else _compiled.finite(a)
                      for ch, a in data.items() if ch not in ("time", "normal_force")))
        return bool(ok), float(fmax)
    ok = (all(bool(np.isfinite(a).all()) for a in data.values())
          and bool((t[1:] > t[:-1]).all()) and float(fn.min()) >= 0.0)
    if ok and "stick" in data:
        s = data["stick"]
        ok = bool(((s == 0.0) | (s == 1.0)).all())
    return ok, float(fn.max()) if ok else float("nan")


def fast_history(arrays: Mapping[str, np.ndarray], *, columns: Sequence[str],
                 mapping: Mapping[str, int], factors: Mapping[str, float], label: str,
                 name: str, metadata: Mapping[str, Any], first_row: int = 0) -> ContactHistory:
    """:func:`build_history` without copying the arrays when they pass every check.

    The checks of :class:`~fretwear.history.ContactHistory` run as whole-array reductions
    (finite values, strictly increasing time, Fn >= 0, stick flags 0/1, equal lengths, dy with
    dz); the arrays then go into the history as read-only views (converted to SI first when a
    unit factor is not 1). Anything else, including small negative forces that the validation
    sets to 0 in its own copy, goes through :func:`build_history`, which raises the same errors
    or returns the same history.

    Examples
    --------
    >>> raw = {"time": np.array([0.0, 1.0]), "normal_force": np.array([2.0, 3.0]),
    ...        "vt1": np.zeros(2), "vt2": np.zeros(2)}
    >>> h = fast_history(raw, columns=["t", "fn", "v1", "v2"], mapping={"time": 0,
    ...                  "normal_force": 1, "vt1": 2, "vt2": 3}, factors={}, label="x",
    ...                  name="x", metadata={})
    >>> np.shares_memory(h.time, raw["time"]), h.force_tolerance
    (True, 3e-09)
    """
    data: dict[str, np.ndarray] = {}
    for channel, raw in arrays.items():
        arr = np.asarray(raw, dtype=float)
        factor = factors.get(channel, 1.0)
        data[channel] = arr * factor if factor != 1.0 else arr
    sizes = {a.shape for a in data.values()}
    t = data["time"]
    ok = (len(sizes) == 1 and t.ndim == 1 and t.size >= 2 and ("dy" in data) == ("dz" in data))
    if ok:
        ok, fmax = _checks(data)
    if not ok:
        return build_history(arrays, columns=columns, mapping=mapping, factors=factors,
                             label=label, name=name, metadata=metadata, first_row=first_row)
    tolerance = max(1e-12, 1e-9 * fmax)
    return ContactHistory._checked_elsewhere(data, name=name, metadata=metadata,
                                             force_tolerance=tolerance)


def describe_aliases() -> str:
    """A text table of the accepted column names of every channel (used by docs and errors).

    Examples
    --------
    >>> print(describe_aliases().splitlines()[0])
    time: time, t, inst, instant, temps, time_s
    """
    return "\n".join(f"{ch}: {', '.join(ALIASES[ch])}" for ch in CHANNELS)
