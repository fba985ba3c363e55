"""The result of a window of one block (a bundle's contact) in fewer numpy calls: the same numbers.

:meth:`fretwear.power.PowerAccumulator.result` takes the row sum of one block as the sum of all,
the sector powers as the one row of the block × sector powers, and builds the
:class:`~fretwear.power.PowerResult` and its :class:`~fretwear.power.ContactStatistics` with
their arrays frozen in place (:func:`fretwear.power.statistics.frozen_instance`). The reference
is the general expressions of the window's powers (docs/theory.md §2-§3, as ``result`` computes
them for B blocks: ``power.sum(axis=1) / (T / B)``, ``power.sum() / T``,
``power.sum(axis=0) / T``, ``power / (T / B)``) on the accumulator's own sums, and the
dataclasses' own constructors: equal bit for bit (the same IEEE operations on the same values).
"""

from __future__ import annotations

import pickle
from dataclasses import fields

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.power import PowerAccumulator, PowerResult
from fretwear.power.statistics import ContactStatistics


def _history(seed: int, n: int, kind: str) -> ContactHistory:
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(1e-5, 3e-5, n))
    fn = np.maximum(rng.normal(5.0, 20.0, n), 0.0)
    if kind == "free":  # no contact at all: every power 0
        fn[:] = 0.0
    v1, v2 = rng.normal(0.0, 0.1, n), rng.normal(0.0, 0.1, n)
    return ContactHistory(time=t, normal_force=fn, vt1=v1, vt2=v2,
                          dy=rng.normal(0.0, 1e-4, n), dz=rng.normal(0.0, 1e-4, n),
                          stick=(rng.random(n) < 0.2).astype(float), name=f"h{seed}")


def _reference(acc: PowerAccumulator, T: float):
    nb = acc.blocks
    p = acc.power
    return (float(p.sum()) / T, p.sum(axis=1) / (T / nb), p.sum(axis=0) / T, p / (T / nb))


def _same(a, b) -> None:
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("kind", ["random", "free"])
@pytest.mark.parametrize("sectors", [None, 1, 8, [-180.0, -30.0, 10.0, 180.0]])
@pytest.mark.parametrize("seed, n", [(0, 2), (1, 3), (2, 1000), (3, 4097)])
def test_one_block_powers_equal_the_general_expressions(kind, sectors, seed, n):
    h = _history(seed, n, kind)
    acc = PowerAccumulator(t_start=float(h.time[0]), t_end=float(h.time[-1]),
                           sectors=sectors).update(h)
    r = acc.result()
    total, blocks, sector_powers, block_sectors = _reference(acc, r.duration)
    _same(r.total, total)
    _same(r.blocks, blocks)
    assert r.spread == 0.0
    if sectors is None:
        assert r.sectors is None and r.block_sectors is None
    else:
        _same(r.sectors, sector_powers)
        _same(r.block_sectors, block_sectors)
        assert r.sectors.sum() == pytest.approx(r.total, rel=1e-12, abs=0.0)


@pytest.mark.parametrize("blocks", [1, 2, 7])
def test_the_result_is_the_dataclasses_own(blocks):
    """Every field the constructors would hold, read-only arrays, a dict and a pickle alike."""
    h = _history(5, 2000, "random")
    acc = PowerAccumulator(t_start=float(h.time[0]), t_end=float(h.time[-1]), blocks=blocks,
                           sectors=8).update(h)
    r = acc.result(stationarity_threshold=10.0)
    built = PowerResult(**{f.name: getattr(r, f.name) for f in fields(PowerResult)})
    stats = ContactStatistics(**{f.name: getattr(r.statistics, f.name)
                                 for f in fields(ContactStatistics)})
    assert r.to_dict() == built.to_dict()
    assert r.statistics.to_dict() == stats.to_dict()
    for obj in (r, r.statistics):
        arrays = [v for v in vars(obj).values() if isinstance(v, np.ndarray)]
        assert arrays and all(not a.flags.writeable for a in arrays)
    with pytest.raises(ValueError):
        r.sectors[0] = 1.0
    again = pickle.loads(pickle.dumps(r))
    assert again.to_dict() == r.to_dict() and not again.block_sectors.flags.writeable



@pytest.mark.parametrize("backend", ["numpy", "numba"])
@pytest.mark.parametrize("kind", ["random", "free"])
def test_the_first_chunk_sums_are_zeros_plus_the_kernels(backend, kind):
    """The first chunk's sums are taken as the accumulator's (nothing to add them to): equal bit
    for bit to the zeros they were added to before plus the kernel's sums, as
    :mod:`fretwear.power.kernels` computes them; a second accumulator fed the same history in
    two chunks gives the one-shot power (the reduction's associativity, theory §2)."""
    from fretwear.power.kernels import fused
    from fretwear.power.statistics import merge_groups

    h = _history(21, 3001, kind)
    acc = PowerAccumulator(t_start=float(h.time[0]), t_end=float(h.time[-1]), sectors=8,
                           backend=backend).update(h)
    s = fused(backend)(h.time, h.normal_force, h.vt1, h.vt2, h.dy, h.dz, h.stick, acc._lo,
                       acc._hi, acc._block_edges, acc._edges, 0.0, 0.0)
    _same(acc.power, np.zeros_like(s.power) + s.power)
    _same(acc.block_stats, np.zeros_like(s.block_stats) + s.block_stats)
    _same(acc.groups, merge_groups(np.zeros_like(s.groups), s.groups, 0.0))
    assert acc.force_max == s.force_max
    two = PowerAccumulator(t_start=float(h.time[0]), t_end=float(h.time[-1]), sectors=8,
                           backend=backend)
    two.update(h.window(h.time[0], h.time[1500])).update(h.window(h.time[1500], h.time[-1]))
    assert two.result().total == pytest.approx(acc.result().total, rel=1e-12, abs=0.0)
