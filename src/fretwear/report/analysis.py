"""One case analysed end to end: the wear table, the power's interval, the Monte Carlo
propagation of the wear coefficients' scatter, and optionally the calibration on inspections.

The ``[uncertainty]`` section of a case file (keys :data:`UNCERTAINTY_KEYS`) sets the scatter and
the sampling; the command-line options of ``fretwear report`` override it.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear.errors import FretwearWarning, InputError
from fretwear.keys import check_keys
from fretwear.power import PowerResult
from fretwear.power.confidence import PowerInterval
from fretwear.uncertainty import LogNormal, calibrate, monte_carlo
from fretwear.uncertainty.calibration import CalibrationResult
from fretwear.uncertainty.monte_carlo import UncertaintyResult
from fretwear.uncertainty.sampling import METHODS
from fretwear.workflows.case_files import CaseResult, load_case, run_case

__all__ = ["UNCERTAINTY_KEYS", "Analysis", "analyse_case", "uncertainty_options"]

#: key -> (type, description with unit) of a case file's ``[uncertainty]`` section.
UNCERTAINTY_KEYS: dict[str, tuple[Any, str]] = {
    "coefficient_scatter": ((int, float), "factor F > 1 such that the wear coefficients lie "
                                          "within [K/F, K·F] with 95 % probability (lognormal), "
                                          "default 3"),
    "coefficient_sigma_ln": ((int, float), "standard deviation of ln K [-] instead of the "
                                           "scatter factor"),
    "power": (str, "'interval' (default: the block powers' batch-means interval, when the "
                   "power has >= 2 blocks) or 'fixed'"),
    "samples": (int, "Monte Carlo samples (rounded up to a power of 2 for sobol), default 4096"),
    "method": (str, f"sampling: {' or '.join(METHODS)} (default sobol)"),
    "seed": (int, "seed of the sampling, default 0"),
    "level": ((int, float), "confidence level of the power's interval [-], default 0.95"),
    "inspections": (str, "CSV of inspected depths (contact, sector, instant, depth or "
                         "depth_mm, measurement_sigma), relative to the case file"),
    "measurement_sigma": ((int, float), "standard deviation of ln(measured depth) [-], "
                                        "default 0.1"),
    "forecast": ((int, float), "instant [time unit] of the posterior predictive (next outage)"),
}
#: Defaults of the ``[uncertainty]`` keys.
DEFAULTS = {"coefficient_scatter": 3.0, "power": "interval", "samples": 4096, "method": "sobol",
            "seed": 0, "level": 0.95, "measurement_sigma": 0.1}


@dataclass
class Analysis:
    """What ``fretwear report`` shows.

    Attributes
    ----------
    case : CaseResult
        The run of the case (table, power, warnings, validated case, wear case).
    interval : PowerInterval or None
        The power's confidence interval (None with fewer than 2 blocks or a given power).
    sector_intervals : list of PowerInterval
        The sector powers' intervals.
    uncertainty : UncertaintyResult or None
        The Monte Carlo propagation (global depth).
    calibration : CalibrationResult or None
        The calibration on inspections.
    options : dict
        The ``[uncertainty]`` options used (defaults filled in).
    warnings : list of str
        Warnings of the analysis beyond the run's (confidence, ranges).
    source : str
        The case file (or "(dict)").
    """

    case: CaseResult
    interval: PowerInterval | None = None
    sector_intervals: list = field(default_factory=list)
    uncertainty: UncertaintyResult | None = None
    calibration: CalibrationResult | None = None
    options: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    source: str = "(dict)"


def uncertainty_options(case: Mapping[str, Any], overrides: Mapping[str, Any] | None = None
                        ) -> dict[str, Any]:
    """The ``[uncertainty]`` options of a case with the defaults and the ``overrides`` (None
    values ignored), checked.

    Examples
    --------
    >>> uncertainty_options({}, {"samples": 1024})["samples"]
    1024
    """
    section = dict(case.get("uncertainty", {}))
    check_keys(section, UNCERTAINTY_KEYS, "[uncertainty]")
    out = {**DEFAULTS, **section, **{k: v for k, v in (overrides or {}).items()
                                     if v is not None}}
    if "coefficient_sigma_ln" in section and "coefficient_scatter" in section:
        raise InputError("[uncertainty]: give coefficient_scatter or coefficient_sigma_ln, "
                         "not both")
    if (overrides or {}).get("coefficient_sigma_ln") is not None:
        out.pop("coefficient_scatter", None)
    if out["power"] not in ("interval", "fixed"):
        raise InputError(f"[uncertainty] power = {out['power']!r}: 'interval' or 'fixed'")
    if out["method"] not in METHODS:
        raise InputError(f"[uncertainty] method = {out['method']!r}: one of {list(METHODS)}")
    return out


def _factor(options: Mapping[str, Any]) -> LogNormal:
    if options.get("coefficient_sigma_ln") is not None:
        return LogNormal(1.0, sigma_ln=float(options["coefficient_sigma_ln"]))
    return LogNormal(1.0, scatter=float(options["coefficient_scatter"]))


def _instants(result: CaseResult) -> np.ndarray:
    """The durations of the fan chart [user unit]: the case's and 24 evenly spaced ones."""
    durations = np.asarray(result.wear_case.instants, dtype=float)
    grid = np.linspace(0.0, durations.max(), 25)[1:]
    return np.unique(np.concatenate([durations[durations > 0], grid]))


def analyse_case(case, *, result: CaseResult | None = None, inspections=None,
                 source: str | os.PathLike | None = None, **overrides) -> Analysis:
    """Run a case and analyse its uncertainty.

    Parameters
    ----------
    case : path-like or mapping
        A TOML case file or its dict (``[uncertainty]`` section optional).
    result : CaseResult, optional
        The case's run when it has been run already (``fretwear run --report``).
    inspections : path-like or DataFrame, optional
        Inspected depths for a calibration (default the section's ``inspections``).
    source : path-like, optional
        The case file the report names, when ``case`` is its loaded dict (else "(dict)").
    **overrides
        Options of :data:`UNCERTAINTY_KEYS` replacing the section's (None: keep).

    Returns
    -------
    Analysis

    Notes
    -----
    The wear coefficients' scatter is a factor f ~ LogNormal(1, σ) on every coefficient (of both
    bodies and every sector), the power's the batch-means interval of its blocks
    (docs/uncertainty.md). Sobol' indices are computed for the depth at the last instant.
    """
    # the case file the report names (a loaded case's dict does not hold its name)
    source = (os.fspath(source) if source is not None
              else "(dict)" if isinstance(case, Mapping) else os.fspath(case))
    data = dict(case) if isinstance(case, Mapping) else load_case(case)
    options = uncertainty_options(data, overrides)
    result = run_case(data) if result is None else result
    notes: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        interval, sector_intervals = None, []
        power = result.power
        if isinstance(power, PowerResult) and len(power.blocks) >= 2:
            interval = power.confidence_interval(float(options["level"]))
            sector_intervals = power.sector_confidence_intervals(float(options["level"]))
        scatter = "interval" if options["power"] == "interval" and interval is not None \
            else "fixed"
        mc = monte_carlo(result.table, interval if interval is not None else power,
                         factor=_factor(options), power_scatter=scatter,
                         samples=int(options["samples"]), seed=int(options["seed"]),
                         method=options["method"], instants=_instants(result),
                         name=result.wear_case.name or "")
        mc.sensitivity()
        if mc.limit is not None:
            mc.time_to_limit()
        calibration = None
        path = inspections if inspections is not None else options.get("inspections")
        if path is not None:
            if isinstance(path, str) and not Path(path).is_absolute():
                path = Path(data.get("_directory", ".")) / path
            calibration = calibrate(result.table, path, prior=_factor(options),
                                    measurement_sigma=float(options["measurement_sigma"]),
                                    forecast=options.get("forecast"))
    for w in caught:
        if issubclass(w.category, FretwearWarning):
            notes.append(f"{w.category.__name__}: {w.message}")
    return Analysis(case=result, interval=interval, sector_intervals=sector_intervals,
                    uncertainty=mc, calibration=calibration, options=options,
                    warnings=list(dict.fromkeys(notes)), source=source)
