"""Streaming a history file for the wear power (issue 13): blocks without copies, the time range
from the file's metadata, and the KWU-EPRI class counts in the same pass."""

import warnings

import numpy as np
import pytest

import fretwear.io as fio
import fretwear.power.core as core
from fretwear.errors import HistoryError, UnitsWarning
from fretwear.history import ContactHistory
from fretwear.io import history_time_range, iter_history_blocks, write_history
from fretwear.laws import KwuEpriAccumulator, kwu_epri_statistics
from fretwear.power import wear_power


def _history(n=20_000, seed=3):
    rng = np.random.default_rng(seed)
    t = 0.25 + np.cumsum(rng.uniform(0.5, 1.5, n)) * 2e-5
    phase = 2 * np.pi * 80 * t
    fn = np.maximum(0.0, 40 * np.sin(phase) - 10 + rng.normal(0, 2, n))
    ang = 1.5 * np.sin(2 * np.pi * 3 * t)
    return ContactHistory(time=t, normal_force=fn, vt1=0.03 * np.cos(phase),
                          vt2=0.02 * np.sin(phase), dy=1e-4 * np.cos(ang),
                          dz=1e-4 * np.sin(ang), stick=(rng.uniform(size=n) < 0.05) * 1.0,
                          name="h")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    h = _history()
    d = tmp_path_factory.mktemp("stream")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = {fmt: write_history(h, d / f"h.{fmt}") for fmt in ("parquet", "h5", "nc", "csv")}
        out["parquet_small_groups"] = write_history(h, d / "g.parquet", row_group_size=3000)
    return h, out


@pytest.mark.parametrize("fmt", ["parquet", "parquet_small_groups", "h5", "nc", "csv"])
def test_blocks_are_the_file_without_overlap(files, fmt):
    h, paths = files
    blocks = list(iter_history_blocks(paths[fmt], chunk_size=4096))
    assert len(blocks) > 3
    for ch in h.channels:
        np.testing.assert_array_equal(np.concatenate([getattr(b, ch) for b in blocks]),
                                      getattr(h, ch))
    assert [b.metadata["first_row"] for b in blocks] == list(
        np.cumsum([0] + [len(b) for b in blocks[:-1]]))
    assert not blocks[0].time.flags.writeable


@pytest.mark.parametrize("fmt", ["parquet", "parquet_small_groups"])
def test_a_file_of_one_block_is_read_whole(files, fmt):
    """A Parquet file no longer than the chunk is one block read as a table (its row groups
    joined): the file's values, read-only, as the record batches give them
    (test_blocks_are_the_file_without_overlap reads the same files in record batches)."""
    h, paths = files
    blocks = list(iter_history_blocks(paths[fmt], chunk_size=len(h)))
    assert len(blocks) == 1 and blocks[0].metadata["first_row"] == 0
    for ch in h.channels:
        np.testing.assert_array_equal(getattr(blocks[0], ch), getattr(h, ch))
    assert not blocks[0].time.flags.writeable


def test_a_file_of_one_block_given_in_several_chunks_is_joined(files, monkeypatch):
    """pyarrow 26's ParquetFile.read gives the row groups of a column in one chunk; a reader
    that gives one chunk a row group (as pyarrow's dataset reader, pq.read_table, does) must
    give the same block: the file's values, in order, read-only."""
    pq = pytest.importorskip("pyarrow.parquet")
    pa = pytest.importorskip("pyarrow")
    h, paths = files
    real = pq.ParquetFile.read

    def by_row_group(self, *args, **kwargs):  # the row groups of the file hold 3000 rows
        return pa.Table.from_batches(real(self, *args, **kwargs).to_batches(max_chunksize=3000))

    monkeypatch.setattr(pq.ParquetFile, "read", by_row_group)
    blocks = list(iter_history_blocks(paths["parquet_small_groups"], chunk_size=len(h)))
    assert len(blocks) == 1 and len(blocks[0]) == len(h)
    for ch in h.channels:
        np.testing.assert_array_equal(getattr(blocks[0], ch), getattr(h, ch))
    assert not blocks[0].time.flags.writeable


def test_blocks_are_checked_like_chunks(tmp_path):
    # the same errors as the validated chunks: a repeated instant across two blocks, a force
    # below the tolerance in a later block, a NaN
    h = _history(5000)
    t = h.time.copy()
    t[3000] = t[2999]  # the repeated instant sits on a block boundary (blocks of 1000)
    fn = h.normal_force.copy()
    fn[4321] = -1.0
    # the rows named are the file's (the planted rows 3000 and 4321), not the block's
    for change, words in (({"time": t}, ["not strictly increasing", "at row 3000 "]),
                          ({"normal_force": fn}, ["negative", "at row 4321 "])):
        path = tmp_path / f"bad{len(words)}{list(change)[0]}.csv"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            frame = h.to_frame()
            for k, v in change.items():
                frame[k] = v
            frame.to_csv(path, index=False)
        with pytest.raises(HistoryError) as err:
            list(iter_history_blocks(path, chunk_size=1000))
        assert all(w in str(err.value) for w in words), str(err.value)


def test_small_negative_forces_are_zeroed_in_a_copy_like_the_validation(tmp_path):
    h = _history(3000)
    frame = h.to_frame()
    frame.loc[1000, "normal_force"] = -1e-12  # solver noise, within the tolerance
    path = tmp_path / "noise.csv"
    frame.to_csv(path, index=False)
    got = np.concatenate([b.normal_force for b in iter_history_blocks(path, chunk_size=700)])
    assert got[1000] == 0.0 and (got >= 0).all()


@pytest.mark.parametrize("fmt", ["parquet", "parquet_small_groups", "h5", "nc"])
def test_time_range_from_metadata(files, fmt):
    h, paths = files
    assert history_time_range(paths[fmt]) == (float(h.time[0]), float(h.time[-1]))
    with pytest.warns(UnitsWarning, match="override the units the file declares for time"):
        lo, hi = history_time_range(paths[fmt], units={"time": "ms"})  # the file says s
    assert (lo, hi) == (float(h.time[0]) * 1e-3, float(h.time[-1]) * 1e-3)


def test_time_range_without_parquet_statistics(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    h = _history(5000)
    table = pq.read_table(write_history(h, tmp_path / "a.parquet"))
    path = tmp_path / "nostats.parquet"
    pq.write_table(table, path, write_statistics=False, row_group_size=1500)
    assert history_time_range(path) == (float(h.time[0]), float(h.time[-1]))


def test_text_formats_have_no_time_range_without_a_pass(files):
    assert history_time_range(files[1]["csv"]) is None


def _count_passes(monkeypatch):
    calls = []
    real = core.iter_history_blocks

    def counting(*args, **kwargs):
        calls.append(args[0])
        return real(*args, **kwargs)

    monkeypatch.setattr(core, "iter_history_blocks", counting)
    return calls


@pytest.mark.parametrize("fmt, passes", [("parquet", 1), ("h5", 1), ("nc", 1), ("csv", 2)])
def test_blocks_without_bounds_read_the_file_once(files, fmt, passes, monkeypatch):
    h, paths = files
    calls = _count_passes(monkeypatch)
    got = wear_power(paths[fmt], blocks=4, sectors=6, chunk_size=3000)
    assert len(calls) == passes  # a text file still needs a pass for its time range
    ref = wear_power(h, blocks=4, sectors=6)
    assert got.total == pytest.approx(ref.total, rel=1e-12)
    np.testing.assert_allclose(got.block_sectors, ref.block_sectors, rtol=1e-12, atol=1e-15)
    assert (got.t_start, got.t_end) == (ref.t_start, ref.t_end)
    assert got.statistics.impact_count == ref.statistics.impact_count


@pytest.mark.parametrize("maxima, passes", [((None, None), 2), ((35.0, None), 2),
                                            ((35.0, 0.02), 1)])
@pytest.mark.parametrize("window", [(None, None), (0.3, 0.5)])
def test_kwu_counts_in_the_power_pass(files, maxima, passes, window, monkeypatch):
    # the KWU-EPRI statistics of wear_power(kwu=...) equal kwu_epri_statistics of the whole
    # history; one pass over the file when both maxima are given, else two
    h, paths = files
    calls = _count_passes(monkeypatch)
    t0, t1 = window
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # samples above the given maxima: a LawWarning
        got = wear_power(paths["parquet"], t_start=t0, t_end=t1, kwu=maxima, chunk_size=3000)
        ref = kwu_epri_statistics(h, t_start=t0, t_end=t1, force_max=maxima[0],
                                  speed_max=maxima[1])
        stats = got.kwu.result()
    assert len(calls) == passes
    assert isinstance(got.kwu, KwuEpriAccumulator)
    np.testing.assert_array_equal(stats.class_time, ref.class_time)
    assert stats.intensity == pytest.approx(ref.intensity, rel=1e-12)
    assert (stats.force_max, stats.speed_max) == (ref.force_max, ref.speed_max)
    assert stats.window_time == pytest.approx(ref.window_time, rel=1e-12)
    assert stats.time_above_max == pytest.approx(ref.time_above_max, rel=1e-12, abs=1e-15)


def test_kwu_of_an_in_memory_history(files):
    h, _ = files
    got = wear_power(h, kwu=(None, None)).kwu.result()
    np.testing.assert_array_equal(got.class_time, kwu_epri_statistics(h).class_time)


def test_merged_accumulators_count_the_interval_between_them():
    from fretwear.power import PowerAccumulator

    h = _history(6000)
    kw = dict(t_start=float(h.time[0]), t_end=float(h.time[-1]), kwu=(40.0, 0.05))
    parts = [PowerAccumulator(**kw).update(h.window(h.time[a], h.time[b - 1]))
             for a, b in ((0, 2000), (2000, 4100), (4100, 6000))]  # no shared sample
    merged = parts[1].merge(parts[0]).merge(parts[2])  # before, then after
    one = PowerAccumulator(**kw).update(h)
    np.testing.assert_array_equal(merged.kwu.class_time, one.kwu.class_time)
    assert merged.kwu.window_time == pytest.approx(one.kwu.window_time, rel=1e-12)


def test_plausibility_checked_on_the_first_block(tmp_path):
    h = _history(5000)
    frame = h.to_frame()
    frame["normal_force"] *= 1e4  # a file in mN read as N: a force implausible in SI
    path = tmp_path / "mN.csv"
    frame.to_csv(path, index=False)
    with pytest.warns(fio.plausibility.UnitsWarning):
        list(iter_history_blocks(path, chunk_size=1000))


@pytest.mark.parametrize("fmt", ["parquet", "csv"])
def test_first_block_is_given_the_readers_first_block_before_the_reduction(files, fmt):
    """``first_block`` sees the first block a file's reader gives (the file's first 4 096 rows:
    the history written, read back bit for bit in this process, float64 in both formats'
    round trip as test_blocks_are_the_file_without_overlap asserts) once, and the power is the
    one computed without it (same process: bit for bit); an in-memory history is its own first
    block."""
    h, paths = files
    seen = []
    got = wear_power(paths[fmt], chunk_size=4096, first_block=seen.append)
    assert len(seen) == 1 and len(seen[0]) == 4096
    for ch in h.channels:
        np.testing.assert_array_equal(getattr(seen[0], ch), getattr(h, ch)[:4096])
    assert got.total == wear_power(paths[fmt], chunk_size=4096).total
    whole = []
    wear_power(h, first_block=whole.append)
    assert whole == [h]
