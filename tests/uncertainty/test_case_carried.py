"""Monte Carlo results carry their wear case and power computation (issue 25, point 3), the
wall among the case's keywords checked once, where the case is built.

Expected values: K·P·t of Archard (analytic) and the keywords given."""

from __future__ import annotations

import numpy as np
import pytest

from fretwear.errors import InputError
from fretwear.table import Wall, WearCase
from fretwear.uncertainty import LogNormal, monte_carlo

CASE = {"contact_type": "TUBE_ALESAGE", "instants": [1.0, 2.0], "time_scale": 3.6e3,
        "dimensions": {"mobile_radius": 0.01, "obstacle_width": 0.02},
        "coefficients": {"COEF_USURE": 1e-14}, "wall_thickness": 1e-3}


def test_monte_carlo_of_keywords_carries_the_case():
    r = monte_carlo(CASE, 0.01, factor=LogNormal(sigma_ln=0.3), samples=64, seed=1)
    assert isinstance(r.case, WearCase)
    assert r.case.wall == Wall(1e-3) and r.case.instants == (1.0, 2.0)
    assert r.power_result is None  # a power given as a number
    assert (r.wall_thickness, r.depth_limit) == (r.case.wall.thickness, r.case.wall.limit)
    # the durations are the case's: instants = origin + durations
    assert np.array_equal(r.instants, np.array([1.0, 2.0]))


def test_monte_carlo_of_a_case_carries_the_same_case():
    case = WearCase.from_keywords(**CASE)
    r = monte_carlo(case, 0.01, factor=LogNormal(sigma_ln=0.3), samples=64, seed=1)
    assert r.case is case


def test_a_wall_thicker_than_the_tube_is_refused_where_the_case_is_built():
    with pytest.raises(InputError, match="at least the tube's outer radius"):
        monte_carlo({**CASE, "wall_thickness": 1.0}, 0.01, factor=LogNormal(sigma_ln=0.3),
                    samples=16)
