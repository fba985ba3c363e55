"""The wear table's fast paths (issue 13) against independent computations.

* the table's frame, built from one float block (fretwear.table._columns._frame), against pandas'
  own ``pd.DataFrame(columns)``;
* the global limit instant of a law linear in time with an unworn obstacle, inverted in closed
  form (DepthModel.time_to), against the bracketed solver on depth(t)
  (fretwear.table.limit.time_to_depth) and against the geometry's forward relation: the depth
  of the volume K·P·t at the found t is the target;
* the sector columns of every sector at once (DepthModel.sector_table) against Archard sector
  by sector (restarts and replacements included);
* the limit and through-wall instants solved together (obstacle worn, trace shared: TUBE_BAV)
  against the closed form of docs/theory.md §6 inverted by hand; the geometries'
  ``mobile_depth_alone`` against their relations.
"""

import math
import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import InputError, PerforationWarning, RangeWarning
from fretwear.geometry import CONTACT_TYPES, contact_geometry, sector_depth_mobile
from fretwear.history import ContactHistory
from fretwear.laws import get_law
from fretwear.table import _columns, wear_table
from fretwear.table._columns import _frame
from fretwear.table.depth import DepthModel
from fretwear.table.limit import time_to_depth
from fretwear.table.schema import GLOBAL_COLUMNS, SECTOR_COLUMNS

YEAR = 3.1536e7
R, WALL = 9.525e-3, 1.09e-3
K = 1e-14  # [1/Pa]


def _model(g, v0, rates, obstacle_rates=None):
    """Archard's DepthModel of terms V_j = K·P_j·t of the given rates r_j = K·P_j [m³/s] (and
    the obstacle's, at the same powers), V0 = Σ v0 [m³], origin 0, time unit a year."""
    rates = np.atleast_1d(np.asarray(rates, dtype=float))
    powers = tuple((rates / K).tolist())
    obstacle = (None,) * rates.size if obstacle_rates is None else tuple(
        {"coefficient": K * ro / r} for r, ro in zip(rates, obstacle_rates, strict=True))
    return DepthModel(law=get_law("ARCHARD"), geometry=g, powers=powers,
                      coefficients_mobile=({"coefficient": K},) * rates.size,
                      coefficients_obstacle=obstacle, time_scale=YEAR,
                      initial_mobile=float(np.sum(v0)))


def _seconds(model, targets):
    """DepthModel.time_to in seconds after the origin (0)."""
    return np.asarray(model.time_to(targets), dtype=float) * YEAR


@pytest.mark.parametrize("names", [GLOBAL_COLUMNS, SECTOR_COLUMNS])
def test_frame_is_pandas_own_frame(names):
    rng = np.random.default_rng(3)
    columns = {c: rng.random(12) for c in names}
    if "sector" in columns:
        columns["sector"] = np.tile(np.arange(1, 5), 3)
    columns["wall_fraction"] = rng.random(12)
    expected = pd.DataFrame(columns)
    got = _frame(columns)
    pd.testing.assert_frame_equal(got, expected, check_exact=True)
    assert list(got.dtypes) == list(expected.dtypes)
    assert _blocks(got) == _blocks(expected)  # the same blocks: one per dtype
    got["instant"] = 0.0  # a table is the caller's own: the cached column index is not touched
    got.columns.name = "mine"
    again = _frame(columns)
    assert list(again.columns) == list(expected.columns) and again.columns.name is None
    assert again["instant"].tolist() == columns["instant"].tolist()  # the columns were copied
    pd.testing.assert_frame_equal(_columns._frame_inserted(columns), expected, check_exact=True)


def _blocks(frame):
    """The frame's blocks: (dtype, the places of its columns), sorted."""
    return sorted((str(b.dtype), b.mgr_locs.as_array.tolist()) for b in frame._mgr.blocks)


@pytest.mark.parametrize("kind", ["dtypes", "not arrays", "objects"])
def test_frame_of_other_columns_is_pandas_own_frame(kind):
    """Several integer and boolean columns (one block per dtype, as pandas makes them), and
    columns that are not one-length numeric numpy arrays (pandas' constructor itself)."""
    rng = np.random.default_rng(5)
    columns = {"a": rng.integers(0, 9, 5), "x": rng.random(5), "b": rng.random(5) > 0.5,
               "c": np.arange(5, dtype=np.int32), "d": rng.integers(0, 9, 5), "y": rng.random(5)}
    if kind == "not arrays":
        columns["z"] = [1.5, 2.5, None, 4.0, 5.0]
    if kind == "objects":
        columns["z"] = np.array(["p", "q", None, "r", "s"], dtype=object)
    expected = pd.DataFrame(columns)
    got = _frame(columns)
    pd.testing.assert_frame_equal(got, expected, check_exact=True)
    assert list(got.dtypes) == list(expected.dtypes)
    if kind == "dtypes":
        assert _blocks(got) == _blocks(expected)
        first = int(columns["a"][0])
        got.iloc[0, 0] = first + 1  # the table's own data: the columns given are not changed
        assert columns["a"][0] == first


GEOMETRIES = [
    ("TUBE_BAV", {"mobile_radius": R, "obstacle_width": 12.7e-3, "tilt_angle": 0.3}),
    ("TUBE_ALESAGE", {"mobile_radius": R, "obstacle_radius": 9.75e-3,
                      "obstacle_width": 20e-3}),
    ("TUBE_3_ENCO", {"mobile_radius": R, "obstacle_radius": 9.725e-3, "obstacle_width": 30e-3,
                     "tilt_angle": 0.05, "isthmus_angle": 20.0}),
    ("GRAPPE_ALESAGE", {"mobile_radius": 4.84e-3, "obstacle_radius": 5.5e-3,
                        "obstacle_width": 10e-3}),
]


@pytest.mark.parametrize(("kind", "dims"), GEOMETRIES)
def test_global_closed_form_matches_the_solver_and_the_forward_relation(kind, dims):
    g = contact_geometry(kind, **dims)
    rates = np.array([3e-13, 1e-13, 2e-13])  # three terms (sectors) [m³/s]
    for v0 in (np.zeros(3), np.array([1e-13, 0.0, 5e-14])):
        model = _model(g, v0, rates)
        targets = np.array([1e-5, 1e-4, 2e-4])
        closed = _seconds(model, targets)
        assert (closed > 0).all()
        solved = time_to_depth(lambda t, m=model: m.depth(t, warn=False), targets,
                               first_guess=YEAR)
        assert closed == pytest.approx(solved, rel=1e-11)
        # forward: the geometry's depth of the total volume at t is the target
        volume = v0.sum() + rates.sum() * closed
        dm, _ = g.depth_from_volume(volume)
        assert np.asarray(dm) == pytest.approx(targets, rel=1e-12)
    # already there at the origin, never there without wear
    deep = _model(g, np.array([1e-7]), np.array([1e-13]))
    assert _seconds(deep, np.array([1e-6])).tolist() == [0.0]
    idle = _model(g, np.zeros(1), np.zeros(1))
    assert _seconds(idle, np.array([1e-6])).tolist() == [math.inf]


def test_global_closed_form_beyond_the_range_uses_the_solver():
    g = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=12.7e-3)
    model = _model(g, np.zeros(1), np.array([1e-12]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = _seconds(model, np.array([2 * R]))  # deeper than the relation's range
        expected = time_to_depth(lambda t: model.depth(t, warn=False), np.array([2 * R]),
                                 first_guess=YEAR)
    assert t == pytest.approx(np.asarray(expected), rel=1e-15)


def test_worn_obstacle_sharing_the_trace_solves_both_targets_at_once():
    """TUBE_BAV with the bar worn as fast as the tube: d_m = D·V_m/(V_m + V_o) = D/2 with
    D = (1/(2R))^(1/3)·(3V/(4l))^(2/3) (docs/theory.md §6), so the tube reaches d at
    V = 2·K·P·t = (2d/c)^(3/2)."""
    g = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=12.7e-3)
    assert not g.mobile_depth_alone
    width, k, power = 12.7e-3, 1e-12, 1e-3
    kw = {"contact_type": "TUBE_BAV", "time_scale": YEAR, "instants": [0.1, 10.0],
          "dimensions": {"mobile_radius": R, "obstacle_width": width},
          "coefficients": {"coefficient": k}, "obstacle_coefficients": {"coefficient": k}}
    with pytest.warns(PerforationWarning):
        t = wear_table(power, wall_thickness=WALL, **kw)
    c = (1 / (2 * R)) ** (1 / 3) * (3 / (4 * width)) ** (2 / 3)

    def reach(d):  # [year]
        return (2 * d / c) ** 1.5 / (2 * k * power) / YEAR

    assert t["limit_instant"].iloc[0] == pytest.approx(reach(0.4 * WALL), rel=1e-12)
    assert t.attrs["through_wall"]["global"] == pytest.approx(reach(WALL), rel=1e-12)
    # each element as the one-target call finds it
    rate = np.array([k * power])
    model = _model(g, np.zeros(1), rate, rate)
    one = [model.time_to(target) for target in (0.4 * WALL, WALL)]
    assert t["limit_instant"].iloc[0] == pytest.approx(one[0], rel=1e-14)
    assert t.attrs["through_wall"]["global"] == pytest.approx(one[1], rel=1e-14)


@pytest.mark.parametrize("kind", sorted(CONTACT_TYPES))
def test_mobile_depth_alone_is_what_the_relation_does(kind):
    """A geometry that says its mobile's depth ignores the obstacle's volume: d_m(V_m, V_o) is
    d_m(V_m, 0) bit for bit; one that does not: some V_o changes it."""
    cls = CONTACT_TYPES[kind]
    g = cls(**cls.example)
    vm = np.array([1e-12, 1e-11, 1e-10, 1e-9])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        alone = np.asarray(g.depth_from_volume(vm, 0.0)[0])
        worn = np.asarray(g.depth_from_volume(vm, 0.3 * vm)[0])
    assert np.isfinite(alone).all()
    if cls.mobile_depth_alone:
        assert np.array_equal(alone, worn)
    else:
        assert not np.array_equal(alone, worn, equal_nan=True)


def test_tube_tube_both_worn_limit_in_closed_form():
    """TUBE_TUBE: each tube's flat from its own volume, d = (1/(2R))^(1/5)·(15θV/8)^(2/5)
    (docs/theory.md §6), however fast the other tube wears."""
    g = contact_geometry("TUBE_TUBE", mobile_radius=R, obstacle_radius=R, tilt_angle=5.0)
    rate_m, rate_o = np.array([1e-15]), np.array([3e-15])
    model = _model(g, np.zeros(1), rate_m, rate_o)
    theta = math.radians(5.0)
    targets = np.array([0.4 * WALL, WALL])
    expected = (targets * (2 * R) ** 0.2) ** 2.5 * 8 / (15 * theta) / rate_m[0]
    assert _seconds(model, targets) == pytest.approx(expected, rel=1e-13)


def _sector_history():
    time = np.linspace(0.0, 2.0, 4001)
    angle = np.radians(170.0 * np.sin(2.1 * time))
    return ContactHistory(time=time, normal_force=np.full(time.size, 3.0),
                          vt1=np.full(time.size, 0.05), vt2=np.zeros(time.size),
                          dy=np.cos(angle), dz=np.sin(angle))


SECTOR_CASES = {
    "bav": {"contact_type": "TUBE_BAV", "sectors": 8,
            "dimensions": {"mobile_radius": R, "obstacle_width": 12.7e-3},
            "coefficients": {"coefficient": 9.2e-15}},
    "obstacle worn, replaced": {
        "contact_type": "TUBE_ALESAGE", "sectors": 6, "tube_replacement": 1.5,
        "dimensions": {"mobile_radius": R, "obstacle_radius": 9.75e-3,
                       "obstacle_width": 20e-3},
        "coefficients": {"coefficient": 2e-14}, "obstacle_coefficients": {"coefficient": 1e-14}},
    "sector coefficients": {
        "contact_type": "TUBE_ALESAGE", "sectors": 4,
        "dimensions": {"mobile_radius": R, "obstacle_radius": 9.75e-3,
                       "obstacle_width": 20e-3},
        "coefficients": {"coefficient": 9.2e-15},
        "sector_coefficients": [(1e-14, None), (2e-14, 1e-15), (5e-15, None), (0.0, 3e-15)]},
}


def _sector_pairs(kw: dict) -> list:
    """(mobile, obstacle) Archard coefficients [1/Pa] of each sector as the case gives them: a
    missing obstacle one is 0 when another sector's obstacle wears (docs/theory.md §3)."""
    m = kw["sectors"]
    obstacle = kw.get("obstacle_coefficients", {}).get("coefficient")
    pairs = kw.get("sector_coefficients") or [(kw["coefficients"]["coefficient"], obstacle)] * m
    wears = any(p[1] is not None for p in pairs)
    return [(p[0], (0.0 if p[1] is None else p[1]) if wears else None) for p in pairs]


@pytest.mark.parametrize("name", sorted(SECTOR_CASES))
def test_every_sector_at_once_is_archard_sector_by_sector(name):
    """The sector columns (every sector at once, by the case's DepthModel) against Archard
    computed here sector by sector: V_j(t) = V0_j + k_j·P_j·t (docs/theory.md §3), the tube's
    from 0 at its replacement, V0_j the restarted table's last row of the sector; the sector
    depth of V_j (fretwear.geometry.sector_depth_mobile, checked in tests/geometry); first run
    and a restart of it."""
    kw = {"instants": [0.5, 1.0, 3.0], "time_scale": YEAR, "wall_thickness": WALL,
          **SECTOR_CASES[name]}
    history = _sector_history()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        first = wear_table(history, **kw)
        again = wear_table(history, initial_state=first, **{**kw, "tube_replacement": None})
    pairs = _sector_pairs(kw)
    m, width = kw["sectors"], kw["dimensions"]["obstacle_width"]
    last = first[first["instant"] == first["instant"].max()].set_index("sector")
    for table, restart in ((first, False), (again, True)):
        run = table[table["origin"] == table["origin"].iloc[-1]]
        for j in range(1, m + 1):
            rows = run[run["sector"] == j]
            t = rows["duration"].to_numpy() * YEAR
            p = rows["sector_power"].to_numpy()
            k_m, k_o = pairs[j - 1]
            v0m = last.at[j, "volume_mobile_cumulated"] if restart else 0.0
            v0o = last.at[j, "volume_obstacle_cumulated"] if restart else 0.0
            vm = v0m + k_m * p * t
            replaced = kw.get("tube_replacement")
            if replaced is not None and not restart:
                vm = np.where(t >= replaced * YEAR, k_m * p * (t - replaced * YEAR), vm)
            vo = v0o + (0.0 if k_o is None else k_o * p * t)
            assert rows["volume_mobile_cumulated"].to_numpy() == pytest.approx(vm, rel=1e-14)
            assert rows["volume_obstacle_cumulated"].to_numpy() == pytest.approx(vo, rel=1e-14,
                                                                                  abs=0.0)
            arc = rows["angle_end"].iloc[0] - rows["angle_start"].iloc[0]
            assert rows["depth_mobile_sector"].to_numpy() == pytest.approx(
                sector_depth_mobile(vm, R, width, arc), rel=1e-13)


def test_sector_loop_keeps_its_warning_naming_the_sectors():
    """An obstacle that wears without a radius: the loop's warning, naming the sectors."""
    kw = {"contact_type": "TUBE_BAV", "sectors": 4, "instants": [1.0],
          "dimensions": {"mobile_radius": R, "obstacle_width": 12.7e-3},
          "coefficients": {"coefficient": 9.2e-15},
          "sector_coefficients": [(1e-14, None), (2e-14, 1e-15), (5e-15, None), (1e-14, None)]}
    with pytest.warns(RangeWarning, match=r"sectors \[2\]: the obstacle wears"):
        t = wear_table(_sector_history(), **kw)
    assert np.isnan(t["depth_obstacle_sector"].iloc[1])


def test_case_dict_made_once_and_handed_out_as_copies():
    """WearCase.to_dict is made once per (immutable) case: every call gets its own copy, a
    table's attrs["case"] changed by its user changes neither the case nor the next table, and
    pickles do not carry the made dict."""
    import pickle

    from fretwear.table import WearCase, wear_table_from_case
    kw = {"contact_type": "TUBE_BAV", "instants": [1.0, 2.0], "time_scale": YEAR,
          "dimensions": {"mobile_radius": R, "obstacle_width": 12.7e-3},
          "coefficients": {"coefficient": 9.2e-15}, "sectors": 4}
    case = WearCase.from_keywords(**kw)
    first = case.to_dict()
    first["instants"].append(99.0)
    first["coefficients"]["coefficient"]["value"] = 1.0
    again = case.to_dict()
    assert again == WearCase.from_keywords(**kw).to_dict()  # a case never asked before
    assert again["instants"] == [1.0, 2.0] and again is not first
    plain = WearCase.from_keywords(**{k: v for k, v in kw.items() if k != "sectors"})
    t = wear_table_from_case(plain, 0.01)
    t.attrs["case"]["law"] = "changed"
    assert wear_table_from_case(plain, 0.01).attrs["case"]["law"] == "ARCHARD"
    assert plain.to_dict()["law"] == "ARCHARD"
    copy = pickle.loads(pickle.dumps(case))
    assert "_as_dict" not in vars(copy) and copy == case and copy.to_dict() == again


def test_sector_table_of_an_obstacle_that_does_not_wear_is_zero():
    """An obstacle without coefficients and without earlier wear: its sector volumes and
    depths exactly 0 (V_o,j = 0 + 0·t, docs/theory.md §3), the tube's Archard's
    V_j = V0_j + K·P_j·t, V0_j given (independent computation here)."""
    g = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=20e-3)
    rates = np.array([1e-17, 3e-17, 0.0])
    v0 = (1e-10, 0.0, 2e-10)
    model = DepthModel(law=get_law("ARCHARD"), geometry=g, powers=tuple((rates / K).tolist()),
                       coefficients_mobile=({"coefficient": K},) * 3,
                       coefficients_obstacle=(None,) * 3, sector_arcs=(120.0,) * 3,
                       term_initial=(v0, (0.0,) * 3), time_scale=YEAR)
    t = np.array([0.0, 0.5 * YEAR, 2.0 * YEAR])
    out = model.sector_table(t)
    assert out["volume_mobile"] == pytest.approx(np.array(v0) + rates * t[:, None], rel=1e-15)
    assert np.array_equal(out["volume_obstacle"], np.zeros((3, 3)))
    assert np.array_equal(out["depth_obstacle"], np.zeros((3, 3)))
    assert out["unradiused"] == []


@pytest.mark.parametrize("bad", [-1e-12, math.inf, math.nan])
def test_sector_initial_volumes_checked_where_the_model_is_built(bad):
    """A restart's sector volume that is negative or not finite: an InputError naming the body
    when the model is built (not at each of its sector tables)."""
    g = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=20e-3)
    with pytest.raises(InputError, match=r"sector volumes of the obstacle must be finite"):
        DepthModel(law=get_law("ARCHARD"), geometry=g, powers=(1e-3, 1e-3),
                   coefficients_mobile=({"coefficient": K},) * 2,
                   coefficients_obstacle=(None,) * 2, sector_arcs=(180.0, 180.0),
                   term_initial=((0.0, 0.0), (0.0, bad)))
