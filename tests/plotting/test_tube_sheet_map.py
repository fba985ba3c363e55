"""The one tube-sheet map (issue 26, point 5): discrete bands at the plugging limit and the
wall, probabilities in bands up to the target, inspected and plugged tubes marked, for the
bundle, the calibration and the assessment alike."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from fretwear.errors import InputError  # noqa: E402
from fretwear.plotting.bundle import plot_tube_sheet  # noqa: E402


def _frame():
    return pd.DataFrame({"tube_row": [1, 1, 2, 2], "tube_column": [1, 2, 1, 2],
                         "depth": [1e-4, 4.5e-4, 1.2e-3, 2e-4],
                         "depth_fraction": [0.09, 0.41, 1.1, 0.39],
                         "p_exceed": [1e-7, 0.02, 1.0, 0.06],
                         "inspected": [True, True, False, False],
                         "plugged": [False, False, False, True]})


def test_fraction_bands_change_colour_at_the_limit_and_the_wall():
    fig = plot_tube_sheet(_frame(), quantity="fraction", limit=0.4)
    mesh = fig.axes[0].collections[0]
    colours = mesh.cmap(mesh.norm(np.array([39.0, 41.0, 99.0, 101.0])))
    assert not np.allclose(colours[0], colours[1])   # 39 % and 41 %: across the limit
    assert np.allclose(colours[1], colours[2])       # 41 % and 99 %: one band
    assert not np.allclose(colours[2], colours[3])   # across the wall
    assert list(mesh.norm.boundaries[:6]) == [0, 10, 20, 30, 40, 100]


def test_probability_bands_edge_at_the_target():
    fig = plot_tube_sheet(_frame(), quantity="probability", target=0.05)
    norm = fig.axes[0].collections[0].norm
    assert 0.05 in list(norm.boundaries)
    assert norm(0.049) != norm(0.051)


def test_inspected_and_plugged_tubes_are_marked_and_keyed():
    fig = plot_tube_sheet(_frame(), quantity="fraction")
    axis = fig.axes[0]
    offsets = [c.get_offsets().tolist() for c in axis.collections[1:]
               if hasattr(c, "get_offsets") and len(c.get_offsets())]
    assert [[1.0, 1.0], [2.0, 1.0]] in offsets    # ringed: (column, row) of the inspected
    assert [[2.0, 2.0]] in offsets                # the plugged tube's dot
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert any("inspected (2 tubes)" in t for t in texts)
    assert any("plugged (1 tube)" in t for t in texts)


def test_a_missing_probability_column_is_named():
    with pytest.raises(InputError, match="p_exceed"):
        plot_tube_sheet(_frame().drop(columns="p_exceed"), quantity="probability")
