"""Worn depth of an angular sector (theory §3; Code_Aster R7.20.01 §5).

The wear of a sector j (volume V_j) is assumed to fill the sector's arc Δθ uniformly over the
obstacle width l: on the mobile (convex) it removes an annular slice of the outer surface, in the
bore (concave) it adds an annular slice beyond the bore's surface. Δθ is in radians here
(Code_Aster uses degrees, a factor 180/π ≈ 57 too small a depth, which we do not copy).
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from fretwear.errors import InputError, KeywordError, RangeWarning, UnusedKeywordWarning
from fretwear.geometry._shapes import _out

__all__ = [
    "SectorGeometry",
    "SectorSlices",
    "sector_geometry",
    "sector_slices",
    "mobile_depth_from_area_density",
    "obstacle_depth_from_area_density",
    "sector_depth_mobile",
    "sector_depth_obstacle",
    "sector_volume_mobile",
    "sector_volume_obstacle",
]


def _checked(value, name: str, unit: str) -> np.ndarray:
    """``value`` as a float array, each element finite and >= 0 (NaN passes) [``unit``]."""
    array = np.array(value, dtype=float)
    bad = np.isinf(array) | (array < 0.0)
    if bad.any():
        raise InputError(
            f"{name} must be finite and >= 0 [{unit}]: got "
            f"{float(array[tuple(np.argwhere(bad)[0])]):g}")
    return array


def _depth_within_sector(area, radius):
    """The mobile's sector depth [m] of the volume per unit width and angle ``area`` [m²]
    (:func:`_mobile_depth`); NaN with a RangeWarning (said to the caller's caller) beyond the
    whole sector."""
    depth, root2 = _mobile_depth(area, radius)
    beyond = root2 < 0.0  # 2a_θ > R²
    if beyond.any():
        warnings.warn(
            f"sector depth of the mobile: {int(np.count_nonzero(beyond))} volume(s) exceed the "
            "whole sector of the mobile's section (l·Δθ·R_m²/2): depth NaN", RangeWarning,
            stacklevel=3)
    return depth


def _volume_within_radius(depth, radius, half_width_arc):
    """(the mobile's sector volume [m³] l·Δθ/2·d·(2R_m − d) of ``depth`` [m],
    ``half_width_arc`` = l·Δθ/2 [m·rad]; whether a depth was beyond the radius: NaN there,
    with a RangeWarning said to the caller's caller)."""
    beyond = depth > radius
    said = bool(np.any(beyond))
    if said:
        warnings.warn(
            f"sector volume of the mobile: {int(np.count_nonzero(beyond))} depth(s) exceed the "
            "mobile radius R_m: volume NaN", RangeWarning, stacklevel=3)
    return np.where(beyond, np.nan, half_width_arc * depth * (2.0 * radius - depth)), said


def _inputs(value, value_name, unit, radius, radius_name, width, arc_deg):
    array = _checked(value, value_name, unit)
    r = np.array(radius, dtype=float)
    l = np.array(width, dtype=float)
    arc = np.array(arc_deg, dtype=float)
    for name, item, what in ((radius_name, r, "m"), ("width", l, "m")):
        if not (_positive(item.item()) if item.ndim == 0
                else (np.isfinite(item) & (item > 0.0)).all()):
            raise InputError(f"{name} must be finite and > 0 [{what}], got {item.tolist()}")
    if not ((arc > 0.0) & (arc <= 360.0)).all():  # NaN and ±inf fail one of the two
        raise InputError(
            f"arc_deg (the sector's angular extent) must lie in (0, 360] deg, got {arc.tolist()}")
    try:
        # radius and width numbers, arcs of the volumes' last axes (a table's sectors):
        # they broadcast without asking numpy
        if r.ndim or l.ndim or array.shape[array.ndim - arc.ndim:] != arc.shape:
            np.broadcast_shapes(array.shape, r.shape, l.shape, arc.shape)
    except ValueError:
        raise InputError(
            f"{value_name} {array.shape}, {radius_name} {r.shape}, width {l.shape} and arc_deg "
            f"{arc.shape} do not broadcast together") from None
    return array, r, l, np.radians(arc)


def _positive(number: float) -> bool:
    """``number`` is finite and > 0."""
    return math.isfinite(number) and number > 0.0


def mobile_depth_from_area_density(density, radius):
    """Depth of an annular slice removed from a convex arc, from its area per radian [m].

    Parameters
    ----------
    density : float or array_like
        Worn section area per radian of arc a_θ [m²/rad] (a sector: V_j/(l·Δθ)), ≥ 0.
    radius : float or array_like
        Radius R of the convex surface (the mobile) [m].

    Returns
    -------
    numpy.ndarray
        d = R − √(R² − 2a_θ) [m], written as 2a_θ/(R + √(R² − 2a_θ)) (no cancellation for thin
        wear); NaN where 2a_θ > R² (the slice would pass the centre).

    Examples
    --------
    >>> round(float(mobile_depth_from_area_density((0.01**2 - 0.009**2) / 2, 0.01)), 12)
    0.001
    """
    return _mobile_depth(np.asarray(density, dtype=float), radius)[0]


def _mobile_depth(density: np.ndarray, radius):
    """(:func:`mobile_depth_from_area_density`, R² − 2a_θ) [m, m²]: the depth is NaN where the
    second is < 0 (exactly where 2a_θ > R²: a difference of two floats has the sign of their
    exact difference) or NaN."""
    twice = 2.0 * density
    root2 = radius * radius - twice
    if type(root2) is np.ndarray and root2.size and root2.min() >= 0.0:  # no NaN, none < 0:
        return twice / (radius + np.sqrt(root2)), root2  # where and maximum change nothing
    with np.errstate(invalid="ignore"):
        depth = np.where(root2 >= 0.0, twice / (radius + np.sqrt(np.maximum(root2, 0.0))),
                         np.nan)
    return depth, root2


def obstacle_depth_from_area_density(density, radius):
    """Depth of an annular slice added beyond a concave arc (a bore), from its area per radian [m].

    Parameters
    ----------
    density : float or array_like
        Worn section area per radian of arc a_θ [m²/rad], ≥ 0.
    radius : float or array_like
        Radius r of the concave surface (the bore) [m].

    Returns
    -------
    numpy.ndarray
        d = √(r² + 2a_θ) − r [m], written as 2a_θ/(√(r² + 2a_θ) + r).

    Examples
    --------
    >>> round(float(obstacle_depth_from_area_density((0.011**2 - 0.01**2) / 2, 0.01)), 12)
    0.001
    """
    density = np.asarray(density, dtype=float)
    return 2.0 * density / (np.sqrt(radius * radius + 2.0 * density) + radius)


def sector_depth_mobile(volume, mobile_radius, width, arc_deg):
    """Depth of a sector's wear on the mobile (convex surface) [m].

    Parameters
    ----------
    volume : float or array_like
        Worn volume of the sector V_j [m³], ≥ 0 (NaN passes through).
    mobile_radius : float or array_like
        Mobile outer radius R_m [m].
    width : float or array_like
        Worn width l [m] (obstacle width).
    arc_deg : float or array_like
        Angular extent Δθ of the sector [deg], in (0, 360].

    Returns
    -------
    numpy.ndarray or float
        d [m]; NaN (with a RangeWarning) where V_j exceeds the whole sector of the disk,
        l·Δθ·R_m²/2.

    Notes
    -----
    The slice between radii R_m − d and R_m over the arc Δθ [rad] and width l has the volume
    V = l·Δθ·(R_m² − (R_m − d)²)/2, so

    .. math:: d = R_m - \\sqrt{R_m^2 - \\frac{2V}{l\\,\\Delta\\theta}}
              = \\frac{a}{R_m + \\sqrt{R_m^2 - a}},\\quad a = \\frac{2V}{l\\,\\Delta\\theta}

    (second form used: no cancellation for thin wear).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §5.

    Examples
    --------
    >>> import numpy as np
    >>> v = 0.01 * (np.pi / 2) * (0.01**2 - 0.009**2) / 2  # 1 mm deep over 90°, 10 mm wide
    >>> round(float(sector_depth_mobile(v, 0.01, 0.01, 90.0)), 12)
    0.001
    """
    v, r, l, arc = _inputs(volume, "volume", "m³", mobile_radius, "mobile_radius", width,
                           arc_deg)
    return _out(_depth_within_sector(v / (l * arc), r))


def sector_depth_obstacle(volume, obstacle_radius, width, arc_deg):
    """Depth of a sector's wear in the obstacle's bore (concave surface) [m].

    Parameters
    ----------
    volume : float or array_like
        Worn volume of the sector V_j [m³], ≥ 0 (NaN passes through).
    obstacle_radius : float or array_like
        Bore radius R_o [m].
    width : float or array_like
        Worn width l [m].
    arc_deg : float or array_like
        Angular extent Δθ of the sector [deg], in (0, 360].

    Returns
    -------
    numpy.ndarray or float
        d [m].

    Notes
    -----
    The slice between radii R_o and R_o + d has the volume V = l·Δθ·((R_o + d)² − R_o²)/2, so

    .. math:: d = \\sqrt{R_o^2 + \\frac{2V}{l\\,\\Delta\\theta}} - R_o
              = \\frac{a}{\\sqrt{R_o^2 + a} + R_o}

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §5.

    Examples
    --------
    >>> import numpy as np
    >>> v = 0.01 * (np.pi / 2) * (0.011**2 - 0.01**2) / 2  # 1 mm deep over 90°, 10 mm wide
    >>> round(float(sector_depth_obstacle(v, 0.01, 0.01, 90.0)), 12)
    0.001
    """
    v, r, l, arc = _inputs(volume, "volume", "m³", obstacle_radius, "obstacle_radius", width,
                           arc_deg)
    return _out(obstacle_depth_from_area_density(v / (l * arc), r))


def sector_volume_mobile(depth, mobile_radius, width, arc_deg):
    """Volume of a sector's wear on the mobile from its depth [m³] (inverse of the depth).

    Parameters
    ----------
    depth : float or array_like
        Depth d [m], 0 ≤ d ≤ R_m (NaN beyond, with a RangeWarning).
    mobile_radius : float or array_like
        Mobile outer radius R_m [m].
    width : float or array_like
        Worn width l [m].
    arc_deg : float or array_like
        Angular extent Δθ [deg].

    Returns
    -------
    numpy.ndarray or float
        V = l·Δθ·d·(2R_m − d)/2 [m³].

    Notes
    -----
    .. math:: V = \\frac{l\\,\\Delta\\theta}{2}\\left(R_m^2 - (R_m - d)^2\\right)
              = \\frac{l\\,\\Delta\\theta}{2}\\,d\\,(2R_m - d)

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3.

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.isclose(sector_volume_mobile(0.01, 0.01, 0.02, 360.0), 0.02 * np.pi * 1e-4))
    True
    """
    d, r, l, arc = _inputs(depth, "depth", "m", mobile_radius, "mobile_radius", width, arc_deg)
    return _out(_volume_within_radius(d, r, 0.5 * l * arc)[0])


def sector_volume_obstacle(depth, obstacle_radius, width, arc_deg):
    """Volume of a sector's wear in the bore from its depth [m³] (inverse of the depth).

    Parameters
    ----------
    depth : float or array_like
        Depth d [m], ≥ 0.
    obstacle_radius : float or array_like
        Bore radius R_o [m].
    width : float or array_like
        Worn width l [m].
    arc_deg : float or array_like
        Angular extent Δθ [deg].

    Returns
    -------
    numpy.ndarray or float
        V = l·Δθ·d·(2R_o + d)/2 [m³].

    Notes
    -----
    .. math:: V = \\frac{l\\,\\Delta\\theta}{2}\\left((R_o + d)^2 - R_o^2\\right)

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3.

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.isclose(sector_volume_obstacle(0.01, 0.01, 0.02, 360.0), 0.02 * np.pi * 3e-4))
    True
    """
    d, r, l, arc = _inputs(depth, "depth", "m", obstacle_radius, "obstacle_radius", width,
                           arc_deg)
    return _out(0.5 * l * arc * d * (2.0 * r + d))


class SectorSlices:
    """The sectors of one contact, their dimensions checked once: the sector depths and volumes
    of :func:`sector_depth_mobile`, :func:`sector_depth_obstacle` and
    :func:`sector_volume_mobile` for many calls of the same radii, width and arcs (a wear
    table's every instant; a bundle's contacts of the same dimensions share one, kept by
    :func:`sector_slices`).

    The same operations in the same order as those functions (the results equal bit for bit,
    their warnings the same); only the dimensions' checks and the arcs' conversion to radians
    are made once, here. The volumes and depths given to the methods are checked as there.

    Parameters
    ----------
    mobile_radius : float
        Mobile outer radius R_m [m], > 0.
    width : float
        Worn width l [m], > 0.
    arcs_deg : tuple of float
        Angular extent Δθ of each sector [deg], in (0, 360]: the values' last axis.
    obstacle_radius : float, optional
        Bore radius R_o [m], > 0 (the obstacle's depths need it).

    Examples
    --------
    >>> s = SectorSlices(0.01, 0.01, (90.0, 270.0))
    >>> v = 0.01 * (np.pi / 2) * (0.01**2 - 0.009**2) / 2  # 1 mm deep over 90°
    >>> bool(s.depth_mobile(np.array([v, v]))[0] == sector_depth_mobile(v, 0.01, 0.01, 90.0))
    True
    """

    def __init__(self, mobile_radius: float, width: float, arcs_deg: tuple[float, ...],
                 obstacle_radius: float | None = None) -> None:
        arcs = np.asarray(arcs_deg, dtype=float)
        _, r, l, arc = _inputs(np.zeros(arcs.shape), "volume", "m³", mobile_radius,
                               "mobile_radius", width, arcs)
        if obstacle_radius is not None:
            _inputs(0.0, "volume", "m³", obstacle_radius, "obstacle_radius", width, arcs)
        self.mobile_radius = float(r)
        self.obstacle_radius = None if obstacle_radius is None else float(obstacle_radius)
        self._width_arc = l * arc  # l·Δθ [m·rad], as the functions make it
        self._half_width_arc = 0.5 * l * arc
        self._volumes: dict = {}  # volume_mobile of a few depths (a table's limit and wall)

    def depth_mobile(self, volume) -> np.ndarray:
        """:func:`sector_depth_mobile` of the sectors' volumes [m³] (last axis: the sectors) [m];
        NaN with a RangeWarning beyond the whole sector."""
        if not (type(volume) is np.ndarray and volume.dtype == np.float64 and volume.size
                and volume.min() >= 0.0 and volume.max() < np.inf):  # else the checks' copy
            volume = _checked(volume, "volume", "m³")
        return _depth_within_sector(volume / self._width_arc, self.mobile_radius)

    def depth_obstacle(self, volume) -> np.ndarray:
        """:func:`sector_depth_obstacle` of the sectors' volumes [m³] [m] (needs the bore
        radius)."""
        v = _checked(volume, "volume", "m³")
        return obstacle_depth_from_area_density(v / self._width_arc, self.obstacle_radius)

    def volume_mobile(self, depth) -> np.ndarray:
        """:func:`sector_volume_mobile` of the sectors' depths [m] [m³]; NaN with a
        RangeWarning beyond the mobile radius."""
        d = _checked(depth, "depth", "m")
        small = d.size <= _KEPT_SIZE  # kept: the same few depths for every table
        if small:
            key = (d.shape, d.tobytes())
            found = self._volumes.get(key)
            if found is not None:
                return found.copy()
        volume, said = _volume_within_radius(d, self.mobile_radius, self._half_width_arc)
        if small and not said:  # a warning is said at every call: not kept
            if len(self._volumes) >= _KEPT_SIZE:
                self._volumes.clear()
            self._volumes[key] = volume.copy()
        return volume


#: Inputs of at most this many depths, and this many of them, kept by
#: :meth:`SectorSlices.volume_mobile`.
_KEPT_SIZE = 8


@functools.lru_cache(maxsize=256)
def sector_slices(mobile_radius: float, width: float, arcs_deg: tuple[float, ...],
                  obstacle_radius: float | None = None) -> SectorSlices:
    """The :class:`SectorSlices` of these dimensions [m] and arcs [deg], made once (the last
    256 kept: a geometry's constants shared by every table of the same dimensions)."""
    return SectorSlices(mobile_radius, width, arcs_deg, obstacle_radius)


@dataclass(frozen=True)
class SectorGeometry:
    """The dimensions of sector depths when no contact type is given (SECTEUR without CONTACT).

    Code_Aster's POST_USURE computes sector depths from RAYON_MOBILE, RAYON_OBST and LARGEUR_OBST
    alone (its SECTEUR has no CONTACT keyword): theory §3's depths need no contact type, the
    global depths (theory §6) do. This object stands in for a
    :class:`~fretwear.geometry.base.ContactGeometry` there: the same attributes, and
    :meth:`depth_from_volume` gives NaN (the reason is :attr:`reason`).

    Parameters
    ----------
    mobile_radius : float
        Mobile outer radius R_m [m] (RAYON_MOBILE), > 0.
    obstacle_width : float
        Obstacle width l [m] (LARGEUR_OBST), > 0.
    obstacle_radius : float, optional
        Bore radius R_o [m] (RAYON_OBST), > 0: the obstacle's sector depths need it.

    Examples
    --------
    >>> g = SectorGeometry(mobile_radius=0.0048, obstacle_width=0.011)
    >>> g.contact_type, g.depth_from_volume([1e-9])
    (None, (array([nan]), array([nan])))
    """

    mobile_radius: float
    obstacle_width: float
    obstacle_radius: float | None = None
    contact_type: ClassVar[None] = None
    #: Why the global depths are NaN.
    reason: ClassVar[str] = (
        "no contact type (CONTACT): the global depths P_USUR_TUBE and P_USUR_OBST need one "
        "(theory §6); the sector depths (theory §3) need only RAYON_MOBILE, LARGEUR_OBST and "
        "RAYON_OBST, and are computed")

    def __post_init__(self) -> None:
        for name in ("mobile_radius", "obstacle_width", "obstacle_radius"):
            value = getattr(self, name)
            if value is None and name == "obstacle_radius":
                continue
            try:
                number = float(value)
            except (TypeError, ValueError):
                number = math.nan
            if not math.isfinite(number) or number <= 0:
                raise InputError(f"{name} must be a length > 0 [m], got {value!r}")
            object.__setattr__(self, name, number)

    def dimensions(self) -> dict[str, float]:
        """The dimensions given (native names) [m]."""
        out = {"mobile_radius": self.mobile_radius, "obstacle_width": self.obstacle_width}
        if self.obstacle_radius is not None:
            out["obstacle_radius"] = self.obstacle_radius
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: ``contact_type`` None and the dimensions."""
        return {"contact_type": None, **self.dimensions()}

    def depth_from_volume(self, volume_mobile, volume_obstacle=0.0):
        """NaN depths [m] of the shape of the volumes [m³]: no contact type, no global depth."""
        shape = np.broadcast(np.asarray(volume_mobile, float), np.asarray(volume_obstacle,
                                                                          float)).shape
        return np.full(shape, np.nan), np.full(shape, np.nan)


def sector_geometry(**dimensions) -> SectorGeometry:
    """A :class:`SectorGeometry` from native dimension names, naming what is missing.

    Dimensions of a contact type (tilt_angle, isthmus_angle, impact_angle) are not used without
    one: a warning says so (Code_Aster's POST_USURE warns the same for ANGL_INCLI, ANGL_ISTHME,
    ANGL_IMPACT with SECTEUR, message PREPOST4_3).

    Raises
    ------
    KeywordError
        mobile_radius (RAYON_MOBILE) or obstacle_width (LARGEUR_OBST) missing, or an unknown name.
    """
    dims = {k: v for k, v in dimensions.items() if v is not None}
    known = ("mobile_radius", "obstacle_width", "obstacle_radius")
    angles = ("tilt_angle", "isthmus_angle", "impact_angle")
    unknown = sorted(set(dims) - set(known) - set(angles))
    if unknown:
        raise KeywordError(f"sector depths: unknown dimension(s) {unknown}; they take "
                           f"{list(known)}")
    missing = [k for k in ("mobile_radius", "obstacle_width") if k not in dims]
    if missing:
        raise KeywordError(f"sector depths need {missing} (RAYON_MOBILE, LARGEUR_OBST) [m]")
    unused = [k for k in angles if k in dims and dims[k] != 0]
    if unused:
        warnings.warn(f"without a contact type (CONTACT) the dimensions {unused} are not used: "
                      "sector depths depend on the radii and the width only", UnusedKeywordWarning,
                      stacklevel=3)
    return SectorGeometry(**{k: dims[k] for k in known if k in dims})
