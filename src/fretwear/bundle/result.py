"""What a bundle run returns: every contact's wear table, the same as a Dataset, the failures,
and a ranking of the contacts by worn depth."""

from __future__ import annotations

import math
import numbers
from concurrent.futures import Future
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.manifest import IDENTITY
from fretwear.bundle.read_ahead import ReadAhead
from fretwear.bundle.result_dataset import build_dataset
from fretwear.bundle.summary_quantities import ContactQuantities
from fretwear.bundle.table_file import SUMMARY_COLUMNS, contact_pieces, read_columns
from fretwear.errors import InputError, KeywordError
from fretwear.table.depth_rows import (
    FROM_TABLE,
    METHODS,
    ContactModels,
)
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT

#: The columns of :attr:`BundleResult.contacts` a contact's depth model is built from
#: (:func:`fretwear.table.depth_build.record_model`).
RECORD_KEYS = ("contact_type", "dimensions", "law", "coefficients_mobile",
               "coefficients_obstacle", "time_scale", "origin", "tube_replacement",
               "wall_thickness", "depth_limit", "sector_coefficients")

#: Columns of :attr:`BundleResult.errors`.
ERROR_COLUMNS = ("contact", "error", "message", "rows_kept")


@dataclass
class BundleResult:
    """The results of :func:`fretwear.bundle.run_bundle`.

    Attributes
    ----------
    table : DataFrame
        Every contact's wear table (columns of :func:`fretwear.table.wear_table`, units in
        :data:`fretwear.table.COLUMNS`), the identity columns ``contact, tube_row, tube_column,
        support, node, history`` in front, contacts in manifest order. With an output directory
        of Parquet tables, read from ``table_file`` when first asked for (then kept).
    errors : DataFrame
        One row per contact that failed (``error`` = the error class, ``message``,
        ``rows_kept`` False), failed this run but keeps an earlier run's rows (status
        ``stale``: ``rows_kept`` True, the message names the earlier part), or whose depth left
        its relation's range (``error`` = ``RangeWarning``, ``rows_kept`` True: its rows are in
        the table with NaN depths).
    warnings : DataFrame
        ``contact, category, message``: every warning of every contact, captured in its task.
    contacts : DataFrame
        One row per contact: identity, ``status`` (``done``, ``failed``, ``skipped`` = done by an
        earlier run with the same inputs, ``stale`` = failed this run, the rows of an earlier
        run kept in the table and in the output directory), ``samples``, ``seconds`` (compute time),
        ``power`` [W], ``time_unit``, ``origin`` and ``tube_replacement`` [time unit],
        ``wall_thickness`` [m] (when given), ``depth_limit`` [-], and the wear table's
        ``contact_type``, ``dimensions`` (dict: lengths [m], angles [deg]), ``law``,
        ``coefficients_mobile`` and ``coefficients_obstacle`` (dicts, the law's units; the
        obstacle's None when it does not wear) and ``time_scale`` [s per time unit] (None for
        a failed contact).
    stats : dict
        ``contacts``, ``done``, ``failed``, ``skipped``, ``stale``, ``seconds`` (wall time of
        the run [s], from the call to the results assembled and the output files written),
        ``startup_seconds`` (starting or joining the cluster), ``contacts_per_s`` and
        ``samples_per_s`` (computed contacts and history samples per second of the run without
        the start-up), ``samples``, ``workers``, ``two_pass_contacts`` (contacts computed
        this run whose history was read twice: KWU-EPRI without both FNOR_MAXI and VTAN_MAXI;
        with them, or any other law, once).
    output : str or None
        The output directory.
    cases : dict of str to WearCase
        The wear case of every contact whose rows are in the table as computed from it (done
        this run, or skipped: done by an earlier run with the same inputs), as the bundle
        built it once from the manifest: its wall (``cases[c].wall``), window, restart.
    table_file : str or None
        The Parquet file ``table`` is read from on demand (``table=None``): the client never
        holds a bundle's whole table unless asked (issue 28); :meth:`summary` reads only the
        columns it needs from it.
    """

    table: pd.DataFrame | None = field(repr=False)
    errors: pd.DataFrame
    warnings: pd.DataFrame
    contacts: pd.DataFrame
    stats: dict[str, Any] = field(default_factory=dict)
    output: str | None = None
    cases: dict[str, Any] = field(default_factory=dict, repr=False)
    table_file: str | None = field(default=None, repr=False)
    _dataset: Any = field(default=None, repr=False)
    #: ``summary()``'s rankings, one per :func:`summary_key`: a result is never changed once
    #: built, so a ranking is computed once and read after (issue 28); a ranking still being
    #: made (the run's limit's, by the bundle's end beside the rest: :func:`summarize_ahead`)
    #: is its future, waited for when first read
    _summaries: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def dataset(self):
        """The table as an xarray Dataset: ``contact × instant`` (× ``sector`` in sector mode),
        the identity columns, ``time_unit``, ``wall_thickness`` [m] and ``status`` as
        coordinates along ``contact`` (every one, empty ones too: NaN or ""; whole numbers as
        int64), units and meanings in ``attrs``."""
        if self._dataset is None:
            self._dataset = build_dataset(self.table, self.contacts)
        return self._dataset

    def summary(self, limit: float | None = None, *, limit_m: float | None = None,
                wall_thickness: float | None = None) -> pd.DataFrame:
        """Contacts ranked by the tube's worn depth at the last instant, deepest first.

        Parameters
        ----------
        limit : float, optional
            Depth limit as a fraction of the wall [-]; default each contact's ``depth_limit``
            (its wear case's, 0.4 = 40 % through-wall unless set); used where the wall
            thickness is known (the case's ``wall_thickness``, or the manifest's
            ``wall_thickness_m``).
        limit_m : float, optional
            Depth limit [m] for every contact instead (when no wall thickness is given); give
            ``limit`` or ``limit_m``, not both.
        wall_thickness : float, optional
            Wall thickness [m] of every tube, where the manifest gives none.

        Computed once per ``(limit, limit_m, wall_thickness)`` and kept on the result (a
        result is not changed once built); each call returns a copy, so that a caller's
        change to its ranking is not seen by the next call.

        Returns
        -------
        DataFrame
            ``rank``, identity columns, ``instant`` (last, in the contact's time unit),
            ``time_unit`` (the unit of ``instant`` and ``time_to_limit``, per contact: a manifest
            may give contacts different units), ``power`` [W], ``depth`` [m] (global tube depth
            ``depth_mobile``), ``depth_sector_max`` [m] (the deepest sector, sector mode),
            ``wall_thickness`` [m], ``depth_fraction`` (depth / wall) [-], ``limit_depth`` [m],
            ``time_to_limit`` (instant at which the depth reaches the limit, in ``time_unit``; NaN
            if not reached by the last instant), ``time_to_limit_method`` and ``note`` (beyond the
            relation's range, ...). A depth beyond its relation's range (NaN) ranks first. Where the
            limit is the contact's own (its case's ``depth_limit`` of its own wall, whether by
            default or asked for here) and its table has ``limit_instant``, the time is that instant
            (law and geometry inverted) when it is reached by the last instant, NaN otherwise;
            ``limit_forecast`` (in ``time_unit``) is that instant wherever it lies, also beyond
            the last instant (the wear table's ``limit_instant``: the law and geometry inverted
            at the history's power, inf if never reached), NaN for another limit. Any other
            limit: the contact's depth model's :meth:`~fretwear.table.DepthModel.time_to` (the
            one meaning of the time to a limit, docs/uncertainty.md §1: the first instant the
            tube in place reaches it, a restart's earlier rows included; built once from the
            contact's record and rows, :func:`fretwear.table.depth_build.record_model`); where
            the contact's law or geometry is not known, depth(t) interpolated between the
            instants (monotone cubic) and inverted.
            ``time_to_limit_method`` says which per contact, ``attrs["time_to_limit"]`` lists
            them.

        Raises
        ------
        KeywordError
            ``limit`` and ``limit_m`` given together, or a ``limit`` outside (0, 1] (a
            fraction of the wall: 0.4, not 40).
        InputError
            A ``limit_m`` that is not a finite number > 0.
        """
        key = summary_key(limit, limit_m, wall_thickness)
        try:
            ranking = self._summaries.get(key)
        except TypeError:  # an unhashable argument: summarize says what is wrong with it
            ranking, key = None, None
        if isinstance(ranking, Future):
            ranking = self._summaries[key] = ranking.result()
        if ranking is None:
            rows = self._summary_rows()
            try:
                ranking = summarize(rows, self.contacts, limit=limit, limit_m=limit_m,
                                    wall_thickness=wall_thickness)
            finally:
                if isinstance(rows, ReadAhead):
                    rows.close()
            if key is None:
                return ranking
            self._summaries[key] = ranking
        return ranking.copy()


    def _summary_rows(self):
        """The table, or the columns :func:`summarize` reads from ``table_file`` when the
        table is not read (read for this call, not kept): :func:`summary_rows`."""
        if self._table is None and self.table_file is not None:
            return summary_rows(self.table_file)
        return self.table


def summary_key(limit: float | None = None, limit_m: float | None = None,
                wall_thickness: float | None = None) -> tuple:
    """The key of :meth:`BundleResult.summary`'s rankings: the type in it (limit=True, refused,
    is not the cached limit=1)."""
    return tuple((type(v), v) for v in (limit, limit_m, wall_thickness))


def summarize_ahead(rows: ReadAhead, contacts: pd.DataFrame, limit: float | None
                    ) -> pd.DataFrame:
    """:func:`summarize` of a written table's pieces being read (:func:`summary_rows`) for the
    limit ``limit`` [-], ``rows`` closed after: the bundle's end makes it in a thread while it
    writes the rest (issue 28: the summary was 0.6-0.9 s after the last result, alone)."""
    try:
        return summarize(rows, contacts, limit=limit, limit_m=None, wall_thickness=None)
    finally:
        rows.close()


def summary_rows(table_file, depth: int = 1) -> ReadAhead:
    """The columns of a written Parquet table :func:`summarize` reads, a piece of whole
    contacts at a time (:func:`~fretwear.bundle.table_file.contact_pieces`; issue 28: the whole
    table's columns and their copies took the client's memory up by 0.7 GB at 10^5
    contacts), else the whole table as one piece, read in a thread (:class:`ReadAhead`:
    ``depth`` pieces ahead of the one summed up, pyarrow reading without the GIL); its
    ``close()`` stops the reading."""
    return ReadAhead(_pieces_of(Path(table_file)), depth)


def _pieces_of(path: Path):
    pieces = contact_pieces(path, SUMMARY_COLUMNS)
    if pieces is None:  # contact only factorised (ContactQuantities)
        yield read_columns(path, SUMMARY_COLUMNS, categorical=("contact",))
    else:
        yield from pieces


def _get_table(self) -> pd.DataFrame:
    if self._table is None and self.table_file is not None:
        self._table = read_columns(Path(self.table_file))
        self._table["contact"] = self._table["contact"].astype(str)
    return self._table


def _set_table(self, table) -> None:
    self._table = table


# the field ``table`` (given to the constructor, compared, copied by dataclasses.replace) kept
# as ``_table``, read from ``table_file`` on first use
BundleResult.table = property(_get_table, _set_table, doc=BundleResult.__doc__ and
                              "Every contact's wear table (see the class' attributes).")


def check_limit(limit) -> None:
    """``limit`` is None or a fraction of the wall, 0 < limit <= 1 [-]; a KeywordError naming
    it otherwise (:func:`fretwear.bundle.run_bundle`'s ``limit``, checked before any run)."""
    if limit is None:
        return
    ok = isinstance(limit, numbers.Real) and not isinstance(limit, bool | np.bool_)
    if not (ok and math.isfinite(limit) and 0 < limit <= 1):
        raise KeywordError(f"limit must be a fraction of the wall, 0 < limit <= 1 [-] (0.4: "
                           f"40 % through-wall), or None for each contact's depth_limit; got "
                           f"{limit!r}")


def summarize(table, contacts: pd.DataFrame, *, limit: float | None,
              limit_m: float | None, wall_thickness: float | None) -> pd.DataFrame:
    """The ranking of :meth:`BundleResult.summary`.

    ``table`` is the table, or its rows in pieces each holding whole contacts, in the table's
    order (an iterable of DataFrames: :func:`fretwear.bundle.table_file.contact_pieces`): a
    contact's values depend on its own rows only, so the ranking is the whole table's.
    The per-contact quantities are taken over a piece at once (:class:`ContactQuantities`);
    a contact's depth model (:meth:`ContactQuantities.time_to`) is inverted only for the contacts
    whose depth reaches the limit.
    """
    if limit is not None and limit_m is not None:
        raise KeywordError(f"limit={limit!r} (a fraction of the wall) and limit_m={limit_m!r} "
                           "(a depth [m]) given together; give one of them")
    check_limit(limit)  # as run_bundle's: 40 given for 40 % is refused, not a depth past the wall
    if limit_m is not None and not (0 < limit_m and math.isfinite(limit_m)):
        raise InputError(f"limit_m must be a depth > 0 [m], got {limit_m!r}")
    lookup = _Lookup(contacts)
    models = ContactModels()
    rows: dict[str, list] = {name: [] for name in _RANKED}
    for piece in [table] if isinstance(table, pd.DataFrame) else table:
        for name, values in _piece_rows(piece, lookup, models,
                                        (limit, limit_m, wall_thickness)).items():
            rows[name] += values
    return _ranking(rows, contacts, limit, limit_m)


#: The ranking's columns :func:`_piece_rows` gives, in their order (before the identity's).
_RANKED = ("contact", "instant", "time_unit", "power", "depth", "depth_sector_max",
           "wall_thickness", "depth_fraction", "limit_depth", "time_to_limit", "limit_forecast",
           "time_to_limit_method", "note")


def _piece_rows(table: pd.DataFrame, lookup: _Lookup, models: ContactModels,
                limits: tuple) -> dict[str, list]:
    """The ranking's rows (unranked) of the contacts of ``table``, in their order there, as
    columns (:data:`_RANKED`: a dict per contact was a third of the summary, issue 28);
    ``limits``: :func:`summarize`'s ``(limit, limit_m, wall_thickness)``."""
    limit, limit_m, wall_thickness = limits
    # the wear table's own limit instant (law and geometry inverted), for the case's limit
    given = "limit_instant" in table.columns and limit_m is None
    per = ContactQuantities(table, given)
    where = lookup.rows_of(per.names)
    walls = lookup("wall_thickness", per.names, where)
    owns = lookup("depth_limit", per.names, where)
    replacements = lookup("tube_replacement", per.names, where)
    units = lookup("time_unit", per.names, where)
    # each contact's record (its wear case's values), the depth model of its table: made for
    # the contacts whose time to the limit is sought only (a dict and a geometry looked up for
    # each of 10^5 contacts was a fifth of the summary, issue 28)
    known = [lookup(key, per.names, where) for key in RECORD_KEYS]
    types, dimensions = (known[RECORD_KEYS.index(key)] for key in ("contact_type", "dimensions"))
    targets, replaced_at, own_limit, wall_of, fractions = [], [], [], [], []
    for k in range(len(per.names)):
        given_wall = walls[k]
        wall = math.nan if given_wall is None or pd.isna(given_wall) else float(given_wall)
        its_wall = math.isfinite(wall)
        if not its_wall and wall_thickness is not None:
            wall = float(wall_thickness)
        own = owns[k]
        own = DEFAULT_DEPTH_LIMIT if own is None or pd.isna(own) else float(own)
        fraction = own if limit is None else limit
        # the limit of the table's limit_instant: the case's depth_limit of its own wall
        own_limit.append(its_wall and fraction == own)
        target = (fraction * wall if math.isfinite(wall) and limit_m is None
                  else (limit_m if limit_m is not None else math.nan))
        replaced = replacements[k]
        replaced = None if replaced is None or pd.isna(replaced) else float(replaced)
        targets.append(target)
        replaced_at.append(replaced)
        wall_of.append(wall)
        fractions.append(per.depth[k] / wall if wall > 0 else math.nan)
    reached = per.reaches(targets, replaced_at)
    times, forecasts, methods, notes = [], [], [], []
    for k, target in enumerate(targets):
        if given and per.has_limit[k] and own_limit[k]:
            # reached by the last instant: by the table's depths, or the instant itself
            t_lim = per.limit_instant[k]
            t_lim = t_lim if reached[k] or t_lim <= per.instant[k] else math.nan
            t_lim = math.nan if math.isinf(t_lim) else t_lim
            method = FROM_TABLE
        elif math.isfinite(target):
            t_lim, method = per.time_to(
                k, target, replaced_at[k], bool(reached[k]),
                dict(zip(RECORD_KEYS, [values[k] for values in known], strict=True)),
                models.geometry(types[k], dimensions[k]))
        else:
            t_lim, method = math.nan, "no limit: give the wall thickness or limit_m"
        # the table's forecast for the contact's own limit, also beyond the last instant
        forecasts.append(per.limit_instant[k] if given and per.has_limit[k] and own_limit[k]
                         else math.nan)
        first_nan = per.first_nan[k]
        times.append(t_lim)
        methods.append(method)
        notes.append("" if first_nan is None
                     else f"depth beyond the relation's range from instant {first_nan:g}")
    return dict(zip(_RANKED, (
        per.names, per.instant, [None if u is None or pd.isna(u) else u for u in units],
        per.power, per.depth, per.sector_max, wall_of, fractions, targets, times, forecasts,
        methods, notes), strict=True))


def _ranking(rows: dict[str, list], contacts: pd.DataFrame, limit: float | None,
             limit_m: float | None) -> pd.DataFrame:
    """:func:`summarize`'s ranking of its rows (columns of :data:`_RANKED`): identity
    columns, ranks, ``attrs``."""
    # no row: the frame a list of no dicts makes (object columns; empty lists: float64)
    out = pd.DataFrame(rows if rows["contact"] else [], columns=list(_RANKED))
    ident = [c for c in IDENTITY if c != "contact" and c in contacts.columns]
    if len(out):
        out = out.merge(contacts[["contact", *ident]], on="contact", how="left")
    else:  # every contact failed: an empty ranking with every column
        out = out.assign(**{c: pd.Series(dtype=contacts[c].dtype) for c in ident})
    beyond = out["depth"].isna()
    out = (out.assign(_beyond=beyond).sort_values(["_beyond", "depth"],
                                                  ascending=[False, False], kind="stable")
           .drop(columns="_beyond").reset_index(drop=True))
    out.insert(0, "rank", np.arange(1, len(out) + 1))
    front = ["rank", "contact", *ident]
    out = out[front + [c for c in out.columns if c not in front]]
    methods = [m for m in out["time_to_limit_method"].unique() if m in METHODS]
    out.attrs["time_to_limit"] = "; ".join(methods) if methods else "no limit"
    out.attrs["limit"] = limit
    out.attrs["limit_m"] = limit_m
    return out


class _Lookup:
    """The contacts' values of :func:`summarize`'s pieces: ``info.at[name, column]`` for each
    contact name (None where the contact or the column is missing), each column made a list
    once per summary and the ids' uniqueness asked once (not once a piece and column: at 10^5
    contacts in 19 pieces that was 3.4 s of the summary); a name's row found once for every
    column (a dict of the contacts per column took 0.6 s at 10^4 contacts)."""

    def __init__(self, contacts: pd.DataFrame) -> None:
        self.info = contacts.set_index("contact") if len(contacts) else contacts
        self.index = pd.Index(contacts["contact"]) if contacts["contact"].is_unique else None
        self.ids = None if self.index is None else contacts["contact"].tolist()
        self.first: dict | None = None  # id -> its row, made when first asked
        self.columns: dict[str, list] = {}

    def rows_of(self, names: list) -> np.ndarray | slice | None:
        """Each name's row in the contacts (-1: not there), a slice where they are rows
        that follow one another (a piece of a bundle's table: its contacts in manifest
        order, told by one list comparison: the index's get_indexer of a piece's names took
        20 ms a piece at 10^5 contacts, issue 28); None where contact ids repeat."""
        if self.index is None:
            return None
        if self.first is None:
            self.first = {name: i for i, name in enumerate(self.ids)}
        start = self.first.get(names[0], -1) if names else -1
        if start >= 0 and self.ids[start:start + len(names)] == names:
            return slice(start, start + len(names))
        return self.index.get_indexer(pd.Index(names, dtype=object))

    def __call__(self, column: str, names: list, where: np.ndarray | slice | None) -> list:
        """The contacts' ``column`` for ``names``, ``where`` their rows (:meth:`rows_of`)."""
        info = self.info
        if column not in info.columns:
            return [None] * len(names)
        if where is None:  # ids repeat
            return [info.at[name, column] if name in info.index else None for name in names]
        values = self.columns.get(column)
        if values is None:  # the Series' own scalars, as iterating it gives them
            values = self.columns[column] = info[column].tolist()
        if isinstance(where, slice):
            return values[where]
        return [values[i] if i >= 0 else None for i in where.tolist()]
