"""``fretwear obstacle``: update the obstacle's clearance profile from a wear table."""

from __future__ import annotations

import warnings
from pathlib import Path

import click
import numpy as np

from fretwear._optional import require
from fretwear.cli._units import parse_units, units_line, units_option, with_history_units
from fretwear.errors import FretwearWarning, KeywordError
from fretwear.io.atomic import check_outputs
from fretwear.obstacle import obstacle_from_config
from fretwear.obstacle.config import section_with_options
from fretwear.obstacle.depth import DEPTH_SHAPES
from fretwear.obstacle.update import PROFILE_FORMATS
from fretwear.plotting import plot_obstacle, save_figure
from fretwear.workflows.case_files import load_case, run_case
from fretwear.workflows.inputs import case_inputs

_HELP = """Update the obstacle's clearance figure from a wear table (MODI_OBSTACLE).

Either a case file CASE (its [obstacle] section; the wear table is its `table` key, --table,
or the case is run), or --table WEAR_TABLE with the geometry given as options. The cumulated
sector volumes at --instant (default the last) give the worn depth profiles of the mobile and
the obstacle; the worn clearance in each direction is the exact translation of the worn mobile
inside the worn obstacle. Writes the profile table (-o: .csv, or a Code_Aster TABLEAU), the
worn clearance figure as a DISCRET obstacle file (--write-discret) for the next dynamic
computation,
and a polar plot (--plot DIR). SI units (m, m³); angles in degrees.

\b
Examples:
  fretwear obstacle case.toml -o build/profile.csv --plot build
  fretwear obstacle --table wear.tab --mobile-radius 9.5e-3 --wall-thickness 1.09e-3 \\
      --gap 0.5e-3 --width 20e-3 --instant 10 -o profile.tab --write-discret worn_discret.txt
"""


def _renamed(new: str, does: str):
    """The callback of a retired option: refused with the new name (the old --discrete and
    --discret differed by one letter, and taking one for the other double-counts the wear)."""
    def refuse(ctx: click.Context, param: click.Parameter, value) -> None:
        if value is not None:
            raise click.UsageError(
                f"{param.opts[0]} was renamed {new} (it {does} a DISCRET obstacle table; the "
                "old names --discrete and --discret differed by one letter): use "
                f"{new} {value}")
    return refuse


def _summary(result, echo) -> None:
    d = result.depth
    when = "" if result.instant is None else f" at instant {result.instant:g}"
    echo(f"obstacle update{when}: {d.edges.size - 1} sectors, {d.shape} depth, "
         f"obstacle {type(result.obstacle).__name__}, R_m = {result.mobile.outer_radius:g} m")
    # the obstacle-profile depth, not the wear table's global or sector depth
    d_label = "profile d" if d.shape == "uniform" else "max profile d"
    echo(f"{'sector':>6} {'angles [deg]':>15} {'V tube [mm3]':>13} {'V obst [mm3]':>13} "
         f"{d_label + ' tube [mm]':>24} {d_label + ' obst [mm]':>24}")
    for j in range(d.edges.size - 1):
        flag = "  PERFORATED" if j + 1 in result.perforated_sectors else ""
        echo(f"{j + 1:>6} {f'{d.edges[j]:g}..{d.edges[j + 1]:g}':>15} "
             f"{d.volume_mobile[j] * 1e9:>13.4g} {d.volume_obstacle[j] * 1e9:>13.4g} "
             f"{d.sector_depth_mobile[j] * 1e3:>24.4g} {d.sector_depth_obstacle[j] * 1e3:>24.4g}"
             f"{flag}")
    opening = result.clearance_worn - result.clearance_initial
    if np.isfinite(opening).any():
        k = int(np.nanargmax(opening))
        echo(f"clearance: new {np.nanmin(result.clearance_initial) * 1e3:.4g}.."
             f"{np.nanmax(result.clearance_initial) * 1e3:.4g} mm, worn "
             f"{np.nanmin(result.clearance_worn) * 1e3:.4g}.."
             f"{np.nanmax(result.clearance_worn) * 1e3:.4g} mm; largest opening "
             f"{opening[k] * 1e3:.4g} mm at {result.angle[k]:g} deg")
    else:
        echo("clearance: undefined (a worn depth is NaN: the mobile is worn through)")


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("case_file", required=False,
                type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--table", "table_path", type=click.Path(exists=True, dir_okay=False,
                                                        path_type=Path),
              help="Wear table (CSV or Code_Aster text), sector mode.")
@click.option("--instant", type=float, help="Instant of the wear table [user unit]; default last.")
@click.option("--mobile-radius", type=float, help="Mobile outer radius R_m [m].")
@click.option("--wall-thickness", type=float, help="Mobile wall thickness [m].")
@click.option("--width", type=float, help="Obstacle width l [m] (LARGEUR_OBST).")
@click.option("--gap", type=float, help="Circular bore: radial gap [m].")
@click.option("--bore-radius", type=float, help="Circular bore: radius [m].")
@click.option("--plane-gap", type=float, help="Two planes: gap to the plane facing "
                                             "--orientation [m].")
@click.option("--plane-gap-opposite", type=float, help="Two planes: gap to the opposite plane "
                                                      "[m].")
@click.option("--orientation", type=float,
              help="Two planes: angle of the first plane's normal [deg] (default 0).")
@click.option("--closing-radius", type=float,
              help="Two planes: radius of the far circle closing the figure [m] (default "
                   "100 × (R_m + gap)).")
@click.option("--obstacle-table", "discrete_file", type=click.Path(exists=True, dir_okay=False,
                                                                    path_type=Path),
              help="Input: the NEW obstacle as a DISCRET table (THETA [deg], JEU [m]).")
@click.option("--discrete", hidden=True, expose_value=False, is_eager=True,
              callback=_renamed("--obstacle-table", "reads"))
@click.option("--shape", type=click.Choice(list(DEPTH_SHAPES)),
              help="Depth shape within a sector (default uniform).")
@click.option("--perforation", type=float,
              help="PERCEMENT: perforation at depth > this × wall thickness (default 1.0).")
@click.option("--resolution", type=float, help="Angular step of the exact search [deg] "
                                              "(default 0.05).")
@click.option("--step", type=float, help="Angular step of the output grid [deg] (default 0.5: "
                                        "Code_Aster's 721 points).")
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help="Profile table: .csv, or a Code_Aster TABLEAU for any other suffix.")
@click.option("--format", "fmt", type=click.Choice(PROFILE_FORMATS, case_sensitive=False),
              help="Force the profile table format.")
@click.option("--write-discret", "discret_path", type=click.Path(dir_okay=False,
                                                                  path_type=Path),
              help="Output: write the worn clearance figure as a DISCRET obstacle file.")
@click.option("--discret", hidden=True, expose_value=False, is_eager=True,
              callback=_renamed("--write-discret", "writes"))
@units_option
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Write obstacle_polar.png and .svg into this directory.")
@click.option("-q", "--quiet", is_flag=True, help="No summary.")
def command(case_file, table_path, instant, mobile_radius, wall_thickness, width, gap,
            bore_radius, plane_gap, plane_gap_opposite, orientation, closing_radius,
            discrete_file, shape, perforation, resolution, step, output, fmt, discret_path,
            units, plot_dir, quiet) -> None:
    echo = (lambda *a, **k: None) if quiet else click.echo
    section = None
    geometry: dict = {}
    directory = None
    case = None
    if case_file is not None:
        case = with_history_units(load_case(case_file), parse_units(units))
        section = dict(case.get("obstacle", {}))
        geometry = dict(case.get("geometry", {}))
        directory = case.get("_directory")
        if not section:
            raise KeywordError(f"{case_file}: no [obstacle] section; add one (see "
                               "docs/obstacle.md) or use --table with options")
    elif table_path is None:
        raise click.UsageError("give a case file CASE.toml or --table WEAR_TABLE")
    elif units:
        raise click.UsageError("--units gives the units of the history a case file reads; "
                               "a --table wear table is in SI (volumes m³)")
    section = section_with_options(section, {
        "mobile_radius_m": mobile_radius, "wall_thickness_m": wall_thickness, "width_m": width,
        "shape": shape, "perforation": perforation, "instant": instant,
        "resolution_deg": resolution, "step_deg": step, "gap_m": gap,
        "bore_radius_m": bore_radius, "plane_gap_m": plane_gap,
        "plane_gap_opposite_m": plane_gap_opposite, "orientation_deg": orientation,
        "closing_radius_m": closing_radius,
        "file": None if discrete_file is None else str(discrete_file.resolve())},
        table=None if table_path is None else str(table_path.resolve()))
    setup = obstacle_from_config(section, geometry=geometry, directory=directory)
    inputs = case_inputs(case or {}, case_file)
    inputs.update({"wear table (--table)": table_path, "obstacle table": discrete_file,
                   "obstacle's wear table": setup.table})
    check_outputs({"-o": output if output is not None else setup.output,
                   "--write-discret": discret_path if discret_path is not None
                   else setup.discret}, inputs)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if setup.table is not None:
            result = setup.update()
        else:
            echo("running the case for its wear table ...", err=True)
            run = run_case(case)  # the case read above
            echo(units_line(run.units))
            result = setup.update(run.table)
    _summary(result, echo)
    for w in caught:
        if issubclass(w.category, FretwearWarning):
            click.echo(f"warning: {w.category.__name__}: {w.message}", err=True)
    output = output if output is not None else setup.output
    discret_path = discret_path if discret_path is not None else setup.discret
    plot_dir = plot_dir if plot_dir is not None else setup.plot
    if output is not None:
        echo(f"profile table written to {result.write(output, format=fmt)}")
    if plot_dir is not None:
        require("matplotlib.pyplot", purpose="the obstacle figure (--plot or [obstacle] plot)")
        files = save_figure(plot_obstacle(result), plot_dir, "obstacle_polar", close=True)
        echo(f"figures written to {plot_dir}: " + ", ".join(f.name for f in files))
    if discret_path is not None:
        echo(f"DISCRET obstacle written to {result.write_discret(discret_path)}")
