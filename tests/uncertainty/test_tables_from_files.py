"""A wear table written to a file and read back is rebuilt into its depth model (issue 25,
point 3): CSV and Parquet carry the wear case (its ``to_dict``) and the power in their
provenance; ``models_from_table`` rebuilds the case once (``WearCase.from_dict``), and Monte
Carlo and the calibration on the table read back give the in-memory table's numbers.

The comparison is within one process on one machine, but the path through the file is not the
same arithmetic (the CSV's text, the case rebuilt and validated again), so the numbers are
compared at 1e-12 relative, not bit for bit. Independently of that comparison, the model
rebuilt from the file must give the depths of the file's own rows (wear_table's columns).
A table without a case (Code_Aster text, an older file, attrs dropped) is a clear InputError.
"""

import math
import warnings

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import InputError
from fretwear.history import ContactHistory
from fretwear.table import (
    WearCase,
    models_from_table,
    read_wear_table,
    wear_table,
    write_wear_table,
)
from fretwear.table.depth_build import table_case
from fretwear.uncertainty import LogNormal, calibrate, monte_carlo

R, L_BAR = 9.525e-3, 12.7e-3
K0 = 9.2e-15
YEAR = 3.15576e7
RTOL = 1e-12
BASE = {"time_scale": YEAR, "dimensions": {"mobile_radius": R, "obstacle_width": L_BAR},
        "wall_thickness": 1.09e-3}


def _sector_history() -> ContactHistory:
    t = np.linspace(0, 2, 2001)
    angle = np.radians(150 * np.sin(3 * t))
    return ContactHistory(time=t, normal_force=np.full(t.size, 2.0), vt1=np.full(t.size, 0.1),
                          vt2=np.zeros(t.size), dy=np.cos(angle), dz=np.sin(angle))


def _kwu_history() -> ContactHistory:
    t = np.linspace(0.0, 2.0, 4001)
    return ContactHistory(time=t, normal_force=np.abs(np.sin(20 * t)) * 5,
                          vt1=0.05 * np.cos(7 * t), vt2=np.zeros(t.size))


def _tables() -> dict[str, pd.DataFrame]:
    """One table of each kind the model is built from: a plain table, a restart (the earlier
    rows first, origin 8), a sector table (per-sector coefficients and powers), and KWU-EPRI
    (the intensity is computed from the history: not in the case)."""
    archard = {"contact_type": "TUBE_BAV", "coefficients": {"COEF_USURE": K0}, **BASE}
    first = wear_table(0.01, instants=[0.0, 4.0, 8.0], **archard)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the synthetic histories' units/stationarity notes
        return {
            "plain": wear_table(0.01, instants=[1.0, 5.0, 10.0, 20.0], **archard),
            "restart": wear_table(0.01, instants=[2.0, 6.0, 12.0], initial_state=first,
                                  **archard),
            "sectors": wear_table(_sector_history(), instants=[1.0, 10.0], sectors=4,
                                  sector_coefficients=[(K0, None), (2 * K0, None),
                                                       (K0, None), (3 * K0, None)],
                                  **archard),
            "kwu": wear_table(_kwu_history(), contact_type="TUBE_BAV", law="KWU_EPRI",
                              instants=[5.0, 10.0], blocks=4,
                              coefficients={"reference_coefficient": 1e-14}, **BASE),
        }


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    """{(kind, suffix): (table in memory, the same table read back from its file)}."""
    folder = tmp_path_factory.mktemp("tables")
    out = {}
    for kind, table in _tables().items():
        for suffix in ("csv", "parquet"):
            back = read_wear_table(write_wear_table(table, folder / f"{kind}.{suffix}"))
            out[kind, suffix] = (table, back)
    return out


KEYS = [(k, s) for k in ("plain", "restart", "sectors", "kwu") for s in ("csv", "parquet")]


@pytest.mark.filterwarnings("ignore::fretwear.errors.RangeWarning")  # NaN past the range
@pytest.mark.parametrize("key", KEYS, ids=["-".join(k) for k in KEYS])
def test_the_file_carries_the_case_and_rebuilds_the_models(tables, key):
    table, back = tables[key]
    assert set(back.attrs) == {"provenance"}  # a file's table: its provenance only
    assert table_case(back) == WearCase.from_dict(table.attrs["case"])
    here, there = models_from_table(table), models_from_table(back)
    assert sorted(here) == sorted(there)
    # independent of the in-memory model: the rebuilt model gives the file's own depth rows
    origin = there["global"].origin
    rows = back[np.isclose(back["origin"], origin) & (back["instant"] >= origin)]
    for name, model in there.items():
        if name == "global":
            got = model.depth(rows["duration"].drop_duplicates().to_numpy() * YEAR)
            want = rows.drop_duplicates("instant")["depth_mobile"].to_numpy()
        else:
            j = int(name.split()[1])
            one = rows[rows["sector"] == j]
            got = model.depth(one["duration"].to_numpy() * YEAR)
            want = one["depth_mobile_sector"].to_numpy()
        np.testing.assert_allclose(got, want, rtol=RTOL)
        # and the in-memory path's model at other times and for the limit
        times = np.array([0.5, 3.0, 7.0, 30.0]) * YEAR
        np.testing.assert_allclose(model.depth(times, factor=[0.5, 1.0, 2.0, 4.0]),
                                   here[name].depth(times, factor=[0.5, 1.0, 2.0, 4.0]),
                                   rtol=RTOL)
        limits = np.array([0.1, 0.3, 0.4]) * 1.09e-3
        np.testing.assert_allclose(model.time_to(limits), here[name].time_to(limits),
                                   rtol=RTOL)


@pytest.mark.parametrize("key", KEYS, ids=["-".join(k) for k in KEYS])
def test_monte_carlo_on_the_file_equals_the_table_in_memory(tables, key):
    table, back = tables[key]
    sector = 2 if key[0] == "sectors" else None
    runs = [monte_carlo(t, factor=LogNormal(1.0, sigma_ln=0.5), samples=256, seed=3,
                        sector=sector) for t in (table, back)]
    np.testing.assert_allclose(runs[1].depth, runs[0].depth, rtol=RTOL)
    np.testing.assert_allclose(runs[1].nominal_depth, runs[0].nominal_depth, rtol=RTOL)
    np.testing.assert_allclose(runs[1].time_to_limit(), runs[0].time_to_limit(), rtol=RTOL)
    np.testing.assert_allclose(runs[1].instants, runs[0].instants, rtol=RTOL)
    # the result carries the table's case, on both paths
    assert runs[0].case == runs[1].case == WearCase.from_dict(table.attrs["case"])


@pytest.mark.parametrize("key", KEYS, ids=["-".join(k) for k in KEYS])
def test_calibration_on_the_file_equals_the_table_in_memory(tables, key):
    table, back = tables[key]
    origin = models_from_table(table)["global"].origin
    nominal = float(models_from_table(table)["global"].depth(3.0 * YEAR))
    inspections = pd.DataFrame({"instant": [origin + 3.0], "depth": [1.4 * nominal],
                                "measurement_sigma": [0.2]})
    prior = LogNormal(1.0, sigma_ln=0.6)
    here, there = (calibrate(t, inspections, prior=prior, forecast=origin + 20.0)
                   for t in (table, back))
    assert math.isclose(there.factor_median, here.factor_median, rel_tol=RTOL)
    for col in ("depth_q5", "depth_q50", "depth_q95", "exceedance"):
        np.testing.assert_allclose(there.predictive[col], here.predictive[col], rtol=RTOL)


def test_a_code_aster_text_table_has_no_case_and_says_the_fix(tables, tmp_path):
    table, _ = tables["plain", "csv"]
    back = read_wear_table(write_wear_table(table, tmp_path / "t.tab"))
    with pytest.raises(InputError, match=r"carries no wear case.*Code_Aster text table.*"
                                         r"case=WearCase"):
        models_from_table(back)
    # given the case, the same model as the table in memory
    model = models_from_table(back, case=WearCase.from_dict(table.attrs["case"]))["global"]
    np.testing.assert_allclose(model.depth(np.array([5.0, 20.0]) * YEAR),
                               models_from_table(table)["global"].depth(
                                   np.array([5.0, 20.0]) * YEAR), rtol=RTOL)


def test_an_older_csv_without_its_case_line_says_what_is_missing(tables, tmp_path):
    table, _ = tables["plain", "csv"]
    path = write_wear_table(table, tmp_path / "t.csv")
    lines = path.read_text(encoding="utf-8").splitlines(keepends=True)
    old = tmp_path / "old.csv"  # the file of a fretwear that did not keep the case
    old.write_text("".join(x for x in lines if not x.startswith("# fretwear.case")),
                   encoding="utf-8")
    with pytest.raises(InputError, match="provenance has no case"):
        monte_carlo(read_wear_table(old), factor=LogNormal(1.0, sigma_ln=0.5), samples=16)
    with pytest.raises(InputError, match="provenance has no case"):
        calibrate(read_wear_table(old), pd.DataFrame({"instant": [3.0], "depth": [1e-4]}))


def test_a_table_whose_attrs_were_dropped_says_so():
    table = _tables()["plain"]
    bare = table.copy()
    bare.attrs = {}
    with pytest.raises(InputError, match="attrs are empty"):
        models_from_table(bare)


def test_a_case_without_sectors_and_a_power_with_sectors_keeps_the_sector_models():
    """A WearCase without sectors run on a PowerResult computed with sectors makes a sector
    table (the run's sectors): its sector models come from the case the table carries."""
    from fretwear.power import wear_power
    from fretwear.table import wear_table_from_case

    power = wear_power(_sector_history(), sectors=4, blocks=4)
    case = WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0, 10.0],
                                  coefficients={"COEF_USURE": K0}, **BASE)
    assert case.sectors is None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the synthetic history's notes
        table = wear_table_from_case(case, power)
        runs = [monte_carlo(source, *extra, factor=LogNormal(1.0, sigma_ln=0.3), samples=64,
                            seed=1, sector=2, power_scatter="fixed")
                for source, *extra in ((case, power), (table,))]
    last = table[(table["instant"] == 10.0) & (table["sector"] == 2)]
    assert runs[0].nominal_depth[-1] == pytest.approx(last["depth_mobile_sector"].iloc[0],
                                                      rel=RTOL)
    np.testing.assert_allclose(runs[0].depth, runs[1].depth, rtol=RTOL)
