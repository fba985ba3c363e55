"""The shipped example bundle (examples/bundle): small, complete, and physically sensible.

It is the output of ``fretwear simulate examples/bundle/bundle_geometry.toml -o examples/bundle``
(docs/flow.md §5); tests/flow/test_simulated_example.py checks the stability side.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from fretwear.bundle import read_manifest, run_bundle
from fretwear.flow.bundle import run_simulate
from fretwear.flow.description import read_description
from fretwear.io import read_history

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


def test_shipped_example_is_small_and_complete():
    size = sum(p.stat().st_size for p in EXAMPLE.rglob("*") if p.is_file())
    assert size < 5e6
    manifest = read_manifest(EXAMPLE / "manifest.csv")
    assert len(manifest) == 24
    assert all(Path(r.history.path).is_file() for r in manifest.rows)


def test_example_runs_and_wear_grows_toward_the_u_bend_rows():
    result = run_bundle(EXAMPLE / "manifest.csv", EXAMPLE / "bundle.toml", scheduler="serial")
    assert result.errors.empty
    # the only warning: the example's impacts last about one archived sample (its archive step
    # keeps it under 5 MB; bundle_geometry.toml says so), said for every contact with impacts
    assert set(result.warnings["category"]) == {"ResolutionWarning"}, result.warnings
    assert result.warnings["message"].str.contains("samples on average").all()
    s = result.summary()
    # the SPEC_LONG_COR_1 force spectrum grows as ρ²Ū³ at a reduced frequency, and the velocity
    # grows toward the outer rows: the median wear power of a row's contacts grows with the row
    by_row = s.groupby("tube_row")["power"].median()
    assert (np.diff(by_row.to_numpy()) > 0).all(), by_row
    # the gaps written are those the description draws (its seeded lognormal), contact by contact
    gaps = pd.read_csv(EXAMPLE / "gaps.csv").set_index("contact")["gap_m"]
    drawn = {f"{spec.tube}-{sup['name']}": sup["gap_m"]
             for spec in read_description(EXAMPLE / "bundle_geometry.toml")
             for sup in spec.supports}
    assert sorted(gaps.index) == sorted(drawn)
    np.testing.assert_allclose(gaps[list(drawn)], list(drawn.values()),
                               rtol=1e-5)  # written with 6 digits


def test_simulate_rebuilds_the_shipped_histories(tmp_path):
    """Same description, same seed, same first tube: fretwear simulate writes R1C1's shipped
    histories again (bit for bit on the machine that wrote them; another CPU's rounding,
    amplified by the rattling, may move them: compared at a tolerance of the motion)."""
    spec = read_description(EXAMPLE / "bundle_geometry.toml")[0]
    result = run_simulate([spec], tmp_path, scheduler="serial")
    assert not result.errors and result.manifest()["contact"].tolist() == ["R1C1-AVB1",
                                                                           "R1C1-AVB2"]
    for history in result.manifest()["history"]:
        new, shipped = read_history(tmp_path / history), read_history(EXAMPLE / history)
        scale = np.max(np.abs(shipped.dy))
        np.testing.assert_allclose(new.time, shipped.time, rtol=1e-12)
        np.testing.assert_allclose(new.dy, shipped.dy, atol=0.05 * scale)
