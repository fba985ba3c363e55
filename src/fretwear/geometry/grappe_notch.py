"""Control-rod against the notch(es) of a guide card: GRAPPE_1_ENCO and GRAPPE_2_ENCO (theory §6).

A rodlet of the control-rod cluster (outer diameter 9.7 mm) slides in the notch of a guide card
(bore diameter 10.5 mm). The worn section of the rod is an empirical cubic of its depth, fitted on
feedback from the field (Lina & Zbinden 1995, cited by Code_Aster R7.20.01 §4.2-§4.3):

    V_m / l = A·d_m³ + B·d_m² + C·d_m        (d_m in mm, V_m / l in mm²)

with (A, B, C) = (−2.76, 10.30, 0.83) for one notch and (−5.52, 20.60, 1.66) for two diametrically
opposite notches (exactly twice: two identical traces). The card wears as
V_o = κ·π·l·R_o·d_o with κ = 0.47 (one notch) or 0.94 (two notches).

The cubic only rises up to its maximum (d ≈ 2.53 mm); a volume beyond the maximum area has no depth
on the rising branch: the depth is NaN there and a :class:`~fretwear.errors.RangeWarning` says so.
The polynomial holds only for the 9.7 mm rod in the 10.5 mm card: other radii get a RangeWarning.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import ClassVar

import numpy as np

from fretwear.errors import InputError, RangeWarning
from fretwear.geometry.base import ContactGeometry

__all__ = [
    "CALIBRATION_MOBILE_RADIUS",
    "CALIBRATION_OBSTACLE_RADIUS",
    "NOTCH_LAWS",
    "Grappe1Enco",
    "Grappe2Enco",
    "notch_area",
    "notch_depth",
    "notch_depth_limit",
    "notch_obstacle_volume",
]

#: Empirical notch laws, keyed by Code_Aster contact type: cubic coefficients (A, B, C) of
#: V_m/l [mm²] in d_m [mm], obstacle factor κ [-], number of notches. Source: Code_Aster
#: R7.20.01 §4.2-§4.3 (Lina & Zbinden 1995); D_m = 0 in both.
NOTCH_LAWS: dict[str, dict] = {
    "GRAPPE_1_ENCO": {"coefficients": (-2.76, 10.30, 0.83), "kappa": 0.47, "notches": 1},
    "GRAPPE_2_ENCO": {"coefficients": (-5.52, 20.60, 1.66), "kappa": 0.94, "notches": 2},
}

#: Rod outer radius [m] and card bore radius [m] the polynomials were fitted for (9.7 / 10.5 mm
#: diameters, Code_Aster R7.20.01 §4.2-§4.3).
CALIBRATION_MOBILE_RADIUS = 9.7e-3 / 2.0
CALIBRATION_OBSTACLE_RADIUS = 10.5e-3 / 2.0
#: Relative difference of a user radius from the calibration radius above which we warn.
RADIUS_TOLERANCE = 1e-3

_MM = 1e-3   # m per mm
_MM2 = 1e-6  # m² per mm²


def _law(contact_type: str) -> dict:
    try:
        return NOTCH_LAWS[contact_type]
    except KeyError:
        raise InputError(
            f"unknown notch contact type {contact_type!r}; use one of {sorted(NOTCH_LAWS)}"
        ) from None


def notch_depth_limit(contact_type: str) -> float:
    """Depth [m] at the maximum of the notch polynomial: the end of its rising branch.

    Parameters
    ----------
    contact_type : str
        ``"GRAPPE_1_ENCO"`` or ``"GRAPPE_2_ENCO"``.

    Returns
    -------
    float
        d_max [m], the positive root of the derivative 3A·d² + 2B·d + C = 0.

    Notes
    -----
    With A < 0 < C the derivative has one positive root,
    d_max = (−B − √(B² − 3AC)) / (3A) [mm]. Both notch laws share it (the two-notch coefficients are
    twice the one-notch ones): d_max = 2.5276 mm.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.2-§4.3.
    .. [3] Lina, A., & Zbinden, M. (1995). [Wear of control-rod rodlet cladding: relations between
           worn volume and wear depth]. EDF-DER report HT.22/95-06A (in French).

    Examples
    --------
    >>> round(notch_depth_limit("GRAPPE_1_ENCO") * 1e3, 4)
    2.5276
    """
    a, b, c = _law(contact_type)["coefficients"]
    return float((-b - np.sqrt(b * b - 3.0 * a * c)) / (3.0 * a)) * _MM


def notch_area(depth, contact_type: str) -> np.ndarray:
    """Worn section of the rod [m²] (V_m / l) for a rod depth [m], by the empirical cubic.

    Parameters
    ----------
    depth : array_like
        Worn depth of the rod d_m [m], ≥ 0.
    contact_type : str
        ``"GRAPPE_1_ENCO"`` or ``"GRAPPE_2_ENCO"``.

    Returns
    -------
    numpy.ndarray
        V_m / l [m²]; NaN where the depth is beyond the polynomial's maximum (see
        :func:`notch_depth_limit`; no warning here, the caller warns).

    Notes
    -----
    V_m / l = A·d³ + B·d² + C·d with d in mm and V_m / l in mm² (Code_Aster R7.20.01 §4.2-§4.3
    [2]_, from [3]_); converted here: area [m²] = 1e-6 · P(1e3 · d [m]).

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.2-§4.3.
    .. [3] Lina, A., & Zbinden, M. (1995). [Wear of control-rod rodlet cladding: relations
           between worn volume and wear depth]. EDF-DER report HT.22/95-06A (in French).

    Examples
    --------
    >>> float(notch_area(1e-3, "GRAPPE_1_ENCO") * 1e6)  # -2.76 + 10.30 + 0.83 mm²
    8.37
    """
    a, b, c = _law(contact_type)["coefficients"]
    d = np.asarray(depth, dtype=float) / _MM
    area = ((a * d + b) * d + c) * d * _MM2
    return np.where(d <= notch_depth_limit(contact_type) / _MM * (1 + 1e-15), area, np.nan)


def notch_depth(area, contact_type: str, rtol: float = 1e-13) -> np.ndarray:
    """Rod depth [m] for a worn section [m²]: the root of the cubic on its rising branch.

    Parameters
    ----------
    area : array_like
        Worn section of the rod V_m / l [m²], ≥ 0.
    contact_type : str
        ``"GRAPPE_1_ENCO"`` or ``"GRAPPE_2_ENCO"``.
    rtol : float
        Relative tolerance on the depth [-].

    Returns
    -------
    numpy.ndarray
        d_m [m] in [0, d_max]; NaN where the area exceeds the polynomial's maximum (no warning
        here, the caller warns).

    Notes
    -----
    P(d) = A·d³ + B·d² + C·d is increasing on [0, d_max] (P' > 0 there), so the root is unique and
    bracketed: safeguarded Newton iterations (a Newton step that leaves the current bracket is
    replaced by bisection), vectorised over all areas; a few areas (up to
    :data:`_SCALAR_AREAS`, a table's instants) take the same iterations element by element in
    Python floats (:func:`_notch_roots`: the same IEEE operations in the same order, the same
    bits, without numpy's cost per call).

    Examples
    --------
    >>> round(float(notch_depth(8.37e-6, "GRAPPE_1_ENCO")) * 1e3, 12)
    1.0
    """
    a, b, c = _law(contact_type)["coefficients"]
    y = np.asarray(area, dtype=float) / _MM2
    d_max = notch_depth_limit(contact_type) / _MM
    p_max = ((a * d_max + b) * d_max + c) * d_max
    flat = np.atleast_1d(y).astype(float).ravel()
    out = np.full(flat.shape, np.nan)
    out[flat == 0.0] = 0.0  # the root at zero: no iteration (bisection would leave it)
    ok = np.isfinite(flat) & (flat > 0.0) & (flat <= p_max)
    target = flat[ok]
    if target.size <= _SCALAR_AREAS:
        out[ok] = _notch_roots(target.tolist(), (a, b, c), d_max, rtol)
        return out.reshape(np.shape(y)) * _MM
    lo = np.zeros_like(target)
    hi = np.full_like(target, d_max)
    x = np.minimum(target / c, d_max)  # start from the linear (small-depth) guess
    converged = np.zeros(target.shape, dtype=bool)
    for _ in range(200):
        f = ((a * x + b) * x + c) * x - target
        lo = np.where(f <= 0.0, x, lo)
        hi = np.where(f > 0.0, x, hi)
        slope = (3.0 * a * x + 2.0 * b) * x + c
        with np.errstate(divide="ignore", invalid="ignore"):
            step = x - f / slope
        bad = ~np.isfinite(step) | (step < lo) | (step > hi)
        new = np.where(bad, 0.5 * (lo + hi), step)
        # converged elements (and exact roots, f = 0) keep their value
        new = np.where(converged | (f == 0.0), x, new)
        converged |= (np.abs(new - x) <= rtol * np.abs(new)) | (hi - lo <= rtol * hi)
        x = new
        if converged.all():
            break
    out[ok] = x
    out = out.reshape(np.shape(y))
    return out * _MM


#: Number of areas up to which :func:`notch_depth` iterates element by element.
_SCALAR_AREAS = 16


def _notch_roots(targets: list[float], coefficients, d_max: float, rtol: float) -> list[float]:
    """The rising-branch roots [mm] of P(d) = targets [mm²] (each in (0, P(d_max)]), one by one:
    :func:`notch_depth`'s vectorised iterations written for one element (an element stops where
    the vectorised loop freezes it: converged, or after 200 iterations)."""
    a, b, c = coefficients
    roots = []
    for target in targets:
        lo, hi = 0.0, d_max
        x = min(target / c, d_max)  # start from the linear (small-depth) guess
        for _ in range(200):
            f = ((a * x + b) * x + c) * x - target
            if f <= 0.0:
                lo = x
            if f > 0.0:
                hi = x
            slope = (3.0 * a * x + 2.0 * b) * x + c
            step = x - f / slope if slope != 0.0 else math.nan
            bad = not math.isfinite(step) or step < lo or step > hi
            new = 0.5 * (lo + hi) if bad else step
            if f == 0.0:  # an exact root keeps its value
                new = x
            done = abs(new - x) <= rtol * abs(new) or hi - lo <= rtol * hi
            x = new
            if done:
                break
        roots.append(x)
    return roots


def notch_obstacle_volume(depth_obstacle, obstacle_radius: float, width: float,
                          kappa: float) -> np.ndarray:
    """Worn volume of the guide card [m³] from its depth [m]: V_o = κ·π·l·R_o·d_o.

    Parameters
    ----------
    depth_obstacle : array_like
        Worn depth of the card d_o [m].
    obstacle_radius : float
        Card bore radius R_o [m].
    width : float
        Worn height l [m] (the h of Code_Aster R7.20.01).
    kappa : float
        Shape factor κ [-]: 0.47 (one notch), 0.94 (two notches).

    Returns
    -------
    numpy.ndarray
        V_o [m³].

    Notes
    -----
    V_o = κ·π·l·R_o·d_o (Code_Aster R7.20.01 §4.2-§4.3; its h is the width l).

    Examples
    --------
    >>> round(float(notch_obstacle_volume(1e-4, 5.25e-3, 0.02, 0.47)) * 1e9, 5)  # [mm³]
    15.50376
    """
    return kappa * np.pi * width * obstacle_radius * np.asarray(depth_obstacle, dtype=float)


@dataclasses.dataclass(frozen=True)
class _GuideCardNotch(ContactGeometry):
    """Common relations of GRAPPE_1_ENCO and GRAPPE_2_ENCO (see the module docstring)."""

    obstacle_width: float
    mobile_radius: float | None = None
    obstacle_radius: float | None = None

    required: ClassVar[tuple[str, ...]] = ("obstacle_width",)
    optional: ClassVar[tuple[str, ...]] = ("mobile_radius", "obstacle_radius")
    mobile_depth_alone: ClassVar[bool] = True  # the rod's notch from its own volume
    example: ClassVar[dict[str, float]] = {
        "obstacle_width": 20e-3, "mobile_radius": CALIBRATION_MOBILE_RADIUS,
        "obstacle_radius": CALIBRATION_OBSTACLE_RADIUS}

    def __post_init__(self) -> None:
        super().__post_init__()
        for name, keyword, value, reference, what in (
                ("mobile_radius", "RAYON_MOBILE", self.mobile_radius,
                 CALIBRATION_MOBILE_RADIUS, "rod"),
                ("obstacle_radius", "RAYON_OBST", self.obstacle_radius,
                 CALIBRATION_OBSTACLE_RADIUS, "guide-card bore")):
            if value is not None and abs(value - reference) > RADIUS_TOLERANCE * reference:
                warnings.warn(
                    f"{self.contact_type}: the notch polynomial was fitted for a 9.7 mm rod in a "
                    f"10.5 mm guide card (radii {CALIBRATION_MOBILE_RADIUS:g} / "
                    f"{CALIBRATION_OBSTACLE_RADIUS:g} m); {name} ({keyword}) = {value:g} m "
                    f"differs from the {what} radius {reference:g} m: the depths are "
                    "extrapolated outside the fitted geometry",
                    RangeWarning, stacklevel=3)

    @property
    def kappa(self) -> float:
        """Obstacle factor κ [-] of V_o = κ·π·l·R_o·d_o."""
        return NOTCH_LAWS[self.contact_type]["kappa"]

    @property
    def card_radius(self) -> float:
        """R_o [m] used in V_o: the given obstacle_radius, else the fitted 5.25 mm."""
        return CALIBRATION_OBSTACLE_RADIUS if self.obstacle_radius is None \
            else float(self.obstacle_radius)

    @property
    def max_depth(self) -> float:
        return notch_depth_limit(self.contact_type)

    @property
    def range_limit(self) -> str:
        a, b, c = NOTCH_LAWS[self.contact_type]["coefficients"]
        d = self.max_depth / _MM
        area = ((a * d + b) * d + c) * d
        return (f"rod depth up to {self.max_depth:.6g} m, the maximum of the notch polynomial "
                f"(V_m/l up to {area:.6g} mm²)")

    def _depth_from_volume(self, volume_mobile, volume_obstacle):
        l = float(self.obstacle_width)
        depth_mobile = np.asarray(notch_depth(volume_mobile / l, self.contact_type), dtype=float)
        depth_obstacle = volume_obstacle / (self.kappa * math.pi * l * self.card_radius)
        return depth_mobile, depth_obstacle

    def _volume_from_depth(self, depth_mobile, depth_obstacle):
        l = float(self.obstacle_width)
        volume_mobile = l * np.asarray(notch_area(depth_mobile, self.contact_type), dtype=float)
        volume_obstacle = np.asarray(notch_obstacle_volume(
            depth_obstacle, self.card_radius, l, self.kappa), dtype=float)
        return volume_mobile, volume_obstacle


@dataclasses.dataclass(frozen=True)
class Grappe1Enco(_GuideCardNotch):
    """GRAPPE_1_ENCO: control-rod against the single notch of a guide card.

    Parameters
    ----------
    obstacle_width : float
        Worn height l of the card [m] (LARGEUR_OBST; the h of Code_Aster R7.20.01).
    mobile_radius : float, optional
        Rod outer radius [m] (RAYON_MOBILE): only checked against the fitted 4.85 mm.
    obstacle_radius : float, optional
        Card bore radius R_o [m] (RAYON_OBST), used in V_o; default the fitted 5.25 mm.

    Notes
    -----
    V_m/l = −2.76·d_m³ + 10.30·d_m² + 0.83·d_m (d_m in mm, V_m/l in mm²), d_m on the rising
    branch (d_m ≤ 2.5276 mm); V_o = 0.47·π·l·R_o·d_o. See docs/geometry.md.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.2.
    .. [3] Lina, A., & Zbinden, M. (1995). [Wear of control-rod rodlet cladding: relations between
           worn volume and wear depth]. EDF-DER report HT.22/95-06A (in French).

    Examples
    --------
    >>> g = Grappe1Enco(obstacle_width=0.02)
    >>> dm, do = g.depth_from_volume(0.02 * 8.37e-6)  # V_m/l = P(1 mm) = 8.37 mm²
    >>> round(float(dm) * 1e3, 12), float(do)
    (1.0, 0.0)
    """

    contact_type: ClassVar[str] = "GRAPPE_1_ENCO"


@dataclasses.dataclass(frozen=True)
class Grappe2Enco(_GuideCardNotch):
    """GRAPPE_2_ENCO: control-rod against the two diametrically opposite notches of a guide card.

    Parameters
    ----------
    obstacle_width : float
        Worn height l of the card [m] (LARGEUR_OBST).
    mobile_radius : float, optional
        Rod outer radius [m] (RAYON_MOBILE): only checked against the fitted 4.85 mm.
    obstacle_radius : float, optional
        Card bore radius R_o [m] (RAYON_OBST), used in V_o; default the fitted 5.25 mm.

    Notes
    -----
    V_m/l = −5.52·d_m³ + 20.60·d_m² + 1.66·d_m (d_m in mm, V_m/l in mm²: twice the single
    notch, two identical traces), d_m ≤ 2.5276 mm; V_o = 0.94·π·l·R_o·d_o.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.3.
    .. [3] Lina, A., & Zbinden, M. (1995). [Wear of control-rod rodlet cladding: relations between
           worn volume and wear depth]. EDF-DER report HT.22/95-06A (in French).

    Examples
    --------
    >>> g = Grappe2Enco(obstacle_width=0.02, obstacle_radius=5.25e-3)
    >>> vm, vo = g.volume_from_depth(1e-3, 1e-4)
    >>> round(float(vm) * 1e9, 6), round(float(vo) * 1e9, 6)  # [mm³]
    (334.8, 31.007519)
    """

    contact_type: ClassVar[str] = "GRAPPE_2_ENCO"
