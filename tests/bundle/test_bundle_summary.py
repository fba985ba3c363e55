"""fretwear.bundle.result.summarize, which takes each contact's quantities over the whole
table at once, against the per-contact loop it replaced (kept below, unchanged, as the
reference): the same DataFrame bit for bit (rows, order, columns, dtypes, values, notes,
methods), the same attrs and the same errors, on the bundle tests' tables (tests/bundle/
bundle_helpers.py: the shipped oscillator history scaled per contact) with and without
sectors, walls, limits, a tube replacement, depths beyond the relation's range, and on the
same tables reshuffled, renamed, with equal instants or signed zeros.

The reference follows the summary's rules as they change: since the fix of the default time to
the limit (the table's limit_instant only where reached by the last instant, and for an explicit
limit equal to the contact's own too), its FROM_TABLE branch says so; since the exact time to
another limit (through the contact's geometry and worn volume), it hands each contact's rows,
taken here group by group, to the contact's DepthModel (fretwear.table.depth_build.
record_model) where its geometry and law are known (that inversion is checked against
independent computations in test_bundle_time_to_other_limit.py), the monotone cubic
otherwise; the rest is the old loop."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from bundle_helpers import BASE_CASE, oscillator, write_bundle

from fretwear.bundle import run_bundle
from fretwear.bundle.manifest import IDENTITY
from fretwear.bundle.result import RECORD_KEYS, check_limit, summarize
from fretwear.errors import InputError
from fretwear.table.depth_build import record_model
from fretwear.table.depth_rows import (
    FROM_MODEL,
    FROM_TABLE,
    INTERPOLATED,
    METHODS,
    ContactModels,
    interpolated_time,
)
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT


# ------------------------------------------------------------------ the reference (old loop)
def _reference_global_rows(rows: pd.DataFrame) -> pd.DataFrame:
    """One row per instant (sector tables repeat the global columns on every sector row)."""
    if "sector" in rows.columns and rows["sector"].notna().any():
        rows = rows.drop_duplicates("instant", keep="first")
    return rows.sort_values("instant")


def _deepest(rows: pd.DataFrame) -> float:
    """The deepest depth of rows of finite instants, a NaN depth of a finite volume (beyond the
    relation's range) counting as deeper than any."""
    rows = rows[np.isfinite(rows["instant"])]
    depth = rows["depth_mobile"].to_numpy(dtype=float)
    if "volume_mobile" in rows.columns:
        beyond = np.isnan(depth) & np.isfinite(rows["volume_mobile"].to_numpy(dtype=float))
        depth = np.where(beyond, np.inf, depth)
    return float(np.nanmax(depth)) if np.isfinite(depth).any() or np.isinf(depth).any() \
        else math.nan


def reference_summarize(table: pd.DataFrame, contacts: pd.DataFrame, *, limit: float | None,
              limit_m: float | None, wall_thickness: float | None) -> pd.DataFrame:
    """summarize as it was up to commit bb56e91 (a loop over the contacts), with the rule of
    the table's limit_instant of the later fix (module docstring) and the time_unit column."""
    check_limit(limit)  # since run_bundle(limit=): the one check of a fraction of the wall
    if limit_m is not None and not (0 < limit_m and math.isfinite(limit_m)):
        raise InputError(f"limit_m must be a depth > 0 [m], got {limit_m!r}")
    info = contacts.set_index("contact") if len(contacts) else contacts
    # the wear table's own limit instant (law and geometry inverted), for the case's limit
    given = "limit_instant" in table.columns and limit_m is None
    rows = []
    for contact, group in table.groupby("contact", sort=False):
        glob = _reference_global_rows(group)
        last = glob.iloc[-1]
        depth = float(last["depth_mobile"])
        sector_max = (float(group.loc[group["instant"] == last["instant"],
                                      "depth_mobile_sector"].max())
                      if "depth_mobile_sector" in group.columns else math.nan)
        wall = math.nan
        if "wall_thickness" in info.columns and contact in info.index:
            given_wall = info.at[contact, "wall_thickness"]
            wall = math.nan if given_wall is None or pd.isna(given_wall) else float(given_wall)
        its_wall = math.isfinite(wall)
        if not math.isfinite(wall) and wall_thickness is not None:
            wall = float(wall_thickness)
        own = info.at[contact, "depth_limit"] if "depth_limit" in info.columns \
            and contact in info.index else None
        own = DEFAULT_DEPTH_LIMIT if own is None or pd.isna(own) else float(own)
        fraction = own if limit is None else limit
        target = (fraction * wall if math.isfinite(wall) and limit_m is None
                  else (limit_m if limit_m is not None else math.nan))
        note = ""
        finite = np.isfinite(glob["depth_mobile"].to_numpy(dtype=float))
        if not finite.all():
            first_nan = float(glob["instant"].to_numpy()[~finite][0])
            note = f"depth beyond the relation's range from instant {first_nan:g}"
        replaced = (info.at[contact, "tube_replacement"]
                    if "tube_replacement" in info.columns and contact in info.index else None)
        replaced = None if replaced is None or pd.isna(replaced) else float(replaced)
        forecast = math.nan
        if given and glob["limit_instant"].notna().any() and its_wall and fraction == own:
            t_lim = forecast = float(glob["limit_instant"].dropna().iloc[-1])
            since = glob if replaced is None else glob[glob["instant"] >= replaced]
            deepest = _deepest(since)
            reached = target <= 0 or deepest >= target
            t_lim = t_lim if reached or t_lim <= float(last["instant"]) else math.nan
            t_lim = math.nan if math.isinf(t_lim) else t_lim
            method = FROM_TABLE
        elif math.isfinite(target):
            def get(column, contact=contact):
                value = (info.at[contact, column] if column in info.columns
                         and contact in info.index else None)
                return None if not isinstance(value, str | dict | float) or (
                    isinstance(value, float) and math.isnan(value)) else value

            geometry = MODELS.geometry(get("contact_type"), get("dimensions"))
            sectored = "sector" in group.columns and bool(group["sector"].notna().any())
            model = _reference_model(glob, group, info, contact, geometry, sectored)
            since = glob if replaced is None else glob[glob["instant"] >= replaced]
            deepest = _deepest(since)
            label = INTERPOLATED if model is None else FROM_MODEL
            if not (target <= 0 or deepest >= target):
                t_lim, method = math.nan, label
            elif target <= 0:  # reached at once: the start of the tube in place
                method = label
                t_lim = (replaced if replaced is not None
                         else 0.0 if float(glob["origin"].iloc[0]) == 0
                         else float(glob["instant"].iloc[0]))
            elif model is None:
                sel = since
                origin = (float(sel["origin"].iloc[0]) if "origin" in sel.columns and len(sel)
                          else 0)
                t_lim = interpolated_time(sel["instant"].to_numpy(dtype=float),
                                      sel["depth_mobile"].to_numpy(dtype=float), target,
                                      from_zero=origin == 0)
                method = INTERPOLATED
            else:  # the contact's depth model (its inversion checked against independent
                # computations in test_bundle_time_to_other_limit.py)
                t_lim, method = float(model.time_to(target)), FROM_MODEL
        else:
            t_lim, method = math.nan, "no limit: give the wall thickness or limit_m"
        unit = (info.at[contact, "time_unit"] if "time_unit" in info.columns
                and contact in info.index else None)
        row = {"contact": contact, "instant": float(last["instant"]),
               "time_unit": None if unit is None or pd.isna(unit) else unit,
               "power": float(last["power"]), "depth": depth, "depth_sector_max": sector_max,
               "wall_thickness": wall, "depth_fraction": depth / wall if wall > 0 else math.nan,
               "limit_depth": target, "time_to_limit": t_lim, "limit_forecast": forecast,
               "time_to_limit_method": method, "note": note}
        rows.append(row)
    out = pd.DataFrame(rows, columns=["contact", "instant", "time_unit", "power", "depth",
                                      "depth_sector_max",
                                      "wall_thickness", "depth_fraction", "limit_depth",
                                      "time_to_limit", "limit_forecast",
                                      "time_to_limit_method", "note"])
    ident = [c for c in IDENTITY if c != "contact" and c in contacts.columns]
    if len(out):
        out = out.merge(contacts[["contact", *ident]], on="contact", how="left")
    beyond = out["depth"].isna()
    out = (out.assign(_beyond=beyond).sort_values(["_beyond", "depth"],
                                                  ascending=[False, False], kind="stable")
           .drop(columns="_beyond").reset_index(drop=True))
    out.insert(0, "rank", np.arange(1, len(out) + 1))
    front = ["rank", "contact", *ident]
    out = out[front + [c for c in out.columns if c not in front]]
    methods = [m for m in out["time_to_limit_method"].unique() if m in METHODS]
    out.attrs["time_to_limit"] = "; ".join(methods) if methods else "no limit"
    out.attrs["limit"] = limit
    out.attrs["limit_m"] = limit_m
    return out


MODELS = ContactModels()


def _reference_model(glob, group, info, contact, geometry, sectored):
    """The contact's DepthModel from its record (the contacts frame's values) and global
    rows, sector powers at the last instant; None where the law or geometry is not known."""
    if geometry is None or "volume_mobile" not in glob.columns:
        return None
    record = {}
    for key in RECORD_KEYS:
        value = info.at[contact, key] if key in info.columns and contact in info.index else None
        record[key] = None if isinstance(value, float) and math.isnan(value) else value
    if MODELS.law(record["law"]) is None:
        return None
    sectors = None
    if sectored:
        last = group[(group["instant"] == glob["instant"].iloc[-1]) & group["sector"].notna()]
        sectors = last.sort_values("sector", kind="stable")["sector_power"].to_numpy(float)
    try:
        return record_model(record, instants=glob["instant"].to_numpy(float),
                            origins=glob["origin"].to_numpy(float),
                            depths=glob["depth_mobile"].to_numpy(float),
                            volume_mobile=glob["volume_mobile"].to_numpy(float),
                            volume_obstacle=glob["volume_obstacle"].to_numpy(float),
                            power=float(glob["power"].iloc[-1]), geometry=geometry,
                            sector_powers=sectors)
    except (InputError, ValueError, TypeError):
        return None


# ------------------------------------------------------------------ the bundles
NO_SECTORS = BASE_CASE.replace("[sectors]\ncount = 4\n", "")
#: Limits asked of summary(): none (the table's limit_instant or the case's), fractions of the
#: wall reached between instants or not at all, depths in metres (reached by every contact, by
#: some, by none; an int), a wall for every tube, and combinations.
LIMITS = [{}, {"limit": 0.4}, {"limit": 0.03}, {"limit": 1}, {"limit_m": 3e-5},
          {"limit_m": 1e-9}, {"limit_m": 7e-5}, {"limit_m": 1}, {"wall_thickness": 2e-4},
          {"wall_thickness": 2e-4, "limit": 0.25}, {"wall_thickness": 1e-3, "limit_m": 5e-5}]


def _run(directory, case_text, count=4, extra=None, more=None):
    """run_bundle (serial) on ``count`` contacts of bundle_helpers.write_bundle, the base case
    replaced by ``case_text``; ``more``: manifest rows appended."""
    manifest, case = write_bundle(directory, oscillator(), count, extra=extra)
    case.write_text(case_text)
    frame = pd.read_csv(manifest)
    if more is not None:
        frame = pd.concat([frame, pd.DataFrame(more)], ignore_index=True)
    frame["history"] = [str(directory / h) for h in frame["history"]]
    return run_bundle(frame, case, scheduler="serial")


@pytest.fixture(scope="module")
def bundles(tmp_path_factory):
    """name -> (table, contacts) of bundles run once for the module."""
    made = {}

    def run(name, *args, **kwargs):
        result = _run(tmp_path_factory.mktemp(name), *args, **kwargs)
        assert result.stats["failed"] == 0, result.errors
        made[name] = (result.table, result.contacts)

    run("sectors", BASE_CASE)
    run("no_sectors", NO_SECTORS)
    # a wall per contact (the tables get limit_instant; NaN where no wall), a case limit and a
    # tube replaced at 1.5 and 1 year (the depth restarts from zero)
    run("walls", BASE_CASE, extra={"wall_thickness_m": [1.1e-3, None, 1e-5, 6e-5],
                                   "tube_replacement": [None, 1.5, None, 1.0],
                                   "depth_limit": [None, 0.3, 0.5, None]})
    run("replaced_no_sectors", NO_SECTORS, extra={"tube_replacement": [None, 1.5, 0.5, 1.0],
                                                  "wall_thickness_m": [None, 2e-4, None, 1e-4]})
    # "deep": a bore worn past its relation's range (NaN depths from some instant on), as in
    # test_bundle_engine.test_bad_contacts_land_in_errors_and_the_others_complete
    deep = {"contact": ["deep"], "history": ["histories/t0.parquet"],
            "contact_type": ["TUBE_ALESAGE"], "obstacle_radius_m": [9.725e-3],
            "law.mobile.COEF_USURE": [1e-10], "sectors.count": [1]}
    run("deep", BASE_CASE, 3, more=deep)
    run("deep_no_sectors", NO_SECTORS, 2, more={**deep, "sectors.count": [None]})
    # some contacts with sectors, some without (sector Int64 with <NA>)
    run("mixed", NO_SECTORS, 4, extra={"sectors.count": [4, None, 2, None]})
    return made


# ------------------------------------------------------------------ the comparison
def _bits(values: pd.Series) -> np.ndarray:
    return values.to_numpy(dtype=float).view(np.int64)


def assert_same(table: pd.DataFrame, contacts: pd.DataFrame, limits=LIMITS, *,
                fails: bool = False) -> list:
    """summarize == reference_summarize for every limit: frames equal exactly, float columns
    equal bit for bit (signed zeros, NaN payloads), attrs equal; or, where ``fails``, the same
    error (class and message). Returns the summaries."""
    out = []
    for kw in limits:
        args = {"limit": None, "limit_m": None, "wall_thickness": None, **kw}
        if fails:
            with pytest.raises(Exception) as expected:  # noqa: B017, PT011 - any: the same
                reference_summarize(table, contacts, **args)
            with pytest.raises(expected.type) as raised:
                summarize(table, contacts, **args)
            assert str(raised.value) == str(expected.value)
            continue
        old = reference_summarize(table, contacts, **args)
        new = summarize(table, contacts, **args)
        pd.testing.assert_frame_equal(new, old, check_exact=True)
        assert new.attrs == old.attrs, kw
        for column in new.columns:
            if new[column].dtype == np.float64:
                assert np.array_equal(_bits(new[column]), _bits(old[column])), (kw, column)
        out.append(new)
    return out


def _interpolated(summaries) -> int:
    """How many times to the limit were found strictly between two instants (through the
    volume, not a table instant)."""
    count = 0
    for s in summaries:
        t = s.loc[s["time_to_limit_method"] == FROM_MODEL, "time_to_limit"].dropna()
        count += int((t % 0.5 != 0).sum())
    return count


@pytest.mark.parametrize("name", ["sectors", "no_sectors", "walls", "replaced_no_sectors",
                                  "deep", "deep_no_sectors", "mixed"])
def test_summary_equals_the_per_contact_loop(bundles, name):
    table, contacts = bundles[name]
    summaries = assert_same(table, contacts)
    assert len(summaries) == len(LIMITS)
    # depths of the table as limits: reached exactly at an instant (the deepest contact's last
    # one, another's earlier one), and a negative wall (a limit reached at once)
    depth = table["depth_mobile"][table["depth_mobile"] > 0]
    exact = [{"limit_m": float(depth.max())}, {"limit_m": float(depth.iloc[len(depth) // 2])},
             {"wall_thickness": -1e-3}]
    reached = assert_same(table, contacts, exact)
    # (the depth model inverted: the instant to 1e-12 relative, not bit for bit)
    assert np.isclose(reached[0]["time_to_limit"], reached[0]["instant"], rtol=1e-12,
                      atol=0).any()
    assert _interpolated(summaries) > 0  # the inversion through the volume was exercised
    if name.startswith("deep"):
        assert summaries[0]["contact"].iloc[0] == "deep"
        assert summaries[0]["note"].iloc[0].startswith("depth beyond the relation's range")
    if name == "walls":  # the table's own limit instant, the case's limit and the replacement
        s = summaries[0].set_index("contact")
        assert s.loc["R1C1-AVB", "time_to_limit_method"] == FROM_TABLE
        assert s.loc["R1C2-AVB", "time_to_limit_method"].startswith("no limit")
        assert s.loc["R2C1-AVB", "limit_depth"] == 0.5 * 1e-5
        # limit=0.4: R1C1's own limit (its table's instant), R2C1's is 0.5 (through the volume)
        s = summaries[1].set_index("contact")
        assert s.loc["R1C1-AVB", "time_to_limit_method"] == FROM_TABLE
        assert s.loc["R2C1-AVB", "time_to_limit_method"] == FROM_MODEL
        assert summaries[2].attrs["time_to_limit"] == FROM_MODEL  # limit=0.03


def test_summary_of_reshaped_tables(bundles):
    """The same tables with their rows shuffled (contacts interleaved, instants unsorted), three
    copies under other names, contacts missing from ``contacts``, a contact with no identity
    row, and limit_instant edited (inf: never, NaN on some rows)."""
    rng = np.random.default_rng(20240607)
    for name in ("walls", "mixed", "deep", "replaced_no_sectors"):
        table, contacts = bundles[name]
        shuffled = table.iloc[rng.permutation(len(table))].reset_index(drop=True)
        assert_same(shuffled, contacts)
        copies, infos = [], []
        for k in range(3):
            copies.append(table.assign(contact=table["contact"] + f"/{k}"))
            infos.append(contacts.assign(contact=contacts["contact"] + f"/{k}"))
        many = pd.concat(copies, ignore_index=True)
        assert_same(many.iloc[rng.permutation(len(many))], pd.concat(infos, ignore_index=True))
        assert_same(table, contacts.iloc[1:].reset_index(drop=True))
        assert_same(table, contacts.iloc[:0])
        assert_same(table, contacts[["contact"]])
        if "limit_instant" in table.columns:
            edited = table.copy()
            lim = edited["limit_instant"].to_numpy(dtype=float).copy()
            lim += edited["instant"].to_numpy(dtype=float)  # the last one counts
            lim[::3] = np.nan
            lim[edited["contact"].to_numpy() == edited["contact"].iloc[0]] = np.inf
            edited["limit_instant"] = lim
            summaries = assert_same(edited, contacts, [{}])
            first = summaries[0].set_index("contact").loc[table["contact"].iloc[0]]
            if math.isnan(first["wall_thickness"]):  # an instant without a wall: unused
                assert first["time_to_limit_method"].startswith("no limit")
            else:
                assert first["time_to_limit_method"] == FROM_TABLE
            assert math.isnan(first["time_to_limit"])


def test_summary_with_equal_instants_signed_zeros_and_no_rows(bundles):
    """Rows repeating an instant (their order is the sort's), sector depths of -0.0 and 0.0 at
    the last instant, NaN instants, an empty table, and a table whose contacts are all NaN."""
    table, contacts = bundles["mixed"]
    rng = np.random.default_rng(7)
    plain = table[table["sector"].isna()]
    # five rows per instant (pandas' sort is not stable on them: the order is its own)
    repeated = pd.concat([plain.assign(depth_mobile=plain["depth_mobile"] * (1 + k / 4),
                                       power=plain["power"] + k) for k in range(5)])
    for _ in range(4):
        shuffled = repeated.iloc[rng.permutation(len(repeated))]
        assert_same(shuffled, contacts, [{}, {"limit_m": 1}, {"limit_m": 6e-5}])
        # without the geometry, PCHIP refuses the repeated instants: the same ValueError
        assert_same(shuffled, contacts[["contact"]], [{"limit_m": 6e-5}], fails=True)
    # 9 sector rows at the last instant (the 4 sectors twice and sector 1 again), depths 0.0
    # and -0.0: which zero the max keeps is numpy's reduction's (here unlike a running max)
    sectors, info = bundles["sectors"]
    final = sectors["instant"] == sectors["instant"].max()
    nine = pd.concat([sectors, sectors, sectors[final & (sectors["sector"] == 1)]],
                     ignore_index=True)
    depth = nine["depth_mobile_sector"].to_numpy(dtype=float).copy()
    last = nine["instant"].to_numpy() == nine["instant"].max()
    assert last.sum() == 9 * len(info)
    for _ in range(8):
        depth[last] = np.where(rng.random(last.sum()) < 0.5, -0.0, 0.0)
        summaries = assert_same(nine.assign(depth_mobile_sector=depth), info, [{}])
        assert (summaries[0]["depth_sector_max"] == 0).all()
    nan_instant = table.copy()
    instants = nan_instant["instant"].to_numpy(dtype=float).copy()
    instants[::7] = np.nan
    nan_instant["instant"] = instants
    assert_same(nan_instant, contacts)
    # no rows (every contact failed): the old code raised a KeyError selecting the identity
    # columns (and run_bundle(output=...) crashed writing summary.csv); now an empty ranking
    # with every column
    for info in (contacts, contacts.iloc[:0]):
        with pytest.raises(KeyError):
            reference_summarize(table.iloc[:0], info, limit=None, limit_m=None,
                                wall_thickness=None)
        empty = summarize(table.iloc[:0], info, limit=None, limit_m=None, wall_thickness=None)
        assert len(empty) == 0
        assert list(empty.columns[:2]) == ["rank", "contact"]
        assert {"tube_row", "time_to_limit", "depth_fraction"} <= set(empty.columns)
    assert_same(table.iloc[:0], contacts[["contact"]])
    assert_same(table.assign(contact=pd.Series([None] * len(table), dtype=object)),
                contacts[["contact"]])


def test_summary_errors_are_the_same(bundles):
    table, contacts = bundles["sectors"]
    bad = [{"limit": 0}, {"limit": -0.4}, {"limit": math.nan}, {"limit": math.inf},
           {"limit_m": 0.0}, {"limit_m": -1e-4}, {"limit_m": math.nan}, {"limit_m": math.inf}]
    for kw in bad:
        args = {"limit": None, "limit_m": None, "wall_thickness": None, **kw}
        with pytest.raises(InputError) as expected:
            reference_summarize(table, contacts, **args)
        with pytest.raises(InputError) as raised:
            summarize(table, contacts, **args)
        assert str(raised.value) == str(expected.value)
    # a contact listed twice in ``contacts``: the same failure as the loop's
    twice = pd.concat([contacts, contacts.iloc[:1]], ignore_index=True)
    assert_same(table, twice, [{}, {"limit_m": 1e-5}], fails=True)


def test_summary_is_computed_once_per_limit_and_kept(bundles, monkeypatch):
    """BundleResult.summary() calls summarize once per (limit, limit_m, wall_thickness) and
    reads its ranking after (issue 28); distinct limits give distinct rankings, each the one
    summarize gives directly; a caller's change to a returned ranking is not seen again; a
    refused limit is refused on every call (limit=True is not the cached limit=1)."""
    from fretwear.bundle import result as result_module
    from fretwear.bundle.result import BundleResult
    from fretwear.errors import KeywordError

    table, contacts = bundles["walls"]
    result = BundleResult(table=table, errors=pd.DataFrame(), warnings=pd.DataFrame(),
                          contacts=contacts)
    calls = []

    def counted(*args, **kwargs):
        calls.append(kwargs)
        return summarize(*args, **kwargs)

    monkeypatch.setattr(result_module, "summarize", counted)
    first = result.summary()
    first["depth"] = -1.0  # the caller's copy
    again = result.summary()
    assert len(calls) == 1
    direct = summarize(table, contacts, limit=None, limit_m=None, wall_thickness=None)
    pd.testing.assert_frame_equal(again, direct, check_exact=True)  # same process: exact
    assert again.attrs == direct.attrs
    deep = result.summary(0.03)
    assert result.summary(0.03) is not deep
    pd.testing.assert_frame_equal(result.summary(0.03), deep)
    assert len(calls) == 2
    # a shallower limit: reached earlier by the contacts that reach both
    both = deep.merge(again, on="contact", suffixes=("_03", "_own"))
    assert not both["limit_depth_03"].equals(both["limit_depth_own"])
    result.summary(limit_m=1e-5)
    result.summary(limit_m=1e-5)
    assert len(calls) == 3
    assert result.summary(1) is not None
    with pytest.raises(KeywordError):
        result.summary(True)
    with pytest.raises(KeywordError):
        result.summary(True)


def test_summary_of_a_table_file_read_by_pieces_of_whole_contacts(bundles, tmp_path):
    """A result whose table is a Parquet file ranks its contacts from pieces of whole contacts
    (table_file.contact_pieces, issue 28: the client's memory) exactly as the per-contact loop
    ranks the whole table read at once (reference_summarize, the independent computation):
    every bundle's tables end to end under other names (pieces with and without sectors, a
    sector column with <NA> in some pieces only), one contact a piece, a few, all; and the
    pieces are the whole read's rows. A table whose contact's rows are not consecutive, or
    with a row without contact, is read whole (None)."""
    from fretwear.bundle.result import BundleResult
    from fretwear.bundle.table_file import SUMMARY_COLUMNS, contact_pieces, read_columns

    tables, infos = [], []
    for name, (table, contacts) in bundles.items():
        tables.append(table.assign(contact=table["contact"] + f"@{name}"))
        infos.append(contacts.assign(contact=contacts["contact"] + f"@{name}"))
    table, contacts = pd.concat(tables, ignore_index=True), pd.concat(infos, ignore_index=True)
    path = tmp_path / "table.parquet"
    table.to_parquet(path, index=False, row_group_size=100)  # groups cut through contacts
    whole = read_columns(path, SUMMARY_COLUMNS, categorical=("contact",))
    count, some = table["contact"].nunique(), len(table) // 4
    for rows, expected in ((1, count), (some, None), (len(table), 1)):
        pieces = list(contact_pieces(path, SUMMARY_COLUMNS, rows=rows))
        assert len(pieces) == expected or (expected is None and 3 <= len(pieces) < count)
        assert sum(p["contact"].nunique() for p in pieces) == count
        glued = pd.concat(pieces, ignore_index=True)
        pd.testing.assert_frame_equal(glued.astype({"contact": str}),
                                      whole.astype({"contact": str}), check_dtype=False,
                                      check_exact=True)
    for kw in LIMITS:
        args = {"limit": None, "limit_m": None, "wall_thickness": None, **kw}
        expected = reference_summarize(whole, contacts, **args)
        for rows in (1, some):
            got = summarize(contact_pieces(path, SUMMARY_COLUMNS, rows=rows), contacts, **args)
            pd.testing.assert_frame_equal(got, expected, check_exact=True)
            assert got.attrs == expected.attrs
    result = BundleResult(table=None, table_file=str(path), errors=pd.DataFrame(),
                          warnings=pd.DataFrame(), contacts=contacts)
    pd.testing.assert_frame_equal(result.summary(0.03), reference_summarize(
        whole, contacts, limit=0.03, limit_m=None, wall_thickness=None), check_exact=True)
    # read whole: a contact in two runs of rows, a row without contact
    table.iloc[::-1].to_parquet(path, index=False)
    assert contact_pieces(path, SUMMARY_COLUMNS) is not None  # reversed: still consecutive
    table.iloc[np.r_[1:len(table), 0]].to_parquet(path, index=False)
    assert contact_pieces(path, SUMMARY_COLUMNS) is None
    table.assign(contact=table["contact"].where(table.index != 5)).to_parquet(path, index=False)
    assert contact_pieces(path, SUMMARY_COLUMNS) is None
