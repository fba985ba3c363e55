"""The wall and its limit in the wear table (fretwear.table.limit, wear_table's wall keywords).

Oracles, independent of the solver: closed-form inversions of the depth relations of
docs/theory.md §6 (TUBE_BAV without tilt D = c·V^(2/3); TUBE_TUBE d = (1/(2R))^(1/5)·
(15θV/8)^(2/5); the sector depth d = R − √(R² − 2V/(lΔθ)) inverted as V = lΔθ(R² − (R−d)²)/2)
with V = K·P·t, and for EDF_MZ the law's own equivalent time of the geometry's volume.
"""

import math
import warnings

import numpy as np
import pytest

from fretwear.errors import PerforationWarning
from fretwear.geometry import contact_geometry
from fretwear.history import ContactHistory
from fretwear.laws import get_law
from fretwear.table import WALL_COLUMNS, wear_table
from fretwear.table.limit import time_to_depth

YEAR = 3.1536e7
R, W, WALL = 9.525e-3, 12.7e-3, 1.09e-3
BAV = {"contact_type": "TUBE_BAV", "dimensions": {"mobile_radius": R, "obstacle_width": W},
       "coefficients": {"coefficient": 9.2e-15}, "time_scale": YEAR}


def test_tube_bav_limit_instant_closed_form():
    t = wear_table(0.01, instants=[5.0, 10.0, 20.0], wall_thickness=WALL, **BAV)
    limit = 0.4 * WALL
    c = (1 / (2 * R)) ** (1 / 3) * (3 / (4 * W)) ** (2 / 3)
    expected = (limit / c) ** 1.5 / (9.2e-15 * 0.01) / YEAR
    assert t["limit_instant"].tolist() == pytest.approx([expected] * 3, rel=1e-12)
    assert t["wall_fraction"].tolist() == pytest.approx((t["depth_mobile"] / WALL).tolist(),
                                                        rel=1e-15)
    assert t.attrs["limit_depth"] == pytest.approx(limit)
    # a user limit of 60 %
    t60 = wear_table(0.01, instants=[5.0], wall_thickness=WALL, depth_limit=0.6, **BAV)
    assert t60["limit_instant"].iloc[0] == pytest.approx(expected * 1.5 ** 1.5, rel=1e-12)


def test_new_columns_leave_the_others_bit_identical():
    plain = wear_table(0.01, instants=[1.0, 10.0], **BAV)
    walled = wear_table(0.01, instants=[1.0, 10.0], wall_thickness=WALL, **BAV)
    assert list(walled.columns) == list(plain.columns) + list(WALL_COLUMNS)
    for column in plain.columns:
        assert np.array_equal(walled[column], plain[column], equal_nan=True)


def test_tube_tube_through_the_wall_is_named():
    """The tube_tube example: 1.41 mm at 2 years on a 1.09 mm wall."""
    kw = {"contact_type": "TUBE_TUBE", "time_scale": YEAR, "instants": [0.1, 0.5, 1.0, 2.0],
          "dimensions": {"mobile_radius": R, "obstacle_radius": R, "tilt_angle": 5.0},
          "coefficients": {"coefficient": 1e-12}, "obstacle_coefficients": {"coefficient": 1e-12}}
    with pytest.warns(PerforationWarning, match=r"worn through its wall \(1.09 mm\).*"
                                                r"from instant 1.049.*deepest 1.411 mm \(129%"):
        t = wear_table(1e-3, wall_thickness=WALL, time_unit="year", **kw)
    theta = math.radians(5.0)

    def reach(depth):  # d = (1/(2R))^(1/5)·(15θ·K·P·t/8)^(2/5)
        return (depth * (2 * R) ** 0.2) ** 2.5 * 8 / (15 * theta * 1e-12 * 1e-3) / YEAR

    assert t["limit_instant"].iloc[0] == pytest.approx(reach(0.4 * WALL), rel=1e-12)
    assert t.attrs["through_wall"]["global"] == pytest.approx(reach(WALL), rel=1e-12)
    assert t["wall_fraction"].iloc[-1] == pytest.approx(1.2944, abs=1e-4)


def _sector_history():
    time = np.linspace(0.0, 2.0, 4001)
    angle = np.radians(170.0 * np.sin(2.1 * time))
    return ContactHistory(time=time, normal_force=np.full(time.size, 3.0),
                          vt1=np.full(time.size, 0.05), vt2=np.zeros(time.size),
                          dy=np.cos(angle), dz=np.sin(angle))


def test_sector_limit_instants_closed_form():
    pairs = [(9.2e-15, None), (2e-14, None), (5e-15, None), (9.2e-15, None)]
    t = wear_table(_sector_history(), instants=[0.5, 1.0], sectors=4, wall_thickness=WALL,
                   sector_coefficients=pairs, **BAV)
    power = t.attrs["power"]["sectors"]
    limit = 0.4 * WALL
    arc = math.pi / 2
    volume = W * arc * (R ** 2 - (R - limit) ** 2) / 2
    last = t[t["instant"] == 1.0]
    for j in range(4):
        expected = volume / (pairs[j][0] * power[j]) / YEAR
        assert last["limit_instant_sector"].iloc[j] == pytest.approx(expected, rel=1e-12)
        assert last["wall_fraction_sector"].iloc[j] == pytest.approx(
            last["depth_mobile_sector"].iloc[j] / WALL, rel=1e-15)
    # the global depth comes from the sum of the sector volumes: its limit is reached once
    # Σ k_j·P_j·t gives the flat's volume
    c = (1 / (2 * R)) ** (1 / 3) * (3 / (4 * W)) ** (2 / 3)
    rate = sum(k * p for (k, _), p in zip(pairs, power, strict=True))
    assert last["limit_instant"].iloc[0] == pytest.approx((limit / c) ** 1.5 / rate / YEAR,
                                                          rel=1e-12)


def test_edf_mz_limit_through_the_law_and_geometry():
    kw = {"contact_type": "TUBE_ALESAGE", "law": "EDF_MZ", "time_scale": YEAR,
          "dimensions": {"mobile_radius": R, "obstacle_width": W}}
    t = wear_table(0.02, instants=[1.0], wall_thickness=WALL, **kw)
    g = contact_geometry("TUBE_ALESAGE", mobile_radius=R, obstacle_width=W)
    volume, _ = g.volume_from_depth(0.4 * WALL)
    expected = float(get_law("EDF_MZ").equivalent_time(volume, 0.02)) / YEAR
    assert t["limit_instant"].iloc[0] == pytest.approx(expected, rel=1e-10)


def test_restart_and_replacement():
    whole = wear_table(0.01, instants=[20.0], wall_thickness=WALL, **BAV)
    first = wear_table(0.01, instants=[5.0], **BAV)
    later = wear_table(0.01, instants=[15.0], initial_state=first, wall_thickness=WALL, **BAV)
    assert later["limit_instant"].iloc[-1] == pytest.approx(whole["limit_instant"].iloc[0],
                                                            rel=1e-12)
    assert later["limit_instant"].iloc[0] == later["limit_instant"].iloc[-1]  # every row
    # limit already passed at the origin: where it was passed among the earlier table's rows
    # (from 0 at instant 0 to its row at 200 years, the volume linear between them: the same
    # Archard run, so the instant of the whole run's closed form), not the origin
    deep = wear_table(0.01, instants=[200.0], **BAV)
    with pytest.warns(PerforationWarning, match="worn through"):
        after = wear_table(0.01, instants=[1.0], initial_state=deep, wall_thickness=WALL, **BAV)
    assert after["limit_instant"].iloc[-1] == pytest.approx(whole["limit_instant"].iloc[0],
                                                            rel=1e-12)
    # the tube replaced at 2 years: the new tube reaches the limit 2 years after the first did
    replaced = wear_table(0.01, instants=[1.0, 3.0, 20.0], tube_replacement=2.0,
                          wall_thickness=WALL, **BAV)
    assert replaced["limit_instant"].iloc[0] == pytest.approx(
        2.0 + whole["limit_instant"].iloc[0], rel=1e-12)


def test_time_to_depth_never_and_at_once():
    out = time_to_depth(lambda t: np.zeros_like(t), np.array([1e-3, 2e-3]))
    assert np.isinf(out).all()
    assert time_to_depth(lambda t: 1e-3 + 0 * t, 5e-4) == 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        # NaN (beyond the range) counts as deeper than the target
        t = time_to_depth(lambda t: np.where(t > 5.0, np.nan, t * 1e-4), 4e-4)
    assert t == pytest.approx(4.0, rel=1e-12)


def test_a_depth_beyond_the_relation_is_through_the_wall():
    """A flat past the tube's axis (depth NaN, beyond the relation's range) is through the wall
    too: named, with the instant it passes the wall from the closed form, and no numpy
    warning (the wall fraction is all NaN)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t = wear_table(0.01, instants=[2000.0], wall_thickness=WALL, **BAV)
    assert np.isnan(t["depth_mobile"].iloc[0])
    c = (1 / (2 * R)) ** (1 / 3) * (3 / (4 * W)) ** (2 / 3)
    expected = (WALL / c) ** 1.5 / (9.2e-15 * 0.01) / YEAR
    assert t.attrs["through_wall"]["global"] == pytest.approx(expected, rel=1e-12)
    names = [w.category.__name__ for w in caught]
    assert "PerforationWarning" in names and "RuntimeWarning" not in names, names
    perforation = next(str(w.message) for w in caught if w.category is PerforationWarning)
    assert "beyond the geometric relation's range" in perforation
