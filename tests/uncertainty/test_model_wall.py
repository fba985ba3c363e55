"""The wall and its limit are checked once (fretwear.table.limit.check_wall), where the
:class:`~fretwear.table.Wall` is built: a wear case and a wall given to the uncertainty
functions accept and refuse the same values with the same message (issue 10), and a
DepthModel takes the case's Wall as it is, never checking it again on the way from the case
to Monte Carlo (issue 25).
"""

from __future__ import annotations

import sys

import pytest

from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import Wall, WearCase
from fretwear.table import limit as limit_module
from fretwear.table.depth import DepthModel
from fretwear.table.limit import check_wall
from fretwear.uncertainty import LogNormal, monte_carlo

DIMENSIONS = {"mobile_radius": 0.01, "obstacle_width": 0.02}


def _case(**wall):
    return WearCase.from_keywords(contact_type="TUBE_BAV", dimensions=DIMENSIONS, instants=[1.0],
                                  coefficients={"COEF_USURE": 1e-14}, **wall)


def _model(wall):
    return DepthModel(law=get_law("ARCHARD"), geometry=contact_geometry("TUBE_BAV", **DIMENSIONS),
                      powers=(0.01,), coefficients_mobile=({"coefficient": 1e-14},),
                      coefficients_obstacle=(None,), wall=wall)


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
    with pytest.raises(InputError, match=match):  # the uncertainty functions' wall keywords
        monte_carlo(_model(Wall()), samples=4, instants=[1.0], **wall)


def test_accepted_walls_are_the_same_floats():
    assert check_wall(None, 0.4) == (None, 0.4)
    assert check_wall(1, 1) == (1.0, 1.0)  # a limit of the whole wall is allowed
    case = _case(wall_thickness=1.09e-3, depth_limit=1)
    model = _model(case.wall)
    assert model.wall is case.wall and case.wall == Wall(1.09e-3, 1.0)
    assert model.limit_depth == 1.09e-3  # depth_limit × wall_thickness [m]


def test_a_model_takes_a_wall_not_floats():
    with pytest.raises(InputError, match=r"wall must be a Wall \(fretwear.table.Wall"):
        _model(1.09e-3)


def test_the_wall_is_checked_once_from_the_case_to_monte_carlo(monkeypatch):
    """check_wall runs where the case's Wall is built, and never again on the way to the
    propagated depths (the wear table's model, the models of its table, Monte Carlo's)."""
    calls = []
    real = limit_module.check_wall

    def counted(*args):
        calls.append(args)
        return real(*args)

    for module in list(sys.modules.values()):  # every module that imported the one check
        if getattr(module, "__name__", "").startswith("fretwear") and \
                getattr(module, "check_wall", None) is real:
            monkeypatch.setattr(module, "check_wall", counted)
    case = _case(wall_thickness=1.09e-3)
    assert len(calls) == 1
    result = monte_carlo(case, 0.01, factor=LogNormal(1.0, sigma_ln=0.7), samples=8)
    assert len(calls) == 1
    assert (result.wall_thickness, result.depth_limit) == (1.09e-3, 0.4)
    monte_carlo(case, 0.01, factor=LogNormal(1.0, sigma_ln=0.7), samples=8, depth_limit=0.5)
    assert len(calls) == 2  # a limit given in place of the case's: a new wall, checked once
