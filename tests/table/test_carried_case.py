"""The wear case a table carries (issue 25, point 3): read back from ``attrs["case"]`` or from
the provenance of a file fretwear wrote, once, by ``WearCase.from_dict``; the operations on a
table take its law and geometry from it rather than from loose ``attrs`` keys.

Expected values: replace_tube's own in-memory result (same process; the file path is compared
at 1e-12 relative, its text being exact to the last digit, %.16E) and the geometry's depth of
the new tube's volume (theory §6), computed here independently.
"""

import numpy as np
import pytest

from fretwear.errors import InputError
from fretwear.geometry import contact_geometry
from fretwear.table import (
    WearCase,
    carried_case,
    models_from_table,
    read_wear_table,
    replace_tube,
    table_case,
    wear_table,
    write_wear_table,
)

YEAR = 3.15576e7
DIMS = {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3}
KW = {"contact_type": "TUBE_BAV", "instants": [2.0, 4.0, 6.0], "time_scale": YEAR,
      "dimensions": DIMS, "coefficients": {"COEF_USURE": 9.2e-15}, "wall_thickness": 1.09e-3}


@pytest.fixture(scope="module")
def table():
    return wear_table(0.01, **KW)


@pytest.mark.parametrize("suffix", ["csv", "parquet"])
def test_replace_tube_on_a_file_gets_the_geometry_from_its_case(table, suffix, tmp_path):
    """Before, a table read back had no attrs contact_type/dimensions: its new tube's depths
    after the replacement were NaN. The case in the file's provenance gives the geometry."""
    back = read_wear_table(write_wear_table(table, tmp_path / f"t.{suffix}"))
    assert carried_case(back) == WearCase.from_dict(table.attrs["case"])
    here, there = replace_tube(table, 2.0), replace_tube(back, 2.0)
    later = there["instant"] > 2.0
    assert np.isfinite(there.loc[later, "depth_mobile"]).all()
    np.testing.assert_allclose(there["depth_mobile"], here["depth_mobile"], rtol=1e-12)
    # independently: the depth of the new tube's volume, V(t) − V(2), by the geometry
    geometry = contact_geometry("TUBE_BAV", **DIMS)
    volume = table["volume_mobile"].to_numpy() - table["volume_mobile"].iloc[0]
    depth, _ = geometry.depth_from_volume(volume, np.zeros_like(volume))
    np.testing.assert_allclose(there["depth_mobile"].to_numpy()[1:], depth[1:], rtol=1e-12)


def test_replace_tube_carries_the_case_with_the_tube_replaced(table):
    new = replace_tube(table, 4.0)
    case = table_case(new)
    assert case.restart.tube_replacement == 4.0
    assert case.replace(tube_replacement=None) == table_case(table)  # nothing else changed
    assert "case" in table.attrs and table_case(table).restart.tube_replacement is None
    with pytest.raises(InputError, match="replaces the tube after its origin"):
        models_from_table(new)
    # a restart of the replaced table continues the new tube from 6 (the last instant)
    after = wear_table(0.01, **{**KW, "instants": [1.0]}, initial_state=replace_tube(table))
    model = models_from_table(after)["global"]
    assert model.origin == 6.0 and model.initial_mobile == 0.0


def test_replaced_among_a_restarts_earlier_rows_no_case_computes_the_table(table):
    restart = wear_table(0.01, **{**KW, "instants": [1.0, 2.0]}, initial_state=table)
    new = replace_tube(restart, 4.0)  # before the restart's origin, 6
    assert "case" not in new.attrs and carried_case(new) is None
    with pytest.raises(InputError, match="carries no wear case"):
        models_from_table(new)


@pytest.mark.filterwarnings("ignore::fretwear.errors.UnitsWarning")  # orbit of 1 m
def test_the_obstacle_width_of_a_file_comes_from_its_case(tmp_path):
    """Before, a table read back from its file had no attrs dimensions: width= was needed."""
    from fretwear.history import ContactHistory
    from fretwear.obstacle.profiles import CircleObstacle
    from fretwear.obstacle.update import Mobile, update_obstacle_from_table

    t = np.linspace(0.0, 1.0, 2001)  # 10 N sliding at 0.1 m/s, the angle turning once a second
    h = ContactHistory(time=t, normal_force=np.full(t.size, 10.0), vt1=np.full(t.size, 0.1),
                       vt2=np.zeros(t.size), dy=np.cos(2 * np.pi * t), dz=np.sin(2 * np.pi * t))
    dims = {"mobile_radius": 0.0048, "obstacle_radius": 0.0051, "obstacle_width": 0.011}
    sectors = wear_table(h, contact_type="TUBE_ALESAGE", dimensions=dims,
                         instants=[1.0, 2.0], sectors=[-180.0, 0.0, 180.0],
                         sector_coefficients=[(1e-13, 1e-14), (2e-13, 2e-14)],
                         time_scale=3600.0)
    back = read_wear_table(write_wear_table(sectors, tmp_path / "s.parquet"))
    obstacle, mobile = CircleObstacle(0.0048, 0.0051), Mobile(0.0048, 1e-3)
    found = update_obstacle_from_table(back, obstacle, mobile, resolution=1.0)
    given = update_obstacle_from_table(back, obstacle, mobile, resolution=1.0,
                                       width=dims["obstacle_width"])
    np.testing.assert_array_equal(found.clearance_worn, given.clearance_worn)
    bare = back.copy()
    bare.attrs = {}
    with pytest.raises(InputError, match="obstacle width is needed"):
        update_obstacle_from_table(bare, obstacle, mobile, resolution=1.0)
