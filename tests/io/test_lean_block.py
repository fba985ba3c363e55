"""The lean lane of :func:`fretwear.io.iter_history_blocks` (issue 28): a Parquet file of one
block whose column layout is already known is read by one pyarrow call and checked by the same
functions; anything that would raise or warn is read again by the full path.

Independent computation: the full path itself, forced by disabling the lane
(``streaming._lean_block`` returning None), on the same files in the same process. The values
are then compared bit for bit (the same pyarrow read and the same power kernel in the same
order, one process and one machine); the errors and warnings by their class and text.
"""

from __future__ import annotations

import warnings
from collections import OrderedDict

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.io import iter_history_blocks, sources, streaming
from fretwear.io.parquet import write_parquet
from fretwear.power import wear_power

pa = pytest.importorskip("pyarrow")
pq = pytest.importorskip("pyarrow.parquet")


def _history(kind: str, n: int = 1000, seed: int = 0) -> ContactHistory:
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 1e-5
    phase = 2 * np.pi * 300 * t
    if kind == "random":
        fn = np.maximum(0.0, 20 * np.sin(phase) + rng.normal(0, 5, n))
        vt1, vt2 = rng.normal(0, 0.02, n), rng.normal(0, 0.02, n)
    elif kind == "flat":
        fn, vt1, vt2 = np.full(n, 10.0), np.full(n, 0.01), np.zeros(n)
    else:  # "free": no impact, no force
        fn, vt1, vt2 = np.zeros(n), 0.01 * np.cos(phase), 0.01 * np.sin(phase)
    return ContactHistory(time=t, normal_force=fn, vt1=vt1, vt2=vt2,
                          dy=1e-4 * np.cos(phase / 7), dz=1e-4 * np.sin(phase / 7),
                          name=f"h-{kind}")


@pytest.fixture
def lean_count(monkeypatch):
    """Fresh layout cache; counts the files the lean lane read (a history returned)."""
    monkeypatch.setattr(sources, "_LAYOUTS", OrderedDict())
    taken = []
    lean = streaming._lean_block

    def counted(*args):
        chunk = lean(*args)
        taken.append(chunk is not None)
        return chunk

    monkeypatch.setattr(streaming, "_lean_block", counted)
    return taken


def _full_path(monkeypatch, fn, *args, **kwargs):
    with monkeypatch.context() as m:
        m.setattr(streaming, "_lean_block", lambda *a: None)
        return fn(*args, **kwargs)


def _outcome(fn, *args, **kwargs):
    """(value or None, (error class, text) or None, [(warning class, text)])."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            value, error = fn(*args, **kwargs), None
        except Exception as exc:  # noqa: BLE001 - compared below
            value, error = None, (type(exc).__name__, str(exc))
    return value, error, [(w.category.__name__, str(w.message)) for w in caught]


def _blocks(path, **kwargs):
    return list(iter_history_blocks(path, **kwargs))


@pytest.mark.parametrize("kind", ["random", "flat", "free"])
def test_lean_blocks_equal_the_full_paths_bit_for_bit(tmp_path, monkeypatch, lean_count, kind):
    paths = [write_parquet(_history(kind, seed=k), tmp_path / f"{kind}{k}.parquet")
             for k in range(3)]
    for path in paths:
        for name in (None, "N12"):
            lean = _blocks(path, name=name)
            full = _full_path(monkeypatch, _blocks, path, name=name)
            assert len(lean) == len(full) == 1
            a, b = lean[0], full[0]
            assert a.name == b.name and a.channels == b.channels
            assert a.metadata == b.metadata and a.force_tolerance == b.force_tolerance
            for ch in a.channels:
                np.testing.assert_array_equal(getattr(a, ch), getattr(b, ch))
    # the first file resolves the layout by the full path; the others take the lean lane
    assert lean_count.count(True) >= 5


CASES = [
    dict(),
    dict(blocks=4, sectors=6),
    dict(t_start=2e-3, t_end=8.5e-3, blocks=3, sectors=[-180, -30, 45, 180]),
    dict(force_threshold=5.0, minimum_rest_time=1e-4, blocks=2),
    dict(blocks=2, kwu=(60.0, 0.1)),      # KWU-EPRI counts in the same pass
    dict(blocks=2, kwu=(None, None)),     # the maxima, then a second pass
]


@pytest.mark.parametrize("options", CASES)
@pytest.mark.parametrize("kind", ["random", "flat", "free"])
def test_wear_power_equals_the_full_paths(tmp_path, monkeypatch, lean_count, kind, options):
    write_parquet(_history(kind, seed=9), tmp_path / "first.parquet")
    _blocks(tmp_path / "first.parquet")  # the layout now known
    path = write_parquet(_history(kind, seed=1), tmp_path / "h.parquet")
    lean = _outcome(wear_power, path, stationarity_threshold=1e9, **options)
    full = _outcome(_full_path, monkeypatch, wear_power, path, stationarity_threshold=1e9,
                    **options)
    assert lean_count[1:] and all(lean_count[1:])  # [0]: the first file, full path
    assert lean[1:] == full[1:]
    if full[0] is None:
        assert lean[0] is None
        return
    assert lean[0].to_dict() == full[0].to_dict()
    if options.get("kwu") is not None:
        a, b = lean[0].kwu, full[0].kwu
        np.testing.assert_array_equal(a.class_time, b.class_time)
        assert (a.window_time, a.time_above_max, a.samples) == (
            b.window_time, b.time_above_max, b.samples)


def _rewrite(path, out, change):
    """``path``'s table with ``change(name, values)`` applied to its columns: the same schema
    (field units, fretwear metadata), so the same layout as the good files."""
    table = pq.read_table(path)
    for i, field in enumerate(table.schema):
        values = table.column(i).to_numpy().copy()
        table = table.set_column(i, field, pa.array(change(field.name, values)))
    pq.write_table(table, out)
    return out


def _nan(name, v):
    if name == "vt1":
        v[5] = np.nan
    return v


BAD = {
    "nan": _nan,
    "force 1e4 too small (a file in kN)": lambda name, v: v * 1e-4 if name == "normal_force"
    else v,
    "force 1e4 too large": lambda name, v: v * 1e4 if name == "normal_force" else v,
    "speed in mm/s read as m/s": lambda name, v: v * 1e3 if name in ("vt1", "vt2") else v,
    "time not increasing": lambda name, v: v[::-1].copy() if name == "time" else v,
    "negative force": lambda name, v: v - 50.0 if name == "normal_force" else v,
}


@pytest.mark.parametrize("bad", sorted(BAD))
def test_bad_files_give_the_full_paths_errors_and_warnings(tmp_path, monkeypatch, lean_count,
                                                            bad):
    good = write_parquet(_history("random"), tmp_path / "good.parquet")
    _blocks(good)
    path = _rewrite(good, tmp_path / "bad.parquet", BAD[bad])
    for fn in (_blocks, wear_power):
        lean = _outcome(fn, path, name="N12")
        full = _outcome(_full_path, monkeypatch, fn, path, name="N12")
        assert lean[1:] == full[1:]
        assert lean[1] is not None or lean[2], f"{bad}: the file should raise or warn"
    assert True not in lean_count  # every bad file was read again by the full path


@pytest.mark.parametrize("damage", ["truncated", "missing column", "not parquet", "directory"])
def test_damaged_files_give_the_full_paths_errors(tmp_path, monkeypatch, lean_count, damage):
    good = write_parquet(_history("random"), tmp_path / "good.parquet")
    _blocks(good)
    path = tmp_path / "bad.parquet"
    if damage == "truncated":
        data = good.read_bytes()
        path.write_bytes(data[: len(data) // 2])
    elif damage == "missing column":
        pq.write_table(pq.read_table(good).drop(["vt2"]), path)
    elif damage == "not parquet":
        path.write_text("time,fn\n0,1\n")
    else:
        path.mkdir()
    lean = _outcome(_blocks, path, name="N12")
    full = _outcome(_full_path, monkeypatch, _blocks, path, name="N12")
    assert lean[1] is not None and lean[1:] == full[1:]
    assert True not in lean_count


def test_long_files_options_and_other_formats_take_the_full_path(tmp_path, lean_count):
    good = write_parquet(_history("random"), tmp_path / "good.parquet")
    _blocks(good)
    # more rows than a block: the reader's record batches (full path); options given
    assert len(_blocks(good, chunk_size=300)) == 4
    _blocks(good, units={"force": "N"})
    _blocks(good, format="parquet")
    assert True not in lean_count
    assert _blocks(good)[0].name == "h-random" and lean_count[-1] is True


@pytest.mark.parametrize("bad", ["force 1e4 too large", "force 1e4 too small (a file in kN)",
                                 "speed in mm/s read as m/s"])  # read, and warn
def test_quiet_checks_return_the_messages_they_would_warn(tmp_path, bad):
    """``emit=False`` (the lane's checks: no change to the warning state other threads
    share) gathers the very messages ``emit=True`` warns (the reference), and warns none."""
    from fretwear.io.plausibility import StreamPlausibility

    good = write_parquet(_history("random"), tmp_path / "good.parquet")
    path = _rewrite(good, tmp_path / "bad.parquet", BAD[bad])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        chunk = _blocks(path, name="N12", format="parquet")[0]
    with warnings.catch_warnings(record=True) as loud:
        warnings.simplefilter("always")
        stream = StreamPlausibility()
        stream.update(chunk, check=True)
        stream.finish()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning fails
        quiet = StreamPlausibility(emit=False)
        quiet.update(chunk, check=True)
        quiet.finish()
    assert quiet.found and quiet.found == stream.found == [str(w.message) for w in loud]



def test_a_nested_column_never_shifts_the_columns_read(tmp_path):
    """A struct column (two Parquet columns) ahead of float columns: the lean read takes
    columns by their Parquet index, which a nested field shifts from the field's position
    (leaf 2 is ``junk``, field 2 is ``time``). It gives the file up (None: the full path reads
    it by name) or the very columns named; pyarrow's read by name is the reference."""
    from fretwear.io.parquet import read_known_block

    n = 50
    extra = pa.StructArray.from_arrays([pa.array(np.full(n, 7.0)), pa.array(np.full(n, 9.0))],
                                       ["a", "b"])
    table = pa.table({"extra": extra, "junk": np.arange(n) + 100.0, "time": np.arange(n) * 1e-3,
                      "normal_force": np.full(n, 5.0)})
    path = tmp_path / "nested.parquet"
    pq.write_table(table, path)
    read = read_known_block(path, 1000, lambda names, units: [names.index("time"),
                                                              names.index("normal_force")])
    if read is not None:
        expected = pq.read_table(path, columns=["time", "normal_force"])
        for got, want in zip(read[3], expected.columns, strict=True):
            np.testing.assert_array_equal(got, want.to_numpy())
