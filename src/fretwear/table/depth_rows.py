"""The time to a depth through a table's rows: a restart's earlier rows, a bundle's tables.

The rows' side of :class:`fretwear.table.DepthModel` (its :attr:`~DepthModel.rows` and
:func:`earlier_rows_time`), and :func:`time_to_limit`, the time at which a contact's global
depth reaches a limit from its table's rows (:meth:`fretwear.bundle.BundleResult.summary`).

For a limit other than the case's own (whose instant the wear table holds, ``limit_instant``),
from the table's rows of one contact:

* **exact through the volume** (:data:`FROM_VOLUME`, :data:`FROM_LAW`): the limit depth [m] is
  inverted through the contact's geometry to the tube's worn volume [m³]
  (``volume_from_depth``, obstacle depth 0, where the tube's depth is a function of its own
  volume; otherwise the depth of the two volumes is solved for along the segment), and that
  volume to a time. The worn volume of a law linear in time (ARCHARD, KWU-EPRI) at the run's
  constant power is linear in time between the table's instants, from the volume at the
  tube's origin (0 at the origin of a new tube, the initial table's volume at a restart's
  origin, 0 at a tube replacement): the time is the linear interpolation of the volume. A law
  not linear in time (EDF-MZ) continues its volume from its equivalent time (theory §7): the
  time is the difference of the law's equivalent times of the two volumes at the run's power;
* **among a restart's initial-table rows** (:data:`INITIAL_ROWS`): those rows may come from
  another law or hold a tube replacement at an instant the table does not give; a limit
  reached among them is found through the geometry with the volume linear in time between
  them (exact for an earlier run of a law linear in time at constant power), after a
  replacement among them from their last row before it (the earliest it can be);
* **interpolated** (:data:`INTERPOLATED`, the fallback where the geometry or the law is not
  known, or for a law not linear in time without the run's power or, where the tube's depth
  needs a wearing obstacle's volume, without the obstacle's coefficients): depth(t) by a
  monotone cubic between the instants, inverted (:func:`interpolated_time`).

Times are in the contact's time unit (the table's ``instant``); ``time_scale`` [s per unit].
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
                "(PCHIP), from depth 0 at the origin of a new tube (the contact's geometry or "
                "law not known, or a law not linear in time without the run's power or, where "
                "the tube's depth needs the obstacle's wear, without the obstacle's "
                "coefficients)")
FROM_TABLE = ("the wear table's limit_instant (law and geometry inverted for the case's limit), "
              "where reached by the last instant")
FROM_VOLUME = ("exact: the limit depth inverted through the contact's geometry to a worn "
               "volume, the volume linear in time between the table's instants (a law linear "
               "in time at the run's power), from the tube's volume at its origin")
FROM_LAW = ("exact: the limit depth inverted through the contact's geometry to a worn volume, "
            "that volume to a time through the law's equivalent time at the run's power (a law "
            "not linear in time)")
INITIAL_ROWS = ("among a restart's initial-table rows (their law not known to this run): the "
                "limit depth inverted through the contact's geometry to a worn volume, the "
                "volume linear in time between those rows (exact when the earlier run's law "
                "was linear in time at constant power; after a tube replaced among them, from "
                "their last row before the replacement, the earliest it can be)")
#: The methods named in ``summary().attrs["time_to_limit"]``.
METHODS = (FROM_TABLE, FROM_VOLUME, FROM_LAW, INITIAL_ROWS, INTERPOLATED)


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
    contact's geometry or law is not known (:func:`time_to_limit`).

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
                out[value] = found[0]
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


def exact_method(geometry, law, *, sectors: bool, volumes: bool = True,
                 time_scale: float | None = 1.0, obstacle_wears: bool = False,
                 obstacle_coefficients: dict | None = None, powers: bool = True) -> str | None:
    """The exact method :func:`time_to_limit` uses for a contact (:data:`FROM_VOLUME` or
    :data:`FROM_LAW`) after its run's origin, or None where it interpolates: the geometry or
    the law not known, no volume column, or a law not linear in time with sectors, without a
    time scale or the run's power, or whose tube depth needs the obstacle's wear
    (``obstacle_wears``) without the obstacle's coefficients."""
    if geometry is None or law is None or not volumes:
        return None
    if law.linear_in_time:
        return FROM_VOLUME
    if sectors or not time_scale or not powers:
        return None
    if obstacle_wears and not geometry.mobile_depth_alone and obstacle_coefficients is None:
        return None
    return FROM_LAW


class _LinearInTime:
    """What :func:`_through_volume` asks of a law among a restart's initial-table rows, whose
    law is not known: volumes linear in time between the rows."""

    linear_in_time = True


def time_to_limit(instants, depths, target: float, *, origins, replaced: float | None,
                  volume_mobile=None, volume_obstacle=None, powers=None, geometry=None,
                  law=None, coefficients=None, time_scale: float | None = None,
                  sectors: bool = False, obstacle_coefficients=None) -> tuple[float, str]:
    """The instant at which a contact's global depth first reaches ``target``, and the method.

    Parameters
    ----------
    instants : array
        The contact's instants, one per row, increasing [table time unit].
    depths, volume_mobile, volume_obstacle, powers : array
        At those instants: the global tube depth ``depth_mobile`` [m] (NaN beyond the
        relation's range: deeper than it describes), the cumulated worn volumes of the tube and
        the obstacle [m³], the run's wear power [W].
    target : float
        Depth to reach [m].
    origins : array or None
        The rows' ``origin`` [table time unit] (None: 0): a first row of origin 0 is a new
        tube's (its volumes 0 at instant 0); otherwise the first row is an initial table's,
        holding the volumes at its instant.
    replaced : float or None
        Instant of a tube replacement in this run [table time unit]: only the new tube counts,
        its volume 0 there.
    geometry : ContactGeometry, optional
        The contact's geometry (:func:`fretwear.geometry.contact_geometry`).
    law : WearLaw, optional
        Its wear law; ``coefficients`` the tube's coefficients, ``obstacle_coefficients`` the
        obstacle's (None: it does not wear), ``time_scale`` [s per unit] (for a law not linear
        in time).
    sectors : bool
        The table has sectors (a law not linear in time then sums the sectors' laws: not the
        law at the global power).

    Returns
    -------
    (float, str)
        The instant (NaN when not reached by the last instant) and the method:
        :data:`FROM_VOLUME`, :data:`FROM_LAW`, :data:`INITIAL_ROWS` or :data:`INTERPOLATED`
        (module docstring).

    Notes
    -----
    A restart's table starts with the initial table's rows (their own origin, before this
    run's). They may come from another law, other coefficients or a tube replaced at an instant
    the table does not hold, so a limit reached among them (or between the last of them and
    this run's first row, when the initial table has no row at this run's origin) is found
    among them (:data:`INITIAL_ROWS`, the volume linear between those rows; the cubic where
    the geometry is not known); the exact methods apply from this run's origin on. With a
    replacement in this run, only the new tube counts: the initial rows do not.
    """
    t = np.asarray(instants, dtype=float)
    d = np.asarray(depths, dtype=float)
    origins = np.zeros_like(t) if origins is None else np.asarray(origins, dtype=float)
    vm = None if volume_mobile is None else np.asarray(volume_mobile, dtype=float)
    vo = (np.zeros_like(t) if volume_obstacle is None
          else np.nan_to_num(np.asarray(volume_obstacle, dtype=float)))
    p = np.zeros_like(t) if powers is None else np.asarray(powers, dtype=float)
    method = exact_method(geometry, law, sectors=sectors, volumes=vm is not None,
                          time_scale=time_scale, obstacle_wears=bool((vo != 0).any()),
                          obstacle_coefficients=obstacle_coefficients,
                          powers=powers is not None)
    earlier = 0 if replaced is not None else _earlier_rows(origins)
    rows = slice(None)
    if earlier:  # a restart: the initial table's rows first
        origin = float(origins[-1])
        start = earlier - 1 if t[earlier - 1] == origin else earlier
        hit = _reached(d, vm, target, _tube_start(d, vm, start))
        if hit is not None and hit <= start:  # reached in the initial table's rows: there
            end = max(earlier, hit + 1)  # or up to this run's first row past them
            return earlier_rows_time(t[:end], d[:end], None if vm is None else vm[:end],
                                     vo[:end], target, geometry, float(origins[0]) == 0)
        if method is None:
            return _interpolated(t, d, vm, target, float(origins[0]) == 0), INTERPOLATED
        rows = slice(start, None)
    if method is not None:
        origin = float(origins[-1] if earlier else (origins[0] if origins.size else 0.0))
        found = _through_volume(t[rows], d[rows], vm[rows], vo[rows], p[rows], target, origin,
                                replaced, geometry, law, coefficients, time_scale,
                                obstacle_coefficients)
        if found is not None:
            return found, method
    if replaced is not None:
        keep = t >= replaced
        t, d, origins = t[keep], d[keep], origins[keep]
        d = np.where(t == replaced, 0.0, d)  # the new tube, unworn at its replacement
    origin = float(origins[0]) if origins.size else 0.0
    return interpolated_time(t, d, target, from_zero=origin == 0), INTERPOLATED


def earlier_rows_time(t, d, vm, vo, target: float, geometry, from_zero: bool
                      ) -> tuple[float, str] | None:
    """The instant [table time unit] at which the tube in place reaches ``target`` [m] among a
    restart's initial-table rows (their law not known to this run), and the method; None
    where its depth there stays below ``target``.

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
    (float, str) or None
        Through the geometry with the volume linear in time between the rows
        (:data:`INITIAL_ROWS`), after a tube replaced among them from their last row before
        the replacement; where the geometry or the volumes are not known, the depth
        interpolated between the rows (:data:`INTERPOLATED`).
    """
    t, d = np.asarray(t, dtype=float), np.asarray(d, dtype=float)
    vm = None if vm is None else np.asarray(vm, dtype=float)
    vo = np.zeros_like(t) if vo is None else np.nan_to_num(np.asarray(vo, dtype=float))
    if t.size == 0 or _reached(d, vm, target, _tube_start(d, vm, t.size - 1)) is None:
        return None
    found = None
    if geometry is not None and vm is not None:
        found = _through_volume(t, d, vm, vo, np.zeros_like(t), target,
                                0.0 if from_zero else math.nan, None, geometry, _LinearInTime,
                                None, 1.0)
    if found is not None:
        return found, INITIAL_ROWS
    return _interpolated(t, d, vm, target, from_zero), INTERPOLATED


def _earlier_rows(origins: np.ndarray) -> int:
    """How many leading rows are an initial table's (a restart): rows whose origin differs
    from this run's (the last row's), when this run's origin is after 0."""
    if origins.size == 0 or not origins[-1] > 0:
        return 0
    return int(np.argmax(origins == origins[-1]))


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


def _through_volume(t, d, vm, vo, p, target, origin, replaced, geometry, law, coefficients,
                    time_scale, obstacle_coefficients=None) -> float | None:
    """:func:`time_to_limit` through the volume; None where it cannot invert (a law not linear
    in time whose tube depth needs a wearing obstacle's volume without its coefficients, a
    volume out of the relation's range)."""
    keep = np.isfinite(t)
    t, d, vm, vo, p = t[keep], d[keep], vm[keep], vo[keep], p[keep]
    if origin == 0 and (t.size == 0 or t[0] > 0):  # a new tube: no wear at instant 0
        t, d, vm, vo = (np.concatenate(([0.0], a)) for a in (t, d, vm, vo))
        p = np.concatenate((p[:1], p))
    if replaced is not None:  # the new tube from the replacement on (the obstacle's goes on)
        after = t >= replaced
        if not after.any():
            return math.nan
        if t[after][0] > replaced:
            vo_r = _obstacle_at(replaced, t, vo, p, law, obstacle_coefficients, time_scale)
            t = np.concatenate(([replaced], t[after]))
            d, vm = np.concatenate(([0.0], d[after])), np.concatenate(([0.0], vm[after]))
            vo, p = np.concatenate(([vo_r], vo[after])), np.concatenate((p[after][:1], p[after]))
        else:  # a row at the replacement: the new tube's, unworn (a restart's origin row
            # holds the old tube's volumes there)
            t, d, vm, vo, p = t[after], d[after].copy(), vm[after].copy(), vo[after], p[after]
            d[0] = vm[0] = 0.0
    j = _tube_start(d, vm, vm.size - 1)  # a tube replaced among an initial table's rows
    if j:  # the new tube from the last row before, the earliest it can be
        t, vo, p = t[j - 1:], vo[j - 1:], p[j - 1:]
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
            if law.linear_in_time:
                fraction = (volume - vm[a]) / (vm[b] - vm[a])
            else:  # the law's volume continues from its equivalent time at the run's power
                coefs = dict(coefficients or {})
                since = (float(law.equivalent_time(volume, p[b], **coefs))
                         - float(law.equivalent_time(vm[a], p[b], **coefs))) / time_scale
                fraction = since / (t[b] - t[a])
        else:  # the depth of both volumes along the segment
            volumes = _segment_volumes(vm, vo, p, a, b, t, law, coefficients,
                                       obstacle_coefficients, time_scale)
            if volumes is None:
                return None

            def excess(s):
                depth = geometry.depth_from_volume(*volumes(s))[0]
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


def _obstacle_at(instant: float, t, vo, p, law, obstacle_coefficients, time_scale) -> float:
    """The obstacle's worn volume [m³] at ``instant`` between two rows: linear for a law linear
    in time, else its law continued from the equivalent time of the row before (the obstacle
    does not change at the tube's replacement)."""
    if t.size == 0:
        return 0.0
    a = int(np.searchsorted(t, instant, side="right")) - 1
    if a < 0:
        return float(vo[0])
    if a + 1 >= t.size or vo[a + 1] == vo[a] or law.linear_in_time \
            or obstacle_coefficients is None:
        return float(np.interp(instant, t, vo))
    other = dict(obstacle_coefficients)
    power = p[a + 1]
    start = float(law.equivalent_time(vo[a], power, **other))
    return float(law.volume(power, start + (instant - t[a]) * time_scale, **other))


def _segment_volumes(vm, vo, p, a: int, b: int, t, law, coefficients, obstacle_coefficients,
                     time_scale):
    """``s -> (tube volume, obstacle volume)`` [m³] at the fraction ``s`` of the segment from
    row ``a`` to row ``b``: linear for a law linear in time; otherwise each body's law continued
    from the equivalent time of its volume at row ``a`` (theory §7) at the run's power, the
    obstacle's volume constant when it does not wear. None for a wearing obstacle whose
    coefficients are not known."""
    if law.linear_in_time:
        return lambda s: (vm[a] + s * (vm[b] - vm[a]), vo[a] + s * (vo[b] - vo[a]))
    if vo[b] != vo[a] and obstacle_coefficients is None:
        return None
    span = (t[b] - t[a]) * time_scale  # [s]
    mobile = dict(coefficients or {})
    start_m = float(law.equivalent_time(vm[a], p[b], **mobile))
    if vo[b] == vo[a]:
        def obstacle(s):
            return vo[a]
    else:
        other = dict(obstacle_coefficients)
        start_o = float(law.equivalent_time(vo[a], p[b], **other))

        def obstacle(s):
            return float(law.volume(p[b], start_o + s * span, **other))
    return lambda s: (float(law.volume(p[b], start_m + s * span, **mobile)), obstacle(s))
