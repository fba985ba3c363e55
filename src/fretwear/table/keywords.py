"""The keywords of a wear computation, documented once: :data:`KEYWORDS`.

:func:`fretwear.table.wear_table` and :meth:`fretwear.table.WearCase.from_keywords` take these
keywords (the user's vocabulary, with Code_Aster's POST_USURE name of each); their docstrings
are written from this table (:func:`keywords_doc`) and the keywords they accept are checked
against it (:func:`check_keywords`: an unknown one is a KeywordError naming the closest), so
that the list is kept in one place. A case file (:mod:`fretwear.workflows.case_files`) and the
Code_Aster command (:mod:`fretwear.workflows.aster`) name the same values with their own keys.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from fretwear.errors import KeywordError
from fretwear.keys import keyword_hint
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT

__all__ = ["KEYWORDS", "REQUIRED", "Keyword", "check_keywords", "keywords_doc"]

#: A keyword without a default: it must be given.
REQUIRED = object()


@dataclass(frozen=True)
class Keyword:
    """One keyword of a wear computation.

    Attributes
    ----------
    name : str
        The keyword (a parameter of :func:`fretwear.table.wear_table`).
    kind : str
        Its type as the docstrings write it (``"float, optional"``).
    unit : str
        Its unit (``"m"``, ``"s"``, ``"-"``, ``"user time unit"``), ``""`` when it has none.
    meaning : str
        What it is, one sentence or a few.
    default : object
        Its default value, :data:`REQUIRED` when it has none.
    aster : str
        The Code_Aster keyword of POST_USURE it stands for, ``""`` for a fretwear extension.
    """

    name: str
    kind: str
    unit: str
    meaning: str
    default: Any = None
    aster: str = ""

    def doc(self) -> str:
        """The numpydoc entry of the keyword (``name : kind`` and its indented meaning)."""
        text = self.meaning
        if self.unit:
            text += f" [{self.unit}]"
        if self.aster:
            text += f" ({self.aster})"
        text += "."
        if self.default is not REQUIRED and self.default is not None:
            text += f" Default {self.default!r}."
        body = textwrap.fill(text, 88, initial_indent="    ", subsequent_indent="    ")
        return f"{self.name} : {self.kind}\n{body}"


def _keywords(*rows: Keyword) -> dict[str, Keyword]:
    return {k.name: k for k in rows}


#: Every keyword of :func:`fretwear.table.wear_table` (besides ``source``, ``case``,
#: ``history``), in the order of the documentation.
KEYWORDS: dict[str, Keyword] = _keywords(
    Keyword("contact_type", "str", "",
            "Contact type, one of fretwear.geometry.CONTACT_TYPES (e.g. 'TUBE_BAV'); None only "
            "with sectors (the sector depths need the radii and the width alone, the global "
            "depths are then NaN)", REQUIRED, "CONTACT"),
    Keyword("dimensions", "mapping, optional", "m, deg",
            "Geometry of the contact: mobile_radius, obstacle_radius, obstacle_width [m], "
            "tilt_angle, isthmus_angle, impact_angle [deg], whichever the type uses "
            "(fretwear.geometry)", None, "RAYON_MOBILE, LARGEUR_OBST, ..."),
    Keyword("instants", "sequence of float", "user time unit",
            "Durations of service after the origin, strictly increasing; the table's instant "
            "is origin + duration", REQUIRED, "INST / LIST_INST"),
    Keyword("law", "str", "",
            "Wear law, a key of fretwear.laws.WEAR_LAWS ('ARCHARD', 'KWU_EPRI', 'EDF_MZ'); "
            "sector mode is Archard only", "ARCHARD", "LOI_USURE"),
    Keyword("coefficients", "mapping, optional", "SI",
            "Law coefficients of the mobile, native names or Code_Aster keywords (e.g. "
            "{'COEF_USURE': 1e-14} [1/Pa]); the law's defaults for the others", None,
            "COEF_USURE, ..."),
    Keyword("obstacle_coefficients", "mapping, optional", "SI",
            "Law coefficients of the obstacle; the obstacle wears only if given (or with "
            "obstacle_wear and materials), its volume otherwise stays at its initial value",
            None, "COEF_USURE of the obstacle"),
    Keyword("materials", "(str, str), optional", "",
            "(mobile, obstacle) material pair of the coefficient database, instead of the "
            "coefficients", None, "MATER_USURE"),
    Keyword("obstacle_wear", "bool", "",
            "Take the obstacle coefficient from the database too (needs materials)", False,
            "USURE_OBST"),
    Keyword("coefficient_files", "path-like or sequence of path-like, optional", "",
            "The user's coefficient CSV file(s) in the format of fretwear.database "
            "(docs/laws.md), extending and overriding the built-in table for materials; a "
            "later file wins over an earlier one (a fretwear extension)", None),
    Keyword("sectors", "int or sequence of float, optional", "deg",
            "Angular sectors: their number (equal sectors over -180..180) or their edges; "
            "needs a history with dy/dz", None, "SECTEUR"),
    Keyword("sector_coefficients", "sequence of (float, float or None), optional", "1/Pa",
            "Archard coefficients (mobile, obstacle) per sector, one pair for all allowed; "
            "default the law's coefficients", None, "COEF_USUR_MOBILE, COEF_USUR_OBST"),
    Keyword("time_scale", "float", "s",
            "Seconds per user time unit, e.g. 31 536 000 for years", 1.0, "COEF_INST"),
    Keyword("time_unit", "str, optional", "",
            "Name of the user time unit ('year', ...) for the metadata; time_scale gives the "
            "seconds", None),
    Keyword("t_start", "float, optional", "s",
            "Start of the window of the history the power is computed over; ignored (warned) "
            "with a power given as a number, the PowerResult's own with a PowerResult source",
            None, "INST_INIT of RESU_GENE"),
    Keyword("t_end", "float, optional", "s",
            "End of the window of the history, as t_start", None, "INST_FIN of RESU_GENE"),
    Keyword("blocks", "int", "",
            "Number of blocks of equal duration of the power computation, as t_start", 1,
            "NB_BLOC"),
    Keyword("stationarity_threshold", "float", "-",
            "Relative block spread (max - min) / mean above which a StationarityWarning is "
            "given", 0.1),
    Keyword("force_max", "float, optional", "N",
            "KWU-EPRI force class range; default the window's maximum", None, "FNOR_MAXI"),
    Keyword("speed_max", "float, optional", "m/s",
            "KWU-EPRI speed class range; default the window's maximum", None, "VTAN_MAXI"),
    Keyword("initial_state", "DataFrame, path-like or fretwear.table.InitialState, optional",
            "", "Previous wear table to continue, ours or Code_Aster's", None,
            "ETAT_INIT / TABL_USURE"),
    Keyword("initial_instant", "float, optional", "user time unit",
            "Instant of initial_state to continue from; default its last", None,
            "INST_INIT of ETAT_INIT"),
    Keyword("tube_replacement", "float, optional", "user time unit",
            "Instant at which the tube is replaced by a new one: from it on the tube's "
            "volumes restart from zero, the obstacle's continue", None, "TUBE_NEUF"),
    Keyword("wall_thickness", "float, optional", "m",
            "Wall thickness of the mobile (tube), when known: the table gains the depth over "
            "the wall and the instant of reaching the limit (a fretwear extension)", None),
    Keyword("depth_limit", "float", "-",
            "Depth limit as a fraction of the wall thickness, 0 < depth_limit <= 1 (a plugging "
            "criterion)", DEFAULT_DEPTH_LIMIT),
    Keyword("name", "str, optional", "",
            "A name or title of the case (the table's metadata, the files' provenance)", None,
            "TITRE"),
)


#: The keywords that must be given, and the defaults of the others (read at every call).
_REQUIRED = tuple(k.name for k in KEYWORDS.values() if k.default is REQUIRED)
_DEFAULTS = {k.name: k.default for k in KEYWORDS.values()}


def keywords_doc(indent: int = 4) -> str:
    """The numpydoc entries of every keyword of :data:`KEYWORDS`, indented by ``indent``.

    Examples
    --------
    >>> keywords_doc(0).splitlines()[0]
    'contact_type : str'
    """
    return textwrap.indent("\n".join(k.doc() for k in KEYWORDS.values()), " " * indent)


def check_keywords(keywords: Mapping[str, Any], where: str = "wear_table") -> dict[str, Any]:
    """The keywords with the defaults of :data:`KEYWORDS` for those not given.

    Raises
    ------
    KeywordError
        A keyword that is not in :data:`KEYWORDS` (with the closest one), or a required one
        missing.

    Examples
    --------
    >>> check_keywords({"contact_type": "TUBE_BAV", "instants": [1.0]})["depth_limit"]
    0.4
    >>> try:
    ...     check_keywords({"contact_type": "TUBE_BAV", "instants": [1.0], "wall": 1e-3})
    ... except KeywordError as exc:
    ...     print(str(exc).split(";")[0])
    wear_table: unknown keyword wall
    """
    unknown = [k for k in keywords if k not in KEYWORDS]
    if unknown:
        hints = ", ".join(f"{k}{keyword_hint(k, KEYWORDS)}" for k in unknown)
        raise KeywordError(f"{where}: unknown keyword {hints}; the keywords are "
                           f"{', '.join(KEYWORDS)} (docs: help(fretwear.table.wear_table))")
    missing = [name for name in _REQUIRED if name not in keywords]
    if missing:
        raise KeywordError(f"{where}: missing keyword(s) {', '.join(missing)}: "
                           + "; ".join(KEYWORDS[k].doc().replace("\n   ", "") for k in missing))
    return {**_DEFAULTS, **keywords}
