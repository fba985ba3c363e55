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

try:  # numba is an optional dependency ("fast" extra)
    from numba import njit

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False

    def njit(*args, **kwargs):
        def wrap(func):
            func.py_func = func
            return func
        if args and callable(args[0]):
            return wrap(args[0])
        return wrap

#: Channel columns of the output buffer, in ContactHistory order (time is column 0).
OUT_COLUMNS = ("time", "normal_force", "ft1", "ft2", "vn", "vt1", "vt2", "dy", "dz", "stick")
# energy accumulator slots
E_EXT, E_PRE, E_DAMP, E_CN, E_FRIC = 0, 1, 2, 3, 4
N_ENERGY = 5
# per-shock channel slots in `chan`
C_FN, C_FT1, C_FT2, C_VN, C_VT1, C_VT2, C_DY, C_DZ, C_STICK, C_DELTA = range(10)


@njit(cache=True)
def _signal(kind, hp, tab_t, tab_v, lo, hi, ptr, t):
    if kind == 0:
        return hp[0] * math.sin(2.0 * math.pi * hp[1] * t + hp[2])
    p = ptr
    if t <= tab_t[lo]:
        return tab_v[lo]
    if t >= tab_t[hi - 1]:
        return tab_v[hi - 1]
    if p < lo or p >= hi - 1 or tab_t[p] > t:
        p = lo
    while p < hi - 2 and tab_t[p + 1] <= t:
        p += 1
    w = (t - tab_t[p]) / (tab_t[p + 1] - tab_t[p])
    return tab_v[p] + w * (tab_v[p + 1] - tab_v[p])


@njit(cache=True)
def _table_pointer(tab_t, lo, hi, ptr, t):
    p = ptr
    if p < lo or p >= hi - 1 or tab_t[p] > t:
        p = lo
    while p < hi - 2 and tab_t[p + 1] <= t:
        p += 1
    return p


@njit(cache=True)
def _geometry(kind, gap, angle, oy, oz, prof_a, prof_r, plo, phi, uy, uz, out):
    """Penetration and outward normal of the obstacle; out = (delta, ny, nz)."""
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
        out[0] = c - gap
        out[1] = ny
        out[2] = nz
        return
    r = math.sqrt(y * y + z * z)
    if kind == 2:
        if r > 0.0:
            out[1] = y / r
            out[2] = z / r
        else:
            out[1] = math.cos(angle)
            out[2] = math.sin(angle)
        out[0] = r - gap
        return
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
    out[0] = (y - p0y) * ny + (z - p0z) * nz
    out[1] = ny
    out[2] = nz


@njit(cache=True)
def _forces(t, q, v, shapes, lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr,
            skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, spre,
            prof_a, prof_r, prof_off, fs, uprev, incontact, frame, chan,
            f_ext, f_pre, f_cont, geo, u, w):
    """Evaluate generalized forces at (t, q, v); update friction state and channels."""
    nm = q.shape[0]
    ns = shapes.shape[0]
    nl = lshape.shape[0]
    for r in range(nm):
        f_ext[r] = 0.0
        f_pre[r] = 0.0
        f_cont[r] = 0.0
    for l in range(nl):
        lo = tab_off[l]
        hi = tab_off[l + 1]
        if lkind[l] == 1:
            ptr[l] = _table_pointer(tab_t, lo, hi, ptr[l], t)
        s = _signal(lkind[l], lhp[l], tab_t, tab_v, lo, hi, ptr[l], t)
        for r in range(nm):
            f_ext[r] += lshape[l, r] * s
    for i in range(ns):
        for c in range(3):
            su = 0.0
            sw = 0.0
            for r in range(nm):
                su += shapes[i, c, r] * q[r]
                sw += shapes[i, c, r] * v[r]
            u[c] = su
            w[c] = sw
        _geometry(skind[i], sgap[i], sangle[i], sorig[i, 0], sorig[i, 1], prof_a, prof_r,
                  prof_off[i], prof_off[i + 1], u[0], u[1], geo)
        delta = geo[0]
        ny = geo[1]
        nz = geo[2]
        frame[i, 0] = ny
        frame[i, 1] = nz
        vn = w[0] * ny + w[1] * nz
        fn = 0.0
        f1 = 0.0
        f2 = 0.0
        f3 = 0.0
        stick = 0.0
        if delta > 0.0:
            if incontact[i] == 0:
                incontact[i] = 1
                fs[i, 0] = 0.0
                fs[i, 1] = 0.0
                fs[i, 2] = 0.0
            fn = kn[i] * delta + cn[i] * vn
            if fn < 0.0:
                fn = 0.0
            if mu[i] > 0.0 and fn > 0.0:
                # tangential increments and velocities (remove the normal part)
                d0 = u[0] - uprev[i, 0]
                d1 = u[1] - uprev[i, 1]
                d2 = u[2] - uprev[i, 2]
                dn = d0 * ny + d1 * nz
                d0 -= dn * ny
                d1 -= dn * nz
                w0 = w[0] - vn * ny
                w1 = w[1] - vn * nz
                w2 = w[2]
                sn = fs[i, 0] * ny + fs[i, 1] * nz
                s0 = fs[i, 0] - sn * ny
                s1 = fs[i, 1] - sn * nz
                s2 = fs[i, 2]
                e0 = s0 - kt[i] * d0
                e1 = s1 - kt[i] * d1
                e2 = s2 - kt[i] * d2
                t0 = e0 - ct[i] * w0
                t1 = e1 - ct[i] * w1
                t2 = e2 - ct[i] * w2
                norm = math.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
                lim = mu[i] * fn
                if norm <= lim:
                    stick = 1.0
                    f1, f2, f3 = t0, t1, t2
                    fs[i, 0], fs[i, 1], fs[i, 2] = e0, e1, e2
                else:
                    sc = lim / norm
                    f1, f2, f3 = t0 * sc, t1 * sc, t2 * sc
                    fs[i, 0], fs[i, 1], fs[i, 2] = f1, f2, f3
            else:
                fs[i, 0] = 0.0
                fs[i, 1] = 0.0
                fs[i, 2] = 0.0
        else:
            incontact[i] = 0
            fs[i, 0] = 0.0
            fs[i, 1] = 0.0
            fs[i, 2] = 0.0
        # force on the mobile at the shock point
        g0 = -fn * ny + f1
        g1 = -fn * nz + f2
        g2 = f3
        for r in range(nm):
            f_cont[r] += shapes[i, 0, r] * g0 + shapes[i, 1, r] * g1 + shapes[i, 2, r] * g2
            f_pre[r] += shapes[i, 0, r] * spre[i, 0] + shapes[i, 1, r] * spre[i, 1]
        uprev[i, 0] = u[0]
        uprev[i, 1] = u[1]
        uprev[i, 2] = u[2]
        chan[i, C_FN] = fn
        chan[i, C_FT1] = -f1 * nz + f2 * ny
        chan[i, C_FT2] = f3
        chan[i, C_DY] = u[0] - sorig[i, 0]
        chan[i, C_DZ] = u[1] - sorig[i, 1]
        chan[i, C_STICK] = stick
        chan[i, C_DELTA] = delta


@njit(cache=True)
def _velocity_channels(v, shapes, frame, chan):
    ns = shapes.shape[0]
    nm = v.shape[0]
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


@njit(cache=True)
def _accel(q, v, omega, zeta, invmass, f_ext, f_pre, f_cont, a):
    for r in range(q.shape[0]):
        a[r] = (f_ext[r] + f_pre[r] + f_cont[r]) * invmass[r] - 2.0 * zeta[r] * omega[r] * v[r] \
            - omega[r] * omega[r] * q[r]


@njit(cache=True)
def _powers(v, mass, omega, zeta, f_ext, f_pre, chan, kn, p):
    """Instantaneous powers: external, preload, modal damping, normal contact dissipation,
    tangential contact force on the mobile."""
    pe = 0.0
    pp = 0.0
    pd = 0.0
    for r in range(v.shape[0]):
        pe += f_ext[r] * v[r]
        pp += f_pre[r] * v[r]
        pd += 2.0 * zeta[r] * omega[r] * mass[r] * v[r] * v[r]
    pc = 0.0
    pt = 0.0
    for i in range(chan.shape[0]):
        d = chan[i, C_DELTA]
        el = kn[i] * d if d > 0.0 else 0.0
        pc += (chan[i, C_FN] - el) * chan[i, C_VN]
        pt += chan[i, C_FT1] * chan[i, C_VT1] + chan[i, C_FT2] * chan[i, C_VT2]
    p[0] = pe
    p[1] = pp
    p[2] = pd
    p[3] = pc
    p[4] = pt


@njit(cache=True)
def advance(n_out, record_first, k0, t0, h, m_coarse, archive_every, adaptive,
            q, v, a, omega, zeta, invmass, mass, shapes,
            lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr,
            skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, spre, prof_a, prof_r, prof_off,
            fs, uprev, incontact, frame, chan, energy, wear, pprev, out, counters):
    """Integrate until ``n_out`` archive samples are written to ``out`` (n_out, ns, 10).

    State arrays are updated in place; returns the new fine-step index k, or -1 when the state
    became non-finite (instability). ``counters`` = [fine steps, coarse steps].
    """
    nm = q.shape[0]
    ns = shapes.shape[0]
    f_ext = np.zeros(nm)
    f_pre = np.zeros(nm)
    f_cont = np.zeros(nm)
    geo = np.zeros(3)
    u = np.zeros(3)
    w = np.zeros(3)
    stick_prev = np.zeros(ns)
    pw_prev = np.zeros(ns)
    vh = np.zeros(nm)
    p = np.zeros(5)
    k = k0
    j = 0
    if record_first:
        for i in range(ns):
            out[0, i, 0] = t0 + k * h
            for c in range(9):
                out[0, i, c + 1] = chan[i, c]
        j = 1
    while j < n_out:
        target = k + archive_every
        while k < target:
            step = 1
            if adaptive and m_coarse > 1 and k % m_coarse == 0 and k + m_coarse <= target:
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
            _forces(t, q, v, shapes, lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr,
                    skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, spre,
                    prof_a, prof_r, prof_off, fs, uprev, incontact, frame, chan,
                    f_ext, f_pre, f_cont, geo, u, w)
            _accel(q, v, omega, zeta, invmass, f_ext, f_pre, f_cont, a)
            finite = True
            for r in range(nm):
                v[r] = vh[r] + 0.5 * hs * a[r]
                if not (math.isfinite(v[r]) and math.isfinite(q[r])):
                    finite = False
            if not finite:
                return -1
            _velocity_channels(v, shapes, frame, chan)
            _powers(v, mass, omega, zeta, f_ext, f_pre, chan, kn, p)
            energy[E_EXT] += 0.5 * hs * (pprev[0] + p[0])
            energy[E_PRE] += 0.5 * hs * (pprev[1] + p[1])
            energy[E_DAMP] += 0.5 * hs * (pprev[2] + p[2])
            energy[E_CN] += 0.5 * hs * (pprev[3] + p[3])
            energy[E_FRIC] += 0.5 * hs * (pprev[4] + p[4])
            for c in range(5):
                pprev[c] = p[c]
            for i in range(ns):
                if stick_prev[i] == 0.0:
                    pw = chan[i, C_FN] * math.sqrt(chan[i, C_VT1] ** 2 + chan[i, C_VT2] ** 2)
                    wear[i] += 0.5 * hs * (pw_prev[i] + pw)
            counters[0] += step
            counters[1] += 1
        for i in range(ns):
            out[j, i, 0] = t0 + k * h
            for c in range(9):
                out[j, i, c + 1] = chan[i, c]
        j += 1
    return k


@njit(cache=True)
def initialise(t, q, v, a, omega, zeta, invmass, mass, shapes,
               lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr,
               skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, spre, prof_a, prof_r, prof_off,
               fs, uprev, incontact, frame, chan, pprev):
    """Forces, acceleration, channels and powers of the initial state."""
    nm = q.shape[0]
    f_ext = np.zeros(nm)
    f_pre = np.zeros(nm)
    f_cont = np.zeros(nm)
    geo = np.zeros(3)
    u = np.zeros(3)
    w = np.zeros(3)
    _forces(t, q, v, shapes, lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr,
            skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, spre,
            prof_a, prof_r, prof_off, fs, uprev, incontact, frame, chan,
            f_ext, f_pre, f_cont, geo, u, w)
    _accel(q, v, omega, zeta, invmass, f_ext, f_pre, f_cont, a)
    _velocity_channels(v, shapes, frame, chan)
    _powers(v, mass, omega, zeta, f_ext, f_pre, chan, kn, pprev)
