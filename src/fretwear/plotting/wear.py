"""Figures of a service-life wear table (:func:`fretwear.table.wear_table`).

matplotlib is imported here only, with the Agg backend (no display needed).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.plotting._common import pyplot as _pyplot
from fretwear.plotting._common import save_figure


def _unit(table: pd.DataFrame) -> str:
    """The table's time unit: its ``time_unit``, else the first name of its ``time_scale`` in
    :data:`fretwear.workflows.case_files.TIME_UNITS`, else the scale in seconds."""
    if table.attrs.get("time_unit"):
        return str(table.attrs["time_unit"])
    from fretwear.timeunits import TIME_UNITS

    scale = float(table.attrs.get("time_scale", 1.0))
    return next((name for name, s in TIME_UNITS.items() if s == scale), f"× {scale:g} s")


def plot_wear_table(table: pd.DataFrame, directory: str | os.PathLike, *, stem: str = "wear"
                    ) -> list[Path]:
    """Write the figures of a wear table as PNG and SVG files.

    Parameters
    ----------
    table : pandas.DataFrame
        A wear table with native column names (Code_Aster names are converted).
    directory : path-like
        Output directory (created), files written atomically.
    stem : str
        File-name prefix.

    Returns
    -------
    list of pathlib.Path
        ``<stem>_history.png/.svg`` (volumes [mm³] and depths [mm] of tube and obstacle against
        time; a replaced tube's curve is broken at the replacement, a restart origin is marked)
        and, in sector mode, ``<stem>_sectors.png/.svg`` (sector power [W] and sector
        depths [mm] at the last instant on polar axes).

    Examples
    --------
    >>> import tempfile
    >>> t = pd.DataFrame({"instant": [1.0, 2.0], "volume_mobile": [1e-9, 2e-9],
    ...                   "volume_obstacle": [0.0, 0.0], "depth_mobile": [1e-4, 1.6e-4],
    ...                   "depth_obstacle": [0.0, 0.0]})
    >>> [p.name for p in plot_wear_table(t, tempfile.mkdtemp())]
    ['wear_history.png', 'wear_history.svg']
    """
    from fretwear.table import from_aster_names

    table = from_aster_names(table)
    directory = Path(directory)
    plt = _pyplot()
    unit = _unit(table)
    glob = table.drop_duplicates("instant", keep="last").sort_values("instant")
    fig, (ax_v, ax_d) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    t = glob["instant"].to_numpy(dtype=float)
    replaced = table.attrs.get("tube_replacement")
    origin = table.attrs.get("origin") or 0.0
    # the tube's curve is broken at a replacement (the old and the new tube are two bodies)
    new_tube = np.zeros(t.shape, bool) if replaced is None else t >= float(replaced)
    for ax, column, scale in ((ax_v, "volume", 1e9), (ax_d, "depth", 1e3)):
        mobile = glob[f"{column}_mobile"].to_numpy(dtype=float) * scale
        ax.plot(t, np.where(new_tube, np.nan, mobile), "o-", color="C0", label="tube (mobile)")
        if new_tube.any():
            ax.plot(t[new_tube], mobile[new_tube], "o-", color="C0", mfc="white",
                    label="new tube")
            ax.axvline(float(replaced), color="0.4", ls=":", lw=1)
        ax.plot(t, glob[f"{column}_obstacle"] * scale, "s--", color="C1", label="obstacle")
        if origin:
            ax.axvline(float(origin), color="0.6", ls="-.", lw=1)
        ax.grid(alpha=0.3)
    if new_tube.any():
        ax_v.annotate("tube replaced", (float(replaced), 1.0), xycoords=("data", "axes fraction"),
                      xytext=(3, -12), textcoords="offset points", fontsize="small")
    if origin:
        ax_v.annotate("restart", (float(origin), 1.0), xycoords=("data", "axes fraction"),
                      xytext=(3, -24), textcoords="offset points", fontsize="small")
    ax_v.set_ylabel("cumulated worn volume [mm³]")
    ax_v.legend()
    ax_d.set_ylabel("worn depth [mm]")
    ax_d.set_xlabel(f"instant [{unit}]")
    ax_d.legend()
    title = table.attrs.get("title") or "wear table"
    fig.suptitle(f"{title}: {table.attrs.get('contact_type', '')} "
                 f"{table.attrs.get('law', '')}".strip())
    files = save_figure(fig, directory, f"{stem}_history")
    plt.close(fig)
    if "sector" in table.columns and table["sector"].notna().any():
        last = table[table["instant"] == table["instant"].max()].sort_values("sector")
        start = np.radians(last["angle_start"].to_numpy(dtype=float))
        width = np.radians(last["angle_end"].to_numpy(dtype=float)) - start
        fig, axes = plt.subplots(1, 2, figsize=(11, 5), subplot_kw={"projection": "polar"})
        axes[0].bar(start, last["sector_power"], width=width, align="edge", alpha=0.7,
                    edgecolor="k")
        axes[0].set_title("sector wear power [W]")
        axes[1].bar(start, last["depth_mobile_sector"] * 1e3, width=width, align="edge",
                    alpha=0.7, edgecolor="k", label="tube")
        axes[1].bar(start, last["depth_obstacle_sector"].fillna(0.0) * 1e3, width=width,
                    align="edge", alpha=0.4, edgecolor="k", label="obstacle")
        axes[1].set_title(f"sector depth [mm] at instant {last['instant'].iloc[0]:g} {unit}")
        axes[1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")
        # radial labels where the bars are lowest, so that they do not hide the bars
        low = int(np.argmin(last["sector_power"].to_numpy()))
        quiet = float(np.degrees(start[low] + width[low] / 2))
        for ax in axes:  # contact angle atan2(dz, dy) in (-180, 180] deg, as the table
            ax.set_thetagrids(range(0, 360, 45),
                              [f"{a if a <= 180 else a - 360}°" for a in range(0, 360, 45)])
            ax.set_rlabel_position(quiet)
            ax.tick_params(axis="y", labelsize="small")
        files += save_figure(fig, directory, f"{stem}_sectors")
        plt.close(fig)
    return files
