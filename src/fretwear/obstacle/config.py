"""The ``[obstacle]`` section of a case file (``fretwear obstacle CASE.toml``, the case runner).

Keys carry their unit in their name, like the rest of the case file; every key is listed in
:data:`OBSTACLE_KEYS`. Unknown keys are errors naming them. Defaults come from ``[geometry]``
(``mobile_radius_m``, ``obstacle_width_m``, ``obstacle_radius_m`` for a bore). Example::

    [obstacle]
    type = "circle"              # circle | planes | discrete
    gap_m = 0.5e-3               # or bore_radius_m
    wall_thickness_m = 1.09e-3
    perforation = 0.4            # PERCEMENT
    shape = "smooth"             # uniform | smooth
    instant = 10                 # default: the table's last
    output = "build/obstacle_profile.csv"
    discret = "build/obstacle_discret.txt"
    plot = "build"
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fretwear.errors import KeywordError, UnusedKeywordWarning
from fretwear.keys import check_keys, keyword_hint
from fretwear.obstacle.clearance import RESOLUTION
from fretwear.obstacle.depth import DEPTH_SHAPES
from fretwear.obstacle.discret_file import read_discret
from fretwear.obstacle.profiles import (
    DISCRET_STEP,
    OBSTACLE_MODELS,
    CircleObstacle,
    Mobile,
    PlanesObstacle,
)
from fretwear.obstacle.update import ObstacleResult, update_obstacle_from_table

_NUMBER = (int, float)
#: key -> (type, description with unit) of the ``[obstacle]`` section.
OBSTACLE_KEYS: dict[str, tuple[type | tuple[type, ...], str]] = {
    "type": (str, "obstacle model: circle, planes or discrete (default circle)"),
    "gap_m": (_NUMBER, "circle: radial gap around the new mobile [m]"),
    "bore_radius_m": (_NUMBER, "circle: bore radius [m] (default [geometry] obstacle_radius_m)"),
    "plane_gap_m": (_NUMBER, "planes: gap to the plane facing orientation_deg [m]"),
    "plane_gap_opposite_m": (_NUMBER, "planes: gap to the opposite plane [m] (default "
                                      "plane_gap_m)"),
    "orientation_deg": (_NUMBER, "planes: angle of the first plane's outward normal [deg]"),
    "closing_radius_m": (_NUMBER, "planes: radius of the far circle closing the figure [m]"),
    "file": (str, "discrete: DISCRET table of the NEW obstacle (THETA [deg], JEU [m])"),
    "mobile_radius_m": (_NUMBER, "mobile outer radius [m] (default [geometry] mobile_radius_m)"),
    "wall_thickness_m": (_NUMBER, "mobile wall thickness [m] (required, default [geometry] "
                                  "wall_thickness_m)"),
    "width_m": (_NUMBER, "obstacle width l [m] (default [geometry] obstacle_width_m)"),
    "perforation": (_NUMBER, "PERCEMENT: perforation at depth > this fraction of the wall "
                             "thickness [-], default 1.0"),
    "shape": (str, "depth shape in a sector: uniform or smooth (default uniform)"),
    "instant": (_NUMBER, "instant of the wear table to use [user unit] (default its last)"),
    "table": (str, "wear table to read instead of running the case (CSV or Code_Aster text)"),
    "step_deg": (_NUMBER, "angular step of the output grid [deg] (default 0.5: 721 points)"),
    "resolution_deg": (_NUMBER, "angular step of the exact clearance search [deg] "
                                "(default 0.05)"),
    "output": (str, "profile table to write (.csv, or Code_Aster TABLEAU otherwise)"),
    "discret": (str, "DISCRET obstacle file of the worn clearance figure to write"),
    "plot": (str, "directory for the polar plot (obstacle_polar.png and .svg)"),
}


#: The keys that belong to one obstacle type (a key of another type is ignored, with a warning).
MODEL_KEYS: dict[str, tuple[str, ...]] = {
    "circle": ("gap_m", "bore_radius_m"),
    "planes": ("plane_gap_m", "plane_gap_opposite_m", "orientation_deg", "closing_radius_m"),
    "discrete": ("file",),
}


@dataclass(frozen=True)
class ObstacleSetup:
    """A validated ``[obstacle]`` section: what to update and where to write it.

    Call :meth:`update` with the wear table (DataFrame or file).
    """

    obstacle: Any
    mobile: Mobile
    width: float | None
    shape: str = "uniform"
    perforation: float = 1.0
    instant: float | None = None
    step: float = DISCRET_STEP
    resolution: float = RESOLUTION
    table: Path | None = None
    output: Path | None = None
    discret: Path | None = None
    plot: Path | None = None

    def update(self, table=None) -> ObstacleResult:
        """Run the obstacle update on ``table`` (default the section's ``table`` file)."""
        source = self.table if table is None else table
        if source is None:
            raise KeywordError("[obstacle]: no wear table: give table = \"...\" or run the case")
        return update_obstacle_from_table(
            source, self.obstacle, self.mobile, instant=self.instant, width=self.width,
            shape=self.shape, perforation=self.perforation, step=self.step,
            resolution=self.resolution)


#: How a command names each key it gives (``fretwear obstacle``'s options), for messages.
OPTION_NAMES = {"gap_m": "--gap", "bore_radius_m": "--bore-radius", "plane_gap_m": "--plane-gap",
                "plane_gap_opposite_m": "--plane-gap-opposite",
                "orientation_deg": "--orientation", "closing_radius_m": "--closing-radius",
                "file": "--obstacle-table", "mobile_radius_m": "--mobile-radius",
                "wall_thickness_m": "--wall-thickness"}


def section_with_options(section: Mapping[str, Any] | None, options: Mapping[str, Any], *,
                         table: str | None = None,
                         names: Mapping[str, str] = OPTION_NAMES) -> dict[str, Any]:
    """An ``[obstacle]`` section (None: none, the options alone) with given values in front.

    Parameters
    ----------
    section : mapping or None
        The case file's ``[obstacle]`` section (not modified).
    options : mapping
        Section keys (:data:`OBSTACLE_KEYS`) -> values, None where not given. One obstacle at
        most (``gap_m``, ``bore_radius_m``, ``plane_gap_m`` or ``file``): it replaces the
        section's (its type and every key of its :data:`MODEL_KEYS`); ``plane_gap_m`` makes it
        two planes (``plane_gap_opposite_m``, ``orientation_deg``, ``closing_radius_m`` go
        with it only), ``file`` a DISCRET table.
    table : str, optional
        The wear table's path (the section's ``table``).
    names : mapping
        How the caller names each key, for the messages (default the command's options).

    Returns
    -------
    dict
        The merged section for :func:`obstacle_from_config`.

    Raises
    ------
    KeywordError
        Two obstacles, plane keys without ``plane_gap_m``, and, without a section, a missing
        ``mobile_radius_m``, ``wall_thickness_m`` or obstacle.
    """
    merged = dict(section or {})
    obstacles = ("gap_m", "bore_radius_m", "plane_gap_m", "file")
    planes = ("plane_gap_opposite_m", "orientation_deg", "closing_radius_m")
    given = {k: options[k] for k in obstacles if options.get(k) is not None}
    merged.update({k: v for k, v in options.items()
                   if v is not None and k not in obstacles and k not in planes})
    if len(given) > 1:
        raise KeywordError(f"give one obstacle: {', '.join(names.get(k, k) for k in obstacles)}")
    stray = [names.get(k, k) for k in planes if options.get(k) is not None]
    if "plane_gap_m" not in given and stray:
        raise KeywordError(f"{', '.join(stray)} describe two planes: give "
                           f"{names.get('plane_gap_m', 'plane_gap_m')} too (or put the planes "
                           "in the case's [obstacle] section)")
    if given:
        for key in ("type", *(k for keys in MODEL_KEYS.values() for k in keys)):
            merged.pop(key, None)  # the given obstacle replaces the section's
        merged.update(given)
        if "plane_gap_m" in given:
            merged["type"] = "planes"
            merged.update({k: options[k] for k in planes if options.get(k) is not None})
        elif "file" in given:
            merged["type"] = "discrete"
    if table is not None:
        merged["table"] = table
    if section is None:
        missing = [names.get(k, k) for k in ("mobile_radius_m", "wall_thickness_m")
                   if k not in merged]
        if not given:
            missing.append(f"an obstacle ({', '.join(names.get(k, k) for k in obstacles)})")
        if missing:
            raise KeywordError(f"with a wear table alone, give {', '.join(missing)}")
    return merged


def _need(section: Mapping, key: str, fallback=None, hint: str = ""):
    if key in section:
        return section[key]
    if fallback is not None:
        return fallback
    raise KeywordError(f"[obstacle] needs {key} ({OBSTACLE_KEYS[key][1]}){hint}")


def obstacle_from_config(config: Mapping[str, Any], *, geometry: Mapping | None = None,
                         directory=None) -> ObstacleSetup:
    """Build an :class:`ObstacleSetup` from the ``[obstacle]`` section of a case file.

    Parameters
    ----------
    config : mapping
        The ``[obstacle]`` section, or a whole case (with keys ``obstacle`` and ``geometry``,
        and ``_directory`` as :func:`fretwear.workflows.case_files.load_case` returns it).
    geometry : mapping, optional
        The ``[geometry]`` section for defaults (mobile_radius_m, obstacle_width_m,
        obstacle_radius_m).
    directory : path-like, optional
        Folder relative paths are resolved against (default the case's ``_directory`` or '.').

    Returns
    -------
    ObstacleSetup

    Raises
    ------
    KeywordError
        An unknown key (with the closest valid one), a missing one, a wrong type.

    Warns
    -----
    UnusedKeywordWarning
        A key of another obstacle type (e.g. ``gap_m`` with ``type = "planes"``).

    Examples
    --------
    >>> s = obstacle_from_config({"obstacle": {"gap_m": 5e-4, "wall_thickness_m": 1e-3},
    ...                           "geometry": {"mobile_radius_m": 9.5e-3,
    ...                                        "obstacle_width_m": 0.02}})
    >>> type(s.obstacle).__name__, round(s.obstacle.bore_radius, 9), s.width
    ('CircleObstacle', 0.01, 0.02)
    """
    if "obstacle" in config and isinstance(config["obstacle"], Mapping):
        geometry = geometry if geometry is not None else config.get("geometry", {})
        directory = directory if directory is not None else config.get("_directory")
        config = config["obstacle"]
    geometry = geometry or {}
    base = Path(directory) if directory is not None else Path(".")
    check_keys(config, OBSTACLE_KEYS, "[obstacle]")

    def path(key):
        if key not in config:
            return None
        p = Path(config[key])
        return p if p.is_absolute() else base / p

    rm = float(_need(config, "mobile_radius_m", geometry.get("mobile_radius_m"),
                     " or [geometry] mobile_radius_m"))
    mobile = Mobile(rm, float(_need(config, "wall_thickness_m",
                                    geometry.get("wall_thickness_m"),
                                    " or [geometry] wall_thickness_m")))
    model = config.get("type", "circle")
    if model not in OBSTACLE_MODELS:
        raise KeywordError(f"[obstacle] type = {model!r} is unknown"
                           f"{keyword_hint(model, OBSTACLE_MODELS)}; choose one of "
                           f"{', '.join(OBSTACLE_MODELS)}")
    unused = [k for kind, keys in MODEL_KEYS.items() if kind != model for k in keys
              if k in config]
    if unused:
        warnings.warn(f"[obstacle] type = {model!r} does not use {', '.join(unused)} (keys of "
                      f"another obstacle type): ignored", UnusedKeywordWarning, stacklevel=2)
    if model == "circle":
        if "gap_m" in config and "bore_radius_m" in config:
            raise KeywordError("[obstacle]: give gap_m or bore_radius_m, not both")
        if "gap_m" in config:
            obstacle = CircleObstacle.from_gap(rm, config["gap_m"])
        else:
            obstacle = CircleObstacle(rm, _need(config, "bore_radius_m",
                                                geometry.get("obstacle_radius_m"),
                                                " or gap_m, or [geometry] obstacle_radius_m"))
    elif model == "planes":
        obstacle = PlanesObstacle(rm, _need(config, "plane_gap_m"),
                                  config.get("plane_gap_opposite_m"),
                                  config.get("orientation_deg", 0.0),
                                  config.get("closing_radius_m"))
    else:
        obstacle = read_discret(path("file") or _need(config, "file"), mobile_radius=rm)
    shape = config.get("shape", "uniform")
    if shape not in DEPTH_SHAPES:
        raise KeywordError(f"[obstacle] shape = {shape!r}; choose one of {', '.join(DEPTH_SHAPES)}")
    width = config.get("width_m", geometry.get("obstacle_width_m"))
    return ObstacleSetup(
        obstacle=obstacle, mobile=mobile, width=None if width is None else float(width),
        shape=shape, perforation=float(config.get("perforation", 1.0)),
        instant=config.get("instant"), step=float(config.get("step_deg", DISCRET_STEP)),
        resolution=float(config.get("resolution_deg", RESOLUTION)), table=path("table"),
        output=path("output"), discret=path("discret"), plot=path("plot"))
