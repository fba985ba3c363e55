"""The time to a depth through a table's rows: a restart's earlier rows, a bundle's tables.

The rows' side of :class:`fretwear.table.DepthModel` (its :attr:`~DepthModel.rows` and
:func:`earlier_rows_time`: a restart's earlier rows, whose law is not known to the run), and
the labels of :meth:`fretwear.bundle.BundleResult.summary`'s ``time_to_limit_method``.

The summary's time to a limit is the contact's :class:`~fretwear.table.DepthModel`'s
:meth:`~fretwear.table.DepthModel.time_to` (:data:`FROM_MODEL`; docs/uncertainty.md §1), or
the table's own ``limit_instant`` for the case's limit (:data:`FROM_TABLE`, the same model);
only where the contact's law or geometry is not known (a Code_Aster table from another law),
depth(t) interpolated between its rows (:func:`rows_time`, :data:`INTERPOLATED`).

Times are in the contact's time unit (the table's ``instant``).
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from fretwear.geometry import contact_geometry
from fretwear.laws import WEAR_LAWS

_TIME_TOL = 1e-9

#: How the time to reach the limit was found, in :meth:`BundleResult.summary`.
INTERPOLATED = ("interpolated: depth(t) between the table's instants by a monotone cubic "
                "(PCHIP), from depth 0 at the origin of a new tube (the contact's law or "
                "geometry not known)")
FROM_TABLE = ("the wear table's limit_instant (the contact's depth model inverted for the "
              "case's limit), where reached by the last instant")
FROM_MODEL = ("the contact's depth model (DepthModel.time_to: the law and the geometry at the "
              "run's power, from the tube's volume at its origin or replacement; a restart's "
              "earlier rows through the geometry, the volume linear in time between them)")
#: The methods named in ``summary().attrs["time_to_limit"]``.
METHODS = (FROM_TABLE, FROM_MODEL, INTERPOLATED)


def interpolated_time(instants: np.ndarray, depths: np.ndarray, target: float, *,
                  from_zero: bool = True) -> float:
    """The instant at which a non-decreasing depth history reaches ``target``.

    Parameters
    ----------
    instants : array
        Increasing instants (any time unit; the result is in the same unit).
    depths : array
        Depths at those instants [m]; NaN entries are dropped.
    target : float
        Depth to reach [m].
    from_zero : bool
        Prepend (0, 0): a new tube has no wear at the origin.

    Returns
    -------
    float
        The instant, NaN when the last finite depth is below ``target``.

    Notes
    -----
    depth(t) is interpolated by a piecewise monotone cubic (PCHIP, Fritsch & Carlson 1980
    [1]_), which is monotone wherever the data are, and inverted on the bracketing interval
    with Brent's method to 1e-12 relative. Not exact: the summary's fallback where the
    contact's geometry or law is not known (:func:`rows_time`).

    References
    ----------
    .. [1] Fritsch, F. N., Carlson, R. E. (1980). Monotone piecewise cubic interpolation.
       SIAM J. Numer. Anal. 17(2), 238-246.

    Examples
    --------
    >>> t = np.array([1.0, 2.0, 4.0]); d = 1e-4 * t  # linear wear, 0.1 mm per unit
    >>> round(interpolated_time(t, d, 2.5e-4), 9)
    2.5
    """
    t = np.asarray(instants, dtype=float)
    d = np.asarray(depths, dtype=float)
    keep = np.isfinite(d) & np.isfinite(t)
    t, d = t[keep], d[keep]
    if from_zero and (t.size == 0 or t[0] > 0):
        t, d = np.concatenate(([0.0], t)), np.concatenate(([0.0], d))
    if t.size == 0 or d.max() < target:
        return math.nan
    d = np.maximum.accumulate(d)  # guard against round-off wiggles
    i = int(np.argmax(d >= target))
    if i == 0 or d[i] == target:
        return float(t[i])
    if t.size == 2:
        return float(t[0] + (target - d[0]) * (t[1] - t[0]) / (d[1] - d[0]))
    f = PchipInterpolator(t, d)
    return float(brentq(lambda x: float(f(x)) - target, t[i - 1], t[i], rtol=1e-12))


@dataclasses.dataclass(frozen=True, eq=False)
class EarlierRows:
    """A restart's earlier rows: the tube's known history up to the origin (one row per
    instant), whose law is not known to this run.

    Attributes
    ----------
    instants : numpy.ndarray
        Increasing instants [user time unit], the origin's row last.
    depths : numpy.ndarray
        The tube's global depth ``depth_mobile`` [m] at those instants.
    volume_mobile, volume_obstacle : numpy.ndarray or None
        The worn volumes of the tube and the obstacle [m³] (None: not known).
    from_zero : bool
        The first row's origin is 0: a new tube, unworn at instant 0.
    """

    instants: np.ndarray
    depths: np.ndarray
    volume_mobile: np.ndarray | None = None
    volume_obstacle: np.ndarray | None = None
    from_zero: bool = True

    @classmethod
    def from_rows(cls, rows, origin: float, *, column: str = "depth_mobile",
                  volumes=("volume_mobile", "volume_obstacle")) -> EarlierRows | None:
        """The earlier rows of a table's rows (native names) at or before ``origin`` [user time
        unit] (one per instant: the first of a sector table's, or give one sector's rows);
        ``column`` the depth, ``volumes`` the tube's and obstacle's volume columns (None: not
        known). None without a row."""
        if rows is None or len(rows) == 0 or "instant" not in rows.columns:
            return None
        tol = _TIME_TOL * max(1.0, abs(origin))
        keep = rows[np.asarray(rows["instant"], dtype=float) <= origin + tol]
        keep = keep.drop_duplicates("instant", keep="first").sort_values("instant")
        if keep.empty or column not in keep.columns:
            return None

        def values(name):
            return (keep[name].to_numpy(dtype=float) if name is not None
                    and name in keep.columns else None)

        first = values("origin")
        return cls(values("instant"), values(column), values(volumes[0]), values(volumes[1]),
                   bool(first is None or first[0] == 0))

    def times(self, targets, geometry) -> dict[float, float]:
        """Target depth [m] -> instant [user time unit], for the targets the tube in place
        reaches among these rows (:func:`fretwear.table.depth_rows.earlier_rows_time`)."""
        out = {}
        for value in np.atleast_1d(targets).tolist():
            found = earlier_rows_time(self.instants, self.depths, self.volume_mobile,
                                      self.volume_obstacle, value,
                                      geometry if hasattr(geometry, "contact_type")
                                      and geometry.contact_type else None, self.from_zero)
            if found is not None:
                out[value] = found
        return out


class ContactModels:
    """Each contact's geometry and wear law from the records' ``contact_type``, ``dimensions``
    and ``law`` (:attr:`BundleResult.contacts`), built once per distinct value; None where
    not known (a record without them, a contact type None: sector geometry only)."""

    def __init__(self):
        self._geometries: dict = {}

    def geometry(self, contact_type, dimensions):
        if not isinstance(contact_type, str) or not isinstance(dimensions, dict):
            return None
        key = (contact_type, tuple(sorted(dimensions.items())))
        if key not in self._geometries:
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    self._geometries[key] = contact_geometry(contact_type, **dimensions)
            except Exception:  # noqa: BLE001 - not a geometry this version knows: fallback
                self._geometries[key] = None
        return self._geometries[key]

    @staticmethod
    def law(name):
        return WEAR_LAWS.get(name.strip().upper()) if isinstance(name, str) else None


def rows_time(instants, depths, target: float, *, origins, replaced: float | None,
              volume_mobile=None) -> float:
    """The instant [table time unit] at which a contact's tube in place first reaches
    ``target`` [m], from its table's rows only: where its law or geometry is not known
    (:data:`INTERPOLATED`; otherwise :meth:`fretwear.table.DepthModel.time_to`).

    Parameters
    ----------
    instants, depths : array
        The contact's global rows, one per instant, increasing [table time unit], and the
        tube's depth ``depth_mobile`` [m] (NaN beyond the relation's range).
    target : float
        Depth to reach [m].
    origins : array or None
        The rows' ``origin`` [table time unit] (None: 0); a restart's initial-table rows come
        first, their own origin before this run's.
    replaced : float or None
        Instant of a tube replacement in this run: only the new tube counts, unworn there.
    volume_mobile : array, optional
        The tube's worn volume [m³]: its drop among the rows marks a replacement there.

    Returns
    -------
    float
        The instant (NaN when not reached by the last instant): depth(t) interpolated by a
        monotone cubic (:func:`interpolated_time`), the tube in place's rows only.

    Examples
    --------
    >>> rows_time([1.0, 2.0], [1e-4, 2e-4], 1.5e-4, origins=None, replaced=None)
    1.5
    """
    t = np.asarray(instants, dtype=float)
    d = np.asarray(depths, dtype=float)
    origins = np.zeros_like(t) if origins is None else np.asarray(origins, dtype=float)
    vm = None if volume_mobile is None else np.asarray(volume_mobile, dtype=float)
    if replaced is not None:
        keep = t >= replaced
        t, d, origins = t[keep], d[keep], origins[keep]
        d = np.where(t == replaced, 0.0, d)  # the new tube, unworn at its replacement
        return interpolated_time(t, d, target,
                                 from_zero=bool(origins.size == 0 or origins[0] == 0))
    from_zero = bool(origins.size == 0 or origins[0] == 0)
    if origins.size and origins[-1] > 0 and origins[0] != origins[-1]:  # a restart's rows:
        return _interpolated(t, d, vm, target, from_zero)  # the tube in place's
    return interpolated_time(t, d, target, from_zero=from_zero)


def earlier_rows_time(t, d, vm, vo, target: float, geometry, from_zero: bool
                      ) -> float | None:
    """The instant [table time unit] at which the tube in place reaches ``target`` [m] among a
    restart's initial-table rows (their law not known to this run); None where its depth
    there stays below ``target``.

    Parameters
    ----------
    t, d, vm, vo : array
        The rows' instants, ``depth_mobile`` [m] and worn volumes of the tube and the obstacle
        [m³] (``vm`` None: not known), up to the restart's origin.
    geometry : ContactGeometry or None
        The contact's geometry (None: not known).
    from_zero : bool
        The rows' first origin is 0: a new tube, unworn at instant 0.

    Returns
    -------
    float or None
        Through the geometry with the volume linear in time between the two rows that bracket
        ``target`` (exact when the earlier run's law was linear in time at constant power),
        after a tube replaced among them from their last row before the replacement (the
        earliest it can be); where the geometry or the volumes are not known, the depth
        interpolated between the rows (:func:`interpolated_time`).
    """
    t, d = np.asarray(t, dtype=float), np.asarray(d, dtype=float)
    vm = None if vm is None else np.asarray(vm, dtype=float)
    vo = np.zeros_like(t) if vo is None else np.nan_to_num(np.asarray(vo, dtype=float))
    if t.size == 0 or _reached(d, vm, target, _tube_start(d, vm, t.size - 1)) is None:
        return None
    found = None
    if geometry is not None and vm is not None:
        found = _through_volume(t, d, vm, vo, target, from_zero, geometry)
    return found if found is not None else _interpolated(t, d, vm, target, from_zero)


def _tube_start(d, vm, end: int) -> int:
    """The first row of the tube in place among rows ``[0, end]``: after the last drop of the
    tube's worn volume (a replacement; the depth alone can fall without one, when the
    obstacle's wear flattens the contact), or of the depth where no volume is known."""
    values = d if vm is None else vm
    drops = np.flatnonzero(values[1:end + 1] < values[:end])
    return int(drops[-1]) + 1 if drops.size else 0


def _reached(d, vm, target: float, first: int = 0) -> int | None:
    """The first row from ``first`` on whose depth reaches ``target``: a NaN depth of a finite
    volume is beyond the relation's range, deeper than any it describes, so it reaches it."""
    deep = d >= target
    if vm is not None:
        deep |= np.isnan(d) & np.isfinite(vm)
    hit = np.flatnonzero(deep[first:])
    return int(first + hit[0]) if hit.size else None


def _interpolated(t, d, vm, target: float, from_zero: bool) -> float:
    """:func:`interpolated_time` for the tube in place: after a replacement among the rows (a drop
    of the volume, or of the depth where no volume is known), from depth 0 at the last row
    before it, the earliest the replacement can be (the table does not say when it was)."""
    j = _tube_start(d, vm, len(d) - 1)
    if j:
        t = np.concatenate(([t[j - 1]], t[j:]))
        d, from_zero = np.concatenate(([0.0], d[j:])), False
    return interpolated_time(t, d, target, from_zero=from_zero)


def _through_volume(t, d, vm, vo, target: float, from_zero: bool, geometry) -> float | None:
    """:func:`earlier_rows_time` through the geometry: the instant [table time unit] at which
    the tube in place reaches ``target`` [m], its volume (and the obstacle's) linear in time
    between the two rows that bracket it; NaN where not reached; None where it cannot invert
    (a volume out of the relation's range)."""
    keep = np.isfinite(t)
    t, d, vm, vo = t[keep], d[keep], vm[keep], vo[keep]
    if from_zero and (t.size == 0 or t[0] > 0):  # a new tube: no wear at instant 0
        t, d, vm, vo = (np.concatenate(([0.0], a)) for a in (t, d, vm, vo))
    j = _tube_start(d, vm, vm.size - 1)  # a tube replaced among the rows
    if j:  # the new tube from the last row before, the earliest it can be
        t, vo = t[j - 1:], vo[j - 1:]
        d, vm = np.concatenate(([0.0], d[j:])), np.concatenate(([0.0], vm[j:]))
    b = _reached(d, vm, target)
    if b is None:
        return math.nan
    if b == 0 or d[b] == target or t[b] == t[b - 1]:
        return float(t[b])
    a = b - 1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # range warnings of trial volumes
        if geometry.mobile_depth_alone or (vo[a] == 0 and vo[b] == 0):
            volume = float(np.asarray(geometry.volume_from_depth(target, 0.0)[0]))
            if not math.isfinite(volume):
                return None
            fraction = (volume - vm[a]) / (vm[b] - vm[a])
        else:  # the depth of both volumes along the segment, each linear in time

            def excess(s):
                depth = geometry.depth_from_volume(vm[a] + s * (vm[b] - vm[a]),
                                                   vo[a] + s * (vo[b] - vo[a]))[0]
                depth = float(np.asarray(depth))
                return target if math.isnan(depth) else depth - target

            if excess(0.0) >= 0:
                fraction = 0.0
            elif excess(1.0) <= 0:
                fraction = 1.0
            else:
                fraction = brentq(excess, 0.0, 1.0, xtol=1e-15, rtol=1e-14)
    if not math.isfinite(fraction):
        return None
    return float(t[a] + min(max(fraction, 0.0), 1.0) * (t[b] - t[a]))
