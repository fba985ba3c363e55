"""The README's POST_USURE example runs as written on the shipped file and gives Archard's
V = K·P·t (theory §4), with P computed independently by wear_power from the same file and the
TUBE_BAV depth of theory §6."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np

from fretwear.geometry import contact_geometry
from fretwear.io import read_history
from fretwear.power import wear_power

ROOT = Path(__file__).resolve().parents[2]


def test_readme_post_usure_example(monkeypatch):
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    code = next(m.group(1) for m in re.finditer(r"^```python\n(.*?)^```$", text, re.S | re.M)
                if "POST_USURE" in m.group(1))
    monkeypatch.chdir(ROOT)
    namespace: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the example runs cleanly
        exec(compile(code, "README.md", "exec"), namespace)  # noqa: S102 - the README's code
    tab = namespace["tab"]
    power = wear_power(read_history(ROOT / "examples" / "data" / "shock_N12.tab",
                                    node="N12")).total
    volume = 1.2e-13 * power * 31_536_000.0 * np.array([1.0, 5.0])
    np.testing.assert_allclose(tab["PUIS_USUR_GLOBAL"], power, rtol=1e-14)
    np.testing.assert_allclose(tab["V_USUR_TUBE"], volume, rtol=1e-14)
    bav = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)
    np.testing.assert_allclose(tab["P_USUR_TUBE"], bav.depth_from_volume(volume)[0], rtol=1e-12)
