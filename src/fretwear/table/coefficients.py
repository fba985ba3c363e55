"""The law coefficients of a wear case, each with its source (user, database row, default).

:func:`resolve_coefficients` turns what the user gave (coefficients by name or Code_Aster
keyword, or a database material pair extended by coefficient files, and the separate KWU-EPRI
class ranges) into each body's coefficients by native name, the law's defaults filled in, each a
:class:`Coefficient` that says where it came from. Used by :class:`fretwear.table.WearCase`.
"""

from __future__ import annotations

import numbers
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from fretwear.database import lookup
from fretwear.errors import InputError, KeywordError
from fretwear.laws import WEAR_LAWS

__all__ = ["DEFAULT", "USER", "Coefficient", "coefficient_file_paths", "law_coefficients",
           "laws_with", "material_pair", "plain", "resolve_coefficients", "sector_parameter"]

#: Source of a coefficient the user gave (keyword, case file, Code_Aster MOBILE/OBSTACLE).
USER = "user"
#: Source of a coefficient filled in from the law's defaults (:attr:`WearLaw.defaults`).
DEFAULT = "default"


@dataclass(frozen=True)
class Coefficient:
    """One law coefficient and where it came from.

    Attributes
    ----------
    value : float or None
        The value, SI (the law's unit: :attr:`fretwear.laws.WearLaw.units`); None for an optional
        one left to the computation (KWU-EPRI's class ranges: the window's maxima).
    source : str
        ``"user"``, ``"default"`` (the law's default) or ``"database <mobile>/<obstacle>
        (<contact type>, <law>): <row source> (<file>)"``.

    Examples
    --------
    >>> Coefficient(1.2e-13, "user")
    Coefficient(value=1.2e-13, source='user')
    """

    value: Any
    source: str


# --------------------------------------------------------------------------- small checks
def sector_parameter(law) -> str | None:
    """The coefficient a law takes per sector, or None: sectors split V = k·P·t (theory §3), so
    only a law linear in time with a single coefficient (Archard) has sector coefficients."""
    return law.parameters[0] if law.linear_in_time and len(law.parameters) == 1 else None


def laws_with(predicate) -> str:
    return ", ".join(f"'{name}'" for name, law in WEAR_LAWS.items() if predicate(law))


def law_coefficients(law, given: Mapping[str, Any] | None, body: str) -> dict[str, Any]:
    """The law's coefficients of one body: native names (Code_Aster keywords translated),
    defaults filled in (:meth:`fretwear.laws.WearLaw.resolve`).

    Raises
    ------
    KeywordError
        For a keyword the law does not have (naming the body and listing the accepted ones).

    Examples
    --------
    >>> law_coefficients(WEAR_LAWS["ARCHARD"], {"COEF_USURE": 1e-13}, "mobile")
    {'coefficient': 1e-13}
    """
    try:
        values = law.resolve(**dict(given or {}))
    except KeywordError as exc:
        raise KeywordError(f"{body} coefficients: {exc}") from None
    for name, value in values.items():
        if value is not None and (isinstance(value, bool | np.bool_)
                                  or not isinstance(value, numbers.Real)):
            keyword = law.aster_keywords.get(name, name)
            raise KeywordError(
                f"{body} coefficients: {keyword} = {value!r} is not a number; give one real "
                f"number [{law.units.get(name, 'SI')}] (per-sector coefficients: [sectors] "
                "mobile_coefficients_per_Pa, one per sector)")
    return values


def plain(value: Any) -> Any:
    """A number as a Python int/float (numpy scalars converted), anything else unchanged."""
    return value.item() if isinstance(value, np.generic) else value


def coefficient_file_paths(files, materials) -> tuple[str, ...] | None:
    """The user's coefficient files as path strings (None for none), each checked to exist;
    they only make sense with a database pair."""
    if files is None:
        return None
    items = [files] if isinstance(files, str | os.PathLike) else list(files)
    if not items:
        return None
    for item in items:
        if not isinstance(item, str | os.PathLike):
            raise InputError(f"coefficient_files must be paths of CSV files, got {item!r}")
        if not Path(item).is_file():
            raise InputError(f"coefficient file {str(item)!r} (coefficient_files) does not exist; "
                             "give the path of a CSV in the coefficient-database format "
                             "(docs/laws.md)")
    return tuple(os.fspath(item) for item in items)


def _tagged(law, given: Mapping[str, Any], extra: Mapping[str, Any], body: str,
            source_of) -> dict[str, Coefficient]:
    """The body's resolved coefficients, each with its source: ``extra`` (the separate KWU
    keywords) and ``given`` from ``source_of(name)``, the rest the law's defaults."""
    values = law_coefficients(law, {**given, **extra}, body)
    by_keyword = {kw: p for p, kw in law.aster_keywords.items()}
    given_names = {by_keyword.get(k, k) for k in given}
    out = {}
    for name, value in values.items():
        source = (USER if name in extra else source_of(name) if name in given_names
                  else DEFAULT)
        out[name] = Coefficient(plain(value), source)
    return out


def resolve_coefficients(law, contact_type, coefficients, obstacle_coefficients, materials,
                          obstacle_wear, force_max, speed_max, files):
    """(mobile, obstacle or None) coefficients of the law by native name, each a Coefficient."""
    given_m = dict(coefficients or {})
    given_o = None if obstacle_coefficients is None else dict(obstacle_coefficients)
    def source_m(name: str) -> str:
        return USER

    source_o = source_m
    if materials is not None:
        if coefficients is not None:
            raise KeywordError("give either coefficients (MOBILE) or materials (MATER_USURE), "
                               "not both")
        if obstacle_coefficients is not None:
            raise KeywordError("materials (MATER_USURE) excludes obstacle_coefficients "
                               "(OBSTACLE): ask for obstacle_wear (USURE_OBST) instead")
        pair = material_pair(materials)
        found = lookup(contact_type, pair[0], pair[1], law.name, obstacle=bool(obstacle_wear),
                       extra=None if files is None else list(files))
        where = (f"database {found.mobile_material}/{found.obstacle_material} "
                 f"({found.contact_type}, {found.law})")
        given_m = dict(found.mobile)

        def source_m(name: str) -> str:
            return f"{where}: {found.sources[f'mobile.{name}']}"

        if obstacle_wear:
            if not found.obstacle:
                raise KeywordError(
                    f"obstacle_wear (USURE_OBST='OUI') asked for, but the database has no "
                    f"obstacle coefficient for {contact_type} {pair[0]}/{pair[1]} "
                    f"({law.name}); give obstacle_coefficients instead")
            given_o = dict(found.obstacle)

            def source_o(name: str) -> str:
                return f"{where}: {found.sources[f'obstacle.{name}']}"
    # the separate class-range keywords join both bodies' coefficients (laws that take them)
    extra = {k: v for k, v in (("force_max", force_max), ("speed_max", speed_max))
             if v is not None and k in law.accepted}
    mobile = _tagged(law, given_m, extra, "mobile", source_m)
    obstacle = None if given_o is None else _tagged(law, given_o, extra, "obstacle", source_o)
    return mobile, obstacle


def material_pair(materials) -> tuple[str, str]:
    if isinstance(materials, str) or len(materials) != 2:
        raise KeywordError(f"materials (MATER_USURE) must be a (mobile, obstacle) pair of "
                           f"material codes, e.g. ('I600', 'A405'), got {materials!r}")
    return str(materials[0]), str(materials[1])
