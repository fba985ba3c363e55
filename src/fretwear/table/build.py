"""Building the service-life wear table of a :class:`~fretwear.table.WearCase` (theory §3, §6, §7).

:func:`wear_table_from_case` turns a wear power (or a contact history, from which the power is
computed) and a validated wear case into the table of worn volumes and depths at the instants of
service, optionally per angular sector, continuing the case's restart state and with the tube
replaced on the way. The steps, one function each:

1. :func:`_power_of`: the power [W] of the source (and the PowerResult, the history);
2. :func:`_body_coefficients`: each body's coefficients, the history's KWU-EPRI intensity added
   for a law whose registry entry says it ``needs_history``;
3. :class:`_Clock`: the elapsed seconds of each instant and the replacement;
4. :func:`_global_frame` or :func:`_sector_frame` (:mod:`fretwear.table._columns`): cumulated
   volumes and depths from them by the case's :class:`~fretwear.table.DepthModel`
   (:func:`~fretwear.table.depth.case_model`; per sector
   :func:`~fretwear.geometry.sector_depth_mobile`), as columns made a DataFrame once;
5. the initial table's rows in front; with a wall thickness, the depth as a fraction of the wall
   and the instant of reaching the limit (:func:`_wall`, :mod:`fretwear.table._wall`,
   :mod:`fretwear.table.limit`);
6. the metadata in ``attrs`` (:func:`_attrs`).

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

import functools
import os
from dataclasses import dataclass

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, KeywordError
from fretwear.history import ContactHistory
from fretwear.io.geometry_units import check_against_geometry
from fretwear.power import wear_power
from fretwear.table._columns import _frame, _global_frame, _sector_frame
from fretwear.table._wall import _wall
from fretwear.table.case import WearCase
from fretwear.table.depth_build import case_model

__all__ = ["wear_table_columns", "wear_table_from_case"]

#: Source of a coefficient computed from the contact history (KWU-EPRI's intensity w).
HISTORY = "history (class statistics over the window)"


def wear_table_from_case(case: WearCase, source, *, history: ContactHistory | None = None
                         ) -> pd.DataFrame:
    """The service-life wear table of one contact (theory §7; Code_Aster's POST_USURE).

    Parameters
    ----------
    case : WearCase
        The validated description of the computation (:meth:`WearCase.from_keywords`).
    source : float, ContactHistory, PowerResult or path-like
        The wear power P [W] (PUIS_USURE), or a contact history (RESU_GENE) or its file, whose
        power is computed over the case's ``[t_start, t_end]`` [s] in ``blocks`` blocks
        (theory §2).
    history : ContactHistory, optional
        With a PowerResult ``source``, the history it was computed from: a law that needs the
        history's class statistics (KWU_EPRI) reads them over ``[t_start, t_end]`` without
        computing the power again.

    Returns
    -------
    pandas.DataFrame
        Native columns (:data:`fretwear.table.COLUMNS`), one row per instant (or instant and
        sector), preceded by the initial table's rows up to the origin on a restart. ``attrs``
        holds the run's metadata: ``case`` (``case.to_dict()``), ``coefficient_sources`` (where
        each coefficient came from), ``power``, ``dimensions``, ...

    Raises
    ------
    InputError
        Sectors without a history with contact angles, ``history`` without a PowerResult
        ``source``, a PowerResult whose sectors differ from the case's.
    KeywordError
        A law that needs the history's statistics given a power alone.

    Notes
    -----
    Per body, with ``t = duration × time_scale`` and ``V₀`` the volume at the origin:
    ``V(t) = V₀ + V_law(P, t)`` for a law linear in time, ``V(t) = V_law(P, τ₀ + t)`` with
    ``V_law(P, τ₀) = V₀`` otherwise (theory §7). Sectors: ``V_j = k_j·P_j·t`` (theory §3).
    Depths always come from the cumulated volumes (theory §6, §3).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3, §6, §7.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §6 ("actualisation du
           tableau": updating the table).

    Examples
    --------
    >>> case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...     coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> wear_table_from_case(case, 0.01)["volume_mobile"].tolist()  # K·P·t
    [3.6e-13, 7.2e-13]
    """
    columns, frame, attrs, _ = _table_parts(case, source, history)
    if frame is None:
        frame = _frame(columns)
    frame.attrs = attrs
    return frame


def wear_table_columns(case: WearCase, source, *, history: ContactHistory | None = None,
                       attrs=None) -> tuple[dict[str, np.ndarray], dict]:
    """The columns and metadata of :func:`wear_table_from_case`, without the DataFrame.

    For a caller that only passes the table on (a bundle's worker sends each contact's table
    back to the client as arrays): the DataFrame and its column-by-column unpacking cost about
    0.2 ms a table.

    Parameters
    ----------
    case, source, history
        As :func:`wear_table_from_case`.
    attrs : iterable of str, optional
        The keys of the table's ``attrs`` wanted (default all): a caller that keeps a few
        (a bundle's worker) spares the others' making, the case's description (``case``) and
        the power's statistics (``power``) the dearest. The values of those given are the
        table's own.

    Returns
    -------
    columns : dict
        Column name -> 1-d numpy array, in the table's order, the arrays
        ``wear_table_from_case(case, source, history=history)[name].to_numpy()`` gives (the
        same values and dtypes; units in :data:`fretwear.table.COLUMNS`).
    attrs : dict
        The table's ``attrs`` (those of ``attrs`` given).

    Examples
    --------
    >>> case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...     dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...     coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> columns, attrs = wear_table_columns(case, 0.01)
    >>> columns["volume_mobile"].tolist(), attrs["law"]
    ([3.6e-13, 7.2e-13], 'ARCHARD')
    >>> wear_table_columns(case, 0.01, attrs=("law", "time_scale"))[1]
    {'law': 'ARCHARD', 'time_scale': 3600.0}
    """
    columns, frame, attrs, plain = _table_parts(case, source, history,
                                                None if attrs is None else tuple(attrs))
    if frame is None and not (plain or _plain_numeric(columns)):
        frame = _frame(columns)  # what pandas makes of other columns
    if frame is not None:
        frame.attrs = {}  # pandas would deep-copy attrs into every column it hands out
        columns = {str(c): frame[c].to_numpy() for c in frame.columns}
    return columns, attrs


def _plain_numeric(columns: dict) -> bool:
    """Whether every column is a 1-d numeric or boolean numpy array, all of one length (the
    DataFrame then holds the arrays' values and dtypes as they are)."""
    arrays = list(columns.values())
    return bool(arrays) and all(type(a) is np.ndarray and a.ndim == 1
                                and a.dtype.kind in "fiub" for a in arrays) \
        and len({a.shape for a in arrays}) == 1


def _table_parts(case: WearCase, source, history: ContactHistory | None, keys=None):
    """(columns, frame, attrs, plain) of :func:`wear_table_from_case`: the columns, or the
    frame when the initial table's rows come first (then columns is None), the metadata (its
    ``keys`` only, when given), and whether the columns are those of :func:`_sector_frame`
    alone (1-d numeric arrays of one length: :func:`_plain_numeric` need not look)."""
    if not isinstance(case, WearCase):
        raise InputError(f"case must be a WearCase (WearCase.from_keywords(...)), got "
                         f"{type(case).__name__}")
    result, history, power = _power_of(case, source, history)
    if isinstance(source, ContactHistory):  # lengths and speeds against the geometry
        check_against_geometry(source, mobile_radius=case.dimensions.get("mobile_radius"),
                               obstacle_radius=case.dimensions.get("obstacle_radius"),
                               name=case.name or "")
    case, edges = _with_run_sectors(case, result)
    mobile, obstacle, sources = _body_coefficients(case, history, result)
    geometry = _geometry(case)
    clock = _Clock(case)
    model = case_model(case, power, result, mobile, obstacle, clock.fresh, geometry)
    if case.sectors is None:
        head = {"instant": case.origin + clock.durations, "duration": clock.durations,
                "origin": np.full(clock.n, case.origin), "power": np.full(clock.n, power)}
        columns = _global_frame(model, head, clock)
    else:
        columns = _sector_frame(model, power, clock, edges)
    state = case.restart.table
    frame = None
    plain = case.sectors is not None and state is None and case.wall.thickness is None
    if state is not None and len(state.rows):
        after = _after_rows(state.rows, columns, state.row_dtypes)
        if isinstance(after, dict):
            columns = after  # the rows' columns then the run's: no DataFrame yet
        else:
            frame = after
    limit = None
    if case.wall.thickness is not None:
        wall, limit = _wall(case, columns if frame is None else frame, model)
        if frame is None:
            columns.update(wall)
        else:
            frame = frame.assign(**wall)
    attrs = _attrs(case, geometry, mobile, obstacle, sources, result, edges, keys)
    if limit is not None:
        attrs.update(limit)
    if keys is not None:
        attrs = {k: attrs[k] for k in keys if k in attrs}
    return (columns if frame is None else None), frame, attrs, plain


#: Geometries by (contact type, dimensions), at most _GEOMETRIES_KEPT (:func:`_geometry`).
_GEOMETRIES: dict = {}
_GEOMETRIES_KEPT = 256


def _geometry(case: WearCase):
    """The case's geometry (:attr:`WearCase.geometry`: validated when the case was built), one
    per distinct contact type and dimensions: a geometry is immutable, its constants computed
    once for every table of the same contact (a bundle's contacts share them)."""
    return case.derived("geometry", lambda: _shared_geometry(case))


def _shared_geometry(case: WearCase):
    """The geometry of :func:`_geometry`, one per distinct contact type and dimensions."""
    key = (case.contact_type, tuple(case.dimensions.items()))
    found = _GEOMETRIES.get(key)
    if found is None:
        found = case.geometry
        if len(_GEOMETRIES) >= _GEOMETRIES_KEPT:
            _GEOMETRIES.clear()
        _GEOMETRIES[key] = found
    return found


# --------------------------------------------------------------------------- 1. the power
def _power_of(case: WearCase, source, history):
    """(PowerResult or None, history or None, total power [W]); ``history`` goes with a
    PowerResult only (the history it was computed from)."""
    is_result = hasattr(source, "total") and hasattr(source, "blocks")
    if history is not None and (not is_result or not isinstance(history, ContactHistory)):
        raise InputError("history is the ContactHistory a PowerResult source was computed from "
                         "(for the KWU_EPRI classes); give it with a PowerResult source only")
    if isinstance(source, str | os.PathLike):
        # streamed in one pass (two for KWU_EPRI without FNOR_MAXI/VTAN_MAXI): the law's class
        # counts come with the power (result.kwu), the history is never held whole
        result = wear_power(source, **case.power_options)
        return result, None, float(result.total)
    if isinstance(source, ContactHistory):
        window = case.window
        result = wear_power(source, t_start=window.t_start, t_end=window.t_end,
                            blocks=window.blocks, sectors=case.sectors,
                            stationarity_threshold=window.stationarity_threshold)
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


def _with_run_sectors(case: WearCase, result) -> tuple[WearCase, np.ndarray | None]:
    """(the case whose sectors are the run's, its ``sector_edges`` [deg]): a PowerResult
    computed with sectors makes a sector table (checked as if the case had them); sectors need
    a power with sectors."""
    run_edges = None if result is None else getattr(result, "sector_edges", None)
    if getattr(result, "sectors", None) is None:
        run_edges = None
    if case.sectors is None:
        if run_edges is None:
            return case, None
        case = case.replace(sectors=tuple(np.asarray(run_edges, dtype=float).tolist()))
        return case, case.sector_edges
    if run_edges is None:
        raise InputError("sectors need a contact history with dy and dz (RESU_GENE): a power "
                         "alone (PUIS_USURE) has no contact angle")
    edges = case.sector_edges  # finite (checked where the case was built)
    run = np.asarray(run_edges, dtype=float)
    if not (run.shape == edges.shape and run.tobytes() == edges.tobytes()  # the same floats
            or np.array_equal(run, edges)):
        raise InputError(f"the PowerResult's sector edges {list(run_edges)} differ from the "
                         f"case's sectors {edges.tolist()} [deg]; compute the power "
                         "with the same sectors")
    return case, edges


# --------------------------------------------------------------------------- 2. coefficients
def _pass_counts(result, case: WearCase, coefs: dict):
    """The KWU-EPRI class counts of the power's pass (``result.kwu``) when they are those of
    ``coefs``'s maxima over the case's window, else None."""
    counts = getattr(result, "kwu", None)
    given = getattr(counts, "given", None)
    if given is None or given != (coefs.get("force_max"), coefs.get("speed_max")):
        return None
    # the case's window; a missing bound is the record's end (the power's window), which
    # selects the same samples as no bound at all
    for bound, power_bound, counted, open_end in (
            (case.window.t_start, result.t_start, counts.t_start, -np.inf),
            (case.window.t_end, result.t_end, counts.t_end, np.inf)):
        if counted != (power_bound if bound is None else bound) and not (
                bound is None and counted == open_end):
            return None
    return counts


def _body_coefficients(case: WearCase, history, result=None):
    """(mobile, obstacle or None, sources) coefficient dicts by native name; a law that needs
    the history's statistics gets each body's intensity from them (unless given)."""
    law = case.wear_law
    mobile = case.coefficient_values("mobile")
    obstacle = case.coefficient_values("obstacle")
    sources = case.coefficient_sources
    if law.needs_history:
        if history is None and getattr(result, "kwu", None) is None:
            raise KeywordError(f"the {law.name} law needs the contact history's force/speed "
                               "classes: give a history (RESU_GENE), or history= with a "
                               "PowerResult, not a power alone (PUIS_USURE)")
        for body, coefs in (("mobile", mobile), ("obstacle", obstacle)):
            if coefs is not None and coefs.get("intensity") is None:
                counts = _pass_counts(result, case, coefs) if history is None else None
                if counts is not None:
                    factors = law.resolve(**coefs)
                    stats = counts.result(**{k: factors[k] for k in
                                             ("impact_factor", "sliding_factor", "k", "c")})
                elif history is None:
                    raise KeywordError(
                        f"the PowerResult's KWU-EPRI class counts were made with the maxima "
                        f"{getattr(result.kwu, 'given', None)}, the {body}'s are "
                        f"{(coefs.get('force_max'), coefs.get('speed_max'))} (force_max, "
                        "speed_max): give the history too (history=)")
                else:
                    stats = law.statistics(history, t_start=case.window.t_start,
                                           t_end=case.window.t_end, **coefs)
                coefs["intensity"] = float(stats.intensity)
                sources[f"{body}.intensity"] = HISTORY
    return mobile, obstacle, sources


# --------------------------------------------------------------------------- 3. the clock
@dataclass(frozen=True)
class _Clock:
    """The run's durations [user unit], elapsed seconds [s] and the tube replacement."""

    case: WearCase

    @functools.cached_property
    def durations(self) -> np.ndarray:
        """The instants' durations since the origin [user unit] (made once a table)."""
        return np.asarray(self.case.instants, dtype=float)

    @property
    def n(self) -> int:
        return len(self.case.instants)

    @functools.cached_property
    def elapsed(self) -> np.ndarray:
        """Seconds since the origin at each instant [s]."""
        return self.durations * self.case.time_scale

    @property
    def fresh(self) -> float | None:
        """Seconds after the origin at which a new tube starts (None: no replacement) [s]."""
        at = self.case.restart.tube_replacement
        return None if at is None else (at - self.case.origin) * self.case.time_scale

    @property
    def replaced(self) -> np.ndarray:
        """Instants at which the tube in place is the new one."""
        fresh = self.fresh
        return np.zeros(self.n, bool) if fresh is None else self.elapsed >= fresh


def _after_rows(rows: pd.DataFrame, columns: dict, dtypes=None) -> dict | pd.DataFrame:
    """The initial table's rows (reindexed to the run's columns, NaN where they lack one) then
    the run's: ``pd.concat([rows.reindex(columns=...), _frame(columns)], ignore_index=True)``;
    as the columns of that frame (name -> float64 array: :func:`_frame` of them is it) when
    every column is float64 (a restart of a table without sectors: 0.11 -> 0.02 ms), by that
    concat otherwise. ``dtypes``: the rows' dtypes, when known
    (:attr:`InitialState.row_dtypes`)."""
    names = list(columns)
    new = [np.asarray(columns[c]) for c in names]
    if (rows.columns.is_unique and all(a.dtype == np.float64 and a.ndim == 1 for a in new)
            and all(t == np.float64 for t in (rows.dtypes if dtypes is None else dtypes))):
        block = rows.to_numpy()  # (taking columns one by one deep-copies the rows' attrs)
        at = {c: i for i, c in enumerate(rows.columns)}
        blank = np.full(len(rows), np.nan)
        return {c: np.concatenate([block[:, at[c]] if c in at else blank, a])
                for c, a in zip(names, new, strict=True)}
    return pd.concat([rows.reindex(columns=names), _frame(columns)], ignore_index=True)


# --------------------------------------------------------------------------- 6. metadata
def _attrs(case: WearCase, geometry, mobile, obstacle, sources, result, edges,
           keys=None) -> dict:
    """The table's metadata: the run's description, the coefficients and their sources
    (``edges``: the case's ``sector_edges`` [deg]); ``keys`` given: the power's statistics
    and the case's description made only when asked for."""
    dimensions = geometry.dimensions()  # a new dict
    dimensions.pop("contact_type", None)
    out = {
        "title": case.name, "contact_type": case.contact_type, "dimensions": dimensions,
        "law": case.law, "coefficients_mobile": mobile, "coefficients_obstacle": obstacle,
        "coefficient_sources": sources,
        "materials": None if case.materials is None else list(case.materials),
        "coefficient_files": None if case.coefficient_files is None
        else list(case.coefficient_files),
        "sector_edges": None if edges is None else edges.tolist(),
        "sector_coefficients": None if case.sector_coefficients is None
        else [list(p) for p in case.sector_coefficients],
        "time_scale": case.time_scale,
        "time_unit": case.time_label,
        "origin": case.origin, "tube_replacement": case.restart.tube_replacement,
        "wall_thickness": case.wall.thickness, "depth_limit": case.wall.limit,
        "global_depth": getattr(geometry, "reason", None),  # why the global depths are NaN
    }
    if keys is None or "power" in keys:
        out["power"] = None if result is None else _power_dict(result)
    if keys is None or "case" in keys:
        out["case"] = case.to_dict()
    return out


def _power_dict(result) -> dict:
    try:
        return dict(result.to_dict())
    except Exception:  # noqa: BLE001 - metadata only
        return {"total": float(result.total)}
