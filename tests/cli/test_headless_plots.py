"""The CLI writes its figures on a machine without a display: neither the library nor the CLI
selects a backend; matplotlib falls back to Agg by itself when there is no display (none, or an
unreachable one). Run in fresh interpreters so that no earlier test has chosen a backend."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = """
import sys
from fretwear.cli import main
code = main(sys.argv[1:])
import matplotlib
print(matplotlib.get_backend().lower())
raise SystemExit(code)
"""


@pytest.mark.parametrize("display", [None, ":99"], ids=["no-display", "unreachable-display"])
def test_run_plot_headless(display, tmp_path):
    env = {k: v for k, v in os.environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "MPLBACKEND")}
    env["MPLCONFIGDIR"] = str(tmp_path / "mpl")  # no user matplotlibrc choosing a backend
    if display is not None:
        env["DISPLAY"] = display
    out = subprocess.run([sys.executable, "-c", SCRIPT, "run",
                          str(ROOT / "examples" / "tube_bav.toml"), "-q",
                          "--plot", str(tmp_path / "fig")],
                         capture_output=True, text=True, env=env, cwd=tmp_path, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split()[-1] == "agg"
    assert sorted(p.name for p in (tmp_path / "fig").iterdir()) == [
        "wear_history.png", "wear_history.svg", "wear_sectors.png", "wear_sectors.svg"]
