"""GRAPPE_ALESAGE (control-rod rodlet in a guide bore, one lunule), theory §6, R7.20.01 §4.1.

Sources: the oracle's lunule (crossings found numerically, interface circle through the
crossings and the worn apex, areas by quadrature) times the width; the lens's small-depth
asymptotics derived from x² ≈ 2R_oR_m·D/g (g = R_o − R_m) and a section ≈ (4/3)·x·D·(1 − …):
checked here through the oracle only; R7.20.01's corrected system R_m sin α = r sin β =
R_o sin γ = x, checked by recomputing the angles.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from oracle import lens_oracle, lunule_oracle

from fretwear.errors import InputError, RangeWarning
from fretwear.geometry import contact_geometry
from fretwear.geometry.grappe_alesage import GrappeAlesage

RM, RO, L = 4.85e-3, 5.25e-3, 10e-3  # 9.7 mm rodlet, 10.5 mm card bore (R7.20.01 §4.2)


@pytest.fixture
def geometry():
    return GrappeAlesage(mobile_radius=RM, obstacle_radius=RO, obstacle_width=L)


@pytest.mark.parametrize(("dm", "do"), [(1e-6, 0.0), (2e-5, 1e-5), (3e-4, 5e-4), (1e-3, 1e-4)])
def test_volumes_against_oracle(geometry, dm, do):
    vm, vo = geometry.volume_from_depth(dm, do)
    om, oo = lunule_oracle(RM, RO, dm, do)
    assert vm == pytest.approx(L * om, rel=1e-9)
    assert vo == pytest.approx(L * oo, rel=1e-9, abs=1e-9 * vm)  # oracle round-off at d_o = 0


def test_manual_system_holds(geometry):
    """R7.20.01's (corrected) equations, with α, β, γ from R_m sin α = r sin β = R_o sin γ = x:
    V_m/l = R_m²(α − ½ sin 2α) − r²(β − ½ sin 2β), V_o/l = r²(β − …) − R_o²(γ − …)."""
    dm, do = 2e-4, 1e-4
    vm, vo = geometry.volume_from_depth(dm, do)
    _, x = lens_oracle(RM, RO, dm + do)
    # interface radius from its sagitta: s(r, x) = s(R_m, x) − d_m
    s = RM - math.sqrt(RM**2 - x**2) - dm
    r = (s**2 + x**2) / (2 * s)
    alpha, beta, gamma = (math.asin(x / rho) for rho in (RM, r, RO))

    def seg(rho, phi):
        return rho**2 * (phi - 0.5 * math.sin(2 * phi))

    assert vm / L == pytest.approx(seg(RM, alpha) - seg(r, beta), rel=1e-9)
    assert vo / L == pytest.approx(seg(r, beta) - seg(RO, gamma), rel=1e-9)
    assert RM < r < RO


def test_round_trip_and_obstacle_limit(geometry):
    limit = geometry.max_depth
    depth = np.geomspace(1e-9, 0.99 * limit, 25)
    for share in (1.0, 0.6, 0.1):
        vm, vo = geometry.volume_from_depth(share * depth, (1 - share) * depth)
        dm, do = geometry.depth_from_volume(vm, vo)
        assert np.all(np.abs(dm - share * depth) <= 1e-10 * depth)
        assert np.all(np.abs(do - (1 - share) * depth) <= 1e-10 * depth)
    vm = geometry.volume_from_depth(5e-4)[0]
    dm_small, do_small = geometry.depth_from_volume(vm, 1e-24)
    assert dm_small == pytest.approx(5e-4, rel=1e-10) and do_small < 1e-16


def test_bore_must_exceed_rod_and_range():
    with pytest.raises(InputError, match=r"RAYON_OBST.*must exceed"):
        contact_geometry("GRAPPE_ALESAGE", mobile_radius=RM, obstacle_radius=RM,
                         obstacle_width=L)
    geometry = GrappeAlesage(mobile_radius=RM, obstacle_radius=RO, obstacle_width=L)
    with pytest.warns(RangeWarning, match=r"GRAPPE_ALESAGE.*0.00160998 m"):
        dm, _ = geometry.depth_from_volume(geometry.max_volume * 1.001)
    assert np.isnan(dm)


def test_small_depth_asymptotics(geometry):
    """Near first contact the gap between the surfaces is D − (t²/2)(1/R_m − 1/R_o): a parabolic
    lens of half-chord x₀ = √(2D·R_mR_o/(R_o − R_m)) and area (4/3)·x₀·D, to O(D/(R_o − R_m))."""
    gap = RO - RM
    for depth in (1e-9, 1e-8, 1e-7):
        x0 = math.sqrt(2 * depth * RM * RO / gap)
        ratio = geometry.volume_from_depth(depth)[0] / (L * 4 / 3 * x0 * depth)
        assert abs(ratio - 1) < 0.5 * depth / gap  # measured: −0.451·D/(R_o − R_m)
