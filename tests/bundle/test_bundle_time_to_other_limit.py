"""``BundleResult.summary(limit)``'s ``time_to_limit`` for a limit other than the case's own:
exact, through the contact's geometry and the worn volume, not an interpolation of the depth.

Independent computations (no code of fretwear.table.depth_rows):

* Archard's worn volume at constant power is V = K·P·t (theory §2; K = 9.2e-15 1/Pa of
  bundle_helpers.BASE_CASE, P the contact's power, t in seconds, a year of 365 days): the
  instant at which the TUBE_BAV relation ``geometry.depth_from_volume(K·P·t)`` reaches the limit
  depth, found here by bisection;
* the single-contact wear table (``fretwear.table.wear_table`` on the same history) of a case
  whose ``depth_limit`` and ``wall_thickness`` give the same limit depth: its ``limit_instant``
  is the law and the geometry inverted in closed form (fretwear.table.limit), with sectors, a
  tube replacement, a restart from an earlier table (the volume at the origin not 0) and the
  EDF-MZ law (not linear in time).

Each contact's own wall puts its limit before the first instant (0.5 year), between two
instants, or beyond the last one (NaN). The monotone cubic the summary used before comes out
late before the first instant (more than 10 % here; up to 76 % on the shipped example bundle at
1 % of the wall: the depth of a flat grows as the volume to about 2/3, steeply near 0), which a
plugging decision must not be; it stays the fallback where the geometry is not known.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bundle_helpers import BASE_CASE, oscillator, reference, write_bundle

from fretwear.bundle import run_bundle
from fretwear.bundle.result import summarize
from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.table import write_wear_table
from fretwear.table.depth_build import record_model
from fretwear.table.depth_rows import FROM_MODEL, INTERPOLATED, interpolated_time

pytest.importorskip("xarray")
# the walls are made thin to put the limits where wanted: worn through by the last instant
pytestmark = pytest.mark.filterwarnings("ignore::fretwear.errors.PerforationWarning")

YEAR = 365 * 86400.0  # [s]
K = 9.2e-15  # [1/Pa], BASE_CASE's COEF_USURE
LIMIT = 0.25  # [-], not the case's depth_limit (0.4)
NO_SECTORS = BASE_CASE.replace("[sectors]\ncount = 4\n", "")
BAR = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)


def _global(result, contact):
    rows = result.table[result.table["contact"] == contact].drop_duplicates("instant")
    return rows.sort_values("instant")


def _bundle(directory, case_text, extra=None, count=3):
    manifest, case = write_bundle(directory, oscillator(), count, extra=extra)
    case.write_text(case_text)
    return manifest, case


def _walls(directory, case_text, extra=None, *, replaced=False):
    """Walls putting contact 0's limit depth (LIMIT × wall) at half its depth at the first
    instant, contact 1's midway between its depths at 1 and 2 years (at 80 % of its depth at
    5 years after a replacement), contact 2's at 1.2 times its last depth (never reached)."""
    manifest, case = _bundle(directory, case_text, extra)
    first = run_bundle(manifest, case, scheduler="serial")
    d = {c: _global(first, c)["depth_mobile"].to_numpy() for c in first.contacts["contact"]}
    names = list(d)
    targets = [0.5 * d[names[0]][0],
               0.8 * d[names[1]][-1] if replaced else 0.5 * (d[names[1]][1] + d[names[1]][2]),
               1.2 * d[names[2]][-1]]
    return manifest, case, [float(t) / LIMIT for t in targets]


def _single(directory, history, case_text, wall, **keys):
    """limit_instant of the single-contact table with depth_limit LIMIT of ``wall``."""
    text = case_text.replace("[geometry]\n", f"[geometry]\nwall_thickness_m = {float(wall)!r}\n"
                             f"depth_limit = {LIMIT}\n")
    for section, line in keys.items():
        text = text.replace(f"[{section}]\n", f"[{section}]\n{line}\n")
    path = directory / "single.toml"
    path.write_text(text)
    return float(reference(directory / history, path)["limit_instant"].iloc[-1])


def _run_with_walls(directory, case_text, walls, extra=None):
    manifest, case = _bundle(directory, case_text, {**(extra or {}), "wall_thickness_m": walls})
    return run_bundle(manifest, case, scheduler="serial")


def _check_against_single(directory, result, case_text, walls, method, keys=()):
    s = result.summary(LIMIT).set_index("contact")
    for k, contact in enumerate(result.contacts["contact"]):
        row = s.loc[contact]
        assert row["time_to_limit_method"] == method
        expected = _single(directory, f"histories/t{k}.parquet", case_text, walls[k],
                           **dict(keys[k] if keys else {}))
        if k == 2:  # beyond the last instant: NaN (the single table's instant is later)
            assert math.isnan(row["time_to_limit"]) and expected > row["instant"]
        else:
            assert row["time_to_limit"] == pytest.approx(expected, rel=1e-12), contact
    return s


def test_archard_against_the_bisection_of_k_p_t(tmp_path):
    manifest, case, walls = _walls(tmp_path / "a", NO_SECTORS)
    result = _run_with_walls(tmp_path / "b", NO_SECTORS, walls)
    s = result.summary(LIMIT).set_index("contact")
    old = summarize(result.table, result.contacts[["contact", "wall_thickness", "tube_row"]],
                    limit=LIMIT, limit_m=None, wall_thickness=None).set_index("contact")
    for k, contact in enumerate(result.contacts["contact"]):
        rows = _global(result, contact)
        power = float(rows["power"].iloc[0])
        # the model: the table's volumes are K·P·t
        volume = K * power * rows["instant"].to_numpy() * YEAR
        assert np.allclose(rows["volume_mobile"], volume, rtol=1e-12, atol=0)
        target = LIMIT * walls[k]
        row = s.loc[contact]
        assert row["limit_depth"] == pytest.approx(target, rel=1e-15)
        assert row["time_to_limit_method"] == FROM_MODEL
        if k == 2:
            assert math.isnan(row["time_to_limit"])
            continue
        lo, hi = 0.0, float(rows["instant"].iloc[-1])
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if BAR.depth_from_volume(K * power * mid * YEAR)[0] < target:
                lo = mid
            else:
                hi = mid
        assert row["time_to_limit"] == pytest.approx(hi, rel=1e-12), contact
        assert (row["time_to_limit"] < 0.5) == (k == 0)  # before the first instant
        # without the geometry (a contacts frame without it): the cubic, late before 0.5 year
        assert old.loc[contact, "time_to_limit_method"] == INTERPOLATED
        cubic = interpolated_time(rows["instant"], rows["depth_mobile"], target)
        assert old.loc[contact, "time_to_limit"] == cubic
        if k == 0:
            assert cubic > 1.1 * hi
    assert s.attrs["time_to_limit"] == FROM_MODEL


def test_sectors_against_the_single_contact_table(tmp_path):
    _, _, walls = _walls(tmp_path / "a", BASE_CASE)
    result = _run_with_walls(tmp_path / "b", BASE_CASE, walls)
    _check_against_single(tmp_path / "b", result, BASE_CASE, walls, FROM_MODEL)


def test_a_replaced_tube_against_the_single_contact_table(tmp_path):
    """Contact 1's tube replaced at 1.5 years (between the instants 1 and 2): its volume
    starts again from 0 there, not at instant 0."""
    extra = {"tube_replacement": [None, 1.5, None]}
    _, _, walls = _walls(tmp_path / "a", NO_SECTORS, extra, replaced=True)
    result = _run_with_walls(tmp_path / "b", NO_SECTORS, walls, extra)
    keys = [{}, {"time": "tube_replacement = 1.5"}, {}]
    s = _check_against_single(tmp_path / "b", result, NO_SECTORS, walls, FROM_MODEL, keys)
    assert s.iloc[0]["time_to_limit_method"] == FROM_MODEL
    replaced = s.loc[result.contacts["contact"].iloc[1], "time_to_limit"]
    assert 2.0 < replaced < 5.0


def test_edf_mz_against_the_single_contact_table(tmp_path):
    """EDF-MZ's volume is not linear in time (a run-in decaying as exp(-n·t)): the time comes
    from the law's equivalent times of the volumes, as the single-contact table's."""
    # A = 9.2e-15 (the base's COEF_USURE) and S = 1e-19 m³/s, below these contacts' initial
    # rate A·P^b (4e-18 to 7e-18 m³/s): a run-in slowing down, as the law means (the default
    # S = 1.14e-16 m³/s would exceed it, and the law warns)
    case_text = NO_SECTORS.replace("[law]\nmobile = { COEF_USURE = 9.2e-15 }\n",
                                   '[law]\nname = "EDF_MZ"\n'
                                   "mobile = { COEF_USURE = 9.2e-15, COEF_S = 1e-19 }\n")
    assert "COEF_S" in case_text
    _, _, walls = _walls(tmp_path / "a", case_text)
    result = _run_with_walls(tmp_path / "b", case_text, walls)
    _check_against_single(tmp_path / "b", result, case_text, walls, FROM_MODEL)


def _restarted(directory, case_text):
    """(case text continuing contact 0's 5-year Archard table with ``case_text``, the global
    rows of the 2 contacts run with it)."""
    _, case = _bundle(directory, NO_SECTORS, count=2)
    earlier = reference(directory / "histories/t0.parquet", case)
    write_wear_table(earlier, directory / "earlier.csv")
    restarted = case_text + f'[restart]\ntable = "{directory / "earlier.csv"}"\n'
    first = run_bundle(*_bundle(directory, restarted, count=2), scheduler="serial")
    return restarted, [_global(first, c) for c in first.contacts["contact"]]


def test_a_restart_from_an_earlier_table_starts_from_its_volume(tmp_path):
    """A run continuing an earlier 5-year table (origin 5, its volume there not 0), limits
    between the origin and the first new instant (5.5) and between new instants."""
    directory = tmp_path / "r"
    restarted, rows = _restarted(directory, NO_SECTORS)
    assert rows[0]["origin"].iloc[-1] == 5.0 and rows[0]["volume_mobile"].iloc[3] > 0
    d0, d1 = (r.set_index("instant")["depth_mobile"] for r in rows)
    walls = [(d0[5.0] + d0[5.5]) / 2 / LIMIT, (d1[6.0] + d1[7.0]) / 2 / LIMIT]
    result = run_bundle(*_bundle(directory, restarted, {"wall_thickness_m": walls}, count=2),
                        scheduler="serial")
    s = result.summary(LIMIT).set_index("contact")
    for k, contact in enumerate(result.contacts["contact"]):
        expected = _single(directory, f"histories/t{k}.parquet", restarted, walls[k])
        assert s.loc[contact, "time_to_limit_method"] == FROM_MODEL
        assert s.loc[contact, "time_to_limit"] == pytest.approx(expected, rel=1e-12)
    assert 5.0 < s.loc[result.contacts["contact"].iloc[0], "time_to_limit"] < 5.5


EDF_MZ = ('[law]\nname = "EDF_MZ"\nmobile = { COEF_USURE = 9.2e-15, COEF_S = 1e-19 }\n')


def test_edf_mz_with_a_wearing_obstacle_against_the_single_contact_table(tmp_path):
    """The tube's depth on a flat bar depends on the bar's wear too (TUBE_BAV): both volumes
    follow EDF-MZ from their equivalent times along the segment (obstacle A = 5e-15, its own
    S), solved for the limit depth; it used to fall back to the cubic, 2.4 times late here
    before the first instant (a review). Against the single-contact table's limit_instant."""
    case_text = NO_SECTORS.replace("[law]\nmobile = { COEF_USURE = 9.2e-15 }\n",
                                   EDF_MZ + "obstacle = { COEF_USURE = 5e-15, COEF_S = 1e-19 }\n")
    assert "obstacle = {" in case_text
    _, _, walls = _walls(tmp_path / "a", case_text)
    result = _run_with_walls(tmp_path / "b", case_text, walls)
    assert (_global(result, result.contacts["contact"][0])["volume_obstacle"] > 0).all()
    _check_against_single(tmp_path / "b", result, case_text, walls, FROM_MODEL)


def test_a_limit_reached_in_the_initial_tables_rows_is_interpolated_there(tmp_path):
    """A restart's table starts with the initial table's rows, which may come from another
    law (here an Archard table continued with EDF-MZ): a limit reached among them is not this
    run's law's to invert (it used to be, giving the next instant and calling it exact: up to
    74 % late, a review); it is found among those rows, the volume linear in time between them
    (FROM_MODEL: exact for the Archard table, checked against its own single-contact
    table). A limit after the origin stays exact (FROM_MODEL, against the single-contact
    table)."""
    directory = tmp_path / "r"
    edf = NO_SECTORS.replace("[law]\nmobile = { COEF_USURE = 9.2e-15 }\n", EDF_MZ)
    restarted, rows = _restarted(directory, edf)
    d0, d1 = (r.set_index("instant")["depth_mobile"] for r in rows)
    # contact 0: between the initial table's 1 and 2 years; contact 1: after the origin (5)
    walls = [(d0[1.0] + d0[2.0]) / 2 / LIMIT, (d1[6.0] + d1[7.0]) / 2 / LIMIT]
    result = run_bundle(*_bundle(directory, restarted, {"wall_thickness_m": walls}, count=2),
                        scheduler="serial")
    s = result.summary(LIMIT).set_index("contact")
    c0, c1 = result.contacts["contact"]
    # among the initial (Archard) table's rows: its volume linear in time, exact for it, so
    # the single-contact Archard table of the same history gives the instant
    expected = _single(directory, "histories/t0.parquet", NO_SECTORS, walls[0])
    assert s.loc[c0, "time_to_limit_method"] == FROM_MODEL
    assert s.loc[c0, "time_to_limit"] == pytest.approx(expected, rel=1e-12)
    assert 1.0 < s.loc[c0, "time_to_limit"] < 2.0
    assert s.loc[c1, "time_to_limit_method"] == FROM_MODEL
    single = _single(directory, "histories/t1.parquet", restarted, walls[1])
    assert s.loc[c1, "time_to_limit"] == pytest.approx(single, rel=1e-12)


def _bar_model(t, vm, origins, rate):
    """The bundle contact's depth model (record_model) of rows on the flat bar: Archard from
    the origin at ``rate`` [m³ per year] (K·P·year = rate at P = 0.01 W)."""
    record = {"contact_type": "TUBE_BAV", "dimensions": BAR.dimensions(), "law": "ARCHARD",
              "coefficients_mobile": {"coefficient": rate / (0.01 * YEAR)},
              "coefficients_obstacle": None, "time_scale": YEAR,
              "origin": float(origins[-1])}
    d = np.asarray(BAR.depth_from_volume(vm)[0])
    return record_model(record, instants=t, origins=origins, depths=d, volume_mobile=vm,
                        volume_obstacle=None, power=0.01, geometry=BAR)


def test_a_limit_after_a_replacement_inside_the_initial_table_is_not_called_exact():
    """An initial table that replaced the tube (its volume drops) holds no replacement
    instant: the new tube is counted from the initial table's last row before the drop, the
    earliest the replacement can be, so the time is never late (it was the first row after the
    drop, called exact, a review); a limit the old tube had reached before it was replaced
    does not count (the tube in place is the new one, as for a replacement in this run)."""
    t = np.array([0.5, 1.0, 2.0, 5.0, 6.0, 7.0])
    vm = 1e-9 * np.array([4.0, 8.0, 4.0, 16.0, 20.0, 24.0])  # replaced between 1 and 2
    model = _bar_model(t, vm, np.array([0.0, 0.0, 0.0, 0.0, 5.0, 5.0]), 4e-9)
    # the new tube's 4e-9 m³ at 2 counted from 1, its earliest replacement: 2e-9 m³ at 1.5
    got = model.time_to(float(BAR.depth_from_volume(2e-9)[0]))
    assert got == pytest.approx(1.5, rel=1e-12)
    # after the origin: the law from the origin's 16e-9 m³, 4e-9 m³ a year (22e-9 m³ at 6.5)
    got = model.time_to(float(BAR.depth_from_volume(22e-9)[0]))
    assert got == pytest.approx(6.5, rel=1e-12)


def test_a_contact_without_its_geometry_keeps_the_cubic_and_says_so(tmp_path):
    manifest, case = _bundle(tmp_path, NO_SECTORS, count=2)
    result = run_bundle(manifest, case, scheduler="serial")
    contacts = result.contacts.copy()
    contacts.loc[0, "contact_type"] = None  # as the record of an older version's part
    s = summarize(result.table, contacts, limit=None, limit_m=1e-6, wall_thickness=None)
    s = s.set_index("contact")
    a, b = contacts["contact"]
    assert s.loc[a, "time_to_limit_method"] == INTERPOLATED
    assert s.loc[b, "time_to_limit_method"] == FROM_MODEL
    assert s.attrs["time_to_limit"] in (f"{FROM_MODEL}; {INTERPOLATED}",
                                        f"{INTERPOLATED}; {FROM_MODEL}")
    rows = _global(result, a)
    assert s.loc[a, "time_to_limit"] == interpolated_time(rows["instant"], rows["depth_mobile"],
                                                      1e-6)


def test_an_initial_table_without_a_row_at_the_origin_is_refused():
    """A restart's origin is an instant of its initial table (INST_INIT: restart._state
    refuses another); rows whose earlier part ends before the origin do not give the volume
    at the origin, so no model is made of them (the summary then interpolates the rows)."""
    t = np.array([1.0, 2.0, 3.0, 4.0])  # the initial table's 1 and 2; this run's origin 2.5
    vm = 1e-9 * np.array([2.0, 4.0, 6.0, 8.0])
    with pytest.raises(InputError, match="origin"):
        _bar_model(t, vm, np.array([0.0, 0.0, 2.5, 2.5]), 2e-9)
