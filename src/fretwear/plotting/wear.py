"""Figures of a service-life wear table (:func:`fretwear.table.wear_table`).

Each function takes the table, accepts ``ax=`` and returns the matplotlib Figure; nothing is
written (the CLI and the loop save them with :func:`fretwear.plotting.save_figure`).
"""

from __future__ import annotations

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.plotting._common import figure_and_axes, legend_clear_of
from fretwear.table import carried_case, from_aster_names
from fretwear.timeunits import TIME_UNITS

#: quantity -> (column prefix, scale from SI, axis label)
_QUANTITIES = {"volume": ("volume", 1e9, "cumulated worn volume [mm³]"),
               "depth": ("depth", 1e3, "global worn depth [mm]")}


def _unit(table: pd.DataFrame, case) -> str:
    """The table's time unit: its case's ``time_unit``, else its ``time_scale`` in seconds;
    without a case (a Code_Aster table) the first name of 1 s in
    :data:`fretwear.timeunits.TIME_UNITS`."""
    if case is not None:
        return case.time_label
    return next((name for name, s in TIME_UNITS.items() if s == 1.0), "1 s")


def _title(table: pd.DataFrame, case) -> str:
    """The case's name, contact type and law (without a case, the file's title)."""
    if case is None:
        return str(table.attrs.get("title") or "wear table")  # provenance, display only
    return f"{case.name or 'wear table'}: {case.contact_type or ''} {case.law}".strip()


def _draw_history(ax, table: pd.DataFrame, quantity: str, case) -> list:
    """Draw one quantity (volume or depth) of tube and obstacle against the instants; the
    restart, the tube replacement and the wall are the table's ``case``'s (None: none).
    Returns the limit and wall lines drawn (for :func:`legend_clear_of`); no legend."""
    if quantity not in _QUANTITIES:
        raise InputError(f"quantity={quantity!r}: choose one of {list(_QUANTITIES)}")
    column, scale, label = _QUANTITIES[quantity]
    glob = table.drop_duplicates("instant", keep="last").sort_values("instant")
    t = glob["instant"].to_numpy(dtype=float)
    replaced = None if case is None else case.restart.tube_replacement
    origin = 0.0 if case is None else case.origin
    # the tube's curve is broken at a replacement (the old and the new tube are two bodies)
    new_tube = np.zeros(t.shape, bool) if replaced is None else t >= float(replaced)
    mobile = glob[f"{column}_mobile"].to_numpy(dtype=float) * scale
    ax.plot(t, np.where(new_tube, np.nan, mobile), "o-", color="C0", label="tube (mobile)")
    if new_tube.any():
        ax.plot(t[new_tube], mobile[new_tube], "o-", color="C0", mfc="white", label="new tube")
        ax.axvline(float(replaced), color="0.4", ls=":", lw=1)
        ax.annotate("tube replaced", (float(replaced), 1.0), xycoords=("data", "axes fraction"),
                    xytext=(3, -12), textcoords="offset points", fontsize="small")
    ax.plot(t, glob[f"{column}_obstacle"] * scale, "s--", color="C1", label="obstacle")
    if origin:
        ax.axvline(float(origin), color="0.6", ls="-.", lw=1)
        ax.annotate("restart", (float(origin), 1.0), xycoords=("data", "axes fraction"),
                    xytext=(3, -24), textcoords="offset points", fontsize="small")
    wall = None if case is None else case.wall.thickness
    marks = []
    if quantity == "depth" and wall:
        limit = case.wall.limit_depth
        marks.append(ax.axhline(limit * scale, color="C3", ls="--", lw=1,
                                label=f"limit {100 * limit / wall:g} % of the wall"))
        if np.nanmax(glob["depth_mobile"], initial=0.0) > wall:
            marks.append(ax.axhline(float(wall) * scale, color="k", lw=1.2,
                                    label="wall (through)"))
    ax.grid(alpha=0.3)
    ax.set_ylabel(label)
    ax.set_xlabel(f"instant [{_unit(table, case)}]")
    return marks


def plot_wear_history(table: pd.DataFrame, quantity: str = "depth", *, ax=None):
    """Worn depth (or volume) of the tube and the obstacle against the instants.

    A replaced tube's curve is broken at the replacement; a restart origin is marked.

    Parameters
    ----------
    table : pandas.DataFrame
        A wear table (native or Code_Aster column names); in sector mode the global rows are
        used.
    quantity : {"depth", "volume"}
        Worn depth [mm] or cumulated worn volume [mm³].
    ax : matplotlib Axes or Figure, optional
        Where to draw (default: a new figure).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0, 2.0], "volume_mobile": [1e-9, 2e-9],
    ...                   "volume_obstacle": [0.0, 0.0], "depth_mobile": [1e-4, 1.6e-4],
    ...                   "depth_obstacle": [0.0, 0.0]})
    >>> fig = plot_wear_history(t)
    >>> fig.axes[0].get_ylabel()
    'global worn depth [mm]'
    """
    table = from_aster_names(table)
    case = carried_case(table)
    fig, (axis,), own = figure_and_axes(ax, 1, lambda f: [f.add_subplot()], figsize=(7, 4),
                                        what="plot_wear_history")
    marks = _draw_history(axis, table, quantity, case)
    if own:
        axis.set_title(_title(table, case))
    legend_clear_of(axis, marks)  # not on the limit or the wall line
    return fig


def plot_wear_table(table: pd.DataFrame, *, ax=None):
    """Cumulated worn volumes [mm³] (top) and worn depths [mm] (bottom) against the instants.

    Parameters
    ----------
    table : pandas.DataFrame
        A wear table with native column names (Code_Aster names are converted).
    ax : two matplotlib Axes, or a Figure, optional
        The volume and depth axes (default: a new figure with both, sharing the time axis).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    plot_sector_wear : the sector power and depths of a sector table.

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0, 2.0], "volume_mobile": [1e-9, 2e-9],
    ...                   "volume_obstacle": [0.0, 0.0], "depth_mobile": [1e-4, 1.6e-4],
    ...                   "depth_obstacle": [0.0, 0.0]})
    >>> fig = plot_wear_table(t)
    >>> [a.get_ylabel() for a in fig.axes]
    ['cumulated worn volume [mm³]', 'global worn depth [mm]']
    """
    table = from_aster_names(table)

    def layout(fig):
        top = fig.add_subplot(2, 1, 1)
        return [top, fig.add_subplot(2, 1, 2, sharex=top)]

    fig, (ax_v, ax_d), own = figure_and_axes(ax, 2, layout, figsize=(7, 6.5),
                                             what="plot_wear_table")
    case = carried_case(table)
    _draw_history(ax_v, table, "volume", case)
    marks = _draw_history(ax_d, table, "depth", case)
    if own:
        ax_v.set_xlabel("")
        ax_v.tick_params(labelbottom=False)
        fig.suptitle(_title(table, case))
    ax_v.legend()
    legend_clear_of(ax_d, marks)  # not on the limit or the wall line
    return fig


def plot_sector_wear(table: pd.DataFrame, *, ax=None):
    """Sector wear power [W] and sector depths [mm] at the last instant, on polar axes.

    Parameters
    ----------
    table : pandas.DataFrame
        A sector wear table (``sector``, ``angle_start``, ``angle_end``, ``sector_power``,
        ``depth_mobile_sector``, ``depth_obstacle_sector``).
    ax : two polar Axes, or a Figure, optional
        Default: a new figure with both.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    InputError
        The table has no sectors.

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0, 1.0], "sector": [1, 2], "angle_start": [-180.0, 0.0],
    ...                   "angle_end": [0.0, 180.0], "sector_power": [0.1, 0.3],
    ...                   "depth_mobile_sector": [1e-5, 3e-5], "depth_obstacle_sector": [0.0, 0.0]})
    >>> [a.name for a in plot_sector_wear(t).axes]
    ['polar', 'polar']
    """
    table = from_aster_names(table)
    if "sector" not in table.columns or not table["sector"].notna().any():
        raise InputError("plot_sector_wear needs a sector wear table (column 'sector'); "
                         "this table has no sectors")
    unit = _unit(table, carried_case(table))
    last = table[table["instant"] == table["instant"].max()].sort_values("sector")
    start = np.radians(last["angle_start"].to_numpy(dtype=float))
    width = np.radians(last["angle_end"].to_numpy(dtype=float)) - start
    fig, axes, _ = figure_and_axes(
        ax, 2, lambda f: [f.add_subplot(1, 2, i, projection="polar") for i in (1, 2)],
        figsize=(11, 5), what="plot_sector_wear", polar=(0, 1))
    axes[0].bar(start, last["sector_power"], width=width, align="edge", alpha=0.7,
                edgecolor="k")
    axes[0].set_title("sector wear power [W]")
    axes[1].bar(start, last["depth_mobile_sector"] * 1e3, width=width, align="edge",
                alpha=0.7, edgecolor="k", label="tube")
    axes[1].bar(start, last["depth_obstacle_sector"].fillna(0.0) * 1e3, width=width,
                align="edge", alpha=0.4, edgecolor="k", label="obstacle")
    axes[1].set_title(f"sector depths [mm] at instant {last['instant'].iloc[0]:g} {unit}")
    axes[1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")
    # radial labels where the bars are lowest, so that they do not hide the bars
    low = int(np.argmin(last["sector_power"].to_numpy()))
    quiet = float(np.degrees(start[low] + width[low] / 2))
    for axis in axes:  # contact angle atan2(dz, dy) in (-180, 180] deg, as the table
        axis.set_thetagrids(range(0, 360, 45),
                            [f"{a if a <= 180 else a - 360}°" for a in range(0, 360, 45)])
        axis.set_rlabel_position(quiet)
        axis.tick_params(axis="y", labelsize="small")
    return fig


def wear_figures(table: pd.DataFrame) -> dict[str, object]:
    """Every figure of a wear table: ``{"history": ..., "sectors": ...}`` (sectors only for a
    sector table), each a new matplotlib Figure; what ``fretwear run --plot`` saves as
    ``wear_history.png``/``.svg`` and ``wear_sectors.png``/``.svg``.

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0], "volume_mobile": [1e-9], "volume_obstacle": [0.0],
    ...                   "depth_mobile": [1e-4], "depth_obstacle": [0.0]})
    >>> list(wear_figures(t))
    ['history']
    """
    table = from_aster_names(table)
    out = {"history": plot_wear_table(table)}
    if "sector" in table.columns and table["sector"].notna().any():
        out["sectors"] = plot_sector_wear(table)
    return out
