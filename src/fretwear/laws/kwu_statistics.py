"""KWU-EPRI class statistics of a contact history (theory §4): the wear-intensity factor w.

The contact samples (Fn > 0) are sorted into 5 normal-force classes f and 5 sliding-speed classes v.
Choices where Code_Aster R7.20.01 and docs/theory.md are silent (also in docs/laws.md):

* **Time shares.** p_vf is the share of *contact time* spent in class (v, f). Each interval [t_i,
  t_i+1) belongs to its left sample (the convention of the stick rule and of angular sectors, theory
  §2-§3), so a sample weighs its interval t_i+1 − t_i and the last sample of the window weighs
  nothing. With a constant time step this is the share of samples (Code_Aster counts samples).
  Shares are fractions (Σ p = 1), not percentages: w scales with that normalisation.
* **Class bounds.** Force classes split (0, F_max] into 5 equal widths, closed on the right: a force
  on a bound f·F_max/5 belongs to class f (the lower one); F_max is in class 5. Speed classes split
  [0, V_max] into 5, closed on the left: a speed on a bound v·V_max/5 belongs to class v + 1; zero
  is in class 1 and V_max in class 5. Widths are not rounded.
* **Maxima.** F_max and V_max default to the largest normal force and the largest sliding speed of
  the *contact* samples in the window. A sample above a user-given maximum goes to the last class,
  with a LawWarning giving its share of contact time.
* **No contact.** A window without contact gives zero shares, w = 0 and a LawWarning.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import HistoryError, InputError, LawWarning
from fretwear.laws.kwu_stream import KwuEpriMaxima, class_pass  # noqa: F401 - re-exported

#: Number of classes per axis.
N_CLASSES = 5
#: Impact cells: speed class v = 1 (row 0), every force class.
IMPACT_MASK = np.zeros((N_CLASSES, N_CLASSES), dtype=bool)
IMPACT_MASK[0, :] = True
#: Sliding cells: v >= 2 (rows 1..4), every force class, and the single cell (1, 1).
SLIDING_MASK = np.zeros((N_CLASSES, N_CLASSES), dtype=bool)
SLIDING_MASK[1:, :] = True
SLIDING_MASK[0, 0] = True
IMPACT_MASK.flags.writeable = False
SLIDING_MASK.flags.writeable = False


def _positive(name: str, value, *, strict: bool) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name!r} must be a number, got {value!r}") from None
    if not np.isfinite(x) or x < 0 or (strict and x == 0):
        raise InputError(f"{name!r} must be finite and {'> 0' if strict else '>= 0'}, got {x!r}")
    return x


def force_classes(normal_force, force_max: float) -> np.ndarray:
    """Force class f in 1..5 of each normal force [N] (right-closed classes on (0, F_max]).

    Forces above F_max go to class 5. Meaningful for Fn > 0 only.

    Examples
    --------
    >>> force_classes([0.5, 2.0, 2.0001, 10.0, 12.0], 10.0).tolist()
    [1, 1, 2, 5, 5]
    """
    f = np.ceil(np.asarray(normal_force, dtype=float) * N_CLASSES / force_max)
    return np.clip(f, 1, N_CLASSES).astype(np.int64)


def speed_classes(sliding_speed, speed_max: float) -> np.ndarray:
    """Speed class v in 1..5 of each sliding speed [m/s] (left-closed classes on [0, V_max]).

    V_max itself and speeds above it go to class 5; with V_max = 0 a zero speed is in class 1
    (and a positive one, above the maximum, in class 5).

    Examples
    --------
    >>> speed_classes([0.0, 0.19, 0.2, 0.99, 1.0, 3.0], 1.0).tolist()
    [1, 1, 2, 5, 5, 5]
    """
    s = np.asarray(sliding_speed, dtype=float)
    if speed_max == 0:
        return np.where(s > 0, N_CLASSES, 1).astype(np.int64)
    v = np.floor(s * N_CLASSES / speed_max) + 1
    return np.clip(v, 1, N_CLASSES).astype(np.int64)


def _chunk_arrays(chunk: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(time, normal_force, sliding_speed) of a ContactHistory or a mapping/object of channels."""
    get = chunk.get if isinstance(chunk, Mapping) else (lambda k: getattr(chunk, k, None))
    arrays = {}
    for key in ("time", "normal_force", "vt1"):
        value = get(key)
        if value is None:
            raise HistoryError(f"KWU-EPRI statistics: the chunk has no {key!r} channel; give "
                               "time, normal_force, vt1 (and vt2)")
        arrays[key] = np.asarray(value, dtype=float)
    vt2 = get("vt2")
    vt2 = np.zeros_like(arrays["vt1"]) if vt2 is None else np.asarray(vt2, dtype=float)
    return arrays["time"], arrays["normal_force"], np.hypot(arrays["vt1"], vt2)


class KwuEpriAccumulator:
    """Streaming KWU-EPRI class counts with fixed maxima; partial accumulators merge.

    Parameters
    ----------
    force_max : float
        F_max [N], > 0 (Code_Aster ``FNOR_MAXI``).
    speed_max : float
        V_max [m/s], >= 0 (``VTAN_MAXI``).
    t_start, t_end : float, optional
        Window [s]: samples with ``t_start <= t <= t_end`` are used.

    Notes
    -----
    :meth:`update` takes consecutive chunks and keeps the last sample, so the interval across two
    chunks is counted. Accumulators run on separate pieces of a record and then :meth:`merge`\\ d
    must get pieces that share their boundary sample (the last sample of one piece is the first of
    the next), so that every interval lies in exactly one piece.

    Examples
    --------
    >>> acc = KwuEpriAccumulator(force_max=10.0, speed_max=1.0)
    >>> acc.update(time=[0.0, 1.0, 2.0], normal_force=[10.0, 0.0, 5.0],
    ...            sliding_speed=[0.0, 0.0, 1.0])
    >>> acc.contact_time
    1.0
    """

    def __init__(self, force_max: float, speed_max: float, *, t_start: float | None = None,
                 t_end: float | None = None) -> None:
        self.force_max = _positive("force_max", force_max, strict=True)
        self.speed_max = _positive("speed_max", speed_max, strict=False)
        self.t_start = -np.inf if t_start is None else float(t_start)
        self.t_end = np.inf if t_end is None else float(t_end)
        if self.t_end <= self.t_start:
            raise InputError(f"t_end ({t_end}) must be after t_start ({t_start}) [s]")
        self.class_time = np.zeros((N_CLASSES, N_CLASSES))
        self.window_time = 0.0
        self.time_above_max = 0.0
        self.samples = 0
        self.first_time: float | None = None
        self._last: tuple[float, float, float] | None = None
        #: (force_max, speed_max) as the user gave them (None: the window's maximum), when the
        #: counts come from a power pass (fretwear.power.wear_power(kwu=...)); None otherwise.
        self.given: tuple[float | None, float | None] | None = None

    @property
    def contact_time(self) -> float:
        """Contact time counted so far [s]."""
        return float(self.class_time.sum())

    def update(self, time=None, normal_force=None, sliding_speed=None, *,
               history: Any = None) -> None:
        """Add a chunk: arrays (time [s], normal_force [N], sliding_speed [m/s]) or ``history=``
        (a ContactHistory or a mapping with time, normal_force, vt1, vt2)."""
        if history is not None:
            t, fn, vs = _chunk_arrays(history)
        else:
            t, fn, vs = (np.asarray(a, dtype=float) for a in (time, normal_force, sliding_speed))
        if not (t.shape == fn.shape == vs.shape) or t.ndim != 1:
            raise HistoryError("KWU-EPRI statistics: time, normal_force and sliding_speed must be "
                               f"1-D of equal length, got {t.shape}, {fn.shape}, {vs.shape}")
        for name, arr in (("time", t), ("normal_force", fn), ("sliding_speed", vs)):
            if not np.isfinite(arr).all():
                i = int(np.flatnonzero(~np.isfinite(arr))[0])
                raise HistoryError(f"KWU-EPRI statistics: {name!r} is not finite at row {i} of "
                                   "the chunk; remove or fill it")
        keep = (t >= self.t_start) & (t <= self.t_end)
        t, fn, vs = t[keep], fn[keep], vs[keep]
        if t.size == 0:
            return
        if self._last is not None:
            if t[0] == self._last[0]:
                t, fn, vs = t[1:], fn[1:], vs[1:]  # the chunks share their boundary sample
                if t.size == 0:
                    return
            elif t[0] < self._last[0]:
                raise HistoryError(
                    f"KWU-EPRI statistics: chunk starts at t = {t[0]!r} s, before the end of the "
                    f"previous chunk ({self._last[0]!r} s); give chunks in time order")
            t = np.concatenate(([self._last[0]], t))
            fn = np.concatenate(([self._last[1]], fn))
            vs = np.concatenate(([self._last[2]], vs))
        elif self.first_time is None:
            self.first_time = float(t[0])
        self.samples += int(keep.sum())
        self._last = (float(t[-1]), float(fn[-1]), float(vs[-1]))
        if t.size < 2:
            return
        dt = np.diff(t)
        if (dt <= 0).any():
            i = int(np.flatnonzero(dt <= 0)[0])
            raise HistoryError(f"KWU-EPRI statistics: time is not strictly increasing at "
                               f"t = {t[i + 1]!r} s; sort the samples")
        self.window_time += float(dt.sum())
        f_left, v_left = fn[:-1], vs[:-1]
        contact = f_left > 0
        if not contact.any():
            return
        fc = force_classes(f_left[contact], self.force_max)
        vc = speed_classes(v_left[contact], self.speed_max)
        w = dt[contact]
        counts = np.bincount((vc - 1) * N_CLASSES + (fc - 1), weights=w,
                             minlength=N_CLASSES * N_CLASSES)
        self.class_time += counts.reshape(N_CLASSES, N_CLASSES)
        above = (f_left[contact] > self.force_max) | (v_left[contact] > self.speed_max)
        self.time_above_max += float(w[above].sum())

    def update_velocities(self, time, normal_force, vt1, vt2) -> None:
        """Add a chunk given by its velocity components: the same counts as :meth:`update`
        with ``sliding_speed = numpy.hypot(vt1, vt2)``, in one compiled pass without computing
        every speed's hypot (:func:`fretwear.laws.kwu_stream.class_pass`). The chunk's channels
        must be finite and its time increasing (a validated history's are).

        Examples
        --------
        >>> acc = KwuEpriAccumulator(force_max=10.0, speed_max=1.0)
        >>> acc.update_velocities([0.0, 1.0, 2.0], [10.0, 0.0, 5.0], [0.0, 0.0, 0.6],
        ...                       [0.0, 0.0, 0.8])
        >>> acc.contact_time, acc.window_time
        (1.0, 2.0)
        """
        last = None
        if self._last is not None:
            last = (*self._last[:3], 0.0)  # a speed is its own hypot with 0
        out = class_pass(self.class_time, last, time, normal_force, vt1, vt2, self.t_start,
                         self.t_end, self.force_max, self.speed_max)
        if out[0]:
            raise HistoryError(
                f"KWU-EPRI statistics: chunk starts at t = {out[1]!r} s, before the end of the "
                "previous chunk or time is not increasing; give chunks in time order")
        if out[4] == 0:
            return
        if self._last is None and self.first_time is None:
            self.first_time = float(out[5])
        self.samples += int(out[4])
        self.window_time += float(out[2])
        self.time_above_max += float(out[3])
        self._last = (float(out[6]), float(out[7]), float(np.hypot(out[8], out[9])))

    def merge(self, other: KwuEpriAccumulator) -> KwuEpriAccumulator:
        """A new accumulator holding the counts of both (same maxima and window required)."""
        if (self.force_max, self.speed_max, self.t_start, self.t_end) != (
                other.force_max, other.speed_max, other.t_start, other.t_end):
            raise InputError("KWU-EPRI accumulators can merge only with the same force_max, "
                             "speed_max and window; compute the maxima first (two passes)")
        out = KwuEpriAccumulator(self.force_max, self.speed_max)
        out.t_start, out.t_end = self.t_start, self.t_end
        out.class_time = self.class_time + other.class_time
        out.window_time = self.window_time + other.window_time
        out.time_above_max = self.time_above_max + other.time_above_max
        out.samples = self.samples + other.samples
        firsts = [x for x in (self.first_time, other.first_time) if x is not None]
        out.first_time = min(firsts) if firsts else None
        lasts = [x._last for x in (self, other) if x._last is not None]
        out._last = max(lasts) if lasts else None
        out.given = self.given if self.given == other.given else None
        return out

    def result(self, *, impact_factor: float = 1.0, sliding_factor: float = 1.0, k: float = 5.0,
               c: float = 10.0) -> KwuEpriStatistics:
        """The :class:`KwuEpriStatistics` of the counts so far (factors as kwu_epri_statistics).

        The last result is kept while the counts and factors stay the same (its arrays are
        read-only; a wear table per contact asks once per table), unless it warned: a warning
        is said again at every call."""
        key = (impact_factor, sliding_factor, k, c, self.force_max, self.speed_max,
               self.samples, self.window_time, self.time_above_max, self.first_time,
               self._last, self.class_time.tobytes())
        kept = self.__dict__.get("_kept")
        if kept is not None and kept[0] == key:
            return kept[1]
        out = _statistics(self, impact_factor, sliding_factor, k, c)
        if out.contact_time > 0 and out.time_above_max == 0:  # it did not warn
            self._kept = (key, out)
        return out


@dataclass(frozen=True, eq=False)
class KwuEpriStatistics:
    """KWU-EPRI class statistics and wear-intensity factor of a contact (theory §4).

    Arrays indexed ``[v − 1, f − 1]``: rows are speed classes v = 1..5, columns force classes
    f = 1..5.

    Attributes
    ----------
    shares : ndarray (5, 5)
        p_vf, share of contact time in each class [1] (sums to 1, or 0 without contact).
    class_time : ndarray (5, 5)
        Contact time in each class [s].
    contact_time, window_time : float
        Total contact time and window length covered by the samples [s].
    force_bounds, speed_bounds : ndarray (6,)
        Class bounds [N], [m/s]. ``force_mid``, ``speed_mid`` (5,): mid-class values F̄_f, V̄_v.
    impact_intensity : ndarray (5, 5)
        m_h = k1·k·(F̄_f/c)³ on impact cells (v = 1), 0 elsewhere.
    sliding_intensity : ndarray (5, 5)
        m_w = k2·F̄_f·V̄_v² on sliding cells (v >= 2 and (1, 1)), 0 elsewhere.
    impact_sum, sliding_sum : float
        ΣP_h = Σ p·m_h and ΣP_w = Σ p·m_w.
    intensity : float
        w = (ΣP_w)²/(ΣP_h + ΣP_w) (0 when both sums are 0).
    force_max, speed_max, impact_factor, sliding_factor, k, c : float
        F_max [N], V_max [m/s], k1, k2, k, c used.
    time_above_max : float
        Contact time of samples above F_max or V_max, counted in the last class [s].
    t_start, t_end : float or None
        First and last sample time used [s].
    """

    shares: np.ndarray
    class_time: np.ndarray
    contact_time: float
    window_time: float
    force_bounds: np.ndarray
    speed_bounds: np.ndarray
    force_mid: np.ndarray
    speed_mid: np.ndarray
    impact_intensity: np.ndarray
    sliding_intensity: np.ndarray
    impact_sum: float
    sliding_sum: float
    intensity: float
    force_max: float
    speed_max: float
    impact_factor: float
    sliding_factor: float
    k: float
    c: float
    time_above_max: float
    t_start: float | None
    t_end: float | None

    def to_frame(self):
        """The 25 classes as a long :class:`pandas.DataFrame` (one row per class, SI units)."""
        v, f = np.meshgrid(np.arange(1, N_CLASSES + 1), np.arange(1, N_CLASSES + 1), indexing="ij")
        vi, fi = v.ravel() - 1, f.ravel() - 1
        return pd.DataFrame({
            "speed_class": v.ravel(), "force_class": f.ravel(),
            "speed_low": self.speed_bounds[vi], "speed_high": self.speed_bounds[vi + 1],
            "speed_mid": self.speed_mid[vi],
            "force_low": self.force_bounds[fi], "force_high": self.force_bounds[fi + 1],
            "force_mid": self.force_mid[fi],
            "contact_time": self.class_time.ravel(), "share": self.shares.ravel(),
            "impact": IMPACT_MASK.ravel(), "sliding": SLIDING_MASK.ravel(),
            "impact_intensity": self.impact_intensity.ravel(),
            "sliding_intensity": self.sliding_intensity.ravel(),
            "impact_weighted": (self.shares * self.impact_intensity).ravel(),
            "sliding_weighted": (self.shares * self.sliding_intensity).ravel(),
        })

    def share_table(self):
        """The 5×5 shares p_vf as a DataFrame, rows speed classes, columns force classes."""
        return pd.DataFrame(self.shares, index=pd.Index(range(1, 6), name="speed_class"),
                            columns=pd.Index(range(1, 6), name="force_class"))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary."""
        return {
            "shares": self.shares.tolist(), "class_time": self.class_time.tolist(),
            "contact_time": self.contact_time, "window_time": self.window_time,
            "force_bounds": self.force_bounds.tolist(), "speed_bounds": self.speed_bounds.tolist(),
            "force_mid": self.force_mid.tolist(), "speed_mid": self.speed_mid.tolist(),
            "impact_intensity": self.impact_intensity.tolist(),
            "sliding_intensity": self.sliding_intensity.tolist(),
            "impact_sum": self.impact_sum, "sliding_sum": self.sliding_sum,
            "intensity": self.intensity, "force_max": self.force_max, "speed_max": self.speed_max,
            "impact_factor": self.impact_factor, "sliding_factor": self.sliding_factor,
            "k": self.k, "c": self.c, "time_above_max": self.time_above_max,
            "t_start": self.t_start, "t_end": self.t_end,
        }

    def __str__(self) -> str:
        """The 5×5 shares [%] with class bounds and mid-values, the sums and w, as text."""
        cols = [f"f{j + 1} {self.force_bounds[j]:.4g}-{self.force_bounds[j + 1]:.4g}"
                for j in range(N_CLASSES)]
        width = max(12, *(len(x) + 2 for x in cols))
        rows = [f"v{i + 1} {self.speed_bounds[i]:.4g}-{self.speed_bounds[i + 1]:.4g}"
                for i in range(N_CLASSES)]
        label = max(24, *(len(x) + 2 for x in rows))
        window = ("no sample in the window" if self.t_start is None
                  else f"window {self.t_start:.6g} to {self.t_end:.6g} s")
        lines = [
            f"KWU-EPRI class statistics ({window}; contact {self.contact_time:.6g} s of "
            f"{self.window_time:.6g} s); F_max = {self.force_max:.6g} N, "
            f"V_max = {self.speed_max:.6g} m/s",
            "share of contact time p_vf [%]",
            "speed [m/s] \\ force [N]".ljust(label) + "".join(f"{x:>{width}}" for x in cols)
            + "   mid V̄_v [m/s]",
            "mid F̄_f [N]".ljust(label) + "".join(f"{x:>{width}.4g}" for x in self.force_mid)]
        for i in range(N_CLASSES):
            lines.append(rows[i].ljust(label) + "".join(
                f"{100 * self.shares[i, j]:>{width}.3f}" for j in range(N_CLASSES))
                + f"   {self.speed_mid[i]:.4g}")
        lines += [
            f"impact cells v=1: m_h = k1·k·(F̄/c)³; sliding cells v>=2 and (1,1): "
            f"m_w = k2·F̄·V̄²; k1={self.impact_factor:g}, k2={self.sliding_factor:g}, "
            f"k={self.k:g}, c={self.c:g}",
            f"sum P_h = {self.impact_sum:.6g}   sum P_w = {self.sliding_sum:.6g}   "
            f"w = {self.intensity:.6g}",
        ]
        if self.time_above_max > 0:
            share = 100 * self.time_above_max / self.contact_time
            lines.append(f"{share:.3g}% of the contact time is above F_max or V_max (counted in "
                         "the last class)")
        return "\n".join(lines)


def _statistics(acc: KwuEpriAccumulator, k1: float, k2: float, k: float, c: float,
                stacklevel: int = 3) -> KwuEpriStatistics:
    k1 = _positive("impact_factor", k1, strict=False)
    k2 = _positive("sliding_factor", k2, strict=False)
    k = _positive("k", k, strict=False)
    c = _positive("c", c, strict=True)
    contact = acc.contact_time
    if contact > 0:
        shares = acc.class_time / contact
    else:
        shares = np.zeros_like(acc.class_time)
        warnings.warn("KWU-EPRI: no contact (Fn > 0) in the window: shares are 0 and w = 0",
                      LawWarning, stacklevel=stacklevel)
    if acc.time_above_max > 0:
        warnings.warn(
            f"KWU-EPRI: {100 * acc.time_above_max / contact:.3g}% of the contact time is above "
            f"force_max = {acc.force_max:g} N or speed_max = {acc.speed_max:g} m/s and was counted "
            "in the last class; raise FNOR_MAXI/VTAN_MAXI or leave them to the window maxima",
            LawWarning, stacklevel=stacklevel)
    fb = acc.force_max * np.arange(N_CLASSES + 1) / N_CLASSES
    vb = acc.speed_max * np.arange(N_CLASSES + 1) / N_CLASSES
    fm = 0.5 * (fb[:-1] + fb[1:])
    vm = 0.5 * (vb[:-1] + vb[1:])
    mh = np.where(IMPACT_MASK, k1 * k * (fm[None, :] / c) ** 3, 0.0)
    mw = np.where(SLIDING_MASK, k2 * fm[None, :] * vm[:, None] ** 2, 0.0)
    ph = float((shares * mh).sum())
    pw = float((shares * mw).sum())
    w = pw * pw / (ph + pw) if ph + pw > 0 else 0.0
    class_time = np.array(acc.class_time)
    for a in (shares, class_time, fb, vb, fm, vm, mh, mw):
        a.flags.writeable = False
    last = None if acc._last is None else acc._last[0]
    return KwuEpriStatistics(
        shares=shares, class_time=class_time, contact_time=contact,
        window_time=acc.window_time, force_bounds=fb, speed_bounds=vb, force_mid=fm, speed_mid=vm,
        impact_intensity=mh, sliding_intensity=mw, impact_sum=ph, sliding_sum=pw, intensity=w,
        force_max=acc.force_max, speed_max=acc.speed_max, impact_factor=k1, sliding_factor=k2,
        k=k, c=c, time_above_max=acc.time_above_max, t_start=acc.first_time, t_end=last)
