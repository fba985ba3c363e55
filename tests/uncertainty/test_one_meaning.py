"""One meaning per word in the uncertainty API (issue 29, point 3): a scatter or a factor is
relative to the nominal, an absolute power distribution is ``power=``, and ``factor=`` with
``coefficients=`` is refused rather than compounded silently.

Reference values: the quantiles of a lognormal, median·exp(σ·Φ⁻¹(q)), and Archard's depth
through the geometry being monotone in the power (theory §4-5): the median depth is the depth
at the median power.
"""

from __future__ import annotations

import numpy as np
import pytest

from fretwear.errors import InputError
from fretwear.uncertainty import LogNormal, monte_carlo

CASE = {"law": "ARCHARD", "coefficients": {"COEF_USURE": 1e-14}, "contact_type": "TUBE_BAV",
        "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
        "instants": [1.0, 10.0], "time_scale": 31_536_000.0, "wall_thickness": 1.09e-3}
NOMINAL = 0.01  # [W]


def _median_depth(result) -> np.ndarray:
    return result.quantiles([0.5])[0.5].to_numpy(dtype=float)  # [m], one per instant


def test_relative_scatter_and_absolute_power_agree():
    """power_scatter=LogNormal(σ) on a nominal of 0.01 W and power=LogNormal(0.01 W, σ) are the
    same distribution of the power: the same samples, the same depths."""
    relative = monte_carlo(CASE, NOMINAL, power_scatter=LogNormal(sigma_ln=0.2), samples=1024,
                           seed=1)
    absolute = monte_carlo(CASE, LogNormal(NOMINAL, sigma_ln=0.2), samples=1024, seed=1)
    explicit = monte_carlo(CASE, NOMINAL, power_scatter=LogNormal(1.0, sigma_ln=0.2),
                           samples=1024, seed=1)
    np.testing.assert_allclose(_median_depth(relative), _median_depth(absolute), rtol=1e-12)
    np.testing.assert_allclose(_median_depth(relative), _median_depth(explicit), rtol=1e-12)
    from fretwear.table import wear_table

    nominal = wear_table(NOMINAL, **CASE)["depth_mobile"].to_numpy(dtype=float)
    # the median of the power is the nominal, and the depth is monotone in it: the median
    # depth is the nominal depth (to the sampling of the median, 1024 points)
    np.testing.assert_allclose(_median_depth(relative), nominal, rtol=2e-2)


def test_a_power_in_watts_given_as_a_scatter_is_refused():
    """The issue's trap: LogNormal(1.0, ...) read as 1 W (100 × the nominal) gave a NaN median
    and P = 1; now 1.0 is ×1, and a median that looks like watts is refused with the fix."""
    with pytest.raises(InputError, match=r"power=LogNormal\(0.01"):
        monte_carlo(CASE, NOMINAL, power_scatter=LogNormal(0.01, sigma_ln=0.2), samples=16)


def test_factor_with_coefficients_is_refused():
    with pytest.raises(InputError, match="compound"):
        monte_carlo(CASE, NOMINAL, factor=LogNormal(sigma_ln=0.3),
                    coefficients={"COEF_USURE": LogNormal(sigma_ln=0.5)}, samples=16)


def test_power_distribution_and_scatter_together_are_refused():
    with pytest.raises(InputError, match="compound"):
        monte_carlo(CASE, LogNormal(NOMINAL, sigma_ln=0.2),
                    power_scatter=LogNormal(sigma_ln=0.1), samples=16)


def test_a_power_distribution_needs_its_median():
    with pytest.raises(InputError, match="needs its median"):
        monte_carlo(CASE, LogNormal(sigma_ln=0.2), samples=16)
