"""The geometry contract (docs/DESIGN.md "Geometry"), checked on every entry of CONTACT_TYPES.

Sources: the contract itself (theory §6 last paragraph: monotone relations inverted by a
bracketed solver, NaN and a warning naming the type beyond the range, an error naming a missing
keyword, a warning for an unused one) and the identity depth -> volume -> depth.
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings

import numpy as np
import pytest

from fretwear.errors import InputError, KeywordError, RangeWarning, UnusedKeywordWarning
from fretwear.geometry import ASTER_KEYWORDS, CONTACT_TYPES, contact_geometry

NAMES = sorted(CONTACT_TYPES)


def build(name, **changes):
    dims = {**CONTACT_TYPES[name].example, **changes}
    return contact_geometry(name, **{k: v for k, v in dims.items() if v is not None})


def test_all_eight_types_are_registered():
    assert set(CONTACT_TYPES) == {
        "TUBE_BAV", "TUBE_ALESAGE", "TUBE_3_ENCO", "TUBE_4_ENCO", "TUBE_TUBE",
        "GRAPPE_ALESAGE", "GRAPPE_1_ENCO", "GRAPPE_2_ENCO"}
    for name, cls in CONTACT_TYPES.items():
        assert cls.contact_type == name
        assert set(cls.example) <= set(cls.required) | set(cls.optional)


@pytest.mark.parametrize("name", NAMES)
def test_monotone_and_zero(name):
    geometry = build(name)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        volume = geometry.max_volume * np.linspace(0.0, 0.999, 300)
        depth = geometry.depth_from_volume(volume)[0]
        assert depth[0] == 0.0 and np.all(np.diff(depth) > 0.0)
        assert geometry.depth_from_volume(0.0, 0.0) == (0.0, 0.0)
        assert geometry.volume_from_depth(0.0, 0.0) == (0.0, 0.0)


@pytest.mark.parametrize("name", NAMES)
def test_round_trip_mobile_only_and_with_obstacle(name):
    geometry = build(name)
    depth = np.geomspace(1e-9 * geometry.max_depth, 0.95 * geometry.max_depth, 40)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        vm, vo = geometry.volume_from_depth(depth)
        assert not np.any(vo)
        back = geometry.depth_from_volume(vm, vo)[0]
        # the solvers work to ~1e-12 relative (measured <= 5e-12 over 2000 depths per type)
        assert np.all(np.abs(back - depth) <= 1e-11 * depth)
        # obstacle wear: a volume split (a depth split may be infeasible, e.g. for the
        # broached holes, where V_o = κπ·l·R_o·d_o grows faster than the lens at small depth)
        vm = geometry.max_volume * np.geomspace(1e-9, 0.5, 30)
        vo = 0.2 * vm
        dm, do = geometry.depth_from_volume(vm, vo)
        assert np.all(do > 0.0) and np.all(dm > 0.0)
        vm2, vo2 = geometry.volume_from_depth(dm, do)
        assert np.allclose(vm2, vm, rtol=1e-10, atol=0) and np.allclose(vo2, vo, rtol=1e-10, atol=0)
        dm2, do2 = geometry.depth_from_volume(vm2, vo2)
        assert np.all(np.abs(dm2 - dm) <= 1e-10 * (dm + do))
        assert np.all(np.abs(do2 - do) <= 1e-10 * (dm + do))


@pytest.mark.parametrize("name", NAMES)
def test_beyond_range_is_nan_with_warning(name):
    geometry = build(name)
    with pytest.warns(RangeWarning, match=name):
        dm, do = geometry.depth_from_volume([0.5 * geometry.max_volume, 1.5 * geometry.max_volume])
    assert np.isfinite(dm[0]) and np.isnan(dm[1])  # (d_o may stay valid when independent)
    with pytest.warns(RangeWarning, match=name):
        vm, _ = geometry.volume_from_depth([0.5 * geometry.max_depth, 1.5 * geometry.max_depth])
    assert np.isfinite(vm[0]) and np.isnan(vm[1])
    with pytest.warns(RangeWarning) as record:
        geometry.depth_from_volume(2.0 * geometry.max_volume)
    message = str(record[0].message)
    assert message.startswith(f"{name}:") and geometry.range_limit in message  # names the limit
    assert f"{geometry.max_depth:.6g}" in geometry.range_limit  # ... with its value


@pytest.mark.parametrize("name", NAMES)
def test_missing_and_unused_dimensions(name):
    cls = CONTACT_TYPES[name]
    for missing in cls.required:
        dims = {k: v for k, v in cls.example.items() if k != missing}
        with pytest.raises(KeywordError, match=rf"{missing} \({ASTER_KEYWORDS[missing]}"):
            contact_geometry(name, **dims)
    unused = [k for k in ASTER_KEYWORDS if k not in cls.required + cls.optional]
    for extra in unused:
        value = 10.0 if extra.endswith("angle") else 0.01
        with pytest.warns(UnusedKeywordWarning, match=ASTER_KEYWORDS[extra]):
            geometry = contact_geometry(name, **cls.example, **{extra: value})
        assert geometry == contact_geometry(name, **cls.example)
    with pytest.raises(KeywordError, match="not a contact dimension"):
        contact_geometry(name, **cls.example, wall_thickness=1e-3)
    with pytest.raises(KeywordError, match="unknown contact type"):
        contact_geometry(name + "_X", **cls.example)


@pytest.mark.parametrize("name", NAMES)
def test_bad_inputs_and_keywords(name):
    cls = CONTACT_TYPES[name]
    length = next(k for k in cls.required if not k.endswith("angle"))
    for bad in (-1e-3, 0.0, float("nan")):
        with pytest.raises(InputError, match=ASTER_KEYWORDS[length]):
            contact_geometry(name, **{**cls.example, length: bad})
    geometry = build(name)
    with pytest.raises(InputError, match="volume_mobile"):
        geometry.depth_from_volume([1e-12, -1e-12])
    with pytest.raises(InputError, match="depth_obstacle"):
        geometry.volume_from_depth(1e-6, float("inf"))
    aster = {ASTER_KEYWORDS[k]: v for k, v in cls.example.items()}
    assert contact_geometry(name.lower(), **aster) == geometry
    json.dumps(geometry.to_dict())
    with pytest.raises(dataclasses.FrozenInstanceError):
        geometry.mobile_radius = 1.0  # type: ignore[misc]


@pytest.mark.parametrize("name", NAMES)
def test_vectorised_and_inputs_untouched(name):
    geometry = build(name)
    vm = geometry.max_volume * np.array([[0.1, 0.2, 0.3], [0.0, 0.05, 0.4]])
    vo = 0.1 * vm
    vm_copy, vo_copy = vm.copy(), vo.copy()
    dm, do = geometry.depth_from_volume(vm, vo)
    assert dm.shape == vm.shape and do.shape == vm.shape
    assert np.array_equal(vm, vm_copy) and np.array_equal(vo, vo_copy)
    for i in range(vm.shape[0]):
        for j in range(vm.shape[1]):
            single = geometry.depth_from_volume(float(vm[i, j]), float(vo[i, j]))
            assert single[0] == pytest.approx(dm[i, j], rel=1e-12, abs=0)
    dm_copy = dm.copy()
    volumes = geometry.volume_from_depth(dm, do)
    assert np.array_equal(dm, dm_copy) and volumes[0].shape == vm.shape
    assert isinstance(geometry.depth_from_volume(1e-12)[0], float)


# Small-depth power laws V ∝ d^p (obstacle not worn), derived from the worn shapes (theory §6):
# near first contact a convex body against a flat or a larger bore leaves a parabolic segment,
# of area (2/3)·chord·d with chord ∝ √d, so p = 3/2; a tilted trace integrates the section
# along the wedge, whose length is d/θ, adding one power (p = 5/2, both for the exact wedge
# and for the frustum rule (d/θ)·A(d)/3); the flat-front triangle of the broached holes
# (∝ d²) is of higher order than the lens; the uniform layer 2π·l·R_m·d and the notch cubic
# (linear term C·d) give p = 1.
EXPONENTS = [
    ("TUBE_BAV", {"tilt_angle": None}, 1.5),
    ("TUBE_BAV", {}, 2.5),
    ("TUBE_ALESAGE", {"obstacle_radius": None, "tilt_angle": None}, 1.0),
    ("TUBE_ALESAGE", {"tilt_angle": None}, 1.5),
    ("TUBE_ALESAGE", {}, 2.5),
    ("TUBE_TUBE", {}, 2.5),
    ("GRAPPE_ALESAGE", {}, 1.5),
    ("TUBE_3_ENCO", {"tilt_angle": None}, 1.5),
    ("TUBE_3_ENCO", {}, 2.5),
    ("TUBE_4_ENCO", {"tilt_angle": None}, 1.5),
    ("TUBE_4_ENCO", {}, 2.5),
    ("GRAPPE_1_ENCO", {}, 1.0),
    ("GRAPPE_2_ENCO", {}, 1.0),
]


@pytest.mark.parametrize(("name", "changes", "exponent"), EXPONENTS)
def test_small_depth_power_law(name, changes, exponent):
    """Local log-slope of V(d) at d = 1e-8·max_depth equals the analytic exponent (the next
    terms are O(d/R) or O(d/(R_o − R_m)): ≤ 2e-6 here)."""
    geometry = build(name, **changes)
    depth = 1e-8 * geometry.max_depth
    v1, v2 = geometry.volume_from_depth([depth, 2.0 * depth])[0]
    assert math.log2(v2 / v1) == pytest.approx(exponent, abs=1e-5)
    # and the inverse follows the same law: d(V) ∝ V^(1/p)
    d1, d2 = geometry.depth_from_volume([v1, v1 * 2.0 ** exponent])[0]
    assert d2 / d1 == pytest.approx(2.0, rel=1e-5)


TILTED_WITH_WIDTH = [name for name in NAMES
                     if {"tilt_angle", "obstacle_width"} <= set(CONTACT_TYPES[name].example)]


def test_every_frustum_type_is_checked_for_continuity():
    assert TILTED_WITH_WIDTH == ["TUBE_3_ENCO", "TUBE_4_ENCO", "TUBE_ALESAGE", "TUBE_BAV"]


@pytest.mark.parametrize("name", TILTED_WITH_WIDTH)
def test_continuous_at_width_times_tilt(name):
    """At d = l·θ the two branches of the tilted relation (trace shorter / longer than the
    width) meet: V is continuous (both give (l/3)·A(lθ)) and so is its inverse."""
    geometry = build(name)
    reach = geometry.obstacle_width * math.radians(geometry.tilt_angle)
    assert reach < 0.5 * geometry.max_depth
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        below, at, above = geometry.volume_from_depth(reach * np.array([1 - 1e-10, 1.0,
                                                                        1 + 1e-10]))[0]
        assert below < at < above
        assert below == pytest.approx(at, rel=1e-8) and above == pytest.approx(at, rel=1e-8)
        depth = geometry.depth_from_volume(at * np.array([1 - 1e-12, 1.0, 1 + 1e-12]))[0]
        assert np.allclose(depth, reach, rtol=1e-11, atol=0)
        # with obstacle wear too: the switch is on the total depth d_m + d_o, which comes from
        # the total volume V_m + V_o
        dm, do = geometry.depth_from_volume(0.8 * at, 0.2 * at)
        assert do > 0.0
        assert dm + do == pytest.approx(reach, rel=1e-11)


@pytest.mark.parametrize("name", NAMES)
def test_obstacle_volume_to_zero(name):
    """V_o → 0 gives back the depths of the intact obstacle: d_m → d_m(V_m, 0) linearly in
    ε = V_o/V_m, d_o → 0 (no slower than ε^(2/5), the TUBE_TUBE law d_o ∝ V_o^(2/5))."""
    geometry = build(name)
    vm = 0.1 * geometry.max_volume
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        alone, zero = geometry.depth_from_volume(vm)
        assert zero == 0.0
        for eps in (1e-4, 1e-6, 1e-8):
            dm, do = geometry.depth_from_volume(vm, eps * vm)
            assert abs(dm - alone) <= eps * alone
            assert 0.0 < do <= 1.01 * eps**0.4 * alone


def test_keywords_any_case_and_dimensions_as_plain_floats():
    """Code_Aster keywords are accepted in any case; ints/numpy scalars become plain floats."""
    geometry = contact_geometry("grappe_alesage", rayon_mobile=np.float64(4.85e-3),
                                RAYON_OBST=5.25e-3, obstacle_width=1)
    assert type(geometry.obstacle_width) is float and geometry.obstacle_width == 1.0
    assert type(geometry.mobile_radius) is float
    with pytest.raises(InputError, match=r"LARGEUR_OBST\) must be a number"):
        contact_geometry("TUBE_BAV", mobile_radius=0.01, obstacle_width=True)
    with pytest.raises(KeywordError, match="given twice"):
        contact_geometry("TUBE_BAV", mobile_radius=0.01, RAYON_MOBILE=0.01, obstacle_width=0.01)


# Random dimensions (hypothesis) for the four circle-based types: round trips stay at 1e-10.
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=40, deadline=None)
@given(rm=st.floats(1e-3, 2e-2), clearance=st.floats(1e-3, 0.5), width=st.floats(2e-3, 5e-2),
       tilt=st.sampled_from([0.0, 0.1, 1.0, 5.0]), fraction=st.floats(1e-6, 0.95),
       share=st.floats(0.0, 1.0),
       name=st.sampled_from(["TUBE_BAV", "TUBE_ALESAGE", "TUBE_TUBE", "GRAPPE_ALESAGE"]))
def test_round_trip_random_dimensions(rm, clearance, width, tilt, fraction, share, name):
    dims = {"mobile_radius": rm, "obstacle_radius": rm * (1 + clearance),
            "obstacle_width": width, "tilt_angle": tilt if name != "TUBE_TUBE" else tilt + 1.0}
    cls = CONTACT_TYPES[name]
    used = set(cls.required) | set(cls.optional)
    geometry = contact_geometry(name, **{k: v for k, v in dims.items() if k in used})
    depth = fraction * geometry.max_depth
    dm, do = share * depth, (1 - share) * depth
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        vm, vo = geometry.volume_from_depth(dm, do)
        dm2, do2 = geometry.depth_from_volume(vm, vo)
    assert abs(dm2 - dm) <= 1e-10 * depth and abs(do2 - do) <= 1e-10 * depth
