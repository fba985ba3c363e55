"""The one meaning of "the time to a limit" (issue 25, docs/uncertainty.md §1): the first
instant at which the tube in place reaches the depth, over every row of its table, a restart's
earlier rows included; the same on the wear table (``limit_instant``), the bundle's summary
and Monte Carlo without scatter, and non-decreasing in the limit.

The issue's case: a restart of a TUBE_ALESAGE table (1 mm wall, Archard), whose earlier 8 years
are already past 20-60 % of the wall. Before issue 25 the table said 8 (the restart's origin)
for every limit and the bundle jumped to 8 at the case's own limit (0.4).

Reference (independent of fretwear.table.depth): the earlier run is Archard at constant power
from an unworn tube at instant 0, so its worn volume is V = K·P·t (theory §2) and the depth d
is reached at t = V(d)/(K·P), V(d) from the geometry's forward relation volume_from_depth
(theory §6; checked against its own closed forms in tests/geometry).
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.result import summarize
from fretwear.geometry import contact_geometry
from fretwear.table import wear_table
from fretwear.uncertainty import LogNormal, monte_carlo

YEAR = 365 * 86400.0  # [s]
DIMENSIONS = {"mobile_radius": 0.01, "obstacle_width": 0.02}  # [m]
K, P, WALL = 1e-12, 0.01, 1e-3  # [1/Pa], [W], [m]
LIMITS = (0.2, 0.39, 0.4, 0.4000001, 0.41, 0.6)  # fractions of the wall [-]
CASE = {"contact_type": "TUBE_ALESAGE", "dimensions": DIMENSIONS,
        "coefficients": {"COEF_USURE": K}, "time_scale": YEAR, "wall_thickness": WALL}


@pytest.fixture(scope="module")
def tables():
    """The earlier 8 years (one row a year), and the restart's table for each limit."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # worn through the wall: the point of the case
        first = wear_table(P, instants=np.arange(1.0, 9.0), **CASE)
        return first, {limit: wear_table(P, instants=[1.0, 2.0, 4.0], initial_state=first,
                                          depth_limit=limit, **CASE) for limit in LIMITS}


def _expected(limit):
    g = contact_geometry("TUBE_ALESAGE", **DIMENSIONS)
    volume = float(np.asarray(g.volume_from_depth(limit * WALL)[0]))
    return volume / (K * P) / YEAR


def _bundle(table, limit):
    """BundleResult.summary's time to ``limit`` on this table as one contact's."""
    a = table.attrs
    contacts = pd.DataFrame([{
        "contact": "c0", "wall_thickness": WALL, "depth_limit": a["depth_limit"],
        "tube_replacement": None, "time_unit": "year", "contact_type": "TUBE_ALESAGE",
        "dimensions": DIMENSIONS, "law": "ARCHARD",
        "coefficients_mobile": a["coefficients_mobile"],
        "coefficients_obstacle": a["coefficients_obstacle"], "time_scale": YEAR,
        "status": "done", "origin": 8.0}])
    s = summarize(table.assign(contact="c0"), contacts, limit=limit, limit_m=None,
                  wall_thickness=None)
    return float(s["time_to_limit"].iloc[0])


def test_the_issue_table_is_one_non_decreasing_row(tables):
    first, restarts = tables
    table = [float(restarts[f]["limit_instant"].iloc[-1]) for f in LIMITS]
    bundle = [_bundle(restarts[f], f) for f in LIMITS]
    expected = [_expected(f) for f in LIMITS]
    assert table == pytest.approx(expected, rel=1e-12)
    assert bundle == pytest.approx(table, rel=1e-12)
    assert np.all(np.diff(table) >= 0) and np.all(np.diff(bundle) >= 0)
    # placed between the two earlier rows that bracket it, not at the restart's origin (8)
    depth = first["depth_mobile"].to_numpy()
    for f, t in zip(LIMITS, table, strict=True):
        i = int(np.argmax(depth >= f * WALL))
        assert (0.0 if i == 0 else first["instant"].iloc[i - 1]) < t <= first["instant"].iloc[i]
    # every row of the table holds the same instant
    assert restarts[0.4]["limit_instant"].nunique() == 1


def test_monte_carlo_without_scatter_is_the_table(tables):
    _, restarts = tables
    for f in LIMITS:
        result = monte_carlo(restarts[f], samples=4, wall_thickness=WALL, depth_limit=f,
                             factor=LogNormal(1.0, sigma_ln=0.0))
        t = result.time_to_limit()
        assert t == pytest.approx(np.full(t.shape, _expected(f)), rel=1e-12)
        assert t == pytest.approx(np.full(t.shape, restarts[f]["limit_instant"].iloc[-1]),
                                  rel=1e-12)


def test_a_limit_after_the_origin_is_the_law_from_there(tables):
    """A limit the earlier rows do not reach: through the law from the origin (V0 + K·P·t)."""
    _, restarts = tables
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        later = wear_table(P, instants=[1.0, 2.0, 4.0], initial_state=tables[0],
                           depth_limit=1.0, **{**CASE, "wall_thickness": 2.5e-3})
    g = contact_geometry("TUBE_ALESAGE", **DIMENSIONS)
    volume = float(np.asarray(g.volume_from_depth(2.5e-3)[0]))
    assert later["limit_instant"].iloc[-1] == pytest.approx(volume / (K * P) / YEAR, rel=1e-12)
    assert later["limit_instant"].iloc[-1] > 8.0


def test_after_a_replacement_only_the_new_tube_counts():
    """The old tube passes 40 % of the wall at 1.59 years; replaced at 2 years, the new tube
    reaches it 1.59 years after its replacement."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = wear_table(P, instants=[1.0, 3.0, 6.0], tube_replacement=2.0, **CASE)
    assert t["limit_instant"].iloc[0] == pytest.approx(2.0 + _expected(0.4), rel=1e-12)


def _sector_history():
    """A contact whose angle sweeps ±170° (every sector of four worn, unevenly) [SI]."""
    from fretwear.history import ContactHistory
    time = np.linspace(0.0, 2.0, 4001)
    angle = np.radians(170.0 * np.sin(2.1 * time))
    return ContactHistory(time=time, normal_force=np.full(time.size, 3.0),
                          vt1=np.full(time.size, 0.05), vt2=np.zeros(time.size),
                          dy=1e-4 * np.cos(angle), dz=1e-4 * np.sin(angle))


def test_sector_limits_look_at_a_restart_earlier_rows():
    """Each sector's ``limit_instant_sector`` on a restart has the global meaning: the first
    instant the tube's sector depth reaches the limit, over every row (the earlier 8 years
    included), not the restart's origin. Reference: the earlier run is Archard at the sector's
    constant power P_j, V_j = K·P_j·t, and the sector depth d is reached at
    t = V(d)/(K·P_j), V(d) = l·Δθ·d·(2R − d)/2 (docs/theory.md §3;
    fretwear.geometry.sector_volume_mobile, checked in tests/geometry)."""
    from fretwear.geometry import sector_volume_mobile
    k = 2e-14  # [1/Pa]: the sectors cross 20-60 % of the wall between 1 and 17 years
    case = {**CASE, "coefficients": {"COEF_USURE": k}, "sectors": 4}
    history = _sector_history()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        first = wear_table(history, instants=np.arange(1.0, 9.0), **case)
        restarts = {f: wear_table(history, instants=[1.0, 2.0, 40.0], initial_state=first,
                                  depth_limit=f, **case) for f in LIMITS}
    rows = first[first["instant"] == 1.0].set_index("sector")
    inside = 0
    for f, table in restarts.items():
        found = table.attrs["limit_instant_sector"]
        for j in range(1, 5):
            arc = rows.at[j, "angle_end"] - rows.at[j, "angle_start"]
            volume = sector_volume_mobile(f * WALL, DIMENSIONS["mobile_radius"],
                                          DIMENSIONS["obstacle_width"], arc)
            expected = volume / (k * rows.at[j, "sector_power"]) / YEAR
            assert found[j - 1] == pytest.approx(expected, rel=1e-12), (f, j)
            inside += expected < 8.0
        at = table["limit_instant_sector"].to_numpy()
        assert np.array_equal(at, np.asarray(found)[table["sector"].to_numpy() - 1])
    assert 0 < inside < len(LIMITS) * 4  # some reached among the earlier rows, some after
    for j in range(4):  # non-decreasing in the limit
        assert np.all(np.diff([restarts[f].attrs["limit_instant_sector"][j]
                               for f in LIMITS]) >= 0)
