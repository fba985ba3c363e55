"""WearCase.derived: one per-case memo for the values derived from a case (issue 28 point 5).

What is checked: ``make`` runs once per key and case (a counter), two equal cases do not
share their values, a pickled case leaves them out and makes them again, and the tables of
a case keep the depth model's parts there (the same table as from a fresh, equal case:
exact equality, one process).
"""

from __future__ import annotations

import pickle

import numpy as np
import pandas as pd

from fretwear.table import WearCase, wear_table_from_case


def _case(**extra) -> WearCase:
    return WearCase.from_keywords(contact_type="TUBE_BAV", instants=[1.0, 2.0, 3.0],
                                  dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
                                  coefficients={"COEF_USURE": 1e-14}, time_scale=3.15e7,
                                  wall_thickness=1e-3, **extra)


def test_made_once_per_key_and_case():
    calls = []

    def make():
        calls.append(1)
        return {"value": len(calls)}

    case, other = _case(), _case()
    assert case == other  # equal cases, each its own values
    first = case.derived("k", make)
    assert case.derived("k", make) is first and len(calls) == 1
    assert other.derived("k", make) == {"value": 2} and len(calls) == 2
    assert case.derived("other key", list) == []


def test_pickle_leaves_the_values_out():
    case = _case()
    case.derived("k", lambda: np.arange(3))
    back = pickle.loads(pickle.dumps(case))
    assert back == case
    assert "_derived" not in vars(back)
    assert back.derived("k", lambda: "again") == "again"


def test_tables_keep_the_model_parts_on_the_case():
    case = _case()
    first = wear_table_from_case(case, 0.01)
    parts = case.derived("depth model parts", dict)
    assert len(parts) == 1  # one set of coefficients
    again = wear_table_from_case(case, 0.01)
    assert case.derived("depth model parts", dict) is parts and len(parts) == 1
    fresh = wear_table_from_case(_case(), 0.01)  # an equal case, its parts made anew
    pd.testing.assert_frame_equal(first, again, check_exact=True)
    pd.testing.assert_frame_equal(first, fresh, check_exact=True)
