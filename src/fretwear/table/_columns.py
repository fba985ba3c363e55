"""The columns of the wear table: cumulated volumes and depths (theory §3, §6, §7).

Step 4 of :func:`~fretwear.table.wear_table_from_case` (:mod:`fretwear.table.build` states the
table's conventions): the columns of the table without sectors (:func:`_global_frame`) or per
instant and sector (:func:`_sector_frame`, every sector at once), their volumes and depths
computed by the case's :class:`~fretwear.table.DepthModel` (the one implementation of
volume(t) and depth(t)), and the DataFrame of the columns built in one go (:func:`_frame`). SI
units: volumes [m³], depths [m], durations [s], powers [W].
"""

from __future__ import annotations

import functools
import warnings

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import RangeWarning
from fretwear.table.depth_terms import initial_arrays


# --------------------------------------------------------------------------- 4. volumes, depths
def _global_frame(model, head, clock) -> dict:
    """The table without sectors: one row per instant, the volumes and depths of the case's
    :class:`~fretwear.table.DepthModel` (:meth:`~fretwear.table.DepthModel.table_columns`)."""
    return {**head, **model.table_columns(clock.elapsed)}


def _sector_frame(model, power: float, clock, edges) -> dict:
    """The sector table's columns: one row per instant and sector (instant-major), every
    sector at once by the case's :class:`~fretwear.table.DepthModel`
    (:meth:`~fretwear.table.DepthModel.sector_table`; the global depth from the sum of the
    sectors' volumes, :meth:`~fretwear.table.DepthModel.body_depths`)."""
    sectors = model.sector_table(clock.elapsed)
    if sectors["unradiused"]:
        geometry = model.geometry
        warnings.warn(f"sectors {sectors['unradiused']}: the obstacle wears but "
                      f"{geometry.contact_type or 'the sector geometry'} has no obstacle_radius "
                      "(RAYON_OBST): their obstacle sector depth is NaN", RangeWarning,
                      stacklevel=4)
    vm, vo = sectors["volume_mobile"], sectors["volume_obstacle"]
    n, m = vm.shape
    pm, po = initial_arrays(model.term_initial)
    # a replaced tube starts from zero (without a replacement, pm in every row)
    was_m = pm if clock.fresh is None else np.where(clock.replaced[:, None], 0.0, pm)
    total_m, total_o = vm.sum(axis=1), vo.sum(axis=1)
    dm, do = model.body_depths(total_m, total_o)
    # every float column in one (columns, instants, sectors) block: instant-major rows (row =
    # i*m + j); a value per instant repeated over the sectors, a value per sector over the
    # instants. The case's own rows (instants, durations, origin, angles) and the sector
    # numbers are a copy of the case's template (:func:`_template`); the contact's filled here
    template, sector = _template(clock, edges, n, m)
    block = template.copy()
    block[3] = power  # the run's power [W] in every row
    # the four values per instant in one assignment, the differences into their rows (no
    # temporaries): the same numbers, fewer numpy calls (about 1 µs each on 48 rows)
    block[4:8] = np.array((total_m, total_o, dm, do), dtype=float)[:, :, None]
    block[10] = model.powers
    np.subtract(vm, was_m, out=block[11])
    np.subtract(vo, po, out=block[12])
    block[13] = sectors["depth_mobile"]
    block[14] = sectors["depth_obstacle"]
    block[15] = vm
    block[16] = vo
    rows = list(block.reshape(len(_SECTOR_FLOATS), n * m))
    data = dict(zip(_SECTOR_FLOATS[:8], rows[:8], strict=True))
    data["sector"] = sector.copy()
    data.update(zip(_SECTOR_FLOATS[8:], rows[8:], strict=True))
    return data  # in the order of fretwear.table.schema.SECTOR_COLUMNS


#: The float columns of a sector table in the order :func:`_sector_frame` fills them: the
#: run's head (instant, duration, origin, power) and the global volumes and depths, a value per
#: instant; the sectors' angles and powers, a value per sector; the sectors' volumes and depths.
_SECTOR_FLOATS = ("instant", "duration", "origin", "power", "volume_mobile", "volume_obstacle",
                  "depth_mobile", "depth_obstacle", "angle_start", "angle_end", "sector_power",
                  "volume_mobile_sector", "volume_obstacle_sector", "depth_mobile_sector",
                  "depth_obstacle_sector", "volume_mobile_cumulated",
                  "volume_obstacle_cumulated")


#: Sector templates by their values (:func:`_template`), at most _TEMPLATES_KEPT, each of at
#: most _TEMPLATE_BYTES (a larger one is made for its table and not kept: 64 cases of 2 000
#: instants and 36 sectors held 664 MB): the cache holds at most 4 MB.
_TEMPLATES: dict = {}
_TEMPLATES_KEPT = 64
_TEMPLATE_BYTES = 65_536


def _template(clock, edges, n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """(the float block of :func:`_sector_frame` with the rows that are the case's alone
    filled: instant (origin + duration), duration, origin [user unit], angle_start, angle_end
    [deg]; the sector numbers 1..m per instant, int), made once per distinct values (a bundle's
    contacts of one case share them) and kept read-only: the caller copies them."""
    edges = np.asarray(edges, dtype=float)  # the sectors' edges [deg]
    durations, origin = clock.durations, clock.case.origin
    key = (n, m, edges.tobytes(), durations.tobytes(), float(origin).hex())
    found = _TEMPLATES.get(key)
    if found is None:
        block = np.zeros((len(_SECTOR_FLOATS), n, m))
        for i, values in enumerate((origin + durations, durations, np.full(n, origin))):
            block[i] = values[:, None]
        block[8], block[9] = edges[:-1], edges[1:]
        sector = _tiled(np.arange(1, m + 1), n)
        block.flags.writeable = sector.flags.writeable = False
        found = (block, sector)
        if block.nbytes + sector.nbytes <= _TEMPLATE_BYTES:
            if len(_TEMPLATES) >= _TEMPLATES_KEPT:
                _TEMPLATES.clear()
            _TEMPLATES[key] = found
    return found


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
def _rows(n: int) -> pd.RangeIndex:
    """The rows' index of a table of ``n`` rows (each table gets a view: a name set on one
    table's index stays with it)."""
    return pd.RangeIndex(n)


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
    # a view of the cached indexes per table: their data shared (immutable), their names their
    # own (Index.view: 2 µs, Index.copy: 14 µs)
    return make(blocks, index=_rows(arrays[0].shape[0]).view(), columns=_index(names).view())


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

