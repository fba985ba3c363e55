"""Each contact's quantities of a bundle's ranking (:func:`fretwear.bundle.result.summarize`),
taken over a table (or a piece of it holding whole contacts) at once."""

from __future__ import annotations

import math

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, KeywordError
from fretwear.table.depth_build import record_model
from fretwear.table.depth_rows import FROM_MODEL, INTERPOLATED, ContactModels, rows_time


def _global_rows(rows: pd.DataFrame) -> pd.DataFrame:
    """One row per instant (sector tables repeat the global columns on every sector row)."""
    if "sector" in rows.columns and rows["sector"].notna().any():
        rows = rows.drop_duplicates("instant", keep="first")
    return rows.sort_values("instant")


def _ordered(codes: np.ndarray, instant: np.ndarray) -> bool:
    """Whether the rows of each contact (``codes``: the contacts factorised in order of first
    appearance) are consecutive and by instant [table unit], every instant finite."""
    if codes.size < 2:
        return bool(np.isfinite(instant).all())
    step = codes[1:] - codes[:-1]
    if not ((step >= 0).all() and np.isfinite(instant).all()):
        return False
    return bool((instant[1:] >= instant[:-1])[step == 0].all())


class ContactQuantities:
    """Each contact's quantities for :func:`fretwear.bundle.result.summarize`, taken over the
    whole table (or a piece of whole contacts) at once.

    A contact's global rows are its rows in table order, only the first row of each instant
    when it has sectors, sorted by instant (as by :func:`_global_rows`); the arrays below are
    in the order the contacts first appear in the table (``names``, as ``groupby(sort=False)``).

    Attributes
    ----------
    names : list
        The contacts.
    instant, power, depth : list of float
        The last global row's instant [table unit], power [W] and ``depth_mobile`` [m].
    sector_max : list of float
        The largest ``depth_mobile_sector`` of the rows at that instant [m] (NaN without it).
    first_nan : list
        The instant of the first global row whose depth is not finite (None: none is).
    has_limit, limit_instant : list
        Whether a global row has a ``limit_instant``, and the last one [table unit] (when
        ``given``).
    """

    def __init__(self, table: pd.DataFrame, given: bool):
        codes, uniques = pd.factorize(table["contact"], sort=False)  # -1: no contact, dropped
        self.names = list(uniques)
        n = len(self.names)
        self.table, self.codes = table, codes
        self.instant, self.power, self.depth, self.sector_max = [], [], [], []
        self.first_nan, self.has_limit, self.limit_instant = [], [], []
        self._models: dict = {}  # contact -> its DepthModel or None (:meth:`model`)
        self._sector_rows = None  # (sector powers, first, end) of every contact's last instant
        if n == 0:
            return
        valid = codes >= 0
        instant = table["instant"].to_numpy(dtype=float)
        rows = valid.copy()
        has = np.zeros(n, dtype=bool)
        # a bundle's table: each contact's rows together, by instant (then sector): the
        # repeated instants are neighbours and the rows already in the order sought (the
        # general answers took 0.3 s of the summary at 10^5 contacts, issue 28)
        ordered = _ordered(codes, instant) and table["instant"].dtype == np.float64
        if "sector" in table.columns:
            has[codes[valid & table["sector"].notna().to_numpy()]] = True
            if ordered:  # DataFrame.duplicated's answer (-0.0 is 0.0), from the neighbours
                repeated = np.zeros(codes.size, dtype=bool)
                repeated[1:] = (codes[1:] == codes[:-1]) & (instant[1:] == instant[:-1])
            else:
                repeated = pd.DataFrame({"c": codes, "t": table["instant"]}).duplicated() \
                    .to_numpy()
            rows &= ~(has[codes] & repeated)
        pos = np.flatnonzero(rows)
        if not ordered:  # what the lexsort leaves as it is, when ordered
            pos = pos[np.lexsort((instant[pos], codes[pos]))]  # stable: NaN instants last
        gcode, t = codes[pos], instant[pos]
        self.start = np.searchsorted(gcode, np.arange(n))
        self.end = np.searchsorted(gcode, np.arange(n), side="right")
        tied = np.flatnonzero((gcode[1:] == gcode[:-1]) & (t[1:] == t[:-1]))
        if tied.size:  # equal instants: their order is pandas' sort's (not a stable one)
            for c in np.unique(gcode[tied]):
                mine = np.sort(pos[self.start[c]:self.end[c]])
                group = table.iloc[mine].reset_index(drop=True)
                pos[self.start[c]:self.end[c]] = mine[_global_rows(group).index.to_numpy()]
            t = instant[pos]
        self.pos, self.t = pos, t
        self.d = table["depth_mobile"].to_numpy(dtype=float)[pos]
        last = pos[self.end - 1]
        self.instant = instant[last].tolist()
        self.power = table["power"].to_numpy(dtype=float)[last].tolist()
        self.depth = self.d[self.end - 1].tolist()
        self.sector_max = (self._sector_max(instant[last]) if "depth_mobile_sector"
                           in table.columns else [math.nan] * n)
        bad = np.flatnonzero(~np.isfinite(self.d))
        first = [None] * n
        for c, i in zip(*np.unique(gcode[bad], return_index=True), strict=True):
            first[c] = float(t[bad[i]])
        self.first_nan = first
        self.has_limit = [False] * n
        self.limit_instant = [math.nan] * n
        if given:
            lim = table["limit_instant"].to_numpy(dtype=float)[pos]
            have = np.flatnonzero(~np.isnan(lim))[::-1]  # the last one of each contact first
            for c, i in zip(*np.unique(gcode[have], return_index=True), strict=True):
                self.has_limit[c] = True
                self.limit_instant[c] = float(lim[have[i]])
        self.origin = (table["origin"].to_numpy(dtype=float)[pos]
                       if "origin" in table.columns else None)
        self.sectored = has.tolist()  # contacts with sector rows

        def column(name):
            return table[name].to_numpy(dtype=float)[pos] if name in table.columns else None

        self.vm, self.vo, self.p = (column("volume_mobile"), column("volume_obstacle"),
                                    column("power"))

    def _sector_max(self, last: np.ndarray) -> list:
        """The largest sector depth of each contact's rows at its last instant [m]."""
        valid = self.codes >= 0
        codes = np.where(valid, self.codes, 0)
        at = np.flatnonzero(valid & (self.table["instant"].to_numpy(dtype=float) == last[codes]))
        values = self.table["depth_mobile_sector"].to_numpy(dtype=float)[at]
        out = np.full(len(self.names), -np.inf)
        np.maximum.at(out, codes[at], np.where(np.isnan(values), -np.inf, values))
        counted = np.bincount(codes[at][~np.isnan(values)], minlength=len(self.names))
        out[counted == 0] = np.nan
        # -0.0 and 0.0 tie: the one pandas' max keeps
        signed = np.unique(codes[at][(values == 0) & np.signbit(values)])
        for c in signed[out[signed] == 0]:
            out[c] = float(self.table["depth_mobile_sector"].iloc[at[codes[at] == c]].max())
        return out.tolist()

    def reaches(self, targets: list, replaced: list) -> np.ndarray:
        """Whether a time can be found for each contact's target depth [m] (False where
        :meth:`time_to` returns NaN: its deepest depth
        since a replacement is below a positive target; a NaN depth of a finite volume is
        beyond the relation's range, deeper than any target)."""
        n = len(self.names)
        if n == 0:
            return np.zeros(0, dtype=bool)
        target = np.array(targets, dtype=float)
        since = np.array([-np.inf if r is None else r for r in replaced], dtype=float)
        gcode = self.codes[self.pos]
        depth = self.d
        if self.vm is not None:
            depth = np.where(np.isnan(depth) & np.isfinite(self.vm), np.inf, depth)
        usable = ~np.isnan(depth) & np.isfinite(self.t) & (self.t >= since[gcode])
        deepest = np.full(n, np.nan)
        np.fmax.at(deepest, gcode[usable], depth[usable])
        return np.isfinite(target) & ~((target > 0) & ~(deepest >= target))

    def obstacle_wears(self, k: int) -> bool:
        """Whether contact ``k``'s obstacle volume is not 0 at some instant."""
        if self.vo is None:
            return False
        return bool(np.nan_to_num(self.vo[self.start[k]:self.end[k]]).any())

    def time_to(self, k: int, target: float, replaced: float | None, reached: bool,
                record: dict, geometry) -> tuple[float, str]:
        """The instant [table time unit] at which contact ``k``'s tube reaches ``target`` [m]
        (NaN where its rows do not reach it by the last instant), and the method: its depth
        model's :meth:`~fretwear.table.DepthModel.time_to` (:data:`FROM_MODEL`), built once
        from its ``record`` and global rows (:func:`~fretwear.table.depth_build.record_model`);
        where the law or the geometry is not known, its rows interpolated
        (:func:`~fretwear.table.depth_rows.rows_time`, :data:`INTERPOLATED`)."""
        model = self.model(k, record, geometry)
        if not reached:
            return math.nan, INTERPOLATED if model is None else FROM_MODEL
        if target <= 0:  # reached at once: the start of the tube in place
            return self._start(k, replaced), INTERPOLATED if model is None else FROM_MODEL
        if model is not None:
            found = float(model.time_to(target))
            if math.isfinite(found):
                return found, FROM_MODEL
        s = slice(self.start[k], self.end[k])
        return rows_time(self.t[s], self.d[s], target,
                         origins=None if self.origin is None else self.origin[s],
                         replaced=replaced,
                         volume_mobile=None if self.vm is None else self.vm[s]), INTERPOLATED

    def _start(self, k: int, replaced: float | None) -> float:
        """The first instant of contact ``k``'s tube in place [table time unit]: its
        replacement, 0 for a new tube, else its first row's instant."""
        if replaced is not None:
            return float(replaced)
        first = self.start[k]
        new = self.origin is None or self.origin[first] == 0
        return 0.0 if new else float(self.t[first])

    def model(self, k: int, record: dict, geometry):
        """Contact ``k``'s :class:`~fretwear.table.DepthModel` (made once), None where its
        law or geometry is not known, or its record cannot make one (a record read back from a
        part file that lacks what the model needs; a case never gives sectors under a law not
        linear in time, theory §3)."""
        if k in self._models:
            return self._models[k]
        model = None
        plain = {key: None if isinstance(value, float) and math.isnan(value) else value
                 for key, value in record.items()}  # a missing value: None
        if geometry is not None and ContactModels.law(plain.get("law")) is not None \
                and self.vm is not None:
            s = slice(self.start[k], self.end[k])
            sectors = self._sector_powers(k) if self.sectored[k] else None
            try:
                if self.sectored[k] and sectors is None:
                    raise InputError("no sector powers")
                model = record_model(
                    plain, instants=self.t[s], depths=self.d[s],
                    origins=None if self.origin is None else self.origin[s],
                    volume_mobile=self.vm[s],
                    volume_obstacle=None if self.vo is None else self.vo[s],
                    power=self.power[k], geometry=geometry,
                    sector_powers=sectors)
            except (InputError, KeywordError, TypeError, ValueError):
                model = None
        self._models[k] = model
        return model

    def _sector_powers(self, k: int):
        """Each sector's wear power [W] at contact ``k``'s last instant (``sector_power``),
        by sector; None without them. The rows of every contact are found once."""
        if self._sector_rows is None:
            table, n = self.table, len(self.names)
            valid = (self.codes >= 0) & table["sector"].notna().to_numpy()
            codes = np.where(valid, self.codes, 0)
            last = np.asarray(self.instant, dtype=float)[codes]
            at = np.flatnonzero(valid & (table["instant"].to_numpy(dtype=float) == last))
            at = at[np.lexsort((table["sector"].to_numpy(dtype=float)[at], codes[at]))]
            powers = (table["sector_power"].to_numpy(dtype=float)[at]
                      if "sector_power" in table.columns else np.full(at.size, np.nan))
            self._sector_rows = (powers, np.searchsorted(codes[at], np.arange(n)),
                                 np.searchsorted(codes[at], np.arange(n), side="right"))
        powers, start, end = self._sector_rows
        mine = powers[start[k]:end[k]]
        return mine if mine.size and np.isfinite(mine).all() else None
