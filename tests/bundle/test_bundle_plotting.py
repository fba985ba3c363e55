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
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
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


def cells(mesh):
    """{(row, column): value} of a QuadMesh's cells, from its own coordinates (the centre of
    each cell); a masked cell is None. Also checks that the edges lie at the half-integers."""
    corners = mesh.get_coordinates()  # (rows + 1, columns + 1, 2): x = column, y = row
    assert np.array_equal(corners % 1.0, np.full(corners.shape, 0.5))
    centres = (corners[:-1, :-1] + corners[1:, 1:]) / 2
    values = mesh.get_array()
    assert values.shape == centres.shape[:2]
    return {(int(y), int(x)): (None if v is np.ma.masked else float(v))
            for (x, y), v in zip(centres.reshape(-1, 2), values.ravel(), strict=True)}


def test_tube_sheet_colours_the_worst_contact_of_each_tube(result):
    fig = Figure()
    plot_tube_sheet(result, ax=fig.subplots())
    mesh = fig.axes[0].collections[0]
    values = cells(mesh)
    s = result.summary()
    worst = s.groupby(["tube_row", "tube_column"])["depth_fraction"].max() * 100
    assert len(values) == 4  # four tubes, five contacts: a 2 x 2 grid
    for (row, col), v in worst.items():
        assert values[(row, col)] == pytest.approx(v, rel=1e-12)
    assert values[(1, 1)] == pytest.approx(
        100 * s.set_index("contact").loc["R1C1-AVB2", "depth_fraction"], rel=1e-12)
    assert not mesh.get_rasterized()  # a handful of tubes stays vector


def tube_sheet(rows, columns, *, half_disk=True, beyond=(), seed=1):
    """A synthetic summary: a U-tube steam generator's tube sheet (a half disk of ``rows`` x
    ``columns``, tubes missing outside it), two supports per tube in random order, the depth of
    support 2 of the tubes ``beyond`` beyond its relation's range (NaN)."""
    rng = np.random.default_rng(seed)
    r, c = (a.ravel() for a in np.meshgrid(np.arange(1, rows + 1), np.arange(1, columns + 1),
                                           indexing="ij"))
    if half_disk:
        keep = (c - (columns + 1) / 2) ** 2 + (r - 0.5) ** 2 <= (columns / 2) ** 2
        r, c = r[keep], c[keep]
    s = pd.concat([pd.DataFrame({"contact": [f"R{i}C{j}-AVB{k}" for i, j in zip(r, c, strict=True)],
                                 "tube_row": r, "tube_column": c,
                                 "depth_fraction": rng.uniform(0.01, 0.6, r.size)})
                   for k in (1, 2)], ignore_index=True)
    s["depth"] = s["depth_fraction"] * 1.09e-3
    for row, col in beyond:
        at = (s["tube_row"] == row) & (s["tube_column"] == col) & s["contact"].str.endswith("2")
        s.loc[at, ["depth", "depth_fraction"]] = np.nan
    return s.sample(frac=1.0, random_state=seed, ignore_index=True)


@pytest.fixture(scope="module")
def steam_generator():
    """12 575 tubes (89 rows x 179 columns, a half disk), two beyond the range."""
    s = tube_sheet(89, 179, beyond=[(40, 90), (60, 60)])
    fig = plot_tube_sheet(s)
    yield s, fig
    matplotlib.pyplot.close(fig)


def test_tube_sheet_cells_of_a_steam_generator(steam_generator):
    s, fig = steam_generator
    axis = fig.axes[0]
    mesh, status = axis.collections[0], axis.collections[1]
    values, marks = cells(mesh), cells(status)
    ok = s[s["depth"].notna()]  # the worst contact, by pandas
    worst = ok.groupby(["tube_row", "tube_column"])["depth_fraction"].max() * 100
    tubes = set(zip(s["tube_row"], s["tube_column"], strict=True))
    assert len(tubes) == 12575 and {(40, 90), (60, 60)} <= tubes
    assert len(values) == 89 * 179  # the whole grid, rows 1-89 x columns 1-179
    for (row, col), v in values.items():
        if (row, col) in {(40, 90), (60, 60)}:  # black: beyond, whatever its other support
            assert v is None and marks[(row, col)] == 1.0
        elif (row, col) in tubes:
            assert v == pytest.approx(worst[(row, col)], rel=1e-12)
            assert marks[(row, col)] is None
        else:  # no tube there: an empty cell
            assert v is None and marks[(row, col)] is None
    assert sum(v is not None for v in values.values()) == len(tubes) - 2
    assert mesh.get_rasterized() and status.get_rasterized()
    # the two black cells are ringed to be found, and the key says so
    assert len(axis.collections[3].get_offsets()) == 2
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert "beyond the relation's range (2 tubes, ringed in red)" in texts


def test_tube_sheet_fills_its_axes(steam_generator):
    _, fig = steam_generator
    axis = fig.axes[0]
    fig.canvas.draw()
    assert axis.get_xlim() == (0.5, 179.5) and axis.get_ylim() == (0.5, 89.5)  # nothing else
    box = axis.get_window_extent()
    assert box.width / box.height == pytest.approx(179 / 89, rel=0.01)  # a square pitch
    bar = axis.collections[0].colorbar.ax.get_window_extent()
    assert (bar.y0, bar.y1) == pytest.approx((box.y0, box.y1), abs=0.5)  # as tall as the map
    whole = fig.get_tightbbox().transformed(fig.dpi_scale_trans)
    assert box.width * box.height / (whole.width * whole.height) > 0.6  # little space wasted


def test_tube_sheet_svg_of_a_steam_generator_is_small(steam_generator):
    import io

    _, fig = steam_generator
    out = io.BytesIO()
    fig.savefig(out, format="svg", dpi=120, bbox_inches="tight")  # as the CLI's save_figure
    svg = out.getvalue()
    # one embedded image for the cells (one <path> per tube before: 2.26 MB), axes, ticks and
    # labels vector
    assert len(svg) < 300_000
    assert svg.count(b"<image") >= 1 and b"tube column" in svg


def test_tube_sheet_has_no_gaps_between_cells():
    s = tube_sheet(50, 100, half_disk=False)  # 5 000 tubes: every cell a tube
    fig = Figure(figsize=(7, 6), dpi=100)
    canvas = FigureCanvasAgg(fig)
    plot_tube_sheet(s, ax=fig)
    axis = fig.axes[0]
    canvas.draw()
    pixels = np.asarray(canvas.buffer_rgba())[..., :3].astype(int)
    box = axis.get_window_extent()
    height = pixels.shape[0]
    inner = pixels[int(height - box.y1) + 2:int(height - box.y0) - 2,
                   int(box.x0) + 2:int(box.x1) - 2]
    assert (inner.min(axis=-1) < 250).all()  # no white (or light) pixel between the tubes
    # and each tube's own colour at its centre (no overlap of its neighbours)
    mesh = axis.collections[0]
    worst = s.groupby(["tube_row", "tube_column"])["depth_fraction"].max() * 100
    for (row, col), v in worst.iloc[::97].items():
        x, y = axis.transData.transform((col, row))
        expected = np.array(mesh.cmap(mesh.norm(v))[:3]) * 255
        assert np.abs(pixels[int(height - y), int(x)] - expected).max() <= 2


def test_tube_sheet_cells_without_a_value_and_beyond():
    s = pd.DataFrame({"tube_row": [1, 1, 2, 2, 2], "tube_column": [1, 2, 1, 2, 2],
                      "depth": [1e-4, 2e-4, 3e-4, 4e-4, np.nan],
                      "depth_fraction": [0.1, np.nan, 0.3, 0.35, np.nan]})
    fig = plot_tube_sheet(s, quantity="fraction")  # the wall of tube (1, 2) unknown
    axis = fig.axes[0]
    values, marks = cells(axis.collections[0]), cells(axis.collections[1])
    assert values == {(1, 1): pytest.approx(10.0), (1, 2): None, (2, 1): pytest.approx(30.0),
                      (2, 2): None}
    assert marks == {(1, 1): None, (1, 2): 0.0, (2, 1): None, (2, 2): 1.0}  # grey; black
    crosses = axis.collections[2].get_segments()
    assert len(crosses) == 2 and all(np.allclose(np.mean(seg, axis=0), (2, 2)) for seg in crosses)
    texts = {t.get_text() for t in fig.findobj(matplotlib.text.Text)}
    assert {"beyond the relation's range (1 tube)",
            "no value (wall thickness unknown) (1 tube)"} <= texts
    assert axis.collections[0].colorbar.ax.get_ylabel() == "worst contact: global depth / wall [%]"
    assert plot_tube_sheet(s).axes[0].collections[0].colorbar.ax.get_ylabel() == (
        "worst contact: global depth of the tube [mm]")  # auto: a wall unknown, the depth
    matplotlib.pyplot.close("all")


def test_tube_sheet_of_positions_off_the_integer_grid_draws_markers():
    """Half columns (a staggered numbering) are no grid of cells: one square marker a tube at
    its position, coloured by the worst contact (as the map was drawn before the cells)."""
    s = pd.DataFrame({"tube_row": [1, 1, 2, 2], "tube_column": [1, 1, 1.5, 2.5],
                      "depth": [1e-4, 3e-4, 2e-4, np.nan]})
    fig = plot_tube_sheet(s, quantity="depth")
    markers = fig.axes[0].collections[0]
    assert np.asarray(markers.get_offsets()).tolist() == [[1.0, 1.0], [1.5, 2.0]]
    np.testing.assert_allclose(markers.get_array(), [0.3, 0.2])  # worst per tube [mm]
    assert np.asarray(fig.axes[0].collections[1].get_offsets()).tolist() == [[2.5, 2.0]]
    matplotlib.pyplot.close("all")


def test_tube_sheet_needs_numbers_for_positions():
    """Letter rows give no position on the map: a clear error (numpy's 'zero-size array'
    before), which fretwear bundle --plot reports while it writes the other figures."""
    with pytest.raises(InputError, match=r"tube_row and tube_column as numbers.*\['A', 'B'\]"):
        plot_tube_sheet(pd.DataFrame({"tube_row": ["A", "B"], "tube_column": [1, 2],
                                      "depth": [1e-4, 2e-4]}))


@pytest.mark.parametrize("where", ["subfigure", "panel", "small"])
def test_tube_sheet_in_the_users_figure_keeps_within_its_axes(where):
    """In the user's room (a SubFigure, the left panel of two, a small figure) the map and
    its colour bar share the Axes' own room: the colour bar and its label end inside the
    figure, the bar before the next panel (an inset at fixed inches overlapped them, and a
    SubFigure raised)."""
    s = pd.DataFrame({"tube_row": [1, 1, 2, 3], "tube_column": [1, 2, 1, 3],
                      "depth": [1e-4, 2e-4, 3e-4, 4e-4]})
    pyplot = matplotlib.pyplot
    if where == "subfigure":
        fig = pyplot.figure(figsize=(8, 4))
        left, right = fig.subfigures(1, 2)
        target, neighbour = left, right.add_subplot(1, 1, 1)
    elif where == "panel":
        fig, (target, neighbour) = pyplot.subplots(1, 2, figsize=(6.4, 4.8))
    else:
        fig, target = pyplot.subplots(figsize=(4, 4))
        neighbour = None
    plot_tube_sheet(s, ax=target)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    bar = [a for a in fig.axes if a.get_ylabel().startswith("worst contact")][0]
    assert bar.get_tightbbox(renderer).x1 <= fig.bbox.width + 0.5  # its label included
    if neighbour is not None:
        assert bar.bbox.x1 <= neighbour.bbox.x0
    pyplot.close("all")


def test_power_distribution_counts_every_contact(result):
    fig = plot_power_distribution(result, bins=5)
    counts = sum(p.get_height() for p in fig.axes[0].patches)
    assert counts == len(result.summary())
    matplotlib.pyplot.close(fig)


def test_tube_sheet_needs_positions():
    with pytest.raises(InputError, match="tube_row"):
        plot_tube_sheet(pd.DataFrame({"depth": [1e-4], "tube_column": [1]}))
