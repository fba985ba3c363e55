"""PowerResult.to_dict is made once per result and copied at each call (issue 28 point 5).

Independent computation: the dict of a fresh result of the same values
(``dataclasses.replace``: a new result, its dict made anew), and the JSON text of both.
Exact equality is right here: the same floats in one process, written by ``tolist``.
"""

from __future__ import annotations

import dataclasses
import json
import pickle

import numpy as np

from fretwear.history import ContactHistory
from fretwear.power import wear_power


def _result():
    t = np.linspace(0.0, 1.0, 2001)
    phase = 2 * np.pi * 20 * t
    h = ContactHistory(time=t, normal_force=np.maximum(0.0, 30 * np.sin(phase)),
                       vt1=0.02 * np.cos(phase), vt2=0.01 * np.sin(phase),
                       dy=1e-4 * np.cos(phase / 3), dz=1e-4 * np.sin(phase / 3))
    return wear_power(h, blocks=4, sectors=6)


def test_dict_made_once_equals_a_fresh_one_and_is_the_callers():
    result = _result()
    first = result.to_dict()
    fresh = dataclasses.replace(result).to_dict()  # another result: its own dict
    assert first == fresh
    assert json.dumps(first) == json.dumps(fresh)
    # the caller changes its copy: the next call is unchanged
    first["blocks"][0] = -1.0
    first["statistics"]["contact_fraction"] = -1.0
    first["block_sectors"][0][0] = -1.0
    again = result.to_dict()
    assert again == fresh
    assert again["blocks"] is not result.to_dict()["blocks"]


def test_pickle_leaves_the_dict_out_and_makes_it_again():
    result = _result()
    made = result.to_dict()
    assert "_as_dict" in vars(result)
    back = pickle.loads(pickle.dumps(result))
    assert "_as_dict" not in vars(back)
    assert back.to_dict() == made


_ARRAYS = ("blocks", "block_edges", "sectors", "sector_edges", "block_sectors")
_STAT_ARRAYS = ("block_contact_fraction", "block_force_mean", "block_sliding_distance")


def test_arrays_are_read_only_so_the_cached_dict_cannot_go_stale():
    """Writing into a result's array raises (it would otherwise leave to_dict's cached dict
    stale); the dict then still equals a fresh result's (independent computation above)."""
    result = _result()
    made = result.to_dict()
    for name in _ARRAYS:
        with np.testing.assert_raises(ValueError):
            getattr(result, name)[0] = -1.0
    for name in _STAT_ARRAYS:
        with np.testing.assert_raises(ValueError):
            getattr(result.statistics, name)[0] = -1.0
    assert made == dataclasses.replace(result).to_dict()
    back = pickle.loads(pickle.dumps(result))  # unpickled: still read-only
    assert not back.blocks.flags.writeable and not back.statistics.block_force_mean.flags.writeable


def test_the_callers_arrays_stay_writable():
    """A result made from the caller's arrays freezes views of them, not the arrays."""
    result = _result()
    blocks = np.array(result.blocks)
    made = dataclasses.replace(result, blocks=blocks)
    assert blocks.flags.writeable and not made.blocks.flags.writeable
    blocks[0] = -1.0  # the caller's own array: theirs to change
    assert blocks[0] == -1.0
