"""Contact statistics of a shock point, like Code_Aster's POST_DYNA_MODA_T (options USURE, IMPACT).

All quantities are computed on the same piecewise-linear reading of the samples as the wear power
(theory §2): the normal force Fn and the sliding speed ‖Vt‖ are linear between samples, the window
[t_start, t_end] and block edges cut intervals exactly.

Definitions (F_s = ``force_threshold`` [N], τ = ``minimum_rest_time`` [s]):

* *contact*: the times where the interpolated Fn > F_s (default F_s = 0: Fn > 0);
* *episode*: a maximal time interval of contact;
* *impact*: episodes separated by a rest (time below F_s) shorter than τ form one impact; an
  impact starts when Fn rises above F_s after at least τ below it (Code_Aster SEUIL_FORCE and
  DUREE_REPOS). The first episode of the window starts an impact; an impact cut by a window bound
  counts, with its duration inside the window. An impact's duration runs from its first up-crossing
  to its last down-crossing (short rests inside it included); its peak is its largest Fn.

The streaming form (:func:`merge_groups`) keeps, for a stretch of time, its first and last impacts
explicitly (they may fuse with a neighbouring stretch) and only sums for those in between, so
partial results of consecutive chunks merge associatively.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from fretwear.power.reference import GROUP_FIELDS

_G = {name: k for k, name in enumerate(GROUP_FIELDS)}

#: Unit of each field of :class:`ContactStatistics`.
STATISTICS_UNITS: dict[str, str] = {
    "duration": "s",
    "contact_time": "s",
    "contact_fraction": "1",
    "impact_count": "1",
    "impact_duration_mean": "s",
    "impact_duration_max": "s",
    "force_max": "N",
    "impact_peak_force_mean": "N",
    "force_mean_contact": "N",
    "force_rms_contact": "N",
    "force_mean": "N",
    "force_rms": "N",
    "sliding_distance": "m",
    "force_threshold": "N",
    "minimum_rest_time": "s",
    "block_contact_fraction": "1",
    "block_force_mean": "N",
    "block_sliding_distance": "m",
}


@dataclass(frozen=True, eq=False)
class ContactStatistics:
    """Contact statistics over a window (USURE/IMPACT-like). Every field in SI units.

    Attributes
    ----------
    duration : float
        Window length T [s].
    contact_time : float
        Time with Fn > force_threshold [s].
    contact_fraction : float
        contact_time / T [-].
    impact_count : int
        Number of impacts [-].
    impact_duration_mean, impact_duration_max : float
        Mean and largest impact duration [s] (0 without impacts, Code_Aster's convention).
    force_max : float
        Largest normal force in the window [N].
    impact_peak_force_mean : float
        Mean over impacts of each impact's largest force [N] (0 without impacts).
    force_mean_contact, force_rms_contact : float
        Mean and RMS of Fn over the contact time [N] (0 without contact).
    force_mean, force_rms : float
        Mean and RMS of Fn over the whole window [N].
    sliding_distance : float
        ∫ ‖Vt‖ dt over the contact time, sticking intervals excluded [m].
    force_threshold : float
        Contact / impact force threshold used [N].
    minimum_rest_time : float
        Minimum rest time separating two impacts [s].
    block_contact_fraction, block_force_mean, block_sliding_distance : numpy.ndarray
        Per block: contact fraction [-], mean force over the block [N], sliding distance [m].

    Notes
    -----
    force_mean_contact = ∫_c Fn dt / t_c, force_rms_contact = √(∫_c Fn² dt / t_c) with t_c the
    contact time; force_mean and force_rms use the whole window and T. The integrals are exact for
    the piecewise-linear force: ∫ Fn² dt = Δt (F_a² + F_a F_b + F_b²)/3 on each piece.

    Without contact (or without impacts) the contact-time means and the impact durations and
    peaks are 0, as Code_Aster's POST_DYNA_MODA_T writes them (``statch``: T_CHOC_MOYEN,
    T_CHOC_MAXI = 0 when no shock is counted; ``fstat0``: MOYEN_T_CHOC, RMS_T_CHOC = 0;
    ``impact``: F_MAX_MOY = 0), not NaN: a table of many shock points then sums and plots.

    Examples
    --------
    >>> from fretwear.history import ContactHistory
    >>> from fretwear.power import contact_statistics
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0, 3.0, 4.0], normal_force=[0.0, 2.0, 0.0, 2.0, 0.0],
    ...                    vt1=[1.0] * 5, vt2=[0.0] * 5)
    >>> s = contact_statistics(h)
    >>> s.impact_count, s.contact_fraction, s.force_max, s.sliding_distance
    (2, 1.0, 2.0, 4.0)
    """

    duration: float
    contact_time: float
    contact_fraction: float
    impact_count: int
    impact_duration_mean: float
    impact_duration_max: float
    force_max: float
    impact_peak_force_mean: float
    force_mean_contact: float
    force_rms_contact: float
    force_mean: float
    force_rms: float
    sliding_distance: float
    force_threshold: float
    minimum_rest_time: float
    block_contact_fraction: np.ndarray
    block_force_mean: np.ndarray
    block_sliding_distance: np.ndarray

    def __post_init__(self) -> None:
        frozen_arrays(self, _ARRAYS)

    def __setstate__(self, state: dict) -> None:  # unpickled: read-only again
        self.__dict__.update(state)
        frozen_arrays(self, _ARRAYS)

    def to_dict(self) -> dict:
        """JSON-ready dictionary (arrays as lists, NaN as None).

        Examples
        --------
        >>> from fretwear.history import ContactHistory
        >>> from fretwear.power import contact_statistics
        >>> h = ContactHistory(time=[0.0, 1.0], normal_force=[1.0, 1.0], vt1=[0.0, 0.0],
        ...                    vt2=[0.0, 0.0])
        >>> contact_statistics(h).to_dict()["contact_fraction"]
        1.0
        """
        return {f.name: _jsonable(getattr(self, f.name)) for f in fields(self)}


_ARRAYS = ("block_contact_fraction", "block_force_mean", "block_sliding_distance")


def frozen_arrays(obj: object, names: tuple[str, ...]) -> None:
    """Set each named array field of the frozen dataclass ``obj`` to a read-only view of it.

    A result is read, not changed (its ``to_dict`` is cached): a read-only view makes a write
    into it fail at once, and the array the caller gave stays writable (a view, not the
    caller's array, is frozen). None and non-arrays are left as they are.
    """
    for name in names:
        value = getattr(obj, name)
        if isinstance(value, np.ndarray):
            view = value.view()
            view.flags.writeable = False
            object.__setattr__(obj, name, view)


def frozen_instance(cls: type, values: dict[str, Any], arrays: tuple[str, ...]) -> Any:
    """An instance of the frozen dataclass ``cls`` (no ``__slots__``) holding ``values`` (every
    field, by name), equal to ``cls(**values)``, for a caller that made its arrays for it.

    ``cls(**values)`` sets each field through ``object.__setattr__`` and then
    :func:`frozen_arrays` makes a read-only view of each array named in ``arrays`` (the
    caller's array stays writable); here the arrays themselves are made read-only and the
    fields set in one dictionary update: 3.4 -> 1 µs for a
    :class:`~fretwear.power.PowerResult`, a bundle's contact makes two such objects (issue 28).
    """
    for name in arrays:
        value = values[name]
        if isinstance(value, np.ndarray):
            value.flags.writeable = False
    obj = object.__new__(cls)
    obj.__dict__.update(values)
    return obj


def _jsonable(value):
    if isinstance(value, np.ndarray):  # a list of floats, NaN as None (v != v: NaN)
        if value.ndim > 1:
            return [_jsonable(row) for row in value]
        return [None if v != v else v for v in np.asarray(value, dtype=float).tolist()]
    if isinstance(value, float | np.floating):
        v = float(value)
        return None if math.isnan(v) else v
    if isinstance(value, np.integer):
        return int(value)
    return value


# ---------------------------------------------------------------------------- impact groups
def _explicit(g: np.ndarray) -> list[list[float]]:
    """The explicit groups [start, end, peak, open_left, open_right] of a group vector."""
    n = int(g[_G["count"]])
    if n == 0:
        return []
    first = [g[1], g[2], g[3], g[4], 0.0]
    if n == 1:
        first[4] = g[8]
        return [first]
    return [first, [g[5], g[6], g[7], 0.0, g[8]]]


def merge_groups(left: np.ndarray, right: np.ndarray, minimum_rest_time: float) -> np.ndarray:
    """Merge the impact-group vectors of two consecutive stretches of time (left then right).

    Parameters
    ----------
    left, right : numpy.ndarray
        Group vectors (layout :data:`fretwear.power.reference.GROUP_FIELDS`) of two stretches,
        ``left`` ending no later than ``right`` starts.
    minimum_rest_time : float
        τ [s]: the last impact of ``left`` and the first of ``right`` fuse when the rest between
        them is shorter than τ, or when both are open at the shared boundary (one episode cut in
        two).

    Returns
    -------
    numpy.ndarray
        The group vector of the union.

    Notes
    -----
    Associative: merge(merge(a, b), c) == merge(a, merge(b, c)).

    Examples
    --------
    >>> a = np.array([1, 0.0, 1.0, 5.0, 0, 0.0, 1.0, 5.0, 1, 0, 0, 0, 0])
    >>> b = np.array([1, 1.0, 2.0, 7.0, 1, 1.0, 2.0, 7.0, 0, 0, 0, 0, 0])
    >>> m = merge_groups(a, b, 0.0)
    >>> int(m[0]), float(m[1]), float(m[2]), float(m[3])
    (1, 0.0, 2.0, 7.0)
    """
    ea, eb = _explicit(left), _explicit(right)
    if not ea:
        return right.copy()
    if not eb:
        return left.copy()
    la, fb = ea[-1], eb[0]
    fuse = (la[4] == 1.0 and fb[3] == 1.0) or (fb[0] - la[1] < minimum_rest_time)
    if fuse:
        fused = [la[0], fb[1], max(la[2], fb[2]), la[3], fb[4]]
        seq = ea[:-1] + [fused] + eb[1:]
    else:
        seq = ea + eb
    out = np.zeros(len(GROUP_FIELDS))
    out[0] = len(seq) + left[9] + right[9]
    first, last = seq[0], seq[-1]
    out[1:5] = first[0], first[1], first[2], first[3]
    out[5:9] = last[0], last[1], last[2], last[4]
    mids = seq[1:-1]
    out[9] = left[9] + right[9] + len(mids)
    out[10] = left[10] + right[10] + sum(g[1] - g[0] for g in mids)
    out[11] = max([left[11], right[11]] + [g[1] - g[0] for g in mids])
    out[12] = left[12] + right[12] + sum(g[2] for g in mids)
    return out


def finalize_statistics(block_stats: np.ndarray, groups: np.ndarray, force_max: float,
                        duration: float, force_threshold: float,
                        minimum_rest_time: float) -> ContactStatistics:
    """Turn the merged partial sums of a window into :class:`ContactStatistics`.

    Parameters
    ----------
    block_stats : numpy.ndarray
        [B, 6] per-block integrals (:data:`fretwear.power.kernels.BLOCK_STATS`).
    groups : numpy.ndarray
        Merged impact-group vector.
    force_max : float
        Largest normal force in the window [N].
    duration : float
        Window length T [s].
    force_threshold, minimum_rest_time : float
        Parameters used [N], [s].

    Examples
    --------
    >>> s = finalize_statistics(np.array([[1.0, 2.0, 4.0, 2.0, 4.0, 0.5]]),
    ...                         np.array([1, 0, 1, 2.0, 0, 0, 1, 2.0, 0, 0, 0, 0, 0]),
    ...                         2.0, 2.0, 0.0, 0.0)
    >>> s.contact_fraction, s.force_mean_contact, s.force_mean, s.impact_duration_mean
    (0.5, 2.0, 1.0, 1.0)
    """
    T = float(duration)
    nb = block_stats.shape[0]
    tb = T / nb
    # the window's sums as Python floats: the same IEEE operations as numpy's scalars, without
    # a numpy scalar made at every step (issue 28)
    tot = block_stats.sum(axis=0).tolist()
    ct = tot[0]
    explicit = _explicit(groups)
    count = int(groups[0])
    if count:
        durs = [g[1] - g[0] for g in explicit]
        peaks = [g[2] for g in explicit]
        dmean = (groups[10] + sum(durs)) / count
        dmax = max([groups[11], *durs])
        pmean = (groups[12] + sum(peaks)) / count
    else:
        dmean = dmax = pmean = 0.0  # Code_Aster's convention (statch, impact)
    with np.errstate(invalid="ignore", divide="ignore"):
        blocks = (block_stats[:, 0] / tb, block_stats[:, 3] / tb)
    return frozen_instance(ContactStatistics, dict(
        duration=T,
        contact_time=ct,
        contact_fraction=ct / T,
        impact_count=count,
        impact_duration_mean=float(dmean),
        impact_duration_max=float(dmax),
        force_max=float(force_max),
        impact_peak_force_mean=float(pmean),
        force_mean_contact=tot[1] / ct if ct > 0 else 0.0,  # fstat0's convention
        force_rms_contact=math.sqrt(tot[2] / ct) if ct > 0 else 0.0,
        force_mean=tot[3] / T,
        force_rms=math.sqrt(max(tot[4], 0.0) / T),
        sliding_distance=tot[5],
        force_threshold=float(force_threshold),
        minimum_rest_time=float(minimum_rest_time),
        block_contact_fraction=blocks[0],
        block_force_mean=blocks[1],
        block_sliding_distance=block_stats[:, 5].copy(),
    ), _ARRAYS)  # arrays made here: frozen in place
