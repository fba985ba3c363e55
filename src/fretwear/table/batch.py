"""The sector tables of several contacts of one case at once (a bundle's worker, issue 28).

A bundle's contacts of one case differ by their wear power only: their sector tables
(:func:`fretwear.table.wear_table_columns` of a :class:`~fretwear.power.PowerResult` with
sectors) are the case's instants and sectors with each contact's sector powers. Built one
contact at a time, a table of 8 sectors and 6 instants costs some forty numpy calls on a few
dozen values and a :class:`~fretwear.table.DepthModel` each (0.05-0.07 ms a contact, almost all
of it the calls' own cost); :func:`sector_tables` makes those of a batch of contacts with each
numpy call over all of them: the same operations on the same values, element by element, so
every value equals the one-contact table's bit for bit (tests/table/test_batch.py).

Only the cases whose table is made of elementwise operations take it (:func:`batched`): a law
linear in time (each sector's volume V0_j + r_j·t), no restart, no tube replacement, no wall,
and the obstacle's depths known (it wears only where the sectors have its bore radius). The
global depths are computed for all the contacts in one call only for a geometry whose
depth-volume relation is a closed form value by value (:func:`_rowwise`: TUBE_BAV without
tilt), else per contact (a solver's iterations may depend on its other values). SI units:
volumes [m³], depths [m], powers [W], angles [deg].
"""

from __future__ import annotations

import numpy as np

from fretwear.geometry import TubeBav
from fretwear.table._columns import _SECTOR_FLOATS, _template
from fretwear.table.build import (
    _attrs,
    _body_coefficients,
    _Clock,
    _geometry,
    _power_of,
    _with_run_sectors,
)
from fretwear.table.case import WearCase
from fretwear.table.depth_build import case_model
from fretwear.table.depth_terms import _plain, initial_arrays


def batched(case: WearCase) -> bool:
    """Whether the sector tables of ``case`` may be made by :func:`sector_tables`: sectors, a
    law linear in time whose coefficients come from the case alone (not the history), no
    restart's table, no tube replacement, no wall thickness (its limit instants)."""
    def check() -> bool:
        law = case.wear_law
        return not (case.sectors is None or not law.linear_in_time or law.needs_history
                    or case.restart.table is not None
                    or case.restart.tube_replacement is not None
                    or case.wall.thickness is not None)

    return case.derived("sector tables batched", check)


def sector_tables(case: WearCase, results: list, attrs=None) -> list[tuple[dict, dict]] | None:
    """``[wear_table_columns(case, r, attrs=attrs) for r in results]`` computed together.

    Parameters
    ----------
    case : WearCase
        A case that :func:`batched` accepts.
    results : list of PowerResult
        The contacts' powers, with the case's sectors.
    attrs : iterable of str, optional
        As :func:`fretwear.table.wear_table_columns`.

    Returns
    -------
    list of (columns, attrs), or None
        What :func:`fretwear.table.wear_table_columns` gives each contact (the same values,
        dtypes and column order; the columns are views of one block); None where the batch
        cannot be made (the case or a power not as :func:`batched` needs, the powers not
        finite and >= 0, the law's coefficients not plain floats): the caller then makes each
        table alone, which raises or warns as it does.

    Notes
    -----
    A caller that must tell which contact a warning belongs to records the warnings of the
    call and makes the tables one by one when there are any (a depth beyond the relation's
    range warns here for the whole batch).
    """
    if not results or not batched(case):
        return None
    keys = None if attrs is None else tuple(attrs)
    parts = []
    for result in results:
        if getattr(result, "sectors", None) is None or not hasattr(result, "total"):
            return None
        run_case, edges = _with_run_sectors(case, result)  # raises as the table would
        mobile, obstacle, sources = _body_coefficients(run_case, None, result)
        parts.append((result, edges, mobile, obstacle, sources, _power_of(case, result, None)[2]))
    geometry = _geometry(case)
    clock = _Clock(case)
    first = parts[0]
    model = case_model(case, first[5], first[0], first[2], first[3], clock.fresh, geometry)
    powers = np.array([np.asarray(p[0].sectors, dtype=float) for p in parts])
    if powers.ndim != 2 or powers.shape[1] != len(model.powers) or any(
            p[2] != first[2] or p[3] != first[3] for p in parts[1:]):
        return None  # other sectors or coefficients (not from the case alone): one by one
    blocks = _blocks(model, powers, clock, first[1], [p[5] for p in parts])
    if blocks is None:
        return None
    out = []
    for (result, edges, mobile, obstacle, sources, _), block in zip(parts, blocks, strict=True):
        table_attrs = _attrs(case, geometry, mobile, obstacle, sources, result, edges, keys)
        if keys is not None:
            table_attrs = {k: table_attrs[k] for k in keys if k in table_attrs}
        out.append((block, table_attrs))
    return out


def _rates(law, powers: np.ndarray, coefficients) -> np.ndarray | None:
    """The terms' volumes per second [m³/s] of each contact (contacts, sectors), as
    :func:`fretwear.table.depth_terms._rates` makes one contact's: the law's rate of every
    power in one call where the sectors share their coefficients (one dict of plain floats),
    zeros where the body does not wear; None otherwise (one by one)."""
    if all(c is None for c in coefficients):
        return np.zeros(powers.shape)
    first = coefficients[0]
    if not (_plain(first) and all(c is first or (_plain(c) and c == first)
                                  for c in coefficients)):
        return None
    # the law's checks of the powers are the one-contact call's on each row: all pass or a
    # row fails (then its own table takes the law's general route)
    if not (powers.min() >= 0.0 and powers.max() < np.inf):
        return None
    rates = np.asarray(law.rate(powers, **first), dtype=float)
    return rates.astype(float) if rates.shape == powers.shape else None


def _rowwise(geometry) -> bool:
    """Whether the global depths of several contacts may be computed in one call: a relation
    that is a closed form value by value (TUBE_BAV without tilt: D from V by cube roots;
    others may solve for D, their iterations shared by the values)."""
    return type(geometry) is TubeBav and geometry.angle("tilt_angle") == 0.0


def _blocks(model, powers: np.ndarray, clock, edges, totals: list[float]) -> list | None:
    """The columns of each contact's :func:`fretwear.table._columns._sector_frame` (the
    model's :meth:`~fretwear.table.DepthModel.sector_table` and
    :meth:`~fretwear.table.DepthModel.body_depths` with the contacts on a first axis: the same
    operations element by element); None where a contact's rates are not the plain ones or
    the obstacle wears without its bore radius."""
    rate_m = _rates(model.law, powers, model.coefficients_mobile)
    rate_o = _rates(model.law, powers, model.coefficients_obstacle)
    if rate_m is None or rate_o is None:
        return None
    b, m = powers.shape
    t = np.asarray(clock.elapsed, dtype=float)[:, None]
    v0m, v0o = model._term_initial()
    vm = v0m + rate_m[:, None, :] * t  # (contacts, instants, sectors)
    slices = model.slices
    dm = slices.depth_mobile(vm)
    vo = v0o + rate_o[:, None, :] * t
    if slices.obstacle_radius is None:
        if v0o.any() or (any(c is not None for c in model.coefficients_obstacle)
                         and rate_o.any()):
            return None  # an obstacle that wears without its bore radius: NaN, said per contact
        do = np.zeros(vm.shape)  # neither wears nor was worn: depths 0
    else:
        do = slices.depth_obstacle(vo)
    total_m, total_o = vm.sum(axis=2), vo.sum(axis=2)
    if _rowwise(model.geometry):
        gm, go = model.body_depths(total_m, total_o)
    else:
        pairs = [model.body_depths(total_m[k], total_o[k]) for k in range(b)]
        gm, go = np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])
    n = t.shape[0]
    pm, po = initial_arrays(model.term_initial)
    template, sector = _template(clock, edges, n, m)
    block = np.empty((b, *template.shape))
    block[:] = template
    block[:, 3] = np.asarray(totals, dtype=float)[:, None, None]
    block[:, 4:8] = np.stack((total_m, total_o, gm, go), axis=1)[:, :, :, None]
    block[:, 10] = powers[:, None, :]
    np.subtract(vm, pm, out=block[:, 11])
    np.subtract(vo, po, out=block[:, 12])
    block[:, 13] = dm
    block[:, 14] = do
    block[:, 15] = vm
    block[:, 16] = vo
    floats = block.reshape(b, len(_SECTOR_FLOATS), n * m)
    out = []
    for k in range(b):
        rows = list(floats[k])
        data = dict(zip(_SECTOR_FLOATS[:8], rows[:8], strict=True))
        data["sector"] = sector.copy()
        data.update(zip(_SECTOR_FLOATS[8:], rows[8:], strict=True))
        out.append(data)
    return out
