"""The sector tables of several contacts of one case made together
(fretwear.table.batch.sector_tables) equal each contact's own table
(fretwear.table.wear_table_columns of its PowerResult, the reference) bit for bit: every column's
values and dtype, their order, and the attrs; for every kind of case the batch takes (one
coefficient for all sectors, sector coefficients, an obstacle that wears with its bore radius,
a tilted bar whose global depths are solved, sectors without a contact type, a coefficient of
0, powers of zero) and None for those it leaves to one table at a time."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from fretwear.errors import RangeWarning
from fretwear.history import ContactHistory
from fretwear.power import wear_power
from fretwear.table import WearCase, wear_table_columns
from fretwear.table.batch import batched, sector_tables

ATTRS = ("contact_type", "dimensions", "law", "coefficients_mobile", "coefficients_obstacle",
         "coefficient_sources", "sector_edges", "time_scale", "origin")


def _results(count: int, sectors, *, seed: int = 0, zero: int | None = None):
    """``count`` PowerResults with ``sectors`` of random orbits (a different power in each
    sector and contact); contact ``zero`` has no force (every power 0)."""
    rng = np.random.default_rng(seed)
    out = []
    for k in range(count):
        t = np.linspace(0.0, 1.0, 801)
        phase = rng.uniform(0, 2 * np.pi, 3)
        dy = 1e-4 * np.cos(2 * np.pi * 7 * t + phase[0]) + rng.normal(0, 2e-5, t.size)
        dz = 1e-4 * np.sin(2 * np.pi * 5 * t + phase[1])
        fn = np.abs(rng.normal(3.0 * (k + 1), 1.0, t.size)) * (k != zero)
        h = ContactHistory(time=t, normal_force=fn, vt1=5e-3 * np.sin(40 * t + phase[2]),
                           vt2=2e-3 * np.cos(30 * t), dy=dy, dz=dz, name=f"c{k}")
        out.append(wear_power(h, sectors=sectors))
    return out


def _same(batch, alone) -> None:
    assert len(batch) == len(alone)
    for (columns, attrs), (ref_columns, ref_attrs) in zip(batch, alone, strict=True):
        assert list(columns) == list(ref_columns)
        for name, ref in ref_columns.items():
            got = columns[name]
            assert got.dtype == ref.dtype and got.shape == ref.shape, name
            assert got.tobytes() == ref.tobytes(), name  # bit for bit (NaN and -0.0 too)
        assert attrs == ref_attrs


CASES = {
    "one coefficient, TUBE_BAV": dict(
        contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                             "obstacle_width": 12.7e-3},
        coefficients={"COEF_USURE": 1e-16}, sectors=8, instants=[1, 2, 5, 10, 20, 40],
        time_scale=3.15576e7),
    "36 sectors, 37 instants": dict(
        contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                             "obstacle_width": 12.7e-3},
        coefficients={"COEF_USURE": 3e-15}, sectors=36, instants=np.linspace(0.1, 9, 37),
        time_scale=3.6e3),
    "tilted bar (global depths solved)": dict(
        contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                             "obstacle_width": 12.7e-3, "tilt_angle": 2.0},
        coefficients={"COEF_USURE": 1e-14}, sectors=4, instants=[1, 3, 9], time_scale=3.15e7),
    "obstacle wears, bore radius": dict(
        contact_type="TUBE_ALESAGE", dimensions={"mobile_radius": 9.525e-3,
                                                 "obstacle_radius": 9.8e-3,
                                                 "obstacle_width": 12.7e-3},
        coefficients={"COEF_USURE": 1e-14}, obstacle_coefficients={"COEF_USURE": 4e-15},
        sectors=[-180.0, -30.0, 45.0, 180.0], instants=[0.5, 1, 2], time_scale=3.15e7),
    "no wear (a coefficient of 0)": dict(
        contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                             "obstacle_width": 12.7e-3},
        coefficients={"COEF_USURE": 0.0}, sectors=8, instants=[1, 2], time_scale=3.15e7),
    "sectors without a contact type (global depths NaN)": dict(
        contact_type=None, dimensions={"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
        coefficients={"COEF_USURE": 1e-14}, sectors=6, instants=[1, 2, 4], time_scale=3.15e7),
    "sector coefficients": dict(
        contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                             "obstacle_width": 12.7e-3},
        coefficients={"COEF_USURE": 1e-14}, sectors=4, instants=[1, 2],
        sector_coefficients=[(1e-14, None), (2e-14, None), (1e-14, None), (5e-15, None)],
        time_scale=3.15e7),
}


@pytest.mark.parametrize("name", list(CASES))
def test_a_case_s_tables_together_equal_each_alone(name):
    case = WearCase.from_keywords(**CASES[name])
    assert batched(case)
    results = _results(9, case.sectors if isinstance(case.sectors, int) else case.sector_edges,
                       seed=len(name), zero=4)
    alone = [wear_table_columns(case, r, attrs=ATTRS) for r in results]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # none of these warns
        batch = sector_tables(case, results, attrs=ATTRS)
    if batch is None:  # sector coefficients that differ: one table at a time
        assert name == "sector coefficients"
        return
    _same(batch, alone)
    # every attribute when none are asked for (the power's statistics, the case)
    full = sector_tables(case, results[:2])
    ref = [wear_table_columns(case, r) for r in results[:2]]
    assert [sorted(a) for _, a in full] == [sorted(a) for _, a in ref]
    _same([(c, {k: a[k] for k in ATTRS}) for c, a in full],
          [(c, {k: a[k] for k in ATTRS}) for c, a in ref])


def test_depths_beyond_the_range_warn_as_alone_then_are_nan_as_alone():
    """A power that wears the tube through: NaN depths and a RangeWarning, as each table's."""
    case = WearCase.from_keywords(**{**CASES["one coefficient, TUBE_BAV"],
                                     "coefficients": {"COEF_USURE": 1e-9}})
    results = _results(3, 8, seed=3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        alone = [wear_table_columns(case, r, attrs=ATTRS) for r in results]
    assert caught and all(w.category is RangeWarning for w in caught)
    with pytest.warns(RangeWarning):
        batch = sector_tables(case, results, attrs=ATTRS)
    assert np.isnan(alone[0][0]["depth_mobile"]).any()
    _same(batch, alone)


def test_cases_the_batch_leaves_to_one_table_at_a_time():
    base = CASES["one coefficient, TUBE_BAV"]
    results = _results(2, 8)
    # an obstacle that wears without its bore radius: NaN depths, warned per contact
    case = WearCase.from_keywords(**{**base, "obstacle_coefficients": {"COEF_USURE": 1e-15}})
    assert batched(case) and sector_tables(case, results) is None
    # no sectors, a wall (its limit instants), a tube replaced during the run
    for other in ({k: v for k, v in base.items() if k != "sectors"},
                  {**base, "wall_thickness": 1.07e-3},
                  {**base, "tube_replacement": 3.0}):
        assert not batched(WearCase.from_keywords(**other))
    # a power without sectors, or with other sectors than the case's
    case = WearCase.from_keywords(**base)
    assert sector_tables(case, []) is None
    with pytest.raises(Exception, match="sector"):
        sector_tables(case, _results(2, 4))
