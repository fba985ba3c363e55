"""Reference (plain numpy) reduction of a chunk of a contact history: the partial sums of the wear
power and the contact statistics (theory §2-§3), vectorised, without numba.

It is the independent implementation the compiled kernel of :mod:`fretwear.power.kernels` is tested
against, and the fallback when numba is not installed. It refines the time grid at the window
bounds and block edges (interpolating linearly), then integrates every piece in closed form:
∫g = Δt(g_a + g_b)/2, ∫Fn² = Δt(F_a² + F_aF_b + F_b²)/3; threshold crossings are located by linear
interpolation. Conventions: see :mod:`fretwear.power.kernels`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from fretwear.history import contact_angle
from fretwear.sectors import sector_index

#: Columns of ``block_stats``: per-block integrals, window-clipped.
BLOCK_STATS: tuple[str, ...] = (
    "contact_time",            # [s]      measure of {Fn > threshold}
    "force_integral_contact",  # [N·s]    ∫ Fn dt over contact time
    "force2_integral_contact", # [N²·s]   ∫ Fn² dt over contact time
    "force_integral",          # [N·s]    ∫ Fn dt over the whole block
    "force2_integral",         # [N²·s]   ∫ Fn² dt over the whole block
    "sliding_distance",        # [m]      ∫ ‖Vt‖ dt over contact time, sticking intervals excluded
)
#: Layout of the impact-group vector (``groups``) of a chunk.
GROUP_FIELDS: tuple[str, ...] = (
    "count",                                                   # number of groups (impacts)
    "first_start", "first_end", "first_peak", "first_open",    # first group, open on the left
    "last_start", "last_end", "last_peak", "last_open",        # last group, open on the right
    "mid_count", "mid_duration_sum", "mid_duration_max", "mid_peak_sum",  # groups in between
)
_NSTAT = len(BLOCK_STATS)
_NGROUP = len(GROUP_FIELDS)


class ChunkSums(NamedTuple):
    """Partial sums of one chunk (see the module docstring); all arrays freshly allocated."""

    power: np.ndarray        # [B, N] [J]
    block_stats: np.ndarray  # [B, len(BLOCK_STATS)]
    force_max: float         # [N], -inf when the chunk has no sample in the window
    groups: np.ndarray       # [len(GROUP_FIELDS)]


def reference_sector_index(dy, dz, edges: np.ndarray) -> np.ndarray:
    """Sector of each sample by the reference rule ``sector_index(θ, edges)``, θ via arctan2.

    θ = :func:`fretwear.history.contact_angle` (atan2(dz, dy) in degrees folded into
    (-180, 180], and θ = 0 whenever dy = dz = 0, including negative zeros).

    Examples
    --------
    >>> reference_sector_index([1.0, -1.0, -0.0], [0.0, -1e-300, 0.0],
    ...                        np.array([-180.0, 0.0, 180.0])).tolist()
    [0, 1, 0]
    """
    return sector_index(contact_angle(dy, dz), edges)


def _lin(g0, g1, t0, t1, x):
    """Linear interpolant between (t0, g0) and (t1, g1) at x, exact at the ends."""
    with np.errstate(invalid="ignore", divide="ignore"):
        val = g0 + (g1 - g0) * ((x - t0) / (t1 - t0))
    return np.where(x == t1, g1, np.where(x == t0, g0, val))


def _groups_from_episodes(start, end, peak, open_left, open_right, min_rest) -> np.ndarray:
    """Mergeable impact-group vector from the ordered episodes of one chunk."""
    out = np.zeros(_NGROUP)
    if start.size == 0:
        return out
    new = np.ones(start.size, dtype=bool)
    new[1:] = (start[1:] - end[:-1]) >= min_rest
    first_idx = np.flatnonzero(new)
    g_start = start[first_idx]
    last_idx = np.append(first_idx[1:] - 1, start.size - 1)
    g_end = end[last_idx]
    g_peak = np.maximum.reduceat(peak, first_idx)
    ng = g_start.size
    out[0] = ng
    out[1:5] = g_start[0], g_end[0], g_peak[0], float(open_left)
    out[5:9] = g_start[-1], g_end[-1], g_peak[-1], float(open_right)
    if ng > 2:
        dur = g_end[1:-1] - g_start[1:-1]
        out[9:13] = ng - 2, dur.sum(), dur.max(), g_peak[1:-1].sum()
    return out


# Values near the float range (Fn or Vt ~ 1e154 and above) overflow to inf or give inf·0 = nan
# here: the caller (fretwear.power.core) then rescales the speeds exactly or raises the
# HistoryError of fretwear.power.ranges.check_finite_sums naming the instant and values, so numpy's
# raw RuntimeWarnings would only duplicate that report. errstate changes no computed value.
@np.errstate(over="ignore", invalid="ignore")
def fused_numpy(t, fn, vt1, vt2, dy, dz, stick, lo, hi, block_edges, edges,
                threshold, min_rest) -> ChunkSums:
    """Partial sums of one chunk, plain vectorised numpy (reference implementation).

    Parameters
    ----------
    t, fn, vt1, vt2 : numpy.ndarray
        Time [s], normal force [N], sliding velocities [m/s] of the chunk.
    dy, dz : numpy.ndarray or None
        Local displacements [m] (needed when ``edges`` has more than one sector).
    stick : numpy.ndarray or None
        Stick flags (1 = sticking).
    lo, hi : float
        Window [s] (may be ±inf).
    block_edges : numpy.ndarray
        B + 1 block edges [s], first ``lo`` and last ``hi``.
    edges : numpy.ndarray
        N + 1 sector edges [deg].
    threshold : float
        Contact force threshold [N]: contact means Fn > threshold.
    min_rest : float
        Minimum rest time [s] below the threshold that separates two impacts.

    Returns
    -------
    ChunkSums
        Sums that may be inf or nan when products leave the float range (no numpy warning:
        :func:`fretwear.power.ranges.out_of_range` and ``check_finite_sums`` deal with them).

    Examples
    --------
    >>> s = fused_numpy(np.array([0.0, 1.0, 2.0]), np.array([2.0, 2.0, 2.0]),
    ...                 np.array([1.0, 1.0, 1.0]), np.zeros(3), None, None, None,
    ...                 -np.inf, np.inf, np.array([-np.inf, np.inf]),
    ...                 np.array([-180.0, 180.0]), 0.0, 0.0)
    >>> float(s.power.sum()), float(s.block_stats[0, 0])
    (4.0, 2.0)
    """
    nb = block_edges.size - 1
    ns = edges.size - 1
    power = np.zeros((nb, ns))
    bstats = np.zeros((nb, _NSTAT))
    i0 = max(int(np.searchsorted(t, lo, side="right")) - 1, 0)
    i1 = min(int(np.searchsorted(t, hi, side="left")), t.size - 1)
    if i1 <= i0:
        return ChunkSums(power, bstats, -np.inf, np.zeros(_NGROUP))
    sl = slice(i0, i1 + 1)
    tt = t[sl]
    fnn = fn[sl]
    sp = np.sqrt(vt1[sl] * vt1[sl] + vt2[sl] * vt2[sl])
    g = fnn * sp
    m = tt.size
    if ns > 1:
        sec = reference_sector_index(dy[sl], dz[sl], edges)
    else:
        sec = np.zeros(m, dtype=np.int64)
    slides = np.ones(m, dtype=bool) if stick is None else (stick[sl] == 0)
    # refined grid: samples + window bounds + block edges strictly inside the chunk
    lo_c = max(tt[0], lo)
    hi_c = min(tt[-1], hi)
    cuts = np.concatenate(([lo_c, hi_c], block_edges))
    cuts = cuts[(cuts > tt[0]) & (cuts < tt[-1])]
    cuts = np.unique(cuts)
    cuts = cuts[tt[np.searchsorted(tt, cuts)] != cuts]  # drop cuts on a sample
    owner = np.searchsorted(tt, cuts, side="right") - 1
    pos = np.searchsorted(tt, cuts)
    tg = np.insert(tt, pos, cuts)
    og = np.insert(np.arange(m), pos, owner)
    keep = (tg >= lo_c) & (tg <= hi_c)
    tg, og = tg[keep], og[keep]
    o_c = np.minimum(owner, m - 2)

    def at(arr):  # samples exact, cut points interpolated in their interval
        vals = _lin(arr[o_c], arr[o_c + 1], tt[o_c], tt[o_c + 1], cuts)
        return np.insert(arr, pos, vals)[keep]

    fg, gg, sg = at(fnn), at(g), at(sp)
    pa, pb = tg[:-1], tg[1:]
    own = og[:-1]
    width = pb - pa
    blk = np.clip(np.searchsorted(block_edges, pa, side="right") - 1, 0, nb - 1)
    fa, fb = fg[:-1], fg[1:]

    def by_block(values):
        return np.bincount(blk, weights=values, minlength=nb)

    w_g = 0.5 * width * (gg[:-1] + gg[1:]) * slides[own]
    power += np.bincount(blk * ns + sec[own], weights=w_g, minlength=nb * ns).reshape(nb, ns)
    i1 = 0.5 * width * (fa + fb)
    i2 = width * (fa * fa + fa * fb + fb * fb) / 3.0
    bstats[:, 3] = by_block(i1)
    bstats[:, 4] = by_block(i2)
    # contact (above-threshold) part [ca, cb] of each piece, linear force
    above_a, above_b = fa > threshold, fb > threshold
    full = above_a & above_b
    ca, cb = pa.copy(), np.where(full, pb, pa)
    fca, fcb = fa.copy(), fb.copy()
    sa, sb = sg[:-1], sg[1:]
    sca, scb = sa.copy(), sb.copy()
    x = np.flatnonzero(above_a ^ above_b)  # pieces crossing the threshold
    cross = pa[x] + (fa[x] - threshold) / (fa[x] - fb[x]) * width[x]
    ca[x] = np.clip(np.where(above_a[x], pa[x], cross), pa[x], pb[x])
    cb[x] = np.clip(np.where(above_b[x], pb[x], cross), ca[x], pb[x])
    for v, w_, store in ((fa, fb, (fca, fcb)), (sa, sb, (sca, scb))):
        store[0][x] = _lin(v[x], w_[x], pa[x], pb[x], ca[x])
        store[1][x] = _lin(v[x], w_[x], pa[x], pb[x], cb[x])
    nonempty = (above_a | above_b) & (cb > ca)
    cw = np.where(nonempty, cb - ca, 0.0)
    c1 = np.where(full, i1, np.where(nonempty, 0.5 * cw * (fca + fcb), 0.0))
    c2 = np.where(full, i2, np.where(nonempty, cw * (fca * fca + fca * fcb + fcb * fcb) / 3.0,
                                     0.0))
    bstats[:, 0] = by_block(cw)
    bstats[:, 1] = by_block(c1)
    bstats[:, 2] = by_block(c2)
    bstats[:, 5] = by_block(np.where(nonempty & slides[own], 0.5 * cw * (sca + scb), 0.0))
    force_max = float(fg.max())
    # episodes: maximal runs of pieces whose above-threshold parts touch
    npieces = pa.size
    prev_above = np.concatenate(([False], fg[1:-1] > threshold))
    next_above = np.concatenate((fg[1:-1] > threshold, [False]))
    starts = np.flatnonzero(nonempty & ~prev_above)
    ends = np.flatnonzero(nonempty & ~next_above)
    if starts.size:
        peak_piece = np.where(nonempty, np.maximum(fca, fcb), -np.inf)
        peaks = np.maximum.reduceat(peak_piece, starts)
        open_left = bool(starts[0] == 0 and fg[0] > threshold)
        open_right = bool(ends[-1] == npieces - 1 and fg[-1] > threshold)
        groups = _groups_from_episodes(ca[starts], cb[ends], peaks, open_left, open_right,
                                       min_rest)
    else:
        groups = np.zeros(_NGROUP)
    return ChunkSums(power, bstats, force_max, groups)
