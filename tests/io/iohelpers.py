"""Helpers of the fretwear.io tests (imported by name: tests/io is on sys.path)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fretwear.history import CHANNELS, ContactHistory

FIXTURES = Path(__file__).parent / "fixtures"


def analytic_history(n: int = 201, name: str = "N12") -> ContactHistory:
    """Every channel of theory §1 from closed-form signals (a contact turning at 20 Hz).

    Fn = max(0, 50 sin 2π20t) [N], vt1 = 0.1 cos 2π20t, vt2 = 0.05 sin 2π20t [m/s],
    dy = 2e-4 cos 2π20t, dz = 2e-4 sin 2π20t [m], ft = −0.3·Fn·sign(vt), vn = 0.01 sin 2π7t,
    stick = 1 where Fn > 0 and |vt1| < 0.02.
    """
    t = np.linspace(0.0, 0.1, n)
    w = 2 * np.pi * 20.0
    fn = np.maximum(0.0, 50.0 * np.sin(w * t))
    vt1, vt2 = 0.1 * np.cos(w * t), 0.05 * np.sin(w * t)
    return ContactHistory(
        time=t, normal_force=fn, vt1=vt1, vt2=vt2, ft1=-0.3 * fn * np.sign(vt1),
        ft2=-0.3 * fn * np.sign(vt2), vn=0.01 * np.sin(2 * np.pi * 7.0 * t),
        dy=2e-4 * np.cos(w * t), dz=2e-4 * np.sin(w * t),
        stick=((fn > 0) & (np.abs(vt1) < 0.02)).astype(float), name=name,
        metadata={"node": name, "case": "analytic"})


def assert_same_history(a: ContactHistory, b: ContactHistory, rtol: float = 0.0) -> None:
    assert a.channels == b.channels
    for ch in CHANNELS:
        x, y = getattr(a, ch), getattr(b, ch)
        if x is None:
            assert y is None
        elif rtol == 0.0:
            np.testing.assert_array_equal(x, y, err_msg=ch)
        else:
            np.testing.assert_allclose(y, x, rtol=rtol, atol=0, err_msg=ch)
