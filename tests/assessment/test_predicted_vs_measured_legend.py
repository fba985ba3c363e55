"""The predicted-against-measured scatters (the assessment's and the calibration's) put their
legend on no data point (a new user's trial: the assessment's legend, fixed upper left, sat on
the deepest indication when it was under-predicted, the usual case of a campaign that calibrates
the wear factor up).

Checked on the rendered figure (Agg): the legend's box [px] against each indication's marker
box (its centre ± half the marker size) and each point of its interval bars; the geometry is
matplotlib's own, not fretwear's (as tests/plotting/test_legend_placement.py).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import synthetic
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.transforms import Bbox

from fretwear.assessment import LogisticPOD, SizingModel
from fretwear.assessment.growth import FactorNodes
from fretwear.assessment.outage import assess
from fretwear.plotting.assessment import plot_predicted_vs_measured
from fretwear.plotting.uncertainty import plot_calibration
from fretwear.table import wear_table
from fretwear.uncertainty import calibrate

POWERS = [0.02, 0.05, 0.08, 0.11, 0.03, 0.06, 0.09, 0.12, 0.04]


def _covered(fig, axis) -> list[str]:
    """What of ``axis``'s data the legend covers: markers (by their size) and bar points."""
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    legend = axis.get_legend().get_window_extent(renderer)
    px = fig.dpi / 72.0
    out = []
    for line in axis.get_lines():
        if line.get_marker() in (None, "", " ", "None", "none"):
            continue  # the 1:1 line
        h = line.get_markersize() * px / 2
        for x, y in line.get_transform().transform(line.get_xydata()):
            if legend.overlaps(Bbox.from_extents(x - h, y - h, x + h, y + h)):
                out.append(f"marker at {x:.0f}, {y:.0f} px")
    for collection in axis.collections:
        for seg in getattr(collection, "get_segments", list)():
            ends = collection.get_transform().transform(np.asarray(seg, dtype=float))
            box = Bbox.from_extents(*ends.min(axis=0), *ends.max(axis=0)).padded(0.5)
            if legend.overlaps(box):
                out.append(f"bar {ends.round().tolist()}")
    return out


@pytest.fixture(scope="module")
def assessed():
    """Four sized indications, the deepest (0.65 mm) measured five times its prediction: the
    top left of the scatter, where the legend used to be."""
    tubes = [(r, c) for r in (1, 2, 3) for c in (1, 2, 3)]
    insp = pd.DataFrame({"contact": ["c7", "c8", "c2", "c1"], "instant": [10.0] * 4,
                         "depth": [3.0e-4, 3.6e-4, 1.2e-4, 6.5e-4], "result": [""] * 4})
    return assess(synthetic.bundle(POWERS, tubes), insp, interval=2.0,
                  sizing=SizingModel(0.0, 1.0, 5e-5),
                  pod=LogisticPOD.from_depths(1.5e-4, 3e-4),
                  posterior=FactorNodes([0.0], [1.0], contact_sigma=0.3))


def test_the_assessment_scatter_legend_is_on_no_indication(assessed):
    p = assessed.predictions
    top = p.loc[p["measured"].idxmax()]
    assert top["measured"] > 4 * top["predicted"]  # the case of the trial: top left
    fig = plot_predicted_vs_measured(assessed)
    assert _covered(fig, fig.axes[0]) == []


@pytest.mark.parametrize("depths", [[4e-4, 9e-4, 1.5e-4], [2e-4, 2.5e-4, 6e-4]])
def test_the_calibration_scatter_legend_is_on_no_inspection(depths):
    table = wear_table(0.01, contact_type="TUBE_BAV", instants=[2.0, 5.0, 10.0],
                       time_scale=3.15e7, dimensions={"mobile_radius": 9.525e-3,
                                                      "obstacle_width": 12.7e-3},
                       coefficients={"coefficient": 9.2e-15})
    result = calibrate(table, pd.DataFrame({"instant": [2.0, 5.0, 10.0], "depth": depths}))
    fig = plot_calibration(result)
    assert _covered(fig, fig.axes[1]) == []
