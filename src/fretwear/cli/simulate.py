"""``fretwear simulate BUNDLE.toml -o HISTORIES/``: a bundle's contact histories from its
description (docs/flow.md)."""

from __future__ import annotations

from pathlib import Path

import click
from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from fretwear.flow.bundle import (
    instability_lines,
    near_critical_lines,
    near_critical_tubes,
    run_simulate,
    unstable_tubes,
)
from fretwear.flow.description import read_description
from fretwear.flow.stability import NEAR_CRITICAL

#: Exit code when some tubes failed (the others are written).
EXIT_SOME_FAILED = 1

_HELP = """Simulate every tube of a bundle description (docs/flow.md) and write its contacts'
histories and a manifest that `fretwear bundle` reads as it is.

For each tube (one task on a local Dask cluster, or --scheduler): its modes, the turbulence of its
flow (Code_Aster's DEFI_SPEC_TURB families) projected onto them, correlated modal forces
synthesised from that matrix, the shock dynamics at its supports, and the fluid-elastic stability
ratio of each mode (Connors). OUT/ gets tubes/<tube>/<support>.parquet, manifest.csv, tubes.csv
(stability ratio and wear power per tube), stability.csv (per mode), gaps.csv, errors.csv. A second
run into OUT skips the tubes whose inputs did not change (--force recomputes).

\b
Then:  fretwear bundle OUT/manifest.csv --case CASE.toml -o WEAR/

\b
Exit status: 0 every tube simulated; 1 some tubes failed (OUT/errors.csv; the others are
written); 2 the run could not start (bad description or option; the message says which).
"""


#: ``--near-critical RATIO`` of ``fretwear simulate``, ``bundle`` (docs/flow.md §4).
near_critical_option = click.option(
    "--near-critical", "near_critical", default=NEAR_CRITICAL, show_default=True,
    type=click.FloatRange(min=0, min_open=True), metavar="RATIO",
    help="Design threshold on the stability ratio U_eff/U_c: a tube above it and not flagged "
         "unstable is said NEAR-CRITICAL after the bad news (0.75: a 25 % margin on the "
         "critical velocity; docs/flow.md §4).")


def _table(result, console: Console, threshold: float) -> None:
    tubes = result.tubes()
    table = Table(title="tubes, fluid-elastically flagged first (stability ratio U_eff/U_c of "
                        "the most critical mode)")
    for col in ("tube", "row", "col", "stability ratio", "flagged", "max wear power [W]"):
        table.add_column(col, justify="right")
    for r in tubes.itertuples():
        near = not r.flagged and r.max_stability_ratio > threshold
        style = "bold red" if r.flagged else "yellow" if near else None
        table.add_row(r.tube, str(r.row), str(r.column), f"{r.max_stability_ratio:.3f}",
                      "UNSTABLE" if r.flagged else "near-critical" if near else "",
                      f"{r.max_wear_power_w:.4g}", style=style)
    console.print(table)


@click.command(help=_HELP)
@click.argument("description", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path), required=True,
              help="Output directory of the histories and the manifest.")
@click.option("--scheduler", metavar="ADDRESS",
              help="Join this Dask scheduler (tcp://host:port), or 'serial' (this process).")
@click.option("--workers", type=click.IntRange(min=1),
              help="Worker processes of the local cluster (default: one per core).")
@click.option("--force", is_flag=True, help="Recompute every tube, even unchanged ones.")
@near_critical_option
@click.option("-q", "--quiet", is_flag=True,
              help="No progress bar and no table (failures and stability news stay).")
def command(description: Path, output: Path, scheduler: str | None, workers: int | None,
            force: bool, near_critical: float, quiet: bool) -> int:
    if workers is not None and scheduler is not None and scheduler.lower() != "serial":
        raise click.UsageError("--workers applies to the local cluster started without "
                               "--scheduler")
    specs = read_description(description)
    console = Console(quiet=quiet)
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
               TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True, quiet=quiet), transient=True) as bar:
        task = bar.add_task("tubes", total=len(specs))
        result = run_simulate(specs, output, scheduler=scheduler, workers=workers, force=force,
                              progress=lambda tube, ok: bar.advance(task))
    news = Console()  # the failures and the stability news stay with -q (no table then)
    manifest = output / "manifest.csv"
    for line in instability_lines(unstable_tubes(manifest)):  # bad news first, in the words
        news.print(line, style="bold red", markup=False, soft_wrap=True)  # of bundle, assess
    if result.errors:
        news.print(f"[red]{len(result.errors)} tube(s) failed (in {output / 'errors.csv'}):[/]")
        for tube, message in result.errors.items():
            news.print(f"  {tube}: {message}", markup=False, highlight=False)
    for line in near_critical_lines(near_critical_tubes(manifest, near_critical)):
        news.print(line, style="yellow", markup=False, soft_wrap=True)
    _table(result, console, near_critical)
    click.echo(f"done {len(result.records) - len(result.reused)}, reused {len(result.reused)}, "
               f"failed {len(result.errors)} of {len(specs)} tubes; manifest in "
               f"{manifest}")
    return EXIT_SOME_FAILED if result.errors else 0
