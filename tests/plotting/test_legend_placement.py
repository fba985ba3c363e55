"""A legend never covers a figure's reference lines (the limit, the wall, a target): a new
user's trial found the TUBE_TUBE example's depth panel with its legend on the wall line.

Checked on the rendered figure (Agg): the legend's box [px] against each line's, the line's
box widened by half its drawn width; the geometry is matplotlib's own, not fretwear's.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from fretwear.plotting import plot_wear_history, plot_wear_table
from fretwear.plotting._common import legend_clear_of
from fretwear.workflows.case_files import run_case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _covers(fig, axis, lines) -> list[str]:
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    legend = axis.get_legend().get_window_extent(renderer)
    half = [line.get_linewidth() * fig.dpi / 72.0 / 2 for line in lines]
    return [line.get_label() for line, h in zip(lines, half, strict=True)
            if legend.overlaps(line.get_window_extent(renderer).padded(h))]


@pytest.fixture(scope="module")
def tube_tube():
    return run_case(EXAMPLES / "tube_tube.toml").table  # through the wall within 2 years


@pytest.mark.parametrize("plot", [plot_wear_table, plot_wear_history])
def test_the_depth_legend_is_off_the_limit_and_wall_lines(tube_tube, plot):
    fig = plot(tube_tube)
    axis = fig.axes[-1]
    marks = [line for line in axis.get_lines() if line.get_label().startswith(("limit",
                                                                               "wall"))]
    assert len(marks) == 2  # the example goes through the wall: both lines are drawn
    assert _covers(fig, axis, marks) == []


def test_a_crowded_axis_slides_the_legend_or_puts_it_beside():
    for gaps in ([0.3, 0.7], [0.2, 0.4, 0.6, 0.8], list(np.linspace(0.05, 0.95, 10))):
        fig = Figure(figsize=(6, 3))
        axis = fig.add_subplot()
        t = np.linspace(0, 1, 50)
        for k in range(6):
            axis.plot(t, t ** (k + 1), label=f"curve {k}")
        marks = [axis.axhline(y, color="k", label=f"line {y:.2f}") for y in gaps]
        legend_clear_of(axis, marks)
        assert _covers(fig, axis, marks) == [], gaps
        if len(gaps) == 10:  # no room inside: beside the axes, right of them
            renderer = fig.canvas.get_renderer()
            box = axis.get_legend().get_window_extent(renderer)
            assert box.x0 >= axis.get_window_extent(renderer).x1
