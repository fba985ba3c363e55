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
