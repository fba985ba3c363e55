"""``fretwear run CASE.toml``: the service-life wear table of a case file."""

from __future__ import annotations

import warnings
from pathlib import Path

import click
import numpy as np
from rich.console import Console
from rich.progress import (
    BarColumn,
    Progress,
    SpinnerColumn,
    TaskProgressColumn,
    TextColumn,
    TimeElapsedColumn,
)
from rich.rule import Rule
from rich.table import Table

from fretwear._optional import require
from fretwear.cli._units import parse_units, units_line, units_option, with_history_units
from fretwear.errors import ConfidenceWarning
from fretwear.io.aster import TABLE_FORMATS
from fretwear.io.atomic import check_outputs
from fretwear.laws import WEAR_LAWS
from fretwear.plotting import save_figure, wear_figures
from fretwear.report import analyse_case, write_report
from fretwear.table import COLUMNS, DEFAULT_DEPTH_LIMIT, write_wear_table
from fretwear.table.files import ASTER_SUFFIXES
from fretwear.workflows.case_files import keys_help, load_case, run_case
from fretwear.workflows.inputs import RESTART_TABLE, case_inputs


def columns_help() -> str:
    """The output columns (native name, Code_Aster name, unit, meaning), as plain text."""
    placeholder = COLUMNS["instant"][1]  # the schema's word for the case's [time] unit
    return "\n".join(f"  {native} ({aster}) "
                     f"[{'time unit of [time] unit, e.g. year' if unit == placeholder else unit}]"
                     f": {meaning}" for native, (aster, unit, meaning) in COLUMNS.items())


_ASTER = "/".join(ASTER_SUFFIXES)
_HELP = f"""Run a TOML case file: wear power, wear law, depths, service-life table.

Writes the table to OUTPUT (.csv, .parquet, or {_ASTER} for a Code_Aster IMPR_TABLE
file that LIRE_TABLE reads) and prints a summary (power, block spread, sector powers, volumes
and depths at the last instant, warnings). Units: SI (m, m³, W, s; angles in degrees).

\b
Case-file keys (units in the names; docs/case_files.md):
{keys_help()}

\b
Output columns, native (Code_Aster) [unit]; one row per instant, or per instant and sector:
{columns_help()}
"""


def _summary(result, console) -> None:
    table, case = result.table, result.wear_case  # the case the table was computed from
    attrs = table.attrs  # the computation's outputs: coefficients resolved, through-wall
    title = case.name or "fretwear run"
    # a rule as wide as the terminal, or 100 columns in a file (its width is then unbounded)
    console.print(Rule(f"[bold]{title}"), width=console.width if console.is_terminal else 100)
    power = result.power
    unit = case.time_label
    console.print(f"contact [bold]{case.contact_type}[/], law [bold]{case.law}"
                  f"[/], time unit = {unit}")
    console.print(f"wear power P = [bold]{result.total_power:.6g} W[/]")
    console.print(units_line(getattr(result, "units", None)), markup=False, highlight=False)
    origin = case.origin
    if origin:
        previous = result.case.get("restart", {}).get("table", "the initial table")
        console.print(f"continues {previous} from instant {origin:g} (ORIG_INST)", markup=False,
                      highlight=False)
    if case.restart.tube_replacement is not None:
        console.print(f"tube replaced by a new one at instant "
                      f"{case.restart.tube_replacement:g} (TUBE_NEUF)")
    units = WEAR_LAWS[case.law].units
    for key, source in (attrs.get("coefficient_sources") or {}).items():
        body, _, name = key.partition(".")
        value = (attrs.get(f"coefficients_{body}") or {}).get(name)
        unit = units.get(name, "1")
        shown = " (the window's maximum)" if value is None else (
            f" = {float(value):.4g}" + ("" if unit == "1" else f" {unit}"))
        console.print(f"{body} {name}{shown}, source: {source}", markup=False, highlight=False)
    intensity = (attrs.get("coefficients_mobile") or {}).get("intensity")
    if intensity is not None:
        console.print(f"KWU-EPRI wear-intensity factor w = {float(intensity):.4g}")
    blocks = getattr(power, "blocks", None)
    notes: list[str] = []
    if blocks is not None and len(blocks) > 1:
        console.print(f"block powers [W]: {', '.join(f'{b:.4g}' for b in blocks)}; spread "
                      f"(max-min)/mean = {float(power.spread):.3g}")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ConfidenceWarning)
            interval = power.confidence_interval(0.95)
        notes = [f"{w.category.__name__}: {w.message}" for w in caught]
        console.print(f"{interval}  (batch means over {len(blocks)} blocks)", markup=False,
                      highlight=False)
    last = table[table["instant"] == table["instant"].iloc[-1]]
    if "sector" in table.columns and table["sector"].notna().any():
        st = Table(title=f"sectors at instant {last['instant'].iloc[0]:g} "
                         "(P in W, V in mm³, sector depths d in mm)")
        walled = "wall_fraction_sector" in table.columns
        for col in ("sector", "angles (deg)", "P", "V tube", "V obst", "d tube (sector)",
                    "d obst (sector)") + (("% wall", "limit at") if walled else ()):
            st.add_column(col, justify="right")
        for _, row in last.iterrows():
            extra = (f"{100 * row['wall_fraction_sector']:.3g}",
                     _instant(row["limit_instant_sector"])) if walled else ()
            st.add_row(f"{int(row['sector'])}", f"{row['angle_start']:g}..{row['angle_end']:g}",
                       f"{row['sector_power']:.4g}",
                       f"{row['volume_mobile_cumulated'] * 1e9:.4g}",
                       f"{row['volume_obstacle_cumulated'] * 1e9:.4g}",
                       f"{row['depth_mobile_sector'] * 1e3:.4g}",
                       f"{row['depth_obstacle_sector'] * 1e3:.4g}", *extra)
        console.print(st)
    row = last.iloc[0]
    console.print(
        f"at instant {row['instant']:g}: V tube = {row['volume_mobile'] * 1e9:.4g} mm³, "
        f"V obstacle = {row['volume_obstacle'] * 1e9:.4g} mm³, global depth of the tube = "
        f"{row['depth_mobile'] * 1e3:.4g} mm, global depth of the obstacle = "
        f"{row['depth_obstacle'] * 1e3:.4g} mm")
    glob = table.drop_duplicates("instant")
    walled = "wall_fraction" in table.columns
    gt = Table(title="service life (global depths, from the total volumes)")
    for col in ("instant", "V tube (mm³)", "depth tube (mm)", "V obst (mm³)",
                "depth obst (mm)") + (("% wall",) if walled else ()):
        gt.add_column(col, justify="right")

    def mm(depth: float) -> str:
        return "NaN (out of range)" if np.isnan(depth) else f"{depth * 1e3:.4g}"

    for _, r in glob.iterrows():
        extra = (_percent_of_wall(r["wall_fraction"]),) if walled else ()
        gt.add_row(f"{r['instant']:g}", f"{r['volume_mobile'] * 1e9:.4g}",
                   mm(r["depth_mobile"]), f"{r['volume_obstacle'] * 1e9:.4g}",
                   mm(r["depth_obstacle"]), *extra)
    console.print(gt)
    for line, style in _limit_lines(table, case):
        console.print(line, markup=False, highlight=False, style=style)
    if result.warnings or notes:
        console.print("[yellow]warnings:[/]")
        for w in [*result.warnings, *notes]:
            console.print(f"  - {w}", markup=False, highlight=False, style="yellow")


def _instant(value: float) -> str:
    """An instant [user unit] for the summary: ``never`` for inf."""
    return "never" if np.isinf(value) else "-" if np.isnan(value) else f"{value:.4g}"


def _percent_of_wall(fraction: float) -> str:
    if np.isnan(fraction):
        return "-"
    return f"{100 * fraction:.3g}" + (" THROUGH" if fraction > 1 else "")


def _limit_lines(table, case) -> list[tuple[str, str | None]]:
    """Lines on the wall and the limit of ``case``, through the wall first (bad news first; empty
    without a wall thickness)."""
    wall = case.wall.thickness
    if wall is None or "limit_instant" not in table.columns:
        return []
    unit = case.time_label
    fraction, limit = case.wall.limit, case.wall.limit_depth
    out = [(f"limit: {100 * fraction:g} % of the {wall * 1e3:.4g} mm wall "
            f"= {limit * 1e3:.4g} mm; the global depth reaches it at instant "
            f"{_instant(table['limit_instant'].iloc[-1])} [{unit}]", "bold")]
    if "limit_instant_sector" in table.columns:
        last = table[table["instant"] == table["instant"].iloc[-1]]
        first = last.loc[last["limit_instant_sector"].idxmin()]
        out.append((f"by the sector depths (each sector's own volume spread over its arc, "
                    f"theory §3, not the contact type's global depth): the first sector to "
                    f"reach it is sector {int(first['sector'])}, at instant "
                    f"{_instant(first['limit_instant_sector'])} [{unit}]", "bold"))
    for where, instant in reversed(list((table.attrs.get("through_wall") or {}).items())):
        depth = "global depth" if where == "global" else f"{where} depth"
        out.insert(0, (f"THROUGH THE WALL: the tube's {depth} passes the {wall * 1e3:.4g} mm wall "
                    f"at instant {instant:.4g} [{unit}]", "bold red"))
    return out


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("case_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help=f"Write the table here: .csv, .parquet, or {_ASTER} (Code_Aster table).")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Write PNG and SVG figures into this directory.")
@click.option("--aster-names", is_flag=True,
              help="Code_Aster column names (INST, V_USUR_TUBE, ...) in CSV/Parquet output.")
@click.option("--aster-format", type=click.Choice(TABLE_FORMATS, case_sensitive=False),
              default=TABLE_FORMATS[0], show_default=True,
              help=f"IMPR_TABLE format of a {_ASTER} output (LIRE_TABLE's FORMAT).")
@click.option("--database", "databases", multiple=True, metavar="CSV",
              type=click.Path(exists=True, dir_okay=False, path_type=Path),
              help="A coefficient CSV of your own (format in docs/laws.md) for [law] materials, "
                   "added after the case's [law] database files (repeatable; later files win).")
@click.option("--wall-thickness", "wall_thickness", type=click.FloatRange(min=0, min_open=True),
              metavar="METRES",
              help="Wall thickness of the tube [m] (overrides [geometry] wall_thickness_m): the "
                   "table gains the depth over the wall and the instant of reaching the limit.")
@click.option("--depth-limit", "depth_limit", type=click.FloatRange(min=0, min_open=True),
              metavar="FRACTION",
              help="Depth limit as a fraction of the wall [-] (overrides [geometry] "
                   f"depth_limit; default {DEFAULT_DEPTH_LIMIT}).")
@click.option("--report", "report", type=click.Path(dir_okay=False, path_type=Path),
              help="Also write one self-contained HTML report (uncertainty from the case's "
                   "[uncertainty] section; see fretwear report).")
@units_option
@click.option("--force", is_flag=True,
              help="Let -o replace the case's restart table ([restart] table, ETAT_INIT) with "
                   "the continued one (refused otherwise; other inputs are never replaced).")
@click.option("-q", "--quiet", is_flag=True, help="No summary on the terminal.")
def command(case_file: Path, output: Path | None, plot_dir: Path | None, aster_names: bool,
            aster_format: str, databases: tuple[Path, ...], wall_thickness: float | None,
            depth_limit: float | None, report: Path | None, units: tuple[str, ...],
            force: bool, quiet: bool) -> None:
    if plot_dir is not None:  # before the computation, not after it
        require("matplotlib.pyplot", purpose="--plot")
    if report is not None:
        require("jinja2", purpose="--report")
        require("matplotlib.pyplot", purpose="--report")
    case: Path | dict = case_file
    if databases:  # the command line's files come after the case's (later files win)
        case = load_case(case_file)
        law = dict(case.get("law", {}))
        given = law.get("database", [])
        law["database"] = ([given] if isinstance(given, str) else list(given)) + [
            str(p.resolve()) for p in databases]
        case["law"] = law
    if wall_thickness is not None or depth_limit is not None:
        case = case if isinstance(case, dict) else load_case(case_file)
        geometry = dict(case.get("geometry", {}))
        for key, value in (("wall_thickness_m", wall_thickness), ("depth_limit", depth_limit)):
            if value is not None:
                geometry[key] = value
        case["geometry"] = geometry
    case = with_history_units(case, parse_units(units))
    case = case if isinstance(case, dict) else load_case(case_file)
    inputs = case_inputs(case, case_file)
    inputs.update({f"--database {p}": p for p in databases})
    check_outputs({"-o": output, "--report": report}, inputs, force=force,
                  overwritable=(RESTART_TABLE,))
    console = Console(stderr=False, quiet=quiet)
    columns = (SpinnerColumn(), TextColumn("{task.description}"), BarColumn(),
               TaskProgressColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True, quiet=quiet), transient=True) as bar:
        task = bar.add_task("reading the case", total=None)

        def step(description: str, done: int | None = None, total: int | None = None) -> None:
            bar.update(task, description=description, completed=done or 0, total=total)

        result = run_case(case, progress=step)
    _summary(result, console)
    if output is not None:
        written = write_wear_table(result.table, output, aster_names=aster_names,
                              title=result.wear_case.name, aster_format=aster_format)
        console.print(f"table written to [bold]{written}[/]")
    if plot_dir is not None:
        files = [path for name, fig in wear_figures(result.table).items()
                 for path in save_figure(fig, plot_dir, f"wear_{name}", close=True)]
        console.print(f"figures written to [bold]{plot_dir}[/]: "
                      + ", ".join(f.name for f in files))
    if report is not None:
        written = write_report(analyse_case(case, result=result, source=case_file), report)
        console.print(f"report written to [bold]{written}[/]")
