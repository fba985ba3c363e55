"""GRAPPE_ALESAGE: control-rod (cluster) rodlet in a guide bore (theory §6; R7.20.01 §4.1).

The rod is centred in a bore of radius R_o > R_m; the trace is one lunule. Both bodies may wear:
the lens S(D) of total depth D = d_m + d_o holds (V_m + V_o)/l, and the new common surface, an
arc of radius r through the chord ends, gives V_m/l to the rod and V_o/l to the bore.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from fretwear.geometry._lunule import lunule_areas, lunule_depths
from fretwear.geometry._shapes import lens_depth_limit
from fretwear.geometry.base import ContactGeometry

__all__ = ["GrappeAlesage"]


@dataclasses.dataclass(frozen=True)
class GrappeAlesage(ContactGeometry):
    """GRAPPE_ALESAGE: rod in a bore, one lunule, both bodies worn.

    Parameters
    ----------
    mobile_radius : float
        Rod outer radius R_m [m] (RAYON_MOBILE).
    obstacle_radius : float
        Bore radius R_o [m] (RAYON_OBST), > R_m.
    obstacle_width : float
        Worn height l of the bore [m] (LARGEUR_OBST).

    Notes
    -----
    .. math:: S(D) = \\frac{V_m + V_o}{l},\\quad
              \\frac{V_m}{l} = \\mathrm{seg}(R_m, x) - \\mathrm{seg}(r, x),\\quad
              d_m = s(R_m, x) - s(r, x),\\ d_o = D - d_m

    Range: D ≤ √(R_o² − R_m²) − (R_o − R_m) (the chord reaches the rod's axis). Code_Aster sets
    an area equal to a volume here (no width): we follow Code_Aster R7.20.01 [2]_ and divide by l.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §6.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §4.1 (corrected: R_m sin α =
           r sin β = R_o sin γ, segment ρ²(φ − ½ sin 2φ)).

    Examples
    --------
    >>> g = GrappeAlesage(mobile_radius=4.85e-3, obstacle_radius=5.25e-3, obstacle_width=0.01)
    >>> dm, do = g.depth_from_volume(1e-10)
    >>> round(float(dm) * 1e6, 3), float(do)
    (7.66, 0.0)
    """

    mobile_radius: float
    obstacle_radius: float
    obstacle_width: float

    contact_type: ClassVar[str] = "GRAPPE_ALESAGE"
    required: ClassVar[tuple[str, ...]] = ("mobile_radius", "obstacle_radius", "obstacle_width")
    optional: ClassVar[tuple[str, ...]] = ()
    example: ClassVar[dict[str, float]] = {
        "mobile_radius": 4.85e-3, "obstacle_radius": 5.25e-3, "obstacle_width": 10e-3}

    def __post_init__(self) -> None:
        super().__post_init__()
        self._check_room("the bore radius", "the mobile radius")

    @property
    def max_depth(self) -> float:
        return float(lens_depth_limit(self.mobile_radius, self.obstacle_radius))

    @property
    def range_limit(self) -> str:
        return (f"total depth d_m + d_o up to {self.max_depth:.6g} m, where the lunule's chord "
                "reaches the mobile's axis")

    def _depth_from_volume(self, volume_mobile, volume_obstacle):
        l = self.obstacle_width
        return lunule_depths(self.mobile_radius, self.obstacle_radius,
                             volume_mobile / l, volume_obstacle / l)

    def _volume_from_depth(self, depth_mobile, depth_obstacle):
        am, ao = lunule_areas(self.mobile_radius, self.obstacle_radius, depth_mobile,
                              depth_obstacle)
        return np.asarray(am) * self.obstacle_width, np.asarray(ao) * self.obstacle_width
