"""The keywords of a wear computation are listed once (fretwear.table.keywords.KEYWORDS): every
keyword accepted is documented, every keyword documented is accepted (issue 25, point 3)."""

import inspect
import re

import pytest

from fretwear.errors import KeywordError
from fretwear.table import WearCase, wear_table
from fretwear.table.case import FLAT_KEYS
from fretwear.table.keywords import KEYWORDS, REQUIRED, check_keywords
from fretwear.workflows.case_files import case_arguments

DIMS = {"mobile_radius": 0.01, "obstacle_width": 0.02}


def _documented(doc: str) -> set[str]:
    """The names of the numpydoc entries ``name : type`` of a docstring."""
    return {m.group(1) for m in re.finditer(r"^\s*(\w+) : ", doc, re.MULTILINE)}


def test_the_case_keys_are_the_keywords_and_where_the_restart_came_from():
    # the user's flat vocabulary of WearCase.to_dict / from_dict is the keyword table's, in the
    # order of the stored format fretwear.WearCase/1 (attrs["case"], a bundle's task)
    assert FLAT_KEYS == (
        "contact_type", "dimensions", "instants", "law", "coefficients",
        "obstacle_coefficients", "materials", "obstacle_wear", "coefficient_files", "sectors",
        "sector_coefficients", "time_scale", "time_unit", "t_start", "t_end", "blocks",
        "stationarity_threshold", "force_max", "speed_max", "initial_state", "initial_instant",
        "initial_table", "tube_replacement", "wall_thickness", "depth_limit", "name")
    case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0], dimensions=DIMS)
    assert list(case.to_dict()) == ["format", *FLAT_KEYS]


@pytest.mark.parametrize("function", [wear_table, WearCase.from_keywords])
def test_every_keyword_is_documented_and_every_documented_one_accepted(function):
    documented = _documented(inspect.getdoc(function))
    assert set(KEYWORDS) <= documented
    own = {"source", "case", "history"}  # wear_table's own parameters besides the keywords
    assert documented - set(KEYWORDS) <= own
    for name in documented - own:  # each documented keyword is accepted by the function
        value = {"name": "x", "time_unit": "year", "depth_limit": 0.5}.get(name)
        if value is not None:
            kw = {"contact_type": "TUBE_ALESAGE", "instants": [1.0], "dimensions": DIMS,
                  "coefficients": {"COEF_USURE": 1e-14}, name: value}
            if function is wear_table:
                function(0.01, **kw)
            else:
                function(**kw)


def test_the_defaults_are_those_of_the_case():
    # independent: the case built with the required keywords alone holds the table's defaults
    case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0], dimensions=DIMS,
                                  coefficients={"COEF_USURE": 1e-14})
    flat = case.to_dict()
    for k in KEYWORDS.values():
        if k.default is REQUIRED or k.name in ("dimensions", "coefficients"):
            continue
        assert flat[k.name] == k.default, k.name


def test_an_unknown_keyword_is_named_with_the_closest():
    with pytest.raises(KeywordError, match=r"unknown keyword wall_thicknes .*'wall_thickness'"):
        wear_table(0.01, contact_type="TUBE_ALESAGE", instants=[1.0], dimensions=DIMS,
                   wall_thicknes=1e-3)
    with pytest.raises(KeywordError, match="missing keyword.*instants"):
        WearCase.from_keywords(contact_type="TUBE_ALESAGE")


def test_wear_table_of_a_case_with_keywords_replaced():
    case = WearCase.from_keywords(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
                                  dimensions=DIMS, coefficients={"COEF_USURE": 1e-14},
                                  time_scale=3.6e3)
    # K·P·t = 1e-14 · 0.01 · 3600 s (analytic, Archard)
    assert wear_table(0.01, case)["volume_mobile"].tolist() == [3.6e-13, 7.2e-13]
    longer = wear_table(0.01, case, instants=[4.0], wall_thickness=1e-3)
    assert longer["volume_mobile"].tolist() == [4 * 3.6e-13]
    assert "wall_fraction" in longer.columns
    with pytest.raises(KeywordError, match="unknown keyword"):
        wear_table(0.01, case, instant=[4.0])


def test_a_case_file_gives_keywords_of_the_table():
    args = case_arguments({"power": {"value_W": 0.01},
                           "geometry": {"contact_type": "TUBE_BAV", "mobile_radius_m": 0.01},
                           "time": {"instants": [1]}})
    assert set(args) == set(KEYWORDS)
    assert args == check_keywords(args)
