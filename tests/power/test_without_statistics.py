"""``wear_power(..., statistics=False)`` (a bundle worker's call: its records drop the
statistics) gives the very result of ``wear_power(...)`` (the reference) but for its
``statistics``, None: every other field equal bit for bit, for a file of one block and of
several, with sectors and blocks, with the KWU-EPRI counts of the same pass, and in memory;
``to_dict`` then holds ``statistics: None``."""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.io import write_history
from fretwear.power import wear_power

pytest.importorskip("pyarrow")


def _history(n=1201):
    t = np.linspace(0.0, 0.6, n)
    rng = np.random.default_rng(7)
    return ContactHistory(time=t, normal_force=np.maximum(0.0, 20 * np.sin(60 * t) - 5),
                          vt1=0.02 * np.cos(80 * t), vt2=0.01 * np.sin(50 * t),
                          dy=1e-4 * np.cos(40 * t) + rng.normal(0, 1e-5, n),
                          dz=1e-4 * np.sin(30 * t), name="h")


def _equal_but_statistics(lean, full) -> None:
    assert lean.statistics is None and full.statistics is not None
    for f in fields(full):
        if f.name in ("statistics", "kwu"):
            continue
        a, b = getattr(lean, f.name), getattr(full, f.name)
        if isinstance(b, np.ndarray):
            assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), f.name
        else:
            assert a == b or (a != a and b != b), f.name
    assert {**full.to_dict(), "statistics": None} == lean.to_dict()


@pytest.mark.parametrize("options", [
    {}, {"sectors": 8}, {"sectors": 4, "blocks": 3, "force_threshold": 1.0},
    {"sectors": 8, "kwu": (40.0, 0.05)}, {"chunk_size": 500, "sectors": 6, "blocks": 2}])
def test_the_same_powers_without_the_statistics(tmp_path, options):
    h = _history()
    path = write_history(h, tmp_path / "h.parquet")
    _equal_but_statistics(wear_power(path, statistics=False, **options),
                          wear_power(path, **options))
    memory = {k: v for k, v in options.items() if k != "chunk_size"}
    _equal_but_statistics(wear_power(h, statistics=False, **memory), wear_power(h, **memory))
    if "kwu" in options:
        lean, full = wear_power(path, statistics=False, **options), wear_power(path, **options)
        factors = dict(k=1.0, c=1.0, impact_factor=1.0, sliding_factor=1.0)
        assert lean.kwu.result(**factors).intensity == full.kwu.result(**factors).intensity
