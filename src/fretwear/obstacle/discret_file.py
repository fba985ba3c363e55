"""Code_Aster's DEFI_OBSTACLE 'DISCRET' table as a text file: read and write (theory §8).

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

import re
from pathlib import Path

import numpy as np

from fretwear.errors import FormatError, InputError
from fretwear.io.atomic import atomic_write
from fretwear.io.guard import readable_file, reading
from fretwear.obstacle.profiles import (
    DISCRET_STEP,
    CircleObstacle,
    DiscreteObstacle,
    discret_angles,
)

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
