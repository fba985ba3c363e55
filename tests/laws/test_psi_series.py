"""EDF_MZ's ψ₂(x) = (x − 1 + e^(−x))/x (fretwear.laws.models._psi2): its Taylor series compiled
(numba) against the numpy loop bit for bit, and both against the closed form with math.expm1
(ψ₂ = (x + expm1(−x))/x, accurate where x is not tiny) and ψ₂ ≈ x/2 − x²/6 + x³/24 (tiny x)."""

import math

import numpy as np
import pytest

from fretwear._numba import HAVE_NUMBA
from fretwear.laws import models


def _cases():
    rng = np.random.default_rng(3)
    return [rng.random(500) * 0.6, np.geomspace(1e-300, 0.5, 2000),
            np.array([0.0, -0.0, 0.49999999, 0.5, 1e-17, 3.0]), np.array(0.2), np.zeros(0),
            rng.random((3, 4)) * 0.5]


@pytest.mark.skipif(not HAVE_NUMBA, reason="the compiled series needs numba (extra 'fast')")
def test_compiled_series_is_the_numpy_series_bit_for_bit(monkeypatch):
    compiled = [models._psi2(x) for x in _cases()]
    assert models._psi2_series_kernel() is not None
    monkeypatch.setattr(models, "_psi2_series_kernel", lambda: None)  # numpy path
    plain = [models._psi2(x) for x in _cases()]
    for a, b in zip(compiled, plain, strict=True):
        assert a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a, b)


def test_psi2_against_its_closed_form():
    x = np.array([1e-3, 0.01, 0.1, 0.3, 0.49, 0.7, 2.0])
    expected = [(v + math.expm1(-v)) / v for v in x]
    assert models._psi2(x) == pytest.approx(expected, rel=1e-12)
    tiny = np.array([1e-12, 1e-8])
    assert models._psi2(tiny) == pytest.approx(tiny / 2 - tiny**2 / 6 + tiny**3 / 24,
                                               rel=1e-15)
