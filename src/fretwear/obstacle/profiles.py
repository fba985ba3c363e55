"""The mobile and the obstacle's inner boundary as polar functions of the angle (theory §8).

The clearance figure is described in the shock frame of the mobile at rest: the origin is the
mobile's centre, the angle φ [deg] is measured like the contact angle θ = atan2(Dz, Dy) of theory §3
(from the local y axis towards z). The obstacle's inner boundary is the polar curve
``radius(φ)`` [m] (the bore, the planes, or a table of points); the radial gap is
``gap(φ) = radius(φ) − R_m`` [m]. The mobile is a tube of outer radius ``R_m`` and wall thickness
``e``.

Three obstacle models share one interface (``radius``, ``gap``, ``mobile_radius``,
``to_discrete``) and are listed in :data:`OBSTACLE_MODELS`:

* :class:`CircleObstacle` — a bore of radius ``R_o`` (or the radial gap ``R_o − R_m``);
* :class:`PlanesObstacle` — two parallel planes at gaps ``g₊`` (towards the orientation angle) and
  ``g₋`` (opposite), closed far away by a circle of radius ``closing_radius`` so the figure stays
  bounded (the open directions then show a large but finite clearance);
* :class:`DiscreteObstacle` — a periodic table of (angle, gap) points, linearly interpolated in
  angle: radial gaps (radius = R_m + gap), or a clearance figure whose obstacle is the figure
  dilated by the mobile's disk (:mod:`fretwear.obstacle.dilation`); Code_Aster's DEFI_OBSTACLE
  'DISCRET' layout (721 points, 0…360° by 0.5°, a clearance figure) is read and written by
  :func:`fretwear.obstacle.discret_file.read_discret` /
  :func:`~fretwear.obstacle.discret_file.write_discret` (layout in that module).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fretwear.errors import InputError
from fretwear.obstacle.clearance import clearance_figure, polar_polygon
from fretwear.obstacle.dilation import dilated_radius

#: Angular step [deg] and number of points of Code_Aster's DEFI_OBSTACLE 'DISCRET' table.
DISCRET_STEP = 0.5
DISCRET_POINTS = 721
#: Finest output step [deg] accepted: the update's time grows as 1/step (0.5 deg: 0.4 s,
#: 0.05 deg: 2.5 s, 0.01 deg: 13 s for a 6-sector update).
MIN_STEP = 0.05
#: Most points of a discrete obstacle (a DISCRET table): 0.036 deg apart over a turn.
MAX_DISCRETE_POINTS = 10_001
#: Radial gap [m] of a new Code_Aster DISCRET obstacle.
DISCRET_NEW_GAP = 0.5e-3


def discret_angles(step: float = DISCRET_STEP) -> np.ndarray:
    """Angles [deg] of the DISCRET grid: 0 to 360 inclusive by ``step`` (721 points by default).

    Examples
    --------
    >>> a = discret_angles()
    >>> a.size, float(a[0]), float(a[1]), float(a[-1])
    (721, 0.0, 0.5, 360.0)
    """
    if isinstance(step, bool) or not isinstance(step, (int, float, np.number)) \
            or not MIN_STEP <= step <= 120.0:
        raise InputError(f"the angular step (step_deg) = {step!r}: give a number of degrees "
                         f"from {MIN_STEP} to 120 that divides 360 (default {DISCRET_STEP}: "
                         "Code_Aster's 721 points)")
    n = int(round(360.0 / step))
    if n < 3 or not math.isclose(n * step, 360.0, rel_tol=0, abs_tol=1e-9):
        raise InputError(f"the angular step must divide 360 deg into >= 3 parts, got {step} deg")
    return np.arange(n + 1) * (360.0 / n)


def _positive(name: str, value, unit: str = "m", allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number [{unit}], got {value!r}") from None
    if math.isfinite(v) and v < 0:
        raise InputError(f"negative {name}: {v:g} {unit}; it must be >= 0 [{unit}]")
    if not math.isfinite(v) or (v == 0 and not allow_zero):
        sign = ">= 0" if allow_zero else "> 0"
        raise InputError(f"{name} must be finite and {sign} [{unit}], got {value!r}")
    if unit == "m" and (v > 1e3 or (not allow_zero and v < 1e-9)):
        # beyond, the clearance search overflows (r² of 1e154 m, a volume / 5e-324 m)
        raise InputError(f"{name} = {v:g} m is not a plausible obstacle dimension (1e-9 to "
                         "1e3 m); give it in metres (0.5 mm is 0.5e-3)")
    return v


@dataclass(frozen=True)
class Mobile:
    """The mobile tube: outer radius and wall thickness.

    Parameters
    ----------
    outer_radius : float
        Outer radius R_m [m].
    wall_thickness : float
        Wall thickness e [m], 0 < e <= R_m (e = R_m for a solid rod).

    Examples
    --------
    >>> Mobile(9.5e-3, 1.09e-3).wall_thickness
    0.00109
    """

    outer_radius: float
    wall_thickness: float

    def __post_init__(self):
        r = _positive("mobile outer_radius", self.outer_radius)
        e = _positive("mobile wall_thickness", self.wall_thickness)
        if e > r:
            raise InputError(
                f"mobile wall_thickness ({e:g} m) exceeds its outer_radius ({r:g} m); "
                "give the wall thickness, not the diameter")
        object.__setattr__(self, "outer_radius", r)
        object.__setattr__(self, "wall_thickness", e)


class _Obstacle:
    """Shared methods of the obstacle models (``radius`` is defined by each model)."""

    mobile_radius: float

    def gap(self, angle) -> np.ndarray:
        """Radial gap [m] between the obstacle and the new mobile at ``angle`` [deg]."""
        return self.radius(angle) - self.mobile_radius

    def to_discrete(self, step: float = DISCRET_STEP) -> DiscreteObstacle:
        """Sample the profile on the DISCRET grid (0…360° by ``step`` [deg])."""
        a = discret_angles(step)
        return DiscreteObstacle(a, self.gap(a), self.mobile_radius)

    def clearance(self, angle, resolution: float = 0.05) -> np.ndarray:
        """Clearance figure of the NEW mobile (a disk of radius R_m) in this obstacle [m].

        How far the disk can translate along each direction ``angle`` [deg] before it touches
        the obstacle: the figure the shock node of a dynamic computation sees. It equals
        ``gap(angle)`` for a bore, not for planes (g/cos ψ, not (R_m + g)/cos ψ − R_m) nor for
        a non-circular table. ``resolution`` [deg]: polygon step of the exact search
        (:mod:`fretwear.obstacle.clearance`).

        Examples
        --------
        >>> p = PlanesObstacle(9.5e-3, 0.5e-3)
        >>> [round(float(c), 9) for c in p.clearance([0.0, 60.0])]
        [0.0005, 0.001]
        """
        rm = self.mobile_radius
        if rm is None:
            raise InputError("the clearance of the new mobile needs the obstacle's mobile_radius")
        nodes = getattr(self, "angles", ())
        disk = polar_polygon(lambda a, side: np.full(np.shape(a), rm), nodes, resolution)
        bore = polar_polygon(lambda a, side: self.radius(a), nodes, resolution)
        return clearance_figure(angle, disk, bore)


@dataclass(frozen=True)
class CircleObstacle(_Obstacle):
    """A circular bore of radius R_o around the mobile (radius R_m) at rest.

    Parameters
    ----------
    mobile_radius : float
        Outer radius of the mobile R_m [m].
    bore_radius : float
        Radius of the bore R_o [m], >= R_m.

    Notes
    -----
    radius(φ) = R_o, gap(φ) = R_o − R_m for every φ.

    Examples
    --------
    >>> c = CircleObstacle.from_gap(9.5e-3, 0.5e-3)
    >>> float(c.radius(30.0)), round(float(c.gap(30.0)), 12)
    (0.01, 0.0005)
    """

    mobile_radius: float
    bore_radius: float

    def __post_init__(self):
        rm = _positive("mobile_radius", self.mobile_radius)
        ro = _positive("bore_radius", self.bore_radius)
        if ro < rm:
            raise InputError(
                f"negative gap: bore_radius {ro:g} m is smaller than mobile_radius {rm:g} m; "
                "the mobile must fit in the bore (bore_radius >= mobile_radius)")
        object.__setattr__(self, "mobile_radius", rm)
        object.__setattr__(self, "bore_radius", ro)

    @classmethod
    def from_gap(cls, mobile_radius: float, gap: float) -> CircleObstacle:
        """A bore given by its radial gap [m] around the mobile of radius ``mobile_radius`` [m]."""
        g = _positive("gap", gap, allow_zero=True)
        return cls(mobile_radius, _positive("mobile_radius", mobile_radius) + g)

    def radius(self, angle) -> np.ndarray:
        """Bore radius [m] at ``angle`` [deg] (constant)."""
        return np.full(np.shape(angle), self.bore_radius, dtype=float)


@dataclass(frozen=True)
class PlanesObstacle(_Obstacle):
    """Two parallel planes (a flat bar on each side) around the mobile.

    Parameters
    ----------
    mobile_radius : float
        Outer radius of the mobile R_m [m].
    plane_gap : float
        Gap g₊ [m] to the plane whose outward normal points at ``orientation``.
    plane_gap_opposite : float, optional
        Gap g₋ [m] to the plane on the opposite side (default: ``plane_gap``).
    orientation : float
        Angle [deg] of the outward normal of the first plane (default 0: planes normal to y).
    closing_radius : float, optional
        Radius [m] of the circle that closes the figure far away along the planes (default
        100 × (R_m + max(g₊, g₋))); the figure is the strip between the planes cut by that circle.

    Notes
    -----
    With ψ = φ − orientation, radius(φ) = min((R_m + g₊)/cos ψ if cos ψ > 0,
    (R_m + g₋)/(−cos ψ) if cos ψ < 0, closing_radius). The clearance of the new disk in
    direction φ is g₊/cos ψ (resp. g₋/(−cos ψ)) while that stays below the closing circle.

    Examples
    --------
    >>> p = PlanesObstacle(9.5e-3, 0.5e-3, 0.3e-3, orientation=90.0)
    >>> [round(float(g), 9) for g in p.gap([90.0, 270.0])]
    [0.0005, 0.0003]
    """

    mobile_radius: float
    plane_gap: float
    plane_gap_opposite: float | None = None
    orientation: float = 0.0
    closing_radius: float | None = None

    def __post_init__(self):
        rm = _positive("mobile_radius", self.mobile_radius)
        for name, v in (("plane_gap", self.plane_gap),
                        ("plane_gap_opposite", self.plane_gap_opposite)):
            if v is not None and isinstance(v, (int, float)) and float(v) < 0:
                raise InputError(f"negative gap: {name} = {float(v):g} m; plane gaps must be >= 0")
        gp = _positive("plane_gap", self.plane_gap, allow_zero=True)
        gm = gp if self.plane_gap_opposite is None else _positive(
            "plane_gap_opposite", self.plane_gap_opposite, allow_zero=True)
        try:
            orient = float(self.orientation)
        except (TypeError, ValueError):
            orient = math.nan
        if not math.isfinite(orient):
            raise InputError(f"orientation must be a finite angle [deg], got {self.orientation!r}")
        far = 100.0 * (rm + max(gp, gm)) if self.closing_radius is None else _positive(
            "closing_radius", self.closing_radius)
        if far <= rm + max(gp, gm):
            raise InputError(
                f"closing_radius {far:g} m must exceed R_m + gap = {rm + max(gp, gm):g} m")
        object.__setattr__(self, "mobile_radius", rm)
        object.__setattr__(self, "plane_gap", gp)
        object.__setattr__(self, "plane_gap_opposite", gm)
        object.__setattr__(self, "orientation", orient)
        object.__setattr__(self, "closing_radius", far)

    def radius(self, angle) -> np.ndarray:
        """Polar radius [m] of the figure (planes closed by the far circle) at ``angle`` [deg]."""
        gp, gm = self.plane_gap, self.plane_gap_opposite
        c = np.cos(np.radians(np.asarray(angle, dtype=float) - float(self.orientation)))
        rm = self.mobile_radius
        with np.errstate(divide="ignore"):
            r = np.where(c > 0, (rm + gp) / np.abs(c), (rm + gm) / np.abs(c))
        return np.minimum(r, self.closing_radius)


@dataclass(frozen=True)
class DiscreteObstacle(_Obstacle):
    """A periodic table of (angle, gap) points: radial gaps, or a clearance figure.

    Parameters
    ----------
    angles : array_like
        Angles [deg], strictly increasing, spanning one turn at most (e.g. 0…360 or −180…180; a
        last point at first + 360 must repeat the first gap).
    gaps : array_like
        Gap [m] at each angle, >= 0: the radial gap of the obstacle's inner boundary, or (with
        ``clearance_figure``) the clearance figure, how far the new mobile's centre can move.
    mobile_radius : float or None
        Outer radius of the mobile R_m [m]; needed for ``radius`` and for the obstacle update;
        may be None for a bare table.
    clearance_figure : bool
        False (default): radius(φ) = R_m + gap(φ). True (a Code_Aster DISCRET table, a DISCRET
        file read by :func:`~fretwear.obstacle.discret_file.read_discret`, a worn figure): the
        points are the clearance figure C (the polygon through them) and the obstacle's inner
        boundary is C dilated by the mobile's disk, so the new mobile's clearance is the table again
        (:mod:`fretwear.obstacle.dilation`).

    Notes
    -----
    gap(φ) is the periodic piecewise-linear interpolant of the table in φ. radius(φ) = R_m +
    gap(φ), or, for a clearance figure, the polar radius of C ⊕ D(R_m). Both agree for a circle;
    for two planes the figure g/|cos ψ| gives (R_m + g)/|cos ψ|, not R_m + g/|cos ψ|.

    Examples
    --------
    >>> d = DiscreteObstacle([0.0, 90.0, 180.0, 270.0], [1e-3, 2e-3, 1e-3, 2e-3], 0.01)
    >>> [round(float(g), 9) for g in d.gap([45.0, 315.0, -45.0])]
    [0.0015, 0.0015, 0.0015]
    >>> f = DiscreteObstacle(np.arange(0.0, 360.0, 0.5), np.full(720, 5e-4), 0.0095,
    ...                      clearance_figure=True)
    >>> round(float(f.radius(30.0)), 12)      # a 0.5 mm figure: a bore of 10 mm
    0.01
    """

    angles: np.ndarray
    gaps: np.ndarray
    mobile_radius: float | None = None
    clearance_figure: bool = False

    def __post_init__(self):
        a = np.array(self.angles, dtype=float).ravel()
        g = np.array(self.gaps, dtype=float).ravel()
        if a.size != g.size:
            raise InputError(f"discrete obstacle: {a.size} angles but {g.size} gaps")
        if a.size < 3:
            raise InputError(f"discrete obstacle needs >= 3 points, got {a.size}")
        if a.size > MAX_DISCRETE_POINTS:
            raise InputError(
                f"discrete obstacle: {a.size} points; at most {MAX_DISCRETE_POINTS} are accepted "
                "(the update's time grows as the square of the count: 7201 points 2 s, 72001 "
                "points 150 s); resample the table, e.g. every 0.5 deg (Code_Aster's 721)")
        if not (np.isfinite(a).all() and np.isfinite(g).all()):
            row = int(np.flatnonzero(~(np.isfinite(a) & np.isfinite(g)))[0])
            raise InputError(f"discrete obstacle: row {row} has a non-finite angle or gap")
        steps = np.diff(a)
        if (steps <= 0).any():
            row = int(np.flatnonzero(steps <= 0)[0]) + 1
            raise InputError(
                f"discrete obstacle: angles must be strictly increasing; row {row} "
                f"({a[row]:g} deg) does not exceed row {row - 1} ({a[row - 1]:g} deg)")
        span = a[-1] - a[0]
        if span > 360.0 + 1e-9:
            raise InputError(f"discrete obstacle: angles span {span:g} deg, more than one turn")
        if abs(span - 360.0) <= 1e-9:
            if abs(g[-1] - g[0]) > 1e-12 * max(1.0, abs(g[0])) + 1e-15:
                raise InputError(
                    f"discrete obstacle: the last point ({a[-1]:g} deg) closes the turn but its "
                    f"gap {g[-1]:g} m differs from the first ({g[0]:g} m)")
            a, g = a[:-1], g[:-1]
        if (g < 0).any():
            row = int(np.flatnonzero(g < 0)[0])
            raise InputError(
                f"negative gap in the discrete obstacle at row {row} (angle {a[row]:g} deg): "
                f"{g[row]:g} m; gaps must be >= 0 [m]")
        rm = None if self.mobile_radius is None else _positive("mobile_radius", self.mobile_radius)
        object.__setattr__(self, "angles", a)
        object.__setattr__(self, "gaps", g)
        object.__setattr__(self, "mobile_radius", rm)
        object.__setattr__(self, "clearance_figure", bool(self.clearance_figure))
        a.flags.writeable = False
        g.flags.writeable = False

    def gap(self, angle) -> np.ndarray:
        """Radial gap [m] at ``angle`` [deg], periodic linear interpolation of the table."""
        x = np.asarray(angle, dtype=float)
        a0 = self.angles[0]
        xp = np.append(self.angles, a0 + 360.0)
        fp = np.append(self.gaps, self.gaps[0])
        return np.interp(np.mod(x - a0, 360.0) + a0, xp, fp)

    def radius(self, angle) -> np.ndarray:
        """Polar radius [m] of the obstacle's inner boundary at ``angle`` [deg].

        mobile_radius + gap(angle), or for a clearance figure the radius of the figure dilated
        by the mobile's disk.
        """
        if self.mobile_radius is None:
            raise InputError(
                "this discrete obstacle has no mobile_radius: give it (mobile_radius=...) to "
                "turn gaps into radii")
        if self.clearance_figure:
            return dilated_radius(angle, self.angles, self.gaps, self.mobile_radius)
        return self.mobile_radius + self.gap(angle)


#: The obstacle models, keyed by the name used in case files (``[obstacle] type = ...``).
OBSTACLE_MODELS: dict[str, type] = {
    "circle": CircleObstacle,
    "planes": PlanesObstacle,
    "discrete": DiscreteObstacle,
}
