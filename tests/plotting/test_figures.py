"""fretwear.plotting as python-control's plotting: every function returns the Figure, draws in the
``ax=`` it is given (same figure returned, its artists in those axes), and leaves matplotlib's
backend alone (never ``matplotlib.use``). Without matplotlib, the error names the extra."""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd
import pytest
from matplotlib.figure import Figure

from fretwear import plotting
from fretwear.errors import InputError, MissingDependencyError
from fretwear.history import ContactHistory
from fretwear.obstacle import CircleObstacle, Mobile, update_obstacle
from fretwear.workflows.case_files import run_case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
RM, GAP, WALL, WIDTH = 9.5e-3, 0.5e-3, 1.09e-3, 20e-3


@pytest.fixture(scope="module")
def sector_table():
    """The shipped TUBE_BAV example: a sector wear table (10 sectors, 4 instants)."""
    return run_case(EXAMPLES / "tube_bav.toml").table


@pytest.fixture(scope="module")
def obstacle_result():
    vm = np.zeros(10)
    vm[4] = 2e-10  # one sector worn [m³]
    return update_obstacle(CircleObstacle(RM, RM + GAP), Mobile(RM, WALL),
                           np.linspace(-180.0, 180.0, 11), vm, width=WIDTH, resolution=1.0)


@pytest.fixture(scope="module")
def history():
    t = np.linspace(0.0, 1.0, 201)
    phase = 2 * np.pi * 5 * t
    return ContactHistory(time=t, normal_force=np.maximum(np.sin(phase), 0.0),
                          vt1=0.01 * np.cos(phase), vt2=np.zeros_like(t),
                          dy=GAP * np.cos(phase), dz=GAP * np.sin(phase), name="N1")


@pytest.fixture(scope="module")
def summary():
    return pd.DataFrame({"cycle": [1, 2], "instant": [1.0, 2.0], "power": [0.1, 0.09],
                         "depth_mobile_max": [1e-5, 2e-5], "depth_obstacle_max": [0.0, 0.0]})


def _profiles():
    a = np.linspace(0.0, 360.0, 37)
    return [(a, np.full(a.shape, 5e-4)), (a, np.full(a.shape, 5.2e-4))]


#: name -> (call(data, ax), panels, indices of polar panels)
CASES = {
    "plot_wear_history": (lambda d, ax: plotting.plot_wear_history(d["table"], ax=ax), 1, ()),
    "plot_wear_table": (lambda d, ax: plotting.plot_wear_table(d["table"], ax=ax), 2, ()),
    "plot_sector_wear": (lambda d, ax: plotting.plot_sector_wear(d["table"], ax=ax), 2, (0, 1)),
    "plot_clearance": (lambda d, ax: plotting.plot_clearance(d["obstacle"], ax=ax), 1, (0,)),
    "plot_obstacle_depth": (lambda d, ax: plotting.plot_obstacle_depth(d["obstacle"], ax=ax),
                            1, ()),
    "plot_obstacle": (lambda d, ax: plotting.plot_obstacle(d["obstacle"], ax=ax), 2, (0,)),
    "plot_contact_history": (lambda d, ax: plotting.plot_contact_history(
        d["history"], profiles={"gap": _profiles()[0]}, ax=ax), 3, ()),
    "plot_iteration": (lambda d, ax: plotting.plot_iteration(d["summary"], _profiles(), ax=ax),
                       3, (2,)),
}


@pytest.fixture(scope="module")
def data(sector_table, obstacle_result, history, summary):
    return {"table": sector_table, "obstacle": obstacle_result, "history": history,
            "summary": summary}


def test_every_public_plotting_function_is_checked():
    public = {name for name in plotting.__all__ if name.startswith("plot_")}
    assert public == set(CASES)


def _artists(ax) -> int:
    return len(ax.lines) + len(ax.patches) + len(ax.collections) + len(ax.texts)


@pytest.mark.parametrize("name", sorted(CASES))
def test_returns_a_figure_with_its_panels(name, data):
    call, panels, polar = CASES[name]
    fig = call(data, None)
    try:
        assert isinstance(fig, Figure)
        assert len(fig.axes) >= panels
        assert all(_artists(ax) > 0 for ax in fig.axes[:panels])
        assert [i for i, ax in enumerate(fig.axes[:panels]) if ax.name == "polar"] == list(polar)
    finally:
        matplotlib.pyplot.close(fig)


@pytest.mark.parametrize("name", sorted(CASES))
def test_given_axes_are_honoured(name, data):
    """The user's axes receive the artists and their figure is returned; nothing else is
    added to it."""
    call, panels, polar = CASES[name]
    fig = Figure()  # not pyplot's: the function must not need a backend to draw in it
    axes = [fig.add_subplot(1, panels, i + 1, projection="polar" if i in polar else None)
            for i in range(panels)]
    before = [_artists(ax) for ax in axes]
    out = call(data, axes[0] if panels == 1 else axes)
    assert out is fig
    assert fig.axes == axes  # no new axes
    assert all(_artists(ax) > n for ax, n in zip(axes, before, strict=True))


@pytest.mark.parametrize("name", sorted(CASES))
def test_an_empty_figure_receives_the_panels(name, data):
    call, panels, _ = CASES[name]
    fig = Figure(figsize=(12, 6))
    assert call(data, fig) is fig
    assert len(fig.axes) >= panels and tuple(fig.get_size_inches()) == (12, 6)


def test_wrong_axes_are_refused(data):
    fig = Figure()
    one = fig.add_subplot()
    with pytest.raises(InputError, match=r"plot_wear_table draws 2 panel\(s\).*not 1 Axes"):
        plotting.plot_wear_table(data["table"], ax=[one])
    with pytest.raises(InputError, match="plot_clearance: panel 1 is a polar plot"):
        plotting.plot_clearance(data["obstacle"], ax=one)
    other = Figure().add_subplot()
    with pytest.raises(InputError, match="belong to 2 figures"):
        plotting.plot_obstacle(data["obstacle"], ax=[fig.add_subplot(projection="polar"), other])


def test_sector_figure_needs_a_sector_table(data):
    glob = data["table"].drop(columns=["sector"])
    with pytest.raises(InputError, match="needs a sector wear table"):
        plotting.plot_sector_wear(glob)
    figures = plotting.wear_figures(data["table"])
    assert list(figures) == ["history", "sectors"]
    for fig in figures.values():
        matplotlib.pyplot.close(fig)


def test_backend_is_left_alone(data, monkeypatch):
    """No function selects a backend: matplotlib.use is never called and the backend (and the
    rcParams entry) are the same after every function has run."""
    def forbidden(*args, **kwargs):
        raise AssertionError("a plotting function called matplotlib.use")

    backend, rc = matplotlib.get_backend(), matplotlib.rcParams["backend"]
    monkeypatch.setattr(matplotlib, "use", forbidden)
    monkeypatch.setattr(matplotlib.pyplot, "switch_backend", forbidden)
    for call, _, _ in CASES.values():
        matplotlib.pyplot.close(call(data, None))
    for fig in plotting.wear_figures(data["table"]).values():
        matplotlib.pyplot.close(fig)
    assert matplotlib.get_backend() == backend
    assert matplotlib.rcParams["backend"] == rc


def test_save_figure_writes_png_and_svg_atomically(tmp_path, data):
    fig = plotting.plot_wear_table(data["table"])
    files = plotting.save_figure(fig, tmp_path / "new", "wear", close=True)
    assert [p.name for p in files] == ["wear.png", "wear.svg"]
    assert files[0].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert b"<svg" in files[1].read_bytes()[:500]
    assert sorted(p.name for p in (tmp_path / "new").iterdir()) == ["wear.png", "wear.svg"]
    assert not matplotlib.pyplot.fignum_exists(fig.number)


def test_without_matplotlib_the_error_names_the_extra(data, monkeypatch):
    for module in ("matplotlib.pyplot", "matplotlib.figure", "matplotlib.axes",
                   "matplotlib.ticker"):
        monkeypatch.setitem(sys.modules, module, None)
    for call, _, _ in CASES.values():
        with pytest.raises(MissingDependencyError,
                           match=r"plotting needs the optional package 'matplotlib\.\w+': "
                                 r"pip install 'fretwear\[plot\]'"):
            call(data, None)
