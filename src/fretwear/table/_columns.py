"""The columns of the wear table: cumulated volumes and depths (theory §3, §6, §7).

Step 4 of :func:`~fretwear.table.wear_table_from_case` (:mod:`fretwear.table.build` states the
table's conventions): the cumulated volume of a body (:func:`_cumulated`), the depths from the
cumulated volumes (:func:`_depths`), the columns of the table without sectors
(:func:`_global_frame`) or per instant and sector (:func:`_sector_frame`, every sector at once),
and the DataFrame of the columns built in one go (:func:`_frame`). SI units: volumes [m³],
depths [m], durations [s], powers [W], coefficients [1/Pa].
"""

from __future__ import annotations

import functools
import warnings

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import RangeWarning
from fretwear.geometry.sectors import sector_depth_mobile, sector_depth_obstacle
from fretwear.table.case import WearCase
from fretwear.table.schema import GLOBAL_COLUMNS, SECTOR_COLUMNS


# --------------------------------------------------------------------------- 4. volumes, depths
def _cumulated(law, power: float, coefficients, elapsed_s: np.ndarray, previous: float,
               fresh_from_s: float | None, body: str) -> np.ndarray:
    """Cumulated volume of one body at ``elapsed_s`` seconds after the origin [m³].

    ``previous`` is the body's volume at the origin; a linear law adds ``V(P, Δt)``, another
    law continues from its equivalent time (theory §7). ``fresh_from_s`` (a replacement, seconds
    after the origin) restarts the body from zero there. The law's warnings name the body.
    """
    if coefficients is None:  # this body does not wear
        out = np.full(elapsed_s.shape, float(previous))
        if fresh_from_s is not None:
            out[elapsed_s >= fresh_from_s] = 0.0
        return out
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if previous == 0.0:
            out = np.asarray(law.volume(power, elapsed_s, **coefficients), dtype=float)
        else:  # linear: V0 + V(Δt); otherwise from the equivalent time of V0 (theory §7)
            out = np.asarray(law.cumulated_volume(previous, power, elapsed_s, **coefficients),
                             dtype=float)
        out = np.broadcast_to(out, elapsed_s.shape).copy()
        if fresh_from_s is not None:
            new = elapsed_s >= fresh_from_s
            out[new] = np.asarray(law.volume(power, elapsed_s[new] - fresh_from_s,
                                             **coefficients), dtype=float)
    for w in caught:
        warnings.warn(f"{body}: {w.message}", w.category, stacklevel=5)
    return out


def _depths(geometry, volume_mobile: np.ndarray, volume_obstacle: np.ndarray):
    """(mobile, obstacle) depths [m] from the cumulated volumes [m³] (theory §6).

    An obstacle without volume has no depth: exactly 0 where the mobile's depth is defined
    (the split d_o = D − D·V_m/V of a shared trace leaves a rounding residue otherwise).
    """
    dm, do = geometry.depth_from_volume(volume_mobile, volume_obstacle)
    dm, do = _float_of_shape(dm, volume_mobile.shape), _float_of_shape(do, volume_mobile.shape)
    return dm, np.where((volume_obstacle == 0) & np.isfinite(dm), 0.0, do)


def _float_of_shape(values, shape) -> np.ndarray:
    """A float copy of ``values`` broadcast to ``shape`` (``np.broadcast_to(values, shape)
    .astype(float)``; a plain copy when they have that shape already)."""
    if type(values) is np.ndarray and values.shape == shape:
        return values.astype(float)
    return np.broadcast_to(values, shape).astype(float)


def _global_frame(case, head, power, mobile, obstacle, clock, geometry) -> pd.DataFrame:
    """The table without sectors: one row per instant."""
    law, state = case.wear_law, case.restart.table
    prev_m = 0.0 if state is None else state.volume_mobile
    prev_o = 0.0 if state is None else state.volume_obstacle
    vm = _cumulated(law, power, mobile, clock.elapsed, prev_m, clock.fresh, "mobile")
    vo = _cumulated(law, power, obstacle, clock.elapsed, prev_o, None, "obstacle")
    dm, do = _depths(geometry, vm, vo)
    return {**head, "volume_mobile": vm, "volume_obstacle": vo, "depth_mobile": dm,
            "depth_obstacle": do}


def _sector_coefficients(case: WearCase, m: int, mobile, obstacle):
    """(mobile [m], obstacle [m] or None) Archard coefficients [1/Pa] of the ``m`` sectors:
    the case's sector coefficients (a missing obstacle one is 0 when others wear), else the
    law's coefficient in every sector."""
    key = case.wear_law.parameters[0]
    if case.sector_coefficients is None:
        k_o = None if obstacle is None else obstacle.get(key)
        return np.full(m, mobile[key]), (None if k_o is None else np.full(m, k_o))
    km = np.array([p[0] for p in case.sector_coefficients])
    ko = np.array([np.nan if p[1] is None else p[1] for p in case.sector_coefficients])
    if np.isnan(ko).all():
        return km, None
    return km, np.nan_to_num(ko, nan=0.0)


def _sector_frame(case, head, result, mobile, obstacle, clock, geometry) -> dict:
    """The sector table's columns: one row per instant and sector (instant-major).

    Every sector at once (:func:`_sector_columns`); sector by sector below when that path
    meets a warning or an error (the messages name the body and the sectors as they are made
    here) or a law not linear in time.
    """
    columns = _sector_columns(case, head, result, mobile, obstacle, clock, geometry)
    if columns is not None:
        return columns
    law, state = case.wear_law, case.restart.table
    key = law.parameters[0]
    edges = np.asarray(result.sector_edges, dtype=float)
    powers = np.asarray(result.sectors, dtype=float)
    m, n = powers.size, clock.n
    k_m, k_o = _sector_coefficients(case, m, mobile, obstacle)
    r_m, r_o = geometry.mobile_radius, getattr(geometry, "obstacle_radius", None)
    width = geometry.obstacle_width
    elapsed, fresh, replaced = clock.elapsed, clock.fresh, clock.replaced
    cols = {c: [] for c in SECTOR_COLUMNS if c not in GLOBAL_COLUMNS}
    cum_m = np.zeros((n, m))
    cum_o = np.zeros((n, m))
    unradiused: list[int] = []
    for j in range(m):
        pm = 0.0 if state is None else float(state.sector_volume_mobile[j])
        po = 0.0 if state is None else float(state.sector_volume_obstacle[j])
        vm = _cumulated(law, powers[j], {key: k_m[j]}, elapsed, pm, fresh, "mobile")
        vo = _cumulated(law, powers[j], None if k_o is None else {key: k_o[j]}, elapsed, po,
                        None, "obstacle")
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
        warnings.warn(f"sectors {unradiused}: the obstacle wears but "
                      f"{geometry.contact_type or 'the sector geometry'} has no obstacle_radius "
                      "(RAYON_OBST): their obstacle sector depth is NaN", RangeWarning,
                      stacklevel=4)
    total_m, total_o = cum_m.sum(axis=1), cum_o.sum(axis=1)
    dm, do = _depths(geometry, total_m, total_o)
    glob = {"volume_mobile": total_m, "volume_obstacle": total_o,
            "depth_mobile": dm, "depth_obstacle": do}
    data = {k: np.repeat(np.asarray(v), m) for k, v in {**head, **glob}.items()}
    for c, parts in cols.items():  # instant-major order: row = i*m + j
        data[c] = np.column_stack(parts).ravel()
    return {c: data[c] for c in SECTOR_COLUMNS}


def _sector_columns(case, head, result, mobile, obstacle, clock, geometry) -> dict | None:
    """The columns of :func:`_sector_frame` with every sector at once: (instant, sector)
    arrays through the same element-wise operations as sector by sector (the same bits);
    None where that loop is needed (a warning, an error, a law not linear in time)."""
    law, state = case.wear_law, case.restart.table
    if not law.linear_in_time:
        return None
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            columns = _sector_arrays(law, state, head, result, case, mobile, obstacle, clock,
                                     geometry)
    except Exception:  # noqa: BLE001 - the loop raises it with its own message
        return None
    return None if caught or columns is None else columns


def _linear_sectors(law, key, powers, coefficients, elapsed, previous, fresh):
    """(instant, sector) cumulated volumes [m³] of a law linear in time: as :func:`_cumulated`
    per sector (V0 + V(P_j, t), exactly V where V0 = 0; restarted from zero at ``fresh``)."""
    m = powers.size
    if coefficients is None:  # this body does not wear
        return np.ascontiguousarray(np.broadcast_to(previous, (elapsed.size, m)), dtype=float)
    k = {key: coefficients}
    volume = np.asarray(law.volume(powers, elapsed[:, None], **k), dtype=float)
    if fresh is None and not previous.any():  # V0 = 0 (or -0) in every sector: V itself
        return np.ascontiguousarray(volume, dtype=float)
    out = np.where(previous == 0.0, volume, previous + volume)
    if fresh is not None:
        new = elapsed >= fresh
        out[new] = np.asarray(law.volume(powers, (elapsed[new] - fresh)[:, None], **k),
                              dtype=float)
    return np.ascontiguousarray(out, dtype=float)


def _sector_arrays(law, state, head, result, case, mobile, obstacle, clock, geometry):
    key = law.parameters[0]
    edges = np.asarray(result.sector_edges, dtype=float)
    powers = np.asarray(result.sectors, dtype=float)
    m, n = powers.size, clock.n
    k_m, k_o = _sector_coefficients(case, m, mobile, obstacle)
    r_m, r_o = geometry.mobile_radius, getattr(geometry, "obstacle_radius", None)
    width = geometry.obstacle_width
    elapsed, fresh = clock.elapsed, clock.fresh
    if state is None:
        pm = po = np.zeros(m)
    else:
        pm = np.array(state.sector_volume_mobile, dtype=float)
        po = np.array(state.sector_volume_obstacle, dtype=float)
        if pm.shape != (m,) or po.shape != (m,) or not (
                np.isfinite(pm).all() and np.isfinite(po).all() and (pm >= 0).all()
                and (po >= 0).all()):
            return None  # the law's own checks, sector by sector
    vm = _linear_sectors(law, key, powers, k_m, elapsed, pm, fresh)
    vo = _linear_sectors(law, key, powers, k_o, elapsed, po, None)
    if r_o is None and (vo > 0).any():
        return None  # the loop names the sectors
    arcs = edges[1:] - edges[:-1]
    # a replaced tube starts from zero (without a replacement, pm in every row)
    was_m = pm if fresh is None else np.where(clock.replaced[:, None], 0.0, pm)
    total_m, total_o = vm.sum(axis=1), vo.sum(axis=1)
    dm, do = _depths(geometry, total_m, total_o)
    # instant-major order: row = i*m + j; per instant, each value repeated m times
    per_instant = _repeated((*head.values(), total_m, total_o, dm, do), m)
    data = dict(zip((*head, "volume_mobile", "volume_obstacle", "depth_mobile",
                     "depth_obstacle"), per_instant, strict=True))
    depth_o = (np.where(vo == 0, 0.0, np.nan) if r_o is None
               else sector_depth_obstacle(vo, r_o, width, arcs))
    data.update({  # per sector, the sectors' values in every instant
        "sector": _tiled(np.arange(1, m + 1), n), "angle_start": _tiled(edges[:-1], n),
        "angle_end": _tiled(edges[1:], n), "sector_power": _tiled(powers, n),
        "volume_mobile_sector": (vm - was_m).ravel(),
        "volume_obstacle_sector": (vo - po).ravel(),
        "depth_mobile_sector": np.asarray(sector_depth_mobile(vm, r_m, width, arcs)).ravel(),
        "depth_obstacle_sector": np.asarray(depth_o, dtype=float).ravel(),
        "volume_mobile_cumulated": vm.ravel(), "volume_obstacle_cumulated": vo.ravel()})
    return {c: data[c] for c in SECTOR_COLUMNS}


def _repeated(columns, m: int) -> np.ndarray:
    """The rows of ``columns`` (k arrays of n values) with each value repeated ``m`` times:
    ``np.repeat(column, m)`` of each, in one (k, n·m) array."""
    values = np.stack([np.asarray(c) for c in columns])
    out = np.empty((*values.shape, m), dtype=values.dtype)
    out[...] = values[..., None]
    return out.reshape(values.shape[0], -1)


def _tiled(values: np.ndarray, n: int) -> np.ndarray:
    """``values`` (m of them) repeated n times in a row: ``np.tile(values, n)``."""
    out = np.empty((n, values.size), dtype=values.dtype)
    out[...] = values
    return out.reshape(-1)


@functools.lru_cache(maxsize=64)
def _index(names: tuple[str, ...]) -> pd.Index:
    """The columns' index of a table's columns (each table gets a copy: a name set on one
    table's columns stays with it)."""
    return pd.Index(list(names))


@functools.lru_cache(maxsize=64)
def _layout(names: tuple[str, ...], dtypes: tuple) -> tuple | None:
    """The blocks ``pd.DataFrame(columns)`` makes of columns of these names and numpy dtypes:
    one per dtype, its columns' places in order ((dtype, places), float64 first); None unless
    every dtype is numeric or boolean."""
    if any(d.kind not in "fiub" for d in dtypes):
        return None
    groups: dict = {}
    for at, dtype in enumerate(dtypes):
        groups.setdefault(dtype, []).append(at)
    order = sorted(groups, key=lambda d: d != np.float64)  # stable: then first appearance
    return tuple((d, tuple(groups[d])) for d in order)


@functools.cache
def _from_blocks():
    """pandas' public constructor from blocks (pandas >= 3), None before it (looked up at the
    first table: pandas is imported when first used)."""
    try:
        from pandas.api.internals import create_dataframe_from_blocks
    except ImportError:  # pragma: no cover - pandas 2
        return None
    return create_dataframe_from_blocks


def _frame(columns: dict) -> pd.DataFrame:
    """The DataFrame of ``columns`` (name -> 1-d array, one length), as
    ``pd.DataFrame(columns)`` gives it (the same columns, dtypes, index and blocks: one per
    dtype), built from its blocks directly: each dtype's columns stacked once.

    Columns that are not 1-d numpy arrays of one length and a numeric or boolean dtype take
    ``pd.DataFrame(columns)`` itself; a pandas without
    ``pandas.api.internals.create_dataframe_from_blocks`` (pandas 2) :func:`_frame_inserted`.
    """
    arrays = tuple(columns.values())
    names = tuple(columns)
    layout = (None if not arrays or any(type(a) is not np.ndarray for a in arrays)
              or len({a.shape for a in arrays}) != 1 or arrays[0].ndim != 1
              else _layout(names, tuple(a.dtype for a in arrays)))
    if layout is None:
        return pd.DataFrame(columns)
    make = _from_blocks()
    if make is None:  # pragma: no cover - pandas 2
        return _frame_inserted(columns)
    blocks = [(np.stack([arrays[at] for at in places]), np.array(places, dtype=np.intp))
              for _, places in layout]
    # a copy of the cached index per table: its data shared (immutable), its name its own
    return make(blocks, index=pd.RangeIndex(arrays[0].shape[0]), columns=_index(names).copy())


def _frame_inserted(columns: dict) -> pd.DataFrame:
    """:func:`_frame` through pandas' own constructors: the float columns stacked once into a
    DataFrame, the others (the sector numbers) inserted at their place."""
    names = tuple(columns)
    floats = tuple(c for c in names if np.asarray(columns[c]).dtype == np.float64)
    block = np.stack([columns[c] for c in floats]) if floats else np.empty((0, 0))
    # a copy of the cached index per table: its data shared (immutable), its name its own
    frame = pd.DataFrame(block.T, columns=_index(floats).copy(), copy=False)
    for at, name in enumerate(names):
        if name not in floats:
            frame.insert(at, name, columns[name])
    return frame

