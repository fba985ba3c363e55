"""The wear table of a contact from keywords: :func:`wear_table` (theory §3, §7).

:func:`wear_table` turns a wear power (or a contact history, from which the power is computed),
a wear law and a contact geometry into the table of worn volumes and depths at the instants of
service the user asks for, optionally per angular sector, optionally continuing an earlier table
(restart, Code_Aster's ETAT_INIT) and optionally with the tube replaced on the way (TUBE_NEUF).
It is the convenience of ``wear_table_from_case(WearCase.from_keywords(**keywords), source)``:
the keywords are resolved and validated by :class:`~fretwear.table.WearCase`
(:mod:`fretwear.table.case`) and the table is built by
:func:`~fretwear.table.wear_table_from_case` (:mod:`fretwear.table.build`, which states the
table's conventions).

Column names are native (:data:`COLUMNS`); :func:`to_aster_names` / :func:`from_aster_names`
convert to and from Code_Aster's POST_USURE names. Reading previous tables, the restart state
and the tube replacement are in :mod:`fretwear.table`.
"""

from __future__ import annotations

import numbers
import warnings
from collections.abc import Mapping

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import UnusedKeywordWarning
from fretwear.history import ContactHistory
from fretwear.power.result import PowerResult
from fretwear.table.build import wear_table_from_case
from fretwear.table.case import WearCase, law_coefficients  # noqa: F401 - re-exported
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT
from fretwear.table.schema import (  # noqa: F401 - re-exported
    COLUMNS,
    GLOBAL_COLUMNS,
    SECTOR_COLUMNS,
    from_aster_names,
    to_aster_names,
)


# --------------------------------------------------------------------------- wear table
def wear_table(source, *, contact_type: str, dimensions: Mapping[str, float] | None = None,
               instants, law: str = "ARCHARD",
               coefficients: Mapping[str, float] | None = None,
               obstacle_coefficients: Mapping[str, float] | None = None,
               materials: tuple[str, str] | None = None, obstacle_wear: bool = False,
               sectors=None, sector_coefficients=None, time_scale: float = 1.0,
               initial_state=None,
               initial_instant: float | None = None, tube_replacement: float | None = None,
               t_start: float | None = None, t_end: float | None = None, blocks: int = 1,
               stationarity_threshold: float = 0.1, force_max: float | None = None,
               speed_max: float | None = None,
               coefficient_files=None, wall_thickness: float | None = None,
               depth_limit: float = DEFAULT_DEPTH_LIMIT, time_unit: str | None = None,
               name: str | None = None,
               history: ContactHistory | None = None) -> pd.DataFrame:
    """The service-life wear table of one contact (theory §7; Code_Aster's POST_USURE).

    Parameters
    ----------
    source : float, ContactHistory, PowerResult or path-like
        The wear power P [W] (PUIS_USURE), or a contact history (RESU_GENE) or its file, whose
        power is computed over ``[t_start, t_end]`` [s] in ``blocks`` blocks (theory §2).
    contact_type : str
        One of :data:`fretwear.geometry.CONTACT_TYPES` (CONTACT), e.g. ``"TUBE_BAV"``.
    dimensions : mapping
        Geometry in SI: ``mobile_radius`` [m], ``obstacle_radius`` [m], ``obstacle_width`` [m],
        ``tilt_angle``, ``isthmus_angle``, ``impact_angle`` [deg], whichever the type uses.
    instants : sequence of float
        Durations of service after the origin [user time unit] (INST / LIST_INST); the table's
        ``instant`` is origin + duration.
    law : str
        ``"ARCHARD"``, ``"KWU_EPRI"`` or ``"EDF_MZ"`` (LOI_USURE). Sector mode is Archard only.
    coefficients, obstacle_coefficients : mapping, optional
        Law coefficients of the mobile / obstacle (native names or Code_Aster keywords, e.g.
        ``{"COEF_USURE": 1e-14}`` [1/Pa]). The obstacle wears only if given (or
        ``obstacle_wear`` with ``materials``): otherwise its volume stays at its initial value.
    materials : (str, str), optional
        (mobile, obstacle) material pair of the coefficient database (MATER_USURE).
    obstacle_wear : bool
        Take the obstacle coefficient from the database too (USURE_OBST='OUI').
    sectors : int or sequence of float, optional
        Angular sectors (count or edges [deg]); needs a history with ``dy``/``dz``.
    sector_coefficients : sequence of (float, float or None), optional
        Archard coefficients (mobile, obstacle) [1/Pa] per sector (one pair for all allowed);
        default the law coefficients.
    time_scale : float
        Seconds per user time unit [s] (COEF_INST), e.g. 31 536 000 for years.
    initial_state : DataFrame, path-like or fretwear.table.InitialState, optional
        Previous wear table to continue (ETAT_INIT / TABL_USURE), ours or Code_Aster's.
    initial_instant : float, optional
        INST_INIT [user time unit]: continue from this instant of ``initial_state``.
    tube_replacement : float, optional
        Instant [user time unit] at which the tube is replaced by a new one (TUBE_NEUF): from it
        on the tube's volumes restart from zero, the obstacle's continue.
    t_start, t_end : float, optional
        Window of the history [s] (INST_INIT/INST_FIN of RESU_GENE). With a plain power
        ``source`` (a number: nothing to window) they are ignored with an
        :class:`~fretwear.errors.UnusedKeywordWarning`, as POST_USURE ignores them with
        PUIS_USURE.
    blocks : int
        Number of blocks of the power computation (NB_BLOC); ignored, warned, with a plain
        power, as ``t_start`` and ``t_end``. With a PowerResult ``source``, the three are those
        of the result: other values are ignored with an UnusedKeywordWarning.
    stationarity_threshold : float
        Relative block spread above which a StationarityWarning is raised [-].
    force_max, speed_max : float, optional
        KWU_EPRI class ranges FNOR_MAXI [N] and VTAN_MAXI [m/s] (default: the history's maxima).
    coefficient_files : path-like or sequence of path-like, optional
        The user's coefficient CSV file(s), in the format of :mod:`fretwear.database`
        (docs/laws.md), extending and overriding the built-in table for ``materials``; a later
        file wins over an earlier one (``lookup(..., extra=coefficient_files)``). A fretwear
        extension: POST_USURE has no such keyword.
    wall_thickness : float, optional
        Wall thickness of the mobile [m], when known (carried in the case and ``attrs``).
    depth_limit : float
        Depth limit as a fraction of the wall thickness [-], default 0.4.
    time_unit : str, optional
        Name of the user time unit (``"year"``, ...) for the metadata; ``time_scale`` gives the
        seconds.
    name : str, optional
        A name or title of the case (the table's ``attrs["title"]``, the files' provenance).
    history : ContactHistory, optional
        With a PowerResult ``source``, the history it was computed from: a law that needs the
        history's class statistics (KWU_EPRI) reads them over ``[t_start, t_end]`` without
        computing the power again.

    Returns
    -------
    pandas.DataFrame
        Native columns (:data:`COLUMNS`), one row per instant (or instant and sector), preceded
        by the initial table's rows up to the origin on a restart. ``attrs`` holds the run's
        metadata, the case (``attrs["case"]``, :meth:`WearCase.to_dict`) and where each
        coefficient came from (``attrs["coefficient_sources"]``).

    Raises
    ------
    KeywordError
        Unknown law, missing coefficient, sector mode with a non-Archard law,
        ``coefficient_files`` without ``materials``.
    InputError
        Bad instants, sector count differing from the initial table's, replacement before the
        origin, a coefficient file that does not exist (a malformed one is a FormatError),
        ``history`` without a PowerResult ``source``.

    Notes
    -----
    ``wear_table(source, **keywords)`` is ``wear_table_from_case(WearCase.from_keywords(
    **keywords), source)``: the equations (cumulated volumes per body, a restart continuing
    from the equivalent time, sector volumes ``V_j = k_j·P_j·t``, depths from the cumulated
    volumes) are those of :func:`~fretwear.table.wear_table_from_case`.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §7.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §6 ("actualisation du
           tableau": updating the table).

    Examples
    --------
    >>> t = wear_table(0.01, contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
    ...                dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
    ...                coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)
    >>> t["volume_mobile"].tolist()  # K·P·t
    [3.6e-13, 7.2e-13]
    """
    case = WearCase.from_keywords(
        contact_type=contact_type, dimensions=dimensions, instants=instants, law=law,
        coefficients=coefficients, obstacle_coefficients=obstacle_coefficients,
        materials=materials, obstacle_wear=obstacle_wear, sectors=sectors,
        sector_coefficients=sector_coefficients, time_scale=time_scale,
        initial_state=initial_state, initial_instant=initial_instant,
        tube_replacement=tube_replacement, t_start=t_start, t_end=t_end, blocks=blocks,
        stationarity_threshold=stationarity_threshold, force_max=force_max, speed_max=speed_max,
        coefficient_files=coefficient_files, wall_thickness=wall_thickness,
        depth_limit=depth_limit, time_unit=time_unit, name=name)
    window = {key: value for key, value, default in (("t_start", t_start, None),
                                                     ("t_end", t_end, None), ("blocks", blocks, 1))
              if value != default}  # the window keywords given
    if history is None and isinstance(source, numbers.Real | np.ndarray) and np.ndim(source) == 0:
        ignored = list(window)
        if ignored:
            warnings.warn(f"wear_table: {', '.join(ignored)} window the history the power is "
                          f"computed from; with a wear power given as a number "
                          f"({float(source):g} W) they are ignored (as POST_USURE ignores "
                          "INST_INIT, INST_FIN and NB_BLOC with PUIS_USURE): give the history or "
                          "its PowerResult instead",
                          UnusedKeywordWarning, stacklevel=2)
    elif isinstance(source, PowerResult):
        own = {"t_start": source.t_start, "t_end": source.t_end, "blocks": len(source.blocks)}
        ignored = [key for key, value in window.items() if value != own[key]]
        if ignored:
            warnings.warn(f"wear_table: {', '.join(ignored)} window the history the power is "
                          f"computed from; the PowerResult source was computed over "
                          f"[{source.t_start:g}, {source.t_end:g}] s in {own['blocks']} "
                          f"block(s), which the table uses: they are ignored; compute the power "
                          f"with them (wear_power(history, t_start=..., t_end=..., blocks=...)) "
                          f"or give the history", UnusedKeywordWarning, stacklevel=2)
    return wear_table_from_case(case, source, history=history)
