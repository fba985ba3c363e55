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
  :func:`read_discret` / :func:`write_discret`.

DISCRET file layout adopted (a Code_Aster IMPR_TABLE 'TABLEAU'-style text table)::

    #
    # fretwear DISCRET obstacle: clearance figure, angle THETA [deg], clearance JEU [m] = R [m]
    # mobile_radius = 9.50000000000E-03
    #
    THETA JEU R
     0.0000000000E+00  5.0000000000E-04  5.0000000000E-04
     ...                (721 rows, THETA = 0, 0.5, ..., 360; the last row repeats the first)

``JEU`` is the clearance seen from the mobile (0.5 mm for a new Code_Aster DISCRET obstacle,
theory §8); ``R`` repeats it under the name Code_Aster's obstacle tables give the polar radius of
the clearance figure, so a Code_Aster reader taking (THETA, R) gets the clearance too. The
reader accepts THETA with JEU (preferred) or with R (Code_Aster: the clearance), or with RADIUS
(the obstacle boundary's radius R_m + gap, which needs a mobile radius from the header line or
the argument); native names ``angle``/``gap``/``radius`` too; other columns (e.g. Code_Aster's
LIEU, TYPE) are ignored; any increasing angle grid covering one turn; no '-' or NaN cells.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fretwear.errors import FormatError, InputError
from fretwear.io.atomic import atomic_write
from fretwear.io.guard import readable_file, reading
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
        file read by :func:`read_discret`, a worn figure): the points are the clearance figure
        C (the polygon through them) and the obstacle's inner boundary is C dilated by the
        mobile's disk, so the new mobile's clearance is the table again
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


_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"


def write_discret(path, obstacle, *, step: float = DISCRET_STEP, gaps=None,
                  title: str = "fretwear DISCRET obstacle") -> Path:
    """Write an obstacle (or explicit gaps) as a DISCRET table (layout in the module docstring).

    Parameters
    ----------
    path : str or path-like
        Output file (written atomically).
    obstacle : obstacle model or None
        Obstacle whose clearance figure is written (``clearance(angle)`` of the new mobile; its
        ``gap`` directly for a bore or a clearance-figure table); its ``mobile_radius`` is
        written in the header.
    step : float
        Angular step [deg] (0.5 for Code_Aster's 721 points).
    gaps : array_like, optional
        Gaps [m] on ``discret_angles(step)`` to write instead of sampling ``obstacle``.
    title : str
        First comment line.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "o.txt"
    >>> _ = write_discret(p, CircleObstacle.from_gap(9.5e-3, 5e-4))
    >>> d = read_discret(p)
    >>> d.angles.size, round(float(d.gap(12.25)), 12), d.mobile_radius
    (720, 0.0005, 0.0095)
    """
    a = discret_angles(step)
    rm = getattr(obstacle, "mobile_radius", None)
    if gaps is not None:
        g = np.asarray(gaps, dtype=float)
    elif isinstance(obstacle, CircleObstacle) or getattr(obstacle, "clearance_figure", False):
        g = obstacle.gap(a)  # already the clearance figure
    else:  # the figure of the new mobile, not the radial gap (they differ off a bore)
        g = obstacle.clearance(a[:-1])
        g = np.append(g, g[0])
    if g.shape != a.shape:
        raise InputError(f"write_discret: {g.size} gaps for {a.size} angles (step {step} deg)")
    lines = ["#", f"# {title}: clearance figure, angle THETA [deg], clearance JEU [m] = R [m]"]
    if rm is not None:
        lines.append(f"# mobile_radius = {rm:.11E}")
    lines += ["#", "THETA JEU R"]
    for ai, gi in zip(a, g, strict=True):
        lines.append(f"{ai: .10E} {gi: .10E} {gi: .10E}")
    target = Path(path)
    with atomic_write(target, "w", encoding="utf-8") as fh:
        fh.write("\n".join(lines) + "\n")
    return target


_ALIASES = {"THETA": "THETA", "ANGLE": "THETA", "ANGLE_DEG": "THETA",
            "JEU": "JEU", "GAP": "JEU", "R": "R", "RAYON": "RADIUS", "RADIUS": "RADIUS"}


def _column_name(cell: str) -> str:
    """The DISCRET name of a column (IMPR_FONCTION's ``_<curve number>`` suffix dropped)."""
    name = cell.strip('"').upper()
    if name not in _ALIASES:
        name = re.sub(r"_\d+$", "", name)
    return _ALIASES.get(name, name)


def _theta_degrees(theta: np.ndarray, unit: str | None, label: str) -> np.ndarray:
    """THETA in degrees: given in ``unit`` ('deg'/'rad'), or recognised from its range.

    Code_Aster's DEFI_OBSTACLE takes VALE angles in degrees but stores the DISCRET function
    R = f(THETA) with THETA in radians (``op0073``: ``THETA * r8dgrd()``): a printed table runs
    0 … 6.28319. Without ``unit``, angles within ±2π (+ print precision) spanning more than half
    a turn in radians are radians; a span beyond 2π is degrees; a shorter span is ambiguous.
    """
    tol = 1e-4  # %12.5E prints 2π as 6.28319: 1.5e-6 above it
    if unit is None:
        span = float(theta.max() - theta.min())
        if np.abs(theta).max() <= 2 * np.pi + tol and span > np.pi:
            unit = "rad"
        elif span > 2 * np.pi + tol:
            unit = "deg"
        else:
            raise FormatError(
                f"{label}: THETA runs {theta.min():g} … {theta.max():g}: less than half a turn "
                "in radians and than 2π in degrees, the unit is ambiguous; give "
                "angle_unit='deg' or 'rad' (Code_Aster's DEFI_OBSTACLE stores THETA in radians)")
    if str(unit).lower() in ("deg", "degree", "degrees"):
        return theta
    if str(unit).lower() not in ("rad", "radian", "radians"):
        raise InputError(f"angle_unit={unit!r}: give 'deg' or 'rad'")
    degrees = np.degrees(theta)
    turn = degrees[0] + 360.0
    if abs(degrees[-1] - turn) <= np.degrees(tol):  # the printed closing point: exactly a turn
        degrees[-1] = turn
    return degrees


def read_discret(path, *, mobile_radius: float | None = None,
                 angle_unit: str | None = None) -> DiscreteObstacle:
    """Read a DISCRET obstacle table (layout in the module docstring).

    Parameters
    ----------
    path : str or path-like
        Text file: '#' comment lines (``# mobile_radius = ...`` is read), a line of column names
        (THETA with JEU, or R = Code_Aster's name of the clearance, or RADIUS = R_m + clearance;
        native names angle/gap/radius accepted; other columns ignored), then rows.
        Code_Aster's ``#DEBUT_TABLE``/``#FIN_TABLE`` and type lines (``R``, ``K8``...) are
        skipped.
    mobile_radius : float, optional
        Mobile outer radius [m]; overrides the header; needed when only RADIUS is given.
    angle_unit : {"deg", "rad"}, optional
        Unit of THETA. Default: recognised from the range: Code_Aster's DEFI_OBSTACLE stores
        THETA in radians (a printed table runs 0 … 6.28319), fretwear writes degrees (0 … 360).

    Returns
    -------
    DiscreteObstacle
        Angles in degrees.

    Raises
    ------
    FormatError
        Naming the file and the line when a column is missing or a cell is not a number; THETA
        whose unit cannot be told from its range (give ``angle_unit``).
    """
    p = readable_file(path, "DISCRET obstacle file")
    header_rm = None
    names = None
    rows: list[list[float]] = []
    with reading(p, "DISCRET obstacle", "DISCRET obstacle file"):
        text = p.read_text(encoding="utf-8-sig", errors="replace")
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            m = re.match(r"#\s*mobile_radius\s*=\s*(" + _NUM + ")", line)
            if m:
                header_rm = float(m.group(1).replace("D", "E").replace("d", "e"))
            continue
        cells = line.replace(",", " ").replace(";", " ").split()
        if names is None:
            names = [_column_name(c) for c in cells]
            if "THETA" not in names or not ({"JEU", "R", "RADIUS"} & set(names)):
                raise FormatError(
                    f"{p}: line {lineno}: the column names {cells} need THETA (angle [deg]) and "
                    "JEU or R (clearance [m]), or RADIUS (obstacle radius R_m + clearance [m])")
            value = next(c for c in ("JEU", "R", "RADIUS") if c in names)
            wanted = [names.index("THETA"), names.index(value)]
            continue
        if all(re.fullmatch(r"[A-Z]\d*", c.upper()) for c in cells):  # ASTER type line: R K8
            continue
        if len(cells) != len(names):
            raise FormatError(
                f"{p}: line {lineno} has {len(cells)} cells, expected {len(names)} ({names})")
        try:
            rows.append([float(cells[i].replace("D", "E").replace("d", "e")) for i in wanted])
        except ValueError:
            raise FormatError(f"{p}: line {lineno}: a cell of {[names[i] for i in wanted]} is not "
                              f"a number: {line!r}") from None
    if names is None or not rows:
        raise FormatError(f"{p}: no DISCRET table found (need a THETA JEU header and rows)")
    data = np.array(rows)
    rm = mobile_radius if mobile_radius is not None else header_rm
    theta, gaps = _theta_degrees(data[:, 0], angle_unit, str(p)), data[:, 1]
    if value == "RADIUS":
        if rm is None:
            raise FormatError(
                f"{p}: the table gives obstacle radii (RADIUS) but no mobile radius: add a "
                "'# mobile_radius = ...' header line or pass mobile_radius=")
        gaps = gaps - float(rm)
    elif value == "R" and rm is not None and gaps.min() >= float(rm):
        raise FormatError(
            f"{p}: column R holds {gaps.min():g}..{gaps.max():g} m, not less than the mobile "
            f"radius {float(rm):g} m: in a DISCRET table R is the clearance (0.5e-3 m for a new "
            "Code_Aster obstacle); if these are radii of the obstacle, name the column RADIUS")
    try:
        return DiscreteObstacle(theta, gaps, rm, clearance_figure=value != "RADIUS")
    except InputError as exc:
        raise InputError(f"{p}: {exc}") from None


def load_obstacle_profile(path, *, mobile_radius: float | None = None) -> DiscreteObstacle:
    """Load an obstacle file written by the obstacle update (the worn clearance figure).

    The returned profile has vectorised ``gap(angle)`` and ``radius(angle)`` [m] (angle [deg]),
    for the next dynamic computation.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "o.txt"
    >>> _ = write_discret(p, CircleObstacle(0.01, 0.0105))
    >>> prof = load_obstacle_profile(p)
    >>> prof.clearance_figure, [round(float(r), 12) for r in prof.radius([0.0, 123.5])]
    (True, [0.0105, 0.0105])
    """
    return read_discret(path, mobile_radius=mobile_radius)
