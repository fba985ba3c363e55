"""fretwear.geometry.sectors.SectorSlices: the sector depth-volume relations of one set of
dimensions, checked once.

Independent computation: the module functions :func:`sector_depth_mobile`,
:func:`sector_depth_obstacle` and :func:`sector_volume_mobile` on the same inputs, which check
their dimensions at every call: the same values bit for bit (the same operations in the same
order, in this one process), NaN and the RangeWarning at the same places; and the closed forms
of theory §3 at 1e-12 relative (V = l·Δθ·d·(2R − d)/2 for the mobile, l·Δθ·d·(2r + d)/2 for
the bore). Bad dimensions and volumes raise the functions' InputError.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from fretwear.errors import InputError, RangeWarning
from fretwear.geometry.sectors import (
    SectorSlices,
    sector_depth_mobile,
    sector_depth_obstacle,
    sector_slices,
    sector_volume_mobile,
)

R, RO, L = 9.525e-3, 9.725e-3, 12.7e-3
ARCS = (45.0, 45.0, 90.0, 180.0)


def _volumes() -> np.ndarray:
    rng = np.random.default_rng(5)
    v = rng.uniform(0.0, 2e-7, (7, len(ARCS)))
    v[0] = 0.0
    v[3, 1] = np.nan
    v[5, 0] = 1e-3  # beyond the whole 45° sector of the tube: NaN with a RangeWarning
    return v


def test_depths_and_volumes_equal_the_functions_bit_for_bit():
    s = SectorSlices(R, L, ARCS, RO)
    v = _volumes()
    with warnings.catch_warnings(record=True) as mine:
        warnings.simplefilter("always")
        dm = s.depth_mobile(v)
    with warnings.catch_warnings(record=True) as theirs:
        warnings.simplefilter("always")
        expected = sector_depth_mobile(v, R, L, np.array(ARCS))
    assert np.array_equal(dm, expected, equal_nan=True)
    assert [str(w.message) for w in mine] == [str(w.message) for w in theirs]
    assert [w.category for w in mine] == [RangeWarning]
    assert np.array_equal(s.depth_obstacle(v[:3]),
                          sector_depth_obstacle(v[:3], RO, L, np.array(ARCS)))
    d = np.array([[0.0], [1e-4], [2e-3], [R]])
    assert np.array_equal(s.volume_mobile(d), sector_volume_mobile(d, R, L, np.array(ARCS)))


def test_the_closed_forms_of_theory_section_3():
    s = SectorSlices(R, L, ARCS, RO)
    d = np.array([[1e-6], [1e-4], [1e-3]])
    arcs = np.radians(ARCS)
    v_m = L * arcs * d * (2 * R - d) / 2
    v_o = L * arcs * d * (2 * RO + d) / 2
    np.testing.assert_allclose(s.volume_mobile(d), v_m, rtol=1e-12)
    np.testing.assert_allclose(s.depth_mobile(v_m), np.broadcast_to(d, v_m.shape), rtol=1e-12)
    np.testing.assert_allclose(s.depth_obstacle(v_o), np.broadcast_to(d, v_o.shape),
                               rtol=1e-12)


@pytest.mark.parametrize("args, culprit", [
    ((0.0, L, ARCS), "mobile_radius"), ((R, -1.0, ARCS), "width"),
    ((R, L, (45.0, 400.0)), "arc_deg"), ((R, L, ARCS, float("inf")), "obstacle_radius")])
def test_bad_dimensions_name_the_culprit(args, culprit):
    with pytest.raises(InputError, match=culprit):
        SectorSlices(*args)


def test_bad_volumes_and_depths_raise_as_the_functions_do():
    s = SectorSlices(R, L, ARCS)
    with pytest.raises(InputError, match="volume must be finite and >= 0"):
        s.depth_mobile(np.array([[1e-9, -1e-9, 0.0, 0.0]]))
    with pytest.raises(InputError, match="depth must be finite and >= 0"):
        s.volume_mobile(np.array([[np.inf]]))


def test_one_object_per_set_of_dimensions():
    assert sector_slices(R, L, ARCS, RO) is sector_slices(R, L, ARCS, RO)
    assert sector_slices(R, L, ARCS, None) is not sector_slices(R, L, ARCS, RO)


def test_kept_volumes_are_the_callers_own_and_warnings_said_every_call():
    """A few depths' volumes are kept per object: each call gets its own array (changing it
    changes nothing else), equal to the function's; depths past the radius warn every call."""
    s = SectorSlices(R, L, ARCS)
    d = np.array([[4e-4], [1.09e-3]])
    first = s.volume_mobile(d)
    first[:] = -1.0
    assert np.array_equal(s.volume_mobile(d), sector_volume_mobile(d, R, L, np.array(ARCS)))
    for _ in range(2):
        with pytest.warns(RangeWarning, match="exceed the mobile radius"):
            assert np.isnan(s.volume_mobile(np.array([[2 * R]]))).all()
