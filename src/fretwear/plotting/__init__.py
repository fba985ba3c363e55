"""Figures of fretwear. Only this package imports matplotlib (extra ``plot``).

Computation returns data; these functions only draw it. As python-control's: each takes
results, accepts ``ax=`` (an Axes, a sequence of Axes for several panels, or a Figure to lay its
panels out in), returns the :class:`matplotlib.figure.Figure`, and never selects a matplotlib
backend (matplotlib falls back to Agg by itself where there is no display). Saving is separate:
:func:`save_figure` (atomic PNG/SVG), used by the CLI and the coupled loop.

* :mod:`fretwear.plotting.wear`: service-life wear table (volumes and depths against time,
  sector power and depth on polar plots): :func:`plot_wear_table`, :func:`plot_wear_history`,
  :func:`plot_sector_wear`, :func:`wear_figures`.
* :mod:`fretwear.plotting.obstacle`: obstacle update (new and worn clearance figure, depth
  profiles of mobile and obstacle): :func:`plot_obstacle`, :func:`plot_clearance`,
  :func:`plot_obstacle_depth`.
* :mod:`fretwear.plotting.dynamics`: built-in dynamics and the coupled loop (time histories,
  orbit in the clearance figure, depth per cycle): :func:`plot_contact_history`,
  :func:`plot_iteration`.
"""

from fretwear.plotting._common import save_figure
from fretwear.plotting.dynamics import plot_contact_history, plot_iteration
from fretwear.plotting.obstacle import plot_clearance, plot_obstacle, plot_obstacle_depth
from fretwear.plotting.wear import (
    plot_sector_wear,
    plot_wear_history,
    plot_wear_table,
    wear_figures,
)

__all__ = [
    "plot_clearance",
    "plot_contact_history",
    "plot_iteration",
    "plot_obstacle",
    "plot_obstacle_depth",
    "plot_sector_wear",
    "plot_wear_history",
    "plot_wear_table",
    "save_figure",
    "wear_figures",
]
