"""Figures of an outage's assessment (:func:`fretwear.assessment.outage.assess`): predicted
against measured, the bundle's probability against the operating interval, the worst tubes'
fan charts, and the tube-sheet maps (:func:`fretwear.plotting.bundle.plot_tube_sheet`, the one
map). Each takes the :class:`~fretwear.assessment.outage.Assessment`, accepts ``ax=`` and
returns the Figure.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.plotting._common import figure_and_axes, legend_clear_of
from fretwear.plotting.bundle import plot_tube_sheet

__all__ = ["assessment_map", "plot_bundle_probability", "plot_fan_charts",
           "plot_predicted_vs_measured"]


def _check(result: Any) -> None:
    if not hasattr(result, "bundle") or not hasattr(result, "contacts"):
        raise InputError("give the Assessment of fretwear.assessment.outage.assess, not a "
                         f"{type(result).__name__}")


def assessment_map(result: Any, which: str = "as_found", *, ax: Any = None):
    """The tube sheet of an assessment: ``"as_found"`` (depth / wall), ``"end"`` (the median
    depth at the end of the interval / wall) or ``"probability"`` (P(exceeding the limit by
    the end of the interval)); inspected tubes ringed, plugged ones dotted."""
    _check(result)
    c = result.contacts
    limit = float(np.nanmedian(c["limit_depth"] / c["wall_thickness"]))
    frame = pd.DataFrame({"tube_row": c["tube_row"], "tube_column": c["tube_column"],
                          "inspected": c["state"].isin(["sized", "NDD"]),
                          "plugged": c["state"].eq("plugged"), "p_exceed": c["p_exceed"]})
    b = result.bundle
    if which == "probability":
        return plot_tube_sheet(frame, quantity="probability", target=b["target"], ax=ax,
                               title=f"P(exceeding the limit by {b['interval']:g} {b['unit']} "
                                     "after the outage)")
    column = {"as_found": "as_found", "end": "depth_end_q50"}.get(which)
    if column is None:
        raise InputError(f"which={which!r}: choose 'as_found', 'end' or 'probability'")
    frame["depth_fraction"] = c[column] / c["wall_thickness"]
    frame["depth"] = c[column]
    title = ("as found at the outage (sized, else the prediction's median)" if which ==
             "as_found" else f"median depth after {b['interval']:g} {b['unit']}")
    return plot_tube_sheet(frame, quantity="fraction", limit=limit, ax=ax, title=title)


def plot_predicted_vs_measured(result: Any, *, ax: Any = None):
    """Every sized indication: the measurement [mm] against the prediction's median [mm], the
    prediction's 90 % interval as a bar, and the 1:1 line."""
    _check(result)
    p = result.predictions
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(1, 1, 1)],
                                      figsize=(6, 5), what="plot_predicted_vs_measured")
    if len(p):
        x, y = p["predicted"] * 1e3, p["measured"] * 1e3
        axis.errorbar(x, y, xerr=[x - p["low"] * 1e3, p["high"] * 1e3 - x], fmt="o",
                      color="C0", ecolor="0.6", capsize=2, label="indication (bar: 90 %)")
        top = float(max(y.max(), (p["high"] * 1e3).max())) * 1.05
        axis.plot([0, top], [0, top], "--", color="0.3", lw=1, label="1:1")
        axis.set_xlim(0, top)
        axis.set_ylim(0, top)
        f = result.fit
        axis.set_title(f"{f['indications']} indications, {f['coverage']:.0%} inside the "
                       f"{f['level']:.0%} interval")
    else:
        axis.set_title("no sized indication")
    axis.set_xlabel("predicted measurement [mm]")
    axis.set_ylabel("measured depth [mm]")
    axis.set_aspect("equal", adjustable="box")
    if len(p):
        axis.apply_aspect()  # the box the legend is placed in
        legend_clear_of(axis, [], fontsize="small")  # on no indication nor its bar
    return fig


def plot_bundle_probability(result: Any, *, ax: Any = None):
    """P(any tube past its limit) against the operating interval, after the plugging list
    (solid) and with only the tubes at the limit as measured plugged (dashed), the target, the
    asked interval and the longest interval under the target after plugging."""
    _check(result)
    b, curve = result.bundle, result.curve
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(1, 1, 1)],
                                      figsize=(7, 4.5), what="plot_bundle_probability")
    axis.plot(curve["interval"], curve["p_any"], color="C0", lw=2,
              label="P(any tube past limit), plugging list plugged")
    if "p_any_before_plugging" in curve:
        axis.plot(curve["interval"], curve["p_any_before_plugging"], color="C0", lw=1,
                  ls="--", label="before plugging")
    marks = [axis.axhline(b["target"], color="C3", ls="--", label=f"target {b['target']:g}"),
             axis.axvline(b["interval"], color="0.4", ls=":",
                          label=f"asked {b['interval']:g} {b['unit']}")]
    if 0 < b["longest_interval"] < b["horizon"]:
        marks.append(axis.axvline(b["longest_interval"], color="C2", ls="-.",
                                  label=f"longest {b['longest_interval']:.3g} {b['unit']}"))
    axis.set_yscale("log")
    low = max(float(curve["p_any"][curve["p_any"] > 0].min()) if (curve["p_any"] > 0).any()
              else 1e-6, 1e-12)  # the plugged curve lies under the other
    axis.set_ylim(low / 2, 1.0)
    axis.set_xlabel(f"operating interval after the outage [{b['unit']}]")
    axis.set_ylabel("probability [-]")
    axis.grid(alpha=0.3, which="both")
    legend_clear_of(axis, marks, fontsize="small")  # not on the target or the intervals
    return fig


def plot_fan_charts(result: Any, *, count: int = 4, ax: Any = None):
    """The ``count`` riskiest tubes' worst contacts: depth [mm] after the outage, median and
    5-95 % band, with the plugging limit; one panel each."""
    _check(result)
    tubes = result.tubes[~result.tubes["plugged"]].head(count)
    n = max(len(tubes), 1)
    cols = min(n, 2)
    rows = -(-n // cols)

    def layout(f):
        return list(np.atleast_1d(f.subplots(rows, cols, squeeze=False).ravel()[:n]))

    fig, axes, own = figure_and_axes(ax, n, layout, figsize=(5.5 * cols, 3.6 * rows),
                                     what="plot_fan_charts")
    b = result.bundle
    grid = np.linspace(0.0, b["horizon"], 21)
    marks = []
    for axis, row in zip(axes, tubes.itertuples(), strict=False):
        q = result.fan(row.worst_contact, grid) * 1e3
        axis.fill_between(grid, q[:, 0], q[:, 2], color="C0", alpha=0.25, label="5-95 %")
        axis.plot(grid, q[:, 1], color="C0", label="median")
        limit = result.contacts.set_index("contact").loc[row.worst_contact, "limit_depth"]
        marks.append([axis.axhline(limit * 1e3, color="C3", ls="--", label="plugging limit"),
                      axis.axvline(b["interval"], color="0.4", ls=":")])
        axis.set_title(f"{row.tube} ({row.worst_contact}): P = {row.p_exceed:.2g}",
                       fontsize="medium")
        axis.set_xlabel(f"after the outage [{b['unit']}]")
        axis.set_ylabel("depth [mm]")
        axis.grid(alpha=0.3)
    if own:
        fig.tight_layout()
    if len(tubes):  # once the layout is final: not on the limit line
        legend_clear_of(axes[0], marks[0], fontsize="small")
    return fig
