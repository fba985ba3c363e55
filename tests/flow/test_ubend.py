"""U-bend radii in a bundle description: rows, radii and straight legs → span lengths and the
abscissae of supports given by their angle in the bend.

Checked against the geometry, computed independently of the formulas under test: the centre
line of a U-bend (a straight leg, a half circle of radius R, a second leg) is drawn as a fine
polyline in the plane and its length summed segment by segment (π·R + 2·leg to 1e-6); the point
at 90° is the apex of that polyline (the point farthest from the legs' base), and walking the
polyline to an abscissa lands on the circle at the given angle.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from fretwear.errors import InputError, KeywordError
from fretwear.flow.description import read_description, u_bend_abscissa, u_bend_span_length

from .test_simulate import small_description


def centre_line(radius: float, leg: float, n: int = 200_001) -> np.ndarray:
    """Points (x, y) of a U-bend's centre line: up the left leg, over the half circle, down."""
    up = np.column_stack([np.full(n, -radius), np.linspace(0.0, leg, n)])
    phi = np.linspace(math.pi, 0.0, n)
    arc = np.column_stack([radius * np.cos(phi), leg + radius * np.sin(phi)])
    down = np.column_stack([np.full(n, radius), np.linspace(leg, 0.0, n)])
    return np.vstack([up, arc[1:], down[1:]])


def walk(points: np.ndarray, distance: float) -> np.ndarray:
    steps = np.hypot(*np.diff(points, axis=0).T)
    cumulative = np.concatenate([[0.0], np.cumsum(steps)])
    return np.array([np.interp(distance, cumulative, points[:, k]) for k in (0, 1)])


@pytest.mark.parametrize("radius, leg", [(0.06, 0.0), (0.5, 0.1), (1.4, 0.35)])
def test_span_length_is_the_centre_line_length(radius, leg):
    points = centre_line(radius, leg)
    length = float(np.sum(np.hypot(*np.diff(points, axis=0).T)))
    assert u_bend_span_length(radius, leg) == pytest.approx(length, rel=1e-6)


@pytest.mark.parametrize("angle", [0.0, 30.0, 90.0, 145.0, 180.0])
def test_angle_abscissa_lands_on_the_bend(angle):
    radius, leg = 0.5, 0.1
    x, y = walk(centre_line(radius, leg), u_bend_abscissa(radius, leg, angle))
    expected = (-radius * math.cos(math.radians(angle)),
                leg + radius * math.sin(math.radians(angle)))
    assert (x, y) == pytest.approx(expected, abs=1e-6)


def ubend_description(tmp_path, radii="{ first = 0.5, pitch = 0.1 }", leg="0.1", **changes):
    return small_description(tmp_path, **{
        "span_lengths_m = 1.2": f"u_bend_radii_m = {radii}\nstraight_leg_m = {leg}",
        "position_m = 0.4": "angle_deg = 45.0", "position_m = 0.8": "angle_deg = 135.0",
        **changes})


def test_rows_radii_and_legs_give_the_spans(tmp_path):
    """Row r has R₁ + (r − 1)·pitch; its span is the developed length, its AVBs at 45° and 135°
    sit symmetric about the apex."""
    specs = read_description(ubend_description(tmp_path))
    assert [s.row for s in specs] == [1, 2]
    for spec, radius in zip(specs, (0.5, 0.6), strict=True):
        length = spec.beam["length"]
        assert length == pytest.approx(math.pi * radius + 0.2, rel=1e-12)
        a, b = (c["position_m"] for c in spec.supports)
        assert a + b == pytest.approx(length, rel=1e-12)
        assert a == pytest.approx(0.1 + radius * math.pi / 4, rel=1e-12)
        assert spec.extra == {"u_bend_radius_m": radius, "straight_leg_m": 0.1}
    explicit = read_description(ubend_description(tmp_path, radii="[0.5, 0.6]"))
    assert [s.beam["length"] for s in explicit] == [s.beam["length"] for s in specs]


def test_ubend_errors_name_the_key(tmp_path):
    with pytest.raises(KeywordError, match="either span_lengths_m or u_bend_radii_m"):
        read_description(small_description(tmp_path, **{
            "span_lengths_m = 1.2": "span_lengths_m = 1.2\nu_bend_radii_m = 0.5"}))
    with pytest.raises(KeywordError, match="angle_deg: only with"):
        read_description(small_description(tmp_path, **{"position_m = 0.4": "angle_deg = 45.0"}))
    with pytest.raises(InputError, match=r"angle_deg: in \[0, 180\]"):
        read_description(ubend_description(tmp_path, **{"angle_deg = 45.0": "angle_deg = 200.0"}))
    with pytest.raises(KeywordError, match="first = "):
        read_description(ubend_description(tmp_path, radii="{ first = 0.5 }"))
    with pytest.raises(InputError, match="one per row"):
        read_description(ubend_description(tmp_path, radii="[0.5, 0.6, 0.7]"))
    with pytest.raises(InputError, match="beyond the span"):   # 0° with no leg: at the end
        read_description(ubend_description(tmp_path, leg="0.0",
                                           **{"angle_deg = 45.0": "angle_deg = 0.0"}))


def test_shipped_ubend_example():
    """examples/bundle/ubend_geometry.toml: rows bend with 0.35 + 0.03 (r − 1) m, legs 0.05 m,
    AVBs at 60° and 120°, symmetric about the apex."""
    from .test_simulate import EXAMPLE

    specs = read_description(EXAMPLE / "ubend_geometry.toml")
    assert len(specs) == 12
    for spec in specs:
        radius = 0.35 + 0.03 * (spec.row - 1)
        assert spec.beam["length"] == pytest.approx(math.pi * radius + 0.1, rel=1e-12)
        a, b = (c["position_m"] for c in spec.supports)
        assert a == pytest.approx(0.05 + radius * math.pi / 3, rel=1e-12)
        assert a + b == pytest.approx(spec.beam["length"], rel=1e-12)


def test_ubend_stability_ratio_scales_as_velocity_times_span_squared():
    """Connors' U_c ∝ f and a clamped beam's f ∝ 1/L² (same section, same mass per length: the
    rows share the density 350 kg/m³), U_eff = U in uniform flow: the most critical ratio of row
    4 over row 1 is (U₄/U₁)·(L₄/L₁)², with L = πR + 2·leg."""
    import dataclasses

    from fretwear.flow.bundle import tube_forces
    from fretwear.flow.stability import stability_ratios

    from .test_simulate import EXAMPLE

    specs = {s.row: s for s in read_description(EXAMPLE / "ubend_geometry.toml")
             if s.column == 1}
    ratio = {}
    for row in (1, 4):
        spec = dataclasses.replace(specs[row], duration=0.05)
        model, tube, _, _ = tube_forces(spec)
        table = stability_ratios(model, tube, mass_per_length=spec.mass_per_length,
                                 constant=spec.connors_constant, margin=spec.stability_margin)
        ratio[row] = table["stability_ratio"].max()
    lengths = {row: math.pi * (0.35 + 0.03 * (row - 1)) + 0.1 for row in (1, 4)}
    assert ratio[4] / ratio[1] == pytest.approx(3.5 / 2.0 * (lengths[4] / lengths[1]) ** 2,
                                                rel=1e-6)
