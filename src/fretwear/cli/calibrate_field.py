"""``fretwear calibrate INSPECTIONS --bundle RESULTS``: the hierarchical calibration of the
bundle's factor on a field campaign (sized, NDD, not inspected), bad news first, the worst
tubes on the terminal (``--top``) and every contact in the file (``-o``)."""

from __future__ import annotations

import functools
import math

import click
from rich.console import Console
from rich.table import Table

from fretwear.assessment import (
    FactorPrior,
    LogisticPOD,
    LogSizingModel,
    SizingModel,
    Technique,
    calibrate_bundle,
    read_field_inspections,
)
from fretwear.assessment.calibration import CONTACT_SIGMA_LN, POWER_SIGMA_LN
from fretwear.assessment.outage import calibration_fit
from fretwear.assessment.summary import (
    coverage_line,
    factor_line,
    probability_text,
    summary_counts,
    tube_summary,
)

_TECHNIQUE = [
    click.option("--sizing-sigma-mm", type=click.FloatRange(min=0, min_open=True),
                 default=None, help="Sizing error σ [mm] of measured = a + b·true + e "
                 "(default: the command's, above)."),
    click.option("--sizing-intercept-mm", type=float, default=0.0, show_default=True,
                 help="Sizing intercept a [mm]."),
    click.option("--sizing-slope", type=click.FloatRange(min=0, min_open=True), default=1.0,
                 show_default=True, help="Sizing slope b [-]."),
    click.option("--pod-a50-mm", type=click.FloatRange(min=0, min_open=True), default=None,
                 help="Depth detected half the time [mm] (logistic POD in ln depth; default: "
                 "the command's, above)."),
    click.option("--pod-a90-mm", type=click.FloatRange(min=0, min_open=True), default=None,
                 help="Depth detected 90 % of the time [mm]."),
]
_FACTOR = [
    click.option("--contact-sigma-ln", type=click.FloatRange(min=0), default=CONTACT_SIGMA_LN,
                 show_default=True, help="σ of ln of one contact's factor about its group's "
                 "(the contact scatter inspections of the others cannot remove) [-]."),
    click.option("--power-sigma-ln", type=click.FloatRange(min=0), default=POWER_SIGMA_LN,
                 show_default=True, help="σ of ln of the factor on each contact's wear power "
                 "(its confidence interval) [-]."),
    click.option("--group-sigma-ln", type=click.FloatRange(min=0), default=0.0,
                 show_default=True, help="σ of ln of a support type's factor about the "
                 "bundle's [-] (> 0: one level per support type, AVB, TSP...; 0: none)."),
]
_CAMPAIGN = [
    click.option("--origin-date", default=None,
                 help="Date of the predictions' instant 0 (ISO 8601), for inspections given "
                 "by date."),
    click.option("--top", type=click.IntRange(min=0), default=10, show_default=True,
                 help="Tubes shown on the terminal (every row goes to the file)."),
]


def _apply(options):
    return lambda func: functools.reduce(lambda f, option: option(f), reversed(options), func)


technique_options = _apply(_TECHNIQUE)
"""The technique's options in mm, shared by ``fretwear assess`` and ``calibrate --bundle``."""
factor_options = _apply(_FACTOR)
"""The hierarchical factor's σ options, one name and one default for both commands."""
campaign_options = _apply(_CAMPAIGN)
"""--origin-date and --top, shared."""


def field_options(func):
    """The options of the field campaign (``fretwear calibrate --bundle``)."""
    func = campaign_options(factor_options(technique_options(func)))
    return click.option("--wall-mm", type=click.FloatRange(min=0, min_open=True), default=None,
                        help="Tube wall [mm] for depth_pct without a wall_thickness column."
                        )(func)


def technique_from_options(measurement_sigma, sizing_sigma_mm, sizing_intercept_mm,
                           sizing_slope, pod_a50_mm, pod_a90_mm) -> Technique:
    """The technique of the command line's options in mm (a lognormal sizing error of
    ``measurement_sigma`` where no ``sizing_sigma_mm`` is given; no POD where none)."""
    sizing = LogSizingModel(measurement_sigma) if sizing_sigma_mm is None else SizingModel(
        sizing_intercept_mm * 1e-3, sizing_slope, sizing_sigma_mm * 1e-3)
    if (pod_a50_mm is None) != (pod_a90_mm is None):
        raise click.UsageError("give both --pod-a50-mm and --pod-a90-mm")
    pod = None if pod_a50_mm is None else LogisticPOD.from_depths(pod_a50_mm * 1e-3,
                                                                  pod_a90_mm * 1e-3)
    return Technique(sizing, pod, name="command line")


def calibrate_field(predictions, identity, inspections, prior, measurement_sigma, forecast,
                    limit_mm, *, sizing_sigma_mm, sizing_intercept_mm, sizing_slope,
                    pod_a50_mm, pod_a90_mm, contact_sigma_ln, group_sigma_ln,
                    power_sigma_ln, origin_date, wall_mm, top, notes=()):
    """Calibrate, print (bad news first; ``notes``, the near-critical tubes, after it) and
    return the table for the file."""
    tech = technique_from_options(measurement_sigma, sizing_sigma_mm, sizing_intercept_mm,
                                  sizing_slope, pod_a50_mm, pod_a90_mm)
    ins = read_field_inspections(inspections, origin_date=origin_date,
                                 wall_thickness=None if wall_mm is None else wall_mm * 1e-3)
    techniques = {name: tech for name in set(ins.table["technique"])}
    cal = calibrate_bundle(predictions, ins, techniques=techniques,
                           prior=FactorPrior(prior, group_sigma_ln, contact_sigma_ln),
                           groups="support type" if group_sigma_ln > 0 else None,
                           identity=identity, power_sigma_ln=power_sigma_ln)
    console = Console()
    _, fit = calibration_fit(cal, tech.sizing, identity=identity)  # as assess: said first
    n = fit["indications"]
    poor = coverage_line(round(fit["coverage"] * n), n, fit["level"]) if n else None
    for line in (poor, factor_line(cal.bundle_factor()[0])):
        if line:
            _say(console, line, "bold red")
    if forecast is None:
        for line in notes:
            _say(console, line, "yellow")
        _factor_lines(cal, ins, console, fit)
        frame = cal.factor_summary()
        return identity.merge(frame, on="contact", how="right")
    frame = cal.forecast(forecast, limit=None if limit_mm is None else limit_mm * 1e-3)
    counts = summary_counts(frame, identity)
    _bad_news(counts, frame, forecast, console)
    for line in notes:
        _say(console, line, "yellow")
    _factor_lines(cal, ins, console, fit)
    _tubes(tube_summary(frame, identity), top, forecast, console)
    return identity.merge(frame, on="contact", how="right")


def _say(console: Console, text: str, style: str | None = None) -> None:
    console.print(text, markup=False, highlight=False, style=style, soft_wrap=True)


def _bad_news(c: dict, frame, instant, console: Console) -> None:
    bad = c["contacts_past_limit"] or c["contacts_through_wall"]
    plugged = f"; {c['tubes_plugged']} plugged tubes left out" if c["tubes_plugged"] else ""
    _say(console, f"at instant {instant:g}: {c['contacts_past_limit']} contact(s) "
                  f"({c['tubes_past_limit']} tube(s)) at or past the limit, "
                  f"{c['contacts_through_wall']} contact(s) ({c['tubes_through_wall']} tube(s)) "
                  f"through the wall (median depth){plugged}", "bold red" if bad else None)
    if "worst_contact" not in c:
        return
    worst = frame[frame["contact"] == c["worst_contact"]].iloc[0]
    _say(console, f"worst: {c['worst_contact']} (tube {c['worst_tube']}), P(depth > limit) "
                  f"{c['worst_exceedance']:.3g}, median depth "
                  f"{c['worst_depth_q50'] * 1e3:.4g} mm "
                  f"({worst.get('wall_fraction_q50', math.nan) * 100:.0f} % of the wall)")


def _factor_lines(cal, ins, console: Console, fit: dict) -> None:
    median, (low, high) = cal.bundle_factor()  # beyond [0.1, 10]: said with the bad news
    _say(console, str(ins))
    _say(console, f"bundle factor: median {median:.4g}, 90 % [{low:.4g}, {high:.4g}]; "
                  f"contact scatter sigma_ln {cal.prior.contact_sigma_ln:.3g}")
    if len(cal.groups) > 1:
        for g in cal.groups:
            m, (lo, hi) = cal.group_factor(g)
            _say(console, f"  {g}: median {m:.4g}, 90 % [{lo:.4g}, {hi:.4g}]")
    if fit["indications"]:
        _say(console, f"predicted against measured: {fit['indications']} indications, "
                      f"{fit['coverage']:.0%} inside the prediction's {fit['level']:.0%} "
                      "interval")


def _tubes(tubes, top: int, instant, console: Console) -> None:
    if not top:
        return
    table = Table(title=f"the {min(top, len(tubes))} worst of {len(tubes)} tubes at "
                        f"instant {instant:g} (depths in mm)")
    for col in ("tube", "contacts", "worst contact", "P > limit", "its median depth",
                "% wall", "inspected"):
        table.add_column(col, justify="right")
    for _, r in tubes.head(top).iterrows():
        table.add_row(str(r["tube"]), str(r["contacts"]), str(r["worst_contact"]),
                      probability_text(r["exceedance_max"]),
                      f"{r['worst_depth_q50'] * 1e3:.4g}",
                      f"{r['worst_wall_fraction_q50'] * 100:.0f}",
                      "yes" if r["inspected"] else "no")
    console.print(table)
