"""The volume terms of a :class:`~fretwear.table.DepthModel`: the volume of one body through
its law (:func:`body_volume`), the volume rates of a law linear in time, a sector's tube
depth-volume relation (:class:`SectorRelation`, theory §3), the geometry of a case and the native
names of given coefficients. Split out of :mod:`fretwear.table.depth`; no behaviour of its own.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.geometry.sectors import sector_geometry, sector_volume_mobile
from fretwear.laws.registry import WearLaw

__all__ = ["SectorRelation", "body_volume", "given_names"]


def _dict(value) -> dict | None:
    return None if value is None else dict(value)


def _linear_volume(t, v0, rate):
    """V0 + r·t [m³] (exactly r·t where V0 = 0)."""
    v = rate * t
    return v if v0 == 0.0 else v0 + v


def _float_of_shape(values, shape) -> np.ndarray:
    """A float copy of ``values`` broadcast to ``shape`` (a plain copy when they have that
    shape already)."""
    if type(values) is np.ndarray and values.shape == shape:
        return values.astype(float)
    return np.broadcast_to(values, shape).astype(float)


def _relabelled(caught, body: str, stacklevel: int) -> None:
    """The law's warnings ``caught`` again, naming the body."""
    for w in caught:
        warnings.warn(f"{body}: {w.message}", w.category, stacklevel=stacklevel + 1)


def body_volume(law, power: float, coefficients, elapsed_s: np.ndarray, previous: float,
                fresh_s: float | None, body: str, stacklevel: int = 6) -> np.ndarray:
    """Cumulated volume of one body at ``elapsed_s`` seconds after the origin [m³].

    ``previous`` is the body's volume at the origin [m³]; a linear law adds ``V(P, Δt)``,
    another law continues from its equivalent time (theory §7). ``fresh_s`` (a replacement,
    seconds after the origin) restarts the body from zero there. ``coefficients`` None: the
    body does not wear. The law's warnings name the body.
    """
    if coefficients is None:  # this body does not wear
        out = np.full(elapsed_s.shape, float(previous))
        if fresh_s is not None:
            out[elapsed_s >= fresh_s] = 0.0
        return out
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if previous == 0.0:
            out = np.asarray(law.volume(power, elapsed_s, **coefficients), dtype=float)
        else:  # linear: V0 + V(Δt); otherwise from the equivalent time of V0 (theory §7)
            out = np.asarray(law.cumulated_volume(previous, power, elapsed_s, **coefficients),
                             dtype=float)
        out = np.broadcast_to(out, elapsed_s.shape).copy()
        if fresh_s is not None:
            new = elapsed_s >= fresh_s
            out[new] = np.asarray(law.volume(power, elapsed_s[new] - fresh_s,
                                             **coefficients), dtype=float)
    _relabelled(caught, body, stacklevel)
    return out


class SectorRelation:
    """The tube's depth-volume relation of one sector (theory §3), as
    :func:`~fretwear.table.depth_rows.earlier_rows_time` asks of a geometry: the tube's depth
    is a function of its own volume, V = l·Δθ·d·(2R − d)/2."""

    mobile_depth_alone = True
    contact_type = "sector"

    def __init__(self, geometry, arc_deg: float):
        self.radius, self.width, self.arc = geometry.mobile_radius, geometry.obstacle_width, \
            arc_deg

    def volume_from_depth(self, depth_mobile, depth_obstacle=0.0):
        """(tube volume [m³], 0) of the sector depth ``depth_mobile`` [m]."""
        v = sector_volume_mobile(depth_mobile, self.radius, self.width, self.arc)
        return np.asarray(v, dtype=float), 0.0


def _plain(coefficients) -> bool:
    """Whether a term's coefficients are given, each a plain float."""
    return coefficients is not None and all(type(v) is float for v in coefficients.values())


def _rates(law, powers, coefficients) -> np.ndarray:
    """Volume per second [m³/s] of each term of a law linear in time (0 where the body does
    not wear; :meth:`~fretwear.laws.WearLaw.rate`, its warnings dropped: the table's own volumes
    already warned), every term in one call of the law where they share their coefficients or
    their coefficients' names."""
    if all(c is None for c in coefficients):  # any sequence (a DepthModel's, the user's)
        return np.zeros(len(powers))
    if len(powers) == 1:  # one term (a table without sectors)
        return np.array([float(law.rate(float(powers[0]), **coefficients[0]))])
    first = coefficients[0]
    if _plain(first) and (len(set(map(id, coefficients))) == 1  # one dict for all
                          or all(c is first or (_plain(c) and c == first)
                                 for c in coefficients)):
        given = first  # the law's numbers in every sector (one dict for all: no check each)
    else:
        names = {tuple(sorted(c)) for c in coefficients if c is not None}
        if len(names) != 1 or any(c is None for c in coefficients):
            return np.array([0.0 if c is None else float(law.rate(float(p), **c))
                             for p, c in zip(powers, coefficients, strict=True)])
        given = {k: np.array([c[k] for c in coefficients]) for k in next(iter(names))}
    rates = np.asarray(law.rate(np.asarray(powers, dtype=float), **given), dtype=float)
    if rates.shape != (len(powers),):
        rates = np.broadcast_to(rates, (len(powers),))
    return rates.astype(float)  # a new array (the law's result is never handed out)


def initial_arrays(term_initial) -> tuple[np.ndarray, np.ndarray]:
    """The terms' (mobile, obstacle) volumes at the origin [m³] of a
    :attr:`DepthModel.term_initial` as float arrays; a tuple of tuples (immutable) made once,
    kept by identity (a bundle's contacts of one case share theirs; an equal tuple may differ
    in the sign of a zero), read-only."""
    found = _INITIAL.get(id(term_initial))
    if found is not None and found[0] is term_initial:
        return found[1]
    pm, po = (np.asarray(v, dtype=float) for v in term_initial)
    if type(term_initial) is tuple and all(type(v) is tuple for v in term_initial):
        pm.flags.writeable = po.flags.writeable = False
        if len(_INITIAL) >= 64:
            _INITIAL.clear()
        _INITIAL[id(term_initial)] = (term_initial, (pm, po))  # the key's object kept alive
    return pm, po


#: :func:`initial_arrays` by the id of their tuple (the tuple kept beside them).
_INITIAL: dict = {}


def _check_initial(term_initial) -> None:
    """:attr:`DepthModel.term_initial`'s volumes finite and >= 0 [m³], else an InputError;
    a tuple found good is remembered (the same tuples for a case's every contact)."""
    try:
        if term_initial in _GOOD_INITIAL:
            return
    except TypeError:  # not hashable (lists): checked each time
        pass
    for name, v0 in zip(("mobile", "obstacle"), term_initial, strict=True):
        if not all(math.isfinite(v) and v >= 0 for v in v0):
            raise InputError(f"the initial state's sector volumes of the {name} must "
                             f"be finite and >= 0 [m³], got {[float(v) for v in v0]}")
    if type(term_initial) is tuple and all(type(v) is tuple for v in term_initial):
        if len(_GOOD_INITIAL) >= 64:
            _GOOD_INITIAL.clear()
        _GOOD_INITIAL.add(term_initial)


#: :attr:`DepthModel.term_initial` values found good by :func:`_check_initial`.
_GOOD_INITIAL: set = set()


def _geometry(contact_type: str | None, dimensions: Mapping[str, float]):
    """The contact geometry, or the sector geometry of a case without contact type."""
    if contact_type is None:
        return sector_geometry(**dict(dimensions))
    return contact_geometry(contact_type, **dict(dimensions))


def given_names(law: WearLaw, given: Mapping[str, Any]) -> list[str]:
    """Native names of the coefficients in ``given`` (Code_Aster keywords translated)."""
    by_keyword = {kw: p for p, kw in law.aster_keywords.items()}
    return [by_keyword.get(k, k) for k in given]
