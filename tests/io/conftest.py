"""Fixtures of the fretwear.io tests."""

from __future__ import annotations

import pytest
from iohelpers import analytic_history

from fretwear.history import ContactHistory


@pytest.fixture
def history() -> ContactHistory:
    return analytic_history()
