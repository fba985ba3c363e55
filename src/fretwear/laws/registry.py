"""The registry of wear laws: ``WEAR_LAWS`` keyed by the Code_Aster names (docs/DESIGN.md)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np

from fretwear.errors import KeywordError, LawWarning
from fretwear.history import DEFAULT_CHUNK_SIZE
from fretwear.laws import models
from fretwear.laws.kwu_history import kwu_epri_statistics
from fretwear.laws.kwu_statistics import KwuEpriStatistics

#: Marker of a parameter without default (the user must give it).
REQUIRED = None
#: The most sets of coefficients a law keeps checked for :meth:`WearLaw.rate`.
_PLAIN_KEPT = 64


@dataclass(frozen=True, eq=False)
class WearLaw:
    """One wear law: its coefficients, their Code_Aster keywords, and how to apply it.

    Attributes
    ----------
    name : str
        Code_Aster name (``"ARCHARD"``, ``"KWU_EPRI"``, ``"EDF_MZ"``).
    description : str
        One line with the equation.
    parameters : tuple of str
        Coefficients of the volume function.
    history_parameters : tuple of str
        Coefficients of the class statistics of a history (KWU-EPRI only).
    defaults : mapping
        Default of each optional coefficient (a required one is absent). ``force_max`` and
        ``speed_max`` default to None (the maxima of the window).
    units : mapping
        Unit of each coefficient.
    aster_keywords : mapping
        Coefficient -> Code_Aster keyword. Coefficients without a keyword (``intensity``, computed;
        ``reference_intensity``, implicit 1 in Code_Aster) are absent.
    linear_in_time : bool
        V proportional to t (then the equivalent time is V / (dV/dt)).
    needs_history : bool
        The law needs class statistics of the contact history (:meth:`statistics`).
    symbols : mapping
        Coefficient -> its symbol in the equations (``coefficient -> "K"``), for tables and help
        texts; a coefficient without a symbol is shown by its name.

    Notes
    -----
    Coefficients are given by their full names or by their Code_Aster keywords; a missing required
    one is a :class:`~fretwear.errors.KeywordError` naming it, an unknown one a KeywordError listing
    the accepted names. The law is always named by the user: nothing is guessed.

    Examples
    --------
    >>> law = WEAR_LAWS["ARCHARD"]
    >>> float(law.volume(0.01, 1000.0, coefficient=1e-13))
    1e-12
    >>> float(law.volume(0.01, 1000.0, COEF_USURE=1e-13))
    1e-12
    """

    name: str
    description: str
    parameters: tuple[str, ...]
    defaults: Mapping[str, Any]
    units: Mapping[str, str]
    aster_keywords: Mapping[str, str]
    linear_in_time: bool
    needs_history: bool
    history_parameters: tuple[str, ...] = ()
    symbols: Mapping[str, str] = field(default_factory=dict)
    _volume: Callable[..., np.ndarray] = field(default=None, repr=False)
    _equivalent_time: Callable[..., np.ndarray] = field(default=None, repr=False)
    #: V(P, 1 s) of a law linear in time from checked inputs: the law function's own
    #: expression at t = 1 without its checks (:meth:`rate`; None: not linear in time).
    _rate: Callable[..., np.ndarray] | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "defaults", MappingProxyType(dict(self.defaults)))
        object.__setattr__(self, "units", MappingProxyType(dict(self.units)))
        object.__setattr__(self, "aster_keywords", MappingProxyType(dict(self.aster_keywords)))
        object.__setattr__(self, "symbols", MappingProxyType(dict(self.symbols)))
        # made once (resolve runs at every volume): keyword -> name, and the accepted names
        object.__setattr__(self, "_by_keyword",
                           {kw: p for p, kw in self.aster_keywords.items()})
        object.__setattr__(self, "_accepted", frozenset(self.accepted))
        object.__setattr__(self, "_plain_rates", {})  # :meth:`_rate_coefficients`

    @property
    def accepted(self) -> tuple[str, ...]:
        """Every coefficient name the law accepts (volume and history parameters)."""
        return self.parameters + self.history_parameters

    @property
    def required(self) -> tuple[str, ...]:
        """Coefficients of the volume without default."""
        return tuple(p for p in self.parameters if p not in self.defaults)

    def resolve(self, **coefficients: Any) -> dict[str, Any]:
        """Coefficients by full name, Code_Aster keywords translated, defaults filled in.

        Raises
        ------
        KeywordError
            An unknown name (listing the accepted ones), or one coefficient given twice (by its
            name and by its keyword).

        Examples
        --------
        >>> WEAR_LAWS["EDF_MZ"].resolve(COEF_B=1.0)["power_exponent"]
        1.0
        """
        by_keyword = self._by_keyword
        out: dict[str, Any] = {}
        origin: dict[str, str] = {}
        for key, value in coefficients.items():
            name = by_keyword.get(key, key)
            if name not in self._accepted:
                listing = ", ".join(
                    f"{p} ({self.aster_keywords[p]})" if p in self.aster_keywords else p
                    for p in self.accepted)
                raise KeywordError(
                    f"{self.name}: unknown coefficient {key!r}; accepted: {listing}")
            if name in out:
                raise KeywordError(
                    f"{self.name}: coefficient {name!r} given twice ({origin[name]!r} and "
                    f"{key!r}); give it once")
            out[name] = value
            origin[name] = key
        return {**self.defaults, **out}

    def _for_volume(self, coefficients: Mapping[str, Any]) -> dict[str, Any]:
        resolved = self.resolve(**coefficients)
        for p in self.required:
            if resolved.get(p) is None:
                kw = self.aster_keywords.get(p)
                hint = (" (compute it with fretwear.laws.kwu_epri_statistics(history).intensity or "
                        "WEAR_LAWS['KWU_EPRI'].statistics(history))" if p == "intensity" else "")
                raise KeywordError(
                    f"{self.name}: the coefficient {p!r}"
                    f"{f' ({kw})' if kw else ''} [{self.units[p]}] is missing; give {p}=...{hint}")
        return {p: resolved[p] for p in self.parameters}

    def volume(self, power, duration, **coefficients: Any) -> np.ndarray:
        """Worn volume [m³] after ``duration`` [s] at wear power ``power`` [W].

        History parameters (KWU-EPRI's k1, k2, k, c, maxima) are accepted and ignored here: they
        enter through ``intensity`` (see :meth:`statistics`).
        """
        c = self._for_volume(coefficients)
        return _warning_once(lambda: self._volume(power, duration, **c))

    def rate(self, power, **coefficients: Any) -> np.ndarray:
        """Worn volume per second [m³/s] of a law linear in time at wear power ``power`` [W]:
        :meth:`volume` after 1 s, the same values, without its LawWarnings (dropped: a caller
        whose volumes at the same inputs already warned) and without ``warnings.catch_warnings``
        (whose swap of the process's filters costs every call and is not safe between threads).
        The law's expression at t = 1 s; its checks made once on plain float coefficients > 0
        and the powers, the law function's own where they fail, naming the culprit.

        Examples
        --------
        >>> law = WEAR_LAWS["KWU_EPRI"]
        >>> c = {"reference_coefficient": 1e-14, "intensity": 0.5}
        >>> bool(law.rate(np.array([0.02, 0.03]), **c)[1] == law.volume(0.03, 1.0, **c))
        True
        """
        c, plain = self._rate_coefficients(coefficients)
        if plain:
            p = np.asarray(power, dtype=float)
            # every power in [0, inf): the least >= 0 and the greatest < inf (a NaN fails both)
            if p.ndim == 0 and 0.0 <= float(p) < math.inf \
                    or p.ndim and (not p.size or p.min() >= 0.0 and p.max() < math.inf):
                return self._rate(p, **c)
        token = models._collected.set([])
        try:
            return self._volume(power, 1.0, **c)
        finally:
            models._collected.reset(token)

    def _rate_coefficients(self, coefficients: dict) -> tuple[dict[str, Any], bool]:
        """(:meth:`_for_volume` of ``coefficients``, whether :attr:`_rate` takes them: each a
        plain float > 0 and finite). Those :attr:`_rate` takes are kept per law by the given
        names and values (at most :data:`_PLAIN_KEPT` sets: a bundle's contacts share theirs;
        equal floats > 0 are the same number); the dict is then shared: read it only."""
        key = tuple(coefficients.items())
        if all(type(v) is float for _, v in key):  # hashable, and 1 is not 1.0 here
            found = self._plain_rates.get(key)
            if found is not None:
                return found, True
        else:
            key = None
        c = self._for_volume(coefficients)
        plain = self._rate is not None and all(type(v) is float and 0.0 < v < math.inf
                                               for v in c.values())
        if plain and key is not None:
            if len(self._plain_rates) >= _PLAIN_KEPT:
                self._plain_rates.clear()
            self._plain_rates[key] = c
        return c, plain

    def equivalent_time(self, volume, power, **coefficients: Any) -> np.ndarray:
        """Duration [s] at which the law reaches ``volume`` [m³] at ``power`` [W] (theory §7)."""
        c = self._for_volume(coefficients)
        return _warning_once(lambda: self._equivalent_time(volume, power, **c))

    def cumulated_volume(self, previous_volume, power, duration, **coefficients: Any) -> np.ndarray:
        """Volume [m³] after continuing ``duration`` [s] from ``previous_volume`` [m³] (restart).

        ``V_prev + V(t_eq + Δt) − V(t_eq)`` with t_eq the equivalent time of ``previous_volume``
        (for a law linear in time, simply ``V_prev + V(Δt)``); where t_eq is infinite the volume
        stays at V_prev.

        Examples
        --------
        >>> law = WEAR_LAWS["EDF_MZ"]
        >>> a = law.volume(0.01, 5e7)
        >>> b = law.cumulated_volume(law.volume(0.01, 2e7), 0.01, 3e7)
        >>> bool(abs(float(b) / float(a) - 1) < 1e-12)
        True
        """
        c = self._for_volume(coefficients)
        v0 = models._checked("previous_volume", previous_volume)
        if self.linear_in_time:
            return _warning_once(lambda: v0 + self._volume(power, duration, **c))

        def continued() -> np.ndarray:
            t0 = self._equivalent_time(v0, power, **c)
            t = models._checked("duration", duration)
            t0, t = np.broadcast_arrays(t0, t)
            finite = np.isfinite(t0)
            t0f = np.where(finite, t0, 0.0)
            delta = self._volume(power, t0f + t, **c) - self._volume(power, t0f, **c)
            return v0 + np.where(finite, delta, 0.0)

        return _warning_once(continued)

    def statistics(self, history, *, t_start=None, t_end=None,
                   chunk_size: int = DEFAULT_CHUNK_SIZE,
                   read_options: Mapping[str, Any] | None = None,
                   **coefficients: Any) -> KwuEpriStatistics:
        """Class statistics of a contact history (laws with ``needs_history`` only).

        ``history`` is a ContactHistory, a history file (streamed in chunks of ``chunk_size``
        samples, reader options in ``read_options``) or a list of chunks, as for
        :func:`~fretwear.laws.kwu_epri_statistics`; window ``t_start``, ``t_end`` [s]. Takes the
        law's coefficients (by name or keyword) and uses the history parameters.
        """
        if not self.needs_history:
            raise KeywordError(f"{self.name} does not use class statistics of a history")
        resolved = self.resolve(**coefficients)
        return kwu_epri_statistics(history, t_start=t_start, t_end=t_end, chunk_size=chunk_size,
                                   **{p: resolved[p] for p in self.history_parameters},
                                   **dict(read_options or {}))


def _warning_once(compute: Callable[[], np.ndarray]) -> np.ndarray:
    """``compute()``, its LawWarnings issued once each and attributed to the caller's caller.

    A method of :class:`WearLaw` calls the law's functions several times (a restart: equivalent
    time, then two volumes); the user should see one LawWarning, pointing at their own line.
    The law functions keep their messages in a context variable while ``compute`` runs
    (:data:`fretwear.laws.models._collected`): no ``warnings.catch_warnings``, whose swap of the
    process's filters cost every call and is not safe between threads.
    """
    token = models._collected.set([])
    try:
        result = compute()
    finally:
        caught = models._collected.get()
        models._collected.reset(token)
    for message in dict.fromkeys(caught):  # once each, in their order
        warnings.warn(message, LawWarning, stacklevel=3)
    return result


def _archard_time(volume, power, coefficient):
    rate = models._checked("coefficient", coefficient) * models._checked("power", power)
    return models.linear_equivalent_time(volume, rate)


def _kwu_time(volume, power, reference_coefficient, intensity, reference_intensity=1.0):
    rate = models.kwu_epri(power, 1.0, reference_coefficient, intensity, reference_intensity)
    return models.linear_equivalent_time(volume, rate)


WEAR_LAWS: Mapping[str, WearLaw] = MappingProxyType({
    "ARCHARD": WearLaw(
        name="ARCHARD",
        description="V = K·P·t",
        parameters=("coefficient",),
        defaults={},
        units={"coefficient": "Pa⁻¹"},
        aster_keywords={"coefficient": "COEF_USURE"},
        symbols={"coefficient": "K"},
        linear_in_time=True,
        needs_history=False,
        _volume=models.archard,
        _equivalent_time=_archard_time,
        _rate=lambda power, coefficient: coefficient * power * 1.0,  # models.archard's K·P·t
    ),
    "KWU_EPRI": WearLaw(
        name="KWU_EPRI",
        description="V = (k_r·w/w_r)·P·t, w from the 5×5 force/speed class statistics",
        parameters=("reference_coefficient", "intensity", "reference_intensity"),
        history_parameters=("impact_factor", "sliding_factor", "k", "c", "force_max", "speed_max"),
        defaults={"reference_intensity": 1.0, "impact_factor": 1.0, "sliding_factor": 1.0,
                  "k": 5.0, "c": 10.0, "force_max": None, "speed_max": None},
        # Code_Aster R7.20.01 calls k1, k2, k, c and w adimensional: they are numbers applied to
        # forces in N and speeds in m/s (docs/laws.md)
        units={"reference_coefficient": "Pa⁻¹", "intensity": "1", "reference_intensity": "1",
               "impact_factor": "1", "sliding_factor": "1", "k": "1", "c": "1",
               "force_max": "N", "speed_max": "m/s"},
        aster_keywords={"reference_coefficient": "COEF_USURE", "impact_factor": "COEF_FNOR",
                        "sliding_factor": "COEF_VTAN", "k": "COEF_K", "c": "COEF_C",
                        "force_max": "FNOR_MAXI", "speed_max": "VTAN_MAXI"},
        symbols={"reference_coefficient": "k_r", "intensity": "w", "reference_intensity": "w_r",
                 "impact_factor": "k1", "sliding_factor": "k2"},
        linear_in_time=True,
        needs_history=True,
        _volume=models.kwu_epri,
        _equivalent_time=_kwu_time,
        # models.kwu_epri's k_r·w/w_r·P·t
        _rate=lambda power, reference_coefficient, intensity, reference_intensity:
            reference_coefficient * intensity / reference_intensity * power * 1.0,
    ),
    "EDF_MZ": WearLaw(
        name="EDF_MZ",
        description="V = ((A·P^b − S)/n)·(1 − exp(−n·t)) + S·t",
        parameters=("rate_coefficient", "power_exponent", "decay_constant", "asymptotic_rate"),
        defaults=models.EDF_MZ_DEFAULTS,
        units={"rate_coefficient": "m³/(s·W^b)", "power_exponent": "1", "decay_constant": "s⁻¹",
               "asymptotic_rate": "m³/s"},
        aster_keywords={"rate_coefficient": "COEF_USURE", "power_exponent": "COEF_B",
                        "decay_constant": "COEF_N", "asymptotic_rate": "COEF_S"},
        symbols={"rate_coefficient": "A", "power_exponent": "b", "decay_constant": "n",
                 "asymptotic_rate": "S"},
        linear_in_time=False,
        needs_history=False,
        _volume=models.edf_mz,
        _equivalent_time=models.edf_mz_equivalent_time,
    ),
})


def get_law(name: str) -> WearLaw:
    """The law called ``name`` (a Code_Aster name, any case), or a KeywordError listing the laws.

    Examples
    --------
    >>> get_law("EDF_MZ").linear_in_time
    False
    >>> get_law("kwu_epri").name
    'KWU_EPRI'
    """
    try:
        return WEAR_LAWS[name.strip().upper()]
    except (KeyError, TypeError, AttributeError):
        raise KeywordError(f"unknown wear law {name!r}; choose one of {list(WEAR_LAWS)} "
                           "(the names of Code_Aster's LOI_USURE)") from None
