"""Contact time histories of one shock point (theory §1).

A :class:`ContactHistory` holds the channels of one shock point of a transient dynamic computation,
in its local shock frame, in SI units:

========== ====== ============================================================
channel    unit   meaning
========== ====== ============================================================
time       [s]    instants, strictly increasing
normal_force [N]  normal contact force Fn, >= 0 (0 outside contact)
ft1, ft2   [N]    tangential contact forces (optional)
vn         [m/s]  normal relative velocity (optional)
vt1, vt2   [m/s]  tangential (sliding) relative velocities
dy, dz     [m]    local displacements in the plane normal to the mobile's axis (optional)
stick      [-]    1 while sticking, 0 while slipping or in free flight (optional)
========== ====== ============================================================
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import InitVar, dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import HistoryError

#: Every channel, in canonical order.
CHANNELS: tuple[str, ...] = (
    "time", "normal_force", "ft1", "ft2", "vn", "vt1", "vt2", "dy", "dz", "stick",
)
#: Default number of samples per chunk when a history file is streamed (about 80 MB for ten
#: channels); used by fretwear.io, fretwear.power and the KWU-EPRI statistics.
DEFAULT_CHUNK_SIZE = 1_000_000
#: Channels a history cannot do without.
REQUIRED: tuple[str, ...] = ("time", "normal_force", "vt1", "vt2")
#: Channels that may be absent (None).
OPTIONAL: tuple[str, ...] = ("ft1", "ft2", "vn", "dy", "dz", "stick")
#: Unit of each channel (SI).
UNITS: Mapping[str, str] = MappingProxyType({
    "time": "s", "normal_force": "N", "ft1": "N", "ft2": "N", "vn": "m/s", "vt1": "m/s",
    "vt2": "m/s", "dy": "m", "dz": "m", "stick": "1",
})
#: One-line description of each channel, used in documentation and file headers.
DESCRIPTIONS: Mapping[str, str] = MappingProxyType({
    "time": "instant [s], strictly increasing",
    "normal_force": "normal contact force Fn [N], >= 0",
    "ft1": "tangential contact force along local axis 1 [N]",
    "ft2": "tangential contact force along local axis 2 [N]",
    "vn": "normal relative velocity [m/s]",
    "vt1": "sliding velocity along local axis 1 [m/s]",
    "vt2": "sliding velocity along local axis 2 [m/s]",
    "dy": "local displacement along y in the plane normal to the mobile [m]",
    "dz": "local displacement along z in the plane normal to the mobile [m]",
    "stick": "stick flag: 1 sticking, 0 slipping or free [-]",
})


def _first_bad(mask: np.ndarray) -> int:
    return int(np.flatnonzero(mask)[0])


@dataclass(frozen=True, eq=False)
class ContactHistory:
    """Time histories of one shock point, validated, immutable, SI units.

    Parameters
    ----------
    time : array_like
        Instants [s], strictly increasing, at least two.
    normal_force : array_like
        Normal force Fn [N], >= 0. Values in ``[-force_tolerance, 0)`` (solver noise) are set to 0
        in the history's own copy; anything more negative is an error.
    vt1, vt2 : array_like
        Sliding velocities in the local tangent plane [m/s].
    ft1, ft2 : array_like, optional
        Tangential forces [N].
    vn : array_like, optional
        Normal velocity [m/s].
    dy, dz : array_like, optional
        Local displacements [m]; give both or neither. They define the contact angle
        ``atan2(dz, dy)`` used by angular sectors.
    stick : array_like, optional
        Stick flag, 1 = sticking (the interval that starts on a sticking sample produces no wear).
    name : str
        A label (node, group, file) for tables and messages.
    metadata : mapping
        Free provenance information (source file, units converted, ...).
    force_tolerance : float, optional
        Absolute tolerance [N] on negative normal forces. Default ``1e-9 × max|Fn|`` (at least
        1e-12 N).
    first_row : int
        Row number of the first sample in the file it was read from (a chunk of a long file),
        so that the messages name the file's rows; not stored. Default 0.

    Raises
    ------
    HistoryError
        Naming the channel and the first bad row: lengths differ, a value is NaN or infinite,
        time is not strictly increasing, the normal force is negative, only one of dy/dz given,
        or a stick flag that is not 0/1.

    Notes
    -----
    The arrays are copied and made read-only: nothing the user passed is modified.

    Examples
    --------
    >>> h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[10.0, 10.0, 10.0],
    ...                    vt1=[0.1, 0.1, 0.1], vt2=[0.0, 0.0, 0.0])
    >>> len(h), h.duration
    (3, 2.0)
    """

    time: np.ndarray
    normal_force: np.ndarray
    vt1: np.ndarray
    vt2: np.ndarray
    ft1: np.ndarray | None = None
    ft2: np.ndarray | None = None
    vn: np.ndarray | None = None
    dy: np.ndarray | None = None
    dz: np.ndarray | None = None
    stick: np.ndarray | None = None
    name: str = ""
    metadata: Mapping[str, Any] = field(default_factory=dict)
    force_tolerance: float | None = None
    first_row: InitVar[int] = 0

    def __post_init__(self, first_row: int = 0) -> None:
        r = int(first_row)  # rows named in the messages are the file's: r + index
        arrays: dict[str, np.ndarray] = {}
        for ch in CHANNELS:
            value = getattr(self, ch)
            if value is None:
                if ch in REQUIRED:
                    raise HistoryError(
                        f"contact history {self.name!r}: the required channel {ch!r} is missing; "
                        f"give {ch}=... ({DESCRIPTIONS[ch]})")
                continue
            try:
                arr = np.array(value, dtype=float, copy=True)
            except (TypeError, ValueError) as exc:
                raise HistoryError(
                    f"contact history {self.name!r}: channel {ch!r} is not numeric ({exc}); "
                    "give a sequence of numbers") from None
            if arr.ndim != 1:
                raise HistoryError(
                    f"contact history {self.name!r}: channel {ch!r} must be one-dimensional, "
                    f"got shape {arr.shape}")
            arrays[ch] = arr
        n = arrays["time"].size
        for ch, arr in arrays.items():
            if arr.size != n:
                raise HistoryError(
                    f"contact history {self.name!r}: channel {ch!r} has {arr.size} samples but "
                    f"'time' has {n}; every channel needs one value per instant")
        if n < 2:
            raise HistoryError(
                f"contact history {self.name!r}: at least two instants are needed, got {n}")
        for ch, arr in arrays.items():
            bad = ~np.isfinite(arr)
            if bad.any():
                i = _first_bad(bad)
                raise HistoryError(
                    f"contact history {self.name!r}: channel {ch!r} has a non-finite value "
                    f"({float(arr[i])}) at row {r + i}; remove or fill it before reading")
        dt = np.diff(arrays["time"])
        if (dt <= 0).any():
            i = _first_bad(dt <= 0) + 1
            t0, t1 = float(arrays["time"][i - 1]), float(arrays["time"][i])
            raise HistoryError(
                f"contact history {self.name!r}: channel 'time' is not strictly increasing at row "
                f"{r + i} (t[{r + i - 1}] = {t0!r}, t[{r + i}] = {t1!r}); "
                "sort the samples and drop duplicated instants")
        fn = arrays["normal_force"]
        tol = self.force_tolerance
        if tol is None:
            tol = max(1e-12, 1e-9 * float(np.max(np.abs(fn))))
        if tol < 0:
            raise HistoryError(f"force_tolerance must be >= 0 [N], got {tol}")
        neg = fn < -tol
        if neg.any():
            i = _first_bad(neg)
            raise HistoryError(
                f"contact history {self.name!r}: channel 'normal_force' is negative "
                f"({float(fn[i])} N) at row {r + i} (t = {float(arrays['time'][i])!r} s); the "
                "normal force must be >= 0 - check the sign convention of the exported FN column "
                "or negate it")
        np.maximum(fn, 0.0, out=fn)
        if ("dy" in arrays) != ("dz" in arrays):
            missing = "dz" if "dy" in arrays else "dy"
            raise HistoryError(
                f"contact history {self.name!r}: {missing!r} is missing while its partner is "
                "given; the contact angle needs both dy and dz (or neither)")
        if "stick" in arrays:
            s = arrays["stick"]
            bad = (s != 0) & (s != 1)
            if bad.any():
                i = _first_bad(bad)
                raise HistoryError(
                    f"contact history {self.name!r}: channel 'stick' must be 0 or 1, got "
                    f"{float(s[i])} at row {r + i}; Code_Aster's VINT13 is 1 while sticking")
        for ch, arr in arrays.items():
            arr.flags.writeable = False
            object.__setattr__(self, ch, arr)
        object.__setattr__(self, "metadata", MappingProxyType(dict(self.metadata)))
        object.__setattr__(self, "force_tolerance", float(tol))

    @classmethod
    def _checked_elsewhere(cls, arrays: Mapping[str, np.ndarray], *, name: str,
                           metadata: Mapping[str, Any], force_tolerance: float
                           ) -> ContactHistory:
        """A history of arrays that already pass every rule of the validation, *not copied*.

        For readers that check a chunk without copying it
        (:func:`fretwear.io.channels.fast_history`); the arrays are made read-only views.
        ``force_tolerance`` [N] is the one the validation would have set.
        """
        self = object.__new__(cls)
        for ch in CHANNELS:
            value = arrays.get(ch)
            if value is not None:
                value = value.view()
                value.flags.writeable = False
            object.__setattr__(self, ch, value)
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "metadata", MappingProxyType(dict(metadata)))
        object.__setattr__(self, "force_tolerance", float(force_tolerance))
        return self

    # ------------------------------------------------------------------ properties
    def __len__(self) -> int:
        return int(self.time.size)

    @property
    def duration(self) -> float:
        """Length of the record, ``time[-1] - time[0]`` [s]."""
        return float(self.time[-1] - self.time[0])

    @property
    def channels(self) -> tuple[str, ...]:
        """Names of the channels present, in canonical order."""
        return tuple(ch for ch in CHANNELS if getattr(self, ch) is not None)

    @property
    def sliding_speed(self) -> np.ndarray:
        """Sliding speed ``sqrt(vt1² + vt2²)`` [m/s]."""
        return np.hypot(self.vt1, self.vt2)

    @property
    def angle(self) -> np.ndarray:
        """Contact angle ``atan2(dz, dy)`` [deg] in (-180, 180]; 0 where dy = dz = 0 or absent."""
        if self.dy is None:
            return np.zeros_like(self.time)
        return contact_angle(self.dy, self.dz)

    # ------------------------------------------------------------------ conversions
    def window(self, t_start: float | None = None, t_end: float | None = None) -> ContactHistory:
        """The samples with ``t_start <= time <= t_end`` [s], as a new history."""
        lo = -np.inf if t_start is None else t_start
        hi = np.inf if t_end is None else t_end
        keep = (self.time >= lo) & (self.time <= hi)
        if keep.sum() < 2:
            raise HistoryError(
                f"contact history {self.name!r}: the window [{t_start}, {t_end}] s holds fewer "
                f"than two samples (record spans {float(self.time[0])} .. {float(self.time[-1])} s)"
            )
        return self.replace(**{ch: getattr(self, ch)[keep] for ch in self.channels})

    def replace(self, **changes: Any) -> ContactHistory:
        """A copy with some channels or attributes replaced (validated again)."""
        kw: dict[str, Any] = {ch: getattr(self, ch) for ch in CHANNELS}
        kw.update(name=self.name, metadata=dict(self.metadata))
        kw.update(changes)
        return ContactHistory(**kw)

    def to_frame(self):
        """The channels as a :class:`pandas.DataFrame` with canonical column names (SI units)."""
        return pd.DataFrame({ch: np.array(getattr(self, ch)) for ch in self.channels})

    @classmethod
    def from_frame(cls, frame, *, name: str = "", metadata: Mapping[str, Any] | None = None,
                   **kwargs: Any) -> ContactHistory:
        """Build a history from a DataFrame whose columns are canonical channel names."""
        unknown = [c for c in frame.columns if c not in CHANNELS]
        if unknown:
            raise HistoryError(
                f"unknown column(s) {unknown}; expected canonical channel names {list(CHANNELS)}")
        data = {c: frame[c].to_numpy() for c in frame.columns}
        return cls(**data, name=name, metadata=dict(metadata or {}), **kwargs)

    def __repr__(self) -> str:
        return (f"ContactHistory(name={self.name!r}, samples={len(self)}, "
                f"t=[{self.time[0]:g}, {self.time[-1]:g}] s, channels={list(self.channels)})")


def contact_angle(dy, dz) -> np.ndarray:
    """Contact angle ``atan2(dz, dy)`` [deg], folded into (-180, 180]; 0 where dy = dz = 0.

    Parameters
    ----------
    dy, dz : array_like
        Local displacements [m] (any common unit).

    Returns
    -------
    numpy.ndarray
        θ [deg] in (-180, 180].

    Notes
    -----
    θ = atan2(dz, dy); -180 is folded to +180, and θ = 0 when dy = dz = 0, signed zeros
    included (theory §3).

    Examples
    --------
    >>> contact_angle([1.0, 0.0, -1.0, 0.0, -0.0], [0.0, 1.0, -0.0, 0.0, -0.0]).tolist()
    [0.0, 90.0, 180.0, 0.0, 0.0]
    """
    y = np.asarray(dy, dtype=float)
    z = np.asarray(dz, dtype=float)
    theta = np.degrees(np.arctan2(z, y))
    theta = np.where(theta <= -180.0, 180.0, theta)
    # theory §3: 0 where dy = dz = 0, signed zeros included (atan2(0, -0.0) would give 180).
    theta = np.where((y == 0.0) & (z == 0.0), 0.0, theta)
    return theta + 0.0  # turn -0.0 into 0.0
