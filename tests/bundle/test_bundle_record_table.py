"""A worker's record of a contact is the contact's wear table (issue 28, point 5).

The worker builds its record from the depth model's arrays (``wear_table_columns``, no
DataFrame), the depth model's case-wide parts and the record's case-wide metadata made once per
case and shared by the case's contacts. Independent computation: the wear table the user gets,
``wear_table_from_case(case, source)``, packed by ``pack`` (its columns one by one): the record
holds the same column names in the same order, the same dtypes and the same values bit for bit
(one process, one machine), and its metadata are the table's ``attrs`` made JSON-ready by a
plain converter written here. Two contacts of one case in a row (the second reuses what the
first made), over every contact type, with and without sectors, a restart, a tube replacement,
a given power, a history file (the power a PowerResult) and KWU-EPRI whose intensity comes from
each contact's own history (the two contacts' coefficients differ).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fretwear import ContactHistory
from fretwear.bundle.cases import ContactTask
from fretwear.bundle.manifest import HistoryRef
from fretwear.bundle.tasks import pack, run_contact
from fretwear.geometry import CONTACT_TYPES
from fretwear.table import WearCase, wear_table, wear_table_from_case

YEAR = 3.1536e7
DIMENSIONS = {name: {**({"obstacle_width": 12.7e-3} if "obstacle_width" in
                        {f.name for f in dataclasses.fields(cls)} else {}), **cls.example}
              for name, cls in CONTACT_TYPES.items()}
#: the table attributes a record keeps, and the power's values
KEPT = ("contact_type", "dimensions", "law", "coefficients_mobile", "coefficients_obstacle",
        "materials", "coefficient_sources", "sector_edges", "sector_coefficients",
        "time_scale", "origin", "tube_replacement", "wall_thickness", "depth_limit")
POWER = ("total", "blocks", "spread", "t_start", "t_end", "duration", "sectors")


def _history(force: float = 10.0, n: int = 4001) -> ContactHistory:
    # sliding at 0.1 m/s with impacts, the contact angle turning 7 times a second
    t = np.linspace(0.0, 2.0, n)
    return ContactHistory(time=t, normal_force=force * np.clip(np.sin(2 * np.pi * 7 * t), 0, None),
                          vt1=np.full(n, 0.1), vt2=0.05 * np.cos(2 * np.pi * 3 * t),
                          dy=1e-4 * np.cos(2 * np.pi * 7 * t), dz=1e-4 * np.sin(2 * np.pi * 7 * t))


def _json(value):
    """``value`` as JSON holds it: dicts and lists, NaN/inf None, numpy values Python's."""
    if isinstance(value, dict):
        return {str(k): _json(v) for k, v in value.items()}
    if isinstance(value, list | tuple | np.ndarray):
        return [_json(v) for v in list(value)]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _expected_attrs(table, task: ContactTask) -> dict:
    attrs = {k: _json(table.attrs.get(k)) for k in KEPT}
    power = table.attrs.get("power") or {}
    attrs["power"] = {k: _json(power.get(k)) for k in POWER}
    if not power and task.power is not None:
        attrs["power"]["total"] = float(task.power)
    attrs["time_unit"] = task.time_unit
    return attrs


def _task(case: WearCase, source, name: str, tmp_path=None) -> ContactTask:
    if isinstance(source, float):
        return ContactTask(name, HistoryRef("none"), case.to_dict(), power=source,
                           time_unit="year")
    arrays = {c: getattr(source, c) for c in ("time", "normal_force", "vt1", "vt2", "dy", "dz")}
    if tmp_path is None:
        return ContactTask(name, HistoryRef("memory", arrays=arrays), case.to_dict(),
                           time_unit="year")
    import pandas as pd
    path = tmp_path / f"{name}.parquet"
    pd.DataFrame(arrays).to_parquet(path)
    return ContactTask(name, HistoryRef("file", path=str(path)), case.to_dict(),
                       time_unit="year")


def _check(case: WearCase, sources, tmp_path=None) -> None:
    """Each source's record (one case, contacts in a row) against its wear table."""
    for i, source in enumerate(sources):
        task = _task(case, source, f"c{i}", tmp_path)
        record = run_contact(task)
        assert record["status"] == "done", record["error"]
        given = source if tmp_path is None or isinstance(source, float) else task.history.path
        table = wear_table_from_case(task.wear_case(), given)
        expected = pack(table)
        assert record["table"]["columns"] == expected["columns"]
        for name, got, want in zip(expected["columns"], record["table"]["arrays"],
                                   expected["arrays"], strict=True):
            assert type(got) is np.ndarray and got.dtype == want.dtype, name
            # bit for bit: the same computation in one process
            assert np.array_equal(got, want, equal_nan=got.dtype.kind == "f"), name
        assert record["attrs"] == _expected_attrs(table, task)


def _case(contact_type="TUBE_BAV", **keywords) -> WearCase:
    args = {"contact_type": contact_type, "dimensions": DIMENSIONS[contact_type],
            "coefficients": {"COEF_USURE": 1e-17}, "instants": [1.0, 2.0, 5.0],
            "time_scale": YEAR, "time_unit": "year"}
    args.update(keywords)
    return WearCase.from_keywords(**args)


@pytest.mark.parametrize("contact_type", CONTACT_TYPES)
def test_every_contact_type_with_and_without_sectors(contact_type):
    _check(_case(contact_type), [_history(), _history(20.0)])
    _check(_case(contact_type, wall_thickness=1.09e-3), [0.01, 0.03])  # a given power
    if "obstacle_width" in DIMENSIONS[contact_type]:  # sector depths need it
        _check(_case(contact_type, sectors=6), [_history(), _history(20.0)])


@pytest.mark.parametrize("sectors", [None, 4])
def test_a_restart_and_a_replacement_from_a_file(sectors, tmp_path):
    first = wear_table(_history(), contact_type="TUBE_BAV", dimensions=DIMENSIONS["TUBE_BAV"],
                       coefficients={"COEF_USURE": 1e-17}, instants=[1.0, 2.0],
                       time_scale=YEAR, sectors=sectors)
    case = _case(instants=[1.0, 3.0, 6.0], sectors=sectors, initial_state=first,
                 tube_replacement=4.0, wall_thickness=1.09e-3,
                 obstacle_coefficients={"COEF_USURE": 1e-18})
    assert len(case.restart.table.rows)
    _check(case, [_history(), _history(20.0)], tmp_path)


def test_kwu_intensity_of_each_contacts_history(tmp_path):
    case = _case(law="KWU_EPRI", coefficients={"COEF_USURE": 1e-17, "reference_intensity": 2.0})
    _check(case, [_history(), _history(40.0)])
    _check(case, [_history(), _history(40.0)], tmp_path)
    one, two = (run_contact(_task(case, h, f"k{i}"))["attrs"]["coefficients_mobile"]
                for i, h in enumerate((_history(), _history(40.0))))
    assert one["intensity"] != two["intensity"]  # each contact's own
