"""Code_Aster compatibility: ``POST_USURE(**keywords)`` as written in a command file.

A Code_Aster user can paste the keywords of a POST_USURE command::

    from fretwear.workflows.aster import POST_USURE, _F
    table = POST_USURE(RESU_GENE="shock_N12.csv", NOEUD="N12", LOI_USURE="ARCHARD",
                       MOBILE=_F(COEF_USURE=1.2e-13), CONTACT="TUBE_BAV",
                       RAYON_MOBILE=9.525e-3, LARGEUR_OBST=12.7e-3,
                       INST=(1.0, 5.0, 10.0), COEF_INST=3.1536e7)

The catalogue's rules are enforced (exactly one of PUIS_USURE, RESU_GENE, TUBE_NEUF; exactly one
of MOBILE, MATER_USURE, SECTEUR; MATER_USURE excludes OBSTACLE; exactly one of INST, LIST_INST;
NOEUD excludes GROUP_NO ...), each violation a :class:`~fretwear.errors.KeywordError` naming the
keywords. The result is a DataFrame with Code_Aster's column names (theory §7); the computation is
:func:`fretwear.table.wear_table_from_case` of a :class:`~fretwear.table.WearCase`. Values are
SI, angles in degrees, as in Code_Aster.
Deliberate differences from Code_Aster are listed in ``docs/code_aster.md``. Extras beyond the
catalogue (:data:`EXTRA_KEYWORDS`): ``EPAIS_PAROI`` (wall thickness [m]) and ``LIMITE_PAROI``
(depth limit, fraction of the wall), which add the columns FRAC_PAROI and INST_LIMITE.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from fretwear.errors import KeywordError, UnusedKeywordWarning
from fretwear.geometry import CONTACT_TYPES
from fretwear.geometry.base import ASTER_KEYWORDS
from fretwear.history import ContactHistory
from fretwear.laws import WEAR_LAWS
from fretwear.table import WearCase, replace_tube, to_aster_names, wear_table_from_case


class _F(dict):
    """A factor keyword (``MOBILE=_F(COEF_USURE=1e-13)``), a plain dict of keywords.

    Examples
    --------
    >>> _F(COEF_USURE=1e-13)["COEF_USURE"]
    1e-13
    """

    def __repr__(self) -> str:
        return "_F(" + ", ".join(f"{k}={v!r}" for k, v in self.items()) + ")"


#: Simple keywords of POST_USURE and their fretwear meaning.
SIMPLE_KEYWORDS: dict[str, str] = {
    "PUIS_USURE": "wear power [W]",
    "RESU_GENE": "contact history: a ContactHistory, a path, or a mapping label -> either",
    "NOEUD": "shock node label (selects in a RESU_GENE mapping)",
    "GROUP_NO": "shock node group label (selects in a RESU_GENE mapping)",
    "INST_INIT": "start of the history window t_start [s]",
    "INST_FIN": "end of the history window t_end [s]",
    "NB_BLOC": "number of blocks of the power computation",
    "LOI_USURE": f"wear law: {', '.join(WEAR_LAWS)}",
    "MATER_USURE": "material pair of the database: 'MOBILE/OBSTACLE' or a (mobile, obstacle) pair",
    "USURE_OBST": "'OUI': obstacle coefficient from the database",
    "FNOR_MAXI": "KWU_EPRI force class range [N]",
    "VTAN_MAXI": "KWU_EPRI speed class range [m/s]",
    "CONTACT": f"contact type: {', '.join(CONTACT_TYPES)}",
    "RAYON_MOBILE": "mobile radius [m]",
    "RAYON_OBST": "obstacle radius [m]",
    "LARGEUR_OBST": "obstacle width [m]",
    "ANGL_INCLI": "tilt angle [deg]",
    "ANGL_ISTHME": "isthmus angle [deg]",
    "ANGL_IMPACT": "impact angle [deg]",
    "INST": "instants of service [user unit] (or the replacement instant under TUBE_NEUF)",
    "LIST_INST": "instants of service, a sequence [user unit]",
    "COEF_INST": "seconds per user time unit [s]",
    "TUBE_NEUF": "'OUI': replace the tube in TABL_USURE",
    "TABL_USURE": "wear table of TUBE_NEUF (DataFrame or path)",
    "TITRE": "title (ignored)",
    "INFO": "verbosity (ignored)",
    # fretwear extras, not in Code_Aster's catalogue
    "EPAIS_PAROI": "wall thickness of the tube [m] (fretwear extra): adds FRAC_PAROI and "
                   "INST_LIMITE (the instant the depth reaches LIMITE_PAROI of the wall)",
    "LIMITE_PAROI": "depth limit as a fraction of the wall [-], default 0.4 (fretwear extra)",
}
#: The keywords of :data:`SIMPLE_KEYWORDS` that Code_Aster's catalogue does not have.
EXTRA_KEYWORDS: tuple[str, ...] = ("EPAIS_PAROI", "LIMITE_PAROI")
#: Factor keywords and the keywords each accepts.
FACTOR_KEYWORDS: dict[str, tuple[str, ...]] = {
    "MOBILE": ("COEF_USURE", "COEF_FNOR", "COEF_VTAN", "COEF_K", "COEF_C", "COEF_B", "COEF_N",
               "COEF_S"),
    "OBSTACLE": ("COEF_USURE", "COEF_FNOR", "COEF_VTAN", "COEF_K", "COEF_C", "COEF_B", "COEF_N",
                 "COEF_S"),
    "SECTEUR": ("CONTACT", "COEF_USUR_MOBILE", "COEF_USUR_OBST", "ANGL_INIT", "ANGL_FIN"),
    "ETAT_INIT": ("TABL_USURE", "INST_INIT"),
}
#: Geometry keyword -> native dimension name (the geometry's table, inverted).
DIMENSIONS: dict[str, str] = {keyword: name for name, keyword in ASTER_KEYWORDS.items()}
_TUBE_NEUF_KEYWORDS = ("TUBE_NEUF", "TABL_USURE", "INST", "TITRE", "INFO")


def _one_of(kw: Mapping[str, Any], names: Sequence[str], context: str = "") -> str:
    given = [n for n in names if kw.get(n) is not None]
    if len(given) != 1:
        what = "none" if not given else " and ".join(given)
        raise KeywordError(f"POST_USURE{context}: exactly one of {', '.join(names)} is required, "
                           f"got {what}")
    return given[0]


def _exclusive(kw: Mapping[str, Any], a: str, b: str, context: str = "") -> None:
    if kw.get(a) is not None and kw.get(b) is not None:
        raise KeywordError(f"POST_USURE{context}: {a} excludes {b}; give only one of them")


def _fact(value: Any, name: str, multiple: bool = False) -> list[dict]:
    """A factor keyword's occurrences as a list of dicts, unknown keywords rejected."""
    if value is None:
        return []
    items = list(value) if isinstance(value, list | tuple) else [value]
    if not multiple and len(items) != 1:
        raise KeywordError(f"POST_USURE: {name} takes one occurrence, got {len(items)}")
    out = []
    for i, item in enumerate(items):
        if not isinstance(item, Mapping):
            raise KeywordError(f"POST_USURE: {name} must be given as _F(...), got {item!r}")
        unknown = [k for k in item if k not in FACTOR_KEYWORDS[name]]
        if unknown:
            where = f"{name}[{i}]" if multiple else name
            raise KeywordError(f"POST_USURE: unknown keyword(s) {unknown} in {where}; it accepts "
                               f"{list(FACTOR_KEYWORDS[name])}")
        out.append(dict(item))
    return out


def _real(value: Any, name: str) -> float:
    """A keyword's real value (Code_Aster ``typ='R'``), or an error naming the keyword.

    Examples
    --------
    >>> _real(3, "COEF_INST")
    3.0
    """
    if isinstance(value, bool | str | bytes) or value is None:
        ok = False
    else:
        try:
            out = float(value)
            ok = bool(np.isfinite(out))
        except (TypeError, ValueError):
            ok = False
    if not ok:
        raise KeywordError(f"POST_USURE: {name} must be a finite real number, got {value!r}")
    return out


def _integer(value: Any, name: str) -> int:
    """A keyword's integer value (Code_Aster ``typ='I'``), or an error naming the keyword.

    Examples
    --------
    >>> _integer(4.0, "NB_BLOC")
    4
    """
    real = _real(value, name)
    if real != int(real):
        raise KeywordError(f"POST_USURE: {name} must be a whole number, got {value!r}")
    return int(real)


def _reals(value: Any, name: str) -> list[float]:
    """A keyword's list of reals (``max='**'``): a number or a sequence of numbers."""
    if np.isscalar(value) or isinstance(value, bool):
        return [_real(value, name)]
    try:
        items = list(value)
    except TypeError:
        raise KeywordError(f"POST_USURE: {name} must be a real or a sequence of reals, "
                           f"got {value!r}") from None
    return [_real(v, f"{name}[{i}]") for i, v in enumerate(items)]


def _yes(value: Any, name: str) -> bool:
    if value is None:
        return False
    if str(value).upper() != "OUI":
        raise KeywordError(f"POST_USURE: {name} accepts only 'OUI', got {value!r}")
    return True


def _materials(value: Any) -> tuple[str, str]:
    if isinstance(value, str):
        for sep in ("/", " ", ","):
            parts = [p for p in value.split(sep) if p]
            if len(parts) == 2:
                return parts[0].strip(), parts[1].strip()
    elif isinstance(value, Sequence) and len(value) == 2:
        return str(value[0]), str(value[1])
    raise KeywordError(f"POST_USURE: MATER_USURE must name the mobile and obstacle materials, "
                       f"e.g. 'I600/Z10C13' or ('I600', 'Z10C13'), got {value!r}")


def _history(kw: Mapping[str, Any]):
    source = kw["RESU_GENE"]
    _exclusive(kw, "NOEUD", "GROUP_NO")
    label = kw.get("NOEUD", kw.get("GROUP_NO"))
    if isinstance(source, Mapping):
        if label is None:
            if len(source) != 1:
                raise KeywordError(f"POST_USURE: RESU_GENE holds the nodes {list(source)}: pick "
                                   "one with NOEUD or GROUP_NO")
            label = next(iter(source))
        if label not in source:
            raise KeywordError(f"POST_USURE: NOEUD/GROUP_NO {label!r} is not in RESU_GENE; it "
                               f"holds {list(source)}")
        source = source[label]
    if not isinstance(source, ContactHistory | str | os.PathLike):
        raise KeywordError(f"POST_USURE: RESU_GENE must be a ContactHistory, the path of a "
                           f"history file, or a mapping node label -> either; got "
                           f"{type(source).__name__}")
    return source


def POST_USURE(**keywords: Any) -> pd.DataFrame:  # noqa: N802 - Code_Aster's name
    """Code_Aster's wear operator with its keywords (theory §7; POST_USURE [U4.84.05]).

    Parameters
    ----------
    **keywords
        The keywords of the command (see :data:`SIMPLE_KEYWORDS`, :data:`FACTOR_KEYWORDS`),
        SI units, angles in degrees. Factor keywords as :class:`_F` (or tuples of them).

    Returns
    -------
    pandas.DataFrame
        The wear table with Code_Aster's column names (PUIS_USUR_GLOBAL, INST, DUREE,
        ORIG_INST, V_USUR_TUBE, ...); P_USUR_OBST only when the obstacle wears.

    Raises
    ------
    KeywordError
        An unknown keyword, or a violated catalogue rule, naming the keywords.

    Notes
    -----
    Archard: ``V = COEF_USURE · PUIS_USURE · INST · COEF_INST``; depths from the geometry of
    CONTACT (theory §4, §6).

    Examples
    --------
    >>> t = POST_USURE(PUIS_USURE=0.01, LOI_USURE="ARCHARD", MOBILE=_F(COEF_USURE=1e-14),
    ...                CONTACT="TUBE_ALESAGE", RAYON_MOBILE=0.01, LARGEUR_OBST=0.02,
    ...                INST=(1.0,), COEF_INST=3600.0)
    >>> t[["INST", "V_USUR_TUBE"]].values.tolist()
    [[1.0, 3.6e-13]]
    """
    allowed = set(SIMPLE_KEYWORDS) | set(FACTOR_KEYWORDS)
    unknown = sorted(k for k in keywords if k not in allowed)
    if unknown:
        raise KeywordError(f"POST_USURE: unknown keyword(s) {unknown}; POST_USURE accepts "
                           f"{sorted(allowed)}")
    kw = {k: v for k, v in keywords.items() if v is not None}
    kind = _one_of(kw, ("PUIS_USURE", "RESU_GENE", "TUBE_NEUF"))
    if kind == "TUBE_NEUF":
        return _tube_neuf(kw)
    law = str(kw.get("LOI_USURE", "")).upper()
    if not law:
        raise KeywordError(f"POST_USURE: LOI_USURE is required ({', '.join(WEAR_LAWS)})")
    if law not in WEAR_LAWS:
        raise KeywordError(f"POST_USURE: LOI_USURE={kw['LOI_USURE']!r} is not a wear law; "
                           f"choose one of {sorted(WEAR_LAWS)}")
    if "TABL_USURE" in kw:
        raise KeywordError("POST_USURE: TABL_USURE goes under TUBE_NEUF='OUI', or inside "
                           "ETAT_INIT=_F(TABL_USURE=...) to continue a table")
    coef_kind = _one_of(kw, ("MOBILE", "MATER_USURE", "SECTEUR"))
    _exclusive(kw, "MATER_USURE", "OBSTACLE")
    if "USURE_OBST" in kw and coef_kind != "MATER_USURE":
        raise KeywordError("POST_USURE: USURE_OBST goes with MATER_USURE (the obstacle "
                           "coefficient comes from the database); give OBSTACLE=_F(...) instead")
    times = _one_of(kw, ("INST", "LIST_INST"))
    if kind == "PUIS_USURE":
        for k in ("NOEUD", "GROUP_NO", "INST_INIT", "INST_FIN", "NB_BLOC"):
            if k in kw:
                raise KeywordError(f"POST_USURE: {k} applies to RESU_GENE, not to PUIS_USURE")

    mobile = _fact(kw.get("MOBILE"), "MOBILE")
    obstacle = _fact(kw.get("OBSTACLE"), "OBSTACLE")
    etat = _fact(kw.get("ETAT_INIT"), "ETAT_INIT")
    secteurs = _fact(kw.get("SECTEUR"), "SECTEUR", multiple=True)
    if etat and etat[0].get("TABL_USURE") is None:
        raise KeywordError("POST_USURE: ETAT_INIT needs TABL_USURE (the table to continue)")
    contact = kw.get("CONTACT")
    sectors = sector_coefficients = None
    if secteurs:
        sectors, sector_coefficients, contact = _secteurs(secteurs, contact)
    if contact is None:
        raise KeywordError("POST_USURE: CONTACT is required (the contact type gives the depths)")
    dimensions = {DIMENSIONS[k]: _real(v, k) for k, v in kw.items() if k in DIMENSIONS}
    instants = _reals(kw[times], times)
    coefficients = None
    if mobile:
        coefficients = _law_keywords(mobile[0], law, "MOBILE")

    def optional(name: str) -> float | None:
        return None if name not in kw else _real(kw[name], name)

    if kind == "PUIS_USURE":
        source = _real(kw["PUIS_USURE"], "PUIS_USURE")
    else:
        source = _history(kw)
    etat_instant = None
    if etat and etat[0].get("INST_INIT") is not None:
        etat_instant = _real(etat[0]["INST_INIT"], "ETAT_INIT INST_INIT")
    # the rules between the keywords (FNOR_MAXI with KWU_EPRI, SECTEUR with ARCHARD, ...)
    # are the wear case's, checked once by WearCase
    case = WearCase.from_keywords(
        contact_type=str(contact), dimensions=dimensions, instants=instants, law=law,
        coefficients=coefficients,
        obstacle_coefficients=_law_keywords(obstacle[0], law, "OBSTACLE") if obstacle else None,
        materials=_materials(kw["MATER_USURE"]) if coef_kind == "MATER_USURE" else None,
        obstacle_wear=_yes(kw.get("USURE_OBST"), "USURE_OBST"), sectors=sectors,
        sector_coefficients=sector_coefficients,
        time_scale=_real(kw.get("COEF_INST", 1.0), "COEF_INST"),
        initial_state=etat[0].get("TABL_USURE") if etat else None,
        initial_instant=etat_instant, t_start=optional("INST_INIT"), t_end=optional("INST_FIN"),
        blocks=_integer(kw.get("NB_BLOC", 1), "NB_BLOC"),
        force_max=optional("FNOR_MAXI"), speed_max=optional("VTAN_MAXI"),
        wall_thickness=optional("EPAIS_PAROI"),
        depth_limit=0.4 if "LIMITE_PAROI" not in kw else _real(kw["LIMITE_PAROI"],
                                                               "LIMITE_PAROI"))
    table = wear_table_from_case(case, source)
    return to_aster_names(_obstacle_depths_that_exist(table))


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


def _law_keywords(fact: Mapping[str, Any], law: str, name: str) -> dict[str, float]:
    """The law's coefficients from MOBILE/OBSTACLE keywords (Code_Aster names)."""
    known = set(dict(getattr(WEAR_LAWS[law], "aster_keywords", {})).values())
    extra = [k for k in fact if k not in known]
    if extra:
        raise KeywordError(f"POST_USURE: {name} keyword(s) {extra} do not belong to "
                           f"LOI_USURE='{law}', which takes {sorted(known)}")
    return {k: _real(v, f"{name} {k}") for k, v in fact.items()}


def _secteurs(secteurs: list[dict], contact: Any):
    edges: list[float] = []
    pairs = []
    for i, s in enumerate(secteurs):
        for k in ("ANGL_INIT", "ANGL_FIN", "COEF_USUR_MOBILE"):
            if s.get(k) is None:
                raise KeywordError(f"POST_USURE: SECTEUR[{i}] needs {k}")
        start = _real(s["ANGL_INIT"], f"SECTEUR[{i}] ANGL_INIT")
        if not edges:
            edges.append(start)
        elif abs(start - edges[-1]) > 1e-9:
            raise KeywordError(f"POST_USURE: SECTEUR[{i}] ANGL_INIT = {s['ANGL_INIT']} must equal "
                               f"the ANGL_FIN of SECTEUR[{i - 1}] ({edges[-1]}): sectors are "
                               "contiguous from -180 to 180 deg")
        edges.append(_real(s["ANGL_FIN"], f"SECTEUR[{i}] ANGL_FIN"))
        obst = s.get("COEF_USUR_OBST")
        pairs.append((_real(s["COEF_USUR_MOBILE"], f"SECTEUR[{i}] COEF_USUR_MOBILE"),
                      None if obst is None else _real(obst, f"SECTEUR[{i}] COEF_USUR_OBST")))
    kinds = {str(s["CONTACT"]).upper() for s in secteurs if s.get("CONTACT") is not None}
    if contact is None:
        if len(kinds) != 1:
            raise KeywordError(f"POST_USURE: the SECTEUR occurrences give the contact types "
                               f"{sorted(kinds) or 'none'}; give one CONTACT for the global depth")
        contact = kinds.pop()
    return edges, pairs, contact


def _tube_neuf(kw: Mapping[str, Any]) -> pd.DataFrame:
    _yes(kw["TUBE_NEUF"], "TUBE_NEUF")
    if kw.get("TABL_USURE") is None:
        raise KeywordError("POST_USURE: TUBE_NEUF='OUI' needs TABL_USURE (the table of the "
                           "tube being replaced)")
    extra = sorted(k for k in kw if k not in _TUBE_NEUF_KEYWORDS)
    if extra:
        warnings.warn(f"POST_USURE: with TUBE_NEUF only {list(_TUBE_NEUF_KEYWORDS)} are used; "
                      f"ignored {extra}", UnusedKeywordWarning, stacklevel=3)
    instant = kw.get("INST")
    if instant is not None and not np.isscalar(instant):
        if len(instant) != 1:
            raise KeywordError("POST_USURE: under TUBE_NEUF, INST is one instant (of the "
                               f"replacement), got {list(instant)}")
        instant = instant[0]
    return to_aster_names(replace_tube(kw["TABL_USURE"], None if instant is None
                                       else _real(instant, "INST")))
