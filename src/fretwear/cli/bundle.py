"""``fretwear bundle MANIFEST``: the wear tables of every contact of a tube bundle, on Dask."""

from __future__ import annotations

import math
from pathlib import Path

import click
from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.table import Table
from rich.text import Text

from fretwear.bundle import run_bundle
from fretwear.bundle.digest import limit_lines, warning_lines
from fretwear.bundle.interrupted import BundleInterrupted
from fretwear.bundle.manifest import BUNDLE_COLUMNS, WALL_COLUMN
from fretwear.bundle.store import DATASET_FORMATS, TABLE_FORMATS
from fretwear.cli._units import parse_units, units_option, with_bundle_units
from fretwear.cli.simulate import near_critical_option
from fretwear.errors import InputError
from fretwear.flow.bundle import (
    NEAR_CRITICAL_FILE,
    instability_lines,
    near_critical_lines,
    near_critical_tubes,
    record_unstable,
    unstable_tubes,
)
from fretwear.plotting import save_figure
from fretwear.plotting.bundle import plot_power_distribution, plot_tube_sheet, plot_worst_depths
from fretwear.table import DEFAULT_DEPTH_LIMIT

#: Exit code when some contacts failed or left their relation's range (the others are written).
EXIT_SOME_FAILED = 1

_COLUMNS = "\n".join(f"  {name}: {text}" for name, text in BUNDLE_COLUMNS.items())
_HELP = f"""Compute the wear table of every contact of a bundle (docs/bundle.md).

MANIFEST is a table of contacts (.csv, .parquet, or .toml with [[contacts]]), a Code_Aster
table holding several nodes (one contact per NOEUD), or a Zarr/NetCDF store with dimensions
(contact, time). Each contact starts from the base case (--case, a TOML case file of
`fretwear run`) and the manifest's columns override its keys for that contact. The work runs on
a local Dask cluster (one worker process per core, --workers) or joins an existing one
(--scheduler tcp://host:port). Results go to OUT/: table.parquet|csv, dataset.zarr|nc,
errors.csv, warnings.csv, summary.csv, run.json and the parts written as contacts finish; a
second run into OUT skips the contacts whose inputs did not change (--force recomputes).

\b
Manifest columns:
{_COLUMNS}
  {WALL_COLUMN}: wall thickness of the tube [m] (depth as a fraction of the wall,
    time to reach the limit)
  any case key (`fretwear run --help`), bare when unique or as section.key, e.g.
    mobile_radius_m, geometry.obstacle_radius_m, law.mobile.COEF_USURE, law.materials
    (lists and inline tables in TOML syntax in a CSV cell: [1, 2, 5])
  sectors: {{}} drops the base case's [sectors] for the contact (a law other than
    ARCHARD refuses sectors); a table, {{ count = 8 }}, replaces them

\b
Exit status: 0 every contact computed; {EXIT_SOME_FAILED} some contacts failed or their depth
left the relation's range (listed in OUT/errors.csv; the others are written); 2 the run could
not start (bad manifest, case or option; the message says which); 130 interrupted (Ctrl-C):
the contacts finished are written to OUT, and the same command resumes from them.
"""


def _summary(summary, console, top: int, limit: float | None, unstable=None) -> None:
    """The ranking table; a tube the simulation flagged unstable (``unstable``, of
    :func:`unstable_tubes`) is marked UNSTABLE on its rows."""
    if not len(summary):
        return
    flagged = set() if unstable is None or not len(unstable) else set(zip(
        unstable["tube_row"], unstable["tube_column"], strict=True))
    shown = "each case's depth_limit" if limit is None else f"{limit:.0%} of the wall"
    shown_count = min(top, len(summary))
    what = "the deepest contact" if shown_count == 1 else f"the {shown_count} deepest contacts"
    table = Table(title=f"{what} (global depth of the tube at the last instant; limit: "
                        f"{shown})")
    # one time unit: in the header; several (the manifest's time.unit per contact): per row
    units = summary["time_unit"].dropna().astype(str).unique()
    one_unit = units[0] if len(units) == 1 else None
    time_header = "time to limit" + (f" [{one_unit}]" if one_unit else "")
    # the forecast for the contacts' own limit; none for another --limit: no column
    forecasts = bool(summary["limit_forecast"].notna().any())
    forecast_header = "forecast" + (f" [{one_unit}]" if one_unit else "")
    for col in ("rank", "contact", "row", "col", "support", "P [W]", "global depth [mm]",
                "depth/wall", time_header, *([forecast_header] if forecasts else []),
                *(["stability"] if flagged else [])):
        table.add_column(Text(col), justify="right")  # Text: "[mm]" is not rich markup

    def text(v, fmt="{}"):
        return "" if v is None or (isinstance(v, float) and math.isnan(v)) else fmt.format(v)

    for r in summary.head(top).itertuples():
        depth = "beyond range" if math.isnan(r.depth) else f"{r.depth * 1e3:.4g}"
        t_lim = text(r.time_to_limit, "{:.4g}")
        forecast = text(r.limit_forecast, "{:.4g}").replace("inf", "never")
        if one_unit is None and isinstance(r.time_unit, str):
            t_lim = f"{t_lim} {r.time_unit}" if t_lim else t_lim
            forecast = f"{forecast} {r.time_unit}" if forecast[:1].isdigit() else forecast
        cells = (str(r.rank), str(r.contact), text(getattr(r, "tube_row", None)),
                 text(getattr(r, "tube_column", None)), text(getattr(r, "support", None)),
                 f"{r.power:.4g}", depth, text(r.depth_fraction, "{:.1%}"), t_lim,
                 *([forecast] if forecasts else []),
                 *([_stability(r, flagged)] if flagged else []))
        table.add_row(*(Text(c) for c in cells))
    console.print(table)
    if summary["time_to_limit"].notna().any():
        console.print(f"time to limit: {summary.attrs['time_to_limit']}", style="dim",
                      markup=False, highlight=False)
    if forecasts:
        console.print("forecast: when the wear table's law and geometry, at the history's "
                      "power, reach the limit, also beyond the last instant", style="dim",
                      markup=False, highlight=False)


def _stability(row, flagged: set) -> str:
    """"UNSTABLE" where the row's tube is among the flagged (row, column) pairs."""
    try:
        key = (int(row.tube_row), int(row.tube_column))
    except (AttributeError, TypeError, ValueError):
        return ""
    return "UNSTABLE" if key in flagged else ""


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("manifest", type=click.Path(exists=True, path_type=Path))
@click.option("--case", "case_file", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              help="Base case file (TOML, keys of `fretwear run`).")
@click.option("--scheduler", metavar="ADDRESS",
              help="Join this Dask scheduler (tcp://host:port) instead of a local cluster.")
@click.option("--workers", type=click.IntRange(min=1),
              help="Worker processes of the local cluster (default: one per core).")
@click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path),
              help="Output directory (default: <MANIFEST stem>_bundle in the current one).")
@click.option("--force", is_flag=True, help="Recompute every contact, even unchanged ones.")
@click.option("--chunk-size", type=click.IntRange(min=2), default=1_000_000, show_default=True,
              help="Samples per chunk of a long history (memory per task).")
@click.option("--table-format", type=click.Choice(TABLE_FORMATS), default=TABLE_FORMATS[0],
              show_default=True, help="Format of the table and of the parts.")
@click.option("--dataset-format", type=click.Choice(DATASET_FORMATS),
              help="Format of the dataset (default zarr).")
@click.option("--limit", type=click.FloatRange(min=0, max=1, min_open=True),
              help="Depth limit, fraction of the wall (0 < FRACTION <= 1), for the summary "
                   f"shown and OUT/summary.csv (default: each contact's depth_limit, "
                   f"{DEFAULT_DEPTH_LIMIT} unless "
                   "its case sets it).")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Write the figures (tube-sheet map, power distribution, worst depths).")
@click.option("--top", type=click.IntRange(min=1), default=10, show_default=True,
              help="Contacts shown in the terminal summary.")
@units_option
@near_critical_option
@click.option("-q", "--quiet", is_flag=True,
              help="No progress bar, no summary table, no list of errors; the final line (the "
                   "counts and where the results are) stays, and the exit status says whether "
                   "contacts failed.")
def command(manifest: Path, case_file: Path | None, scheduler: str | None, workers: int | None,
            output: Path | None, force: bool, chunk_size: int, table_format: str,
            dataset_format: str | None, limit: float | None, plot_dir: Path | None, top: int,
            units: tuple[str, ...], near_critical: float, quiet: bool) -> None:
    if workers is not None and scheduler is not None:
        if scheduler.lower() != "serial":
            raise click.UsageError("--workers applies to the local cluster started without "
                                   "--scheduler; the cluster joined by --scheduler has its own "
                                   "workers")
        if workers != 1:
            raise click.UsageError("--scheduler serial runs in this process: --workers must be "
                                   "1 or left out")
    console = Console(quiet=quiet)
    base = with_bundle_units(case_file, parse_units(units))
    if output is None:
        output = Path.cwd() / f"{manifest.name.split('.')[0]}_bundle"
    columns = (TextColumn("contacts"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
               TimeRemainingColumn())
    with Progress(*columns, console=Console(stderr=True, quiet=quiet), transient=True) as bar:
        task = bar.add_task("contacts", total=None)

        def step(done: int, total: int, record: dict) -> None:
            bar.update(task, completed=done, total=total)

        try:
            result = run_bundle(manifest, base, scheduler=scheduler, workers=workers,
                                output=output, force=force, chunk_size=chunk_size,
                                table_format=table_format, dataset_format=dataset_format,
                                progress=step, limit=limit)
        except BundleInterrupted as exc:  # Ctrl-C: the main entry prints it, exit 130
            raise KeyboardInterrupt(f"{exc}; run the same command again to resume") from exc
    # bad news first: tubes the simulation found unstable, through the wall, past the limit,
    # units that look wrong (one line per kind)
    unstable = unstable_tubes(manifest)
    record_unstable(output, unstable)  # for fretwear assess and calibrate --bundle
    for line in instability_lines(unstable):
        click.echo(line)
    summary = result.summary(limit)
    for line in limit_lines(summary):  # counts past the limit and through the wall first
        click.echo(line)
    for line in warning_lines(result.warnings, list(summary["contact"].astype(str))):
        click.echo(line)  # shown with -q too
    near = near_critical_tubes(manifest, near_critical)  # after the bad news
    record_unstable(output, near, NEAR_CRITICAL_FILE)
    for line in near_critical_lines(near):
        click.echo(line)
    _summary(summary, console, top, limit, unstable)
    s = result.stats
    errors = result.errors
    if len(errors):
        console.print(f"[yellow]{len(errors)} contact(s) in {output / 'errors.csv'}:[/]")
        for r in errors.head(10).itertuples():
            console.print(f"  {r.contact}: {r.error}: {r.message}", markup=False,
                          highlight=False, style="yellow")
    if plot_dir is not None and len(result.table):
        figures = [(plot_power_distribution(result), "bundle_power"),
                   (plot_worst_depths(result, limit=limit), "bundle_worst_depths")]
        if result.contacts[["tube_row", "tube_column"]].notna().all(axis=None):
            try:  # positions it cannot place (letters): said, the other figures still written
                figures.insert(0, (plot_tube_sheet(result.summary(limit)), "bundle_tube_sheet"))
            except InputError as exc:
                console.print(f"[yellow]no tube-sheet map: {exc}[/]", highlight=False)
        for fig, stem in figures:
            save_figure(fig, plot_dir, stem, close=True)
        console.print(f"figures written to [bold]{plot_dir}[/]")
    stale = f", stale {s['stale']} (earlier rows kept)" if s.get("stale") else ""
    counts = (f"done {s['done']}, failed {s['failed']}{stale}, skipped {s['skipped']} of "
              f"{s['contacts']} contacts in {s['seconds']:.1f} s")
    if s["done"] == 0 and s["skipped"] == s["contacts"]:  # nothing computed: no cluster
        click.echo(f"{counts} (every contact unchanged since the last run: no cluster started, "
                   f"--force recomputes); results in {output}")
    else:
        click.echo(f"{counts} (cluster start {s['startup_seconds']:.1f} s) on {s['workers']} "
                   f"worker(s): {s['contacts_per_s']:.3g} contacts/s, "
                   f"{s['samples_per_s']:.3g} samples/s; results in {output}")
    if s.get("two_pass_contacts"):
        click.echo(f"{s['two_pass_contacts']} KWU-EPRI contact(s) read twice (the class "
                   "bounds from the window's maxima); give force_max_N and speed_max_m_per_s "
                   "(FNOR_MAXI, VTAN_MAXI) in the case or the manifest to read them once")
    if len(errors):
        raise click.exceptions.Exit(EXIT_SOME_FAILED)
