"""Contact statistics (USURE/IMPACT-like): analytic triangle-pulse trains and streaming merges.

Analytic source: a triangular force pulse 0 -> P -> 0 over [s, s + 2w] (linear between samples)
is above a threshold F_s on [s + wF_s/P, s + 2w - wF_s/P]; on each ramp's above part
∫Fn dt = w(1 - F_s/P)(F_s + P)/2 and ∫Fn² dt = w(1 - F_s/P)(F_s² + F_s·P + P²)/3.
"""

import json
import math

import numpy as np
import pytest

from fretwear.history import ContactHistory
from fretwear.power import PowerAccumulator, contact_statistics, wear_power
from fretwear.power.kernels import HAVE_NUMBA, fused_numpy
from fretwear.power.statistics import merge_groups

BACKENDS = ["numpy", "numba"] if HAVE_NUMBA else ["numpy"]
W = 1.0  # half-width of every pulse [s]
PEAKS = [4.0, 2.0, 8.0, 4.0]  # [N]
GAPS = [0.5, 3.0, 0.2]  # zero-force rest between pulse k's end and pulse k+1's start [s]
V = 0.3  # sliding speed [m/s]


def _train(stick_pulse=None):
    t, f, st = [], [], []
    s = 0.0
    starts = []
    for k, p in enumerate(PEAKS):
        starts.append(s)
        t += [s, s + W, s + 2 * W]
        f += [0.0, p, 0.0]
        st += [1.0 if k == stick_pulse else 0.0] * 3
        s += 2 * W + (GAPS[k] if k < len(GAPS) else 0.0)
    t.append(t[-1] + 1.0)  # a final rest of 1 s
    f.append(0.0)
    st.append(0.0)
    t = np.array(t)
    h = ContactHistory(time=t, normal_force=f, vt1=np.full(t.size, V), vt2=np.zeros(t.size),
                       stick=st, name="train")
    return h, np.array(starts)


def _crossings(starts, thr):
    up = np.array([s + W * thr / p for s, p in zip(starts, PEAKS, strict=True)])
    down = np.array([s + 2 * W - W * thr / p for s, p in zip(starts, PEAKS, strict=True)])
    return up, down


@pytest.mark.parametrize("backend", BACKENDS)
def test_pulse_train_threshold_and_rest(backend):
    h, starts = _train()
    thr, rest = 1.0, 1.5
    s = contact_statistics(h, force_threshold=thr, minimum_rest_time=rest, backend=backend)
    up, down = _crossings(starts, thr)
    rests = up[1:] - down[:-1]  # 1.25, 3.625, 0.575 s: merge 1+2 and 3+4
    assert np.allclose(rests, [1.25, 3.625, 0.575])
    assert s.impact_count == 2
    durations = [down[1] - up[0], down[3] - up[2]]
    assert s.impact_duration_mean == pytest.approx(np.mean(durations), rel=1e-13)
    assert s.impact_duration_max == pytest.approx(max(durations), rel=1e-13)
    assert s.impact_peak_force_mean == pytest.approx((4.0 + 8.0) / 2, rel=1e-13)
    assert s.force_max == 8.0
    ct = np.sum(down - up)
    assert s.contact_time == pytest.approx(ct, rel=1e-13)
    T = h.duration
    assert s.duration == T and s.contact_fraction == pytest.approx(ct / T, rel=1e-13)
    frac = [1 - thr / p for p in PEAKS]
    i1 = sum(2 * W * q * (thr + p) / 2 for q, p in zip(frac, PEAKS, strict=True))
    i2 = sum(2 * W * q * (thr**2 + thr * p + p**2) / 3 for q, p in zip(frac, PEAKS, strict=True))
    assert s.force_mean_contact == pytest.approx(i1 / ct, rel=1e-12)
    assert s.force_rms_contact == pytest.approx(math.sqrt(i2 / ct), rel=1e-12)
    assert s.force_mean == pytest.approx(sum(p * W for p in PEAKS) / T, rel=1e-13)
    assert s.force_rms == pytest.approx(math.sqrt(sum(2 * W * p**2 / 3 for p in PEAKS) / T),
                                        rel=1e-13)
    assert s.sliding_distance == pytest.approx(V * ct, rel=1e-13)
    assert (s.force_threshold, s.minimum_rest_time) == (thr, rest)


@pytest.mark.parametrize("backend", BACKENDS)
def test_defaults_count_every_pulse(backend):
    # threshold 0, rest 0: every pulse is an impact lasting 2w; mean contact force P/2 weighted
    h, starts = _train(stick_pulse=2)
    s = contact_statistics(h, backend=backend)
    assert s.impact_count == 4
    assert s.impact_duration_mean == pytest.approx(2 * W, rel=1e-13)
    assert s.contact_time == pytest.approx(8 * W, rel=1e-13)
    assert s.force_mean_contact == pytest.approx(sum(PEAKS) * W / (8 * W), rel=1e-13)
    # sticking pulse 3: no sliding distance there, and no wear power there either
    assert s.sliding_distance == pytest.approx(V * 6 * W, rel=1e-13)
    r = wear_power(h, backend=backend)
    assert r.total == pytest.approx(V * W * (sum(PEAKS) - PEAKS[2]) / h.duration, rel=1e-13)


def test_window_cuts_an_impact():
    # window starting at the peak of pulse 1: the impact counts, truncated at t_start
    h, starts = _train()
    s = contact_statistics(h, t_start=starts[0] + W, force_threshold=0.0)
    assert s.impact_count == 4
    assert s.impact_duration_max == pytest.approx(2 * W, rel=1e-13)
    assert s.impact_duration_mean == pytest.approx((W + 6 * W) / 4, rel=1e-13)
    assert s.force_max == 8.0


def test_touching_pulses_are_two_impacts_even_across_chunks():
    # 0 -> 5 -> 0 -> 5 -> 0 with rest 0: the force touches zero at t = 2, two impacts;
    # a chunk boundary inside a pulse (t = 1) must not split it, one at t = 2 must not fuse.
    h = ContactHistory(time=[0.0, 1.0, 2.0, 3.0, 4.0], normal_force=[0.0, 5.0, 0.0, 5.0, 0.0],
                       vt1=[1.0] * 5, vt2=[0.0] * 5)
    assert contact_statistics(h).impact_count == 2
    for cut in (1, 2, 3):
        acc = PowerAccumulator()
        acc.update(h.window(0.0, float(cut))).update(h.window(float(cut), 4.0))
        assert acc.result().statistics.impact_count == 2
    # with a rest time of 0.1 s, the instantaneous touch does not end the impact
    assert contact_statistics(h, minimum_rest_time=0.1).impact_count == 1


def test_no_contact():
    h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[0.0] * 3, vt1=[1.0] * 3,
                       vt2=[0.0] * 3)
    s = contact_statistics(h)
    assert s.impact_count == 0 and s.contact_time == 0.0 and s.force_max == 0.0
    # Code_Aster's convention (POST_DYNA_MODA_T: statch T_CHOC_MOYEN/T_CHOC_MAXI, fstat0
    # MOYEN_T_CHOC/RMS_T_CHOC, impact F_MAX_MOY are 0 without a shock), not NaN
    assert s.impact_duration_mean == 0.0 and s.impact_duration_max == 0.0
    assert s.impact_peak_force_mean == 0.0
    assert s.force_mean_contact == 0.0 and s.force_rms_contact == 0.0
    d = json.loads(json.dumps(s.to_dict()))
    assert d["force_mean_contact"] == 0.0 and d["impact_count"] == 0


def test_merge_groups_is_associative():
    # Independent computation: the one-shot groups of a random pulse train.
    rng = np.random.default_rng(3)
    n = 600
    t = np.cumsum(rng.uniform(0.01, 0.1, n))
    fn = np.maximum(rng.normal(0.0, 1.0, n), 0.0)
    z = np.zeros(n)
    edges = np.array([-180.0, 180.0])
    be = np.array([-np.inf, np.inf])

    def groups(i, j, rest):
        return fused_numpy(t[i:j], fn[i:j], z[i:j] + 1.0, z[i:j], None, None, None, -np.inf,
                           np.inf, be, edges, 0.3, rest).groups

    for rest in (0.0, 0.15, 1.0):
        whole = groups(0, n, rest)
        a, b, c = groups(0, 201, rest), groups(200, 401, rest), groups(400, n, rest)
        left = merge_groups(merge_groups(a, b, rest), c, rest)
        right = merge_groups(a, merge_groups(b, c, rest), rest)
        np.testing.assert_allclose(left, whole, rtol=1e-13)
        np.testing.assert_allclose(right, whole, rtol=1e-13)
        assert whole[0] > (3 if rest < 1.0 else 0)


def test_per_block_fields():
    # blocks of the pulse train: per-block contact fraction and mean force add up to the totals
    h, _ = _train()
    s = contact_statistics(h, blocks=4)
    assert s.block_contact_fraction.mean() == pytest.approx(s.contact_fraction, rel=1e-13)
    assert s.block_force_mean.mean() == pytest.approx(s.force_mean, rel=1e-13)
    assert s.block_sliding_distance.sum() == pytest.approx(s.sliding_distance, rel=1e-13)
