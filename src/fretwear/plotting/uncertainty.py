"""Figures of the uncertainty of wear predictions (:mod:`fretwear.uncertainty`).

* :func:`plot_fan_chart`: depth against time, percentile bands of a Monte Carlo propagation,
  the nominal depth, the limit and the wall;
* :func:`plot_sensitivity`: first-order and total Sobol' indices of the inputs;
* :func:`plot_calibration`: prior and posterior of the wear-coefficient factor, and the
  inspected depths against their predictions;

Each takes results, accepts ``ax=``, returns the :class:`matplotlib.figure.Figure` and leaves the
backend alone (:mod:`fretwear.plotting._common`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.plotting._common import figure_and_axes, legend_clear_of, matplotlib_module
from fretwear.uncertainty.sampling import index_intervals

#: Percentile bands of the fan chart (lower, upper) [-], widest first.
BANDS = ((0.05, 0.95), (0.25, 0.75))


def plot_fan_chart(result, *, bands=BANDS, limit: float | None = None, unit: str = "",
                   ax: Any = None):
    """Worn depth against time: percentile bands, median, nominal, the limit and the wall.

    Parameters
    ----------
    result : UncertaintyResult
        A Monte Carlo propagation (:func:`fretwear.uncertainty.monte_carlo`).
    bands : sequence of (float, float)
        Quantile pairs of the shaded bands [-], widest first (default 5-95 % and 25-75 %).
    limit : float, optional
        Depth limit [m] (default the result's depth_limit × wall_thickness, if any).
    unit : str
        Name of the time unit for the axis label.
    ax : Axes or Figure, optional
        Where to draw (one panel).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from fretwear.uncertainty import LogNormal, monte_carlo
    >>> case = {"contact_type": "TUBE_BAV", "instants": [1.0, 10.0], "time_scale": 3.15e7,
    ...         "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
    ...         "coefficients": {"coefficient": 9.2e-15}, "wall_thickness": 1.09e-3}
    >>> r = monte_carlo(case, 0.01, factor=LogNormal(1.0, sigma_ln=0.5), samples=256)
    >>> plot_fan_chart(r).axes[0].get_ylabel()
    'global depth of the tube [mm]'
    """
    if not hasattr(result, "quantiles") or not hasattr(result, "instants"):
        raise InputError(f"plot_fan_chart takes an UncertaintyResult "
                         f"(fretwear.uncertainty.monte_carlo), not {type(result).__name__}")
    fig, (axis,), own = figure_and_axes(ax, 1, lambda f: [f.add_subplot()], figsize=(7, 4.5),
                                        what="plot_fan_chart")
    t = np.asarray(result.instants, dtype=float)
    levels = sorted({q for pair in bands for q in pair} | {0.5})
    quant = result.quantiles(levels)
    for k, (lo, hi) in enumerate(bands):
        axis.fill_between(t, quant[lo] * 1e3, quant[hi] * 1e3, color="C0",
                          alpha=0.18 + 0.17 * k, lw=0,
                          label=f"{100 * lo:g}-{100 * hi:g} %")
    axis.plot(t, quant[0.5] * 1e3, "-", color="C0", lw=2, label="median")
    axis.plot(t, np.asarray(result.nominal_depth) * 1e3, "--", color="k", lw=1,
              label="nominal")
    value = result.limit if limit is None else float(limit)
    marks = []
    if value is not None:
        marks.append(axis.axhline(value * 1e3, color="C3", ls="--", lw=1.2, label="limit"))
    wall = result.wall_thickness
    top = np.nanmax(np.where(np.isfinite(quant.to_numpy()), quant.to_numpy(), np.nan)) * 1e3
    if wall is not None and top > wall * 1e3:
        marks.append(axis.axhline(wall * 1e3, color="k", lw=1.5, label="wall"))
    axis.set_ylabel(f"{getattr(result, 'depth_of', 'global')} depth of the tube [mm]")
    axis.set_xlabel(f"instant [{unit}]" if unit else "instant")
    axis.grid(alpha=0.3)
    if own:
        axis.set_title(f"{result.name or 'contact'}: {result.samples} samples ({result.method})")
    legend_clear_of(axis, marks, fontsize="small")  # not on the limit or the wall line
    return fig


def plot_sensitivity(result, *, instant: float | None = None, ax: Any = None):
    """First-order and total Sobol' indices, one pair of bars per input.

    Parameters
    ----------
    result : UncertaintyResult or DataFrame
        A propagation (its :meth:`~fretwear.uncertainty.UncertaintyResult.sensitivity` at
        ``instant`` is computed), or that DataFrame (``first``, ``total`` and optionally
        ``first_conf``, ``total_conf``; index = input names).
    instant : float, optional
        Instant of the depth [user time unit] (default the last).
    ax : Axes or Figure, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> s = pd.DataFrame({"first": [0.7, 0.2], "total": [0.77, 0.3]},
    ...                  index=["coefficient", "power"])
    >>> plot_sensitivity(s).axes[0].get_ylabel()
    "Sobol' index [-]"
    """
    table = result if isinstance(result, pd.DataFrame) else result.sensitivity(instant)
    for col in ("first", "total"):
        if col not in table.columns:
            raise InputError(f"plot_sensitivity needs the column {col!r} (Sobol' indices)")
    fig, (axis,), own = figure_and_axes(ax, 1, lambda f: [f.add_subplot()], figsize=(7, 4),
                                        what="plot_sensitivity")
    x = np.arange(len(table))
    bounds = index_intervals(table)  # the interval cut to [0, 1], the range of an index
    clipped = bool(bounds["clipped"].any())
    label = "95 % bootstrap interval" + (", clipped to [0, 1]" if clipped else "")
    for k, (col, name) in enumerate((("first", "first order S_i"),
                                     ("total", "total S_T,i"))):
        axis.bar(x + (k - 0.5) * 0.38, table[col], width=0.38, label=name, color=f"C{k}")
        low = bounds[f"{col}_low"].to_numpy(dtype=float)
        high = bounds[f"{col}_high"].to_numpy(dtype=float)
        shown = np.isfinite(low) & np.isfinite(high)
        if shown.any():
            axis.errorbar((x + (k - 0.5) * 0.38)[shown], (0.5 * (low + high))[shown],
                          yerr=(0.5 * (high - low))[shown], fmt="none", ecolor="k",
                          capsize=3, lw=1, label=label)
            label = None  # one legend entry for both
    axis.set_xticks(x, [str(i) for i in table.index])
    top = float(np.nanmax(table[["first", "total"]].to_numpy()))
    axis.set_ylim(min(0.0, float(np.nanmin(table[["first", "total"]].to_numpy()))),
                  max(1.0, top) + 0.35)  # room for the legend above the bars
    axis.set_yticks(np.linspace(0.0, 1.0, 6))  # an index is in [0, 1]
    axis.set_ylabel("Sobol' index [-]")
    axis.grid(axis="y", alpha=0.3)
    axis.legend(fontsize="small", loc="upper center", ncol=2)
    if own:
        axis.set_title("share of the depth's variance")
    return fig


def plot_calibration(result, *, ax: Any = None):
    """Prior and posterior of the wear-coefficient factor (left), inspected against predicted
    depths (right).

    Parameters
    ----------
    result : CalibrationResult
        From :func:`fretwear.uncertainty.calibrate`.
    ax : two Axes or a Figure, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from fretwear.uncertainty import LogNormal, calibrate
    >>> from fretwear.table import wear_table
    >>> t = wear_table(0.01, contact_type="TUBE_BAV", instants=[10.0], time_scale=3.15e7,
    ...                dimensions={"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
    ...                coefficients={"coefficient": 9.2e-15})
    >>> c = calibrate(t, pd.DataFrame({"instant": [8.0], "depth": [4e-4]}))
    >>> [a.get_xlabel() for a in plot_calibration(c).axes]
    ['wear-coefficient factor f [-]', 'predicted depth [mm]']
    """
    if not hasattr(result, "posterior") or not hasattr(result, "observations"):
        raise InputError(f"plot_calibration takes a CalibrationResult "
                         f"(fretwear.uncertainty.calibrate), not {type(result).__name__}")
    fig, (left, right), own = figure_and_axes(
        ax, 2, lambda f: [f.add_subplot(1, 2, 1), f.add_subplot(1, 2, 2)], figsize=(11, 4.5),
        what="plot_calibration")
    prior, post = result.prior, result.posterior
    lo = min(float(prior.ppf(1e-4)), float(post.ppf(1e-4)))
    hi = max(float(prior.ppf(1 - 1e-4)), float(post.ppf(1 - 1e-4)))
    f = np.geomspace(lo, hi, 600)
    # densities of ln f (what a log axis shows): p_f(f)·f
    left.plot(f, np.asarray(prior.pdf(f)) * f, "--", color="0.4", label=f"prior: {prior}")
    left.plot(f, np.asarray(post.pdf(f)) * f, "-", color="C0", lw=2,
              label=f"posterior ({result.method}): median {result.factor_median:.3g}")
    low, high = result.factor_interval(0.95)
    left.axvspan(low, high, color="C0", alpha=0.12, label=f"95 %: {low:.3g}-{high:.3g}")
    left.set_xscale("log")
    ticker = matplotlib_module("ticker")
    left.xaxis.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
    left.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    left.xaxis.set_minor_formatter(ticker.NullFormatter())
    left.set_xlabel("wear-coefficient factor f [-]")
    left.set_ylabel("density of ln f [-]")
    left.legend(fontsize="small")
    left.grid(alpha=0.3)
    obs = result.observations
    measured = obs["depth"].to_numpy(dtype=float) * 1e3
    sig = obs["measurement_sigma"].to_numpy(dtype=float)
    for column, marker, label in (("prior_depth", "s", "prior median"),
                                  ("posterior_depth", "o", "posterior median")):
        right.errorbar(obs[column] * 1e3, measured,
                       yerr=[measured * (1 - np.exp(-sig)), measured * (np.exp(sig) - 1)],
                       fmt=marker, ms=5, capsize=2, label=label,
                       mfc="white" if marker == "s" else None)
    span = np.concatenate([measured, obs["prior_depth"] * 1e3, obs["posterior_depth"] * 1e3])
    span = span[np.isfinite(span)]
    if span.size:
        line = [0.0, 1.1 * float(span.max())]
        right.plot(line, line, ":", color="0.5", lw=1, label="measured = predicted")
    right.set_xlabel("predicted depth [mm]")
    right.set_ylabel("inspected depth [mm] (±1σ)")
    right.grid(alpha=0.3)
    if own:
        fig.suptitle(f"calibration on {len(obs)} inspection(s)")
        fig.tight_layout()
    legend_clear_of(right, [], fontsize="small")  # on no inspection nor its bar
    return fig
