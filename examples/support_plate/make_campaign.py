"""Write the support-plate example's manifest and its inspection campaign (seeded): rerun it
and the files come out the same.

* ``manifest.csv``: 12 tubes (rows 1-3, columns 1-4), one contact each at the third support
  plate (TSP3), wall 1.09 mm, a wear power [W] drawn log-normal about 2 mW (σ_ln 0.5) and
  rising with the row (the flow is faster up the bundle), as a simulation would give it;
* ``campaign.csv``: the outage at 10 years, 8 of the 12 tubes inspected, every one sized
  (``depth_mm``; the 4 others ``inspected = no``): the true depth at a bundle factor of 2.5
  (the pair wears 2.5 times faster than the database coefficient says), each contact's own
  factor about it (σ_ln 0.35) and its true power about the manifest's (σ_ln 0.2), measured
  with a log-normal sizing error (σ_ln 0.1): the model ``fretwear calibrate --bundle``
  assumes with its defaults;
* ``campaign_truth.csv``: each contact's true factor, power and depth (never read by fretwear).

Depth of uniform wear in a drilled hole (TUBE_ALESAGE, no bore radius): the worn volume
V = K·P·t (Archard, K [Pa⁻¹], P [W], t [s]) spread over the hole's surface 2π·l·R, so
d = f·K·P·t/(2π·l·R) [m] (docs/theory.md).

Run: python examples/support_plate/make_campaign.py
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
SEED = 20261128
K = 5.2e-14                 # Pa⁻¹, TUBE_ALESAGE I690 on I600 (POST_USURE theory note §3)
R, L = 9.525e-3, 20e-3      # m: tube radius, plate thickness
WALL = 1.09e-3              # m
YEAR = 31_536_000.0         # s (fretwear's year, 365 days)
OUTAGE = 10.0               # years
TRUE_FACTOR, CONTACT_SIGMA, POWER_SIGMA, SIZING_SIGMA = 2.5, 0.35, 0.2, 0.1
INSPECTED = ["R1C1", "R1C3", "R2C1", "R2C2", "R2C4", "R3C1", "R3C2", "R3C4"]


def depth(factor, power, years):
    """Uniform depth [m] of a tube in a drilled hole after ``years`` at ``power`` [W]."""
    return factor * K * power * years * YEAR / (2 * math.pi * L * R)


def main() -> None:
    rng = np.random.default_rng(SEED)
    tubes = [(r, c) for r in (1, 2, 3) for c in (1, 2, 3, 4)]
    power = np.array([2e-3 * (0.7 + 0.3 * r) for r, _ in tubes]) * np.exp(
        0.5 * rng.standard_normal(len(tubes)))
    names = [f"R{r}C{c}" for r, c in tubes]
    manifest = pd.DataFrame({"contact": [f"{n}-TSP3" for n in names],
                             "tube_row": [r for r, _ in tubes],
                             "tube_column": [c for _, c in tubes], "support": "TSP3",
                             "wall_thickness_m": WALL,
                             "power.value_W": [float(f"{p:.4g}") for p in power]})
    manifest.to_csv(HERE / "manifest.csv", index=False)

    factor = TRUE_FACTOR * np.exp(CONTACT_SIGMA * rng.standard_normal(len(tubes)))
    true_power = manifest["power.value_W"].to_numpy() * np.exp(
        POWER_SIGMA * rng.standard_normal(len(tubes)))
    true_depth = depth(factor, true_power, OUTAGE)
    measured = true_depth * np.exp(SIZING_SIGMA * rng.standard_normal(len(tubes)))
    pd.DataFrame({"tube": names, "true_factor": factor.round(4),
                  "true_power_W": [float(f"{p:.4g}") for p in true_power],
                  "true_depth_mm": (true_depth * 1e3).round(4)}).to_csv(
        HERE / "campaign_truth.csv", index=False)
    inspected = [n in INSPECTED for n in names]
    pd.DataFrame({"tube_row": manifest["tube_row"], "tube_column": manifest["tube_column"],
                  "support": "TSP3", "instant": OUTAGE,
                  "inspected": ["yes" if i else "no" for i in inspected],
                  "depth_mm": [f"{m * 1e3:.3f}" if i else "" for m, i in
                               zip(measured, inspected, strict=True)]}).to_csv(
        HERE / "campaign.csv", index=False)


if __name__ == "__main__":
    main()
