"""The bundle engine without Dask (``scheduler="serial"``): chunked contacts and their merge
tree, failures, per-contact warnings, restarts, the summary and the dataset."""

from __future__ import annotations

import json
import math
import warnings
import weakref
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import (
    BASE_CASE,
    assert_identical,
    oscillator,
    reference,
    rows_of,
    scaled,
    write_bundle,
)

from fretwear.bundle import engine as engine_module
from fretwear.bundle import run_bundle
from fretwear.errors import StationarityWarning
from fretwear.io import iter_history_chunks, write_history
from fretwear.power import PowerAccumulator
from fretwear.table import wear_table
from fretwear.table.depth_rows import FROM_MODEL, interpolated_time
from fretwear.workflows.case_files import case_arguments, load_case

YEAR = 31536000.0


def test_long_contact_splits_into_chunks_merged_in_a_tree(tmp_path, monkeypatch):
    h = oscillator()
    path = tmp_path / "long.parquet"
    write_history(h, path, row_group_size=400)
    (tmp_path / "base.toml").write_text(BASE_CASE + "[power]\nblocks = 3\n")
    frame = pd.DataFrame({"contact": ["long"], "history": [str(path)]})
    merges = []
    real = engine_module.merge_states
    monkeypatch.setattr(engine_module, "merge_states",
                        lambda *r: merges.append(len(r)) or real(*r))
    # 3001 samples in chunks of 500 sharing one sample: ceil(3000/499) = 7 chunks, merged in
    # pairs: 4 merges (the last of one state), then 2, then 1
    result = run_bundle(frame, tmp_path / "base.toml", scheduler="serial", chunk_size=500,
                        split_every=2)
    assert result.errors.empty
    assert sorted(merges) == [1, 2, 2, 2, 2, 2, 2]
    assert result.contacts["samples"].tolist() == [len(h)]
    got = rows_of(result, "long")
    # the same sums in another order: equal to rounding (theory §2), not bit for bit
    with pytest.warns(StationarityWarning):  # 3 blocks of a 0.6 s start-up record
        expected = reference(path, tmp_path / "base.toml")
    for c in expected.columns:
        np.testing.assert_allclose(got[c], expected[c], rtol=1e-13, atol=0, err_msg=c)
    # and equal to the sequential fold of the same chunks (PowerAccumulator.update)
    kw = case_arguments(load_case(tmp_path / "base.toml"), history_elsewhere=True)
    acc = PowerAccumulator(t_start=h.time[0], t_end=h.time[-1], blocks=3, sectors=4)
    for chunk in iter_history_chunks(path, 500):
        acc.update(chunk)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        folded = wear_table(acc.result(), **kw)
    for c in folded.columns:
        np.testing.assert_allclose(got[c], folded[c], rtol=1e-13, atol=0, err_msg=c)
    # a chunk larger than the history: one task, bit for bit
    whole = run_bundle(frame, tmp_path / "base.toml", scheduler="serial")
    assert_identical(rows_of(whole, "long"), expected)


def test_a_chunked_contacts_warnings_come_with_it_not_on_the_terminal(tmp_path, recwarn):
    """A contact split into chunks whose units option disagrees with the file's declared units
    (velocity in mm/s on an SI file): the UnitsWarning is in the contact's warnings, once;
    nothing escapes to the caller's warnings (the client reads the first and last instants to
    plan the chunks: that read's warnings were printed twice a contact)."""
    h = oscillator()
    path = tmp_path / "long.parquet"
    write_history(h, path, row_group_size=400)
    (tmp_path / "base.toml").write_text(BASE_CASE + '[history]\nunits = { velocity = "mm/s" }\n')
    frame = pd.DataFrame({"contact": ["long"], "history": [str(path)]})
    result = run_bundle(frame, tmp_path / "base.toml", scheduler="serial", chunk_size=500)
    override = [m for m in result.warnings["message"] if "override the units" in m]
    assert len(override) == 1 and "vt1 'mm/s' (the file: 'm/s')" in override[0]
    assert not [w for w in recwarn if "override the units" in str(w.message)]


def test_bad_contacts_land_in_errors_and_the_others_complete(tmp_path):
    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 3)
    frame = pd.read_csv(manifest)
    (tmp_path / "histories" / "corrupt.parquet").write_bytes(b"PAR1 this is not parquet")
    bad = scaled(h, 0).to_frame()
    bad.loc[17, "vt1"] = np.nan
    bad.to_csv(tmp_path / "histories" / "nan.csv", index=False)
    extra = pd.DataFrame({"contact": ["missing", "corrupt", "nan", "deep"],
                          "history": ["histories/none.parquet", "histories/corrupt.parquet",
                                      "histories/nan.csv", "histories/t0.parquet"]})
    frame = pd.concat([frame, extra], ignore_index=True)
    # "deep": a bore (lunule) worn past its relation's range by a huge coefficient
    frame["contact_type"] = [None] * 6 + ["TUBE_ALESAGE"]
    frame["obstacle_radius_m"] = [None] * 6 + [9.725e-3]
    frame["law.mobile.COEF_USURE"] = [None] * 6 + [1e-10]
    frame["sectors.count"] = [None] * 6 + [1]
    frame.to_csv(manifest, index=False)
    result = run_bundle(manifest, case, scheduler="serial")
    errors = result.errors.set_index("contact")
    assert errors.loc["missing", "error"] == "InputError"
    assert "does not exist" in errors.loc["missing", "message"]
    assert errors.loc["corrupt", "error"] == "FormatError"
    assert errors.loc["nan", "error"] == "HistoryError"
    assert "row 17" in errors.loc["nan", "message"]
    assert errors.loc["deep", "error"] == "RangeWarning"
    assert bool(errors.loc["deep", "rows_kept"]) is True
    assert not errors.loc[["missing", "corrupt", "nan"], "rows_kept"].any()
    assert result.stats["done"] == 4 and result.stats["failed"] == 3
    assert rows_of(result, "deep")["depth_mobile"].isna().any()
    for k in range(3):
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.parquet", case))
    # the beyond-range contact ranks first in the summary
    assert result.summary()["contact"].iloc[0] == "deep"


def test_warnings_belong_to_their_contact(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 2, extra={"blocks": [4, None]})
    result = run_bundle(manifest, case, scheduler="serial")
    assert set(result.warnings["contact"]) == {"R1C1-AVB"}
    assert result.warnings["category"].tolist() == ["StationarityWarning"]


def test_threads_of_one_process_never_mix_warnings(tmp_path):
    """Tasks running in threads of one worker: each record holds its own warnings only."""
    from fretwear.bundle.cases import build_task
    from fretwear.bundle.manifest import read_manifest
    from fretwear.bundle.tasks import run_contact

    manifest, case = write_bundle(tmp_path, oscillator(), 2, extra={"blocks": [4, None]})
    m = read_manifest(manifest)
    base = load_case(case)
    tasks = [build_task(base, row, "m", chunk_size=10**6) for row in m.rows] * 8
    with ThreadPoolExecutor(max_workers=8) as pool:
        records = list(pool.map(run_contact, tasks))
    for rec in records:
        expected = 1 if rec["contact"] == "R1C1-AVB" else 0
        assert len(rec["warnings"]) == expected, rec["warnings"]


def test_restart_skips_unchanged_contacts(tmp_path):
    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 4)
    out = tmp_path / "out"
    first = run_bundle(manifest, case, scheduler="serial", output=out, part_size=1)
    assert first.stats["done"] == 4
    again = run_bundle(manifest, case, scheduler="serial", output=out)
    assert again.stats["skipped"] == 4 and again.stats["done"] == 0
    pd.testing.assert_frame_equal(again.table, first.table)
    # a changed history and a changed override are recomputed, nothing else
    write_history(scaled(h, 7), tmp_path / "histories" / "t1.parquet")
    frame = pd.read_csv(manifest)
    frame["obstacle_width_m"] = [None, None, 10e-3, None]
    frame.to_csv(manifest, index=False)
    third = run_bundle(manifest, case, scheduler="serial", output=out)
    status = third.contacts.set_index("contact")["status"]
    assert status.to_dict() == {"R1C1-AVB": "skipped", "R1C2-AVB": "done",
                                "R2C1-AVB": "done", "R2C2-AVB": "skipped"}
    assert_identical(rows_of(third, "R1C2-AVB"),
                     reference(tmp_path / "histories/t1.parquet", case))
    forced = run_bundle(manifest, case, scheduler="serial", output=out, force=True)
    assert forced.stats["done"] == 4
    pd.testing.assert_frame_equal(forced.table, third.table)
    # files: the table read back is the result's; superseded parts are removed
    stored = pd.read_parquet(out / "table.parquet")
    pd.testing.assert_frame_equal(stored, forced.table, check_dtype=False)
    run = json.loads((out / "run.json").read_text())
    assert run["done"] == 4
    names = {p.name.split(".")[0] for p in (out / "parts").iterdir()}
    assert len(names) == 1  # forced run wrote its 4 contacts in one part


def test_a_restart_in_waves_opens_the_engine_at_the_first_wave_to_compute(tmp_path,
                                                                           monkeypatch):
    """In waves (engine.waves; here 4 rows, then 8, for 20 contacts: 4, 8, 8) a restart whose
    first two waves are all done before opens its engine once, at the third, and computes only
    that wave's contacts; a restart with nothing to compute opens none. The table is the
    whole fresh run's."""
    monkeypatch.setattr(engine_module, "FIRST_WAVE", 4)
    monkeypatch.setattr(engine_module, "LARGEST_WAVE", 8)
    assert engine_module.waves(20) == [(0, 4), (4, 12), (12, 20)]
    manifest, case = write_bundle(tmp_path, oscillator(), 20)
    whole = run_bundle(manifest, case, scheduler="serial")
    frame = pd.read_csv(manifest)
    frame.iloc[:12].to_csv(tmp_path / "first12.csv", index=False)
    out = tmp_path / "out"
    run_bundle(tmp_path / "first12.csv", case, scheduler="serial", output=out)
    opened = []
    real_open = engine_module.open_engine
    monkeypatch.setattr(engine_module, "open_engine", lambda *a: opened.append(
        len(built)) or real_open(*a))
    built = []
    real_build = engine_module.build_task
    monkeypatch.setattr(engine_module, "build_task", lambda *a, **k: built.append(1) or
                        real_build(*a, **k))
    again = run_bundle(manifest, case, scheduler="serial", output=out)
    assert opened == [20]  # once, after the third wave's rows were built
    assert again.stats["skipped"] == 12 and again.stats["done"] == 8
    pd.testing.assert_frame_equal(again.table, whole.table)
    opened.clear()
    last = run_bundle(manifest, case, scheduler="serial", output=out)
    assert opened == [] and last.stats["skipped"] == 20
    pd.testing.assert_frame_equal(last.table, whole.table)


def test_csv_outputs_round_trip_exactly(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    result = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "o",
                        table_format="csv", dataset_format="netcdf")
    stored = pd.read_csv(tmp_path / "o" / "table.csv")
    for c in ("power", "volume_mobile_sector", "depth_mobile_sector"):
        assert np.array_equal(stored[c].to_numpy(), result.table[c].to_numpy())
    xr = pytest.importorskip("xarray")
    ds = xr.open_dataset(tmp_path / "o" / "dataset.nc")
    assert np.array_equal(ds["depth_mobile"].values, result.dataset["depth_mobile"].values)
    ds.close()


def test_dataset_dimensions_values_and_units(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    result = run_bundle(manifest, case, scheduler="serial")
    ds = result.dataset
    assert dict(ds.sizes) == {"contact": 3, "instant": 4, "sector": 4}
    assert ds["instant"].values.tolist() == [0.5, 1, 2, 5]
    assert ds["instant"].attrs["units"] == "year"
    assert ds["depth_mobile_sector"].attrs["units"] == "m"
    assert ds["volume_mobile"].attrs["aster_name"] == "V_USUR_TUBE"
    t = result.table
    row = t[(t.contact == "R1C2-AVB") & (t.instant == 2.0) & (t.sector == 3)].iloc[0]
    cell = ds.sel(contact="R1C2-AVB", instant=2.0, sector=3)
    assert cell["depth_mobile_sector"].item() == row["depth_mobile_sector"]
    assert cell["depth_mobile"].item() == row["depth_mobile"]
    assert ds["tube_row"].values.tolist() == [1, 1, 2]


def test_interpolated_time_linear_and_monotone():
    t = np.array([1.0, 2.0, 4.0, 8.0])
    assert interpolated_time(t, 2e-5 * t, 5e-5) == pytest.approx(2.5, rel=1e-12)
    assert math.isnan(interpolated_time(t, 2e-5 * t, 1.0))
    assert interpolated_time(t, 2e-5 * t, 1e-5) == pytest.approx(0.5, rel=1e-12)  # from (0, 0)


def test_summary_time_to_limit_against_archard_on_a_flat_bar(tmp_path):
    """TUBE_BAV, no tilt (theory §6): D = (1/(2R))^(1/3)·(3V/(4l))^(2/3) with V = K·P·t, so
    the depth reaches d at t = (4l/3)·d^(3/2)·(2R)^(1/2)/(K·P)."""
    R, width, K, wall = 9.525e-3, 12.7e-3, 9.2e-15, 1.09e-3
    case = tmp_path / "base.toml"
    case.write_text(BASE_CASE.replace("[sectors]\ncount = 4\n", "").replace(
        "instants = [0.5, 1, 2, 5]", f"instants = {list(range(1, 41))}"))
    powers = [5e-3, 2e-2, 1e-3]
    frame = pd.DataFrame({"contact": ["a", "b", "c"], "power.value_W": powers,
                          "wall_thickness_m": [wall, wall, None]})
    result = run_bundle(frame, case, scheduler="serial")
    s = result.summary(0.4).set_index("contact")
    assert s.index.tolist() == ["b", "a", "c"]  # deepest first
    assert s.loc["b", "depth_fraction"] == s.loc["b", "depth"] / wall
    for name, p in zip("ab", powers, strict=False):
        d = 0.4 * wall
        exact = (4 * width / 3) * d ** 1.5 * math.sqrt(2 * R) / (K * p) / YEAR
        assert s.loc[name, "limit_depth"] == pytest.approx(d, rel=1e-15)
        assert s.loc[name, "time_to_limit"] == pytest.approx(exact, rel=2e-3), name
    assert math.isnan(s.loc["c", "time_to_limit"])  # no wall given
    s_m = result.summary(limit_m=0.4 * wall).set_index("contact")
    assert s_m.loc["c", "time_to_limit"] > 40 or math.isnan(s_m.loc["c", "time_to_limit"])
    # an explicit limit other than the case's own goes through the contact's depth model,
    # exact (the same closed form at 0.3 of the wall); 0.4, the case's own, gives the table's
    # limit_instant as the default does
    other = result.summary(0.3).set_index("contact")
    assert other.attrs["time_to_limit"] == FROM_MODEL
    for name, p in zip("ab", powers, strict=False):
        exact = (4 * width / 3) * (0.3 * wall) ** 1.5 * math.sqrt(2 * R) / (K * p) / YEAR
        assert other.loc[name, "time_to_limit"] == pytest.approx(exact, rel=1e-9), name
    assert "limit_instant" in result.summary(0.4).attrs["time_to_limit"]
    # by default, the wear table's own limit instant when it has one (theory: the law and the
    # geometry inverted, so equal to the closed form to the solver's tolerance)
    if "limit_instant" in result.table.columns:
        own = result.summary().set_index("contact")
        assert "limit_instant" in own.attrs["time_to_limit"]
        for name, p in zip("ab", powers, strict=False):
            exact = (4 * width / 3) * (0.4 * wall) ** 1.5 * math.sqrt(2 * R) / (K * p) / YEAR
            assert own.loc[name, "time_to_limit"] == pytest.approx(exact, rel=1e-9), name


def test_without_dask_the_error_names_the_extra(tmp_path, monkeypatch):
    import sys

    from fretwear.errors import MissingDependencyError

    manifest, case = write_bundle(tmp_path, oscillator(), 1)
    monkeypatch.setitem(sys.modules, "dask", None)  # as if not installed
    with pytest.raises(MissingDependencyError, match=r"pip install 'fretwear\[bundle\]'"):
        run_bundle(manifest, case)


def test_parts_are_written_as_contacts_finish(tmp_path):
    """Each part is on disk before the next contact is computed (serial engine too): a run
    stopped at any point keeps what it finished."""
    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    out = tmp_path / "out"
    seen = []

    def progress(done, total, record):
        seen.append((done, len(list((out / "parts").glob("*.json")))))

    run_bundle(manifest, case, scheduler="serial", output=out, part_size=1, progress=progress)
    assert seen == [(1, 1), (2, 2), (3, 3)]


def test_a_long_text_history_is_streamed_in_one_task(tmp_path):
    """A CSV longer than a chunk cannot be read by row range: one task folds its chunks
    (fretwear.power.PowerAccumulator.update), memory bounded by the chunk."""
    h = oscillator()
    path = tmp_path / "long.csv"
    write_history(h, path)
    (tmp_path / "base.toml").write_text(BASE_CASE + "[power]\nblocks = 2\n")
    frame = pd.DataFrame({"contact": ["csv"], "history": [str(path)]})
    result = run_bundle(frame, tmp_path / "base.toml", scheduler="serial", chunk_size=700)
    assert result.errors.empty and result.contacts["samples"].tolist() == [len(h)]
    with pytest.warns(StationarityWarning):
        expected = reference(path, tmp_path / "base.toml")
    got = rows_of(result, "csv")
    for c in expected.columns:
        np.testing.assert_allclose(got[c], expected[c], rtol=1e-13, atol=0, err_msg=c)


KWU_CASE = """\
title = "bundle test KWU-EPRI"
[law]
name = "KWU_EPRI"
mobile = {{ COEF_USURE = 5.2e-14, reference_intensity = 1.0e-7 }}
{maxima}
[geometry]
contact_type = "TUBE_ALESAGE"
mobile_radius_m = 9.525e-3
obstacle_radius_m = 9.725e-3
obstacle_width_m = 20e-3
[time]
instants = [10, 100]
unit = "hour"
"""


@pytest.mark.parametrize("maxima, split", [
    ("force_max_N = 400.0\nspeed_max_m_per_s = 0.5", True),  # counts merge with the power
    ("", False),  # class bounds from the window's maxima: one task, two passes
])
def test_kwu_epri_contact_is_split_only_with_both_maxima(tmp_path, monkeypatch, maxima, split):
    """KWU_EPRI's class counts of a split contact merge with its power state when FNOR_MAXI and
    VTAN_MAXI are given (fretwear.laws.kwu_stream); otherwise the contact is one task. Either
    way the table equals the single-contact wear_table of the history read whole (to rounding
    when split, theory §2)."""
    h = oscillator()
    path = tmp_path / "long.parquet"
    write_history(h, path, row_group_size=400)
    (tmp_path / "base.toml").write_text(KWU_CASE.format(maxima=maxima))
    frame = pd.DataFrame({"contact": ["kwu"], "history": [str(path)]})
    states = []
    real = engine_module.chunk_state
    monkeypatch.setattr(engine_module, "chunk_state",
                        lambda *a: states.append(a[1:3]) or real(*a))
    result = run_bundle(frame, tmp_path / "base.toml", scheduler="serial", chunk_size=500)
    assert result.errors.empty, result.errors
    assert (len(states) == 7) is split and (len(states) == 0) is not split
    expected = reference(path, tmp_path / "base.toml")
    got = rows_of(result, "kwu")
    assert np.all(expected["volume_mobile"] > 0)
    for c in expected.columns:
        np.testing.assert_allclose(got[c], expected[c], rtol=1e-13, atol=0, err_msg=c)


def test_concat_packed_equals_pandas_concat_of_the_tables(tmp_path):
    """The bundle's table is assembled column by column from the packed tables; it equals
    pandas.concat of the contacts' DataFrames with the contact inserted (values, dtypes, column
    order); tables of different columns are aligned by pandas.concat itself."""
    from fretwear.bundle.tasks import concat_packed, pack

    h = oscillator()
    manifest, case = write_bundle(tmp_path, h, 3)
    tables = [reference(tmp_path / f"histories/t{k}.parquet", case) for k in range(3)]
    names = ["a", "b", "c"]
    expected = []
    for name, t in zip(names, tables, strict=True):
        f = t.copy()
        f.insert(0, "contact", name)
        expected.append(f)
    expected = pd.concat(expected, ignore_index=True)
    got = concat_packed(names, [pack(t) for t in tables])
    pd.testing.assert_frame_equal(got, expected, check_exact=True)
    assert "sector" in got.columns and got["sector"].dtype == expected["sector"].dtype
    other = tables[0].drop(columns=["sector"])
    aligned = pd.concat([expected[expected["contact"] == "b"],
                         other.assign(contact="a")[["contact", *other.columns]]],
                        ignore_index=True)
    pd.testing.assert_frame_equal(concat_packed(["b", "a"], [pack(tables[1]), pack(other)]),
                                  aligned, check_exact=True)


def test_a_bundle_whose_every_contact_failed_still_writes_its_outputs(tmp_path):
    """Every history missing: the run ends, errors.csv names them, summary.csv is an empty
    ranking (it used to raise a KeyError while writing it)."""
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    frame = pd.read_csv(manifest)
    frame["history"] = ["histories/none0.parquet", "histories/none1.parquet"]
    frame.to_csv(manifest, index=False)
    out = tmp_path / "out"
    result = run_bundle(manifest, case, scheduler="serial", output=out)
    assert result.stats["failed"] == 2 and result.table.empty
    assert pd.read_csv(out / "errors.csv")["error"].tolist() == ["InputError", "InputError"]
    summary = pd.read_csv(out / "summary.csv")
    assert summary.empty and "time_to_limit" in summary.columns


def test_the_client_freezes_its_old_objects_only_while_it_runs(tmp_path, monkeypatch):
    """run_bundle freezes the objects alive at its start (gc.freeze: the collector's full
    passes skip them while the bundle runs) and unfreezes them at the end; a process that froze
    objects itself keeps its freeze, and a disabled collector is left alone."""
    import gc

    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    seen = []
    real = engine_module.read_manifest

    def spy(*args, **kwargs):
        seen.append((gc.isenabled(), gc.get_freeze_count()))
        return real(*args, **kwargs)

    monkeypatch.setattr(engine_module, "read_manifest", spy)
    assert gc.get_freeze_count() == 0
    run_bundle(manifest, case, scheduler="serial")
    assert seen[-1][1] > 0 and gc.get_freeze_count() == 0  # frozen during the run only
    gc.freeze()
    try:
        mine = gc.get_freeze_count()
        run_bundle(manifest, case, scheduler="serial")
        # the caller's freeze kept: not unfrozen, nothing more frozen (a frozen object freed
        # by its reference count leaves the count)
        assert seen[-1][1] <= mine and 0 < gc.get_freeze_count() <= mine
    finally:
        gc.unfreeze()
    gc.disable()
    try:
        run_bundle(manifest, case, scheduler="serial")
        assert seen[-1] == (False, 0) and not gc.isenabled()
    finally:
        gc.enable()


def test_the_client_freezes_what_survives_an_older_generations_pass(tmp_path,
                                                                          monkeypatch):
    """During run_bundle, what survives a collection of generation 1 or 2 is frozen as well
    (the records and tasks made since the start: the next passes skip them), the callback
    removed and every object unfrozen at the end; a cycle made garbage before the pass is
    collected by it, not frozen; a pass of the youngest generation freezes nothing."""
    import gc

    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    seen = {}
    real = engine_module.read_manifest

    class Node:
        pass

    def spy(*args, **kwargs):
        gc.disable()  # only the passes asked for below: none promotes the cycle before them
        try:
            look(seen)
        finally:
            gc.enable()
        return real(*args, **kwargs)

    def look(seen):
        garbage = Node()
        garbage.me = garbage  # a cycle, unreachable once this function returns
        alive = [Node() for _ in range(1000)]  # made during the run, kept to its end
        young = gc.get_freeze_count()
        gc.collect(0)
        seen["after a young pass"] = gc.get_freeze_count() - young
        ref = weakref.ref(garbage)
        del garbage
        before = gc.get_freeze_count()
        gc.collect(1)
        seen["collected"] = ref() is None
        seen["frozen by the middle pass"] = gc.get_freeze_count() - before
        more = [Node() for _ in range(500)]
        before = gc.get_freeze_count()
        gc.collect()
        seen["frozen by the full pass"] = gc.get_freeze_count() - before
        seen["alive"] = alive + more

    monkeypatch.setattr(engine_module, "read_manifest", spy)
    callbacks = list(gc.callbacks)
    run_bundle(manifest, case, scheduler="serial")
    assert seen["after a young pass"] <= 0 and seen["collected"]
    assert seen["frozen by the middle pass"] >= 1000
    assert seen["frozen by the full pass"] >= 500
    assert gc.get_freeze_count() == 0 and gc.callbacks == callbacks


def test_errors_keep_the_global_depth_range_warning_rather_than_a_sectors(tmp_path):
    """A bore (lunule, TUBE_ALESAGE) worn past its relation's range by a huge coefficient, in
    4 sectors: each sector's depth leaves its range first (RangeWarnings of the sector depths,
    in the contact's warnings first), then the tube's global depth (the geometry's relation):
    errors.csv says the global one, the one the summary ranks by."""
    from fretwear.geometry.base import GLOBAL_RANGE

    manifest, case = write_bundle(tmp_path, oscillator(), 1, extra={
        "contact_type": ["TUBE_ALESAGE"], "obstacle_radius_m": [9.725e-3],
        "law.mobile.COEF_USURE": [1e-10]})
    result = run_bundle(manifest, case, scheduler="serial")
    ranged = result.warnings[result.warnings["category"] == "RangeWarning"]["message"].tolist()
    assert ranged[0].startswith("sector depth")  # the sectors' warnings come first
    assert sum(GLOBAL_RANGE in m for m in ranged) == 1
    assert result.errors["error"].tolist() == ["RangeWarning"]
    message = result.errors["message"].iloc[0]
    assert message.startswith("TUBE_ALESAGE: 4 volume(s) beyond the range of the relation")
    assert message == next(m for m in ranged if GLOBAL_RANGE in m)


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal dtype, length and bytes (NaN payloads and the sign of zero included); object
    arrays element by element."""
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype == object:
        return all(x is y or x == y for x, y in zip(a.tolist(), b.tolist(), strict=True))
    return a.tobytes() == b.tobytes()


def test_a_groups_records_travel_as_blocks_and_come_back_bit_for_bit():
    """tasks.pickled lays a group's tables end to end (one array per column and layout) and
    tasks.unpickled gives back every record with the same table, bit for bit: layouts with and
    without sectors, an int column, a text column, -0.0 and NaN payloads, empty tables, failed
    records without a table, and a record that is not a dict; the rest of each record is
    untouched. Independent reference: the records pickled as they are."""
    import pickle

    from fretwear.bundle.tasks import pickled, unpickled

    rng = np.random.default_rng(7)

    def table(rows: int, sectors: bool) -> dict:
        values = rng.normal(size=rows)
        values[::3] = -0.0
        values[1::5] = np.frombuffer(np.uint64(0x7FF8_0000_0000_0ABC).tobytes() * 1, float)[0]
        columns = {"instant": np.arange(rows, dtype=float), "volume_mobile": values}
        if sectors:
            columns["sector"] = np.arange(rows, dtype=np.int64)
            columns["label"] = np.array([f"s{k}" for k in range(rows)], dtype=object)
        return {"columns": list(columns), "arrays": list(columns.values())}

    records = []
    for k in range(9):
        rec = {"contact": f"c{k}", "status": "done", "warnings": [["W", "m"]], "seconds": 0.1 * k,
               "attrs": {"law": "ARCHARD"}, "table": table(6 * (k % 4), sectors=k % 2 == 0)}
        records.append(rec)
    records[4] = {"contact": "c4", "status": "failed", "table": None, "error": ["E", "m"]}
    records.append(ValueError("a task's exception"))
    expected = pickle.loads(pickle.dumps(records))
    data = pickled(lambda: records)
    got = unpickled(data)
    assert len(got) == len(expected)
    for g, e in zip(got, expected, strict=True):
        if not isinstance(e, dict):
            assert type(g) is type(e) and str(g) == str(e)
            continue
        assert {k: v for k, v in g.items() if k != "table"} == \
            {k: v for k, v in e.items() if k != "table"}
        if e["table"] is None:
            assert g["table"] is None
            continue
        assert g["table"]["columns"] == e["table"]["columns"]
        for a, b in zip(g["table"]["arrays"], e["table"]["arrays"], strict=True):
            assert _same_bits(a, b)
    # one array per column and layout crossed the wire, not one per contact
    _, light, blocks = pickle.loads(data)
    assert len(blocks) == 2 and all(r is None or not isinstance(r, dict) or r["table"] is None
                                    for r in light)
    assert records[0]["table"] is not None  # the worker's own records are not modified


def test_a_restart_reads_the_parts_rows_back_as_the_contacts_tables(tmp_path):
    """OutputDirectory.packed_rows (the rows of skipped contacts, each part's columns converted
    once and sliced) equals tasks.pack of each contact's rows taken out of the part by pandas
    (groupby, drop, reset_index: the reference), bit for bit, for a part mixing contacts with
    and without sectors, in both table formats; OutputDirectory.rows gives those frames."""
    from fretwear.bundle.store import OutputDirectory
    from fretwear.bundle.tasks import pack

    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    tables = [reference(tmp_path / f"histories/t{k}.parquet", case) for k in range(3)]
    tables.append(tables[0].drop(columns=["sector"]).iloc[:4])
    records = [{"contact": f"c{k}", "status": "done", "key": "k", "table": pack(t),
                "warnings": [], "error": None} for k, t in enumerate(tables)]
    for fmt in ("parquet", "csv"):
        store = OutputDirectory(tmp_path / f"out-{fmt}", table_format=fmt)
        store.write_part([dict(r) for r in records[:2]])
        store.write_part([dict(r) for r in records[2:]])
        previous = store.previous()
        wanted = [previous[c] for c in ("c3", "c0", "c2")]
        got = store.packed_rows(wanted)
        frames = store.rows(wanted)
        assert sorted(got) == sorted(frames) == ["c0", "c2", "c3"]
        for contact in got:
            part = pd.read_parquet(store.parts / previous[contact]["rows_file"]) \
                if fmt == "parquet" else pd.read_csv(store.parts / previous[contact]["rows_file"],
                                                     dtype={"contact": str})
            rows = part[part["contact"] == contact].drop(columns="contact") \
                .reset_index(drop=True)
            pd.testing.assert_frame_equal(frames[contact], rows, check_exact=True)
            expected = pack(rows)
            assert got[contact]["columns"] == expected["columns"]
            for a, b in zip(got[contact]["arrays"], expected["arrays"], strict=True):
                assert _same_bits(a, b), (fmt, contact)


def test_the_runs_wall_time_includes_assembling_and_writing_the_results(tmp_path, monkeypatch):
    """stats["seconds"] (the final line's time, run.json's) runs up to the files written: a
    dataset that takes 1 s more to write makes the run at least 1 s long (at 20 000 contacts the
    time stopped before the last 4 s of assembling and writing)."""
    import time as time_module

    from fretwear.bundle.store import OutputDirectory

    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    calls = []

    def slowed(name):
        real = getattr(OutputDirectory, name)

        def slow(self, *args, **kwargs):
            calls.append(name)
            time_module.sleep(1.0)
            return real(self, *args, **kwargs)
        return slow

    # the dataset is written by regions of the table file (Zarr) or whole (NetCDF, in memory)
    for name in ("write_dataset", "write_zarr_by_regions"):
        monkeypatch.setattr(OutputDirectory, name, slowed(name))
    result = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    written = json.loads((tmp_path / "out" / "run.json").read_text())
    assert result.stats["seconds"] >= 1.0 and written["seconds"] >= 1.0
    assert written["contacts_per_s"] == result.stats["contacts_per_s"] > 0
    no_output = run_bundle(manifest, case, scheduler="serial")
    # without an output directory nothing is written; its time is measured all the same
    assert no_output.stats["seconds"] > 0 and len(calls) == 1


@pytest.mark.parametrize("n, workers", [(500, 2), (1_601, 2), (7_777, 3)])
def test_workers_share_a_cost_that_grows_along_the_manifest(n, workers):
    """engine.submitted_slices and engine.worker_order: every contact in exactly one group, each
    group a consecutive slice of the manifest, the sizes of task_sizes in submission order (each
    worker's run the same number of contacts within one); Dask gives each worker a
    consecutive run of the submitted groups, and when the cost grows linearly along the
    manifest (1 to 2: a manifest sorted by row, the U-bend rows impacting more) the runs' work
    (computed here by summing the costs) is the same within 1 %, where consecutive halves hold
    0.625 of the work against 0.875 (the integral of 1 + x over
    each half of [0, 1]); each run is in the manifest's order, and the r-th groups of the runs
    are neighbours in the manifest (the parts arrive about in its order)."""
    from fretwear.bundle.engine import submitted_slices, task_sizes, worker_order

    sizes = task_sizes(n, workers)
    submitted = worker_order(len(sizes), workers)
    assert sorted(submitted) == list(range(len(sizes)))
    groups = submitted_slices(list(range(n)), sizes, submitted)
    assert [len(g) for g in groups] == sizes
    cut = [groups[submitted.index(k)] for k in range(len(sizes))]  # the manifest's order
    assert [i for g in cut for i in g] == list(range(n))
    cost = 1 + np.arange(n) / (n - 1)
    runs = np.array(submitted).reshape(workers, -1)
    counts = [sum(len(cut[k]) for k in run) for run in runs]
    assert np.ptp(counts) <= 1
    work = [sum(cost[cut[k]].sum() for k in run) for run in runs]
    assert np.ptp(work) <= 0.01 * np.mean(work)
    assert all((np.diff(run) > 0).all() for run in runs)
    assert np.ptp(runs, axis=0).max() == workers - 1  # round r: the groups r*w ... r*w + w-1
    consecutive = cost[:n // 2].sum() / cost.sum()
    assert consecutive == pytest.approx(0.625 / 1.5, rel=1e-2)


@pytest.mark.parametrize("contacts, workers", [(16, 2), (500, 2), (1_601, 2), (20_000, 2),
                                               (50_000, 2), (50_000, 3), (7_777, 64)])
def test_task_groups_stay_small_however_large_the_bundle(contacts, workers):
    """engine.task_sizes: every contact in a group, at least 8 groups a worker, none beyond
    GROUP_SIZE contacts, sizes within one, the group count a multiple of the workers (Dask
    gives each a consecutive run) and each worker's run holding the same number of contacts
    within one (a scale trial found 16 tasks of 3 125 contacts for 50 000 on 2 workers)."""
    from fretwear.bundle.engine import GROUP_SIZE, TASKS_PER_WORKER, task_sizes

    sizes = task_sizes(contacts, workers)
    assert sum(sizes) == contacts and max(sizes) <= GROUP_SIZE and np.ptp(sizes) <= 1
    assert len(sizes) % workers == 0 and len(sizes) >= TASKS_PER_WORKER * workers
    runs = np.array(sizes).reshape(workers, -1).sum(axis=1)
    assert np.ptp(runs) <= 1


def test_every_dataset_cell_is_the_tables_value(tmp_path):
    """BundleResult.dataset holds the table's values cell by cell (each contact × instant
    variable from the contact's first row at that instant, each sector variable from the row of
    that sector, the sector bounds from the contact's rows), located here by a plain loop over
    the table's rows: the independent reading of build_dataset's pandas → xarray path."""
    from fretwear.bundle.result_dataset import _SECTOR_ONLY, _sector_columns

    manifest, case = write_bundle(tmp_path, oscillator(), 3)
    result = run_bundle(manifest, case, scheduler="serial")
    ds, table = result.dataset, result.table
    sector_vars = [v for v in ds.data_vars if v in _sector_columns() and v not in _SECTOR_ONLY]
    global_vars = [v for v in ds.data_vars if v not in _sector_columns()]
    assert sector_vars and global_vars
    seen = set()
    for row in table.itertuples(index=False):
        c, t, s = row.contact, row.instant, int(row.sector)
        if (c, t) not in seen:
            seen.add((c, t))
            for v in global_vars:
                assert ds[v].sel(contact=c, instant=t).item() == getattr(row, v), v
        for v in sector_vars:
            assert ds[v].sel(contact=c, instant=t, sector=s).item() == getattr(row, v), v
        for v in _SECTOR_ONLY:
            assert ds[v].sel(contact=c, sector=s).item() == getattr(row, v), v
    assert len(seen) == ds.sizes["contact"] * ds.sizes["instant"]


def test_kwu_epri_one_pass_with_the_maxima_equals_two_passes_without(tmp_path):
    """issue 28: a KWU-EPRI contact whose FNOR_MAXI and VTAN_MAXI come from the manifest
    (columns force_max_N, speed_max_m_per_s, per contact) is read once; without them, twice
    (the power's pass gives the window's maxima, a second the class counts), which
    ``stats["two_pass_contacts"]`` says. Given the window's own maxima (the largest normal force
    and the largest numpy.hypot(Vt1, Vt2) of the history: theory §4, computed here
    independently with numpy), both give the same table bit for bit: both run in this process,
    on this machine (across machines only to rounding). Contacts computed in one task (a
    contact split in time chunks sums in another order: equal to rounding,
    test_kwu_epri_contact_is_split_only_with_both_maxima); among them a file of several row
    groups, streamed in blocks."""
    h = oscillator()
    manifest, _ = write_bundle(tmp_path, h, 3)
    write_history(scaled(h, 3), tmp_path / "histories" / "groups.parquet", row_group_size=400)
    frame = pd.read_csv(manifest)
    frame.loc[3] = {**frame.loc[2].to_dict(), "contact": "groups",
                    "history": "histories/groups.parquet"}
    frame.to_csv(manifest, index=False)
    (tmp_path / "kwu.toml").write_text(KWU_CASE.format(maxima=""))
    two = run_bundle(manifest, tmp_path / "kwu.toml", scheduler="serial")
    assert two.errors.empty, two.errors
    assert two.stats["two_pass_contacts"] == 4
    forces, speeds = [], []
    for k in range(4):
        hk = scaled(h, k)
        forces.append(float(np.max(hk.normal_force)))
        speeds.append(float(np.max(np.hypot(hk.vt1, hk.vt2))))
    frame["force_max_N"], frame["speed_max_m_per_s"] = forces, speeds
    given = tmp_path / "given.csv"
    frame.to_csv(given, index=False, float_format="%.17g")
    one = run_bundle(given, tmp_path / "kwu.toml", scheduler="serial")
    assert one.errors.empty, one.errors
    assert one.stats["two_pass_contacts"] == 0
    for contact in frame["contact"]:
        assert_identical(rows_of(one, contact), rows_of(two, contact))
    assert np.all(rows_of(one, "groups")["volume_mobile"] > 0)
