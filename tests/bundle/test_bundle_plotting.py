"""Figures of a bundle (fretwear.plotting.bundle): each returns its Figure, draws in a given
Axes, leaves the backend alone, and shows the numbers of the results."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.errors import InputError

matplotlib = pytest.importorskip("matplotlib")
from matplotlib.figure import Figure  # noqa: E402

from fretwear.plotting.bundle import (  # noqa: E402
    plot_power_distribution,
    plot_tube_sheet,
    plot_worst_depths,
)


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    directory = tmp_path_factory.mktemp("plots")
    manifest, case = write_bundle(directory, oscillator(), 4,
                                  extra={"wall_thickness_m": [1.09e-3] * 4})
    frame = pd.read_csv(manifest)
    # a second support on tube (1, 1): the map shows the deeper of its two contacts
    extra = frame.iloc[[3]].assign(contact="R1C1-AVB2", tube_row=1, tube_column=1)
    pd.concat([frame, extra]).to_csv(manifest, index=False)
    return run_bundle(manifest, case, scheduler="serial")


def test_each_figure_returns_its_figure_and_keeps_the_backend(result):
    backend = matplotlib.get_backend()
    for fig in (plot_tube_sheet(result), plot_power_distribution(result),
                plot_worst_depths(result, count=3)):
        assert isinstance(fig, Figure)
        matplotlib.pyplot.close(fig)
    assert matplotlib.get_backend() == backend


def test_given_axes_are_used(result):
    fig = Figure()
    axes = fig.subplots(1, 3)
    assert plot_tube_sheet(result, ax=axes[0]) is fig
    assert plot_power_distribution(result, ax=axes[1]) is fig
    assert plot_worst_depths(result, ax=axes[2]) is fig
    assert axes[2].get_ylabel() == "global depth of the tube [mm]"  # which depth (issue 12)
    assert len(axes[2].get_lines()) >= 5  # one line per contact (+ the limit line)


def test_tube_sheet_colours_the_worst_contact_of_each_tube(result):
    fig = Figure()
    plot_tube_sheet(result, ax=fig.subplots())
    squares = fig.axes[0].collections[0]
    xy = squares.get_offsets()
    values = dict(zip(map(tuple, np.asarray(xy).tolist()), squares.get_array(), strict=True))
    s = result.summary()
    worst = s.groupby(["tube_column", "tube_row"])["depth_fraction"].max() * 100
    assert len(values) == 4  # four tubes, five contacts
    for (col, row), v in worst.items():
        assert values[(float(col), float(row))] == pytest.approx(v, rel=1e-12)
    assert values[(1.0, 1.0)] == pytest.approx(
        100 * s.set_index("contact").loc["R1C1-AVB2", "depth_fraction"], rel=1e-12)


def test_power_distribution_counts_every_contact(result):
    fig = plot_power_distribution(result, bins=5)
    counts = sum(p.get_height() for p in fig.axes[0].patches)
    assert counts == len(result.summary())
    matplotlib.pyplot.close(fig)


def test_tube_sheet_needs_positions():
    with pytest.raises(InputError, match="tube_row"):
        plot_tube_sheet(pd.DataFrame({"depth": [1e-4], "tube_column": [1]}))
