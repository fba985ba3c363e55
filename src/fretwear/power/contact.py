"""Contact statistics of a history over a window (Code_Aster POST_DYNA_MODA_T, options USURE
and IMPACT): the same single pass as :func:`fretwear.power.wear_power`, its statistics read."""

from __future__ import annotations

import math

from fretwear.power.core import wear_power
from fretwear.power.statistics import ContactStatistics

__all__ = ["contact_statistics"]


def contact_statistics(history, *, t_start: float | None = None, t_end: float | None = None,
                       blocks: int = 1, force_threshold: float = 0.0,
                       minimum_rest_time: float = 0.0, **options) -> ContactStatistics:
    """Contact statistics of a history (or a history file) over a window.

    Parameters
    ----------
    history : ContactHistory or path
        The contact history, or a file streamed chunk by chunk (see
        :func:`fretwear.power.wear_power`).
    t_start, t_end : float, optional
        Window [s]; default the whole record.
    blocks : int
        Number of equal blocks for the per-block fields.
    force_threshold : float
        Contact / impact threshold F_s [N] (Code_Aster SEUIL_FORCE), default 0.
    minimum_rest_time : float
        Minimum rest τ [s] below F_s between two impacts (Code_Aster DUREE_REPOS), default 0.
    **options
        Passed to :func:`fretwear.power.wear_power` (``chunk_size``, ``format``, ``backend`` ...).

    Returns
    -------
    ContactStatistics

    Notes
    -----
    The same single pass as the wear power; see the module docstring for the definitions.
    Reference: Code_Aster POST_DYNA_MODA_T user documentation, options USURE and IMPACT.

    Examples
    --------
    >>> from fretwear.history import ContactHistory
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[4.0, 4.0, 0.0], vt1=[0.0] * 3,
    ...                    vt2=[0.0] * 3)
    >>> s = contact_statistics(h)
    >>> s.contact_time, s.force_mean, round(s.force_rms_contact, 6)
    (2.0, 3.0, 3.265986)
    """
    return wear_power(history, t_start=t_start, t_end=t_end, blocks=blocks,
                      force_threshold=force_threshold, minimum_rest_time=minimum_rest_time,
                      stationarity_threshold=math.inf, **options).statistics
