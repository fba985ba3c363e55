"""A bundle's wear tables as an xarray Dataset (``contact × instant`` × ``sector``), built whole
from a table (:func:`build_dataset`, :attr:`fretwear.bundle.BundleResult.dataset`) or written to
Zarr a group of contacts at a time from the written table (:func:`write_zarr_by_regions`)."""

from __future__ import annotations

import os
import shutil
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._version import __version__
from fretwear.bundle.datasets import require
from fretwear.bundle.zarr_chunks import appender
from fretwear.table import COLUMNS, GLOBAL_COLUMNS, SECTOR_COLUMNS

_CONTACT_VARS = ("power",)
_SECTOR_ONLY = ("angle_start", "angle_end")


#: Identity columns of numbers (all missing: NaN, not text).
_NUMBER_COORDINATES = ("tube_row", "tube_column", "wall_thickness")
#: Columns along ``contact`` made coordinates, every one whether given or not.
_CONTACT_COORDINATES = ("tube_row", "tube_column", "support", "node", "history", "time_unit",
                        "wall_thickness", "status")


def _coordinate(values: pd.Series, name: str) -> np.ndarray:
    """A column along ``contact`` -> a NetCDF/Zarr-friendly array.

    Numbers as int64 where every value is given and whole (tube rows and columns; not
    ``wall_thickness`` [m]), else float64 with NaN where missing; anything else as text, ""
    where missing. A column without any value: NaN for ``tube_row``, ``tube_column`` and
    ``wall_thickness``, "" for the text columns.
    """
    given = values.notna().to_numpy()
    if not given.any():
        return (np.full(len(values), np.nan) if name in _NUMBER_COORDINATES
                else np.full(len(values), "", dtype=object))
    numeric = pd.to_numeric(values, errors="coerce")
    if numeric.notna().sum() == given.sum():
        number = numeric.to_numpy(dtype=float)
        if (name != "wall_thickness" and given.all() and np.isfinite(number).all()
                and (number == np.round(number)).all() and (np.abs(number) < 2.0**53).all()):
            return number.astype(np.int64)
        return number
    return values.fillna("").astype(str).to_numpy(dtype=object)


def build_dataset(table: pd.DataFrame, contacts: pd.DataFrame):
    """The bundle's wear tables as an xarray Dataset (see :attr:`BundleResult.dataset`)."""
    xr = require("xarray")
    done = _done(contacts)
    ids = [c for c in done["contact"].astype(str)] if len(done) else []
    sector_mode = "sector" in table.columns and table["sector"].notna().any()
    ds = xr.Dataset(_variables(table, sector_mode))
    if "contact" in ds.dims:  # the manifest's order (the set built once: 20 000 contacts took
        present = set(ds["contact"].values)  # 28 s when it was rebuilt for each of them)
        ds = ds.reindex(contact=[c for c in ids if c in present])
    info = done.set_index("contact") if len(done) else done
    if "contact" in ds.dims:
        ds = ds.assign_coords(_contact_coordinates(info, [str(c) for c in ds["contact"].values]))
    return _described(ds, info)


def _done(contacts: pd.DataFrame) -> pd.DataFrame:
    """The contacts whose rows are in the table (done, skipped or stale)."""
    return (contacts[contacts["status"].isin(["done", "skipped", "stale"])] if len(contacts)
            else contacts)


def _variables(table: pd.DataFrame, sector_mode: bool) -> dict:
    """The Dataset's variables of the table's rows: the global columns along ``(contact,
    instant)``, in sector mode the sector columns along ``(contact, instant, sector)`` and the
    sectors' angles along ``(contact, sector)``."""
    wear = [c for c in table.columns if c in COLUMNS and c not in ("instant", "sector")]
    global_cols = [c for c in wear if c not in _sector_columns()]
    data = {}
    if len(table):
        # each variable group's columns taken before indexing: set_index copies every column
        # it is given (the whole table, three times, made the peak 5x the dataset at 20 000
        # contacts)
        keys = ["contact", "instant"]
        glob = table[keys + global_cols].drop_duplicates(keys, keep="first")
        g = glob.set_index(keys).to_xarray()
        del glob
        data.update({k: g[k] for k in g.data_vars})
        if sector_mode:
            s_cols = [c for c in wear if c in _sector_columns() and c not in _SECTOR_ONLY]
            rows = table["sector"].notna().to_numpy()
            sect = table.loc[rows, [*keys, "sector", *s_cols]]
            sect["sector"] = sect["sector"].astype(int)
            s = sect.set_index([*keys, "sector"]).to_xarray()
            data.update({k: s[k] for k in s.data_vars})
            del sect
            ends = table.loc[rows, ["contact", "sector", *_SECTOR_ONLY]]
            ends["sector"] = ends["sector"].astype(int)
            a = ends.drop_duplicates(["contact", "sector"]).set_index(
                ["contact", "sector"]).to_xarray()
            data.update({k: a[k] for k in a.data_vars})
    return data


def _contact_coordinates(info: pd.DataFrame, order: list[str]) -> dict:
    """The coordinates along ``contact`` of the contacts ``order`` (every one of
    :data:`_CONTACT_COORDINATES`, given or not: docs/bundle.md)."""
    out = {}
    # the contacts' rows found once, not once a column (``info.loc[order, col]``: 0.3 s at
    # 10^5 contacts, issue 28); the same values, where every id is there once
    where = info.index.get_indexer(order) if info.index.is_unique else None
    if where is not None and not (where >= 0).all():
        where = None  # .loc says which is missing
    for col in _CONTACT_COORDINATES:
        values = ((info.loc[order, col] if where is None else info[col].iloc[where])
                  if col in info.columns else pd.Series([None] * len(order), dtype=object))
        out[col] = ("contact", _coordinate(values, col))
    return out


def _described(ds, info: pd.DataFrame):
    """``ds`` with the units and meanings of its variables and coordinates in ``attrs``."""
    units = sorted(set(info["time_unit"].astype(str))) if "time_unit" in info.columns else []
    # the contacts' time unit where the table says "user time unit" (instant, duration, origin,
    # limit_instant ...): the same on the coordinate and on every time variable
    time_unit = units[0] if len(units) == 1 else "see the time_unit coordinate"
    for name in ds.data_vars:
        if name in COLUMNS:
            aster, unit, description = COLUMNS[name]
            unit = time_unit if unit == COLUMNS["instant"][1] else unit
            ds[name].attrs.update(units=unit, long_name=description, aster_name=aster)
    if "instant" in ds.coords:
        ds["instant"].attrs.update(units=time_unit, long_name=COLUMNS["instant"][2])
    if "sector" in ds.coords:
        ds["sector"].attrs.update(units="1", long_name=COLUMNS["sector"][2])
    if "wall_thickness" in ds.coords:
        ds["wall_thickness"].attrs.update(units="m", long_name="wall thickness of the tube")
    ds.attrs.update(title="fretwear bundle: wear tables of every contact",
                    fretwear_version=__version__,
                    conventions="SI units (m, m³, W); instants in the time unit of the case")
    return ds


def contact_chunks(ds) -> dict:
    """The Zarr encoding of a Dataset's first group of contacts: every variable along
    ``contact`` in chunks of the group's contacts, whole along its other dimensions. The
    groups appended after it (a row group of the table each, about
    :data:`fretwear.bundle.table_file.ROWS_PER_GROUP` rows: some 2 MB of a float column) then
    fill about one chunk each, where zarr's own guess (1 375 contacts x 3 instants x 8 sectors
    for 5 000 contacts x 6 x 8) cut each into a dozen and rewrote the partial ones: the
    appends of 2x10^4 contacts took 0.54-0.76 s of CPU, 0.31 s in these chunks (issue 28)."""
    n = ds.sizes["contact"]
    return {name: {"chunks": (n, *var.shape[1:])} for name, var in ds.variables.items()
            if var.dims and var.dims[0] == "contact" and name not in ds.dims}


def write_zarr_by_regions(path: Path, contacts: pd.DataFrame, target: Path,
                          **options) -> bool:
    """Write the Dataset of the Parquet table ``path`` (:func:`build_dataset` of it and
    ``contacts``) to the Zarr store ``target`` a group of contacts at a time (the table's row
    groups, about :data:`fretwear.bundle.table_file.ROWS_PER_GROUP` rows each): the first group
    makes the store, each next one is appended along ``contact`` (issue 28: the client built
    the whole Dataset, about the table's size, beside the table). ``options`` go to
    ``Dataset.to_zarr``.

    Only where every contact has every instant (and, in sector mode, every sector at each), so
    that each group's variables have the whole Dataset's coordinates and types; False (nothing
    written) otherwise, or for a table without rows: the caller builds the Dataset whole."""
    import pyarrow.parquet as pq

    keys = [c for c in ("contact", "instant", "sector") if c in pq.read_schema(path).names]
    grid = _full_grid(pq.read_table(path, columns=keys, read_dictionary=["contact"]))
    if grid is None:
        return False
    present, sector_mode = grid[:2]
    done = _done(contacts)
    done = done.assign(contact=done["contact"].astype(str))
    ids = [c for c in done["contact"] if c in present]
    if len(ids) != len(present):
        return False
    info = done.set_index("contact")
    coordinates = _contact_coordinates(info, ids)
    width = np.array(ids).dtype  # the contact ids' one text type, as the whole Dataset's
    start = 0
    labels = np.array(ids, dtype=width)
    for group in _contact_groups(pq.ParquetFile(path)):
        ds = _grid_dataset(group, labels[start:], grid)
        if ds is None:  # not laid out as the grid: through pandas' MultiIndex
            ds = require("xarray").Dataset(_variables(group, sector_mode))
        order = ids[start:start + ds.sizes["contact"]]
        ds = ds.reindex(contact=np.array(order, dtype=width))
        ds = ds.assign_coords({name: ("contact", values[start:start + len(order)])
                               for name, (_, values) in coordinates.items()})
        ds = _described(ds, info)
        if start == 0:
            ds.to_zarr(target, mode="w", encoding=contact_chunks(ds), **options)
        else:
            ds.to_zarr(target, append_dim="contact", **options)
        start += len(order)
    return start == len(ids)


def _grid_dataset(group: pd.DataFrame, ids: np.ndarray, grid):
    """:func:`_variables` of a group of whole contacts laid out as the table writes them on a
    full grid (``grid``, :func:`_full_grid`): the contacts ``ids[:n]`` one after the other,
    each the instants in increasing order, each (in sector mode) the sectors in increasing
    order. Each column is then reshaped to ``(contact, instant[, sector])`` as it is, where
    ``set_index(...).to_xarray()`` sorted a MultiIndex and unstacked it (0.85 s of the 4 s
    the Dataset took at 10^4 contacts). None where the group is laid out otherwise or has a
    column that is not a numpy number: the caller goes through :func:`_variables`."""
    _, sector_mode, instants, sectors = grid
    wear = [c for c in group.columns if c in COLUMNS and c not in ("instant", "sector")]
    if any(group[c].dtype.kind not in "fiub" or not isinstance(group[c].dtype, np.dtype)
           for c in wear):
        return None
    per = len(instants) * (len(sectors) if sector_mode else 1)
    n, rest = divmod(len(group), per)
    if rest or n == 0 or n > len(ids):
        return None
    ids = ids[:n]
    if not _in_blocks(group["contact"], ids, per):
        return None
    layout = [("instant", group["instant"].to_numpy(),
               np.tile(np.repeat(instants, per // len(instants)), n))]
    if sector_mode:
        layout.append(("sector", group["sector"].to_numpy(),
                       np.tile(sectors, n * len(instants))))
    if not all(np.array_equal(got.astype(want.dtype), want) for _, got, want in layout):
        return None
    shape = (n, len(instants), len(sectors)) if sector_mode else (n, len(instants))
    dims = ("contact", "instant", "sector")[:len(shape)]
    coords = {"contact": ids, "instant": instants}
    if sector_mode:
        coords["sector"] = sectors.astype(int)
    data = {}
    for c in wear:
        values = group[c].to_numpy().reshape(shape)
        if c not in _sector_columns():
            data[c] = (dims[:2], values[:, :, 0] if sector_mode else values)
        elif sector_mode and c in _SECTOR_ONLY:
            data[c] = (("contact", "sector"), values[:, 0, :])
        elif sector_mode:
            data[c] = (dims, values)
    return require("xarray").Dataset(data, coords=coords)


def _in_blocks(contact: pd.Series, ids: np.ndarray, per: int) -> bool:
    """Whether ``contact`` is ``ids[0]`` ``per`` times, then ``ids[1]`` ``per`` times, and so
    on (each compared as ``ids``' text type): by the column's codes (``pandas.factorize``),
    not its values one by one (their conversion to Python text took 0.08 s a row group of
    2 800 contacts)."""
    codes, uniques = pd.factorize(contact)
    return (len(uniques) == len(ids) and len(codes) == per * len(ids)
            and np.array_equal(codes, np.repeat(np.arange(len(ids)), per))
            and np.array_equal(np.asarray(uniques.to_numpy(dtype=object)).astype(ids.dtype),
                               ids))


def _full_grid(keys) -> tuple[set[str], bool, np.ndarray, np.ndarray | None] | None:
    """``(the contacts, sector mode, the instants, the sectors)`` of a table's ``contact``,
    ``instant`` (and ``sector``) columns (Arrow, ``contact`` dictionary-encoded) when every
    contact has every instant (and every sector at each, no row without one), the instants and
    sectors increasing (the sectors None out of sector mode); None otherwise."""
    if keys.num_rows == 0:
        return None
    contact = keys.column("contact").combine_chunks()
    codes = contact.indices.to_numpy(zero_copy_only=False)
    names = contact.dictionary.to_pylist()
    instant = keys.column("instant").to_numpy()
    if contact.null_count or not np.isfinite(instant).all():
        return None
    instants, at = np.unique(instant, return_inverse=True)
    used = np.unique(codes)
    if len({str(names[c]) for c in used}) != used.size:
        return None
    cells = [codes, at]
    sizes = [used.size, instants.size]
    sector_mode = "sector" in keys.column_names and keys.column("sector").null_count < len(codes)
    if sector_mode:
        sector = keys.column("sector").to_numpy(zero_copy_only=False)
        if keys.column("sector").null_count or not np.isfinite(sector.astype(float)).all():
            return None
        sectors, where = np.unique(sector, return_inverse=True)
        cells.append(where)
        sizes.append(sectors.size)
    flat = np.ravel_multi_index(cells, [len(names), *sizes[1:]])
    if np.unique(flat).size != len(codes) or len(codes) != int(np.prod(sizes)):
        return None
    return ({str(names[c]) for c in used}, bool(sector_mode), instants,
            sectors if sector_mode else None)


def _contact_groups(table_file):
    """The table's rows by groups of whole contacts, in its order: each row group, the rows of
    its last contact held back to the next one (a contact's rows may span two groups)."""
    held = None
    for i in range(table_file.num_row_groups):
        frame = table_file.read_row_group(i).to_pandas()
        frame["contact"] = frame["contact"].astype(str)
        if held is not None:
            frame = pd.concat([held, frame], ignore_index=True)
        last = frame["contact"].iloc[-1]
        mine = (frame["contact"] == last).to_numpy()
        held = frame[mine].reset_index(drop=True)
        if not mine.all():
            yield frame[~mine].reset_index(drop=True)
    if held is not None and len(held):
        yield held


def _sector_columns() -> tuple[str, ...]:
    """Columns that differ between the sectors of one instant."""
    return tuple(c for c in COLUMNS if c not in GLOBAL_COLUMNS and (
        c in SECTOR_COLUMNS or c.endswith("_sector")))


class GridZarr:
    """``dataset.zarr`` written while the table is (:class:`fretwear.bundle.table_file.
    PrefixTable`): each group of whole contacts the table writes as a row group, reshaped onto
    the grid (:func:`_grid_dataset`), appended along ``contact`` to a Zarr store in ``folder``;
    the coordinates along ``contact`` (known once every record is in) and every array's and the
    store's attributes added by :meth:`finish`. Its Dataset is the one
    :func:`write_zarr_by_regions` writes of the table (test_bundle_table_prefix.py): the same
    variables, values, coordinates and attributes.

    It gives up (:meth:`abort`, its folder removed; the caller writes the dataset from the
    table) where that one would not be written by groups or could differ: a group off the grid
    of the first (other instants or sectors, a contact missing one, sectors with gaps), contacts
    with rows other than those it wrote, or contact ids of another text width.

    Parameters
    ----------
    folder : Path
        The store being written (a temporary folder beside ``dataset.zarr``).
    width : numpy dtype
        The contact ids' text type (``numpy.array(ids).dtype`` of every contact that can have
        rows).
    options : dict
        ``Dataset.to_zarr``'s options (the Zarr format).
    """

    def __init__(self, folder: Path, width, options: dict) -> None:
        self.folder, self.width, self.options = folder, width, options
        self.grid: tuple | None = None
        self.first = None  # the Dataset of the first contact written
        self.labels: list[str] = []
        self.arrays: dict | None = None  # the store's arrays along contact (_append)
        #: Each array's whole-chunk writer (zarr_chunks.appender; None: zarr's append).
        self.appenders: dict = {}
        self.aborted = False

    def add(self, frame: pd.DataFrame) -> None:
        """Append a group of whole contacts, the table's rows in its order."""
        if self.aborted:
            return
        try:
            if self.grid is None:
                self.grid = _frame_grid(frame)
            ids = pd.factorize(frame["contact"])[1].to_numpy(dtype=object)
            ds = None if self.grid is None else _grid_dataset(
                frame, np.array(ids, dtype=self.width), self.grid)
            if ds is None or ds.sizes["contact"] != len(ids):
                return self.abort()
            if self.labels:
                self._append(ds)
            else:
                shutil.rmtree(self.folder, ignore_errors=True)
                ds.to_zarr(self.folder, mode="w", encoding=contact_chunks(ds), **self.options)
                # its first contact: the Dataset whose attributes finish() takes (reading it
                # back from the store through dask took 2.5 s at 10^4 contacts)
                self.first = ds.isel(contact=[0]).copy(deep=True)
            self.labels.extend(str(c) for c in ids)
        except Exception:  # noqa: BLE001 - a shortcut: write_zarr_by_regions decides
            self.abort()

    def _append(self, ds) -> None:
        """``ds``'s variables along ``contact`` appended to the store's arrays by zarr itself
        (``Array.append``), the arrays opened once: what ``to_zarr(append_dim="contact")``
        stores (its others, ``instant`` and ``sector``, are the grid's, already there) without
        opening and decoding the store and consolidating its metadata at every row group
        (about half of its 0.2-0.3 s a group of 2 800 contacts); :meth:`finish` consolidates
        once. An array whose layout :mod:`fretwear.bundle.zarr_chunks` knows is written by it
        a whole chunk at a time (the same files, without zarr's codec pipeline: 2.5 ms of CPU an
        array a group), :meth:`finish` writing its last chunk. Raises where a variable is not
        an array of the store's type and shape beyond ``contact``: the caller gives up the
        route before anything is written."""
        along = {name: var for name, var in ds.variables.items() if "contact" in var.dims}
        if self.arrays is None:
            zarr = require("zarr")
            major = int(zarr.__version__.split(".")[0])
            group = zarr.open_group(str(self.folder), mode="r+",
                                    **({"use_consolidated": False} if major >= 3 else {}))
            self.arrays = {name: group[name] for name in along}
            self.appenders = {name: appender(array, self.folder / name)
                              for name, array in self.arrays.items()}
        values = {}
        for name, var in along.items():
            array, data = self.arrays[name], np.asarray(var.values)
            if var.dims[0] != "contact" or data.dtype != array.dtype \
                    or data.shape[1:] != tuple(array.shape[1:]):
                raise ValueError(f"{name}: not the store's array")
            values[name] = data
        if set(values) != set(self.arrays):
            raise ValueError("not the store's variables")
        for name, data in values.items():
            if self.appenders.get(name) is not None:
                self.appenders[name].add(data)
            else:
                self.arrays[name].append(data, axis=0)

    def finish(self, contacts: pd.DataFrame, target: Path) -> bool:
        """Add the coordinates of ``contacts`` (the result's) and the attributes, and move the
        store to ``target``: True; False (nothing moved, the folder removed) where the store is
        not the Dataset of those contacts."""
        if self.aborted or not self.labels:
            self.abort()
            return False
        try:
            done = _done(contacts)
            ids = [str(c) for c in done["contact"]]
            if ids != self.labels or np.array(ids).dtype != self.width:
                self.abort()
                return False
            for chunks in self.appenders.values():  # their last chunks, the arrays' length
                if chunks is not None:
                    chunks.close()
            info = done.assign(contact=ids).set_index("contact")
            self._coordinates_and_attributes(info, ids)
            shutil.rmtree(target, ignore_errors=True)
            os.replace(self.folder, target)
        finally:
            self.abort()
        return True

    def _coordinates_and_attributes(self, info: pd.DataFrame, ids: list[str]) -> None:
        """The coordinates along ``contact`` written whole beside the store's variables, then
        every array's attributes and the store's those of the same Dataset's first contact
        (with its coordinates and :func:`_described`'s attributes) written by xarray (the
        names of its coordinates, units, meanings), the metadata consolidated again."""
        xr = require("xarray")
        zarr = require("zarr")
        coordinates = _contact_coordinates(info, ids)
        scratch = self.folder.with_name(f"{self.folder.name}.coordinates")
        skeleton = self.folder.with_name(f"{self.folder.name}.attributes")
        try:
            first = self.first.assign_coords({name: ("contact", values[:1])
                                              for name, (_, values) in coordinates.items()})
            # the two stores written at once (each mostly waits on zarr's I/O: at 10^5
            # contacts, 0.6 s each one after the other, the last thing after the summary)
            with ThreadPoolExecutor(1) as pool:
                attributes = pool.submit(lambda: _described(first, info).to_zarr(
                    skeleton, mode="w", **self.options))
                xr.Dataset(coords={"contact": np.array(ids, dtype=self.width), **coordinates}
                           ).to_zarr(scratch, mode="w", **self.options)
                attributes.result()
            for name in coordinates:
                os.replace(scratch / name, self.folder / name)
            for attrs in [skeleton / ".zattrs", *skeleton.glob("*/.zattrs")]:
                shutil.copyfile(attrs, self.folder / attrs.relative_to(skeleton))
            zarr.consolidate_metadata(str(self.folder))
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
            shutil.rmtree(skeleton, ignore_errors=True)

    def abort(self) -> None:
        """Give up: the folder removed."""
        self.aborted = True
        shutil.rmtree(self.folder, ignore_errors=True)


def _frame_grid(frame: pd.DataFrame) -> tuple | None:
    """``(None, sector mode, the instants, the sectors)`` of a group of contacts (as
    :func:`_full_grid` gives them for the whole table), None where an instant is not finite or
    the sectors have gaps."""
    instant = frame["instant"].to_numpy(dtype=float)
    if not np.isfinite(instant).all():
        return None
    sector_mode = "sector" in frame.columns and bool(frame["sector"].notna().any())
    if not sector_mode:
        return None, False, np.unique(instant), None
    if frame["sector"].isna().any() or frame["sector"].dtype.kind not in "iu":
        return None
    return None, True, np.unique(instant), np.unique(frame["sector"].to_numpy())
