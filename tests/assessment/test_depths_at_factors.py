"""growth.depths_at_factors, the calibration's depths of every inspection at every factor,
against the depth model itself (DepthModel.depth(t, factor=f), one call per row): a tilted
TUBE_BAV bar (no power law: the shifted table's linear reading in ln is not exact), the
geometry's range passed (NaN), an unworn contact, and a model with a replacement (not
scalable: computed directly)."""

from __future__ import annotations

import warnings

import numpy as np

from fretwear.assessment.family import depths_at_factors, scalable
from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import Wall
from fretwear.table.depth import DepthModel

YEAR = 31536000.0


def _model(power, name, tilt=0.0, replacement=None):
    geometry = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3,
                                tilt_angle=tilt)
    return DepthModel(law=get_law("ARCHARD"), geometry=geometry, powers=(power,),
                      coefficients_mobile=({"coefficient": 4e-16},),
                      coefficients_obstacle=(None,), time_scale=YEAR, name=name,
                      wall=Wall(1.09e-3), replacement=replacement)


def test_the_shifted_table_reads_the_models_depths():
    tilted = [_model(p, f"t{i}", tilt=0.02) for i, p in enumerate([1e-3, 2e-3, 5e-2, 0.0])]
    models = tilted + [_model(1e-3, "flat"), _model(2e-3, "new", replacement=5 * YEAR)]
    assert [scalable(m) for m in models] == [True] * 5 + [False]
    elapsed = np.array([10.0, 30.0, 40.0, 20.0, 12.0, 30.0]) * YEAR
    factors = np.exp(np.linspace(-4.0, 6.0, 701))
    d = depths_at_factors(models, elapsed, factors)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = np.array([m.depth(np.full(factors.size, t), factor=factors, warn=False)
                        for m, t in zip(models, elapsed, strict=True)])
    finite = np.isfinite(ref)
    assert (~finite).any() and finite.any()  # the range is passed somewhere
    # NaN where the geometry's range is passed, but for the table's cell at its edge
    assert np.sum(np.isnan(d) != np.isnan(ref)) <= len(models)
    both = finite & np.isfinite(d) & (ref > 0)
    # linear in ln D between points 2e-4 apart in ln(f·t): an error of step²/8·|(ln D)''|
    np.testing.assert_allclose(d[both], ref[both], rtol=1e-7)
    np.testing.assert_array_equal(d[3], 0.0)  # no power, no wear
