"""``--units`` on the commands that read histories through a case or a manifest: ``fretwear
bundle`` and ``fretwear calibrate --case``. Oracle: the same histories written in SI give the
same tables; written in mm and mm/s and read with ``--units length=mm,velocity=mm/s`` they are
converted back (to rounding: x·1000·0.001), and read without it they are not (the UnitsWarning
of docs/formats.md "Plausibility checks" and a power 10³ times too large)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.cli import main
from fretwear.io import read_history, write_history

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BASE = """\
[law]
mobile = { COEF_USURE = 9.2e-15 }
[geometry]
contact_type = "TUBE_BAV"
mobile_radius_m = 9.525e-3
obstacle_width_m = 12.7e-3
[sectors]
count = 4
[time]
instants = [1, 2]
unit = "year"
"""


def _in_mm(history):
    return history.replace(vt1=history.vt1 * 1e3, vt2=history.vt2 * 1e3,
                           dy=history.dy * 1e3, dz=history.dz * 1e3)


def _bundle(directory: Path, mm: bool) -> Path:
    h = read_history(EXAMPLES / "data" / "oscillator_gap.csv")
    directory.mkdir()
    rows = []
    for k in range(2):
        hk = h.replace(normal_force=h.normal_force * (1 + k))
        write_history(_in_mm(hk) if mm else hk, directory / f"c{k}.parquet")
        rows.append({"contact": f"c{k}", "history": f"c{k}.parquet"})
    pd.DataFrame(rows).to_csv(directory / "manifest.csv", index=False)
    (directory / "base.toml").write_text(BASE)
    return directory


def _table(out: Path) -> pd.DataFrame:
    return pd.read_parquet(out / "table.parquet")


def test_bundle_units(tmp_path):
    si = _bundle(tmp_path / "si", mm=False)
    mm = _bundle(tmp_path / "mm", mm=True)
    common = ["--scheduler", "serial", "-q"]
    assert main(["bundle", str(si / "manifest.csv"), "--case", str(si / "base.toml"),
                 "-o", str(tmp_path / "o_si"), *common]) == 0
    assert main(["bundle", str(mm / "manifest.csv"), "--case", str(mm / "base.toml"),
                 "--units", "length=mm,velocity=mm/s", "-o", str(tmp_path / "o_mm"),
                 *common]) == 0
    expected, got = _table(tmp_path / "o_si"), _table(tmp_path / "o_mm")
    for column in ("power", "sector_power", "volume_mobile", "depth_mobile_sector"):
        np.testing.assert_allclose(got[column], expected[column], rtol=1e-12, err_msg=column)
    # without --units the mm files are read as SI: flagged, the power is 10³ too large and the
    # depths leave the relation's range (rows kept, exit code 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        code = main(["bundle", str(mm / "manifest.csv"), "--case", str(mm / "base.toml"),
                     "-o", str(tmp_path / "o_raw"), *common])
    assert code == 1
    assert set(pd.read_csv(tmp_path / "o_raw" / "errors.csv")["error"]) == {"RangeWarning"}
    raw = _table(tmp_path / "o_raw")
    np.testing.assert_allclose(raw["power"], 1e3 * expected["power"], rtol=1e-9)
    flagged = pd.read_csv(tmp_path / "o_raw" / "warnings.csv")
    assert (flagged["category"] == "UnitsWarning").any()


def test_calibrate_units(tmp_path, capsys):
    h = read_history(EXAMPLES / "data" / "oscillator_gap.csv")
    write_history(h, tmp_path / "si.parquet")
    write_history(_in_mm(h), tmp_path / "mm.parquet")
    for name in ("si", "mm"):
        (tmp_path / f"{name}.toml").write_text(
            BASE + f'[history]\nfile = "{name}.parquet"\n')
    insp = tmp_path / "insp.csv"
    insp.write_text("instant,depth_mm\n1,0.05\n2,0.07\n")
    posteriors = []
    for name, extra in (("si", []), ("mm", ["--units", "length=mm,velocity=mm/s"])):
        assert main(["calibrate", str(insp), "--case", str(tmp_path / f"{name}.toml"),
                     "--json", *extra]) == 0
        posteriors.append(json.loads(capsys.readouterr().out)["posterior"]["median"])
    assert posteriors[1] == pytest.approx(posteriors[0], rel=1e-9)
    bundle_dir = tmp_path / "results"
    bundle_dir.mkdir()
    assert main(["calibrate", str(insp), "--bundle", str(bundle_dir), "--units",
                 "length=mm"]) == 2
    assert "--units gives the units of the case's history file" in capsys.readouterr().err
