"""A sector's CONTACT does not change its depth (docs/code_aster.md §7, theory §3): the old
catalogue's ``SECTEUR=_F(CONTACT='TUBE_BAV', ...)`` with RAYON_OBST gives the obstacle sector
depths that the same call without CONTACT gives. A new user's trial found the P_USUR_OBST_SECT
column dropped and two contradictory warnings ("RAYON_OBST: ignored", then "TUBE_BAV has no
obstacle_radius (RAYON_OBST)")."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from fretwear.geometry.sectors import sector_depth_obstacle
from fretwear.workflows.aster import _F, POST_USURE

DATA = Path(__file__).resolve().parents[2] / "examples" / "data" / "shock_N12.tab"
CALL = dict(RESU_GENE=str(DATA), NOEUD="N12", LOI_USURE="ARCHARD", RAYON_MOBILE=9.525e-3,
            RAYON_OBST=9.75e-3, LARGEUR_OBST=20e-3, INST=(1.0, 5.0), COEF_INST=31536000.0)


def sectors(contact=None):
    extra = {"CONTACT": contact} if contact else {}
    return tuple(_F(**extra, ANGL_INIT=a, ANGL_FIN=a + 90.0, COEF_USUR_MOBILE=1e-13,
                    COEF_USUR_OBST=1e-13) for a in (-180.0, -90.0, 0.0, 90.0))


@pytest.mark.filterwarnings("ignore::fretwear.errors.ResolutionWarning")
def test_a_sector_contact_keeps_the_obstacle_sector_depths():
    plain = POST_USURE(SECTEUR=sectors(), **CALL)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)  # no "RAYON_OBST: ignored", no NaN depth
        bav = POST_USURE(SECTEUR=sectors("TUBE_BAV"), **CALL)
    for column in ("V_USUR_OBST_SECT", "P_USUR_OBST_SECT", "P_USUR_TUBE_SECT"):
        np.testing.assert_allclose(bav[column], plain[column], rtol=1e-14, atol=0)
    # the sector depth of the obstacle is theory §3's, from the bore radius given
    expected = sector_depth_obstacle(bav["V_USUR_OBST_SECT"].to_numpy(), 9.75e-3, 20e-3, 90.0)
    np.testing.assert_allclose(bav["P_USUR_OBST_SECT"], expected, rtol=1e-12)
    assert np.all(bav["P_USUR_OBST_SECT"] > 0)
    # and the global depths are TUBE_BAV's (the contact type the sectors name)
    assert np.isfinite(bav["P_USUR_TUBE"]).all() and plain["P_USUR_TUBE"].isna().all()
