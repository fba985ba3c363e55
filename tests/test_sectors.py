"""Sector edges and sector membership (theory §3)."""

import numpy as np
import pytest

from fretwear.errors import InputError
from fretwear.history import contact_angle
from fretwear.sectors import sector_edges, sector_index


def test_equal_sectors():
    np.testing.assert_array_equal(sector_edges(10), np.arange(-180.0, 181.0, 36.0))


@pytest.mark.parametrize(
    ("bad", "words"),
    [
        ([-170, 0, 180], ["-180..180", "-170"]),
        ([-180, 0, 170], ["-180..180", "170"]),
        ([-180, 10, 10, 180], ["strictly increasing", "edge 2"]),
        ([-180], ["at least two"]),
        (0, ["from 1 to 720"]),
        (36000, ["from 1 to 720", "got 36000"]),  # a typo for 36: refused, not a 1 GB table
        (np.linspace(-180, 180, 1000), ["999 sectors", "at most 720"]),
        ("abc", ["edge angles"]),
        ([-180, np.nan, 180], ["finite"]),
    ],
)
def test_bad_edges_named(bad, words):
    with pytest.raises(InputError) as err:
        sector_edges(bad)
    for w in words:
        assert w in str(err.value)


def test_membership_left_closed_first_right_closed_others():
    edges = sector_edges([-180, -90, 0, 90, 180])
    # An angle on an inner edge belongs to the sector below it (edges[j] < theta <= edges[j+1]).
    assert sector_index([-180.0, -90.0, -89.999, 0.0, 1e-9, 90.0, 180.0], edges).tolist() == [
        0, 0, 1, 1, 2, 2, 3]


def test_membership_matches_brute_force_on_random_points():
    # Independent check: compare with a direct loop over the definition.
    rng = np.random.default_rng(0)
    dy, dz = rng.normal(size=(2, 2000))
    theta = contact_angle(dy, dz)
    edges = sector_edges([-180, -120.5, -3, 45, 179, 180])
    idx = sector_index(theta, edges)
    for t, j in zip(theta, idx, strict=True):
        inside = [k for k in range(len(edges) - 1)
                  if (edges[k] < t <= edges[k + 1]) or (k == 0 and t == edges[0])]
        assert inside == [j]
