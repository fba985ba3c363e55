"""The obstacle behind a clearance figure: the figure dilated by the mobile's disk (theory §8).

A clearance figure C (Code_Aster's DEFI_OBSTACLE 'DISCRET' table, or the worn figure this
package writes) is the set of positions the mobile's centre may take: for a disk mobile of
radius R_m in an obstacle whose free space is O, C = O ⊖ D(R_m) (erosion). The obstacle the
figure stands for is then C ⊕ D(R_m) (dilation), the largest free space with that figure for
the disk: its clearance figure is C again whenever C is the figure of some obstacle (the
identity ((O ⊖ D) ⊕ D) ⊖ D = O ⊖ D of mathematical morphology; J. Serra, *Image Analysis and
Mathematical Morphology*, Academic Press, 1982, ch. II). Reading the table as radial gaps
(r_o = R_m + c(φ)) instead is exact for a circle only: for two planes it gives R_m + g/cos ψ
where the planes are at (R_m + g)/cos ψ.

C is taken as the polygon through the table points (as the dynamics reads it); it is
star-shaped around the origin (0 ∈ C), and so is C ⊕ D: a point p of D(q, R_m), q ∈ C, has
λp ∈ D(λq, R_m) with λq ∈ C for 0 ≤ λ ≤ 1. Its polar radius along e(φ) is therefore the largest
distance at which the ray leaves one of the stadiums [q_k, q_{k+1}] ⊕ D(R_m): the far crossing
of a vertex disk, ρ = q·e + √(R_m² − (q × e)²), or of an edge moved by ±R_m along its normal.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._numba import njit


@njit(cache=True)
def _dilated_radius(phi, px, py, radius):
    n = px.size
    r2 = radius * radius
    out = np.empty(phi.size)
    for k in range(phi.size):
        ex = math.cos(phi[k])
        ey = math.sin(phi[k])
        best = radius  # 0 ∈ C, so D(0, R_m) ⊂ C ⊕ D
        for i in range(n):
            qx = px[i]
            qy = py[i]
            j = (i + 1) % n
            dx = px[j] - qx
            dy = py[j] - qy
            b0 = qx * ex + qy * ey
            b1 = px[j] * ex + py[j] * ey
            if max(b0, b1) + radius <= best:
                continue  # nothing of this stadium lies beyond the best crossing so far
            a = qx * ey - qy * ex  # q × e
            if abs(a) <= radius:
                rho = b0 + math.sqrt(r2 - a * a)
                if rho > best:
                    best = rho
            length = math.hypot(dx, dy)
            den = ex * dy - ey * dx  # e × d
            if length == 0.0 or den == 0.0:
                continue
            nx = dy / length
            ny = -dx / length
            for side in (-1.0, 1.0):  # t·e = o + s·d with o = q ± R_m·n, 0 <= s <= 1
                ox = qx + side * radius * nx
                oy = qy + side * radius * ny
                s = (ox * ey - oy * ex) / den
                if 0.0 <= s <= 1.0:
                    t = (ox * dy - oy * dx) / den
                    if t > best:
                        best = t
        out[k] = best
    return out


def dilated_radius(angle, figure_angles, figure_gaps, mobile_radius: float) -> np.ndarray:
    """Polar radius [m] of the clearance figure dilated by the mobile's disk.

    Parameters
    ----------
    angle : array_like
        Directions [deg].
    figure_angles : array_like
        Angles [deg] of the figure's points, increasing, one turn (no repeated end point).
    figure_gaps : array_like
        Clearance [m] at each point, >= 0: the polygon through the points is the figure C.
    mobile_radius : float
        R_m [m].

    Returns
    -------
    numpy.ndarray
        r(φ) [m] of C ⊕ D(R_m), the obstacle's inner boundary the figure stands for.

    Notes
    -----
    r(φ) = max over the figure's edges of the far crossing of the ray with the stadium
    [q_k, q_{k+1}] ⊕ D(R_m) (module docstring). For a figure that is a disk of radius c it is
    R_m + c; for two planes, the figure g/|cos ψ| gives (R_m + g)/|cos ψ|.

    Examples
    --------
    The figure of two planes at 0.4 mm (normal along y), every 2° up to 88° from the normal
    (it reaches y = ±11.5 mm there): the planes at R_m + 0.4 mm = 9.9 mm, i.e.
    9.9/cos 30° = 11.431535 mm at 30°.

    >>> a = np.arange(-88.0, 89.0, 2.0)
    >>> a = np.concatenate([a, a + 180.0])
    >>> g = 0.4e-3 / np.abs(np.cos(np.radians(a)))
    >>> np.round(dilated_radius([0.0, 30.0, 180.0], a, g, 9.5e-3) * 1e3, 6).tolist()
    [9.9, 11.431535, 9.9]
    """
    t = np.radians(np.asarray(figure_angles, dtype=float))
    g = np.asarray(figure_gaps, dtype=float)
    px = np.ascontiguousarray(g * np.cos(t))
    py = np.ascontiguousarray(g * np.sin(t))
    phi = np.radians(np.asarray(angle, dtype=float))
    return _dilated_radius(phi.ravel(), px, py, float(mobile_radius)).reshape(phi.shape)
