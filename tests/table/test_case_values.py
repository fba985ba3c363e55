"""The frozen values a WearCase is made of (issue 25, point 3): Wall, PowerWindow, Restart,
each checked once where it is built; the case's flat keys (case files, to_dict) unchanged.

Expected values: limit depth = limit × thickness and fraction = depth / thickness (the
definitions of docs/uncertainty.md §1), with the default limit 0.4 (DEFAULT_DEPTH_LIMIT)."""

import math
import warnings

import numpy as np
import pytest

from fretwear.errors import InputError, KeywordError, UnitsWarning
from fretwear.table import DEFAULT_DEPTH_LIMIT, PowerWindow, Restart, Wall, WearCase

DIMS = {"mobile_radius": 0.01, "obstacle_width": 0.02}


def test_wall_limit_depth_and_fraction():
    wall = Wall(1.09e-3)
    assert wall.limit == DEFAULT_DEPTH_LIMIT
    assert math.isclose(wall.limit_depth, 0.4 * 1.09e-3, rel_tol=1e-15)
    assert np.allclose(wall.fraction([0.0, 1.09e-3, 2.18e-3]), [0.0, 1.0, 2.0], rtol=1e-15)
    assert Wall().limit_depth is None
    with pytest.raises(InputError, match="no wall thickness"):
        Wall().fraction(1e-4)


@pytest.mark.parametrize("thickness, limit, match", [
    (-1e-3, 0.4, "wall_thickness must be > 0"), (math.nan, 0.4, "finite"),
    (1e-3, 40, "fraction of the wall"), (1e-3, 0, "fraction of the wall")])
def test_a_bad_wall_is_refused_where_it_is_built(thickness, limit, match):
    with pytest.raises(InputError, match=match):
        Wall(thickness, limit)


def test_power_window_checks():
    assert PowerWindow(0.0, 10.0, blocks=4) == PowerWindow(0, 10, 4, 0.1)
    with pytest.raises(InputError, match="must be after t_start"):
        PowerWindow(10.0, 1.0)
    with pytest.raises(InputError, match="blocks .NB_BLOC. must be a whole number"):
        PowerWindow(blocks=0)


def test_restart_checks():
    assert Restart().origin == 0.0 and Restart(tube_replacement=3.0).tube_replacement == 3.0
    with pytest.raises(KeywordError, match="needs an initial_state"):
        Restart(instant=2.0)
    with pytest.raises(InputError, match="must be an InitialState"):
        Restart(table="table.csv")


def test_the_case_is_grouped_and_its_flat_keys_kept():
    case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0], dimensions=DIMS,
                                  coefficients={"COEF_USURE": 1e-14}, wall_thickness=1e-3,
                                  depth_limit=0.5, t_start=0.0, t_end=2.0, blocks=2,
                                  tube_replacement=0.5)
    assert case.wall == Wall(1e-3, 0.5)
    assert case.window == PowerWindow(0.0, 2.0, 2)
    assert case.restart.tube_replacement == 0.5 and case.restart.table is None
    data = case.to_dict()
    assert (data["wall_thickness"], data["depth_limit"], data["blocks"]) == (1e-3, 0.5, 2)
    assert WearCase.from_dict(data) == case
    # replace by flat key or by group, the same case
    assert case.replace(wall_thickness=2e-3) == case.replace(wall=Wall(2e-3, 0.5))
    with pytest.raises(KeywordError, match="unknown wear-case key"):
        case.replace(wall_thicknes=2e-3)
    # a wall thicker than the tube (mm typed for m): refused by the case, naming the key
    with pytest.raises(InputError, match="wall_thickness .*at least the tube's outer radius"):
        case.replace(wall_thickness=1.0)


def test_every_length_in_mm_is_refused():
    """Issue 29 (a new user): radius 9.525, width 12.7, wall 1.09 all in mm passed the
    wall-vs-radius check (consistently wrong) and ran to a 3.4e9-year forecast. A steam-generator
    tube of 9.525 mm radius (19.05 mm OD, 1.09 mm wall: the reference document's tube) is the
    source of the right values. A wall in mm is refused; a radius or width alone is warned of,
    since Code_Aster's own POST_USURE test cases use RAYON_MOBILE=1., LARGEUR_OBST=10.
    (tests/workflows/test_aster_pasted_calls.py computes them)."""
    base = dict(contact_type="TUBE_ALESAGE", instants=[1.0], coefficients={"COEF_USURE": 1e-14})
    ok = {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3}
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitsWarning)
        WearCase.from_keywords(dimensions=ok, wall_thickness=1.09e-3, **base)
    mm = {"mobile_radius": 9.525, "obstacle_width": 12.7}
    with pytest.raises(InputError, match=r"wall_thickness = 1.09 m is implausible.*in mm\? "
                                         r"Give metres: wall_thickness = 0.00109"):
        WearCase.from_keywords(dimensions=mm, wall_thickness=1.09, **base)
    with pytest.warns(UnitsWarning, match=r"obstacle_width = 12.7 m .*= 0.0127"):
        WearCase.from_keywords(dimensions={**ok, "obstacle_width": 12.7}, **base)
    with pytest.warns(UnitsWarning, match=r"mobile_radius = 9.525 m is implausible"):
        WearCase.from_keywords(dimensions={**mm, "obstacle_width": 0.0127}, **base)
    with pytest.raises(InputError, match=r"wall_thickness = 0.2 m is implausible"):
        WearCase.from_keywords(dimensions={"mobile_radius": 0.4, "obstacle_width": 0.01},
                               wall_thickness=0.2, **base)


def test_a_radius_in_mm_beside_a_wall_in_metres_is_refused():
    """A new user's trial (session 4): mobile_radius_m = 9.525 with wall_thickness_m = 1.09e-3
    was only warned of, at the end of the output, and the life came out 1159 year instead of
    36.6 (the depth of a volume falls with the radius). A tube's radius is 8-25 walls (the
    reference document's tube: 9.525 mm on 1.09 mm, ratio 8.7, so 8 700 in the slip); a thousand
    walls is refused with the value in metres, and 25 or 950 walls is not."""
    base = dict(contact_type="TUBE_ALESAGE", instants=[1.0], coefficients={"COEF_USURE": 1e-14})
    with pytest.raises(InputError, match=r"mobile_radius = 9.525 m is 8739 times the wall "
                                         r"0.00109 m .*mobile_radius = 0.009525"):
        WearCase.from_keywords(dimensions={"mobile_radius": 9.525, "obstacle_width": 0.0127},
                               wall_thickness=1.09e-3, **base)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitsWarning)
        WearCase.from_keywords(dimensions={"mobile_radius": 0.0125, "obstacle_width": 0.0127},
                               wall_thickness=0.5e-3, **base)
        WearCase.from_keywords(dimensions={"mobile_radius": 0.0095, "obstacle_width": 0.0127},
                               wall_thickness=1e-5, **base)
