"""Build the example tube bundle: 24 contact histories from fretwear's own dynamics, a manifest.

Model (an illustration of the orders of magnitude of steam-generator tubes, not a qualified
case):

* **Tubes**: 12 tubes of the U-bend region, rows 1-4 × columns 1-3 of the tube sheet, each a
  span of Inconel 690 tube (OD 19.05 mm, wall 1.09 mm: I = π/4 (R⁴ − r⁴) = 2.489e-9 m⁴;
  0.87 kg/m with the water inside and the added mass) 1.2 m long, clamped at both ends,
  4 bending modes per plane, 2 % modal damping (:func:`fretwear.dynamics.uniform_beam_modes`).
* **Anti-vibration bars**: two per tube, at 0.4 m and 0.8 m (``AVB1``, ``AVB2``): a pair of
  flat bars on either side of the tube, normal to y (:class:`fretwear.dynamics.Shock`,
  ``two_planes``), contact stiffness 1e7 N/m, damping 50 N·s/m, friction 0.3. The gap of each
  contact is drawn from a seeded lognormal distribution (median 40 µm, σ_ln = 0.6: a few
  tight, a few loose supports), the manufacturing scatter that makes some supports wear and
  others not.
* **Cross-flow**: random forces along y (out of plane) and z (in plane: the sliding direction
  along the bar) at the span's quarter points, band 5-200 Hz (:class:`fretwear.dynamics.Signal`
  ``random``, seeded per tube). The two-phase flow velocity grows toward the outer U-bend rows,
  and the turbulent force PSD grows as the dynamic pressure squared, V⁴: the PSD of row r is
  S₀·(V_r/V₁)⁴ with V_r/V₁ = 1 + 0.25 (r − 1).
* 0.7 s simulated per tube, archived every 0.5 ms (1 401 samples per contact); the wear case
  (``bundle.toml``) drops the first 0.2 s (start-up transient).

Writes ``histories/R<row>C<col>_AVB<k>.parquet`` (one per contact), ``manifest.csv`` (contact,
history, tube_row, tube_column, support, wall_thickness_m) and ``gaps.csv`` (the gap drawn for
each contact, for reference: the wear case does not use it). Then::

    fretwear bundle examples/bundle/manifest.csv --case examples/bundle/bundle.toml \\
        -o build/bundle --plot build/bundle/figures

Usage::

    python examples/bundle/make_bundle.py [--output DIR] [--seed 2026]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.dynamics import NodalForce, Shock, Signal, simulate, uniform_beam_modes
from fretwear.io import write_history

ROWS, COLUMNS = 4, 3
SUPPORTS = {"AVB1": 0.4, "AVB2": 0.8}      # [m] positions of the anti-vibration bars
WALL = 1.09e-3                             # [m] tube wall thickness
BEAM = dict(young_modulus=2.0e11, second_moment=2.489e-9, mass_per_length=0.87, length=1.2,
            n_modes=4, ends=("clamped", "clamped"), damping_ratio=0.02)
FORCING = (0.3, 0.9)                       # [m] forcing points
PSD_ROW1 = 0.004                           # [N²/Hz] force PSD of row 1, per direction
BAND = (5.0, 200.0)                        # [Hz]
GAP_MEDIAN, GAP_SIGMA_LN = 40e-6, 0.6      # [m], [-]
DURATION, ARCHIVE = 0.7, 5e-4              # [s]


def velocity_ratio(row: int) -> float:
    """Cross-flow velocity of a row relative to row 1 [-] (grows toward the outer U-bends)."""
    return 1.0 + 0.25 * (row - 1)


def tube_histories(row: int, column: int, gaps: dict[str, float], seed: int):
    """The contact histories of one tube (one per anti-vibration bar)."""
    model = uniform_beam_modes(**BEAM, shock_positions=list(SUPPORTS.values()),
                               shock_names=list(SUPPORTS), forcing_positions=list(FORCING))
    shocks = [Shock(point=name, obstacle="two_planes", gap=gaps[name], angle=0.0,
                    normal_stiffness=1e7, normal_damping=50.0, tangential_stiffness=1e7,
                    tangential_damping=50.0, friction=0.3, name=name) for name in SUPPORTS]
    psd = PSD_ROW1 * velocity_ratio(row) ** 4
    forces = [NodalForce(p, direction, Signal("random", psd_frequencies=list(BAND),
                                              psd=[psd, psd], duration=DURATION + 0.1,
                                              seed=seed + 10 * p + d))
              for p in range(len(FORCING)) for d, direction in enumerate(("y", "z"))]
    result = simulate(model, shocks, forces, duration=DURATION, archive_step=ARCHIVE)
    return {name: result.history(name) for name in SUPPORTS}


def build(output: Path, seed: int = 2026) -> pd.DataFrame:
    """Write the histories, the manifest and the gaps into ``output``; returns the manifest."""
    rng = np.random.default_rng(seed)
    (output / "histories").mkdir(parents=True, exist_ok=True)
    rows, gaps = [], []
    for row in range(1, ROWS + 1):
        for column in range(1, COLUMNS + 1):
            drawn = {name: float(GAP_MEDIAN * np.exp(GAP_SIGMA_LN * rng.standard_normal()))
                     for name in SUPPORTS}
            tube_seed = seed + 1000 * row + 100 * column
            for name, history in tube_histories(row, column, drawn, tube_seed).items():
                contact = f"R{row}C{column}-{name}"
                path = f"histories/R{row}C{column}_{name}.parquet"
                write_history(history.replace(name=contact), output / path)
                rows.append({"contact": contact, "history": path, "tube_row": row,
                             "tube_column": column, "support": name, "wall_thickness_m": WALL})
                gaps.append({"contact": contact, "gap_m": drawn[name],
                             "velocity_ratio": velocity_ratio(row)})
    manifest = pd.DataFrame(rows)
    manifest.to_csv(output / "manifest.csv", index=False)
    pd.DataFrame(gaps).to_csv(output / "gaps.csv", index=False, float_format="%.6g")
    return manifest


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", type=Path, default=Path(__file__).resolve().parent,
                        help="directory of the manifest and histories (default: this one)")
    parser.add_argument("--seed", type=int, default=2026, help="seed of gaps and forces")
    args = parser.parse_args(argv)
    manifest = build(args.output, args.seed)
    print(f"{len(manifest)} contacts written to {args.output / 'manifest.csv'}")


if __name__ == "__main__":
    main()
