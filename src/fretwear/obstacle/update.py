"""Obstacle update (MODI_OBSTACLE): worn depth profiles and the new clearance figure (theory §8).

Always start from the NEW geometry (the obstacle model and the mobile radius of the first
dynamic computation) with the CUMULATED sector volumes of the wear table: the table continues
through restarts (ETAT_INIT), so recomputing from the new state never counts wear twice. The
worn clearance figure (``clearance_worn``) is what the next dynamic computation reads.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FretwearWarning, InputError, PerforationWarning
from fretwear.io.aster import TABLE_FORMATS
from fretwear.obstacle.clearance import (
    RESOLUTION,
    clearance_figure,
    polar_polygon,
    resolution_steps,
)
from fretwear.obstacle.depth import DEPTH_SHAPES, WornDepth, sector_of, worn_depth_profiles
from fretwear.obstacle.discret_file import write_discret
from fretwear.obstacle.profiles import (
    DISCRET_STEP,
    DiscreteObstacle,
    Mobile,
    discret_angles,
)
from fretwear.sectors import sector_edges
from fretwear.table import carried_case, read_wear_table
from fretwear.table.files import write_profile_table
from fretwear.table.schema import COLUMNS, PROFILE_COLUMNS

#: Native column -> Code_Aster column of the wear table columns read here (the table schema's).
WEAR_COLUMNS: dict[str, str] = {
    name: COLUMNS[name][0] for name in ("instant", "sector", "angle_start", "angle_end",
                                        "volume_mobile_cumulated", "volume_obstacle_cumulated")}
#: Formats of the profile table: CSV, or a Code_Aster table (IMPR_TABLE's FORMAT).
PROFILE_FORMATS: tuple[str, ...] = ("csv", *TABLE_FORMATS)


def _column(frame: pd.DataFrame, native: str, required: bool = True):
    names = {str(c).lower(): c for c in frame.columns}
    for key in (native, WEAR_COLUMNS[native]):
        if key.lower() in names:
            return frame[names[key.lower()]]
    if required:
        raise InputError(
            f"the wear table has no column {native!r} (Code_Aster {WEAR_COLUMNS[native]!r}); "
            f"columns: {list(frame.columns)}. The obstacle update needs a sector-mode wear table "
            "(run the wear operator with sectors, e.g. [sectors] count = 10)")
    return None


def _numbers(frame: pd.DataFrame, native: str, required: bool = True) -> np.ndarray | None:
    """A column of the wear table as floats [its unit], empty cells NaN; a cell that is not a
    number (text in a table written by hand or by another tool) is an InputError naming the
    column, the row and the value."""
    column = _column(frame, native, required)
    if column is None:
        return None
    values = pd.to_numeric(column, errors="coerce").to_numpy(dtype=float)
    text = column.notna().to_numpy() & np.isnan(values)
    if text.any():
        k = int(np.flatnonzero(text)[0])
        raise InputError(
            f"the wear table's column {column.name!r}, row {k + 1}: {column.iloc[k]!r} is not a "
            "number; give the number (or leave the cell empty)")
    return values


def sector_volumes(table: pd.DataFrame, instant: float | None = None):
    """Sector edges and cumulated sector volumes at one instant of a wear table.

    Parameters
    ----------
    table : pandas.DataFrame
        Sector-mode wear table, native (``instant``, ``sector``, ``angle_start``, ``angle_end``,
        ``volume_mobile_cumulated``, ``volume_obstacle_cumulated``) or Code_Aster names (INST,
        SECTEUR, ANGLE_DEBUT, ANGLE_FIN, V_USUR_TUBE_CUMU, V_USUR_OBST_CUMU). The obstacle
        column may be absent or empty at that instant (no obstacle wear: zero volumes). Rows
        with neither angle (global rows of a mixed table) are skipped.
    instant : float, optional
        Instant [user time unit] to read (default the last one).

    Returns
    -------
    (instant, edges [deg], volume_mobile [m³], volume_obstacle [m³])

    Raises
    ------
    InputError
        A missing column, an instant not in the table (the message lists them), sectors that do
        not cover −180…180° contiguously (naming the sector), a negative or missing volume.

    Examples
    --------
    >>> t = pd.DataFrame({"INST": [1.0, 1.0], "SECTEUR": [1, 2], "ANGLE_DEBUT": [-180.0, 0.0],
    ...                   "ANGLE_FIN": [0.0, 180.0], "V_USUR_TUBE_CUMU": [1e-9, 2e-9]})
    >>> inst, e, vm, vo = sector_volumes(t)
    >>> inst, e.tolist(), vm.tolist(), vo.tolist()
    (1.0, [-180.0, 0.0, 180.0], [1e-09, 2e-09], [0.0, 0.0])
    """
    inst = _numbers(table, "instant")
    start = _numbers(table, "angle_start")
    end = _numbers(table, "angle_end")
    vm_all = _numbers(table, "volume_mobile_cumulated")
    vo_all = _numbers(table, "volume_obstacle_cumulated", required=False)
    vo_all = np.zeros(len(table)) if vo_all is None else vo_all
    sec_col = _column(table, "sector", required=False)
    if sec_col is not None:
        sec_col = pd.Series(_numbers(table, "sector"))
    available = np.unique(inst[np.isfinite(inst)])
    if available.size == 0:
        raise InputError("the wear table has no instant (empty table or INST all missing)")
    if instant is None:
        chosen = float(available[-1])
    else:
        t = float(instant)
        hit = np.isclose(available, t, rtol=1e-9, atol=1e-12 * max(1.0, abs(t)))
        if not hit.any():
            shown = ", ".join(f"{a:g}" for a in available[:20])
            raise InputError(
                f"instant {t:g} is not in the wear table; its instants (INST) are: {shown}"
                f"{' ...' if available.size > 20 else ''}; pick one of them")
        chosen = float(available[np.flatnonzero(hit)[0]])
    rows = np.flatnonzero(np.isclose(inst, chosen, rtol=1e-9, atol=1e-12 * max(1.0, abs(chosen))))
    sector_rows = rows[np.isfinite(start[rows]) | np.isfinite(end[rows])]
    if sector_rows.size:  # rows without any angle are global rows of a mixed table: skip them
        rows = sector_rows
    order = rows[np.argsort(start[rows], kind="stable")]
    s, e = start[order], end[order]
    label = (lambda k: f"sector {sec_col.iloc[order[k]]:g}") if sec_col is not None else (
        lambda k: f"row {int(order[k])}")
    if not (np.isfinite(s).all() and np.isfinite(e).all()):
        k = int(np.flatnonzero(~(np.isfinite(s) & np.isfinite(e)))[0])
        raise InputError(f"wear table at instant {chosen:g}: {label(k)} has no angle_start/"
                         "angle_end (ANGLE_DEBUT/ANGLE_FIN); the obstacle update needs sectors")
    if abs(s[0] + 180.0) > 1e-6 or abs(e[-1] - 180.0) > 1e-6:
        raise InputError(
            f"wear table at instant {chosen:g}: the sectors must cover -180..180 deg, they run "
            f"from {s[0]:g} to {e[-1]:g} deg; give the table of every sector")
    for k in range(order.size - 1):
        if abs(e[k] - s[k + 1]) > 1e-6:
            raise InputError(
                f"wear table at instant {chosen:g}: sectors not covering -180..180 contiguously: "
                f"{label(k)} ends at {e[k]:g} deg but the next ({label(k + 1)}) starts at "
                f"{s[k + 1]:g} deg (duplicated or missing sector rows?)")
    edges = sector_edges(np.append(s, e[-1]))
    vm, vo = vm_all[order], vo_all[order]
    if np.isnan(vo).all():  # an empty obstacle column ('-' cells): the obstacle does not wear
        vo = np.zeros_like(vo)
    for name, v in (("volume_mobile_cumulated (V_USUR_TUBE_CUMU)", vm),
                    ("volume_obstacle_cumulated (V_USUR_OBST_CUMU)", vo)):
        bad = ~np.isfinite(v) | (v < 0)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise InputError(f"wear table at instant {chosen:g}: {label(k)} has {name} = "
                             f"{v[k]!r}; cumulated volumes must be finite and >= 0 [m³]")
    return chosen, edges, vm, vo


def _case_dimension(table: pd.DataFrame, name: str) -> float | None:
    """A dimension [m] of the wear case the table carries (:func:`fretwear.table.carried_case`:
    wear_table's, or a file's fretwear wrote), None without a case or that dimension."""
    case = carried_case(table)
    value = None if case is None else case.dimensions.get(name)
    return None if value is None else float(value)


@dataclass(frozen=True)
class ObstacleResult:
    """Result of an obstacle update.

    Attributes
    ----------
    angle : numpy.ndarray
        Directions [deg] of the output grid (0…360 by the step; 721 points by default).
    clearance_initial, clearance_worn : numpy.ndarray
        Clearance of the new / worn mobile in the new / worn obstacle along each direction [m].
    depth_mobile, depth_obstacle : numpy.ndarray
        Worn radial depths at each angle [m].
    depth : WornDepth
        The depth profiles (callable at any angle).
    instant : float or None
        Instant of the wear table read [user time unit].
    perforated_sectors : tuple of int
        1-based sectors where the mobile depth exceeds PERCEMENT × wall thickness.
    """

    angle: np.ndarray
    clearance_initial: np.ndarray
    clearance_worn: np.ndarray
    depth_mobile: np.ndarray
    depth_obstacle: np.ndarray
    depth: WornDepth
    mobile: Mobile
    obstacle: object
    perforation: float
    instant: float | None = None
    perforated_sectors: tuple = ()
    metadata: dict = field(default_factory=dict)

    @property
    def perforated(self) -> bool:
        """True when the mobile is perforated somewhere."""
        return bool(self.perforated_sectors)

    def to_frame(self) -> pd.DataFrame:
        """The profile table (native names, SI; units in ``attrs['units']``)."""
        frame = pd.DataFrame({"angle": self.angle, "clearance_initial": self.clearance_initial,
                              "clearance_worn": self.clearance_worn,
                              "depth_mobile": self.depth_mobile,
                              "depth_obstacle": self.depth_obstacle})
        frame.attrs = {"units": {k: u for k, (_, u, _) in PROFILE_COLUMNS.items()},
                       "instant": self.instant, "perforated_sectors": list(self.perforated_sectors),
                       **self.metadata}
        return frame

    def sector_frame(self) -> pd.DataFrame:
        """One row per sector: edges [deg], cumulated volumes [m³], depths [m]."""
        d = self.depth
        return pd.DataFrame({
            "sector": np.arange(1, d.edges.size), "angle_start": d.edges[:-1],
            "angle_end": d.edges[1:], "volume_mobile_cumulated": d.volume_mobile,
            "volume_obstacle_cumulated": d.volume_obstacle,
            "depth_mobile_sector": d.sector_depth_mobile,
            "depth_obstacle_sector": d.sector_depth_obstacle,
            "perforated": [j + 1 in self.perforated_sectors for j in range(d.edges.size - 1)]})

    def clearance_profile(self) -> DiscreteObstacle:
        """The worn clearance figure as a discrete obstacle (for the next dynamic computation)."""
        return DiscreteObstacle(self.angle, self.clearance_worn, self.mobile.outer_radius,
                                clearance_figure=True)

    def write(self, path, format: str | None = None) -> Path:
        """Write the profile table: CSV (``.csv``), Parquet (``.parquet``) or Code_Aster
        ``TABLEAU``/``ASTER`` text, by :func:`fretwear.table.files.write_profile_table` (the
        table layer's schema :data:`~fretwear.table.schema.PROFILE_COLUMNS`, exact reals and
        the provenance header).

        ``format`` is ``"csv"``, ``"TABLEAU"`` or ``"ASTER"`` (default from the suffix: .csv ->
        CSV, .parquet -> Parquet, else TABLEAU). The Code_Aster table uses THETA, JEU_INIT,
        JEU_USE, P_USUR_TUBE, P_USUR_OBST.
        """
        if format is not None and str(format).upper() not in {f.upper() for f in PROFILE_FORMATS}:
            raise InputError(f"unknown profile table format {format!r}; use "
                             f"{', '.join(PROFILE_FORMATS)}")
        title = "fretwear obstacle update (MODI_OBSTACLE)" + (
            f" at INST = {self.instant:g}" if self.instant is not None else "")
        return write_profile_table(self.to_frame(), path, format=format, title=title,
                                   instant=self.instant)

    def write_discret(self, path) -> Path:
        """Write the worn clearance figure as a DISCRET file (read by ``load_obstacle_profile``).

        Raises
        ------
        InputError
            When the worn clearance is undefined (NaN: a mobile depth past its centre).
        """
        bad = ~np.isfinite(self.clearance_worn)
        if bad.any():
            raise InputError(
                f"no DISCRET obstacle written to {str(path)!r}: the worn clearance is undefined "
                f"(NaN) in {int(bad.sum())} of {bad.size} directions because a mobile depth is "
                f"beyond its centre (perforated sectors {list(self.perforated_sectors)}); use an "
                "earlier instant")
        step = float(self.angle[1] - self.angle[0])
        title = "fretwear worn obstacle (MODI_OBSTACLE)" + (
            f" at INST = {self.instant:g}" if self.instant is not None else "")
        return write_discret(path, self.clearance_profile(), step=step,
                             gaps=self.clearance_worn, title=title)


def _check_perforation(depth: WornDepth, mobile: Mobile, fraction: float) -> tuple:
    limit = fraction * mobile.wall_thickness
    e = depth.edges
    fine = np.linspace(-180.0, 180.0, 7201)
    idx = sector_of(fine, e)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        prof = depth.mobile(fine)
    hits = []
    for j in range(e.size - 1):
        sel = idx == j
        d = prof[sel]
        if np.isnan(d).any() or (d > limit).any():
            k = int(np.argmax(np.where(np.isnan(d), np.inf, d)))
            at = float(fine[sel][k]) if depth.shape == "smooth" else 0.5 * (e[j] + e[j + 1])
            dj = float(d[k])
            hits.append(j + 1)
            what = ("beyond the mobile's centre (volume larger than the wedge)"
                    if math.isnan(dj) else f"{dj:.4g} m")
            warnings.warn(
                f"mobile perforated in sector {j + 1} ({e[j]:g}..{e[j + 1]:g} deg): worn depth "
                f"{what} at angle {at:g} deg exceeds PERCEMENT {fraction:g} × wall thickness "
                f"{mobile.wall_thickness:g} m = {limit:.4g} m", PerforationWarning, stacklevel=3)
    return tuple(hits)


def _check_figure(figure, angle, initial) -> None:
    """Warn when a clearance-figure table is not the figure its mobile can have.

    The obstacle behind a figure C is C ⊕ D(R_m); the new mobile's clearance in it is the
    closing of C by the disk, which is C itself for any real figure (an erosion by the disk)
    but fills dents narrower than the mobile in a made-up one.
    """
    table = figure.gap(angle)
    diff = np.abs(initial - table)
    tol = 1e-3 * float(np.max(table)) + 1e-9
    if np.nanmax(diff) > tol:
        k = int(np.nanargmax(diff))
        warnings.warn(
            f"the clearance figure table is not the figure of a mobile of radius "
            f"{figure.mobile_radius:g} m: at {angle[k]:g} deg it gives {table[k]:.4g} m but the "
            f"mobile's clearance in the obstacle behind it is {initial[k]:.4g} m (dents narrower "
            "than the mobile are filled); the update uses the latter (clearance_initial). If "
            "the table holds radial gaps of the obstacle, give it as RADIUS = R_m + gap",
            FretwearWarning, stacklevel=3)


def update_obstacle(obstacle, mobile: Mobile, edges, volume_mobile, volume_obstacle=None, *,
                    width: float, shape: str = "uniform", perforation: float = 1.0,
                    step: float = DISCRET_STEP, resolution: float = RESOLUTION,
                    instant: float | None = None) -> ObstacleResult:
    """Worn depth profiles and the worn clearance figure from cumulated sector volumes.

    Parameters
    ----------
    obstacle : obstacle model
        The NEW obstacle (:class:`CircleObstacle`, :class:`PlanesObstacle`,
        :class:`DiscreteObstacle`); its ``mobile_radius`` must be the mobile's [m].
    mobile : Mobile
        Outer radius and wall thickness [m].
    edges : int or array_like
        Sector edges [deg] (−180…180) or a number of equal sectors.
    volume_mobile, volume_obstacle : array_like
        Cumulated worn volume of each sector [m³] (obstacle default 0).
    width : float
        Obstacle width l [m] (worn height, LARGEUR_OBST).
    shape : {"uniform", "smooth"}
        Depth shape within a sector (:data:`fretwear.obstacle.depth.DEPTH_SHAPES`).
    perforation : float
        PERCEMENT: the mobile is perforated where its depth exceeds this fraction of the wall
        thickness [-] (e.g. 1.0, or 0.4 for a plugging criterion).
    step : float
        Angular step [deg] of the output grid (0.5: Code_Aster's 721 points).
    resolution : float
        Angular step [deg] of the polygons of the exact clearance search.
    instant : float, optional
        Instant the volumes belong to (metadata).

    Returns
    -------
    ObstacleResult

    Warns
    -----
    PerforationWarning
        Naming the sector, the angle and the depth.

    Notes
    -----
    Worn mobile r_m(φ) = R_m − d_m(φ); worn obstacle r_O(φ) = r_o(φ) + d_o(φ); the clearance
    along φ is s*(φ) = sup{s : M + s·u(φ) ⊂ O}, computed exactly on the polygons
    (:mod:`fretwear.obstacle.clearance`). To first order, a sector worn by d_m and d_o opens
    the clearance at its centre by d_m + d_o.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §3 (sector depths) and §8 (obstacle update).
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §5 (sectors) and §6 (the
           MODI_OBSTACLE step this replaces).

    Examples
    --------
    Uniform wear all round: the clearance is (R_o + d_o) − (R_m − d_m) in every direction.

    >>> from fretwear.obstacle.profiles import CircleObstacle
    >>> r = update_obstacle(CircleObstacle(0.01, 0.0105), Mobile(0.01, 0.001), 1, [1e-7],
    ...                     [5e-8], width=0.02, resolution=0.5)
    >>> dm, do = float(r.depth_mobile[0]), float(r.depth_obstacle[0])
    >>> bool(np.allclose(r.clearance_worn, 0.0005 + dm + do, rtol=0, atol=1e-12))
    True
    """
    rm = mobile.outer_radius
    orm = getattr(obstacle, "mobile_radius", None)
    if orm is None or not math.isclose(orm, rm, rel_tol=1e-12):
        raise InputError(
            f"the obstacle was described around a mobile of radius {orm!r} m but the mobile's "
            f"outer_radius is {rm:g} m; build the obstacle with mobile_radius={rm:g}")
    try:
        frac = float(perforation)
    except (TypeError, ValueError):
        frac = math.nan
    if not math.isfinite(frac) or frac <= 0:
        raise InputError(f"perforation (PERCEMENT) must be a fraction > 0 of the wall thickness, "
                         f"got {perforation!r}")
    if shape not in DEPTH_SHAPES:
        raise InputError(f"unknown depth shape {shape!r}; choose one of {sorted(DEPTH_SHAPES)}")
    # the output grid and the polygon resolution are checked before the wear is: a wrong
    # option is an error before any PerforationWarning of an update that cannot finish
    angle = discret_angles(step)
    resolution_steps(resolution)
    depth = worn_depth_profiles(edges, volume_mobile, volume_obstacle, width=width,
                                mobile_radius=rm, obstacle=obstacle, shape=shape)
    perforated = _check_perforation(depth, mobile, frac)
    breaks = depth.edges[:-1] if shape == "uniform" else ()
    nodes = getattr(obstacle, "angles", ())

    def new_mobile(a, side):
        return np.full(np.shape(a), rm)

    def worn_mobile(a, side):
        return rm - depth.mobile(a, side)

    def new_obstacle(a, side):
        return obstacle.radius(a)

    def worn_obstacle(a, side):
        return obstacle.radius(a) + depth.obstacle(a, side)

    # the same vertex angles for the new and the worn polygons: zero wear gives the same figure
    cuts = np.concatenate([np.asarray(breaks, float), np.asarray(nodes, float)])
    turn = angle[:-1]  # 360° is 0°: copy it, so the figure is exactly periodic
    initial = clearance_figure(turn, polar_polygon(new_mobile, cuts, resolution),
                               polar_polygon(new_obstacle, cuts, resolution))
    worn = clearance_figure(turn, polar_polygon(worn_mobile, cuts, resolution),
                            polar_polygon(worn_obstacle, cuts, resolution))
    initial, worn = np.append(initial, initial[0]), np.append(worn, worn[0])
    if getattr(obstacle, "clearance_figure", False):
        _check_figure(obstacle, angle, initial)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        dm, do = depth.mobile(angle), depth.obstacle(angle)
    meta = {"shape": shape, "width": float(width), "mobile_radius": rm,
            "wall_thickness": mobile.wall_thickness, "perforation": frac,
            "sector_edges": depth.edges.tolist(), "obstacle": type(obstacle).__name__}
    return ObstacleResult(angle, initial, worn, dm, do, depth, mobile, obstacle, frac, instant,
                          perforated, meta)


def update_obstacle_from_table(table, obstacle, mobile: Mobile, *, instant: float | None = None,
                               width: float | None = None, **options) -> ObstacleResult:
    """Obstacle update from a wear table (DataFrame or file) at one instant.

    Parameters
    ----------
    table : pandas.DataFrame or path-like
        Sector-mode wear table (:func:`sector_volumes` for the columns); a file is read by
        :func:`fretwear.table.read_wear_table` (CSV, Parquet or Code_Aster text).
    obstacle, mobile
        As in :func:`update_obstacle`.
    instant : float, optional
        Instant to read [user time unit] (default the last).
    width : float, optional
        Obstacle width [m]; default the ``obstacle_width`` of the wear case the table carries
        (:func:`fretwear.table.carried_case`).
    **options
        ``shape``, ``perforation``, ``step``, ``resolution`` of :func:`update_obstacle`.

    Returns
    -------
    ObstacleResult

    Examples
    --------
    Two sectors, the mobile worn on the +y side only (Code_Aster names):

    >>> from fretwear.obstacle.profiles import CircleObstacle
    >>> t = pd.DataFrame({"INST": [5.0, 5.0], "SECTEUR": [1, 2], "ANGLE_DEBUT": [-180.0, 0.0],
    ...                   "ANGLE_FIN": [0.0, 180.0], "V_USUR_TUBE_CUMU": [0.0, 1e-9]})
    >>> r = update_obstacle_from_table(t, CircleObstacle(0.0095, 0.01), Mobile(0.0095, 1e-3),
    ...                                width=0.02, resolution=0.5)
    >>> r.instant, round(float(r.clearance_worn[180]) * 1e3, 6)   # at 90 deg [mm]
    (5.0, 0.501675)
    """
    frame = table if isinstance(table, pd.DataFrame) else read_wear_table(table)  # native names
    inst, edges, vm, vo = sector_volumes(frame, instant)
    if width is None:
        width = _case_dimension(frame, "obstacle_width")
        if width is None:
            raise InputError("the obstacle width is needed: width= [m] (CLI --width, case "
                             "[obstacle] width_m or [geometry] obstacle_width_m); the wear "
                             "table does not carry it")
    return update_obstacle(obstacle, mobile, edges, vm, vo, width=width, instant=inst, **options)
