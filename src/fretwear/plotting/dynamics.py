"""Figures of the built-in dynamics and of the coupled loop.

Each function takes results, accepts ``ax=`` and returns the matplotlib Figure; nothing is
written (the loop saves them with :func:`fretwear.plotting.save_figure`).
"""

from __future__ import annotations

import numpy as np

from fretwear.plotting._common import figure_and_axes


def _decimate(n: int, limit: int = 20000) -> slice:
    return slice(None, None, max(1, n // limit))


def plot_contact_history(history, *, profiles=None, ax=None):
    """Normal force, sliding speed and orbit of one shock point.

    Parameters
    ----------
    history : ContactHistory
        With ``dy``/``dz`` for the orbit.
    profiles : mapping, optional
        label -> (angles [deg], clearance [m]): clearance figures drawn on the orbit (e.g. the
        new one, the one the dynamics saw, the worn one after the update).
    ax : three matplotlib Axes (force, speed, orbit) or a Figure, optional
        Default: a new figure, force and speed on the left sharing the time axis, the orbit on
        the right.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from fretwear.history import ContactHistory
    >>> h = ContactHistory(time=[0, 1, 2], normal_force=[0, 1, 0], vt1=[0, 1, 0], vt2=[0, 0, 0],
    ...                    dy=[0, 1e-4, 0], dz=[0, 0, 1e-4])
    >>> [a.get_ylabel() for a in plot_contact_history(h).axes]
    ['normal force Fn [N]', 'sliding speed [m/s]', 'dz [mm]']
    """
    def layout(fig):
        force = fig.add_subplot(2, 2, 1)
        return [force, fig.add_subplot(2, 2, 3, sharex=force), fig.add_subplot(1, 2, 2)]

    fig, (ax1, ax2, ax3), own = figure_and_axes(ax, 3, layout, figsize=(11, 6),
                                                what="plot_contact_history")
    s = _decimate(len(history))
    t = history.time[s]
    ax1.plot(t, history.normal_force[s], lw=0.6)
    ax1.set_ylabel("normal force Fn [N]")
    ax2.plot(t, history.sliding_speed[s], lw=0.6, label="‖Vt‖")
    if history.stick is not None and np.any(history.stick):
        st = history.stick[s] > 0
        ax2.plot(t[st], history.sliding_speed[s][st], ".", ms=1.5, color="C3", label="stick")
        ax2.legend(loc="upper right", fontsize=8)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("sliding speed [m/s]")
    if history.dy is not None:
        ax3.plot(history.dy[s] * 1e3, history.dz[s] * 1e3, lw=0.4, color="C0", label="orbit")
        hit = history.normal_force[s] > 0
        ax3.plot(history.dy[s][hit] * 1e3, history.dz[s][hit] * 1e3, ".", ms=1.5, color="C1",
                 label="in contact")
    for j, (label, (angles, gap)) in enumerate((profiles or {}).items()):
        ang = np.radians(np.asarray(angles, float))
        g = np.asarray(gap, float)
        ax3.plot(g * np.cos(ang) * 1e3, g * np.sin(ang) * 1e3, lw=1.0, color=f"C{j + 2}",
                 label=label)
    ax3.set_aspect("equal", adjustable="datalim")
    ax3.set_xlabel("dy [mm]")
    ax3.set_ylabel("dz [mm]")
    if ax3.get_legend_handles_labels()[0]:
        ax3.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, fontsize=8,
                   markerscale=4)
    if own:
        fig.suptitle(f"shock {history.name}" if history.name else "contact history")
    return fig


def plot_iteration(summary, profiles, *, ax=None):
    """Evolution over the loop's cycles: depths, power, clearance figures.

    Parameters
    ----------
    summary : DataFrame
        :attr:`fretwear.workflows.loop.IterationResult.summary`.
    profiles : sequence of (angles [deg], clearance [m])
        The worn clearance after each cycle.
    ax : three matplotlib Axes (depths, power, polar clearance) or a Figure, optional
        Default: a new figure with the three side by side.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import pandas as pd
    >>> s = pd.DataFrame({"cycle": [1, 2], "instant": [1.0, 2.0], "power": [0.1, 0.09],
    ...                   "depth_mobile_max": [1e-5, 2e-5], "depth_obstacle_max": [0.0, 0.0]})
    >>> a = np.linspace(0, 360, 9)
    >>> fig = plot_iteration(s, [(a, np.full(9, 5e-4)), (a, np.full(9, 5.2e-4))])
    >>> [a.name for a in fig.axes]
    ['rectilinear', 'rectilinear', 'polar']
    """
    fig, (ax1, ax2, ax3), own = figure_and_axes(
        ax, 3, lambda f: [f.add_subplot(1, 3, 1), f.add_subplot(1, 3, 2),
                          f.add_subplot(1, 3, 3, projection="polar")],
        figsize=(11, 4.5), what="plot_iteration", polar=(2,))
    ax1.plot(summary["instant"], np.asarray(summary["depth_mobile_max"]) * 1e3, "o-",
             label="mobile")
    ax1.plot(summary["instant"], np.asarray(summary["depth_obstacle_max"]) * 1e3, "s-",
             label="obstacle")
    unit = summary.attrs.get("time_unit") if hasattr(summary, "attrs") else None
    ax1.set_xlabel(f"instant [{unit}]" if unit else "instant (the case's time unit)")
    ax1.set_ylabel("max obstacle-profile depth [mm]")
    ax1.legend(fontsize=8)
    ax2.plot(summary["cycle"], summary["power"], "o-")
    ax2.set_xlabel("cycle")
    ax2.set_ylabel("wear power [W]")
    for j, (ang, gap) in enumerate(profiles):
        ax3.plot(np.radians(np.asarray(ang, float)), np.asarray(gap, float) * 1e3, lw=0.8,
                 label=f"cycle {j + 1}")
    ax3.set_rlabel_position(112.5)  # radius labels off the 0° axis, where wear often lies
    ax3.tick_params(axis="y", labelsize=7)
    ax3.set_title("worn clearance [mm]", fontsize=9)
    if 0 < len(profiles) <= 8:
        ax3.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.15, 0.5))
    if own:
        fig.tight_layout()
    return fig
