"""The instant at which a contact's global depth reaches a limit, for :meth:`BundleResult.summary`.

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
* **interpolated** (:data:`INTERPOLATED`, the fallback where the geometry or the law is not
  known, and for a law not linear in time with sectors or a depth of both volumes): depth(t)
  by a monotone cubic between the instants, inverted (:func:`time_to_depth`).

Times are in the contact's time unit (the table's ``instant``); ``time_scale`` [s per unit].
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from fretwear.geometry import contact_geometry
from fretwear.laws import WEAR_LAWS

#: How the time to reach the limit was found, in :meth:`BundleResult.summary`.
INTERPOLATED = ("interpolated: depth(t) between the table's instants by a monotone cubic "
                "(PCHIP), from depth 0 at the origin of a new tube (the contact's geometry or "
                "law not known, or a law not linear in time with sectors)")
FROM_TABLE = ("the wear table's limit_instant (law and geometry inverted for the case's limit), "
              "where reached by the last instant")
FROM_VOLUME = ("exact: the limit depth inverted through the contact's geometry to a worn "
               "volume, the volume linear in time between the table's instants (a law linear "
               "in time at the run's power), from the tube's volume at its origin")
FROM_LAW = ("exact: the limit depth inverted through the contact's geometry to a worn volume, "
            "that volume to a time through the law's equivalent time at the run's power (a law "
            "not linear in time)")
#: The methods named in ``summary().attrs["time_to_limit"]``.
METHODS = (FROM_TABLE, FROM_VOLUME, FROM_LAW, INTERPOLATED)


def time_to_depth(instants: np.ndarray, depths: np.ndarray, target: float, *,
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
    >>> round(time_to_depth(t, d, 2.5e-4), 9)
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
                 time_scale: float | None = 1.0) -> str | None:
    """The exact method :func:`time_to_limit` uses for a contact (:data:`FROM_VOLUME` or
    :data:`FROM_LAW`), or None where it interpolates: the geometry or the law not known, no
    volume column, or a law not linear in time with sectors or without a time scale."""
    if geometry is None or law is None or not volumes:
        return None
    if law.linear_in_time:
        return FROM_VOLUME
    return None if sectors or not time_scale else FROM_LAW


def time_to_limit(instants, depths, target: float, *, origins, replaced: float | None,
                  volume_mobile=None, volume_obstacle=None, powers=None, geometry=None,
                  law=None, coefficients=None, time_scale: float | None = None,
                  sectors: bool = False) -> tuple[float, str]:
    """The instant at which a contact's global depth first reaches ``target``, and the method.

    Parameters
    ----------
    instants : array
        The contact's instants, one per row, increasing [table time unit].
    depths, volume_mobile, volume_obstacle, powers : array
        At those instants: the global tube depth ``depth_mobile`` [m], the cumulated worn
        volumes of the tube and the obstacle [m³], the run's wear power [W].
    target : float
        Depth to reach [m].
    origins : array or None
        The rows' ``origin`` [table time unit] (None: 0): a first row of origin 0 is a new
        tube's (its volumes 0 at instant 0); otherwise the first row is an initial table's,
        holding the volumes at its instant.
    replaced : float or None
        Instant of a tube replacement [table time unit] (the new tube's volume is 0 there).
    geometry : ContactGeometry, optional
        The contact's geometry (:func:`fretwear.geometry.contact_geometry`).
    law : WearLaw, optional
        Its wear law; ``coefficients`` the tube's coefficients, ``time_scale`` [s per unit]
        (for a law not linear in time).
    sectors : bool
        The table has sectors (a law not linear in time then sums the sectors' laws: not the
        law at the global power).

    Returns
    -------
    (float, str)
        The instant (NaN when not reached by the last instant) and the method:
        :data:`FROM_VOLUME`, :data:`FROM_LAW` or :data:`INTERPOLATED` (module docstring).
    """
    t = np.asarray(instants, dtype=float)
    d = np.asarray(depths, dtype=float)
    origins = np.zeros_like(t) if origins is None else np.asarray(origins, dtype=float)
    method = exact_method(geometry, law, sectors=sectors, volumes=volume_mobile is not None,
                          time_scale=time_scale)
    if method is not None:
        origin = float(origins[0]) if origins.size else 0.0
        found = _through_volume(t, d, np.asarray(volume_mobile, dtype=float),
                                np.zeros_like(t) if volume_obstacle is None
                                else np.nan_to_num(np.asarray(volume_obstacle, dtype=float)),
                                np.zeros_like(t) if powers is None
                                else np.asarray(powers, dtype=float),
                                target, origin, replaced, geometry, law, coefficients,
                                time_scale)
        if found is not None:
            return found, method
    if replaced is not None:
        keep = t >= replaced
        t, d, origins = t[keep], d[keep], origins[keep]
    origin = float(origins[0]) if origins.size else 0.0
    return time_to_depth(t, d, target, from_zero=origin == 0), INTERPOLATED


def _through_volume(t, d, vm, vo, p, target, origin, replaced, geometry, law, coefficients,
                    time_scale) -> float | None:
    """:func:`time_to_limit` through the volume; None where it cannot invert (a law not linear
    in time whose tube depth needs the obstacle's volume too, a volume out of the relation's
    range)."""
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
            vo_r = float(np.interp(replaced, t, vo)) if t.size else 0.0
            t = np.concatenate(([replaced], t[after]))
            d, vm = np.concatenate(([0.0], d[after])), np.concatenate(([0.0], vm[after]))
            vo, p = np.concatenate(([vo_r], vo[after])), np.concatenate((p[after][:1], p[after]))
        else:
            t, d, vm, vo, p = t[after], d[after], vm[after], vo[after], p[after]
    drops = np.flatnonzero(vm[1:] < vm[:-1])  # a tube replaced in the initial table
    if drops.size:
        s = slice(int(drops[-1]) + 1, None)
        t, d, vm, vo, p = t[s], d[s], vm[s], vo[s], p[s]
    hit = np.flatnonzero(d >= target)  # NaN (beyond the relation's range) never counts
    if not hit.size:
        return math.nan
    b = int(hit[0])
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
        elif law.linear_in_time:  # the depth of both volumes, each linear along the segment
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
        else:
            return None
    if not math.isfinite(fraction):
        return None
    return float(t[a] + min(max(fraction, 0.0), 1.0) * (t[b] - t[a]))
