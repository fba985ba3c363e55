"""Sobol' indices are fractions of the output's variance, in [0, 1]; their estimators and the
symmetric bootstrap interval S ± z·σ are not bounded (a new user's trial: a one-variable
propagation drew the interval of its bars up to 1.2). The figure draws the interval cut to
[0, 1] and says so in its legend; the estimates themselves are left as computed.

Independent sources: the analytic indices of a model with one random input (S_1 = S_T,1 = 1:
the input carries all the variance, by the definition of the variance decomposition), the
table of :meth:`UncertaintyResult.sensitivity` (the estimator's values and half-widths, cut
here by hand), and the rendered Agg boxes of matplotlib for the legend.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.transforms import Bbox

from fretwear.errors import InputError
from fretwear.plotting.uncertainty import plot_sensitivity
from fretwear.uncertainty import LogNormal, index_intervals, monte_carlo

CASE = {"contact_type": "TUBE_BAV", "instants": [1.0, 10.0], "time_scale": 3.15e7,
        "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
        "coefficients": {"coefficient": 9.2e-15}, "wall_thickness": 1.09e-3}


@pytest.fixture(scope="module")
def one_input():
    return monte_carlo(CASE, 0.01, factor=LogNormal(1.0, sigma_ln=0.5), samples=256)


def _drawn_intervals(axis) -> list[tuple[float, float, float]]:
    """(x, bottom, top) [data] of every error bar drawn on ``axis``."""
    out = []
    for collection in axis.collections:
        if isinstance(collection, LineCollection):
            for seg in collection.get_segments():
                if np.isclose(seg[0, 0], seg[-1, 0]):  # vertical: the bar, not a cap
                    out.append((float(seg[0, 0]), float(seg[:, 1].min()),
                                float(seg[:, 1].max())))
    return sorted(out)


def test_a_lone_inputs_interval_is_drawn_inside_0_1_and_said_clipped(one_input):
    table = one_input.sensitivity()
    s, h = table.iloc[0][["first", "first_conf"]], table.iloc[0][["total", "total_conf"]]
    assert s.iloc[0] + s.iloc[1] > 1.0 and h.iloc[0] + h.iloc[1] > 1.0  # the case of the trial
    assert abs(table["first"].iloc[0] - 1.0) < 0.05  # the analytic 1, within sampling error
    fig = plot_sensitivity(one_input)
    axis = fig.axes[0]
    drawn = _drawn_intervals(axis)
    assert len(drawn) == 2  # first, total
    expected = [(max(0.0, v - w), min(1.0, v + w)) for v, w in (s, h)]
    for (_, low, high), (lo, hi) in zip(drawn, expected, strict=True):
        assert high <= 1.0 + 1e-12 and low >= -1e-12
        assert low == pytest.approx(lo, abs=1e-12) and high == pytest.approx(hi, abs=1e-12)
    labels = [t.get_text() for t in axis.get_legend().get_texts()]
    assert "95 % bootstrap interval, clipped to [0, 1]" in labels, labels
    # the bars are the estimates as computed, not cut
    heights = sorted(p.get_height() for p in axis.patches)
    assert heights == pytest.approx(sorted([s.iloc[0], h.iloc[0]]), abs=1e-12)


def test_an_interval_inside_0_1_is_drawn_as_computed_and_not_said_clipped():
    table = pd.DataFrame({"first": [0.7, 0.2], "first_conf": [0.05, 0.02],
                          "total": [0.77, 0.3], "total_conf": [0.04, 0.03]},
                         index=["coefficient", "power"])
    axis = plot_sensitivity(table).axes[0]
    drawn = [bound for _, lo, hi in _drawn_intervals(axis) for bound in (lo, hi)]
    # bars in x order: coefficient first, coefficient total, power first, power total
    assert drawn == pytest.approx([0.65, 0.75, 0.73, 0.81, 0.18, 0.22, 0.27, 0.33], abs=1e-12)
    labels = [t.get_text() for t in axis.get_legend().get_texts()]
    assert "95 % bootstrap interval" in labels and not any("clipped" in x for x in labels)


def test_index_intervals_cut_by_hand():
    table = pd.DataFrame({"first": [0.99, -0.004, 0.5], "first_conf": [0.2, 0.01, np.nan],
                          "total": [1.003, 0.002, 0.6], "total_conf": [0.13, 0.001, 0.1]},
                         index=["a", "b", "c"])
    got = index_intervals(table)
    np.testing.assert_allclose(got["first_low"], [0.79, 0.0, np.nan], atol=1e-12)
    np.testing.assert_allclose(got["first_high"], [1.0, 0.006, np.nan], atol=1e-12)
    np.testing.assert_allclose(got["total_low"], [0.873, 0.001, 0.5], atol=1e-12)
    np.testing.assert_allclose(got["total_high"], [1.0, 0.003, 0.7], atol=1e-12)
    assert got["clipped"].tolist() == [True, True, False]
    assert table["total"].tolist() == [1.003, 0.002, 0.6]  # the estimates are not touched
    with pytest.raises(InputError, match="'total'"):
        index_intervals(table.drop(columns="total"))


def test_the_legend_covers_no_bar_nor_interval(one_input):
    fig = plot_sensitivity(one_input)
    axis = fig.axes[0]
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    legend = axis.get_legend().get_window_extent(renderer)
    covered = [p for p in axis.patches if legend.overlaps(p.get_window_extent(renderer))]
    for x, low, high in _drawn_intervals(axis):  # the error bars, capped ends included
        (x0, y0), (x1, y1) = axis.transData.transform([(x, low), (x, high)])
        if legend.overlaps(Bbox.from_extents(x0 - 4, y0 - 2, x1 + 4, y1 + 2)):
            covered.append((x, low, high))
    assert len(axis.patches) == 2 and covered == []
