"""Units checked against the contact's own geometry: a length typed in millimetres is caught.

The plausibility checks of :mod:`fretwear.io.plausibility` compare a history with absolute limits
(50 mm, 10 m/s): a quiet contact exported in mm and mm/s (a 41 µm orbit read as 41 mm, 5 mm/s
read as 5 m/s) passes them and gives a wear power 1000 times too large. The checks here compare
the numbers with what the contact itself allows:

* the wall of a tube is thinner than the tube's outer radius (:func:`check_wall_thickness`,
  an :class:`~fretwear.errors.InputError`: no table is right with such a wall);
* the displacement orbit (half the peak-to-peak of ``dy``, ``dz``) stays within the tube's
  radius, and within :data:`ORBIT_GAP_FACTOR` times the radial gap of a tube or rod in a bore;
* the largest sliding speed is not far above what the orbit at the motion's frequency gives,
  ``2π f A`` (:data:`SPEED_ORBIT_FACTOR` times it at most; ``f`` from the zero crossings of
  ``dy`` about its median: noise there only raises ``f`` and the bound).

A failed history check is a :class:`~fretwear.errors.UnitsWarning` naming the quantity, the
dimension it was compared with, the likely unit and the ``units = {...}`` option that fixes it.
Nothing is changed.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from fretwear.errors import InputError, UnitsWarning
from fretwear.io.plausibility import _kernel_for

#: The orbit of a tube or rod in a bore may exceed the radial gap by the contact's penetration
#: and the obstacle's own motion; ten gaps leave a decade of margin (a file in mm is 1000×).
ORBIT_GAP_FACTOR = 10.0
#: The largest sliding speed may exceed 2π f A (the orbit's speed at its frequency) through
#: impacts' higher harmonics and axial sliding; a hundred times leaves two decades of margin and
#: still catches speeds in mm/s beside lengths in m (1000×).
SPEED_ORBIT_FACTOR = 100.0

_FIX = ("case file: [history] units = {{ {entry} }}; command line: --units {cli}; Python: "
        "read_history(..., units={{'{key}': '{unit}'}})")


def _fix(key: str, unit: str) -> str:
    return _FIX.format(entry=f"{key} = '{unit}'", cli=f"{key}={unit}", key=key, unit=unit)


#: The largest ratio of a tube's outer radius to its wall accepted: steam-generator tubes are
#: 8-25 (9.525 mm on 1.09 mm, 11.1 mm on 0.5 mm), fuel and control rods about 10, so a radius
#: typed in mm beside a wall in metres gives 8 000 or more; a thousand catches every such slip
#: and leaves studies room for thin walls (a 10 µm wall on a 9.5 mm tube to reach perforation
#: in a test).
RADIUS_WALL_RATIO = 1000.0


def check_wall_thickness(wall: float | None, radius: float | None, *,
                         key: str = "wall_thickness") -> None:
    """Refuse a wall [m] at least as thick as the tube's outer radius [m], or a radius more than
    :data:`RADIUS_WALL_RATIO` times the wall (a radius typed in mm: the depth of a given volume
    falls with the radius, so the life came out about 30 times too long).

    Parameters
    ----------
    wall : float or None
        Wall thickness of the tube [m] (None: nothing to check).
    radius : float or None
        Outer radius of the tube, ``mobile_radius`` [m] (None: nothing to check).
    key : str
        The name the user gave the wall under, for the message.

    Raises
    ------
    InputError
        ``wall >= radius``, naming the key, the likely unit and the value in metres.

    Examples
    --------
    >>> check_wall_thickness(0.00109, 0.009525)
    >>> try:
    ...     check_wall_thickness(1.09, 0.009525, key="wall_thickness_m")
    ... except InputError as exc:
    ...     print(str(exc)[:73])
    wall_thickness_m = 1.09 m is at least the tube's outer radius 0.009525 m
    >>> try:
    ...     check_wall_thickness(0.00109, 9.525)
    ... except InputError as exc:
    ...     print(str(exc)[:71])
    mobile_radius = 9.525 m is 8739 times the wall 0.00109 m (1.09 mm): a t
    """
    if wall is None or radius is None or not wall > 0:
        return
    if radius > RADIUS_WALL_RATIO * wall:
        raise InputError(
            f"mobile_radius = {radius:g} m is {radius / wall:.0f} times the wall {wall:g} m "
            f"({wall * 1e3:.4g} mm): a tube's radius is 8 to 25 walls. A radius in mm? Give "
            f"it in metres: mobile_radius = {radius * 1e-3:g} (case file: mobile_radius_m)")
    if not wall >= radius > 0:
        return
    unit, scale = next(((u, s) for u, s in (("mm", 1e-3), ("µm", 1e-6)) if wall * s < radius),
                        ("mm", 1e-3))
    raise InputError(
        f"{key} = {wall:g} m is at least the tube's outer radius {radius:g} m (mobile_radius, "
        f"{radius * 1e3:.4g} mm): a wall is thinner than its tube. A value in {unit}? Give it in "
        f"metres: {key} = {wall * scale:g}")


#: The largest plausible absolute sizes [m] of a fretting contact (steam-generator tubes of
#: 5-15 mm radius and about 1 mm wall, bars and plates 5-50 mm wide, control rods of about 5 mm
#: radius): ten to a hundred times these, so that no real contact is refused and a length typed
#: in mm (1000× too large in metres) always is.
SIZE_BOUNDS = {"mobile_radius": 0.5, "obstacle_width": 1.0}
#: The largest plausible wall thickness [m] (a tube wall of about 1 mm: a hundred times it).
WALL_BOUND = 0.1


def check_absolute_sizes(dimensions: dict, wall: float | None = None) -> None:
    """Catch a case whose every length was typed in mm: a wall [m] of a metre's order is
    refused, a tube radius or obstacle width [m] of a metre's order is warned of.

    A case with every length in mm passes :func:`check_wall_thickness` (the wall stays thinner
    than the tube); the absolute bounds :data:`SIZE_BOUNDS` and :data:`WALL_BOUND` [m] catch it.
    A wall is a steam-generator tube's, so a wall above :data:`WALL_BOUND` is an error. A radius
    or width alone is only warned of: Code_Aster's own POST_USURE test cases use a unit radius
    and a 10 m obstacle width (RAYON_MOBILE=1., LARGEUR_OBST=10.), which must compute as there.

    Parameters
    ----------
    dimensions : dict
        The contact's dimensions [m] (``mobile_radius``, ``obstacle_width`` checked when given).
    wall : float or None
        Wall thickness of the tube [m].

    Raises
    ------
    InputError
        A wall above :data:`WALL_BOUND`, with its value in metres if it was in mm.

    Warns
    -----
    UnitsWarning
        A radius or width above its bound in :data:`SIZE_BOUNDS`.

    Examples
    --------
    >>> check_absolute_sizes({"mobile_radius": 0.009525, "obstacle_width": 0.0127}, 0.00109)
    >>> try:
    ...     check_absolute_sizes({"mobile_radius": 9.525}, 1.09)
    ... except InputError as exc:
    ...     print(str(exc)[:57])
    wall_thickness = 1.09 m is implausible for a fretting con
    """
    if wall is not None and wall > WALL_BOUND:
        raise InputError(_implausible("wall_thickness", wall, WALL_BOUND))
    for key, bound in SIZE_BOUNDS.items():
        value = dimensions.get(key)
        if value is not None and value > bound:
            warnings.warn(_implausible(key, value, bound), UnitsWarning, stacklevel=3)


def _implausible(key: str, value: float, bound: float) -> str:
    return (f"{key} = {value:g} m is implausible for a fretting contact (above {bound:g} m): "
            f"a value in mm? Give metres: {key} = {value * 1e-3:g} (every length of a case "
            f"file or manifest is in metres: *_m keys)")


def _orbit(history) -> float:
    """Half the largest peak-to-peak of ``dy`` and ``dz`` [m] (0 without them)."""
    if history.dy is None:
        return 0.0
    dy, dz = history.dy, history.dz
    return 0.5 * max(float(dy.max() - dy.min()), float(dz.max() - dz.min()))


def median(values: np.ndarray) -> float:
    """The median of a 1-D array of finite values, as :func:`numpy.median` gives it (the middle
    value of a partition, or the mean of the two middle ones), without its generic machinery
    (axes, NaN checks: a quarter of its time on the 10³ samples of a bundle's history).

    The middle values are taken from numpy's sort (vectorised, without branches: 5 µs for a
    bundle's 10³ fresh samples, against 12 µs for the partition, whose branches the processor
    mispredicts on data it has not seen; issue 28): the same values, an order statistic being
    one number, but for the sign of a zero (0.0 and -0.0 compare equal): a zero in the middle
    is therefore taken from the partition, as before (:func:`_partition_median`).

    Examples
    --------
    >>> a = np.array([3.0, 1.0, 4.0, 1.5, 9.0, 2.6])
    >>> median(a) == float(np.median(a)), median(a[:5]) == float(np.median(a[:5]))
    (True, True)
    """
    k = values.size // 2
    ordered = np.sort(values)
    if values.size % 2:
        if ordered[k] != 0.0:
            return float(ordered[k])
    elif ordered[k - 1] != 0.0 and ordered[k] != 0.0:
        return float((ordered[k - 1] + ordered[k]) / 2.0)
    return _partition_median(values)


def _partition_median(values: np.ndarray) -> float:
    """:func:`median` from a partition (numpy's introselect), the reference."""
    k = values.size // 2
    if values.size % 2:
        return float(np.partition(values, k)[k])
    part = np.partition(values, (k - 1, k))
    return float((part[k - 1] + part[k]) / 2.0)


def _frequency(history) -> float:
    """The motion's frequency [Hz] from the crossings of ``dy`` about its median."""
    dy = history.dy
    duration = float(history.time[-1] - history.time[0])
    if dy is None or dy.size < 3 or not duration > 0:
        return math.nan
    sign = np.signbit(dy - median(dy))
    return _crossing_frequency(int(np.count_nonzero(sign[1:] != sign[:-1])), duration)


def _crossing_frequency(crossings: int, duration: float) -> float:
    """The frequency [Hz] of a motion crossing its median ``crossings`` times in ``duration``
    [s] (two crossings a period; NaN without a crossing or a duration)."""
    return crossings / (2.0 * duration) if crossings and duration > 0 else math.nan


def _speed(history) -> float:
    """The largest sliding speed √(vt1² + vt2²) [m/s] (``inf`` when the squares overflow)."""
    with np.errstate(over="ignore"):
        return float(np.sqrt((history.vt1 ** 2 + history.vt2 ** 2).max()))


def _motion(history) -> tuple[float, float, float]:
    """The history's orbit (:func:`_orbit`) [m], frequency (:func:`_frequency`) [Hz] and largest
    sliding speed [m/s] (NaN where the check needs none: no orbit or no frequency).

    One compiled pass (:func:`fretwear.io._compiled.motion`) when the plausibility checks run
    compiled (:func:`fretwear.io.plausibility._kernel_for`: numba installed, and a long history
    or the module already imported, as it is in a stream), with contiguous channels and dy; the
    numpy expressions otherwise, the reference: the same numbers (about ten array passes of a
    1 000-sample block of a bundle, issue 28)."""
    dy, dz, t = history.dy, history.dz, history.time
    kernel = _kernel_for(t.size)
    duration = float(t[-1] - t[0])
    if (kernel is None or dy is None or dy.size < 3
            or not all(a.flags.c_contiguous for a in (dy, dz, history.vt1, history.vt2))):
        orbit, frequency = _orbit(history), _frequency(history)
        speed = _speed(history) if orbit > 0 and math.isfinite(frequency) else math.nan
        return orbit, frequency, speed
    y_range, z_range, crossings, speed2 = kernel.motion(dy, dz, history.vt1, history.vt2,
                                                        median(dy))
    orbit = 0.5 * max(float(y_range), float(z_range))
    return orbit, _crossing_frequency(int(crossings), duration), math.sqrt(speed2)


def check_against_geometry(history, *, mobile_radius: float | None = None,
                           obstacle_radius: float | None = None, name: str = "") -> list[str]:
    """Warn (:class:`UnitsWarning`) where a history's lengths or speeds do not fit its contact.

    Parameters
    ----------
    history : ContactHistory
        The history, SI units (``metadata['units']`` when read from a file).
    mobile_radius : float, optional
        Outer radius of the tube or rod [m].
    obstacle_radius : float, optional
        Radius of the bore [m] (a tube or rod in a bore: the radial gap is
        ``obstacle_radius - mobile_radius``).
    name : str
        The contact, for the messages.

    Returns
    -------
    list of str
        The messages warned.

    Examples
    --------
    >>> import warnings
    >>> from fretwear.history import ContactHistory
    >>> t = np.linspace(0.0, 1.0, 2001)
    >>> mm = ContactHistory(time=t, normal_force=np.full(t.size, 5.0),
    ...                     vt1=5.0 * np.cos(2 * np.pi * 20 * t), vt2=0 * t,
    ...                     dy=0.041 * np.sin(2 * np.pi * 20 * t), dz=0 * t)
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     found = check_against_geometry(mm, mobile_radius=9.525e-3, name="R1C1")
    >>> print(found[0].split(";")[0])
    contact 'R1C1': the displacement orbit 0.041 m (half the peak-to-peak of dy, dz
    """
    found: list[str] = []
    label = name or history.name or history.metadata.get("source", "")
    units = history.metadata.get("units") or {}
    orbit, frequency, speed = _motion(history)
    limit, what = math.inf, ""
    if mobile_radius:
        limit, what = mobile_radius, f"the tube's outer radius {mobile_radius:g} m"
    if obstacle_radius and mobile_radius and obstacle_radius > mobile_radius:
        gap = obstacle_radius - mobile_radius
        if ORBIT_GAP_FACTOR * gap < limit:
            limit = ORBIT_GAP_FACTOR * gap
            what = (f"{ORBIT_GAP_FACTOR:g} times the radial gap {gap:g} m (obstacle_radius - "
                    "mobile_radius)")
    if orbit > limit:
        found.append(f"contact {label!r}: the displacement orbit {orbit:.4g} m (half the "
                     f"peak-to-peak of dy, dz; read in {units.get('dy', 'SI')!r}) is larger than "
                     f"{what}: a file in 'mm' gives this: if so, give the units: "
                     f"{_fix('length', 'mm')}")
    if orbit > 0 and math.isfinite(frequency):
        bound = 2.0 * math.pi * frequency * orbit
        if math.isfinite(speed) and speed > SPEED_ORBIT_FACTOR * bound:
            found.append(
                f"contact {label!r}: the largest sliding speed {speed:.4g} m/s (read in "
                f"{units.get('vt1', 'SI')!r}) is {speed / bound:.3g} times what the orbit "
                f"{orbit:.4g} m at its frequency {frequency:.4g} Hz gives (2π f A = "
                f"{bound:.4g} m/s; plausible up to {SPEED_ORBIT_FACTOR:g} times): speeds in "
                f"'mm/s' beside lengths in 'm' give this: if so, give the units: "
                f"{_fix('velocity', 'mm/s')}")
    for message in found:
        warnings.warn(message, UnitsWarning, stacklevel=2)
    return found
