"""``iter_history_chunks``: chunks equal the one-shot read, overlap by one sample, and a trapezoid
reduction over the chunks equals the one-shot reduction (the contract the streaming power uses).

Reference: the one-shot ``read_history`` of the same file, and an independent trapezoid sum
``Σ ½(Fn_i‖Vt_i‖ + Fn_{i+1}‖Vt_{i+1}‖)(t_{i+1} − t_i)`` written here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from iohelpers import FIXTURES, analytic_history, assert_same_history

from fretwear.errors import HistoryError, KeywordError
from fretwear.history import CHANNELS
from fretwear.io import iter_history_chunks, read_history, write_history

SUFFIX = {"csv": ".csv", "parquet": ".parquet", "hdf5": ".h5", "netcdf": ".nc", "npz": ".npz",
          "aster": ".resu"}


def work(time, fn, vt1, vt2) -> float:
    """Trapezoid integral of Fn·‖Vt‖ [J], written independently of fretwear.power."""
    p = fn * np.hypot(vt1, vt2)
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(time)))


def stitched(chunks, channel):
    parts = [getattr(c, channel) for c in chunks]
    return np.concatenate([parts[0]] + [p[1:] for p in parts[1:]])


# Chunks of 2 or 7 samples: the first chunk's largest force is the analytic history's rounding
# zero (6e-15 N), below the 0.01 N floor of the 'force_min' check; that check is made on the
# whole file's largest force (io.plausibility.StreamPlausibility), so no chunk size warns.
@pytest.mark.filterwarnings("error::fretwear.errors.UnitsWarning")
@pytest.mark.parametrize("fmt", sorted(SUFFIX))
@pytest.mark.parametrize("size", [2, 7, 64, 201, 500])
def test_chunks_equal_the_full_read(tmp_path, fmt, size):
    h = analytic_history(n=201)
    options = {"row_group_size": 16} if fmt == "parquet" else {}  # batches cross row groups
    path = write_history(h, tmp_path / f"h{SUFFIX[fmt]}", **options)
    full = read_history(path)
    chunks = list(iter_history_chunks(path, chunk_size=size))
    n = len(full)
    assert len(chunks) == max(1, math.ceil((n - 1) / (size - 1)))
    assert all(2 <= len(c) <= size for c in chunks)
    for a, b in zip(chunks[:-1], chunks[1:], strict=True):  # one shared sample
        for ch in full.channels:
            assert getattr(a, ch)[-1] == getattr(b, ch)[0]
    for k, c in enumerate(chunks):
        assert c.metadata["chunk"] == k and c.metadata["first_row"] == k * (size - 1)
        assert c.name == full.name
    for ch in CHANNELS:
        if getattr(full, ch) is not None:
            np.testing.assert_array_equal(stitched(chunks, ch), getattr(full, ch), err_msg=ch)
    one_shot = work(full.time, full.normal_force, full.vt1, full.vt2)
    summed = math.fsum(work(c.time, c.normal_force, c.vt1, c.vt2) for c in chunks)
    assert summed == pytest.approx(one_shot, rel=1e-13)


def test_chunks_apply_aliases_and_units(tmp_path):
    path = tmp_path / "mm.txt"
    rows = "".join(f"{i} {i % 3} {2 * i} 0\n" for i in range(10))
    path.write_text("INST FN VT1 VT2\n" + rows)
    chunks = list(iter_history_chunks(path, chunk_size=4, units={"time": "ms", "force": "kN",
                                                                 "velocity": "mm/s"}))
    assert [len(c) for c in chunks] == [4, 4, 4]
    full = read_history(path, units={"time": "ms", "force": "kN", "velocity": "mm/s"})
    np.testing.assert_array_equal(stitched(chunks, "time"), full.time)
    np.testing.assert_array_equal(stitched(chunks, "normal_force"), np.arange(10) % 3 * 1e3)
    assert chunks[1].metadata["units"]["vt1"] == "mm/s"


def test_chunks_of_a_code_aster_table():
    full = read_history(FIXTURES / "impr_table_tableau.txt")
    chunks = list(iter_history_chunks(FIXTURES / "impr_table_tableau.txt", chunk_size=3))
    assert [c.time.tolist() for c in chunks] == [[0.0, 1e-3, 2e-3], [2e-3, 3e-3, 4e-3]]
    assert_same_history(full.window(2e-3, 4e-3), chunks[1])


# samples 1 s apart: the coarse step is flagged (likely ms), irrelevant to the row in the error
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_error_in_a_later_chunk_names_the_file_row(tmp_path):
    path = tmp_path / "bad.csv"
    times = [0, 1, 2, 3, 4, 5, 5, 7]  # repeated instant at data row 6
    path.write_text("t,fn,vt1,vt2\n" + "".join(f"{t},1,1,0\n" for t in times))
    chunks = iter_history_chunks(path, chunk_size=4)
    first = next(chunks)
    assert first.time.tolist() == [0.0, 1.0, 2.0, 3.0]
    # the file's row (0-based, header excluded), not the row within the chunk (3): found by a
    # user's trial, who had to add the chunk's first row to the row named
    with pytest.raises(HistoryError, match=r"not strictly increasing at row 6 \(t\[5\] = 5\.0, "
                                           r"t\[6\] = 5\.0\)"):
        next(chunks)


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
@pytest.mark.parametrize(("channel", "value", "message"), [
    ("normal_force", -2.0, r"'normal_force' is negative \(-2\.0 N\) at row 12345 "),
    ("stick", 0.5, r"'stick' must be 0 or 1, got 0\.5 at row 12345;"),
    ("time", None, r"not strictly increasing at row 12345 \(t\[12344\] = "),
])
def test_errors_of_a_long_file_read_by_blocks_name_the_file_row(tmp_path, suffix, channel, value,
                                                                 message):
    """The streaming reader's blocks (iter_history_blocks: wear_power of a file, the bundle's
    chunks) name the file's row of a bad sample planted at row 12345, in a block starting at
    row 10000 (blocks of 5000)."""
    import pandas as pd

    from fretwear.io import iter_history_blocks

    n, bad = 20_000, 12_345
    arrays = {"time": np.arange(n) * 1e-4, "normal_force": np.ones(n), "vt1": np.full(n, 0.1),
              "vt2": np.zeros(n), "stick": np.zeros(n)}
    arrays[channel][bad] = arrays[channel][bad - 1] if value is None else value
    path = tmp_path / f"h{suffix}"
    if suffix == ".parquet":
        pd.DataFrame(arrays).to_parquet(path, index=False)
    else:
        pd.DataFrame(arrays).to_csv(path, index=False)
    with pytest.raises(HistoryError, match=message):
        for _ in iter_history_blocks(path, chunk_size=5000):
            pass


@pytest.mark.parametrize("bad", [1, 0, -5, 2.5, "10", True])
def test_chunk_size_must_be_an_integer_of_at_least_two(tmp_path, bad):
    path = write_history(analytic_history(n=5), tmp_path / "h.csv")
    with pytest.raises(KeywordError, match="chunk_size=.*integer >= 2"):
        next(iter_history_chunks(path, chunk_size=bad))


@pytest.mark.parametrize("suffix", [".h5", ".csv", ".parquet", ".nc"])
def test_memory_stays_bounded_by_the_chunk(tmp_path, suffix):
    """Peak traced (numpy) memory while iterating is O(chunk), not O(file).

    400 000 samples x 4 channels = 12.8 MB of data; chunks of 5 000 samples = 160 kB each.
    """
    import tracemalloc

    from fretwear.history import ContactHistory

    n = 400_000
    t = np.arange(n) * 1e-5
    h = ContactHistory(time=t, normal_force=np.abs(np.sin(t)), vt1=np.cos(t), vt2=np.sin(t))
    path = write_history(h, tmp_path / f"big{suffix}")
    del h, t
    tracemalloc.start()
    try:
        total = 0
        for chunk in iter_history_chunks(path, chunk_size=5_000):
            total += len(chunk) - (1 if chunk.metadata["chunk"] else 0)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert total == n
    assert peak < 3e6, f"peak {peak / 1e6:.1f} MB for 12.8 MB of data"
