"""The compiled checks of a streamed block decide as numpy's expressions.

:func:`fretwear.io.channels._checks` (what :func:`fast_history` runs on every block of
``iter_history_blocks``) takes one compiled pass a channel when numba is installed
(:mod:`fretwear.io._compiled`: finiteness and the largest force read from the bits) and numpy's
expressions otherwise, the reference. Both are run on the same blocks, each with one defect
planted where a vectorised loop could miss it (first, middle and last sample): NaN, ±inf,
equal or decreasing instants, a negative force, a stick flag of 0.5; and on blocks without a
defect, including -0.0 forces and flags. The decision must be the same, and the largest force
equal (a largest zero may differ in sign only).
"""

from __future__ import annotations

import numpy as np
import pytest

import fretwear._numba
from fretwear.io.channels import _checks

pytest.importorskip("numba")

N = 1031  # not a multiple of any vector width


def _block(seed: int) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    return {"time": np.cumsum(rng.uniform(1e-5, 2e-5, N)),
            "normal_force": np.maximum(rng.normal(0.0, 20.0, N), 0.0),
            "vt1": rng.normal(0.0, 0.05, N), "vt2": rng.normal(0.0, 0.05, N),
            "dy": rng.normal(0.0, 1e-4, N), "dz": rng.normal(0.0, 1e-4, N),
            "stick": (rng.random(N) < 0.3).astype(float)}


def _both(data, monkeypatch) -> tuple[tuple[bool, float], tuple[bool, float]]:
    compiled = _checks(data)
    with monkeypatch.context() as m:
        m.setattr(fretwear._numba, "HAVE_NUMBA", False)
        reference = _checks(data)
    return compiled, reference


DEFECTS = [(channel, value) for channel in ("time", "normal_force", "vt1", "dz", "stick")
           for value in (np.nan, np.inf, -np.inf)]
DEFECTS += [("normal_force", -1e-300), ("normal_force", -3.0), ("stick", 0.5),
            ("stick", 2.0), ("vt2", -np.nan)]


@pytest.mark.parametrize("channel, value", DEFECTS)
@pytest.mark.parametrize("where", [0, N // 2, N - 1])
def test_a_defect_anywhere_fails_both(monkeypatch, channel, value, where):
    data = _block(where)
    data[channel][where] = value
    (ok, _), (ok_, _) = _both(data, monkeypatch)
    assert ok is False and ok_ is False


@pytest.mark.parametrize("where", [1, N // 2, N - 1])
@pytest.mark.parametrize("step", [0.0, -1e-9])
def test_instants_not_increasing_fail_both(monkeypatch, where, step):
    data = _block(7)
    data["time"][where] = data["time"][where - 1] + step
    (ok, _), (ok_, _) = _both(data, monkeypatch)
    assert ok is False and ok_ is False


@pytest.mark.parametrize("seed", range(4))
def test_a_sound_block_passes_both_with_the_same_largest_force(monkeypatch, seed):
    data = _block(seed)
    data["normal_force"][:: 7] = -0.0  # counts as zero on both
    data["stick"][:: 5] = -0.0
    if seed == 3:  # the channels of a history without stick or dy/dz
        data = {k: data[k] for k in ("time", "normal_force", "vt1", "vt2")}
    (ok, fmax), (ok_, fmax_) = _both(data, monkeypatch)
    assert ok is True and ok_ is True
    assert fmax == fmax_ == data["normal_force"].max()


def test_all_zero_forces_give_a_zero_largest_force(monkeypatch):
    data = _block(9)
    data["normal_force"][:] = 0.0
    data["normal_force"][::2] = -0.0
    (ok, fmax), (ok_, fmax_) = _both(data, monkeypatch)
    assert ok and ok_ and fmax == fmax_ == 0.0  # the sign of the zero may differ


def test_a_strided_channel_takes_the_numpy_path(monkeypatch):
    """A non-contiguous array (a view with a step) cannot be read as bits in place: the
    reference decides, compiled kernels untouched."""
    from fretwear.io import _compiled

    monkeypatch.setattr(_compiled, "finite", lambda a: pytest.fail("compiled path taken"))
    data = {k: np.repeat(v, 2)[::2] if k == "vt1" else v for k, v in _block(3).items()}
    data["vt1"][5] = np.nan
    assert _checks(data)[0] is False
