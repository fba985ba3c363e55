"""Base contract of the contact geometries (theory §6, docs/DESIGN.md "Geometry").

A contact geometry is a frozen dataclass whose fields are the dimensions the contact type
uses (SI lengths [m], user angles [deg]). Subclasses declare

- ``contact_type``: the Code_Aster name (``"TUBE_BAV"`` ...),
- ``required`` / ``optional``: the dimension names the type needs / may use,
- ``example``: typical dimensions (docs, tests, figures),

and implement the two element-wise relations on validated float arrays of one shape,

- ``_depth_from_volume(volume_mobile, volume_obstacle) -> (depth_mobile, depth_obstacle)``,
- ``_volume_from_depth(depth_mobile, depth_obstacle) -> (volume_mobile, volume_obstacle)``,

returning NaN where the input lies beyond the relation's range, plus the ``max_depth`` property
(the largest mobile depth of the range when the obstacle does not wear, [m]) and, optionally,
``range_limit`` (a sentence naming the limit). The public methods :meth:`depth_from_volume` and
:meth:`volume_from_depth` validate and broadcast the inputs (never modifying them), call the
relation, and warn with :class:`~fretwear.errors.RangeWarning` (naming the contact type and the
limit) where the result is NaN.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Any, ClassVar

import numpy as np

from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.geometry._shapes import _out

__all__ = [
    "ANGLE_DIMENSIONS",
    "ASTER_KEYWORDS",
    "DIMENSION_DESCRIPTIONS",
    "DIMENSION_UNITS",
    "LENGTH_DIMENSIONS",
    "ContactGeometry",
]

#: Native dimension name -> Code_Aster keyword of POST_USURE.
ASTER_KEYWORDS: dict[str, str] = {
    "mobile_radius": "RAYON_MOBILE",
    "obstacle_radius": "RAYON_OBST",
    "obstacle_width": "LARGEUR_OBST",
    "tilt_angle": "ANGL_INCLI",
    "isthmus_angle": "ANGL_ISTHME",
    "impact_angle": "ANGL_IMPACT",
}

#: Unit of each dimension (SI lengths, user angles in degrees).
DIMENSION_UNITS: dict[str, str] = {
    "mobile_radius": "m",
    "obstacle_radius": "m",
    "obstacle_width": "m",
    "tilt_angle": "deg",
    "isthmus_angle": "deg",
    "impact_angle": "deg",
}

DIMENSION_DESCRIPTIONS: dict[str, str] = {
    "mobile_radius": "outer radius of the mobile (tube or rod)",
    "obstacle_radius": "radius of the obstacle (bore radius, or the other tube's radius)",
    "obstacle_width": "width of the obstacle (worn height along the mobile's axis)",
    "tilt_angle": "tilt of the mobile relative to the obstacle (the crossing angle of two tubes)",
    "isthmus_angle": "angle of the isthmus edge of a broached (trefoil/quatrefoil) hole",
    "impact_angle": "angle between the impact direction and the bar's normal",
}

#: The words of the RangeWarning of a contact's global depths or volumes leaving the relation's
#: range (the sector depths' warnings say "sector"): how a bundle's errors.csv tells it apart.
GLOBAL_RANGE = "beyond the range of the relation"
LENGTH_DIMENSIONS = ("mobile_radius", "obstacle_radius", "obstacle_width")
ANGLE_DIMENSIONS = ("tilt_angle", "isthmus_angle", "impact_angle")


def _label(name: str) -> str:
    return f"{name} ({ASTER_KEYWORDS.get(name, name)})"


def _plain_pair(mobile, obstacle) -> bool:
    """Whether a pair is two float64 arrays of one shape, each finite and >= 0 (a min or max
    NaN fails too: the general path then takes NaN through): what the general path of
    :func:`_volumes_or_depths` would copy unchanged, checked in two reductions."""
    return (type(mobile) is np.ndarray and type(obstacle) is np.ndarray
            and mobile.dtype == np.float64 and obstacle.dtype == np.float64
            and mobile.shape == obstacle.shape and mobile.size > 0
            # np.minimum and np.maximum keep a NaN: min(min(m, o)) is NaN or the least of both
            and bool(np.minimum(mobile, obstacle).min() >= 0.0)
            and bool(np.maximum(mobile, obstacle).max() < np.inf))


def _plain_result(values, shape: tuple) -> bool:
    """Whether a relation's result is a float64 array of ``shape`` (what ``np.where`` of
    :meth:`ContactGeometry._apply` would copy unchanged where every input is given)."""
    return type(values) is np.ndarray and values.dtype == np.float64 and values.shape == shape


def _volumes_or_depths(kind: str, mobile, obstacle) -> tuple[np.ndarray, np.ndarray]:
    """Validated float copies of a (mobile, obstacle) pair, broadcast to one shape."""
    if _plain_pair(mobile, obstacle):  # the usual pair (a table's own): the same copies
        return mobile.copy(), obstacle.copy()
    unit = "m³" if kind == "volume" else "m"
    arrays = []
    for body, value in (("mobile", mobile), ("obstacle", obstacle)):
        name = f"{kind}_{body}"
        try:
            array = np.array(value, dtype=float)  # a copy: inputs are never modified
        except (TypeError, ValueError):
            raise InputError(f"{name} must be numbers [{unit}], got {value!r}") from None
        bad = np.isinf(array) | (array < 0.0)  # NaN (the out-of-range marker) passes through
        if bad.any():
            index = np.argwhere(bad)[0]
            where = f" at index {tuple(int(i) for i in index)}" if array.ndim else ""
            raise InputError(
                f"{name} must be finite and >= 0 [{unit}]: got {float(array[tuple(index)]):g}"
                f"{where}; pass a non-negative {kind}")
        arrays.append(array)
    try:
        mobile_array, obstacle_array = np.broadcast_arrays(*arrays)
    except ValueError:
        raise InputError(
            f"{kind}_mobile (shape {arrays[0].shape}) and {kind}_obstacle (shape "
            f"{arrays[1].shape}) do not broadcast together; give arrays of the same length"
        ) from None
    return mobile_array.astype(float, copy=True), obstacle_array.astype(float, copy=True)


#: :meth:`ContactGeometry.mobile_volume` keeps the volumes of at most this many depth arrays of
#: at most _KEPT_DEPTHS_SIZE depths per geometry (a case's depth limit and wall thickness: the
#: wear table's time to the limit asks them of every table of the same geometry).
_KEPT_VOLUMES = 16
_KEPT_DEPTHS_SIZE = 4

#: Lengths [m] a contact dimension may take: beyond them the formulas of theory §6 overflow or
#: underflow (a width of 5e-324 m divided into a volume is inf) and no real contact is that size.
LENGTH_RANGE = (1e-9, 1e3)


@dataclasses.dataclass(frozen=True)
class ContactGeometry:
    """Base of the eight contact geometries: volume ↔ depth relations of theory §6.

    Subclasses are frozen dataclasses with the dimensions as fields (see module docstring).
    Build them by name with :func:`fretwear.geometry.contact_geometry`.

    Examples
    --------
    Uniform wear of a tube in a hole, d_m = V_m/(2π·l·R_m) (theory §6): 2π·l·R_m·d with
    l = 20 mm, R_m = 10 mm, d = 1 µm is 1.2566 mm³.

    >>> import math
    >>> from fretwear.geometry import contact_geometry
    >>> g = contact_geometry("TUBE_ALESAGE", mobile_radius=0.01, obstacle_width=0.02)
    >>> volume = 2 * math.pi * 0.02 * 0.01 * 1e-6
    >>> depth_mobile, depth_obstacle = g.depth_from_volume([0.0, volume])
    >>> depth_mobile.round(15).tolist(), depth_obstacle.tolist()
    ([0.0, 1e-06], [0.0, 0.0])
    >>> bool(np.isclose(g.volume_from_depth(1e-6)[0], volume, rtol=1e-15))
    True
    """

    contact_type: ClassVar[str] = ""
    required: ClassVar[tuple[str, ...]] = ()
    optional: ClassVar[tuple[str, ...]] = ()
    example: ClassVar[dict[str, float]] = {}
    #: The mobile's depth depends on the mobile's volume alone, d_m(V_m, V_o) = d_m(V_m, 0)
    #: (each body wears a trace of its own): a depth of the mobile then inverts to one mobile
    #: volume whatever the obstacle's wear (the wear table's closed-form limit instants).
    mobile_depth_alone: ClassVar[bool] = False

    # ------------------------------------------------------------------ validation
    def __post_init__(self) -> None:
        self._validate_dimensions()

    def _validate_dimensions(self) -> None:
        """Check the dimensions: lengths finite and > 0, angles finite in [0, 90) [deg]."""
        for name in self.required:
            if getattr(self, name, None) is None:
                raise KeywordError(
                    f"{self.contact_type} needs {_label(name)}: "
                    f"{DIMENSION_DESCRIPTIONS.get(name, name)} [{DIMENSION_UNITS.get(name, '')}]")
        for name in self.required + self.optional:
            value = getattr(self, name, None)
            if value is None:
                continue
            try:
                if isinstance(value, (bool, np.bool_)):  # True would silently become 1 m
                    raise TypeError
                number = float(value)
            except (TypeError, ValueError):
                raise InputError(
                    f"{self.contact_type}: {_label(name)} must be a number "
                    f"[{DIMENSION_UNITS.get(name, '')}], got {value!r}") from None
            if not math.isfinite(number):
                raise InputError(
                    f"{self.contact_type}: {_label(name)} must be finite, got {value!r}")
            if name in ANGLE_DIMENSIONS:
                if not 0.0 <= number < 90.0:
                    raise InputError(
                        f"{self.contact_type}: {_label(name)} must lie in [0, 90) deg, got "
                        f"{number:g}; give the angle in degrees")
            elif number <= 0.0:
                raise InputError(
                    f"{self.contact_type}: {_label(name)} must be > 0 [m], got {number:g}")
            elif not LENGTH_RANGE[0] <= number <= LENGTH_RANGE[1]:
                raise InputError(
                    f"{self.contact_type}: {_label(name)} = {number:g} m is not a plausible "
                    f"contact dimension (accepted {LENGTH_RANGE[0]:g} to {LENGTH_RANGE[1]:g} m); "
                    "give it in metres (9.525 mm is 9.525e-3)")
            if type(value) is not float:  # ints, numpy scalars -> plain float (JSON-ready)
                object.__setattr__(self, name, number)

    def _check_room(self, hole: str, mobile: str) -> None:
        """The hole of radius R_o must hold the mobile: R_o > R_m (``hole``/``mobile`` name
        the two radii in the message, e.g. "the bore radius", "the mobile radius")."""
        if not self.obstacle_radius > self.mobile_radius:
            raise InputError(
                f"{self.contact_type}: {hole} obstacle_radius (RAYON_OBST) = "
                f"{self.obstacle_radius:g} m must exceed {mobile} mobile_radius "
                f"(RAYON_MOBILE) = {self.mobile_radius:g} m")

    # ------------------------------------------------------------------ helpers
    def angle(self, name: str) -> float:
        """Dimension ``name`` [deg] converted to radians [rad] (0 when not given)."""
        value = getattr(self, name, None)
        return 0.0 if value is None else math.radians(value)

    def dimensions(self) -> dict[str, float]:
        """The dimensions given (native names, SI lengths [m], angles [deg]): a new dict."""
        kept = self.__dict__.get("_dimensions")  # immutable: its dimensions found once
        if kept is None:
            kept = tuple((f.name, getattr(self, f.name)) for f in dataclasses.fields(self)
                         if getattr(self, f.name) is not None)
            object.__setattr__(self, "_dimensions", kept)
        return dict(kept)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: contact type and dimensions.

        Examples
        --------
        >>> from fretwear.geometry import contact_geometry
        >>> contact_geometry("TUBE_BAV", mobile_radius=0.01, obstacle_width=0.02).to_dict()
        {'contact_type': 'TUBE_BAV', 'mobile_radius': 0.01, 'obstacle_width': 0.02, \
'tilt_angle': 0.0, 'impact_angle': 0.0}
        """
        return {"contact_type": self.contact_type, **self.dimensions()}

    @property
    def max_depth(self) -> float:
        """Largest mobile depth of the relation's range, obstacle not worn [m]."""
        raise NotImplementedError

    @property
    def max_volume(self) -> float:
        """Mobile volume at :attr:`max_depth`, obstacle not worn [m³]."""
        volume, _ = self._volume_from_depth(np.array([self.max_depth]), np.zeros(1))
        return float(volume[0])

    @property
    def range_limit(self) -> str:
        """Sentence naming the limit of the relation's range."""
        return f"largest valid depth {self.max_depth:.6g} m"

    # ------------------------------------------------------------------ relations
    def _depth_from_volume(self, volume_mobile: np.ndarray, volume_obstacle: np.ndarray):
        raise NotImplementedError

    def _volume_from_depth(self, depth_mobile: np.ndarray, depth_obstacle: np.ndarray):
        raise NotImplementedError

    def mobile_volume(self, depth_mobile: np.ndarray) -> np.ndarray:
        """The mobile's worn volume [m³] of valid mobile depths [m] (an array, each ≥ 0), the
        obstacle unworn: :meth:`volume_from_depth`'s relation without its checks and warning,
        for a caller whose depths are valid by construction (NaN beyond the range).

        Examples
        --------
        >>> from fretwear.geometry import contact_geometry
        >>> g = contact_geometry("TUBE_BAV", mobile_radius=0.01, obstacle_width=0.02)
        >>> bool(g.mobile_volume(np.array([1e-4]))[0] == g.volume_from_depth(1e-4)[0])
        True
        """
        depth = np.asarray(depth_mobile, dtype=float)
        small = depth.size <= _KEPT_DEPTHS_SIZE  # a limit and the wall: kept per geometry
        if small:
            kept = self.__dict__.get("_mobile_volumes")
            if kept is None:
                kept = {}
                object.__setattr__(self, "_mobile_volumes", kept)  # immutable: one cache
            key = (depth.shape, depth.tobytes())
            found = kept.get(key)
            if found is not None:
                return found.copy()
        volume = np.asarray(self._volume_from_depth(depth, np.zeros_like(depth))[0],
                            dtype=float)
        if small:
            if len(kept) >= _KEPT_VOLUMES:
                kept.clear()
            kept[key] = volume.copy()
        return volume

    def _apply(self, relation, kind: str, mobile, obstacle):
        """``relation`` on the validated pair of ``kind`` ("volume"/"depth"): NaN inputs give
        NaN, and new NaNs (beyond the range) a RangeWarning at the public method's caller."""
        if _plain_pair(mobile, obstacle) and mobile.ndim:  # no NaN given: fewer calls
            a, b = mobile.copy(), obstacle.copy()  # as _volumes_or_depths copies them
            x, y = relation(a, b)
            if _plain_result(x, a.shape) and _plain_result(y, a.shape):
                x, y = x.copy(), y.copy()  # np.where(given, x, nan) with every input given
                if np.isnan(np.minimum(x, y).min()):  # a NaN in either (both keep it)
                    self._say_range(kind, int(np.count_nonzero(np.isnan(x) | np.isnan(y))))
                return x, y
        else:
            a, b = _volumes_or_depths(kind, mobile, obstacle)
            x, y = relation(a, b)
        given = ~(np.isnan(a) | np.isnan(b))
        x = np.where(given, np.asarray(x, dtype=float), np.nan)
        y = np.where(given, np.asarray(y, dtype=float), np.nan)
        self._say_range(kind, int(np.count_nonzero(given & (np.isnan(x) | np.isnan(y)))))
        return _out(x), _out(y)

    def _say_range(self, kind: str, count: int) -> None:
        """The RangeWarning of ``count`` new NaNs of :meth:`_apply`, at the public method's
        caller (none for 0)."""
        if count:
            warnings.warn(
                f"{self.contact_type}: {count} {kind}(s) {GLOBAL_RANGE} "
                f"({self.range_limit}); the result there is NaN",
                RangeWarning, stacklevel=4)

    def depth_from_volume(self, volume_mobile, volume_obstacle=0.0):
        """Worn depths of mobile and obstacle from their worn volumes.

        Parameters
        ----------
        volume_mobile : float or array_like
            Worn volume of the mobile V_m [m³], ≥ 0 (one per instant, any shape). NaN passes
            through as NaN (it is the out-of-range marker), without a warning.
        volume_obstacle : float or array_like
            Worn volume of the obstacle V_o [m³], ≥ 0 (0 when the obstacle does not wear).

        Returns
        -------
        depth_mobile, depth_obstacle : numpy.ndarray or float
            d_m, d_o [m], of the broadcast shape; NaN (with a RangeWarning) beyond the range.
        """
        return self._apply(self._depth_from_volume, "volume", volume_mobile, volume_obstacle)

    def volume_from_depth(self, depth_mobile, depth_obstacle=0.0):
        """Worn volumes of mobile and obstacle from their worn depths.

        Parameters
        ----------
        depth_mobile : float or array_like
            Worn depth of the mobile d_m [m], ≥ 0 (NaN passes through as NaN).
        depth_obstacle : float or array_like
            Worn depth of the obstacle d_o [m], ≥ 0.

        Returns
        -------
        volume_mobile, volume_obstacle : numpy.ndarray or float
            V_m, V_o [m³]; NaN (with a RangeWarning) beyond the range.
        """
        return self._apply(self._volume_from_depth, "depth", depth_mobile, depth_obstacle)
