"""The suite's watchdog (tests/conftest.py): a test that hangs ends its process with every
thread's stack on stderr after ``WATCHDOG`` seconds, instead of holding CI to its time limit."""

import os
import subprocess
import sys
import time
from pathlib import Path

TESTS = Path(__file__).resolve().parent


def test_a_hanging_test_is_ended_with_its_stack(tmp_path):
    (tmp_path / "test_hangs.py").write_text(
        "import time\n\n\ndef test_hangs():\n    time.sleep(300)\n")
    env = {**os.environ, "PYTHONPATH": str(TESTS), "FRETWEAR_TEST_WATCHDOG": "2"}
    env.pop("FRETWEAR_FUZZ_SCALE", None)
    t0 = time.monotonic()
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "conftest",
                          "-p", "no:cacheprovider", "-p", "no:xdist", str(tmp_path)],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode != 0
    assert time.monotonic() - t0 < 100  # not the 300 s the test sleeps
    assert "Timeout (0:00:02)!" in run.stderr and "test_hangs" in run.stderr, run.stderr
