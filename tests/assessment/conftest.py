"""Fixtures shared by the assessment's tests."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


@pytest.fixture(scope="session")
def example_bundle_out(tmp_path_factory) -> Path:
    """The shipped examples/bundle run once (serial), its output directory."""
    from fretwear.bundle import run_bundle

    out = tmp_path_factory.mktemp("example") / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run_bundle(EXAMPLE / "manifest.csv", EXAMPLE / "bundle.toml", scheduler="serial",
                   output=out)
    return out
