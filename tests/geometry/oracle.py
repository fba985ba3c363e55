"""Independent numerical oracle for the worn-shape relations (issue 4 tests).

Nothing here uses the closed forms of ``fretwear.geometry``: areas are computed from the bodies'
surface profiles by adaptive quadrature (scipy.integrate.quad) between crossing points found by
root bracketing (scipy.optimize.brentq), or from polygons (shoelace formula, Sutherland-Hodgman
clipping by a convex polygon); tilted traces are integrated numerically along the width.

Conventions: the section is drawn in the (t, y) plane, y along the approach direction (the
mobile presses towards +y into the obstacle), t across it. A body's surface is a function
t -> y. The worn area between two surfaces is ∫ max(0, upper(t) - lower(t)) dt.

Shared by the engineers of issue 4 (the broached-hole and notch types build their own profiles
with these primitives).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable

import numpy as np
from scipy.integrate import IntegrationWarning
from scipy.integrate import quad as _scipy_quad
from scipy.optimize import brentq

QUAD = {"epsabs": 0.0, "epsrel": 1e-13, "limit": 400}


def quad(func, a, b, **options):
    """scipy's adaptive quadrature, silent about round-off (the tests compare the results)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        return _scipy_quad(func, a, b, **options)


# --------------------------------------------------------------------------- polygons
def polygon_area(x, y) -> float:
    """Signed area of a simple polygon (shoelace formula) [m²]; positive when counter-clockwise."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def circle_polygon(centre_t: float, centre_y: float, radius: float, vertices: int):
    """Counter-clockwise polygon inscribed in a circle, of equal area (radius scaled) [m]."""
    angles = np.linspace(0.0, 2.0 * math.pi, vertices, endpoint=False)
    # Scale so that the polygon has the circle's exact area (removes the O(1/N²) area bias).
    step = 2.0 * math.pi / vertices
    scale = math.sqrt(2.0 * math.pi / (vertices * math.sin(step)))
    return (centre_t + scale * radius * np.cos(angles),
            centre_y + scale * radius * np.sin(angles))


def clip_convex(subject: tuple[np.ndarray, np.ndarray], clip: tuple[np.ndarray, np.ndarray]):
    """Sutherland-Hodgman: the part of polygon ``subject`` inside convex CCW polygon ``clip``."""
    px, py = (np.asarray(a, dtype=float) for a in subject)
    cx, cy = (np.asarray(a, dtype=float) for a in clip)
    for i in range(len(cx)):
        ax, ay = cx[i], cy[i]
        bx, by = cx[(i + 1) % len(cx)], cy[(i + 1) % len(cx)]
        if len(px) == 0:
            break
        side = (bx - ax) * (py - ay) - (by - ay) * (px - ax)  # > 0 inside (left of a->b)
        qx, qy = np.roll(px, -1), np.roll(py, -1)
        qside = np.roll(side, -1)
        out_x, out_y = [], []
        for k in range(len(px)):
            if side[k] >= 0.0:
                out_x.append(px[k])
                out_y.append(py[k])
            if (side[k] >= 0.0) != (qside[k] >= 0.0):
                f = side[k] / (side[k] - qside[k])
                out_x.append(px[k] + f * (qx[k] - px[k]))
                out_y.append(py[k] + f * (qy[k] - py[k]))
        px, py = np.array(out_x), np.array(out_y)
    return px, py


def polygon_outside_area(subject, clip) -> float:
    """Area of polygon ``subject`` outside convex polygon ``clip`` [m²]."""
    inside = clip_convex(subject, clip)
    inner = polygon_area(*inside) if len(inside[0]) >= 3 else 0.0
    return polygon_area(*subject) - inner


# --------------------------------------------------------------------------- profiles
def crossings(func: Callable[[float], float], a: float, b: float, samples: int = 4001):
    """Zeros of ``func`` on [a, b], located by sign changes on a grid and refined by brentq."""
    t = np.linspace(a, b, samples)
    f = np.array([func(v) for v in t])
    roots = []
    for i in range(samples - 1):
        if f[i] == 0.0:
            roots.append(float(t[i]))
        elif f[i] * f[i + 1] < 0.0:
            roots.append(brentq(func, t[i], t[i + 1], xtol=1e-300, rtol=1e-15, maxiter=400))
    if f[-1] == 0.0:
        roots.append(float(t[-1]))
    return roots


def overlap_area(upper: Callable, lower: Callable, a: float, b: float,
                 breakpoints=()) -> float:
    """∫_a^b max(0, upper(t) - lower(t)) dt by quadrature between the crossing points [m²]."""
    gap = lambda t: upper(t) - lower(t)  # noqa: E731
    edges = sorted({a, b, *[p for p in breakpoints if a < p < b], *crossings(gap, a, b)})
    total = 0.0
    for left, right in zip(edges[:-1], edges[1:], strict=True):
        if right <= left or gap(0.5 * (left + right)) <= 0.0:
            continue
        total += quad(gap, left, right, **QUAD)[0]
    return total


def arc(centre_y: float, radius: float, sign: float = 1.0) -> Callable[[float], float]:
    """Profile t -> centre_y + sign·√(radius² − t²) of a circle centred on the y axis."""
    def profile(t: float) -> float:
        return centre_y + sign * math.sqrt(max(radius * radius - t * t, 0.0))
    return profile


# --------------------------------------------------------------------------- worn sections
def flat_cut_area(radius: float, depth: float) -> float:
    """Exact area of a disk beyond a straight line at ``depth`` below its top (flat bar) [m²].

    The gap √(R² − t²) − (R − D) decreases on [0, R]: one crossing, found by brentq; the area is
    twice the quadrature of the gap up to it.
    """
    if depth <= 0.0:
        return 0.0
    top = arc(0.0, radius)
    gap = lambda t: top(t) - (radius - depth)  # noqa: E731
    if gap(radius) >= 0.0:
        half = radius
    else:
        half = brentq(gap, 0.0, radius, xtol=1e-300, rtol=1e-15, maxiter=400)
    return 2.0 * quad(gap, 0.0, half, **QUAD)[0]


def lens_oracle(mobile_radius: float, obstacle_radius: float, depth: float):
    """(area, half_chord) of the mobile's disk outside the bore, mobile protruding by ``depth``.

    Bore centred at the origin, mobile centre at y = c = R_o − R_m + D: the mobile's top
    profile against the bore's top profile (upper halves: valid while the chord lies beyond the
    mobile's centre).
    """
    rm, ro = mobile_radius, obstacle_radius
    if depth <= 0.0:
        return 0.0, 0.0
    c = ro - rm + depth
    mobile, bore = arc(c, rm), arc(0.0, ro)
    gap = lambda t: mobile(t) - bore(t)  # noqa: E731  (decreasing on [0, R_m] as R_m < R_o)
    if gap(rm) >= 0.0:
        raise ValueError("depth beyond the lens range: the chord passes the mobile's centre")
    half_chord = brentq(gap, 0.0, rm, xtol=1e-300, rtol=1e-15, maxiter=400)
    area = 2.0 * quad(lambda t: mobile(t) - bore(t), 0.0, half_chord, **QUAD)[0]
    return area, half_chord


def lunule_oracle(mobile_radius: float, obstacle_radius: float, depth_mobile: float,
                  depth_obstacle: float):
    """(A_m, A_o): worn section areas of mobile and bore when both wear in one lunule [m²].

    The new common surface is the circle through the two crossing points of the original
    surfaces and through the apex at y = R_o + d_o (the bore worn d_o beyond its surface, the
    mobile d_m below its top at R_o + D). Its centre (0, y_c) follows from
    t*² + (y* − y_c)² = (apex − y_c)².
    """
    rm, ro = mobile_radius, obstacle_radius
    depth = depth_mobile + depth_obstacle
    if depth <= 0.0:
        return 0.0, 0.0
    c = ro - rm + depth
    mobile, bore = arc(c, rm), arc(0.0, ro)
    _, half_chord = lens_oracle(rm, ro, depth)
    y_star = bore(half_chord)
    apex = ro + depth_obstacle
    y_c = (apex ** 2 - half_chord ** 2 - y_star ** 2) / (2.0 * (apex - y_star))
    interface = arc(y_c, apex - y_c)
    a_m = 2.0 * quad(lambda t: mobile(t) - interface(t), 0.0, half_chord, **QUAD)[0]
    a_o = 2.0 * quad(lambda t: interface(t) - bore(t), 0.0, half_chord, **QUAD)[0]
    return a_m, a_o


def wedge_volume(section: Callable[[float], float], depth: float, width: float,
                 tilt: float) -> float:
    """∫_0^l A(depth − θ z) dz: a trace whose depth falls by θ per unit length [m³].

    ``width`` may be ``math.inf`` (unbounded wedge). A(d ≤ 0) = 0.
    """
    if tilt == 0.0:
        return width * section(depth)
    length = min(width, depth / tilt)
    return quad(lambda z: section(depth - tilt * z), 0.0, length, **QUAD)[0]
