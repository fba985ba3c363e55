"""Figures of the built-in dynamics and of the coupled loop (PNG and SVG).

matplotlib is imported here only, with the Agg backend (no display needed).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from fretwear.plotting._common import pyplot as _pyplot
from fretwear.plotting._common import save_figure


def _save(fig, directory: Path, stem: str) -> list[Path]:
    return save_figure(fig, directory, stem, dpi=110)


def _decimate(n: int, limit: int = 20000) -> slice:
    return slice(None, None, max(1, n // limit))


def plot_contact_history(history, directory: str | os.PathLike, *, profiles=None,
                         stem: str = "contact_history") -> list[Path]:
    """Normal force, sliding speed and orbit of one shock point.

    Parameters
    ----------
    history : ContactHistory
        With ``dy``/``dz`` for the orbit.
    directory : path-like
        Output folder; writes ``<stem>.png`` and ``<stem>.svg``.
    profiles : mapping, optional
        label -> (angles [deg], clearance [m]): clearance figures drawn on the orbit (e.g. the
        new one, the one the dynamics saw, the worn one after the update).
    stem : str
        File name stem.

    Returns
    -------
    list of Path
        The files written.

    Examples
    --------
    >>> import tempfile
    >>> from fretwear.history import ContactHistory
    >>> h = ContactHistory(time=[0, 1, 2], normal_force=[0, 1, 0], vt1=[0, 1, 0], vt2=[0, 0, 0],
    ...                    dy=[0, 1e-4, 0], dz=[0, 0, 1e-4])
    >>> [p.suffix for p in plot_contact_history(h, tempfile.mkdtemp())]
    ['.png', '.svg']
    """
    plt = _pyplot()
    directory = Path(directory)
    s = _decimate(len(history))
    t = history.time[s]
    fig = plt.figure(figsize=(11, 6))
    ax1 = fig.add_subplot(2, 2, 1)
    ax1.plot(t, history.normal_force[s], lw=0.6)
    ax1.set_ylabel("normal force Fn [N]")
    ax2 = fig.add_subplot(2, 2, 3, sharex=ax1)
    ax2.plot(t, history.sliding_speed[s], lw=0.6, label="‖Vt‖")
    if history.stick is not None and np.any(history.stick):
        st = history.stick[s] > 0
        ax2.plot(t[st], history.sliding_speed[s][st], ".", ms=1.5, color="C3", label="stick")
        ax2.legend(loc="upper right", fontsize=8)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("sliding speed [m/s]")
    ax3 = fig.add_subplot(1, 2, 2)
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
    ax3.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, fontsize=8,
               markerscale=4)
    fig.suptitle(f"shock {history.name}" if history.name else "contact history")
    try:
        return _save(fig, directory, stem)
    finally:
        plt.close(fig)


def plot_iteration(summary, profiles, directory: str | os.PathLike, *,
                   stem: str = "iteration") -> list[Path]:
    """Evolution over the loop's cycles: depths, power, clearance figures.

    Parameters
    ----------
    summary : DataFrame
        :attr:`fretwear.workflows.loop.IterationResult.summary`.
    profiles : sequence of (angles [deg], clearance [m])
        The worn clearance after each cycle.
    directory : path-like
        Output folder.
    stem : str
        File name stem.

    Returns
    -------
    list of Path

    Examples
    --------
    >>> import tempfile, pandas as pd
    >>> s = pd.DataFrame({"cycle": [1, 2], "instant": [1.0, 2.0], "power": [0.1, 0.09],
    ...                   "depth_mobile_max": [1e-5, 2e-5], "depth_obstacle_max": [0.0, 0.0]})
    >>> a = np.linspace(0, 360, 9)
    >>> len(plot_iteration(s, [(a, np.full(9, 5e-4)), (a, np.full(9, 5.2e-4))], tempfile.mkdtemp()))
    2
    """
    plt = _pyplot()
    directory = Path(directory)
    fig = plt.figure(figsize=(11, 4.5))
    ax1 = fig.add_subplot(1, 3, 1)
    ax1.plot(summary["instant"], np.asarray(summary["depth_mobile_max"]) * 1e3, "o-",
             label="mobile")
    ax1.plot(summary["instant"], np.asarray(summary["depth_obstacle_max"]) * 1e3, "s-",
             label="obstacle")
    ax1.set_xlabel("instant [user unit]")
    ax1.set_ylabel("max worn depth [mm]")
    ax1.legend(fontsize=8)
    ax2 = fig.add_subplot(1, 3, 2)
    ax2.plot(summary["cycle"], summary["power"], "o-")
    ax2.set_xlabel("cycle")
    ax2.set_ylabel("wear power [W]")
    ax3 = fig.add_subplot(1, 3, 3, projection="polar")
    for j, (ang, gap) in enumerate(profiles):
        ax3.plot(np.radians(np.asarray(ang, float)), np.asarray(gap, float) * 1e3, lw=0.8,
                 label=f"cycle {j + 1}")
    ax3.set_rlabel_position(112.5)  # radius labels off the 0° axis, where wear often lies
    ax3.tick_params(axis="y", labelsize=7)
    ax3.set_title("worn clearance [mm]", fontsize=9)
    if len(profiles) <= 8:
        ax3.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.15, 0.5))
    fig.tight_layout()
    try:
        return _save(fig, directory, stem)
    finally:
        plt.close(fig)
