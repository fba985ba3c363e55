"""fretwear.table.wear_table_columns: the columns and metadata of wear_table_from_case without
the DataFrame (what a bundle's worker sends back).

Independent computation: the DataFrame of :func:`fretwear.table.wear_table_from_case` on the
same case and source, column by column (``frame[name].to_numpy()``): the same names in the same
order, the same dtypes, the same values bit for bit (NaN at the same places), the same attrs.
Cases: without and with sectors, with a wall thickness (its fraction and limit columns), a
restart whose initial rows come first (with and without sectors), a tube replacement, KWU-EPRI
from a history (its class statistics), every contact type.
The warnings the table build raises point at the line that called it, through either function
(the frames in between are counted by each warning's stacklevel).
"""

from __future__ import annotations

import dataclasses
import inspect
import warnings

import numpy as np
import pytest

from fretwear import ContactHistory
from fretwear.geometry import CONTACT_TYPES
from fretwear.table import WearCase, wear_table, wear_table_columns, wear_table_from_case

YEAR = 3.1536e7
#: each geometry's example dimensions, with the obstacle width that sector depths need where
#: the geometry takes one
DIMENSIONS = {name: {**({"obstacle_width": 12.7e-3} if "obstacle_width" in
                        {f.name for f in dataclasses.fields(cls)} else {}), **cls.example}
              for name, cls in CONTACT_TYPES.items()}


def _history(n: int = 4001) -> ContactHistory:
    # sliding at 0.1 m/s under 10 N with impacts, the angle turning once a second
    t = np.linspace(0.0, 2.0, n)
    force = 10.0 * np.clip(np.sin(2 * np.pi * 7 * t), 0.0, None)
    return ContactHistory(time=t, normal_force=force, vt1=np.full(n, 0.1),
                          vt2=0.05 * np.cos(2 * np.pi * 3 * t), dy=np.cos(2 * np.pi * t),
                          dz=np.sin(2 * np.pi * t))


def _same(case: WearCase, source, history=None) -> None:
    frame = wear_table_from_case(case, source, history=history)
    columns, attrs = wear_table_columns(case, source, history=history)
    assert list(columns) == [str(c) for c in frame.columns]
    for name, values in columns.items():
        expected = frame[name].to_numpy()
        assert type(values) is np.ndarray and values.dtype == expected.dtype, name
        assert np.array_equal(values, expected, equal_nan=values.dtype.kind == "f"), name
    assert attrs.keys() == frame.attrs.keys()
    assert repr(attrs) == repr(frame.attrs)  # NaN-safe equality of nested metadata


def _case(contact_type="TUBE_BAV", **keywords) -> WearCase:
    args = {"contact_type": contact_type, "dimensions": DIMENSIONS[contact_type],
            "coefficients": {"COEF_USURE": 1e-17}, "instants": [1.0, 2.0, 5.0],
            "time_scale": YEAR}
    args.update(keywords)
    return WearCase.from_keywords(**args)


@pytest.mark.parametrize("contact_type", CONTACT_TYPES)
def test_every_contact_type_without_and_with_sectors(contact_type):
    _same(_case(contact_type), 0.01)
    if "obstacle_width" in DIMENSIONS[contact_type]:  # sector depths need it
        _same(_case(contact_type, sectors=6), _history())


def test_wall_thickness_and_its_limit():
    _same(_case(wall_thickness=1.09e-3, coefficients={"COEF_USURE": 1e-15}), 0.05)
    _same(_case(wall_thickness=1.09e-3, sectors=4, coefficients={"COEF_USURE": 1e-16}),
          _history())


@pytest.mark.parametrize("sectors", [None, 4])
def test_restart_rows_come_first(sectors):
    first = wear_table(_history(), contact_type="TUBE_BAV", dimensions=DIMENSIONS["TUBE_BAV"],
                       coefficients={"COEF_USURE": 1e-17}, instants=[1.0, 2.0],
                       time_scale=YEAR, sectors=sectors)
    case = _case(instants=[1.0, 3.0], sectors=sectors, initial_state=first)
    assert len(case.restart.table.rows)  # the initial table's rows are in the table
    _same(case, _history())


def test_tube_replacement_and_kwu_from_a_history():
    _same(_case(instants=[1.0, 4.0], tube_replacement=2.0), 0.02)
    history = _history()
    _same(_case(law="KWU_EPRI", coefficients={"COEF_USURE": 1e-17, "reference_intensity": 2.0}),
          history)


#: (case keywords, source, warning category, message start) of each warning raised while the
#: table is built: the law's (through the cumulated volumes), the sectors' without obstacle
#: radius, the wall's
WARNED = {
    "law": (dict(law="EDF_MZ", coefficients={"COEF_USURE": 1e-20, "COEF_S": 1e-10}), 0.01,
            "LawWarning", "mobile: EDF_MZ: the asymptotic rate"),
    "sectors": (dict(sectors=4, obstacle_coefficients={"COEF_USURE": 1e-17}), "history",
                "RangeWarning", "sectors [1, 2, 3, 4]: the obstacle wears"),
    "wall": (dict(wall_thickness=1e-4, coefficients={"COEF_USURE": 1e-13}), 0.05,
             "PerforationWarning", "the tube is worn through its wall"),
}


@pytest.mark.parametrize("name", WARNED)
@pytest.mark.parametrize("function", [wear_table_from_case, wear_table_columns])
def test_table_build_warnings_point_at_the_caller(name, function):
    keywords, source, category, start = WARNED[name]
    case = _case(**keywords)
    source = _history() if source == "history" else source
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        function(case, source)
    found = [w for w in caught
             if w.category.__name__ == category and str(w.message).startswith(start)]
    assert found, [str(w.message) for w in caught]
    assert {(w.filename, w.lineno) for w in found} == {(__file__, line)}


@pytest.mark.parametrize("keys", [("law", "time_scale"), ("power", "case", "dimensions"),
                                  ("limit_instant", "no_such_key", "sector_edges")])
def test_attrs_asked_for_are_the_tables_own(keys):
    """``attrs=keys``: the table's own values of those keys (the same repr: nested metadata,
    NaN-safe), in the order asked, a key the table lacks left out; the columns unchanged (bit
    for bit: one process)."""
    case = _case(wall_thickness=1.09e-3, sectors=4, coefficients={"COEF_USURE": 1e-16})
    source = _history()
    full_columns, full = wear_table_columns(case, source)
    columns, attrs = wear_table_columns(case, source, attrs=keys)
    assert list(attrs) == [k for k in keys if k in full]
    assert repr(attrs) == repr({k: full[k] for k in attrs})
    assert all(np.array_equal(columns[c], full_columns[c], equal_nan=True) for c in columns)
