"""Worn-depth profiles over the angle from cumulated sector volumes (theory §3, §8).

The worn cross-section between the new boundary r(φ) and the worn one is, per unit width, the
polar area element: for the mobile (material removed inwards from R_m)
``a(φ) = ½(R_m² − (R_m − d)²)`` and for the obstacle (material removed outwards from r_o(φ))
``a(φ) = ½((r_o + d)² − r_o²)`` [m²/rad]. A sector's volume is kept when
``l·∫_sector a(φ) dφ = V_j`` (l the obstacle width). Two shapes keep it exactly:

* ``"uniform"`` — constant depth over the sector (theory §3): mobile
  d = R_m − √(R_m² − 2V/(lΔθ)); obstacle, the root of ½Δθ·d² + I·d = V/l with I = ∫ r_o dφ over
  the sector, i.e. d = √(R̄² + 2V/(lΔθ)) − R̄ with the mean radius R̄ = I/Δθ (= R_o for a bore,
  theory §3's formula).
* ``"smooth"`` — a continuous shape: the cumulated area A(φ) = ∫ a dφ is interpolated through
  its exact values at the sector edges by a periodic monotone cubic (Fritsch–Carlson PCHIP);
  its derivative a(φ) ≥ 0 is continuous, zero where the sector holds no volume, and its sector
  integrals are the sector volumes by construction. The depth follows pointwise from a(φ).

Reference: F. N. Fritsch, R. E. Carlson, "Monotone piecewise cubic interpolation", SIAM J.
Numer. Anal. 17 (1980) 238-246.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from fretwear.errors import InputError, RangeWarning
from fretwear.geometry.sectors import (
    mobile_depth_from_area_density,
    obstacle_depth_from_area_density,
)
from fretwear.sectors import sector_edges

#: The depth shapes, keyed by name (``shape=`` argument, ``[obstacle] shape`` in case files).
DEPTH_SHAPES: dict[str, str] = {
    "uniform": "constant depth over each sector (docs/theory.md §3)",
    "smooth": "periodic monotone-cubic area density whose sector integrals are the volumes",
}


def sector_of(angle, edges: np.ndarray, side: str = "right") -> np.ndarray:
    """0-based sector index of angles [deg]; ``side`` picks the sector at an edge.

    ``side="right"``: edges[j] <= φ < edges[j+1]; ``side="left"``: edges[j] < φ <= edges[j+1];
    angles are wrapped modulo 360° first.

    Examples
    --------
    >>> e = np.array([-180.0, 0.0, 180.0])
    >>> sector_of([0.0, 0.0, 180.0, -180.0, 90.0], e, "right").tolist()
    [1, 1, 0, 0, 1]
    >>> sector_of([0.0, -180.0], e, "left").tolist()
    [0, 1]
    """
    a = np.mod(np.asarray(angle, dtype=float) + 180.0, 360.0) - 180.0  # [-180, 180)
    if side == "left":
        a = np.where(a <= edges[0], a + 360.0, a)  # (-180, 180]
        idx = np.searchsorted(edges, a, side="left") - 1
    else:
        idx = np.searchsorted(edges, a, side="right") - 1
    return np.clip(idx, 0, edges.size - 2)


def _sector_mean_radius(obstacle, edges: np.ndarray, points: int = 721) -> np.ndarray:
    """Mean polar radius R̄_j = (1/Δθ)∫ r_o dφ over each sector [m] (trapezoid, table nodes kept)."""
    nodes = getattr(obstacle, "angles", None)
    out = np.empty(edges.size - 1)
    for j in range(edges.size - 1):
        a = np.linspace(edges[j], edges[j + 1], points)
        if nodes is not None:
            extra = np.concatenate([nodes - 360.0, nodes, nodes + 360.0])
            extra = extra[(extra > edges[j]) & (extra < edges[j + 1])]
            a = np.union1d(a, extra)
        r = obstacle.radius(a)
        out[j] = np.trapezoid(r, a) / (edges[j + 1] - edges[j])
    return out


@dataclass(frozen=True)
class WornDepth:
    """Worn depth profiles of the mobile and of the obstacle over the angle.

    Build it with :func:`worn_depth_profiles`. ``mobile(angle)`` and ``obstacle(angle)`` return
    the radial depths [m] at angles [deg] (vectorised); ``side`` picks the left or right limit
    at a sector edge for the uniform shape.

    Attributes
    ----------
    edges : numpy.ndarray
        Sector edges [deg] (−180 … 180).
    volume_mobile, volume_obstacle : numpy.ndarray
        Cumulated sector volumes [m³].
    width : float
        Obstacle width l [m].
    mobile_radius : float
        R_m [m].
    shape : str
        ``"uniform"`` or ``"smooth"``.
    sector_depth_mobile, sector_depth_obstacle : numpy.ndarray
        Uniform shape: the sector depths [m]; smooth shape: the largest depth in each sector [m].
    """

    edges: np.ndarray
    volume_mobile: np.ndarray
    volume_obstacle: np.ndarray
    width: float
    mobile_radius: float
    obstacle_model: object
    shape: str
    sector_depth_mobile: np.ndarray
    sector_depth_obstacle: np.ndarray
    _density: tuple  # per body: None or (PchipInterpolator of A/total, total [m²])

    def _area_density(self, which: int, angle, side: str) -> np.ndarray:
        a = np.asarray(angle, dtype=float)
        if self.shape == "uniform":
            dtheta = np.radians(np.diff(self.edges))
            vol = self.volume_mobile if which == 0 else self.volume_obstacle
            return (vol / (self.width * dtheta))[sector_of(a, self.edges, side)]
        interp = self._density[which]
        if interp is None:
            return np.zeros(a.shape)
        x = np.radians(np.mod(a + 180.0, 360.0) - 180.0)
        return np.maximum(interp[0](x, 1), 0.0) * interp[1]

    def mobile(self, angle, side: str = "right") -> np.ndarray:
        """Mobile's worn radial depth [m] at ``angle`` [deg]; NaN past the mobile's centre."""
        a = np.asarray(angle, dtype=float)
        if self.shape == "uniform":
            return self.sector_depth_mobile[sector_of(a, self.edges, side)]
        return mobile_depth_from_area_density(self._area_density(0, a, side), self.mobile_radius)

    def obstacle(self, angle, side: str = "right") -> np.ndarray:
        """Obstacle's worn radial depth [m] at ``angle`` [deg]."""
        a = np.asarray(angle, dtype=float)
        if self.shape == "uniform":
            return self.sector_depth_obstacle[sector_of(a, self.edges, side)]
        return obstacle_depth_from_area_density(
            self._area_density(1, a, side), self.obstacle_model.radius(a))


def _pchip_cumulated(edges: np.ndarray, areas: np.ndarray):
    """Periodic monotone cubic through the cumulated areas A(edge) [m²] (angle in radians)."""
    if not (areas > 0).any():
        return None
    x = np.radians(edges)
    scale = float(np.sum(areas))  # PCHIP is scale-free: work on A/total (no under/overflow)
    cum = np.concatenate([[0.0], np.cumsum(areas / scale)])
    total = cum[-1]
    xs = np.concatenate([x[:-1] - 2 * np.pi, x, x[1:] + 2 * np.pi])
    ys = np.concatenate([cum[:-1] - total, cum, cum[1:] + total])
    with np.errstate(over="ignore", divide="ignore"):  # a slope ~1e-300: harmonic mean -> 0
        return PchipInterpolator(xs, ys, extrapolate=False), scale


def worn_depth_profiles(edges, volume_mobile, volume_obstacle=None, *, width: float,
                        mobile_radius: float, obstacle, shape: str = "uniform") -> WornDepth:
    """Worn depth profiles over the angle from the cumulated sector volumes.

    Parameters
    ----------
    edges : int or array_like
        Sector edges [deg] (−180 … 180, increasing) or a number of equal sectors.
    volume_mobile : array_like
        Cumulated worn volume of the mobile in each sector [m³], >= 0.
    volume_obstacle : array_like, optional
        Same for the obstacle [m³] (default zero).
    width : float
        Obstacle width l [m] (the worn height).
    mobile_radius : float
        Mobile outer radius R_m [m].
    obstacle : obstacle model
        The new obstacle (``radius(angle)`` [m]), see :mod:`fretwear.obstacle.profiles`.
    shape : {"uniform", "smooth"}
        Depth shape within sectors (:data:`DEPTH_SHAPES`).

    Returns
    -------
    WornDepth

    Warns
    -----
    RangeWarning
        When a sector's mobile volume exceeds the whole wedge (2V/(lΔθ) > R_m²): depth NaN.

    Notes
    -----
    Uniform (theory §3): d_m = R_m − √(R_m² − 2V_m/(lΔθ)), d_o = √(R̄² + 2V_o/(lΔθ)) − R̄.
    Smooth: a(φ) = dA/dφ with A the periodic PCHIP through the cumulated sector areas V/l;
    d_m(φ) = R_m − √(R_m² − 2a(φ)), d_o(φ) = √(r_o(φ)² + 2a(φ)) − r_o(φ).

    Examples
    --------
    >>> from fretwear.obstacle.profiles import CircleObstacle
    >>> w = worn_depth_profiles([-180, 0, 180], [0.0, 1e-9], [0.0, 0.0], width=0.02,
    ...                         mobile_radius=0.01, obstacle=CircleObstacle(0.01, 0.0105))
    >>> float(w.mobile(-90.0)), round(float(w.mobile(90.0)) * 1e9, 3)   # [nm], ≈ V/(lΔθR_m)
    (0.0, 1591.676)
    """
    e = sector_edges(edges)
    n = e.size - 1
    if shape not in DEPTH_SHAPES:
        raise InputError(f"unknown depth shape {shape!r}; choose one of {sorted(DEPTH_SHAPES)}")

    def volumes(name, v):
        arr = np.zeros(n) if v is None else np.array(v, dtype=float).ravel()
        if arr.size != n:
            raise InputError(f"{name}: {arr.size} sector volumes for {n} sectors (edges {e})")
        bad = ~np.isfinite(arr) | (arr < 0)
        if bad.any():
            j = int(np.flatnonzero(bad)[0])
            raise InputError(f"{name}: sector {j + 1} volume {arr[j]!r} m³ must be finite >= 0")
        arr.flags.writeable = False
        return arr

    vm = volumes("volume_mobile", volume_mobile)
    vo = volumes("volume_obstacle", volume_obstacle)
    l_ = float(width)
    if not np.isfinite(l_) or l_ <= 0:
        raise InputError(f"the obstacle width must be > 0 [m], got {width!r}")
    if not 1e-9 <= l_ <= 1e3:  # a volume over 5e-324 m is infinite
        raise InputError(f"the obstacle width = {l_:g} m is not a plausible obstacle dimension "
                         "(1e-9 to 1e3 m); give it in metres (20 mm is 20e-3)")
    rm = float(mobile_radius)
    dtheta = np.radians(np.diff(e))
    area_m, area_o = vm / l_, vo / l_
    dens_m = area_m / dtheta
    full = 2.0 * dens_m > rm * rm
    if full.any():
        j = int(np.flatnonzero(full)[0])
        warnings.warn(
            f"sector {j + 1} ({e[j]:g}..{e[j + 1]:g} deg): the mobile volume {vm[j]:.4g} m³ "
            f"exceeds the whole wedge l·Δθ·R_m²/2 = {l_ * dtheta[j] * rm * rm / 2:.4g} m³; "
            "its depth is NaN", RangeWarning, stacklevel=2)
    if shape == "uniform":
        dm = mobile_depth_from_area_density(dens_m, rm)
        rbar = _sector_mean_radius(obstacle, e) if (vo > 0).any() else np.full(n, np.nan)
        # root of ½Δθ d² + I d = A with I = R̄Δθ: d = 2A/(I + √(I² + 2ΔθA)), exact 0 at A = 0
        i_ = rbar * dtheta
        with np.errstate(invalid="ignore"):
            do = np.where(area_o > 0, 2 * area_o / (i_ + np.sqrt(i_ * i_ + 2 * dtheta * area_o)),
                          0.0)
        density = (None, None)
    else:
        density = (_pchip_cumulated(e, area_m), _pchip_cumulated(e, area_o))
        dm = np.zeros(n)
        do = np.zeros(n)
    w = WornDepth(e, vm, vo, l_, rm, obstacle, shape, dm, do, density)
    if shape == "smooth":
        fine = np.linspace(-180.0, 180.0, 7201)
        idx = sector_of(fine, e)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m_ = w.mobile(fine)
            o_ = w.obstacle(fine)
        dm = np.array([np.nanmax(m_[idx == j], initial=0.0) if not np.isnan(m_[idx == j]).any()
                       else np.nan for j in range(n)])
        over = np.isnan(dm) & ~full
        if over.any():
            j = int(np.flatnonzero(over)[0])
            warnings.warn(
                f"sector {j + 1} ({e[j]:g}..{e[j + 1]:g} deg): the smooth profile's area density "
                f"passes R_m²/2 (wear past the mobile's centre); its depth is NaN there: use "
                "shape='uniform' or finer sectors", RangeWarning, stacklevel=2)
        do = np.array([np.max(o_[idx == j], initial=0.0) for j in range(n)])
        w = WornDepth(e, vm, vo, l_, rm, obstacle, shape, dm, do, density)
    return w
