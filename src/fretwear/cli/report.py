"""``fretwear report CASE.toml -o report.html``: one self-contained HTML report of a case."""

from __future__ import annotations

from pathlib import Path

import click
from rich.console import Console

from fretwear._optional import require
from fretwear.cli._units import parse_units, units_option, with_history_units
from fretwear.io.atomic import check_outputs
from fretwear.report import UNCERTAINTY_KEYS, analyse_case, write_report
from fretwear.uncertainty.sampling import METHODS
from fretwear.workflows.case_files import load_case
from fretwear.workflows.inputs import case_inputs

_KEYS = "\n".join(f"  {k}: {d}" for k, (_, d) in UNCERTAINTY_KEYS.items())

_HELP = f"""Run CASE_FILE and write one self-contained HTML report (CASE_FILE a finished
bundle's output directory: its results read back, the bad news, the tube-sheet map and the
deepest contacts): inputs, every coefficient with
its source, the fretwear version, warnings, the wear table and its figures, the wear power's
confidence interval, the Monte Carlo propagation of the wear coefficients' scatter (depth
quantiles, probability of exceeding the limit, time to reach it, Sobol' indices) and, with
inspections, the calibration. Options override the case's [uncertainty] section:

\b
{_KEYS}
"""


def report_options(function):
    """The options shared by ``fretwear report`` and ``fretwear run --report``."""
    for option in reversed((
        click.option("--scatter", "coefficient_scatter", type=click.FloatRange(min=1,
                     min_open=True), help="Scatter factor of the wear coefficients (95 %) [-]."),
        click.option("--sigma-ln", "coefficient_sigma_ln", type=click.FloatRange(min=0,
                     min_open=True), help="Standard deviation of ln K [-] instead."),
        click.option("--samples", type=click.IntRange(min=2), help="Monte Carlo samples."),
        click.option("--method", type=click.Choice(METHODS),
                     help="Sampling method."),
        click.option("--seed", type=int, help="Seed of the sampling."),
        click.option("--inspections", type=click.Path(exists=True, dir_okay=False,
                                                      path_type=Path),
                     help="Inspected depths (CSV) to calibrate on."),
        click.option("--measurement-sigma", type=click.FloatRange(min=0, min_open=True),
                     help="Standard deviation of ln(measured depth) [-]."),
        click.option("--forecast", type=float, help="Instant of the posterior forecast."),
    )):
        function = option(function)
    return function


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("case_file", metavar="CASE_FILE|BUNDLE_DIR",
                type=click.Path(exists=True, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help="The HTML file to write (a bundle directory's default: "
                   "BUNDLE_DIR/report.html).")
@report_options
@units_option
def command(case_file: Path, output: Path | None, inspections, units, **options) -> None:
    require("jinja2", purpose="fretwear report")
    require("matplotlib.pyplot", purpose="fretwear report")
    if case_file.is_dir():  # a finished bundle's output directory: read back, not re-run
        from fretwear.bundle import load
        from fretwear.report.assessment import write_bundle_report

        written = write_bundle_report(load(case_file), output or case_file / "report.html")
        Console().print(f"report written to [bold]{written}[/]")
        return
    if output is None:
        raise click.UsageError("give the HTML file to write: -o report.html")
    case = with_history_units(load_case(case_file), parse_units(units))
    check_outputs({"-o": output}, {**case_inputs(case, case_file), "inspections": inspections})
    analysis = analyse_case(case, inspections=inspections, source=case_file, **options)
    written = write_report(analysis, output)
    Console().print(f"report written to [bold]{written}[/]")
