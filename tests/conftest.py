"""Shared test set-up.

The CLI prints with rich, which wraps at the terminal width (80 columns when not a terminal, as
under CI). Tests that look for a phrase or a path in the printed summary must not depend on where
a temporary path happens to wrap, so every test sees a wide terminal.
"""

from pathlib import Path

import pytest


@pytest.fixture(autouse=True)
def _wide_terminal(monkeypatch):
    monkeypatch.setenv("COLUMNS", "240")


#: The [obstacle] section of the small control-rod case below (a bore, coarse steps: fast).
GRAPPE_OBSTACLE = """[obstacle]
type = "circle"
wall_thickness_m = 0.47e-3
step_deg = 5.0
resolution_deg = 1.0
"""


def write_grappe_case(path, history, *, instants: str = "[1000, 5000]", sectors: int = 4,
                      obstacle: bool = False, extra: str = "") -> Path:
    """A small case file: a control rod (304L) in a guide-card notch (GRAPPE_1_ENCO), Archard
    with both bodies wearing, ``history`` read from a file; with ``obstacle`` the
    :data:`GRAPPE_OBSTACLE` section; ``extra`` TOML appended."""
    path = Path(path)
    path.write_text(f"""[history]
file = "{history}"
[law]
name = "ARCHARD"
mobile = {{ COEF_USURE = 30e-15 }}
obstacle = {{ COEF_USURE = 17e-15 }}
[geometry]
contact_type = "GRAPPE_1_ENCO"
mobile_radius_m = 4.85e-3
obstacle_radius_m = 5.25e-3
obstacle_width_m = 20e-3
[sectors]
count = {sectors}
[time]
instants = {instants}
unit = "h"
{GRAPPE_OBSTACLE if obstacle else ""}{extra}""")
    return path


@pytest.fixture
def grappe_case():
    """:func:`write_grappe_case`, for tests in any folder."""
    return write_grappe_case
