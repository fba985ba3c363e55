"""Shared test set-up.

The CLI prints with rich, which wraps at the terminal width (80 columns when not a terminal, as
under CI). Tests that look for a phrase or a path in the printed summary must not depend on where
a temporary path happens to wrap, so every test sees a wide terminal.
"""

import pytest


@pytest.fixture(autouse=True)
def _wide_terminal(monkeypatch):
    monkeypatch.setenv("COLUMNS", "240")
