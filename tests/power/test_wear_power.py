"""Wear power (theory §2-§3): analytic cases, blocks, windows, sectors, streaming, errors."""

import json
import math
import warnings
from functools import reduce

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from fretwear.errors import HistoryError, InputError, StationarityWarning
from fretwear.history import ContactHistory
from fretwear.power import PowerAccumulator, PowerResult, wear_power
from fretwear.power.kernels import HAVE_NUMBA

BACKENDS = ["numpy", "numba"] if HAVE_NUMBA else ["numpy"]


def _slice(h, i, j):
    return h.replace(**{c: getattr(h, c)[i:j] for c in h.channels})


@pytest.mark.parametrize("backend", BACKENDS)
def test_constant_force_rotating_sliding_direction(backend):
    # Analytic: ‖Vt‖ = V constant while its direction turns, Fn = F: P = F·V exactly
    # (the integrand is constant, so the trapezoid rule is exact).
    F, V, w = 30.0, 0.02, 2 * np.pi * 7.0
    t = np.linspace(0.0, 3.0, 4001)
    h = ContactHistory(time=t, normal_force=np.full_like(t, F), vt1=V * np.cos(w * t),
                       vt2=V * np.sin(w * t))
    r = wear_power(h, blocks=3, backend=backend)
    assert r.total == pytest.approx(F * V, rel=1e-13)
    np.testing.assert_allclose(r.blocks, F * V, rtol=1e-12)
    assert r.spread == pytest.approx(0.0, abs=1e-12)
    assert r.sectors is None and r.duration == 3.0


@pytest.mark.parametrize("backend", BACKENDS)
def test_sinusoidal_sliding_gives_two_over_pi(backend):
    # Analytic: Vt = V0 sin ωt over whole periods, Fn = F: P = F·V0·2/π. The trapezoid rule
    # with N intervals per half period (step h = π/N in phase) gives exactly F·V0·h·cot(h/2)/π
    # (identity Σ_{k=1}^{N-1} sin(kπ/N) = cot(π/2N)).
    F, V0, f = 12.0, 0.05, 50.0
    N, periods = 400, 5
    t = np.linspace(0.0, periods / f, 2 * N * periods + 1)
    h = ContactHistory(time=t, normal_force=np.full_like(t, F),
                       vt1=V0 * np.sin(2 * np.pi * f * t), vt2=np.zeros_like(t))
    r = wear_power(h, backend=backend)
    step = np.pi / N
    assert r.total == pytest.approx(F * V0 * step / np.tan(step / 2) / np.pi, rel=1e-11)
    assert r.total == pytest.approx(F * V0 * 2 / np.pi, rel=1e-5)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("edges", [10, [-180.0, -100.0, 20.0, 45.0, 180.0]])
def test_turning_contact_point_gives_angular_shares(backend, edges):
    # Analytic: the contact point turns at a constant rate over 3 whole turns with constant
    # F and V, so each sector receives F·V·(arc/360°). Samples sit half a degree off the
    # (integer-degree) edges, each interval takes its left sample's sector.
    F, V, R = 5.0, 0.1, 1e-3
    theta = -180.0 + 0.5 + np.arange(3 * 360 + 1)  # degrees, 1° per step
    t = np.arange(theta.size) * 1e-3
    rad = np.radians(theta)
    h = ContactHistory(time=t, normal_force=np.full_like(t, F), vt1=np.full_like(t, V),
                       vt2=np.zeros_like(t), dy=R * np.cos(rad), dz=R * np.sin(rad))
    r = wear_power(h, sectors=edges, backend=backend)
    arcs = np.diff(r.sector_edges)
    np.testing.assert_allclose(r.sectors, F * V * arcs / 360.0, rtol=1e-12)
    assert r.sectors.sum() == pytest.approx(r.total, rel=1e-14)


@pytest.mark.parametrize("backend", BACKENDS)
def test_free_flight_and_sticking_excluded(backend):
    # Analytic: F·V on sliding contact intervals, 0 in free flight (Fn = 0) and on intervals
    # whose LEFT sample sticks; the time average keeps the whole window T.
    F, V = 8.0, 0.5
    t = np.arange(101) * 0.01  # 100 intervals, T = 1 s
    fn = np.full_like(t, F)
    fn[60:] = 0.0  # free flight from t = 0.6; interval 59 (F -> 0) is a half-trapezoid
    stick = np.zeros_like(t)
    stick[10:20] = 1.0  # 10 sticking intervals
    stick[-1] = 1.0  # the last sample starts no interval: no effect
    h = ContactHistory(time=t, normal_force=fn, vt1=np.full_like(t, V), vt2=np.zeros_like(t),
                       stick=stick)
    r = wear_power(h, backend=backend)
    sliding_contact = (59 - 10) * 0.01 + 0.5 * 0.01
    assert r.total == pytest.approx(F * V * sliding_contact / 1.0, rel=1e-13)
    s = r.statistics
    assert s.contact_time == pytest.approx(0.6, rel=1e-13)  # Fn linear from F to 0 on [0.59, 0.6]
    assert s.sliding_distance == pytest.approx(V * (0.6 - 0.1), rel=1e-13)


@pytest.mark.parametrize("backend", BACKENDS)
def test_blocks_and_window_on_a_ramp(backend):
    # Analytic: Fn = a + b·t, V constant: ∫ over [u, w] = V·(w - u)·(a + b·(u + w)/2), exact for
    # the trapezoid rule; window bounds and block edges fall inside intervals on purpose.
    a, b, V = 2.0, 3.0, 0.1
    t = np.linspace(0.0, 10.0, 101)  # step 0.1
    h = ContactHistory(time=t, normal_force=a + b * t, vt1=np.zeros_like(t),
                       vt2=np.full_like(t, -V))
    t0, t1, nb = 1.234, 8.765, 3
    with pytest.warns(StationarityWarning, match="3 block powers spread"):
        r = wear_power(h, t_start=t0, t_end=t1, blocks=nb, backend=backend)
    edges = np.linspace(t0, t1, nb + 1)
    mids = 0.5 * (edges[:-1] + edges[1:])
    np.testing.assert_allclose(r.block_edges, edges, rtol=1e-15)
    np.testing.assert_allclose(r.blocks, V * (a + b * mids), rtol=1e-12)
    assert r.total == pytest.approx(V * (a + b * (t0 + t1) / 2), rel=1e-12)
    assert r.total == pytest.approx(r.blocks.mean(), rel=1e-14)
    spread = b * (mids[-1] - mids[0]) / (a + b * (t0 + t1) / 2)
    assert r.spread == pytest.approx(spread, rel=1e-12)
    assert (r.t_start, r.t_end, r.duration) == (t0, t1, pytest.approx(t1 - t0))
    # statistics on the same window: mean force of a ramp, RMS from ∫(a+bt)² dt
    s = r.statistics
    assert s.force_mean == pytest.approx(a + b * (t0 + t1) / 2, rel=1e-12)
    ms = ((a + b * t1) ** 3 - (a + b * t0) ** 3) / (3 * b) / (t1 - t0)
    assert s.force_rms == pytest.approx(math.sqrt(ms), rel=1e-12)
    assert s.force_max == pytest.approx(a + b * t1, rel=1e-14)
    # a high threshold silences the warning
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wear_power(h, t_start=t0, t_end=t1, blocks=nb, stationarity_threshold=1.0,
                   backend=backend)


def test_window_inside_one_interval():
    # Analytic: a window strictly inside one interval integrates the linear interpolant there.
    h = ContactHistory(time=[0.0, 1.0], normal_force=[0.0, 10.0], vt1=[1.0, 1.0],
                       vt2=[0.0, 0.0])
    r = wear_power(h, t_start=0.2, t_end=0.6, blocks=2, stationarity_threshold=math.inf)
    np.testing.assert_allclose(r.blocks, [3.0, 5.0], rtol=1e-13)  # Fn at block midpoints
    assert r.total == pytest.approx(4.0, rel=1e-13)


def _random_history(seed, n=3000):
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.01, 0.02, n))
    ang = np.radians(rng.choice(np.arange(-180.0, 181.0, 36.0), n))
    dy, dz = rng.normal(size=n), rng.normal(size=n)
    on = rng.uniform(size=n) < 0.2
    dy[on], dz[on] = np.cos(ang[on]), np.sin(ang[on])
    return ContactHistory(time=t, normal_force=np.maximum(rng.normal(0.5, 1.0, n), 0.0),
                          vt1=rng.normal(size=n), vt2=rng.normal(size=n), dy=dy, dz=dz,
                          stick=(rng.uniform(size=n) < 0.1).astype(float), name="random")


KW = dict(blocks=4, sectors=10, force_threshold=0.2, minimum_rest_time=0.05)


def _same(r1: PowerResult, r2: PowerResult):
    assert r2.total == pytest.approx(r1.total, rel=1e-12)
    np.testing.assert_allclose(r2.blocks, r1.blocks, rtol=1e-12)
    np.testing.assert_allclose(r2.sectors, r1.sectors, rtol=1e-12, atol=1e-15)
    d1, d2 = r1.statistics.to_dict(), r2.statistics.to_dict()
    for key, v1 in d1.items():
        np.testing.assert_allclose(d2[key], v1, rtol=1e-11, err_msg=key)


@pytest.mark.parametrize("backend", BACKENDS)
def test_chunked_equals_one_shot(backend):
    # Independent computation: the one-shot result; chunks cut at arbitrary samples, with and
    # without a shared boundary sample, then merged in a tree (Dask-like) order.
    h = _random_history(5)
    t = h.time
    t0, t1 = t[10] + 0.003, t[-10] - 0.004
    one = wear_power(h, t_start=t0, t_end=t1, stationarity_threshold=math.inf,
                     backend=backend, **KW)
    cuts = [0, 7, 9, 400, 1201, 1202, 2000, 2999]
    overlapping = [_slice(h, i, min(j + 1, len(h)))
                   for i, j in zip(cuts[:-1], cuts[1:], strict=True)]
    bounds = [0, 500, 502, 1700, 3000]
    disjoint = [_slice(h, i, j) for i, j in zip(bounds[:-1], bounds[1:], strict=True)]
    for chunks in (overlapping, disjoint):
        acc = PowerAccumulator(t_start=t0, t_end=t1, backend=backend, **KW)
        for c in chunks:
            acc.update(c)
        _same(one, acc.result(stationarity_threshold=math.inf))
        parts = [PowerAccumulator(t_start=t0, t_end=t1, backend=backend, **KW).update(c)
                 for c in chunks]
        tree = reduce(lambda x, y: x.merge(y), parts[::-1])  # reversed order on purpose
        _same(one, tree.result(stationarity_threshold=math.inf))
    # an iterable of chunks is accepted directly
    _same(one, wear_power(iter(overlapping), t_start=t0, t_end=t1,
                          stationarity_threshold=math.inf, backend=backend, **KW))


def test_sector_sum_equals_total_and_backends_agree():
    h = _random_history(9)
    r = wear_power(h, blocks=3, sectors=[-180, -45, 0, 10, 170, 180], backend="numpy",
                   stationarity_threshold=math.inf)
    assert r.sectors.sum() == pytest.approx(r.total, rel=1e-13)
    assert r.blocks.mean() == pytest.approx(r.total, rel=1e-13)
    if HAVE_NUMBA:
        _same(r, wear_power(h, blocks=3, sectors=[-180, -45, 0, 10, 170, 180],
                            backend="numba", stationarity_threshold=math.inf))


def test_to_dict_is_json_ready():
    r = wear_power(_random_history(2, 200), sectors=4, stationarity_threshold=math.inf)
    d = json.loads(json.dumps(r.to_dict()))
    assert d["total"] == pytest.approx(r.total)
    assert len(d["sectors"]) == 4 and d["sector_edges"] == [-180.0, -90.0, 0.0, 90.0, 180.0]
    assert d["statistics"]["impact_count"] == r.statistics.impact_count


H = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[1.0, 1.0, 1.0], vt1=[1.0] * 3,
                   vt2=[0.0] * 3, name="h")


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        (dict(t_start=1.5, t_end=1.0), ["t_end = 1.0", "t_start = 1.5"]),
        (dict(t_end=3.0), ["t_end = 3.0", "last instant 2.0", "'h'"]),
        (dict(t_start=-1.0), ["t_start = -1.0", "first instant 0.0"]),
        (dict(t_start="soon"), ["t_start", "'soon'"]),
        (dict(t_end=math.nan), ["t_end", "finite"]),
        (dict(blocks=0), ["blocks", ">= 1"]),
        (dict(blocks=2.5), ["blocks", "integer"]),
        (dict(blocks=True), ["blocks", "integer"]),
        (dict(sectors=[-180, 0, 170]), ["sectors", "-180..180"]),
        (dict(sectors=[-180, 10, 10, 180]), ["sectors", "strictly increasing"]),
        (dict(sectors=0), ["sectors", "from 1 to 720"]),
        (dict(stationarity_threshold=-0.1), ["stationarity_threshold"]),
        (dict(force_threshold=-1.0), ["force_threshold", ">= 0"]),
        (dict(minimum_rest_time=math.inf), ["minimum_rest_time"]),
        (dict(chunk_size=1), ["chunk_size"]),
        (dict(backend="gpu"), ["backend", "'gpu'"]),
    ],
)
def test_bad_input_names_the_culprit(kwargs, words):
    with pytest.raises(InputError) as err:
        wear_power(H, **kwargs)
    for w in words:
        assert w in str(err.value)


def test_sectors_need_dy_dz():
    with pytest.raises(HistoryError, match="'dy'/'dz'"):
        wear_power(H, sectors=4)
    assert wear_power(H, sectors=1).sectors.tolist() == [1.0]  # one sector needs no angle


def test_streaming_errors():
    with pytest.raises(InputError, match="t_start is needed"):
        PowerAccumulator(blocks=2, t_end=1.0)
    acc = PowerAccumulator()
    with pytest.raises(HistoryError, match="no samples"):
        acc.result()
    acc.update(_slice(_random_history(1, 50), 10, 20))
    with pytest.raises(HistoryError, match="before the last instant"):
        acc.update(_slice(_random_history(1, 50), 5, 15))
    with pytest.raises(InputError, match="differ"):
        acc.merge(PowerAccumulator(sectors=3))
    with pytest.raises(InputError, match="ContactHistory chunk"):
        acc.update({"time": [0, 1]})
    with pytest.raises(InputError, match="history must be"):
        wear_power(3.0)


def test_user_arrays_not_modified():
    h = _random_history(4, 100)
    before = {c: getattr(h, c).copy() for c in h.channels}
    wear_power(h, blocks=2, sectors=3, stationarity_threshold=math.inf)
    for c, v in before.items():
        np.testing.assert_array_equal(getattr(h, c), v)


# _random_history draws displacements of order 1 m sampled every ~15 ms: a file of it is flagged
# as a likely mm / ms export (UnitsWarning, tested in tests/io/test_plausibility.py); this test
# is about chunked streaming, so that warning is expected here
@pytest.mark.filterwarnings("ignore::fretwear.errors.UnitsWarning")
@pytest.mark.parametrize("suffix", ["parquet", "csv"])
def test_file_is_streamed_in_chunks(tmp_path, suffix):
    # Independent computation: the in-memory one-shot result of the same history; the file is
    # read in chunks of 37 samples (bounded memory) and the time range found by a first pass.
    from fretwear.io import write_history

    h = _random_history(12, 500)
    path = tmp_path / f"h.{suffix}"
    write_history(h, path)
    kw = dict(blocks=3, sectors=10, force_threshold=0.1, minimum_rest_time=0.02,
              stationarity_threshold=math.inf)
    _same(wear_power(h, **kw), wear_power(path, chunk_size=37, **kw))
    # A numpy integer block count (e.g. from a config array) also triggers the time-range pass.
    kw["blocks"] = np.int64(3)
    _same(wear_power(h, **kw), wear_power(path, chunk_size=37, **kw))


_H = _random_history(21, 400)


@settings(max_examples=40, deadline=None)
@given(cuts=st.lists(st.integers(1, 398), min_size=1, max_size=8, unique=True),
       share=st.booleans(), order=st.randoms(use_true_random=False),
       window=st.tuples(st.floats(0.0, 0.4), st.floats(0.6, 1.0)))
def test_any_chunking_and_merge_order_equals_one_shot(cuts, share, order, window):
    # Property: the reduction is associative - any cut points, shared boundary sample or not,
    # merged in any order, give the one-shot result (independent computation).
    t = _H.time
    t0 = t[0] + window[0] * (t[-1] - t[0])
    t1 = t[0] + window[1] * (t[-1] - t[0])
    one = wear_power(_H, t_start=t0, t_end=t1, stationarity_threshold=math.inf, **KW)
    bounds = [0, *sorted(cuts), len(_H)]
    ranges = [(i, min(j + 1, len(_H)) if share else j)
              for i, j in zip(bounds[:-1], bounds[1:], strict=True)]
    assume(all(j - i >= 2 for i, j in ranges))  # a one-sample chunk is not a ContactHistory
    chunks = [_slice(_H, i, j) for i, j in ranges]
    parts = [PowerAccumulator(t_start=t0, t_end=t1, **KW).update(c) for c in chunks]
    while len(parts) > 1:
        k = order.randrange(len(parts) - 1)
        parts[k:k + 2] = [parts[k].merge(parts[k + 1]) if order.random() < 0.5
                          else parts[k + 1].merge(parts[k])]
    _same(one, parts[0].result(stationarity_threshold=math.inf))


def test_file_sets_and_tables_are_read_whole(tmp_path):
    # Independent computation: Fn = 4 N constant, ‖Vt‖ = 0.5 m/s constant (vt1 = 0.3,
    # vt2 = 0.4): P = 2 W exactly. IMPR_FONCTION TABLEAU files (one per channel, theory §1) and an
    # in-memory table with Code_Aster names and units (kN, mm/s) go through read_history.
    import pandas as pd

    t = [0.0, 1.0e-3, 2.0e-3]
    values = {"FN": 4.0, "VT1": 0.3, "VT2": 0.4}
    files = {}
    for name, v in values.items():
        rows = "".join(f" {x:12.5E}  {v:12.5E}\n" for x in t)
        files[name] = tmp_path / f"{name}.txt"
        files[name].write_text(f"#\n#FONCTION {name}\n INST         {name}\n{rows}")
    assert wear_power(list(files.values())).total == pytest.approx(2.0, rel=1e-12)
    keyed = {"fn": files["FN"], "vt1": files["VT1"], "vt2": files["VT2"]}
    assert wear_power(keyed, units={"force": "kN"}).total == pytest.approx(2e3, rel=1e-12)
    frame = pd.DataFrame({"INST": t, "FN": [4e-3] * 3, "VINT11": [300.0] * 3,
                          "VINT12": [400.0] * 3})
    r = wear_power(frame, units={"force": "kN", "velocity": "mm/s"}, blocks=2)
    assert r.total == pytest.approx(2.0, rel=1e-12)
    assert frame["FN"].tolist() == [4e-3] * 3  # the user's table is not modified
