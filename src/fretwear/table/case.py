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
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, KeywordError
from fretwear.geometry import check_sector_contact, contact_geometry, sector_obstacle_radius
from fretwear.geometry.sectors import SectorGeometry, sector_geometry
from fretwear.io.geometry_units import check_absolute_sizes, check_wall_thickness
from fretwear.laws import WEAR_LAWS, get_law
from fretwear.sectors import sector_edges
from fretwear.table._serial import FrozenMap, jsonable, state_from_dict, state_to_dict
from fretwear.table.case_values import PowerWindow, Restart, Wall, _real
from fretwear.table.coefficients import (
    USER,
    Coefficient,
    coefficient_file_paths,
    law_coefficients,
    laws_with,
    material_pair,
    plain,
    resolve_coefficients,
    sector_parameter,
)
from fretwear.table.keywords import KEYWORDS, check_keywords, keywords_doc
from fretwear.table.restart import InitialState
from fretwear.table.restart import initial_state as _read_initial_state
from fretwear.timeunits import TIME_UNITS, time_unit_name, unit_seconds

__all__ = ["Coefficient", "PowerWindow", "Restart", "Wall", "WearCase", "law_coefficients"]

#: The Code_Aster names of the KWU-EPRI class ranges given as separate keywords.
_HISTORY_KEYWORDS = {"force_max": "FNOR_MAXI", "speed_max": "VTAN_MAXI"}
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


def _instants(instants, restart: bool) -> tuple[float, ...]:
    try:
        arr = np.atleast_1d(np.asarray(instants, dtype=float)).ravel()
    except OverflowError:  # a 400-digit integer
        raise InputError(f"instants must be finite numbers, got one beyond the float range "
                         f"({str(instants)[:40]}...)") from None
    except (TypeError, ValueError):
        raise InputError(f"instants must be numbers (user time unit), got {instants!r}") from None
    if arr.size == 0 or not np.isfinite(arr).all():
        raise InputError(f"instants must be finite numbers and at least one, got {arr.tolist()}")
    if (arr < 0).any() or (restart and (arr <= 0).any()):
        low = "> 0 (they count from the restart origin)" if restart else ">= 0"
        raise InputError(f"instants (INST) must be {low}, got {arr.tolist()}")
    if (np.diff(arr) <= 0).any():
        raise InputError(f"instants (INST) must be strictly increasing, got {arr.tolist()}")
    return tuple(arr.tolist())


def _coefficient_map(value, body: str) -> FrozenMap:
    if not isinstance(value, Mapping):
        raise InputError(f"{body} coefficients must be a mapping name -> Coefficient, got "
                         f"{type(value).__name__}")
    out = {}
    for name, c in value.items():
        if isinstance(c, Mapping):
            c = Coefficient(plain(c.get("value")), str(c.get("source", USER)))
        elif not isinstance(c, Coefficient):
            c = Coefficient(plain(c), USER)
        out[str(name)] = c
    return FrozenMap(out)


def _sector_pairs(pairs, n: int) -> tuple[tuple[float, float | None], ...]:
    """(mobile, obstacle or None) Archard coefficients [1/Pa] of each of the ``n`` sectors."""
    pairs = list(pairs)
    if len(pairs) == 1 and n > 1:
        pairs = pairs * n
    if len(pairs) != n:
        raise InputError(f"sector_coefficients has {len(pairs)} entries for {n} sectors; give "
                         "one (mobile, obstacle) pair [1/Pa] per sector, or one for all")
    out = []
    for j, pair in enumerate(pairs):
        if np.isscalar(pair):
            pair = (pair, None)
        if len(pair) != 2:
            raise InputError(f"sector_coefficients[{j}] must be a (mobile, obstacle) pair "
                             f"[1/Pa], got {pair!r}")
        out.append((float(pair[0]), None if pair[1] is None else float(pair[1])))
    return tuple(out)


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
        return {k: _copied(v) for k, v in value.items()}
    if type(value) is list:
        return [_copied(v) for v in value]
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
        put("coefficients", _coefficient_map(self.coefficients, "mobile"))
        if self.obstacle_coefficients is not None:
            put("obstacle_coefficients", _coefficient_map(self.obstacle_coefficients, "obstacle"))
        for field, kind in (("window", PowerWindow), ("restart", Restart), ("wall", Wall)):
            if not isinstance(getattr(self, field), kind):
                raise InputError(f"{field} must be a {kind.__name__}, got "
                                 f"{type(getattr(self, field)).__name__}")
        state = self.restart.table
        put("instants", _instants(self.instants, state is not None))
        self._check_time()
        self._check_restart_unit(state)
        self._check_materials()
        self._check_history_keywords(law)
        self._check_sectors(law, geometry, state)
        self._check_wall()

    def _check_time(self) -> None:
        try:
            scale = float(self.time_scale)
        except (TypeError, ValueError):
            scale = math.nan
        if not math.isfinite(scale) or scale <= 0:
            raise InputError(f"time_scale (COEF_INST) must be > 0 [s per unit], got "
                             f"{self.time_scale!r}")
        object.__setattr__(self, "time_scale", scale)
        if self.time_unit is not None and not isinstance(self.time_unit, str):
            raise InputError(f"time_unit must be the name of the unit, got {self.time_unit!r}")

    def _check_restart_unit(self, state: InitialState | None) -> None:
        """A restart's table counts time in the case's unit (its header's ``time_unit``)."""
        seconds = None if state is None else unit_seconds(state.time_unit)
        if seconds is None or math.isclose(seconds, self.time_scale, rel_tol=1e-2) or (
                self.time_unit is not None
                and time_unit_name(self.time_unit) == time_unit_name(state.time_unit)):
            return  # the same unit (a year of 365 or 365.25 days alike): only a slip is refused
        table = f" {self.restart.source}" if self.restart.source else ""
        name = time_unit_name(state.time_unit)
        key = (f'unit = "{name}"' if name in TIME_UNITS
               else f"seconds_per_unit = {seconds:g}")
        raise InputError(
            f"the initial wear table{table} counts time in {state.time_unit!r} ({seconds:g} s, "
            f"its header's time_unit) and this case in {self.time_label!r} ({self.time_scale:g} "
            "s): its instants would be read in the wrong unit. Give the case the table's unit "
            f"({key} in a case file's [time], time_scale={seconds:g} in Python), or restart "
            "from a table written in the case's unit")

    def _check_materials(self) -> None:
        if self.materials is not None:
            object.__setattr__(self, "materials", material_pair(self.materials))
        if not isinstance(self.obstacle_wear, bool | np.bool_):
            raise InputError(f"obstacle_wear (USURE_OBST) must be True or False, got "
                             f"{self.obstacle_wear!r}")
        object.__setattr__(self, "obstacle_wear", bool(self.obstacle_wear))
        if self.obstacle_wear and self.materials is None:
            raise KeywordError("obstacle_wear (USURE_OBST) takes the obstacle coefficient from "
                               "the database: give materials (MATER_USURE) too")
        if self.coefficient_files is not None:
            files = tuple(os.fspath(f) for f in self.coefficient_files) or None
            object.__setattr__(self, "coefficient_files", files)
            if files and self.materials is None:
                raise KeywordError("coefficient_files extend the coefficient database, which is "
                                   "read for materials (MATER_USURE) only: give materials too, "
                                   "or the coefficients directly")

    def _check_history_keywords(self, law) -> None:
        """The class ranges FNOR_MAXI/VTAN_MAXI belong to laws with history statistics."""
        for name, keyword in _HISTORY_KEYWORDS.items():
            value = getattr(self, name)
            if value is None:
                continue
            if name not in law.accepted:
                owners = laws_with(lambda lw, n=name: n in lw.accepted)
                raise KeywordError(f"{keyword} belongs to LOI_USURE={owners}, not {law.name}: "
                                   f"remove {name} ({keyword}), a class range of the history "
                                   "statistics")
            object.__setattr__(self, name, _real(value, f"{name} ({keyword})"))

    def _check_sectors(self, law, geometry, state: InitialState | None) -> None:
        if self.sectors is None:
            if self.sector_coefficients is not None:
                raise KeywordError("sector_coefficients (SECTEUR COEF_USUR_MOBILE/COEF_USUR_OBST) "
                                   "need sectors: give sectors= (a count or edges [deg])")
            if state is not None and state.sector_count:
                raise InputError(f"the initial wear table has {state.sector_count} sectors and "
                                 "this run has none; the number of sectors must match")
            return
        spec = self.sectors
        if isinstance(spec, int | np.integer) and not isinstance(spec, bool):
            spec = int(spec)
        elif not isinstance(spec, bool):
            try:
                spec = tuple(float(v) for v in np.asarray(spec, dtype=float).ravel())
            except (TypeError, ValueError):
                pass  # sector_edges names the problem
        edges = sector_edges(spec)
        object.__setattr__(self, "sectors", spec)
        if sector_parameter(law) is None:
            raise KeywordError(
                f"law {law.name!r} with sectors: SECTEUR belongs to LOI_USURE="
                f"{laws_with(lambda lw: sector_parameter(lw) is not None)} (sector tables take "
                "Archard coefficients only: V_j = k_j·P_j·t); use law='ARCHARD' or remove sectors")
        m = edges.size - 1
        if state is not None:
            if state.sector_count != m:
                raise InputError(f"the initial wear table has {state.sector_count} sectors and "
                                 f"this run has {m}; the number of sectors must match")
            if not np.allclose(state.edges, edges, atol=1e-6):
                raise InputError(f"the initial wear table's sector edges {state.edges.tolist()} "
                                 f"differ from this run's {edges.tolist()} [deg]; use the same")
        if self.sector_coefficients is not None:
            object.__setattr__(self, "sector_coefficients",
                               _sector_pairs(self.sector_coefficients, m))
        elif self.coefficients.get(sector_parameter(law)) is None or \
                self.coefficients[sector_parameter(law)].value is None:
            raise KeywordError("sector mode needs Archard coefficients: give "
                               "sector_coefficients (SECTEUR COEF_USUR_MOBILE) or coefficients")
        if getattr(geometry, "mobile_radius", None) is None or \
                getattr(geometry, "obstacle_width", None) is None:
            raise KeywordError("sector depths need mobile_radius (RAYON_MOBILE) and "
                               "obstacle_width (LARGEUR_OBST); give them in the dimensions")

    def _check_wall(self) -> None:
        """The wall is checked by :class:`Wall`; here against the tube it belongs to: a wall in
        mm typed into a metre key is thicker than the tube (issue 29)."""
        check_wall_thickness(self.wall.thickness, self.dimensions.get("mobile_radius"),
                             key="wall_thickness (wall_thickness_m in a case file or manifest)")
        check_absolute_sizes(self.dimensions, self.wall.thickness)

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
        state.pop("_model_parts", None)  # its depth models' parts (table.depth_build)
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
