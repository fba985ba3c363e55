"""The compiled (numba) one-pass kernel of the wear power and contact statistics (theory §2-§3).

Private to :mod:`fretwear.power.kernels`, which imports it only when numba is installed and
documents the contract (partial sums of one chunk, conventions, sector classification). This
module holds the machine code's structure:

* :func:`_fused` walks the chunk. The intervals that a window bound or a block edge cuts go one
  by one through the general (splitting) code; the intervals between them, inside one block,
  are scanned by blocks of ``BLOCK`` intervals, and a block whose ``BLOCK + 1`` forces are all
  zero (free flight: nothing to integrate) is skipped without reading its other channels.
* A run of busy blocks of at least ``LONG`` intervals is reduced in two passes over the run
  (:mod:`fretwear.power._passes`): :func:`_map` computes, without a branch, every integral of
  the interval (power, ∫Fn, ∫Fn², contact time and its force integrals with the threshold
  crossings located by linear interpolation, sliding distance) and the pseudo-angle of its
  left sample; it is written so that LLVM vectorises it. :func:`_scan_dense` (many
  crossings, white-noise-like signals: no branch on the data) or :func:`_scan_sparse` (few
  crossings: predictable branches and a same-sector shortcut) then classifies the
  pseudo-angles into sectors through the bin table,
  adds each interval's power to its sector, and follows the episodes (contact runs).
* A shorter run, and the tail of a long one, goes through :func:`_short`, a scalar loop that
  skips free-flight intervals one by one.
* A sample whose pseudo-angle lies within ``AMBIGUITY`` of a sector edge (where rounding could
  put ``arctan2`` on the other side) is *deferred*: its interval's power and block go to the
  ``dfi``/``dfk``/``dfw`` buffers, and the caller classifies those few samples with the numpy
  reference and adds them. When the buffers fill up the kernel stops at a block boundary
  (status 1) after closing its sums as if the chunk ended there; the caller resumes from there
  (the partial sums merge exactly, as consecutive chunks do).

``dy``, ``dz``, ``stick`` and ``sec`` are ``None`` when absent (no sectors, no stick flags,
sectors not precomputed): numba compiles a version per combination with the dead branches
removed.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._numba import HAVE_NUMBA, njit
from fretwear.power._passes import (
    _EP_OPEN,
    _EP_PEAK,
    _EP_START,
    _FMAX,
    _NSUMS,
    AMBIGUITY,
    _map,
    _mn,
    _mx,
    _scan_dense,
    _scan_sparse,
)

if HAVE_NUMBA:  # pragma: no branch - the kernels use this module only with numba
    from llvmlite import ir as llvm_ir
    from numba.core import cgutils, types
    from numba.extending import intrinsic
else:  # pragma: no cover - importable without numba (plain Python, a prefetch does nothing)

    def intrinsic(func):
        return lambda array, index: None

#: Free-flight skipping granularity [intervals].
BLOCK = 16
#: Samples of a run whose lines are prefetched before it is reduced.
PREFETCH = 256
#: Longest run reduced by one call of the vectorised passes [intervals] (buffer size).
RUNMAX = 4096
#: Runs of at least this many intervals take the vectorised passes, in multiples of ``VEC``.
LONG = 256
VEC = 32
#: A run with fewer than one threshold crossing per ``SPARSE`` intervals takes _scan_sparse.
SPARSE = 16


@njit(nogil=True, error_model="numpy", inline="always")
def _at(g0, g1, t0, t1, x):  # pragma: no cover - compiled
    """Linear interpolant between (t0, g0) and (t1, g1) at x, exact at the ends."""
    if x == t0:
        return g0
    if x == t1:
        return g1
    return g0 + (g1 - g0) * ((x - t0) / (t1 - t0))


@njit(nogil=True, error_model="numpy", inline="always")
def _pseudo(y, z):  # pragma: no cover - compiled
    """Diamond pseudo-angle of one point (see :func:`fretwear.power.kernels.pseudo_angle`)."""
    s = abs(y) + abs(z)
    r = z / (s if s != 0.0 else 1.0)
    alt = (2.0 if z >= 0.0 else -2.0) - r
    q = r if y >= 0.0 else alt
    return 0.0 if s == 0.0 else q


@njit(nogil=True, error_model="numpy", inline="always")
def _classify(y, z, scale, base, edge, exact):  # pragma: no cover - compiled
    """(sector, ambiguous) of one point through the bin table."""
    q = _pseudo(y, z)
    b = _mn(math.floor((q + 2.0) * scale), base.shape[0] - 1)
    e = edge[b]
    j = base[b] + (1 if q > e else 0)
    on_axis = y == 0.0 or z == 0.0
    amb = q + 2.0 <= AMBIGUITY or (abs(q - e) <= AMBIGUITY and not (on_axis and exact[b] != 0))
    return j, amb


@njit(cache=True, nogil=True, error_model="numpy")
def _classify_points(dy, dz, scale, base, edge, exact, out):  # pragma: no cover - compiled
    """Sector of each point into ``out`` (-1 where ambiguous); returns the number ambiguous."""
    n_amb = 0
    for i in range(dy.shape[0]):
        j, amb = _classify(dy[i], dz[i], scale, base, edge, exact)
        out[i] = -1 if amb else j
        n_amb += amb
    return n_amb


@njit(nogil=True, error_model="numpy", inline="always")
def _add_episode(g, start, end, peak, open_left, open_right,
                 min_rest):  # pragma: no cover - compiled
    """Append an episode to the group vector ``g`` (layout GROUP_FIELDS)."""
    n = g[0]
    if n > 0 and start - g[6] < min_rest:  # short rest: same impact as the last group
        g[6] = end
        g[7] = _mx(g[7], peak)
        g[8] = 1.0 if open_right else 0.0
        if n == 1:
            g[2] = end
            g[3] = g[7]
        return
    if n >= 2:  # the last group becomes a middle one
        d = g[6] - g[5]
        g[9] += 1.0
        g[10] += d
        g[11] = _mx(g[11], d)
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


@njit(cache=True, nogil=True, error_model="numpy")
def _episodes(groups, eps, ne, min_rest):  # pragma: no cover - compiled
    """Fold the ``ne`` closed episodes of ``eps`` (start, end, peak, open_left) into groups."""
    for e in range(ne):
        _add_episode(groups, eps[e, 0], eps[e, 1], eps[e, 2], eps[e, 3] != 0.0, False, min_rest)


@njit(nogil=True, error_model="numpy", inline="always")
def _free(fn, a, b):  # pragma: no cover - compiled
    """Whether fn[a..b] (both included) are all zero."""
    z = False
    for m in range(a, b + 1):
        z |= fn[m] != 0.0
    return not z


@njit(nogil=True, error_model="numpy", inline="always")
def _free_block(fn, a):  # pragma: no cover - compiled
    """Whether fn[a..a+BLOCK] (both included) are all zero."""
    z = fn[a + BLOCK] != 0.0
    for m in range(BLOCK):
        z |= fn[a + m] != 0.0
    return not z


@intrinsic
def _prefetch(typingctx, array, index):  # pragma: no cover - compiled
    """Hint the CPU to load ``array[index]``'s cache line (LLVM's prefetch: read, keep in all
    cache levels); no bounds check: ``index`` must lie in the array."""
    sig = types.void(array, index)

    def codegen(context, builder, signature, args):
        ary = context.make_array(signature.args[0])(context, builder, args[0])
        ptr = cgutils.get_item_pointer(context, builder, signature.args[0], ary, [args[1]],
                                       wraparound=False)
        i8p = llvm_ir.IntType(8).as_pointer()
        i32 = llvm_ir.IntType(32)
        fn = cgutils.get_or_insert_function(
            builder.module, llvm_ir.FunctionType(llvm_ir.VoidType(), [i8p, i32, i32, i32]),
            "llvm.prefetch.p0")
        builder.call(fn, [builder.bitcast(ptr, i8p), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return sig, codegen


@njit(nogil=True, error_model="numpy", inline="always")
def _prefetch_run(t, v1, v2, dy, dz, stick, a, b):  # pragma: no cover - compiled
    """Prefetch the channels other than Fn of the samples [a, b) (a line per 8 samples)."""
    for m in range(a, b + 7, 8):
        k = _mn(m, b - 1)
        _prefetch(t, k)
        _prefetch(v1, k)
        _prefetch(v2, k)
        if dy is not None:
            _prefetch(dy, k)
            _prefetch(dz, k)
        if stick is not None:
            _prefetch(stick, k)


@njit(nogil=True, error_model="numpy", inline="always")
def _skip_free(fn, i, end, sums):  # pragma: no cover - compiled
    """The first block from ``i`` (by blocks of BLOCK intervals) that is not free flight."""
    while i + BLOCK <= end and _free_block(fn, i):
        i += BLOCK
        sums[_FMAX] = _mx(sums[_FMAX], 0.0)
    return i


@njit(cache=True, nogil=True, error_model="numpy")
def _short(t, fn, v1, v2, dy, dz, stick, sec, i, r, threshold, scale, base, edge, exact, qe,
           acc, sums, groups, min_rest, dfi, dfw, nd):  # pragma: no cover - compiled
    """Scalar reduction of [i, r) inside one block, skipping free flight interval by interval
    (short runs and the tails of long ones). Returns the number of deferrals."""
    ns = acc.shape[0] // 4
    nbm1 = base.shape[0] - 1
    third = 1.0 / 3.0
    ct = 0.0
    fc_ = 0.0
    f2c = 0.0
    ft = 0.0
    f2t = 0.0
    sd = 0.0
    fmax = sums[_FMAX]
    ep_start = sums[_EP_START]
    ep_peak = sums[_EP_PEAK]
    ep_open = sums[_EP_OPEN] != 0.0
    j_last = 0
    q_lo = np.inf
    q_hi = -np.inf
    s1 = 0.0
    prev = -1  # the last interval reduced (its right speed is this one's left speed)
    for ii in range(i, r):  # a counted loop: fewer instructions than a while with a skip loop
        f0 = fn[ii]
        f1 = fn[ii + 1]
        if f0 == 0.0 and f1 == 0.0:  # free flight
            continue
        t0 = t[ii]
        t1 = t[ii + 1]
        s0 = s1 if prev == ii - 1 else math.sqrt(v1[ii] * v1[ii] + v2[ii] * v2[ii])
        s1 = math.sqrt(v1[ii + 1] * v1[ii + 1] + v2[ii + 1] * v2[ii + 1])
        prev = ii
        dt = t1 - t0
        slide = 1.0  # a factor, not a branch: sticking comes and goes within an impact
        if stick is not None:
            slide = 1.0 - stick[ii]
        w = 0.5 * dt * (f0 * s0 + f1 * s1) * slide
        j = 0
        if dy is not None:
            y = dy[ii]
            z = dz[ii]
            q = _pseudo(y, z)
            if q > q_lo and q < q_hi:
                j = j_last
            else:  # _classify written out: no reference counting of the tables
                b = _mn(math.floor((q + 2.0) * scale), nbm1)
                e = edge[b]
                j = base[b] + (1 if q > e else 0)
                amb = q + 2.0 <= AMBIGUITY or (
                    abs(q - e) <= AMBIGUITY
                    and not ((y == 0.0 or z == 0.0) and exact[b] != 0))
                if not amb:
                    j_last = j
                    q_lo = qe[j] + AMBIGUITY
                    q_hi = qe[j + 1] - AMBIGUITY
                elif w != 0.0:
                    dfi[nd] = ii
                    dfw[nd] = w
                    nd += 1
                    w = 0.0
        if sec is not None:
            j = sec[ii]
        acc[(ii & 3) * ns + j] += w
        i1f = 0.5 * dt * (f0 + f1)
        i2f = dt * (f0 * f0 + f0 * f1 + f1 * f1) * third
        ft += i1f
        f2t += i2f
        fmax = _mx(fmax, f1)
        a0 = f0 > threshold
        a1 = f1 > threshold
        if a0 and a1:
            ct += dt
            fc_ += i1f
            f2c += i2f
            sd += 0.5 * dt * (s0 + s1) * slide
            ep_peak = _mx(ep_peak, f1)
        elif a0 or a1:  # a threshold crossing inside the interval
            frac = (f0 - threshold) / (f0 - f1)
            cross = t0 + frac * dt
            fc = f0 + (f1 - f0) * frac
            sc = s0 + (s1 - s0) * frac
            if a0:
                cw = cross - t0
                fca, fcb, sca, scb = f0, fc, s0, sc
            else:
                cw = t1 - cross
                fca, fcb, sca, scb = fc, f1, sc, s1
            ct += cw
            fc_ += 0.5 * cw * (fca + fcb)
            f2c += cw * (fca * fca + fca * fcb + fcb * fcb) * third
            sd += 0.5 * cw * (sca + scb) * slide
            if a1:
                ep_start = cross
                ep_peak = _mx(fc, f1)
                ep_open = False
            else:
                _add_episode(groups, ep_start, cross, _mx(ep_peak, fc), ep_open, False, min_rest)
    sums[0] += ct
    sums[1] += fc_
    sums[2] += f2c
    sums[3] += ft
    sums[4] += f2t
    sums[5] += sd
    sums[_FMAX] = fmax
    sums[_EP_START] = ep_start
    sums[_EP_PEAK] = ep_peak
    sums[_EP_OPEN] = 1.0 if ep_open else 0.0
    return nd


@njit(cache=True, nogil=True, error_model="numpy")
def _fused(t, fn, v1, v2, dy, dz, stick, sec, lo, hi, be, scale, base, edge, exact, qe,
           threshold, min_rest, power, bstats, groups, dfi, dfk, dfw,
           out):  # pragma: no cover - compiled
    """Add the partial sums of the chunk's intervals inside [lo, hi] to power, bstats, groups.

    Returns 0 when done, 1 when the deferral buffers filled up: the sums then stop at sample
    ``out[2]`` (the chunk's end for the episodes in progress). ``out[0]`` is the largest force,
    ``out[1]`` the number of deferrals (interval ``dfi``, block ``dfk``, power ``dfw``).
    """
    n = t.shape[0]
    nb = be.shape[0] - 1
    ns = power.shape[1]
    nbm1 = base.shape[0] - 1
    third = 1.0 / 3.0
    cap = dfi.shape[0]
    i0 = np.searchsorted(t, lo, side="right") - 1
    if i0 < 0:
        i0 = 0
    i1 = np.searchsorted(t, hi, side="left")
    if i1 > n - 1:
        i1 = n - 1
    fmax = -np.inf
    nd = 0
    out[0] = fmax
    out[1] = 0.0
    out[2] = -1.0
    if i1 <= i0:
        return 0
    L = _mx(t[i0], lo)
    in_ep = False
    ep_start = 0.0
    ep_peak = 0.0
    ep_open = False
    acc = np.zeros(4 * ns)
    sums = np.zeros(_NSUMS)
    eps = np.empty((RUNMAX + 1, 4))
    wb = np.empty(RUNMAX)
    qb = np.empty(RUNMAX)
    cb = np.empty(RUNMAX)
    fb = np.empty(RUNMAX)
    bb = np.zeros(RUNMAX, np.int64)
    i = i0
    k = 0
    status = 0
    stop = i1
    while i < stop:
        while k < nb - 1 and _mx(t[i], lo) >= be[k + 1]:
            k += 1
        upper = be[k + 1] if k < nb - 1 else hi
        upper = _mn(upper, hi)
        fast_end = _mn(np.searchsorted(t, upper, side="right") - 1, stop)
        if i == i0 or t[i] < lo or fast_end <= i:
            # ---- one interval cut by a window bound or a block edge (or the first one)
            if nd + nb + 2 > cap:
                status = 1
                stop = i
                break
            t0 = t[i]
            t1 = t[i + 1]
            fn0 = fn[i]
            fn1 = fn[i + 1]
            s0 = math.sqrt(v1[i] * v1[i] + v2[i] * v2[i])
            s1 = math.sqrt(v1[i + 1] * v1[i + 1] + v2[i + 1] * v2[i + 1])
            a = _mx(t0, lo)
            bnd = _mn(t1, hi)
            i += 1
            if bnd <= a:
                continue
            slide = True
            if stick is not None:
                slide = stick[i - 1] == 0.0
            g0 = fn0 * s0
            g1 = fn1 * s1
            j = 0
            amb = False
            if sec is not None:
                j = sec[i - 1]
            if dy is not None:
                j, amb = _classify(dy[i - 1], dz[i - 1], scale, base, edge, exact)
            above0 = fn0 > threshold
            above1 = fn1 > threshold
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
            fb_w = _at(fn0, fn1, t0, t1, bnd)
            fmax = _mx(fmax, _mx(fa_w, fb_w))
            pa = a
            kk = 0
            while kk < nb - 1 and pa >= be[kk + 1]:
                kk += 1
            while True:
                pb = bnd
                if kk < nb - 1 and be[kk + 1] < bnd:
                    pb = be[kk + 1]
                if pb > pa:
                    w = pb - pa
                    fa = _at(fn0, fn1, t0, t1, pa)
                    fbv = _at(fn0, fn1, t0, t1, pb)
                    if slide:
                        pw = 0.5 * w * (_at(g0, g1, t0, t1, pa) + _at(g0, g1, t0, t1, pb))
                        if amb and pw != 0.0:
                            dfi[nd] = i - 1
                            dfk[nd] = kk
                            dfw[nd] = pw
                            nd += 1
                        else:
                            power[kk, j] += pw
                    bstats[kk, 3] += 0.5 * w * (fa + fbv)
                    bstats[kk, 4] += w * (fa * fa + fa * fbv + fbv * fbv) * third
                    ca = _mx(pa, ua)
                    cbv = _mn(pb, ub)
                    if cbv > ca:
                        cw = cbv - ca
                        fca = _at(fn0, fn1, t0, t1, ca)
                        fcb = _at(fn0, fn1, t0, t1, cbv)
                        bstats[kk, 0] += cw
                        bstats[kk, 1] += 0.5 * cw * (fca + fcb)
                        bstats[kk, 2] += cw * (fca * fca + fca * fcb + fcb * fcb) * third
                        if slide:
                            bstats[kk, 5] += 0.5 * cw * (_at(s0, s1, t0, t1, ca)
                                                         + _at(s0, s1, t0, t1, cbv))
                if pb >= bnd:
                    break
                pa = pb
                kk += 1
            ca = _mx(a, ua)
            cbv = _mn(bnd, ub)
            if cbv > ca:  # the episodes of the (window-clipped) interval
                fca = _at(fn0, fn1, t0, t1, ca)
                fcb = _at(fn0, fn1, t0, t1, cbv)
                if not in_ep:
                    in_ep = True
                    ep_start = ca
                    ep_peak = fca
                    ep_open = ca == L and fca > threshold
                ep_peak = _mx(ep_peak, _mx(fca, fcb))
                if not fb_w > threshold:
                    in_ep = False
                    _add_episode(groups, ep_start, cbv, ep_peak, ep_open, False, min_rest)
            continue
        # ---- the intervals [i, fast_end), inside block k and the window
        sums[:6] = 0.0
        sums[_FMAX] = _mx(fmax, fn[i])
        sums[_EP_START] = ep_start
        sums[_EP_PEAK] = ep_peak
        sums[_EP_OPEN] = 1.0 if ep_open else 0.0
        nxt = _skip_free(fn, i, fast_end, sums)
        while i < fast_end:
            i = nxt  # the first busy block (free flight skipped)
            if i >= fast_end:
                break
            r = _mn(i + BLOCK, fast_end)
            while r < fast_end and r - i < RUNMAX:
                if r + BLOCK <= fast_end:
                    if _free_block(fn, r):
                        break
                elif _free(fn, r, fast_end):
                    break
                r = _mn(r + BLOCK, fast_end)
            # the next run found now, and its first lines and this run's fetched while this run
            # is reduced: a short run would otherwise wait for memory at each cache line
            nxt = _skip_free(fn, r, fast_end, sums)
            _prefetch_run(t, v1, v2, dy, dz, stick, i, _mn(r, i + PREFETCH) + 1)
            if nxt < fast_end:
                _prefetch_run(t, v1, v2, dy, dz, stick, nxt, _mn(fast_end, nxt + BLOCK) + 1)
            if nd + (r - i) + 2 > cap:
                status = 1
                stop = i
                break
            nd0 = nd
            rv = i + ((r - i) // VEC) * VEC if r - i >= LONG else i
            if rv > i:
                ncross = _map(t, fn, v1, v2, dy, dz, stick, i, rv, threshold, scale, nbm1, sums,
                              wb, qb, cb, fb, bb)
                if SPARSE * ncross < rv - i:
                    ne, nd = _scan_sparse(fn, dy, dz, sec, i, rv, threshold, base, edge, exact,
                                          qe, acc, sums, eps, dfi, dfw, nd, wb, qb, cb, fb, bb)
                else:
                    ne, nd = _scan_dense(fn, dy, dz, sec, i, rv, threshold, base, edge, exact,
                                         acc, sums, eps, dfi, dfw, nd, wb, qb, cb, fb, bb)
                if ne:
                    _episodes(groups, eps, ne, min_rest)
            if rv < r:
                nd = _short(t, fn, v1, v2, dy, dz, stick, sec, rv, r, threshold, scale, base,
                            edge, exact, qe, acc, sums, groups, min_rest, dfi, dfw, nd)
            for d in range(nd0, nd):
                dfk[d] = k
            i = r
        fmax = sums[_FMAX]
        ep_start = sums[_EP_START]
        ep_peak = sums[_EP_PEAK]
        ep_open = sums[_EP_OPEN] != 0.0
        in_ep = fn[i] > threshold
        for c in range(6):
            bstats[k, c] += sums[c]
        for jj in range(ns):
            power[k, jj] += acc[jj] + acc[ns + jj] + acc[2 * ns + jj] + acc[3 * ns + jj]
        acc[:] = 0.0
        if status == 1:
            break
    if in_ep:  # open on the right: still above the threshold at the chunk's end
        _add_episode(groups, ep_start, _mn(t[stop], hi), ep_peak, ep_open, True, min_rest)
    out[0] = fmax
    out[1] = nd
    out[2] = stop
    return status
