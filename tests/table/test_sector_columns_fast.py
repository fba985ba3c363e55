"""The sector table's lean per-contact path (issue 28: the bundle worker's wear table) against
the general paths and independent computations.

* SectorSlices.depth_mobile of plain volumes (no NaN, within the sector: no checks' copies, no
  np.errstate) against sector_depth_mobile (the general function, its checks and masks) bit for
  bit, and against the closed form d = R − √(R² − 2V/(l·Δθ)) of docs/theory.md §3;
* the geometries' global depths of a plain pair (ContactGeometry._apply without its NaN masks;
  TUBE_BAV without them where no depth is NaN) against the same values given as lists (the
  general path), beyond the range included (NaN, the same RangeWarning);
* wear_table_columns of a sector case against Archard computed here: V_j = K·P_j·t, the sector
  depth of §3, the global depth of the flat trace D = (1/(2R))^(1/3)·(3V/(4l))^(2/3) (§6), the
  rows of the case (instants, origin, angles, sector numbers) for cases taken in turn;
* WearLaw.rate's coefficients kept per law: each call the law's volume after 1 s;
* a DepthModel's initial sector volumes remembered good still refuse a bad one.

Exact equality where the same floating-point operations are made in one process; rel 1e-13
against the closed forms (other operations: a few ulps).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from fretwear.errors import InputError, RangeWarning
from fretwear.geometry import CONTACT_TYPES, contact_geometry, sector_depth_mobile
from fretwear.geometry.sectors import SectorSlices
from fretwear.history import ContactHistory
from fretwear.laws import get_law
from fretwear.power import wear_power
from fretwear.table import WearCase, wear_table_columns
from fretwear.table.depth import DepthModel
from fretwear.table.schema import SECTOR_COLUMNS

R, L = 9.525e-3, 12.7e-3  # tube radius, bar width [m]
YEAR = 3.15576e7  # [s]
K = 1e-17  # Archard coefficient [1/Pa]


def _recorded(call):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = call()
    return out, [(w.category, str(w.message)) for w in caught]


def test_sector_depths_of_plain_volumes_equal_the_function_and_theory():
    arcs = (30.0, 60.0, 90.0, 180.0)
    s = SectorSlices(R, L, arcs)
    rng = np.random.default_rng(28)
    whole = L * np.radians(arcs) * R * R / 2  # the whole sector of the tube [m³]
    v = rng.uniform(0.0, 1.0, (6, 4)) * whole
    v[0] = 0.0
    v[1] = -0.0
    v[2, 3] = whole[3]  # the whole sector: R² − 2a_θ about 0
    fast, said = _recorded(lambda: s.depth_mobile(v))
    general, expected = _recorded(lambda: sector_depth_mobile(v, R, L, np.array(arcs)))
    assert fast.tobytes() == np.asarray(general).tobytes() and said == expected
    a = 2 * v / (L * np.radians(arcs))
    assert fast[3:] == pytest.approx(R - np.sqrt(R * R - a[3:]), rel=1e-13)
    beyond = v.copy()
    beyond[4, 0] = 2 * whole[0]  # beyond the whole sector: NaN with the function's warning
    fast, said = _recorded(lambda: s.depth_mobile(beyond))
    general, expected = _recorded(lambda: sector_depth_mobile(beyond, R, L, np.array(arcs)))
    assert np.array_equal(fast, general, equal_nan=True) and np.isnan(fast[4, 0])
    assert said == expected and said[0][0] is RangeWarning


@pytest.mark.parametrize("contact_type, extra", [
    ("TUBE_BAV", {"tilt_angle": 0.0}), ("TUBE_BAV", {}),  # the example is tilted 1°
    ("TUBE_BAV", {"tilt_angle": 1.0, "impact_angle": 20.0}),
    ("GRAPPE_ALESAGE", {}), ("TUBE_ALESAGE", {}), ("TUBE_TUBE", {}), ("GRAPPE_1_ENCO", {}),
    ("TUBE_3_ENCO", {})])
@pytest.mark.parametrize("obstacle_wears", [False, True])
def test_global_depths_of_plain_pairs_equal_the_general_path(contact_type, extra,
                                                             obstacle_wears):
    """Arrays (the plain pair) against lists (converted, checked, masked), volumes beyond the
    relation's range included: the same depths bit for bit, the same RangeWarning."""
    g = contact_geometry(contact_type, **{**CONTACT_TYPES[contact_type].example, **extra})
    vm = np.geomspace(1e-13, 1e-4, 9)  # the last ones beyond every geometry's range
    vm[0] = 0.0
    vo = vm / 3 if obstacle_wears else np.zeros(9)
    fast, said = _recorded(lambda: g.depth_from_volume(vm, vo))
    general, expected = _recorded(lambda: g.depth_from_volume(vm.tolist(), vo.tolist()))
    for a, b in zip(fast, general, strict=True):
        assert type(a) is np.ndarray and a.dtype == np.float64
        assert np.array_equal(a, b, equal_nan=True)
        assert np.array_equal(np.signbit(a), np.signbit(b))
    assert said == expected and np.isnan(fast[0][-1])
    if extra == {"tilt_angle": 0.0}:  # TUBE_BAV's flat trace of docs/theory.md §6
        d = (1 / (2 * R)) ** (1 / 3) * (3 * (vm + vo) / (4 * L)) ** (2 / 3)
        share = np.divide(vm, vm + vo, out=np.zeros(9), where=vm + vo > 0)
        ok = d <= R
        assert fast[0][ok] == pytest.approx(d[ok] * share[ok], rel=1e-13, abs=0.0)


def _power(m: int, scale: float):
    t = np.linspace(0.0, 1.0, 1001)
    phase = 2 * np.pi * 20 * t
    h = ContactHistory(time=t, normal_force=np.maximum(0.0, scale * np.sin(phase)),
                       vt1=0.02 * np.cos(phase), vt2=0.01 * np.sin(phase),
                       dy=1e-4 * np.cos(phase / 3), dz=1e-4 * np.sin(phase / 9))
    return wear_power(h, sectors=m)


def _case(m: int, instants):
    kw = {"contact_type": "TUBE_BAV", "instants": instants, "sectors": m, "time_scale": YEAR,
          "dimensions": {"mobile_radius": R, "obstacle_width": L},
          "coefficients": {"COEF_USURE": K}}
    return WearCase.from_keywords(**kw)


def _archard(case: WearCase, power) -> dict:
    """The sector columns computed here: Archard V_j = K·P_j·t (§3), no earlier wear."""
    p = np.asarray(power.sectors, dtype=float)
    edges = np.asarray(power.sector_edges, dtype=float)
    durations = np.asarray(case.instants, dtype=float)
    n, m = durations.size, p.size
    vm = K * p * (durations * YEAR)[:, None]
    total = vm.sum(axis=1)
    arcs = np.radians(np.diff(edges))
    depth = (1 / (2 * R)) ** (1 / 3) * (3 * total / (4 * L)) ** (2 / 3)
    return {"instant": np.repeat(case.origin + durations, m),
            "duration": np.repeat(durations, m), "origin": np.full(n * m, case.origin),
            "power": np.full(n * m, float(power.total)), "volume_mobile": np.repeat(total, m),
            "depth_mobile": np.repeat(depth, m), "sector": np.tile(np.arange(1, m + 1), n),
            "angle_start": np.tile(edges[:-1], n), "angle_end": np.tile(edges[1:], n),
            "sector_power": np.tile(p, n), "volume_mobile_cumulated": vm.ravel(),
            "depth_mobile_sector": (R - np.sqrt(R * R - 2 * vm / (L * arcs))).ravel()}


def test_sector_columns_are_archard_for_cases_taken_in_turn():
    """Cases of other instants and sector counts in turn (a bundle's workers take
    many): each table's own rows of the case, its volumes and depths Archard's, the obstacle's
    exactly 0; a table's columns changed by its user change no other table."""
    cases = [(_case(8, [1, 2, 5, 10, 20, 40]), _power(8, 30.0)),
             (_case(4, [0.5, 3.0]), _power(4, 10.0)),
             (_case(8, [1, 2, 5, 10, 20, 41]), _power(8, 3.0))]
    for _ in range(2):
        for case, power in cases:
            columns, _ = wear_table_columns(case, power)
            expected = _archard(case, power)
            assert list(columns) == list(SECTOR_COLUMNS)  # the table's order
            for name in ("instant", "duration", "origin", "power", "sector", "angle_start",
                         "angle_end", "sector_power"):
                assert np.array_equal(columns[name], expected[name]), name
            assert columns["sector"].dtype.kind == "i"
            for name in ("volume_mobile", "depth_mobile", "volume_mobile_cumulated",
                         "depth_mobile_sector"):
                assert columns[name] == pytest.approx(expected[name], rel=1e-13), name
            assert np.array_equal(columns["volume_mobile_sector"],
                                  columns["volume_mobile_cumulated"])
            for name in ("volume_obstacle", "depth_obstacle", "volume_obstacle_sector",
                         "depth_obstacle_sector", "volume_obstacle_cumulated"):
                assert not columns[name].any(), name
            columns["instant"][:] = -1.0  # the user's own arrays
            columns["sector"][:] = -1
            columns["angle_start"][:] = -1.0


def test_rate_of_each_coefficient_is_the_volume_after_one_second():
    """The coefficients kept per law never stand for others: K1, K2, K1 again, and an int
    coefficient (the law function's path) after the equal float."""
    law = get_law("ARCHARD")
    p = np.array([0.0, 0.01, 0.3])
    for k in (1e-17, 3e-17, 1e-17):
        assert law.rate(p, coefficient=k).tobytes() == law.volume(p, 1.0, coefficient=k) \
            .tobytes()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert law.rate(p, coefficient=2.0).tolist() == law.rate(p, coefficient=2).tolist()
        assert law.rate(p, COEF_USURE=1e-17).tobytes() == law.rate(p, coefficient=1e-17) \
            .tobytes()
    with pytest.raises(InputError, match="power"):
        law.rate(np.array([0.01, -0.01]), coefficient=1e-17)


@pytest.mark.parametrize("bad", [-1e-12, math.inf, math.nan])
def test_initial_volumes_remembered_good_still_refuse_a_bad_one(bad):
    g = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=L)

    def model(v0):
        return DepthModel(law=get_law("ARCHARD"), geometry=g, powers=(1e-3, 1e-3),
                          coefficients_mobile=({"coefficient": K},) * 2,
                          coefficients_obstacle=(None,) * 2, sector_arcs=(180.0, 180.0),
                          term_initial=((0.0, 1e-12), v0))

    model((0.0, 2e-12))
    model((0.0, 2e-12))  # remembered
    with pytest.raises(InputError, match=r"sector volumes of the obstacle must be finite"):
        model((0.0, bad))
    with pytest.raises(InputError, match=r"sector volumes of the obstacle must be finite"):
        model([0.0, bad])  # a list: not remembered, checked


@pytest.mark.parametrize("edges, differ", [
    ([-180.0, -90.0, -0.0, 90.0, 180.0], False),  # -0.0 is 0.0: the same edges, other bytes
    ([-180.0, -100.0, 0.0, 90.0, 180.0], True), (8, True)])
def test_power_of_other_sector_edges_is_refused(edges, differ):
    """A PowerResult's sector edges against the case's: equal numbers pass (whatever their
    bytes), others raise an InputError naming both (np.array_equal's meaning)."""
    power = _power(4, 30.0)  # edges -180, -90, 0, 90, 180 [deg]
    case = _case(edges, [1, 2])
    if differ:
        with pytest.raises(InputError, match="sector edges .* differ from the case's sectors"):
            wear_table_columns(case, power)
    else:
        assert wear_table_columns(case, power)[0]["angle_start"][2] == 0.0


def test_initial_volumes_of_equal_tuples_keep_their_own_zeros():
    """term_initial ((0.0,), (0.0,)) then the equal ((-0.0,), (0.0,)): each model's own
    volumes, V = V0 + K·P·t computed here with P = -0.0 (the sign of zero kept as IEEE adds)."""
    g = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=L)
    t = np.array([1.0])
    for v0 in (0.0, -0.0, 0.0):
        model = DepthModel(law=get_law("ARCHARD"), geometry=g, powers=(-0.0,),
                           coefficients_mobile=({"coefficient": K},),
                           coefficients_obstacle=(None,), sector_arcs=(360.0,),
                           term_initial=((v0,), (0.0,)))
        vm = model.sector_table(t)["volume_mobile"]
        expected = np.float64(v0) + K * np.float64(-0.0) * 1.0 * t[:, None]
        assert np.signbit(vm).tolist() == np.signbit(expected).tolist()
        assert bool(np.signbit(vm[0, 0])) == (math.copysign(1.0, v0) < 0)


def test_a_large_tables_rows_are_not_kept_after_it():
    """The case's rows kept for the next table (table._columns' templates) are small: a table
    of 400 instants × 36 sectors (a 2 MB block) is made right, Archard's as above, and not kept
    (64 such cases held 664 MB for the life of the process)."""
    from fretwear.table import _columns

    case, power = _case(36, list(np.arange(1.0, 401.0))), _power(36, 30.0)
    columns, _ = wear_table_columns(case, power)
    expected = _archard(case, power)
    for name in ("instant", "sector", "angle_start", "angle_end"):
        assert np.array_equal(columns[name], expected[name]), name
    assert columns["depth_mobile_sector"] == pytest.approx(expected["depth_mobile_sector"],
                                                           rel=1e-13)
    held = sum(b.nbytes + s.nbytes for b, s in _columns._TEMPLATES.values())
    assert held <= _columns._TEMPLATES_KEPT * _columns._TEMPLATE_BYTES
    assert all(b.shape[1:] != (400, 36) for b, _ in _columns._TEMPLATES.values())


def test_a_depth_models_coefficients_as_any_sequence():
    """DepthModel takes its terms' coefficients as any sequence (the dataclass checks their
    number only): as NumPy object arrays the same depths as tuples (a tuple's ``count`` was
    asked of them: AttributeError). Reference: the tuples' model."""
    geometry = contact_geometry("TUBE_BAV", mobile_radius=R, obstacle_width=L)

    def model(mobile, obstacle):
        return DepthModel(law=get_law("ARCHARD"), geometry=geometry, powers=(0.01, 0.02),
                          coefficients_mobile=mobile, coefficients_obstacle=obstacle,
                          time_scale=YEAR, sector_arcs=(1.0, 1.0),
                          term_initial=((0.0, 0.0), (0.0, 0.0)))

    coef = {"coefficient": K}
    tuples = model((coef, coef), (None, None)).sector_table(np.array([YEAR]))
    arrays = model(np.array([coef, coef], dtype=object),
                   np.array([None, None], dtype=object)).sector_table(np.array([YEAR]))
    for name in ("depth_mobile", "depth_obstacle"):
        assert np.array_equal(arrays[name], tuples[name]), name
    assert tuples["depth_mobile"].all()
