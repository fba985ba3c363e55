"""fretwear.plotting.uncertainty as the other figure modules: each function returns the Figure,
draws in the ``ax=`` it is given, accepts an empty Figure, and leaves the backend alone; the fan
chart's bands are the result's quantiles."""

from __future__ import annotations

import warnings

import matplotlib
import numpy as np
import pandas as pd
import pytest
from matplotlib.figure import Figure

from fretwear.errors import InputError
from fretwear.plotting import uncertainty as figures
from fretwear.table import wear_table
from fretwear.uncertainty import LogNormal, calibrate, monte_carlo

CASE = {"contact_type": "TUBE_BAV", "instants": [1.0, 5.0, 10.0, 20.0], "time_scale": 3.15e7,
        "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
        "coefficients": {"coefficient": 9.2e-15}, "wall_thickness": 1.09e-3}


@pytest.fixture(scope="module")
def data():
    mc = monte_carlo(CASE, 0.01, factor=LogNormal(1.0, sigma_ln=0.6),
                     power_scatter=LogNormal(sigma_ln=0.2), samples=512)
    table = wear_table(0.01, **{k: v for k, v in CASE.items() if k != "wall_thickness"})
    cal = calibrate(table, pd.DataFrame({"instant": [5.0, 10.0], "depth": [3e-4, 4.5e-4]}))
    return {"mc": mc, "cal": cal}


CASES = {
    "plot_fan_chart": (lambda d, ax: figures.plot_fan_chart(d["mc"], ax=ax), 1),
    "plot_sensitivity": (lambda d, ax: figures.plot_sensitivity(d["mc"], ax=ax), 1),
    "plot_calibration": (lambda d, ax: figures.plot_calibration(d["cal"], ax=ax), 2),
}


def test_every_function_is_checked():
    assert {n for n in dir(figures) if n.startswith("plot_")} == set(CASES)


def _artists(ax) -> int:
    return len(ax.lines) + len(ax.patches) + len(ax.collections) + len(ax.texts)


@pytest.mark.parametrize("name", sorted(CASES))
def test_returns_a_figure_and_honours_ax(name, data):
    call, panels = CASES[name]
    backend = matplotlib.get_backend()
    fig = call(data, None)
    try:
        assert isinstance(fig, Figure) and len(fig.axes) >= panels
        assert all(_artists(ax) > 0 for ax in fig.axes[:panels])
    finally:
        matplotlib.pyplot.close(fig)
    own = Figure()
    axes = [own.add_subplot(1, panels, i + 1) for i in range(panels)]
    assert call(data, axes[0] if panels == 1 else axes) is own
    assert own.axes == axes and all(_artists(ax) > 0 for ax in axes)
    empty = Figure(figsize=(9, 5))
    assert call(data, empty) is empty and len(empty.axes) >= panels
    assert matplotlib.get_backend() == backend


def test_fan_chart_bands_are_the_quantiles(data):
    mc = data["mc"]
    fig = Figure()
    figures.plot_fan_chart(mc, ax=fig.add_subplot())
    ax = fig.axes[0]
    band = ax.collections[0]  # 5-95 %
    vertices = band.get_paths()[0].vertices
    q = mc.quantiles([0.05, 0.95]) * 1e3
    for i, t in enumerate(mc.instants):
        ys = vertices[np.isclose(vertices[:, 0], t), 1]
        assert np.isclose(ys.min(), q.iloc[i, 0]) and np.isclose(ys.max(), q.iloc[i, 1])
    labels = [line.get_label() for line in ax.lines]
    assert {"median", "nominal", "limit"} <= set(labels)
    limit = next(line for line in ax.lines if line.get_label() == "limit")
    assert limit.get_ydata()[0] == pytest.approx(0.4 * 1.09)


def test_bad_inputs():
    with pytest.raises(InputError, match="UncertaintyResult"):
        figures.plot_fan_chart(pd.DataFrame())
    with pytest.raises(InputError, match="'first'"):
        figures.plot_sensitivity(pd.DataFrame({"total": [0.1]}))


def test_fan_chart_names_the_sector_depth_whatever_the_contact_name():
    """The y label names the depth the result propagates (UncertaintyResult.depth_of), not a
    guess from the contact's name: a sector propagation of a contact called "R4C2" says
    "sector 2", a global one of a contact called "sector side" says "global"."""
    from fretwear.history import ContactHistory
    from fretwear.uncertainty import LogNormal, monte_carlo

    t = np.linspace(0, 2, 2001)
    angle = np.radians(150 * np.sin(3 * t))
    h = ContactHistory(time=t, normal_force=np.full(t.size, 2.0), vt1=np.full(t.size, 0.1),
                       vt2=np.zeros(t.size), dy=np.cos(angle), dz=np.sin(angle))
    case = {"contact_type": "TUBE_BAV", "instants": [1.0, 10.0], "time_scale": 3.15e7,
            "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
            "sectors": 4, "coefficients": {"coefficient": 9.2e-15}}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sector = monte_carlo(case, h, factor=LogNormal(1.0, sigma_ln=0.3), sector=2,
                             samples=32, name="R4C2")
        whole = monte_carlo(case, h, factor=LogNormal(1.0, sigma_ln=0.3), samples=32,
                            name="sector side")
    assert sector.depth_of == "sector 2" and whole.depth_of == "global"
    assert sector.to_dict()["depth_of"] == "sector 2"
    assert sector.summary().attrs["depth_of"] == "sector 2"
    label = figures.plot_fan_chart(sector, ax=Figure().add_subplot()).axes[0].get_ylabel()
    assert label == "sector 2 depth of the tube [mm]"
    label = figures.plot_fan_chart(whole, ax=Figure().add_subplot()).axes[0].get_ylabel()
    assert label == "global depth of the tube [mm]"
