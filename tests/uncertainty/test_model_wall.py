"""The wall and its limit are checked once (fretwear.table.limit.check_wall): a wear case and an
uncertainty DepthModel accept and refuse the same values with the same message (issue 10)."""

from __future__ import annotations

import pytest

from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import WearCase
from fretwear.table.depth import DepthModel
from fretwear.table.limit import check_wall

DIMENSIONS = {"mobile_radius": 0.01, "obstacle_width": 0.02}


def _case(**wall):
    return WearCase.from_keywords(contact_type="TUBE_BAV", dimensions=DIMENSIONS, instants=[1.0],
                                  coefficients={"COEF_USURE": 1e-14}, **wall)


def _model(**wall):
    return DepthModel(law=get_law("ARCHARD"), geometry=contact_geometry("TUBE_BAV", **DIMENSIONS),
                        powers=(0.01,), coefficients_mobile=({"coefficient": 1e-14},),
                        coefficients_obstacle=(None,), **wall)


@pytest.mark.parametrize("wall, match", [
    (dict(wall_thickness=-1e-3), r"wall_thickness must be > 0 \[m\], got -0.001"),
    (dict(wall_thickness=float("nan")), r"wall_thickness \[m\] must be a finite number"),
    (dict(wall_thickness=1e-3, depth_limit=40.0), r"0 < depth_limit <= 1 \[-\], got 40"),
    (dict(wall_thickness=1e-3, depth_limit=0.0), r"0 < depth_limit <= 1 \[-\], got 0"),
    (dict(depth_limit=True), r"depth_limit must be a finite number, got True"),
])
def test_case_and_model_refuse_the_same_walls(wall, match):
    with pytest.raises(InputError, match=match):
        _case(**wall)
    with pytest.raises(InputError, match=match):
        _model(**wall)


def test_accepted_walls_are_the_same_floats():
    assert check_wall(None, 0.4) == (None, 0.4)
    assert check_wall(1, 1) == (1.0, 1.0)  # a limit of the whole wall is allowed
    case, model = _case(wall_thickness=1.09e-3, depth_limit=1), _model(wall_thickness=1.09e-3,
                                                                       depth_limit=1)
    assert (case.wall.thickness, case.wall.limit) == (model.wall_thickness,
                                                       model.depth_limit) == (1.09e-3, 1.0)
    assert model.limit_depth == 1.09e-3  # depth_limit × wall_thickness [m]
