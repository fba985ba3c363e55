"""Exact clearance of a worn mobile inside a worn obstacle, direction by direction (theory §8).

Both bodies are star-shaped around the mobile's rest centre (the origin): the mobile is
{ρ ≤ r_m(φ)}, the obstacle's free space is {ρ ≤ r_O(φ)}. Each boundary is discretised as a
closed polygon with vertices on a fine angular grid (default 0.05°) plus the profile's
discontinuities (sector edges of a uniform depth, inserted twice: left and right limits, so a
step is a radial segment). The clearance in direction u is the largest translation s ≥ 0 before
the translated mobile touches the obstacle:

    s*(u) = min( min over mobile vertices p of the first boundary crossing of p + s·u in O,
                 min over obstacle vertices q of the first boundary crossing of q − s·u in M ),

which is exact for two polygons (first contact is vertex-on-edge). Touching is not overlapping:
a vertex crossing an edge's interior counts when it moves to the other side, a vertex meeting a
vertex counts when the two local cones (the mobile's material, the obstacle's material) overlap
right after; a body starting in contact (zero gap) and moving away is free. Each ray is
intersected only with the edges in the angular window it sweeps between a lower bound (it
cannot meet the obstacle inside the disk of radius min r_O; it cannot meet the mobile outside
max r_m, both sharpened per window by block bounds) and the best contact found so far, the
likeliest candidate first. Two prunings leave the minimum unchanged: a block of edges whose
offsets across the ray (x × u) do not bracket the ray's own offset cannot be crossed, and a
vertex whose ray runs straight into its own body cannot make the first contact (its body's
interior would have touched earlier). The search is exact, not a small-wear sum.

The only approximation is the polygon: its chords lie within R(1 − cos(h/2)) ≈ R·h²/8 of a
curved profile (1.0e-9 m for R = 10 mm and h = 0.05°); the clearance error is O(h²), a few
1e-9 m at h = 0.05° when the contact is grazing (measured: 4e-9 m on a random worn discrete
obstacle, 1e-18 m for a disk in a bore, whose inscribed polygons share their angles).
Cost (720 directions, 0.05°, one figure, 2 busy cores): ~0.05 s in a bore, ~0.9 s between two
planes (the directions along the planes have clearances up to the closing circle, and each ray
sweeps a wide angular window; 7-8 s before the two prunings, results bit-identical).
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._numba import njit
from fretwear.errors import InputError

#: Default angular resolution [deg] of the polygons used by the clearance search.
RESOLUTION = 0.05
#: Finest resolution [deg] accepted: the search time grows as 1/resolution (measured: 0.05 deg
#: 0.4 s, 0.005 deg 4 s for a 6-sector update); finer would run for minutes or exhaust memory.
MIN_RESOLUTION = 0.005


def resolution_steps(resolution: float = RESOLUTION) -> int:
    """Number of grid steps of ``resolution`` [deg] over a turn (360°), checked: an
    :class:`~fretwear.errors.InputError` unless it is a number from :data:`MIN_RESOLUTION` to
    90° that divides 360° into at least 4 steps.

    Examples
    --------
    >>> resolution_steps(0.05), resolution_steps(90)
    (7200, 4)
    """
    if isinstance(resolution, bool) or not isinstance(resolution, (int, float, np.number)) \
            or not MIN_RESOLUTION <= resolution <= 90.0:
        raise InputError(f"resolution (resolution_deg) = {resolution!r}: give a number of "
                         f"degrees from {MIN_RESOLUTION} to 90 that divides 360 (default "
                         f"{RESOLUTION})")
    n = int(round(360.0 / resolution))
    if n < 4 or abs(n * resolution - 360.0) > 1e-9:
        raise InputError(f"resolution must divide 360 deg into >= 4 steps, got {resolution} deg")
    return n


def polar_polygon(radius, breaks=(), resolution: float = RESOLUTION):
    """Closed polygon of a star-shaped polar profile.

    Parameters
    ----------
    radius : callable
        ``radius(angle_deg, side)`` -> radii [m]; ``side`` is ``"left"`` or ``"right"`` (the
        limit taken at a discontinuity).
    breaks : array_like
        Angles [deg] where the profile may jump; each becomes two vertices (left, right limits).
    resolution : float
        Grid step [deg].

    Returns
    -------
    (angle [rad], x [m], y [m]) : tuple of numpy.ndarray
        Vertices sorted by angle in [−π, π) (duplicated angles at breaks).

    Examples
    --------
    >>> a, x, y = polar_polygon(lambda ang, side: np.full(np.shape(ang), 2.0), resolution=90)
    >>> np.round(x, 12).tolist(), np.round(y, 12).tolist()
    ([-2.0, -0.0, 2.0, 0.0], [-0.0, -2.0, 0.0, 2.0])
    """
    n = resolution_steps(resolution)
    grid = -180.0 + np.arange(n) * (360.0 / n)
    br = np.unique(np.mod(np.asarray(breaks, dtype=float) + 180.0, 360.0) - 180.0)
    if br.size:
        near = np.min(np.abs(grid[:, None] - br[None, :]), axis=1) < 1e-9
        near |= np.abs(grid[:, None] - br[None, :] - 360.0).min(axis=1) < 1e-9
        grid = grid[~near]
    ang = np.concatenate([grid, br, br])
    side = np.concatenate([np.zeros(grid.size), np.zeros(br.size), np.ones(br.size)])
    order = np.lexsort((side, ang))
    ang, side = ang[order], side[order]
    r = np.empty(ang.size)
    left = side == 0
    r[left] = radius(ang[left], "left")
    r[~left] = radius(ang[~left], "right")
    # grid points (not breaks) are continuous: left == right there
    t = np.radians(ang)
    return t, r * np.cos(t), r * np.sin(t)


_BLOCK = 32  # edges per block of the local radius bounds


@njit(cache=True)
def _window(ang, ax, ay, ux, uy, s_lo, s_hi):
    """Edges swept by the ray segment a + s·u, s in [s_lo, s_hi]: (first edge, step, count)."""
    n = ang.size
    a0 = math.atan2(ay + s_lo * uy, ax + s_lo * ux)
    a1 = math.atan2(ay + s_hi * uy, ax + s_hi * ux)
    k0 = np.searchsorted(ang, a0, side="right") - 1
    k1 = np.searchsorted(ang, a1, side="right") - 1
    if k0 < 0:
        k0 = n - 1
    if k1 < 0:
        k1 = n - 1
    da = a1 - a0
    if da > math.pi:
        da -= 2 * math.pi
    elif da < -math.pi:
        da += 2 * math.pi
    if ax * uy - ay * ux >= 0:  # the polar angle of a line not through 0 is monotone
        return k0, 1, ((k1 - k0) % n if da >= 0 else 0)
    return k0, -1, ((k0 - k1) % n if da <= 0 else 0)


_T_VERTEX = 1e-9  # edge parameter within which a crossing is at a vertex
_ARC_TOL = 1e-10  # [rad] a direction on a cone's edge is not inside it (sliding contact)
_TWO_PI = 2.0 * math.pi


@njit(cache=True)
def _cones(xs, ys, interior):
    """Per vertex, the cone of the polygon's interior (or exterior) as (start angle, width).

    Counter-clockwise polygon: with d_in, d_out the directions of the edges into and out of the
    vertex (zero-length edges skipped), the interior is the arc from angle(d_out)
    counter-clockwise to angle(−d_in); the exterior is the complementary arc.
    """
    n = xs.size
    start = np.empty(n)
    width = np.empty(n)
    for k in range(n):
        kp = (k - 1) % n
        for _ in range(n):
            if xs[kp] != xs[k] or ys[kp] != ys[k]:
                break
            kp = (kp - 1) % n
        kn = (k + 1) % n
        for _ in range(n):
            if xs[kn] != xs[k] or ys[kn] != ys[k]:
                break
            kn = (kn + 1) % n
        a_out = math.atan2(ys[kn] - ys[k], xs[kn] - xs[k])
        a_back = math.atan2(ys[kp] - ys[k], xs[kp] - xs[k])  # direction of −d_in
        w = (a_back - a_out) % _TWO_PI
        if interior:
            start[k] = a_out
            width[k] = w
        else:
            start[k] = a_back
            width[k] = _TWO_PI - w
    return start, width


@njit(cache=True)
def _in_arc(x, start, width):
    d = (x - start) % _TWO_PI
    return _ARC_TOL < d < width - _ARC_TOL


_CULL_TOL = 1e-7  # [rad] a direction this close to a cone's edge is not culled


@njit(cache=True)
def _behind(direction, start, width):
    """Whether a vertex moving along ``direction`` [rad] goes straight into its own body.

    ``start``, ``width``: the cone of the vertex's own body (the mobile's interior, or the
    obstacle's material). If p + εu lies inside the body for small ε > 0, p cannot make the
    first contact: had p + s·u reached the other boundary at s, the body's interior point
    p + εu would already have been there at s − ε, an overlap before s. So its hits are never
    the minimum and the vertex is skipped (the first contact is found by another vertex, of
    this body or of the other one). A margin ``_CULL_TOL`` keeps rays along a cone's edge.
    """
    d = (direction - start) % _TWO_PI
    return _CULL_TOL < d < width - _CULL_TOL


@njit(cache=True)
def _vertex_contact_overlaps(o_start, o_width, m_start, m_width, ux, uy):
    """Whether two touching vertices overlap once the mobile moves on by ε·u (ε -> 0+).

    W_o: the obstacle's material cone at its vertex, W_m: the mobile's interior cone at its
    vertex, both with apex at the contact point. (W_m + εu) ∩ W_o ≠ ∅ iff u ∈ W_o − W_m: when
    W_o is not convex (its complement, the free cone F, is convex and holds W_m) iff u ∈ W_o;
    when W_m is not convex iff −u ∈ W_m; when both are convex iff u is in the open conic hull
    of W_o ∪ (−W_m) (the whole plane when they are not within a half-plane).
    """
    u = math.atan2(uy, ux)
    if o_width > math.pi + _ARC_TOL:
        return _in_arc(u, o_start, o_width)
    if m_width > math.pi + _ARC_TOL:
        return _in_arc(u + math.pi, m_start, m_width)
    b_start = m_start + math.pi
    cover_a = max(o_width, (b_start - o_start) % _TWO_PI + m_width)
    cover_b = max(m_width, (o_start - b_start) % _TWO_PI + o_width)
    if cover_a <= cover_b:
        start, cover = o_start, cover_a
    else:
        start, cover = b_start, cover_b
    if cover > math.pi + _ARC_TOL:
        return True
    return _in_arc(u, start, cover)


@njit(cache=True)
def _first_hit(ang, xs, ys, t_start, t_width, t_lo, t_hi, ax, ay, a_start, a_width, ux, uy,
               s_lo, s_hi, leaving):
    """Smallest s in [0, s_hi) where the vertex a + s·u starts to overlap the target polygon.

    ``leaving`` (forward pass): a is a mobile vertex in the obstacle's free space, the target
    is the obstacle (t_* its material cones, a_* the mobile's interior cone at a); otherwise
    (backward pass) a is an obstacle vertex moving by −u relative to the mobile, the target is
    the mobile (t_* its interior cones, a_* the obstacle's material cone at a). A crossing of an
    edge's interior counts when the vertex moves to the other side; a vertex-on-vertex contact
    counts when the two local cones overlap right after (:func:`_vertex_contact_overlaps`).
    Touching without overlapping (a start on the boundary moving away, sliding, grazing) does
    not count: the bodies may touch. Blocks of edges whose offsets across the ray (t_lo, t_hi
    from :func:`_offset_blocks`) do not bracket the ray's own offset a × u cannot be crossed
    and are skipped; the minimum over the remaining edges is the same.
    """
    n = ang.size
    k0, step, count = _window(ang, ax, ay, ux, uy, s_lo, s_hi)
    best = s_hi
    found = False
    c_a = ax * uy - ay * ux  # offset of the ray's line across u: x × u is constant along it
    first = k0 - 2 if step > 0 else k0 - count - 2
    last = first + count + 4
    idx = first
    while idx <= last:
        k = idx % n
        b = k // _BLOCK
        if c_a < t_lo[b] or c_a > t_hi[b]:  # no edge of this block brackets the ray
            idx += min((b + 1) * _BLOCK, n) - k
            continue
        idx += 1
        kn = (k + 1) % n
        ex = xs[kn] - xs[k]
        ey = ys[kn] - ys[k]
        den = ux * ey - uy * ex  # u · outward normal (ey, -ex) of the counter-clockwise edge
        if abs(den) <= 1e-12 * math.hypot(ex, ey):
            continue  # parallel: sliding along the edge; its ends are vertex contacts
        wx = xs[k] - ax
        wy = ys[k] - ay
        t = (wx * uy - wy * ux) / den
        if t < -_T_VERTEX or t > 1.0 + _T_VERTEX:
            continue
        if t <= _T_VERTEX or t >= 1.0 - _T_VERTEX:
            v = k if t <= _T_VERTEX else kn
            if leaving:
                hit = _vertex_contact_overlaps(t_start[v], t_width[v], a_start, a_width, ux, uy)
            else:  # the mobile moves by +u = −(ray direction)
                hit = _vertex_contact_overlaps(a_start, a_width, t_start[v], t_width[v],
                                               -ux, -uy)
            if not hit:
                continue
        elif (leaving and den < 0.0) or (not leaving and den > 0.0):
            continue
        s = (wx * ey - wy * ex) / den
        if s < -1e-15:
            continue
        if s < 0.0:
            s = 0.0
        if s < best:
            best = s
            found = True
    if found:
        return best
    return np.inf


@njit(cache=True)
def _block_bound(bounds, k0, step, count, n, lowest):
    """Min (lowest) or max of the block bounds over the edges k0 + step·j, j in [-2, count+2]."""
    first = k0 - 2 if step > 0 else k0 - count - 2
    last = first + count + 4
    nb = bounds.size
    b_first = first // _BLOCK
    b_last = last // _BLOCK
    if b_last - b_first + 1 >= nb:
        b_first = 0
        b_last = nb - 1
    out = bounds[b_first % nb]
    for b in range(b_first, b_last + 1):
        v = bounds[b % nb]
        if (lowest and v < out) or (not lowest and v > out):
            out = v
    return out


@njit(cache=True)
def _edge_distances(xs, ys):
    """Distance from the origin to each edge k -> k+1 (its nearest point) [m]."""
    n = xs.size
    d = np.empty(n)
    for k in range(n):
        kn = (k + 1) % n
        ex = xs[kn] - xs[k]
        ey = ys[kn] - ys[k]
        e2 = ex * ex + ey * ey
        t = 0.0 if e2 == 0.0 else -(xs[k] * ex + ys[k] * ey) / e2
        t = min(max(t, 0.0), 1.0)
        d[k] = math.hypot(xs[k] + t * ex, ys[k] + t * ey)
    return d


@njit(cache=True)
def _blocks(values, lowest):
    nb = (values.size + _BLOCK - 1) // _BLOCK
    out = np.empty(nb)
    for b in range(nb):
        chunk = values[b * _BLOCK:min((b + 1) * _BLOCK, values.size)]
        out[b] = chunk.min() if lowest else chunk.max()
    return out


@njit(cache=True)
def _forward(m, o, o_in_blocks, o_lo, o_hi, r_in, r_out, ux, uy):
    """Min over mobile vertices of the distance at which p + s·u starts to overlap the obstacle.

    The obstacle's boundary lies in the annulus r_in <= ρ <= r_out (r_in: nearest edge point),
    so p + s·u cannot leave before the exit from the disk r_in (lower bound) and has left by
    the exit from the disk r_out; the lower bound is then sharpened with the nearest edge point
    of the angular window the ray sweeps (block minima). Vertices whose ray enters the mobile
    itself are skipped (:func:`_behind`).
    """
    mang, mx, my, m_start, m_width = m
    oang, ox, oy, o_start, o_width = o
    n = mx.size
    no = oang.size
    lb = np.empty(n)
    hi = np.empty(n)
    u_angle = math.atan2(uy, ux)
    for i in range(n):
        b = mx[i] * ux + my[i] * uy
        p2 = mx[i] * mx[i] + my[i] * my[i]
        if p2 < r_in * r_in:  # inside the disk the obstacle cannot reach: exit from it first
            lb[i] = max(-b + math.sqrt(b * b - (p2 - r_in * r_in)), 0.0)
        else:  # (zero gap somewhere: the polygon's chords dip below the mobile)
            lb[i] = 0.0
        d_out = b * b - (p2 - r_out * r_out)
        hi[i] = -b + math.sqrt(max(d_out, 0.0)) * (1.0 + 1e-9) + 1e-15
    best = np.inf
    i0 = np.argmin(lb)  # the likeliest contact first: its hit bounds every later window
    if not _behind(u_angle, m_start[i0], m_width[i0]):
        best = _first_hit(oang, ox, oy, o_start, o_width, o_lo, o_hi, mx[i0], my[i0],
                          m_start[i0], m_width[i0], ux, uy, lb[i0], hi[i0], True)
    for i in range(n):
        if lb[i] >= best or i == i0 or _behind(u_angle, m_start[i], m_width[i]):
            continue
        s_hi = min(best, hi[i])
        k0, step, count = _window(oang, mx[i], my[i], ux, uy, lb[i], s_hi)
        r_loc = _block_bound(o_in_blocks, k0, step, count, no, True)
        if r_loc > r_in:
            b = mx[i] * ux + my[i] * uy
            p2 = mx[i] * mx[i] + my[i] * my[i]
            if p2 < r_loc * r_loc and -b + math.sqrt(b * b - (p2 - r_loc * r_loc)) >= best:
                continue
        s = _first_hit(oang, ox, oy, o_start, o_width, o_lo, o_hi, mx[i], my[i], m_start[i],
                       m_width[i], ux, uy, lb[i], s_hi, True)
        if s < best:
            best = s
    return best


@njit(cache=True)
def _backward(o, m, m_out_blocks, m_lo, m_hi, r_in, r_out, ux, uy, best):
    """Min over obstacle vertices of the distance at which q − s·u starts to overlap the mobile.

    The mobile's boundary lies in r_in <= ρ <= r_out (r_in: nearest edge point, r_out: farthest
    vertex): q − s·u cannot enter before the disk r_out and has entered by the disk r_in; the
    lower bound is sharpened with the farthest vertex of the swept window (block maxima).
    Vertices whose ray −u enters the obstacle's material are skipped (:func:`_behind`).
    """
    qang, qx, qy, q_start, q_width = o
    mang, mx, my, m_start, m_width = m
    n = qx.size
    nm = mang.size
    lb = np.empty(n)
    hi = np.empty(n)
    wx = -ux
    wy = -uy
    w_angle = math.atan2(wy, wx)
    for i in range(n):
        b = qx[i] * wx + qy[i] * wy
        q2 = qx[i] * qx[i] + qy[i] * qy[i]
        d_out = b * b - (q2 - r_out * r_out)
        if d_out < 0.0 or -b + math.sqrt(d_out) < 0.0:
            lb[i] = np.inf
            hi[i] = np.inf
            continue
        lb[i] = max(-b - math.sqrt(d_out), 0.0)
        d_in = b * b - (q2 - r_in * r_in)
        if d_in >= 0.0 and -b - math.sqrt(d_in) >= lb[i]:
            hi[i] = -b - math.sqrt(d_in)
        else:
            hi[i] = -b + math.sqrt(d_out)
        hi[i] = hi[i] * (1.0 + 1e-9) + 1e-15
    for i in range(n):
        if lb[i] >= best or _behind(w_angle, q_start[i], q_width[i]):
            continue
        s_hi = min(best, hi[i])
        k0, step, count = _window(mang, qx[i], qy[i], wx, wy, lb[i], s_hi)
        r_loc = _block_bound(m_out_blocks, k0, step, count, nm, False)
        if r_loc < r_out:
            b = qx[i] * wx + qy[i] * wy
            q2 = qx[i] * qx[i] + qy[i] * qy[i]
            d_loc = b * b - (q2 - r_loc * r_loc)
            if d_loc < 0.0:
                continue  # the ray misses every vertex and edge of the window
            if -b - math.sqrt(d_loc) >= best:
                continue
        s = _first_hit(mang, mx, my, m_start, m_width, m_lo, m_hi, qx[i], qy[i], q_start[i],
                       q_width[i], wx, wy, lb[i], s_hi, False)
        if s < best:
            best = s
    return best


@njit(cache=True)
def _edge_slack(xs, ys, slack):
    """Per block of edges, the margin added to its offset bounds [m].

    A crossing is accepted up to the edge parameter ``_T_VERTEX`` beyond an end, i.e. an offset
    up to ``_T_VERTEX`` × edge length outside the edge's own range: twice that for the longest
    edge of the block, plus ``slack`` for rounding.
    """
    n = xs.size
    nb = (n + _BLOCK - 1) // _BLOCK
    out = np.empty(nb)
    for b in range(nb):
        longest = 0.0
        for k in range(b * _BLOCK, min((b + 1) * _BLOCK, n)):
            kn = (k + 1) % n
            longest = max(longest, math.hypot(xs[kn] - xs[k], ys[kn] - ys[k]))
        out[b] = 2.0 * _T_VERTEX * longest + slack
    return out


@njit(cache=True)
def _offset_blocks(xs, ys, ux, uy, tol, lo, hi):
    """Per block of edges, the range [lo, hi] of the offsets x × u of its vertices [m].

    The points of a ray a + s·u all have the offset a × u; the ray can cross an edge only if
    that offset lies between the offsets of the edge's ends (widened by ``tol``), so a block
    whose range misses it holds no candidate. Fills ``lo`` and ``hi`` in place.
    """
    n = xs.size
    for b in range(lo.size):
        end = min((b + 1) * _BLOCK, n)
        k = end % n  # the last edge's end vertex
        c = xs[k] * uy - ys[k] * ux
        mn = c
        mx = c
        for k in range(b * _BLOCK, end):
            c = xs[k] * uy - ys[k] * ux
            if c < mn:
                mn = c
            if c > mx:
                mx = c
        lo[b] = mn - tol[b]
        hi[b] = mx + tol[b]


@njit(cache=True)
def _clearance_kernel(psi, mang, mx, my, oang, ox, oy):
    m_start, m_width = _cones(mx, my, True)  # the mobile's material: its interior
    o_start, o_width = _cones(ox, oy, False)  # the obstacle's material: outside the free space
    m = (mang, mx, my, m_start, m_width)
    o = (oang, ox, oy, o_start, o_width)
    m_edge = _edge_distances(mx, my)
    o_edge = _edge_distances(ox, oy)
    m_vertex = np.sqrt(mx * mx + my * my)
    o_vertex = np.sqrt(ox * ox + oy * oy)
    m_out_blocks = _blocks(np.maximum(m_vertex, np.roll(m_vertex, -1)), False)
    o_in_blocks = _blocks(o_edge, True)
    rm_in = m_edge.min()
    rm_out = m_vertex.max()
    ro_in = o_edge.min()
    ro_out = o_vertex.max()
    # offsets across the ray are compared to ~1e-16 relative: a margin far above rounding
    slack = 1e-12 * max(rm_out, ro_out)
    m_tol = _edge_slack(mx, my, slack)
    o_tol = _edge_slack(ox, oy, slack)
    m_lo = np.empty(m_tol.size)
    m_hi = np.empty(m_tol.size)
    o_lo = np.empty(o_tol.size)
    o_hi = np.empty(o_tol.size)
    out = np.empty(psi.size)
    for k in range(psi.size):
        ux = math.cos(psi[k])
        uy = math.sin(psi[k])
        _offset_blocks(ox, oy, ux, uy, o_tol, o_lo, o_hi)  # rays p + s·u on the obstacle
        _offset_blocks(mx, my, -ux, -uy, m_tol, m_lo, m_hi)  # rays q − s·u on the mobile
        best = _forward(m, o, o_in_blocks, o_lo, o_hi, ro_in, ro_out, ux, uy)
        out[k] = _backward(o, m, m_out_blocks, m_lo, m_hi, rm_in, rm_out, ux, uy, best)
    return out


def clearance_figure(directions, mobile_polygon, obstacle_polygon) -> np.ndarray:
    """Clearance [m] of the mobile polygon inside the obstacle polygon along each direction.

    Parameters
    ----------
    directions : array_like
        Directions of translation [deg].
    mobile_polygon, obstacle_polygon : tuple
        ``(angle [rad], x [m], y [m])`` from :func:`polar_polygon`.

    Returns
    -------
    numpy.ndarray
        s*(φ) [m]: the largest translation along φ before contact (0 when already touching; NaN
        when a polygon is not finite).

    Notes
    -----
    s*(u) = sup{s ≥ 0 : M + s'u ⊂ O for all 0 ≤ s' ≤ s}, computed vertex-on-edge (module
    docstring).

    Examples
    --------
    A disk of radius 1 in a disk of radius 1.5: the clearance is 0.5 in every direction.

    >>> m = polar_polygon(lambda a, s: np.full(np.shape(a), 1.0))
    >>> o = polar_polygon(lambda a, s: np.full(np.shape(a), 1.5))
    >>> np.round(clearance_figure([0.0, 33.3, 270.0], m, o), 8).tolist()
    [0.5, 0.5, 0.5]
    """
    psi = np.radians(np.asarray(directions, dtype=float))
    shape = psi.shape
    mang, mx, my = (np.ascontiguousarray(v, dtype=float) for v in mobile_polygon)
    oang, ox, oy = (np.ascontiguousarray(v, dtype=float) for v in obstacle_polygon)
    if not (np.isfinite(mx).all() and np.isfinite(my).all()
            and np.isfinite(ox).all() and np.isfinite(oy).all()):
        return np.full(shape, np.nan)
    return _clearance_kernel(psi.ravel(), mang, mx, my, oang, ox, oy).reshape(shape)
