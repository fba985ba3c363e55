"""The wear operator: service-life table, restart, tube replacement (theory §3, §6, §7).

Expected values are computed independently in each test from the closed forms of docs/theory.md:
Archard V = K·P·t (§4), EDF_MZ V = ((A·P^b − S)/n)(1 − e^(−n·t)) + S·t (§4), the TUBE_BAV depth
without tilt D = (1/(2R_m))^(1/3)·(3V/(4l))^(2/3) (§6) and the sector depth of a convex mobile
d = R_m − √(R_m² − 2V/(l·Δθ)) (§3).
"""

import math

import numpy as np
import pandas as pd
import pytest

from fretwear import ContactHistory
from fretwear.errors import InputError, KeywordError
from fretwear.geometry import contact_geometry
from fretwear.table import (
    COLUMNS,
    from_aster_names,
    initial_state,
    replace_tube,
    to_aster_names,
    wear_table,
)

YEAR = 31_536_000.0
BAV = {"mobile_radius": 0.0111, "obstacle_width": 0.0127}
P = 0.012  # [W]
K_M, K_O = 1.2e-13, 3.0e-14  # [1/Pa]


def bav_depth(volume, radius=BAV["mobile_radius"], width=BAV["obstacle_width"]):
    """Theory §6 TUBE_BAV, no tilt: D = (1/(2R))^(1/3)·(3V/(4l))^(2/3)."""
    return (1 / (2 * radius)) ** (1 / 3) * (3 * np.asarray(volume) / (4 * width)) ** (2 / 3)


def edf(power, t, a=1e-13, b=1.2, n=2.44e-8, s=1.14e-16):
    """Theory §4 EDF_MZ volume [m³]."""
    return (a * power**b - s) / n * (1 - np.exp(-n * t)) + s * t


def archard_table(instants, **kw):
    args = dict(contact_type="TUBE_BAV", dimensions=BAV, instants=instants,
                coefficients={"COEF_USURE": K_M}, time_scale=YEAR)
    args.update(kw)
    return wear_table(P, **args)


def test_archard_volumes_and_depths_analytic():
    t = archard_table([1.0, 2.0, 10.0], obstacle_coefficients={"coefficient": K_O})
    inst = np.array([1.0, 2.0, 10.0])
    np.testing.assert_allclose(t["volume_mobile"], K_M * P * inst * YEAR, rtol=1e-15)
    np.testing.assert_allclose(t["volume_obstacle"], K_O * P * inst * YEAR, rtol=1e-15)
    total = (K_M + K_O) * P * inst * YEAR
    depth = bav_depth(total)
    np.testing.assert_allclose(t["depth_mobile"], depth * K_M / (K_M + K_O), rtol=1e-9)
    np.testing.assert_allclose(t["depth_obstacle"], depth * K_O / (K_M + K_O), rtol=1e-9)
    assert t["origin"].eq(0.0).all() and t["duration"].tolist() == [1.0, 2.0, 10.0]
    assert t["power"].eq(P).all()
    assert list(t.columns) == ["instant", "duration", "origin", "power", "volume_mobile",
                               "volume_obstacle", "depth_mobile", "depth_obstacle"]
    assert t.attrs["law"] == "ARCHARD" and t.attrs["time_scale"] == YEAR


def test_obstacle_does_not_wear_without_coefficient():
    t = archard_table([1.0, 3.0])
    assert t["volume_obstacle"].eq(0.0).all() and t["depth_obstacle"].eq(0.0).all()
    np.testing.assert_allclose(t["depth_mobile"], bav_depth(K_M * P * np.array([1, 3]) * YEAR),
                               rtol=1e-9)


def test_restart_chain_equals_one_long_run_archard():
    long = archard_table([1.0, 2.0, 3.0, 5.0], obstacle_coefficients={"COEF_USURE": K_O})
    first = archard_table([1.0, 2.0], obstacle_coefficients={"COEF_USURE": K_O})
    second = archard_table([1.0, 3.0], obstacle_coefficients={"COEF_USURE": K_O},
                           initial_state=first)
    assert second["instant"].tolist() == [1.0, 2.0, 3.0, 5.0]
    assert second["origin"].tolist() == [0.0, 0.0, 2.0, 2.0]
    assert second["duration"].tolist() == [1.0, 2.0, 1.0, 3.0]
    for col in ("volume_mobile", "volume_obstacle", "depth_mobile", "depth_obstacle"):
        np.testing.assert_allclose(second[col], long[col], rtol=1e-14, atol=0)


def test_restart_from_initial_instant_drops_later_rows():
    first = archard_table([1.0, 2.0, 4.0])
    second = archard_table([2.0], initial_state=first, initial_instant=2.0)
    assert second["instant"].tolist() == [1.0, 2.0, 4.0]  # the old 4.0 row is dropped
    np.testing.assert_allclose(second["volume_mobile"].iloc[-1], K_M * P * 4 * YEAR, rtol=1e-14)
    with pytest.raises(InputError, match="INST_INIT.*3"):
        archard_table([1.0], initial_state=first, initial_instant=3.0)


def test_restart_from_code_aster_names():
    first = to_aster_names(archard_table([1.0, 2.0]))
    second = archard_table([1.0], initial_state=first)
    np.testing.assert_allclose(second["volume_mobile"].iloc[-1], K_M * P * 3 * YEAR, rtol=1e-14)


def test_edf_mz_continuity_across_restart():
    """A restart continues from the equivalent time: V(t1) then V(t1 + Δt) (theory §7)."""
    args = dict(contact_type="TUBE_BAV", dimensions=BAV, law="EDF_MZ", time_scale=YEAR)
    first = wear_table(P, instants=[0.5, 1.0], **args)
    second = wear_table(P, instants=[0.5, 2.0], initial_state=first, **args)
    expected = edf(P, np.array([0.5, 1.0, 1.5, 3.0]) * YEAR)
    np.testing.assert_allclose(second["volume_mobile"], expected, rtol=1e-10)
    # a naive restart (V1 + V(Δt)) would overestimate: the run-in rate is not applied twice
    naive = edf(P, 1.0 * YEAR) + edf(P, 2.0 * YEAR)
    assert second["volume_mobile"].iloc[-1] < naive * (1 - 1e-3)


def test_tube_replacement_restarts_tube_keeps_obstacle():
    t = archard_table([1.0, 2.0, 3.0, 5.0], obstacle_coefficients={"COEF_USURE": K_O},
                      tube_replacement=2.0)
    inst = np.array([1.0, 2.0, 3.0, 5.0])
    vm = K_M * P * np.where(inst >= 2.0, inst - 2.0, inst) * YEAR
    vo = K_O * P * inst * YEAR
    np.testing.assert_allclose(t["volume_mobile"], vm, rtol=1e-14)
    np.testing.assert_allclose(t["volume_obstacle"], vo, rtol=1e-14)
    depth = bav_depth(vm + vo)
    np.testing.assert_allclose(t["depth_mobile"], depth * vm / (vm + vo), rtol=1e-9, atol=1e-15)
    assert t["depth_mobile"].iloc[1] == 0.0


def test_tube_replacement_edf_mz_new_tube_runs_in_again():
    args = dict(contact_type="TUBE_BAV", dimensions=BAV, law="EDF_MZ", time_scale=YEAR)
    t = wear_table(P, instants=[1.0, 4.0], tube_replacement=1.5, **args)
    np.testing.assert_allclose(t["volume_mobile"], [edf(P, YEAR), edf(P, 2.5 * YEAR)],
                               rtol=1e-12)


def test_replace_tube_table_seeds_a_new_tube():
    old = archard_table([1.0, 2.0, 3.0], obstacle_coefficients={"COEF_USURE": K_O})
    seeded = replace_tube(old, 2.0)
    # the later rows are kept (as Code_Aster's TUBE_NEUF does), with the tube restarted at 2:
    # Archard, the new tube has worn K·P·(3 − 2) years at 3 (theory §4, §7)
    assert seeded["instant"].tolist() == [1.0, 2.0, 3.0]
    assert seeded["volume_mobile"].iloc[1] == 0.0 and seeded["depth_mobile"].iloc[1] == 0.0
    np.testing.assert_allclose(seeded["volume_mobile"].iloc[2], K_M * P * YEAR, rtol=1e-14)
    geometry = contact_geometry("TUBE_BAV", **old.attrs["dimensions"])
    np.testing.assert_allclose(seeded["depth_mobile"].iloc[2], geometry.depth_from_volume(
        K_M * P * YEAR, seeded["volume_obstacle"].iloc[2])[0], rtol=1e-12)
    assert seeded["volume_obstacle"].tolist() == old["volume_obstacle"].tolist()
    assert seeded["volume_mobile"].iloc[0] == old["volume_mobile"].iloc[0]
    assert old["volume_mobile"].iloc[1] > 0  # the user's table is unchanged
    # continue from the replacement (ETAT_INIT INST_INIT = 2): a new tube, the worn obstacle
    new = archard_table([1.0], obstacle_coefficients={"COEF_USURE": K_O}, initial_state=seeded,
                        initial_instant=2.0)
    np.testing.assert_allclose(new["volume_mobile"].iloc[-1], K_M * P * YEAR, rtol=1e-14)
    np.testing.assert_allclose(new["volume_obstacle"].iloc[-1], K_O * P * 3 * YEAR, rtol=1e-14)
    # or from the table's last instant (3): the new tube has worn one year already
    new = archard_table([1.0], obstacle_coefficients={"COEF_USURE": K_O}, initial_state=seeded)
    np.testing.assert_allclose(new["volume_mobile"].iloc[-1], 2 * K_M * P * YEAR, rtol=1e-14)
    np.testing.assert_allclose(new["volume_obstacle"].iloc[-1], K_O * P * 4 * YEAR, rtol=1e-14)
    aster = replace_tube(to_aster_names(old))  # Code_Aster names in, Code_Aster names out
    assert "V_USUR_TUBE" in aster.columns and aster["V_USUR_TUBE"].iloc[-1] == 0.0


def test_tube_replacement_before_origin_is_an_error():
    first = archard_table([2.0])
    with pytest.raises(InputError, match="tube_replacement.*before the origin"):
        archard_table([1.0], initial_state=first, tube_replacement=1.0)


def test_instant_errors():
    with pytest.raises(InputError, match="strictly increasing"):
        archard_table([2.0, 1.0])
    with pytest.raises(InputError, match=">= 0"):
        archard_table([-1.0])
    with pytest.raises(InputError, match="> 0"):
        archard_table([0.0, 1.0], initial_state=archard_table([1.0]))
    with pytest.raises(InputError, match="COEF_INST"):
        archard_table([1.0], time_scale=0.0)
    with pytest.raises(KeywordError, match="initial_state"):
        archard_table([1.0], initial_instant=1.0)


def test_missing_and_unknown_coefficients_are_named():
    with pytest.raises(KeywordError, match="coefficient"):
        wear_table(P, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0])
    with pytest.raises(KeywordError, match="COEF_USRE"):
        wear_table(P, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0],
                   coefficients={"COEF_USRE": 1e-13})
    with pytest.raises(KeywordError, match="KWU_EPRI"):
        wear_table(P, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0], law="KWU_EPRI",
                   coefficients={"COEF_USURE": 1e-13})
    with pytest.raises(KeywordError, match="materials"):
        wear_table(P, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0],
                   coefficients={"COEF_USURE": 1e-13}, obstacle_wear=True)


def test_power_alone_cannot_have_sectors():
    with pytest.raises(InputError, match="sectors need a contact history"):
        archard_table([1.0], sectors=4)


def test_sector_count_must_match_global_table():
    prev = archard_table([1.0])
    state = initial_state(prev)
    assert state.sector_count == 0 and state.origin == 1.0


def test_column_names_round_trip():
    t = archard_table([1.0])
    aster = to_aster_names(t)
    assert aster.columns.tolist()[:5] == ["INST", "DUREE", "ORIG_INST", "PUIS_USUR_GLOBAL",
                                          "V_USUR_TUBE"]
    pd.testing.assert_frame_equal(from_aster_names(aster), t)
    assert all(len(v) == 3 for v in COLUMNS.values())


# --------------------------------------------------------------------------- sector mode
def sector_history():
    """Constant Fn = 20 N and sliding speed 0.05 m/s; the left samples of the first 4 intervals
    lie at 45° (sector 3 of 4), the next 4 at −135° (sector 1): P_1 = P_3 = 0.5 W, P = 1 W
    (theory §2-§3: trapezoid, interval owned by its left sample)."""
    n = 9
    t = np.linspace(0.0, 8.0, n)
    angle = np.where(np.arange(n) < 4, 45.0, -135.0)
    dy, dz = 1e-4 * np.cos(np.radians(angle)), 1e-4 * np.sin(np.radians(angle))
    return ContactHistory(time=t, normal_force=np.full(n, 20.0), vt1=np.full(n, 0.03),
                          vt2=np.full(n, 0.04), dy=dy, dz=dz, name="N1")


def sector_table(instants, **kw):
    pytest.importorskip("fretwear.power")
    pytest.importorskip("fretwear.geometry.sectors")
    args = dict(contact_type="TUBE_BAV", dimensions=BAV, instants=instants, sectors=4,
                sector_coefficients=[(1e-13, None), (2e-13, None), (3e-13, 1e-14),
                                     (4e-13, None)], time_scale=3600.0)
    args.update(kw)
    return wear_table(sector_history(), **args)


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
def test_sector_volumes_and_depths_analytic():
    t = sector_table([1.0, 2.0])
    assert len(t) == 8 and t["sector"].tolist() == [1, 2, 3, 4] * 2
    powers = t["sector_power"].to_numpy()[:4]
    np.testing.assert_allclose(powers, [0.5, 0.0, 0.5, 0.0], rtol=1e-12)
    last = t.iloc[4:]
    k = np.array([1e-13, 2e-13, 3e-13, 4e-13])
    vm = k * powers * 2 * 3600.0
    np.testing.assert_allclose(last["volume_mobile_cumulated"], vm, rtol=1e-12)
    np.testing.assert_allclose(last["volume_obstacle_cumulated"], [0, 0, 1e-14 * 0.5 * 2 * 3600.0,
                                                                   0], rtol=1e-12)
    r, width, arc = BAV["mobile_radius"], BAV["obstacle_width"], math.radians(90.0)
    np.testing.assert_allclose(last["depth_mobile_sector"],
                               r - np.sqrt(r**2 - 2 * vm / (width * arc)), rtol=1e-9)
    np.testing.assert_allclose(last["volume_mobile"], vm.sum(), rtol=1e-12)
    np.testing.assert_allclose(t["power"], 1.0, rtol=1e-12)


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
def test_sector_restart_chain_equals_long_run_and_count_must_match():
    long = sector_table([1.0, 3.0])
    first = sector_table([1.0])
    second = sector_table([2.0], initial_state=first)
    cols = ["volume_mobile_cumulated", "volume_obstacle_cumulated", "depth_mobile_sector"]
    np.testing.assert_allclose(second[cols].to_numpy(), long[cols].to_numpy(), rtol=1e-14)
    np.testing.assert_allclose(second["volume_mobile_sector"].iloc[4:],
                               long["volume_mobile_sector"].iloc[4:] / 3 * 2, rtol=1e-14)
    with pytest.raises(InputError, match="4 sectors and this run has 2"):
        sector_table([1.0], initial_state=first, sectors=2, sector_coefficients=[(1e-13, None)])
    with pytest.raises(InputError, match="4 sectors and this run has none"):
        archard_table([1.0], initial_state=first, time_scale=3600.0)  # first's unit


# --------------------------------------------------------------------------- database
def test_database_pair_coefficients():
    """R7.20.01 §3 tables: TUBE_BAV I600TT/Z6C13 Archard 9.2e-15 (no obstacle value);
    GRAPPE_ALESAGE A304L/A304L Archard 2.6e-15 / 3.7e-15."""
    pytest.importorskip("fretwear.database")
    from fretwear.errors import DatabaseError

    t = wear_table(P, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0], time_scale=YEAR,
                   materials=("I600TT", "Z6C13"))
    np.testing.assert_allclose(t["volume_mobile"], 9.2e-15 * P * YEAR, rtol=1e-15)
    assert t["volume_obstacle"].eq(0.0).all()
    with pytest.raises(DatabaseError):
        wear_table(P, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0],
                   materials=("I600TT", "Z6C13"), obstacle_wear=True)
    g = {"mobile_radius": 4.84e-3, "obstacle_radius": 5.25e-3, "obstacle_width": 0.02}
    t = wear_table(P, contact_type="GRAPPE_ALESAGE", dimensions=g, instants=[1.0, 2.0],
                   time_scale=3600.0, materials=("A304L", "A304L"), obstacle_wear=True)
    np.testing.assert_allclose(t["volume_mobile"], 2.6e-15 * P * 3600.0 * np.array([1, 2]),
                               rtol=1e-15)
    np.testing.assert_allclose(t["volume_obstacle"], 3.7e-15 * P * 3600.0 * np.array([1, 2]),
                               rtol=1e-15)
    with pytest.raises(KeywordError, match="excludes obstacle_coefficients"):
        wear_table(P, contact_type="GRAPPE_ALESAGE", dimensions=g, instants=[1.0],
                   materials=("A304L", "A304L"), obstacle_coefficients={"coefficient": 1e-15})


def test_kwu_epri_uses_history_intensity():
    """K = k_r·w/w_r (theory §4) with w from kwu_epri_statistics of the same history."""
    pytest.importorskip("fretwear.power")
    from fretwear.laws import kwu_epri_statistics

    h = sector_history()
    t = wear_table(h, contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0], law="KWU_EPRI",
                   coefficients={"COEF_USURE": 1e-13, "reference_intensity": 2.0},
                   time_scale=3600.0)
    w = kwu_epri_statistics(h).intensity
    assert w > 0
    np.testing.assert_allclose(t["volume_mobile"], 1e-13 * w / 2.0 * 1.0 * 3600.0, rtol=1e-12)
    assert t.attrs["coefficients_mobile"]["intensity"] == pytest.approx(w)


def test_kwu_epri_power_result_with_its_history():
    """A PowerResult with history= gives the table of the history itself (same power, same
    KWU_EPRI classes, theory §2/§4): an independent path through wear_power."""
    from fretwear.power import wear_power

    h = sector_history()
    args = dict(contact_type="TUBE_BAV", dimensions=BAV, instants=[1.0, 2.0], law="KWU_EPRI",
                coefficients={"COEF_USURE": 1e-13, "reference_intensity": 2.0},
                time_scale=3600.0, t_start=1.0, t_end=7.0)
    direct = wear_table(h, **args)
    given = wear_table(wear_power(h, t_start=1.0, t_end=7.0), history=h, **args)
    pd.testing.assert_frame_equal(given, direct)
    assert given.attrs == direct.attrs
    with pytest.raises(InputError, match="history is the ContactHistory a PowerResult"):
        wear_table(h, history=h, **args)
    with pytest.raises(InputError, match="with a PowerResult source only"):
        wear_table(1.0, history=h, **args)


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
def test_sector_tube_replacement():
    """Tube replaced at 1 h: its sector volumes restart from zero, the obstacle's continue
    (theory §7 TUBE_NEUF); V_j = k_j·P_j·t (theory §3) with P_1 = P_3 = 0.5 W."""
    t = sector_table([1.0, 3.0], tube_replacement=1.0)
    k_m = np.array([1e-13, 2e-13, 3e-13, 4e-13])
    powers = np.array([0.5, 0.0, 0.5, 0.0])
    at1, at3 = t.iloc[:4], t.iloc[4:]
    assert at1["volume_mobile_cumulated"].eq(0.0).all()
    np.testing.assert_allclose(at3["volume_mobile_cumulated"], k_m * powers * 2 * 3600.0,
                               rtol=1e-14)
    np.testing.assert_allclose(at3["volume_mobile_sector"], k_m * powers * 2 * 3600.0,
                               rtol=1e-14)
    np.testing.assert_allclose(at3["volume_obstacle_cumulated"], [0, 0, 1e-14 * 0.5 * 3 * 3600.0,
                                                                  0], rtol=1e-14)


def test_sector_obstacle_depth_needs_obstacle_radius():
    """TUBE_BAV (flat bar) has no bore radius: the concave sector depth (theory §3) is undefined."""
    from fretwear.errors import RangeWarning

    with pytest.warns(RangeWarning, match=r"sectors \[3\]: the obstacle wears but TUBE_BAV"):
        t = sector_table([1.0])
    assert np.isnan(t["depth_obstacle_sector"].iloc[2])
    assert t["depth_obstacle_sector"].iloc[[0, 1, 3]].eq(0.0).all()


# TUBE_BAV has no bore radius, so an obstacle sector depth is NaN by design (asserted in
# test_sector_obstacle_depth_needs_obstacle_radius); the warning is expected here.
@pytest.mark.filterwarnings(
    "ignore:sectors .*obstacle_radius:fretwear.errors.RangeWarning")
def test_restart_from_a_sector_table_with_global_rows():
    """A Code_Aster-like sector table that also holds one global row per instant (SECTEUR
    empty): the sector state comes from the sector rows only; the chain still equals one long
    run (theory §7, V_j = k_j·P_j·t, theory §3)."""
    first = to_aster_names(sector_table([1.0]))
    glob = first.drop_duplicates("INST")[["INST", "DUREE", "ORIG_INST", "PUIS_USUR_GLOBAL",
                                          "V_USUR_TUBE", "V_USUR_OBST", "P_USUR_TUBE"]]
    mixed = pd.concat([glob, first], ignore_index=True)  # SECTEUR NaN on the global row
    state = initial_state(mixed)
    assert state.sector_count == 4
    np.testing.assert_allclose(state.sector_volume_mobile,
                               np.array([1e-13, 0.0, 3e-13, 0.0]) * 0.5 * 3600.0, rtol=1e-14)
    second = sector_table([2.0], initial_state=mixed)
    long = sector_table([1.0, 3.0])
    np.testing.assert_allclose(second["volume_mobile_cumulated"].iloc[-4:],
                               long["volume_mobile_cumulated"].iloc[-4:], rtol=1e-14)


# --------------------------------------------------------------------------- user coefficient files
def coefficient_csv(path, rows):
    """A user coefficient file in the format of fretwear.database (docs/laws.md)."""
    lines = ["contact_type,mobile_material,obstacle_material,law,parameter,value,unit"]
    lines += [f"TUBE_BAV,{m},{o},ARCHARD,COEF_USURE,{k!r},1/Pa" for m, o, k in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_coefficient_file_overrides_a_builtin_pair(tmp_path):
    """R7.20.01 §3: TUBE_BAV I600/A405 Archard K = 6.2e-14 Pa⁻¹. A user file giving K' = 3.1e-15
    replaces it; Archard is linear in K (V = K·P·t, theory §4), so V'/V = K'/K exactly."""
    pytest.importorskip("fretwear.database")
    k_builtin, k_user = 6.2e-14, 3.1e-15
    mine = coefficient_csv(tmp_path / "mine.csv", [("I600", "A405", k_user)])
    base = archard_table([1.0, 2.0], coefficients=None, materials=("I600", "A405"))
    user = archard_table([1.0, 2.0], coefficients=None, materials=("I600", "A405"),
                         coefficient_files=mine)
    np.testing.assert_allclose(base["volume_mobile"], k_builtin * P * YEAR * np.array([1, 2]),
                               rtol=1e-15)
    np.testing.assert_allclose(user["volume_mobile"] / base["volume_mobile"],
                               k_user / k_builtin, rtol=1e-15)
    assert user.attrs["coefficients_mobile"] == {"coefficient": k_user}
    assert user.attrs["coefficient_files"] == [str(mine)]
    assert str(mine) in user.attrs["coefficient_sources"]["mobile.coefficient"]
    assert "built-in" in base.attrs["coefficient_sources"]["mobile.coefficient"]
    # a list of files: the later one wins (load_database order)
    other = coefficient_csv(tmp_path / "other.csv", [("I600", "A405", 1.0e-14)])
    both = archard_table([1.0], coefficients=None, materials=("I600", "A405"),
                         coefficient_files=[mine, other])
    np.testing.assert_allclose(both["volume_mobile"], 1.0e-14 * P * YEAR, rtol=1e-15)


def test_coefficient_file_adds_a_pair(tmp_path):
    """R7.20.01's TUBE_BAV table has no I690TT/A405 box: the lookup fails; a user row for it
    makes the run work with V = K·P·t (theory §4)."""
    pytest.importorskip("fretwear.database")
    from fretwear.errors import DatabaseError

    with pytest.raises(DatabaseError, match="I690TT on obstacle A405"):
        archard_table([1.0], coefficients=None, materials=("I690TT", "A405"))
    mine = coefficient_csv(tmp_path / "mine.csv", [("I690TT", "A405", 2.5e-15)])
    t = archard_table([1.0, 3.0], coefficients=None, materials=("i690tt", "a405"),
                      coefficient_files=str(mine))
    np.testing.assert_allclose(t["volume_mobile"], 2.5e-15 * P * YEAR * np.array([1, 3]),
                               rtol=1e-15)
    np.testing.assert_allclose(t["depth_mobile"], bav_depth(t["volume_mobile"]), rtol=1e-12)


def test_coefficient_file_errors(tmp_path):
    pytest.importorskip("fretwear.database")
    from fretwear.errors import FormatError

    missing = tmp_path / "no_such_coefficients.csv"
    with pytest.raises(InputError, match="no_such_coefficients.csv.*does not exist"):
        archard_table([1.0], coefficients=None, materials=("I600", "A405"),
                      coefficient_files=[missing])
    mine = coefficient_csv(tmp_path / "mine.csv", [("I600", "A405", 1e-14)])
    with pytest.raises(KeywordError, match="give materials too"):
        archard_table([1.0], coefficient_files=mine)
    bad = tmp_path / "bad.csv"
    bad.write_text("contact_type,law\nTUBE_BAV,ARCHARD\n", encoding="utf-8")
    with pytest.raises(FormatError, match="bad.csv"):
        archard_table([1.0], coefficients=None, materials=("I600", "A405"),
                      coefficient_files=bad)
