"""The contact check of the grid reshape by codes (result_dataset._in_blocks) against its
definition, the column compared value by value with ``numpy.repeat(ids, per)`` (the code
before, an independent computation). Exact: booleans."""

import numpy as np
import pandas as pd
import pytest

from fretwear.bundle import result_dataset


def _by_values(column: pd.Series, ids: np.ndarray, per: int) -> bool:
    values = column.to_numpy(dtype=object)
    want = np.repeat(ids, per)
    return len(values) == len(want) and np.array_equal(values.astype(ids.dtype), want)


CASES = {
    "laid out": ["a", "a", "b", "b", "c", "c"],
    "two rows swapped": ["a", "b", "a", "b", "c", "c"],
    "a contact twice": ["a", "a", "b", "b", "a", "a"],
    "another contact": ["a", "a", "b", "b", "d", "d"],
    "ids in another order": ["b", "b", "a", "a", "c", "c"],
    "one row short": ["a", "a", "b", "b", "c"],
}


@pytest.mark.parametrize("dtype", [object, "str"])
@pytest.mark.parametrize("name", list(CASES))
def test_in_blocks_is_the_value_by_value_check(name, dtype):
    column = pd.Series(CASES[name], dtype=dtype)
    ids = np.array(["a", "b", "c"])
    assert result_dataset._in_blocks(column, ids, 2) == _by_values(column, ids, 2)
    assert result_dataset._in_blocks(column, ids, 2) == (name == "laid out")


def test_in_blocks_compares_in_the_ids_text_type():
    """Ids of a narrower text type than the column's values compare as the values cast to it,
    as the value-by-value check does."""
    column = pd.Series(["ab", "ab", "cd", "cd"], dtype="str")
    ids = np.array(["a", "c"])  # <U1
    assert result_dataset._in_blocks(column, ids, 2) == _by_values(column, ids, 2)
