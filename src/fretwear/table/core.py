"""The wear operator: the service-life table of a contact (theory §3, §7).

:func:`wear_table` turns a wear power (or a contact history, from which the power is computed),
a wear law and a contact geometry into the table of worn volumes and depths at the instants of
service the user asks for, optionally per angular sector, optionally continuing an earlier table
(restart, Code_Aster's ETAT_INIT) and optionally with the tube replaced on the way (TUBE_NEUF).

Column names are native (:data:`COLUMNS`); :func:`to_aster_names` / :func:`from_aster_names`
convert to and from Code_Aster's POST_USURE names. Reading previous tables, the restart state
and the tube replacement are in :mod:`fretwear.table`.

Conventions of the table (one row per instant, or per instant and sector):

* ``instant`` is in the user's time unit; the laws use ``t = instant × time_scale`` [s].
* ``volume_mobile``/``volume_obstacle`` are the *cumulated* volumes of the bodies in place at
  that instant (initial state included; the tube's restart from zero at a replacement) [m³];
  ``depth_*`` are computed from them by the contact geometry (theory §6).
* In sector mode ``volume_*_sector`` is the volume worn in the sector over ``duration`` (since
  ``origin``, by the tube in place), ``volume_*_cumulated`` the sector's cumulated volume and
  ``depth_*_sector`` the sector depth from it (theory §3); ``volume_*`` is then the sum over
  sectors of the cumulated volumes.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from fretwear.database import lookup
from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.geometry import contact_geometry
from fretwear.geometry.sectors import sector_depth_mobile, sector_depth_obstacle
from fretwear.history import ContactHistory
from fretwear.io import read_history
from fretwear.laws import WEAR_LAWS
from fretwear.power import wear_power
from fretwear.table.restart import InitialState
from fretwear.table.restart import initial_state as _initial_state
from fretwear.table.schema import (  # noqa: F401 - re-exported
    _TIME_TOL,
    COLUMNS,
    GLOBAL_COLUMNS,
    SECTOR_COLUMNS,
    from_aster_names,
    to_aster_names,
)


# --------------------------------------------------------------------------- wear table
def _law(law: str):
    key = str(law).upper()
    if key not in WEAR_LAWS:
        raise KeywordError(f"unknown wear law {law!r} (LOI_USURE); choose one of "
                           f"{sorted(WEAR_LAWS)}")
    return WEAR_LAWS[key]


def law_coefficients(law, given: Mapping[str, Any] | None, body: str) -> dict[str, Any]:
    """The law's coefficients of one body: native names (Code_Aster keywords translated),
    defaults filled in (:meth:`fretwear.laws.WearLaw.resolve`).

    Raises
    ------
    KeywordError
        For a keyword the law does not have (naming the body and listing the accepted ones).

    Examples
    --------
    >>> law_coefficients(_law("ARCHARD"), {"COEF_USURE": 1e-13}, "mobile")
    {'coefficient': 1e-13}
    """
    try:
        return law.resolve(**dict(given or {}))
    except KeywordError as exc:
        raise KeywordError(f"{body} coefficients: {exc}") from None


def _instants(instants, restart: bool) -> np.ndarray:
    try:
        arr = np.atleast_1d(np.asarray(instants, dtype=float)).ravel()
    except (TypeError, ValueError):
        raise InputError(f"instants must be numbers (user time unit), got {instants!r}") from None
    if arr.size == 0 or not np.isfinite(arr).all():
        raise InputError(f"instants must be finite numbers and at least one, got {arr.tolist()}")
    if (arr < 0).any() or (restart and (arr <= 0).any()):
        low = "> 0 (they count from the restart origin)" if restart else ">= 0"
        raise InputError(f"instants (INST) must be {low}, got {arr.tolist()}")
    if (np.diff(arr) <= 0).any():
        raise InputError(f"instants (INST) must be strictly increasing, got {arr.tolist()}")
    return arr


def _cumulated(law, power: float, coefficients, elapsed_s: np.ndarray, previous: float,
               fresh_from_s: float | None) -> np.ndarray:
    """Cumulated volume of one body at ``elapsed_s`` seconds after the origin [m³].

    ``previous`` is the body's volume at the origin; a linear law adds ``V(P, Δt)``, another
    law continues from its equivalent time (theory §7). ``fresh_from_s`` (a replacement, seconds
    after the origin) restarts the body from zero there.
    """
    if coefficients is None:  # this body does not wear
        out = np.full(elapsed_s.shape, float(previous))
        if fresh_from_s is not None:
            out[elapsed_s >= fresh_from_s] = 0.0
        return out
    if previous == 0.0:
        out = np.asarray(law.volume(power, elapsed_s, **coefficients), dtype=float)
    else:  # linear: V0 + V(Δt); otherwise from the equivalent time of V0 (theory §7)
        out = np.asarray(law.cumulated_volume(previous, power, elapsed_s, **coefficients),
                         dtype=float)
    out = np.broadcast_to(out, elapsed_s.shape).copy()
    if fresh_from_s is not None:
        new = elapsed_s >= fresh_from_s
        out[new] = np.asarray(law.volume(power, elapsed_s[new] - fresh_from_s, **coefficients),
                              dtype=float)
    return out


def _power_of(source, history, *, t_start, t_end, blocks, sectors, stationarity_threshold):
    """(PowerResult or None, history or None, total power [W]); ``history`` goes with a
    PowerResult only (the history it was computed from)."""
    is_result = hasattr(source, "total") and hasattr(source, "blocks")
    if history is not None and (not is_result or not isinstance(history, ContactHistory)):
        raise InputError("history is the ContactHistory a PowerResult source was computed from "
                         "(for the KWU_EPRI classes); give it with a PowerResult source only")
    if isinstance(source, str | os.PathLike):
        source = read_history(source)
    if isinstance(source, ContactHistory):
        result = wear_power(source, t_start=t_start, t_end=t_end, blocks=blocks,
                            sectors=sectors, stationarity_threshold=stationarity_threshold)
        return result, source, float(result.total)
    if is_result:
        return source, history, float(source.total)
    try:
        power = float(source)
    except (TypeError, ValueError):
        raise InputError(f"source must be a wear power [W], a ContactHistory, a PowerResult or "
                         f"the path of a history file, got {type(source).__name__}") from None
    if not np.isfinite(power) or power < 0:
        raise InputError(f"the wear power (PUIS_USURE) must be finite and >= 0 [W], got {power}")
    return None, None, power


def _coefficient_pairs(sector_coefficients, n: int, mobile: float, obstacle: float | None):
    if sector_coefficients is None:
        if mobile is None:
            raise KeywordError("sector mode needs Archard coefficients: give "
                               "sector_coefficients (SECTEUR COEF_USUR_MOBILE) or coefficients")
        return np.full(n, mobile), (None if obstacle is None else np.full(n, obstacle))
    pairs = list(sector_coefficients)
    if len(pairs) == 1 and n > 1:
        pairs = pairs * n
    if len(pairs) != n:
        raise InputError(f"sector_coefficients has {len(pairs)} entries for {n} sectors; give "
                         "one (mobile, obstacle) pair [1/Pa] per sector, or one for all")
    km, ko = [], []
    for j, pair in enumerate(pairs):
        if np.isscalar(pair):
            pair = (pair, None)
        if len(pair) != 2:
            raise InputError(f"sector_coefficients[{j}] must be a (mobile, obstacle) pair "
                             f"[1/Pa], got {pair!r}")
        km.append(float(pair[0]))
        ko.append(np.nan if pair[1] is None else float(pair[1]))
    ko_arr = np.array(ko)
    if np.isnan(ko_arr).all():
        return np.array(km), None
    return np.array(km), np.nan_to_num(ko_arr, nan=0.0)


def wear_table(source, *, contact_type: str, dimensions: Mapping[str, float] | None = None,
               instants, law: str = "ARCHARD",
               coefficients: Mapping[str, float] | None = None,
               obstacle_coefficients: Mapping[str, float] | None = None,
               materials: tuple[str, str] | None = None, obstacle_wear: bool = False,
               sectors=None, sector_coefficients=None, time_scale: float = 1.0,
               initial_state=None,
               initial_instant: float | None = None, tube_replacement: float | None = None,
               t_start: float | None = None, t_end: float | None = None, blocks: int = 1,
               stationarity_threshold: float = 0.1, force_max: float | None = None,
               speed_max: float | None = None,
               coefficient_files=None, history: ContactHistory | None = None) -> pd.DataFrame:
    """The service-life wear table of one contact (theory §7; Code_Aster's POST_USURE).

    Parameters
    ----------
    source : float, ContactHistory, PowerResult or path-like
        The wear power P [W] (PUIS_USURE), or a contact history (RESU_GENE) or its file, whose
        power is computed over ``[t_start, t_end]`` [s] in ``blocks`` blocks (theory §2).
    contact_type : str
        One of :data:`fretwear.geometry.CONTACT_TYPES` (CONTACT), e.g. ``"TUBE_BAV"``.
    dimensions : mapping
        Geometry in SI: ``mobile_radius`` [m], ``obstacle_radius`` [m], ``obstacle_width`` [m],
        ``tilt_angle``, ``isthmus_angle``, ``impact_angle`` [deg], whichever the type uses.
    instants : sequence of float
        Durations of service after the origin [user time unit] (INST / LIST_INST); the table's
        ``instant`` is origin + duration.
    law : str
        ``"ARCHARD"``, ``"KWU_EPRI"`` or ``"EDF_MZ"`` (LOI_USURE). Sector mode is Archard only.
    coefficients, obstacle_coefficients : mapping, optional
        Law coefficients of the mobile / obstacle (native names or Code_Aster keywords, e.g.
        ``{"COEF_USURE": 1e-14}`` [1/Pa]). The obstacle wears only if given (or
        ``obstacle_wear`` with ``materials``): otherwise its volume stays at its initial value.
    materials : (str, str), optional
        (mobile, obstacle) material pair of the coefficient database (MATER_USURE).
    obstacle_wear : bool
        Take the obstacle coefficient from the database too (USURE_OBST='OUI').
    sectors : int or sequence of float, optional
        Angular sectors (count or edges [deg]); needs a history with ``dy``/``dz``.
    sector_coefficients : sequence of (float, float or None), optional
        Archard coefficients (mobile, obstacle) [1/Pa] per sector (one pair for all allowed);
        default the law coefficients.
    time_scale : float
        Seconds per user time unit [s] (COEF_INST), e.g. 31 536 000 for years.
    initial_state : DataFrame, path-like or fretwear.table.InitialState, optional
        Previous wear table to continue (ETAT_INIT / TABL_USURE), ours or Code_Aster's.
    initial_instant : float, optional
        INST_INIT [user time unit]: continue from this instant of ``initial_state``.
    tube_replacement : float, optional
        Instant [user time unit] at which the tube is replaced by a new one (TUBE_NEUF): from it
        on the tube's volumes restart from zero, the obstacle's continue.
    t_start, t_end : float, optional
        Window of the history [s] (INST_INIT/INST_FIN of RESU_GENE).
    blocks : int
        Number of blocks of the power computation (NB_BLOC).
    stationarity_threshold : float
        Relative block spread above which a StationarityWarning is raised [-].
    force_max, speed_max : float, optional
        KWU_EPRI class ranges FNOR_MAXI [N] and VTAN_MAXI [m/s] (default: the history's maxima).
    coefficient_files : path-like or sequence of path-like, optional
        The user's coefficient CSV file(s), in the format of :mod:`fretwear.database`
        (docs/laws.md), extending and overriding the built-in table for ``materials``; a later
        file wins over an earlier one (``lookup(..., extra=coefficient_files)``). A fretwear
        extension: POST_USURE has no such keyword.
    history : ContactHistory, optional
        With a PowerResult ``source``, the history it was computed from: the KWU_EPRI law reads
        its force/speed classes over ``[t_start, t_end]`` without computing the power again.

    Returns
    -------
    pandas.DataFrame
        Native columns (:data:`COLUMNS`), one row per instant (or instant and sector), preceded
        by the initial table's rows up to the origin on a restart. ``attrs`` holds the run's
        metadata.

    Raises
    ------
    KeywordError
        Unknown law, missing coefficient, sector mode with a non-Archard law,
        ``coefficient_files`` without ``materials``.
    InputError
        Bad instants, sector count differing from the initial table's, replacement before the
        origin, a coefficient file that does not exist (a malformed one is a FormatError),
        ``history`` without a PowerResult ``source``.

    Notes
    -----
    Per body, with ``t = duration × time_scale`` and ``V₀`` the volume at the origin:
    ``V(t) = V₀ + V_law(P, t)`` for a law linear in time, ``V(t) = V_law(P, τ₀ + t)`` with
    ``V_law(P, τ₀) = V₀`` otherwise (theory §7). Sectors: ``V_j = k_j·P_j·t`` (theory §3).
    Depths always come from the cumulated volumes (theory §6, §3).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §7.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §6 ("actualisation du
           tableau": updating the table).

    Examples
    --------
    >>> t = wear_table(0.01, contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...                dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...                coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> t["volume_mobile"].tolist()  # K·P·t
    [3.6e-13, 7.2e-13]
    """
    law_obj = _law(law)
    files = _coefficient_files(coefficient_files, materials)
    restart = initial_state is not None
    if initial_instant is not None and not restart:
        raise KeywordError("initial_instant (INST_INIT of ETAT_INIT) needs an initial_state "
                           "(TABL_USURE): give the table to continue")
    durations = _instants(instants, restart)
    time_scale = float(time_scale)
    if not np.isfinite(time_scale) or time_scale <= 0:
        raise InputError(f"time_scale (COEF_INST) must be > 0 [s per unit], got {time_scale}")
    if restart and not isinstance(initial_state, InitialState):
        state = _initial_state(initial_state, initial_instant)
    else:
        state = initial_state
    origin = 0.0 if state is None else state.origin

    result, history, power = _power_of(
        source, history, t_start=t_start, t_end=t_end, blocks=blocks, sectors=sectors,
        stationarity_threshold=stationarity_threshold)
    sector_mode = result is not None and getattr(result, "sectors", None) is not None
    if sectors is not None and not sector_mode:
        raise InputError("sectors need a contact history with dy and dz (RESU_GENE): a power "
                         "alone (PUIS_USURE) has no contact angle")

    mobile, obstacle, sources = _resolve_coefficients(
        law_obj, contact_type, coefficients, obstacle_coefficients, materials, obstacle_wear,
        history, t_start, t_end, force_max, speed_max, files)

    geometry = contact_geometry(contact_type, **dict(dimensions or {}))
    fresh = None
    if tube_replacement is not None:
        if tube_replacement < origin - _TIME_TOL * max(1.0, abs(origin)):
            raise InputError(f"tube_replacement (TUBE_NEUF) at {tube_replacement:g} is before "
                             f"the origin {origin:g} of this run; replace the tube in the initial "
                             "table with replace_tube() instead")
        fresh = (float(tube_replacement) - origin) * time_scale
    elapsed = durations * time_scale
    n = durations.size
    replaced = np.zeros(n, bool) if fresh is None else elapsed >= fresh

    def body_volumes(pw, prev_m, prev_o, k_m=None, k_o=None):
        cm = mobile if k_m is None else {law_obj.parameters[0]: k_m}
        co = obstacle if k_m is None else (None if k_o is None else {law_obj.parameters[0]: k_o})
        vm = _cumulated(law_obj, pw, cm, elapsed, prev_m, fresh)
        vo = _cumulated(law_obj, pw, co, elapsed, prev_o, None)
        return vm, vo

    head = {"instant": origin + durations, "duration": durations,
            "origin": np.full(n, origin), "power": np.full(n, power)}
    if not sector_mode:
        if state is not None and state.sector_count:
            raise InputError(f"the initial wear table has {state.sector_count} sectors and this "
                             "run has none; the number of sectors must match")
        prev_m = 0.0 if state is None else state.volume_mobile
        prev_o = 0.0 if state is None else state.volume_obstacle
        vm, vo = body_volumes(power, prev_m, prev_o)
        dm, do = _depths(geometry, vm, vo)
        frame = pd.DataFrame({**head, "volume_mobile": vm, "volume_obstacle": vo,
                              "depth_mobile": dm, "depth_obstacle": do})
        edges = None
    else:
        frame, edges = _sector_frame(head, result, law_obj, mobile, obstacle, sector_coefficients,
                                     state, body_volumes, geometry, replaced, n)
    if state is not None and len(state.rows):
        frame = pd.concat([state.rows.reindex(columns=frame.columns), frame],
                          ignore_index=True)
    frame.attrs = {
        "contact_type": str(contact_type).upper(), "dimensions": _dimensions_dict(geometry),
        "law": law_obj.name, "coefficients_mobile": mobile, "coefficients_obstacle": obstacle,
        "materials": None if materials is None else list(materials),
        "coefficient_files": files, "coefficient_sources": sources,
        "sector_edges": None if edges is None else edges.tolist(), "time_scale": time_scale,
        "origin": origin, "tube_replacement": tube_replacement,
        "power": None if result is None else _power_dict(result),
    }
    return frame


def _depths(geometry, volume_mobile: np.ndarray, volume_obstacle: np.ndarray):
    """(mobile, obstacle) depths [m] from the cumulated volumes [m³] (theory §6).

    An obstacle without volume has no depth: exactly 0 where the mobile's depth is defined
    (the split d_o = D − D·V_m/V of a shared trace leaves a rounding residue otherwise).
    """
    dm, do = geometry.depth_from_volume(volume_mobile, volume_obstacle)
    dm = np.broadcast_to(dm, volume_mobile.shape).astype(float)
    do = np.broadcast_to(do, volume_mobile.shape).astype(float)
    return dm, np.where((volume_obstacle == 0) & np.isfinite(dm), 0.0, do)


def _dimensions_dict(geometry) -> dict:
    """The geometry's dimensions with native names (SI, angles in degrees), for ``attrs``."""
    out = dict(geometry.to_dict())
    out.pop("contact_type", None)
    return out


def _power_dict(result) -> dict:
    try:
        return dict(result.to_dict())
    except Exception:  # noqa: BLE001 - metadata only
        return {"total": float(result.total)}


def _sector_frame(head, result, law, mobile, obstacle, sector_coefficients, state,
                  body_volumes, geometry, replaced, n):
    if law.name != "ARCHARD" or len(law.parameters) != 1:
        raise KeywordError(f"sector mode (SECTEUR) takes Archard coefficients per sector; the "
                           f"{law.name} law cannot be used with sectors")
    edges = np.asarray(result.sector_edges, dtype=float)
    powers = np.asarray(result.sectors, dtype=float)
    m = powers.size
    if state is not None:
        if state.sector_count != m:
            raise InputError(f"the initial wear table has {state.sector_count} sectors and this "
                             f"run has {m}; the number of sectors must match")
        if not np.allclose(state.edges, edges, atol=1e-6):
            raise InputError(f"the initial wear table's sector edges {state.edges.tolist()} "
                             f"differ from this run's {edges.tolist()} [deg]; use the same")
    key = law.parameters[0]
    k_m, k_o = _coefficient_pairs(sector_coefficients, m, mobile.get(key),
                                  None if obstacle is None else obstacle.get(key))
    r_m = getattr(geometry, "mobile_radius", None)
    r_o = getattr(geometry, "obstacle_radius", None)
    width = getattr(geometry, "obstacle_width", None)
    if r_m is None or width is None:
        raise KeywordError("sector depths need mobile_radius (RAYON_MOBILE) and obstacle_width "
                           "(LARGEUR_OBST); give them in the dimensions")
    cols = {c: [] for c in SECTOR_COLUMNS if c not in GLOBAL_COLUMNS}
    cum_m = np.zeros((n, m))
    cum_o = np.zeros((n, m))
    unradiused: list[int] = []
    for j in range(m):
        pm = 0.0 if state is None else float(state.sector_volume_mobile[j])
        po = 0.0 if state is None else float(state.sector_volume_obstacle[j])
        vm, vo = body_volumes(powers[j], pm, po, k_m[j], None if k_o is None else k_o[j])
        cum_m[:, j], cum_o[:, j] = vm, vo
        arc = edges[j + 1] - edges[j]
        was_m = np.where(replaced, 0.0, pm)  # a replaced tube starts from zero
        cols["sector"].append(np.full(n, j + 1))
        cols["angle_start"].append(np.full(n, edges[j]))
        cols["angle_end"].append(np.full(n, edges[j + 1]))
        cols["sector_power"].append(np.full(n, powers[j]))
        cols["volume_mobile_sector"].append(vm - was_m)
        cols["volume_obstacle_sector"].append(vo - po)
        cols["depth_mobile_sector"].append(sector_depth_mobile(vm, r_m, width, arc))
        if r_o is None:
            if (vo > 0).any():
                unradiused.append(j + 1)
            cols["depth_obstacle_sector"].append(np.where(vo == 0, 0.0, np.nan))
        else:
            cols["depth_obstacle_sector"].append(sector_depth_obstacle(vo, r_o, width, arc))
        cols["volume_mobile_cumulated"].append(vm)
        cols["volume_obstacle_cumulated"].append(vo)
    if unradiused:
        warnings.warn(f"sectors {unradiused}: the obstacle wears but {geometry.contact_type} has "
                      "no obstacle_radius (RAYON_OBST): their obstacle sector depth is NaN",
                      RangeWarning, stacklevel=3)
    total_m, total_o = cum_m.sum(axis=1), cum_o.sum(axis=1)
    dm, do = _depths(geometry, total_m, total_o)
    glob = {"volume_mobile": total_m, "volume_obstacle": total_o,
            "depth_mobile": dm, "depth_obstacle": do}
    data = {k: np.repeat(np.asarray(v), m) for k, v in {**head, **glob}.items()}
    for c, parts in cols.items():  # instant-major order: row = i*m + j
        data[c] = np.column_stack(parts).ravel()
    return pd.DataFrame({c: data[c] for c in SECTOR_COLUMNS}), edges


def _coefficient_files(files, materials) -> list[str] | None:
    """The user's coefficient files as a list of path strings (None for none), each checked to
    exist; they only make sense with a database pair."""
    if files is None:
        return None
    items = [files] if isinstance(files, str | os.PathLike) else list(files)
    if not items:
        return None
    for item in items:
        if not isinstance(item, str | os.PathLike):
            raise InputError(f"coefficient_files must be paths of CSV files, got {item!r}")
        if not Path(item).is_file():
            raise InputError(f"coefficient file {str(item)!r} (coefficient_files) does not exist; "
                             "give the path of a CSV in the coefficient-database format "
                             "(docs/laws.md)")
    if materials is None:
        raise KeywordError("coefficient_files extend the coefficient database, which is read for "
                           "materials (MATER_USURE) only: give materials too, or the "
                           "coefficients directly")
    return [os.fspath(item) for item in items]


def _resolve_coefficients(law, contact_type, coefficients, obstacle_coefficients, materials,
                          obstacle_wear, history, t_start, t_end, force_max, speed_max,
                          coefficient_files=None):
    """(mobile coefficients, obstacle coefficients or None, database sources or None) of the
    law, native names."""
    sources = None
    given_m = dict(coefficients or {})
    given_o = None if obstacle_coefficients is None else dict(obstacle_coefficients)
    if materials is not None:
        if coefficients is not None:
            raise KeywordError("give either coefficients (MOBILE) or materials (MATER_USURE), "
                               "not both")
        if obstacle_coefficients is not None:
            raise KeywordError("materials (MATER_USURE) excludes obstacle_coefficients "
                               "(OBSTACLE): ask for obstacle_wear (USURE_OBST) instead")
        if len(materials) != 2:
            raise InputError(f"materials must be a (mobile, obstacle) pair, got {materials!r}")
        given_m, found_o, sources = _database(contact_type, materials, law.name, obstacle_wear,
                                              coefficient_files)
        if obstacle_wear:
            if not found_o:
                raise KeywordError(
                    f"obstacle_wear (USURE_OBST='OUI') asked for, but the database has no "
                    f"obstacle coefficient for {contact_type} {materials[0]}/{materials[1]} "
                    f"({law.name}); give obstacle_coefficients instead")
            given_o = found_o
    elif obstacle_wear:
        raise KeywordError("obstacle_wear (USURE_OBST) takes the obstacle coefficient from the "
                           "database: give materials (MATER_USURE) too")
    extra = {k: v for k, v in (("force_max", force_max), ("speed_max", speed_max))
             if v is not None}
    if extra and not law.needs_history:
        raise KeywordError(f"force_max/speed_max (FNOR_MAXI/VTAN_MAXI) belong to KWU_EPRI, "
                           f"not to {law.name}")
    mobile = law_coefficients(law, {**given_m, **extra}, "mobile")
    obstacle = None if given_o is None else law_coefficients(law, {**given_o, **extra},
                                                             "obstacle")
    if law.needs_history:
        if history is None:
            raise KeywordError(f"the {law.name} law needs the contact history's force/speed "
                               "classes: give a history (RESU_GENE), or history= with a "
                               "PowerResult, not a power alone (PUIS_USURE)")
        for coefs in (mobile, obstacle):
            if coefs is not None and coefs.get("intensity") is None:
                stats = law.statistics(history, t_start=t_start, t_end=t_end, **coefs)
                coefs["intensity"] = float(stats.intensity)
    return mobile, obstacle, sources


def _database(contact_type, materials, law_name, obstacle_wear, coefficient_files=None
              ) -> tuple[dict, dict | None, dict]:
    """(mobile, obstacle, sources) coefficient dicts of a database pair (theory §5), the user's
    coefficient files extending the built-in table."""
    found = lookup(contact_type, materials[0], materials[1], law_name,
                   obstacle=bool(obstacle_wear), extra=coefficient_files)
    return (dict(found.mobile), dict(found.obstacle) if found.obstacle else None,
            dict(found.sources))
