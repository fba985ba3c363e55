"""Code_Aster compatibility: ``POST_DYNA_MODA_T(RESU_GENE=..., CHOC=_F(OPTION=...))``.

Code_Aster's POST_DYNA_MODA_T post-processes the shocks of a transient modal computation
(``bibfor/op/op0130.F90``): with ``OPTION='USURE'`` (``statch``) the statistics of the local
displacements, of the normal and tangential forces, of the shocks and the wear power of every
shock point; with ``OPTION='IMPACT'`` (``statim``, ``impact``) one row per impact (instant of the
peak, peak force, impulse, duration, impact velocity, rebounds), the peaks' maximum, mean and
standard deviation, and their histogram. This facade computes the same tables, with Code_Aster's
column names, from fretwear contact histories: the wear power from
:func:`fretwear.power.wear_power`, the force and shock statistics from
:func:`fretwear.power.contact_statistics`, the impacts from :func:`fretwear.power.impacts` and the
displacement and tangential-force statistics from :func:`fretwear.power.channel_statistics`, on
their piecewise-linear reading of the samples (Code_Aster averages the samples; the differences
are listed in ``docs/code_aster.md``).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FormatError, FretwearError, KeywordError
from fretwear.history import ContactHistory, contact_angle
from fretwear.io import read_history
from fretwear.io.aster_source import shock_nodes
from fretwear.power import channel_statistics, contact_statistics, impacts, wear_power
from fretwear.workflows.aster_catalogue import _F, EXCLUS, UN_PARMI, Catalogue, Fact, Simp

__all__ = ["POST_DYNA_MODA_T", "CATALOGUE_POST_DYNA_MODA_T", "USURE_COLUMNS", "IMPACT_COLUMNS",
           "_F"]

#: POST_DYNA_MODA_T's catalogue (code_aster 16, ``code_aster/Cata/Commands/
#: post_dyna_moda_t.py``).
CATALOGUE_POST_DYNA_MODA_T = Catalogue(
    name="POST_DYNA_MODA_T",
    source="code_aster/Cata/Commands/post_dyna_moda_t.py (code_aster 16, 2022)",
    rules=(UN_PARMI("CHOC", "RELA_EFFO_DEPL"),),
    keywords={
        "RESU_GENE": Simp("history", "o", help="the shock points' histories: a ContactHistory, "
                                               "a history file (a table of several shock points: "
                                               "every one), or a mapping node -> either"),
        "CHOC": Fact({
            "INST_INIT": Simp("R", default=-1.0, help="start of the window [s] (clipped to the "
                                                      "record)"),
            "INST_FIN": Simp("R", default=999.0, help="end of the window [s] (clipped)"),
            "NB_BLOC": Simp("I", default=1, help="number of blocks of equal duration"),
            "SEUIL_FORCE": Simp("R", default=0.0, help="contact force threshold F_s [N]"),
            "DUREE_REPOS": Simp("R", default=0.0, help="rest separating two impacts [s]"),
            "OPTION": Simp("TXM", default="USURE", into=("IMPACT", "USURE"),
                           help="USURE: statistics and wear power; IMPACT: impacts one by one"),
            "NB_CLASSE": Simp("I", default=10, help="classes of the impact-peak histogram"),
        }, max="**", help="statistics of the shocks"),
        "RELA_EFFO_DEPL": Fact({"NOEUD": Simp("node", "c"), "GROUP_NO": Simp("group"),
                                "NOM_CMP": Simp("TXM", "o")},
                               rules=(UN_PARMI("NOEUD", "GROUP_NO"), EXCLUS("NOEUD", "GROUP_NO")),
                               help="force-displacement relations (not available)"),
        "INFO": Simp("I", default=1, into=(1, 2), help="verbosity (ignored)"),
        "TITRE": Simp("TXM", help="title of the table (attrs['title'])"),
    },
)

#: Columns of the USURE table (Code_Aster's ``statch``), in order.
USURE_COLUMNS = ("INTITULE", "NOEUD", "CALCUL", "MOYEN", "ECART_TYPE", "RMS", "MAXI", "MINI",
                 "MOYEN_T_TOTAL", "MOYEN_T_CHOC", "RMS_T_TOTAL", "RMS_T_CHOC", "NB_CHOC_S",
                 "NB_REBON_CHOC", "T_CHOC_MOYEN", "T_CHOC_MAXI", "T_CHOC_MINI", "T_REBON_MOYEN",
                 "%_T_CHOC", "PUIS_USURE")
#: Columns of the IMPACT table (Code_Aster's ``statim``), in order.
IMPACT_COLUMNS = ("INTITULE", "NOEUD", "CALCUL", "CHOC", "INSTANT", "F_MAX", "IMPULSION",
                  "T_CHOC", "V_IMPACT", "NB_IMPACT", "F_MAX_ABS", "F_MAX_MOY", "F_MAX_ETYPE",
                  "CLASSE", "DEBUT", "FIN", "PROBA")
_INTEGER = ("CHOC", "NB_IMPACT", "CLASSE")
_STAT = {"mean": "MOYEN", "std": "ECART_TYPE", "rms": "RMS", "max": "MAXI", "min": "MINI"}


def _shocks(value: Any) -> list[tuple[str, str, ContactHistory]]:
    """(INTITULE, NOEUD, history) of every shock point of RESU_GENE."""
    def read(item: Any, node: str | None) -> ContactHistory:
        if isinstance(item, ContactHistory):
            return item
        if isinstance(item, str | os.PathLike):
            return read_history(item, **({} if node is None else {"node": node}))
        raise KeywordError(f"POST_DYNA_MODA_T: RESU_GENE must hold ContactHistory objects or "
                           f"history files, got {type(item).__name__}")

    if isinstance(value, Mapping):
        out = []
        for node, item in value.items():
            h = read(item, str(node) if isinstance(item, str | os.PathLike) else None)
            out.append((h.name or str(node), str(node), h))
        return out
    try:
        h = read(value, None)
    except FormatError as exc:
        # a table of several shock points (a NOEUD column): every one, named by its node, as
        # Code_Aster does for a tran_gene holding several shocks
        try:
            nodes = shock_nodes(value) if isinstance(value, str | os.PathLike) else []
        except FretwearError:
            nodes = []
        if len(nodes) < 2:
            raise exc from None
        return [(node, node, read(value, node)) for node in nodes]
    node = str(h.metadata.get("node") or h.name or "CHOC1")
    return [(h.name or node, node, h)]


def _window(h: ContactHistory, occ: Mapping[str, Any]) -> tuple[float, float]:
    """Code_Aster's window: INST_INIT/INST_FIN clipped to the record (pochoc), checked."""
    lo = max(float(occ.get("INST_INIT", -1.0)), float(h.time[0]))
    hi = min(float(occ.get("INST_FIN", 999.0)), float(h.time[-1]))
    if lo >= hi:
        raise KeywordError(f"POST_DYNA_MODA_T: CHOC INST_INIT = {lo:g} s is not before INST_FIN "
                           f"= {hi:g} s within the record {float(h.time[0]):g} .. "
                           f"{float(h.time[-1]):g} s of {h.name!r} (Code_Aster PREPOST4_47)")
    return lo, hi


def _usure_rows(intitule: str, node: str, h: ContactHistory, occ: Mapping[str, Any]
                ) -> list[dict]:
    lo, hi = _window(h, occ)
    blocks = int(occ.get("NB_BLOC", 1))
    threshold, rest = float(occ.get("SEUIL_FORCE", 0.0)), float(occ.get("DUREE_REPOS", 0.0))
    head = {"INTITULE": intitule, "NOEUD": node}

    def signal(calcul: str, values) -> dict:
        row = dict(head, CALCUL=calcul)
        if values is not None:
            s = channel_statistics(h.time, values, t_start=lo, t_end=hi, blocks=blocks)
            row.update({_STAT[k]: v for k, v in s.items()})
        return row

    dy, dz = h.dy, h.dz
    rows = [signal("DEPL_X", None), signal("DEPL_Y", dy), signal("DEPL_Z", dz),
            signal("DEPL_RADIAL", None if dy is None else np.hypot(dy, dz)),
            signal("DEPL_ANGULAIRE", None if dy is None else contact_angle(dy, dz))]
    stats = contact_statistics(h, t_start=lo, t_end=hi, blocks=blocks,
                               force_threshold=threshold, minimum_rest_time=rest)
    rows.append(dict(head, CALCUL="FORCE_NORMALE", MOYEN_T_TOTAL=stats.force_mean,
                     MOYEN_T_CHOC=stats.force_mean_contact, RMS_T_TOTAL=stats.force_rms,
                     RMS_T_CHOC=stats.force_rms_contact, MAXI=stats.force_max))
    rows += [signal("FORCE_TANG_1", h.ft1), signal("FORCE_TANG_2", h.ft2)]
    table = impacts(h, t_start=lo, t_end=hi, force_threshold=threshold,
                    minimum_rest_time=rest)
    n, duration = len(table), hi - lo
    episodes = int(table["episodes"].sum()) if n else 0
    rows.append(dict(
        head, CALCUL="STAT_CHOC", NB_CHOC_S=stats.impact_count / duration,
        NB_REBON_CHOC=episodes / n if n else 0.0, T_CHOC_MOYEN=stats.impact_duration_mean,
        T_CHOC_MAXI=stats.impact_duration_max,
        T_CHOC_MINI=float(table["duration"].min()) if n else 0.0,
        T_REBON_MOYEN=float(table["contact_time"].sum()) / episodes if episodes else 0.0,
        **{"%_T_CHOC": 100.0 * float(table["duration"].sum()) / duration}))
    power = wear_power(h, t_start=lo, t_end=hi, blocks=blocks)
    rows.append(dict(head, CALCUL="PUIS_USURE", PUIS_USURE=power.total))
    return rows


def _impact_rows(intitule: str, node: str, h: ContactHistory, occ: Mapping[str, Any]
                 ) -> list[dict]:
    lo, hi = _window(h, occ)
    threshold, rest = float(occ.get("SEUIL_FORCE", 0.0)), float(occ.get("DUREE_REPOS", 0.0))
    table = impacts(h, t_start=lo, t_end=hi, force_threshold=threshold,
                    minimum_rest_time=rest)
    head = {"INTITULE": intitule, "NOEUD": node}
    rows = [dict(head, CALCUL="IMPACT", CHOC=k + 1, INSTANT=r.peak_time, F_MAX=r.peak_force,
                 IMPULSION=r.impulse, T_CHOC=r.duration, V_IMPACT=r.impact_velocity,
                 NB_IMPACT=int(r.episodes)) for k, r in enumerate(table.itertuples())]
    if not rows:  # Code_Aster writes one row of zeros when there is no impact (impact.F90)
        rows = [dict(head, CALCUL="IMPACT", CHOC=0, INSTANT=0.0, F_MAX=0.0, IMPULSION=0.0,
                     T_CHOC=0.0, V_IMPACT=0.0, NB_IMPACT=0)]
    peaks = table["peak_force"].to_numpy(dtype=float)
    rows.append(dict(head, CALCUL="GLOBAL", F_MAX_ABS=float(peaks.max()) if peaks.size else 0.0,
                     F_MAX_MOY=float(peaks.mean()) if peaks.size else 0.0,
                     F_MAX_ETYPE=float(peaks.std()) if peaks.size else 0.0))
    classes = int(occ.get("NB_CLASSE", 10))
    if classes < 1:
        raise KeywordError(f"POST_DYNA_MODA_T: CHOC NB_CLASSE must be >= 1, got {classes}")
    values = peaks if peaks.size else np.zeros(1)
    counts, edges = np.histogram(values, bins=classes, range=(values.min(), values.max()))
    share = counts / counts.sum() if peaks.size else np.zeros(classes)
    rows += [dict(head, CALCUL="PROBA", CLASSE=k + 1, DEBUT=float(edges[k]),
                  FIN=float(edges[k + 1]), PROBA=float(share[k])) for k in range(classes)]
    return rows


def POST_DYNA_MODA_T(**keywords: Any) -> pd.DataFrame:  # noqa: N802 - Code_Aster's name
    """Code_Aster's shock statistics (POST_DYNA_MODA_T, U4.84.02) with its keywords.

    Parameters
    ----------
    **keywords
        ``RESU_GENE``: a :class:`~fretwear.history.ContactHistory`, a history file (a Code_Aster
        table holding several shock points in a NOEUD column gives every one of them), or a
        mapping node label -> either (every shock point of the computation).
        ``CHOC=_F(OPTION='USURE' or 'IMPACT', INST_INIT, INST_FIN [s], NB_BLOC, SEUIL_FORCE [N],
        DUREE_REPOS [s], NB_CLASSE)``, possibly repeated. ``TITRE``, ``INFO``.
        (:data:`CATALOGUE_POST_DYNA_MODA_T`)

    Returns
    -------
    pandas.DataFrame
        Code_Aster's table, one block of rows per shock point (INTITULE, NOEUD, CALCUL):

        * USURE (:data:`USURE_COLUMNS`): CALCUL = DEPL_X, DEPL_Y, DEPL_Z, DEPL_RADIAL [m],
          DEPL_ANGULAIRE [deg], FORCE_TANG_1, FORCE_TANG_2 [N] with MOYEN, ECART_TYPE, RMS, MAXI,
          MINI (NaN for a channel the history lacks: DEPL_X, the axial displacement, is never
          in a fretwear history); FORCE_NORMALE [N] with MOYEN_T_TOTAL (over the window),
          MOYEN_T_CHOC (over the contact time), RMS_T_TOTAL, RMS_T_CHOC, MAXI; STAT_CHOC with
          NB_CHOC_S (impacts per second [1/s]), NB_REBON_CHOC (contact episodes per impact),
          T_CHOC_MOYEN, T_CHOC_MAXI, T_CHOC_MINI (impact durations [s]), T_REBON_MOYEN (mean
          episode duration [s]), %_T_CHOC (impact time / window [%]); PUIS_USURE [W].
        * IMPACT (:data:`IMPACT_COLUMNS`): CALCUL = IMPACT, one row per impact: CHOC (number),
          INSTANT (of the peak [s]), F_MAX [N], IMPULSION [N·s], T_CHOC [s], V_IMPACT (vn at the
          start [m/s], NaN without vn), NB_IMPACT (its contact episodes); GLOBAL: F_MAX_ABS,
          F_MAX_MOY, F_MAX_ETYPE [N] (largest, mean and standard deviation of the peaks); PROBA:
          CLASSE, DEBUT, FIN [N], PROBA (share of the impacts whose peak is in the class).

        ``attrs``: ``option``, ``missing`` (channels a history lacks), ``title``.

    Raises
    ------
    KeywordError
        A catalogue rule or keyword error; RELA_EFFO_DEPL (not available: it needs the modal
        basis and the physical nodes); a window outside the record.

    Notes
    -----
    Definitions (``docs/power.md``): contact is Fn > SEUIL_FORCE, impacts are contact episodes
    joined across rests shorter than DUREE_REPOS, all on the linear interpolation of the
    samples; without contact the durations and means are 0 (Code_Aster's convention).

    Examples
    --------
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0, 3.0, 4.0], normal_force=[0.0, 2.0, 0.0, 4.0, 0.0],
    ...                    vt1=[0.1] * 5, vt2=[0.0] * 5, name="N12")
    >>> t = POST_DYNA_MODA_T(RESU_GENE=h, CHOC=_F(OPTION="IMPACT"))
    >>> t.loc[t["CALCUL"] == "IMPACT", ["CHOC", "F_MAX", "IMPULSION"]].values.tolist()
    [[1, 2.0, 2.0], [2, 4.0, 4.0]]
    """
    kw = CATALOGUE_POST_DYNA_MODA_T.check(keywords)
    if "RELA_EFFO_DEPL" in kw:
        raise KeywordError("POST_DYNA_MODA_T: RELA_EFFO_DEPL is not available: it needs the modal "
                           "basis and the physical nodes; fretwear's histories hold the shock's "
                           "local channels only (use CHOC)")
    shocks = _shocks(kw["RESU_GENE"])
    rows: list[dict] = []
    options = []
    for occ in kw["CHOC"]:
        option = occ.get("OPTION", "USURE")
        options.append(option)
        for intitule, node, h in shocks:
            rows += (_usure_rows if option == "USURE" else _impact_rows)(intitule, node, h, occ)
    columns = USURE_COLUMNS if set(options) == {"USURE"} else (
        IMPACT_COLUMNS if set(options) == {"IMPACT"}
        else tuple(dict.fromkeys(USURE_COLUMNS + IMPACT_COLUMNS)))
    frame = pd.DataFrame(rows).reindex(columns=list(columns))
    for col in _INTEGER:
        if col in frame.columns:
            frame[col] = frame[col].astype("Int64")
    for col in columns:
        if col not in ("INTITULE", "NOEUD", "CALCUL") and col not in _INTEGER:
            frame[col] = frame[col].astype(float)
    missing = {node: [c for c in ("dy", "dz", "ft1", "ft2", "vn") if getattr(h, c) is None]
               for _, node, h in shocks}
    frame.attrs.update(option=options[0] if len(options) == 1 else options,
                       missing={k: ["DEPL_X (axial)", *v] for k, v in missing.items()},
                       title=kw.get("TITRE"))
    return frame
