"""A history exported in mm, mm/s, ms, mN or kN is caught by the plausibility checks (issue 15).

The shipped example history (a tube in its support gap, SI units) passes every check; the same
history written in other units fails the checks of docs/formats.md "Plausibility checks", each
warning naming the channel, the value, the unit read, the likely unit and the units option; with
that option the history reads back as the SI one (the wear power of the mm file was 1000 times
too large before).
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from fretwear.errors import UnitsWarning
from fretwear.history import ContactHistory
from fretwear.io import iter_history_chunks, read_history, write_history
from fretwear.io.plausibility import THRESHOLDS, check_plausibility, impact_durations
from fretwear.power import wear_power

EXAMPLE = Path(__file__).parents[2] / "examples" / "data" / "oscillator_gap.csv"


def _units_warnings(function, *args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = function(*args, **kwargs)
    return result, [str(w.message) for w in caught if w.category is UnitsWarning]


def test_the_example_history_is_plausible():
    history, found = _units_warnings(read_history, EXAMPLE)
    assert found == []
    assert check_plausibility(history) == []


@pytest.fixture
def in_mm(tmp_path):
    """The example written with displacements in mm and velocities in mm/s (× 1000)."""
    h = read_history(EXAMPLE)
    scaled = h.replace(dy=h.dy * 1e3, dz=h.dz * 1e3, vt1=h.vt1 * 1e3, vt2=h.vt2 * 1e3)
    return write_history(scaled, tmp_path / "mm.csv"), h


def test_a_file_in_millimetres_is_named_with_the_fix(in_mm):
    path, si = in_mm
    history, found = _units_warnings(read_history, path)
    speed = [m for m in found if "sliding speed" in m]
    assert len(speed) == 1 and len(found) == 2
    top = si.sliding_speed.max() * 1e3
    assert (f"channel 'vt1': largest sliding speed ‖Vt‖ {top:.4g} m/s (read in 'm/s') is above "
            "the plausibility limit 10 m/s; a file in 'mm/s' gives this") in speed[0]
    assert "[history] units = { velocity = 'mm/s' }" in speed[0]
    assert "--units velocity=mm/s" in speed[0] and "units={'velocity': 'mm/s'}" in speed[0]
    assert any("radial displacement" in m and "length = 'mm'" in m for m in found)
    # the power read in the wrong units is 1000 times the SI one; with the fix it is the same
    assert wear_power(history).total == pytest.approx(1e3 * wear_power(si).total, rel=1e-12)
    fixed, found = _units_warnings(read_history, path,
                                   units={"length": "mm", "velocity": "mm/s"})
    assert found == []
    np.testing.assert_allclose(fixed.vt1, si.vt1, rtol=1e-15)
    assert wear_power(fixed).total == pytest.approx(wear_power(si).total, rel=1e-12)


def test_a_file_in_milliseconds(tmp_path):
    si = read_history(EXAMPLE)
    path = write_history(si.replace(time=si.time * 1e3, vt1=si.vt1 * 1e-3, vt2=si.vt2 * 1e-3),
                         tmp_path / "ms.csv")  # ms and m/ms
    _, found = _units_warnings(read_history, path)
    step = [m for m in found if "sampling step" in m]
    assert len(step) == 1
    assert "channel 'time': median sampling step 0.2 s (read in 's') is above the plausibility " \
           "limit 0.005 s; a file in 'ms' gives this" in step[0]
    assert any("mean impact duration" in m for m in found)
    fixed, found = _units_warnings(read_history, path, units={"time": "ms", "velocity": "m/ms"})
    assert found == []
    np.testing.assert_allclose(fixed.time, si.time, rtol=1e-12)


@pytest.mark.parametrize("factor, key, likely", [(1e5, "force_max", "mN"),
                                                  (1e-4, "force_min", "kN")])
def test_forces_in_other_units(tmp_path, factor, key, likely):
    si = read_history(EXAMPLE)
    # every force of the file in the other unit (a normal force alone in kN beside tangential
    # forces in N also breaks Coulomb's bound: tests/io/test_plausibility_friction.py)
    path = write_history(si.replace(normal_force=si.normal_force * factor, ft1=si.ft1 * factor,
                                    ft2=si.ft2 * factor), tmp_path / "f.csv")
    _, found = _units_warnings(read_history, path)
    assert len(found) == 1 and f"a file in {likely!r} gives this" in found[0]
    assert THRESHOLDS[key].fix in found[0]


def test_chunked_reading_warns_once_per_check(in_mm):
    path, _ = in_mm
    chunks, found = _units_warnings(lambda p: list(iter_history_chunks(p, chunk_size=1000)), path)
    assert len(chunks) > 10
    assert len(found) == 2  # one per failed check, not one per chunk


def test_in_memory_histories_are_not_checked():
    """Only what is read from a file is checked: code building histories is trusted."""
    h, found = _units_warnings(ContactHistory, time=[0.0, 1.0], normal_force=[1e9, 1e9],
                               vt1=[100.0, 100.0], vt2=[0.0, 0.0])
    assert found == []
    with pytest.warns(UnitsWarning) as seen:
        assert len(check_plausibility(h)) == 3  # speed, force, step, when asked
    assert len(seen) == 3


def test_impact_durations_of_complete_episodes():
    t = np.arange(10.0) * 1e-3
    fn = np.array([5, 0, 1, 1, 0, 0, 2, 2, 2, 0.0])  # open first episode dropped
    np.testing.assert_allclose(impact_durations(t, fn), [2e-3, 3e-3])


def test_force_floor_is_checked_on_the_whole_stream(tmp_path):
    """A file in kN (largest force 0.005 'N') warns once, after the last chunk or block, with
    the file's largest force; a file whose first block is free flight with a rounding residue
    (1e-15 N) and whose later impacts reach 40 N does not warn (StreamPlausibility)."""
    import warnings as _warnings

    import numpy as _np

    from fretwear.errors import UnitsWarning
    from fretwear.history import ContactHistory
    from fretwear.io import iter_history_blocks, iter_history_chunks, write_history

    t = _np.arange(4000) * 1e-4
    fn = _np.where(t > 0.2, 40.0 * _np.maximum(_np.sin(2 * _np.pi * 50 * t), 0.0), 1e-15)
    h = ContactHistory(time=t, normal_force=fn, vt1=0.01 * _np.cos(t), vt2=0.0 * t)
    quiet = write_history(h, tmp_path / "quiet.parquet", row_group_size=500)
    kilo = write_history(h.replace(normal_force=fn / 8000.0), tmp_path / "kilo.parquet",
                         row_group_size=500)
    for iterate in (iter_history_chunks, iter_history_blocks):
        with _warnings.catch_warnings():
            _warnings.simplefilter("error", UnitsWarning)
            assert sum(len(c) for c in iterate(quiet, 500)) >= len(t)
        with pytest.warns(UnitsWarning, match=r"largest normal force 0\.005 N") as caught:
            list(iterate(kilo, 500))
        assert len([w for w in caught if "largest normal force" in str(w.message)]) == 1
