"""A bundle's result carries the wear case of every contact (issue 25, point 3): the case the
bundle built once from the manifest, its wall validated there; the contacts' table reads it.

Expected values: the wall thickness given in the manifest (``wall_thickness_m``, 1.09 mm and
1.27 mm per contact) and the case's default depth limit 0.4 (DEFAULT_DEPTH_LIMIT)."""

from __future__ import annotations

import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.table import DEFAULT_DEPTH_LIMIT, Wall, WearCase

pytest.importorskip("xarray")

WALLS = [1.09e-3, 1.27e-3]  # [m], the manifest's wall thickness of each contact


def test_the_result_carries_each_contacts_case_and_its_wall(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 2, extra={"wall_thickness_m": WALLS})
    result = run_bundle(manifest, case, scheduler="serial")
    order = result.contacts["contact"].tolist()
    assert list(result.cases) == order
    for contact, wall in zip(order, WALLS, strict=True):
        carried = result.cases[contact]
        assert isinstance(carried, WearCase)
        assert carried.wall == Wall(wall, DEFAULT_DEPTH_LIMIT)
        row = result.contacts.set_index("contact").loc[contact]
        assert row["wall_thickness"] == carried.wall.thickness == wall
        assert row["depth_limit"] == carried.wall.limit
        assert row["time_scale"] == carried.time_scale
        # the case the table's attrs recorded (provenance) is the same case
        assert WearCase.from_dict(carried.to_dict()) == carried


def test_a_failed_contact_has_no_case(tmp_path):
    # a wall thicker than the tube (1.09 m typed for 1.09 mm) fails that contact alone,
    # refused where its case is built, once
    manifest, case = write_bundle(tmp_path, oscillator(), 2,
                                  extra={"wall_thickness_m": [1.09e-3, 1.09]})
    result = run_bundle(manifest, case, scheduler="serial")
    failed = result.errors["contact"].tolist()
    assert len(failed) == 1 and failed[0] not in result.cases
    assert "at least the tube's outer radius" in result.errors["message"].iloc[0]
    assert len(result.cases) == 1
