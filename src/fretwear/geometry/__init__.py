"""Worn volume ↔ worn depth for the eight contact geometries of POST_USURE (theory §3, §6).

``CONTACT_TYPES`` maps each Code_Aster contact name to its frozen dataclass;
:func:`contact_geometry` builds one from keyword dimensions (native names or Code_Aster
keywords). Every geometry has ``depth_from_volume(volume_mobile, volume_obstacle=0.0)`` and
``volume_from_depth(depth_mobile, depth_obstacle=0.0)``, vectorised over instants. Sector depths
are in :mod:`fretwear.geometry.sectors`. The derivations are in ``docs/geometry.md``.
"""

from __future__ import annotations

import dataclasses
import warnings

from fretwear.errors import KeywordError, UnusedKeywordWarning
from fretwear.geometry._shapes import solve_monotone
from fretwear.geometry.base import (
    ASTER_KEYWORDS,
    DIMENSION_DESCRIPTIONS,
    DIMENSION_UNITS,
    ContactGeometry,
)
from fretwear.geometry.enco import Tube3Enco, Tube4Enco
from fretwear.geometry.grappe_alesage import GrappeAlesage
from fretwear.geometry.grappe_notch import Grappe1Enco, Grappe2Enco
from fretwear.geometry.sectors import (
    sector_depth_mobile,
    sector_depth_obstacle,
    sector_geometry,
    sector_volume_mobile,
    sector_volume_obstacle,
)
from fretwear.geometry.tube_alesage import TubeAlesage
from fretwear.geometry.tube_bav import TubeBav
from fretwear.geometry.tube_tube import TubeTube

__all__ = [
    "ASTER_KEYWORDS",
    "CONTACT_TYPES",
    "ContactGeometry",
    "check_sector_contact",
    "contact_geometry",
    "sector_depth_mobile",
    "sector_depth_obstacle",
    "sector_volume_mobile",
    "sector_volume_obstacle",
    "solve_monotone",
]

#: Code_Aster contact name -> geometry class (theory §6).
CONTACT_TYPES: dict[str, type[ContactGeometry]] = {
    "TUBE_BAV": TubeBav,
    "TUBE_ALESAGE": TubeAlesage,
    "TUBE_TUBE": TubeTube,
    "GRAPPE_ALESAGE": GrappeAlesage,
    "TUBE_3_ENCO": Tube3Enco,
    "TUBE_4_ENCO": Tube4Enco,
    "GRAPPE_1_ENCO": Grappe1Enco,
    "GRAPPE_2_ENCO": Grappe2Enco,
}

_FROM_ASTER = {keyword: name for name, keyword in ASTER_KEYWORDS.items()}


def sector_obstacle_radius(contact_type: str, dimensions) -> tuple[dict, float | None]:
    """(the dimensions the contact type takes, the obstacle radius [m] kept for the sectors).

    Theory §3: a sector's depth of the obstacle needs the bore radius ``obstacle_radius``
    (RAYON_OBST) whatever the contact type; a type whose global depth does not use it (a flat
    bar, TUBE_BAV) would drop it with an :class:`~fretwear.errors.UnusedKeywordWarning`. With
    sectors it is taken out here, checked like the sector geometry's, and kept for them.
    Names may be native or Code_Aster's, any case.

    >>> dims, r = sector_obstacle_radius("TUBE_BAV", {"RAYON_MOBILE": 0.0095,
    ...                                   "LARGEUR_OBST": 0.02, "RAYON_OBST": 0.00975})
    >>> sorted(dims), r
    (['LARGEUR_OBST', 'RAYON_MOBILE'], 0.00975)
    >>> sector_obstacle_radius("TUBE_ALESAGE", {"obstacle_radius": 0.0115})[1] is None
    True
    """
    cls = CONTACT_TYPES.get(str(contact_type).strip().upper())
    dims = dict(dimensions)
    if cls is None or "obstacle_radius" in cls.required + cls.optional:
        return dims, None
    names = [k for k in dims if _FROM_ASTER.get(str(k).upper(), k) == "obstacle_radius"]
    if len(names) != 1 or dims[names[0]] is None:
        return dims, None
    radius = dims.pop(names[0])
    sector_geometry(mobile_radius=1.0, obstacle_width=1.0, obstacle_radius=radius)  # checked
    return dims, float(radius)


def check_sector_contact(contact_type: str) -> None:
    """Refuse angular sectors for a contact type without an obstacle width.

    A sector's depth assumes the defect fills the sector's arc Δθ over the obstacle's width l
    (theory §3, :func:`fretwear.geometry.sector_depth_mobile`). TUBE_TUBE (two crossed tubes)
    has no width: without this check the geometry would warn that the width given for the
    sectors is not used, and the sectors would then fail for want of it. An unknown contact
    type is left to :func:`contact_geometry`, which names the known ones.

    Raises
    ------
    KeywordError
        The contact type has no ``obstacle_width`` (LARGEUR_OBST).

    Examples
    --------
    >>> check_sector_contact("TUBE_BAV")
    >>> check_sector_contact("TUBE_TUBE")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    fretwear.errors.KeywordError: sectors (SECTEUR) with contact_type TUBE_TUBE (CONTACT): ...
    """
    cls = CONTACT_TYPES.get(str(contact_type).strip().upper())
    if cls is None or "obstacle_width" in {f.name for f in dataclasses.fields(cls)}:
        return
    raise KeywordError(
        f"sectors (SECTEUR) with contact_type {cls.contact_type} (CONTACT): a sector's depth "
        "assumes the defect fills the sector's arc over the obstacle's width (LARGEUR_OBST), and "
        f"{cls.contact_type} has no width (its obstacle is a tube crossing this one); remove "
        "sectors for this contact, or leave contact_type out to get sector depths alone from "
        "mobile_radius and obstacle_width")


def contact_geometry(contact_type: str, **dimensions) -> ContactGeometry:
    """Build the geometry of a contact type from its dimensions.

    Parameters
    ----------
    contact_type : str
        Code_Aster contact name (case-insensitive): one of ``CONTACT_TYPES``.
    **dimensions : float
        ``mobile_radius`` [m], ``obstacle_radius`` [m], ``obstacle_width`` [m],
        ``tilt_angle`` [deg], ``isthmus_angle`` [deg], ``impact_angle`` [deg], or their
        Code_Aster keywords (RAYON_MOBILE, RAYON_OBST, LARGEUR_OBST, ANGL_INCLI, ANGL_ISTHME,
        ANGL_IMPACT). A value of None counts as not given.

    Returns
    -------
    ContactGeometry
        The frozen geometry object.

    Raises
    ------
    KeywordError
        Unknown contact type, unknown dimension name, a dimension given twice, or a dimension
        the type needs and did not get (named with its Code_Aster keyword).
    InputError
        A negative, zero or non-finite length, or an angle outside [0, 90) deg.

    Warns
    -----
    UnusedKeywordWarning
        For a dimension the contact type does not use (it is ignored).

    Examples
    --------
    >>> g = contact_geometry("TUBE_BAV", RAYON_MOBILE=0.0111, LARGEUR_OBST=0.0127)
    >>> type(g).__name__, g.mobile_radius
    ('TubeBav', 0.0111)
    """
    key = str(contact_type).strip().upper()
    cls = CONTACT_TYPES.get(key)
    if cls is None:
        raise KeywordError(
            f"unknown contact type {contact_type!r} (CONTACT): choose one of "
            f"{', '.join(CONTACT_TYPES)}")
    given: dict[str, float] = {}
    for name, value in dimensions.items():
        native = _FROM_ASTER.get(name.upper(), name)  # Code_Aster keywords, any case
        if native not in ASTER_KEYWORDS:
            raise KeywordError(
                f"{name!r} is not a contact dimension; the dimensions are "
                + ", ".join(f"{n} ({k})" for n, k in ASTER_KEYWORDS.items())
                + " (a wall thickness belongs to the perforation check, not the geometry)")
        if native in given:
            raise KeywordError(
                f"{native} ({ASTER_KEYWORDS[native]}) given twice; give it once")
        if value is None:
            continue
        given[native] = value
    used = set(cls.required) | set(cls.optional)
    uses = ", ".join(f"{n} ({ASTER_KEYWORDS[n]})" for n in cls.required + cls.optional)
    for name in list(given):
        if name not in used:
            warnings.warn(
                f"{key} does not use {name} ({ASTER_KEYWORDS[name]}): ignored (it uses {uses})",
                UnusedKeywordWarning, stacklevel=2)
            del given[name]
    missing = [name for name in cls.required if name not in given]
    if missing:
        raise KeywordError(
            f"{key} needs "
            + ", ".join(f"{n} ({ASTER_KEYWORDS[n]}, {DIMENSION_DESCRIPTIONS[n]}) "
                        f"[{DIMENSION_UNITS[n]}]" for n in missing))
    return cls(**given)
