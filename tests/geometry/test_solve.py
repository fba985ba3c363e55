"""The geometry relations' solver (fretwear.geometry._solve.solve_monotone, and solve_on_grid
starting each element from a grid): its compiled steps against its numpy steps, bit for bit,
and both against roots known in closed form.

Sources: x³ = y, √x = y, eˣ − 1 = y inverted by hand; the cases without a root (target outside
[f(lower), f(upper)]: NaN), a NaN target, a function NaN beyond a point, flat steps, an
unbounded bracket and an iteration cap exercise the branches of Chandrupatla's method
(Chandrupatla 1997, Adv. Eng. Software 28(3)).
"""

import math
import warnings

import numpy as np
import pytest

from fretwear._numba import HAVE_NUMBA
from fretwear.geometry._shapes import lens_area
from fretwear.geometry._solve import monotone_grid, solve_monotone, solve_on_grid

FUNCTIONS = {
    "cube": lambda x: x**3,
    "root": np.sqrt,
    "exp": lambda x: np.exp(x) - 1.0,
    "steps": lambda x: np.floor(x * 10) / 10,
    "nan beyond": lambda x: np.where(x > 0.3, np.nan, x),
    "flat": lambda x: x * 0 + 0.5,
    "odd root": lambda x: np.sign(x - 0.5) * np.abs(x - 0.5) ** 0.2,
    "-inf below": lambda x: np.where(x < 0.2, -np.inf, x),
    "tan": lambda x: np.tan(x * 1.5),
    "lens": lambda x: lens_area(9.525e-3, 9.75e-3, x),
}


@pytest.mark.skipif(not HAVE_NUMBA, reason="the compiled steps need numba (extra 'fast')")
@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_compiled_steps_are_the_numpy_steps_bit_for_bit(name):
    func = FUNCTIONS[name]
    rng = np.random.default_rng(sorted(FUNCTIONS).index(name))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(60):
            k = int(rng.integers(0, 9))
            target = rng.random(k) * rng.choice([1.0, 1e-8, 2.0])
            if k and rng.random() < 0.3:
                target[rng.integers(0, k)] = np.nan
            lower = np.where(rng.random(k) < 0.2, 0.0, rng.random(k) * 0.1)
            upper = lower + rng.random(k) * rng.choice([1.0, 1e-3, np.inf])
            if rng.random() < 0.2:
                target, lower, upper = np.array(rng.random()), np.array(0.0), np.array(1.0)
            for rtol, max_iter in ((1e-12, 400), (1e-13, 400), (1e-3, 400), (1e-14, 3),
                                   (0.0, 400)):
                a = solve_monotone(func, target, lower, upper, rtol=rtol, max_iter=max_iter,
                                   compiled=False)
                b = solve_monotone(func, target, lower, upper, rtol=rtol, max_iter=max_iter)
                assert type(a) is type(b) and np.shape(a) == np.shape(b)
                assert np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("compiled", [False, True])
def test_roots_known_in_closed_form(compiled):
    y = np.array([1e-9, 0.008, 0.5, 0.999])
    assert solve_monotone(lambda x: x**3, y, 0.0, 1.0, compiled=compiled) == pytest.approx(
        np.cbrt(y), rel=1e-12)
    assert solve_monotone(np.sqrt, y, 0.0, 1.0, compiled=compiled) == pytest.approx(
        y**2, rel=1e-12)
    assert solve_monotone(lambda x: np.exp(x) - 1, y, 0.0, 1.0, rtol=1e-14,
                          compiled=compiled) == pytest.approx(np.log1p(y), rel=1e-13)
    out = solve_monotone(lambda x: x, np.array([2.0, np.nan, 0.0, 1.0]), 0.0, 1.0,
                         compiled=compiled)
    assert np.isnan(out[:2]).all() and out[2:].tolist() == [0.0, 1.0]


@pytest.mark.parametrize("compiled", [False, True])
def test_roots_from_the_grid_are_the_closed_form_roots(compiled):
    """solve_on_grid (each element from the grid points around its target) against the
    closed-form inverses x = ∛y, y², ln(1 + y), at the solver's tolerance; the bracket's ends and
    the cases without a root as solve_monotone on the whole bracket: NaN outside [f(0), f(1)]
    and for a NaN target, the end itself where the target is its value."""
    y = np.concatenate([[1e-30, 1e-12, 1e-9], np.geomspace(1e-6, 0.999, 50)])
    for func, inverse, rtol in ((lambda x: x**3, np.cbrt, 1e-12), (np.sqrt, np.square, 1e-12),
                                (np.expm1, np.log1p, 1e-14)):
        grid = monotone_grid(func, 1.0, (float(func(0.0)), float(func(1.0))))
        assert grid.x.size == 129 and (np.diff(grid.f) > 0).all()
        found = solve_on_grid(func, y, grid, rtol=rtol, compiled=compiled)
        assert found == pytest.approx(inverse(y), rel=10 * rtol, abs=1e-300)
        full = solve_monotone(func, y, 0.0, 1.0, rtol=rtol, compiled=compiled)
        assert found == pytest.approx(full, rel=10 * rtol, abs=1e-300)
    grid = monotone_grid(lambda x: x, 1.0, (0.0, 1.0))
    out = solve_on_grid(lambda x: x, np.array([2.0, -1.0, np.nan, 0.0, 1.0]), grid,
                        compiled=compiled)
    assert np.isnan(out[:3]).all() and out[3:].tolist() == [0.0, 1.0]


def test_the_grid_leaves_out_points_where_the_function_does_not_increase():
    """A function flat at first (rounding to 0 below 1e-3, as a relation's rounding near 0 may
    be) and constant on [0.5, 0.6]: the grid keeps 0, the increasing points and the upper end, so
    that np.searchsorted finds a bracket whose ends hold the target; the roots are the
    function's inverse (y, and y + 0.1 above 0.5) at the solver's tolerance, 0 and 1 at the
    ends."""
    def func(x):
        return np.where(x < 1e-3, 0.0, np.where(x < 0.5, x, np.maximum(x - 0.1, 0.5)))

    grid = monotone_grid(func, 1.0, (0.0, 0.9))
    assert grid.x[0] == 0.0 and grid.x[-1] == 1.0 and grid.f[-1] == 0.9
    assert (np.diff(grid.f) > 0).all() and np.isfinite(grid.f).all()
    assert grid.x[1] >= 1e-3 and ((grid.x > 0.5) & (grid.x <= 0.6)).sum() <= 1
    y = np.array([2e-3, 0.1, 0.3, 0.49, 0.55, 0.8, 0.0, 0.9])
    assert solve_on_grid(func, y, grid) == pytest.approx(
        [2e-3, 0.1, 0.3, 0.49, 0.65, 0.9, 0.0, 1.0], rel=1e-12)


@pytest.mark.parametrize("compiled", [False, True])
def test_stacked_lens_area_compiled_or_not_is_lens_area(compiled, monkeypatch):
    """The solvers' lens area, its arithmetic compiled (numba) or numpy's, against the public
    lens_area bit for bit: small and large angles (series and direct u − sin u), the range's
    end and beyond, NaN, signed zero."""
    from fretwear.geometry import _shapes
    if compiled and not HAVE_NUMBA:
        pytest.skip("the compiled lens needs numba (extra 'fast')")
    if not compiled:
        monkeypatch.setattr(_shapes, "_lens_kernels", lambda: None)
    rng = np.random.default_rng(5)
    for rm, ro in ((9.525e-3, 9.75e-3), (4.84e-3, 5.5e-3), (3.0, 5.0)):
        limit = float(_shapes.lens_depth_limit(rm, ro))
        area = _shapes.stacked_lens_area(rm, ro)
        assert (area.__name__ == "compiled_area") is compiled
        for d in (rng.random(11) * limit, np.geomspace(1e-14, limit, 500),
                  rng.random(500) * limit * 1.1,
                  np.array([0.0, -0.0, limit, limit * (1 + 1e-13), 1.5 * limit, -1.0, np.nan])):
            with np.errstate(invalid="ignore"):
                assert np.array_equal(area(d), _shapes.lens_area(rm, ro, d), equal_nan=True)


@pytest.mark.skipif(not HAVE_NUMBA, reason="the compiled lunule needs numba (extra 'fast')")
def test_lunule_compiled_is_the_numpy_lunule_bit_for_bit(monkeypatch):
    """The lunule's mobile area (the split solver's function) and the depths of
    lunule_depths / lunule_mobile_depth, compiled (numba) against numpy, bit for bit: any d_m
    in and beyond [0, D] (a common arc past the bore's), NaN, 0-d and 2-d inputs."""
    from fretwear.geometry import _lunule, _shapes
    rng = np.random.default_rng(9)
    cases = []
    for rm, ro in ((9.525e-3, 9.75e-3), (4.84e-3, 5.5e-3), (3.0, 5.0)):
        limit = float(_shapes.lens_depth_limit(rm, ro))
        depth = np.concatenate([rng.random(40) * limit, [0.0, limit, np.nan]])
        x = np.minimum(_shapes.lens_half_chord(rm, ro, depth), rm)
        seg_m = _shapes.segment_area(rm, x)
        s_m = _shapes.sagitta(rm, x)
        dm = np.concatenate([rng.random(40) * limit * 1.2, [0.0, -1e-9, np.nan]])
        area = np.asarray(_shapes.lens_area(rm, ro, depth))
        cases.append((rm, ro, x, s_m, seg_m, dm, depth, area))

    def run():
        out = []
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            for rm, ro, x, s_m, seg_m, dm, depth, area in cases:
                out.append(_lunule._mobile_area(x, s_m, seg_m)(dm))
                share = rng.random(depth.size)
                share[:5] = [0.0, 1.0, np.nan, 1e-12, 1.0 - 1e-12]
                out.append(_lunule.lunule_mobile_depth(rm, ro, depth, share))
                out.append(_lunule.lunule_mobile_depth(rm, ro, depth[3], share[9]))
                out.extend(_lunule.lunule_depths(rm, ro, area * share,
                                                 area * (1 - share)))
                out.extend(_lunule.lunule_depths(rm, ro, (area * share)[:40].reshape(5, 8),
                                                 (area * (1 - share))[:40].reshape(5, 8)))
        return out

    state = rng.bit_generator.state
    assert _lunule._mobile_area(*cases[0][2:5]).__name__ == "compiled_area"
    compiled = run()
    rng.bit_generator.state = state
    monkeypatch.setattr(_lunule, "_kernels", lambda: None)
    monkeypatch.setattr(_shapes, "_lens_kernels", lambda: None)
    monkeypatch.setattr(_shapes, "_lens_area_on_range", _shapes._lens_area_on_range.__wrapped__)
    monkeypatch.setattr(_shapes, "_lens_area_grid", _shapes._lens_area_grid.__wrapped__)
    assert _lunule._mobile_area(*cases[0][2:5]).__name__ == "area"
    assert _shapes.lens_area_on_range(1.0, 2.0)[0].__name__ == "area"
    assert _shapes.lens_area_grid(1.0, 2.0)[0].__name__ == "area"
    plain = run()
    assert len(compiled) == len(plain)
    for a, b in zip(compiled, plain, strict=True):
        assert type(a) is type(b) and np.shape(a) == np.shape(b)
        assert np.array_equal(a, b, equal_nan=True)


@pytest.mark.skipif(not HAVE_NUMBA, reason="the compiled enco volume needs numba (extra 'fast')")
def test_enco_compiled_is_the_numpy_enco_bit_for_bit(monkeypatch):
    """TUBE_3/4_ENCO's solver function (the stacked enco volume) and enco_depth, compiled
    (numba arithmetic around NumPy's arcsin and sin) against the numpy operations, bit for bit:
    no tilt and tilts whose wedge/frustum switch falls inside the range, one and two edges,
    depths beyond the lens limit, negative, NaN; the public enco_volume as third witness."""
    from fretwear.geometry import _shapes, enco
    rng = np.random.default_rng(13)
    dims = [(9.525e-3, 9.75e-3, 0.03, 30.0, 0.0, 1), (9.525e-3, 9.75e-3, 0.03, 30.0, 0.1, 2),
            (4.84e-3, 5.5e-3, 0.02, 45.0, 1.0, 1), (3.0, 5.0, 1.0, 10.0, 20.0, 2)]

    def run():
        out = []
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            for rm, ro, l, alpha, tilt, edges in dims:
                limit = float(_shapes.lens_depth_limit(rm, ro))
                d = np.concatenate([rng.random(60) * limit * 1.1, np.geomspace(1e-13, limit, 40),
                                    [0.0, -0.0, limit, -1e-9, np.nan, l * math.radians(tilt)]])
                func = enco._stacked_enco_volume(rm, ro, l, alpha, tilt, edges)
                out.append((func.__name__, func(d), func(d[:12].reshape(3, 4)), func(d[5])))
                v = np.asarray(enco.enco_volume(rng.random(30) * limit, rm, ro, l, alpha,
                                                tilt_angle=tilt, edges=edges))
                out.append(enco.enco_depth(np.append(v, [0.0, np.nan, 10 * v.max()]), rm, ro, l,
                                           alpha, tilt_angle=tilt, edges=edges))
                out.append(np.asarray(enco.enco_volume(d, rm, ro, l, alpha, tilt_angle=tilt,
                                                       edges=edges)))
        return out

    state = rng.bit_generator.state
    compiled = run()
    rng.bit_generator.state = state
    monkeypatch.setattr(enco, "_enco_kernels", lambda: None)
    monkeypatch.setattr(enco, "_enco_volume_on_range", enco._enco_volume_on_range.__wrapped__)
    monkeypatch.setattr(enco, "_enco_volume_grid", enco._enco_volume_grid.__wrapped__)
    assert enco._enco_volume_grid(1.0, 2.0, 1.0, 10.0, 0.0, 1)[0].__name__ == "volume"
    plain = run()
    for a, b in zip(compiled, plain, strict=True):
        if isinstance(a, tuple):
            assert (a[0], b[0]) == ("compiled_volume", "volume")
            a, b = a[1:], b[1:]
        else:
            a, b = (a,), (b,)
        for x, y in zip(a, b, strict=True):
            assert type(x) is type(y) and np.shape(x) == np.shape(y)
            assert np.array_equal(x, y, equal_nan=True)
    # the public closed-form volume is the solver's function, compiled or not
    for c, p in zip(compiled[::3], compiled[2::3], strict=True):
        assert np.array_equal(c[1], p, equal_nan=True)
