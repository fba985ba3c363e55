"""Histories whose impacts last a few samples are said to be under-resolved (a new user's trial:
the shipped bundle example archived every 0.5 ms impacts of about 0.5 ms, and no command said
so; docs/code_aster.md §5 measured +14.5 % on the power at 5 samples an impact)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from fretwear.errors import ResolutionWarning
from fretwear.history import ContactHistory
from fretwear.io.plausibility import IMPACT_SAMPLES_MIN, check_plausibility


def impacts(step: float, duration: float = 1e-3, period: float = 1e-2, span: float = 0.2):
    """Half-sine impacts of ``duration`` [s] every ``period`` [s], sampled every ``step`` [s]:
    each impact lasts duration/step samples (an impact is a run of Fn > 0)."""
    t = np.arange(0.0, span, step)
    phase = np.mod(t, period)
    fn = np.where(phase < duration, 10.0 * np.sin(np.pi * phase / duration), 0.0)
    return ContactHistory(time=t, normal_force=np.maximum(fn, 0.0), vt1=0.01 * np.cos(t),
                          vt2=np.zeros_like(t), name="N12")


def test_an_impact_of_two_samples_is_said_with_the_step_to_archive_at():
    with pytest.warns(ResolutionWarning) as caught:
        # 1 ms impacts sampled every 0.5 ms: a run of Fn > 0 is one or two samples long
        check_plausibility(impacts(5e-4))
    message = str(caught[0].message)
    samples = float(message.split("impacts last ")[1].split(" samples")[0])
    duration = float(message.split("mean impact duration ")[1].split(" s")[0])
    assert 1.0 <= samples <= 2.0 and duration == pytest.approx(samples * 5e-4, rel=1e-3)
    assert f"a step below {duration / 20:.2g} s" in message and "archive_step_s" in message


@pytest.mark.parametrize("step", [1e-4, 5e-5])
def test_impacts_of_ten_samples_or_more_pass(step):
    assert 1e-3 / step >= 2 * IMPACT_SAMPLES_MIN
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResolutionWarning)
        check_plausibility(impacts(step))


def test_fewer_than_three_impacts_say_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResolutionWarning)
        check_plausibility(impacts(5e-4, span=0.015))  # two impacts
