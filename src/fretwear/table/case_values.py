"""The small frozen values a :class:`~fretwear.table.WearCase` is made of.

* :class:`Wall`: the wall thickness of the tube [m] and its depth limit [-] (plugging
  criterion), with :attr:`Wall.limit_depth` [m] and :meth:`Wall.fraction`;
* :class:`PowerWindow`: the window of the history the wear power is computed over and its
  blocks (INST_INIT, INST_FIN, NB_BLOC of RESU_GENE);
* :class:`Restart`: the restart state (ETAT_INIT: the initial table read into an
  :class:`~fretwear.table.restart.InitialState`, at INST_INIT) and the tube replacement
  (TUBE_NEUF).

Each checks its own values when built, once: a case carries them validated, and whoever reads
``case.wall`` reads a checked wall. The user's vocabulary is the flat keywords of
:func:`fretwear.table.wear_table` (``wall_thickness``, ``depth_limit``, ``t_start``, ...,
:data:`fretwear.table.keywords.KEYWORDS`): these values are the grouping inside the case.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT, check_wall
from fretwear.table.restart import InitialState
from fretwear.table.schema import _TIME_TOL

__all__ = ["PowerWindow", "Restart", "Wall"]


def _real(value: Any, name: str, *, none: bool = True) -> float | None:
    """``value`` as a finite float (None kept when ``none``); InputError naming ``name``."""
    if value is None and none:
        return None
    if isinstance(value, bool | str | bytes) or value is None:
        ok = False
    else:
        try:
            out = float(value)
            ok = math.isfinite(out)
        except (TypeError, ValueError, OverflowError):
            ok = False
    if not ok:
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return out


@dataclass(frozen=True)
class Wall:
    """The wall of the tube (the mobile) and its depth limit.

    Parameters
    ----------
    thickness : float or None
        Wall thickness of the tube [m]; None: not known (no wall columns, no limit).
    limit : float
        Depth limit as a fraction of the wall [-], 0 < limit <= 1 (default
        :data:`~fretwear.table.DEFAULT_DEPTH_LIMIT`, 0.4: a plugging criterion).

    Raises
    ------
    InputError
        A thickness that is not a finite number > 0 [m], a limit outside (0, 1]
        (:func:`fretwear.table.limit.check_wall`, the one check).

    Examples
    --------
    >>> wall = Wall(1.09e-3)
    >>> round(wall.limit_depth, 12), round(float(wall.fraction(0.545e-3)), 12)
    (0.000436, 0.5)
    """

    thickness: float | None = None
    limit: float = DEFAULT_DEPTH_LIMIT

    def __post_init__(self) -> None:
        thickness, limit = check_wall(self.thickness, self.limit)
        object.__setattr__(self, "thickness", thickness)
        object.__setattr__(self, "limit", limit)

    @property
    def limit_depth(self) -> float | None:
        """The depth limit [m] = limit × thickness; None without a thickness."""
        return None if self.thickness is None else self.limit * self.thickness

    def fraction(self, depth):
        """``depth`` [m] (a number or an array) as a fraction of the wall [-].

        Raises
        ------
        InputError
            The wall thickness is not known.
        """
        if self.thickness is None:
            raise InputError("no wall thickness: give wall_thickness [m] (wall_thickness_m in a "
                             "case file or a manifest) to express a depth as a fraction of it")
        return np.asarray(depth, dtype=float) / self.thickness


@dataclass(frozen=True)
class PowerWindow:
    """The window of the contact history the wear power is computed over.

    Parameters
    ----------
    t_start, t_end : float or None
        Window of the history [s] (INST_INIT, INST_FIN of RESU_GENE); None: its first / last
        sample.
    blocks : int
        Blocks of equal duration of the power computation (NB_BLOC), >= 1.
    stationarity_threshold : float
        Relative block spread above which a StationarityWarning is given [-], >= 0.

    Examples
    --------
    >>> PowerWindow(0.0, 10.0, blocks=4).blocks
    4
    """

    t_start: float | None = None
    t_end: float | None = None
    blocks: int = 1
    stationarity_threshold: float = 0.1

    def __post_init__(self) -> None:
        for name, keyword in (("t_start", "INST_INIT"), ("t_end", "INST_FIN")):
            object.__setattr__(self, name, _real(getattr(self, name), f"{name} ({keyword}) [s]"))
        if self.t_start is not None and self.t_end is not None and self.t_end <= self.t_start:
            raise InputError(f"t_end (INST_FIN) = {self.t_end:g} s must be after t_start "
                             f"(INST_INIT) = {self.t_start:g} s")
        blocks = self.blocks
        if isinstance(blocks, bool) or not isinstance(blocks, int | np.integer) or blocks < 1:
            raise InputError(f"blocks (NB_BLOC) must be a whole number >= 1, got {blocks!r}")
        object.__setattr__(self, "blocks", int(blocks))
        threshold = _real(self.stationarity_threshold, "stationarity_threshold", none=False)
        if threshold < 0:
            raise InputError(f"stationarity_threshold must be >= 0 [-], got {threshold:g}")
        object.__setattr__(self, "stationarity_threshold", threshold)


@dataclass(frozen=True, eq=False)
class Restart:
    """Where the run starts: the restart state (ETAT_INIT) and the tube replacement (TUBE_NEUF).

    Parameters
    ----------
    table : InitialState or None
        The restart state, the initial table read (:func:`fretwear.table.initial_state`); None:
        a run from an unworn pair at instant 0.
    instant : float or None
        INST_INIT of ETAT_INIT [user time unit] the state was read at (None: the table's last).
    tube_replacement : float or None
        Instant [user time unit] at which the tube is replaced by a new one (TUBE_NEUF), not
        before the origin.
    source : str or None
        Where the restart state came from (a path, ``"(DataFrame)"``), for the provenance.

    Examples
    --------
    >>> Restart(tube_replacement=5.0).origin
    0.0
    """

    table: InitialState | None = None
    instant: float | None = None
    tube_replacement: float | None = None
    source: str | None = None

    def __post_init__(self) -> None:
        if self.table is not None and not isinstance(self.table, InitialState):
            raise InputError("initial_state must be an InitialState (WearCase.from_keywords reads "
                             f"a table or a file into one), got {type(self.table).__name__}")
        if self.instant is not None:
            if self.table is None:
                raise KeywordError("initial_instant (INST_INIT of ETAT_INIT) needs an "
                                   "initial_state (TABL_USURE): give the table to continue")
            object.__setattr__(self, "instant", _real(self.instant, "initial_instant (INST_INIT)"))
        if self.tube_replacement is not None:
            at = _real(self.tube_replacement, "tube_replacement (TUBE_NEUF)")
            origin = self.origin
            if at < origin - _TIME_TOL * max(1.0, abs(origin)):
                raise InputError(f"tube_replacement (TUBE_NEUF) at {at:g} is before the origin "
                                 f"{origin:g} of this run; replace the tube in the initial table "
                                 "with replace_tube() instead")
            object.__setattr__(self, "tube_replacement", at)

    @property
    def origin(self) -> float:
        """ORIG_INST of the new rows [user time unit]: 0, or the restart state's origin."""
        return 0.0 if self.table is None else float(self.table.origin)
