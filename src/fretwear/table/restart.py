"""Restarts of the wear table: reading previous tables, the initial state, tube replacement.

Theory §7: a previous table (ours, or a Code_Aster one read from its text file) gives the origin
ORIG_INST (its last instant, or INST_INIT) and the cumulated volumes there; TUBE_NEUF replaces
the tube (its volumes and depths restart from zero, the obstacle's are kept). Used by
:func:`fretwear.table.wear_table` (``initial_state=``) and :func:`fretwear.workflows.aster.POST_USURE`.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.errors import InputError
from fretwear.table.files import read_wear_table
from fretwear.table.schema import _TIME_TOL, COLUMNS, from_aster_names, to_aster_names
from fretwear.sectors import sector_edges as _validated_edges

__all__ = ["InitialState", "initial_state", "read_wear_table", "replace_tube"]


@dataclass(frozen=True)
class InitialState:
    """The state a restart continues from (theory §7, ETAT_INIT).

    Attributes
    ----------
    origin : float
        ORIG_INST of the new rows [user time unit].
    volume_mobile, volume_obstacle : float
        Cumulated global volumes at the origin [m³].
    sector_volume_mobile, sector_volume_obstacle : ndarray or None
        Cumulated sector volumes at the origin [m³] (sector tables only).
    edges : ndarray or None
        Sector edges of the table [deg].
    rows : DataFrame
        The table's rows up to the origin (native names), kept at the head of the new table.
    """

    origin: float
    volume_mobile: float
    volume_obstacle: float
    sector_volume_mobile: np.ndarray | None
    sector_volume_obstacle: np.ndarray | None
    edges: np.ndarray | None
    rows: pd.DataFrame

    @property
    def sector_count(self) -> int:
        """Number of sectors of the initial table (0 for a table without sectors)."""
        return 0 if self.edges is None else len(self.edges) - 1


def _column(frame: pd.DataFrame, names: Sequence[str], what: str, source: str) -> np.ndarray:
    for name in names:
        if name in frame.columns:
            values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
            return np.where(np.isnan(values), 0.0, values)
    aster = [COLUMNS[n][0] for n in names if n in COLUMNS]
    raise InputError(f"initial wear table {source}: no column for {what}; expected one of "
                     f"{list(names)} (Code_Aster {aster})")


def initial_state(table: pd.DataFrame | str | os.PathLike,
                  initial_instant: float | None = None) -> InitialState:
    """The restart state of a previous wear table (ours or Code_Aster's), theory §7.

    Parameters
    ----------
    table : DataFrame or path-like
        A previous table, native or Code_Aster column names, or its file.
    initial_instant : float, optional
        INST_INIT [user time unit]: an instant of the table to continue from (rows after it are
        dropped). Default: its last instant.

    Returns
    -------
    InitialState

    Examples
    --------
    >>> prev = pd.DataFrame({"INST": [1.0, 2.0], "V_USUR_TUBE": [1e-9, 2e-9],
    ...                      "V_USUR_OBST": [0.0, 0.0]})
    >>> s = initial_state(prev, initial_instant=1.0)
    >>> s.origin, s.volume_mobile, len(s.rows)
    (1.0, 1e-09, 1)
    """
    source = "(DataFrame)"
    if not isinstance(table, pd.DataFrame):
        source = repr(str(table))
        table = read_wear_table(table)
    else:
        table = from_aster_names(table)
    if len(table) == 0:
        raise InputError(f"initial wear table {source} has no rows")
    inst = _column(table, ["instant"], "the instant (INST)", source)
    if initial_instant is None:
        origin = float(inst.max())
    else:
        origin = float(initial_instant)
        scale = max(1.0, float(np.abs(inst).max()))
        if not np.any(np.abs(inst - origin) <= _TIME_TOL * scale):
            raise InputError(
                f"INST_INIT / initial_instant = {origin:g} is not an instant of the initial wear "
                f"table {source}; its instants are {sorted(set(inst.tolist()))}")
    scale = max(1.0, abs(origin))
    keep = inst <= origin + _TIME_TOL * scale
    rows = table.loc[keep].reset_index(drop=True)
    at = np.abs(inst[keep] - origin) <= _TIME_TOL * scale
    last = rows.loc[at]
    if "sector" in rows.columns and rows["sector"].notna().any():
        # rows without a sector number (a global row per instant) do not hold sector volumes
        last = last[pd.to_numeric(last["sector"], errors="coerce").notna()].sort_values("sector")
        sectors = pd.to_numeric(last["sector"]).to_numpy()
        if len(np.unique(sectors)) != len(sectors):
            raise InputError(f"initial wear table {source}: sector numbers repeat at instant "
                             f"{origin:g}; one row per sector is expected")
        starts = _column(last, ["angle_start"], "the sector start angle (ANGLE_DEBUT)", source)
        ends = _column(last, ["angle_end"], "the sector end angle (ANGLE_FIN)", source)
        edges = np.append(starts, ends[-1])
        if not np.allclose(starts[1:], ends[:-1]):
            raise InputError(f"initial wear table {source}: its sectors are not contiguous "
                             f"(ANGLE_DEBUT {starts.tolist()}, ANGLE_FIN {ends.tolist()})")
        svm = _column(last, ["volume_mobile_cumulated", "volume_mobile_sector"],
                      "the cumulated sector volume of the tube", source)
        svo = _column(last, ["volume_obstacle_cumulated", "volume_obstacle_sector"],
                      "the cumulated sector volume of the obstacle", source)
        return InitialState(origin, float(svm.sum()), float(svo.sum()), svm, svo,
                            _validated_edges(edges), rows)
    vm = _column(last, ["volume_mobile_cumulated", "volume_mobile"], "the tube's volume", source)
    vo = _column(last, ["volume_obstacle_cumulated", "volume_obstacle"],
                 "the obstacle's volume", source)
    return InitialState(origin, float(vm[-1]), float(vo[-1]), None, None, None, rows)


def replace_tube(table: pd.DataFrame | str | os.PathLike, instant: float | None = None
                 ) -> pd.DataFrame:
    """The wear table with the tube replaced by a new one at ``instant`` (TUBE_NEUF, theory §7).

    The rows after ``instant`` are dropped; on the rows at ``instant`` the tube's volumes and
    depths are set to zero and the obstacle's are kept, so that the result seeds a restart
    (:func:`wear_table` ``initial_state=``) of a new tube against the worn obstacle.

    Parameters
    ----------
    table : DataFrame or path-like
        A wear table, native or Code_Aster names (the result keeps the names given).
    instant : float, optional
        Instant of the replacement [user time unit]; an instant of the table. Default: the last.

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0, 2.0], "volume_mobile": [1e-9, 2e-9],
    ...                   "volume_obstacle": [3e-10, 6e-10], "depth_mobile": [1e-5, 2e-5]})
    >>> replace_tube(t, 2.0).iloc[-1].tolist()
    [2.0, 0.0, 6e-10, 0.0]
    """
    if not isinstance(table, pd.DataFrame):
        table = read_wear_table(table)
    aster = "INST" in table.columns
    native = from_aster_names(table)
    state = initial_state(native, instant)
    rows = state.rows.copy()
    at = np.isclose(rows["instant"].to_numpy(dtype=float), state.origin, rtol=0, atol=_TIME_TOL
                    * max(1.0, abs(state.origin)))
    for col in ("volume_mobile", "depth_mobile", "volume_mobile_sector", "depth_mobile_sector",
                "volume_mobile_cumulated"):
        if col in rows.columns:
            rows.loc[at, col] = 0.0
    rows.attrs = dict(table.attrs)
    return to_aster_names(rows) if aster else rows
