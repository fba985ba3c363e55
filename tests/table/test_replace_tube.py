"""TUBE_NEUF before the last instant (fretwear.table.replace_tube): the later rows are kept, the
tube restarted from zero at the replacement (theory §7).

Independent values: Archard V_j = k_j·P_j·t (theory §3, §4) with the sector powers of the run,
sector depths by theory §3's formula (geometry.sector_depth_mobile), and Code_Aster's behaviour
(``bibfor/prepost/motubn.F90``: later rows kept, tube values zeroed) for comparison.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from fretwear import ContactHistory
from fretwear.errors import InputError
from fretwear.geometry import sector_depth_mobile
from fretwear.table import replace_tube, to_aster_names, wear_table

HOUR = 3600.0


def _history():
    # contact sliding at 0.1 m/s with 10 N, the angle turning once a second: P = 1 W spread
    # over the angle (half in each of the sectors -180..0, 0..180)
    t = np.linspace(0.0, 1.0, 2001)
    return ContactHistory(time=t, normal_force=np.full(t.size, 10.0), vt1=np.full(t.size, 0.1),
                          vt2=np.zeros(t.size), dy=np.cos(2 * np.pi * t),
                          dz=np.sin(2 * np.pi * t))


def _sector_table():
    return wear_table(_history(), contact_type="TUBE_ALESAGE",
                      dimensions={"mobile_radius": 0.0048, "obstacle_radius": 0.0051,
                                  "obstacle_width": 0.011},
                      instants=[1.0, 2.0, 3.0], sectors=[-180.0, 0.0, 180.0],
                      sector_coefficients=[(1e-13, 1e-14), (2e-13, 2e-14)], time_scale=HOUR)


def test_sector_table_restarted_at_an_inner_instant():
    old = _sector_table()
    new = replace_tube(old, 2.0)
    assert len(new) == len(old) and new["instant"].tolist() == old["instant"].tolist()
    powers = old.loc[old["instant"] == 1.0, "sector_power"].to_numpy()
    k = np.array([1e-13, 2e-13])
    last = new[new["instant"] == 3.0].sort_values("sector")
    # the new tube, in place since 2 h, has worn k_j·P_j·1 h in sector j
    np.testing.assert_allclose(last["volume_mobile_cumulated"], k * powers * HOUR, rtol=1e-12)
    np.testing.assert_allclose(last["volume_mobile_sector"], k * powers * HOUR, rtol=1e-12)
    np.testing.assert_allclose(last["volume_mobile"], (k * powers).sum() * HOUR, rtol=1e-12)
    np.testing.assert_allclose(last["depth_mobile_sector"],
                               sector_depth_mobile(k * powers * HOUR, 0.0048, 0.011, 180.0),
                               rtol=1e-12)
    at = new[new["instant"] == 2.0]
    assert (at["volume_mobile_cumulated"] == 0.0).all() and (at["depth_mobile"] == 0.0).all()
    # the obstacle is kept, the rows before unchanged, the user's table untouched
    assert new["volume_obstacle_cumulated"].tolist() == old["volume_obstacle_cumulated"].tolist()
    first = new["instant"] == 1.0
    pd.testing.assert_frame_equal(new[first], old[first])
    assert old["volume_mobile_cumulated"].iloc[-1] > 3 * 1e-13 * powers.min() * HOUR
    assert new.attrs["tube_replacement"] == 2.0


def test_code_aster_table_without_geometry_and_its_names():
    old = to_aster_names(_sector_table())
    old.attrs = {}  # as read from Code_Aster's text file: no geometry
    new = replace_tube(old, 2.0)
    assert "V_USUR_TUBE_CUMU" in new.columns  # Code_Aster names in, Code_Aster names out
    later = new["INST"] == 3.0
    assert new.loc[later, "V_USUR_TUBE_CUMU"].gt(0).all()
    assert new.loc[later, "P_USUR_TUBE_SECT"].isna().all()
    assert (new.loc[new["INST"] == 2.0, "P_USUR_TUBE_SECT"] == 0.0).all()
    assert "no geometry" in new.attrs["tube_replacement_depths"]


def test_a_law_not_linear_in_time_is_refused_before_the_last_instant():
    t = wear_table(0.01, contact_type="TUBE_BAV", law="EDF_MZ",
                   dimensions={"mobile_radius": 0.0111, "obstacle_width": 0.0127},
                   instants=[1.0, 2.0], time_scale=3.1536e7)
    with pytest.raises(InputError, match=r"LOI_USURE='EDF_MZ'.*tube_replacement="):
        replace_tube(t, 1.0)
    assert replace_tube(t)["volume_mobile"].iloc[-1] == 0.0  # at the last instant: fine
