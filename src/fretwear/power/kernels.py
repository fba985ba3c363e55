"""Fused one-pass kernels of the wear power and the contact statistics (theory §2-§3).

One call reduces one chunk of a contact history (consecutive samples) to its *partial sums*:

* ``power[b, j]``: ∫ Fn·‖Vt‖ dt over the part of the chunk inside block ``b`` whose interval
  belongs to sector ``j`` (stick rule applied) [J];
* ``block_stats[b, :]``: per-block integrals of the contact statistics (see :data:`BLOCK_STATS`);
* ``force_max``: the largest normal force in the window [N];
* ``groups``: the impacts of the chunk in a mergeable form (see :data:`GROUP_FIELDS`).

Two implementations compute the same sums: a compiled numba kernel (``cache=True``, ``nogil``,
:mod:`fretwear.power._compiled`) that classifies contact angles into sectors *without an
arctangent*, and a plain numpy version (:func:`fretwear.power.reference.fused_numpy`: the
reference, and the fallback when numba is missing). The compiled kernel's cost does not depend
on the signal: it skips free flight by blocks of 16 intervals without reading anything but the
normal force, reduces the long runs of contact with branch-free vectorised passes (sector
classification and threshold crossings included) and the short ones with a scalar loop.

Conventions (shared with :mod:`fretwear.history` and :mod:`fretwear.sectors`)
---------------------------------------------------------------------------------
* The integrand g = Fn·‖Vt‖ is linear between samples (trapezoid rule). A window bound or a block
  edge inside an interval splits it; each part gets the exact integral of the linear interpolant.
* An interval belongs to the sector of its left sample and produces no wear when its left sample
  sticks.
* Contact angle θ = atan2(dz, dy) in (-180°, 180°]; θ = 0 when dy = dz = 0. Sample in sector j
  when ``edges[j] < θ <= edges[j+1]`` (the first sector also takes θ = -180, which cannot occur).

Sector classification without arctangent
----------------------------------------
The kernel maps (dy, dz) to the *diamond pseudo-angle* q ∈ (-2, 2], a strictly increasing
function of θ computed with one division (:func:`pseudo_angle`), and finds its sector through a
table of equal bins of q (:func:`sector_table`: at least 1024, more when edges are close) in
which each bin holds at most one edge: the sector is the bin's count of edges below it, plus one
when q is above the bin's edge. Points on an axis (dy = 0 or dz = 0) have an exact q and are
compared exactly with edges on an axis. Any other point closer than ``1e-11`` in q to an edge
(about 1e-11 rad), where float rounding could make ``arctan2`` land on the other side, is
*ambiguous*: the kernel defers it, and the few deferred samples are classified one by one with
the reference rule (:func:`reference_sector_index`), so that both paths always agree with
``sector_index(contact_angle(dy, dz), edges)``. Edges so close that no bin table separates them
(closer than about 6e-5 rad) are classified with the reference rule for the whole chunk.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from fretwear._optional import optional
from fretwear.errors import KeywordError
from fretwear.power.reference import (  # noqa: F401 - re-exported
    _NGROUP,
    _NSTAT,
    BLOCK_STATS,
    GROUP_FIELDS,
    ChunkSums,
    fused_numpy,
    reference_sector_index,
)
from fretwear.power.statistics import merge_groups

numba = optional("numba")  # extra "fast"; without it the numpy kernel runs
HAVE_NUMBA = numba is not None
if HAVE_NUMBA:
    from fretwear.power import _compiled

#: Half-width of the ambiguity band around an edge, in pseudo-angle units (≈ rad).
AMBIGUITY = 1e-11
#: Bin counts tried for the sector table, smallest first.
_BIN_COUNTS = (1024, 4096, 16384, 65536)


def pseudo_angle(dy, dz) -> np.ndarray:
    """Diamond pseudo-angle q ∈ (-2, 2] of the direction (dy, dz), increasing with θ.

    Parameters
    ----------
    dy, dz : array_like
        Local displacements [m] (any common unit).

    Returns
    -------
    numpy.ndarray
        q [-]: θ = -180°, -90°, 0°, 90°, 180° map to -2 (excluded), -1, 0, 1, 2; q = 0 when
        dy = dz = 0 (θ = 0 by convention).

    Notes
    -----
    With s = |dy| + |dz|: q = dz/s when dy ≥ 0, q = 2 - dz/s when dy < 0 and dz ≥ 0, and
    q = -2 - dz/s when dy < 0 and dz < 0. dq/dθ lies in [1/2, 1] per radian, so a distance in q
    bounds a distance in angle. A negative zero dz counts as +0 (θ = 180° for dy < 0, as
    ``contact_angle`` folds -180° to 180°).

    Examples
    --------
    >>> pseudo_angle([1.0, 0.0, -1.0, 0.0, 1.0], [0.0, 1.0, 0.0, -1.0, 1.0]).tolist()
    [0.0, 1.0, 2.0, -1.0, 0.5]
    """
    y = np.asarray(dy, dtype=float)
    z = np.asarray(dz, dtype=float)
    s = np.abs(y) + np.abs(z)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = z / s
    q = np.where(y >= 0, r, np.where(z >= 0, 2.0 - r, -2.0 - r))
    return np.where(s == 0, 0.0, q) + 0.0


def _edge_pseudo_angles(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pseudo-angles of the sector edges [deg] and whether each is exact (on an axis)."""
    exact = {-180.0: -2.0, -90.0: -1.0, 0.0: 0.0, 90.0: 1.0, 180.0: 2.0}
    rad = np.radians(edges)
    q = pseudo_angle(np.cos(rad), np.sin(rad))
    on_axis = np.zeros(edges.size, dtype=bool)
    for k, e in enumerate(edges):
        if float(e) in exact:
            q[k] = exact[float(e)]
            on_axis[k] = True
    q[0], q[-1] = -2.0, 2.0
    return q, on_axis


class SectorTable(NamedTuple):
    """Lookup structures of the arctangent-free classification (:func:`sector_table`)."""

    q_edges: np.ndarray  # [N+1] pseudo-angles of the edges
    scale: float         # bins per unit of q: bin of q = floor((q + 2)·scale)
    base: np.ndarray     # [bins] number of interior edges below the bin (its own edge excluded)
    edge: np.ndarray     # [bins] the interior edge within or next to the bin, +inf if none
    exact: np.ndarray    # [bins] 1 when that edge lies on an axis (exact pseudo-angle), else 0
    safe: bool           # False when no table separates the edges (reference for the chunk)


def _build_table(edges: tuple[float, ...]) -> SectorTable:
    q, on_axis = _edge_pseudo_angles(np.asarray(edges, dtype=float))
    interior, interior_exact = q[1:-1], on_axis[1:-1]
    margin = AMBIGUITY + 1e-12  # an edge this close to a bin also belongs to it
    for bins in _BIN_COUNTS:
        lower = -2.0 + np.arange(bins) * (4.0 / bins)
        first = np.searchsorted(interior, lower - margin, side="left")
        last = np.searchsorted(interior, lower + 4.0 / bins + margin, side="right")
        if np.any(last - first > 1):
            continue  # two edges in one bin: finer bins
        has = last > first
        edge = np.full(bins, np.inf)
        edge[has] = interior[first[has]]
        exact = np.zeros(bins, dtype=np.int64)
        exact[has] = interior_exact[first[has]]
        return SectorTable(_ro(q), bins / 4.0, _ro(first.astype(np.int64), np.int64), _ro(edge),
                           _ro(exact, np.int64), True)
    one = _ro(np.zeros(1, dtype=np.int64), np.int64)
    return SectorTable(_ro(q), 0.0, one, _ro(np.full(1, np.inf)), one, False)


@functools.lru_cache(maxsize=64)
def _cached_table(edges: tuple[float, ...]) -> SectorTable:
    return _build_table(edges)


def sector_table(edges: np.ndarray) -> SectorTable:
    """The bin table of :func:`pseudo_angle` values for sector ``edges`` [deg] (cached).

    Examples
    --------
    >>> st = sector_table(np.array([-180.0, 0.0, 180.0]))
    >>> st.q_edges.tolist(), bool(st.safe), int(st.base[0]), int(st.base[-1])
    ([-2.0, 0.0, 2.0], True, 0, 1)
    """
    return _cached_table(tuple(np.asarray(edges, dtype=float).tolist()))


def _ro(a, dtype=float) -> np.ndarray:
    """A read-only C-contiguous view (one compiled signature for every caller's arrays)."""
    if (type(a) is np.ndarray and a.dtype == dtype and not a.flags.writeable
            and a.flags.c_contiguous):
        return a  # already one (a checked block's arrays, a history's channels)
    v = np.ascontiguousarray(a, dtype=dtype).view()
    v.flags.writeable = False
    return v


#: Deferral buffer: at least this many entries, else 1/64 of the chunk.
_MIN_DEFERRALS = _compiled.RUNMAX + 16 if HAVE_NUMBA else 0


def _opt(a, dtype=float):
    return None if a is None else _ro(a, dtype)


def fused_numba(t, fn, vt1, vt2, dy, dz, stick, lo, hi, block_edges, edges,
                threshold, min_rest) -> ChunkSums:
    """Partial sums of one chunk with the compiled kernel (same contract as :func:`fused_numpy`).

    The samples whose contact angle lies within the ambiguity band of an edge (see the module
    docstring) are deferred by the kernel and classified here with the reference rule, one by
    one; the rest of the chunk is never recomputed.

    Examples
    --------
    >>> s = fused_numba(np.array([0.0, 1.0, 2.0]), np.array([2.0, 2.0, 2.0]),
    ...                 np.array([1.0, 1.0, 1.0]), np.zeros(3), None, None, None,
    ...                 -np.inf, np.inf, np.array([-np.inf, np.inf]),
    ...                 np.array([-180.0, 180.0]), 0.0, 0.0)
    >>> float(s.power.sum()), float(s.block_stats[0, 0])
    (4.0, 2.0)
    """
    if not HAVE_NUMBA:  # pragma: no cover
        return fused_numpy(t, fn, vt1, vt2, dy, dz, stick, lo, hi, block_edges, edges,
                           threshold, min_rest)
    nb = block_edges.size - 1
    ns = edges.size - 1
    st = sector_table(edges)
    t, fn, vt1, vt2 = _ro(t), _ro(fn), _ro(vt1), _ro(vt2)
    stick = _opt(stick)
    sec = None
    if ns > 1 and not st.safe:  # edges closer than any bin table separates
        sec = _ro(reference_sector_index(dy, dz, edges), np.int64)
    yv = _opt(dy) if ns > 1 and st.safe else None
    zv = _opt(dz) if ns > 1 and st.safe else None
    block_edges = _ro(block_edges)
    cap = max(_MIN_DEFERRALS, t.size >> 6)
    dfi = np.empty(cap, dtype=np.int64)
    dfk = np.empty(cap, dtype=np.int64)
    dfw = np.empty(cap)
    out = np.empty(3)
    channels = (t, fn, vt1, vt2, yv, zv, stick, sec)
    power = bstats = groups = None
    force_max = -np.inf
    start = 0
    while True:  # once, unless the deferral buffer fills up (then resumed where it stopped)
        p = np.zeros((nb, ns))
        bs = np.zeros((nb, _NSTAT))
        g = np.zeros(_NGROUP)
        status = _compiled._fused(
            *(channels if start == 0 else [None if a is None else a[start:] for a in channels]),
            float(lo), float(hi), block_edges, st.scale, st.base, st.edge, st.exact, st.q_edges,
            float(threshold), float(min_rest), p, bs, g, dfi, dfk, dfw, out)
        if status != 0 and int(out[2]) == 0:
            # one sample spans more blocks than the deferral buffer holds (far more blocks
            # than samples): nothing was completed, so this pass is dropped and repeated
            # with a buffer twice as large (it looped forever before)
            cap *= 2
            dfi, dfk, dfw = (np.empty(cap, dtype=np.int64), np.empty(cap, dtype=np.int64),
                             np.empty(cap))
            continue
        nd = int(out[1])
        if nd:  # the ambiguous samples, by the reference rule
            rows = dfi[:nd] + start
            j = reference_sector_index(np.asarray(dy)[rows], np.asarray(dz)[rows], edges)
            np.add.at(p, (dfk[:nd], j), dfw[:nd])
        force_max = max(force_max, float(out[0]))
        if power is None:  # the first pass's sums, summed from +0.0: 0.0 + them is them
            power, bstats, groups = p, bs, g
        else:
            power += p
            bstats += bs
            groups = merge_groups(groups, g, min_rest)
        if status == 0:
            return ChunkSums(power, bstats, force_max, groups)
        start += int(out[2])


def fast_sector_index(dy, dz, edges: np.ndarray) -> np.ndarray:
    """Sector of each sample like :func:`reference_sector_index`, without arctangent.

    Uses the compiled classifier of the fused kernel; ambiguous samples (within the band of an
    edge, see the module docstring) are classified by the reference. Without numba, the
    reference itself.

    Parameters
    ----------
    dy, dz : array_like
        Local displacements [m].
    edges : numpy.ndarray
        Sector edges [deg].

    Examples
    --------
    >>> fast_sector_index([1.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, -1.0],
    ...                   np.array([-180.0, -90.0, 0.0, 90.0, 180.0])).tolist()
    [1, 2, 3, 0]
    """
    y = np.ascontiguousarray(dy, dtype=float)
    z = np.ascontiguousarray(dz, dtype=float)
    st = sector_table(edges)
    if not HAVE_NUMBA or not st.safe or edges.size == 2:
        return reference_sector_index(y, z, edges)
    out = np.empty(y.size, dtype=np.int64)
    if _compiled._classify_points(_ro(y), _ro(z), st.scale, st.base, st.edge, st.exact, out):
        amb = out < 0
        out[amb] = reference_sector_index(y[amb], z[amb], edges)
    return out


#: Kernel implementations by name; ``"auto"`` picks numba when it is installed.
BACKENDS = {"numba": fused_numba, "numpy": fused_numpy}


def fused(backend: str = "auto"):
    """The chunk-reduction function of a backend (``"auto"``, ``"numba"`` or ``"numpy"``).

    Examples
    --------
    >>> fused("numpy") is fused_numpy
    True
    """
    if backend == "auto":
        return fused_numba if HAVE_NUMBA else fused_numpy
    try:
        return BACKENDS[backend]
    except KeyError:
        raise KeywordError(
            f"unknown backend {backend!r}; choose one of {['auto', *BACKENDS]}") from None
