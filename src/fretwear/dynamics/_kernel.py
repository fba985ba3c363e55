"""Compiled time-stepping kernel of the built-in dynamics (numba, ``cache=True``).

Not public: :func:`fretwear.dynamics.integrate.simulate` prepares the arrays and calls
:func:`advance`. The same function runs as plain Python (``advance.py_func``) when numba is absent
and in the benchmark's reference loop.

Scheme (velocity Verlet / central difference with a velocity predictor, second order):

    v½ = v_n + h/2·a_n;  q_{n+1} = q_n + h·v½;  a_{n+1} = f(t_{n+1}, q_{n+1}, v_n + h·a_n);
    v_{n+1} = v½ + h/2·a_{n+1}.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._numba import njit

#: Channel columns of the output buffer, in ContactHistory order (time is column 0).
OUT_COLUMNS = ("time", "normal_force", "ft1", "ft2", "vn", "vt1", "vt2", "dy", "dz", "stick")
# energy accumulator slots (the friction slot accumulates the tangential force's power)
E_EXT, E_PRE, E_DAMP, E_CN, E_FRIC = 0, 1, 2, 3, 4
N_ENERGY = 5
# per-shock channel slots in `chan`
C_FN, C_FT1, C_FT2, C_VN, C_VT1, C_VT2, C_DY, C_DZ, C_STICK, C_DELTA = range(10)


@njit(cache=True)
def _geometry(kind, gap, angle, oy, oz, prof_a, prof_r, plo, phi, uy, uz):
    """Penetration and outward unit normal of the obstacle: (delta, ny, nz)."""
    y = uy - oy
    z = uz - oz
    if kind == 0 or kind == 1:
        ny = math.cos(angle)
        nz = math.sin(angle)
        c = y * ny + z * nz
        if kind == 1 and c < 0.0:
            ny = -ny
            nz = -nz
            c = -c
        return c - gap, ny, nz
    r = math.sqrt(y * y + z * z)
    if kind == 2:
        if r > 0.0:
            return r - gap, y / r, z / r
        return r - gap, math.cos(angle), math.sin(angle)
    # discrete polar profile: polygon, segment holding the angle of (y, z)
    th = math.atan2(z, y)
    if th < 0.0:
        th += 2.0 * math.pi
    n = phi - plo
    if th < prof_a[plo] or th >= prof_a[phi - 1]:
        k = n - 1
    else:
        a, b = 0, n - 1  # prof_a[plo + a] <= th < prof_a[plo + b]
        while b - a > 1:
            mid = (a + b) // 2
            if prof_a[plo + mid] <= th:
                a = mid
            else:
                b = mid
        k = a
    k1 = (k + 1) % n
    p0y = prof_r[plo + k] * math.cos(prof_a[plo + k])
    p0z = prof_r[plo + k] * math.sin(prof_a[plo + k])
    p1y = prof_r[plo + k1] * math.cos(prof_a[plo + k1])
    p1z = prof_r[plo + k1] * math.sin(prof_a[plo + k1])
    ey = p1y - p0y
    ez = p1z - p0z
    le = math.sqrt(ey * ey + ez * ez)
    ny = ez / le
    nz = -ey / le
    if ny * p0y + nz * p0z < 0.0:
        ny = -ny
        nz = -nz
    return (y - p0y) * ny + (z - p0z) * nz, ny, nz


@njit(cache=True)
def advance(n_out, record_first, init, k0, t0, h, m_coarse, archive_every, adaptive,
            q, v, a, omega, zeta, invmass, mass, shapes,
            lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr,
            skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, mus, spre, prof_a, prof_r, prof_off,
            fs, uprev, incontact, frame, chan, energy, wear, pprev, out, counters):
    """Integrate until ``n_out`` archive samples are written to ``out`` (n_out, ns, 10).

    With ``init``, first evaluate the forces, acceleration, channels and powers of the current
    state (no step). State arrays are updated in place; returns the new fine-step index k, or -1
    when the state became non-finite (instability). ``counters`` = [fine steps, steps taken].
    The whole step is written in this one function: calls to compiled helpers taking arrays
    cost reference-count updates on every call, which dominated the step time.
    """
    nm = q.shape[0]
    ns = shapes.shape[0]
    nl = lshape.shape[0]
    f_ext = np.zeros(nm)
    f_pre = np.zeros(nm)
    f_cont = np.zeros(nm)
    vh = np.zeros(nm)
    stick_prev = np.zeros(ns)
    pw_prev = np.zeros(ns)
    p = np.zeros(5)
    k = k0
    j = 0
    if record_first and n_out > 0:
        for i in range(ns):
            out[0, i, 0] = t0 + k * h
            for c in range(9):
                out[0, i, c + 1] = chan[i, c]
        j = 1
    pending = init
    while pending or j < n_out:
        step = 0
        if not pending:
            step = 1
            if adaptive and m_coarse > 1 and k % m_coarse == 0:
                ok = True
                hc = h * m_coarse
                for i in range(ns):
                    if incontact[i] != 0:
                        ok = False
                        break
                    sp = 0.0
                    ac = 0.0
                    for c in range(3):
                        s1 = 0.0
                        s2 = 0.0
                        for r in range(nm):
                            s1 += shapes[i, c, r] * v[r]
                            s2 += shapes[i, c, r] * a[r]
                        sp += s1 * s1
                        ac += s2 * s2
                    margin = 2.0 * math.sqrt(sp) * hc + 2.0 * math.sqrt(ac) * hc * hc
                    if -chan[i, C_DELTA] <= margin:
                        ok = False
                        break
                if ok:
                    step = m_coarse
        hs = h * step
        for r in range(nm):
            vh[r] = v[r] + 0.5 * hs * a[r]
            q[r] += hs * vh[r]
            v[r] = v[r] + hs * a[r]  # predictor
        k += step
        t = t0 + k * h
        for i in range(ns):
            stick_prev[i] = chan[i, C_STICK]
            pw_prev[i] = chan[i, C_FN] * math.sqrt(chan[i, C_VT1] ** 2 + chan[i, C_VT2] ** 2)
        # ---------------------------------------------------------------- forces
        for r in range(nm):
            f_ext[r] = 0.0
            f_pre[r] = 0.0
            f_cont[r] = 0.0
        for l in range(nl):
            lo = tab_off[l]
            hi = tab_off[l + 1]
            if lkind[l] == 0:
                sig = lhp[l, 0] * math.sin(2.0 * math.pi * lhp[l, 1] * t + lhp[l, 2])
            else:
                pp = ptr[l]  # table pointer: t only increases, so it only moves forward
                if pp < lo or pp >= hi - 1 or tab_t[pp] > t:
                    pp = lo
                while pp < hi - 2 and tab_t[pp + 1] <= t:
                    pp += 1
                ptr[l] = pp
                if t <= tab_t[lo]:
                    sig = tab_v[lo]
                elif t >= tab_t[hi - 1]:
                    sig = tab_v[hi - 1]
                else:
                    wt = (t - tab_t[pp]) / (tab_t[pp + 1] - tab_t[pp])
                    sig = tab_v[pp] + wt * (tab_v[pp + 1] - tab_v[pp])
            for r in range(nm):
                f_ext[r] += lshape[l, r] * sig
        for i in range(ns):
            u0 = 0.0
            u1 = 0.0
            u2 = 0.0
            w0 = 0.0
            w1 = 0.0
            w2 = 0.0
            for r in range(nm):
                u0 += shapes[i, 0, r] * q[r]
                u1 += shapes[i, 1, r] * q[r]
                u2 += shapes[i, 2, r] * q[r]
                w0 += shapes[i, 0, r] * v[r]
                w1 += shapes[i, 1, r] * v[r]
                w2 += shapes[i, 2, r] * v[r]
            delta, ny, nz = _geometry(skind[i], sgap[i], sangle[i], sorig[i, 0], sorig[i, 1],
                                      prof_a, prof_r, prof_off[i], prof_off[i + 1], u0, u1)
            frame[i, 0] = ny
            frame[i, 1] = nz
            vn = w0 * ny + w1 * nz
            fn = 0.0
            g0 = 0.0
            g1 = 0.0
            g2 = 0.0
            stick = 0.0
            # sliding at the previous step (Code_Aster's ftang): the slip force is stored in
            # fs and the stick flag is 0; then the threshold is the dynamic one
            sliding = chan[i, C_STICK] == 0.0 and (fs[i, 0] != 0.0 or fs[i, 1] != 0.0
                                                   or fs[i, 2] != 0.0)
            if delta > 0.0:
                if incontact[i] == 0:
                    incontact[i] = 1
                    fs[i, 0] = 0.0
                    fs[i, 1] = 0.0
                    fs[i, 2] = 0.0
                fn = kn[i] * delta + cn[i] * vn
                if fn < 0.0:
                    fn = 0.0
                if (mu[i] > 0.0 or mus[i] > 0.0) and fn > 0.0:
                    # tangential increments and velocities (normal parts removed)
                    d0 = u0 - uprev[i, 0]
                    d1 = u1 - uprev[i, 1]
                    d2 = u2 - uprev[i, 2]
                    dn = d0 * ny + d1 * nz
                    d0 -= dn * ny
                    d1 -= dn * nz
                    x0 = w0 - vn * ny
                    x1 = w1 - vn * nz
                    sn = fs[i, 0] * ny + fs[i, 1] * nz
                    e0 = fs[i, 0] - sn * ny - kt[i] * d0
                    e1 = fs[i, 1] - sn * nz - kt[i] * d1
                    e2 = fs[i, 2] - kt[i] * d2
                    t0_ = e0 - ct[i] * x0
                    t1_ = e1 - ct[i] * x1
                    t2_ = e2 - ct[i] * w2
                    norm = math.sqrt(t0_ * t0_ + t1_ * t1_ + t2_ * t2_)
                    lim = (mu[i] if sliding else mus[i]) * fn
                    if norm <= lim:
                        stick = 1.0
                        g0 = t0_
                        g1 = t1_
                        g2 = t2_
                        fs[i, 0] = e0
                        fs[i, 1] = e1
                        fs[i, 2] = e2
                    else:
                        sc = mu[i] * fn / norm  # slides at the dynamic coefficient
                        g0 = t0_ * sc
                        g1 = t1_ * sc
                        g2 = t2_ * sc
                        fs[i, 0] = g0
                        fs[i, 1] = g1
                        fs[i, 2] = g2
                else:
                    fs[i, 0] = 0.0
                    fs[i, 1] = 0.0
                    fs[i, 2] = 0.0
            else:
                incontact[i] = 0
                fs[i, 0] = 0.0
                fs[i, 1] = 0.0
                fs[i, 2] = 0.0
            chan[i, C_FT1] = -g0 * nz + g1 * ny
            chan[i, C_FT2] = g2
            # force on the mobile at the shock point: −Fn·n + tangential
            g0 -= fn * ny
            g1 -= fn * nz
            for r in range(nm):
                f_cont[r] += shapes[i, 0, r] * g0 + shapes[i, 1, r] * g1 + shapes[i, 2, r] * g2
                f_pre[r] += shapes[i, 0, r] * spre[i, 0] + shapes[i, 1, r] * spre[i, 1]
            uprev[i, 0] = u0
            uprev[i, 1] = u1
            uprev[i, 2] = u2
            chan[i, C_FN] = fn
            chan[i, C_DY] = u0 - sorig[i, 0]
            chan[i, C_DZ] = u1 - sorig[i, 1]
            chan[i, C_STICK] = stick
            chan[i, C_DELTA] = delta
        # ---------------------------------------------------------------- acceleration
        finite = True
        for r in range(nm):
            a[r] = (f_ext[r] + f_pre[r] + f_cont[r]) * invmass[r] \
                - 2.0 * zeta[r] * omega[r] * v[r] - omega[r] * omega[r] * q[r]
            v[r] = vh[r] + 0.5 * hs * a[r]
            if not (math.isfinite(v[r]) and math.isfinite(q[r])):
                finite = False
        if not finite:
            return -1
        # ---------------------------------------------------------------- channels, powers
        pe = 0.0
        pr = 0.0
        pd = 0.0
        for r in range(nm):
            pe += f_ext[r] * v[r]
            pr += f_pre[r] * v[r]
            pd += 2.0 * zeta[r] * omega[r] * mass[r] * v[r] * v[r]
        pc = 0.0
        pt = 0.0
        for i in range(ns):
            w0 = 0.0
            w1 = 0.0
            w2 = 0.0
            for r in range(nm):
                w0 += shapes[i, 0, r] * v[r]
                w1 += shapes[i, 1, r] * v[r]
                w2 += shapes[i, 2, r] * v[r]
            ny = frame[i, 0]
            nz = frame[i, 1]
            chan[i, C_VN] = w0 * ny + w1 * nz
            chan[i, C_VT1] = -w0 * nz + w1 * ny
            chan[i, C_VT2] = w2
            d = chan[i, C_DELTA]
            el = kn[i] * d if d > 0.0 else 0.0
            pc += (chan[i, C_FN] - el) * chan[i, C_VN]
            pt += chan[i, C_FT1] * chan[i, C_VT1] + chan[i, C_FT2] * chan[i, C_VT2]
        p[0] = pe
        p[1] = pr
        p[2] = pd
        p[3] = pc
        p[4] = pt
        if pending:
            for c in range(5):
                pprev[c] = p[c]
            pending = False
            continue
        for c in range(5):
            energy[c] += 0.5 * hs * (pprev[c] + p[c])
            pprev[c] = p[c]
        for i in range(ns):
            if stick_prev[i] == 0.0:
                pw = chan[i, C_FN] * math.sqrt(chan[i, C_VT1] ** 2 + chan[i, C_VT2] ** 2)
                wear[i] += 0.5 * hs * (pw_prev[i] + pw)
        counters[0] += step
        counters[1] += 1
        if k % archive_every == 0:
            for i in range(ns):
                out[j, i, 0] = t
                for c in range(9):
                    out[j, i, c + 1] = chan[i, c]
            j += 1
    return k
