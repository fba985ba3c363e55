"""Plausibility of a contact history in SI units: a file exported in other units is caught.

fretwear computes in SI (s, N, m, m/s). A history exported in millimetres (displacements and
velocities × 1000) gives 1000 times the wear power, and one in milliseconds gives impacts lasting
seconds; nothing in the numbers themselves is wrong, so the reader checks them against what an
impact-sliding contact of flow-induced vibration can do (the thresholds of :data:`THRESHOLDS`,
documented in docs/formats.md, section "Plausibility checks"). A check that fails gives a
:class:`~fretwear.errors.UnitsWarning` naming the channel, the value, the unit it was read in,
the likely unit and the ``units = {...}`` option that fixes it. The checks never change a value.

Examples
--------
>>> import warnings
>>> from fretwear.history import ContactHistory
>>> h = ContactHistory(time=[0.0, 1e-4, 2e-4], normal_force=[0.0, 20.0, 0.0],
...                    vt1=[0.0, 50.0, 0.0], vt2=[0.0, 0.0, 0.0], name="N12")
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     found = check_plausibility(h)
>>> print(found[0][:91])
history 'N12': channel 'vt1': largest sliding speed ‖Vt‖ 50 m/s (read in 'SI') is above the
>>> caught[0].category.__name__
'UnitsWarning'
"""

from __future__ import annotations

import math
import sys
import warnings
from collections.abc import Mapping
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from fretwear.errors import ResolutionWarning, UnitsWarning
from fretwear.history import ContactHistory

#: The largest plausible friction coefficient µ = ‖Ft‖/|Fn| [1]: metal on metal in water or
#: air is 0.1 to 1 (Inconel 600 on steel, dry, up to about 1); ten leaves a decade of margin,
#: and a normal force in kN beside tangential forces in N gives a thousand times µ.
FRICTION_MAX = 10.0


class Check(NamedTuple):
    """One plausibility check: ``quantity [unit]`` compared with ``limit``."""

    quantity: str
    unit: str
    limit: float
    above: bool      # True: implausible above the limit; False: below it (and > 0)
    likely: str      # the unit a file failing the check was probably written in
    fix: str         # the ``units`` entry that fixes it


#: The checks and their thresholds (SI), documented in docs/formats.md "Plausibility checks".
THRESHOLDS: Mapping[str, Check] = MappingProxyType({
    "sliding_speed_max": Check("largest sliding speed ‖Vt‖", "m/s", 10.0, True, "mm/s",
                               "velocity = 'mm/s'"),
    "displacement_max": Check("largest radial displacement √(dy²+dz²)", "m", 0.05, True, "mm",
                              "length = 'mm'"),
    "force_max": Check("largest normal force", "N", 1e5, True, "mN", "force = 'mN'"),
    "force_min": Check("largest normal force", "N", 1e-2, False, "kN", "force = 'kN'"),
    "time_step": Check("median sampling step", "s", 5e-3, True, "ms", "time = 'ms'"),
    "impact_duration": Check("mean impact duration (3 impacts or more)", "s", 0.5, True, "ms",
                             "time = 'ms'"),
    "friction_ratio": Check("ratio of mean(‖Ft‖·‖Vt‖) to mean(|Fn|·‖Vt‖)", "[1]",
                            FRICTION_MAX, True, "kN", "normal_force = 'kN'"),
})

#: The fewest samples an impact may last on average before its wear power is said to be
#: under-resolved (:class:`~fretwear.errors.ResolutionWarning`): docs/code_aster.md §5 measured
#: +2.9 % at 12 samples an impact and +14.5 % at 5, and recommends 20.
IMPACT_SAMPLES_MIN = 5.0

_WHERE = ("case file: [history] units = {{ {fix} }}; command line: --units {cli}; Python: "
          "read_history(..., units={{{py}}})")


def _fix(entry: str) -> str:
    key, _, value = entry.partition(" = ")
    return _WHERE.format(fix=entry, cli=f"{key}={value.strip(chr(39))}",
                         py=f"'{key}': {value}")


def _unit(history: ContactHistory, channel: str) -> str:
    units = history.metadata.get("units") or {}
    return str(units.get(channel, "SI"))


def impact_durations(time: np.ndarray, force: np.ndarray) -> np.ndarray:
    """Durations [s] of the complete contact episodes (Fn > 0 runs, open ends dropped).

    Examples
    --------
    >>> impact_durations(np.arange(8.0), np.array([0, 1, 1, 0, 0, 2, 0, 3.0])).tolist()
    [2.0, 1.0]
    """
    on = force > 0
    change = np.flatnonzero(np.diff(on.astype(np.int8)))
    starts = change[~on[change]] + 1  # off -> on at the next sample
    ends = change[on[change]] + 1     # on -> off at the next sample
    if starts.size == 0 or ends.size == 0:
        return np.empty(0)
    ends = ends[ends > starts[0]]
    n = min(starts.size, ends.size)
    return time[ends[:n]] - time[starts[:n]]


def _largest_squares(a: np.ndarray, b: np.ndarray) -> float:
    """The largest ``a² + b²`` (``inf`` when the squares overflow; :func:`_root` then turns
    to :func:`numpy.hypot`): the numpy reference of :func:`fretwear.io._compiled.statistics`.

    Examples
    --------
    >>> _largest_squares(np.array([3.0, 1.0]), np.array([4.0, 1.0]))
    25.0
    """
    with np.errstate(over="ignore"):  # overflowing squares: numpy.hypot in _root
        return float((a * a + b * b).max())


#: Samples from which the checks run compiled when numba is installed (:mod:`fretwear.io.
#: _compiled`; a 1e5-sample history with dy/dz 0.65 -> 0.23 ms): below, the numpy expressions
#: cost little, and reading short histories alone does not import numba (about 0.3 s, which
#: :mod:`fretwear.power` pays anyway).
_KERNEL_SAMPLES = 1 << 14


def _root(squares: float, a: np.ndarray, b: np.ndarray) -> float:
    """``max(√(a² + b²))`` in the unit of ``a`` and ``b``, given ``squares``, the largest
    ``a² + b²``: its square root (ten times cheaper than :func:`numpy.hypot` per sample), or
    :func:`numpy.hypot` when the squares overflowed.

    Examples
    --------
    >>> a, b = np.array([3.0, 1.0]), np.array([4.0, 1.0])
    >>> big = np.array([3e200]), np.array([4e200])
    >>> _root(_largest_squares(a, b), a, b), _root(_largest_squares(*big), *big)
    (5.0, 5e+200)
    """
    top = math.sqrt(squares)
    return top if math.isfinite(top) else float(np.hypot(a, b).max())


def _statistics(history: ContactHistory) -> tuple[float, float, float, float, np.ndarray]:
    """What the checks compare with their limits: the largest ``vt1² + vt2²`` [m²/s²] and
    ``dy² + dz²`` [m²] (0 without dy), the largest normal force [N], the median time step [s]
    (or a value known to be at most the ``time_step`` limit, when fewer than half the steps
    exceed it: the median is then not needed) and the contact episodes' durations [s].

    Compiled (:func:`fretwear.io._compiled.statistics`) when numba is installed and the history
    is long or the module already imported (:func:`_kernel_for`), else numpy; the same numbers
    either way (but for the sign of a zero force).
    """
    t, fn = history.time, history.normal_force
    limit = THRESHOLDS["time_step"].limit
    kernel = _kernel_for(t.size)
    if kernel is not None:
        speed2, radial2, fmax, above, durations = kernel.statistics(
            t, fn, history.vt1, history.vt2, history.dy, history.dz, limit)
        # the median of the m = size - 1 steps exceeds the limit only if at least m // 2 of
        # them do (sorted, the middle one, or both middle ones, would be at most the limit)
        step = float(np.median(np.diff(t))) if above >= (t.size - 1) // 2 else limit
        return float(speed2), float(radial2), float(fmax), step, durations
    speed2 = _largest_squares(history.vt1, history.vt2)
    radial2 = 0.0 if history.dy is None else _largest_squares(history.dy, history.dz)
    return (speed2, radial2, float(fn.max()), float(np.median(np.diff(t))),
            impact_durations(t, fn))


def _compiled():
    """:mod:`fretwear.io._compiled`, or ``None`` without numba (imported at the first use)."""
    global _KERNEL
    if _KERNEL is False:
        from fretwear._numba import HAVE_NUMBA

        if HAVE_NUMBA:
            from fretwear.io import _compiled as module

            _KERNEL = module
        else:  # pragma: no cover - exercised only without numba
            _KERNEL = None
    return _KERNEL


_KERNEL = False


def _kernel_for(size: int):
    """The compiled module for a history of ``size`` samples, or ``None`` (numpy): from
    :data:`_KERNEL_SAMPLES` samples on when numba is installed, and at any size once the module
    is imported (a streamed block's checks, :func:`fretwear.io.channels.fast_history`, import
    it: numba then costs nothing more, and the numpy expressions cost a 1 000-sample block
    about 0.15 ms, a tenth of a bundle worker's read of the file, issue 28). ``_KERNEL = None``
    forces numpy (the tests' reference)."""
    if size >= _KERNEL_SAMPLES or (_KERNEL is False and _COMPILED_MODULE in sys.modules):
        return _compiled()
    return _KERNEL or None


_COMPILED_MODULE = "fretwear.io._compiled"


def _name(history: ContactHistory) -> str:
    return history.name or history.metadata.get("source", "")


def _warn(key: str, name: str, channel: str, value: float, unit_read: str, skip: set[str],
          found: list[str], emit: bool = True) -> None:
    if key in skip:
        return
    skip.add(key)
    c = THRESHOLDS[key]
    message = (f"history {name!r}: channel {channel!r}: {c.quantity} {value:.4g} {c.unit} "
               f"(read in {unit_read!r}) is {'above' if c.above else 'below'} the "
               f"plausibility limit {c.limit:g} {c.unit}; a file in {c.likely!r} gives "
               f"this: if so, give the units: {_fix(c.fix)}")
    found.append(message)
    if emit:
        warnings.warn(message, UnitsWarning, stacklevel=4)


def _check_resolution(history: ContactHistory, name: str, mean: float, count: int,
                      skip: set[str], found: list[str], emit: bool = True) -> None:
    """Warn (:class:`~fretwear.errors.ResolutionWarning`) when the impacts last fewer than
    :data:`IMPACT_SAMPLES_MIN` samples on average (the mean sampling step [s] of the history)."""
    t = history.time
    step = float(t[-1] - t[0]) / (t.size - 1)
    if "impact_samples" in skip or not step > 0 or mean / step >= IMPACT_SAMPLES_MIN:
        return
    skip.add("impact_samples")
    message = (f"history {name!r}: its {count} impacts last {mean / step:.3g} samples on average "
               f"(mean impact duration {mean:.3g} s, sampling step {step:.3g} s): the wear power "
               "of impacts this coarsely sampled may be off by 15 % or more "
               "(docs/code_aster.md §5: +2.9 % at 12 samples an impact, +14.5 % at 5). "
               "Archive at least 20 samples an impact: a step below "
               f"{mean / 20:.2g} s (Code_Aster: DYNA_VIBRA ARCHIVAGE=_F(PAS_ARCH=...); fretwear "
               "simulate: archive_step_s)")
    found.append(message)
    if emit:
        warnings.warn(message, ResolutionWarning, stacklevel=4)


class StreamPlausibility:
    """The plausibility checks of a history read in chunks or blocks, each warning once.

    Every check but one holds for any part of the file: a value above a limit in a chunk is
    above it in the file, and a unit error shows in the first block. The exception is the
    smallest plausible *largest* force (``force_min``: a file in kN): a chunk of free flight
    whose largest force is a rounding residue (1e-15 N) says nothing of the file. That check is
    therefore made once, in :meth:`finish`, on the largest force of every chunk seen
    (:meth:`update`, one ``max`` per chunk).

    Examples
    --------
    >>> import warnings
    >>> from fretwear.history import ContactHistory
    >>> t = [0.0, 1e-4, 2e-4]
    >>> quiet = ContactHistory(time=t, normal_force=[0.0, 6e-15, 0.0], vt1=[0.0] * 3,
    ...                        vt2=[0.0] * 3, name="N12")
    >>> loud = quiet.replace(normal_force=[0.0, 50.0, 0.0])
    >>> stream = StreamPlausibility()
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("error")   # no warning: the file's largest force is 50 N
    ...     for chunk in (quiet, loud):
    ...         stream.update(chunk, check=True)
    ...     stream.finish()
    []
    """

    def __init__(self, *, emit: bool = True) -> None:
        self.emit = emit  # False: the messages only gathered in ``found``, nothing warned
        self.found: list[str] = []
        self.reported: set[str] = set()
        self.force_max = -math.inf
        self._last: ContactHistory | None = None

    def update(self, chunk: ContactHistory, *, check: bool) -> None:
        """Take a chunk's largest force; ``check``: also run the other checks on it."""
        if check:
            skip = self.reported | {"force_min"}
            self.found += check_plausibility(chunk, skip=skip, emit=self.emit)
            self.reported |= skip - {"force_min"}
        self.force_max = max(self.force_max, float(chunk.normal_force.max()))
        self._last = chunk

    def finish(self) -> list[str]:
        """The ``force_min`` check on the largest force of all the chunks (the messages)."""
        found: list[str] = []
        if self._last is not None and 0.0 < self.force_max < THRESHOLDS["force_min"].limit:
            _warn("force_min", _name(self._last), "normal_force", self.force_max,
                  _unit(self._last, "normal_force"), self.reported, found, self.emit)
        self.found += found
        return found


def check_plausibility(history: ContactHistory, *, skip: set[str] | None = None,
                       emit: bool = True) -> list[str]:
    """Warn (:class:`UnitsWarning`) for every value of ``history`` implausible in SI units.

    Parameters
    ----------
    history : ContactHistory
        The history (SI units), with ``metadata['units']`` when read from a file.
    skip : set of str, optional
        Keys of :data:`THRESHOLDS` already reported (chunked reading warns once per check);
        the keys of the checks that fail are added to it.
    emit : bool
        False: nothing is warned, the messages are only returned (a caller that reads the
        file again when it would warn: :func:`fretwear.io.streaming.iter_history_blocks`).

    Returns
    -------
    list of str
        The messages warned.

    Notes
    -----
    Thresholds: :data:`THRESHOLDS`. Sliding speeds of flow-induced vibration are below 1 m/s,
    radial displacements below the support clearance (≤ 1 mm), contact forces 0.1 to 1000 N,
    impacts last 0.1 to 10 ms and are sampled every 1e-6 to 1e-4 s [1]_; the limits leave a
    margin of one to two decades.

    References
    ----------
    .. [1] M. J. Pettigrew, C. E. Taylor, "Vibration analysis of steam generators and heat
       exchangers: an overview", J. Fluids Struct. 18 (2003) 469-483.
    """
    skip = set() if skip is None else skip
    name = _name(history)
    found: list[str] = []

    def warn(key: str, channel: str, value: float, unit_read: str) -> None:
        _warn(key, name, channel, value, unit_read, skip, found, emit)

    speed2, radial2, fmax, step, durations = _statistics(history)
    top = _root(speed2, history.vt1, history.vt2)
    if top > THRESHOLDS["sliding_speed_max"].limit:
        channel = "vt1" if np.abs(history.vt1).max() >= np.abs(history.vt2).max() else "vt2"
        warn("sliding_speed_max", channel, top, _unit(history, channel))
    if history.dy is not None:
        radial = _root(radial2, history.dy, history.dz)
        if radial > THRESHOLDS["displacement_max"].limit:
            warn("displacement_max", "dy", radial, _unit(history, "dy"))
    if fmax > THRESHOLDS["force_max"].limit:
        warn("force_max", "normal_force", fmax, _unit(history, "normal_force"))
    elif 0.0 < fmax < THRESHOLDS["force_min"].limit:
        warn("force_min", "normal_force", fmax, _unit(history, "normal_force"))
    if step > THRESHOLDS["time_step"].limit:
        warn("time_step", "time", step, _unit(history, "time"))
    # the mean as numpy.mean computes it (the sum over the count), without its machinery
    if durations.size >= 3 and math.isfinite(mean := float(durations.sum()) / durations.size):
        if mean > THRESHOLDS["impact_duration"].limit:
            warn("impact_duration", "time", mean, _unit(history, "time"))
        _check_resolution(history, name, mean, durations.size, skip, found, emit)
    ratio = friction_ratio(history)
    if ratio > THRESHOLDS["friction_ratio"].limit and "friction_ratio" not in skip:
        skip.add("friction_ratio")
        units = (_unit(history, "normal_force"), _unit(history, "ft1"))
        message = (f"history {name!r}: the friction power mean(‖Ft‖·‖Vt‖) is {ratio:.4g} times "
                   f"the wear power's integrand mean(|Fn|·‖Vt‖) (forces read in {units[0]!r} "
                   f"and {units[1]!r}); Coulomb's law ‖Ft‖ ≤ µ·|Fn| bounds it by µ, plausible "
                   f"up to {FRICTION_MAX:g}: a normal force in 'kN' (or tangential forces in "
                   f"'mN') beside the other in 'N' gives this, and a wear power 1000 times too "
                   f"small: if so, give the units: {_fix(THRESHOLDS['friction_ratio'].fix)}")
        found.append(message)
        if emit:
            warnings.warn(message, UnitsWarning, stacklevel=2)
    return found


def friction_ratio(history: ContactHistory) -> float:
    """The ratio mean(‖Ft‖·‖Vt‖) / mean(|Fn|·‖Vt‖) [1] over the samples (NaN without ``ft1``).

    Notes
    -----
    The wear power (docs/theory.md §2) is the time average of g = |Fn|·‖Vt‖ [W], without the
    friction coefficient: P ≤ mean(|Fn|·‖Vt‖) (the stick rule only removes intervals), an
    identity for a power computed from the same force and speed, which no unit of the speed can
    break (both sides scale alike). The independent bound is Coulomb's: at every sample,
    ‖Ft‖ ≤ µ·|Fn| (static friction while sticking, kinetic while sliding), hence for any
    non-negative weights (plain or trapezoid)

    ``mean(‖Ft‖·‖Vt‖) ≤ µ · mean(|Fn|·‖Vt‖)``,

    so the ratio is at most the largest friction coefficient. A ratio of hundreds or thousands
    is a unit mix between the normal and the tangential forces (``kN`` beside ``N``), which
    makes the wear power that many times too small.

    Examples
    --------
    >>> from fretwear.history import ContactHistory
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[0.0, 10.0, 5.0],
    ...                    vt1=[0.0, 0.2, 0.1], vt2=[0.0, 0.0, 0.0], ft1=[0.0, 3.0, 1.5],
    ...                    ft2=[0.0, 0.0, 0.0])
    >>> round(friction_ratio(h), 12)
    0.3
    """
    if history.ft1 is None:
        return math.nan
    ft2 = history.ft2 if history.ft2 is not None else 0.0
    with np.errstate(over="ignore", invalid="ignore"):
        speed = np.hypot(history.vt1, history.vt2)
        normal = float(np.sum(np.abs(history.normal_force) * speed))
        friction = float(np.sum(np.hypot(history.ft1, ft2) * speed))
    if not (normal > 0 and math.isfinite(normal) and math.isfinite(friction)):
        return math.nan
    return friction / normal
