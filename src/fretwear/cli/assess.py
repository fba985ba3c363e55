"""``fretwear assess BUNDLE_OUT INSPECTIONS --interval T -o OUT``: the outage decision of a
bundle (condition monitoring and operational assessment), bad news first."""

from __future__ import annotations

import math
from pathlib import Path

import click
from rich.console import Console
from rich.table import Table

from fretwear.assessment.outage import assess
from fretwear.assessment.summary import probability_text
from fretwear.bundle import load
from fretwear.cli.calibrate_field import (
    campaign_options,
    factor_options,
    technique_from_options,
    technique_options,
)
from fretwear.flow.bundle import (
    NEAR_CRITICAL_FILE,
    instability_lines,
    near_critical_lines,
    recorded_unstable,
)

_HELP = """The outage decision of a bundle: which tubes to plug, which to inspect next, how long
the generator may run.

BUNDLE_OUT is the output directory of a finished bundle run (fretwear bundle -o); INSPECTIONS
the outage's inspections (CSV or Parquet): per contact or tube location (tube_row,
tube_column, support), instant, a depth (depth [m], depth_mm or depth_pct) or NDD (no
detectable degradation), inspected and plugged (yes/no). A contact without a row was not
inspected. The technique's sizing error (measured = a + b·true + e, e ~ N(0, σ)) and its
logistic POD (depths detected 50 % and 90 % of the time) are yours to give: without them,
illustrative values, not qualified (--sizing-sigma-mm 0.05, --pod-a50-mm 0.15, --pod-a90-mm
0.30).

The wear factor is calibrated on these inspections by the hierarchical censored calibration
(as fretwear calibrate --bundle, docs/assessment.md): sized results through the sizing model,
NDD through 1 - POD, uninspected tubes giving nothing; a bundle factor, a contact scatter
(--contact-sigma-ln), the power's spread (--power-sigma-ln) and, with --group-sigma-ln > 0,
a factor per support type shared by its contacts in the assessment.

Prints, bad news first: tubes at or past the plugging limit and through the wall as measured,
then the probability that any tube exceeds its limit by the end of --interval against
--target, the tubes to plug, the longest interval under the target once they are plugged (and
with only the tubes at the limit plugged), and the next inspection's sample; writes the tables
into -o OUT (and OUT/report.html with --report).
"""

_ILLUSTRATIVE = {"sizing_sigma_mm": 0.05, "pod_a50_mm": 0.15, "pod_a90_mm": 0.30}


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("bundle_out", type=click.Path(exists=True, file_okay=False, path_type=Path))
@click.argument("inspections", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--interval", type=click.FloatRange(min=0, min_open=True), required=True,
              help="The next operating interval [the bundle's time unit].")
@click.option("--target", type=click.FloatRange(0, 1, min_open=True, max_open=True),
              default=0.05, show_default=True, help="Target of P(any tube past its limit).")
@click.option("--limit", type=click.FloatRange(0, 1, min_open=True), default=None,
              help="Plugging limit, fraction of the wall (default each contact's, 0.4).")
@technique_options
@factor_options
@click.option("--share", type=click.FloatRange(0, 1, min_open=True), default=0.9,
              show_default=True, help="Share of the bundle's risk the next sample covers.")
@campaign_options
@click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path),
              required=True, help="Directory of the tables (created).")
@click.option("--report", "with_report", is_flag=True,
              help="Also write OUT/report.html, one self-contained page.")
def command(bundle_out, inspections, interval, target, limit, sizing_intercept_mm,
            sizing_slope, sizing_sigma_mm, pod_a50_mm, pod_a90_mm, contact_sigma_ln,
            power_sigma_ln, group_sigma_ln, share, origin_date, top, output,
            with_report) -> None:
    given = {"sizing_sigma_mm": sizing_sigma_mm, "pod_a50_mm": pod_a50_mm,
             "pod_a90_mm": pod_a90_mm}
    defaulted = [k for k, v in given.items() if v is None]
    values = {k: _ILLUSTRATIVE[k] if v is None else v for k, v in given.items()}
    tech = technique_from_options(None, values["sizing_sigma_mm"], sizing_intercept_mm,
                                  sizing_slope, values["pod_a50_mm"], values["pod_a90_mm"])
    result = assess(load(bundle_out), inspections, interval=interval, sizing=tech.sizing,
                    pod=tech.pod, target=target, contact_sigma_ln=contact_sigma_ln,
                    power_sigma_ln=power_sigma_ln, group_sigma_ln=group_sigma_ln,
                    share=share, limit=limit, origin_date=origin_date)
    result.inputs.update({"bundle": str(bundle_out), "inspections": str(inspections),
                          "illustrative": defaulted})
    unstable = recorded_unstable(bundle_out)
    if unstable is not None and len(unstable):  # said first, kept in assessment.json
        result.inputs["unstable_tubes"] = unstable.to_dict("records")
    near = recorded_unstable(bundle_out, NEAR_CRITICAL_FILE)
    if near is not None and len(near):  # said after the bad news, kept in assessment.json
        result.inputs["near_critical_tubes"] = near.to_dict("records")
    result.write(output)
    if with_report:
        from fretwear.report.assessment import write_assessment_report

        write_assessment_report(result, output / "report.html")
    _print(result, Console(highlight=False), top, defaulted, output, with_report)


def _print(result, console: Console, top: int, defaulted, output, with_report) -> None:
    b = result.bundle
    for line in instability_lines(result.inputs.get("unstable_tubes")):
        console.print(line, style="bold red", markup=False, soft_wrap=True)
    for line in result.bad_news():  # not markup: a line may hold [0.1, 10]
        console.print(line, style="bold red", markup=False, soft_wrap=True)
    for line in near_critical_lines(result.inputs.get("near_critical_tubes")):
        console.print(line, style="yellow", markup=False, soft_wrap=True)
    if not (b["past_limit_tubes"] or b["through_wall_tubes"]):
        console.print("no tube at or past the plugging limit as measured")
    if b["p_any"] <= b["target"]:  # else said first, with the bad news
        console.print(result.probability_line())
    plugs = b["plugging"]
    console.print(f"plugging list ({len(plugs)} tube(s)): {', '.join(plugs) or 'none'}; "
                  f"P(any) after plugging {probability_text(b['p_any_after_plugging'])}")
    console.print("longest operating interval under the target: "
                  + _interval(b["longest_interval"], b) + " with the plugging list plugged; "
                  + _interval(b["longest_interval_before_plugging"], b)
                  + (" with only the tubes at the limit plugged" if b["must_plug"]
                     else " with none plugged"))
    fit = result.inputs.get("calibration", {})
    if fit.get("method") == "hierarchical":
        low, high = fit["factor_interval_90"]
        console.print(f"calibrated bundle factor (hierarchical, NDD censored): median "
                      f"{fit['factor_median']:.3g}, 90 % [{low:.3g}, {high:.3g}]"
                      + (f"; groups {', '.join(fit['groups'])}" if fit.get("groups") else ""))
    sample = b["inspection_sample"]
    console.print(f"next inspection sample ({len(sample)} tube(s), {b['share']:.0%} of the "
                  f"risk): {', '.join(sample[:20])}{' ...' if len(sample) > 20 else ''}")
    f = result.fit
    if f.get("indications"):
        console.print(f"predicted against measured: {f['indications']} indications, "
                      f"{f['coverage']:.0%} inside the prediction's {f['level']:.0%} interval")
    if top:
        table = Table(title=f"the {min(top, len(result.tubes))} riskiest tubes of "
                            f"{len(result.tubes)}")
        for col in ("tube", "worst contact", "as found / wall", "end q50 / wall",
                    "P(exceed)", "plug", "reason"):
            table.add_column(col, justify="right" if col != "reason" else "left")
        for r in result.tubes.head(top).itertuples():
            table.add_row(r.tube, str(r.worst_contact), _pct(r.as_found_fraction),
                          _pct(r.end_fraction_q50), probability_text(r.p_exceed),
                          "yes" if r.plug else "", r.reason)
        console.print(table)
    if defaulted:
        console.print(f"illustrative technique values (not qualified) for {', '.join(defaulted)}"
                      ": give your technique's")
    console.print(f"tables in {output}" + (f", report {output / 'report.html'}"
                                            if with_report else ""))


def _interval(value: float, b: dict) -> str:
    if value == 0:
        return "none (the target is missed at the outage already)"
    if value >= b["horizon"]:
        return f"over {b['horizon']:g} {b['unit']} (the horizon searched)"
    return f"{value:.3g} {b['unit']}"


def _pct(x) -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{100 * x:.1f}%"
