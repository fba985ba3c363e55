"""Angular sectors of the clearance figure (theory §3).

Sector edges are angles [deg], strictly increasing, starting at -180 and ending at +180. A sample
of contact angle θ (in (-180, 180]) belongs to sector j when ``edges[j] < θ <= edges[j+1]``,
except that θ = -180 cannot occur (it is folded to +180) and the first sector is closed on the
left: ``edges[0] <= θ``. An interval between two samples belongs to the sector of its left sample.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from fretwear.errors import InputError

_TOL = 1e-9


#: Most sectors accepted (0.5 deg each, the DISCRET grid's step): a sanity bound against a typo
#: (36000 for 36); the table's cost grows with the count (TUBE_BAV, 360 sectors: 7 s).
MAX_SECTORS = 720


def sector_edges(sectors: int | Sequence[float] | np.ndarray) -> np.ndarray:
    """Validated sector edges [deg].

    Parameters
    ----------
    sectors : int or sequence of float
        A count ``N >= 1`` of equal sectors covering -180..180°, or the edges themselves [deg]
        (N + 1 values, strictly increasing, first -180, last 180).

    Returns
    -------
    numpy.ndarray
        The N + 1 edges [deg], first exactly -180.0 and last exactly 180.0.

    Raises
    ------
    InputError
        When the edges do not cover -180..180° or are not strictly increasing, naming the edge.

    Examples
    --------
    >>> sector_edges(4).tolist()
    [-180.0, -90.0, 0.0, 90.0, 180.0]
    >>> sector_edges([-180, 0, 180]).tolist()
    [-180.0, 0.0, 180.0]
    """
    if isinstance(sectors, (int, np.integer)) and not isinstance(sectors, bool):
        if not 1 <= sectors <= MAX_SECTORS:
            raise InputError(f"the number of sectors must be from 1 to {MAX_SECTORS} (sectors "
                             f"of {360 / MAX_SECTORS:g} deg), got {sectors}")
        return np.linspace(-180.0, 180.0, int(sectors) + 1)
    try:
        edges = np.array(sectors, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(
            f"sectors must be a count or a list of edge angles in degrees, got {sectors!r}"
        ) from None
    if edges.size > MAX_SECTORS + 1:
        raise InputError(f"{edges.size - 1} sectors between the edges: at most {MAX_SECTORS} "
                         "sectors are accepted")
    if edges.size < 2:
        raise InputError(
            f"sector edges need at least two values (-180 and 180) [deg], got {edges.tolist()}")
    if not np.isfinite(edges).all():
        raise InputError(f"sector edges must be finite angles [deg], got {edges.tolist()}")
    if abs(edges[0] + 180.0) > _TOL or abs(edges[-1] - 180.0) > _TOL:
        raise InputError(
            f"sector edges must cover -180..180 deg: they run from {edges[0]:g} to {edges[-1]:g}; "
            "make the first edge -180 and the last +180")
    steps = np.diff(edges)
    if (steps <= 0).any():
        i = int(np.flatnonzero(steps <= 0)[0])
        raise InputError(
            f"sector edges must be strictly increasing: edge {i + 1} ({edges[i + 1]:g} deg) does "
            f"not exceed edge {i} ({edges[i]:g} deg)")
    edges[0], edges[-1] = -180.0, 180.0
    return edges


def sector_index(angle, edges: np.ndarray) -> np.ndarray:
    """Index (0-based) of the sector holding each contact angle [deg] in (-180, 180].

    Parameters
    ----------
    angle : array_like
        Contact angles θ [deg] (see :func:`fretwear.history.contact_angle`).
    edges : numpy.ndarray
        Sector edges [deg] from :func:`sector_edges`.

    Returns
    -------
    numpy.ndarray
        j such that ``edges[j] < θ <= edges[j+1]`` (θ = -180 goes to sector 0) [-].

    Examples
    --------
    >>> sector_index([-180.0, -90.0, -89.0, 0.0, 180.0], sector_edges(4)).tolist()
    [0, 0, 1, 1, 3]
    """
    a = np.asarray(angle, dtype=float)
    idx = np.searchsorted(edges, a, side="left") - 1
    return np.clip(idx, 0, len(edges) - 2)
