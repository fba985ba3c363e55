"""Shock definitions: obstacle geometry (gap in a direction), offsets, preload, input errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.dynamics import ModalModel, Shock, circle_profile, simulate
from fretwear.errors import InputError, KeywordError


def test_gap_in_a_direction():
    # plane at g along 30°: distance along direction φ is g/cos(φ − 30°) (inf when moving away)
    p = Shock(point=0, obstacle="plane", gap=1e-3, angle=30.0, normal_stiffness=1.0)
    assert p.gap_at([30.0, 90.0]) == pytest.approx([1e-3, 1e-3 / math.cos(math.radians(60))])
    assert np.isinf(p.gap_at(210.0))
    two = Shock(point=0, obstacle="two_planes", gap=1e-3, angle=0.0, normal_stiffness=1.0)
    assert two.gap_at([0.0, 180.0, 45.0]) == pytest.approx([1e-3, 1e-3, 1e-3 * math.sqrt(2)])
    # 721-point circle: between vertices the chord is inside the circle by g(1 − cos 0.25°)
    a, g = circle_profile(5e-4)
    prof = Shock(point=0, obstacle="profile", profile_angles=a, profile_gaps=g,
                 normal_stiffness=1.0)
    assert prof.gap_at([0.0, 90.5]) == pytest.approx([5e-4, 5e-4], rel=1e-12)
    assert prof.gap_at(0.25)[()] == pytest.approx(5e-4 * math.cos(math.radians(0.25)), rel=1e-12)


def test_origin_and_preload_static_equilibrium():
    # A mass on a soft mode k_m pushed by a preload P into a plane at gap g, obstacle centre
    # shifted by o along the normal: static balance P = k_m x + k_n (x − g − o) once in contact.
    m, km, kn, g, o, pre = 1.0, 1e3, 1e5, 1e-3, 5e-4, 10.0
    model = ModalModel(frequencies=[math.sqrt(km / m) / (2 * math.pi)], damping_ratios=0.5,
                       masses=m, shock_shapes=[[[1.0], [0.0]]])
    s = Shock(point=0, obstacle="plane", gap=g, origin=(o, 0.0), normal_stiffness=kn,
              normal_damping=2 * math.sqrt(kn * m), preload=pre)
    r = simulate(model, [s], duration=1.0, time_step=5e-5, archive_step=1e-3)
    x = (pre + kn * (g + o)) / (km + kn)
    h = r.history(0)
    assert h.dy[-1] + o == pytest.approx(x, rel=1e-6)  # dy is measured from the obstacle centre
    assert h.normal_force[-1] == pytest.approx(kn * (x - g - o), rel=1e-5)
    assert r.energy["preload_work"] > 0


def test_shock_errors():
    with pytest.raises(KeywordError, match="unknown obstacle"):
        Shock(point=0, obstacle="cone", normal_stiffness=1.0)
    with pytest.raises(InputError, match="tangential_stiffness"):
        Shock(point=0, obstacle="circle", gap=1e-4, normal_stiffness=1.0, friction=0.3)
    with pytest.raises(InputError, match="normal_stiffness"):
        Shock(point=0, obstacle="circle", gap=1e-4, normal_stiffness=0.0)
    with pytest.raises(KeywordError, match="profile_angles"):
        Shock(point=0, obstacle="profile", normal_stiffness=1.0)
    with pytest.raises(InputError, match="row 1"):
        Shock(point=0, obstacle="profile", normal_stiffness=1.0, profile_angles=[0, 90, 180],
              profile_gaps=[1e-4, 0.0, 1e-4])
    with pytest.raises(InputError, match="gap"):
        Shock(point=0, obstacle="circle", gap=-1e-4, normal_stiffness=1.0)
