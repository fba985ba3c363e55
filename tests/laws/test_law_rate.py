"""WearLaw.rate: the worn volume per second of a law linear in time, V(P, 1 s).

Independent computation: the law's own volume after one second, :meth:`WearLaw.volume` (the
law function with its checks), on the same inputs: the same values bit for bit (one
process); and the analytic rates K·P (Archard) and k_r·w/w_r·P (KWU-EPRI, theory §4) at 1e-15
relative. Inputs the fast path does not take (arrays of coefficients, a zero coefficient)
give the same values through the law function; bad inputs its InputError naming them.
"""

from __future__ import annotations

import numpy as np
import pytest

from fretwear.errors import InputError, KeywordError
from fretwear.laws import WEAR_LAWS

POWERS = np.array([0.0, 1e-4, 0.0123, 0.5, 7.0])
CASES = [("ARCHARD", {"coefficient": 1.3e-15}, lambda p: 1.3e-15 * p),
         ("ARCHARD", {"COEF_USURE": 2e-14}, lambda p: 2e-14 * p),
         ("KWU_EPRI", {"reference_coefficient": 5.2e-14, "intensity": 0.37,
                       "reference_intensity": 2.0}, lambda p: 5.2e-14 * 0.37 / 2.0 * p)]


@pytest.mark.parametrize("name, coefficients, analytic", CASES)
def test_rate_is_the_volume_after_one_second(name, coefficients, analytic):
    law = WEAR_LAWS[name]
    rate = law.rate(POWERS, **coefficients)
    assert np.array_equal(rate, law.volume(POWERS, 1.0, **coefficients))
    np.testing.assert_allclose(rate, analytic(POWERS), rtol=1e-15, atol=0.0)
    for p in POWERS:  # one power at a time
        assert float(law.rate(float(p), **coefficients)) == float(law.volume(float(p), 1.0,
                                                                              **coefficients))


def test_other_inputs_take_the_law_function():
    law = WEAR_LAWS["ARCHARD"]
    k = np.array([1e-15, 0.0, 3e-15, 1e-15, 2e-15])
    assert np.array_equal(law.rate(POWERS, coefficient=k), law.volume(POWERS, 1.0, coefficient=k))
    assert float(law.rate(0.1, coefficient=0.0)) == 0.0


@pytest.mark.parametrize("power, coefficients, error, culprit", [
    (-1.0, {"coefficient": 1e-15}, InputError, "power"),
    (np.array([0.1, np.nan]), {"coefficient": 1e-15}, InputError, "power"),
    (0.1, {"coefficient": -1e-15}, InputError, "coefficient"),
    (0.1, {}, KeywordError, "coefficient")])
def test_bad_inputs_name_the_culprit(power, coefficients, error, culprit):
    with pytest.raises(error, match=culprit):
        WEAR_LAWS["ARCHARD"].rate(power, **coefficients)


def test_a_law_not_linear_in_time_has_its_volume_after_one_second():
    law = WEAR_LAWS["EDF_MZ"]
    assert float(law.rate(0.01)) == float(law.volume(0.01, 1.0))
