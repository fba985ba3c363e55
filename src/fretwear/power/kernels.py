"""Fused one-pass kernels of the wear power and the contact statistics (theory §2-§3).

One call reduces one chunk of a contact history (consecutive samples) to its *partial sums*:

* ``power[b, j]``: ∫ Fn·‖Vt‖ dt over the part of the chunk inside block ``b`` whose interval
  belongs to sector ``j`` (stick rule applied) [J];
* ``block_stats[b, :]``: per-block integrals of the contact statistics (see :data:`BLOCK_STATS`);
* ``force_max``: the largest normal force in the window [N];
* ``groups``: the impacts of the chunk in a mergeable form (see :data:`GROUP_FIELDS`).

Two implementations compute the same sums: a compiled numba kernel (``cache=True``, ``nogil``)
that reads every sample once and classifies contact angles into sectors *without an arctangent*,
and a plain numpy version (:func:`fretwear.power.reference.fused_numpy`: the reference, and the
fallback when numba is missing). The compiled kernel skips free-flight intervals (Fn = 0 at both
ends) without computing the sliding speed, keeps the per-block sums in registers and reuses the
previous sample's sector while the contact point stays inside it.

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
function of θ computed with one division (:func:`pseudo_angle`), and compares it with the
pseudo-angles of the edges through a 1024-bin lookup table. Points on an axis (dy = 0 or dz = 0)
have an exact q and are compared exactly. Any other point closer than ``1e-11`` in q to an edge
(about 1e-11 rad) — where float rounding could make ``arctan2`` land on the other side — is
*ambiguous*: the kernel then stops and the chunk is recomputed with the reference
classification (:mod:`fretwear.power.reference`), so that both paths always agree with
``sector_index(contact_angle(dy, dz), edges)``.
"""

from __future__ import annotations

import math
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

numba = optional("numba")  # extra "fast"; without it the numpy kernel runs
HAVE_NUMBA = numba is not None

#: Half-width of the ambiguity band around an edge, in pseudo-angle units (≈ rad).
AMBIGUITY = 1e-11
_NBINS = 1024


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


def _edge_pseudo_angles(edges: np.ndarray) -> np.ndarray:
    """Pseudo-angles of the sector edges [deg]; exact on the axes."""
    exact = {-180.0: -2.0, -90.0: -1.0, 0.0: 0.0, 90.0: 1.0, 180.0: 2.0}
    rad = np.radians(edges)
    q = pseudo_angle(np.cos(rad), np.sin(rad))
    for k, e in enumerate(edges):
        if float(e) in exact:
            q[k] = exact[float(e)]
    q[0], q[-1] = -2.0, 2.0
    return q


class SectorTable(NamedTuple):
    """Lookup structures of the arctangent-free classification."""

    q_edges: np.ndarray  # [N+1] pseudo-angles of the edges
    table: np.ndarray    # [1024] number of interior edges below each bin's lower bound
    safe: bool           # False when edges are too close for the fast path (use the reference)


def sector_table(edges: np.ndarray) -> SectorTable:
    """Build the lookup table of :func:`pseudo_angle` values for sector ``edges`` [deg].

    Examples
    --------
    >>> st = sector_table(np.array([-180.0, 0.0, 180.0]))
    >>> st.q_edges.tolist(), bool(st.safe)
    ([-2.0, 0.0, 2.0], True)
    """
    q = _edge_pseudo_angles(np.asarray(edges, dtype=float))
    interior = q[1:-1]
    lower = -2.0 + np.arange(_NBINS) * (4.0 / _NBINS)
    table = np.searchsorted(interior, lower, side="left").astype(np.int64)
    gaps = np.diff(q)
    axes = np.array([-1.0, 0.0, 1.0])
    near_axis = [np.min(np.abs(axes - x)) for x in interior if x not in axes]
    safe = bool(np.all(gaps > 10 * AMBIGUITY)
                and all(d > 10 * AMBIGUITY for d in near_axis))
    return SectorTable(q, table, safe)


if HAVE_NUMBA:
    @numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
    def _at(g0, g1, t0, t1, x):
        if x == t0:
            return g0
        if x == t1:
            return g1
        return g0 + (g1 - g0) * ((x - t0) / (t1 - t0))

    @numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
    def _pseudo(y, z):  # pragma: no cover - compiled
        """:func:`pseudo_angle` of one point."""
        s = abs(y) + abs(z)
        if s == 0.0:
            return 0.0
        if y >= 0.0:
            return z / s
        if z >= 0.0:
            return 2.0 - z / s
        return -2.0 - z / s

    @numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
    def _sector_of(q, exact, qe, table, ns):  # pragma: no cover - compiled
        """Sector of pseudo-angle q by lookup, and whether it is ambiguous (``exact``: the point
        lies on an axis, its q is exact)."""
        bi = int((q + 2.0) * (_NBINS / 4.0))
        if bi > _NBINS - 1:
            bi = _NBINS - 1
        j = table[bi]
        while j < ns - 1 and q > qe[j + 1]:
            j += 1
        amb = False
        if not exact:
            if j >= 1 and q - qe[j] <= AMBIGUITY:
                amb = True
            elif j <= ns - 2 and qe[j + 1] - q <= AMBIGUITY:
                amb = True
            elif q + 2.0 <= AMBIGUITY:
                amb = True
        return j, amb

    @numba.njit(cache=True, nogil=True, error_model="numpy")
    def _classify_numba(dy, dz, qe, table, out):  # pragma: no cover - compiled
        ns = qe.shape[0] - 1
        n_amb = 0
        for i in range(dy.shape[0]):
            y = dy[i]
            z = dz[i]
            j, amb = _sector_of(_pseudo(y, z), y == 0.0 or z == 0.0, qe, table, ns)
            out[i] = -1 if amb else j
            n_amb += amb
        return n_amb

    @numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
    def _flush(bstats, k, ct, fc, f2c, ft, f2t, sd):  # pragma: no cover - compiled
        bstats[k, 0] += ct
        bstats[k, 1] += fc
        bstats[k, 2] += f2c
        bstats[k, 3] += ft
        bstats[k, 4] += f2t
        bstats[k, 5] += sd

    @numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
    def _add_episode(g, start, end, peak, open_left, open_right,
                     min_rest):  # pragma: no cover - compiled
        """Append an episode to the group vector ``g`` (layout GROUP_FIELDS)."""
        n = g[0]
        if n > 0 and start - g[6] < min_rest:  # short rest: same impact as the last group
            g[6] = end
            g[7] = max(g[7], peak)
            g[8] = 1.0 if open_right else 0.0
            if n == 1:
                g[2] = end
                g[3] = g[7]
            return
        if n >= 2:  # the last group becomes a middle one
            d = g[6] - g[5]
            g[9] += 1.0
            g[10] += d
            g[11] = max(g[11], d)
            g[12] += g[7]
        g[5] = start
        g[6] = end
        g[7] = peak
        g[8] = 1.0 if open_right else 0.0
        if n == 0:
            g[1] = start
            g[2] = end
            g[3] = peak
            g[4] = 1.0 if open_left else 0.0
        g[0] = n + 1

    @numba.njit(cache=True, nogil=True, error_model="numpy")
    def _fused_numba(t, fn, v1, v2, dy, dz, stick, has_stick, mode, sec_given,
                     lo, hi, be, qe, table, threshold, min_rest,
                     power, bstats, groups):  # pragma: no cover - compiled
        """mode 0: one sector; 1: classify by pseudo-angle; 2: use sec_given."""
        n = t.shape[0]
        nb = be.shape[0] - 1
        ns = qe.shape[0] - 1
        third = 1.0 / 3.0
        i0 = np.searchsorted(t, lo, side="right") - 1
        if i0 < 0:
            i0 = 0
        i1 = np.searchsorted(t, hi, side="left")
        if i1 > n - 1:
            i1 = n - 1
        fmax = -np.inf
        if i1 <= i0:
            return 0, fmax
        L = max(t[i0], lo)
        k = 0
        while k < nb - 1 and L >= be[k + 1]:
            k += 1
        # per-block statistics of the current block k, flushed into bstats when k changes
        CT = 0.0
        FC = 0.0
        F2C = 0.0
        FT = 0.0
        F2T = 0.0
        SD = 0.0
        # episode in progress (impact groups are kept in ``groups``)
        in_ep = False
        ep_start = 0.0
        ep_peak = 0.0
        ep_open = False
        PW = 0.0  # power integral of the current (block, sector) cell (pk, pj)
        pk = k
        pj = 0
        j_last = 0
        q_lo = np.inf
        q_hi = -np.inf
        t1 = t[i0]
        fn1 = fn[i0]
        s1 = 0.0  # sliding speed of the right sample, computed only when needed (ok1)
        ok1 = False
        for i in range(i0, i1):
            t0 = t1
            fn0 = fn1
            s0 = s1
            ok0 = ok1
            t1 = t[i + 1]
            fn1 = fn[i + 1]
            if fn0 == 0.0 and fn1 == 0.0:
                # free flight: Fn = 0 on the whole interval, nothing to integrate
                if fmax < 0.0:
                    fmax = 0.0
                ok1 = False
                continue
            if not ok0:
                s0 = math.sqrt(v1[i] * v1[i] + v2[i] * v2[i])
            s1 = math.sqrt(v1[i + 1] * v1[i + 1] + v2[i + 1] * v2[i + 1])
            ok1 = True
            a = t0
            b = t1
            full = True
            if t0 < lo:
                a = lo
                full = False
            if t1 > hi:
                b = hi
                full = False
            if b <= a:
                continue
            while k < nb - 1 and a >= be[k + 1]:
                _flush(bstats, k, CT, FC, F2C, FT, F2T, SD)
                CT = FC = F2C = FT = F2T = SD = 0.0
                k += 1
            slide = (not has_stick) or stick[i] == 0.0
            g0 = fn0 * s0
            g1 = fn1 * s1
            # sector of the left sample, only when the interval can produce wear
            j = 0
            wear = slide and (g0 != 0.0 or g1 != 0.0)
            if wear:
                if mode == 2:
                    j = sec_given[i]
                elif mode == 1:
                    y = dy[i]
                    z = dz[i]
                    q = _pseudo(y, z)
                    if q > q_lo and q < q_hi:  # same sector as the last one, clear of its edges
                        j = j_last
                    else:
                        j, amb = _sector_of(q, y == 0.0 or z == 0.0, qe, table, ns)
                        if amb:
                            return 1, fmax
                        j_last = j
                        q_lo = qe[j] + AMBIGUITY
                        q_hi = qe[j + 1] - AMBIGUITY if j < ns - 1 else np.inf
            above0 = fn0 > threshold
            above1 = fn1 > threshold
            if full and above0 == above1 and (k == nb - 1 or t1 <= be[k + 1]):
                # fast path: a whole interval inside one block, no threshold crossing
                dt = t1 - t0
                if wear:
                    if j != pj or k != pk:
                        power[pk, pj] += PW
                        PW = 0.0
                        pk = k
                        pj = j
                    PW += 0.5 * dt * (g0 + g1)
                i1f = 0.5 * dt * (fn0 + fn1)
                i2f = dt * (fn0 * fn0 + fn0 * fn1 + fn1 * fn1) * third
                FT += i1f
                F2T += i2f
                if fn0 > fmax:
                    fmax = fn0
                if fn1 > fmax:
                    fmax = fn1
                if above0:
                    CT += dt
                    FC += i1f
                    F2C += i2f
                    if slide:
                        SD += 0.5 * dt * (s0 + s1)
                    if not in_ep:
                        in_ep = True
                        ep_start = t0
                        ep_peak = fn0
                        ep_open = t0 == L
                    if fn0 > ep_peak:
                        ep_peak = fn0
                    if fn1 > ep_peak:
                        ep_peak = fn1
                continue
            # general path: window bound, block edge or threshold crossing inside the interval
            ua = t0
            ub = t0
            if above0 and above1:
                ub = t1
            elif above0:
                ub = t0 + (fn0 - threshold) / (fn0 - fn1) * (t1 - t0)
            elif above1:
                ua = t0 + (threshold - fn0) / (fn1 - fn0) * (t1 - t0)
                ub = t1
            fa_w = _at(fn0, fn1, t0, t1, a)
            fb_w = _at(fn0, fn1, t0, t1, b)
            if fa_w > fmax:
                fmax = fa_w
            if fb_w > fmax:
                fmax = fb_w
            pa = a
            while True:
                pb = b
                if k < nb - 1 and be[k + 1] < b:
                    pb = be[k + 1]
                if pb > pa:
                    w = pb - pa
                    fa = _at(fn0, fn1, t0, t1, pa)
                    fb = _at(fn0, fn1, t0, t1, pb)
                    if slide:
                        power[k, j] += 0.5 * w * (_at(g0, g1, t0, t1, pa)
                                                  + _at(g0, g1, t0, t1, pb))
                    FT += 0.5 * w * (fa + fb)
                    F2T += w * (fa * fa + fa * fb + fb * fb) * third
                    ca = pa if pa > ua else ua
                    cb = pb if pb < ub else ub
                    if cb > ca:
                        cw = cb - ca
                        fca = _at(fn0, fn1, t0, t1, ca)
                        fcb = _at(fn0, fn1, t0, t1, cb)
                        CT += cw
                        FC += 0.5 * cw * (fca + fcb)
                        F2C += cw * (fca * fca + fca * fcb + fcb * fcb) * third
                        if slide:
                            SD += 0.5 * cw * (_at(s0, s1, t0, t1, ca) + _at(s0, s1, t0, t1, cb))
                if pb >= b:
                    break
                _flush(bstats, k, CT, FC, F2C, FT, F2T, SD)
                CT = FC = F2C = FT = F2T = SD = 0.0
                pa = pb
                k += 1
            # episodes of the whole (window-clipped) interval
            ca = a if a > ua else ua
            cb = b if b < ub else ub
            if cb > ca:
                fca = _at(fn0, fn1, t0, t1, ca)
                fcb = _at(fn0, fn1, t0, t1, cb)
                if not in_ep:
                    in_ep = True
                    ep_start = ca
                    ep_peak = fca
                    ep_open = ca == L and fca > threshold
                if fca > ep_peak:
                    ep_peak = fca
                if fcb > ep_peak:
                    ep_peak = fcb
                if not fb_w > threshold:  # episode closed at cb
                    in_ep = False
                    _add_episode(groups, ep_start, cb, ep_peak, ep_open, False, min_rest)
        _flush(bstats, k, CT, FC, F2C, FT, F2T, SD)
        power[pk, pj] += PW
        if in_ep:  # open on the right: still above the threshold at the chunk's end
            _add_episode(groups, ep_start, t[i1] if t[i1] <= hi else hi, ep_peak, ep_open,
                         True, min_rest)
        return 0, fmax


def _ro(a, dtype=float) -> np.ndarray:
    """A read-only C-contiguous view (one compiled signature for every caller's arrays)."""
    v = np.ascontiguousarray(a, dtype=dtype).view()
    v.flags.writeable = False
    return v


_EMPTY_F = _ro(np.zeros(1))
_EMPTY_I = _ro(np.zeros(1, dtype=np.int64), np.int64)


def fused_numba(t, fn, vt1, vt2, dy, dz, stick, lo, hi, block_edges, edges,
                threshold, min_rest) -> ChunkSums:
    """Partial sums of one chunk with the compiled kernel (same contract as :func:`fused_numpy`).

    Falls back to the reference sector classification for the chunk when a contact point lies
    within the ambiguity band of an edge (see the module docstring).

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
    mode = 0 if ns == 1 else (1 if st.safe else 2)
    has_stick = stick is not None
    t, fn, vt1, vt2 = _ro(t), _ro(fn), _ro(vt1), _ro(vt2)
    dyv = _EMPTY_F if dy is None else _ro(dy)
    dzv = _EMPTY_F if dz is None else _ro(dz)
    stv = _EMPTY_F if stick is None else _ro(stick)
    block_edges = _ro(block_edges)
    sec = _EMPTY_I
    for _attempt in range(2):
        if mode == 2:
            sec = _ro(reference_sector_index(dyv, dzv, edges), np.int64)
        power = np.zeros((nb, ns))
        bstats = np.zeros((nb, _NSTAT))
        groups = np.zeros(_NGROUP)
        status, fmax = _fused_numba(t, fn, vt1, vt2, dyv, dzv, stv, has_stick, mode, sec,
                                    float(lo), float(hi), block_edges, _ro(st.q_edges),
                                    _ro(st.table, np.int64),
                                    float(threshold), float(min_rest), power, bstats, groups)
        if status == 0:
            return ChunkSums(power, bstats, float(fmax), groups)
        mode = 2
    raise AssertionError("unreachable: the reference classification cannot be ambiguous")


def fast_sector_index(dy, dz, edges: np.ndarray) -> np.ndarray:
    """Sector of each sample like :func:`reference_sector_index`, without arctangent.

    Uses the compiled pseudo-angle classifier of the fused kernel; ambiguous samples (within the
    band of an edge, see the module docstring) are classified by the reference. Without numba,
    the reference itself.

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
    if _classify_numba(_ro(y), _ro(z), _ro(st.q_edges), _ro(st.table, np.int64), out):
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
