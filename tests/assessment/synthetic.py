"""A synthetic bundle for the assessment's tests: ``n`` contacts of uniform wear (TUBE_ALESAGE,
Archard), whose depth is linear in the worn volume, V = 2π·l·R·d, so that the time to a
depth is a closed form, τ(d) = 2π·l·R·d/(K·P) (docs/theory.md, TUBE_ALESAGE)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd

R, L_W, K, YEAR, WALL = 0.01, 0.02, 1e-14, 3.15e7, 1.1e-3


def tau(depth, power):
    """Nominal time to ``depth`` [m] at ``power`` [W], in years (the closed form)."""
    return 2 * math.pi * L_W * R * np.asarray(depth) / (K * power) / YEAR


def bundle(powers, tubes=None, last=10.0):
    """One contact per power [W] on its own tube (or the ``tubes`` given: (row, column))."""
    n = len(powers)
    tubes = tubes or [(1, k + 1) for k in range(n)]
    contacts = pd.DataFrame({
        "contact": [f"c{k}" for k in range(n)], "tube_row": [t[0] for t in tubes],
        "tube_column": [t[1] for t in tubes], "support": "TSP", "status": "done",
        "power": list(powers), "time_unit": "year", "origin": 0.0, "wall_thickness": WALL,
        "depth_limit": 0.4, "contact_type": "TUBE_ALESAGE",
        "dimensions": [{"mobile_radius": R, "obstacle_width": L_W}] * n, "law": "ARCHARD",
        "coefficients_mobile": [{"coefficient": K}] * n, "coefficients_obstacle": None,
        "time_scale": YEAR})
    depth = [last * YEAR * K * p / (2 * math.pi * L_W * R) for p in powers]
    table = pd.DataFrame({"contact": contacts["contact"], "instant": last,
                          "depth_mobile": depth})
    return SimpleNamespace(contacts=contacts, table=table, output=None)
