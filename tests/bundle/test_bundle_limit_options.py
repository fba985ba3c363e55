"""The depth limit of a bundle's summary given one way only, and carried to the output files:
``summary(limit, limit_m=...)`` refuses both at once, and ``run_bundle(limit=...)`` (the
command's ``--limit``) writes ``summary.csv`` at that limit and records it in ``run.json``.

Expected values: the limit depth is the fraction times the wall thickness the manifest gives
(``limit_depth = limit × wall_thickness_m``, the definition in docs/bundle.md), and the file
holds what ``BundleResult.summary(limit)`` returns for the same contacts."""

from __future__ import annotations

import numpy as np
import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.errors import KeywordError

pytest.importorskip("xarray")

WALL = 1.09e-3  # [m], the manifest's wall thickness of every tube below


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    """A manifest of 2 contacts (bundle_helpers: 0.6 s of the shipped oscillator history, the
    force scaled per contact) with a wall of 1.09 mm, and its base case."""
    directory = tmp_path_factory.mktemp("limit")
    manifest, case = write_bundle(directory, oscillator(), 2,
                                  extra={"wall_thickness_m": [WALL, WALL]})
    return manifest, case


def test_summary_refuses_a_fraction_and_a_depth_together(bundle):
    manifest, case = bundle
    result = run_bundle(manifest, case, scheduler="serial")
    with pytest.raises(KeywordError) as raised:
        result.summary(0.4, limit_m=1e-3)
    message = str(raised.value)
    assert "limit" in message and "limit_m" in message and "one" in message
    # each alone still works: 0.4 × 1.09 mm, and 1 mm as given
    assert np.allclose(result.summary(0.4)["limit_depth"], 0.4 * WALL, rtol=1e-15)
    assert (result.summary(limit_m=1e-3)["limit_depth"] == 1e-3).all()
