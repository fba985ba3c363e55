"""fretwear.io.prefetch (issue 28): small Parquet histories read ahead of their contacts, then
taken by the lean lane of :func:`fretwear.io.iter_history_blocks` instead of read again.

Independent computation: the same wear power without any file read ahead (the lean lane's own
read) and by the full path (the lane disabled), on the same files in the same process: equal
bit for bit (the same pyarrow read of the same bytes, the same kernel in the same order). Each
file is read once: counted at the two places that read it (``prefetch.read_known_block`` and
``streaming.read_known_block``).
"""

from __future__ import annotations

import threading
from collections import OrderedDict

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.io import iter_history_blocks, prefetch, sources, streaming
from fretwear.io.parquet import write_parquet
from fretwear.power import wear_power

pytest.importorskip("pyarrow")


def _history(seed: int, n: int = 1000) -> ContactHistory:
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 1e-5
    phase = 2 * np.pi * 300 * t
    fn = np.maximum(0.0, 20 * np.sin(phase) + rng.normal(0, 5, n))
    return ContactHistory(time=t, normal_force=fn, vt1=rng.normal(0, 0.02, n),
                          vt2=rng.normal(0, 0.02, n), dy=1e-4 * np.cos(phase / 7),
                          dz=1e-4 * np.sin(phase / 7), name=f"h{seed}")


@pytest.fixture
def reads(monkeypatch):
    """A fresh layout cache; the files read, where: ``("ahead", name)`` or ``("own", name)``."""
    monkeypatch.setattr(sources, "_LAYOUTS", OrderedDict())
    seen = []
    for module, where in ((prefetch, "ahead"), (streaming, "own")):
        real = module.read_known_block

        def counted(path, *args, _real=real, _where=where):
            seen.append((_where, str(path).rsplit("/", 1)[-1]))
            return _real(path, *args)

        monkeypatch.setattr(module, "read_known_block", counted)
    return seen


def _files(tmp_path, count: int, n: int = 1000) -> list:
    return [write_parquet(_history(k, n), tmp_path / f"h{k}.parquet") for k in range(count)]


def _power(path):
    return wear_power(path, stationarity_threshold=1e9, blocks=2, sectors=4).to_dict()


def test_files_read_ahead_give_the_same_power_bit_for_bit_each_read_once(tmp_path, monkeypatch,
                                                                         reads):
    paths = _files(tmp_path, 5)
    first = _power(paths[0])  # the layout resolved (full path): nothing read ahead before
    alone = [_power(p) for p in paths[1:]]  # the lean lane's own reads
    with monkeypatch.context() as m:
        m.setattr(streaming, "_lean_block", lambda *a: None)
        full = [_power(p) for p in paths]
    reads.clear()
    with prefetch.prefetch(paths, 1_000_000) as count:
        ahead = [_power(p) for p in paths]
    assert count == 5
    assert reads == [("ahead", f"h{k}.parquet") for k in range(5)]  # none read again
    assert ahead == [first, *alone] == full


def test_what_is_not_read_ahead(tmp_path, monkeypatch, reads):
    """A layout not resolved yet, a file longer than AHEAD_ROWS or than the reads' size, one
    that fails to read (its own read then says why, as without read-ahead), files beyond the
    AHEAD_BYTES held: none is read ahead; those taken are the others, in order."""
    paths = _files(tmp_path, 3)
    with prefetch.prefetch(paths, 1_000_000) as count:  # no layout known yet
        assert count == 0
    _power(paths[0])
    monkeypatch.setattr(prefetch, "AHEAD_ROWS", 999)
    with prefetch.prefetch(paths, 1_000_000) as count:
        assert count == 0
    monkeypatch.setattr(prefetch, "AHEAD_ROWS", 1 << 16)
    with prefetch.prefetch(paths, 999) as count:
        assert count == 0
    broken = tmp_path / "broken.parquet"
    broken.write_bytes(b"PAR1 not a table PAR1")
    with prefetch.prefetch([broken, *paths], 1_000_000) as count:
        assert count == 3
        with pytest.raises(Exception) as raised:
            _power(broken)
    with pytest.raises(type(raised.value)) as again:
        _power(broken)
    assert str(again.value) == str(raised.value)
    reads.clear()
    with prefetch.prefetch([paths[1], paths[1]], 1_000_000) as count:  # one file, read once
        assert count == 1
    assert reads == [("ahead", "h1.parquet")]
    monkeypatch.setattr(prefetch, "AHEAD_BYTES", 1)  # the first file passes the budget
    with prefetch.prefetch(paths, 1_000_000) as count:
        assert count == 1


def test_a_file_is_taken_once_and_by_its_thread_only(tmp_path, reads):
    paths = _files(tmp_path, 2)
    _power(paths[0])
    other = []
    with prefetch.prefetch(paths, 1_000_000):
        thread = threading.Thread(target=lambda: other.append(prefetch.taken(paths[1],
                                                                             1_000_000)))
        thread.start()
        thread.join()
        assert prefetch.taken(paths[1], 10) is None  # more rows than that read's size
        assert prefetch.taken(paths[0], 1_000_000) is not None
        assert prefetch.taken(paths[0], 1_000_000) is None  # taken once
    assert other == [None]
    assert prefetch.taken(paths[0], 1_000_000) is None  # nothing held after the block
    blocks = list(iter_history_blocks(paths[1]))
    assert len(blocks) == 1 and len(blocks[0]) == 1000
