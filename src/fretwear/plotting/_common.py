"""What every figure module shares: how a plotting function finds the axes it draws in, and an
atomic PNG/SVG saver for the callers that write files (the CLI, the coupled loop).

Conventions of :mod:`fretwear.plotting` (as python-control's plotting functions): a function takes
results, accepts ``ax=`` (one Axes, a sequence of Axes, or a Figure to draw its panels in),
returns the :class:`matplotlib.figure.Figure` and never selects a backend: matplotlib picks one
(Agg when there is no display). matplotlib is imported when a function is called, through
:func:`fretwear._optional.require` (extra ``plot``).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._optional import require
from fretwear.errors import InputError
from fretwear.io.atomic import atomic_path

_PURPOSE = "plotting"


def pyplot():
    """``matplotlib.pyplot`` (extra ``plot``); the backend is left to matplotlib and the user."""
    return require("matplotlib.pyplot", purpose=_PURPOSE)


def matplotlib_module(name: str):
    """A matplotlib submodule (``"ticker"``, ``"figure"``, ...), through :func:`require`."""
    return require(f"matplotlib.{name}", purpose=_PURPOSE)


def figure_and_axes(ax: Any, count: int, layout: Callable[[Any], list], *,
                    figsize: tuple[float, float], what: str,
                    polar: Sequence[int] = ()) -> tuple[Any, list, bool]:
    """The figure and the ``count`` axes a plotting function draws in.

    Parameters
    ----------
    ax : None, Axes, sequence of Axes or Figure
        ``None``: a new pyplot figure of size ``figsize`` [in] with the function's panels;
        a Figure (or SubFigure) without axes: the panels are added to it; a Figure with exactly
        ``count`` axes, or ``count`` Axes: drawn in those.
    count : int
        Number of panels the function draws.
    layout : callable
        ``layout(figure) -> list of count Axes``: the function's own panels.
    figsize : (float, float)
        Size of a new figure [in].
    what : str
        The function's name, for the messages.
    polar : sequence of int
        Indices of the panels that must be polar Axes.

    Returns
    -------
    (Figure, list of Axes, bool)
        The figure holding the axes, the axes, and whether the panels were laid out here (then
        the function may set the figure's title and tight layout; a user's own axes are left as
        they are).

    Raises
    ------
    InputError
        Wrong number of Axes, Axes of several figures, or a cartesian Axes where a polar one is
        drawn.
    """
    if ax is None:
        fig = pyplot().figure(figsize=figsize)
        return fig, layout(fig), True
    if isinstance(ax, matplotlib_module("figure").FigureBase):
        if not ax.axes:
            return ax, layout(ax), True
        axes = list(ax.axes)
    elif isinstance(ax, matplotlib_module("axes").Axes):
        axes = [ax]
    else:
        axes = list(np.ravel(np.asarray(ax, dtype=object)))
    if len(axes) != count:
        raise InputError(f"{what} draws {count} panel(s): give ax= as {count} Axes, an empty "
                         f"Figure or nothing, not {len(axes)} Axes")
    figures = {id(a.figure) for a in axes}
    if len(figures) != 1:
        raise InputError(f"{what}: the Axes given as ax= belong to {len(figures)} figures; "
                         "give Axes of one figure")
    for i in polar:
        if axes[i].name != "polar":
            raise InputError(f"{what}: panel {i + 1} is a polar plot; give a polar Axes there "
                             "(e.g. fig.add_subplot(projection='polar'))")
    return axes[0].figure, axes, False


def save_figure(fig, directory: str | os.PathLike, stem: str, *, dpi: int = 120,
                formats: tuple[str, ...] = ("png", "svg"), close: bool = False) -> list[Path]:
    """Write ``fig`` as ``directory/stem.<fmt>`` for each format, atomically; return the paths.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    directory : path-like
        Output folder (created).
    stem : str
        File name without suffix.
    dpi : int
        Resolution of raster formats [dots per inch].
    formats : tuple of str
        Suffixes, each a format matplotlib writes (``png``, ``svg``, ``pdf``).
    close : bool
        Close the figure afterwards (pyplot keeps every figure it made until closed).

    Returns
    -------
    list of pathlib.Path

    Examples
    --------
    >>> import tempfile
    >>> fig = pyplot().figure()
    >>> [p.name for p in save_figure(fig, tempfile.mkdtemp(), "f", close=True)]
    ['f.png', 'f.svg']
    """
    out = []
    try:
        for fmt in formats:
            target = Path(directory) / f"{stem}.{fmt}"
            with atomic_path(target) as tmp:
                fig.savefig(tmp, format=fmt, dpi=dpi, bbox_inches="tight")
            out.append(target)
    finally:
        if close:
            pyplot().close(fig)
    return out


#: Legend places tried in turn by :func:`legend_clear_of` (after matplotlib's ``"best"``).
LEGEND_PLACES = ("upper left", "lower right", "upper right", "lower left", "center left",
                 "center right", "upper center", "lower center")


def legend_clear_of(axis: Any, lines: Sequence[Any], **kwargs: Any) -> Any:
    """The axis's legend, placed where it covers none of ``lines`` (the reference lines of a
    depth figure: the limit, the wall, a target).

    matplotlib's ``"best"`` weighs a horizontal line by its two end points only, so a legend
    could sit on the wall line. Tried in turn: ``"best"``, :data:`LEGEND_PLACES`, then the
    upper corners slid down the axes in 5 % steps; of the places inside the axes whose box
    [px] clears every line's (padded by half its line width and 2 px), the one covering the
    fewest data points (of the axis's other lines, markers by their size, its error bars and
    scatter points) is kept; else the legend goes beside the axes, on the right. Call it once
    the axes' size and limits are final (after ``tight_layout``).

    Parameters
    ----------
    axis : matplotlib Axes
    lines : sequence of Line2D
        The lines to keep clear (``axhline``/``axvline``'s results).
    **kwargs
        Passed to ``Axes.legend`` (``fontsize``, ``ncol``).

    Returns
    -------
    matplotlib.legend.Legend
    """
    renderer = axis.figure.canvas.get_renderer() if hasattr(
        axis.figure.canvas, "get_renderer") else None
    boxes = []
    for line in lines:
        box = line.get_window_extent(renderer)
        pad = line.get_linewidth() * axis.figure.dpi / 72.0 / 2 + 2.0
        boxes.append(box.padded(pad))
    tries = [{"loc": place} for place in ("best", *LEGEND_PLACES)]
    tries += [{"loc": f"upper {side}", "bbox_to_anchor": (x, top)}  # slid down the axes
              for top in np.linspace(0.95, 0.1, 18) for side, x in (("left", 0.0),
                                                                     ("right", 1.0))]
    points = _data_points(axis, lines)
    frame = axis.get_window_extent(renderer).padded(1.0)
    best, fewest = None, None
    for place in tries:
        legend = axis.legend(**place, **kwargs)
        mine = legend.get_window_extent(renderer)
        inside = frame.x0 <= mine.x0 and mine.x1 <= frame.x1 and frame.y0 <= mine.y0 \
            and mine.y1 <= frame.y1
        if not inside or any(mine.overlaps(b) for b in boxes):
            continue
        covered = sum(int(np.count_nonzero(
            (xy[:, 0] >= mine.x0 - pad) & (xy[:, 0] <= mine.x1 + pad)
            & (xy[:, 1] >= mine.y0 - pad) & (xy[:, 1] <= mine.y1 + pad))) for xy, pad in points)
        if fewest is None or covered < fewest:
            best, fewest = place, covered
            if not covered:
                break
    if best is not None:
        return axis.legend(**best, **kwargs)
    return axis.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                       **kwargs)  # beside the axes (the savers keep it: bbox_inches="tight")


def _data_points(axis: Any, marks: Sequence[Any]) -> list[tuple[np.ndarray, float]]:
    """(points [px], half size [px]) of what a legend should not cover on ``axis``: the
    vertices of its lines other than ``marks`` (a marker's half size), its error bars (points
    along each segment, every 2 px) and its scatter points."""
    px = axis.figure.dpi / 72.0
    out = []
    for line in axis.get_lines():
        if any(line is mark for mark in marks) or not len(line.get_xydata()):
            continue
        marker = line.get_marker() not in (None, "", " ", "None", "none")
        out.append((line.get_transform().transform(line.get_xydata()),
                    line.get_markersize() * px / 2 if marker else 0.0))
    kinds = matplotlib_module("collections")
    for artist in axis.collections:
        transform = artist.get_transform()
        if isinstance(artist, kinds.LineCollection):  # error bars
            for seg in artist.get_segments():
                ends = transform.transform(np.asarray(seg, dtype=float))
                if len(ends) < 2 or not np.isfinite(ends).all():
                    continue
                steps = max(2, int(np.hypot(*(ends[-1] - ends[0])) / 2.0) + 1)
                out.append((np.linspace(ends[0], ends[-1], steps), 1.0))
        elif isinstance(artist, kinds.PathCollection) and len(artist.get_offsets()):
            # scatter points (a fill_between's polygons have a phantom offset at (0, 0))
            sizes = artist.get_sizes()
            out.append((artist.get_offset_transform().transform(artist.get_offsets()),
                        float(np.sqrt(sizes.max()) * px / 2) if len(sizes) else 0.0))
    return out
