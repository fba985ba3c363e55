"""Wear power of a contact history: total, per block and per angular sector (theory §2-§3).

The wear power is the time average over a window [t_start, t_end] (T = t_end - t_start) of the
product of the normal force and the sliding speed:

    P = (1/T) ∫ |Fn|·‖Vt‖ dt,   ‖Vt‖ = √(Vt1² + Vt2²).

The integrand g = Fn·‖Vt‖ is taken linear between samples (trapezoid rule); an interval whose left
sample sticks contributes nothing; free flight (Fn = 0) contributes zero but counts in T. The
window is cut into ``blocks`` equal blocks; a window bound or block edge inside an interval splits
it and each part gets the exact integral of the linear interpolant,
∫_a^b g dt = (b - a)(g(a) + g(b))/2. Each interval goes to the sector of its left sample's contact
angle, so the sector powers add up to the total.

The computation is a reduction: :class:`PowerAccumulator` folds chunks of consecutive samples into
partial sums that merge associatively (chunked result == one-shot result), so a history larger
than memory is streamed from a file and the same code can run on parallel workers.
"""

from __future__ import annotations

import copy
import functools
import math
import os
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from fretwear.errors import (
    HistoryError,
    InputError,
    KeywordError,
    StationarityWarning,
)
from fretwear.history import DEFAULT_CHUNK_SIZE, ContactHistory
from fretwear.io import history_time_range, iter_history_blocks, read_history
from fretwear.laws import KwuEpriAccumulator, KwuEpriMaxima
from fretwear.power._kwu import kwu_counts, merge_kwu
from fretwear.power.kernels import BLOCK_STATS, GROUP_FIELDS, fused
from fretwear.power.ranges import (
    check_finite_power,
    check_finite_sums,
    check_window_length,
    out_of_range,
    speed_scale,
)
from fretwear.power.result import PowerResult, own_result, window_powers
from fretwear.power.statistics import finalize_statistics, merge_groups
from fretwear.sectors import sector_edges as _sector_edges


def _edges(sectors) -> np.ndarray:
    """:func:`fretwear.sectors.sector_edges` [deg], those of a count of equal sectors computed
    once (numpy.linspace costs a bundle's contact 10 µs an accumulator; a new array each time:
    the accumulator owns it)."""
    if isinstance(sectors, int | np.integer) and not isinstance(sectors, bool):
        return np.array(_equal_edges(int(sectors)))
    return _sector_edges(sectors)


@functools.lru_cache(maxsize=64)
def _equal_edges(count: int) -> tuple[float, ...]:
    return tuple(_sector_edges(count).tolist())


_SAMPLE = ("time", "normal_force", "vt1", "vt2", "dy", "dz", "stick")
_SLIDING = BLOCK_STATS.index("sliding_distance")  # the statistics linear in the speed


def _as_bound(value, keyword: str) -> float | None:
    if value is None:
        return None
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{keyword} must be a time in seconds, got {value!r}") from None
    if not math.isfinite(x):
        raise InputError(f"{keyword} must be a finite time in seconds, got {value!r}")
    return x


#: Most blocks of a window (each holds a power per sector and its statistics: some 100 bytes a
#: block for 4 sectors, 100 MB at this bound).
MAX_BLOCKS = 1_000_000


class PowerAccumulator:
    """Streaming reduction of the wear power and contact statistics.

    Parameters
    ----------
    t_start, t_end : float, optional
        Window [s]. Required when ``blocks > 1`` (the block edges must be known before the data).
        With one block, a missing bound is the first / last instant seen.
    blocks : int
        Number of equal blocks B >= 1.
    sectors : int or sequence of float, optional
        Count of equal sectors or edges [deg] (see :func:`fretwear.sectors.sector_edges`).
    force_threshold : float
        Contact / impact force threshold [N] for the statistics, >= 0.
    minimum_rest_time : float
        Minimum rest [s] below the threshold separating two impacts, >= 0.
    backend : str
        ``"auto"`` (numba when installed), ``"numba"`` or ``"numpy"``.
    kwu : tuple, optional
        ``(force_max, speed_max)``, each [N], [m/s] or None (Code_Aster FNOR_MAXI, VTAN_MAXI):
        also reduce, in the same pass, the KWU-EPRI class statistics over the window's samples
        (:class:`fretwear.laws.KwuEpriAccumulator`) when both are given, else the window's
        maxima (:class:`fretwear.laws.KwuEpriMaxima`: the counts then take a second pass, see
        :mod:`fretwear.laws.kwu_stream`). The result's ``kwu`` holds it.

    Notes
    -----
    The partial state is: the [B, N] block × sector integrals of g, per-block statistics
    integrals, the largest force, the impacts in mergeable form
    (:func:`fretwear.power.statistics.merge_groups`), and the first and last samples seen.
    ``update`` accepts consecutive chunks that share their boundary sample or not (the interval
    between the last sample kept and the next chunk's first is then added). ``merge`` combines two
    accumulators over adjacent stretches of time, in either order; it is associative.

    Examples
    --------
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0, 3.0], normal_force=[1.0, 1.0, 1.0, 1.0],
    ...                    vt1=[2.0, 2.0, 2.0, 2.0], vt2=[0.0] * 4)
    >>> acc = PowerAccumulator(t_start=0.0, t_end=3.0, blocks=3)
    >>> _ = acc.update(h.window(0.0, 1.0)).update(h.window(2.0, 3.0))
    >>> acc.result().blocks.tolist()
    [2.0, 2.0, 2.0]
    """

    def __init__(self, *, t_start: float | None = None, t_end: float | None = None,
                 blocks: int = 1, sectors: int | Sequence[float] | None = None,
                 force_threshold: float = 0.0, minimum_rest_time: float = 0.0,
                 backend: str = "auto",
                 kwu: tuple[float | None, float | None] | None = None) -> None:
        if isinstance(blocks, bool) or not isinstance(blocks, int | np.integer):
            raise InputError(f"blocks must be an integer number of blocks >= 1, got {blocks!r}")
        if blocks < 1:
            raise InputError(f"blocks must be >= 1 (number of equal blocks), got {blocks}")
        if blocks > MAX_BLOCKS:  # blocks = 4831838208 tried to allocate 36 GiB (issue 29)
            raise InputError(f"blocks (NB_BLOC) = {blocks} is more than {MAX_BLOCKS:,} blocks "
                             "(each holds a power per sector: the memory grows with them); "
                             "give fewer blocks, at most the history's samples to be useful")
        self.t_start = _as_bound(t_start, "t_start")
        self.t_end = _as_bound(t_end, "t_end")
        if self.t_start is not None and self.t_end is not None and self.t_end <= self.t_start:
            raise InputError(
                f"empty window: t_end = {self.t_end!r} s is not after t_start = "
                f"{self.t_start!r} s; give t_start < t_end")
        self.blocks = int(blocks)
        if self.blocks > 1 and (self.t_start is None or self.t_end is None):
            missing = "t_start" if self.t_start is None else "t_end"
            raise InputError(
                f"{missing} is needed to cut the window into {self.blocks} blocks before the data "
                "streams; give both t_start and t_end (or blocks=1)")
        if sectors is None:
            self.sector_edges = None
        else:
            try:
                self.sector_edges = _edges(sectors)
            except InputError as exc:
                raise InputError(f"sectors: {exc}") from None
        for name, value in (("force_threshold", force_threshold),
                            ("minimum_rest_time", minimum_rest_time)):
            if not (isinstance(value, int | float | np.number) and value >= 0
                    and math.isfinite(value)):
                raise InputError(f"{name} must be a finite number >= 0, got {value!r}")
        self.force_threshold = float(force_threshold)
        self.minimum_rest_time = float(minimum_rest_time)
        self.backend = backend
        self._kernel = fused(backend)
        lo = -math.inf if self.t_start is None else self.t_start
        hi = math.inf if self.t_end is None else self.t_end
        self._lo, self._hi = lo, hi
        if self.blocks == 1:
            self._block_edges = np.array([lo, hi])
        else:
            self._block_edges = lo + (hi - lo) * np.arange(self.blocks + 1) / self.blocks
            self._block_edges[-1] = hi
        self._edges = (np.array([-180.0, 180.0]) if self.sector_edges is None
                       else self.sector_edges)
        ns = self._edges.size - 1
        self.power = np.zeros((self.blocks, ns))
        self.block_stats = np.zeros((self.blocks, len(BLOCK_STATS)))
        self.force_max = -math.inf
        self.groups = np.zeros(len(GROUP_FIELDS))
        self.first: np.ndarray | None = None   # first sample seen, layout _SAMPLE (NaN = absent)
        self.last: np.ndarray | None = None
        self.samples = 0
        self.name = ""
        self.kwu: KwuEpriAccumulator | KwuEpriMaxima | None = None
        if kwu is not None:
            force_max, speed_max = kwu
            if force_max is None or speed_max is None:
                self.kwu = KwuEpriMaxima(t_start=self.t_start, t_end=self.t_end)
            else:
                self.kwu = KwuEpriAccumulator(force_max, speed_max, t_start=self.t_start,
                                              t_end=self.t_end)
                self.kwu.given = (force_max, speed_max)

    # ------------------------------------------------------------------ reduction
    def _empty_like(self) -> PowerAccumulator:
        new = object.__new__(PowerAccumulator)
        new.__dict__.update(self.__dict__)
        new.power = np.zeros_like(self.power)
        new.block_stats = np.zeros_like(self.block_stats)
        new.force_max = -math.inf
        new.groups = np.zeros(len(GROUP_FIELDS))
        new.first = new.last = None
        new.samples = 0
        new.kwu = None
        return new

    def _reduce(self, t, fn, vt1, vt2, dy, dz, stick) -> None:
        if self.sector_edges is not None and self._edges.size > 2 and dy is None:
            raise HistoryError(
                f"contact history {self.name!r} has no 'dy'/'dz' channels: angular sectors need "
                "the local displacements (DYLOC/DZLOC, or VINT5/VINT6); give them or drop sectors")
        s = self._kernel(t, fn, vt1, vt2, dy, dz, stick, self._lo, self._hi, self._block_edges,
                         self._edges, self.force_threshold, self.minimum_rest_time)
        if out_of_range(s):  # √(Vt1²+Vt2²) may have over/underflowed: again, scaled exactly
            scale = speed_scale(vt1, vt2)
            if scale != 1.0:
                s = self._kernel(t, fn, vt1 * scale, vt2 * scale, dy, dz, stick, self._lo,
                                 self._hi, self._block_edges, self._edges,
                                 self.force_threshold, self.minimum_rest_time)
                with np.errstate(over="ignore"):  # an overflow is reported just below
                    s.power[...] /= scale
                    s.block_stats[:, _SLIDING] /= scale
            check_finite_sums(s, t, fn, vt1, vt2, self.name)
        if self.first is None:  # nothing folded in yet: the sums are zeros, and zeros + the
            # chunk's (fresh arrays, summed from +0.0: never -0.0) are the chunk's own
            self.power, self.block_stats = s.power, s.block_stats
            self.force_max = max(self.force_max, s.force_max)
            self.groups = s.groups  # merge_groups(zeros, g) is a copy of g
            return
        self.power += s.power
        self.block_stats += s.block_stats
        self.force_max = max(self.force_max, s.force_max)
        self.groups = merge_groups(self.groups, s.groups, self.minimum_rest_time)

    @staticmethod
    def _sample(arrays: dict, k: int) -> np.ndarray:
        return np.array([np.nan if arrays[c] is None else float(arrays[c][k]) for c in _SAMPLE])

    def _bridge(self, left: np.ndarray, right: np.ndarray) -> None:
        """Add the interval between two samples (left end of an interval is ``left``)."""
        pair = np.vstack([left, right])
        cols = [None if np.isnan(pair[0, k]) else np.ascontiguousarray(pair[:, k])
                for k in range(len(_SAMPLE))]
        self._reduce(*cols)

    def update(self, chunk: ContactHistory) -> PowerAccumulator:
        """Fold the next chunk of consecutive samples in; returns ``self``.

        Parameters
        ----------
        chunk : ContactHistory
            Samples following those already seen: its first instant equals the last one seen
            (one-sample overlap, as :func:`fretwear.io.iter_history_chunks` yields) or comes
            after it.

        Raises
        ------
        HistoryError
            When the chunk starts before the last instant already seen (overlap or disorder).
        """
        if not isinstance(chunk, ContactHistory):
            raise InputError(
                f"update() takes a ContactHistory chunk, got {type(chunk).__name__}")
        if not self.name:
            self.name = chunk.name
        arrays = {c: getattr(chunk, c) for c in _SAMPLE}
        t = chunk.time
        shared = self.last is not None and t[0] == self.last[0]
        if self.last is not None:
            t_prev = self.last[0]
            if t[0] < t_prev:
                raise HistoryError(
                    f"contact history {chunk.name!r}: chunk starts at t = {t[0]!r} s, before the "
                    f"last instant already read ({t_prev!r} s); chunks must follow in time order "
                    "and overlap by at most one sample")
            if t[0] > t_prev:
                self._bridge(self.last, self._sample(arrays, 0))
        self._reduce(*(arrays[c] for c in _SAMPLE))
        if isinstance(self.kwu, KwuEpriAccumulator):
            self.kwu.update_velocities(t, chunk.normal_force, chunk.vt1, chunk.vt2)
        elif self.kwu is not None:
            self.kwu.update(t, chunk.normal_force, chunk.vt1, chunk.vt2)
        if self.first is None:
            self.first = self._sample(arrays, 0)
        self.last = self._sample(arrays, len(chunk) - 1)
        self.samples += len(chunk) - (1 if shared else 0)
        return self

    def merge(self, other: PowerAccumulator) -> PowerAccumulator:
        """Combine with an accumulator over an adjacent stretch of time; returns ``self``.

        ``other`` may lie before or after ``self``; the interval between them, if they do not
        share a sample, is added. Both must have the same window, blocks, sectors, threshold
        and rest time.
        """
        same = (self._lo == other._lo and self._hi == other._hi and self.blocks == other.blocks
                and np.array_equal(self._edges, other._edges)
                and self.force_threshold == other.force_threshold
                and self.minimum_rest_time == other.minimum_rest_time)
        if not same:
            raise InputError("merge(): the accumulators differ in window, blocks, sectors, "
                             "force_threshold or minimum_rest_time; build them alike")
        if other.first is None:
            return self
        if self.first is None:
            self.__dict__.update({k: (v.copy() if isinstance(v, np.ndarray) else v)
                                  for k, v in other.__dict__.items()})
            return self
        if other.first[0] >= self.last[0]:
            left, right = self, other
        elif other.last[0] <= self.first[0]:
            left, right = other, self
        else:
            raise HistoryError(
                f"merge(): the stretches [{self.first[0]!r}, {self.last[0]!r}] s and "
                f"[{other.first[0]!r}, {other.last[0]!r}] s overlap by more than one sample")
        bridge = None
        if right.first[0] > left.last[0]:
            bridge = self._empty_like()
            bridge._bridge(left.last, right.first)
        power = left.power + (bridge.power if bridge else 0.0) + right.power
        bstats = left.block_stats + (bridge.block_stats if bridge else 0.0) + right.block_stats
        groups = left.groups
        if bridge:
            groups = merge_groups(groups, bridge.groups, self.minimum_rest_time)
        groups = merge_groups(groups, right.groups, self.minimum_rest_time)
        fmax = max(left.force_max, right.force_max, bridge.force_max if bridge else -math.inf)
        shared = 1 if right.first[0] == left.last[0] else 0
        self.kwu = merge_kwu(left, right)
        self.samples = left.samples + right.samples - shared
        self.first, self.last = left.first.copy(), right.last.copy()
        self.power, self.block_stats, self.groups, self.force_max = power, bstats, groups, fmax
        self.name = self.name or other.name
        return self

    # ------------------------------------------------------------------ result
    def result(self, *, stationarity_threshold: float = 0.1,
               statistics: bool = True) -> PowerResult:
        """The wear power of the window from the data folded in so far (``statistics``
        False: its ``statistics`` None, not made).

        Raises
        ------
        HistoryError
            When no data was given or the data do not cover the window.

        Warns
        -----
        StationarityWarning
            When the block powers spread more than ``stationarity_threshold``.
        """
        if self.first is None:
            raise HistoryError("no samples were given to the wear-power accumulator")
        t0, t1 = float(self.first[0]), float(self.last[0])
        t_start = t0 if self.t_start is None else self.t_start
        t_end = t1 if self.t_end is None else self.t_end
        if t_start < t0:
            raise InputError(
                f"t_start = {t_start!r} s is before the first instant {t0!r} s of history "
                f"{self.name!r}; give t_start >= {t0!r}")
        if t_end > t1:
            raise InputError(
                f"t_end = {t_end!r} s is after the last instant {t1!r} s of history "
                f"{self.name!r}; give t_end <= {t1!r}")
        if t_end <= t_start:
            raise InputError(f"empty window [{t_start!r}, {t_end!r}] s; give t_start < t_end")
        T = t_end - t_start
        nb = self.blocks
        check_window_length(T, nb, self.name)
        edges = self._block_edges.copy()
        edges[0], edges[-1] = t_start, t_end
        total, block_powers, sectors, block_sectors = window_powers(
            self.power, nb, T, self.sector_edges is not None)
        check_finite_power(total, block_powers, T, self.name)
        mean = float(block_powers[0]) if nb == 1 else float(block_powers.mean())  # x/1 is x
        spread = 0.0 if nb == 1 or mean <= 0 else float(
            (block_powers.max() - block_powers.min()) / mean)
        if spread > stationarity_threshold:
            warnings.warn(
                f"history {self.name!r}: the {nb} block powers spread by {spread:.1%} of their "
                f"mean (> stationarity_threshold {stationarity_threshold:.1%}) over "
                f"[{t_start:g}, {t_end:g}] s; the wear laws assume a stationary power - use a "
                "longer or later window", StationarityWarning, stacklevel=3)
        stats = None if not statistics else finalize_statistics(
            self.block_stats, self.groups, self.force_max, T, self.force_threshold,
            self.minimum_rest_time)
        return own_result(total=total, blocks=block_powers, block_edges=edges, sectors=sectors,
                          sector_edges=None if self.sector_edges is None
                          else self.sector_edges.copy(),
                          t_start=t_start, t_end=t_end, duration=T, spread=spread,
                          statistics=stats, name=self.name, block_sectors=block_sectors,
                          kwu=None if self.kwu is None else copy.deepcopy(self.kwu))


def _time_range(path, chunk_size: int, read_options: dict) -> tuple[float, float]:
    """First and last instant [s] of a history file (one streaming pass)."""
    first = last = None
    for chunk in iter_history_blocks(path, chunk_size, **read_options):
        if first is None:
            first = float(chunk.time[0])
        last = float(chunk.time[-1])
    if first is None:
        raise HistoryError(f"history file {os.fspath(path)!r} holds no samples")
    return first, last


def _is_read_whole(history: Any) -> bool:
    """Whether ``history`` is a set of function files or a table that read_history reads."""
    if hasattr(history, "columns") and not isinstance(history, ContactHistory):
        return True  # a DataFrame
    if isinstance(history, Mapping):
        return True  # {channel: file} or {column: array}
    return (isinstance(history, list | tuple) and len(history) > 0
            and all(isinstance(x, str | os.PathLike) for x in history))


def wear_power(history: ContactHistory | str | os.PathLike, *, t_start: float | None = None,
               t_end: float | None = None, blocks: int = 1,
               sectors: int | Sequence[float] | None = None,
               stationarity_threshold: float = 0.1, force_threshold: float = 0.0,
               minimum_rest_time: float = 0.0, chunk_size: int = DEFAULT_CHUNK_SIZE,
               backend: str = "auto", kwu: tuple[float | None, float | None] | None = None,
               progress: Callable[[int], Any] | None = None,
               first_block: Callable[[ContactHistory], Any] | None = None,
               statistics: bool = True, **read_options: Any) -> PowerResult:
    """Wear power of a contact history over a window, per block and per angular sector.

    Parameters
    ----------
    history : ContactHistory, path, file set, table, or iterable of ContactHistory
        The history; a file path is streamed block by block with
        :func:`fretwear.io.iter_history_blocks` (memory bounded by ``chunk_size``); a set of
        Code_Aster IMPR_FONCTION files (``{channel: file}`` or a list of files), a DataFrame or
        a mapping of arrays is read whole with :func:`fretwear.io.read_history`; an iterable of
        consecutive chunks is folded in as it comes.
    t_start, t_end : float, optional
        Window [s]; default the whole record. Must lie within the record.
    blocks : int
        Number B >= 1 of equal blocks of the window (Code_Aster NB_BLOC).
    sectors : int or sequence of float, optional
        Number of equal angular sectors, or their edges [deg] from -180 to 180.
    stationarity_threshold : float
        Largest relative spread (max - min)/mean of the block powers [-] before a
        :class:`~fretwear.errors.StationarityWarning`; default 0.1.
    force_threshold : float
        Contact / impact threshold of the statistics [N] (SEUIL_FORCE), default 0.
    minimum_rest_time : float
        Minimum rest between impacts [s] (DUREE_REPOS), default 0.
    chunk_size : int
        Samples per chunk when streaming a file.
    backend : str
        ``"auto"``, ``"numba"`` or ``"numpy"``.
    kwu : tuple, optional
        ``(force_max [N] or None, speed_max [m/s] or None)`` (FNOR_MAXI, VTAN_MAXI): also the
        KWU-EPRI class counts of the window (the result's ``kwu``, a
        :class:`fretwear.laws.KwuEpriAccumulator`): in the same pass when both maxima are
        given, else the pass gives the window's maxima and a second pass the counts (a
        ContactHistory or a file; an iterable of chunks gets the maxima only).
    progress : callable, optional
        Called with the number of samples read so far after each block of a file.
    first_block : callable, optional
        Called with the first block (a ContactHistory in SI) before it is reduced: a check of
        the record's first samples without a second read of a file (a bundle's units against
        the contact's geometry). A file's first block is its reader's (at most
        ``chunk_size`` samples); an in-memory history is its own first block.
    statistics : bool
        False: the contact statistics are not made (the result's ``statistics`` is None; its
        powers the same): a caller that keeps the powers only (a bundle's worker, whose
        records drop the statistics: 6 µs a contact of 1 000 samples, issue 28).
    **read_options
        Passed to the reader of a file or file set: ``format``, ``units`` (e.g.
        ``{"length": "mm", "force": "kN"}``), ``columns``, ``name`` and the format's own options
        (see :func:`fretwear.io.read_history`).

    Returns
    -------
    PowerResult

    Raises
    ------
    InputError
        Bad window (outside the record, empty), blocks < 1, bad sector edges, negative threshold.
    HistoryError
        Sectors asked for a history without dy/dz.

    Warns
    -----
    StationarityWarning
        Block powers spread more than ``stationarity_threshold``.

    Notes
    -----
    P = (1/T) ∫_{t_start}^{t_end} Fn·‖Vt‖ dt, trapezoid rule, intervals whose left sample sticks
    excluded; P_b the same over block b of length T/B, P = mean(P_b); P_j the same restricted to
    intervals whose left sample's angle θ = atan2(dz, dy) lies in sector j, Σ P_j = P. A window
    bound or block edge inside an interval [t_i, t_i+1] splits it; each part [a, b] contributes
    (b - a)(g(a) + g(b))/2 with g linearly interpolated, so the split is exact for the
    piecewise-linear integrand. For a file with ``blocks > 1`` and a missing bound, the time
    range comes from the file's metadata (Parquet statistics, HDF5/NetCDF ends), or for text
    formats from a first streaming pass (give t_start and t_end to save it).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §2-§3.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §2 (wear power and blocks)
           and §5 (sectors).
    .. [3] Code_Aster User Manual U4.84.05, *Opérateur POST_USURE* (U4.67.03 in older versions), EDF
           R&D.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 2001)
    >>> h = ContactHistory(time=t, normal_force=np.full_like(t, 10.0),
    ...                    vt1=0.2 * np.sin(2 * np.pi * 5 * t), vt2=np.zeros_like(t))
    >>> r = wear_power(h, blocks=2)
    >>> round(r.total, 4), round(10.0 * 0.2 * 2 / np.pi, 4)
    (1.2732, 1.2732)
    """
    if isinstance(stationarity_threshold, bool) or not isinstance(
            stationarity_threshold, int | float | np.number) or stationarity_threshold < 0:
        raise InputError(
            f"stationarity_threshold must be a number >= 0 (relative spread), "
            f"got {stationarity_threshold!r}")
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, int | np.integer) \
            or chunk_size < 2:
        raise InputError(f"chunk_size must be an integer >= 2 samples, got {chunk_size!r}")
    opts = dict(t_start=t_start, t_end=t_end, blocks=blocks, sectors=sectors,
                force_threshold=force_threshold, minimum_rest_time=minimum_rest_time,
                backend=backend)
    if _is_read_whole(history):
        # a set of IMPR_FONCTION files ({channel: file} or [file, ...]) or an in-memory table:
        # read whole (text functions cannot be streamed), aliases and units applied
        history = read_history(history, **read_options)
        read_options = {}
    opts["kwu"] = kwu
    if isinstance(history, ContactHistory):
        if read_options:
            raise KeywordError(
                f"unknown keyword(s) {sorted(read_options)} for an in-memory history")
        if opts["t_start"] is None:
            opts["t_start"] = float(history.time[0])
        if opts["t_end"] is None:
            opts["t_end"] = float(history.time[-1])
        acc = PowerAccumulator(**opts)
        if first_block is not None:
            first_block(history)
        acc.update(history)
        chunks = lambda: (history,)  # noqa: E731 - the second pass of the KWU counts
    elif isinstance(history, str | os.PathLike):
        needs_range = (isinstance(blocks, int | np.integer) and not isinstance(blocks, bool)
                       and blocks > 1)
        if needs_range and (t_start is None or t_end is None):
            ends = history_time_range(history, **read_options)  # the file's metadata
            lo, hi = ends if ends is not None else _time_range(history, chunk_size,
                                                               read_options)
            opts["t_start"] = lo if t_start is None else t_start
            opts["t_end"] = hi if t_end is None else t_end
        acc = PowerAccumulator(**opts)
        read = 0
        for chunk in iter_history_blocks(history, chunk_size, **read_options):
            if first_block is not None and read == 0:
                first_block(chunk)
            acc.update(chunk)
            read += len(chunk)
            if progress is not None:
                progress(read)
        path = history
        chunks = lambda: iter_history_blocks(path, chunk_size, **read_options)  # noqa: E731
    elif isinstance(history, Iterable):
        if read_options:
            raise KeywordError(f"unknown keyword(s) {sorted(read_options)} for chunks")
        acc = PowerAccumulator(**opts)
        for k, chunk in enumerate(history):
            if first_block is not None and k == 0:
                first_block(chunk)
            acc.update(chunk)
        chunks = None
    else:
        raise InputError(
            f"history must be a ContactHistory, a file path or an iterable of chunks, got "
            f"{type(history).__name__}")
    result = acc.result(stationarity_threshold=float(stationarity_threshold),
                        statistics=statistics)
    if isinstance(acc.kwu, KwuEpriMaxima) and chunks is not None:
        result = replace(result, kwu=kwu_counts(acc, kwu, chunks))
    return result
