"""A wear power implausible for the force and speed (issue 29, point 2): Coulomb's bound.

The wear power is the mean of |Fn|·‖Vt‖ (docs/theory.md §2); its integrand bounds the friction
power: ‖Ft‖ ≤ µ·|Fn| at every sample gives mean(‖Ft‖·‖Vt‖) ≤ µ·mean(|Fn|·‖Vt‖), µ ≤ 1 for metal
on metal (docs/formats.md "Plausibility checks"). A normal force exported in kN beside tangential
forces in N breaks it by 1000·µ and gives a wear power 1000 times too small: the reader says so
(no warning before this check), and the units option it names restores the SI power (an
independent computation: the same history built in N).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from fretwear.errors import UnitsWarning
from fretwear.history import ContactHistory
from fretwear.io import read_history, write_history
from fretwear.io.plausibility import FRICTION_MAX, check_plausibility, friction_ratio
from fretwear.power import wear_power

MU = 0.3  # friction coefficient of the synthetic contact [1]


def _history(force_scale: float = 1.0) -> ContactHistory:
    """A sliding contact with ‖Ft‖ = µ·|Fn| (SI), the normal force multiplied by force_scale."""
    t = np.linspace(0.0, 0.2, 4001)
    fn = np.clip(30.0 * np.sin(2 * np.pi * 40 * t), 0.0, None)
    v1 = 0.05 * np.cos(2 * np.pi * 40 * t)
    sign = np.sign(v1)
    return ContactHistory(time=t, normal_force=fn * force_scale, vt1=v1, vt2=0 * t,
                          ft1=-MU * fn * sign, ft2=0 * t, name="friction")


def _units_warnings(function, *args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = function(*args, **kwargs)
    return result, [str(w.message) for w in caught if w.category is UnitsWarning]


def test_the_ratio_is_the_friction_coefficient():
    # sample by sample ‖Ft‖·‖Vt‖ = µ·|Fn|·‖Vt‖: the ratio is µ (to rounding)
    assert friction_ratio(_history()) == pytest.approx(MU, rel=1e-12)
    assert np.isnan(friction_ratio(_history().replace(ft1=None, ft2=None)))


def test_a_consistent_history_passes():
    _, found = _units_warnings(check_plausibility, _history())
    assert found == []


def test_a_normal_force_in_kN_beside_tangential_forces_in_N_is_warned(tmp_path):
    path = tmp_path / "kN.csv"
    write_history(_history(force_scale=1e-3), path)   # Fn in kN, Ft in N
    history, found = _units_warnings(read_history, path)
    assert friction_ratio(history) == pytest.approx(MU * 1e3, rel=1e-9)
    assert MU * 1e3 > FRICTION_MAX
    assert len(found) == 1
    assert "Coulomb" in found[0] and "'kN'" in found[0] and "normal_force = 'kN'" in found[0]
    # the fix the message names gives the SI history's power, without a warning
    fixed, found = _units_warnings(read_history, path, units={"normal_force": "kN"})
    assert found == []
    expected = wear_power(_history()).total
    assert wear_power(fixed).total == pytest.approx(expected, rel=1e-9)
    assert wear_power(history).total == pytest.approx(expected * 1e-3, rel=1e-9)
