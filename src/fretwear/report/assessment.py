"""One self-contained HTML page of an outage's assessment (``fretwear assess --report``) or of
a finished bundle (``fretwear report OUT``): bad news first, the inputs and their provenance,
the tube-sheet maps, predicted against measured, the bundle's probability against the
operating interval, the plugging list and the inspection sample (tables sortable in the page,
no network), the worst tubes' fan charts. Figures are PNG data URIs.
"""

from __future__ import annotations

import datetime as _dt
import os
import platform
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import require
from fretwear._version import __version__
from fretwear.assessment.summary import probability_text
from fretwear.bundle.digest import limit_lines
from fretwear.flow.bundle import (
    NEAR_CRITICAL_FILE,
    instability_lines,
    near_critical_lines,
    recorded_unstable,
)
from fretwear.io.atomic import atomic_write
from fretwear.report.html import TEMPLATES, _table_html, figure_data_uri

__all__ = ["render_assessment_report", "render_bundle_report", "write_assessment_report",
           "write_bundle_report"]

_PURPOSE = "the assessment report"


def _env():
    jinja2 = require("jinja2", purpose=_PURPOSE)
    require("matplotlib.pyplot", purpose=_PURPOSE)
    return jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                              autoescape=jinja2.select_autoescape(["html", "j2"]),
                              undefined=jinja2.StrictUndefined)


def _meta() -> dict[str, Any]:
    return {"version": __version__, "python": platform.python_version(),
            "numpy": np.__version__,
            "generated": _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")}


def _tubes_table(tubes: pd.DataFrame, names) -> dict[str, Any]:
    frame = tubes[tubes["tube"].isin(list(names))][
        ["tube", "worst_contact", "as_found_fraction", "end_fraction_q50", "p_exceed",
         "reason"]].rename(columns={"as_found_fraction": "as found / wall [%]",
                                    "end_fraction_q50": "end median / wall [%]",
                                    "p_exceed": "P(exceed) [-]", "worst_contact": "worst contact"})
    return _table_html(frame, {"as found / wall [%]": (100.0, ".1f"),
                               "end median / wall [%]": (100.0, ".1f"),
                               "P(exceed) [-]": (1.0, ".3g")})


def _described(value) -> str:
    """An input as the report shows it: a technique's model in engineering units, with its
    units named (``describe()``: sizing error in mm, the POD as a50/a90 in mm), else str."""
    describe = getattr(value, "describe", None)
    return describe() if callable(describe) else str(value)


def render_assessment_report(result, *, title: str | None = None) -> str:
    """The HTML text of the report of an :class:`~fretwear.assessment.outage.Assessment`."""
    from fretwear.plotting.assessment import (
        assessment_map,
        plot_bundle_probability,
        plot_fan_charts,
        plot_predicted_vs_measured,
    )

    env = _env()
    b = result.bundle
    figures = [
        {"id": "map-found", "title": "Tube sheet as found (depth / wall, bands at the plugging "
                                     "limit and the wall; inspected ringed, plugged dotted)",
         "uri": figure_data_uri(assessment_map(result, "as_found"))},
        {"id": "map-end", "title": f"Tube sheet at the end of the interval ({b['interval']:g} "
                                   f"{b['unit']}): median depth / wall",
         "uri": figure_data_uri(assessment_map(result, "end"))},
        {"id": "map-probability", "title": "Tube sheet: probability of exceeding the limit by "
                                           "the end of the interval",
         "uri": figure_data_uri(assessment_map(result, "probability"))},
        {"id": "predicted", "title": "Predicted against measured (1:1 line, the prediction's "
                                     "90 % interval)",
         "uri": figure_data_uri(plot_predicted_vs_measured(result))},
        {"id": "probability", "title": "P(any tube past its limit) against the operating "
                                       "interval, with the target",
         "uri": figure_data_uri(plot_bundle_probability(result))},
        {"id": "fans", "title": "The riskiest tubes' worst contacts: depth after the outage",
         "uri": figure_data_uri(plot_fan_charts(result))}]
    inputs = [{"name": k, "value": _described(v)} for k, v in result.inputs.items()]
    context = {**_meta(), "title": title or "fretwear: outage assessment", "kind": "assessment",
               "bad_news": instability_lines(result.inputs.get("unstable_tubes"))
               + result.bad_news()
               + near_critical_lines(result.inputs.get("near_critical_tubes")), "b": b,
               "p_any": f"{b['p_any']:.3g}", "probability_line": result.probability_line(),
               "longest": f"{b['longest_interval']:.3g}",
               "after": probability_text(b["p_any_after_plugging"]), "inputs": inputs,
               "figures": figures, "fit": result.fit,
               "plugging": _tubes_table(result.tubes, b["plugging"]),
               "sample": _tubes_table(result.tubes, b["inspection_sample"]),
               "condition": _table_html(result.condition[
                   ["contact", "tube", "depth", "true_depth", "fraction", "p_past_limit"]],
                   {"depth": (1e3, ".3g"), "true_depth": (1e3, ".3g"),
                    "fraction": (100.0, ".1f"), "p_past_limit": (1.0, ".3g")})}
    return env.get_template("assessment.html.j2").render(**context)


def write_assessment_report(result, path: str | os.PathLike, *, title: str | None = None
                            ) -> Path:
    """Write the report of an assessment to ``path`` (one HTML file, atomically)."""
    return _write(render_assessment_report(result, title=title), path)


def render_bundle_report(bundle, *, title: str | None = None) -> str:
    """The HTML text of the report of a finished bundle (:func:`fretwear.bundle.load`): its
    bad news, the tube-sheet map, the deepest contacts and their depth against time."""
    from fretwear.plotting.bundle import plot_tube_sheet, plot_worst_depths

    env = _env()
    summary = bundle.summary()
    out = bundle.output
    news = (instability_lines(recorded_unstable(out)) if out is not None else []) \
        + limit_lines(summary) \
        + (near_critical_lines(recorded_unstable(out, NEAR_CRITICAL_FILE)) if out is not None
           else [])
    figures = [{"id": "map", "title": "Tube sheet: worst contact per tube at the last instant",
                "uri": figure_data_uri(plot_tube_sheet(summary))},
               {"id": "worst", "title": "Depth against time of the deepest contacts",
                "uri": figure_data_uri(plot_worst_depths(bundle))}]
    top = summary.head(50)[["rank", "contact", "tube_row", "tube_column", "support", "power",
                            "depth", "depth_fraction", "limit_forecast"]]
    context = {**_meta(), "title": title or "fretwear: bundle results", "kind": "bundle",
               "bad_news": news, "b": {"contacts": len(summary)},
               "inputs": [{"name": k, "value": str(v)} for k, v in bundle.stats.items()]
               + [{"name": "output", "value": str(bundle.output)}],
               "figures": figures,
               "deepest": _table_html(top, {"depth": (1e3, ".4g"),
                                            "depth_fraction": (100.0, ".1f"),
                                            "power": (1.0, ".4g")})}
    return env.get_template("assessment.html.j2").render(**context)


def write_bundle_report(bundle, path: str | os.PathLike, *, title: str | None = None) -> Path:
    """Write the report of a finished bundle to ``path`` (one HTML file, atomically)."""
    return _write(render_bundle_report(bundle, title=title), path)


def _write(text: str, path) -> Path:
    target = Path(path)
    with atomic_write(target, encoding="utf-8") as handle:
        handle.write(text)
    return target
