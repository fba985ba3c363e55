"""The KWU-EPRI part of the wear power's streaming reduction (issue 13, theory §4).

:class:`fretwear.power.PowerAccumulator` with ``kwu=`` carries the class counts
(:class:`fretwear.laws.KwuEpriAccumulator`) or the window's maxima
(:class:`fretwear.laws.KwuEpriMaxima`); these helpers merge that part of two accumulators and
make the second pass of the counts when the maxima were not given.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable

import numpy as np

from fretwear.history import ContactHistory
from fretwear.laws import KwuEpriAccumulator, KwuEpriMaxima


def kwu_counts(acc, kwu, chunks: Callable[[], Iterable[ContactHistory]]) -> KwuEpriAccumulator:
    """The KWU-EPRI class counts of a second pass over ``chunks()``, the maxima not given
    (``kwu`` = (force_max or None, speed_max or None)) taken from the first pass's
    :class:`~fretwear.laws.KwuEpriMaxima` (``acc.kwu`` of a PowerAccumulator)."""
    force_max = acc.kwu.force_max if kwu[0] is None else kwu[0]
    speed_max = acc.kwu.speed_max if kwu[1] is None else kwu[1]
    # F_max = 0 only when no sample of the window has a force: no contact, no class counted
    counts = KwuEpriAccumulator(force_max if force_max > 0 else 1.0, speed_max,
                                t_start=acc.t_start, t_end=acc.t_end)
    for chunk in chunks():
        counts.update_velocities(chunk.time, chunk.normal_force, chunk.vt1, chunk.vt2)
    if force_max == 0:
        counts.force_max = 0.0
    counts.given = tuple(kwu)
    return counts


def merge_kwu(left, right):
    """The KWU-EPRI part of two adjacent PowerAccumulators (``left`` before ``right``), the
    interval between them counted."""
    if left.kwu is None or right.kwu is None:
        return None if left.kwu is None and right.kwu is None else (left.kwu or right.kwu)
    if isinstance(left.kwu, KwuEpriMaxima):
        return copy.deepcopy(left.kwu).merge(right.kwu)
    bridge = copy.deepcopy(left.kwu)  # its counts restart from zero, its last sample is kept
    bridge.class_time = np.zeros_like(bridge.class_time)
    bridge.window_time = bridge.time_above_max = 0.0
    bridge.samples = 0
    first = right.first
    bridge.update_velocities(first[:1], first[1:2], first[2:3], first[3:4])
    return left.kwu.merge(bridge).merge(right.kwu)
