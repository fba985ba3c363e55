"""The coupled loop dynamics → wear table → obstacle update → dynamics (``fretwear iterate``).

Checks against independent computations: the wear power of each cycle's history (theory §2,
trapezoid with the stick rule, computed here), Archard's V = K·P·t chained through the restart
(theory §7: V_cumulated = V_previous + K·P_k·Δt), and the worn clearance fed back to the dynamics.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from fretwear.dynamics.config import dynamics_from_config
from fretwear.errors import KeywordError
from fretwear.workflows.loop import DEPTHS_OF, iterate_case, load_iterate_case

K_MOBILE, K_OBSTACLE = 2e-14, 1e-14  # [1/Pa], large so that one cycle opens the gap visibly
YEAR = 31536000.0


def case(tmp_path, cycles=2, **iterate):
    return {
        "law": {"name": "ARCHARD", "mobile": {"COEF_USURE": K_MOBILE},
                "obstacle": {"COEF_USURE": K_OBSTACLE}},
        "geometry": {"contact_type": "TUBE_ALESAGE", "mobile_radius_m": 9.5e-3,
                     "obstacle_radius_m": 9.7e-3, "obstacle_width_m": 0.02},
        "sectors": {"count": 8},
        "time": {"instants": [0.5, 1.0], "unit": "year"},
        "obstacle": {"type": "circle", "gap_m": 2e-4, "wall_thickness_m": 1.1e-3},
        "dynamics": {
            "duration_s": 0.4, "time_step_s": 2e-5, "archive_step_s": 1e-4,
            "modes": {"frequencies_Hz": [30.0, 30.0], "damping_ratios": 0.02,
                      "masses_kg": 0.5, "shock_shapes": [[[1.0, 0.0], [0.0, 1.0]]],
                      "forcing_shapes": [[[1.0, 0.0], [0.0, 1.0]]]},
            # a harmonic force along y: impacts at 0° and 180°, sliding from friction-free z
            "shocks": [{"name": "bore", "obstacle": "case", "normal_stiffness_N_per_m": 1e6,
                        "normal_damping_N_s_per_m": 20.0, "friction": 0.3,
                        "tangential_stiffness_N_per_m": 1e6}],
            "forces": [{"point": 0, "direction": "y", "kind": "harmonic", "amplitude": 12.0,
                        "frequency_Hz": 25.0},
                       {"point": 0, "direction": "z", "kind": "harmonic", "amplitude": 6.0,
                        "frequency_Hz": 25.0, "phase_deg": 90.0}],
        },
        "iterate": {"cycles": cycles, "plot": False, **iterate},
        "_directory": str(tmp_path),
    }


def _power(h):
    p = h.normal_force * np.hypot(h.vt1, h.vt2)
    keep = h.stick[:-1] == 0
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(h.time) * keep) / h.duration)


def test_loop_chains_tables_and_feeds_the_worn_profile(tmp_path):
    res = iterate_case(case(tmp_path), output=tmp_path / "out")
    assert res.stopped == "cycles" and len(res.tables) == 2
    import pyarrow.parquet as pq

    powers = []
    for k in (1, 2):
        frame = pq.read_table(tmp_path / "out" / f"cycle_{k:02d}" / "histories" /
                              "bore.parquet").to_pandas()
        from fretwear.history import ContactHistory

        powers.append(_power(ContactHistory.from_frame(frame)))
    assert res.summary["power"].tolist() == pytest.approx(powers, rel=1e-9)
    # Archard, chained through the restart: global volumes at the end of each cycle
    t1, t2 = res.tables
    last1 = t1[t1["instant"] == t1["instant"].max()]
    last2 = t2[t2["instant"] == t2["instant"].max()]
    v1 = float(last1["volume_mobile_cumulated"].sum())
    v2 = float(last2["volume_mobile_cumulated"].sum())
    assert v1 == pytest.approx(K_MOBILE * powers[0] * YEAR, rel=1e-9)
    assert v2 == pytest.approx(v1 + K_MOBILE * powers[1] * YEAR, rel=1e-9)
    assert float(last2["instant"].iloc[0]) == pytest.approx(2.0)
    # the worn clearance opened around the impact directions 0° and 180°
    p1 = res.profiles[0]
    i0, i90 = int(np.argmin(np.abs(p1.angle - 0.0))), int(np.argmin(np.abs(p1.angle - 90.0)))
    assert p1.clearance_worn[i0] > p1.clearance_initial[i0] + 1e-6
    assert np.all(p1.clearance_worn >= p1.clearance_initial - 1e-12)
    # ...and the second dynamics saw it: every contact of cycle 2 lies on or beyond the worn
    # clearance of cycle 1 (the new circle would give contacts from r = 0.2 mm on)
    h2 = pd.read_parquet(tmp_path / "out" / "cycle_02" / "histories" / "bore.parquet")
    hit = h2[h2["normal_force"] > 0]
    r = np.hypot(hit["dy"], hit["dz"])
    theta = np.mod(np.degrees(np.arctan2(hit["dz"], hit["dy"])), 360.0)
    seen = np.interp(theta, p1.angle, p1.clearance_worn)
    assert len(hit) > 0 and np.all(r >= seen - 1e-7)
    assert r.max() > 2e-4 + 0.5 * (p1.clearance_worn[i0] - p1.clearance_initial[i0])
    assert p1.clearance_worn[i0] - p1.clearance_initial[i0] > \
        p1.clearance_worn[i90] - p1.clearance_initial[i90]
    for name in ("wear_table.csv", "obstacle_profile.csv", "obstacle_discret.txt",
                 "dynamics.json"):
        assert (tmp_path / "out" / "cycle_02" / name).exists()
    assert (tmp_path / "out" / "summary.csv").exists()


def test_loop_stops_at_depth(tmp_path):
    res = iterate_case(case(tmp_path, cycles=5, max_depth_m=1e-9), output=tmp_path / "o")
    assert res.stopped == "max_depth" and len(res.summary) == 1


def test_case_errors(tmp_path):
    c = case(tmp_path)
    c["iterate"]["cylces"] = 3
    with pytest.raises(KeywordError, match="did you mean 'cycles'"):
        load_iterate_case(c)
    c = case(tmp_path)
    del c["sectors"]
    with pytest.raises(KeywordError, match="sectors"):
        iterate_case(c, output=tmp_path / "x")
    c = case(tmp_path)
    c["dynamics"]["shocks"][0]["normal_stifness_N_per_m"] = 1.0
    with pytest.raises(KeywordError, match="normal_stiffness_N_per_m"):
        dynamics_from_config(c["dynamics"])
    c = case(tmp_path)
    c["history"] = {"file": "x.csv"}
    with pytest.raises(KeywordError, match="history"):
        load_iterate_case(c)
    # sector mode is Archard only (operator._sector_frame): refused before any dynamics runs
    c = case(tmp_path)
    c["law"] = {"name": "KWU_EPRI", "mobile": {"COEF_USURE": 1e-14}}
    with pytest.raises(KeywordError, match="KWU_EPRI.*Archard coefficients only"):
        iterate_case(c, output=tmp_path / "kwu")
    assert not (tmp_path / "kwu").exists()


def test_beam_config_matches_blevins():
    # [dynamics.beam] → clamped-pinned modes, λ1 = 3.92660 (Blevins Table 8-1)
    s = dynamics_from_config({
        "duration_s": 0.1,
        "beam": {"young_modulus_Pa": 2e11, "second_moment_m4": 2.5e-9,
                 "mass_per_length_kg_per_m": 0.9, "length_m": 1.0, "modes": 2,
                 "ends": ["clamped", "pinned"]},
        "shocks": [{"position_m": 0.5, "obstacle": "circle", "gap_m": 1e-4,
                    "normal_stiffness_N_per_m": 1e6}],
        "base": [{"direction": "y", "kind": "random", "psd_frequencies_Hz": [5, 50],
                  "psd": [1.0, 1.0], "seed": 2}]})
    f1 = 3.92660231**2 / (2 * math.pi) * math.sqrt(2e11 * 2.5e-9 / 0.9)
    assert s.model.frequencies[0] == pytest.approx(f1, rel=1e-7)
    assert s.options["archive_step"] == 1e-4


LOOP_TOML = """
[law]
name = "ARCHARD"
mobile = { COEF_USURE = 2e-14 }
[geometry]
contact_type = "TUBE_ALESAGE"
mobile_radius_m = 9.5e-3
obstacle_radius_m = 9.7e-3
obstacle_width_m = 0.02
[sectors]
count = 8
[time]
instants = [1.0]
unit = "year"
[obstacle]
gap_m = 2e-4
wall_thickness_m = 1.1e-3
[dynamics]
duration_s = 0.2
time_step_s = 2e-5
[dynamics.modes]
frequencies_Hz = [30.0, 30.0]
damping_ratios = 0.02
masses_kg = 0.5
shock_shapes = [[[1.0, 0.0], [0.0, 1.0]]]
forcing_shapes = [[[1.0, 0.0], [0.0, 1.0]]]
[[dynamics.shocks]]
name = "bore"
obstacle = "case"
normal_stiffness_N_per_m = 1e6
[[dynamics.forces]]
point = 0
direction = "y"
amplitude = 12.0
frequency_Hz = 25.0
[iterate]
cycles = 3
output = "out"
"""


def test_cli_iterate(tmp_path):
    from fretwear.cli import main

    toml = tmp_path / "loop.toml"
    toml.write_text(LOOP_TOML, encoding="utf-8")
    assert main(["iterate", str(toml), "--cycles", "2", "-q"]) == 0
    summary = pd.read_csv(tmp_path / "out" / "summary.csv")
    assert summary["cycle"].tolist() == [1, 2]
    assert (tmp_path / "out" / "cycle_02" / "contact_history.png").exists()
    assert (tmp_path / "out" / "iteration.svg").exists()
    runner = CliRunner()
    from fretwear.cli import cli

    help_text = runner.invoke(cli, ["iterate", "--help"]).output
    for key in ("max_depth_m", "normal_stiffness_N_per_m", "psd_frequencies_Hz", "supports_m"):
        assert key in help_text


def test_example_case_runs_one_cycle(tmp_path):
    # examples/iterate_tube_support.toml stays valid (one cycle, no figures)
    from pathlib import Path

    from fretwear.cli import main

    example = Path(__file__).resolve().parents[2] / "examples" / "iterate_tube_support.toml"
    assert main(["iterate", str(example), "-n", "1", "--no-plot", "-q", "-o",
                 str(tmp_path)]) == 0
    s = pd.read_csv(tmp_path / "summary.csv")
    assert s["cycle"].tolist() == [1] and s["power"].iloc[0] > 0
    assert s["depth_mobile_max"].iloc[0] > 0


def test_long_histories_are_reduced_by_chunks(tmp_path, monkeypatch):
    # The chunked reduction of the Parquet file (bounded memory) gives the in-memory result:
    # iter_history_chunks shares one sample between chunks, so the trapezoid sums agree.
    import fretwear.workflows.loop as loop

    c = case(tmp_path, cycles=1)
    c["power"] = {"t_start_s": 0.05, "blocks": 2, "t_end_s": 0.4}
    whole = iterate_case(c, output=tmp_path / "whole")
    monkeypatch.setattr(loop, "LOOP_IN_MEMORY", 100)
    monkeypatch.setattr(loop, "PLOT_SAMPLES", 500)
    monkeypatch.setattr(loop, "LOOP_CHUNK", 700)  # 4001 samples: 6 chunks
    seen = {}
    original = loop._cycle_power

    def spy(result, iw, args, *rest):
        out = original(result, iw, args, *rest)
        seen["history"] = out[1]
        return out

    monkeypatch.setattr(loop, "_cycle_power", spy)
    chunked = iterate_case(c, output=tmp_path / "chunked")
    light = seen["history"]
    assert len(light) == 501 and light.metadata["decimated_by"] == 8  # rows 0, 8, ..., 4000
    assert np.allclose(np.diff(light.time), 8e-4)
    a, b = whole.summary.iloc[0], chunked.summary.iloc[0]
    assert b["power"] == pytest.approx(a["power"], rel=1e-12)
    assert b["contact_fraction"] == pytest.approx(a["contact_fraction"], rel=1e-12)
    np.testing.assert_allclose(chunked.tables[0]["volume_mobile_sector"],
                               whole.tables[0]["volume_mobile_sector"], rtol=1e-12)


def test_cycle_one_sees_the_clearance_figure_of_planes(tmp_path, monkeypatch):
    # A disk of radius R_m between two planes at gap g (normal along y) can translate
    # g/|cos ψ| along a direction ψ before it touches (the clearance figure, theory §8; geometry in
    # fretwear.obstacle.PlanesObstacle Notes), not by the radial gap (R_m + g)/|cos ψ| − R_m,
    # which is R_m(1/|cos ψ| − 1) larger (1.47 mm more at 30° for R_m = 9.5 mm). Cycle 1 must
    # feed the dynamics the clearance figure: its profile, and the contacts it produces, lie on
    # the planes |dy| = g.
    import fretwear.workflows.loop as loop

    g, rm = 2e-4, 9.5e-3
    c = case(tmp_path, cycles=1)
    c["dynamics"]["duration_s"] = 0.2
    c["geometry"] = {"contact_type": "TUBE_BAV", "mobile_radius_m": rm,
                     "obstacle_width_m": 0.02}
    c["obstacle"] = {"type": "planes", "plane_gap_m": g, "wall_thickness_m": 1.1e-3}
    seen = []
    original = loop.simulate

    def spy(model, shocks, *args, **kwargs):
        seen.append(list(shocks))
        return original(model, shocks, *args, **kwargs)

    monkeypatch.setattr(loop, "simulate", spy)
    res = iterate_case(c, output=tmp_path / "out")
    shock = seen[0][0]
    assert shock.obstacle == "profile"
    psi = np.radians(shock.profile_angles)
    near = np.abs(np.cos(psi)) >= math.cos(math.radians(80.0))  # inside the closing circle
    np.testing.assert_allclose(shock.profile_gaps[near], g / np.abs(np.cos(psi[near])),
                               rtol=1e-6)
    i60 = int(np.flatnonzero(shock.profile_angles == 60.0)[0])
    assert shock.profile_gaps[i60] == pytest.approx(2 * g, rel=1e-6)  # not 2g + R_m
    # the motion: contacts only on the planes, some of them oblique (|ψ| > 30°), where the
    # radial-gap figure would have kept the tube free
    h = pd.read_parquet(tmp_path / "out" / "cycle_01" / "histories" / "bore.parquet")
    hit = h[h["normal_force"] > 0]
    assert len(hit) > 0 and res.summary["power"].iloc[0] > 0
    assert np.all(np.abs(hit["dy"]) >= g - 1e-12)
    theta = np.arctan2(hit["dz"], hit["dy"])
    oblique = np.abs(np.cos(theta)) < math.cos(math.radians(30.0))
    radial_gap = (rm + g) / np.abs(np.cos(theta)) - rm
    assert np.count_nonzero(oblique) > 0
    assert np.all(np.hypot(hit["dy"], hit["dz"])[oblique] < radial_gap[oblique] - 1e-3)


def test_loop_stop_criterion_names_its_depth(tmp_path):
    """One cycle gives the three depths; a threshold between the smallest and the largest
    stops the loop under 'largest' but not under the smallest one's name."""
    first = iterate_case(case(tmp_path, cycles=1), output=tmp_path / "a")
    row = first.summary.iloc[0]
    values = {name: max(row[c] for c in cols) for name, cols in DEPTHS_OF.items()}
    assert values["largest"] == max(values["global"], values["sector"], values["profile"])
    smallest = min(("global", "sector", "profile"), key=values.get)
    assert values[smallest] < values["largest"]
    threshold = 0.5 * (values[smallest] + values["largest"])
    stop = iterate_case(case(tmp_path, cycles=2, max_depth_m=threshold),
                        output=tmp_path / "b")
    assert stop.stopped == "max_depth" and stop.max_depth_of == "largest"
    assert len(stop.summary) == 1
    # the summary file says which depth the criterion compared, and against what
    saved = json.loads((tmp_path / "b" / "summary.json").read_text(encoding="utf-8"))
    assert saved["stopped"] == "max_depth" and saved["max_depth_of"] == "largest"
    assert saved["max_depth_m"] == threshold
    assert saved["max_depth_columns"] == list(DEPTHS_OF["largest"])
    go_on = iterate_case(case(tmp_path, cycles=2, max_depth_m=threshold,
                              max_depth_of=smallest), output=tmp_path / "c")
    assert len(go_on.summary) == 2  # cycle 1's depth of that name stayed below
    last = go_on.summary.iloc[-1]
    assert (go_on.stopped == "max_depth") == (
        max(last[c] for c in DEPTHS_OF[smallest]) >= threshold)
    with pytest.raises(KeywordError, match="max_depth_of = 'deepest'"):
        iterate_case(case(tmp_path, max_depth_of="deepest"), output=tmp_path / "d")


def _batch_means(h, blocks, level=0.95):
    """(mean, half-width) [W] of the batch-means interval of a history's power over its whole
    span in ``blocks`` equal blocks, computed here: trapezoid with the stick rule per block
    (theory §2), Student's t with B − 1 degrees of freedom (Fishman 1996, §6.6)."""
    from scipy import stats

    edges = np.linspace(h.time[0], h.time[-1], blocks + 1)
    p = h.normal_force * np.hypot(h.vt1, h.vt2)
    powers = []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        inside = (h.time >= a - 1e-12) & (h.time <= b + 1e-12)
        t, q, stick = h.time[inside], p[inside], h.stick[inside]
        keep = stick[:-1] == 0
        powers.append(float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(t) * keep) / (b - a)))
    powers = np.array(powers)
    return powers.mean(), stats.t.ppf(0.5 * (1 + level), blocks - 1) * powers.std(ddof=1) \
        / math.sqrt(blocks)


def test_each_cycle_power_has_its_batch_means_interval(tmp_path):
    """The loop's interval is the batch-means interval of the cycle's history in
    confidence_blocks blocks, computed here independently; the table's power is unchanged."""
    import pyarrow.parquet as pq

    from fretwear.history import ContactHistory

    blocks = 8  # 0.4 s of history: blocks of 0.05 s, each a full period of the 25 Hz force
    res = iterate_case(case(tmp_path, confidence_blocks=blocks, confidence_level=0.9),
                       output=tmp_path / "out")
    # fewer than 10 blocks: a ConfidenceWarning says so, in the loop's warnings
    assert any(w.startswith("ConfidenceWarning") and "only 8 blocks" in w for w in res.warnings)
    for k, row in res.summary.iterrows():
        frame = pq.read_table(tmp_path / "out" / f"cycle_{k + 1:02d}" / "histories" /
                              "bore.parquet").to_pandas()
        h = ContactHistory.from_frame(frame)
        mean, half = _batch_means(h, blocks, level=0.9)
        assert row["power"] == pytest.approx(mean, rel=1e-9)
        assert row["power_half_width"] == pytest.approx(half, rel=1e-6)
        assert row["power_interval_count"] == blocks and row["power_level"] == 0.9
        assert str(res.intervals[k]).endswith("W (90 %)")
    change = res.summary["power"].iloc[1] - res.summary["power"].iloc[0]
    assert res.summary["power_change"].iloc[1] == pytest.approx(change, rel=1e-12)
    assert res.summary["power_change_half_width"].iloc[1] == pytest.approx(
        math.hypot(*res.summary["power_half_width"]), rel=1e-12)
    assert res.summary["power_change_significant"].iloc[1] == (
        abs(change) > res.summary["power_change_half_width"].iloc[1])
    saved = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert saved["convergence"] == res.convergence[0]
    assert saved["power_intervals"] == [str(iv) for iv in res.intervals]


def test_convergence_is_judged_against_the_noise(tmp_path):
    """Convergence is claimed only when the interval of the last change lies inside the
    tolerance band. The same cycles run again (bit for bit on one machine) with a tolerance just
    above |ΔP| + h stop 'converged' after cycle 2; just below, the noise leaves it undecided
    and the loop goes on; without a tolerance a change within the noise is never converged."""
    free = iterate_case(case(tmp_path, cycles=2), output=tmp_path / "free")
    last = free.summary.iloc[-1]
    reach = (abs(last["power_change"]) + last["power_change_half_width"]) / last["power"]
    res = iterate_case(case(tmp_path, cycles=3, convergence_tolerance=1.01 * reach),
                       output=tmp_path / "wide")
    assert res.stopped == "converged" and len(res.summary) == 2
    assert res.convergence[0] == "converged"
    res = iterate_case(case(tmp_path, cycles=2, convergence_tolerance=0.99 * reach),
                       output=tmp_path / "narrow")
    assert res.stopped == "cycles" and len(res.summary) == 2
    expected = ("undecided" if abs(last["power_change"]) - last["power_change_half_width"]
                <= 0.99 * reach * last["power"] else "not converged")
    assert res.convergence[0] == expected
    within = abs(last["power_change"]) <= last["power_change_half_width"]
    assert free.convergence[0] == ("undecided" if within else "not converged")


@pytest.mark.parametrize("key, value", [("confidence_level", 1.5), ("confidence_level", 0.0),
                                        ("confidence_blocks", 1), ("ensemble", 0),
                                        ("convergence_tolerance", 5.0),
                                        ("convergence_tolerance", -0.1)])
def test_bad_noise_keys(tmp_path, key, value):
    with pytest.raises(KeywordError, match=key):
        iterate_case(case(tmp_path, **{key: value}), output=tmp_path / "out")


def test_cli_prints_each_cycle_power_with_its_interval(tmp_path):
    from fretwear.cli import cli

    toml = tmp_path / "loop.toml"
    toml.write_text(LOOP_TOML, encoding="utf-8")
    # a terminal wide enough for the 11 columns with their units (on 80 columns rich wraps
    # each row over several lines)
    out = CliRunner().invoke(cli, ["iterate", str(toml), "--cycles", "2", "--no-plot"],
                             env={"COLUMNS": "320"})
    assert out.exit_code == 0, out.output
    import re

    rows = [line for line in out.output.splitlines() if line.startswith("│")]
    assert len(rows) == 2
    assert all(re.search(r"P = \S+ ± \S+ W \(95 %\)", row) for row in rows)
    assert "convergence: " in out.output


def _random_case(tmp_path, **iterate):
    """:func:`case` under a random force along y and z (seeds 5 and 6)."""
    c = case(tmp_path, **iterate)
    c["dynamics"]["forces"] = [
        {"point": 0, "direction": d, "kind": "random", "psd_frequencies_Hz": [5.0, 100.0],
         "psd": [1.0, 1.0], "seed": seed} for d, seed in (("y", 5), ("z", 6))]
    return c


def test_ensemble_power_is_the_mean_of_its_runs(tmp_path):
    """[iterate] ensemble = 3: three runs of each cycle with the random seeds moved; the table's
    power is the mean of the runs' powers (each computed here from its own history), the
    interval Student's over the three runs (t(2, 0.975) = 4.303), run 1 is the case as
    written (its power equals the single run's)."""
    import pyarrow.parquet as pq
    from scipy import stats

    from fretwear.history import ContactHistory

    single = iterate_case(_random_case(tmp_path, cycles=1), output=tmp_path / "one")
    res = iterate_case(_random_case(tmp_path, cycles=1, ensemble=3), output=tmp_path / "ens")
    folder = tmp_path / "ens" / "cycle_01"
    runs = []
    for name in ("histories", "histories_run02", "histories_run03"):
        frame = pq.read_table(folder / name / "bore.parquet").to_pandas()
        runs.append(_power(ContactHistory.from_frame(frame)))
    assert runs[0] == pytest.approx(single.summary["power"].iloc[0], rel=1e-12)
    assert len(set(runs)) == 3  # the seeds moved: three different computations
    row = res.summary.iloc[0]
    assert row["power"] == pytest.approx(np.mean(runs), rel=1e-9)
    half = stats.t.ppf(0.975, 2) * np.std(runs, ddof=1) / math.sqrt(3)
    assert row["power_half_width"] == pytest.approx(half, rel=1e-6)
    assert row["power_interval_count"] == 3 and res.intervals[0].method == "ensemble"
    # the wear table is fed the mean: Archard's V = K·P̄·t (theory §4)
    last = res.tables[0][res.tables[0]["instant"] == res.tables[0]["instant"].max()]
    assert float(last["volume_mobile_cumulated"].sum()) == pytest.approx(
        K_MOBILE * np.mean(runs) * YEAR, rel=1e-9)


def test_ensemble_needs_a_random_signal(tmp_path):
    with pytest.raises(KeywordError, match="random excitation"):
        iterate_case(case(tmp_path, ensemble=2), output=tmp_path / "out")


def test_cli_says_perforation_first(tmp_path):
    """Bad news first: a tube worn through its wall is the first line printed, before the
    table (a 10 µm wall: perforated in the first cycle)."""
    from fretwear.cli import cli

    toml = tmp_path / "loop.toml"
    toml.write_text(LOOP_TOML.replace("wall_thickness_m = 1.1e-3", "wall_thickness_m = 1e-5"),
                    encoding="utf-8")
    out = CliRunner().invoke(cli, ["iterate", str(toml), "--cycles", "2", "--no-plot"])
    assert out.exit_code == 0, out.output
    first = next(line for line in out.output.splitlines() if line.strip())
    assert first.startswith("PERFORATED: the tube is worn through its wall at cycle 1")
