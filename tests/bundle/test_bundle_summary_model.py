"""``BundleResult.summary(limit)``'s ``time_to_limit`` is the contact's depth model's
:meth:`~fretwear.table.DepthModel.time_to` (issue 25, point 1: no second inversion), at limits
among a restart's earlier rows, at the case's own limit and just past it (0.4 and 0.4000001:
the answer used to jump there), and after the origin; the same after
:func:`fretwear.bundle.load`.

The independent side: the model of the contact's own :class:`~fretwear.table.WearCase`, the one
the bundle carries (``BundleResult.cases``), built by
:func:`fretwear.table.depth_build.case_model` at the contact's power, as the wear table builds
it (the case's restart state and its rows; the summary builds its model from the contact's
record and its rows of the bundle's table instead). Compared to 1e-12 relative: two models of
one case inverted in one process, not bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bundle_helpers import BASE_CASE, oscillator, reference, write_bundle

from fretwear.bundle import load, run_bundle
from fretwear.table import write_wear_table
from fretwear.table.depth_build import case_model
from fretwear.table.depth_rows import FROM_MODEL, FROM_TABLE

pytest.importorskip("xarray")
pytestmark = pytest.mark.filterwarnings("ignore::fretwear.errors.PerforationWarning")

NO_SECTORS = BASE_CASE.replace("[sectors]\ncount = 4\n", "")
#: Fractions of the wall [-]: the first five among the initial table's rows (its depth at the
#: restart's origin is half the wall), the last two after the origin.
FRACTIONS = (0.2, 0.39, 0.4, 0.4000001, 0.41, 0.6, 0.7)


def _restart_bundle(directory):
    """Two contacts continuing contact 0's 5-year Archard table (origin 5, to 10 years), the
    wall twice that table's depth at 5 years; the result with its output directory."""
    manifest, case = write_bundle(directory, oscillator(), 2)
    case.write_text(NO_SECTORS)
    earlier = reference(directory / "histories/t0.parquet", case)
    write_wear_table(earlier, directory / "earlier.csv")
    rows = earlier.drop_duplicates("instant").set_index("instant")
    wall = 2.0 * float(rows.loc[5.0, "depth_mobile"])
    case.write_text(NO_SECTORS.replace("[geometry]\n", f"[geometry]\nwall_thickness_m = "
                                       f"{wall!r}\n")
                    + f'[restart]\ntable = "{directory / "earlier.csv"}"\n')
    return run_bundle(manifest, case, scheduler="serial", output=directory / "out"), wall


def test_time_to_limit_is_the_case_models_time_to(tmp_path):
    result, wall = _restart_bundle(tmp_path)
    loaded = load(tmp_path / "out")
    summaries = {f: result.summary(limit=f).set_index("contact") for f in FRACTIONS}
    again = {f: loaded.summary(limit=f).set_index("contact") for f in FRACTIONS}
    info = result.contacts.set_index("contact")
    for contact in result.contacts["contact"]:
        case = result.cases[contact]
        assert case.origin == 5.0 and case.wall.thickness == wall
        model = case_model(case, float(info.at[contact, "power"]), None,
                           case.coefficient_values("mobile"),
                           case.coefficient_values("obstacle"), None, case.geometry)
        times = []
        for f in FRACTIONS:
            row = summaries[f].loc[contact]
            expected = float(model.time_to(f * wall))
            assert row["time_to_limit_method"] == (FROM_TABLE if f == 0.4 else FROM_MODEL)
            assert row["time_to_limit"] == pytest.approx(expected, rel=1e-12, abs=0), f
            assert again[f].loc[contact, "time_to_limit"] == pytest.approx(
                row["time_to_limit"], rel=1e-12, abs=0), f
            assert (expected < 5.0) == (f < 0.5)  # among the initial table's rows
            times.append(row["time_to_limit"])
        assert np.all(np.diff(times) >= 0), times  # non-decreasing in the limit
        assert not any(math.isnan(t) for t in times)


def test_sector_coefficients_of_the_case_are_the_models(tmp_path):
    """A sector case whose sectors wear with their own Archard coefficients: the global depth
    sums the sectors' volumes K_j·P_j·t, so the summary's time (its model from the contact's
    record, sector_coefficients included) is the case's model's (case_model with the sector
    powers of the table), to 1e-12 relative; with the law's one coefficient in every sector
    (a contacts frame without sector_coefficients) it comes out 2.5 % late here (Σ K_j P_j
    against K Σ P_j, measured)."""
    from types import SimpleNamespace

    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    case.write_text(BASE_CASE.replace(
        "[sectors]\ncount = 4\n",
        "[sectors]\ncount = 4\nmobile_coefficients_per_Pa = [9.2e-15, 5e-15, 2e-14, 1e-14]\n"))
    result = run_bundle(manifest, case, scheduler="serial")
    assert result.stats["failed"] == 0, result.errors
    table = result.table
    for contact in result.contacts["contact"]:
        rows = table[(table["contact"] == contact) & table["sector"].notna()]
        last = rows[rows["instant"] == rows["instant"].max()].sort_values("sector")
        target = 0.5 * float(last["depth_mobile"].iloc[0])
        got = result.summary(limit_m=target).set_index("contact").loc[contact]
        wear_case = result.cases[contact]
        assert wear_case.sector_coefficients is not None
        power = SimpleNamespace(sectors=last["sector_power"].to_numpy(),
                                sector_edges=wear_case.sector_edges)
        model = case_model(wear_case, float(last["power"].iloc[0]), power,
                           wear_case.coefficient_values("mobile"),
                           wear_case.coefficient_values("obstacle"), None, wear_case.geometry)
        assert got["time_to_limit_method"] == FROM_MODEL
        assert got["time_to_limit"] == pytest.approx(float(model.time_to(target)), rel=1e-12,
                                                     abs=0)


def test_the_assessment_models_carry_the_bundles_wall(tmp_path):
    """The assessment's models (:func:`fretwear.assessment.contacts.bundle_models`) take each
    contact's wall as the bundle built it (``BundleResult.cases[c].wall``, the same object,
    checked once there); another limit is a new Wall of that thickness."""
    from fretwear.assessment.contacts import bundle_models

    result, wall = _restart_bundle(tmp_path)
    own = bundle_models(result).set_index("contact")
    other = bundle_models(result, limit=0.5).set_index("contact")
    for contact in result.contacts["contact"]:
        case_wall = result.cases[contact].wall
        assert own.at[contact, "model"].wall is case_wall
        assert own.at[contact, "limit_depth"] == pytest.approx(0.4 * wall, rel=1e-15)
        changed = other.at[contact, "model"].wall
        assert (changed.thickness, changed.limit) == (wall, 0.5)
        assert other.at[contact, "model"].limit_depth == pytest.approx(0.5 * wall, rel=1e-15)
