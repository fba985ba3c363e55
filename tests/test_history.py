"""ContactHistory validation and conversions (theory §1)."""

import numpy as np
import pytest

from fretwear import ContactHistory, HistoryError
from fretwear.history import contact_angle


def make(**changes):
    kw = dict(time=[0.0, 1.0, 2.0, 3.0], normal_force=[0.0, 5.0, 10.0, 0.0],
              vt1=[0.1, 0.2, 0.3, 0.4], vt2=[0.0, 0.0, 0.0, 0.0], name="N1")
    kw.update(changes)
    return ContactHistory(**kw)


def test_valid_history_is_copied_and_read_only():
    fn = np.array([0.0, 5.0, 10.0, 0.0])
    h = make(normal_force=fn)
    fn[1] = 99.0  # the user's array changes, the history does not
    assert h.normal_force[1] == 5.0
    with pytest.raises(ValueError):
        h.normal_force[0] = 1.0
    assert h.duration == 3.0
    assert h.channels == ("time", "normal_force", "vt1", "vt2")


def test_user_array_not_modified_by_negative_noise_clipping():
    fn = np.array([0.0, -1e-15, 10.0, 0.0])
    h = make(normal_force=fn)
    assert fn[1] == -1e-15
    assert h.normal_force[1] == 0.0


@pytest.mark.parametrize(
    ("changes", "words"),
    [
        (dict(time=[0.0, 1.0, 1.0, 3.0]), ["'time'", "row 2", "strictly increasing"]),
        (dict(time=[0.0, 2.0, 1.0, 3.0]), ["'time'", "row 2"]),
        (dict(normal_force=[0.0, np.nan, 1.0, 0.0]), ["'normal_force'", "row 1", "non-finite"]),
        (dict(vt1=[0.0, 0.0, np.inf, 0.0]), ["'vt1'", "row 2"]),
        (dict(normal_force=[0.0, 5.0, -2.0, 0.0]), ["'normal_force'", "negative", "row 2"]),
        (dict(vt2=[0.0, 0.0, 0.0]), ["'vt2'", "3 samples", "4"]),
        (dict(vt1=None), ["'vt1'", "missing"]),
        (dict(dy=[0.0, 0.0, 0.0, 0.0]), ["'dz'", "dy"]),
        (dict(stick=[0, 2, 0, 0]), ["'stick'", "row 1"]),
        (dict(time=[0.0], normal_force=[0.0], vt1=[0.0], vt2=[0.0]), ["two instants"]),
        (dict(vt1=[[0.0, 1.0], [2.0, 3.0]]), ["'vt1'", "one-dimensional"]),
    ],
)
def test_bad_input_names_the_culprit(changes, words):
    with pytest.raises(HistoryError) as err:
        make(**changes)
    for w in words:
        assert w in str(err.value)
    assert "'N1'" in str(err.value)


def test_window_and_replace_and_frame_round_trip():
    h = make(dy=[1.0, 0.0, -1.0, 0.0], dz=[0.0, 1.0, 0.0, -1.0])
    w = h.window(1.0, 2.0)
    assert w.time.tolist() == [1.0, 2.0]
    with pytest.raises(HistoryError, match="fewer than two"):
        h.window(1.2, 1.8)
    back = ContactHistory.from_frame(h.to_frame(), name="N1")
    for ch in h.channels:
        np.testing.assert_array_equal(getattr(back, ch), getattr(h, ch))
    with pytest.raises(HistoryError, match="unknown column"):
        ContactHistory.from_frame(h.to_frame().rename(columns={"vt1": "VTX"}))


def test_angle_convention():
    # theory §3: theta = atan2(dz, dy) in (-180, 180], 0 where dy = dz = 0.
    h = make(dy=[1.0, 0.0, -1.0, 0.0], dz=[0.0, 1.0, -0.0, 0.0])
    assert h.angle.tolist() == [0.0, 90.0, 180.0, 0.0]
    # atan2 rounds to exactly -pi here: folded to +180 (the interval is open at -180).
    assert contact_angle([-1.0], [-1e-300]).tolist() == [180.0]
    assert make().angle.tolist() == [0.0] * 4
    # Signed zeros, as Code_Aster prints -0.00000E+00: still the centre, theta = 0 (theory §3).
    assert contact_angle([-0.0, -0.0, 0.0], [0.0, -0.0, -0.0]).tolist() == [0.0, 0.0, 0.0]
    np.testing.assert_allclose(h.sliding_speed, np.hypot(h.vt1, h.vt2))
