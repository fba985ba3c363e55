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
import os
import warnings

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, UnusedKeywordWarning
from fretwear.history import ContactHistory
from fretwear.power.result import PowerResult
from fretwear.table.build import wear_table_from_case
from fretwear.table.case import WearCase, law_coefficients  # noqa: F401 - re-exported
from fretwear.table.keywords import check_keywords, keywords_doc
from fretwear.table.restart import _memo_bytes
from fretwear.table.schema import (  # noqa: F401 - re-exported
    COLUMNS,
    GLOBAL_COLUMNS,
    SECTOR_COLUMNS,
    from_aster_names,
    to_aster_names,
)


# --------------------------------------------------------------------------- wear table
def wear_table(source, case: WearCase | None = None, *, history: ContactHistory | None = None,
               **keywords) -> pd.DataFrame:
    """The service-life wear table of one contact (theory §7; Code_Aster's POST_USURE).

    Parameters
    ----------
    source : float, ContactHistory, PowerResult or path-like
        The wear power P [W] (PUIS_USURE), or a contact history (RESU_GENE) or its file, whose
        power is computed over ``[t_start, t_end]`` [s] in ``blocks`` blocks (theory §2).
    case : WearCase, optional
        The case to compute (:meth:`WearCase.from_keywords`); keywords given with it replace
        its values. Without it the keywords make the case (``contact_type`` and ``instants``
        are then required).
    history : ContactHistory, optional
        With a PowerResult ``source``, the history it was computed from: a law that needs the
        history's class statistics (KWU_EPRI) reads them over ``[t_start, t_end]`` without
        computing the power again.
    **keywords
        The keywords of the case, :data:`fretwear.table.keywords.KEYWORDS` (their one list):

{keywords}

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
    case = _case(case, keywords)
    window = {key: keywords[key] for key, default in (("t_start", None), ("t_end", None),
                                                      ("blocks", 1))
              if keywords.get(key, default) != default}  # the window keywords given
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


def _case(case: WearCase | None, keywords: dict) -> WearCase:
    """The case of :func:`wear_table`: made of the keywords, or ``case`` with them replaced."""
    if case is None:
        return _case_of_keywords(keywords)
    if not isinstance(case, WearCase):
        raise InputError(f"wear_table: case must be a WearCase (WearCase.from_keywords), got "
                         f"{type(case).__name__}; give the keywords by name")
    if not keywords:
        return case
    check_keywords(dict(keywords, contact_type=case.contact_type, instants=case.instants),
                   "wear_table")
    changes = dict(keywords)
    if "initial_state" in changes or "initial_instant" in changes:
        case = case.with_initial_state(changes.pop("initial_state", case.restart.table),
                                       changes.pop("initial_instant", None))
    return case.replace(**changes) if changes else case


#: Cases made by :func:`wear_table` of keywords whose values say their content
#: (:func:`_keyword_key`): key -> (case, the warnings its validation gave, their registry), at
#: most _CASES_KEPT. A loop of wear_table(power, **keywords) over contacts of one case
#: validates the keywords once (0.3-0.8 ms a call), as wear_table_from_case does.
_CASES: dict = {}
_CASES_KEPT = 32
#: Keywords naming files that may change between calls: their key is each file's content
#: (:func:`_files_key`).
_FILE_KEYWORDS = ("coefficient_files", "initial_state")


def _case_of_keywords(keywords: dict) -> WearCase:
    """``WearCase.from_keywords(**keywords)`` after :func:`check_keywords`, made once for the
    same keyword values; its validation's warnings issued at every call as when it was made
    (their file and line; once each under the default filter, as a warning of one line is)."""
    key = _keyword_key(keywords)
    found = None if key is None else _CASES.get(key)
    if found is None:
        if key is None:  # nothing kept: warnings as they come
            check_keywords(keywords, "wear_table")
            return WearCase.from_keywords(**keywords)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            check_keywords(keywords, "wear_table")
            made = WearCase.from_keywords(**keywords)
        found = (made, tuple(caught), {})
        files = any(keywords.get(name) is not None for name in _FILE_KEYWORDS)
        if not files or _keyword_key(keywords) == key:  # a file unchanged while it was read
            if len(_CASES) >= _CASES_KEPT:
                _CASES.clear()
            _CASES[key] = found
    case, caught, registry = found
    for w in caught:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, registry=registry)
    return case


def _keyword_key(keywords: dict):
    """A hashable key of the keywords' values (each value's type and content; a file's path
    and its bytes, :func:`_files_key`), None where one has no content to say: a DataFrame, an
    object, a file too large or not a regular file."""
    items = tuple((name, _files_key(value) if name in _FILE_KEYWORDS and value is not None
                   else _value_key(value)) for name, value in keywords.items())
    return None if any(k is None for _, k in items) else items


def _files_key(value):
    """The key of a file keyword's value (a path or a list of paths): each path as given and
    the file's bytes (a restart table or a coefficient file of at most 256 KiB, read whole:
    the case is made again when one changes), None for anything else."""
    paths = [value] if isinstance(value, str | os.PathLike) else \
        value if type(value) in (list, tuple) else None
    if paths is None or not all(isinstance(p, str | os.PathLike) for p in paths):
        return None
    out = tuple((type(p), os.fspath(p), _memo_bytes(p, tables_only=False)) for p in paths)
    return None if any(data is None for *_, data in out) else out


def _value_key(value):
    """The key of one keyword's value (:func:`_keyword_key`), None where it has none."""
    kind = type(value)
    if value is None or kind in (bool, int, float, str):
        return kind, value
    if kind in (list, tuple):
        items = tuple(_value_key(v) for v in value)
        return None if any(k is None for k in items) else (kind, items)
    if kind is dict:
        items = tuple((k, _value_key(v)) for k, v in value.items())
        return None if any(type(k) is not str or v is None for k, v in items) else (kind, items)
    if isinstance(value, np.generic) and value.dtype.kind in "fiub":
        return kind, value.item()
    if kind is np.ndarray and value.dtype.kind in "fiub":
        return kind, value.dtype.str, value.shape, value.tobytes()
    return None


wear_table.__doc__ = wear_table.__doc__.replace("{keywords}", keywords_doc(8))
