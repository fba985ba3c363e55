"""The fast path of the geometries' input check (two float arrays, finite and >= 0) gives what
the general path gives, and every other pair still takes the general path (issue 28 point 5).

Independent computation: the same values given as lists (the general path: converted,
checked, broadcast, copied). Exact equality is right: the same floats in one process.
"""

from __future__ import annotations

import numpy as np
import pytest

from fretwear.errors import InputError
from fretwear.geometry import CONTACT_TYPES, contact_geometry


@pytest.mark.parametrize("contact_type",
                         ["TUBE_BAV", "GRAPPE_ALESAGE", "TUBE_ALESAGE", "GRAPPE_1_ENCO"])
def test_depths_of_arrays_equal_depths_of_lists(contact_type):
    g = contact_geometry(contact_type, **_dims(contact_type))
    vm = np.linspace(1e-12, 5e-10, 7)
    vo = np.linspace(0.0, 2e-10, 7)
    fast = g.depth_from_volume(vm, vo)
    general = g.depth_from_volume(vm.tolist(), vo.tolist())
    for a, b in zip(fast, general, strict=True):
        np.testing.assert_array_equal(a, b)
    assert vm[0] == 1e-12 and vo[-1] == 2e-10  # the inputs unchanged


def test_bad_arrays_still_refused_and_nan_still_passes():
    g = contact_geometry("TUBE_BAV", mobile_radius=0.01, obstacle_width=0.02)
    with pytest.raises(InputError, match="volume_mobile must be finite and >= 0"):
        g.depth_from_volume(np.array([1e-12, -1e-12]), np.zeros(2))
    with pytest.raises(InputError, match="volume_obstacle must be finite and >= 0"):
        g.depth_from_volume(np.array([1e-12, 2e-12]), np.array([0.0, np.inf]))
    dm, _ = g.depth_from_volume(np.array([np.nan, 1e-12]), np.zeros(2))
    assert np.isnan(dm[0]) and dm[1] > 0


def _dims(contact_type):
    if contact_type == "TUBE_ALESAGE":  # the two-lunule model (the obstacle wears)
        return {"mobile_radius": 4.85e-3, "obstacle_radius": 5.25e-3, "obstacle_width": 10e-3}
    return dict(CONTACT_TYPES[contact_type].example)
