"""Fused kernels: the compiled one-pass kernel against the plain numpy reference.

Source of truth for sectors: ``sector_index(contact_angle(dy, dz), edges)`` (theory §3, with
θ = 0 when dy = dz = 0); for the sums: the vectorised numpy implementation, which refines the time
grid at window bounds and block edges and integrates each piece independently.
"""

import numpy as np
import pytest

from fretwear.history import contact_angle
from fretwear.power.kernels import (
    HAVE_NUMBA,
    fast_sector_index,
    fused,
    fused_numba,
    fused_numpy,
    pseudo_angle,
    reference_sector_index,
    sector_table,
)
from fretwear.sectors import sector_edges, sector_index

EDGE_SETS = [
    sector_edges(1),
    sector_edges(2),
    sector_edges(4),
    sector_edges(10),
    sector_edges(7),
    np.array([-180.0, -100.0, -0.5, 20.0, 45.0, 90.0, 179.0, 180.0]),
]


def _awkward_points(edges, rng):
    """Random directions plus points exactly on every edge, on the axes, at ±180° and at 0."""
    rad = np.radians(edges)
    r = rng.uniform(0.1, 10.0, edges.size)
    on_edges_y, on_edges_z = r * np.cos(rad), r * np.sin(rad)
    special_y = np.array([0.0, -0.0, 1.0, -1.0, 0.0, 0.0, -1.0, -1.0, -1.0, -1.0, 2.0, 2.0,
                          -3.0, 1e-300, -1e-300, 5.0, 1.0, -1.0])
    special_z = np.array([0.0, 0.0, 0.0, 0.0, 1.0, -1.0, -0.0, 1e-300, -1e-300, -1e-17,
                          1e-300, -1e-300, 0.0, 1.0, 1.0, 5.0, 1.0, 1.0])
    y = np.concatenate([rng.normal(size=3000), on_edges_y, special_y, np.cos(rad + 1e-13)])
    z = np.concatenate([rng.normal(size=3000), on_edges_z, special_z, np.sin(rad + 1e-13)])
    return y, z


@pytest.mark.parametrize("edges", EDGE_SETS, ids=lambda e: f"{e.size - 1}sectors")
def test_fast_sector_index_equals_reference(edges):
    rng = np.random.default_rng(7)
    y, z = _awkward_points(edges, rng)
    ref = sector_index(contact_angle(y, z), edges)
    # the lead's contact_angle gives 180° for (dy, dz) = (-0.0, ±0.0); theory §3 says θ = 0 there
    origin = (y == 0) & (z == 0)
    ref[origin] = sector_index(np.zeros(origin.sum()), edges)
    np.testing.assert_array_equal(reference_sector_index(y, z, edges), ref)
    np.testing.assert_array_equal(fast_sector_index(y, z, edges), ref)


def test_pseudo_angle_is_increasing_in_theta():
    # analytic: q is a strictly increasing function of θ on (-180, 180]
    theta = np.linspace(-179.999, 180.0, 20001)
    q = pseudo_angle(np.cos(np.radians(theta)), np.sin(np.radians(theta)))
    assert np.all(np.diff(q) > 0)
    np.testing.assert_allclose(pseudo_angle([1.0, 0.0, -1.0, 0.0, 1.0, -1.0],
                                            [0.0, 1.0, 0.0, -1.0, -1.0, -1.0]),
                               [0.0, 1.0, 2.0, -1.0, -0.5, -1.5])


def test_close_edges_are_not_safe_but_still_exact():
    edges = np.array([-180.0, 10.0, 10.0 + 1e-12, 180.0])
    assert not sector_table(edges).safe
    y, z = _awkward_points(edges, np.random.default_rng(3))
    np.testing.assert_array_equal(fast_sector_index(y, z, edges),
                                  reference_sector_index(y, z, edges))


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_generic_directions_take_the_fast_path():
    # random directions are almost never within 1e-11 of an edge: none is deferred
    from fretwear.power._compiled import _classify_points

    rng = np.random.default_rng(11)
    y, z = rng.normal(size=100_000), rng.normal(size=100_000)
    st = sector_table(sector_edges(10))
    out = np.empty(y.size, dtype=np.int64)
    assert _classify_points(y, z, st.scale, st.base, st.edge, st.exact, out) == 0
    np.testing.assert_array_equal(out, reference_sector_index(y, z, sector_edges(10)))


def _random_chunk(rng, n, on_edges=True, edges=None):
    t = np.cumsum(rng.uniform(0.05, 1.0, n))
    fn = np.maximum(rng.normal(0.3, 1.0, n), 0.0)
    v1, v2 = rng.normal(size=n), rng.normal(size=n)
    dy, dz = rng.normal(size=n), rng.normal(size=n)
    if on_edges:
        ang = np.radians(rng.choice(edges, n))
        pick = rng.uniform(size=n) < 0.3
        dy[pick], dz[pick] = np.cos(ang[pick]), np.sin(ang[pick])
        dy[::17], dz[::19] = 0.0, 0.0
    stick = (rng.uniform(size=n) < 0.2).astype(float)
    return t, fn, v1, v2, dy, dz, stick


CASES = [
    # (sectors, blocks, window fraction, threshold [N], rest [s], with stick, on edges)
    (10, 4, (0.1, 0.9), 0.0, 0.0, True, True),
    (1, 1, None, 0.0, 0.0, False, False),
    (7, 3, (0.0, 1.0), 0.4, 2.0, True, True),
    (4, 5, (0.33, 0.34), 0.2, 0.0, False, True),
    (2, 2, (0.5, 0.75), 1.0, 10.0, True, False),
]


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("case", CASES)
def test_numba_kernel_equals_numpy_reference(case):
    ns, nb, frac, thr, rest, with_stick, on_edges = case
    edges = sector_edges(ns)
    rng = np.random.default_rng(ns * 100 + nb)
    t, fn, v1, v2, dy, dz, stick = _random_chunk(rng, 3000, on_edges, edges)
    if frac is None:
        lo, hi = -np.inf, np.inf
        be = np.array([lo, hi])
    else:
        # bounds between samples on purpose
        lo = t[0] + frac[0] * (t[-1] - t[0]) + 1e-3
        hi = t[0] + frac[1] * (t[-1] - t[0]) - 1e-3
        be = np.linspace(lo, hi, nb + 1)
    st = stick if with_stick else None
    a = fused_numpy(t, fn, v1, v2, dy, dz, st, lo, hi, be, edges, thr, rest)
    b = fused_numba(t, fn, v1, v2, dy, dz, st, lo, hi, be, edges, thr, rest)
    np.testing.assert_allclose(b.power, a.power, rtol=1e-12, atol=1e-12 * a.power.sum())
    np.testing.assert_allclose(b.block_stats, a.block_stats, rtol=1e-12,
                               atol=1e-12 * np.abs(a.block_stats).max())
    assert b.force_max == a.force_max
    np.testing.assert_allclose(b.groups, a.groups, rtol=1e-12, atol=1e-9)
    assert a.power.sum() > 0


def test_backend_registry():
    assert fused("numpy") is fused_numpy
    with pytest.raises(ValueError, match="unknown backend 'fortran'"):
        fused("fortran")


# ---------------------------------------------------------------- the compiled kernel's paths
def _signal(kind, rng, n):
    """Histories that drive each path of the compiled kernel (issue 13): ``sparse`` (bursts of
    contact of every length between free flights, so short runs, long runs and their tails),
    ``dense`` (white noise: a crossing on every other interval, a sector per sample),
    ``smooth`` (long contact lobes, few crossings, a slowly turning contact point)."""
    t = np.cumsum(rng.uniform(0.5, 1.5, n)) * 1e-3
    if kind == "dense":
        fn = np.maximum(rng.normal(0.0, 1.0, n), 0.0)
        ang = rng.uniform(-np.pi, np.pi, n)
    elif kind == "smooth":
        fn = np.maximum(0.0, np.sin(np.arange(n) * 2 * np.pi / 700) - 0.2
                        + rng.normal(0.0, 0.03, n))
        ang = 2.5 * np.sin(np.arange(n) * 2 * np.pi / 5000)
    else:
        fn = np.zeros(n)
        start = 0
        while start < n:
            length = int(rng.integers(1, 300))
            fn[start:start + length] = rng.uniform(0.0, 2.0, min(length, n - start))
            start += length + int(rng.integers(1, 120))
        ang = np.cumsum(rng.normal(0.0, 0.05, n))
    v1, v2 = rng.normal(size=n), rng.normal(size=n)
    dy, dz = np.cos(ang), np.sin(ang)
    stick = (rng.uniform(size=n) < 0.1).astype(float)
    return t, fn, v1, v2, dy, dz, stick


def _assert_same(a, b):
    """Kernel sums equal to 1e-12 relative (sums reordered, crossings located alike)."""
    scale_p = max(np.abs(a.power).max(), 1e-300)
    np.testing.assert_allclose(b.power, a.power, rtol=1e-12, atol=1e-12 * scale_p)
    scale_s = np.maximum(np.abs(a.block_stats).max(axis=0), 1e-300)  # per statistic
    err = np.abs(b.block_stats - a.block_stats) / (np.abs(a.block_stats) + scale_s)
    assert err.max() <= 1e-12, (err.max(axis=0), a.block_stats, b.block_stats)
    assert b.force_max == a.force_max
    np.testing.assert_allclose(b.groups, a.groups, rtol=1e-12, atol=1e-9)


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("kind", ["sparse", "dense", "smooth"])
@pytest.mark.parametrize("thr, rest, blocks, stick", [(0.0, 0.0, 1, False), (0.3, 0.002, 5, True)])
def test_every_kernel_path_equals_the_reference(kind, thr, rest, blocks, stick):
    rng = np.random.default_rng(abs(hash((kind, thr, blocks))) % 2**32)
    t, fn, v1, v2, dy, dz, st = _signal(kind, rng, 20_000)
    edges = sector_edges(10)
    lo, hi = t[0] + 0.03 * (t[-1] - t[0]), t[-1] - 1e-4  # bounds between samples
    be = np.linspace(lo, hi, blocks + 1)
    args = (t, fn, v1, v2, dy, dz, st if stick else None, lo, hi, be, edges, thr, rest)
    a = fused_numpy(*args)
    _assert_same(a, fused_numba(*args))
    assert a.power.sum() > 0 and a.groups[0] > 10


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_crossings_bounds_and_block_edges_on_samples():
    # Adversarial: forces equal to the threshold at samples (no crossing inside, contact
    # starting exactly there), the window and every block edge exactly on a sample.
    rng = np.random.default_rng(5)
    t, fn, v1, v2, dy, dz, st = _signal("sparse", rng, 6000)
    thr = 0.5
    fn[::7] = thr
    fn[3::11] = 0.0
    edges = sector_edges(4)
    lo, hi = t[100], t[5900]
    be = t[np.linspace(100, 5900, 7).astype(int)]
    a = fused_numpy(t, fn, v1, v2, dy, dz, st, lo, hi, be, edges, thr, 0.01)
    _assert_same(a, fused_numba(t, fn, v1, v2, dy, dz, st, lo, hi, be, edges, thr, 0.01))


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("kind", ["sparse", "dense"])
def test_ambiguous_samples_resolved_one_by_one(kind):
    # Every contact point exactly on a sector edge (45°, 135°, ... of 8 sectors: their
    # pseudo-angles are not exact, so each sample is ambiguous) or on an axis edge (exact):
    # 20 000 deferrals overflow the kernel's buffer several times (it stops and resumes).
    rng = np.random.default_rng(9)
    t, fn, v1, v2, _, _, st = _signal(kind, rng, 20_000)
    edges = sector_edges(8)
    ang = np.radians(rng.choice(edges, t.size))
    dy, dz = 2.0 * np.cos(ang), 2.0 * np.sin(ang)
    dy[::5] = 0.0  # on the ±90° axis edges: exact
    args = (t, fn, v1, v2, dy, dz, st, -np.inf, np.inf, np.array([-np.inf, np.inf]), edges,
            0.0, 0.0)
    a = fused_numpy(*args)
    _assert_same(a, fused_numba(*args))
    # the reference really puts them on both sides of their edges
    assert len(np.unique(reference_sector_index(dy, dz, edges))) == 8


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_edges_too_close_for_a_table_use_the_reference_rule():
    edges = np.array([-180.0, 10.0, 10.0 + 1e-9, 60.0, 180.0])
    assert not sector_table(edges).safe
    rng = np.random.default_rng(2)
    t, fn, v1, v2, dy, dz, st = _signal("dense", rng, 5000)
    ang = np.radians(10.0 + rng.uniform(-1e-7, 1e-7, t.size))
    dy[::3], dz[::3] = np.cos(ang[::3]), np.sin(ang[::3])
    args = (t, fn, v1, v2, dy, dz, st, -np.inf, np.inf, np.array([-np.inf, np.inf]), edges,
            0.0, 0.0)
    _assert_same(fused_numpy(*args), fused_numba(*args))


@pytest.mark.parametrize("edges", [sector_edges(720), np.array([-180.0, 10.0, 10.15, 180.0])],
                         ids=["720sectors", "close"])
def test_sector_table_holds_one_edge_per_bin(edges):
    # the table refines its bins until each holds at most one edge (10° and 10.15° are closer
    # than 4/1024 in pseudo-angle): the bin rule then gives the sector of every q exactly
    st = sector_table(edges)
    assert st.safe
    if edges.size == 4:
        assert st.base.size > 1024
    q = np.linspace(-2.0, 2.0, 400_001)[1:]
    b = np.minimum(np.floor((q + 2.0) * st.scale).astype(int), st.base.size - 1)
    j = st.base[b] + (q > st.edge[b])
    np.testing.assert_array_equal(j, np.searchsorted(st.q_edges[1:-1], q, side="left"))


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("nb", [4122, 8192])
def test_far_more_blocks_than_samples_ends_and_equals_the_reference(nb):
    """A [power] blocks of 4122 on a 200-sample history with 4 sectors looped forever (found
    by the FRETWEAR_FUZZ_SCALE=20 run of the cases family: one sample's ambiguous-sector
    deferrals, one per block it spans, overflowed the deferral buffer, and the pass resumed
    at the same sample). The buffer now grows; the result is the numpy reference's."""
    edges = sector_edges(4)
    rng = np.random.default_rng(nb)
    t, fn, v1, v2, dy, dz, _ = _random_chunk(rng, 200, True, edges)
    be = np.linspace(t[0], t[-1], nb + 1)
    a = fused_numpy(t, fn, v1, v2, dy, dz, None, t[0], t[-1], be, edges, 0.0, 0.0)
    b = fused_numba(t, fn, v1, v2, dy, dz, None, t[0], t[-1], be, edges, 0.0, 0.0)
    np.testing.assert_allclose(b.power, a.power, rtol=1e-12, atol=1e-12 * a.power.sum())
    np.testing.assert_allclose(b.block_stats, a.block_stats, rtol=1e-12,
                               atol=1e-12 * np.abs(a.block_stats).max())
    assert a.power.sum() > 0
