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
from fretwear.plotting._common import figure_and_axes, legend_clear_of, matplotlib_module


def _summary(results: Any, limit: float | None = None) -> pd.DataFrame:
    if isinstance(results, pd.DataFrame):
        return results
    if not hasattr(results, "summary"):
        raise InputError("give the results of fretwear.bundle.run_bundle (a BundleResult) or "
                         f"its summary() table, not a {type(results).__name__}")
    return results.summary() if limit is None else results.summary(limit)


_CELLS_LIMIT = 4_000_000  # cells of the (row, column) grid the map accepts (2000 x 2000)
_VECTOR_CELLS = 2_500     # larger grids are rasterised (an SVG/PDF keeps axes and text vector)
_KEY_LINE = 0.2           # [in] a line of the black/grey cells' key, under the x label


def _tube_grid(worst: pd.DataFrame) -> dict:
    """The tubes on their (row, column) grid: the values, and the cells drawn without one."""
    rows, cols = worst["row"].to_numpy(float), worst["column"].to_numpy(float)
    r0, c0 = int(rows.min()), int(cols.min())
    shape = (int(rows.max()) - r0 + 1, int(cols.max()) - c0 + 1)
    if shape[0] * shape[1] > _CELLS_LIMIT:
        raise InputError(f"the tube-sheet map would span {shape[0]} rows x {shape[1]} columns "
                         f"(rows {r0}-{r0 + shape[0] - 1}, columns {c0}-{c0 + shape[1] - 1}); "
                         "check the manifest's tube_row and tube_column")
    i, j = rows.astype(int) - r0, cols.astype(int) - c0
    beyond = worst["beyond"].to_numpy(bool)
    value = np.full(shape, np.nan)
    value[i, j] = np.where(beyond, np.nan, worst["value"].to_numpy(float))
    status = np.full(shape, np.nan)  # 1: beyond the relation's range, 0: a tube without a value
    status[i, j] = np.where(beyond, 1.0, np.where(np.isnan(value[i, j]), 0.0, np.nan))
    return {"value": value, "status": status, "first": (r0, c0), "shape": shape,
            "beyond": (rows[beyond], cols[beyond])}


def _layout(shape: tuple[int, int], key_lines: int) -> dict:
    """Size of a new figure [in] around a map of square cells (the tube pitch), where its
    colour bar goes (at the right, or under a map too flat to hold the bar's label) and the size
    of a cell [pt]."""
    rows, cols = shape
    cell = min(8.0 / cols, 6.0 / rows, max(0.8, 3.2 / rows))  # [in]: the map within 8 x 6 in
    horizontal = rows * cell < 3.2
    left, top = 0.85, 0.45                   # row numbers and label; title
    right = 0.35 if horizontal else 1.3      # colour bar, its numbers and label
    bottom = (1.4 if horizontal else 0.6) + key_lines * _KEY_LINE
    return {"horizontal": horizontal, "margins": (left, right, bottom, top), "cell": 72 * cell,
            "figsize": (max(left + cols * cell + right, 5.5),  # the title is ~4.6 in long
                        bottom + rows * cell + top)}


def _map_axes(fig: Any, margins: tuple[float, float, float, float]) -> list:
    """The map's Axes in ``fig``, within ``margins`` [in] (left, right, bottom, top)."""
    width, height = fig.get_size_inches()
    left, right, bottom, top = margins
    w, h = max(width - left - right, 0.2 * width), max(height - bottom - top, 0.2 * height)
    return [fig.add_axes((left / width, bottom / height, w / width, h / height))]


def _colour_bar(fig: Any, axis: Any, art: Any, horizontal: bool, label: str) -> Any:
    """The colour bar, an inset of the map's Axes as long as the map (whatever its aspect),
    0.18 in thick, at 0.12 in right of it or under its x label; returns its Axes."""
    transforms = matplotlib_module("transforms")
    inches = fig.dpi_scale_trans
    if horizontal:  # x: the map's width; y: inches from its bottom edge
        frame = transforms.blended_transform_factory(
            axis.transAxes, inches + transforms.ScaledTranslation(0, 0, axis.transAxes))
        bounds = (0.0, -0.78, 1.0, 0.18)
    else:           # x: inches from its right edge; y: the map's height
        frame = transforms.blended_transform_factory(
            inches + transforms.ScaledTranslation(1, 0, axis.transAxes), axis.transAxes)
        bounds = (0.12, 0.0, 0.18, 1.0)
    cax = axis.inset_axes(bounds, transform=frame)
    fig.colorbar(art, cax=cax, orientation="horizontal" if horizontal else "vertical",
                 label=label)
    return cax


def _mark_beyond(axis: Any, grid: dict, raster: bool, cell: float) -> bool:
    """The white cross on each black cell (its diagonals, inset); where the cells are small
    (``cell`` [pt], a large tube sheet), a red ring around it too, so that it is found.
    Returns: ringed."""
    rows, cols = grid["beyond"]
    if not rows.size:
        return False
    n_rows, n_cols = grid["shape"]
    arm = 0.3
    segments = np.concatenate([
        np.stack([np.c_[cols - arm, rows - arm], np.c_[cols + arm, rows + arm]], 1),
        np.stack([np.c_[cols - arm, rows + arm], np.c_[cols + arm, rows - arm]], 1)])
    axis.add_collection(matplotlib_module("collections").LineCollection(
        segments, colors="white", linewidths=float(np.clip(40.0 / max(n_rows, n_cols), 0.4, 1.5)),
        rasterized=raster and rows.size > 200), autolim=False)
    if cell >= 12.0 or rows.size > 100:  # large cells are seen; many black cells are a region
        return False
    axis.scatter(cols, rows, s=max(3.0 * cell, 11.0) ** 2, marker="o", facecolors="none",
                 edgecolors="red", linewidths=1.2)
    return True


def _cell_key(axis: Any, under: Any, entries: list[tuple[str, bool, str]]) -> None:
    """Key of the black and grey cells, one line each, under the label ``under`` (outside the
    map), aligned with the map's left edge."""
    offsetbox = matplotlib_module("offsetbox")
    patches, lines = matplotlib_module("patches"), matplotlib_module("lines")
    items = []
    for face, cross, text in entries:
        swatch = offsetbox.DrawingArea(9, 9)
        swatch.add_artist(patches.Rectangle((0, 0), 9, 9, facecolor=face, edgecolor="0.4",
                                            linewidth=0.5))
        if cross:
            for ys in ((1.5, 7.5), (7.5, 1.5)):
                swatch.add_artist(lines.Line2D((1.5, 7.5), ys, color="white", linewidth=1.2))
        label = offsetbox.TextArea(text, textprops={"fontsize": "small"})
        items.append(offsetbox.HPacker(children=[swatch, label], align="center", pad=0, sep=4))
    axis.add_artist(offsetbox.AnnotationBbox(
        offsetbox.VPacker(children=items, align="left", pad=0, sep=3), (0.0, 0.0),
        xycoords=("axes fraction", under), xybox=(0.0, -4.0), boxcoords="offset points",
        box_alignment=(0.0, 1.0), frameon=False, pad=0.0,
        zorder=6))  # drawn after the colour bar (an inset: zorder 5) has placed its label


def plot_tube_sheet(results: Any, *, quantity: str = "auto", column: str | None = None,
                    limit: float = 0.4, target: float = 0.05, title: str | None = None,
                    ax: Any = None):
    """Tube-sheet map: each tube a cell at (column, row), coloured by its worst contact's depth
    (or probability): the one map of the bundle, the calibration and the assessment.

    Parameters
    ----------
    results : BundleResult, Assessment or DataFrame
        The bundle's results, or their ``summary()`` (columns ``tube_row``, ``tube_column``
        (integers), ``depth`` [m], ``depth_fraction``), or any table of contacts or tubes with
        the position and the ``column`` drawn. Optional boolean columns ``inspected`` and
        ``plugged`` mark the tubes (a ring, a black dot).
    quantity : str
        ``"depth"`` (global tube depth at the last instant [mm]), ``"fraction"`` (depth / wall
        thickness [%], in discrete bands: four below the plugging limit, the limit to the wall,
        through the wall, as the field's maps are drawn), ``"probability"`` (the ``column``, a
        probability of exceeding the limit, in decade bands up to the target and above it), or
        ``"auto"`` (the fraction when every tube's wall is known).
    column : str, optional
        The column drawn for ``"fraction"`` (default ``depth_fraction``) or ``"probability"``
        (default ``p_exceed``, else ``exceedance``).
    limit : float
        The plugging limit, fraction of the wall [-], the edge of the fraction's bands.
    target : float
        The probability target [-], the edge of the probability's top band.
    title : str, optional
    ax : Axes or Figure, optional
        Where to draw (one panel). The colour bar is an inset of that Axes, outside the map: in
        a figure of several panels, ``layout="constrained"`` leaves it room.

    Returns
    -------
    matplotlib.figure.Figure
        One square cell per tube on the (row, column) grid of the tube sheet (cell edges at the
        half-integers, equal aspect: a square pitch), the colour of its deepest contact (over
        its supports); no cell where the results have no tube. A tube with a depth beyond its
        relation's range is a black cell with a white cross (ringed in red where the cells are
        small); a tube without a value (its wall unknown, ``quantity="fraction"``) is grey; a
        key under the map names both. The cells are one ``QuadMesh``
        (``fig.axes[0].collections[0]``: its array the values, rows x columns, masked where no
        value), rasterised above 2 500 cells so that an SVG or PDF stays small while the axes
        and text stay vector. A new figure is sized to the tube sheet.

    Examples
    --------
    >>> s = pd.DataFrame({"tube_row": [1, 1, 2], "tube_column": [1, 2, 1],
    ...                   "depth": [1e-4, 2e-4, np.nan], "depth_fraction": [0.1, 0.2, np.nan]})
    >>> fig = plot_tube_sheet(s)
    >>> fig.axes[0].get_xlabel()
    'tube column'
    >>> print(fig.axes[0].collections[0].get_array())  # rows 1-2 x columns 1-2 [%]
    [[10.0 20.0]
     [-- --]]
    """
    summary = _summary(results)
    if quantity == "probability":
        column = column or next((c for c in ("p_exceed", "exceedance") if c in summary.columns),
                                "p_exceed")
    missing = [c for c in ("tube_row", "tube_column", *([column] if column else []))
               if c not in summary.columns
               or summary[c].isna().all()]
    if missing:
        raise InputError(f"the tube-sheet map needs the columns {' and '.join(missing)} "
                         "(position of each tube, and the value drawn)")
    if quantity not in ("auto", "depth", "fraction", "probability"):
        raise InputError(f"quantity {quantity!r}: choose 'depth', 'fraction', 'probability' "
                         "or 'auto'")
    frac = summary.get(column if quantity == "fraction" and column else "depth_fraction",
                       pd.Series(np.nan, index=summary.index))
    if "depth" not in summary.columns:
        summary = summary.assign(depth=np.where(frac.notna(), 0.0, np.nan)
                                 if quantity != "probability" else 0.0)
    if quantity == "auto":
        known = summary["depth"].isna() | frac.notna()
        quantity = "fraction" if known.all() and frac.notna().any() else "depth"
    values = ((frac * 100.0) if quantity == "fraction" else summary["depth"] * 1e3
              if quantity == "depth" else pd.to_numeric(summary[column], errors="coerce"))
    flags = {k: (summary[k].astype("boolean").fillna(False).to_numpy(bool)
                 if k in summary.columns else np.zeros(len(summary), bool))
             for k in ("inspected", "plugged")}
    data = pd.DataFrame({"row": pd.to_numeric(summary["tube_row"], errors="coerce"),
                         "column": pd.to_numeric(summary["tube_column"], errors="coerce"),
                         "value": values.astype(float),
                         "beyond": summary["depth"].isna(), **flags}
                        ).dropna(subset=["row", "column"])
    worst = data.groupby(["row", "column"], as_index=False).agg(
        value=("value", "max"), beyond=("beyond", "any"), inspected=("inspected", "any"),
        plugged=("plugged", "any"))
    if worst.empty:
        raise InputError("the tube-sheet map needs tube_row and tube_column as numbers (the "
                         "tube's row and column numbers); the results have none: "
                         f"{summary['tube_row'].dropna().astype(str).head(3).tolist()} ...")
    label = {"fraction": "global depth / wall [%]", "depth": "global depth of the tube [mm]",
             "probability": "P(exceeding the limit) [-]"}[quantity]
    scale = _scale(quantity, limit, target)
    rows, cols = worst["row"].to_numpy(float), worst["column"].to_numpy(float)
    if ((rows != np.round(rows)) | (cols != np.round(cols))).any():
        return _marker_map(worst, ax, f"worst contact: {label}", scale)
    grid = _tube_grid(worst)
    status = grid["status"]
    counts = {k: int((status == k).sum()) for k in (1.0, 0.0)}  # beyond; without a value
    layout = _layout(grid["shape"], sum(n > 0 for n in counts.values())
                     + int(worst["inspected"].any()) + int(worst["plugged"].any()))
    # laid out here (a new figure sized to the tube sheet, or the user's empty Figure): the map
    # within margins in inches, its colour bar an inset; else (Axes, a SubFigure) the colour
    # bar takes its room from the user's Axes
    own = ax is None or (isinstance(ax, matplotlib_module("figure").Figure) and not ax.axes)
    fig, (axis,), _ = figure_and_axes(
        ax, 1, (lambda f: _map_axes(f, layout["margins"])) if own
        else (lambda f: [f.add_subplot(1, 1, 1)]),
        figsize=layout["figsize"], what="plot_tube_sheet")
    horizontal = own and layout["horizontal"]
    (r0, c0), (n_rows, n_cols) = grid["first"], grid["shape"]
    col_edges = np.arange(n_cols + 1) + (c0 - 0.5)
    row_edges = np.arange(n_rows + 1) + (r0 - 0.5)
    raster = n_rows * n_cols > _VECTOR_CELLS
    # large cells: thin white lines between them; small ones (a large map): a continuous field
    lines = ({"edgecolors": "white", "linewidth": 0.6} if layout["cell"] >= 10.0
             else {"edgecolors": "none"})
    value = np.ma.masked_invalid(grid["value"])
    art = axis.pcolormesh(col_edges, row_edges, value, shading="flat",
                          rasterized=raster, **scale, **lines)
    if value.count() == 0 and "norm" not in scale:
        art.set_clim(0.0, 1.0)  # no value at all: an empty scale rather than a warning
    ringed = False
    if counts[1.0] or counts[0.0]:
        axis.pcolormesh(col_edges, row_edges, np.ma.masked_invalid(status), shading="flat",
                        cmap=matplotlib_module("colors").ListedColormap(["0.8", "black"]),
                        vmin=0.0, vmax=1.0, rasterized=raster, **lines)
        ringed = _mark_beyond(axis, grid, raster, layout["cell"])
    axis.set_xlim(col_edges[0], col_edges[-1])
    axis.set_ylim(row_edges[0], row_edges[-1])
    axis.set_aspect("equal", adjustable="box")  # a square pitch; the axes fit the tube sheet
    if own:
        cax = _colour_bar(fig, axis, art, horizontal, f"worst contact: {label}")
    else:  # in the user's axes: the colour bar takes its room from them
        cax = fig.colorbar(art, ax=axis, label=f"worst contact: {label}").ax
    _band_ticks(art, quantity, limit)
    ticker = matplotlib_module("ticker")  # tube numbers only, also for a single row/column
    axis.xaxis.set_major_locator(ticker.MaxNLocator(integer=True, min_n_ticks=1))
    axis.yaxis.set_major_locator(ticker.MaxNLocator(integer=True, min_n_ticks=1))
    _sheet_labels(axis, title)
    marks = _mark_tubes(axis, worst, layout["cell"])
    entries = [(face, k == 1.0, f"{text} ({counts[k]} tube{'s' * (counts[k] != 1)}"
                + (", ringed in red" if ringed and k == 1.0 else "") + ")")
               for k, face, text in ((1.0, "black", "beyond the relation's range"),
                                     (0.0, "0.8", "no value (wall thickness unknown)"))
               if counts[k]] + marks
    if entries:
        _cell_key(axis, cax.xaxis.label if horizontal else axis.xaxis.label, entries)
    return fig


#: Colours of the fraction's bands: four below the limit (light to dark blue-green), the
#: limit to the wall (orange), through the wall (dark red).
_FRACTION_COLOURS = ("#e0f3db", "#a8ddb5", "#43a2ca", "#0868ac", "#fd8d3c", "#99000d")
_PROBABILITY_COLOURS = ("#f7f7f7", "#d9d9d9", "#fee391", "#fec44f", "#fe9929", "#cc4c02",
                        "#8c2d04")


def _scale(quantity: str, limit: float, target: float) -> dict:
    """``cmap`` and ``norm`` of the map: discrete bands for a fraction of the wall [%] (edges
    at a quarter, half and three quarters of the limit, the limit, the wall) and for a
    probability (decades to the target, the target to 1); a continuous scale for a depth."""
    colors = matplotlib_module("colors")
    if quantity == "fraction":
        edges = [0.0, 25 * limit, 50 * limit, 75 * limit, 100 * limit, 100.0, 1e9]
        return {"cmap": colors.ListedColormap(_FRACTION_COLOURS),
                "norm": colors.BoundaryNorm(edges, len(_FRACTION_COLOURS))}
    if quantity == "probability":
        edges = [0.0, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, target, 1.0 + 1e-12]
        edges = sorted(set(e for e in edges if e <= target) | {target, 1.0 + 1e-12})
        cmap = colors.ListedColormap(_PROBABILITY_COLOURS[-(len(edges) - 1):])
        return {"cmap": cmap, "norm": colors.BoundaryNorm(edges, len(edges) - 1)}
    return {"cmap": "viridis"}


def _band_ticks(art: Any, quantity: str, limit: float) -> None:
    """The colour bar of the bands: equal steps, ticks at the edges, the top band named."""
    bar = art.colorbar
    if bar is None or quantity == "depth":
        return
    edges = art.norm.boundaries
    if quantity == "fraction":
        bar.set_ticks(edges[:-1])
        names = {len(edges) - 3: " (limit)", len(edges) - 2: " (wall)"}
        bar.set_ticklabels([f"{e:g}{names.get(i, '')}" for i, e in enumerate(edges[:-1])])
    else:
        bar.set_ticks(edges[:-1])
        bar.set_ticklabels([f"{e:.0e}" if 0 < e < 1e-2 else f"{e:g}" for e in edges[:-1]])
    bar.ax.tick_params(labelsize="small")


def _mark_tubes(axis: Any, worst: pd.DataFrame, cell: float) -> list:
    """Rings on the inspected tubes and black dots on the plugged ones; their key entries."""
    out = []
    size = float(np.clip(0.5 * cell, 2.0, 12.0)) ** 2
    seen = worst[worst["inspected"] & ~worst["plugged"]]
    if len(seen):
        axis.scatter(seen["column"], seen["row"], s=size, marker="o", facecolors="none",
                     edgecolors="black", linewidths=0.8, zorder=4)
        out.append(("white", False, f"ringed: inspected ({len(seen)} tube"
                                    f"{'s' * (len(seen) != 1)})"))
    plugged = worst[worst["plugged"]]
    if len(plugged):
        axis.scatter(plugged["column"], plugged["row"], s=size, marker="o", color="black",
                     zorder=4)
        out.append(("black", False, f"black dot: plugged ({len(plugged)} tube"
                                    f"{'s' * (len(plugged) != 1)})"))
    return out


def _sheet_labels(axis: Any, title: str | None = None) -> None:
    axis.set_xlabel("tube column")
    axis.set_ylabel("tube row")
    axis.set_title(title or "tube sheet: worst contact per tube at the last instant")


def _marker_map(worst: pd.DataFrame, ax: Any, label: str, scale: dict):
    """The tube sheet as one square marker a tube, for positions that are not a grid of
    integers (a staggered numbering with half columns): :func:`plot_tube_sheet` otherwise."""
    fig, (axis,), _ = figure_and_axes(ax, 1, lambda f: [f.add_subplot(1, 1, 1)],
                                        figsize=(7, 6), what="plot_tube_sheet")
    ok, bad = worst[~worst["beyond"]], worst[worst["beyond"]]
    size = float(np.clip(2.0e4 / max(len(worst), 1), 4.0, 250.0))  # squares fill a small map
    art = axis.scatter(ok["column"], ok["row"], c=ok["value"], marker="s", s=size,
                       edgecolors="0.3", linewidths=0.4, **scale)
    fig.colorbar(art, ax=axis, label=label)
    if len(bad):
        axis.scatter(bad["column"], bad["row"], c="black", marker="s", s=size)
        axis.scatter(bad["column"], bad["row"], c="white", marker="x", s=size / 2,
                     label="beyond the relation's range")
        axis.legend(loc="upper right", fontsize="small")
    axis.set_aspect("equal", adjustable="datalim")
    _sheet_labels(axis)
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
    marks = [axis.axhline(depth * 1e3, color=color, ls=":", lw=1)
             for depth, color in limits.items()]
    unit = (f" [{units[0]}]" if len(units) == 1
            else " [each contact's own time unit, in the legend]" if mixed else "")
    axis.set_xlabel(f"instant{unit}")
    axis.set_ylabel("global depth of the tube [mm]")
    axis.set_title(f"the {len(summary)} deepest contacts" + (" (dotted: limit depth)"
                                                            if limits else ""))
    if len(summary):
        legend_clear_of(axis, marks, fontsize="x-small", ncol=2)  # not on a limit line
    return fig
