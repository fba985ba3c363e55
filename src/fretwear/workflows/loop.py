"""The coupled loop dynamics → wear table → obstacle update → dynamics (``fretwear iterate``).

Code_Aster R7.20.01 §6 (theory §8): from a clearance figure, compute the dynamics; from its contact
history, the wear table (POST_USURE); from the table's cumulated sector volumes, the worn
clearance figure (MODI_OBSTACLE); compute the dynamics again with it, and so on. Each cycle
continues the previous cycle's wear table through the restart (ETAT_INIT, theory §7), so the
volumes accumulate over the cycles and the obstacle update always starts from the new obstacle
with the cumulated volumes (theory §8).

The case file holds the usual wear sections (``[law]``, ``[geometry]``, ``[sectors]``,
``[time]``: the durations of one cycle, ``[power]`` window), an ``[obstacle]`` section (the new
obstacle and the mobile's wall), a ``[dynamics]`` section (:mod:`fretwear.dynamics.config`) and an
``[iterate]`` section (:data:`ITERATE_KEYS`).
"""

from __future__ import annotations

import json
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import require
from fretwear.dynamics.config import DynamicsSetup, dynamics_from_config
from fretwear.dynamics.integrate import simulate
from fretwear.errors import FretwearWarning, KeywordError
from fretwear.history import CHANNELS, ContactHistory
from fretwear.io import iter_history_chunks
from fretwear.io.atomic import atomic_folder, atomic_path, atomic_write
from fretwear.keys import check_keys
from fretwear.obstacle.config import obstacle_from_config
from fretwear.plotting import (
    plot_contact_history,
    plot_iteration,
    plot_obstacle,
    save_figure,
    wear_figures,
)
from fretwear.power import PowerAccumulator
from fretwear.power.confidence import ensemble_interval
from fretwear.table import WearCase, wear_table_from_case, write_wear_table
from fretwear.table.schema import FLOAT_FORMAT
from fretwear.workflows.case_files import (
    case_arguments,
    chunked_power,
    read_case_toml,
    validate_case,
)
from fretwear.workflows.loop_noise import (
    DEFAULT_CONFIDENCE_BLOCKS,
    DEFAULT_CONFIDENCE_LEVEL,
    convergence_verdict,
    cycle_interval,
    ensemble_power,
    largest_depth,
    max_depth_noise,
    noise_columns,
    reseeded,
    warn_if_noisy,
)

#: key -> (type, description with unit) of the ``[iterate]`` section.
ITERATE_KEYS: dict[str, tuple[Any, str]] = {
    "cycles": (int, "number of cycles dynamics → wear → obstacle (default 1)"),
    "max_depth_m": ((int, float), "stop after the cycle where the worn depth named by "
                                  "max_depth_of reaches this [m]"),
    "max_depth_of": (str, "which depth max_depth_m compares: 'global' (the wear table's depths "
                          "from the total volumes), 'sector' (the largest sector depth), "
                          "'profile' (the obstacle update's depth profiles) or 'largest' of "
                          "them (default), each of the mobile and the obstacle"),
    "shock": (str, "name of the shock whose history feeds the wear table (default the first)"),
    "output": (str, "output folder, relative to the case file (default 'iterate')"),
    "plot": (bool, "write figures for every cycle (default true)"),
    "stop_on_perforation": (bool, "stop when the mobile is perforated (default true)"),
    "confidence_level": (float, "confidence level of each cycle's power interval (default "
                                "0.95)"),
    "confidence_blocks": (int, "blocks of the batch-means interval of each cycle's power when "
                               "[power] blocks is below 2 (default 10)"),
    "ensemble": (int, "runs of each cycle's dynamics with the random signals' seeds moved by "
                      "1000 per run: the cycle's power is their mean and its interval theirs "
                      "(default 1: one run, a batch-means interval)"),
    "convergence_tolerance": ((int, float), "stop when the power's relative change between two "
                                            "cycles is inside ±this beyond the noise (the "
                                            "interval of the change inside the band) [-]"),
}


def _check_iterate(section: Mapping[str, Any]) -> dict[str, Any]:
    check_keys(section, ITERATE_KEYS, "[iterate]")
    out = dict(section)
    if out.get("cycles", 1) < 1:
        raise KeywordError(f"[iterate] cycles must be >= 1, got {out['cycles']}")
    level = out.get("confidence_level", DEFAULT_CONFIDENCE_LEVEL)
    if isinstance(level, bool) or not 0.0 < level < 1.0:
        raise KeywordError(f"[iterate] confidence_level must be a probability in (0, 1) "
                           f"(e.g. 0.95), got {level!r}")
    blocks = out.get("confidence_blocks", DEFAULT_CONFIDENCE_BLOCKS)
    if isinstance(blocks, bool) or not 2 <= blocks <= 10_000:
        raise KeywordError(f"[iterate] confidence_blocks must be an integer in 2..10000 (10 "
                           f"or more for a checked interval), got {blocks!r}")
    runs = out.get("ensemble", 1)
    if isinstance(runs, bool) or not 1 <= runs <= 1000:
        raise KeywordError(f"[iterate] ensemble must be an integer in 1..1000 (runs of each "
                           f"cycle; 5 or more for an interval), got {runs!r}")
    tolerance = out.get("convergence_tolerance")
    if tolerance is not None and (isinstance(tolerance, bool) or not 0.0 < tolerance < 1.0):
        raise KeywordError(f"[iterate] convergence_tolerance is a relative change in (0, 1) "
                           f"(e.g. 0.05 for 5 %), got {tolerance!r}")
    if out.get("max_depth_of", "largest") not in DEPTHS_OF:
        raise KeywordError(f"[iterate] max_depth_of = {out['max_depth_of']!r}: choose one of "
                           f"{list(DEPTHS_OF)}")
    return out


#: The depths the stop criterion max_depth_m may compare: name -> summary columns.
DEPTHS_OF: dict[str, tuple[str, ...]] = {
    "global": ("depth_global_mobile", "depth_global_obstacle"),
    "sector": ("depth_sector_mobile_max", "depth_sector_obstacle_max"),
    "profile": ("depth_mobile_max", "depth_obstacle_max"),
}
DEPTHS_OF["largest"] = tuple(c for cols in list(DEPTHS_OF.values()) for c in cols)


def _table_depths(table: pd.DataFrame) -> dict[str, float]:
    """Global and largest sector depths [m] of the mobile and the obstacle at the table's last
    instant (NaN where the table has none)."""
    last = table[table["instant"] == table["instant"].iloc[-1]]

    def top(column: str) -> float:
        if column not in last.columns:
            return float("nan")
        values = last[column].to_numpy(dtype=float)
        return float(np.nanmax(values)) if np.isfinite(values).any() else float("nan")

    return {"depth_global_mobile": top("depth_mobile"),
            "depth_global_obstacle": top("depth_obstacle"),
            "depth_sector_mobile_max": top("depth_mobile_sector"),
            "depth_sector_obstacle_max": top("depth_obstacle_sector")}


def load_iterate_case(case: str | Path | Mapping[str, Any]) -> dict[str, Any]:
    """Read a case file (or dict) for the loop: validated wear sections plus the raw
    ``[dynamics]`` and checked ``[iterate]`` sections; ``_directory`` is the file's folder.

    Raises
    ------
    InputError
        Missing file, invalid TOML.
    KeywordError
        Unknown sections or keys (with the closest valid name), missing sections.

    Examples
    --------
    >>> c = load_iterate_case({
    ...     "law": {"name": "ARCHARD", "mobile": {"COEF_USURE": 1e-14}},
    ...     "geometry": {"contact_type": "TUBE_ALESAGE", "mobile_radius_m": 9.5e-3,
    ...                  "obstacle_width_m": 0.02},
    ...     "sectors": {"count": 8}, "time": {"instants": [1.0], "unit": "year"},
    ...     "obstacle": {"gap_m": 2e-4, "wall_thickness_m": 1.1e-3},
    ...     "dynamics": {"duration_s": 1.0}, "iterate": {"cycles": 3}})
    >>> c["iterate"], c["dynamics"]
    ({'cycles': 3}, {'duration_s': 1.0})
    >>> load_iterate_case({"iterate": {"cycle": 2}})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    fretwear.errors.KeywordError: [iterate]: unknown key cycle (did you mean 'cycles'?); ...
    """
    if isinstance(case, Mapping):
        raw = dict(case)
        source, directory = "case", raw.pop("_directory", None)
    else:
        raw, directory = read_case_toml(case)
        source = str(case)
    dynamics = raw.pop("dynamics", None)
    iterate = _check_iterate(raw.pop("iterate", {}))
    if dynamics is None:
        raise KeywordError(f"{source}: the loop needs a [dynamics] section (modes, shocks, "
                           "excitation); see docs/dynamics.md")
    if "obstacle" not in raw:
        raise KeywordError(f"{source}: the loop needs an [obstacle] section (the new obstacle "
                           "and the mobile's wall thickness) for the obstacle update")
    power = raw.get("power", {})  # a section, or a top-level key validate_case names
    if "history" in raw or (isinstance(power, Mapping) and "value_W" in power):
        raise KeywordError(f"{source}: [history] file / [power] value_W are not used by the loop "
                           "(the history comes from [dynamics]); remove them")
    out = validate_case(raw, source=source)
    out["dynamics"], out["iterate"] = dict(dynamics), iterate
    out["_directory"] = directory
    return out


@dataclass
class IterationResult:
    """What the loop produced.

    Attributes
    ----------
    summary : DataFrame
        One row per cycle: ``cycle``, ``instant`` (end of the cycle) [user unit], ``power`` [W],
        ``wear_power_steps`` [W] (integrated at every time step over the whole computation,
        not only the ``[power]`` window), ``depth_mobile_max``,
        ``depth_obstacle_max`` [m] (the largest obstacle-profile depths of the update),
        ``clearance_min``, ``clearance_max`` [m] (after the update), ``contact_fraction`` [-],
        ``perforated``, ``depth_global_mobile``, ``depth_global_obstacle`` [m] (the wear
        table's global depths, from the total volumes), ``depth_sector_mobile_max``,
        ``depth_sector_obstacle_max`` [m] (its largest sector depths) at the cycle's end;
        the noise of the cycle (:mod:`fretwear.workflows.loop_noise`): ``power_low``,
        ``power_high``, ``power_half_width`` [W] (the confidence interval of ``power``, batch
        means over the cycle's history, or Student's over an ensemble's runs),
        ``power_level`` [-], ``power_interval_count`` [-] (blocks, or runs),
        ``power_interval_method`` (``"batch means"`` or ``"ensemble"``),
        ``power_change`` [W] (from the previous cycle), ``power_change_half_width`` [W] (the
        two intervals in quadrature), ``power_change_significant`` (the change is beyond its
        interval; None on cycle 1), ``depth_increment_half_width`` [m] (the compared depth's
        increment over the cycle times the power's relative half-width: the increment's
        uncertainty, an upper bound for a law linear in the power and a depth concave in the
        volume), ``max_depth_within_noise`` (the ``max_depth_m`` decision is inside that
        uncertainty).
    tables : list of DataFrame
        The wear table after each cycle (each continues the previous one).
    profiles : list of ObstacleResult
        The obstacle update after each cycle.
    directory : Path or None
        Output folder.
    stopped : str
        Why the loop stopped: ``"cycles"``, ``"max_depth"``, ``"perforation"``,
        ``"converged"`` or ``"invalid_profile"``.
    warnings : list of str
    max_depth_of : str
        Which depth the ``max_depth_m`` criterion compared (:data:`DEPTHS_OF`).
    intervals : list of PowerInterval
        Each cycle's power with its confidence interval (``str()``: ``P = … ± … W (95 %)``).
    convergence : tuple of str
        (verdict, sentence) of :func:`fretwear.workflows.loop_noise.convergence_verdict`:
        whether the loop's power converged beyond the noise.
    """

    summary: pd.DataFrame
    tables: list[pd.DataFrame]
    profiles: list[Any]
    directory: Path | None
    stopped: str
    warnings: list[str] = field(default_factory=list)
    max_depth_of: str = "largest"
    intervals: list[Any] = field(default_factory=list)
    convergence: tuple[str, str] = ("one cycle", "")


def _wear_case(case: Mapping[str, Any]) -> tuple[dict[str, Any], WearCase]:
    """(the wear keywords, the validated wear case) of the loop's case, before any dynamics."""
    # the history comes from [dynamics] (load_iterate_case refuses [history] and value_W)
    args = case_arguments(case, history_elsewhere=True)
    wear = WearCase.from_keywords(**args)  # every rule of the wear keywords, checked once
    if wear.sectors is None:
        raise KeywordError("case: the loop needs [sectors] (count or edges_deg): the obstacle "
                           "update uses the cumulated sector volumes")
    return args, wear


def iterate_case(case: str | Path | Mapping[str, Any], *, output: str | Path | None = None,
                 cycles: int | None = None, plot: bool | None = None,
                 progress: Callable[[str], None] | None = None) -> IterationResult:
    """Run the coupled loop of a case: dynamics → wear table → obstacle update, repeated.

    Parameters
    ----------
    case : path-like or mapping
        The case file (or its content as a dict) with ``[dynamics]``, ``[obstacle]``,
        ``[sectors]``, ``[law]``, ``[geometry]``, ``[time]`` and optionally ``[iterate]``.
    output : path-like, optional
        Output folder (default ``[iterate] output``, else ``iterate`` beside the case file);
        ``cycle_NN/`` holds each cycle's history (Parquet), wear table (CSV), profile (CSV and
        DISCRET) and figures; ``summary.csv`` and ``summary.json`` the per-cycle summary.
    cycles : int, optional
        Overrides ``[iterate] cycles``.
    plot : bool, optional
        Overrides ``[iterate] plot``.
    progress : callable, optional
        ``progress(message)`` before each stage.

    Returns
    -------
    IterationResult

    Notes
    -----
    Cycle k: the shocks with ``obstacle = "case"`` see the clearance figure of the new mobile
    in the new obstacle (k = 1: how far it can translate in each direction, which differs from
    the radial gap for planes and tables) or, for the wear shock, the worn clearance figure of
    cycle k − 1 (a discrete polar profile, 0.5° steps); the wear shock's
    history gives the power over the ``[power]`` window; the wear table of cycle k continues the
    table of cycle k − 1 (ETAT_INIT) over the ``[time] instants`` (the durations of one cycle);
    the obstacle update uses its cumulated sector volumes at the last instant.

    References
    ----------
    .. [1] fretwear theory, docs/theory.md §8.
    .. [2] Code_Aster Reference Manual R7.20.01 (theory of POST_USURE), §6 (updating the table, the
           iterative loop).
    .. [3] EDF-DER (1998). [Control rods of 1300 MW plants: iterative wear computations with
           progressive wear of the antagonists]. Report HT.22/98-009A (in French).
    """
    say = progress or (lambda message: None)
    # the dynamics histories of every cycle are Parquet files: say so before computing anything
    require("pyarrow.parquet", purpose="the coupled loop (its dynamics histories are Parquet)")
    case = load_iterate_case(case)
    it = case["iterate"]
    n_cycles = int(cycles if cycles is not None else it.get("cycles", 1))
    do_plot = bool(plot if plot is not None else it.get("plot", True))
    if do_plot:  # before any computation, not after the first cycle
        require("matplotlib.pyplot", purpose="the loop's figures ([iterate] plot = false or "
                                             "plot=False skips them)")
    directory = case.get("_directory")
    if output is None:
        out = Path(it.get("output", "iterate"))
        output = out if out.is_absolute() or directory is None else Path(directory) / out
    out_dir = Path(output)
    setup: DynamicsSetup = dynamics_from_config(case["dynamics"], directory=directory)
    names = [s.label for s in setup.shocks]
    wear_shock = it.get("shock", names[0])
    if wear_shock not in names:
        raise KeywordError(f"[iterate] shock = {wear_shock!r} is not a shock of [dynamics]; "
                           f"choose one of {names}")
    iw = names.index(wear_shock)
    args, wear = _wear_case(case)
    obstacle = obstacle_from_config(case)
    new = obstacle.obstacle
    if not setup.case_obstacle[iw]:
        warnings.warn(f"the wear shock {wear_shock!r} does not use obstacle = \"case\": its "
                      "obstacle will be replaced by the worn profile from cycle 2 on, but cycle 1 "
                      "uses its own obstacle, not the [obstacle] section's", FretwearWarning,
                      stacklevel=2)
    grid = np.arange(0.0, 360.0, 0.5)
    # The clearance figure of the new mobile (equal to the radial gap only for a bore).
    new_profile = (grid, np.asarray(new.clearance(grid), dtype=float))
    profile = new_profile
    max_depth = it.get("max_depth_m")
    depth_of = it.get("max_depth_of", "largest")
    level = float(it.get("confidence_level", DEFAULT_CONFIDENCE_LEVEL))
    tolerance = it.get("convergence_tolerance")
    args_interval = {**args, "blocks": int(it.get("confidence_blocks",
                                                  DEFAULT_CONFIDENCE_BLOCKS))}
    ensemble = int(it.get("ensemble", 1))
    if ensemble > 1:
        reseeded(setup.excitations, 1)  # a case with no random signal is refused up front
    rows, tables, profiles, intervals = [], [], [], []
    stopped = "cycles"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for k in range(1, n_cycles + 1):
            final = out_dir / f"cycle_{k:02d}"
            # written in a hidden folder, then put in place whole: a run killed at any
            # instant leaves the old cycle folder or the complete new one, never a mix
            with atomic_folder(final) as cdir:
                say(f"cycle {k}/{n_cycles}: dynamics")
                profiles_k = {i: new_profile for i, c in enumerate(setup.case_obstacle) if c}
                if k > 1:
                    profiles_k[iw] = profile
                shocks = setup.shocks_with(profiles_k)
                result, power, history, contact, interval, steps = _cycle_runs(
                    setup, shocks, iw, args, args_interval, cdir, level, ensemble,
                    lambda what, k=k: say(f"cycle {k}/{n_cycles}: {what}"))
                warn_if_noisy(k, interval)
                say(f"cycle {k}/{n_cycles}: wear table")
                table = wear_table_from_case(wear, power)
                say(f"cycle {k}/{n_cycles}: obstacle update")
                update = obstacle.update(table)
                wear = wear.with_initial_state(table)  # the next cycle continues this table
                profile = (np.asarray(update.angle, float),
                           np.asarray(update.clearance_worn, float))
                seen = shocks[iw]
                figures = {"clearance (new)": (update.angle, update.clearance_initial),
                           "clearance seen by the dynamics":
                               (seen.profile_angles, seen.profile_gaps)
                               if seen.obstacle == "profile" else None,
                           "clearance after the update": (update.angle, update.clearance_worn)}
                _write_cycle(cdir, table, update, result, history, do_plot,
                             {k: v for k, v in figures.items() if v is not None}, final)
            tables.append(table)
            profiles.append(update)
            instant = float(np.max(table["instant"]))
            row = {"cycle": k, "instant": instant, "power": float(power.total),
                   "wear_power_steps": steps,
                   "depth_mobile_max": float(np.nanmax(update.depth_mobile)),
                   "depth_obstacle_max": float(np.nanmax(update.depth_obstacle)),
                   "clearance_min": float(np.nanmin(update.clearance_worn)),
                   "clearance_max": float(np.nanmax(update.clearance_worn)),
                   "contact_fraction": contact,
                   "perforated": bool(update.perforated), **_table_depths(table)}
            compared_columns = DEPTHS_OF[depth_of]
            compared = largest_depth(row, compared_columns)  # None when none is finite
            depth_now = compared if compared is not None else 0.0
            depth_before = (largest_depth(rows[-1], compared_columns) if rows else None) or 0.0
            row.update(noise_columns(interval, intervals[-1] if intervals else None,
                                     depth_now - depth_before))
            row["max_depth_within_noise"] = (max_depth_noise(row, compared_columns, max_depth)
                                             if max_depth is not None else False)
            rows.append(row)
            intervals.append(interval)
            if not np.all(np.isfinite(profile[1])):
                warnings.warn(f"cycle {k}: the worn clearance has undefined values (depth beyond "
                              "the geometry's range); the loop stops", FretwearWarning,
                              stacklevel=2)
                stopped = "invalid_profile"
                break
            if update.perforated and it.get("stop_on_perforation", True):
                stopped = "perforation"
                break
            if max_depth is not None and compared is not None and compared >= max_depth:
                stopped = "max_depth"
                break
            if (tolerance is not None and k < n_cycles
                    and convergence_verdict(pd.DataFrame(rows), tolerance)[0] == "converged"):
                stopped = "converged"
                break
    summary = pd.DataFrame(rows)
    convergence = convergence_verdict(summary, tolerance)
    _write_summary(out_dir, summary, stopped, do_plot, profiles,
                   {"max_depth_m": max_depth, "max_depth_of": depth_of,
                    "max_depth_columns": list(DEPTHS_OF[depth_of]),
                    "convergence_tolerance": tolerance, "convergence": convergence[0],
                    "convergence_said": convergence[1],
                    "power_intervals": [str(iv) for iv in intervals]})
    texts = []
    for w in caught:
        t = f"{w.category.__name__}: {w.message}"
        if t not in texts:
            texts.append(t)
    return IterationResult(summary=summary, tables=tables, profiles=profiles,
                           directory=out_dir, stopped=stopped, warnings=texts,
                           max_depth_of=depth_of, intervals=intervals,
                           convergence=convergence)



#: Wear-shock histories up to this many samples are read whole by the loop; longer ones are
#: reduced chunk by chunk from their Parquet file (bounded memory).
LOOP_IN_MEMORY = 2_000_000
#: Samples kept (evenly spaced) for the figure of a history reduced chunk by chunk.
PLOT_SAMPLES = 200_000
#: Samples per chunk of that reduction.
LOOP_CHUNK = 1_000_000


def _cycle_runs(setup, shocks, iw: int, args, args_interval, cdir: Path, level: float,
                ensemble: int, say):
    """The dynamics of one cycle, once or as an ensemble of ``ensemble`` runs (random seeds
    moved by :func:`~fretwear.workflows.loop_noise.reseeded`), and its power.

    Returns (the first run's DynamicsResult, the power for the wear table [W], the first run's
    history, the contact fraction [-], the power's PowerInterval, the power integrated over
    the steps [W]); with an ensemble the power, the contact fraction and the steps' power are
    the runs' means, the interval the runs' Student interval
    (:func:`fretwear.power.ensemble_interval`), and run r's histories are in
    ``histories_run{r:02d}/`` (run 1 in ``histories/``).
    """
    powers, contacts, steps = [], [], []
    first = history = split = None
    for r in range(ensemble):
        say("dynamics" if ensemble == 1 else f"dynamics, run {r + 1}/{ensemble}")
        folder = cdir / ("histories" if r == 0 else f"histories_run{r + 1:02d}")
        result = simulate(setup.model, shocks, reseeded(setup.excitations, r),
                          output_dir=folder, **setup.options)
        say("wear power")
        power, h, contact, s = _cycle_power(result, iw, args, args_interval)
        if r == 0:
            first, history, split = result, h, s
        powers.append(power)
        contacts.append(contact)
        steps.append(float(result.wear_power[iw]))
    if ensemble == 1:
        interval = cycle_interval(powers[0], level, interval_power=split)
    else:
        interval = ensemble_interval(powers, level)
    return (first, ensemble_power(powers), history, float(np.mean(contacts)), interval,
            float(np.mean(steps)))


def _cycle_power(result, iw: int, args: Mapping[str, Any], args_interval: Mapping[str, Any]):
    """(PowerResult, history for the wear table / figures, contact fraction, the power in the
    interval's blocks or None) of the wear shock.

    The wear table's power keeps the user's ``[power] blocks``; when they are fewer than 2, the
    same window is reduced a second time in ``args_interval["blocks"]`` blocks for the
    batch-means interval of the cycle's power.

    Short histories are read whole (:func:`fretwear.workflows.case_files.chunked_power`). Long
    ones are reduced from the Parquet file by :class:`fretwear.power.PowerAccumulator` over
    :func:`fretwear.io.iter_history_chunks` (one shared sample between chunks, so the result is
    the one-shot reduction), keeping an evenly decimated copy for the figures.
    """
    pq = require("pyarrow.parquet", purpose="the coupled loop (its dynamics histories are Parquet)")
    path = result.files[result.shock_names[iw]]
    n = pq.ParquetFile(path).metadata.num_rows
    if n <= LOOP_IN_MEMORY:
        history = result.history(iw)
        split = None
        if args.get("blocks", 1) < 2:
            with warnings.catch_warnings():  # the table's own power says its stationarity
                warnings.simplefilter("ignore")
                split = chunked_power(history, args_interval)
        return (chunked_power(history, args), history,
                float(np.mean(history.normal_force > 0)), split)
    window = dict(
        t_start=args.get("t_start") if args.get("t_start") is not None else result.start_time,
        t_end=args.get("t_end") if args.get("t_end") is not None else result.end_time,
        sectors=args.get("sectors"))
    acc = PowerAccumulator(blocks=args.get("blocks", 1), **window)
    acc_split = (PowerAccumulator(blocks=args_interval["blocks"], **window)
                 if args.get("blocks", 1) < 2 else None)
    stride = max(1, n // PLOT_SAMPLES)
    kept: dict[str, list] = {c: [] for c in CHANNELS}
    in_contact = 0
    row = 0
    for j, chunk in enumerate(iter_history_chunks(path, chunk_size=LOOP_CHUNK)):
        acc.update(chunk)
        if acc_split is not None:
            acc_split.update(chunk)
        skip = 0 if j == 0 else 1  # the sample shared with the previous chunk
        fn = chunk.normal_force[skip:]
        in_contact += int(np.count_nonzero(fn > 0))
        first = row + skip
        pick = np.arange((-first) % stride, fn.size, stride)
        for c in CHANNELS:
            kept[c].append(np.asarray(getattr(chunk, c))[skip:][pick])
        row = first + fn.size - 1
    threshold = args.get("stationarity_threshold", 0.1)
    power = acc.result(stationarity_threshold=threshold)
    split = None
    if acc_split is not None:
        with warnings.catch_warnings():  # the table's own power says its stationarity
            warnings.simplefilter("ignore")
            split = acc_split.result(stationarity_threshold=threshold)
    light = ContactHistory(**{c: np.concatenate(v) for c, v in kept.items()},
                           name=result.shock_names[iw],
                           metadata={"source": str(path), "decimated_by": stride})
    return power, light, in_contact / n, split


def _write_cycle(cdir: Path, table, update, result, history, do_plot: bool, figures,
                 final: Path) -> None:
    """Write a cycle's files into ``cdir``, the temporary folder that becomes ``final``."""
    write_wear_table(table, cdir / "wear_table.csv")
    update.write(cdir / "obstacle_profile.csv")
    if np.all(np.isfinite(update.clearance_worn)):
        update.write_discret(cdir / "obstacle_discret.txt")
    else:
        warnings.warn(f"{cdir.name}: the worn clearance has NaN values (depth beyond the "
                      "geometry's range): obstacle_discret.txt not written", FretwearWarning,
                      stacklevel=2)
    summary = result.summary()
    summary["files"] = {k: str(final / Path(v).relative_to(cdir))  # paths once in place
                        for k, v in summary.get("files", {}).items()}
    with atomic_write(cdir / "dynamics.json", "w", encoding="utf-8") as fh:
        json.dump(summary, fh, indent=2)
    if do_plot:
        save_figure(plot_contact_history(history, profiles=figures), cdir, "contact_history",
                    dpi=110, close=True)
        for what, draw in (
                ("wear-table", lambda: {f"wear_{k}": f for k, f in wear_figures(table).items()}),
                ("obstacle", lambda: {"obstacle_polar": plot_obstacle(update)})):
            try:
                for stem, fig in draw().items():
                    save_figure(fig, cdir, stem, close=True)
            except Exception as exc:  # noqa: BLE001 - a figure must not stop the loop
                warnings.warn(f"{what} figure of {cdir.name} not written: {exc}",
                              FretwearWarning, stacklevel=2)


def _write_summary(out_dir: Path, summary: pd.DataFrame, stopped: str, do_plot: bool,
                   profiles, criterion: dict[str, Any]) -> None:
    with atomic_path(out_dir / "summary.csv") as tmp:
        summary.to_csv(tmp, index=False, float_format=FLOAT_FORMAT)
    with atomic_write(out_dir / "summary.json", "w", encoding="utf-8") as fh:
        json.dump({"stopped": stopped, **criterion,
                   "cycles": summary.to_dict(orient="records")}, fh, indent=2)
    if do_plot and len(summary):
        fig = plot_iteration(summary, [(p.angle, p.clearance_worn) for p in profiles])
        save_figure(fig, out_dir, "iteration", dpi=110, close=True)
