"""KWU-EPRI class statistics of a whole history, a history file or its chunks (theory §4): the
entry points over :class:`fretwear.laws.kwu_statistics.KwuEpriAccumulator` (the maxima's first
pass when they are not given, then the class pass). The conventions are the module docstring of
:mod:`fretwear.laws.kwu_statistics`."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any

import numpy as np

from fretwear.errors import InputError
from fretwear.history import DEFAULT_CHUNK_SIZE
from fretwear.io import iter_history_blocks
from fretwear.laws.kwu_statistics import (
    KwuEpriAccumulator,
    KwuEpriStatistics,
    _chunk_arrays,
    _positive,
    _statistics,
)


def _maxima(chunks: Iterable[Any], t_start, t_end) -> tuple[float, float]:
    lo = -np.inf if t_start is None else t_start
    hi = np.inf if t_end is None else t_end
    fmax = vmax = 0.0
    for chunk in chunks:
        t, fn, vs = _chunk_arrays(chunk)
        sel = (t >= lo) & (t <= hi)   # theory §4: the maxima in the window (all its samples)
        if sel.any():
            fmax = max(fmax, float(fn[sel].max()))
            vmax = max(vmax, float(vs[sel].max()))
    return fmax, vmax


def kwu_epri_statistics(history, *, t_start: float | None = None, t_end: float | None = None,
                        force_max: float | None = None, speed_max: float | None = None,
                        impact_factor: float = 1.0, sliding_factor: float = 1.0, k: float = 5.0,
                        c: float = 10.0, chunk_size: int = DEFAULT_CHUNK_SIZE,
                        **read_options: Any) -> KwuEpriStatistics:
    """KWU-EPRI 5×5 class statistics and wear-intensity factor w of a contact history.

    Parameters
    ----------
    history : ContactHistory, path, or sequence of chunks
        The shock point's history (or a mapping with ``time``, ``normal_force``, ``vt1``, ``vt2``);
        or a history file, streamed block by block with :func:`fretwear.io.iter_history_blocks`
        (memory bounded by ``chunk_size``; two passes when a maximum is not given); or a list of
        consecutive chunks (ContactHistory or mappings, in time order). A one-shot iterator of
        chunks is accepted only with both ``force_max`` and ``speed_max`` given.
    t_start, t_end : float, optional
        Window [s] (samples with ``t_start <= t <= t_end``). Default: the whole record.
    force_max : float, optional
        F_max [N] (``FNOR_MAXI``), > 0. Default: largest normal force in the window (theory §4).
    speed_max : float, optional
        V_max [m/s] (``VTAN_MAXI``), >= 0. Default: largest sliding speed in the window, free
        flight included (theory §4: "the maxima in the window").
    impact_factor : float, optional
        k1 (``COEF_FNOR``), correction of the impact classes. Default 1 (no correction).
    sliding_factor : float, optional
        k2 (``COEF_VTAN``), correction of the sliding classes. Default 1 (no correction).
    k : float, optional
        Experimental constant k (``COEF_K``) [1]. Default 5.
    c : float, optional
        Experimental constant c (``COEF_C``) [1] (it scales a force in N: Code_Aster R7.20.01
        calls it dimensionless), > 0. Default 10.
    chunk_size : int, optional
        Samples per chunk when ``history`` is a file (>= 2). Default 10⁶.
    **read_options
        Reader options for a file (``format``, ``units``, ``columns``, ...; see
        :func:`fretwear.io.read_history`).

    Returns
    -------
    KwuEpriStatistics
        The same whether the history is given whole, as a file or as chunks.

    Raises
    ------
    InputError
        A negative or non-finite factor or maximum, ``force_max = 0``, ``c = 0``, an empty
        window, a one-shot iterator without both maxima, or an object that is not a history.
    HistoryError
        A chunk without ``time``, ``normal_force`` or ``vt1``, non-finite values, time not
        increasing.

    Notes
    -----
    With p_vf the share of contact time in class (v, f) and F̄_f, V̄_v the mid-class values [1]_:

    .. math:: m_h = k_1 k (\\bar F_f / c)^3 \\; (v = 1), \\qquad
              m_w = k_2 \\bar F_f \\bar V_v^2 \\; (v \\ge 2 \\text{ and } (1, 1)),

    .. math:: w = \\frac{(\\sum p\\, m_w)^2}{\\sum p\\, m_h + \\sum p\\, m_w}.

    k1 and k2 carry whatever units make m_h and m_w commensurate; with the defaults k1 = k2 = 1,
    m_w is in N·m²/s² and m_h is a number. Unlike Code_Aster the force class width is not rounded
    to whole newtons and the computation does not stop when ΣP_h < ΣP_w. See the module docstring
    for the time weighting and the class bounds.

    References
    ----------
    .. [1] Hoffmann, P. J., Steininger, D. A., & Schettler, T. (1992). PWR steam generator tube
           fretting and fatigue wear phenomena and correlations. Symposium on Flow-Induced Vibration
           and Noise, Vol. 1, ASME HTD-Vol. 230 / NE-Vol. 9.

    Examples
    --------
    >>> from fretwear import ContactHistory
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[10.0, 10.0, 0.0],
    ...                    vt1=[0.0, 1.0, 0.0], vt2=[0.0, 0.0, 0.0])
    >>> s = kwu_epri_statistics(h)
    >>> float(s.shares[0, 4]), float(s.shares[4, 4])   # (v=1, f=5) and (v=5, f=5)
    (0.5, 0.5)
    >>> round(s.intensity, 6)   # ΣP_h = 0.5·5·(9/10)³, ΣP_w = 0.5·9·0.9², w = ΣP_w²/(ΣP_h + ΣP_w)
    2.43
    """
    options = dict(t_start=t_start, t_end=t_end, force_max=force_max, speed_max=speed_max,
                   impact_factor=impact_factor, sliding_factor=sliding_factor, k=k, c=c)
    if isinstance(history, str | os.PathLike):
        return _from_chunks(
            lambda: iter_history_blocks(history, chunk_size, **read_options), options)
    if read_options:
        raise InputError(f"unknown keyword(s) {sorted(read_options)}: reader options go with a "
                         "history file path only")
    if isinstance(history, Mapping) or hasattr(history, "normal_force"):
        return _from_chunks(lambda: (history,), options)
    if isinstance(history, Iterator):
        if force_max is None or speed_max is None:
            raise InputError(
                "KWU-EPRI statistics of a one-shot iterator of chunks: the default maxima need a "
                "first pass over the record, and an iterator can be read once; give force_max and "
                "speed_max (FNOR_MAXI, VTAN_MAXI), or pass a list of chunks or the file path")
        return _from_chunks(lambda: history, options)
    if isinstance(history, Iterable):
        return _from_chunks(lambda: iter(history), options)
    raise InputError(f"KWU-EPRI statistics: history must be a ContactHistory, a file path or a "
                     f"list of chunks, got {type(history).__name__}")


def kwu_epri_statistics_from_chunks(chunks: Callable[[], Iterable[Any]], **options: Any
                                    ) -> KwuEpriStatistics:
    """KWU-EPRI statistics of a record read in chunks (two passes when a maximum is not given).

    Parameters
    ----------
    chunks : callable
        Called with no argument, returns an iterable of consecutive chunks in time order
        (ContactHistory objects or mappings with ``time``, ``normal_force``, ``vt1``, ``vt2``),
        e.g. ``lambda: iter_history_chunks(path, 100_000)``. Called twice when ``force_max`` or
        ``speed_max`` is missing (first pass: the maxima).
    **options
        As :func:`kwu_epri_statistics`.

    Returns
    -------
    KwuEpriStatistics
        Identical to :func:`kwu_epri_statistics` on the whole record.

    Examples
    --------
    >>> parts = [{"time": [0.0, 1.0], "normal_force": [10.0, 10.0], "vt1": [0.0, 1.0]},
    ...          {"time": [2.0], "normal_force": [0.0], "vt1": [0.0]}]
    >>> round(kwu_epri_statistics_from_chunks(lambda: parts).intensity, 6)
    2.43
    """
    allowed = {"t_start", "t_end", "force_max", "speed_max", "impact_factor", "sliding_factor",
               "k", "c"}
    unknown = sorted(set(options) - allowed)
    if unknown:
        raise InputError(f"unknown option(s) {unknown}; accepted: {sorted(allowed)}")
    return _from_chunks(chunks, options)


def _from_chunks(chunks: Callable[[], Iterable[Any]], options: Mapping[str, Any],
                 stacklevel: int = 4) -> KwuEpriStatistics:
    """Two-pass statistics of ``chunks()`` (warnings point ``stacklevel`` frames up)."""
    t_start, t_end = options.get("t_start"), options.get("t_end")
    if t_start is not None and t_end is not None and not float(t_end) > float(t_start):
        raise InputError(f"t_end ({t_end}) must be after t_start ({t_start}) [s]")
    fmax, vmax = options.get("force_max"), options.get("speed_max")
    if fmax is not None:
        fmax = _positive("force_max", fmax, strict=True)
    if vmax is not None:
        vmax = _positive("speed_max", vmax, strict=False)
    if fmax is None or vmax is None:
        f0, v0 = _maxima(chunks(), t_start, t_end)
        fmax = f0 if fmax is None else fmax
        vmax = v0 if vmax is None else vmax
    factors = {key: options[key] for key in ("impact_factor", "sliding_factor", "k", "c")
               if key in options and options[key] is not None}
    # fmax = 0 only when it was not given and no sample of the window has a force: no contact
    acc = KwuEpriAccumulator(fmax if fmax > 0 else 1.0, vmax, t_start=t_start, t_end=t_end)
    for chunk in chunks():
        acc.update(history=chunk)
    if fmax == 0:
        acc.force_max = 0.0
    return _statistics(acc, factors.get("impact_factor", 1.0), factors.get("sliding_factor", 1.0),
                       factors.get("k", 5.0), factors.get("c", 10.0), stacklevel=stacklevel)
