"""Units checked against the contact's geometry (issue 29, point 2). The histories are built
here: a 20 Hz orbit of amplitude A with the sliding speed 2π f A of that orbit (the analytic
speed of x = A sin 2πft), written in SI or as an export in mm and mm/s would give them."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import InputError, UnitsWarning
from fretwear.history import ContactHistory
from fretwear.table import wear_table

RADIUS, WIDTH = 9.525e-3, 12.7e-3
GEOMETRY = dict(contact_type="TUBE_BAV", dimensions={"mobile_radius": RADIUS,
                                                      "obstacle_width": WIDTH})
LAW = dict(law="ARCHARD", coefficients={"coefficient": 1e-14}, instants=[1.0],
           time_unit="year")


def orbit(amplitude=41e-6, frequency=20.0, length=1.0, speed=1.0) -> ContactHistory:
    """A tube orbiting at ``frequency`` [Hz] in contact (5 N): lengths × ``length``, speeds ×
    ``speed`` (1000, 1000: a file in mm and mm/s read as SI)."""
    t = np.linspace(0.0, 1.0, 20001)
    w = 2 * np.pi * frequency
    return ContactHistory(time=t, normal_force=np.full(t.size, 5.0),
                          vt1=speed * amplitude * w * np.cos(w * t), vt2=np.zeros(t.size),
                          dy=length * amplitude * np.sin(w * t), dz=np.zeros(t.size), name="N1")


def units_warnings(history):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        wear_table(history, **GEOMETRY, **LAW)
    return [str(w.message) for w in caught if issubclass(w.category, UnitsWarning)]


def test_an_si_orbit_passes():
    assert units_warnings(orbit()) == []


def test_an_export_in_mm_and_mm_per_s_is_named_against_the_tube():
    """41 µm and 5 mm/s read as 41 mm and 5 m/s: under the absolute limits (50 mm, 10 m/s),
    but the orbit is larger than the tube's radius (9.525 mm)."""
    said = units_warnings(orbit(length=1000.0, speed=1000.0))
    assert any("orbit" in m and "outer radius" in m and "length = 'mm'" in m for m in said), said


def test_speeds_in_mm_per_s_beside_lengths_in_m_are_named():
    said = units_warnings(orbit(speed=1000.0))
    assert any("sliding speed" in m and "velocity = 'mm/s'" in m for m in said), said
    # the ratio said is the 1000 of the export (2π f A is the orbit's own speed), to the
    # crossing count's resolution (one crossing of the 40 of a second at 20 Hz: 2.5 %)
    ratio = float(said[0].split(" is ")[1].split(" times")[0])
    assert ratio == pytest.approx(1000.0, rel=0.05)


def test_an_orbit_beyond_ten_gaps_of_a_bore_is_named():
    bore = dict(contact_type="TUBE_ALESAGE",
                dimensions={"mobile_radius": RADIUS, "obstacle_radius": RADIUS + 0.2e-3,
                            "obstacle_width": WIDTH})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        wear_table(orbit(amplitude=3e-3), **bore, **LAW)  # 3 mm in a 0.2 mm gap
    said = [str(w.message) for w in caught if issubclass(w.category, UnitsWarning)]
    assert any("radial gap" in m for m in said), said


def test_a_wall_thicker_than_the_tube_is_an_error_naming_the_key_and_the_unit():
    with pytest.raises(InputError) as info:
        wear_table(0.01, **GEOMETRY, **LAW, wall_thickness=1.09)
    text = str(info.value)
    assert "wall_thickness" in text and "mm" in text and "0.00109" in text
    wear_table(0.01, **GEOMETRY, **LAW, wall_thickness=1.09e-3)  # the same in metres: fine


def test_a_manifest_wall_in_mm_fails_that_contact_naming_the_column(tmp_path):
    from fretwear.bundle import run_bundle

    frame = pd.DataFrame({"contact": ["A", "B"], "power.value_W": [1e-3, 1e-3],
                          "wall_thickness_m": [1.09, 1.09e-3]})
    case = tmp_path / "base.toml"
    case.write_text('[law]\nmobile = { COEF_USURE = 1e-14 }\n[geometry]\ncontact_type = '
                    '"TUBE_BAV"\nmobile_radius_m = 9.525e-3\nobstacle_width_m = 12.7e-3\n'
                    '[time]\ninstants = [1]\nunit = "year"\n')
    result = run_bundle(frame, case, scheduler="serial")
    errors = result.errors.set_index("contact")
    assert list(errors.index) == ["A"]
    assert "wall_thickness_m" in errors.loc["A", "message"]
    assert "0.00109" in errors.loc["A", "message"]


def test_the_bundle_terminal_says_units_warnings_one_line_with_counts(tmp_path, capsys):
    """Two streamed histories exported in mm and mm/s, one in SI: one UnitsWarning line on the
    terminal, naming 2 contacts."""
    pytest.importorskip("pyarrow")
    from fretwear.cli import main
    from fretwear.io import write_history

    rows = []
    for name, scale in (("mm1", 1000.0), ("si", 1.0), ("mm2", 1000.0)):
        write_history(orbit(length=scale, speed=scale), tmp_path / f"{name}.parquet")
        rows.append({"contact": name, "history": f"{name}.parquet"})
    pd.DataFrame(rows).to_csv(tmp_path / "manifest.csv", index=False)
    (tmp_path / "base.toml").write_text(
        '[law]\nmobile = { COEF_USURE = 1e-14 }\n[geometry]\ncontact_type = "TUBE_BAV"\n'
        'mobile_radius_m = 9.525e-3\nobstacle_width_m = 12.7e-3\n[time]\ninstants = [1]\n'
        'unit = "year"\n')
    main(["bundle", str(tmp_path / "manifest.csv"), "--case", str(tmp_path / "base.toml"),
          "--scheduler", "serial", "-o", str(tmp_path / "out"), "-q"])
    out = capsys.readouterr().out
    lines = [x for x in out.splitlines() if x.startswith("UnitsWarning:")]
    assert len(lines) == 1, out
    assert "2 contacts" in lines[0] and "mm1" in lines[0] and "mm2" in lines[0]
    assert "si," not in lines[0] and "si)" not in lines[0]
    assert math.isfinite(len(out))


def test_the_median_of_the_crossings_is_numpys():
    """``geometry_units.median`` (a partition, used for the zero crossings of dy) equals
    :func:`numpy.median` bit for bit (one process: the same arithmetic, the middle value or the
    mean of the two middle ones) on odd and even sizes, ties and values of mixed magnitude."""
    from fretwear.io.geometry_units import median

    rng = np.random.default_rng(28)
    for n in [*range(1, 40), 999, 1000, 4096]:
        for _ in range(20):
            a = rng.normal(size=n) * 10.0 ** rng.integers(-9, 9, size=n)
            if n > 4:
                a[: n // 3] = a[n // 2]  # ties across the middle
            assert median(a) == float(np.median(a))


@pytest.mark.parametrize("n", [3, 4, 5, 1000, 1001])
def test_the_compiled_motion_pass_gives_the_numpy_numbers(n, monkeypatch):
    """``geometry_units._motion`` through the compiled pass (``io._compiled.motion``) against
    the numpy expressions (``_orbit``, ``_frequency``, ``_speed``: the reference, forced by
    ``plausibility._KERNEL = None``): orbit, frequency and largest speed equal bit for bit (one
    process: the same operations), on random and flat motions, a dy equal to its median at
    samples (signbit of +0.0 and -0.0), speeds whose squares overflow; and the kernel ran."""
    pytest.importorskip("numba")
    from fretwear.io import _compiled, geometry_units, plausibility

    rng = np.random.default_rng(n)
    t = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, n))
    cases = [rng.normal(0.0, 1e-4, (4, n)), np.zeros((4, n)), rng.normal(0.0, 1e200, (4, n))]
    ties = rng.normal(0.0, 1e-4, (4, n))
    ties[0, ::2] = np.median(ties[0])
    ties[0, 1] = -0.0
    cases.append(ties)
    calls = []
    kernel = _compiled.motion
    monkeypatch.setattr(_compiled, "motion", lambda *a: calls.append(1) or kernel(*a))
    for dy, dz, v1, v2 in cases:
        h = ContactHistory(time=t, normal_force=np.full(n, 5.0), vt1=v1, vt2=v2, dy=dy, dz=dz)
        monkeypatch.setattr(plausibility, "_KERNEL", _compiled)
        compiled = geometry_units._motion(h)
        monkeypatch.setattr(plausibility, "_KERNEL", None)
        reference = (geometry_units._orbit(h), geometry_units._frequency(h),
                     geometry_units._speed(h))
        assert compiled[:2] == pytest.approx(reference[:2], rel=0, abs=0, nan_ok=True)
        if reference[0] > 0 and math.isfinite(reference[1]):  # the speed the check reads
            assert compiled[2] == reference[2]
    assert len(calls) == len(cases)


def test_the_median_is_the_partitions_bit_for_bit():
    """``median`` takes the middle values from numpy's sort: the reference is the partition
    (numpy's introselect, ``_partition_median``) and :func:`numpy.median`, on arrays with
    ties, odd and even sizes and zeros of both signs in the middle (compared with their sign:
    the crossings of ``dy - median`` count by ``numpy.signbit``)."""
    from fretwear.io.geometry_units import _partition_median, median

    rng = np.random.default_rng(28)
    cases = [rng.normal(size=n) for n in (3, 4, 999, 1000)]
    cases += [rng.integers(-3, 4, size=n).astype(float) for n in (5, 6, 1001, 1000)]  # ties
    cases += [np.array([-0.0, 0.0, 1.0, -1.0, -0.0]), np.array([1.0, -0.0, 0.0, -1.0]),
              np.array([0.0, -0.0, -0.0, 2.0, -2.0, 0.0]), np.zeros(7), -np.zeros(8),
              np.array([-1.0, 0.0, 3.0, -0.0])]
    for a in cases:
        got, want = median(a), _partition_median(a)
        assert got == want == float(np.median(a))
        assert math.copysign(1.0, got) == math.copysign(1.0, want), a
