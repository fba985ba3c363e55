"""``fretwear iterate CASE.toml``: the coupled loop dynamics → wear → obstacle → dynamics."""

from __future__ import annotations

import os
from pathlib import Path

import click
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from fretwear.dynamics.config import keys_help as dynamics_keys
from fretwear.workflows.loop import ITERATE_KEYS, iterate_case

_ITERATE = "\n".join(f"  {k}: {d}" for k, (_, d) in ITERATE_KEYS.items())
_HELP = f"""Run the coupled loop of a case file: built-in dynamics (modal model with shocks) ->
wear table (POST_USURE) -> obstacle update (MODI_OBSTACLE) -> dynamics, N cycles or until a
depth. Each cycle continues the previous wear table (ETAT_INIT) over the [time] instants.

The case file holds the wear sections of `fretwear run` ([law], [geometry], [sectors] required,
[time] = durations of one cycle, [power] window, no [history]), an [obstacle] section (the new
obstacle, the wall thickness), a [dynamics] section and an [iterate] section. Writes, in the
output folder, cycle_NN/ (histories/*.parquet, wear_table.csv, obstacle_profile.csv,
obstacle_discret.txt, dynamics.json, figures) and summary.csv / summary.json.
Units: SI (m, N, s, W; angles in degrees). Full reference: docs/dynamics.md.

\b
[iterate]
{_ITERATE}
\b
{dynamics_keys()}
"""


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("case_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path),
              help="Output folder (default [iterate] output, else 'iterate' beside the case).")
@click.option("-n", "--cycles", type=click.IntRange(min=1),
              help="Number of cycles (overrides [iterate] cycles).")
@click.option("--no-plot", is_flag=True, help="Do not write figures.")
@click.option("-q", "--quiet", is_flag=True, help="No summary on the terminal.")
def command(case_file: Path, output: Path | None, cycles: int | None, no_plot: bool,
            quiet: bool) -> None:
    console = Console(quiet=quiet)
    err = Console(stderr=True, quiet=quiet)
    with err.status("reading the case") as status:
        result = iterate_case(case_file, output=output, cycles=cycles,
                              plot=False if no_plot else None,
                              progress=lambda message: status.update(message))
    perforated = result.summary[result.summary["perforated"].astype(bool)] \
        if "perforated" in result.summary else result.summary.iloc[:0]
    if len(perforated):  # bad news first
        k = int(perforated["cycle"].iloc[0])
        console.print(f"PERFORATED: the tube is worn through its wall at cycle {k} (profile "
                      f"depth {1e3 * float(perforated['depth_mobile_max'].iloc[0]):.3g} mm)",
                      style="bold red", markup=False, highlight=False)
    stopped = result.stopped + (f" ({result.max_depth_of} depth)"
                                if result.stopped == "max_depth" else "")
    table = Table(title=f"fretwear iterate: {case_file.name} (stopped: {stopped})")
    level = result.intervals[0].level if result.intervals else 0.95
    unit = (result.tables[-1].attrs.get("time_unit") if result.tables else None) or "case unit"
    columns = (("cycle", "cycle", 1.0), ("instant", f"instant [{unit}]", 1.0),
               ("depth_global_mobile", "global depth tube [mm]", 1e3),
               ("depth_sector_mobile_max", "max sector depth tube [mm]", 1e3),
               ("depth_mobile_max", "profile depth tube [mm]", 1e3),
               ("depth_obstacle_max", "profile depth obst. [mm]", 1e3),
               ("clearance_min", "gap min [mm]", 1e3), ("clearance_max", "gap max [mm]", 1e3),
               ("contact_fraction", "in contact [-]", 1.0))
    for _, label, _ in columns[:2]:
        table.add_column(escape(label), justify="right")  # rich ate '[mm]' as markup
    table.add_column(f"wear power ({100 * level:.3g} % interval)", justify="right")
    table.add_column("change from the previous cycle", justify="right")
    for _, label, _ in columns[2:]:
        table.add_column(escape(label), justify="right")  # rich ate '[mm]' as markup
    for row, interval in zip(result.summary.to_dict(orient="records"), result.intervals,
                             strict=True):
        cells = [f"{row[c] * scale:.4g}" for c, _, scale in columns]
        table.add_row(*cells[:2], str(interval), _change(row), *cells[2:])
    console.print(table)
    verdict, sentence = result.convergence
    style = {"converged": "green", "not converged": "yellow"}.get(verdict, "")
    console.print(f"convergence: {verdict}; {sentence}", style=style, markup=False,
                  highlight=False)
    if result.stopped == "max_depth" and bool(result.summary["max_depth_within_noise"].iloc[-1]):
        console.print("the max_depth_m stop is within the noise: the depth's interval from the "
                      "cycle's power straddles max_depth_m", style="yellow", markup=False,
                      highlight=False)
    if result.warnings:
        console.print("[yellow]warnings:[/]")
        for w in result.warnings:
            console.print(f"  - {w}", markup=False, highlight=False, style="yellow")
    # where it writes, even with -q ("examples/../build" said as "build")
    click.echo(f"outputs written to {os.path.normpath(result.directory)}")


def _change(row) -> str:
    """``+0.0012 ± 0.0030 W, within the noise`` (empty on the first cycle)."""
    significant = row.get("power_change_significant")
    if significant is None or row["power_change"] != row["power_change"]:
        return "-"
    verdict = "beyond the noise" if significant else "within the noise"
    return f"{row['power_change']:+.3g} ± {row['power_change_half_width']:.2g} W, {verdict}"
