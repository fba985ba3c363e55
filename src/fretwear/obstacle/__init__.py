"""Obstacle update (Code_Aster's MODI_OBSTACLE): the worn clearance profile (theory §8).

From the cumulated sector volumes of a wear table at one instant, build the worn depth profiles
of the mobile and of the obstacle over the angle (uniform per sector, theory §3, or a smooth
shape keeping each sector's volume), and the new clearance in each direction: how far the worn
mobile can translate before it touches the worn obstacle, computed exactly on the profiles.

Modules: :mod:`~fretwear.obstacle.profiles` (mobile, obstacle models, DISCRET files),
:mod:`~fretwear.obstacle.depth` (worn depth profiles), :mod:`~fretwear.obstacle.clearance`
(exact translation search), :mod:`~fretwear.obstacle.dilation` (the obstacle behind a
clearance figure), :mod:`~fretwear.obstacle.update` (the update, its tables),
:mod:`~fretwear.obstacle.config` (the ``[obstacle]`` case-file section).
"""

from __future__ import annotations

from fretwear.obstacle.clearance import clearance_figure, polar_polygon
from fretwear.obstacle.config import OBSTACLE_KEYS, ObstacleSetup, obstacle_from_config
from fretwear.obstacle.depth import DEPTH_SHAPES, WornDepth, worn_depth_profiles
from fretwear.obstacle.dilation import dilated_radius
from fretwear.obstacle.discret_file import load_obstacle_profile, read_discret, write_discret
from fretwear.obstacle.profiles import (
    DISCRET_NEW_GAP,
    DISCRET_POINTS,
    DISCRET_STEP,
    OBSTACLE_MODELS,
    CircleObstacle,
    DiscreteObstacle,
    Mobile,
    PlanesObstacle,
    discret_angles,
)
from fretwear.obstacle.update import (
    ObstacleResult,
    read_wear_table,  # fretwear.table's, re-exported
    sector_volumes,
    update_obstacle,
    update_obstacle_from_table,
)

__all__ = [
    "CircleObstacle", "DEPTH_SHAPES", "DISCRET_NEW_GAP", "DISCRET_POINTS", "DISCRET_STEP",
    "DiscreteObstacle", "Mobile", "OBSTACLE_KEYS", "OBSTACLE_MODELS", "ObstacleResult",
    "ObstacleSetup", "PlanesObstacle", "WornDepth", "clearance_figure", "dilated_radius",
    "discret_angles",
    "load_obstacle_profile", "obstacle_from_config", "polar_polygon", "read_discret",
    "read_wear_table", "sector_volumes", "update_obstacle", "update_obstacle_from_table",
    "worn_depth_profiles", "write_discret",
]
