"""KWU-EPRI class statistics (theory §4) on histories designed to fill known classes.

Every expected share, mid-value, m_h, m_w and w below is worked out by hand from theory §4 (and the
time-weighting and bound conventions documented in fretwear.laws.kwu_statistics), not by fretwear.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from fretwear import ContactHistory
from fretwear.errors import HistoryError, InputError, LawWarning
from fretwear.laws import (
    IMPACT_MASK,
    SLIDING_MASK,
    WEAR_LAWS,
    KwuEpriAccumulator,
    force_classes,
    kwu_epri_statistics,
    kwu_epri_statistics_from_chunks,
    speed_classes,
)

# Designed record, one sample per second; each interval belongs to its left sample.
# F_max = 50 N (class width 10 N), V_max = 0.5 m/s (class width 0.1 m/s).
#   samples 0-1 : F = 25 N, V = 0       -> (v=1, f=3)    2 s
#   sample  2   : F = 5 N,  V = 0.05    -> (v=1, f=1)    1 s
#   samples 3-5 : F = 50 N, V = 0.5     -> (v=5, f=5)    3 s   (both maxima: last classes)
#   sample  6   : F = 30 N, V = 0.25    -> (v=3, f=3)    1 s   (F on the bound 30 N: lower class)
#   sample  7   : F = 0,    V = 0.3     -> free flight, not counted
#   samples 8-9 : F = 12 N, V = 0.1     -> (v=2, f=2)    2 s   (V on the bound 0.1: upper class)
#   sample 10   : F = 0 (end of record, weight 0)
FN = [25, 25, 5, 50, 50, 50, 30, 0, 12, 12, 0]
VT = [0, 0, 0.05, 0.5, 0.5, 0.5, 0.25, 0.3, 0.1, 0.1, 0]
CONTACT_TIME = 9.0
EXPECTED_SHARES = {(1, 3): 2 / 9, (1, 1): 1 / 9, (5, 5): 3 / 9, (3, 3): 1 / 9, (2, 2): 2 / 9}
F_MID = [5.0, 15.0, 25.0, 35.0, 45.0]
V_MID = [0.05, 0.15, 0.25, 0.35, 0.45]


def designed_history(time=None, vt_split=False) -> ContactHistory:
    t = np.arange(11.0) if time is None else time
    vt = np.array(VT, dtype=float)
    if vt_split:   # same speeds split over two axes: ‖Vt‖ = √(vt1² + vt2²)
        return ContactHistory(time=t, normal_force=FN, vt1=0.6 * vt, vt2=-0.8 * vt)
    return ContactHistory(time=t, normal_force=FN, vt1=vt, vt2=np.zeros(11))


def hand_sums(k1=1.0, k2=1.0, k=5.0, c=10.0):
    """ΣP_h, ΣP_w, w of the designed record, by hand (theory §4)."""
    p11, p13, p22, p33, p55 = 1 / 9, 2 / 9, 2 / 9, 1 / 9, 3 / 9
    sum_h = p11 * k1 * k * (5 / c) ** 3 + p13 * k1 * k * (25 / c) ** 3       # impact: v = 1
    # sliding: (1,1) and v >= 2
    sum_w = (p11 * k2 * 5 * 0.05 ** 2 + p22 * k2 * 15 * 0.15 ** 2
             + p33 * k2 * 25 * 0.25 ** 2 + p55 * k2 * 45 * 0.45 ** 2)
    return sum_h, sum_w, sum_w ** 2 / (sum_h + sum_w)


def test_designed_history_classes_and_intensity():
    s = kwu_epri_statistics(designed_history())
    assert s.force_max == 50.0 and s.speed_max == 0.5
    assert s.contact_time == CONTACT_TIME and s.window_time == 10.0
    expected = np.zeros((5, 5))
    for (v, f), p in EXPECTED_SHARES.items():
        expected[v - 1, f - 1] = p
    np.testing.assert_allclose(s.shares, expected, rtol=1e-15, atol=0)
    np.testing.assert_allclose(s.force_bounds, [0, 10, 20, 30, 40, 50], rtol=1e-15)
    np.testing.assert_allclose(s.speed_bounds, [0, 0.1, 0.2, 0.3, 0.4, 0.5], rtol=1e-15)
    np.testing.assert_allclose(s.force_mid, F_MID, rtol=1e-15)
    np.testing.assert_allclose(s.speed_mid, V_MID, rtol=1e-15)
    # m_h on the first row: 5·(F̄/10)³; m_w on sliding cells: F̄·V̄²
    np.testing.assert_allclose(s.impact_intensity[0], [5 * 0.5 ** 3, 5 * 1.5 ** 3, 5 * 2.5 ** 3,
                                                       5 * 3.5 ** 3, 5 * 4.5 ** 3], rtol=1e-14)
    assert s.sliding_intensity[0, 0] == pytest.approx(5 * 0.05 ** 2, rel=1e-14)
    assert s.sliding_intensity[4, 4] == pytest.approx(45 * 0.45 ** 2, rel=1e-14)
    assert s.sliding_intensity[0, 1] == 0.0 and s.impact_intensity[1, 0] == 0.0
    sum_h, sum_w, w = hand_sums()
    assert s.impact_sum == pytest.approx(sum_h, rel=1e-14)
    assert s.sliding_sum == pytest.approx(sum_w, rel=1e-14)
    assert s.intensity == pytest.approx(w, rel=1e-14)
    # here ΣP_h > ΣP_w; Code_Aster would stop when ΣP_h < ΣP_w, we never do


def test_cell_11_counts_in_both_sums():
    assert IMPACT_MASK[0, 0] and SLIDING_MASK[0, 0]
    assert IMPACT_MASK.sum() == 5 and SLIDING_MASK.sum() == 21
    # a record entirely in (1,1): ΣP_h = 5·(5/10)³, ΣP_w = 5·0.05², w = ΣP_w²/(ΣP_h + ΣP_w)
    h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[5.0, 5.0, 0.0], vt1=[0.05, 0.05, 0.0],
                       vt2=[0.0, 0.0, 0.0])
    s = kwu_epri_statistics(h, force_max=50.0, speed_max=0.5)
    assert s.shares[0, 0] == 1.0
    assert s.impact_sum == pytest.approx(0.625, rel=1e-14)
    assert s.sliding_sum == pytest.approx(0.0125, rel=1e-14)
    assert s.intensity == pytest.approx(0.0125 ** 2 / 0.6375, rel=1e-14)


def test_factors_k1_k2_k_c():
    s = kwu_epri_statistics(designed_history(), impact_factor=2.0, sliding_factor=3.0, k=4.0,
                            c=20.0)
    sum_h, sum_w, w = hand_sums(k1=2.0, k2=3.0, k=4.0, c=20.0)
    assert (s.impact_sum, s.sliding_sum) == (pytest.approx(sum_h, rel=1e-14),
                                             pytest.approx(sum_w, rel=1e-14))
    assert s.intensity == pytest.approx(w, rel=1e-14)


def test_time_weighting_by_left_interval():
    # stretch the interval of sample 2 (class (1,1)) from 1 s to 4 s: its share becomes 4/12
    t = np.array([0, 1, 2, 6, 7, 8, 9, 10, 11, 12, 13], dtype=float)
    s = kwu_epri_statistics(designed_history(time=t))
    assert s.contact_time == 12.0
    assert s.shares[0, 0] == pytest.approx(4 / 12, rel=1e-15)
    assert s.shares[4, 4] == pytest.approx(3 / 12, rel=1e-15)


def test_speed_is_the_norm_of_vt1_vt2():
    a = kwu_epri_statistics(designed_history())
    b = kwu_epri_statistics(designed_history(vt_split=True))
    np.testing.assert_allclose(b.shares, a.shares, rtol=1e-15)
    assert b.intensity == pytest.approx(a.intensity, rel=1e-12)


def test_class_bounds():
    # force classes closed on the right of (0, F_max]; speed classes on the left of [0, V_max]
    assert force_classes([1e-9, 10.0, 10.000001, 30.0, 49.9, 50.0, 60.0], 50.0).tolist() == \
        [1, 1, 2, 3, 5, 5, 5]
    assert speed_classes([0.0, 0.099, 0.1, 0.3, 0.4999, 0.5, 0.7], 0.5).tolist() == \
        [1, 1, 2, 4, 5, 5, 5]
    assert speed_classes([0.0, 0.0, 0.1], 0.0).tolist() == [1, 1, 5]
    # no rounding of the width to whole newtons: F_max = 7 N -> width 1.4 N
    with pytest.warns(LawWarning):   # most forces are above 7 N
        s = kwu_epri_statistics(designed_history(), force_max=7.0)
    np.testing.assert_allclose(s.force_bounds, [0, 1.4, 2.8, 4.2, 5.6, 7.0], rtol=1e-14)


def test_user_maxima_and_clipping_warning():
    # F_max = 100 N, width 20 N: 25 -> f=2, 5 -> 1, 50 -> 3, 30 -> 2, 12 -> 1;
    # V_max = 1 m/s, width 0.2 m/s: 0 -> v=1, 0.05 -> 1, 0.5 -> 3, 0.25 -> 2, 0.1 -> 1
    s = kwu_epri_statistics(designed_history(), force_max=100.0, speed_max=1.0)
    expected = np.zeros((5, 5))
    expected[0, 1] = 2 / 9     # (1, 2)
    expected[0, 0] = 1 / 9 + 2 / 9   # (1, 1): F=5, V=0.05 and F=12, V=0.1
    expected[2, 2] = 3 / 9     # (3, 3)
    expected[1, 1] = 1 / 9     # (2, 2)
    np.testing.assert_allclose(s.shares, expected, rtol=1e-15)
    # maxima below the data: counted in the last class, with a warning giving the share
    with pytest.warns(LawWarning, match=r"33.3% of the contact time is above"):
        s = kwu_epri_statistics(designed_history(), force_max=40.0)
    assert s.time_above_max == 3.0
    assert s.shares[4, 4] == pytest.approx(3 / 9)


def test_window():
    # [t_start, t_end] = [3, 7]: samples 3..7, intervals 3-6 -> (5,5) 3 s and (3,3) 1 s
    s = kwu_epri_statistics(designed_history(), t_start=3.0, t_end=7.0)
    assert s.contact_time == 4.0 and s.t_start == 3.0 and s.t_end == 7.0
    assert s.shares[4, 4] == pytest.approx(0.75) and s.shares[2, 2] == pytest.approx(0.25)
    assert s.force_max == 50.0 and s.speed_max == 0.5


def test_no_contact():
    h = ContactHistory(time=[0.0, 1.0], normal_force=[0.0, 0.0], vt1=[1.0, 1.0], vt2=[0.0, 0.0])
    with pytest.warns(LawWarning, match="no contact"):
        s = kwu_epri_statistics(h)
    assert s.intensity == 0.0 and s.shares.sum() == 0.0


def test_streaming_matches_whole_record():
    h = designed_history()
    whole = kwu_epri_statistics(h, force_max=50.0, speed_max=0.5)
    # one accumulator fed consecutive chunks (the interval across chunks is kept)
    acc = KwuEpriAccumulator(50.0, 0.5)
    for lo, hi in ((0, 3), (3, 4), (4, 11)):
        acc.update(history={"time": h.time[lo:hi], "normal_force": h.normal_force[lo:hi],
                            "vt1": h.vt1[lo:hi], "vt2": h.vt2[lo:hi]})
    np.testing.assert_allclose(acc.result().shares, whole.shares, rtol=1e-15)
    # two accumulators on pieces sharing their boundary sample, merged
    a, b = KwuEpriAccumulator(50.0, 0.5), KwuEpriAccumulator(50.0, 0.5)
    a.update(h.time[:6], h.normal_force[:6], h.sliding_speed[:6])
    b.update(h.time[5:], h.normal_force[5:], h.sliding_speed[5:])
    merged = a.merge(b).result()
    np.testing.assert_allclose(merged.class_time, whole.class_time, rtol=1e-15)
    assert merged.intensity == pytest.approx(whole.intensity, rel=1e-15)
    with pytest.raises(InputError, match="same force_max"):
        a.merge(KwuEpriAccumulator(60.0, 0.5))
    with pytest.raises(HistoryError, match="time order"):
        acc.update(h.time[:2], h.normal_force[:2], h.sliding_speed[:2])


def test_accumulator_result_kept_only_while_counts_and_factors_are_the_same():
    """result() keeps its last statistics (a wear table per contact asks once per table): the
    kept one is the whole record's (kwu_epri_statistics, an independent pass); new counts or
    other factors give new statistics; a result that warns (force above force_max) warns at
    every call."""
    h = designed_history()
    acc = KwuEpriAccumulator(50.0, 0.5)
    acc.update(h.time[:6], h.normal_force[:6], h.sliding_speed[:6])
    first = acc.result(k=4.0)
    assert acc.result(k=4.0) is first
    other = acc.result(k=6.0)
    assert other is not first and other.k == 6.0 and acc.result(k=4.0) is not other
    acc.update(h.time[6:], h.normal_force[6:], h.sliding_speed[6:])
    whole = kwu_epri_statistics(h, force_max=50.0, speed_max=0.5, k=4.0)
    after = acc.result(k=4.0)
    assert after.intensity == pytest.approx(whole.intensity, rel=1e-15)
    np.testing.assert_allclose(after.class_time, whole.class_time, rtol=1e-15)
    assert after.intensity != first.intensity
    low = KwuEpriAccumulator(0.5 * float(h.normal_force.max()), 0.5)
    low.update(h.time, h.normal_force, h.sliding_speed)
    for _ in range(2):
        with pytest.warns(LawWarning, match="above"):
            low.result()


def test_two_pass_chunks_matches_direct():
    h = designed_history()
    pieces = [{"time": h.time[i:i + 4], "normal_force": h.normal_force[i:i + 4],
               "vt1": h.vt1[i:i + 4]} for i in range(0, 11, 4)]
    calls = []

    def chunks():
        calls.append(1)
        return iter(pieces)

    s = kwu_epri_statistics_from_chunks(chunks, k=4.0)
    assert len(calls) == 2   # first pass: the maxima
    direct = kwu_epri_statistics(h, k=4.0)
    np.testing.assert_allclose(s.shares, direct.shares, rtol=1e-15)
    assert s.intensity == pytest.approx(direct.intensity, rel=1e-15)
    calls.clear()
    kwu_epri_statistics_from_chunks(chunks, force_max=50.0, speed_max=0.5)
    assert len(calls) == 1
    with pytest.raises(InputError, match="unknown option"):
        kwu_epri_statistics_from_chunks(chunks, coef_k=4.0)


def test_result_views():
    s = kwu_epri_statistics(designed_history())
    frame = s.to_frame()
    assert len(frame) == 25 and frame["share"].sum() == pytest.approx(1.0)
    row = frame[(frame.speed_class == 5) & (frame.force_class == 5)].iloc[0]
    assert row.force_mid == 45.0 and row.speed_mid == pytest.approx(0.45) and row.sliding
    assert s.share_table().shape == (5, 5)
    text = str(s)
    _, _, w = hand_sums()
    assert f"w = {w:.6g}" in text and "33.333" in text    # (5,5) share 3/9 in %
    assert s.to_dict()["intensity"] == s.intensity
    with pytest.raises(ValueError):
        s.shares[0, 0] = 1.0    # read-only result


def test_registry_statistics_and_volume():
    law = WEAR_LAWS["KWU_EPRI"]
    s = law.statistics(designed_history(), COEF_FNOR=2.0, COEF_K=4.0, COEF_USURE=1e-14)
    _, _, w = hand_sums(k1=2.0, k=4.0)
    assert s.intensity == pytest.approx(w, rel=1e-14)
    # V = k_r·w/w_r·P·t with the history parameters accepted and unused by the volume
    v = law.volume(0.01, 100.0, reference_coefficient=1e-14, intensity=s.intensity, k=4.0)
    assert float(v) == pytest.approx(1e-14 * w * 0.01 * 100.0, rel=1e-14)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        law.statistics(designed_history())


def test_default_maxima_are_the_window_maxima_free_flight_included():
    """Theory §4: F_max, V_max default to "the maxima in the window" (all samples of the window).

    Hand computation: the free-flight sample (Fn = 0) slides at 2 m/s, every contact sample at
    1 m/s, so V_max = 2 and the contact samples fall in speed class floor(5·1/2) + 1 = 3 (mid-value
    V̄_3 = 2.5·2/5 = 1.0 m/s). Force: F_max = 10 N, class 5 (mid 9 N). Two contact intervals of 1 s
    out of 2 s of contact time: p(3, 5) = 1. No impact class: ΣP_h = 0, ΣP_w = 9·1² = 9, w = 9.
    """
    from fretwear import ContactHistory
    from fretwear.laws import kwu_epri_statistics

    h = ContactHistory(time=[0.0, 1.0, 2.0, 3.0], normal_force=[10.0, 10.0, 0.0, 0.0],
                       vt1=[1.0, 1.0, 2.0, 0.0], vt2=[0.0, 0.0, 0.0, 0.0])
    s = kwu_epri_statistics(h)
    assert s.speed_max == 2.0
    assert s.force_max == 10.0
    assert float(s.shares[2, 4]) == 1.0
    assert s.impact_sum == 0.0
    assert s.intensity == pytest.approx(9.0, rel=1e-14)


# ------------------------------------------------------------ streaming from a file or chunks
# the designed record is sampled every 1 s (hand-computed shares): written to a file, its step
# is flagged as a likely ms export (UnitsWarning), irrelevant to the class counts
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_file_path_is_streamed_and_equals_the_designed_values(tmp_path):
    """A history file read in chunks of 3 samples (consecutive chunks share one sample) gives the
    hand-computed shares and w of the designed record (independent of the in-memory path)."""
    from fretwear.io import write_history

    path = write_history(designed_history(), tmp_path / "designed.csv")
    s = kwu_epri_statistics(path, chunk_size=3)
    expected = np.zeros((5, 5))
    for (v, f), p in EXPECTED_SHARES.items():
        expected[v - 1, f - 1] = p
    np.testing.assert_allclose(s.shares, expected, rtol=1e-15, atol=0)
    assert (s.force_max, s.speed_max, s.contact_time) == (50.0, 0.5, CONTACT_TIME)
    assert s.intensity == pytest.approx(hand_sums()[2], rel=1e-14)
    # through the registry, with a window: samples 0..6 -> contact intervals 0-5 (6 s):
    # (1,3) 2 s, (1,1) 1 s, (5,5) 3 s; F_max, V_max still 50 N, 0.5 m/s
    w = WEAR_LAWS["KWU_EPRI"].statistics(str(path), t_end=6.0, chunk_size=4,
                                         read_options={"format": "csv"})
    assert w.contact_time == 6.0
    assert w.shares[0, 2] == pytest.approx(2 / 6) and w.shares[4, 4] == pytest.approx(3 / 6)
    with pytest.raises(InputError, match="chunk_size"):
        kwu_epri_statistics(path, chunk_size=1)


def test_list_and_iterator_of_chunks():
    h = designed_history()
    pieces = [ContactHistory(time=h.time[i:i + 5], normal_force=h.normal_force[i:i + 5],
                             vt1=h.vt1[i:i + 5], vt2=h.vt2[i:i + 5]) for i in (0, 4, 8)]
    direct = kwu_epri_statistics(h)
    listed = kwu_epri_statistics(pieces)         # re-iterable: two passes
    np.testing.assert_allclose(listed.class_time, direct.class_time, rtol=1e-15)
    once = kwu_epri_statistics(iter(pieces), force_max=50.0, speed_max=0.5)
    assert once.intensity == pytest.approx(direct.intensity, rel=1e-15)
    with pytest.raises(InputError, match="give force_max and speed_max"):
        kwu_epri_statistics(iter(pieces))
    with pytest.raises(InputError, match="reader options go with a history file"):
        kwu_epri_statistics(h, format="csv")
    with pytest.raises(InputError, match="must be a ContactHistory"):
        kwu_epri_statistics(3.0)


def test_given_maxima_are_checked_and_kept_without_contact():
    h = ContactHistory(time=[0.0, 1.0, 2.0], normal_force=[0.0, 0.0, 0.0], vt1=[0.1, 0.2, 0.0],
                       vt2=[0.0, 0.0, 0.0])
    with pytest.warns(LawWarning, match="no contact"):
        s = kwu_epri_statistics(h, force_max=100.0)
    # the user's F_max is kept (bounds 0, 20, ..., 100 N); V_max from the window: 0.2 m/s
    assert s.force_max == 100.0 and s.speed_max == 0.2 and s.intensity == 0.0
    np.testing.assert_allclose(s.force_bounds, [0, 20, 40, 60, 80, 100])
    for bad in ({"force_max": 0.0}, {"force_max": -1.0}, {"speed_max": float("nan")}):
        with pytest.raises(InputError, match=next(iter(bad))):
            kwu_epri_statistics(designed_history(), **bad)
    with pytest.raises(InputError, match="t_end"):
        kwu_epri_statistics(designed_history(), t_start=5.0, t_end=5.0)


def test_printed_table_shows_bounds_mid_values_sums_and_w():
    text = str(kwu_epri_statistics(designed_history()))
    sum_h, sum_w, w = hand_sums()
    assert "F_max = 50 N, V_max = 0.5 m/s" in text
    assert "f3 20-30" in text and "v2 0.1-0.2" in text        # class bounds
    mid_f = next(line for line in text.splitlines() if line.startswith("mid F̄_f"))
    assert mid_f.split()[-5:] == ["5", "15", "25", "35", "45"]
    assert text.splitlines()[5].rstrip().endswith("0.15")       # row v2 ends with V̄_2
    assert f"sum P_h = {sum_h:.6g}" in text and f"sum P_w = {sum_w:.6g}" in text
    assert f"w = {w:.6g}" in text
