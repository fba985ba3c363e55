"""One self-contained HTML page of an analysis: inputs, coefficients and their sources, the
version, warnings, tables, figures (PNG embedded as base64), confidence and exceedance.

The page is rendered from the jinja2 template ``fretwear/report/templates/report.html.j2``
(package data; extra ``report``); it needs no file beside it and no network.
"""

from __future__ import annotations

import base64
import datetime as _dt
import io
import math
import os
import platform
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import require
from fretwear._version import __version__
from fretwear.io.atomic import atomic_write
from fretwear.plotting import plot_sector_wear, plot_wear_table
from fretwear.plotting.uncertainty import plot_calibration, plot_fan_chart, plot_sensitivity
from fretwear.report.analysis import Analysis
from fretwear.table import COLUMNS
from fretwear.uncertainty.sampling import index_intervals

__all__ = ["render_report", "write_report"]

TEMPLATES = Path(__file__).resolve().parent / "templates"
_PURPOSE = "fretwear report"


def figure_data_uri(fig, *, dpi: int = 110) -> str:
    """The figure as a ``data:image/png;base64,...`` URI (the figure is closed)."""
    pyplot = require("matplotlib.pyplot", purpose=_PURPOSE)
    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    finally:
        pyplot.close(fig)
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def _num(value: Any, fmt: str = ".4g") -> str:
    if value is None:
        return "-"
    try:
        x = float(value)
    except (TypeError, ValueError):
        return str(value)
    if math.isnan(x):
        return "-"
    if math.isinf(x):
        return "never" if x > 0 else "-inf"
    return format(x, fmt)


def _table_html(frame: pd.DataFrame, formats: dict[str, tuple[float, str]] | None = None
                ) -> dict[str, Any]:
    """{"columns": [...], "rows": [[...]]} with numbers formatted (scale, format)."""
    formats = formats or {}
    rows = []
    for _, row in frame.iterrows():
        cells = []
        for col in frame.columns:
            scale, fmt = formats.get(col, (1.0, ".4g"))
            value = row[col]
            if isinstance(value, int | float | np.integer | np.floating) and not isinstance(
                    value, bool):
                cells.append(_num(float(value) * scale, fmt))
            else:
                cells.append("-" if value is None else str(value))
        rows.append(cells)
    return {"columns": [str(c) for c in frame.columns], "rows": rows}


def _unit_label(column: str, time_unit: str | None = None) -> str:
    """``column [unit]``: lengths in mm, volumes in mm³, times in the case's unit (``year``),
    never the schema's placeholder "user time unit"."""
    unit = COLUMNS.get(column, (None, ""))[1]
    if unit == COLUMNS["instant"][1]:
        unit = time_unit or "time unit of the case"
    scale = {"m": " [mm]", "m³": " [mm³]"}.get(unit)
    return f"{column}{scale}" if scale else (f"{column} [{unit}]" if unit else column)


def _wear_tables(table: pd.DataFrame, time_unit: str) -> dict[str, Any]:
    label = lambda c: _unit_label(c, time_unit)  # noqa: E731
    scales = {c: (1e3, ".4g") for c, (_, u, _) in COLUMNS.items() if u == "m"}
    scales.update({c: (1e9, ".4g") for c, (_, u, _) in COLUMNS.items() if u == "m³"})
    glob_cols = [c for c in ("instant", "power", "volume_mobile", "volume_obstacle",
                             "depth_mobile", "depth_obstacle", "wall_fraction",
                             "limit_instant") if c in table.columns]
    glob = table.drop_duplicates("instant")[glob_cols]
    out = {"global": _table_html(glob.rename(columns=label),
                                 {label(c): scales.get(c, (1.0, ".4g"))
                                  for c in glob_cols}),
           "sectors": None, "sector_instant": None}
    if "sector" in table.columns and table["sector"].notna().any():
        last = table[table["instant"] == table["instant"].iloc[-1]]
        cols = [c for c in ("sector", "angle_start", "angle_end", "sector_power",
                            "volume_mobile_cumulated", "depth_mobile_sector",
                            "depth_obstacle_sector", "wall_fraction_sector",
                            "limit_instant_sector") if c in last.columns]
        out["sectors"] = _table_html(last[cols].rename(columns=label),
                                     {label(c): scales.get(c, (1.0, ".4g"))
                                      for c in cols})
        out["sector_instant"] = _num(last["instant"].iloc[0])
    return out


def _coefficients(attrs: dict, case) -> list[dict[str, str]]:
    """Every coefficient of both bodies with its value, unit and source (as the run resolved
    them: ``attrs``, provenance), and the ``case``'s sector coefficients."""
    law = case.wear_law
    sources = attrs.get("coefficient_sources") or {}
    rows = []
    for body in ("mobile", "obstacle"):
        coefs = attrs.get(f"coefficients_{body}") or {}
        for name, value in coefs.items():
            if value is None:
                continue
            rows.append({"body": body, "name": name,
                         "keyword": law.aster_keywords.get(name, ""),
                         "value": _num(value, ".6g"), "unit": law.units.get(name, ""),
                         "source": str(sources.get(f"{body}.{name}", "user"))})
    for j, pair in enumerate(case.sector_coefficients or [], start=1):
        rows.append({"body": f"sector {j}", "name": "coefficient (mobile, obstacle)",
                     "keyword": "COEF_USUR_MOBILE/OBST", "unit": "Pa⁻¹", "source": "user",
                     "value": ", ".join(_num(v, ".6g") for v in pair)})
    return rows


def _inputs(analysis: Analysis) -> list[dict[str, str]]:
    rows = []
    for section, keys in analysis.case.case.items():
        if section.startswith("_"):
            continue
        if isinstance(keys, dict):
            for key, value in keys.items():
                rows.append({"section": section, "key": key, "value": str(value)})
        else:
            rows.append({"section": "", "key": section, "value": str(keys)})
    return rows


def _sobol_table(indices: pd.DataFrame) -> pd.DataFrame:
    """The Sobol' indices as computed, each beside its 95 % interval cut to [0, 1]."""
    bounds = index_intervals(indices)
    return pd.DataFrame({
        "variable": indices.index, "first": indices["first"], "first_conf": indices["first_conf"],
        "first low": bounds["first_low"], "first high": bounds["first_high"],
        "total": indices["total"], "total_conf": indices["total_conf"],
        "total low": bounds["total_low"], "total high": bounds["total_high"]})


def _uncertainty(analysis: Analysis, unit: str) -> dict[str, Any] | None:
    mc = analysis.uncertainty
    if mc is None:
        return None
    quant = mc.quantiles([0.05, 0.5, 0.95])
    frame = pd.DataFrame({"instant": mc.instants, "nominal [mm]": mc.nominal_depth * 1e3,
                          "5 % [mm]": quant[0.05].to_numpy() * 1e3,
                          "median [mm]": quant[0.5].to_numpy() * 1e3,
                          "95 % [mm]": quant[0.95].to_numpy() * 1e3})
    if mc.limit is not None:
        ex = mc.exceedance()
        frame["P(depth > limit)"] = ex["probability"].to_numpy()
        frame["± (1σ)"] = ex["standard_error"].to_numpy()
    out = {"samples": mc.samples, "method": mc.method, "seed": mc.seed, "depth_of": mc.depth_of,
           "variables": [{"label": v.label, "distribution": v.describe()}
                         for v in mc.variables],
           "table": _table_html(frame),
           "sobol": _table_html(_sobol_table(mc.sensitivity())),
           "limit": None if mc.limit is None else _num(mc.limit * 1e3),
           "fan": figure_data_uri(plot_fan_chart(mc, unit=unit)),
           "sobol_figure": figure_data_uri(plot_sensitivity(mc)),
           "time_to_limit": None, "last_exceedance": None, "last_instant": None}
    if mc.limit is not None:
        tq = mc.time_to_limit_quantiles([0.05, 0.5, 0.95])
        out["time_to_limit"] = {f"{100 * q:g} %": _num(v) for q, v in tq.items()}
        last = mc.exceedance()["probability"].iloc[-1]
        out["last_exceedance"] = _num(last, ".3g")
        out["last_instant"] = _num(mc.instants[-1])
    return out


def _in_mm(frame: pd.DataFrame, columns) -> pd.DataFrame:
    """A copy with the depth ``columns`` [m] in mm and ``[mm]`` in their names, in place."""
    out = frame.copy()
    for col in columns:
        out[col] = out[col] * 1e3
    return out.rename(columns={c: f"{c} [mm]" for c in columns})


def _calibration(analysis: Analysis) -> dict[str, Any] | None:
    cal = analysis.calibration
    if cal is None:
        return None
    low, high = cal.factor_interval(0.95)
    obs = _in_mm(cal.observations, ("depth", "prior_depth", "posterior_depth"))
    out = {"method": cal.method, "prior": str(cal.prior),
           "median": _num(cal.factor_median), "low": _num(low), "high": _num(high),
           "sigma": _num(cal.posterior.sigma_ln, ".3g"),
           "observations": _table_html(obs),
           "figure": figure_data_uri(plot_calibration(cal)), "predictive": None}
    if cal.predictive is not None:
        pred = cal.predictive
        out["predictive"] = _table_html(_in_mm(pred, [c for c in pred.columns
                                                      if c.startswith("depth") or c == "limit"]))
    return out


def render_report(analysis: Analysis, *, title: str | None = None) -> str:
    """The HTML text of the report of ``analysis`` (:func:`fretwear.report.analyse_case`)."""
    jinja2 = require("jinja2", purpose=_PURPOSE)
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                             autoescape=jinja2.select_autoescape(["html", "j2"]),
                             undefined=jinja2.StrictUndefined)
    result = analysis.case
    table, case = result.table, result.wear_case  # the case the table was computed from
    attrs = table.attrs  # the computation's outputs: coefficients resolved, through-wall
    unit = case.time_label
    figures = [{"title": "Worn volumes and global depths against time",
                "uri": figure_data_uri(plot_wear_table(table))}]
    if "sector" in table.columns and table["sector"].notna().any():
        figures.append({"title": "Sector wear power and sector depths at the last instant",
                        "uri": figure_data_uri(plot_sector_wear(table))})
    power = result.power
    context = {
        "title": title or case.name or "fretwear report",
        "version": __version__,
        "generated": _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "python": platform.python_version(), "numpy": np.__version__,
        "source": analysis.source,
        "contact_type": case.contact_type, "law": case.law,
        "dimensions": {k: _num(v, ".6g") for k, v in case.dimensions.items()},
        "time_unit": unit, "time_scale": _num(case.time_scale, ".6g"),
        "wall": None if case.wall.thickness is None else _num(case.wall.thickness * 1e3),
        "depth_limit": _num(100 * case.wall.limit, "g"),
        "limit_instant": _num(table["limit_instant"].iloc[-1])
        if "limit_instant" in table.columns else None,
        "through_wall": {k: _num(v) for k, v in (attrs.get("through_wall") or {}).items()},
        "inputs": _inputs(analysis), "coefficients": _coefficients(attrs, case),
        "power": _num(result.total_power, ".6g"),
        "interval": None if analysis.interval is None else str(analysis.interval),
        "interval_obj": analysis.interval,
        "blocks": [] if not hasattr(power, "blocks") else [_num(b) for b in power.blocks],
        "sector_intervals": [{"name": iv.name, "estimate": _num(iv.estimate),
                              "half": _num(iv.half_width, ".2g")}
                             for iv in analysis.sector_intervals],
        "tables": _wear_tables(table, unit), "figures": figures,
        "uncertainty": _uncertainty(analysis, unit),
        "calibration": _calibration(analysis),
        "options": analysis.options,
        "warnings": list(dict.fromkeys([*result.warnings, *analysis.warnings])),
    }
    return env.get_template("report.html.j2").render(**context)


def write_report(analysis: Analysis, path: str | os.PathLike, *, title: str | None = None
                 ) -> Path:
    """Write the report of ``analysis`` to ``path`` (one HTML file, atomically)."""
    text = render_report(analysis, title=title)
    target = Path(path)
    with atomic_write(target, encoding="utf-8") as handle:
        handle.write(text)
    return target
