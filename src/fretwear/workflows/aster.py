"""Code_Aster compatibility: ``POST_USURE(**keywords)`` as written in a command file.

A Code_Aster user can paste the keywords of a POST_USURE command::

    from fretwear.workflows.aster import POST_USURE, _F
    table = POST_USURE(RESU_GENE="shock_N12.tab", NOEUD="N12", LOI_USURE="ARCHARD",
                       MOBILE=_F(COEF_USURE=1.2e-13), CONTACT="TUBE_BAV",
                       RAYON_MOBILE=9.525e-3, LARGEUR_OBST=12.7e-3,
                       INST=(1.0, 10.0), COEF_INST=3.1536e7)

The keywords, their types, defaults and allowed values, the blocks and the rules between them are
one description, :data:`CATALOGUE`, a copy of Code_Aster's catalogue
(``code_aster/Cata/Commands/post_usure.py``, code_aster 16) checked by
:meth:`~fretwear.workflows.aster_catalogue.Catalogue.check`: an unknown keyword, a keyword of an
inactive block (FNOR_MAXI without LOI_USURE='KWU_EPRI'), a wrong type or a violated rule
(UN_PARMI, EXCLUS, PRESENT_PRESENT, PRESENT_ABSENT) is a :class:`~fretwear.errors.KeywordError`
naming the keywords. The result is a DataFrame with Code_Aster's column names (theory §7); the
computation is :func:`fretwear.table.wear_table_from_case` of a :class:`~fretwear.table.WearCase`.
Values are SI, angles in degrees, as in Code_Aster. Deliberate differences from Code_Aster are
listed in ``docs/code_aster.md``. Extras beyond the catalogue (:data:`EXTRA_KEYWORDS`):
``EPAIS_PAROI`` (wall thickness [m]) and ``LIMITE_PAROI`` (depth limit, fraction of the wall),
which add the columns FRAC_PAROI and INST_LIMITE.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.database import load_database
from fretwear.errors import DatabaseError, FretwearWarning, KeywordError, UnusedKeywordWarning
from fretwear.geometry import CONTACT_TYPES
from fretwear.geometry.base import ASTER_KEYWORDS
from fretwear.history import ContactHistory
from fretwear.io import read_history
from fretwear.laws import WEAR_LAWS
from fretwear.table import (
    DEFAULT_DEPTH_LIMIT,
    WearCase,
    replace_tube,
    to_aster_names,
    wear_table_from_case,
)
from fretwear.workflows.aster_catalogue import (
    _F,
    EXCLUS,
    PRESENT_ABSENT,
    PRESENT_PRESENT,
    UN_PARMI,
    Bloc,
    Catalogue,
    Fact,
    Simp,
    absent,
    equal_to,
    exists,
    first,
)
from fretwear.workflows.aster_dyna import POST_DYNA_MODA_T  # noqa: F401 - the other facade

__all__ = ["POST_USURE", "POST_DYNA_MODA_T", "_F", "CATALOGUE", "MATERIAL_CODES",
           "SIMPLE_KEYWORDS", "FACTOR_KEYWORDS", "EXTRA_KEYWORDS", "materials_of"]

#: LARGEUR_OBST of a SECTEUR computation without it [m] (Code_Aster's op0153: ``haut = 0.011``).
DEFAULT_SECTOR_WIDTH = 0.011


def _r(text: str, **kw: Any) -> Simp:
    return Simp("R", help=text, **kw)


def _law(keywords: dict[str, Simp], help: str, required: tuple[str, ...] = ()) -> Fact:
    keys = {k: Simp(v.type, "o" if k in required else "f", v.default, v.into, v.max, v.help)
            for k, v in keywords.items()}
    return Fact(keys, help=help)


_ARCHARD = {"COEF_USURE": _r("Archard coefficient K [Pa⁻¹]")}
_KWU = {"COEF_FNOR": _r("impact factor k1 [-]"), "COEF_VTAN": _r("sliding factor k2 [-]"),
        "COEF_USURE": _r("reference coefficient k_r [Pa⁻¹]"),
        "COEF_K": _r("k [-]", default=5.0), "COEF_C": _r("c [-]", default=10.0)}
_EDF_MZ = {"COEF_USURE": _r("A [m³/(s·W^b)]", default=1.0e-13),
           "COEF_B": _r("b [-]", default=1.2), "COEF_N": _r("n [s⁻¹]", default=2.44e-8),
           "COEF_S": _r("S [m³/s]", default=1.14e-16)}
_MATERIALS = {
    "MATER_USURE": Simp("material", help="material pair of the database: Code_Aster's "
                                    "'I600_Z6C13' (MOBILE_OBSTACLE, or one of its codes such as "
                                    "'NITRURE_A304L'), 'I600/Z6C13' or a (mobile, obstacle) pair"),
    "USURE_OBST": Simp("TXM", into=("OUI",), help="'OUI': the obstacle's coefficient from the "
                                                  "database too")}
_LAW_RULES = (UN_PARMI("MOBILE", "MATER_USURE"), EXCLUS("MATER_USURE", "OBSTACLE"),
              EXCLUS("MOBILE", "USURE_OBST"))
_LENGTH = "[m]"

#: POST_USURE's catalogue: keywords, types, defaults, allowed values, blocks and rules, as in
#: code_aster 16's ``code_aster/Cata/Commands/post_usure.py`` (the rules' notes say where
#: fretwear accepts more).
CATALOGUE = Catalogue(
    name="POST_USURE",
    source="code_aster/Cata/Commands/post_usure.py (code_aster 16, 2022)",
    rules=(
        UN_PARMI("TUBE_NEUF", "RESU_GENE", "PUIS_USURE"),
        UN_PARMI("TUBE_NEUF", "LOI_USURE"),
        PRESENT_ABSENT("TUBE_NEUF", "ETAT_INIT", "INST_FIN"),
        PRESENT_ABSENT("TUBE_NEUF", "RAYON_MOBILE", "RAYON_OBST", "LARGEUR_OBST", "CONTACT"),
        PRESENT_ABSENT("TUBE_NEUF", "ANGL_INCLI", "ANGL_ISTHME", "ANGL_IMPACT"),
        PRESENT_PRESENT("ANGL_INCLI", "CONTACT"),
        PRESENT_PRESENT("ANGL_ISTHME", "CONTACT"),
        PRESENT_PRESENT("ANGL_IMPACT", "CONTACT"),
    ),
    keywords={
        "reuse": Simp("concept", "c", help="the table continued: the TABL_USURE of ETAT_INIT or "
                                           "TUBE_NEUF (fretwear returns a new table and never "
                                           "modifies the one given)"),
        "TUBE_NEUF": Simp("TXM", into=("OUI",), help="'OUI': replace the tube of TABL_USURE by "
                                                     "a new one at INST"),
        "ETAT_INIT": Fact({"TABL_USURE": Simp("table", help="the table to continue"),
                           "INST_INIT": _r("its instant to continue from [user unit]")},
                          help="restart from a previous wear table"),
        "RESU_GENE": Simp("history", help="contact history: a ContactHistory, a history file, a "
                                          "list of IMPR_FONCTION files, or a mapping node label "
                                          "-> either"),
        "INST_FIN": _r("end of the history window t_end [s]"),
        "PUIS_USURE": _r("wear power [W]"),
        "LOI_USURE": Simp("TXM", into=tuple(WEAR_LAWS),
                          help=f"wear law: {', '.join(WEAR_LAWS)}"),
        "CONTACT": Simp("TXM", into=tuple(CONTACT_TYPES),
                        help=f"contact type: {', '.join(CONTACT_TYPES)}"),
        "RAYON_MOBILE": _r(f"mobile radius {_LENGTH}"),
        "RAYON_OBST": _r(f"obstacle radius {_LENGTH}"),
        "LARGEUR_OBST": _r(f"obstacle width {_LENGTH} (with SECTEUR, default 0.011 m as in "
                           "Code_Aster)"),
        "ANGL_INCLI": _r("tilt angle [deg]"),
        "ANGL_ISTHME": _r("isthmus angle [deg]"),
        "ANGL_IMPACT": _r("impact angle [deg]"),
        "INFO": Simp("I", default=1, into=(1, 2), help="verbosity (ignored)"),
        "TITRE": Simp("TXM", help="title of the table (attrs['title'])"),
        # fretwear extras, not in Code_Aster's catalogue
        "EPAIS_PAROI": _r("wall thickness of the tube [m] (fretwear extra): adds FRAC_PAROI and "
                          "INST_LIMITE (the instant the depth reaches LIMITE_PAROI of the wall)"),
        "LIMITE_PAROI": _r(f"depth limit as a fraction of the wall [-], default "
                           f"{DEFAULT_DEPTH_LIMIT} (fretwear extra)"),
    },
    blocs=(
        Bloc("RESU_GENE is given", exists("RESU_GENE"),
             {"NOEUD": Simp("node", "c", help="shock node label: selects its rows or tables in "
                                              "RESU_GENE"),
              "GROUP_NO": Simp("group", help="shock node group label: the same")},
             rules=(EXCLUS("NOEUD", "GROUP_NO", note="Code_Aster: UN_PARMI, a tran_gene holds "
                                                     "every shock; a fretwear history or a "
                                                     "single-node file needs neither"),)),
        Bloc("LOI_USURE='ARCHARD'", equal_to("LOI_USURE", "ARCHARD"),
             {"MOBILE": _law(_ARCHARD, "the mobile's coefficient", ("COEF_USURE",)),
              "OBSTACLE": _law(_ARCHARD, "the obstacle's coefficient", ("COEF_USURE",)),
              "SECTEUR": Fact({"COEF_USUR_MOBILE": _r("sector coefficient of the mobile "
                                                      "[Pa⁻¹], default 0"),
                               "COEF_USUR_OBST": _r("sector coefficient of the obstacle [Pa⁻¹]"),
                               "ANGL_INIT": _r("start angle [deg]: -180 in the first sector, "
                                               "then the previous ANGL_FIN"),
                               "ANGL_FIN": _r("end angle [deg]: 180 in the last sector"),
                               "CONTACT": Simp("TXM", into=tuple(CONTACT_TYPES),
                                               help="contact type (catalogues up to code_aster "
                                                    "13; it does not change a sector's depth)")},
                              max="**", help="angular sectors and their coefficients"),
              **_MATERIALS},
             rules=(UN_PARMI("MOBILE", "MATER_USURE", "SECTEUR"), *_LAW_RULES[1:])),
        Bloc("LOI_USURE='KWU_EPRI'", equal_to("LOI_USURE", "KWU_EPRI"),
             {"MOBILE": _law(_KWU, "the mobile's coefficients"),
              "OBSTACLE": _law(_KWU, "the obstacle's coefficients", ("COEF_USURE",)),
              **_MATERIALS,
              "FNOR_MAXI": _r("force class range [N] (default the largest force)"),
              "VTAN_MAXI": _r("speed class range [m/s] (default the largest speed)")},
             rules=_LAW_RULES),
        Bloc("LOI_USURE='EDF_MZ'", equal_to("LOI_USURE", "EDF_MZ"),
             {"MOBILE": _law(_EDF_MZ, "the mobile's coefficients"),
              "OBSTACLE": _law(_EDF_MZ, "the obstacle's coefficients"),
              **_MATERIALS},
             rules=_LAW_RULES),
        Bloc("TUBE_NEUF is absent", absent("TUBE_NEUF"),
             {"INST_INIT": _r("start of the history window t_start [s]"),
              "NB_BLOC": Simp("I", default=1, help="number of blocks of the power computation"),
              "COEF_INST": _r("seconds per user time unit [s]", default=1.0),
              "INST": _r("instants of service [user unit]", max="**"),
              "LIST_INST": Simp("listr8", help="instants of service, a sequence [user unit]")},
             rules=(UN_PARMI("INST", "LIST_INST"),)),
        Bloc("TUBE_NEUF='OUI'", exists("TUBE_NEUF"),
             {"INST": _r("instant of the replacement [user unit] (default the last); one "
                         "value", max="**"),
              "TABL_USURE": Simp("table", "o", help="the table of the tube replaced")}),
    ),
)

#: The keywords that Code_Aster's catalogue does not have.
EXTRA_KEYWORDS: tuple[str, ...] = ("EPAIS_PAROI", "LIMITE_PAROI")
#: Every keyword of POST_USURE and its meaning (from :data:`CATALOGUE`).
SIMPLE_KEYWORDS: dict[str, str] = {
    k: v for k, v in CATALOGUE.describe().items()
    if not isinstance(CATALOGUE.all_keywords()[k][0], Fact)}
#: Factor keywords and the keywords each accepts (every block's, from :data:`CATALOGUE`).
FACTOR_KEYWORDS: dict[str, tuple[str, ...]] = {
    k: tuple(dict.fromkeys(key for d in defs for key in d.keywords))
    for k, defs in CATALOGUE.all_keywords().items() if isinstance(defs[0], Fact)}
#: Geometry keyword -> native dimension name (the geometry's table, inverted).
DIMENSIONS: dict[str, str] = {keyword: name for name, keyword in ASTER_KEYWORDS.items()}

#: Code_Aster's MATER_USURE codes (its database routine ``usuban``) that fretwear's database
#: (the coefficient tables of Code_Aster R7.20.01 §3, theory §5) names otherwise:
#: code -> ((mobile, obstacle), why).
MATERIAL_CODES: dict[str, tuple[tuple[str, str], str]] = {
    "NITRURE_A304L": (("A304LNI", "A304L"), "a nitrided 304L control rod on 304L"),
    "CHROME_A304L": (("A304LCR", "A304L"), "a chromium-plated 304L control rod on 304L"),
    "I690_Z6C13": (("I690TT", "Z6C13"), "Inconel 690 on Z6C13: the reference manual's pair "
                                        "is the thermally treated I690TT"),
}


def materials_of(value: Any) -> tuple[str, str]:
    """The (mobile, obstacle) material codes of a MATER_USURE value.

    Code_Aster writes ``'I600_Z6C13'`` (mobile and obstacle joined by an underscore, as in its
    ``usuban``); ``'I600/Z6C13'``, ``'I600 Z6C13'`` and a pair ``('I600', 'Z6C13')`` are accepted
    too. A Code_Aster code of :data:`MATERIAL_CODES` maps to fretwear's pair with a warning.

    Examples
    --------
    >>> materials_of("I600_Z6C13"), materials_of(("I600", "Z10C13"))
    (('I600', 'Z6C13'), ('I600', 'Z10C13'))
    """
    if isinstance(value, str):
        code = value.strip().upper()
        if code in MATERIAL_CODES:
            pair, why = MATERIAL_CODES[code]
            warnings.warn(f"POST_USURE: MATER_USURE='{value}' is Code_Aster's code for {why}: "
                          f"fretwear's pair {pair[0]}/{pair[1]} (its coefficients are the "
                          "reference manual's, theory §5)", FretwearWarning, stacklevel=3)
            return pair
        for sep in ("/", "_", " ", ","):
            parts = [p.strip() for p in code.split(sep) if p.strip()]
            if len(parts) == 2:
                return parts[0], parts[1]
    elif isinstance(value, list | tuple) and len(value) == 2:
        return str(value[0]).strip().upper(), str(value[1]).strip().upper()
    raise KeywordError(f"POST_USURE: MATER_USURE must name the mobile and obstacle materials, "
                       f"e.g. 'I600_Z6C13' (Code_Aster), 'I600/Z6C13' or ('I600', 'Z6C13'), "
                       f"got {value!r}")


def _aster_pairs(contact: str, law: str) -> str:
    """The database's pairs of a contact type and law in MATER_USURE's Code_Aster form."""
    db = load_database()
    rows = db[(db["contact_type"] == contact) & (db["law"] == law)]
    pairs = dict.fromkeys(f"{m}_{o}" for m, o in zip(rows["mobile_material"],
                                                       rows["obstacle_material"], strict=True))
    codes = [f"{c} (= {p[0]}_{p[1]})" for c, (p, _) in MATERIAL_CODES.items()
             if f"{p[0]}_{p[1]}" in pairs]
    text = ", ".join(pairs) or "none"
    return text + (f"; Code_Aster's codes {', '.join(codes)}" if codes else "")


def POST_USURE(**keywords: Any) -> pd.DataFrame:  # noqa: N802 - Code_Aster's name
    """Code_Aster's wear operator with its keywords (theory §7; POST_USURE, U4.84.05).

    Parameters
    ----------
    **keywords
        The keywords of the command (:data:`CATALOGUE`; :data:`SIMPLE_KEYWORDS`,
        :data:`FACTOR_KEYWORDS`), SI units, angles in degrees. Factor keywords as :class:`_F`
        (or tuples of them).

    Returns
    -------
    pandas.DataFrame
        The wear table with Code_Aster's column names (PUIS_USUR_GLOBAL, INST, DUREE,
        ORIG_INST, V_USUR_TUBE, ...); P_USUR_OBST only when the obstacle wears. With SECTEUR
        and no CONTACT the global depths are NaN (``attrs['global_depth']`` says why).

    Raises
    ------
    KeywordError
        An unknown keyword, a keyword of an inactive block, a bad value or a violated catalogue
        rule, naming the keywords.
    DatabaseError
        A MATER_USURE pair without coefficients (the pairs that exist are listed).

    Notes
    -----
    Archard: ``V = COEF_USURE · PUIS_USURE · INST · COEF_INST``; depths from the geometry of
    CONTACT (theory §4, §6). Forms Code_Aster accepts and fretwear follows: ``reuse=`` with
    ETAT_INIT or TUBE_NEUF (the table given to TABL_USURE; the result is a new table), ANGL_INIT
    in the first SECTEUR only, SECTEUR without COEF_USUR_MOBILE (0), without LARGEUR_OBST
    (0.011 m, warned), without CONTACT (sector depths only), PUIS_USURE with INST_INIT,
    INST_FIN or NB_BLOC (ignored, warned), TUBE_NEUF before the last instant (later rows kept,
    the tube restarted from zero).

    Examples
    --------
    >>> t = POST_USURE(PUIS_USURE=0.01, LOI_USURE="ARCHARD", MOBILE=_F(COEF_USURE=1e-14),
    ...                CONTACT="TUBE_ALESAGE", RAYON_MOBILE=0.01, LARGEUR_OBST=0.02,
    ...                INST=(1.0,), COEF_INST=3600.0)
    >>> t[["INST", "V_USUR_TUBE"]].values.tolist()
    [[1.0, 3.6e-13]]
    """
    kw = CATALOGUE.check(keywords)
    _check_reuse(kw)
    if "TUBE_NEUF" in kw:
        instant = kw.get("INST", [None])
        if len(instant) != 1:
            raise KeywordError(f"POST_USURE: under TUBE_NEUF, INST is one instant (of the "
                               f"replacement), got {instant}")
        table = to_aster_names(replace_tube(kw["TABL_USURE"], instant[0]))
        if "TITRE" in kw:
            table.attrs["title"] = kw["TITRE"]
        return table
    law = kw["LOI_USURE"]
    if "PUIS_USURE" in kw:
        ignored = [k for k in ("INST_INIT", "INST_FIN", "NB_BLOC") if k in kw]
        if ignored:
            warnings.warn(f"POST_USURE: {', '.join(ignored)} apply to RESU_GENE (the window and "
                          "blocks of the power computed from the history); with PUIS_USURE they "
                          "are ignored, as in Code_Aster", UnusedKeywordWarning, stacklevel=2)
            kw = {k: v for k, v in kw.items() if k not in ignored}
    if "USURE_OBST" in kw and "MATER_USURE" not in kw:
        warnings.warn("POST_USURE: USURE_OBST takes the obstacle's coefficient from the database "
                      "of MATER_USURE; without MATER_USURE it is ignored", UnusedKeywordWarning,
                      stacklevel=2)
    contact = kw.get("CONTACT")
    sectors = sector_coefficients = None
    dimensions = {DIMENSIONS[k]: v for k, v in kw.items() if k in DIMENSIONS}
    if "SECTEUR" in kw:
        sectors, sector_coefficients, contact = _secteurs(kw["SECTEUR"], contact)
        if "OBSTACLE" in kw:
            warnings.warn("POST_USURE: with SECTEUR the obstacle's coefficients are the sectors' "
                          "COEF_USUR_OBST; OBSTACLE is not used (as in Code_Aster's usuvu2)",
                          UnusedKeywordWarning, stacklevel=2)
        if "obstacle_width" not in dimensions:
            warnings.warn(f"POST_USURE: SECTEUR without LARGEUR_OBST: the sector depths use "
                          f"LARGEUR_OBST = {DEFAULT_SECTOR_WIDTH} m, Code_Aster's default "
                          "(op0153); give LARGEUR_OBST", UnusedKeywordWarning, stacklevel=2)
            dimensions["obstacle_width"] = DEFAULT_SECTOR_WIDTH
    elif contact is None:
        raise KeywordError("POST_USURE: CONTACT is required (the contact type gives the depths; "
                           "only SECTEUR computes its sector depths without it)")
    materials = materials_of(kw["MATER_USURE"]) if "MATER_USURE" in kw else None
    etat = first(kw.get("ETAT_INIT", []))
    if kw.get("ETAT_INIT") and "TABL_USURE" not in etat:
        raise KeywordError("POST_USURE: ETAT_INIT needs TABL_USURE (the table to continue)")
    mobile, obstacle = first(kw.get("MOBILE", [])), first(kw.get("OBSTACLE", []))
    source = (kw["PUIS_USURE"] if "PUIS_USURE" in kw
              else _history_source(kw["RESU_GENE"], kw.get("NOEUD", kw.get("GROUP_NO"))))
    try:
        given = dict(
            contact_type=contact, dimensions=dimensions,
            instants=kw["INST"] if "INST" in kw else kw["LIST_INST"], law=law,
            coefficients=mobile if "MOBILE" in kw else None,  # _F(): the law's defaults
            obstacle_coefficients=obstacle if "OBSTACLE" in kw else None,
            materials=materials, obstacle_wear="USURE_OBST" in kw and materials is not None,
            sectors=sectors, sector_coefficients=sector_coefficients,
            time_scale=kw.get("COEF_INST"), initial_state=etat.get("TABL_USURE"),
            initial_instant=etat.get("INST_INIT"), t_start=kw.get("INST_INIT"),
            t_end=kw.get("INST_FIN"), blocks=kw.get("NB_BLOC"),
            force_max=kw.get("FNOR_MAXI"), speed_max=kw.get("VTAN_MAXI"),
            wall_thickness=kw.get("EPAIS_PAROI"), depth_limit=kw.get("LIMITE_PAROI"),
            name=kw.get("TITRE"))
        # a keyword not given: its default, written once (fretwear.table.keywords.KEYWORDS)
        case = WearCase.from_keywords(**{k: v for k, v in given.items()
                                         if v is not None or k == "contact_type"})
    except DatabaseError as exc:
        if materials is None or contact is None:
            raise
        raise DatabaseError(f"{str(exc).rstrip('. ')}. MATER_USURE in Code_Aster's form for "
                            f"{contact}/{law}: {_aster_pairs(contact, law)}") from None
    table = wear_table_from_case(case, source)
    return to_aster_names(_obstacle_depths_that_exist(table))


def _same_table(a: Any, b: Any) -> bool:
    if a is b:
        return True
    if isinstance(a, str | os.PathLike) and isinstance(b, str | os.PathLike):
        return os.path.abspath(os.fspath(a)) == os.path.abspath(os.fspath(b))
    return False


def _check_reuse(kw: Mapping[str, Any]) -> None:
    """``reuse=`` names the table POST_USURE continues (Code_Aster's ``reentrant='f:TABL_USURE'``):
    the TABL_USURE of TUBE_NEUF or of ETAT_INIT (op0153: PREPOST4_7, PREPOST4_13)."""
    if "reuse" not in kw:
        return
    target = kw.get("TABL_USURE", first(kw.get("ETAT_INIT", [])).get("TABL_USURE"))
    if target is None:
        raise KeywordError("POST_USURE: reuse= continues the table given to TABL_USURE (under "
                           "ETAT_INIT or TUBE_NEUF); give that table there too")
    if not _same_table(kw["reuse"], target):
        raise KeywordError("POST_USURE: reuse= must be the table given to TABL_USURE (Code_Aster "
                           "continues that table: PREPOST4_7 / PREPOST4_13)")


def _history_source(value: Any, node: str | None):
    """RESU_GENE's history for the shock point ``node`` (NOEUD / GROUP_NO), or its file."""
    if isinstance(value, Mapping):
        if node is None:
            if len(value) != 1:
                raise KeywordError(f"POST_USURE: RESU_GENE holds the nodes {list(value)}: pick "
                                   "one with NOEUD or GROUP_NO")
            node = next(iter(value))
        if node not in value:
            raise KeywordError(f"POST_USURE: NOEUD/GROUP_NO {node!r} is not in RESU_GENE; it "
                               f"holds {list(value)}")
        value, node = value[node], None
    if isinstance(value, ContactHistory):
        stored = value.metadata.get("node") or None
        if node is not None and stored is not None and str(stored).upper() != node.upper():
            raise KeywordError(f"POST_USURE: NOEUD/GROUP_NO {node!r} but RESU_GENE is the "
                               f"history of {stored!r}")
        return value
    if isinstance(value, str | os.PathLike):
        return value if node is None else read_history(value, node=node)
    if isinstance(value, list | tuple) and value and all(isinstance(v, str | os.PathLike)
                                                         for v in value):
        return read_history(list(value), **({} if node is None else {"node": node}))
    raise KeywordError(f"POST_USURE: RESU_GENE must be a ContactHistory, the path of a history "
                       f"file, a list of IMPR_FONCTION files, or a mapping node label -> either; "
                       f"got {type(value).__name__}")


def _obstacle_depths_that_exist(table: pd.DataFrame) -> pd.DataFrame:
    """Drop the obstacle depth columns where no obstacle depth exists (P_USUR_OBST rule).

    ``depth_obstacle`` (P_USUR_OBST) and ``depth_obstacle_sector`` (P_USUR_OBST_SECT) are
    dropped when the obstacle has no volume (it does not wear); ``depth_obstacle_sector`` also
    when no sector has a positive obstacle depth (a contact type without an obstacle radius,
    e.g. TUBE_BAV's flat bar, has no sector depth of the obstacle, theory §3: NaN where it wears).

    Examples
    --------
    >>> t = pd.DataFrame({"volume_obstacle": [1e-9, 1e-9], "depth_obstacle": [1e-5, 1e-5],
    ...                   "depth_obstacle_sector": [np.nan, 0.0]})
    >>> _obstacle_depths_that_exist(t).columns.tolist()
    ['volume_obstacle', 'depth_obstacle']
    """
    volumes = np.nan_to_num(table["volume_obstacle"].to_numpy(dtype=float))
    drop = []
    if not volumes.any():
        drop = ["depth_obstacle", "depth_obstacle_sector"]
    elif "depth_obstacle_sector" in table.columns:
        sector = np.nan_to_num(table["depth_obstacle_sector"].to_numpy(dtype=float))
        if not (sector > 0).any():
            drop = ["depth_obstacle_sector"]
    return table.drop(columns=[c for c in drop if c in table.columns])


def _secteurs(secteurs: list[dict], contact: str | None):
    """Sector edges [deg], (k_mobile, k_obstacle) pairs [Pa⁻¹] and the contact type of the
    SECTEUR occurrences (Code_Aster's op0153: ANGL_INIT read in the first occurrence only and
    equal to -180, ANGL_FIN increasing, the last equal to 180, within 1e-4 deg)."""
    tol = 1e-4
    edges: list[float] = []
    pairs = []
    for i, s in enumerate(secteurs):
        where = f"POST_USURE: SECTEUR[{i}]"
        if i == 0:
            if "ANGL_INIT" not in s:
                raise KeywordError(f"{where} needs ANGL_INIT = -180 (the sectors cover "
                                   "-180..180 deg)")
            if abs(s["ANGL_INIT"] + 180.0) > tol:
                raise KeywordError(f"{where} ANGL_INIT = {s['ANGL_INIT']:g} deg: the first sector "
                                   "starts at -180 deg (the sectors cover -180..180 deg)")
            edges.append(-180.0)
        elif "ANGL_INIT" in s and abs(s["ANGL_INIT"] - edges[-1]) > tol:
            raise KeywordError(f"{where} ANGL_INIT = {s['ANGL_INIT']:g} deg must equal the "
                               f"ANGL_FIN of SECTEUR[{i - 1}] ({edges[-1]:g} deg): sectors are "
                               "contiguous from -180 to 180 deg (or give ANGL_INIT in the first "
                               "sector only)")
        if "ANGL_FIN" not in s:
            raise KeywordError(f"{where} needs ANGL_FIN (the sector's end angle [deg])")
        end = s["ANGL_FIN"]
        if end <= edges[-1]:
            raise KeywordError(f"{where} ANGL_FIN = {end:g} deg must exceed its start "
                               f"{edges[-1]:g} deg (the angles increase from -180 to 180 deg)")
        edges.append(end)
        pairs.append((s.get("COEF_USUR_MOBILE", 0.0), s.get("COEF_USUR_OBST")))
    if abs(edges[-1] - 180.0) > tol:
        raise KeywordError(f"POST_USURE: SECTEUR[{len(secteurs) - 1}] ANGL_FIN = {edges[-1]:g} "
                           "deg: the last sector ends at 180 deg (the sectors cover -180..180 "
                           "deg)")
    edges[-1] = 180.0
    kinds = {s["CONTACT"] for s in secteurs if "CONTACT" in s}
    if contact is None and kinds:
        if len(kinds) != 1:
            raise KeywordError(f"POST_USURE: the SECTEUR occurrences give the contact types "
                               f"{sorted(kinds)}; give one CONTACT for the global depth")
        contact = kinds.pop()
    return edges, pairs, contact
