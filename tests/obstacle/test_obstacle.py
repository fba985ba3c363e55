"""Tests of the obstacle update (fretwear.obstacle, theory §3 sector depths and §8).

Reference values come from closed-form geometry (disk in a disk, disk between parallel planes,
the theory §3 sector-depth formulas, the polar area element), and from an independent brute-force
search (dense polygons, point-in-polygon tests and bisection on the translation) written here.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from fretwear.errors import InputError, KeywordError, PerforationWarning
from fretwear.obstacle import (
    CircleObstacle,
    DiscreteObstacle,
    Mobile,
    PlanesObstacle,
    load_obstacle_profile,
    obstacle_from_config,
    read_discret,
    sector_volumes,
    update_obstacle,
    update_obstacle_from_table,
    worn_depth_profiles,
    write_discret,
)
from fretwear.table.files import read_profile_table

RM, GAP, WALL, WIDTH = 9.5e-3, 0.5e-3, 1.09e-3, 20e-3
RO = RM + GAP
EDGES10 = np.linspace(-180.0, 180.0, 11)


def spec_depth_mobile(v, r, l_, arc_deg):
    """Theory §3: d = R_m − √(R_m² − 2V/(l·Δθ)), Δθ in radians."""
    return r - math.sqrt(r * r - 2 * v / (l_ * math.radians(arc_deg)))


def spec_depth_obstacle(v, r, l_, arc_deg):
    """Theory §3: d = √(R_o² + 2V/(l·Δθ)) − R_o, Δθ in radians."""
    return math.sqrt(r * r + 2 * v / (l_ * math.radians(arc_deg))) - r


def volume_for_depth_mobile(d, r, l_, arc_deg):
    """Inverse of theory §3 (annular sector area × width)."""
    return 0.5 * l_ * math.radians(arc_deg) * (r * r - (r - d) ** 2)


def volume_for_depth_obstacle(d, r, l_, arc_deg):
    return 0.5 * l_ * math.radians(arc_deg) * ((r + d) ** 2 - r * r)


# ---------------------------------------------------------------- independent brute force ----
def _star_radius(px, py, qx, qy):
    """Polar radius of the star-shaped polygon (vertices px, py sorted by angle) at points q.

    The ray from the origin through q meets the edge V_k V_{k+1} of the wedge holding q at
    r = (V_k × e)/(w × e), e = V_{k+1} − V_k, w the unit direction of q.
    """
    ang = np.arctan2(py, px)
    qa = np.arctan2(qy, qx)
    k = (np.searchsorted(ang, qa, side="right") - 1) % ang.size
    k1 = (k + 1) % ang.size
    ex, ey = px[k1] - px[k], py[k1] - py[k]
    wx, wy = np.cos(qa), np.sin(qa)
    return (px[k] * ey - py[k] * ex) / (wx * ey - wy * ex)


def brute_force_clearance(direction_deg, mobile_radius, obstacle_radius, breaks, step=0.05):
    """Bisection on the translation s with point-in-polygon tests of dense polygons.

    Feasible(s): every mobile vertex + s·u is inside the obstacle polygon and every obstacle
    vertex − s·u is outside the mobile polygon. With the same vertices as the exact search
    (same step, jumps at the same angles) both must agree to rounding: the polygons are the
    same, the algorithms independent. First a scan by 10 µm, then 50 bisections.
    """
    n = int(round(360 / step))
    grid = -180 + np.arange(n) * step
    br = np.asarray(breaks, float)
    ang = np.concatenate([grid, br - 1e-12, br])  # a jump: left limit, then right limit
    ang = np.mod(ang + 180.0, 360.0) - 180.0
    ang = ang[np.argsort(ang, kind="stable")]

    def poly(radius):
        r = radius(ang)
        t = np.radians(ang)
        return r * np.cos(t), r * np.sin(t)

    mx, my = poly(mobile_radius)
    ox, oy = poly(obstacle_radius)
    u = np.array([math.cos(math.radians(direction_deg)), math.sin(math.radians(direction_deg))])

    def feasible(s):
        ax, ay = mx + s * u[0], my + s * u[1]
        if (np.hypot(ax, ay) > _star_radius(ox, oy, ax, ay) * (1 + 1e-14)).any():
            return False
        bx, by = ox - s * u[0], oy - s * u[1]
        return not (np.hypot(bx, by) < _star_radius(mx, my, bx, by) * (1 - 1e-14)).any()

    lo, hi = 0.0, 1e-5
    while feasible(hi):
        lo, hi = hi, hi + 1e-5
        assert hi < 0.05
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if feasible(mid) else (lo, mid)
    return 0.5 * (lo + hi)


def _uniform_radius(base, edges, depths, sign):
    """Radius function of a uniformly worn body: base + sign·depth of the sector (left-closed)."""
    def radius(angle):
        a = np.mod(np.asarray(angle) + 180.0, 360.0) - 180.0
        j = np.clip(np.searchsorted(edges, a + 1e-13, side="right") - 1, 0, len(depths) - 1)
        return base + sign * np.asarray(depths)[j]
    return radius


# ------------------------------------------------------------------------------- tests -------
def test_no_wear_leaves_the_clearance_unchanged_exactly():
    """Zero volumes: depth exactly 0 and worn clearance identical to the initial one; the
    initial clearance of a disk in a bore is R_o − R_m in every direction (closed form)."""
    r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, np.zeros(10),
                        np.zeros(10), width=WIDTH)
    assert r.angle.size == 721 and r.angle[-1] == 360.0
    assert np.array_equal(r.clearance_worn, r.clearance_initial)
    assert not r.depth_mobile.any() and not r.depth_obstacle.any()
    np.testing.assert_allclose(r.clearance_initial, GAP, rtol=0, atol=2e-12)


def test_planes_clearance_is_gap_over_cosine():
    """Disk between two parallel planes at gaps g+ (normal at 30°) and g−: moving along ψ,
    the normal travel s·|cos(ψ − 30°)| reaches the gap: s = g/|cos| (closed form)."""
    obst = PlanesObstacle(RM, 0.5e-3, 0.3e-3, orientation=30.0)
    r = update_obstacle(obst, Mobile(RM, WALL), 4, np.zeros(4), width=WIDTH, resolution=0.1)
    c = np.cos(np.radians(r.angle - 30.0))
    expected = np.where(c > 0, 0.5e-3 / np.abs(c), 0.3e-3 / np.abs(c))
    sel = np.abs(c) > 0.2
    np.testing.assert_allclose(r.clearance_initial[sel], expected[sel], rtol=1e-9)
    # the new figure straight from the model; not the radial gap (R_m + g)/cos − R_m
    np.testing.assert_allclose(obst.clearance([30.0, 90.0, 210.0], resolution=0.1),
                               [0.5e-3, 1e-3, 0.3e-3], rtol=1e-9)
    assert float(obst.gap(90.0)) > 0.5e-3 / math.cos(math.radians(60.0)) + 1e-3


def test_uniform_wear_all_round_opens_by_both_depths_exactly():
    """One sector (−180..180): both bodies stay circles, radii R_m − d_m and R_o + d_o, so the
    clearance is g + d_m + d_o everywhere, even for large wear (closed form; depths theory §3)."""
    vm, vo = 2.0e-8, 1.0e-8
    r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), 1, [vm], [vo], width=WIDTH,
                        resolution=0.1)
    dm = spec_depth_mobile(vm, RM, WIDTH, 360.0)
    do = spec_depth_obstacle(vo, RO, WIDTH, 360.0)
    assert dm > 1e-5 and do > 5e-6  # large compared with polygon errors
    np.testing.assert_allclose(r.depth_mobile, dm, rtol=1e-12)
    np.testing.assert_allclose(r.depth_obstacle, do, rtol=1e-12)
    np.testing.assert_allclose(r.clearance_worn, GAP + dm + do, rtol=0, atol=1e-11)


def test_small_wear_in_one_sector_opens_its_direction_by_dm_plus_do():
    """First order: a sector worn by d_m (mobile) and d_o (obstacle) opens the clearance at
    its centre by d_m + d_o (depths from theory §3); directions away from it are unchanged."""
    dm, do = 2e-7, 1e-7
    vm = np.zeros(10)
    vo = np.zeros(10)
    vm[5] = volume_for_depth_mobile(dm, RM, WIDTH, 36.0)  # sector 6: 0..36 deg
    vo[5] = volume_for_depth_obstacle(do, RO, WIDTH, 36.0)
    r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm, vo, width=WIDTH)
    delta = r.clearance_worn - r.clearance_initial
    centre = np.flatnonzero(r.angle == 18.0)[0]
    assert delta[centre] == pytest.approx(dm + do, rel=1e-3)
    far = (r.angle >= 120.0) & (r.angle <= 270.0)
    np.testing.assert_allclose(delta[far], 0.0, atol=1e-15)


@pytest.mark.parametrize("direction", [18.0, 3.0, 30.0, 45.0, 200.0])
def test_large_wear_matches_brute_force_search(direction):
    """Large wear (d_m = 0.25 mm, d_o = 0.15 mm on a 36° sector, gap 0.5 mm): the exact
    search agrees with the independent brute force (dense polygons, bisection)."""
    dm, do = 0.25e-3, 0.15e-3
    vm = np.zeros(10)
    vo = np.zeros(10)
    vm[5] = volume_for_depth_mobile(dm, RM, WIDTH, 36.0)
    vo[5] = volume_for_depth_obstacle(do, RO, WIDTH, 36.0)
    r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm, vo, width=WIDTH,
                        step=1.0)
    dms = np.zeros(10)
    dos = np.zeros(10)
    dms[5], dos[5] = dm, do
    ref = brute_force_clearance(direction, _uniform_radius(RM, EDGES10, dms, -1),
                                _uniform_radius(RO, EDGES10, dos, +1), EDGES10[:-1])
    got = r.clearance_worn[np.flatnonzero(r.angle == direction)[0]]
    assert got == pytest.approx(ref, abs=1e-12)
    if direction == 18.0:  # the sector's edges limit the opening: less than g + d_m + d_o
        assert GAP < got < GAP + dm + do


def test_uniform_depths_are_spec_sector_depths_and_keep_volume():
    """Uniform shape: each sector's depth is theory §3's, and l·∫½(R² − (R − d)²)dφ = V."""
    rng = np.random.default_rng(3)
    edges = np.array([-180.0, -100.0, -30.0, 0.0, 45.0, 180.0])
    vm = rng.uniform(0, 3e-9, 5)
    vo = rng.uniform(0, 2e-9, 5)
    w = worn_depth_profiles(edges, vm, vo, width=WIDTH, mobile_radius=RM,
                            obstacle=CircleObstacle(RM, RO))
    arcs = np.diff(edges)
    for j in range(5):
        assert w.sector_depth_mobile[j] == pytest.approx(
            spec_depth_mobile(vm[j], RM, WIDTH, arcs[j]), rel=1e-12)
        assert w.sector_depth_obstacle[j] == pytest.approx(
            spec_depth_obstacle(vo[j], RO, WIDTH, arcs[j]), rel=1e-12)
        mid = 0.5 * (edges[j] + edges[j + 1])
        assert float(w.mobile(mid)) == w.sector_depth_mobile[j]


def test_smooth_profile_keeps_each_sector_volume_exactly():
    """Smooth shape: the integral of the annular area element over each sector, by adaptive
    quadrature (independent of the construction), gives back V/l; the depth is continuous and
    zero in sectors without wear."""
    vm = np.array([0, 0, 1e-9, 4e-9, 2e-9, 0, 0, 0, 3e-10, 0.0])
    vo = np.array([0, 0, 5e-10, 1e-9, 0, 0, 0, 0, 0, 2e-10])
    w = worn_depth_profiles(EDGES10, vm, vo, width=WIDTH, mobile_radius=RM,
                            obstacle=CircleObstacle(RM, RO), shape="smooth")
    for j in range(10):
        a, b = EDGES10[j], EDGES10[j + 1]
        am = quad(lambda x: 0.5 * (RM**2 - (RM - float(w.mobile(x))) ** 2), a, b,
                  epsabs=1e-22, epsrel=1e-11, limit=200)[0]
        ao = quad(lambda x: 0.5 * ((RO + float(w.obstacle(x))) ** 2 - RO**2), a, b,
                  epsabs=1e-22, epsrel=1e-11, limit=200)[0]
        assert math.radians(1) * am * WIDTH == pytest.approx(vm[j], rel=1e-8, abs=1e-22)
        assert math.radians(1) * ao * WIDTH == pytest.approx(vo[j], rel=1e-8, abs=1e-22)
    for e in EDGES10[1:-1]:  # continuity across the sector edges
        assert abs(float(w.mobile(e - 1e-7)) - float(w.mobile(e + 1e-7))) < 1e-12
    assert not w.mobile(np.linspace(-179, -109, 50)).any()  # sectors 1-2 hold no wear
    assert w.sector_depth_mobile[3] > spec_depth_mobile(vm[3], RM, WIDTH, 36.0)  # peaked


def test_obstacle_depth_keeps_volume_on_a_non_circular_profile():
    """Uniform obstacle depth on a discrete (non-circular) obstacle: the polar area element
    ½((r_o + d)² − r_o²) integrated over the sector (quadrature) gives V/l."""
    a = np.arange(0, 360, 5.0)
    gaps = 0.5e-3 + 0.2e-3 * np.cos(np.radians(2 * a))
    obst = DiscreteObstacle(a, gaps, RM)
    vo = np.array([1e-9, 3e-9, 0.0, 2e-9])
    edges = np.array([-180.0, -90.0, 10.0, 100.0, 180.0])
    for shape in ("uniform", "smooth"):
        w = worn_depth_profiles(edges, np.zeros(4), vo, width=WIDTH, mobile_radius=RM,
                                obstacle=obst, shape=shape)
        for j in range(4):
            pts = a[(a - 360 > edges[j]) & (a - 360 < edges[j + 1])] - 360
            pts = np.concatenate([pts, a[(a > edges[j]) & (a < edges[j + 1])]])
            area = quad(lambda x, w=w: 0.5 * ((float(obst.radius(x)) + float(w.obstacle(x)))
                                              ** 2 - float(obst.radius(x)) ** 2),
                        edges[j], edges[j + 1], points=pts[:50] if pts.size else None,
                        epsabs=1e-22, epsrel=1e-11, limit=400)[0]
            assert math.radians(1) * area * WIDTH == pytest.approx(vo[j], rel=1e-7, abs=1e-22)


def test_perforation_is_reported_with_sector_angle_and_depth():
    """Depth 0.6 mm > PERCEMENT 0.4 × 1.09 mm: PerforationWarning naming the sector; with
    PERCEMENT 1.0 the same wear is not a perforation."""
    vm = np.zeros(10)
    vm[2] = volume_for_depth_mobile(0.6e-3, RM, WIDTH, 36.0)  # sector 3: -108..-72 deg
    with pytest.warns(PerforationWarning, match=r"sector 3 .*-108\.\.-72.*0\.0006 m at angle -90"):
        r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm,
                            width=WIDTH, perforation=0.4, resolution=0.5)
    assert r.perforated and r.perforated_sectors == (3,)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PerforationWarning)
        r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm,
                            width=WIDTH, perforation=1.0, resolution=0.5)
    assert not r.perforated


def test_discret_round_trip_and_layout(tmp_path):
    """DISCRET file: 721 rows THETA = 0..360 by 0.5 deg, JEU and R (the same clearance under
    Code_Aster's name); read back."""
    angles = np.arange(720) * 0.5
    gaps = 0.5e-3 + 0.1e-3 * np.sin(np.radians(3 * angles)) ** 2
    prof = DiscreteObstacle(angles, gaps, RM, clearance_figure=True)
    path = write_discret(tmp_path / "obst.txt", prof)
    rows = [ln for ln in path.read_text().splitlines() if ln and not ln.startswith("#")]
    assert rows[0].split() == ["THETA", "JEU", "R"] and len(rows) == 722
    first, last = rows[1].split(), rows[-1].split()
    assert float(first[0]) == 0.0 and float(last[0]) == 360.0 and first[1] == last[1]
    back = read_discret(path)
    np.testing.assert_allclose(back.angles, angles, rtol=0, atol=1e-12)
    np.testing.assert_allclose(back.gaps, gaps, rtol=1e-10)
    assert back.mobile_radius == pytest.approx(RM, rel=1e-11)
    from fretwear.io.aster import read_aster_table  # the same file is a Code_Aster TABLEAU

    frame = read_aster_table(path)
    np.testing.assert_array_equal(frame["R"], frame["JEU"])
    np.testing.assert_allclose(frame["JEU"].to_numpy()[:-1], gaps, rtol=1e-10)
    radii_only = tmp_path / "radii.txt"
    radii_only.write_text("THETA RADIUS\n0 0.01\n120 0.011\n240 0.012\n")
    d = read_discret(radii_only, mobile_radius=0.0095)
    assert d.gap(60.0) == pytest.approx(1.0e-3, rel=1e-12)  # linear in angle: (0.5+1.5)/2 mm


def test_discret_figure_of_two_planes_gives_the_planes_back(tmp_path):
    """A DISCRET table is a clearance figure. Written for two planes (normal at 30°, gaps 0.4 /
    0.2 mm, closing circle 30 mm), it holds g/|cos ψ| (closed form); read back, the obstacle
    behind it (the figure dilated by the mobile's disk) is the planes, (R_m + g)/|cos ψ|, and
    the update's new clearance is the table again. Reading the same numbers as radial gaps
    (column RADIUS = R_m + JEU) would put the planes elsewhere: R_m + g/|cos ψ|."""
    planes = PlanesObstacle(RM, 4e-4, 2e-4, orientation=30.0, closing_radius=0.03)
    path = write_discret(tmp_path / "planes.txt", planes)
    figure = read_discret(path)
    a = figure.angles
    c = np.cos(np.radians(a - 30.0))
    g = np.where(c > 0, 4e-4, 2e-4)
    sel = np.abs(c) > 0.3
    np.testing.assert_allclose(figure.gaps[sel], g[sel] / np.abs(c[sel]), rtol=1e-9)
    # the plane point (R_m + g)/|cos ψ| comes from the figure point at the same distance
    # along the plane, which the 0.5° table samples exactly up to ~11 mm (g₋ side): |cos| > 0.7
    near = np.abs(c) > 0.7
    np.testing.assert_allclose(figure.radius(a[near]), (RM + g[near]) / np.abs(c[near]),
                               rtol=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a real figure: no "not the figure of" warning
        r = update_obstacle(figure, Mobile(RM, WALL), 1, [0.0], width=WIDTH, resolution=0.1)
    np.testing.assert_allclose(r.clearance_initial[:-1][sel], figure.gaps[sel], rtol=1e-7)
    radial = DiscreteObstacle(a, figure.gaps, RM)  # the wrong reading, for contrast
    k = np.flatnonzero(a == 90.0)[0]  # 60° off the normal: 0.8 mm of clearance
    assert float(radial.clearance([90.0], resolution=0.1)[0]) < 0.9 * figure.gaps[k]


def test_made_up_figure_with_narrow_dents_is_reported():
    """A trefoil table 0.5 + 0.1·cos 3φ mm has dents of curvature radius 0.32 mm at 60°, 180°,
    300°: no disk of 9.5 mm has that clearance figure (the closing by the disk fills them), so
    the update warns; the lobes (convex) are kept, the dents only open (closing ⊇ figure)."""
    from fretwear.errors import FretwearWarning

    a = np.arange(0.0, 360.0, 0.5)
    table = DiscreteObstacle(a, 5e-4 + 1e-4 * np.cos(np.radians(3 * a)), RM,
                             clearance_figure=True)
    with pytest.warns(FretwearWarning, match="not the figure of a mobile of radius 0.0095"):
        r = update_obstacle(table, Mobile(RM, WALL), 1, [0.0], width=WIDTH, resolution=0.25)
    # lobe tip, to the polygons' O(h²) error (chord sagitta ~2e-8 m at 0.25°)
    assert r.clearance_initial[0] == pytest.approx(6e-4, abs=5e-8)
    assert (r.clearance_initial >= table.gap(r.angle) - 5e-8).all()
    assert r.clearance_initial[360] > 4e-4 + 1e-5  # the dent at 180° is filled


def test_code_aster_discret_table_is_read_as_the_clearance(tmp_path):
    """A Code_Aster-style DISCRET obstacle (theory §8: 721 points 0..360 by 0.5°, 0.5 mm when
    new), ASTER layout with string columns LIEU/TYPE and THETA, R: R is the clearance, the
    string columns are ignored, and a new 0.5 mm figure gives a bore of gap 0.5 mm. An R
    column holding radii (>= R_m) is refused with the fix (name it RADIUS)."""
    theta = np.arange(721) * 0.5
    lines = ["#DEBUT_TABLE", "#TITRE obstacle DISCRET", "LIEU TYPE THETA R", "K8 K24 R R"]
    lines += [f"DEFIOBST DISCRET {t:12.5E} {5e-4:12.5E}" for t in theta]
    lines.append("#FIN_TABLE")
    path = tmp_path / "aster_discret.tab"
    path.write_text("\n".join(lines) + "\n")
    d = read_discret(path, mobile_radius=RM)
    assert d.angles.size == 720 and d.angles[-1] == 359.5
    np.testing.assert_array_equal(d.gaps, 5e-4)
    r = update_obstacle(d, Mobile(RM, WALL), 1, [0.0], width=WIDTH, resolution=0.5)
    np.testing.assert_allclose(r.clearance_initial, 5e-4, rtol=0, atol=1e-12)  # R_o − R_m
    bad = tmp_path / "radii_as_r.txt"
    bad.write_text("THETA R\n0 0.01\n120 0.011\n240 0.012\n")
    from fretwear.errors import FormatError

    with pytest.raises(FormatError, match="name the column RADIUS"):
        read_discret(bad, mobile_radius=RM)


def test_worn_figure_file_feeds_the_next_dynamics(tmp_path):
    """The DISCRET file of the worn figure, read back by load_obstacle_profile and by the
    dynamics' own loader ([dynamics.shocks] obstacle = "profile", profile_file): the shock
    gets the 720 angles 0..359.5 deg and the worn clearances written (11 digits)."""
    vm = np.zeros(10)
    vm[5] = 1e-9
    r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm, width=WIDTH,
                        resolution=0.25)
    path = r.write_discret(tmp_path / "worn.txt")
    prof = load_obstacle_profile(path)
    np.testing.assert_allclose(prof.gap(r.angle), r.clearance_worn, rtol=1e-10)
    assert prof.clearance_figure and prof.mobile_radius == pytest.approx(RM, rel=1e-11)
    dynamics = pytest.importorskip("fretwear.dynamics.config")
    setup = dynamics.dynamics_from_config({
        "duration_s": 0.1,
        "modes": {"frequencies_Hz": [10.0], "damping_ratios": [0.01], "masses_kg": [1.0],
                  "shock_shapes": [[[1.0], [1.0]]]},
        "shocks": [{"point": 0, "obstacle": "profile", "profile_file": path.name,
                    "normal_stiffness_N_per_m": 1e6}],
        "forces": [{"point": 0, "direction": "y", "kind": "harmonic", "amplitude": 1.0,
                    "frequency_Hz": 5.0}]}, directory=tmp_path)
    shock = setup.shocks[0]
    np.testing.assert_allclose(shock.profile_angles, r.angle[:-1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(shock.profile_gaps, r.clearance_worn[:-1], rtol=1e-10)


def _table(names="native"):
    t = pd.DataFrame({
        "instant": np.repeat([1.0, 2.0], 4), "sector": np.tile([1, 2, 3, 4], 2),
        "angle_start": np.tile([-180.0, -90.0, 0.0, 90.0], 2),
        "angle_end": np.tile([-90.0, 0.0, 90.0, 180.0], 2),
        "volume_mobile_cumulated": [0, 1e-9, 0, 0, 0, 2e-9, 5e-10, 0],
        "volume_obstacle_cumulated": [0, 5e-10, 0, 0, 0, 1e-9, 0, 0]})
    if names == "aster":
        t = t.rename(columns={"instant": "INST", "sector": "SECTEUR", "angle_start":
                              "ANGLE_DEBUT", "angle_end": "ANGLE_FIN",
                              "volume_mobile_cumulated": "V_USUR_TUBE_CUMU",
                              "volume_obstacle_cumulated": "V_USUR_OBST_CUMU"})
    return t.sample(frac=1.0, random_state=1)  # row order must not matter


def test_table_native_and_aster_names_give_the_same_update(tmp_path):
    obst, mob = CircleObstacle(RM, RO), Mobile(RM, WALL)
    a = update_obstacle_from_table(_table("native"), obst, mob, width=WIDTH, resolution=0.5)
    path = tmp_path / "wear.tab"
    from fretwear.io.aster import write_aster_table

    write_aster_table(_table("aster"), path, float_format="%17.10E")
    b = update_obstacle_from_table(path, obst, mob, width=WIDTH, resolution=0.5)
    assert a.instant == b.instant == 2.0
    np.testing.assert_allclose(a.clearance_worn, b.clearance_worn, rtol=1e-9)
    empty = _table().assign(volume_obstacle_cumulated=np.nan)  # '-' cells: no obstacle wear
    assert not sector_volumes(empty)[3].any()
    inst, edges, vm, vo = sector_volumes(_table(), instant=1.0)
    assert edges.tolist() == [-180.0, -90.0, 0.0, 90.0, 180.0]
    assert vm.tolist() == [0, 1e-9, 0, 0] and vo.tolist() == [0, 5e-10, 0, 0]
    glob = pd.DataFrame({"instant": [1.0], "volume_mobile_cumulated": [1e-9],
                         "volume_obstacle_cumulated": [5e-10]})  # a global row, no sector
    mixed = pd.concat([glob, _table()], ignore_index=True)
    assert sector_volumes(mixed, instant=1.0)[2].tolist() == [0, 1e-9, 0, 0]


def test_profile_table_outputs(tmp_path):
    vm = np.zeros(10)
    vm[1] = 1e-9
    r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm, width=WIDTH,
                        resolution=0.5)
    csv = read_profile_table(r.write(tmp_path / "p.csv"))
    assert list(csv.columns) == ["angle", "clearance_initial", "clearance_worn",
                                 "depth_mobile", "depth_obstacle"]
    np.testing.assert_allclose(csv["clearance_worn"], r.clearance_worn, rtol=1e-10)
    from fretwear.io.aster import read_aster_table

    for fmt in ("TABLEAU", "ASTER"):
        t = read_aster_table(r.write(tmp_path / f"p_{fmt}.txt", format=fmt))
        np.testing.assert_allclose(t["JEU_USE"], r.clearance_worn, rtol=1e-9)
        np.testing.assert_allclose(t["P_USUR_TUBE"], r.depth_mobile, rtol=1e-9)


def test_errors_name_the_culprit():
    t = _table()
    with pytest.raises(InputError, match=r"instant 3 is not in the wear table.*1, 2"):
        sector_volumes(t, instant=3.0)
    gap = t[~((t["sector"] == 2) & (t["instant"] == 2.0))]
    with pytest.raises(InputError, match=r"not covering.*sector 1 ends at -90.*sector 3"):
        sector_volumes(gap)
    with pytest.raises(InputError, match="V_USUR_TUBE_CUMU"):
        sector_volumes(t.drop(columns="volume_mobile_cumulated"))
    with pytest.raises(InputError, match="negative gap"):
        CircleObstacle.from_gap(RM, -1e-4)
    with pytest.raises(InputError, match="negative gap: bore_radius"):
        CircleObstacle(RM, RM - 1e-4)
    with pytest.raises(InputError, match=r"negative gap in the discrete obstacle at row 1"):
        DiscreteObstacle([0, 120, 240], [1e-4, -1e-5, 1e-4], RM)
    with pytest.raises(InputError, match="must cover -180..180"):
        worn_depth_profiles([-180, 0, 170], [0, 0], width=WIDTH, mobile_radius=RM,
                            obstacle=CircleObstacle(RM, RO))
    with pytest.raises(InputError, match="obstacle width"):
        update_obstacle_from_table(t, CircleObstacle(RM, RO), Mobile(RM, WALL))
    with pytest.raises(InputError, match="mobile_radius=0.0095"):
        update_obstacle(CircleObstacle(0.009, RO), Mobile(RM, WALL), 1, [0.0], width=WIDTH)
    with pytest.raises(KeywordError, match="did you mean 'wall_thickness_m'"):
        obstacle_from_config({"gap_m": 1e-4, "wall_thicknes_m": 1e-3, "mobile_radius_m": RM})
    with pytest.raises(KeywordError, match="needs wall_thickness_m"):
        obstacle_from_config({"gap_m": 1e-4, "mobile_radius_m": RM})


def test_inputs_are_not_modified():
    vm = np.array([0.0, 1e-9, 0.0, 0.0])
    t = _table()
    before = t.copy()
    vm0 = vm.copy()
    update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), 4, vm, width=WIDTH,
                    resolution=0.5)
    update_obstacle_from_table(t, CircleObstacle(RM, RO), Mobile(RM, WALL), width=WIDTH,
                               resolution=0.5)
    assert np.array_equal(vm, vm0)
    pd.testing.assert_frame_equal(t, before)


def test_config_builds_models_and_runs(tmp_path):
    """[obstacle] with defaults from [geometry]; the three obstacle models."""
    case = {"geometry": {"mobile_radius_m": RM, "obstacle_width_m": WIDTH,
                         "obstacle_radius_m": RO},
            "obstacle": {"wall_thickness_m": WALL, "shape": "smooth", "instant": 1,
                         "resolution_deg": 0.5},
            "_directory": str(tmp_path)}
    s = obstacle_from_config(case)
    assert s.obstacle == CircleObstacle(RM, RO) and s.width == WIDTH and s.shape == "smooth"
    r = s.update(_table())
    assert r.instant == 1.0 and r.clearance_worn.max() > GAP
    write_discret(tmp_path / "new.txt", CircleObstacle.from_gap(RM, GAP))
    d = obstacle_from_config({"type": "discrete", "file": "new.txt", "mobile_radius_m": RM,
                              "wall_thickness_m": WALL}, directory=tmp_path)
    assert float(d.obstacle.gap(33.0)) == pytest.approx(GAP, rel=1e-10)
    p = obstacle_from_config({"type": "planes", "plane_gap_m": 3e-4, "orientation_deg": 90,
                              "mobile_radius_m": RM, "wall_thickness_m": WALL})
    assert float(p.obstacle.gap(90.0)) == pytest.approx(3e-4, rel=1e-12)
    from fretwear.errors import UnusedKeywordWarning

    with pytest.warns(UnusedKeywordWarning, match="'planes' does not use gap_m"):
        obstacle_from_config({"type": "planes", "plane_gap_m": 3e-4, "gap_m": 1e-4,
                              "mobile_radius_m": RM, "wall_thickness_m": WALL})


@pytest.mark.parametrize("kind,direction", [("smooth-circle", 18.0), ("smooth-circle", 90.0),
                                            ("uniform-planes", 95.0), ("uniform-planes", 60.0),
                                            ("uniform-planes", 2.0), ("uniform-planes", 177.0)])
def test_other_shapes_match_brute_force_search(kind, direction):
    """Smooth depth shape in a bore, and uniform wear on two planes (normal at 90°): the exact
    search agrees with the independent brute force on the same profiles. The directions 2°
    and 177° run nearly along the planes (clearances of 5-12 mm), where the search skips most
    edge blocks and vertices (offset bounds, vertices moving into their own body)."""
    shape, model = kind.split("-")
    obst = CircleObstacle(RM, RO) if model == "circle" else PlanesObstacle(RM, 0.4e-3,
                                                                           orientation=90.0)
    vm = np.zeros(10)
    vo = np.zeros(10)
    vm[5] = vm[7] = volume_for_depth_mobile(0.2e-3, RM, WIDTH, 36.0)
    vo[7] = volume_for_depth_obstacle(0.1e-3, RO, WIDTH, 36.0)
    r = update_obstacle(obst, Mobile(RM, WALL), EDGES10, vm, vo, width=WIDTH, shape=shape,
                        step=1.0, resolution=0.05 if model == "circle" else 0.1)
    w = r.depth
    if shape == "smooth":
        mob = lambda a: RM - w.mobile(a)  # noqa: E731 - continuous profiles
        obs = lambda a: obst.radius(a) + w.obstacle(a)  # noqa: E731
    else:
        mob = _uniform_radius(RM, EDGES10, w.sector_depth_mobile, -1)
        dos = w.sector_depth_obstacle
        obs = lambda a: obst.radius(a) + _uniform_radius(0.0, EDGES10, dos, 1)(a)  # noqa: E731
    ref = brute_force_clearance(direction, mob, obs, EDGES10[:-1],
                                step=0.05 if model == "circle" else 0.1)
    got = r.clearance_worn[np.flatnonzero(r.angle == direction)[0]]
    assert got == pytest.approx(ref, abs=1e-12)
    assert got > r.clearance_initial[np.flatnonzero(r.angle == direction)[0]]


def test_reads_the_wear_operator_table_and_agrees_with_its_sector_depths():
    """End to end with fretwear.table.wear_table (sector mode): the width comes from the
    table's attrs, the volumes are the table's cumulated ones, and the uniform depths equal the
    operator's theory §3 sector depths (an independent implementation, fretwear.geometry)."""
    pytest.importorskip("fretwear.table")
    from fretwear.history import ContactHistory
    from fretwear.table import wear_table

    t = np.linspace(0.0, 1.0, 2001)
    angle = np.radians(np.where(t < 0.5, 20.0, -100.0))  # contact at 20° then at -100°
    history = ContactHistory(time=t, normal_force=np.full(t.size, 10.0),
                             vt1=np.full(t.size, 0.1), vt2=np.zeros(t.size),
                             dy=1e-4 * np.cos(angle), dz=1e-4 * np.sin(angle))
    table = wear_table(history, contact_type="GRAPPE_ALESAGE",
                       dimensions={"mobile_radius": RM, "obstacle_radius": RO,
                                   "obstacle_width": WIDTH},
                       instants=[1.0, 10.0], time_scale=3.6e5, sectors=EDGES10,
                       coefficients={"COEF_USURE": 1e-14},
                       obstacle_coefficients={"COEF_USURE": 5e-15})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = update_obstacle_from_table(table, CircleObstacle(RM, RO), Mobile(RM, WALL),
                                       resolution=0.25)
    last = table[table["instant"] == 10.0].sort_values("angle_start")
    np.testing.assert_allclose(r.depth.volume_mobile, last["volume_mobile_cumulated"])
    np.testing.assert_allclose(r.depth.sector_depth_mobile, last["depth_mobile_sector"],
                               rtol=1e-9)
    np.testing.assert_allclose(r.depth.sector_depth_obstacle, last["depth_obstacle_sector"],
                               rtol=1e-9)
    assert r.instant == 10.0 and r.depth.width == WIDTH
    worn_dirs = (r.angle == 18.0) | (r.angle == 270.0)  # centres of the two worn sectors
    assert (r.clearance_worn[worn_dirs] > GAP + 1e-9).all()


def test_random_non_circular_case_matches_brute_force_search():
    """Seeded random case: a non-circular discrete obstacle (gaps 0.2-0.8 mm), random sector
    edges and volumes on both bodies; exact search vs the independent brute force."""
    rng = np.random.default_rng(11)
    obst = DiscreteObstacle(np.arange(0, 360, 30.0), rng.uniform(0.2e-3, 0.8e-3, 12), RM)
    edges = np.concatenate([[-180.0], np.sort(rng.uniform(-170, 170, 5)), [180.0]])
    vm = rng.uniform(0, 4e-9, 6)
    vo = rng.uniform(0, 2e-9, 6)
    r = update_obstacle(obst, Mobile(RM, WALL), edges, vm, vo, width=WIDTH, step=1.0)
    w = r.depth
    mob = _uniform_radius(RM, edges, w.sector_depth_mobile, -1)
    dos = w.sector_depth_obstacle
    obs = lambda a: obst.radius(a) + _uniform_radius(0.0, edges, dos, 1)(a)  # noqa: E731
    # wear only removes material: the clearance can only open
    assert (r.clearance_worn >= r.clearance_initial - 1e-15).all()
    for direction in rng.choice(np.arange(360.0), 4, replace=False):
        ref = brute_force_clearance(direction, mob, obs,
                                    np.concatenate([edges[:-1], np.arange(-180, 180, 30.0)]))
        got = r.clearance_worn[np.flatnonzero(r.angle == direction)[0]]
        assert got == pytest.approx(ref, abs=1e-12), direction


def test_volume_beyond_the_wedge_is_nan_with_a_range_warning(tmp_path):
    """2V/(lΔθ) > R_m² (theory §6: beyond the range, NaN and a warning naming the limit): the
    mobile depth is NaN, the perforation is reported, the clearance is undefined (NaN); no
    DISCRET file is written for it (error naming the cause), the figure says so."""
    from fretwear.errors import RangeWarning

    vm = np.zeros(10)
    vm[4] = 1.01 * 0.5 * WIDTH * math.radians(36.0) * RM**2
    with pytest.warns(RangeWarning, match="sector 5 .*exceeds the whole wedge"), \
            pytest.warns(PerforationWarning, match="beyond the mobile's centre"):
        r = update_obstacle(CircleObstacle(RM, RO), Mobile(RM, WALL), EDGES10, vm,
                            width=WIDTH, resolution=1.0)
    assert math.isnan(r.depth.sector_depth_mobile[4]) and r.perforated_sectors == (5,)
    assert np.isnan(r.clearance_worn).all() and not np.isnan(r.clearance_initial).any()
    with pytest.raises(InputError, match=r"no DISCRET obstacle written.*sectors \[5\]"):
        r.write_discret(tmp_path / "worn.txt")
    assert not (tmp_path / "worn.txt").exists()
    from fretwear.plotting.obstacle import plot_obstacle

    fig = plot_obstacle(r)
    assert "worn: undefined" in fig.axes[0].get_title()
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_touching_obstacle_zero_gap():
    """A discrete obstacle touching the new mobile at 0° (gap 0 there, 0.5 mm elsewhere, linear
    in angle between nodes every 30°): moving into the contact the clearance is 0; moving away
    the bodies separate (touching is not overlapping) and the clearance matches the brute
    force."""
    angles = np.arange(0, 360, 30.0)
    obst = DiscreteObstacle(angles, np.where(angles == 0, 0.0, 0.5e-3), RM)
    r = update_obstacle(obst, Mobile(RM, WALL), 1, [0.0], width=WIDTH, step=1.0)
    assert r.clearance_initial[0] == 0.0 and r.clearance_initial[1] == 0.0
    for direction in (90.0, 180.0, 250.0):
        ref = brute_force_clearance(direction, lambda a: np.full(np.shape(a), RM), obst.radius,
                                    np.arange(-180, 180, 30.0))
        got = r.clearance_initial[int(direction)]
        assert got > 1e-4 and got == pytest.approx(ref, abs=1e-12)


def test_discret_reader_errors_name_file_and_line(tmp_path):
    from fretwear.errors import FormatError

    bad = tmp_path / "bad.txt"
    bad.write_text("# no columns we know\nANGLE_X FOO\n0 1\n")
    with pytest.raises(FormatError, match=r"bad.txt: line 2: .*THETA"):
        read_discret(bad)
    bad.write_text("THETA JEU\n0 5e-4\n90 abc\n")
    with pytest.raises(FormatError, match=r"bad.txt: line 3: a cell of \['THETA', 'JEU'\] is "
                                          "not a number"):
        read_discret(bad)
    bad.write_text("THETA RADIUS\n0 0.01\n120 0.01\n240 0.01\n")
    with pytest.raises(FormatError, match="mobile radius"):
        read_discret(bad)
    with pytest.raises(InputError, match="missing.txt' does not exist"):
        load_obstacle_profile(tmp_path / "missing.txt")
    bad.write_text("THETA JEU\n0 5e-4\n90 5e-4\n90 5e-4\n")
    with pytest.raises(InputError, match=r"bad.txt: .*row 2 \(90 deg\) does not exceed row 1"):
        read_discret(bad)


@settings(max_examples=15, deadline=None, derandomize=True)
@given(st.lists(st.floats(0.0, 5e-9), min_size=6, max_size=6),
       st.lists(st.floats(0.0, 3e-9), min_size=6, max_size=6),
       st.floats(1.0, 3.0), st.sampled_from(["uniform", "smooth"]), st.booleans())
def test_more_wear_never_closes_the_clearance(vm, vo, factor, shape, circle):
    """Property: wear only removes material, so scaling every sector volume up by `factor`
    nests the worn bodies (smaller mobile, larger obstacle free space: same polygon angles,
    radii moved the same way) and the clearance cannot decrease in any direction (in a bore,
    or in a table touching the mobile at 40°)."""
    table = np.arange(0, 360, 40.0)
    obst = CircleObstacle(RM, RO) if circle else DiscreteObstacle(
        table, np.where(table == 40.0, 0.0, 0.3e-3 + 1e-6 * table), RM)
    vm, vo = np.array(vm), np.array(vo)
    kw = dict(width=WIDTH, shape=shape, resolution=1.0, step=2.0)
    a = update_obstacle(obst, Mobile(RM, RM), 6, vm, vo, **kw)
    b = update_obstacle(obst, Mobile(RM, RM), 6, factor * vm, factor * vo, **kw)
    assert (a.clearance_worn >= a.clearance_initial - 1e-15).all()
    assert (b.clearance_worn >= a.clearance_worn - 1e-15).all()


def test_discret_table_of_code_aster_with_theta_in_radians(tmp_path):
    """Code_Aster's DEFI_OBSTACLE(TYPE='DISCRET', VALE=(θ°, r, ...)) stores R = f(THETA) with THETA
    in radians (op0073: THETA·r8dgrd); IMPR_FONCTION prints it 0 … 6.28319 (%12.5E), the value
    column labelled R_0. Read as the same obstacle as the degree table (0.5 mm, a new one)."""
    theta = np.radians(np.arange(721) * 0.5)
    lines = ["#", "#" + "-" * 80, "### ", "## ", "## Courbe 0", "## OBST_INITIAL",
             "THETA        R_0"]
    lines += [f"{t:12.5E} {5e-4:12.5E}" for t in theta]
    path = tmp_path / "obstacle.txt"
    path.write_text("\n".join(lines) + "\n")
    d = read_discret(path, mobile_radius=RM)
    assert d.angles.size == 720 and d.angles[0] == 0.0
    assert d.angles[1] == pytest.approx(0.5, abs=1e-3)  # 8.72665E-03 rad printed
    assert d.angles[-1] == pytest.approx(359.5, abs=1e-3)
    np.testing.assert_array_equal(d.gaps, 5e-4)
    # the same numbers in degrees are read as degrees
    path.write_text("\n".join(lines[:6] + ["THETA R"] + [f"{a:12.5E} {5e-4:12.5E}"
                                                        for a in np.arange(721) * 0.5]) + "\n")
    assert read_discret(path, mobile_radius=RM).angles[1] == 0.5
    # a span too short to tell is refused, naming the fix
    path.write_text("THETA JEU\n0 5e-4\n1 5e-4\n2 5e-4\n")
    from fretwear.errors import FormatError

    with pytest.raises(FormatError, match=r"the unit is ambiguous; give angle_unit='deg' or "
                                          r"'rad' \(Code_Aster's DEFI_OBSTACLE stores THETA in "
                                          r"radians\)"):
        read_discret(path)
    assert read_discret(path, angle_unit="deg").angles.tolist() == [0.0, 1.0, 2.0]
    assert read_discret(path, angle_unit="rad").angles[1] == pytest.approx(57.29577951308232)


def test_section_with_options_replaces_the_obstacle_and_keeps_the_section():
    """fretwear obstacle's option merging (obstacle/config.py): a given obstacle replaces the
    section's type and its keys, the section itself is not modified, and the refusals."""
    from fretwear.errors import KeywordError
    from fretwear.obstacle.config import section_with_options

    section = {"type": "planes", "plane_gap_m": 4e-4, "orientation_deg": 30.0,
               "wall_thickness_m": 1e-3}
    merged = section_with_options(section, {"gap_m": 5e-4, "instant": 2.0, "shape": None})
    assert merged == {"gap_m": 5e-4, "instant": 2.0, "wall_thickness_m": 1e-3}
    assert section["type"] == "planes"  # the user's section untouched
    planes = section_with_options(None, {"plane_gap_m": 1e-4, "orientation_deg": 10.0,
                                         "mobile_radius_m": 1e-2, "wall_thickness_m": 1e-3},
                                  table="wear.csv")
    assert planes["type"] == "planes" and planes["orientation_deg"] == 10.0
    assert planes["table"] == "wear.csv"
    with pytest.raises(KeywordError, match="give one obstacle"):
        section_with_options(section, {"gap_m": 1e-4, "file": "d.txt"})
    with pytest.raises(KeywordError, match="--orientation describe two planes"):
        section_with_options(section, {"gap_m": 1e-4, "orientation_deg": 5.0})
    with pytest.raises(KeywordError, match="--wall-thickness, an obstacle"):
        section_with_options(None, {"mobile_radius_m": 1e-2})
