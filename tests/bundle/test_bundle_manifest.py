"""Manifests: columns, overrides of the base case, the sources a bundle can come from.

Every contact's rows are compared bit for bit (both sides in this process, on this machine: not
a promise across machines) with the single-contact wear table
(fretwear.table.wear_table) of the same history and case; for a contact whose manifest row
overrides a key, the reference case is a separate TOML file holding that value, read by the
case-file layer (an independent path to the same keywords). These tests run without Dask
(``scheduler="serial"``); tests/bundle/test_bundle_dask.py runs the same on a cluster.
"""

from __future__ import annotations

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

from fretwear.bundle import read_manifest, run_bundle
from fretwear.bundle.manifest import column_key
from fretwear.errors import InputError, KeywordError, LawWarning
from fretwear.io import write_history


def test_column_names_bare_dotted_and_entries():
    assert column_key("mobile_radius_m", "m") == ("geometry", "mobile_radius_m")
    assert column_key("geometry.mobile_radius_m", "m") == ("geometry", "mobile_radius_m")
    assert column_key("law.mobile.COEF_USURE", "m") == ("law", "mobile", "COEF_USURE")
    assert column_key("instants", "m") == ("time", "instants")
    assert column_key("tube_row", "m") == "tube_row"


def test_unknown_column_names_the_closest_key():
    with pytest.raises(KeywordError, match=r"unknown column 'mobile_radus_m' \(did you mean "
                                           r"'mobile_radius_m'\?\)"):
        column_key("mobile_radus_m", "m")
    with pytest.raises(KeywordError, match=r"'tube_rwo' \(did you mean 'tube_row'\?\)"):
        column_key("tube_rwo", "m")
    # [history] name is the contact column: `name` is the law's
    assert column_key("name", "m") == ("law", "name")
    # the history file and the contact id have their own columns
    with pytest.raises(KeywordError, match="unknown column 'history.file'"):
        column_key("history.file", "m")


def test_unknown_column_stops_the_run_before_any_work(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 2,
                                  extra={"obstacle_widht_m": [0.01, 0.01]})
    with pytest.raises(KeywordError, match="did you mean 'obstacle_width_m'"):
        run_bundle(manifest, case, scheduler="serial")


def test_duplicated_contact_and_missing_contact_column(tmp_path):
    with pytest.raises(InputError, match="contact 'a' appears twice"):
        read_manifest(pd.DataFrame({"contact": ["a", "a"], "history": ["x", "y"]}))
    with pytest.raises(KeywordError, match="needs a 'contact' column"):
        read_manifest(pd.DataFrame({"history": ["x"]}))
    bad = tmp_path / "m.toml"
    bad.write_text("[contact]\nhistory = 'x'\n")
    with pytest.raises(KeywordError, match=r"\[\[contacts\]\]"):
        read_manifest(bad)


def test_csv_parquet_and_toml_manifests_agree(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    frame = pd.read_csv(manifest)
    frame.to_parquet(tmp_path / "manifest.parquet")
    (tmp_path / "manifest.toml").write_text("".join(
        f'[[contacts]]\ncontact = "{r.contact}"\nhistory = "{r.history}"\n'
        f"tube_row = {r.tube_row}\ntube_column = {r.tube_column}\nsupport = \"{r.support}\"\n"
        for r in frame.itertuples()))
    tables = [run_bundle(tmp_path / name, case, scheduler="serial").table
              for name in ("manifest.csv", "manifest.parquet", "manifest.toml")]
    for t in tables[1:]:
        pd.testing.assert_frame_equal(t, tables[0])
    assert tables[0]["tube_row"].tolist()[:1] == [1]


def test_rows_equal_the_single_contact_table_with_overrides(tmp_path):
    h = oscillator()
    # contact 1: another tube radius; contact 2: its own coefficient, blocks, instants (CSV
    # cells in TOML syntax); contact 3: database materials instead of the coefficient
    manifest, case = write_bundle(tmp_path, h, 4, extra={
        "mobile_radius_m": [None, 8.0e-3, None, None],
        "law.mobile.COEF_USURE": [None, None, 2.0e-14, None],
        "blocks": [None, None, 2, None],
        "power.t_start_s": [None, None, 0.1, None],
        "power.t_end_s": [None, None, 0.5, None],
        "instants": [None, None, "[1, 3]", None],
        "law.materials": [None, None, None, '["I600TT", "Z6C13"]'],
    })
    # the materials row replaces the base case's coefficient (docs/bundle.md, "Overrides")
    cases = {0: BASE_CASE,
             1: BASE_CASE.replace("mobile_radius_m = 9.525e-3", "mobile_radius_m = 8.0e-3"),
             2: BASE_CASE.replace("9.2e-15", "2.0e-14").replace(
                 "instants = [0.5, 1, 2, 5]", "instants = [1, 3]")
             + "[power]\nblocks = 2\nt_start_s = 0.1\nt_end_s = 0.5\n",
             3: BASE_CASE.replace("mobile = { COEF_USURE = 9.2e-15 }",
                                  'materials = ["I600TT", "Z6C13"]')}
    result = run_bundle(manifest, case, scheduler="serial", force=True)
    assert result.errors.empty, result.errors
    for k in range(4):
        ref_case = tmp_path / f"ref{k}.toml"
        ref_case.write_text(cases[k])
        contact = f"R{k // 2 + 1}C{k % 2 + 1}-AVB"
        assert_identical(rows_of(result, contact),
                         reference(tmp_path / f"histories/t{k}.parquet", ref_case))


def test_a_bad_override_fails_its_contact_only(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 3,
                                  extra={"blocks": [None, "two", None]})
    result = run_bundle(manifest, case, scheduler="serial")
    assert result.errors[["contact", "error"]].values.tolist() == [["R1C2-AVB", "KeywordError"]]
    assert "not a number" in result.errors["message"].iloc[0]
    assert result.stats["done"] == 2 and result.stats["failed"] == 1


def test_given_power_rows_need_no_history(tmp_path):
    case = tmp_path / "base.toml"
    case.write_text(BASE_CASE.replace("[sectors]\ncount = 4\n", ""))
    frame = pd.DataFrame({"contact": ["p1", "p2"], "power.value_W": [1e-3, 2e-3]})
    result = run_bundle(frame, case, scheduler="serial")
    assert result.errors.empty
    # Archard: V = K·P·t at 5 years (theory §4)
    v = result.table.groupby("contact")["volume_mobile"].last()
    assert v["p2"] == pytest.approx(9.2e-15 * 2e-3 * 5 * 31536000.0, rel=1e-15)
    # neither history nor power in any row: one InputError before any work
    # (bundle/manifest_history.py), not an error per contact
    with pytest.raises(InputError, match="'history' column"):
        run_bundle(pd.DataFrame({"contact": ["x"]}), case, scheduler="serial")


def test_code_aster_table_of_several_nodes(tmp_path):
    """One contact per NOEUD; each equals read_history(file, node=...) + wear_table."""
    from fretwear.io.aster import write_aster_table

    h = oscillator()
    frames = []
    for k, node in enumerate(("N12", "N13")):
        g = scaled(h, k)
        frames.append(pd.DataFrame({"NOEUD": node, "INST": g.time, "FN": g.normal_force,
                                    "VT1": g.vt1, "VT2": g.vt2, "DYLOC": g.dy, "DZLOC": g.dz}))
    path = tmp_path / "choc.tab"
    write_aster_table(pd.concat(frames, ignore_index=True), path, float_format="%.17E")
    (tmp_path / "base.toml").write_text(BASE_CASE)
    manifest = read_manifest(path)
    assert [r.contact for r in manifest.rows] == ["N12", "N13"]
    result = run_bundle(path, tmp_path / "base.toml", scheduler="serial")
    assert result.errors.empty
    for node in ("N12", "N13"):
        assert_identical(rows_of(result, node),
                         reference(path, tmp_path / "base.toml", node=node))
    assert result.table["node"].unique().tolist() == ["N12", "N13"]


def _dataset(h, count=3):
    xr = pytest.importorskip("xarray")
    data = {c: (("contact", "time"), np.stack([getattr(scaled(h, k), c) for k in range(count)]))
            for c in h.channels if c != "time"}
    ds = xr.Dataset(data, coords={"contact": [f"c{k}" for k in range(count)], "time": h.time,
                                  "tube_row": ("contact", np.arange(1, count + 1)),
                                  "obstacle_width_m": ("contact", [12.7e-3, 10e-3, 12.7e-3])})
    ds["dy"].attrs["units"] = "m"
    return ds


@pytest.mark.parametrize("where", ["memory", "zarr", "netcdf"])
def test_dataset_and_stores_contact_by_time(tmp_path, where):
    h = oscillator()
    ds = _dataset(h)
    (tmp_path / "base.toml").write_text(BASE_CASE)
    source = ds
    if where == "zarr":
        pytest.importorskip("zarr")
        source = tmp_path / "bundle.zarr"
        ds.to_zarr(source, mode="w", consolidated=False, zarr_format=2)
    elif where == "netcdf":
        source = tmp_path / "bundle.nc"
        ds.to_netcdf(source)
    result = run_bundle(source, tmp_path / "base.toml", scheduler="serial")
    assert result.errors.empty
    (tmp_path / "narrow.toml").write_text(BASE_CASE.replace("12.7e-3", "10e-3"))
    for k in range(3):
        write_history(scaled(h, k), tmp_path / f"c{k}.parquet")
        case = tmp_path / ("narrow.toml" if k == 1 else "base.toml")
        assert_identical(rows_of(result, f"c{k}"), reference(tmp_path / f"c{k}.parquet", case))
    assert result.table.groupby("contact")["tube_row"].first().tolist() == [1, 2, 3]


def test_a_blank_units_attribute_of_a_store_declares_nothing(tmp_path):
    """xarray and netCDF writers may leave ``units = ""`` on a variable: that declares no unit
    (the values are SI, as with no attribute), where every contact used to fail with "unknown
    force unit ''" (a user's trial). The reference: the same Dataset without the attributes."""
    h = oscillator()
    (tmp_path / "base.toml").write_text(BASE_CASE)
    plain = _dataset(h)
    blank = _dataset(h)
    for name in ("normal_force", "vt1", "time"):
        blank[name].attrs["units"] = "  " if name == "time" else ""
    expected = run_bundle(plain, tmp_path / "base.toml", scheduler="serial")
    got = run_bundle(blank, tmp_path / "base.toml", scheduler="serial")
    assert got.errors.empty and expected.errors.empty
    for k in range(3):
        assert_identical(rows_of(got, f"c{k}"), rows_of(expected, f"c{k}"))


def test_history_paths_are_resolved_as_path_resolve_does(tmp_path):
    """The manifest's history paths, resolved folder by folder (one lstat a file), equal
    ``(manifest folder / path).resolve()``: plain files, a file that is a link, a folder that is
    a link, ``..`` and ``.`` in the path, an absolute path."""
    import os

    real = tmp_path / "real"
    (real / "sub").mkdir(parents=True)
    for name in ("a.parquet", "b.parquet", "sub/c.parquet"):
        (real / name).write_bytes(b"")
    os.symlink(real / "a.parquet", real / "link.parquet")
    os.symlink(real / "sub", tmp_path / "linked")
    paths = ["real/a.parquet", "real/link.parquet", "linked/c.parquet", "real/sub/../b.parquet",
             "./real/b.parquet", "linked/../real/a.parquet", str(real / "b.parquet"),
             "real/sub/..", "missing/x.parquet"]
    frame = pd.DataFrame({"contact": [f"c{k}" for k in range(len(paths))], "history": paths})
    manifest = tmp_path / "manifest.csv"
    frame.to_csv(manifest, index=False)
    got = [row.history.path for row in read_manifest(manifest).rows]
    expected = [str(p if os.path.isabs(p) else (tmp_path / p).resolve()) for p in paths]
    assert got == expected
    assert got[1] == str(real / "a.parquet") and got[2] == str(real / "sub" / "c.parquet")


def test_a_history_name_the_system_refuses_fails_its_contact_only(tmp_path):
    """A history whose file name is longer than the file system takes (ENAMETOOLONG on lstat)
    resolves as ``Path.resolve`` resolves it (which ignores that error) and fails its own
    contact (InputError in .errors), not the manifest: the other contacts complete."""
    manifest, case = write_bundle(tmp_path, oscillator(), 2)
    frame = pd.read_csv(manifest)
    long = "z" * 300 + ".parquet"  # NAME_MAX is 255 on Linux, macOS and Windows file systems
    frame.loc[len(frame)] = {**frame.iloc[0].to_dict(), "contact": "long", "history": long}
    frame.to_csv(manifest, index=False)
    rows = read_manifest(manifest).rows
    assert rows[-1].history.path == str((tmp_path / long).resolve())
    result = run_bundle(manifest, case, scheduler="serial")
    assert result.errors[["contact", "error"]].values.tolist() == [["long", "InputError"]]
    assert sorted(set(result.table["contact"])) == ["R1C1-AVB", "R1C2-AVB"]


@pytest.mark.parametrize("kind", ["csv", "toml", "parquet", "empty-csv"])
def test_a_manifest_without_contacts_is_an_input_error(tmp_path, kind):
    path = tmp_path / f"m.{kind.split('-')[-1]}"
    if kind == "csv":
        path.write_text("contact,history\n")
    elif kind == "empty-csv":
        path.write_text("")
    elif kind == "toml":
        path.write_text("contacts = []\n")
    else:
        pd.DataFrame({"contact": pd.Series([], dtype=str),
                      "history": pd.Series([], dtype=str)}).to_parquet(path)
    with pytest.raises(InputError, match=r"has no contacts \(a header only\?\)"):
        read_manifest(path)


def test_the_command_says_a_header_only_manifest_has_no_contacts(tmp_path, capsys):
    from fretwear.cli import main

    path = tmp_path / "empty.csv"
    path.write_text("contact,history\n")
    _, case = write_bundle(tmp_path, oscillator(), 1)
    code = main(["bundle", str(path), "--case", str(case), "-q", "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "empty.csv has no contacts (a header only?)" in err and "internal" not in err


def test_semicolon_manifest_with_decimal_commas_reads_as_the_comma_one(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 3, extra={
        "wall_thickness_m": [1.09e-3, 1.2e-3, None],
        "mobile_radius_m": [None, 8.5e-3, None]})
    frame = pd.read_csv(manifest)
    # as a spreadsheet saves it in a French locale: ';' between cells, ',' as decimal mark
    text = frame.to_csv(index=False, sep=";", decimal=",")
    assert "0,00109" in text and "0,0085" in text
    (tmp_path / "semi.csv").write_text(text)
    (tmp_path / "tab.csv").write_text(frame.to_csv(index=False, sep="\t"))
    expected = read_manifest(manifest)
    for name in ("semi.csv", "tab.csv"):
        got = read_manifest(tmp_path / name)
        assert [(r.contact, r.history, r.identity, r.overrides) for r in got.rows] == [
            (r.contact, r.history, r.identity, r.overrides) for r in expected.rows]
    assert expected.rows[1].overrides == {("geometry", "wall_thickness_m"): 1.2e-3,
                                          ("geometry", "mobile_radius_m"): 8.5e-3}
    a = run_bundle(tmp_path / "semi.csv", case, scheduler="serial")
    b = run_bundle(manifest, case, scheduler="serial")
    pd.testing.assert_frame_equal(a.table, b.table)


def test_unknown_columns_all_at_once_and_toml_keys(tmp_path):
    frame = pd.DataFrame({"contact": ["a"], "history": ["a.csv"], "mobile_radus_m": [1e-3],
                          "tube_rwo": [1]})
    with pytest.raises(KeywordError) as caught:
        read_manifest(frame)
    message = str(caught.value)
    assert ("unknown columns 'mobile_radus_m' (did you mean 'mobile_radius_m'?), 'tube_rwo' "
            "(did you mean 'tube_row'?)") in message
    # every documented column of the manifest is listed, wall_thickness_m too
    assert ("contact, history, node, tube_row, tube_column, support, wall_thickness_m"
            in message)
    toml = tmp_path / "m.toml"
    toml.write_text('[[contacts]]\ncontact = "a"\nhistory = "a.csv"\nmobile_radus_m = 1e-3\n'
                    '[[contacts]]\ncontact = "b"\nhistory = "b.csv"\n'
                    'geometry = { obstacle_widht_m = 1e-2 }\n')
    with pytest.raises(KeywordError) as caught:
        read_manifest(toml)
    message = str(caught.value)
    assert ("unknown keys 'mobile_radus_m' (did you mean 'mobile_radius_m'?), "
            "'geometry.obstacle_widht_m' (did you mean 'geometry.obstacle_width_m'?)") in message
    assert "unknown column" not in message and "has the keys" in message
    # a ;-separated file that the detection cannot take (a line without ';') is named so
    bad = tmp_path / "bad.csv"
    bad.write_text("contact;history\na;a.csv\nb\n")
    with pytest.raises(KeywordError, match="looks ;-separated"):
        read_manifest(bad)


def test_a_windows_1252_manifest_is_named_so_with_the_fix(tmp_path):
    # French Excel's "CSV (séparateur: point-virgule)": ';', decimal commas, Windows-1252
    line = "R1;h.parquet;barre \u00e9paisse;0,00109\n"
    header = "contact;history;support;wall_thickness_m\n"
    path = tmp_path / "cp1252.csv"
    path.write_bytes((header + line).encode("cp1252"))
    with pytest.raises(InputError) as caught:
        read_manifest(path)
    message = str(caught.value)
    assert "is not UTF-8 text (byte 0xe9 on line 2" in message, message
    assert "save it as CSV UTF-8" in message and "no contacts" not in message
    assert "encoding=" not in message  # the manifest reader has no such option
    # saved as CSV UTF-8, the same content reads
    path.write_bytes((header + line).encode("utf-8"))
    row = read_manifest(path).rows[0]
    assert row.identity["support"] == "barre \u00e9paisse"
    assert row.overrides == {("geometry", "wall_thickness_m"): 1.09e-3}
    # an empty or blank file has no contacts; a file of comments only says so
    for text in ("", " \n\n\t\n"):
        path.write_text(text)
        with pytest.raises(InputError, match=r"has no contacts"):
            read_manifest(path)
    path.write_text("# nothing yet\n")
    with pytest.raises(InputError, match=r"no data lines \(only comments"):
        read_manifest(path)


def test_a_tsv_manifest_reads_as_the_csv_one(tmp_path):
    manifest, case = write_bundle(tmp_path, oscillator(), 2,
                                  extra={"mobile_radius_m": [None, 8.5e-3]})
    frame = pd.read_csv(manifest)
    (tmp_path / "m.tsv").write_text(frame.to_csv(index=False, sep="\t"))
    a = run_bundle(tmp_path / "m.tsv", case, scheduler="serial")
    b = run_bundle(manifest, case, scheduler="serial")
    pd.testing.assert_frame_equal(a.table, b.table)
    (tmp_path / "m.txt").write_text(frame.to_csv(index=False, sep="\t"))
    with pytest.raises(InputError, match=r"give a \.csv, \.tsv, \.parquet or \.toml"):
        read_manifest(tmp_path / "m.txt")


def test_a_decimal_comma_not_read_as_a_number_is_hinted(tmp_path):
    # a ;-separated column mixing decimal commas and points stays text: its comma cell fails
    _, case = write_bundle(tmp_path, oscillator(), 1)
    (tmp_path / "m.csv").write_text("contact;history;wall_thickness_m;mobile_radius_m\n"
                                    "a;histories/t0.parquet;0,00109;0,0085\n"
                                    "b;histories/t0.parquet;0,00109;9.525e-3\n")
    result = run_bundle(tmp_path / "m.csv", case, scheduler="serial")
    assert result.errors["contact"].tolist() == ["a"]
    message = result.errors["message"][0]
    assert ("column mobile_radius_m = '0,0085': not a number (a decimal comma? write 0.0085"
            in message), message
    # a word without a comma gets no such hint
    (tmp_path / "m.csv").write_text("contact,history,mobile_radius_m\n"
                                    "a,histories/t0.parquet,abc\n")
    message = run_bundle(tmp_path / "m.csv", case, scheduler="serial").errors["message"][0]
    assert message.endswith("column mobile_radius_m = 'abc': not a number"), message


def test_an_entry_name_may_hold_dots():
    assert column_key("history.columns.F.N", "manifest") == ("history", "columns", "F.N")


@pytest.mark.parametrize("where", ["zarr", "netcdf"])
def test_contact_lengths_of_a_store_with_a_2d_time(tmp_path, where, monkeypatch):
    """A store whose contacts have their own instants (a 2-D time padded with NaN): every
    contact's length (datasets.store_length, which decides its time chunks) equals the last
    finite instant + 1 of its own row, computed here row by row, for contacts of full length,
    shorter, one sample, none; read for all contacts at once in slabs of whole rows (here
    several slabs of 2 rows, the Zarr store chunked across contacts as xarray chunks it by
    default), once per store."""
    xr = pytest.importorskip("xarray")
    from fretwear.bundle import datasets

    lengths = [9, 6, 0, 1, 9, 3, 8]
    time = np.full((len(lengths), 9), np.nan)
    force = np.zeros_like(time)
    for k, n in enumerate(lengths):
        time[k, :n] = 1e-3 * np.arange(n)
        force[k, :n] = 1.0 + k
    ds = xr.Dataset({"time": (("contact", "sample"), time),
                     "normal_force": (("contact", "sample"), force)},
                    coords={"contact": [f"c{k}" for k in range(len(lengths))]})
    if where == "zarr":
        pytest.importorskip("zarr")
        source = tmp_path / "bundle.zarr"
        ds.to_zarr(source, mode="w", consolidated=False, zarr_format=2,
                   encoding={"time": {"chunks": (3, 4)}, "normal_force": {"chunks": (3, 4)}})
    else:
        source = tmp_path / "bundle.nc"
        ds.to_netcdf(source)
    monkeypatch.setattr(datasets, "_LENGTH_SLAB", 18)  # 2 rows of 9 samples a slab
    datasets._store_lengths.cache_clear()
    rows = read_manifest(source).rows
    expected = [int(np.flatnonzero(np.isfinite(r))[-1]) + 1 if np.isfinite(r).any() else 0
                for r in time]
    assert [datasets.store_length(row.history) for row in rows] == expected == lengths
    assert datasets._store_lengths.cache_info().misses == 1


def test_a_misspelt_entry_column_stops_the_run_before_any_work(tmp_path):
    """A column law.mobile.COEF_USUR (COEF_USURE misspelt), filled on one row and empty on the
    other: the run started, the first contact failed without a hint and the second silently
    kept the base coefficient. Now the run stops before any work, as for a bare misspelt name,
    every unknown entry named at once with the closest valid name, whatever the cells hold
    (the entries of law.mobile, law.obstacle, history.units and history.options are known
    sets)."""
    manifest, case = write_bundle(tmp_path, oscillator(), 2, extra={
        "law.mobile.COEF_USUR": [1e-14, None], "history.units.lenght": [None, None],
        "law.obstacle.coef_usure": [None, None], "history.options.delimeter": [None, None]})
    with pytest.raises(KeywordError) as caught:
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    message = str(caught.value)
    assert ("unknown columns 'law.mobile.COEF_USUR' (did you mean 'law.mobile.COEF_USURE'?), "
            "'history.units.lenght' (did you mean 'history.units.length'?), "
            "'law.obstacle.coef_usure' (did you mean 'law.obstacle.COEF_USURE'?), "
            "'history.options.delimeter' (did you mean 'history.options.delimiter'?)"
            ) in message
    assert "the entries of law.mobile are the coefficients of the row's law" in message
    assert "ARCHARD: coefficient (COEF_USURE)" in message
    assert not (tmp_path / "out").exists()
    # a TOML manifest's row tables, inline or dotted, are the same columns
    toml = tmp_path / "m.toml"
    toml.write_text('[[contacts]]\ncontact = "a"\nhistory = "histories/t0.parquet"\n'
                    "law.mobile = { COEF_USUR = 1e-14 }\n"
                    '[[contacts]]\ncontact = "b"\nhistory = "histories/t1.parquet"\n'
                    '"history.units" = { lenght = "mm" }\n')
    with pytest.raises(KeywordError, match=r"unknown keys 'law.mobile.COEF_USUR' \(did you mean "
                                           r"'law.mobile.COEF_USURE'\?\), 'history.units.lenght' "
                                           r"\(did you mean 'history.units.length'\?\)"):
        read_manifest(toml)
    # valid entries pass: every law's coefficients (by name or keyword), channel aliases and
    # quantities in any case as units, every reader's options; history.columns' entries are
    # the file's own columns (free)
    for column in ("law.mobile.COEF_USURE", "law.mobile.coefficient", "law.obstacle.COEF_B",
                   "law.mobile.reference_intensity", "history.units.FN",
                   "history.units.Length", "history.units.dy", "history.options.select",
                   "history.columns.anything"):
        assert column_key(column, "m") == tuple(column.split(".", 2))


def test_a_row_drops_the_base_case_sectors_to_switch_to_a_law_without_them(tmp_path):
    """An Archard base case with [sectors]: a row switching to EDF_MZ failed (EDF_MZ refuses
    sectors) and nothing removed them: a TOML row's sectors = {} was silently ignored, and a
    CSV manifest had no column for it. Now sectors = {} (TOML) or a sectors cell {} (CSV) drops
    them for that row: its rows equal the single-contact wear table of the same history with
    EDF_MZ and no sectors, bit for bit; the other row keeps the base case's sectors."""
    manifest, case = write_bundle(tmp_path, oscillator(), 2, extra={
        "law.name": [None, "EDF_MZ"], "sectors": [None, "{}"]})
    (tmp_path / "m.toml").write_text(
        '[[contacts]]\ncontact = "R1C1-AVB"\nhistory = "histories/t0.parquet"\n'
        '[[contacts]]\ncontact = "R1C2-AVB"\nhistory = "histories/t1.parquet"\n'
        'law.name = "EDF_MZ"\nsectors = {}\n')
    no_sectors = tmp_path / "edf_mz.toml"
    no_sectors.write_text(BASE_CASE.replace("[sectors]\ncount = 4\n", "").replace(
        "mobile = { COEF_USURE = 9.2e-15 }", 'name = "EDF_MZ"'))
    with pytest.warns(LawWarning, match="EDF_MZ"):  # its default S, at this power
        expected = reference(tmp_path / "histories/t1.parquet", no_sectors)
    for source in (manifest, tmp_path / "m.toml"):
        result = run_bundle(source, case, scheduler="serial")
        assert result.errors.empty, result.errors.to_dict("records")
        # the bundle's table holds the sector columns of the other contact: empty here
        rows = rows_of(result, "R1C2-AVB")
        assert_identical(rows[list(expected.columns)], expected)
        assert rows.drop(columns=list(expected.columns)).isna().all().all()
        assert_identical(rows_of(result, "R1C1-AVB"),
                         reference(tmp_path / "histories/t0.parquet", case))
        assert rows_of(result, "R1C1-AVB")["sector"].notna().all()
    # without dropping them, the row's error says how to
    frame = pd.read_csv(manifest).drop(columns="sectors")
    frame["history"] = [str(tmp_path / h) for h in frame["history"]]
    result = run_bundle(frame, case, scheduler="serial")
    assert result.errors["contact"].tolist() == ["R1C2-AVB"]
    message = result.errors["message"][0]
    assert "law 'EDF_MZ' with the base case's [sectors]" in message
    assert "a sectors cell {} in its row (a TOML manifest: sectors = {})" in message
    # a CSV cell holding a table replaces the base case's sectors whole (edges, not count)
    edges = tmp_path / "edges.toml"
    edges.write_text(BASE_CASE.replace("count = 4", "edges_deg = [-180, 0, 180]"))
    result = run_bundle(pd.DataFrame({"contact": ["e"],
                                      "history": [str(tmp_path / "histories/t0.parquet")],
                                      "sectors": ["{ edges_deg = [-180, 0, 180] }"]}),
                        case, scheduler="serial")
    assert result.errors.empty, result.errors.to_dict("records")
    assert_identical(rows_of(result, "e"), reference(tmp_path / "histories/t0.parquet", edges))
    assert rows_of(result, "e")["sector"].nunique() == 2
    # the whole section and one of its keys in the same row: refused (order-dependent)
    frame["sectors"], frame["sectors.count"] = [None, "{}"], [None, 8]
    result = run_bundle(frame, case, scheduler="serial")
    assert "sectors is given whole and by key" in result.errors["message"][0]
    # an empty table of a section that a row cannot drop changed nothing: refused
    (tmp_path / "g.toml").write_text('[[contacts]]\ncontact = "a"\nhistory = "h.csv"\n'
                                     "geometry = {}\n")
    with pytest.raises(KeywordError, match=r"contact 'a': geometry = \{\} would change nothing"):
        read_manifest(tmp_path / "g.toml")


def test_ids_differing_only_by_surrounding_whitespace_are_refused(tmp_path):
    """'A' and 'A ' were two contacts that look the same in the terminal and in summary.csv:
    now the run stops before any work, naming both; ids are never trimmed, so a single id with
    surrounding whitespace and no look-alike runs under its id as written."""
    write_history(oscillator(), tmp_path / "h.parquet")
    (tmp_path / "base.toml").write_text(BASE_CASE)
    (tmp_path / "m.csv").write_text('contact,history\nA,h.parquet\nB,h.parquet\n'
                                    'A ,h.parquet\n')
    with pytest.raises(InputError) as caught:
        run_bundle(tmp_path / "m.csv", tmp_path / "base.toml", scheduler="serial",
                   output=tmp_path / "out")
    assert ("contact ids 'A' (row 1) and 'A ' (row 3) differ only by surrounding whitespace"
            in str(caught.value))
    assert str(caught.value).endswith("make them distinct or trim them")
    assert not (tmp_path / "out").exists()
    with pytest.raises(InputError, match=r"'\\xa0B' \(row 1\) and 'B' \(row 2\)"):
        read_manifest(pd.DataFrame({"contact": ["\xa0B", "B"], "history": ["x", "y"]}))
    # one id with surrounding whitespace and no look-alike: kept as written
    history = str(tmp_path / "h.parquet")
    result = run_bundle(pd.DataFrame({"contact": [" A ", "B"], "history": [history] * 2}),
                        tmp_path / "base.toml", scheduler="serial")
    assert result.errors.empty, result.errors.to_dict("records")
    assert result.contacts["contact"].tolist() == [" A ", "B"]
