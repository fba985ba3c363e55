"""The depth model: worn volumes and depth of a contact at any time, and the time to a depth.

:class:`DepthModel` holds what a wear table is computed from (law and coefficients, power,
contact geometry, time axis, volumes at the origin, a restart's earlier rows, a tube
replacement) and evaluates the worn depth of the mobile for arrays of inputs at once: a factor
on the wear coefficients, the wear power, the law's coefficients, at any times; and
:meth:`DepthModel.time_to`, the instant at which the tube in place reaches a depth (the one
meaning of "the time to a limit", docs/uncertainty.md §1). The wear table's ``limit_instant``,
the bundle's summary, the Monte Carlo propagation and the calibration on inspections all call
it; with its nominal inputs it gives the wear table's depths.

The volume of a body after ``t`` seconds from the origin, with wear-coefficient factor ``f``
(docs/uncertainty.md §1), is

* ``V₀ + f·Σ_j V_law(P_j, t)`` for a law linear in time (Archard, KWU-EPRI; one term, or one per
  sector when the global depth of a sector table is asked for),
* ``f·V_law(P, τ₀ + t)`` with ``f·V_law(P, τ₀) = V₀`` otherwise (EDF-MZ restart, docs/theory §7),

which is the law with every coefficient that multiplies the volume scaled by ``f`` (K for
Archard, k_r for KWU-EPRI, A and S together for EDF-MZ). The factor applies to both bodies.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings

import numpy as np

from fretwear.errors import InputError, KeywordError, RangeWarning
from fretwear.geometry.base import ContactGeometry
from fretwear.geometry.sectors import (
    SectorGeometry,
    SectorSlices,
    sector_depth_mobile,
    sector_slices,
    sector_volume_mobile,
)
from fretwear.laws.registry import WearLaw
from fretwear.table.case_values import Wall
from fretwear.table.depth_rows import EarlierRows
from fretwear.table.depth_terms import (
    SectorRelation,
    _check_initial,
    _dict,
    _float_of_shape,
    _geometry,
    _linear_volume,
    _rates,
    body_volume,
    given_names,
    initial_arrays,
)
from fretwear.table.limit import time_to_depth

__all__ = ["DepthModel", "SectorRelation", "body_volume", "given_names"]

_TIME_TOL = 1e-9


@dataclasses.dataclass(frozen=True, eq=False)
class DepthModel:
    """Worn depth of one contact, or of one angular sector of it, as a function of its inputs.

    Parameters
    ----------
    law : WearLaw
        The wear law (``fretwear.laws.WEAR_LAWS[...]``).
    geometry : ContactGeometry
        Contact geometry with its dimensions (SI, angles [deg]).
    powers : tuple of float
        Wear power of each volume term [W]: one term (the global power, or one sector's power),
        or one per sector for the global depth of a sector table (Archard only).
    coefficients_mobile, coefficients_obstacle : tuple of (dict or None)
        Law coefficients of each term (native names); None: the body does not wear.
    time_scale : float
        Seconds per user time unit [s].
    origin : float
        Origin of the run [user time unit]; times are counted from it.
    initial_mobile, initial_obstacle : float
        Volumes of the bodies at the origin [m³] (global, or of the sector).
    sector_arc : float, optional
        Angular extent of the sector [deg]; None for the global depth.
    name : str
        Contact name (and sector) for messages.
    sector : int, optional
        1-based sector number.
    wall : Wall
        The tube's wall: its thickness [m] (None: not known) and depth limit [-] (a fraction
        of the wall, default 0.4), as the case carries it (:attr:`WearCase.wall`, checked once
        where it was built; not checked again here).
    replacement : float, optional
        Seconds after the origin at which a new tube is put in (TUBE_NEUF) [s].
    rows : EarlierRows or callable, optional
        A restart's earlier rows (the global depth's), or a function that makes them at their
        first use (:attr:`earlier`).
    sector_arcs : tuple of float, optional
        The angular extent of each term's sector [deg], when the terms are a sector table's
        sectors (:meth:`sector_table`, :meth:`sector_time_to`).
    term_initial : (tuple of float, tuple of float), optional
        Volumes of each term at the origin (mobile, obstacle) [m³] (default: all in the first).
    sector_rows : tuple of (EarlierRows or None), or callable, optional
        A restart's earlier rows of each sector (its sector depth and cumulated volume), or a
        function that makes them at their first use (:attr:`earlier_sectors`).
    sector_obstacle_radius : float, optional
        Bore radius of the obstacle for the sector depths [m] (RAYON_OBST, theory §3), when the
        contact type's geometry has none (a flat bar); default the geometry's.

    Examples
    --------
    Archard, TUBE_BAV without tilt: D = (1/(2R))^(1/3)·(3V/(4l))^(2/3) with V = f·K·P·t.

    >>> from fretwear.laws import get_law
    >>> from fretwear.geometry import contact_geometry
    >>> m = DepthModel(law=get_law("ARCHARD"),
    ...                  geometry=contact_geometry("TUBE_BAV", mobile_radius=0.01,
    ...                                            obstacle_width=0.02),
    ...                  powers=(0.01,), coefficients_mobile=({"coefficient": 1e-14},),
    ...                  coefficients_obstacle=(None,), time_scale=3.15e7)
    >>> d = m.depth(3.15e7, factor=[1.0, 8.0])
    >>> round(float(d[1] / d[0]), 12)  # 8^(2/3)
    4.0
    """

    law: WearLaw
    geometry: ContactGeometry | SectorGeometry
    powers: tuple[float, ...]
    coefficients_mobile: tuple[dict | None, ...]
    coefficients_obstacle: tuple[dict | None, ...]
    time_scale: float = 1.0
    origin: float = 0.0
    initial_mobile: float = 0.0
    initial_obstacle: float = 0.0
    sector_arc: float | None = None
    name: str = ""
    sector: int | None = None
    wall: Wall = Wall()
    replacement: float | None = None
    rows: EarlierRows | None = None
    sector_arcs: tuple[float, ...] | None = None
    term_initial: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    sector_rows: tuple[EarlierRows | None, ...] | None = None
    sector_obstacle_radius: float | None = None

    def __post_init__(self) -> None:
        n = len(self.powers)
        if n == 0 or len(self.coefficients_mobile) != n or len(self.coefficients_obstacle) != n:
            raise InputError("DepthModel: give one power and one coefficient set per term")
        if n > 1 and not self.law.linear_in_time:
            raise KeywordError(f"several volume terms (sectors) need a law linear in time, not "
                               f"{self.law.name}: a wear case's sectors are Archard's, V_j = "
                               f"k_j·P_j·t (docs/theory.md §3); give one term")
        if not (math.isfinite(self.time_scale) and self.time_scale > 0):
            raise InputError(f"time_scale must be > 0 [s per unit], got {self.time_scale!r}")
        if self.replacement is not None and not (math.isfinite(self.replacement)
                                                 and self.replacement >= 0):
            raise InputError(f"replacement is the seconds after the origin of a tube "
                             f"replacement, >= 0 [s], got {self.replacement!r}")
        if not isinstance(self.wall, Wall):
            raise InputError(f"wall must be a Wall (fretwear.table.Wall(thickness [m], limit "
                             f"[-]), or a case's WearCase.wall), got {type(self.wall).__name__}")
        if self.term_initial is not None:  # checked once, where the model is built
            _check_initial(self.term_initial)

    @functools.cached_property
    def earlier(self) -> EarlierRows | None:
        """:attr:`rows`, made at the first use where it was given as a function that makes
        them (the wear table's model: read from the rows only for a time to a depth)."""
        return self.rows() if callable(self.rows) else self.rows

    @functools.cached_property
    def earlier_sectors(self) -> tuple[EarlierRows | None, ...] | None:
        """:attr:`sector_rows`, made at the first use (as :attr:`earlier`)."""
        return self.sector_rows() if callable(self.sector_rows) else self.sector_rows

    # ------------------------------------------------------------------ nominal values
    @property
    def power(self) -> float:
        """Total nominal wear power of the terms [W]."""
        return float(sum(self.powers))

    @property
    def limit_depth(self) -> float | None:
        """The depth limit [m] of the :attr:`wall` (limit × thickness), None without a
        thickness."""
        return self.wall.limit_depth

    def nominal(self, name: str, body: str = "mobile") -> float | None:
        """Nominal value of a law coefficient of ``body`` (one term only), None if absent."""
        coefs = (self.coefficients_mobile if body == "mobile" else self.coefficients_obstacle)[0]
        if coefs is None:
            return None
        value = coefs.get(name)
        return None if value is None else float(value)

    def with_dimensions(self, **dimensions: float) -> DepthModel:
        """The same model with other dimensions (SI, angles [deg]), validated."""
        geometry = _geometry(self.geometry.contact_type,
                             {**self.geometry.dimensions(), **dimensions})
        return dataclasses.replace(self, geometry=geometry)

    # ------------------------------------------------------------------ forward model
    def _terms(self, power, coefficients, obstacle_coefficients):
        powers = list(self.powers)
        if power is not None:
            power = np.asarray(power, dtype=float)
            if len(powers) == 1:
                powers = [power]
            else:
                total = self.power
                if total <= 0:
                    raise InputError("the nominal power is 0: it cannot be scaled per sector")
                powers = [p * (power / total) for p in powers]
        mobile = [_dict(c) for c in self.coefficients_mobile]
        obstacle = [_dict(c) for c in self.coefficients_obstacle]
        for given, body, coefs in ((coefficients, "mobile", mobile),
                                   (obstacle_coefficients, "obstacle", obstacle)):
            if not given:
                continue
            if len(coefs) > 1:
                raise KeywordError("coefficients of a sector table's global depth differ per "
                                   "sector: vary them through the wear-coefficient factor")
            if coefs[0] is None:
                raise KeywordError(f"the {body} does not wear in this case: it has no "
                                   f"coefficient {sorted(given)} to vary")
            resolved = self.law.resolve(**dict(given))
            coefs[0].update({k: resolved[k] for k in given_names(self.law, given)})
        return powers, mobile, obstacle

    def _body(self, elapsed, factor, powers, coefs, initial):
        if all(c is None for c in coefs):
            return np.broadcast_to(np.asarray(initial, dtype=float) + 0.0 * elapsed,
                                   np.broadcast(elapsed, factor).shape).astype(float)
        if self.law.linear_in_time:
            total = 0.0
            for p, c in zip(powers, coefs, strict=True):
                if c is not None:
                    total = total + self.law.volume(p, elapsed, **c)
            return initial + factor * total
        (p,), (c,) = powers, coefs
        if initial == 0.0:
            return factor * self.law.volume(p, elapsed, **c)
        return factor * self.law.cumulated_volume(initial / factor, p, elapsed, **c)

    def volumes(self, elapsed_s, *, factor=1.0, power=None, coefficients=None,
                obstacle_coefficients=None):
        """Cumulated volumes (mobile, obstacle) [m³] after ``elapsed_s`` [s] from the origin.

        Parameters
        ----------
        elapsed_s : array_like
            Time since the origin [s], ≥ 0 (after a :attr:`replacement`, the new tube's volume).
        factor : array_like
            Wear-coefficient factor f > 0 [-] (scales every body's new wear).
        power : array_like, optional
            Total wear power [W] (default the nominal; sector terms scale with it).
        coefficients, obstacle_coefficients : mapping, optional
            Law coefficients (native names or Code_Aster keywords) replacing the nominal ones,
            arrays allowed (one term only).

        Returns
        -------
        (numpy.ndarray, numpy.ndarray)
            V_m, V_o [m³], the broadcast shape of the arguments.
        """
        t = np.asarray(elapsed_s, dtype=float)
        f = np.asarray(factor, dtype=float)
        if not (np.isfinite(f) & (f > 0)).all():
            raise InputError("the wear-coefficient factor must be finite and > 0 [-]")
        if self.law.linear_in_time and power is None and not coefficients \
                and not obstacle_coefficients:  # V0 + f·r·t, the rates r computed once
            rate_m, rate_o = f * self.rates[0], f * self.rates[1]
            vm = _linear_volume(t, self.initial_mobile, rate_m)
            if self.replacement is not None:  # the new tube from its replacement on
                vm = np.where(t >= self.replacement, rate_m * (t - self.replacement), vm)
            vo = _linear_volume(t, self.initial_obstacle, rate_o)
        else:
            vm, vo = self._volumes(t, f, power, coefficients, obstacle_coefficients)
        shape = np.broadcast_shapes(np.shape(vm), np.shape(vo))
        return _float_of_shape(vm, shape), _float_of_shape(vo, shape)

    def _volumes(self, t, f, power, coefficients, obstacle_coefficients):
        """(V_m, V_o) [m³] of :meth:`volumes` through the law at every time."""
        powers, mobile, obstacle = self._terms(power, coefficients, obstacle_coefficients)
        vm = self._body(t, f, powers, mobile, self.initial_mobile)
        if self.replacement is not None:  # the new tube from its replacement on, unworn there
            fresh = self.replacement
            vm = np.where(t >= fresh, self._body(np.maximum(t - fresh, 0.0), f, powers, mobile,
                                                 0.0), vm)
        vo = self._body(t, f, powers, obstacle, self.initial_obstacle)
        return vm, vo

    @functools.cached_property
    def term_rates(self) -> tuple[np.ndarray, np.ndarray]:
        """(tube, obstacle) worn volume per second of each term at the nominal inputs [m³/s]
        of a law linear in time (0 for a body that does not wear)."""
        if not self.law.linear_in_time:
            raise KeywordError(f"the {self.law.name} law is not linear in time: no rate")
        return (_rates(self.law, self.powers, self.coefficients_mobile),
                _rates(self.law, self.powers, self.coefficients_obstacle))

    @functools.cached_property
    def rates(self) -> tuple[float, float]:
        """(tube, obstacle) :attr:`term_rates` summed over the terms [m³/s]."""
        return tuple(float(np.cumsum(r)[-1]) for r in self.term_rates)

    def depth(self, elapsed_s, *, factor=1.0, power=None, coefficients=None,
              obstacle_coefficients=None, warn: bool = True) -> np.ndarray:
        """Worn depth of the mobile [m] (global, or of the sector) after ``elapsed_s`` [s].

        Same inputs as :meth:`volumes`. NaN beyond the geometric relation's range (with a
        RangeWarning when ``warn``).
        """
        vm, vo = self.volumes(elapsed_s, factor=factor, power=power, coefficients=coefficients,
                              obstacle_coefficients=obstacle_coefficients)
        with warnings.catch_warnings():
            if not warn:
                warnings.simplefilter("ignore", RangeWarning)
            if self.sector_arc is None:
                dm, _ = self.geometry.depth_from_volume(vm.ravel(), vo.ravel())
            else:
                g = self.geometry
                dm = sector_depth_mobile(vm.ravel(), g.mobile_radius, g.obstacle_width,
                                         self.sector_arc)
        return np.asarray(dm, dtype=float).reshape(vm.shape)

    # ------------------------------------------------------------------ the wear table
    def table_columns(self, elapsed_s: np.ndarray) -> dict[str, np.ndarray]:
        """The wear table's volume and depth columns at ``elapsed_s`` [s] after the origin
        (one term: a table without sectors), at the nominal inputs.

        ``volume_mobile``, ``volume_obstacle`` [m³]: V₀ + r·t for a law linear in time
        (:meth:`volumes`, the rates :attr:`rates` computed once: the law's V(P, t) = r·t),
        otherwise each body's law at every time from its volume at the origin
        (:func:`body_volume`; the law's warnings name the body); the tube's from 0 at a
        :attr:`replacement`. ``depth_mobile``, ``depth_obstacle`` [m] from them
        (:meth:`body_depths`).
        """
        if self.law.linear_in_time:
            vm, vo = self.volumes(elapsed_s)
        else:
            (p,), (cm,), (co,) = self.powers, self.coefficients_mobile, \
                self.coefficients_obstacle
            vm = body_volume(self.law, p, cm, elapsed_s, self.initial_mobile, self.replacement,
                             "mobile")
            vo = body_volume(self.law, p, co, elapsed_s, self.initial_obstacle, None,
                             "obstacle")
        dm, do = self.body_depths(vm, vo)
        return {"volume_mobile": vm, "volume_obstacle": vo, "depth_mobile": dm,
                "depth_obstacle": do}

    def body_depths(self, volume_mobile: np.ndarray, volume_obstacle: np.ndarray):
        """(mobile, obstacle) global depths [m] from the cumulated volumes [m³] (theory §6).

        An obstacle without volume has no depth: exactly 0 where the mobile's depth is defined
        (the split d_o = D − D·V_m/V of a shared trace leaves a rounding residue otherwise).
        """
        dm, do = self.geometry.depth_from_volume(volume_mobile, volume_obstacle)
        shape = volume_mobile.shape
        dm, do = _float_of_shape(dm, shape), _float_of_shape(do, shape)
        return dm, np.where((volume_obstacle == 0) & np.isfinite(dm), 0.0, do)

    def sector_table(self, elapsed_s: np.ndarray):
        """Each sector's cumulated volumes and depths at ``elapsed_s`` [s] (a sector table's
        terms, :attr:`sector_arcs`; theory §3): arrays (times, sectors).

        Returns
        -------
        dict
            ``volume_mobile``, ``volume_obstacle`` [m³] (V0_j + V(P_j, t), the tube's from 0 at
            a replacement), ``depth_mobile``, ``depth_obstacle`` [m] (sector depths; the
            obstacle's NaN where it wears without an ``obstacle_radius``), and ``unradiused``,
            the sectors (1-based) of that case.
        """
        t = np.asarray(elapsed_s, dtype=float)[:, None]
        v0m, v0o = self._term_initial()  # checked where the model was built (__post_init__)
        rate_m, rate_o = self.term_rates  # V_j = V0_j + r_j·t: the law's V(P_j, t) = r_j·t
        vm = v0m + rate_m * t
        if self.replacement is not None:  # the new tube from its replacement on
            new = t[:, 0] >= self.replacement
            vm[new] = rate_m * (t[new] - self.replacement)
        slices = self.slices
        dm = slices.depth_mobile(vm)
        vo = v0o + rate_o * t
        if slices.obstacle_radius is None and not (
                # rate_o is 0 (:func:`_rates`) when no term's obstacle wears
                (any(c is not None for c in self.coefficients_obstacle) and rate_o.any())
                or v0o.any()):
            do, unradiused = np.zeros(vm.shape), []  # neither wears nor was worn: depths 0
        elif slices.obstacle_radius is None:
            do = np.where(vo == 0, 0.0, np.nan)
            unradiused = (np.flatnonzero((vo > 0).any(axis=0)) + 1).tolist()
        else:
            do, unradiused = slices.depth_obstacle(vo), []
        return {"volume_mobile": vm, "volume_obstacle": vo, "depth_mobile": dm,
                "depth_obstacle": do, "unradiused": unradiused}

    @functools.cached_property
    def slices(self) -> SectorSlices:
        """The sectors' depth-volume relations (theory §3) of :attr:`sector_arcs` (a sector
        table's terms; the bore radius :attr:`sector_obstacle_radius`, else the geometry's),
        their dimensions checked once per set of dimensions
        (:func:`~fretwear.geometry.sectors.sector_slices`)."""
        g = self.geometry
        r_o = self.sector_obstacle_radius
        if r_o is None:
            r_o = getattr(g, "obstacle_radius", None)
        arcs = self.sector_arcs  # a case model's tuple of floats: equal numbers, equal keys
        if type(arcs) is not tuple:
            arcs = tuple(float(a) for a in arcs)
        return sector_slices(g.mobile_radius, g.obstacle_width, arcs, r_o)

    def _term_initial(self) -> tuple[np.ndarray, np.ndarray]:
        """Each term's (mobile, obstacle) volumes at the origin [m³]."""
        n = len(self.powers)
        if self.term_initial is not None:
            return initial_arrays(self.term_initial)
        out = np.zeros((2, n))
        out[:, 0] = self.initial_mobile, self.initial_obstacle
        return out[0], out[1]

    def sector_time_to(self, depth) -> np.ndarray:
        """The instant [user time unit] at which each sector's tube depth first reaches
        ``depth`` [m]: :meth:`time_to`'s meaning sector by sector (a restart's earlier rows of
        the sector included, :attr:`sector_rows`; only the new tube after a replacement).

        From the origin, the sector's volume V0_j + r_j·t inverted in closed form through
        V = l·Δθ·d·(2R − d)/2 (:func:`~fretwear.geometry.sectors.sector_volume_mobile`,
        theory §3); ``inf`` where the sector does not wear. ``depth`` a float: one instant a
        sector (m,); an array of k depths: (k, m).
        """
        g = self.geometry
        arcs = np.asarray(self.sector_arcs, dtype=float)
        target = np.asarray(depth, dtype=float)
        d = np.minimum(target, g.mobile_radius)[..., None]
        volume = self.slices.volume_mobile(d)
        rate = self.term_rates[0]
        v0 = np.zeros(arcs.size) if self.replacement is not None else self._term_initial()[0]
        t = _seconds_to(volume, v0, rate)
        if self.replacement is not None:
            t = self.replacement + t
        out = self.origin + t / self.time_scale
        if self.earlier_sectors is not None and self.replacement is None:
            flat = out.reshape(-1, arcs.size)
            targets = np.atleast_1d(target).tolist()
            for j, rows in enumerate(self.earlier_sectors):
                if rows is not None:
                    found = rows.times(targets, SectorRelation(g, float(arcs[j])))
                    for i, value in enumerate(targets):
                        flat[i, j] = found.get(value, flat[i, j])
        return out

    def time_to(self, depth, *, factor=1.0, power=None, coefficients=None,
                obstacle_coefficients=None, rtol: float = 1e-12):
        """The instant [user time unit] at which the tube in place first reaches ``depth`` [m].

        The one meaning of "the time to a limit" (docs/uncertainty.md §1): the first instant
        at which the tube in place reaches the depth, over every row of its table, a restart's
        earlier rows included.

        * Among a restart's earlier rows (:attr:`rows`, the tube's known history up to the
          origin; their law not known to this run): through the geometry, the volume linear in
          time between the two rows that bracket the depth
          (:func:`fretwear.table.depth_rows.earlier_rows_time`; the depth interpolated between
          the rows where the geometry or the volumes are not known).
        * From the origin on: depth(t) through the law and the geometry, inverted in closed
          form for a law linear in time whose tube depth is a function of the tube's volume
          (t = (V(d) − V₀)/(f·Σ r_j), V(d) from the geometry's ``volume_from_depth``), else by
          the bracketed solver (:func:`fretwear.table.limit.time_to_depth`, to ``rtol`` on t).
        * After a tube replacement in this run (:attr:`replacement`) only the new tube counts:
          its time from the replacement, unworn there.

        Non-decreasing in ``depth``; the origin where the depth is reached there (and not
        among earlier rows), ``inf`` where it is never reached (no wear, a power of 0).

        Parameters
        ----------
        depth : float or array_like
            Depths to reach [m], > 0.
        factor, power, coefficients, obstacle_coefficients
            As :meth:`volumes` (arrays broadcast with ``depth``).
        rtol : float
            Relative tolerance on the time of the bracketed solver.

        Returns
        -------
        float or numpy.ndarray
            Instants [user time unit], the broadcast shape of the inputs.

        Examples
        --------
        >>> from fretwear.laws import get_law
        >>> from fretwear.geometry import contact_geometry
        >>> g = contact_geometry("TUBE_ALESAGE", mobile_radius=0.01, obstacle_width=0.02)
        >>> m = DepthModel(law=get_law("ARCHARD"), geometry=g, powers=(0.01,),
        ...                coefficients_mobile=({"coefficient": 1e-14},),
        ...                coefficients_obstacle=(None,))
        >>> t = m.time_to(1e-4)  # uniform wear: V = 2π·l·R·d = K·P·t
        >>> round(float(t) / (2 * np.pi * 0.02 * 0.01 * 1e-4 / 1e-16), 10)
        1.0
        """
        target, kw = self._broadcast(depth, factor, power, coefficients, obstacle_coefficients)
        elapsed = self._closed_form(target, kw)
        if elapsed is None:
            elapsed = self._solved(target, kw, rtol)
        out = self.origin + elapsed / self.time_scale
        if self.earlier is not None and self.replacement is None:
            found = self.earlier.times(np.unique(target), self.geometry)
            for value, instant in found.items():
                out = np.where(target == value, instant, out)
        return out if out.ndim else float(out)

    def time_to_depth(self, depth, **inputs) -> np.ndarray:
        """Seconds after the origin [s] of :meth:`time_to` (negative where the depth is
        reached among a restart's earlier rows)."""
        return (np.asarray(self.time_to(depth, **inputs), dtype=float) - self.origin) \
            * self.time_scale

    def _broadcast(self, depth, factor, power, coefficients, obstacle_coefficients):
        """(targets [m], keyword arguments of :meth:`depth`), broadcast to one shape."""
        target = np.asarray(depth, dtype=float)
        if power is None and not coefficients and not obstacle_coefficients \
                and np.ndim(factor) == 0:  # the nominal inputs and one factor: the depths' shape
            if not (np.isfinite(target) & (target > 0)).all():
                raise InputError(f"the depth to reach must be finite and > 0 [m], got {depth!r}")
            return target, {"factor": float(factor), "power": None, "coefficients": None,
                            "obstacle_coefficients": None}
        shape = np.broadcast_shapes(target.shape, np.shape(factor), np.shape(power)
                                    if power is not None else (),
                                    *[np.shape(v) for v in (coefficients or {}).values()],
                                    *[np.shape(v) for v in (obstacle_coefficients or {}).values()])
        target = np.broadcast_to(target, shape).astype(float)
        if not (np.isfinite(target) & (target > 0)).all():
            raise InputError(f"the depth to reach must be finite and > 0 [m], got {depth!r}")

        def spread(values):
            return {k: np.broadcast_to(np.asarray(v, dtype=float), shape)
                    for k, v in values.items()}

        kw = {"factor": np.broadcast_to(np.asarray(factor, dtype=float), shape),
              "power": None if power is None else np.broadcast_to(
                  np.asarray(power, dtype=float), shape),
              "coefficients": spread(coefficients) if coefficients else None,
              "obstacle_coefficients": (spread(obstacle_coefficients)
                                        if obstacle_coefficients else None)}
        return target, kw

    def _closed_form(self, target, kw) -> np.ndarray | None:
        """Seconds after the origin [s] at which the depth reaches ``target`` in closed form:
        a law linear in time at the nominal power and coefficients whose tube depth is a
        function of the tube's volume (the obstacle's volume stays 0, or does not enter it);
        None otherwise."""
        if not self.law.linear_in_time or kw["power"] is not None or kw["coefficients"] \
                or kw["obstacle_coefficients"]:
            return None
        if not (self.sector_arc is not None or self.geometry.mobile_depth_alone
                or not (self.initial_obstacle or self.rates[1])):
            return None
        volume = self._volume_of(target)
        if not np.isfinite(volume).all():  # a target beyond the relation's range
            return None
        rate = kw["factor"] * self.rates[0]
        v0 = 0.0 if self.replacement is not None else self.initial_mobile
        t = _seconds_to(volume, v0, rate)
        return t if self.replacement is None else self.replacement + t

    def _volume_of(self, target) -> np.ndarray:
        """The tube's worn volume [m³] of the depths ``target`` [m] (the obstacle's 0)."""
        g = self.geometry
        if self.sector_arc is not None:  # V = l·Δθ·d·(2R − d)/2 (theory §3)
            d = np.minimum(target, g.mobile_radius)
            return np.asarray(sector_volume_mobile(d, g.mobile_radius, g.obstacle_width,
                                                   self.sector_arc), dtype=float)
        return g.mobile_volume(target)  # the targets are > 0 and finite (_broadcast)

    def _solved(self, target, kw, rtol: float) -> np.ndarray:
        """Seconds after the origin [s] by the bracketed solver on depth(t)."""
        start = 0.0 if self.replacement is None else self.replacement
        found = time_to_depth(lambda t: self.depth(start + t, warn=False, **kw), target,
                              first_guess=self.time_scale, rtol=rtol)
        return start + np.asarray(found, dtype=float)


def _seconds_to(volume, v0, rate) -> np.ndarray:
    """Seconds [s] for a volume growing from ``v0`` [m³] at ``rate`` [m³/s] to reach
    ``volume`` [m³]: (V − V0)/r, 0 where V0 already reaches it, inf where the body does not
    wear (r not > 0), without a division by zero (the closed forms of
    :meth:`DepthModel.time_to` and :meth:`DepthModel.sector_time_to`).

    >>> _seconds_to(np.array([2.0, 2.0, 2.0]), np.array([0.0, 3.0, 0.0]), np.array([1.0, 1.0, 0.0]))
    array([ 2.,  0., inf])
    """
    rate = np.asarray(rate, dtype=float)
    wears = rate > 0  # NaN or <= 0: never (inf)
    # (V - V0)/r where r > 0, divided by 1 elsewhere (discarded): no division by zero, and the
    # same quotients as a masked division (one ufunc call fewer on a table's few values)
    t = (np.subtract(volume, v0) / np.where(wears, rate, 1.0))
    return np.where(np.greater_equal(v0, volume), 0.0, np.where(wears, t, np.inf))
