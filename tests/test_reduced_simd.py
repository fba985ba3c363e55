"""The reduced-SIMD run of ``make test`` really turns SIMD down (``tests/reduced_simd.py``).

Without this check a misspelt variable would leave the second run on the same code paths as the
first, and it would prove nothing.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from reduced_simd import reduced_environment  # noqa: E402

PROBE = """import json, numba
from numpy._core._multiarray_umath import __cpu_features__ as f
print(json.dumps({"features": {k: bool(v) for k, v in f.items()},
                  "numba_cpu": numba.config.CPU_NAME}))"""


def _probe(env: dict[str, str]) -> dict:
    out = subprocess.run([sys.executable, "-c", PROBE], env=env, capture_output=True,
                         text=True, check=True, timeout=120)
    return json.loads(out.stdout)


def test_the_reduced_environment_turns_off_what_this_cpu_has():
    """In a child interpreter with the run's environment, every numpy dispatch target this CPU
    has is off, and numba compiles for the generic CPU."""
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__

    env = reduced_environment()
    present = [t for t in __cpu_dispatch__ if __cpu_features__.get(t)]
    assert env.get("NPY_DISABLE_CPU_FEATURES", "").split() == present
    seen = _probe({k: v for k, v in {**os.environ, **env}.items()
                   if k != "NPY_DISABLE_CPU_FEATURES" or v})
    assert not any(seen["features"][t] for t in present)
    assert seen["numba_cpu"] == "generic"


def test_this_run_is_reduced_when_it_says_so():
    """Inside the reduced run (FRETWEAR_REDUCED_SIMD set by tests/reduced_simd.py), this very
    interpreter has the targets off; in the ordinary run there is nothing to check."""
    said = os.environ.get("FRETWEAR_REDUCED_SIMD")
    if not said or said == "-":
        pytest.skip("not the reduced-SIMD run (or this CPU has only numpy's baseline)")
    import numba
    from numpy._core._multiarray_umath import __cpu_features__

    assert not any(__cpu_features__[t] for t in said.split())
    assert numba.config.CPU_NAME == "generic"
