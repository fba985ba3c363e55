"""The wear table's schema: every column's native name, Code_Aster name, unit and meaning
(theory §7), in one place for the builder, the readers and writers, the obstacle update and the
Code_Aster facade.
"""

from __future__ import annotations

import pandas as pd

#: Native column -> (Code_Aster name, unit, description).
COLUMNS: dict[str, tuple[str, str, str]] = {
    "instant": ("INST", "user time unit", "instant of service (origin + duration)"),
    "duration": ("DUREE", "user time unit", "time since the origin of this run"),
    "origin": ("ORIG_INST", "user time unit", "origin of this run (0 or the restart instant)"),
    "power": ("PUIS_USUR_GLOBAL", "W", "global wear power of the run"),
    "volume_mobile": ("V_USUR_TUBE", "m³", "cumulated worn volume of the mobile (tube)"),
    "volume_obstacle": ("V_USUR_OBST", "m³", "cumulated worn volume of the obstacle"),
    "depth_mobile": ("P_USUR_TUBE", "m", "worn depth of the mobile, from its cumulated volume"),
    "depth_obstacle": ("P_USUR_OBST", "m", "worn depth of the obstacle, from its cumulated volume"),
    "sector": ("SECTEUR", "1", "sector number, 1-based"),
    "angle_start": ("ANGLE_DEBUT", "deg", "first edge of the sector"),
    "angle_end": ("ANGLE_FIN", "deg", "last edge of the sector"),
    "sector_power": ("PUIS_USUR_SECT", "W", "wear power in the sector (fretwear extension)"),
    "volume_mobile_sector": ("V_USUR_TUBE_SECT", "m³",
                             "mobile volume worn in the sector over the duration"),
    "volume_obstacle_sector": ("V_USUR_OBST_SECT", "m³",
                               "obstacle volume worn in the sector over the duration"),
    "depth_mobile_sector": ("P_USUR_TUBE_SECT", "m",
                            "sector depth of the mobile from its cumulated sector volume"),
    "depth_obstacle_sector": ("P_USUR_OBST_SECT", "m",
                              "sector depth of the obstacle from its cumulated sector volume"),
    "volume_mobile_cumulated": ("V_USUR_TUBE_CUMU", "m³", "cumulated mobile volume in the sector"),
    "volume_obstacle_cumulated": ("V_USUR_OBST_CUMU", "m³",
                                  "cumulated obstacle volume in the sector"),
}
GLOBAL_COLUMNS: tuple[str, ...] = (
    "instant", "duration", "origin", "power", "volume_mobile", "volume_obstacle",
    "depth_mobile", "depth_obstacle")
SECTOR_COLUMNS: tuple[str, ...] = GLOBAL_COLUMNS + (
    "sector", "angle_start", "angle_end", "sector_power", "volume_mobile_sector",
    "volume_obstacle_sector", "depth_mobile_sector", "depth_obstacle_sector",
    "volume_mobile_cumulated", "volume_obstacle_cumulated")
_FROM_ASTER = {aster: native for native, (aster, _, _) in COLUMNS.items()}
_TIME_TOL = 1e-9


def to_aster_names(frame: pd.DataFrame) -> pd.DataFrame:
    """A copy of a wear table with Code_Aster's column names (theory §7).

    Examples
    --------
    >>> to_aster_names(pd.DataFrame({"instant": [1.0], "volume_mobile": [2e-9]})).columns.tolist()
    ['INST', 'V_USUR_TUBE']
    """
    return frame.rename(columns={c: COLUMNS[c][0] for c in frame.columns if c in COLUMNS})


def from_aster_names(frame: pd.DataFrame) -> pd.DataFrame:
    """A copy of a wear table with native column names (Code_Aster names are converted).

    Examples
    --------
    >>> from_aster_names(pd.DataFrame({"INST": [1.0], "P_USUR_TUBE": [1e-4]})).columns.tolist()
    ['instant', 'depth_mobile']
    """
    return frame.rename(columns={c: _FROM_ASTER[c] for c in frame.columns if c in _FROM_ASTER})
