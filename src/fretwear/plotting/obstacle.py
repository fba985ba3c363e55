"""Figures of an obstacle update (:func:`fretwear.obstacle.update_obstacle`).

Each function takes the :class:`~fretwear.obstacle.ObstacleResult`, accepts ``ax=`` and returns
the matplotlib Figure; nothing is written (the CLI and the loop save them with
:func:`fretwear.plotting.save_figure`).
"""

from __future__ import annotations

import numpy as np

from fretwear.plotting._common import figure_and_axes, legend_clear_of, matplotlib_module


def _draw_clearance(ax, result) -> None:
    """Polar plot of the clearance figure, new and worn [mm], sector spokes, perforations."""
    theta = np.radians(result.angle)
    ax.plot(theta, result.clearance_initial * 1e3, color="0.4", lw=1.2, ls="--", label="new")
    ax.plot(theta, result.clearance_worn * 1e3, color="C3", lw=1.6, label="worn")
    both = np.concatenate([result.clearance_initial, result.clearance_worn]) * 1e3
    top = np.nanmax(both)
    # between planes the directions along them see the far closing circle (~100 × the gap):
    # clip the radial axis at 5 × the 10th percentile so the contact region stays readable
    cap = 5.0 * np.nanpercentile(both, 10) if np.isfinite(both).any() else np.nan
    clipped = bool(np.isfinite(cap) and cap > 0 and top > cap)
    if clipped:
        top = cap
    edges = result.depth.edges
    for e in edges[:-1]:
        ax.plot([np.radians(e)] * 2, [0, top], color="0.85", lw=0.6, zorder=0)
    for j in result.perforated_sectors:
        span = np.radians(np.linspace(edges[j - 1], edges[j], 30))
        ax.fill_between(span, 0, top, color="C3", alpha=0.12, lw=0)
    low = np.nanmin(both)
    if np.isfinite(low) and np.isfinite(top) and top > 0:
        # a span of at least 2 % of the clearance: rounding noise (1e-15 m) is not zoomed into
        span = max(top - low, 0.02 * top)
        ax.set_ylim(max(0.0, low - 1.5 * span), top + 0.05 * span)
    ax.yaxis.set_major_locator(matplotlib_module("ticker").MaxNLocator(4))
    ax.set_rlabel_position(100)
    ax.tick_params(axis="y", labelsize=7)
    title = ("clearance [mm] (radial axis does not start at 0)" if ax.get_ylim()[0] > 0
             else "clearance [mm]")
    if clipped:
        title += f"\nclipped at {top:.3g} mm (largest {np.nanmax(both):.3g} mm)"
    if not np.isfinite(result.clearance_worn).any():
        title += "\nworn: undefined (mobile worn past its centre)"
    ax.set_title(title, pad=14, fontsize=10)
    ax.legend(loc="lower left", bbox_to_anchor=(-0.15, -0.12), fontsize=8)


def _draw_depth(ax, result) -> None:
    """Worn depths of mobile and obstacle [mm] against the angle [deg]."""
    edges = result.depth.edges
    ang = np.mod(result.angle + 180.0, 360.0) - 180.0
    order = np.argsort(ang, kind="stable")
    ax.plot(ang[order], result.depth_mobile[order] * 1e3, color="C0", label="mobile")
    ax.plot(ang[order], result.depth_obstacle[order] * 1e3, color="C1", label="obstacle")
    limit = result.perforation * result.mobile.wall_thickness * 1e3
    deepest = np.nanmax(result.depth_mobile, initial=0.0) * 1e3
    marks = []
    if result.perforated or deepest >= 0.3 * limit:
        marks = [ax.axhline(limit, color="C3", ls=":", lw=1,
                            label=f"perforation ({result.perforation:g} × wall)")]
    for e in edges:
        ax.axvline(e, color="0.85", lw=0.6, zorder=0)
    ax.set_xlim(-180, 180)
    ax.set_xticks(np.arange(-180, 181, 60))
    ax.set_xlabel("angle [deg]")
    ax.set_ylabel("obstacle-profile depth [mm]")
    legend_clear_of(ax, marks, fontsize=8)  # not on the perforation line


def plot_clearance(result, *, ax=None):
    """The clearance figure of an obstacle update, new and worn [mm], on a polar Axes.

    The sector edges are drawn as spokes and perforated sectors shaded; the radial axis is
    clipped at 5 × the 10th percentile of the clearances when larger ones exist (the directions
    along two planes), and the title says so.

    Parameters
    ----------
    result : fretwear.obstacle.ObstacleResult
    ax : polar matplotlib Axes or Figure, optional
        Default: a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(projection="polar")],
                                      figsize=(6, 5.5), what="plot_clearance", polar=(0,))
    _draw_clearance(axis, result)
    return fig


def plot_obstacle_depth(result, *, ax=None):
    """Worn depths of the mobile and the obstacle [mm] against the angle [deg], with the
    perforation depth when the mobile comes near it.

    Parameters
    ----------
    result : fretwear.obstacle.ObstacleResult
    ax : matplotlib Axes or Figure, optional
        Default: a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot()], figsize=(6, 4.5),
                                      what="plot_obstacle_depth")
    _draw_depth(axis, result)
    return fig


def plot_obstacle(result, *, ax=None):
    """An obstacle update: the clearance figure (left, :func:`plot_clearance`) and the worn
    depths (right, :func:`plot_obstacle_depth`).

    Parameters
    ----------
    result : fretwear.obstacle.ObstacleResult
    ax : (polar Axes, Axes) or Figure, optional
        Default: a new figure with both.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (polar, cart), own = figure_and_axes(
        ax, 2, lambda f: [f.add_subplot(1, 2, 1, projection="polar"), f.add_subplot(1, 2, 2)],
        figsize=(11, 5), what="plot_obstacle", polar=(0,))
    _draw_clearance(polar, result)
    _draw_depth(cart, result)
    if own:
        when = "" if result.instant is None else f" at instant {result.instant:g}"
        fig.suptitle(f"obstacle update ({result.depth.shape} depth){when}")
        fig.tight_layout()
    return fig
