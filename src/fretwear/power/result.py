"""The result of a wear-power computation: :class:`PowerResult` (theory §2-§3).

The total power of a window, its block and sector powers and the contact statistics, as
:func:`fretwear.power.wear_power` and :meth:`fretwear.power.PowerAccumulator.result` return
them, with the confidence interval of the power from its blocks (batch means,
:mod:`fretwear.power.confidence`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from fretwear.errors import ConfidenceWarning, InputError
from fretwear.power.confidence import PowerInterval, batch_means_interval
from fretwear.power.statistics import (
    ContactStatistics,
    _jsonable,
    frozen_arrays,
    frozen_instance,
)

__all__ = ["PowerResult"]


@dataclass(frozen=True, eq=False)
class PowerResult:
    """Wear power of a window, its blocks and sectors, and the contact statistics.

    Attributes
    ----------
    total : float
        Wear power P over the window [W].
    blocks : numpy.ndarray
        Power of each block P_b [W] (their mean is ``total``).
    block_edges : numpy.ndarray
        B + 1 block edges [s].
    sectors : numpy.ndarray or None
        Power of each angular sector P_j [W] (they add up to ``total``), None without sectors.
    sector_edges : numpy.ndarray or None
        N + 1 sector edges [deg].
    t_start, t_end, duration : float
        Window bounds and length T [s].
    spread : float
        Relative spread of the block powers (max - min)/mean [-]; 0 for one block or no wear.
    statistics : ContactStatistics or None
        Contact statistics over the same window; None where not asked for
        (``wear_power(..., statistics=False)``).
    name : str
        Name of the history.
    block_sectors : numpy.ndarray or None
        Power of each block in each sector [W], shape (B, N) (sector intervals), None without
        sectors.
    kwu : KwuEpriAccumulator or KwuEpriMaxima or None
        The KWU-EPRI class counts (or the window's maxima) reduced in the same pass, when asked
        for (``PowerAccumulator(kwu=...)``, ``wear_power(..., kwu=...)``); not in
        :meth:`to_dict`.

    Examples
    --------
    >>> from fretwear.history import ContactHistory
    >>> from fretwear.power import wear_power
    >>> h = ContactHistory(time=[0.0, 1.0], normal_force=[2.0, 2.0], vt1=[0.5, 0.5],
    ...                    vt2=[0.0, 0.0])
    >>> wear_power(h).to_dict()["total"]
    1.0
    """

    total: float
    blocks: np.ndarray
    block_edges: np.ndarray
    sectors: np.ndarray | None
    sector_edges: np.ndarray | None
    t_start: float
    t_end: float
    duration: float
    spread: float
    statistics: ContactStatistics | None
    name: str = ""
    block_sectors: np.ndarray | None = None
    kwu: Any = field(default=None, repr=False)

    def __post_init__(self) -> None:
        frozen_arrays(self, _ARRAYS)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary; units: powers [W], times [s], angles [deg].

        Made once per result (a result is read, not changed: every wear table of it writes
        this dict in its ``attrs["power"]``), a new copy at each call (its dicts and lists
        new: the caller's to change)."""
        made = self.__dict__.get("_as_dict")
        if made is None:
            made = {f.name: (None if self.statistics is None else self.statistics.to_dict())
                    if f.name == "statistics"
                    else [_jsonable(row) for row in self.block_sectors]
                    if f.name == "block_sectors" and self.block_sectors is not None
                    else _jsonable(getattr(self, f.name)) for f in fields(self)
                    if f.name != "kwu"}
            object.__setattr__(self, "_as_dict", made)
        return _copied(made)

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)  # pickled without the dict of to_dict (made again)
        state.pop("_as_dict", None)
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:  # unpickled: read-only again
        self.__dict__.update(state)
        frozen_arrays(self, _ARRAYS)

    def confidence_interval(self, level: float = 0.95, *, sector: int | None = None
                            ) -> PowerInterval:
        """Confidence interval of the power (or of one sector's power) from the block powers.

        Batch means with Student's t over the B blocks (:mod:`fretwear.power.confidence`);
        ``str()`` of the result reads ``P = 0.184 ± 0.012 W (95 %)``.

        Parameters
        ----------
        level : float
            Confidence level in (0, 1) [-].
        sector : int, optional
            1-based sector (default: the total power).

        Raises
        ------
        InputError
            Fewer than 2 blocks, or no such sector.

        Warns
        -----
        ConfidenceWarning
            Fewer than 10 blocks, or block powers correlated at lag 1.

        Examples
        --------
        Blocks alternating between 2.2 and 1.8 W: mean 2, s = 0.2108, t(9) = 2.262.

        >>> from fretwear.history import ContactHistory
        >>> from fretwear.power import wear_power
        >>> t = np.linspace(0, 10, 10001)
        >>> h = ContactHistory(time=t, normal_force=np.full(t.size, 2.0),
        ...                    vt1=1 + 0.1 * np.cos(np.pi * np.floor(t)), vt2=np.zeros(t.size))
        >>> r = wear_power(h, blocks=10, t_start=0, t_end=10, stationarity_threshold=0.5)
        >>> str(r.confidence_interval())
        'P = 2.00 ± 0.15 W (95 %)'
        """
        if sector is None:
            return batch_means_interval(self.blocks, level, name=self.name or "total")
        if self.sectors is None or self.block_sectors is None:
            raise InputError("this power has no sectors; compute it with sectors=... for "
                             "sector intervals")
        count = len(self.sectors)
        if isinstance(sector, bool) or not 1 <= int(sector) <= count:
            raise InputError(f"sector must be a 1-based sector number in 1..{count}, got "
                             f"{sector!r}")
        return batch_means_interval(self.block_sectors[:, int(sector) - 1], level,
                                    name=f"{self.name or 'power'} sector {int(sector)}")

    def sector_confidence_intervals(self, level: float = 0.95) -> list[PowerInterval]:
        """:meth:`confidence_interval` of every sector, in order (empty without sectors).

        The sectors' ConfidenceWarnings are issued once per kind, naming the sectors.
        """
        if self.sectors is None:
            return []
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ConfidenceWarning)
            out = [self.confidence_interval(level, sector=j + 1)
                   for j in range(len(self.sectors))]
        grouped: dict[str, list[str]] = {}
        for w in caught:
            name, _, rest = str(w.message).partition(": ")
            grouped.setdefault(rest, []).append(name.rpartition(" sector ")[2])
        for rest, sectors in grouped.items():
            warnings.warn(f"{self.name or 'power'} sectors {', '.join(sectors)}: {rest}",
                          ConfidenceWarning, stacklevel=2)
        return out


def own_result(**values: Any) -> PowerResult:
    """``PowerResult(**values)`` (every field given) for a caller that made its arrays for it:
    they are made read-only in place (:func:`fretwear.power.statistics.frozen_instance`)."""
    return frozen_instance(PowerResult, values, _ARRAYS)


def window_powers(power: np.ndarray, blocks: int, duration: float, sectors: bool
                  ) -> tuple[float, np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The total, block, sector and block × sector powers [W] of a window of ``duration`` [s]
    from its [B, N] block × sector integrals ``power`` [J] (each a new array; None without
    ``sectors``): ``Σ power / T``, ``power.sum(axis=1) / (T/B)``, ``power.sum(axis=0) / T``,
    ``power / (T/B)``.

    One block (a bundle's contact): the same numbers in fewer numpy calls. The one row's sum
    is numpy's sum of all (the same pairwise sum of the same contiguous values), divided by
    T / 1 = T as the total; the sector powers are the one row of ``power / T``, as
    ``sum(axis=0)`` of one row is ``+0.0 + x``, which is x: the integrals never hold -0.0
    (they are sums from +0.0).

    Examples
    --------
    >>> total, blocks, by_sector, _ = window_powers(np.array([[1.0, 3.0]]), 1, 2.0, True)
    >>> total, blocks.tolist(), by_sector.tolist()
    (2.0, [2.0], [0.5, 1.5])
    """
    T = duration
    with np.errstate(over="ignore"):  # an overflow is refused by check_finite_power
        if blocks == 1:
            total = float(power.sum()) / T
            block_sectors = power / T if sectors else None
            return (total, np.array([total]),
                    None if block_sectors is None else block_sectors[0], block_sectors)
        block_powers = power.sum(axis=1) / (T / blocks)
        total = float(power.sum()) / T
        if not sectors:
            return total, block_powers, None, None
        return total, block_powers, power.sum(axis=0) / T, power / (T / blocks)


def _copied(value: Any) -> Any:
    """A copy of a JSON-ready value: its dicts and lists new, the numbers, strings and None
    shared (immutable)."""
    if type(value) is dict:
        return {k: _copied(v) if type(v) in _CONTAINERS else v for k, v in value.items()}
    return [_copied(v) if type(v) in _CONTAINERS else v for v in value]


_CONTAINERS = (dict, list)
_ARRAYS = ("blocks", "block_edges", "sectors", "sector_edges", "block_sectors")
