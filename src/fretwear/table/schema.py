"""The schema of fretwear's tables: every column's native name, Code_Aster name, unit and
meaning (theory §7, §8), in one place for the builder, the readers and writers, the obstacle
update, the coupled loop and the Code_Aster facade.

- :data:`COLUMNS`: the wear table (POST_USURE's columns and fretwear's extensions);
- :data:`PROFILE_COLUMNS`: the obstacle update's profile table (MODI_OBSTACLE);
- :data:`FLOAT_FORMAT`: the one format of reals in every text file fretwear writes (CSV and
  Code_Aster tables): ``%.16E``, 17 significant digits, which round-trips every float64
  exactly (Parquet stores the binary float64), always with a mantissa point and an exponent.
  The exponent matters: Code_Aster's LIRE_TABLE (``TableReader.convert``) tries ``int()``
  before ``float()`` on each TABLEAU cell, so a real printed ``1`` (as ``%g`` prints 1.0)
  would come back as an integer and turn the INST column into integers.
"""

from __future__ import annotations

from fretwear._lazy import pandas as pd

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
    # with a wall thickness (fretwear extensions, fretwear.table.limit)
    "wall_fraction": ("FRAC_PAROI", "1", "global depth of the mobile over its wall thickness"),
    "limit_instant": ("INST_LIMITE", "user time unit",
                      "instant at which the global depth reaches depth_limit × wall thickness "
                      "(inf: never; the origin: already there)"),
    "wall_fraction_sector": ("FRAC_PAROI_SECT", "1",
                             "sector depth of the mobile over its wall thickness"),
    "limit_instant_sector": ("INST_LIMITE_SECT", "user time unit",
                             "instant at which the sector depth reaches depth_limit × wall "
                             "thickness"),
}
#: Columns added when the case gives the wall thickness (global, and in sector mode).
WALL_COLUMNS: tuple[str, ...] = ("wall_fraction", "limit_instant")
WALL_SECTOR_COLUMNS: tuple[str, ...] = WALL_COLUMNS + ("wall_fraction_sector",
                                                       "limit_instant_sector")
GLOBAL_COLUMNS: tuple[str, ...] = (
    "instant", "duration", "origin", "power", "volume_mobile", "volume_obstacle",
    "depth_mobile", "depth_obstacle")
SECTOR_COLUMNS: tuple[str, ...] = GLOBAL_COLUMNS + (
    "sector", "angle_start", "angle_end", "sector_power", "volume_mobile_sector",
    "volume_obstacle_sector", "depth_mobile_sector", "depth_obstacle_sector",
    "volume_mobile_cumulated", "volume_obstacle_cumulated")
#: Obstacle profile table (:meth:`fretwear.obstacle.ObstacleResult.to_frame`), one row per
#: direction: native column -> (Code_Aster name, unit, description).
PROFILE_COLUMNS: dict[str, tuple[str, str, str]] = {
    "angle": ("THETA", "deg", "direction of the clearance, 0..360"),
    "clearance_initial": ("JEU_INIT", "m", "clearance of the new mobile in the new obstacle"),
    "clearance_worn": ("JEU_USE", "m", "clearance of the worn mobile in the worn obstacle"),
    "depth_mobile": ("P_USUR_TUBE", "m", "worn radial depth of the mobile in that direction"),
    "depth_obstacle": ("P_USUR_OBST", "m", "worn radial depth of the obstacle in that direction"),
}
#: printf format of every real in fretwear's text tables (CSV, Code_Aster): exact for float64,
#: and never integer-looking (Code_Aster's LIRE_TABLE would read ``1`` as an integer).
FLOAT_FORMAT = "%.16E"
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
