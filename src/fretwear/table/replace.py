"""Tube replacement in a wear table (TUBE_NEUF, theory §7): the tube's volumes and depths
restart from zero at an instant, the obstacle's are kept; the new tube's depths from the
geometry of the wear case the table carries (:func:`fretwear.table.carried_case`).
"""

from __future__ import annotations

import os
import warnings

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FretwearWarning, InputError
from fretwear.geometry.sectors import SectorGeometry, sector_depth_mobile
from fretwear.table.depth_build import carried_case
from fretwear.table.files import read_wear_table
from fretwear.table.restart import _column, initial_state
from fretwear.table.schema import _TIME_TOL, from_aster_names, to_aster_names

__all__ = ["replace_tube"]


def replace_tube(table: pd.DataFrame | str | os.PathLike, instant: float | None = None
                 ) -> pd.DataFrame:
    """The wear table with the tube replaced by a new one at ``instant`` (TUBE_NEUF, theory §7).

    Rows before ``instant`` are unchanged. From ``instant`` on the tube is the new one: its
    cumulated volumes (global and per sector) are the old ones minus their value at ``instant``
    (zero at ``instant``, then what the new tube wears since, for a law linear in time), the
    volume worn in a sector by the tube in place (``volume_mobile_sector``) is the new tube's
    cumulated volume, and the depths are computed again from those volumes with the table's
    geometry (of the case the table carries, :func:`fretwear.table.carried_case`; sector
    depths theory §3). The
    obstacle's volumes are kept. Code_Aster's TUBE_NEUF keeps the later rows too, but sets the
    tube's values to zero on every one of them (``motubn``): a tube that no longer wears.

    The result seeds a restart (:func:`fretwear.table.wear_table` ``initial_state=``) of the new
    tube against the worn obstacle, from the table's last instant, or from ``instant`` with
    ``initial_instant=instant`` (ETAT_INIT INST_INIT).

    Parameters
    ----------
    table : DataFrame or path-like
        A wear table, native or Code_Aster names (the result keeps the names given).
    instant : float, optional
        Instant of the replacement [user time unit]; an instant of the table. Default: the last.

    Returns
    -------
    pandas.DataFrame
        A new table (the one given is not modified); ``attrs`` gain ``tube_replacement`` and,
        when the table carries no geometry (a Code_Aster table read from its file), the note
        ``tube_replacement_depths``: the new tube's depths after ``instant`` are then NaN.

    Raises
    ------
    InputError
        ``instant`` is not an instant of the table; rows after it in a table of a law that is
        not linear in time (EDF_MZ: the new tube's run-in starts again, compute it with
        ``tube_replacement=`` / ``[time] tube_replacement`` instead).

    Examples
    --------
    >>> t = pd.DataFrame({"instant": [1.0, 2.0, 3.0], "volume_mobile": [1e-9, 2e-9, 3e-9],
    ...                   "volume_obstacle": [3e-10, 6e-10, 9e-10]})
    >>> replace_tube(t, 2.0)["volume_mobile"].tolist()
    [1e-09, 0.0, 1e-09]
    """
    if not isinstance(table, pd.DataFrame):
        table = read_wear_table(table)
    aster = "INST" in table.columns
    native = from_aster_names(table)
    attrs = dict(table.attrs)
    case = carried_case(table)  # the case it was computed from, rebuilt once; None: none
    inst = _column(native, ["instant"], "the instant (INST)", "(DataFrame)")
    if instant is not None and len(inst) and not np.any(
            np.abs(inst - float(instant)) <= _TIME_TOL * max(1.0, float(np.abs(inst).max()))):
        raise InputError(f"TUBE_NEUF at INST = {float(instant):g}: not an instant of the wear "
                         f"table (TABL_USURE), whose instants are {sorted(set(inst.tolist()))}; "
                         "replace the tube at one of them (the new tube's volumes are the old "
                         "ones minus their value there), or compute the table with "
                         "tube_replacement= (case file [time] tube_replacement) for another "
                         "instant")
    state = initial_state(native, instant)
    at = state.origin
    tol = _TIME_TOL * max(1.0, abs(at))
    on, after = np.abs(inst - at) <= tol, inst > at + tol
    law = None if case is None else case.wear_law
    if after.any() and law is not None and not law.linear_in_time:
        raise InputError(f"TUBE_NEUF at {at:g} before the table's last instant with "
                         f"LOI_USURE='{law.name}': the new tube's wear is not the old one's "
                         "minus its value at the replacement (the law is not linear in time); "
                         "compute the table with tube_replacement= (case file [time] "
                         "tube_replacement) instead")
    out = native.copy()
    new = on | after
    keys = _sector_keys(native)
    for col in ("volume_mobile", "volume_mobile_cumulated"):
        if col in out.columns:
            out[col] = _restarted(native[col], keys, inst, at, tol, new)
    if "volume_mobile_sector" in out.columns:
        if "volume_mobile_cumulated" in out.columns:
            out.loc[new, "volume_mobile_sector"] = out.loc[new, "volume_mobile_cumulated"]
        else:
            out["volume_mobile_sector"] = _restarted(native["volume_mobile_sector"], keys, inst,
                                                     at, tol, new)
    geometry = None if case is None else _geometry(case)
    _restarted_depths(out, new, on, geometry, keys)
    if geometry is None and after.any():
        attrs["tube_replacement_depths"] = (
            "the table carries no geometry (no wear case: attrs['case'], or its file's "
            "provenance): the new tube's depths after the replacement are NaN; recompute them "
            "with the contact geometry")
        later = sorted(set(inst[after].tolist()))
        warnings.warn(
            f"TUBE_NEUF at INST = {at:g}: the new tube's depths at the {len(later)} later "
            f"instant{'s' if len(later) > 1 else ''} of the table ({later[0]:g} .. "
            f"{later[-1]:g}) are NaN, not computed: the table carries no contact geometry (a "
            "Code_Aster table read from its file). Its volumes are right; for the depths, "
            "replace the tube at the table's last instant and continue with ETAT_INIT, or "
            "compute the table with tube_replacement= ([time] tube_replacement) and the "
            "geometry", FretwearWarning, stacklevel=2)
    attrs["tube_replacement"] = at
    if case is not None and at >= case.origin:  # the case that computes the table now
        attrs["case"] = case.replace(tube_replacement=at).to_dict()
    else:  # replaced among a restart's earlier rows: no case computes this table
        attrs.pop("case", None)
    out.attrs = attrs
    return to_aster_names(out) if aster else out


def _sector_keys(frame: pd.DataFrame) -> np.ndarray:
    """A key per row: its sector number, or -1 for a global row (no sector)."""
    if "sector" not in frame.columns:
        return np.full(len(frame), -1.0)
    sector = pd.to_numeric(frame["sector"], errors="coerce").to_numpy(dtype=float)
    return np.where(np.isnan(sector), -1.0, sector)


def _restarted(values: pd.Series, keys: np.ndarray, inst: np.ndarray, at: float, tol: float,
               new: np.ndarray) -> np.ndarray:
    """A cumulated column minus its value at ``at`` (per sector key) on the ``new`` rows."""
    out = pd.to_numeric(values, errors="coerce").to_numpy(dtype=float).copy()
    for key in np.unique(keys[new]):
        group = keys == key
        base_rows = np.flatnonzero(group & (inst <= at + tol))
        base = 0.0 if base_rows.size == 0 else out[base_rows[-1]]
        rows = group & new
        out[rows] = np.maximum(out[rows] - (0.0 if np.isnan(base) else base), 0.0)
    return out


def _geometry(case):
    """The geometry of a table's wear case: its contact's, or the sector dimensions alone."""
    if case.contact_type is None:
        return SectorGeometry(**{k: v for k, v in case.dimensions.items() if k in
                                 ("mobile_radius", "obstacle_width", "obstacle_radius")})
    return case.geometry


def _restarted_depths(out: pd.DataFrame, new: np.ndarray, on: np.ndarray, geometry,
                      keys: np.ndarray) -> None:
    """Depths of the new tube (and the obstacle's, which may depend on both volumes)."""
    if geometry is None:
        for col in ("depth_mobile", "depth_mobile_sector"):
            if col in out.columns:
                values = out[col].to_numpy(dtype=float).copy()
                values[new] = np.nan
                values[on] = 0.0
                out[col] = values
        return
    if "depth_mobile" in out.columns and "volume_mobile" in out.columns:
        vm = out.loc[new, "volume_mobile"].to_numpy(dtype=float)
        vo = (np.nan_to_num(out.loc[new, "volume_obstacle"].to_numpy(dtype=float))
              if "volume_obstacle" in out.columns else np.zeros_like(vm))
        dm, do = geometry.depth_from_volume(vm, vo)
        out.loc[new, "depth_mobile"] = dm
        if "depth_obstacle" in out.columns:
            out.loc[new, "depth_obstacle"] = np.where(vo == 0, 0.0, do)
    if "depth_mobile_sector" in out.columns and "volume_mobile_cumulated" in out.columns:
        rows = new & (keys >= 0)
        arc = (out.loc[rows, "angle_end"].to_numpy(dtype=float)
               - out.loc[rows, "angle_start"].to_numpy(dtype=float))
        out.loc[rows, "depth_mobile_sector"] = sector_depth_mobile(
            out.loc[rows, "volume_mobile_cumulated"].to_numpy(dtype=float),
            geometry.mobile_radius, geometry.obstacle_width, arc)
