"""BundleResult.summary's ``time_to_limit`` on the shipped example bundle (examples/bundle:
Archard, TUBE_BAV, wall 1.09 mm, the case's depth_limit 0.4 by default, instants 1-40 years),
checked against an independent computation made here from the table's rows: the global depth
at each instant, linearly interpolated.

Expected values: the limit is reached by the last instant exactly where the depth at the last
instant is at least the limit depth (else NaN, as docs/bundle.md says); where reached, the time
lies in the interval of instants where the depth crosses the limit, at or before the time of the
linear interpolation of the depth there (the depth of a flat worn into a cylinder grows as the
volume to the 2/3, and Archard's volume linearly in time: depth(t) is concave, so its chord lies
below it and reaches the limit later). Another limit than the case's (0.3) is found through the
geometry and the worn volume (FROM_MODEL; its values are checked against independent
computations in test_bundle_time_to_other_limit.py): one the two deepest contacts cross, chosen
from the data (0.9 × the second-deepest's last depth), so that the test does not depend on the
example's particular values. The default limit and the same limit
asked for explicitly give the same times bit for bit.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("xarray")

from fretwear.bundle import run_bundle  # noqa: E402
from fretwear.table.depth_rows import FROM_MODEL, FROM_TABLE  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


@pytest.fixture(scope="module")
def result():
    return run_bundle(EXAMPLE / "manifest.csv", EXAMPLE / "bundle.toml", scheduler="serial")


def _global(result, contact):
    """(instants, global depths [m]) of a contact, one row per instant, from its table."""
    rows = result.table[result.table["contact"] == contact].drop_duplicates("instant")
    rows = rows.sort_values("instant")
    return rows["instant"].to_numpy(dtype=float), rows["depth_mobile"].to_numpy(dtype=float)


def _linear_time(t, d, target):
    """The instant where the linear interpolation of depth(t), from (0, 0), reaches target."""
    t, d = np.concatenate(([0.0], t)), np.concatenate(([0.0], d))
    i = int(np.argmax(d >= target))
    return t[i - 1], t[i - 1] + (target - d[i - 1]) * (t[i] - t[i - 1]) / (d[i] - d[i - 1]), t[i]


def _crossed_by_two(result, wall=1.09e-3):
    """A limit [-] that the two deepest contacts cross between two instants: 0.9 × the
    second-deepest last depth over the wall (from the data, not a number of it)."""
    last = sorted(_global(result, c)[1][-1] for c in result.contacts["contact"])
    return 0.9 * last[-2] / wall


@pytest.mark.parametrize("limit", [None, 0.4, "crossed"])
def test_time_to_limit_is_reached_within_the_instants(result, limit):
    if limit == "crossed":
        limit = _crossed_by_two(result)
    summary = result.summary(limit)
    wall = 1.09e-3
    fraction = 0.4 if limit is None else limit
    reached = 0
    for row in summary.itertuples():
        t, d = _global(result, row.contact)
        target = fraction * wall
        assert row.limit_depth == pytest.approx(target, rel=1e-15)
        if d[-1] < target:  # not reached by the last instant (40 years)
            assert math.isnan(row.time_to_limit), row.contact
            continue
        reached += 1
        lo, linear, hi = _linear_time(t, d, target)
        assert lo < row.time_to_limit <= hi, row.contact
        assert row.time_to_limit <= linear * (1 + 1e-12), row.contact
    if fraction != 0.4:
        assert reached >= 2  # the limit is crossed between two instants by some contacts
    expected = FROM_TABLE if fraction == 0.4 else FROM_MODEL
    assert summary.attrs["time_to_limit"] == expected


def test_default_and_explicit_limit_agree(result):
    default, explicit = result.summary(), result.summary(0.4)
    a = default["time_to_limit"].to_numpy(dtype=float)
    b = explicit["time_to_limit"].to_numpy(dtype=float)
    assert np.array_equal(a, b, equal_nan=True)
    # the shallowest contact that wears (its depth far below 40 % at 40 years): no time, not a
    # forecast thousands of years away
    worn = default[default["power"] > 0].set_index("contact")
    shallow = worn.loc[worn["depth_fraction"].idxmin()]
    assert 0 < shallow["depth_fraction"] < 0.4
    assert math.isnan(shallow["time_to_limit"]) and shallow["limit_forecast"] > 40
    # where reached, the time is the wear table's own limit_instant (law and geometry inverted)
    for row in default.dropna(subset=["time_to_limit"]).itertuples():
        rows = result.table[result.table["contact"] == row.contact]
        assert row.time_to_limit == rows["limit_instant"].iloc[-1]


def test_limit_forecast_is_the_law_and_geometry_inverted_beyond_the_last_instant(result):
    """``limit_forecast``: Archard's volume grows linearly in time (constant power), so the
    instant at which the tube's worn volume reaches the volume of the limit depth is the last
    instant scaled by the ratio of the two volumes, computed here with the TUBE_BAV geometry's
    forward relation (fretwear.geometry, independent of the table's inversion). It is given for
    every contact, also where the limit lies far beyond the last instant (time_to_limit NaN),
    and equals time_to_limit where that one is reached."""
    from fretwear.geometry import contact_geometry

    bar = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)
    s = result.summary().set_index("contact")
    beyond = 0
    for contact, row in s.iterrows():
        rows = result.table[result.table["contact"] == contact].drop_duplicates("instant")
        last = rows.sort_values("instant").iloc[-1]
        worn = last["volume_mobile"]  # 0 for a contact that never touches: never reached
        expected = (last["instant"] * bar.volume_from_depth(row["limit_depth"])[0] / worn
                    if worn > 0 else math.inf)
        assert row["limit_forecast"] == pytest.approx(expected, rel=1e-9), contact
        if math.isnan(row["time_to_limit"]):
            beyond += 1
            assert row["limit_forecast"] > row["instant"]
        else:
            assert row["time_to_limit"] == row["limit_forecast"]
    # the contacts whose last depth is below the limit are exactly those beyond the instants
    assert beyond == int((s["depth"] < s["limit_depth"]).sum())
