"""``summary()``'s time to a limit other than the case's own: the cases a review of the exact
method found wrong (each failed on commit bc9d746).

References, independent of :mod:`fretwear.table.depth_rows`:

* the single-contact wear table (:func:`fretwear.table.wear_table`) run forward to a trial
  instant, its depth at that instant, bisected for the instant the depth reaches the limit
  (``_forward``): the case layer's own restart, replacement and law, not the summary's;
* Archard on a flat bar (TUBE_BAV, the obstacle not wearing): the depth of V = K·P·t
  (docs/theory.md §2) through ``geometry.depth_from_volume``, bisected;
* the single-contact table's ``limit_instant`` with ``depth_limit`` at the asked fraction.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle.result import summarize
from fretwear.geometry import contact_geometry
from fretwear.table import wear_table
from fretwear.table.depth_rows import FROM_MODEL

YEAR = 365 * 86400.0  # [s]
K = 9.2e-15  # [1/Pa]
BAV = dict(contact_type="TUBE_BAV", dimensions={"mobile_radius": 9.525e-3,
                                                "obstacle_width": 12.7e-3},
           instants=[0.5, 1, 2, 5], time_scale=YEAR, time_unit="year",
           coefficients={"COEF_USURE": K})
BAR = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)


def _table(power, **keywords):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return wear_table(power, **keywords)


def _summary(table, limit_m=None, *, limit=None, wall=None):
    """(time_to_limit, method) of the table made a one-contact bundle's."""
    frame = table.copy()
    frame["contact"] = "c"
    a = table.attrs
    contacts = pd.DataFrame([{
        "contact": "c", "status": "done", "time_unit": "year", "origin": a.get("origin"),
        "tube_replacement": a.get("tube_replacement"), "wall_thickness": wall,
        "depth_limit": a.get("depth_limit"), "contact_type": a.get("contact_type"),
        "dimensions": a.get("dimensions"), "law": a.get("law"),
        "coefficients_mobile": a.get("coefficients_mobile"),
        "coefficients_obstacle": a.get("coefficients_obstacle"),
        "time_scale": a.get("time_scale")}])
    s = summarize(frame, contacts, limit=limit, limit_m=limit_m, wall_thickness=None)
    return float(s["time_to_limit"].iloc[0]), s["time_to_limit_method"].iloc[0]


def _forward(power, keywords, target, lo, hi):
    """The instant the single-contact table's depth reaches ``target``, bisected on tables run
    forward to a trial instant in (lo, hi)."""
    def depth(instant):
        rows = _table(power, **{**keywords, "instants": [instant]}).drop_duplicates("instant")
        return float(rows["depth_mobile"].iloc[-1])

    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if depth(mid) >= target else (mid, hi)
    return hi


def _archard_flat(power, target, start):
    """The instant a new tube's depth on a flat bar reaches ``target``, Archard from ``start``."""
    lo, hi = start, start + 100.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        depth = BAR.depth_from_volume(K * power * (mid - start) * YEAR)[0]
        lo, hi = (lo, mid) if depth >= target else (mid, hi)
    return hi


@pytest.mark.parametrize("replaced", [6.0, 5.7])
def test_a_restart_with_a_replacement_in_the_run_counts_the_new_tube(replaced):
    """A limit the old tube had passed among the initial table's rows: the new tube's time,
    not the old tube's (0.75 instead of 6.46, a review)."""
    earlier = _table(0.03, **BAV)
    table = _table(0.05, **BAV, initial_state=earlier, tube_replacement=replaced)
    for target in (2e-4, 5e-4):
        got, method = _summary(table, target)
        assert method == FROM_MODEL
        assert got == pytest.approx(_archard_flat(0.05, target, replaced), rel=1e-12)


def test_a_replacement_at_the_restarts_origin_starts_unworn():
    """The origin row holds the old tube's volumes; the tube replaced there starts at 0 (it
    was counted from the old tube's volume, 12 % early on the time since the origin)."""
    earlier = _table(0.002, **BAV)
    table = _table(0.05, **BAV, initial_state=earlier, tube_replacement=5.0)
    for target in (1e-4, 1.9e-4):
        got, method = _summary(table, target)
        assert method == FROM_MODEL
        assert got == pytest.approx(_archard_flat(0.05, target, 5.0), rel=1e-12)


def test_a_depth_falling_without_a_replacement_is_not_one():
    """EDF-MZ with a fast-wearing bar flattens the contact: the tube's depth falls a little
    (12.71 -> 12.57 um between 5 and 10 years) though its volume grows. Only a drop of the
    volume is a replacement (the depth's drop gave 10.0 and NaN, a review): the limits are
    found among the initial rows, inside the interval where the forward table reaches them."""
    kw = {**BAV, "law": "EDF_MZ", "coefficients": {"COEF_USURE": 1e-15, "COEF_S": 1e-19},
          "obstacle_coefficients": {"COEF_USURE": 1e-13, "COEF_S": 1e-16},
          "instants": [0.01, 0.1, 0.5, 1, 2, 5, 10]}
    earlier = _table(0.05, **kw)
    rows = earlier.drop_duplicates("instant")
    assert (np.diff(rows["depth_mobile"]) < 0).any() and (np.diff(rows["volume_mobile"]) > 0).all()
    table = _table(0.05, **{**kw, "initial_state": earlier, "instants": [1, 2]})
    t = rows["instant"].to_numpy()
    for target in (5e-6, 1e-5, 12.6e-6):
        got, method = _summary(table, target)
        expected = _forward(0.05, kw, target, 0.0, 10.0)
        k = int(np.searchsorted(t, expected))
        assert method == FROM_MODEL
        assert t[k - 1] < got <= t[k], (target, got, expected)


def test_edf_mz_obstacle_at_a_replacement_between_rows_follows_its_law():
    """The bar's volume at the tube's replacement (between two rows) continues its EDF-MZ law,
    not a straight line between the rows (0.7-1.4 % short on the time since, a review)."""
    bore = {"mobile_radius": 9.525e-3, "obstacle_radius": 9.725e-3, "obstacle_width": 20e-3}
    kw = {**BAV, "contact_type": "TUBE_ALESAGE", "dimensions": bore, "law": "EDF_MZ",
          "coefficients": {"COEF_USURE": 9.2e-15, "COEF_S": 1e-19},
          "obstacle_coefficients": {"COEF_USURE": 5e-14, "COEF_S": 1e-19},
          "tube_replacement": 3.0}
    table = _table(0.05, **kw)
    last = float(table.drop_duplicates("instant")["depth_mobile"].iloc[-1])
    for fraction in (0.02, 0.3):
        got, method = _summary(table, fraction * last)
        assert method == FROM_MODEL
        expected = _forward(0.05, kw, fraction * last, 3.0, 5.0)
        assert got - 3.0 == pytest.approx(expected - 3.0, rel=1e-9)


def test_a_limit_passed_before_a_depth_beyond_the_relation_is_found():
    """A row whose depth is beyond the relation's range (NaN, its volume finite) is deeper than
    any limit: a limit crossed between a finite row and it is found (it was NaN, "not
    reached", a review); against the single-contact table's limit_instant at 60 %."""
    kw = {**BAV, "instants": [0.1, 40], "wall_thickness": 1.09e-3, "depth_limit": 0.4}
    table = _table(0.2, **kw)
    assert math.isnan(table["depth_mobile"].iloc[-1])
    got, method = _summary(table, limit=0.6, wall=1.09e-3)
    single = _table(0.2, **{**kw, "depth_limit": 0.6})
    assert method == FROM_MODEL
    assert got == pytest.approx(float(single["limit_instant"].iloc[-1]), rel=1e-12)


def test_a_law_not_linear_in_time_follows_its_law_at_the_runs_power():
    """EDF-MZ continued at the run's power (the table's power column; it was evaluated at 0 W
    and clamped to the row's instant, 0.5 against 0.332, a review): against the forward
    single-contact table, bisected."""
    kw = {**BAV, "law": "EDF_MZ", "coefficients": {"COEF_USURE": K, "COEF_S": 1e-19}}
    got, method = _summary(_table(0.05, **kw), 1e-4)
    assert method == FROM_MODEL
    assert got == pytest.approx(_forward(0.05, kw, 1e-4, 0.0, 5.0), rel=1e-9)
