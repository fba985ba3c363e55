"""Helpers of the fuzz suite (tests/fuzz): budget, the 'only fretwear errors' check, seeds.

Budget: every fuzz test runs ``examples(n)`` hypothesis examples, derandomised (the same inputs
on every run, so ``make test`` stays deterministic and well under its time budget). For a deep
run that looks for new defects, set ``FRETWEAR_FUZZ_SCALE=50`` (50 times the examples, random
inputs): ``FRETWEAR_FUZZ_SCALE=50 pytest tests/fuzz``.
"""

from __future__ import annotations

import contextlib
import functools
import os
import signal
import tempfile
import warnings
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

import fretwear.io.guard as guard
from fretwear.errors import FretwearError, FretwearWarning
from fretwear.history import ContactHistory

SCALE = float(os.environ.get("FRETWEAR_FUZZ_SCALE", "1"))
#: seconds one example may take before the test fails as a hang
HANG_SECONDS = 20.0
# a damaged HDF5/NetCDF file can make its C library loop forever: the reader's probe gives up
# after PROBE_TIMEOUT seconds (an error), which must come before the fuzz calls it a hang
guard.PROBE_TIMEOUT = 5.0


def examples(n: int) -> settings:
    """Hypothesis settings of one fuzz test: ``n`` examples (times FRETWEAR_FUZZ_SCALE)."""
    # derandomized in make test, exploring in a deep run; the example database is the
    # profile's (tests/conftest.py: read-only in make test, written by a deep run)
    return settings(max_examples=max(1, int(n * SCALE)), deadline=None,
                    derandomize=SCALE == 1, print_blob=True,
                    suppress_health_check=list(HealthCheck))


class Hang(Exception):
    """An example ran longer than HANG_SECONDS."""


@contextlib.contextmanager
def no_hang(seconds: float = HANG_SECONDS):
    """Fail with :class:`Hang` when the block runs longer than ``seconds`` (SIGALRM)."""
    def alarm(signum, frame):
        raise Hang(f"no result after {seconds} s")

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def only_fretwear(function, *args, **kwargs):
    """Call ``function``: its result, or None when it raised a fretwear error.

    Any other exception propagates (the test fails: a user would see a traceback), and so does a
    warning that is not a :class:`~fretwear.errors.FretwearWarning` (a numpy overflow warning is
    a silent inf in the making). Returns ``(result, warnings)``.
    """
    with warnings.catch_warnings(record=True) as caught, no_hang():
        warnings.simplefilter("always")
        try:
            result = function(*args, **kwargs)
        except FretwearError:
            result = None
    foreign = [w for w in caught if not issubclass(w.category, FretwearWarning)
               and not issubclass(w.category, DeprecationWarning)]
    assert not foreign, [f"{w.category.__name__}: {w.message}" for w in foreign]
    return result, [w for w in caught if issubclass(w.category, FretwearWarning)]


@functools.lru_cache(maxsize=1)
def workdir() -> Path:
    """A temporary folder for the whole fuzz session."""
    return Path(tempfile.mkdtemp(prefix="fretwear-fuzz-"))


def small_history(n: int = 60, name: str = "N1") -> ContactHistory:
    """A short impact-sliding history: Fn = max(0, 40 sin 2π10t) [N], vt = 0.05 m/s cos."""
    t = np.linspace(0.0, 0.2, n)
    fn = np.maximum(0.0, 40.0 * np.sin(2 * np.pi * 10 * t))
    return ContactHistory(time=t, normal_force=fn, vt1=0.05 * np.cos(2 * np.pi * 10 * t),
                          vt2=0.02 * np.sin(2 * np.pi * 10 * t),
                          dy=1e-4 * np.cos(2 * np.pi * 10 * t),
                          dz=1e-4 * np.sin(2 * np.pi * 10 * t), name=name)


TOKENS = [b"+", b"-", b"nan", b"inf", b"1e400", b"1e200", b"-1e200", b"\r\n", b"\x00", b",", b";",
          b" ", b"\t", b"'", b'"', b"#", b"\n", b"\n\n", b"0", b"-0", b"1D+05", b"\xff\xfe",
          b"\xef\xbb\xbf", b"#DEBUT_TABLE\n", b"#FIN_TABLE\n", b"R", b"K8", b"\xe9", b"=", b"["]


@st.composite
def mutated(draw, seed: bytes) -> bytes:
    """``seed`` changed by 1-4 edits: cut, byte flips, deletions, insertions of nasty tokens,
    runs of 0x00/0xff/0x7f."""
    data = bytearray(seed)
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["cut", "flip", "delete", "insert", "run"]))
        n = len(data)
        at = draw(st.integers(0, max(0, n - 1)))
        if kind == "cut" and n:
            del data[at:]
        elif kind == "flip" and n:
            data[at] = draw(st.integers(0, 255))
        elif kind == "delete" and n:
            del data[at:at + draw(st.integers(1, 64))]
        elif kind == "insert":
            data[at:at] = draw(st.sampled_from(TOKENS))
        elif n:
            data[at:at + 8] = bytes([draw(st.sampled_from([0, 0xFF, 0x7F]))]) * 8
    return bytes(data)
