"""``fretwear calibrate INSPECTIONS.csv (--case CASE.toml | --bundle RESULTS)``: Bayesian update
of the wear-coefficient factor on inspected depths, and the forecast of every contact."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click
from rich.console import Console
from rich.table import Table

from fretwear._optional import require
from fretwear.assessment.inspections import INPUT_COLUMNS
from fretwear.cli._units import parse_units, units_option, with_history_units
from fretwear.cli.calibrate_field import calibrate_field, field_options
from fretwear.errors import InputError
from fretwear.io.atomic import atomic_write
from fretwear.io.text_tables import read_text_table
from fretwear.plotting import save_figure
from fretwear.plotting.bundle import plot_tube_sheet
from fretwear.plotting.uncertainty import plot_calibration
from fretwear.report.predictions import bundle_predictions, case_predictions
from fretwear.table.schema import FLOAT_FORMAT
from fretwear.uncertainty import LogNormal, calibrate
from fretwear.uncertainty.calibration import CALIBRATION_METHODS, INSPECTION_COLUMNS


def _columns_help(columns=INSPECTION_COLUMNS) -> str:
    return "\n".join(f"  {name} [{unit}]: {meaning}" for name, (unit, meaning) in columns.items())


_HELP = f"""Calibrate the wear coefficients on inspections and forecast every contact.

INSPECTIONS is a CSV of measured depths; the predictions come from a case file (--case) or
the output directory of a bundle run (--bundle). A factor f on every wear coefficient, with a
lognormal prior (median --prior-median, scatter --prior-scatter or --prior-sigma-ln), is
updated by the depths (lognormal measurement error --measurement-sigma); prints its posterior,
each inspection against its prediction, and with --forecast the posterior predictive depth and
probability of exceeding the limit (depth_limit × wall thickness) of every contact.

With --bundle, the field campaign's hierarchical calibration (docs/assessment.md): sized
results through the sizing model, NDD (no detectable degradation) through 1 - POD, tubes not
inspected give nothing; a bundle factor, a contact scatter (--contact-sigma-ln), the power's
spread (--power-sigma-ln) and, with --group-sigma-ln > 0, a support-type level (the same
options and defaults as fretwear assess); bad news first, the --top worst tubes, every
contact to -o. Without --sizing-sigma-mm the sizing error is lognormal of
--measurement-sigma; without --pod-a50-mm and --pod-a90-mm there is no POD (NDD needs one).

\b
Inspection columns (--case):
{_columns_help()}

\b
Inspection columns (--bundle):
{_columns_help(INPUT_COLUMNS)}
"""


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("inspections", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--case", "case_file", type=click.Path(exists=True, dir_okay=False,
                                                     path_type=Path),
              help="A case file predicting the inspected contact.")
@click.option("--bundle", "bundle_dir", type=click.Path(exists=True, file_okay=False,
                                                        path_type=Path),
              help="The output directory of a bundle run (fretwear bundle -o DIR).")
@click.option("--prior-median", type=click.FloatRange(min=0, min_open=True), default=1.0,
              show_default=True, help="Median of the prior of the factor [-].")
@click.option("--prior-scatter", type=click.FloatRange(min=1, min_open=True), default=None,
              help="Prior scatter F: the factor within [m/F, m·F] at 95 % [-] (default 3).")
@click.option("--prior-sigma-ln", type=click.FloatRange(min=0, min_open=True), default=None,
              help="Prior standard deviation of ln f [-] instead of --prior-scatter.")
@click.option("--measurement-sigma", type=click.FloatRange(min=0, min_open=True), default=0.1,
              show_default=True,
              help="Standard deviation of ln(measured depth) [-], for rows without their own.")
@click.option("--method", type=click.Choice(CALIBRATION_METHODS), default="auto",
              show_default=True, help="Conjugate update (power-law depths) or grid quadrature.")
@click.option("--forecast", type=float, default=None,
              help="Instant of the forecast (next outage) [the cases' time unit].")
@click.option("--limit-mm", type=click.FloatRange(min=0, min_open=True), default=None,
              help="Depth limit [mm] instead of depth_limit × wall thickness.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help="Write the forecast (or the observations without --forecast) as CSV.")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Write the figures (PNG, SVG) into this directory.")
@click.option("--json", "as_json", is_flag=True, help="Print JSON instead of tables.")
@field_options
@units_option
def command(inspections, case_file, bundle_dir, prior_median, prior_scatter, prior_sigma_ln,
            measurement_sigma, method, forecast, limit_mm, output, plot_dir, as_json,
            units, **field) -> None:
    if (case_file is None) == (bundle_dir is None):
        raise click.UsageError("give exactly one of --case CASE.toml and --bundle RESULTS")
    if units and bundle_dir is not None:
        raise click.UsageError("--units gives the units of the case's history file; a bundle's "
                               "results (--bundle) are read in SI as written (give --units to "
                               "`fretwear bundle`)")
    if prior_scatter is not None and prior_sigma_ln is not None:
        raise click.UsageError("give --prior-scatter or --prior-sigma-ln, not both")
    if plot_dir is not None:
        require("matplotlib.pyplot", purpose="--plot")
    prior = (LogNormal(prior_median, sigma_ln=prior_sigma_ln) if prior_sigma_ln is not None
             else LogNormal(prior_median, scatter=prior_scatter or 3.0))
    identity = None
    if bundle_dir is not None:
        from fretwear.flow.bundle import (
            NEAR_CRITICAL_FILE,
            instability_lines,
            near_critical_lines,
            recorded_unstable,
        )

        predictions, identity = bundle_predictions(bundle_dir)
        for line in instability_lines(recorded_unstable(bundle_dir)):  # said first
            click.secho(line, fg="red", bold=True)
        frame = calibrate_field(predictions, identity, inspections, prior, measurement_sigma,
                                forecast, limit_mm, **field, notes=near_critical_lines(
                                    recorded_unstable(bundle_dir, NEAR_CRITICAL_FILE)))
        if output is not None:
            with atomic_write(output, encoding="utf-8", newline="") as handle:
                frame.to_csv(handle, index=False, float_format=FLOAT_FORMAT)
        if plot_dir is not None and "exceedance" in frame and frame["tube_row"].notna().any():
            save_figure(plot_tube_sheet(frame, quantity="probability", column="exceedance",
                                        title="P(exceeding the limit at the forecast)"),
                        plot_dir, "exceedance_map", close=True)
        if as_json:
            click.echo(frame.to_json(orient="records", indent=2))
        return
    else:
        predictions = case_predictions(with_history_units(case_file, parse_units(units)))
    try:
        result = calibrate(predictions, inspections, prior=prior,
                           measurement_sigma=measurement_sigma, method=method,
                           forecast=forecast, limit=None if limit_mm is None else limit_mm * 1e-3)
    except InputError as err:
        field = _field_campaign(inspections)
        if field is None:
            raise
        raise InputError(f"{err}\n{field}") from err
    frame = result.predictive if result.predictive is not None else result.observations
    if identity is not None and result.predictive is not None:
        frame = identity.merge(frame, on="contact", how="right")
        if "exceedance" in frame.columns:
            # ties (probabilities below the float range) ranked by the posterior median depth
            frame = frame.sort_values(["exceedance", "depth_q50"], ascending=False,
                                      kind="stable")
    if output is not None:
        with atomic_write(output, encoding="utf-8", newline="") as handle:
            frame.to_csv(handle, index=False, float_format=FLOAT_FORMAT)
    if as_json:
        payload = result.to_dict()
        payload["predictive"] = None if result.predictive is None else json.loads(
            frame.to_json(orient="records"))
        click.echo(json.dumps(payload, indent=2, default=str))
    else:
        _print(result, frame, Console())
    if plot_dir is not None:
        save_figure(plot_calibration(result), plot_dir, "calibration", close=True)
        if identity is not None and result.predictive is not None \
                and frame.get("tube_row") is not None and frame["tube_row"].notna().any():
            global_rows = frame[frame["sector"].isna()] if "sector" in frame else frame
            save_figure(plot_tube_sheet(global_rows, quantity="probability",
                                        column="exceedance",
                                        title="P(exceeding the limit at the forecast)"),
                        plot_dir, "exceedance_map", close=True)


_FIELD_ONLY = ("result", "inspected", "plugged", "depth_pct", "wall_thickness", "tube_row",
               "tube_column", "support", "date", "technique")


def _field_campaign(path) -> str | None:
    """What --case cannot read in a field campaign (NDD rows, the campaign's own columns), and
    the fix: --bundle; None when the file holds neither."""
    try:
        frame = read_text_table(path, "inspection file")
    except InputError:
        return None
    frame.columns = [str(c).strip() for c in frame.columns]
    ndd = [c for c in ("depth", "depth_mm", "result") if c in frame
           and frame[c].astype(str).str.strip().str.upper().eq("NDD").any()]
    extra = [c for c in _FIELD_ONLY if c in frame and c != "result"]
    if not ndd and not extra:
        return None
    what = ("an NDD (no detectable degradation) row" if ndd else
            f"a field campaign's column(s) {extra}")
    return (f"the file holds {what}: --case calibrates one contact on sized depths only; "
            "NDD, tube locations and the campaign's columns are read by the hierarchical "
            "calibration of a bundle: fretwear calibrate INSPECTIONS --bundle RESULTS (with the "
            "technique's POD, --pod-a50-mm and --pod-a90-mm), or leave the NDD rows out "
            "for --case")


def _mm(value) -> str:
    return "-" if value is None or (isinstance(value, float) and math.isnan(value)) \
        else f"{value * 1e3:.4g}"


def _print(result, frame, console: Console) -> None:
    low, high = result.factor_interval(0.95)
    console.print(f"prior of the factor: {result.prior}", markup=False, highlight=False)
    console.print(f"posterior ({result.method}): median {result.factor_median:.4g}, 95 % "
                  f"[{low:.4g}, {high:.4g}], sigma_ln {result.posterior.sigma_ln:.3g}",
                  markup=False, highlight=False)
    obs = Table(title="inspections (depths in mm)")
    for col in ("contact", "sector", "instant", "measured", "sigma_ln", "prior median",
                "posterior median"):
        obs.add_column(col, justify="right")
    for _, r in result.observations.iterrows():
        obs.add_row(str(r["contact"]), "-" if math.isnan(r["sector"]) else f"{r['sector']:g}",
                    f"{r['instant']:g}", _mm(r["depth"]), f"{r['measurement_sigma']:.3g}",
                    _mm(r["prior_depth"]), _mm(r["posterior_depth"]))
    console.print(obs)
    if result.predictive is None:
        return
    fc = Table(title=f"forecast at instant {frame['instant'].iloc[0]:g} (depths in mm)")
    for col in ("contact", "sector", "prior median", "5 %", "median", "95 %", "limit",
                "P prior", "P posterior"):
        fc.add_column(col, justify="right")
    for _, r in frame.iterrows():
        sector = r.get("sector")
        fc.add_row(str(r["contact"]), "-" if sector is None or sector != sector
                   else f"{sector:g}", _mm(r["depth_prior_q50"]), _mm(r["depth_q5"]),
                   _mm(r["depth_q50"]), _mm(r["depth_q95"]), _mm(r["limit"]),
                   f"{r['exceedance_prior']:.3g}", f"{r['exceedance']:.3g}")
    console.print(fc)
