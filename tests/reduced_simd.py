"""Run the numeric tests again with the SIMD code paths turned down (part of ``make test``).

numpy and numba choose their SIMD code paths by processor, so a sum rounds differently on a
machine with AVX-512, one with AVX2 and FMA only, or an older one. A test that holds only on the
processor that wrote its expected values passes here and fails on the next machine. This run
shows it on one machine: it turns off every numpy dispatch target that this processor has
(``NPY_DISABLE_CPU_FEATURES``: the AVX2/FMA group X86_V3 and the AVX-512 groups on x86-64, the
ASIMD extensions on ARM), compiles numba for a generic CPU (``NUMBA_CPU_NAME=generic``), and
runs the tests marked ``numeric`` (``tests/conftest.py`` says which) in a new interpreter.

Usage: ``python tests/reduced_simd.py [pytest options]``; ``--print-env`` prints the settings.
"""

from __future__ import annotations

import os
import subprocess
import sys


def reduced_environment() -> dict[str, str]:
    """The environment variables of the reduced-SIMD run (NPY_DISABLE_CPU_FEATURES lists the
    dispatch targets this processor has; none when it has none beyond numpy's baseline)."""
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__

    present = [t for t in __cpu_dispatch__ if __cpu_features__.get(t)]
    env = {"NUMBA_CPU_NAME": "generic", "FRETWEAR_REDUCED_SIMD": " ".join(present) or "-"}
    if present:
        env["NPY_DISABLE_CPU_FEATURES"] = " ".join(present)
    return env


def main(argv: list[str]) -> int:
    env = reduced_environment()
    if "--print-env" in argv:
        print(" ".join(f"{k}={v!r}" for k, v in env.items()))
        return 0
    disabled = env.get("NPY_DISABLE_CPU_FEATURES", "none (this CPU has only numpy's baseline)")
    print(f"reduced-SIMD run: numpy dispatch targets off: {disabled}; numba CPU: generic",
          flush=True)
    command = [sys.executable, "-m", "pytest", "-m", "numeric", "-p", "no:cacheprovider",
               *argv]
    code = subprocess.call(command, env={**os.environ, **env})
    if code == 5:
        print("reduced-SIMD run: no test is marked numeric", file=sys.stderr)
        return 1
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
