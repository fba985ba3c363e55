"""The wear case: one validated, immutable description of one contact's wear computation.

:class:`WearCase` holds everything :func:`fretwear.table.wear_table_from_case` needs besides the
wear power (or the contact history it comes from): the contact geometry, the wear law and its
coefficients (each tagged with where it came from: :class:`Coefficient`), the material pair and
coefficient files, the angular sectors and their coefficients, the instants and their unit, the
window of the power computation, the restart state (ETAT_INIT) and the tube replacement
(TUBE_NEUF), the wall thickness and the depth limit, and a name.

Every rule between keywords is checked here, once: :meth:`WearCase.from_keywords` resolves what
the user gave (database look-up, coefficient files, the initial table read into an
:class:`~fretwear.table.restart.InitialState`), and the constructor checks the consistency of the
resolved values, so a case rebuilt by :meth:`WearCase.from_dict` on another machine (a worker
without the user's files) is checked by the same code. A case pickles, and ``to_dict()`` is
JSON-ready (floats written by ``json`` round-trip exactly).
"""

from __future__ import annotations

import dataclasses
import functools
import json
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, KeywordError
from fretwear.geometry import check_sector_contact, contact_geometry, sector_obstacle_radius
from fretwear.geometry.sectors import SectorGeometry, sector_geometry
from fretwear.laws import WEAR_LAWS, get_law
from fretwear.sectors import sector_edges
from fretwear.table._serial import FrozenMap, jsonable, state_from_dict, state_to_dict
from fretwear.table.case_rules import (
    check_restart_unit,
    check_wall,
    coefficient_map,
    history_values,
    material_values,
    sector_values,
    time_values,
)
from fretwear.table.case_rules import instants as normalised_instants
from fretwear.table.case_values import PowerWindow, Restart, Wall
from fretwear.table.coefficients import (
    Coefficient,
    coefficient_file_paths,
    law_coefficients,
    resolve_coefficients,
)
from fretwear.table.keywords import KEYWORDS, check_keywords, keywords_doc
from fretwear.table.restart import InitialState
from fretwear.table.restart import initial_state as _read_initial_state

__all__ = ["Coefficient", "PowerWindow", "Restart", "Wall", "WearCase", "law_coefficients"]

#: Format tag of :meth:`WearCase.to_dict`.
FORMAT = "fretwear.WearCase/1"
#: The keys of :meth:`WearCase.to_dict`, in its order: the user's flat vocabulary (the keywords
#: of :func:`fretwear.table.wear_table` and ``initial_table``, where the restart came from).
FLAT_KEYS = tuple(k for name in KEYWORDS for k in (
    (name, "initial_table") if name == "initial_instant" else (name,)))
#: A grouped field of the case -> (its type, flat key -> the type's attribute).
_GROUPS = {
    "window": (PowerWindow, {"t_start": "t_start", "t_end": "t_end", "blocks": "blocks",
                             "stationarity_threshold": "stationarity_threshold"}),
    "restart": (Restart, {"initial_state": "table", "initial_instant": "instant",
                          "initial_table": "source", "tube_replacement": "tube_replacement"}),
    "wall": (Wall, {"wall_thickness": "thickness", "depth_limit": "limit"}),
}
#: Flat key -> the grouped field holding it.
_GROUP_OF = {key: group for group, (_, names) in _GROUPS.items() for key in names}


def _restart_state(table, initial_instant) -> tuple[InitialState | None, str | None]:
    """(the restart state, where it came from) of ``initial_state=``: read once, here."""
    if table is None:
        return None, None
    if isinstance(table, InitialState):
        return table, "(InitialState)"
    label = "(DataFrame)" if isinstance(table, pd.DataFrame) else os.fspath(table)
    return _read_initial_state(table, initial_instant), label


def _copied(value: Any) -> Any:
    """A copy of a JSON-ready value (its dicts and lists new, the numbers and strings shared)."""
    if type(value) is dict:
        return {k: _copied(v) if type(v) in (dict, list) else v for k, v in value.items()}
    if type(value) is list:
        return [_copied(v) if type(v) in (dict, list) else v for v in value]
    return value


# --------------------------------------------------------------------------- the wear case
@dataclass(frozen=True, eq=False, kw_only=True)
class WearCase:
    """One contact's wear computation, validated: everything but the wear power (theory §7).

    Build it with :meth:`from_keywords` (the keywords of :func:`fretwear.table.wear_table`) and
    compute its table with :func:`fretwear.table.wear_table_from_case`; :meth:`to_dict` /
    :meth:`from_dict` and pickle carry it to another process or machine.

    Attributes
    ----------
    contact_type : str or None
        Code_Aster contact type (CONTACT), upper case, e.g. ``"TUBE_BAV"``. None only with
        sectors (Code_Aster's SECTEUR without CONTACT): the sector depths are computed from the
        radii and the width (theory §3), the global depths are NaN
        (:class:`~fretwear.geometry.sectors.SectorGeometry`).
    dimensions : mapping
        The geometry's dimensions, native names: lengths [m], angles [deg] (defaults included).
    instants : tuple of float
        Durations of service after the origin [user time unit] (INST), strictly increasing.
    law : str
        Wear law (LOI_USURE), a key of :data:`fretwear.laws.WEAR_LAWS`.
    coefficients, obstacle_coefficients : mapping of str to Coefficient
        The law's coefficients of the mobile / obstacle by native name, SI, each with its
        source; ``obstacle_coefficients`` None: the obstacle does not wear.
    materials : (str, str) or None
        Database material pair (MATER_USURE) the coefficients came from.
    obstacle_wear : bool
        Obstacle coefficients from the database (USURE_OBST).
    coefficient_files : tuple of str or None
        The user's coefficient CSV files that extended the database.
    sectors : int, tuple of float or None
        Number of equal sectors, or their edges [deg] (SECTEUR).
    sector_coefficients : tuple of (float, float or None) or None
        Archard coefficients (mobile, obstacle) [1/Pa] of every sector.
    time_scale : float
        Seconds per user time unit [s] (COEF_INST).
    time_unit : str or None
        Name of the user time unit (``"year"``, ...), for the table's metadata.
    window : PowerWindow
        The window of the history the power is computed over, its blocks and the
        stationarity threshold (INST_INIT, INST_FIN, NB_BLOC of RESU_GENE).
    force_max, speed_max : float or None
        KWU-EPRI class ranges [N], [m/s] (FNOR_MAXI, VTAN_MAXI); None: the window's maxima.
    restart : Restart
        The restart state read from the initial table and the instant it was read at
        (ETAT_INIT), the tube replacement (TUBE_NEUF).
    wall : Wall
        The wall thickness of the mobile [m] (when known) and the depth limit [-].
    name : str or None
        A name or title of the case.

    Examples
    --------
    >>> case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...                               dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...                               coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> case.coefficients["coefficient"]
    Coefficient(value=1e-14, source='user')
    >>> case.wall.limit, case.window.blocks, case.restart.origin
    (0.4, 1, 0.0)
    >>> WearCase.from_dict(case.to_dict()) == case
    True
    """

    contact_type: str | None
    dimensions: Mapping[str, float] = dataclasses.field(default_factory=dict)
    instants: tuple[float, ...]
    law: str = "ARCHARD"
    coefficients: Mapping[str, Coefficient] = dataclasses.field(default_factory=dict)
    obstacle_coefficients: Mapping[str, Coefficient] | None = None
    materials: tuple[str, str] | None = None
    obstacle_wear: bool = False
    coefficient_files: tuple[str, ...] | None = None
    sectors: int | tuple[float, ...] | None = None
    sector_coefficients: tuple[tuple[float, float | None], ...] | None = None
    time_scale: float = 1.0
    time_unit: str | None = None
    window: PowerWindow = dataclasses.field(default_factory=PowerWindow)
    force_max: float | None = None
    speed_max: float | None = None
    restart: Restart = dataclasses.field(default_factory=Restart)
    wall: Wall = dataclasses.field(default_factory=Wall)
    name: str | None = None

    # ----------------------------------------------------------------------- construction
    @classmethod
    def from_keywords(cls, **keywords: Any) -> WearCase:
        """The case of the keywords of :func:`fretwear.table.wear_table` (but ``source`` and
        ``history``), resolved and validated.

        Resolving: the law's coefficients by native name with their defaults, or the database
        row of ``materials`` (extended by ``coefficient_files``); the initial table read into an
        :class:`~fretwear.table.InitialState` at ``initial_instant``. Each coefficient keeps its
        source (:class:`Coefficient`).

        Parameters
        ----------
{keywords}

        Raises
        ------
        KeywordError
            An unknown keyword (:data:`fretwear.table.keywords.KEYWORDS` lists them), keywords
            that exclude each other or need another one, naming both and the fix.
        InputError
            A bad value (instants, time scale, sector coefficients, ...), a missing file.
        DatabaseError
            A material pair without coefficients.
        """
        kw = check_keywords(keywords, "WearCase.from_keywords")
        wear_law = get_law(kw["law"])
        files = coefficient_file_paths(kw["coefficient_files"], kw["materials"])
        state, label = _restart_state(kw["initial_state"], kw["initial_instant"])
        mobile, obstacle = resolve_coefficients(
            wear_law, kw["contact_type"], kw["coefficients"], kw["obstacle_coefficients"],
            kw["materials"], kw["obstacle_wear"], kw["force_max"], kw["speed_max"], files)
        kw.update(dimensions=dict(kw["dimensions"] or {}), law=wear_law.name,
                  coefficients=mobile, obstacle_coefficients=obstacle, coefficient_files=files,
                  initial_state=state, initial_table=label)
        return cls._from_flat(kw)

    def __post_init__(self) -> None:
        """Normalise the values and check every rule between them (the one place)."""
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        if self.name is not None and not isinstance(self.name, str):
            raise InputError(f"name must be a string, got {self.name!r}")
        law = get_law(self.law)
        put("law", law.name)
        sector_radius = None
        if self.contact_type is None:
            if self.sectors is None:
                raise KeywordError("contact_type (CONTACT) is required: the depths need the "
                                   "contact geometry (only sector depths can do without it)")
            if self.materials is not None:
                raise KeywordError("materials (MATER_USURE) need a contact_type (CONTACT): the "
                                   "database is keyed by it")
            geometry = sector_geometry(**dict(self.dimensions or {}))
        else:
            dims = dict(self.dimensions or {})
            if self.sectors is not None:
                check_sector_contact(self.contact_type)
                dims, sector_radius = sector_obstacle_radius(self.contact_type, dims)
            geometry = contact_geometry(self.contact_type, **dims)
        put("contact_type", geometry.contact_type)
        dims = geometry.dimensions()
        if sector_radius is not None:
            dims["obstacle_radius"] = sector_radius  # the sectors' (theory §3), not the type's
        put("dimensions", FrozenMap(dims))
        put("coefficients", coefficient_map(self.coefficients, "mobile"))
        if self.obstacle_coefficients is not None:
            put("obstacle_coefficients",
                coefficient_map(self.obstacle_coefficients, "obstacle"))
        for field, kind in (("window", PowerWindow), ("restart", Restart), ("wall", Wall)):
            if not isinstance(getattr(self, field), kind):
                raise InputError(f"{field} must be a {kind.__name__}, got "
                                 f"{type(getattr(self, field)).__name__}")
        state = self.restart.table
        put("instants", normalised_instants(self.instants, state is not None))
        for name, value in time_values(self).items():
            put(name, value)
        check_restart_unit(self, state)
        for values in (material_values(self), history_values(self, law),
                       sector_values(self, law, geometry, state)):
            for name, value in values.items():
                put(name, value)
        check_wall(self)

    # ----------------------------------------------------------------------- derived values
    @property
    def time_label(self) -> str:
        """The time unit as the tables and outputs name it: :attr:`time_unit`, else
        ``"<time_scale> s"`` (read back by :func:`fretwear.timeunits.unit_seconds`).

        >>> WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0], time_scale=3600.0,
        ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02}).time_label
        '3600 s'
        """
        return self.time_unit or f"{self.time_scale:g} s"

    @property
    def wear_law(self):
        """The :class:`~fretwear.laws.WearLaw` of :attr:`law`."""
        return WEAR_LAWS[self.law]

    @property
    def geometry(self):
        """The contact geometry (:func:`fretwear.geometry.contact_geometry`), or the sector
        dimensions alone without a contact type (:class:`~fretwear.geometry.sectors.
        SectorGeometry`)."""
        if self.contact_type is None:
            return SectorGeometry(**self.dimensions)
        if self.sectors is None:  # the radius is kept beside a type without one for sectors only
            return contact_geometry(self.contact_type, **self.dimensions)
        dims, _ = sector_obstacle_radius(self.contact_type, self.dimensions)
        return contact_geometry(self.contact_type, **dims)

    @property
    def power_options(self) -> dict[str, Any]:
        """The keywords of :func:`fretwear.power.wear_power` this case asks for: the window
        ``t_start``, ``t_end`` [s], ``blocks``, ``sectors``, ``stationarity_threshold``, and
        ``kwu`` = (FNOR_MAXI [N], VTAN_MAXI [m/s]) for a law that counts KWU-EPRI classes
        (either may be None: the window's maxima), None for another law.

        Examples
        --------
        >>> case = WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0], blocks=4,
        ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
        ...     coefficients={"COEF_USURE": 1e-14})
        >>> case.power_options["blocks"], case.power_options["kwu"]
        (4, None)
        """
        w = self.window
        return dict(t_start=w.t_start, t_end=w.t_end, blocks=w.blocks,
                    sectors=self.sectors, stationarity_threshold=w.stationarity_threshold,
                    kwu=(self.force_max, self.speed_max) if self.wear_law.needs_history
                    else None)

    @property
    def origin(self) -> float:
        """ORIG_INST of the new rows [user time unit]: 0, or the restart state's origin."""
        return self.restart.origin

    @functools.cached_property
    def sector_edges(self) -> np.ndarray | None:
        """The sector edges [deg], or None without sectors: computed once per case (every
        table of a bundle's contact reads them), read-only."""
        if self.sectors is None:
            return None
        edges = sector_edges(self.sectors)
        edges.flags.writeable = False
        return edges

    def derived(self, key: Any, make: Callable[[], Any]) -> Any:
        """A value derived from this case alone, made once per case: ``make()`` at the first
        call with ``key`` (hashable), the same object after (the case is immutable, so the
        value never goes stale). The one place for a case's derived values, e.g. its depth
        models' parts (:mod:`fretwear.table.depth_build`) and a bundle record's plain attrs
        (:mod:`fretwear.bundle.tasks`); kept on the case (two cases never share them), not
        pickled (made again in another process). The value is shared: treat it as read-only.

        >>> case = WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0],
        ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02})
        >>> case.derived("twice", lambda: [2.0]) is case.derived("twice", list)
        True
        """
        memo = self.__dict__.get("_derived")
        if memo is None:
            memo = {}
            object.__setattr__(self, "_derived", memo)
        try:
            return memo[key]
        except KeyError:
            value = memo[key] = make()
            return value

    def coefficient_values(self, body: str = "mobile") -> dict[str, Any] | None:
        """The coefficients of ``body`` (``"mobile"`` or ``"obstacle"``) as a plain dict of
        values (None: that body does not wear)."""
        coefs = self.coefficients if body == "mobile" else self.obstacle_coefficients
        return None if coefs is None else {k: c.value for k, c in coefs.items()}

    @property
    def coefficient_sources(self) -> dict[str, str]:
        """``"<body>.<coefficient>"`` -> source, for both bodies."""
        out = {f"mobile.{k}": c.source for k, c in self.coefficients.items()}
        for k, c in (self.obstacle_coefficients or {}).items():
            out[f"obstacle.{k}"] = c.source
        return out

    def replace(self, **changes: Any) -> WearCase:
        """A copy with some fields changed, validated again: the case's fields (``wall=``,
        ``window=``, ``restart=``, ...) or the flat keywords of the case file and of
        :meth:`to_dict` (``wall_thickness=``, ``t_start=``, ``initial_state=``, ...)."""
        flat = self._flat()
        for group, (_, names) in _GROUPS.items():
            if group in changes:
                value = changes.pop(group)
                flat.update({key: getattr(value, attr) for key, attr in names.items()})
        unknown = sorted(set(changes) - set(flat))
        if unknown:
            raise KeywordError(f"unknown wear-case key(s) {unknown}; a wear case has "
                               f"{sorted(flat)} (or {sorted(_GROUPS)})")
        flat.update(changes)
        return self._from_flat(flat)

    def with_initial_state(self, table, initial_instant: float | None = None) -> WearCase:
        """The same case continuing ``table`` (a wear table, its file or an InitialState) from
        ``initial_instant`` [user time unit] (default its last instant): ETAT_INIT."""
        state, label = _restart_state(table, initial_instant)
        return self.replace(initial_state=state, initial_instant=initial_instant,
                            initial_table=label)

    def _flat(self) -> dict[str, Any]:
        """The case as the flat keys of :meth:`to_dict`, in their order (values as they are)."""
        out = {}
        for name in FLAT_KEYS:
            group = _GROUP_OF.get(name)
            out[name] = getattr(self, name) if group is None else \
                getattr(getattr(self, group), _GROUPS[group][1][name])
        return out

    @classmethod
    def _from_flat(cls, flat: Mapping[str, Any]) -> WearCase:
        """The case of the flat keys of :meth:`to_dict`, grouped and validated."""
        flat = dict(flat)
        grouped = {group: kind(**{attr: flat.pop(key) for key, attr in names.items()
                                  if key in flat})
                   for group, (kind, names) in _GROUPS.items()}
        return cls(**flat, **grouped)

    # ----------------------------------------------------------------------- dict / JSON
    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dict of the case (NaN written as None); :meth:`from_dict` rebuilds it.

        Examples
        --------
        >>> case = WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0],
        ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
        ...     coefficients={"COEF_USURE": 1e-14})
        >>> case.to_dict()["coefficients"]
        {'coefficient': {'value': 1e-14, 'source': 'user'}}
        """
        made = self.__dict__.get("_as_dict")  # the case is immutable: made once it is reused
        if made is None:
            fresh = self._make_dict()
            if not self.__dict__.get("_dict_made"):  # a case asked once (wear_table(**kw)):
                object.__setattr__(self, "_dict_made", True)  # its dict, nothing kept
                return fresh
            made = fresh
            object.__setattr__(self, "_as_dict", made)
        return _copied(made)

    def _make_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"format": FORMAT}
        for name, value in self._flat().items():
            if name in ("coefficients", "obstacle_coefficients"):
                value = None if value is None else {
                    k: {"value": c.value, "source": c.source} for k, c in value.items()}
            elif name == "initial_state":  # JSON-ready already: not walked again
                out[name] = None if value is None else state_to_dict(value)
                continue
            out[name] = jsonable(value)
        return out

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)  # pickled without the dict of to_dict (made again)
        state.pop("_as_dict", None)
        state.pop("_dict_made", None)
        state.pop("sector_edges", None)  # made again, read-only
        state.pop("_derived", None)  # its derived values (derived): made again
        return state

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> WearCase:
        """The case of :meth:`to_dict` (or of its JSON), validated again.

        Raises
        ------
        KeywordError
            A key that is not a field of the case, or another format.
        """
        data = dict(data)
        fmt = data.pop("format", FORMAT)
        if fmt != FORMAT:
            raise KeywordError(f"not a wear case of this version: format {fmt!r}, expected "
                               f"{FORMAT!r}")
        unknown = sorted(set(data) - set(FLAT_KEYS))
        if unknown:
            raise KeywordError(f"unknown wear-case key(s) {unknown}; a wear case has "
                               f"{sorted(FLAT_KEYS)}")
        if data.get("initial_state") is not None:
            data["initial_state"] = state_from_dict(data["initial_state"])
        for name in ("materials", "coefficient_files"):
            if data.get(name) is not None:
                data[name] = tuple(data[name])
        if isinstance(data.get("sectors"), list):
            data["sectors"] = tuple(data["sectors"])
        if data.get("sector_coefficients") is not None:
            data["sector_coefficients"] = tuple(tuple(p) for p in data["sector_coefficients"])
        return cls._from_flat(data)

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text (floats round-trip exactly)."""
        return json.dumps(self.to_dict(), allow_nan=False)

    @classmethod
    def from_json(cls, text: str) -> WearCase:
        """The case of :meth:`to_json`'s text."""
        return cls.from_dict(json.loads(text))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, WearCase):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        return hash(self.to_json())


WearCase.from_keywords.__func__.__doc__ = WearCase.from_keywords.__func__.__doc__.replace(
    "{keywords}", keywords_doc(8))
