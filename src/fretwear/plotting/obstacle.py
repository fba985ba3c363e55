"""Figures of an obstacle update (:func:`fretwear.obstacle.update_obstacle`).

matplotlib is imported here only, with the Agg backend (no display needed).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from fretwear.plotting._common import pyplot as _pyplot
from fretwear.plotting._common import save_figure


def obstacle_figure(result):
    """A matplotlib figure of an obstacle update.

    Left: polar plot of the clearance figure, new and worn [mm] against the direction [deg],
    the sector edges drawn as spokes and perforated sectors shaded; the radial axis is clipped
    at 5 × the 10th percentile of the clearances when larger ones exist (the directions along
    two planes), and said so in the title. Right: worn depths of the
    mobile and of the obstacle [mm] against the angle [deg].

    Parameters
    ----------
    result : fretwear.obstacle.ObstacleResult

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _pyplot()
    fig = plt.figure(figsize=(11, 5))
    ax = fig.add_subplot(1, 2, 1, projection="polar")
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
    from matplotlib.ticker import MaxNLocator

    ax.yaxis.set_major_locator(MaxNLocator(4))
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
    ax2 = fig.add_subplot(1, 2, 2)
    ang = np.mod(result.angle + 180.0, 360.0) - 180.0
    order = np.argsort(ang, kind="stable")
    ax2.plot(ang[order], result.depth_mobile[order] * 1e3, color="C0", label="mobile")
    ax2.plot(ang[order], result.depth_obstacle[order] * 1e3, color="C1", label="obstacle")
    limit = result.perforation * result.mobile.wall_thickness * 1e3
    deepest = np.nanmax(result.depth_mobile, initial=0.0) * 1e3
    if result.perforated or deepest >= 0.3 * limit:
        ax2.axhline(limit, color="C3", ls=":", lw=1,
                    label=f"perforation ({result.perforation:g} × wall)")
    for e in edges:
        ax2.axvline(e, color="0.85", lw=0.6, zorder=0)
    ax2.set_xlim(-180, 180)
    ax2.set_xticks(np.arange(-180, 181, 60))
    ax2.set_xlabel("angle [deg]")
    ax2.set_ylabel("worn depth [mm]")
    ax2.legend(fontsize=8)
    when = "" if result.instant is None else f" at instant {result.instant:g}"
    fig.suptitle(f"obstacle update ({result.depth.shape} depth){when}")
    fig.tight_layout()
    return fig


def plot_obstacle(result, directory: str | os.PathLike, *, stem: str = "obstacle_polar"
                  ) -> list[Path]:
    """Write :func:`obstacle_figure` as ``<stem>.png`` and ``<stem>.svg`` in ``directory``.

    Parameters
    ----------
    result : fretwear.obstacle.ObstacleResult
    directory : path-like
        Output folder (created); files written atomically.
    stem : str
        File-name stem.

    Returns
    -------
    list of pathlib.Path
    """
    plt = _pyplot()
    fig = obstacle_figure(result)
    try:
        return save_figure(fig, directory, stem, dpi=120)
    finally:
        plt.close(fig)
