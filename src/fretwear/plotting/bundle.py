"""Figures of a tube bundle (:func:`fretwear.bundle.run_bundle`): the tube-sheet map, the
distribution of wear power over the bundle, and depth against time of the worst contacts.

Each function takes the bundle's results (a :class:`~fretwear.bundle.BundleResult`, or for the
map and the power distribution its ``summary()`` table), accepts ``ax=``, returns the
:class:`matplotlib.figure.Figure` and leaves the backend alone (:mod:`fretwear.plotting._common`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.plotting._common import figure_and_axes, matplotlib_module


def _summary(results: Any, limit: float | None = None) -> pd.DataFrame:
    if isinstance(results, pd.DataFrame):
        return results
    if not hasattr(results, "summary"):
        raise InputError("give the results of fretwear.bundle.run_bundle (a BundleResult) or "
                         f"its summary() table, not a {type(results).__name__}")
    return results.summary() if limit is None else results.summary(limit)


def plot_tube_sheet(results: Any, *, quantity: str = "auto", ax: Any = None):
    """Tube-sheet map: each tube at (column, row), coloured by its worst contact's depth.

    Parameters
    ----------
    results : BundleResult or DataFrame
        The bundle's results, or their ``summary()`` (columns ``tube_row``, ``tube_column``,
        ``depth`` [m], ``depth_fraction``).
    quantity : str
        ``"depth"`` (global tube depth at the last instant [mm]), ``"fraction"`` (depth / wall
        thickness [%]), or ``"auto"`` (the fraction when every tube's wall is known).
    ax : Axes or Figure, optional
        Where to draw (one panel).

    Returns
    -------
    matplotlib.figure.Figure
        One square per tube, the colour of its deepest contact (over its supports); a tube with
        a depth beyond its relation's range is drawn black with a white cross.

    Examples
    --------
    >>> s = pd.DataFrame({"tube_row": [1, 1, 2], "tube_column": [1, 2, 1],
    ...                   "depth": [1e-4, 2e-4, np.nan], "depth_fraction": [0.1, 0.2, np.nan]})
    >>> fig = plot_tube_sheet(s)
    >>> fig.axes[0].get_xlabel()
    'tube column'
    """
    summary = _summary(results)
    missing = [c for c in ("tube_row", "tube_column") if c not in summary.columns
               or summary[c].isna().all()]
    if missing:
        raise InputError(f"the tube-sheet map needs the manifest's {' and '.join(missing)} "
                         "columns (position of each tube)")
    if quantity not in ("auto", "depth", "fraction"):
        raise InputError(f"quantity {quantity!r}: choose 'depth', 'fraction' or 'auto'")
    frac = summary.get("depth_fraction", pd.Series(np.nan, index=summary.index))
    if quantity == "auto":
        known = summary["depth"].isna() | frac.notna()
        quantity = "fraction" if known.all() and frac.notna().any() else "depth"
    values = (frac * 100.0) if quantity == "fraction" else summary["depth"] * 1e3
    data = pd.DataFrame({"row": pd.to_numeric(summary["tube_row"], errors="coerce"),
                         "column": pd.to_numeric(summary["tube_column"], errors="coerce"),
                         "value": values.astype(float),
                         "beyond": summary["depth"].isna()}).dropna(subset=["row", "column"])
    worst = data.groupby(["row", "column"], as_index=False).agg(
        value=("value", "max"), beyond=("beyond", "any"))
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(1, 1, 1)],
                                        figsize=(7, 6), what="plot_tube_sheet")
    ok = worst[~worst["beyond"]]
    size = float(np.clip(2.0e4 / max(len(worst), 1), 4.0, 250.0))  # squares fill a small map
    art = axis.scatter(ok["column"], ok["row"], c=ok["value"], marker="s", s=size,
                       cmap="viridis", edgecolors="0.3", linewidths=0.4)
    label = ("global depth / wall [%]" if quantity == "fraction"
             else "global depth of the tube [mm]")
    fig.colorbar(art, ax=axis, label=f"worst contact: {label}")
    bad = worst[worst["beyond"]]
    if len(bad):
        axis.scatter(bad["column"], bad["row"], c="black", marker="s", s=size)
        axis.scatter(bad["column"], bad["row"], c="white", marker="x", s=size / 2,
                     label="beyond the relation's range")
        axis.legend(loc="upper right", fontsize="small")
    ticker = matplotlib_module("ticker")
    axis.xaxis.set_major_locator(ticker.MaxNLocator(integer=True))
    axis.yaxis.set_major_locator(ticker.MaxNLocator(integer=True))
    axis.set_xlabel("tube column")
    axis.set_ylabel("tube row")
    axis.set_aspect("equal", adjustable="datalim")
    axis.set_title("tube sheet: worst contact per tube at the last instant")
    return fig


def plot_power_distribution(results: Any, *, bins: int = 30, ax: Any = None):
    """Histogram of the wear power of the bundle's contacts (logarithmic power axis).

    Parameters
    ----------
    results : BundleResult or DataFrame
        The results, or their ``summary()`` (column ``power`` [W]).
    bins : int
        Number of bins.
    ax : Axes or Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        Contacts per bin of wear power [W], the median and the 95th percentile marked;
        contacts without wear (P = 0) are counted in the legend.

    Examples
    --------
    >>> fig = plot_power_distribution(pd.DataFrame({"power": [1e-3, 2e-3, 5e-3, 0.0]}))
    >>> fig.axes[0].get_xscale()
    'log'
    """
    power = pd.to_numeric(_summary(results)["power"], errors="coerce").dropna().to_numpy()
    positive = power[power > 0]
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(1, 1, 1)],
                                        figsize=(7, 4.5), what="plot_power_distribution")
    if positive.size:
        lo, hi = positive.min(), positive.max()
        edges = (np.geomspace(lo, hi, bins + 1) if hi > lo
                 else np.array([lo / 1.1, hi * 1.1]))
        axis.hist(positive, bins=edges, color="C0", edgecolor="white")
        for q, style in ((50, "--"), (95, ":")):
            v = float(np.percentile(positive, q))
            axis.axvline(v, color="C3", ls=style, label=f"{'median' if q == 50 else 'P95'} "
                                                        f"{v:.3g} W")
    axis.set_xscale("log")
    axis.set_xlabel("wear power [W]")
    axis.set_ylabel("contacts")
    axis.yaxis.set_major_locator(matplotlib_module("ticker").MaxNLocator(integer=True))  # counts
    zero = int((power == 0).sum())
    axis.set_title(f"wear power over {power.size} contacts"
                   + (f" ({zero} without wear)" if zero else ""))
    if positive.size:
        axis.legend(fontsize="small")
    return fig


def plot_worst_depths(results: Any, *, count: int = 10, limit: float | None = None,
                      ax: Any = None):
    """Tube depth against time of the ``count`` deepest contacts.

    Parameters
    ----------
    results : BundleResult
        The results (``table`` and ``summary()``).
    count : int
        Number of contacts drawn (the deepest at the last instant).
    limit : float, optional
        Depth limit as a fraction of the wall (the summary's default 0.4 otherwise); the limit
        depth is drawn for each contact whose wall thickness is known.
    ax : Axes or Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        Depth [mm] against the instant, one line per contact, a dotted line at each contact's
        limit depth. The instants are each contact's own, in its time unit (not converted):
        when the contacts drawn share one unit the x axis names it, else each line's legend
        label names its contact's unit.
    """
    if not hasattr(results, "table"):
        raise InputError("plot_worst_depths needs the BundleResult (its table), not a "
                         f"{type(results).__name__}")
    summary = _summary(results, limit).head(count)
    table = results.table
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(1, 1, 1)],
                                        figsize=(7, 4.5), what="plot_worst_depths")
    limits = {}
    units = summary["time_unit"].dropna().astype(str).unique()  # of the contacts drawn
    mixed = len(units) > 1
    for i, row in enumerate(summary.itertuples()):
        rows = table[table["contact"] == row.contact].drop_duplicates("instant")
        t = rows["instant"].to_numpy(dtype=float)
        d = rows["depth_mobile"].to_numpy(dtype=float) * 1e3
        origin = rows["origin"].iloc[0] if "origin" in rows.columns and len(rows) else 0.0
        if origin == 0 and (t.size == 0 or t[0] > 0):
            t, d = np.concatenate(([0.0], t)), np.concatenate(([0.0], d))
        own = getattr(row, "time_unit", None)
        label = f"{row.contact} [{own}]" if mixed and isinstance(own, str) else str(row.contact)
        axis.plot(t, d, "o-", ms=3, color=f"C{i % 10}", label=label)
        if np.isfinite(getattr(row, "limit_depth", np.nan)):
            limits[float(row.limit_depth)] = f"C{i % 10}"
    for depth, color in limits.items():
        axis.axhline(depth * 1e3, color=color, ls=":", lw=1)
    unit = (f" [{units[0]}]" if len(units) == 1
            else " [each contact's own time unit, in the legend]" if mixed else "")
    axis.set_xlabel(f"instant{unit}")
    axis.set_ylabel("global depth of the tube [mm]")
    axis.set_title(f"the {len(summary)} deepest contacts" + (" (dotted: limit depth)"
                                                            if limits else ""))
    if len(summary):
        axis.legend(fontsize="x-small", ncol=2)
    return fig
