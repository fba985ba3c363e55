"""A measured depth deeper than five walls is refused (a new user's trial, closing2.md: 0.5 m
typed for 0.5 mm on a 1.09 mm wall was said as THROUGH THE WALL, not questioned).

The rule (fretwear.assessment.inspections.DEPTH_WALLS_MAX): up to five walls a depth is kept
(a tube worn through reads about one wall plus its sizing error, and a campaign drawn from the
depth model reads past the wall; a unit slip is 1000x); beyond, an InputError naming the file,
the line, the column and the likely unit. Oracle: the walls and depths written in each test,
their ratio computed here.
"""

from __future__ import annotations

import re
import warnings

import pandas as pd
import pytest
import synthetic

from fretwear.assessment import LogisticPOD, SizingModel, Technique, calibrate_bundle
from fretwear.assessment.inspections import DEPTH_WALLS_MAX, read_field_inspections
from fretwear.assessment.outage import assess
from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import Wall
from fretwear.table.depth import DepthModel

WALL = 1.09e-3
TECH = Technique(SizingModel(0.0, 1.0, 5e-5), LogisticPOD.from_depths(1.5e-4, 3e-4))


def _flat(text: str) -> str:
    return " ".join(text.split())


def _csv(tmp_path, text):
    path = tmp_path / "campaign.csv"
    path.write_text(text, encoding="utf-8")
    return path


def test_metres_for_mm_with_the_wall_in_the_file_is_refused(tmp_path):
    path = _csv(tmp_path, "contact,instant,depth,wall_thickness\n"
                          "a,10,3e-4,1.09e-3\n"
                          "b,10,0.5,1.09e-3\n")
    with pytest.raises(InputError) as err:
        read_field_inspections(path)
    text = _flat(str(err.value))
    assert "campaign.csv" in text and "line 3" in text and "depth = 0.5 [m]" in text
    assert f"{0.5 / WALL:.3g} walls of 1.09 mm" in text  # 459
    assert "a value in mm? (0.5 mm is 0.0005 m; or give the column depth_mm)" in text


def test_micrometres_for_mm_is_refused_and_five_walls_are_kept(tmp_path):
    path = _csv(tmp_path, "contact,instant,depth_mm,wall_thickness\nb,10,300,1.09e-3\n")
    with pytest.raises(InputError, match=re.escape("a value in µm? (300 µm is 0.3 mm)")):
        read_field_inspections(path)
    assert DEPTH_WALLS_MAX == 5.0
    at_most = 5 * WALL * 1e3  # 5.45 mm: past the wall, kept
    path = _csv(tmp_path, f"contact,instant,depth_mm,wall_thickness\n"
                          f"a,10,{at_most:.6g},1.09e-3\nb,10,1.5,1.09e-3\n")
    table = read_field_inspections(path).table
    assert table["status"].tolist() == ["sized", "sized"]
    assert table["depth"].tolist() == pytest.approx([5 * WALL, 1.5e-3], rel=1e-12)
    path = _csv(tmp_path, "contact,instant,depth_mm,wall_thickness\na,10,5.46,1.09e-3\n")
    with pytest.raises(InputError, match="is 5.01 walls of 1.09 mm"):
        read_field_inspections(path)  # 5.46 / 1.09 = 5.009


def _model(name: str) -> DepthModel:
    return DepthModel(law=get_law("ARCHARD"),
                      geometry=contact_geometry("TUBE_BAV", mobile_radius=9.525e-3,
                                                obstacle_width=12.7e-3),
                      powers=(5e-3,), coefficients_mobile=({"coefficient": 1e-14},),
                      coefficients_obstacle=(None,), time_scale=31536000.0, name=name,
                      wall=Wall(WALL))


def test_calibrate_bundle_checks_the_contacts_walls(tmp_path):
    """No wall in the file: the contacts' own walls (the predictions') are used."""
    path = _csv(tmp_path, "contact,instant,depth\nA,10,2e-4\nB,10,0.3\n")
    models = {"A": _model("A"), "B": _model("B")}
    with pytest.raises(InputError) as err:
        calibrate_bundle(models, path, techniques=TECH)
    text = _flat(str(err.value))
    assert "campaign.csv" in text and "line 3" in text and "depth = 0.3 [m]" in text
    assert "a value in mm? (0.3 mm is 0.0003 m" in text


def test_assess_checks_the_bundles_walls(tmp_path):
    powers = [0.02, 0.05]
    insp = pd.DataFrame({"tube_row": [1, 1], "tube_column": [1, 2], "instant": [10.0, 10.0],
                         "depth_mm": [0.3, 450.0]})
    with pytest.raises(InputError) as err, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assess(synthetic.bundle(powers), insp, interval=2.0, sizing=TECH.sizing, pod=TECH.pod)
    text = _flat(str(err.value))
    assert "line 2" in text and "depth_mm = 450 [mm]" in text
    assert f"{0.45 / synthetic.WALL:.3g} walls" in text and "a value in µm?" in text
