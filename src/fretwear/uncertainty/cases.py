"""From what the user has (a wear case and a power, a wear table, a model) to contact models.

A *case* is the description of one contact's wear computation: the keywords of
:func:`fretwear.table.wear_table` as a mapping (plus ``wall_thickness`` [m] and
``depth_limit`` [-]), a wear-case object (``fretwear.table.WearCase``), a wear table that
carries its case (:func:`fretwear.table.wear_table`'s, or read back from a CSV or Parquet file
fretwear wrote), or a :class:`~fretwear.table.depth.DepthModel`. The
*power* is a number [W], a :class:`~fretwear.power.PowerResult` (its block powers give the
interval), a :class:`~fretwear.power.confidence.PowerInterval` (an ensemble of runs), or a
contact history (object or file) from which the power is computed with the case's window,
blocks and sectors.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from fretwear import table as fretwear_table
from fretwear._lazy import pandas as pd
from fretwear.errors import InputError
from fretwear.history import ContactHistory
from fretwear.io import read_history
from fretwear.power import PowerResult, wear_power
from fretwear.power.confidence import PowerInterval
from fretwear.table import Wall, WearCase
from fretwear.table.depth import DepthModel
from fretwear.table.depth_build import carried_case, models_from_table
from fretwear.uncertainty.distributions import is_distribution, median_of

__all__ = ["PreparedCase", "prepare_case"]


@dataclass(frozen=True, eq=False)
class PreparedCase:
    """A case ready for propagation: its models, the power's uncertainty, its nominal table.

    Attributes
    ----------
    models : dict of str to DepthModel
        ``"global"`` and, in sector mode, ``"sector 1"`` ...
    power : PowerResult, PowerInterval or None
        What the power's uncertainty is known from (None: a bare number).
    table : DataFrame or None
        The nominal wear table.
    durations : numpy.ndarray
        Instants of the case after the origin [user time unit].
    case : WearCase or None
        The wear case the models were computed from (a wear table's: the case it carries; None:
        given a model).
    power_result : PowerResult or None
        The power computation of the case (None: a power given as a number or a distribution).
    """

    models: dict[str, DepthModel]
    power: Any
    table: pd.DataFrame | None
    durations: Any
    case: WearCase | None = None
    power_result: PowerResult | None = None

    @property
    def model(self) -> DepthModel:
        """The global model."""
        return self.models["global"]


def _durations(table: pd.DataFrame, origin: float) -> Any:
    """The durations [user time unit] of a table's rows from its ``origin`` on."""
    rows = table[(table["origin"] == origin) & (table["instant"] >= origin)]
    return rows["duration"].drop_duplicates().to_numpy(dtype=float)


def _uncertain(power) -> bool:
    """Whether ``power`` carries the power's uncertainty (an interval or a distribution)."""
    return isinstance(power, PowerResult | PowerInterval) or is_distribution(power)


def _source(power, keywords: dict[str, Any]):
    """(source for wear_table, the power's uncertainty object)."""
    if isinstance(power, PowerInterval):
        return float(power.estimate), power
    if isinstance(power, PowerResult):
        return power, power
    if isinstance(power, str | os.PathLike):
        power = read_history(power)
    if isinstance(power, ContactHistory):
        result = wear_power(power, **{k: keywords[k] for k in (
            "t_start", "t_end", "blocks", "sectors", "stationarity_threshold") if k in keywords})
        keywords["history"] = power
        return result, result
    if power is None:
        raise InputError("give the wear power: a number [W], a PowerResult, a PowerInterval, "
                         "a distribution of the power [W] or a contact history")
    if is_distribution(power):  # an absolute distribution of the power [W]
        median = median_of(power)
        if median is None or not (math.isfinite(median) and median > 0):
            raise InputError(f"power={power!r}: a distribution of the power is absolute [W] "
                             "and needs its median, e.g. LogNormal(0.01, sigma_ln=0.2) for "
                             "0.01 W; a scatter relative to a nominal power is power_scatter=")
        return median, power
    return power, None


def _wall(wall: Wall, thickness: float | None, limit: float | None) -> Wall:
    """The case's ``wall`` as it carries it (checked where it was built), or a new
    :class:`Wall` of the thickness [m] and limit [-] given in its place (checked once)."""
    if thickness is None and limit is None:
        return wall
    return Wall(wall.thickness if thickness is None else thickness,
                wall.limit if limit is None else limit)


def prepare_case(case, power=None, *, wall_thickness: float | None = None,
                 depth_limit: float | None = None) -> PreparedCase:
    """The contact models and the power's uncertainty of ``case`` with ``power``.

    Parameters
    ----------
    case : mapping, WearCase, DataFrame or DepthModel
        The wear case (module docstring).
    power : float, PowerResult, PowerInterval, ContactHistory or path-like, optional
        The wear power source [W] (not needed with a wear table or a model).
    wall_thickness : float, optional
        Wall thickness of the tube [m] (default the case's).
    depth_limit : float, optional
        Depth limit as a fraction of the wall [-] (default the case's, else 0.4).

    Returns
    -------
    PreparedCase
    """
    if isinstance(case, DepthModel):
        wall = _wall(case.wall, wall_thickness, depth_limit)
        model = case if wall is case.wall else dataclasses.replace(case, wall=wall)
        uncertainty = power if _uncertain(power) else None
        return PreparedCase({"global": model}, uncertainty, None, None)
    if isinstance(case, pd.DataFrame):
        carried = carried_case(case)  # rebuilt once, carried by the result
        models = models_from_table(case, case=carried)
        wall = _wall(models["global"].wall, wall_thickness, depth_limit)
        if wall is not models["global"].wall:
            models = {k: dataclasses.replace(m, wall=wall) for k, m in models.items()}
        uncertainty = power if _uncertain(power) else None
        return PreparedCase(models, uncertainty, case,
                            _durations(case, models["global"].origin), carried)
    if isinstance(case, Mapping):  # the keywords of wear_table, with the wall's
        keywords = dict(case)
        window = {k: keywords[k] for k in ("t_start", "t_end", "blocks", "sectors",
                                            "stationarity_threshold") if k in keywords}
        case = WearCase.from_keywords(**keywords)
    elif isinstance(case, WearCase):
        window = {"t_start": case.window.t_start, "t_end": case.window.t_end,
                  "blocks": case.window.blocks, "sectors": case.sectors,
                  "stationarity_threshold": case.window.stationarity_threshold}
    else:
        raise InputError(f"case must be the keywords of wear_table (a mapping), a WearCase, a "
                         f"wear table or a DepthModel, got {type(case).__name__}")
    source, uncertainty = _source(power, window)
    table = fretwear_table.wear_table_from_case(case, source, history=window.get("history"))
    models = models_from_table(table, case=case,
                               wall=_wall(case.wall, wall_thickness, depth_limit))
    result = source if isinstance(source, PowerResult) else None
    return PreparedCase(models, uncertainty, table, np.asarray(case.instants, dtype=float),
                        case, result)
