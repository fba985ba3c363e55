"""The up-front check that a tabular manifest gives its contacts something to wear by: a
history file, or a power (docs/bundle.md). Without both on every row the run would fail each
contact with the same message; it stops before any work with one error instead."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from fretwear.bundle.manifest import Manifest
from fretwear.errors import InputError

#: The case key of a given power [W] (a manifest column ``power.value_W``, or ``[power]``).
POWER_KEY = ("power", "value_W")


def check_histories(manifest: Manifest, base: Mapping[str, Any]) -> None:
    """Stop with one error when no contact of a manifest can get a wear power.

    Parameters
    ----------
    manifest : Manifest
        The contacts (:func:`fretwear.bundle.read_manifest`).
    base : mapping
        The base case (its ``[power] value_W`` [W], if given, serves every row without a
        history).

    Raises
    ------
    InputError
        No row names a history file, no row gives ``power.value_W`` and the base case gives no
        power: the message names the ``history`` column and the two fixes. Rows of a store or
        a Code_Aster table always have a history; a manifest where only some rows lack both
        leaves those rows to fail their own contacts.

    Examples
    --------
    >>> import pandas as pd
    >>> from fretwear.bundle import read_manifest
    >>> m = read_manifest(pd.DataFrame({"contact": ["a", "b"], "tube_row": [1, 2]}))
    >>> check_histories(m, {"power": {"value_W": 1e-4}})   # the base case gives a power
    >>> check_histories(m, {})
    Traceback (most recent call last):
    ...
    fretwear.errors.InputError: <DataFrame>: none of its 2 contacts has a history and no power
    is given: add a 'history' column (each contact's history file, relative to the manifest), or
    give a power [W] (a 'power.value_W' column, or [power] value_W in the base case); nothing was
    computed
    """
    rows = manifest.rows
    if not rows or manifest.kind != "table":
        return
    if POWER_KEY[1] in (base.get(POWER_KEY[0]) or {}):
        return
    if any(r.history.kind != "none" or POWER_KEY in r.overrides for r in rows):
        return
    raise InputError(f"{manifest.source}: none of its {len(rows)} contacts has a history and no "
                     "power is given: add a 'history' column (each contact's history file, "
                     "relative to the manifest), or give a power [W] (a 'power.value_W' column, "
                     "or [power] value_W in the base case); nothing was computed")
