"""Excitations of the modal model: nodal forces and base acceleration.

A *signal* is a function of time, one of the families of :data:`SIGNALS`:

``"harmonic"``  ``amplitude·sin(2π f t + phase)``;
``"table"``     a tabulated function, linear between points, constant beyond its ends;
``"random"``    a stationary Gaussian signal drawn from a one-sided PSD with a seed
                (:func:`random_signal_from_psd`, reproducible), tabulated on a uniform grid.

A :class:`NodalForce` applies a signal [N] at a forcing point along a local direction;
a :class:`BaseAcceleration` moves the supports (and the obstacles, fixed to them) with a signal
[m/s²] along a direction: in relative coordinates every mode sees the force −Γ_r·a(t).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fretwear.dynamics.modal import DIRECTIONS
from fretwear.errors import InputError, KeywordError

#: Signal families and their integer codes in the compiled kernel.
SIGNALS: dict[str, int] = {"harmonic": 0, "table": 1, "random": 1}


def random_signal_from_psd(frequencies, psd, *, duration: float, seed: int,
                           sample_rate: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """A reproducible stationary Gaussian signal with a one-sided PSD (spectral representation).

    Parameters
    ----------
    frequencies : array_like
        Frequencies of the PSD table [Hz], increasing, >= 0.
    psd : array_like
        One-sided power spectral density S(f) [unit²/Hz] (N²/Hz for a force, (m/s²)²/Hz for an
        acceleration), linear between the points, 0 outside.
    duration : float
        Length of the signal [s] (it is periodic with this period).
    seed : int
        Seed of :func:`numpy.random.default_rng`: the same seed gives the same signal.
    sample_rate : float, optional
        Samples per second [Hz]; default 8 × the highest PSD frequency.

    Returns
    -------
    time [s], values [unit]

    Notes
    -----
    Shinozuka's spectral representation: x(t) = Σ_k √(2 S(f_k) Δf) cos(2π f_k t + φ_k), with
    f_k = k/T, Δf = 1/T and independent phases φ_k uniform on [0, 2π), summed by an inverse FFT.
    Over the period T the mean square is exactly Σ_k S(f_k) Δf ≈ ∫ S df.

    References
    ----------
    .. [1] Shinozuka, M., & Deodatis, G. (1991). Simulation of stochastic processes by spectral
           representation. *Applied Mechanics Reviews* 44(4), 191-204.

    Examples
    --------
    >>> t, x = random_signal_from_psd([10, 50], [1.0, 1.0], duration=10.0, seed=1)
    >>> round(float(np.mean(x[:-1]**2)), 6)   # Σ S Δf over 10 <= f <= 50, Δf = 0.1 Hz
    40.1
    """
    f = np.array(frequencies, dtype=float).reshape(-1)
    s = np.array(psd, dtype=float).reshape(-1)
    if f.size != s.size or f.size < 2:
        raise InputError("random signal: the PSD table needs matching 'frequencies' [Hz] and "
                         f"'psd' values (at least two), got {f.size} and {s.size}")
    if np.any(np.diff(f) <= 0) or f[0] < 0:
        raise InputError("random signal: PSD 'frequencies' must be >= 0 and strictly increasing")
    if np.any(s < 0) or not np.all(np.isfinite(s)):
        raise InputError("random signal: 'psd' values must be finite and >= 0")
    n, df, fk = spectral_grid(f[-1], duration, sample_rate, "random signal")
    sk = np.interp(fk, f, s, left=0.0, right=0.0)
    sk[0] = 0.0  # no mean
    sk[-1] = 0.0  # the Nyquist bin (n even) has no phase freedom
    rng = np.random.default_rng(seed)
    phases = rng.uniform(0.0, 2.0 * np.pi, fk.size)
    amp = np.sqrt(2.0 * sk * df)
    spectrum = 0.5 * n * amp * np.exp(1j * phases)
    x = np.fft.irfft(spectrum, n)
    t = np.arange(n) * (duration / n)
    # append the period end so the table covers [0, duration]
    return np.append(t, duration), np.append(x, x[0])


def spectral_grid(highest: float, duration: float, sample_rate: float | None,
                  what: str) -> tuple[int, float, np.ndarray]:
    """The grid of a spectral-representation record: (samples n, Δf [Hz], frequencies f_k [Hz]).

    Parameters
    ----------
    highest : float
        Highest frequency of the spectrum [Hz].
    duration : float
        Record length T [s], > 0; Δf = 1/T.
    sample_rate : float or None
        Samples per second [Hz] (default 8 × ``highest``), at least 2 × ``highest``.
    what : str
        The caller's name, for the messages.

    Returns
    -------
    n (even), Δf, f_k = k Δf for k = 0..n/2

    Examples
    --------
    >>> n, df, fk = spectral_grid(50.0, 2.0, None, "signal")
    >>> n, df, float(fk[-1])
    (800, 0.5, 200.0)
    """
    if not (np.isfinite(duration) and duration > 0):
        raise InputError(f"{what}: 'duration' must be > 0 [s], got {duration}")
    fs = 8.0 * highest if sample_rate is None else float(sample_rate)
    if fs < 2.0 * highest:
        raise InputError(f"{what}: sample_rate {fs} Hz is below twice the spectrum's highest "
                         f"frequency {highest} Hz (Nyquist); raise it")
    n = int(np.ceil(duration * fs))
    n += n % 2
    df = 1.0 / duration
    return n, df, np.arange(n // 2 + 1) * df


@dataclass(frozen=True, eq=False)
class Signal:
    """A function of time used by an excitation (see :data:`SIGNALS`).

    Parameters
    ----------
    kind : str
        ``"harmonic"``, ``"table"`` or ``"random"``.
    amplitude, frequency, phase : float
        Harmonic: amplitude [unit], frequency [Hz], phase [deg].
    times, values : array_like
        Table: instants [s] (strictly increasing) and values [unit].
    psd_frequencies, psd : array_like
        Random: one-sided PSD table ([Hz], [unit²/Hz]).
    duration : float
        Random: length [s] of the generated (periodic) record; it should cover the simulation.
    seed : int
        Random: the seed (required, for reproducibility).
    sample_rate : float, optional
        Random: samples per second f_s [Hz] (default 8 × the highest PSD frequency). The
        integrator interpolates the samples linearly, which scales the PSD by sinc⁴(f/f_s)
        (−10 % at f_s/8): raise it for a flatter top of the band.
    scale : float
        Multiplies the values (e.g. unit conversion), default 1.

    Examples
    --------
    >>> Signal("harmonic", amplitude=2.0, frequency=1.0).evaluate([0.25])
    array([2.])
    """

    kind: str
    amplitude: float = 0.0
    frequency: float = 0.0
    phase: float = 0.0
    times: Any = None
    values: Any = None
    psd_frequencies: Any = None
    psd: Any = None
    duration: float | None = None
    seed: int | None = None
    sample_rate: float | None = None
    scale: float = 1.0
    table: tuple = field(default=(), repr=False)

    def __post_init__(self) -> None:
        if self.kind not in SIGNALS:
            raise KeywordError(f"unknown signal kind {self.kind!r}; choose one of {list(SIGNALS)}")
        if self.kind == "harmonic":
            for key in ("amplitude", "frequency", "phase"):
                if not np.isfinite(float(getattr(self, key))):
                    raise InputError(f"harmonic signal: {key!r} must be finite")
            if self.frequency < 0:
                raise InputError(f"harmonic signal: 'frequency' must be >= 0 [Hz], got "
                                 f"{self.frequency}")
            return
        if self.kind == "table":
            if self.times is None or self.values is None:
                raise KeywordError("table signal: give 'times' [s] and 'values'")
            t = np.array(self.times, dtype=float).reshape(-1)
            v = np.array(self.values, dtype=float).reshape(-1)
            if t.size != v.size or t.size < 1:
                raise InputError(f"table signal: 'times' and 'values' need the same length, got "
                                 f"{t.size} and {v.size}")
            if np.any(np.diff(t) <= 0):
                i = int(np.flatnonzero(np.diff(t) <= 0)[0]) + 1
                raise InputError(f"table signal: 'times' must be strictly increasing (row {i})")
            if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v))):
                raise InputError("table signal: non-finite value in 'times' or 'values'")
        else:
            if self.seed is None:
                raise KeywordError("random signal: give a 'seed' (an integer) so the signal is "
                                   "reproducible")
            if self.duration is None:
                raise KeywordError("random signal: give 'duration' [s] (>= the simulated time)")
            t, v = random_signal_from_psd(self.psd_frequencies, self.psd, duration=self.duration,
                                          seed=int(self.seed), sample_rate=self.sample_rate)
        t.flags.writeable = False
        v.flags.writeable = False
        object.__setattr__(self, "table", (t, v))

    @property
    def code(self) -> int:
        """Integer code in the compiled kernel (0 harmonic, 1 tabulated)."""
        return SIGNALS[self.kind]

    def evaluate(self, time) -> np.ndarray:
        """Value of the signal at ``time`` [s].

        Examples
        --------
        >>> Signal("table", times=[0, 1], values=[0, 10]).evaluate([0.5, 2.0])
        array([ 5., 10.])
        """
        t = np.asarray(time, dtype=float)
        if self.kind == "harmonic":
            return self.scale * self.amplitude * np.sin(
                2 * np.pi * self.frequency * t + np.radians(self.phase))
        tt, vv = self.table
        return self.scale * np.interp(t, tt, vv)


@dataclass(frozen=True, eq=False)
class NodalForce:
    """A force [N] at a forcing point of the modal model along a local direction.

    Parameters
    ----------
    point : int or str
        Forcing point (index or name in ``ModalModel.forcing_names``).
    direction : str
        ``"y"``, ``"z"`` or ``"x"`` (axial).
    signal : Signal
        The force history [N].

    Examples
    --------
    >>> NodalForce(0, "y", Signal("harmonic", amplitude=1.0, frequency=5.0)).direction
    'y'
    """

    point: Any
    direction: str
    signal: Signal

    def __post_init__(self) -> None:
        if self.direction not in DIRECTIONS:
            raise KeywordError(f"nodal force: 'direction' must be 'y', 'z' or 'x', got "
                               f"{self.direction!r}")


@dataclass(frozen=True, eq=False)
class BaseAcceleration:
    """A rigid motion of the supports and obstacles: acceleration [m/s²] along a direction.

    Parameters
    ----------
    direction : str
        ``"y"``, ``"z"`` or ``"x"``.
    signal : Signal
        The acceleration history [m/s²].

    Notes
    -----
    In coordinates relative to the base, mode r sees the generalized force −Γ_r·a(t), with
    Γ_r = φ_rᵀ M e the participation factor [kg] (``ModalModel.participation``).

    Examples
    --------
    >>> BaseAcceleration("z", Signal("harmonic", amplitude=9.81, frequency=10.0)).direction
    'z'
    """

    direction: str
    signal: Signal

    def __post_init__(self) -> None:
        if self.direction not in DIRECTIONS:
            raise KeywordError(f"base acceleration: 'direction' must be 'y', 'z' or 'x', got "
                               f"{self.direction!r}")
