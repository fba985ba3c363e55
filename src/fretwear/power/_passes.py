"""The vectorised passes of the compiled wear-power kernel over a long run of busy intervals.

Private to :mod:`fretwear.power._compiled` (the module docstring there describes the kernel's
structure): a run of at least ``LONG`` intervals inside one block is reduced in two passes.
:func:`_map` computes, without a branch, every integral of each interval (power, ∫Fn, ∫Fn²,
contact time and its force integrals with the threshold crossings located by linear
interpolation, sliding distance) and the pseudo-angle of its left sample, written so that
LLVM vectorises it; :func:`_scan_dense` (many crossings: no branch on the data) or
:func:`_scan_sparse` (few crossings: predictable branches, a same-sector shortcut) then
classifies the pseudo-angles into sectors, adds each interval's power [J] to its sector and
follows the contact episodes. Also here: the constants and the two small helpers both modules
share (the ambiguity band, the layout of ``sums``).
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._numba import njit

#: Half-width of the ambiguity band around a sector edge, in pseudo-angle units (≈ rad).
AMBIGUITY = 1e-11
#: fast-math flags of the vectorised pass: reassociation (vector reductions), FMA, no signed
#: zeros; never no-NaN / no-inf (window bounds may be infinite).
_FM = {"reassoc", "nsz", "contract"}
#: Layout of ``sums``: the six BLOCK_STATS integrals of the current block, then the largest
#: force, and the episode in progress (start [s], peak [N], open on the left 0/1).
_FMAX, _EP_START, _EP_PEAK, _EP_OPEN = 6, 7, 8, 9
_NSUMS = 10


@njit(nogil=True, inline="always")
def _mx(a, b):
    return a if a > b else b


@njit(nogil=True, inline="always")
def _mn(a, b):
    return a if a < b else b


@njit(cache=True, nogil=True, error_model="numpy", fastmath=_FM)
def _map(t, fn, v1, v2, dy, dz, stick, i, te, threshold, scale, nbm1, sums, wb, qb, cb, fb,
         bb):  # pragma: no cover - compiled
    """Branch-free (vectorised) integrals of the intervals [i, te) of one block.

    Adds the six block integrals to ``sums[:6]``; writes per interval the power integral
    (``wb``, zero when the left sample sticks), the pseudo-angle and bin of the left sample
    (``qb``, ``bb``) and the threshold crossing's time and force (``cb``, ``fb``, meaningful
    where exactly one end is above the threshold). Returns the number of crossings.
    """
    n = te - i
    third = 1.0 / 3.0
    tt = t[i:te + 1]
    ff = fn[i:te + 1]
    w1 = v1[i:te + 1]
    w2 = v2[i:te + 1]
    ct = 0.0
    fc_ = 0.0
    f2c = 0.0
    ft = 0.0
    f2t = 0.0
    sd = 0.0
    ncross = 0
    if stick is not None:
        sk = stick[i:te]
    if dy is not None:
        yy = dy[i:te]
        zz = dz[i:te]
    for m in range(n):
        t0 = tt[m]
        t1 = tt[m + 1]
        f0 = ff[m]
        f1 = ff[m + 1]
        s0 = math.sqrt(w1[m] * w1[m] + w2[m] * w2[m])
        s1 = math.sqrt(w1[m + 1] * w1[m + 1] + w2[m + 1] * w2[m + 1])
        dt = t1 - t0
        slide = 1.0
        if stick is not None:
            slide = 1.0 - sk[m]
        wb[m] = 0.5 * dt * (f0 * s0 + f1 * s1) * slide
        if dy is not None:
            y = yy[m]
            z = zz[m]
            s = abs(y) + abs(z)
            r = z / (1.0 if s == 0.0 else s)
            alt = (2.0 if z >= 0.0 else -2.0) - r
            q = r if y >= 0.0 else alt
            q = 0.0 if s == 0.0 else q
            qb[m] = q
            bb[m] = _mn(math.floor((q + 2.0) * scale), nbm1)
        ft += 0.5 * dt * (f0 + f1)
        f2t += dt * (f0 * f0 + f0 * f1 + f1 * f1) * third
        a0 = f0 > threshold
        a1 = f1 > threshold
        den = f0 - f1
        frac = (f0 - threshold) / (1.0 if den == 0.0 else den)
        cross = t0 + frac * dt
        fc = f0 + (f1 - f0) * frac
        sc = s0 + (s1 - s0) * frac
        cb[m] = cross
        fb[m] = fc
        # the contact part [ca, cb] of the interval, its forces and speeds at both ends
        ca_ = t0 if a0 else cross
        cb_ = t1 if a1 else cross
        fca = f0 if a0 else fc
        fcb = f1 if a1 else fc
        sca = s0 if a0 else sc
        scb = s1 if a1 else sc
        cw = cb_ - ca_
        cw = cw if (a0 or a1) else 0.0
        ncross += 1 if a0 != a1 else 0
        ct += cw
        fc_ += 0.5 * cw * (fca + fcb)
        f2c += cw * (fca * fca + fca * fcb + fcb * fcb) * third
        sd += 0.5 * cw * (sca + scb) * slide
    sums[0] += ct
    sums[1] += fc_
    sums[2] += f2c
    sums[3] += ft
    sums[4] += f2t
    sums[5] += sd
    return ncross


@njit(cache=True, nogil=True, error_model="numpy")
def _scan_dense(fn, dy, dz, sec, i, te, threshold, base, edge, exact, acc, sums, eps, dfi, dfw,
                nd, wb, qb, cb, fb, bb):  # pragma: no cover - compiled
    """Sectors, deferrals, largest force and episodes of [i, te) after :func:`_map`, without
    a branch on the data (many crossings). Returns (closed episodes in ``eps``, deferrals)."""
    n = te - i
    ns = acc.shape[0] // 4
    ff = fn[i:te + 1]
    fmax = sums[_FMAX]
    ep_start = sums[_EP_START]
    ep_peak = sums[_EP_PEAK]
    ep_open = sums[_EP_OPEN]
    ne = 0
    if dy is not None:
        yy = dy[i:te]
        zz = dz[i:te]
    for m in range(n):
        f0 = ff[m]
        f1 = ff[m + 1]
        w = wb[m]
        j = 0
        if dy is not None:
            q = qb[m]
            b = bb[m]
            e = edge[b]
            j = base[b] + (1 if q > e else 0)
            if (abs(q - e) <= AMBIGUITY or q + 2.0 <= AMBIGUITY) and w != 0.0:
                on_axis = yy[m] == 0.0 or zz[m] == 0.0
                if q + 2.0 <= AMBIGUITY or not (on_axis and exact[b] != 0):
                    dfi[nd] = i + m
                    dfw[nd] = w
                    nd += 1
                    w = 0.0
        if sec is not None:
            j = sec[i + m]
        acc[(m & 3) * ns + j] += w  # four banks: no store-to-load chain on one sector
        fmax = _mx(fmax, f1)
        a0 = f0 > threshold
        a1 = f1 > threshold
        cross = cb[m]
        fc = fb[m]
        up = a1 & ~a0  # bitwise on booleans: no branch
        ep_start = cross if up else ep_start
        ep_peak = fc if up else ep_peak
        ep_open = 0.0 if up else ep_open
        ep_peak = _mx(ep_peak, f1 if a1 else fc)
        eps[ne, 0] = ep_start  # written every time, kept when the episode closes here
        eps[ne, 1] = cross
        eps[ne, 2] = ep_peak
        eps[ne, 3] = ep_open
        ne += 1 if a0 & ~a1 else 0
    sums[_FMAX] = fmax
    sums[_EP_START] = ep_start
    sums[_EP_PEAK] = ep_peak
    sums[_EP_OPEN] = ep_open
    return ne, nd


@njit(cache=True, nogil=True, error_model="numpy")
def _scan_sparse(fn, dy, dz, sec, i, te, threshold, base, edge, exact, qe, acc, sums, eps, dfi,
                 dfw, nd, wb, qb, cb, fb, bb):  # pragma: no cover - compiled
    """As :func:`_scan_dense` with branches that a smooth signal makes predictable: episodes
    handled where they start and end, the previous sample's sector reused while the contact
    point stays clear of its edges, the power summed in a register while the sector stays."""
    n = te - i
    ff = fn[i:te + 1]
    fmax = sums[_FMAX]
    ep_start = sums[_EP_START]
    ep_peak = sums[_EP_PEAK]
    ep_open = sums[_EP_OPEN]
    ne = 0
    j_last = 0
    q_lo = np.inf
    q_hi = -np.inf
    pj = 0
    pw = 0.0
    if dy is not None:
        yy = dy[i:te]
        zz = dz[i:te]
    for m in range(n):
        f0 = ff[m]
        f1 = ff[m + 1]
        w = wb[m]
        j = 0
        if dy is not None:
            q = qb[m]
            if q > q_lo and q < q_hi:
                j = j_last
            else:
                b = bb[m]
                e = edge[b]
                j = base[b] + (1 if q > e else 0)
                j_last = j
                q_lo = qe[j] + AMBIGUITY
                q_hi = qe[j + 1] - AMBIGUITY
                if (abs(q - e) <= AMBIGUITY or q + 2.0 <= AMBIGUITY) and w != 0.0:
                    on_axis = yy[m] == 0.0 or zz[m] == 0.0
                    if q + 2.0 <= AMBIGUITY or not (on_axis and exact[b] != 0):
                        dfi[nd] = i + m
                        dfw[nd] = w
                        nd += 1
                        w = 0.0
        if sec is not None:
            j = sec[i + m]
        if j != pj:
            acc[pj] += pw
            pw = 0.0
            pj = j
        pw += w
        fmax = _mx(fmax, f1)
        a0 = f0 > threshold
        a1 = f1 > threshold
        if a1:
            if not a0:
                ep_start = cb[m]
                ep_peak = fb[m]
                ep_open = 0.0
            ep_peak = _mx(ep_peak, f1)
        elif a0:
            eps[ne, 0] = ep_start
            eps[ne, 1] = cb[m]
            eps[ne, 2] = _mx(ep_peak, fb[m])
            eps[ne, 3] = ep_open
            ne += 1
    acc[pj] += pw
    sums[_FMAX] = fmax
    sums[_EP_START] = ep_start
    sums[_EP_PEAK] = ep_peak
    sums[_EP_OPEN] = ep_open
    return ne, nd
