"""Validation of user keys (case-file tables, manifest columns, keyword arguments): unknown keys
and wrong value types become a :class:`~fretwear.errors.KeywordError` that names the key, the
closest valid one and the expected type; a confidence level or quantile levels that are not
probabilities an :class:`~fretwear.errors.InputError` naming the argument and the value
(:func:`check_level`, :func:`check_probabilities`). Any layer may import this module.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from fretwear.errors import InputError, KeywordError

__all__ = ["check_keys", "check_level", "check_probabilities", "keyword_hint"]


def _number(value) -> float:
    """``value`` as a float, NaN where it is not a real number (a bool, a string, None)."""
    if isinstance(value, bool | np.bool_ | str | bytes) or value is None:
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def check_level(level, name: str = "level") -> float:
    """A confidence level: a probability strictly between 0 and 1 [-], as a float.

    Raises
    ------
    InputError
        Anything else, naming ``name`` and the value (0.95 for 95 %, not 95).

    Examples
    --------
    >>> check_level(0.9)
    0.9
    """
    p = _number(level)
    if not 0.0 < p < 1.0:
        raise InputError(f"{name} must be a probability in (0, 1) (e.g. 0.95 for 95 %), got "
                         f"{level!r}")
    return p


def check_probabilities(values, name: str = "q", *, closed: bool = True) -> np.ndarray:
    """Quantile levels: one or more probabilities [-], in [0, 1] (``closed``) or (0, 1), as a
    1-d float array.

    Raises
    ------
    InputError
        No value, or a value that is not such a probability, naming ``name`` and the values
        (0.95 for the 95 % quantile, not 95).

    Examples
    --------
    >>> check_probabilities([0.05, 0.5]).tolist()
    [0.05, 0.5]
    """
    raw = np.atleast_1d(np.asarray(values, dtype=object)).ravel()
    p = np.array([_number(v) for v in raw], dtype=float)
    inside = (p >= 0) & (p <= 1) if closed else (p > 0) & (p < 1)
    if p.size == 0 or not inside.all():
        bad = raw[~inside].tolist() if p.size else []
        span = "[0, 1]" if closed else "(0, 1)"
        raise InputError(f"{name} must be probabilities in {span} (e.g. 0.95 for the 95 % "
                         f"quantile), got {bad if bad else 'none'}")
    return p


def keyword_hint(key: str, choices) -> str:
    """`` (did you mean 'x'?)`` naming the closest of ``choices`` to ``key``, or ``""``."""
    close = difflib.get_close_matches(key, list(choices), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_keys(items: Mapping[str, Any], spec: Mapping[str, tuple[Any, str]], source: str, *,
               key_prefix: str = "") -> None:
    """Check the keys and value types of one table of a TOML file against its key list.

    Parameters
    ----------
    items : mapping
        The table (key -> value).
    spec : mapping
        key -> (expected type or tuple of types, description with unit), as :data:`KEYS`.
        ``True``/``False`` are accepted only where the type is ``bool``.
    source : str
        What the messages start with (the file, or the table such as ``[obstacle]``).
    key_prefix : str
        Put before the key in the messages (e.g. ``"[geometry] "``).

    Raises
    ------
    KeywordError
        An unknown key (with the closest valid one and the list of valid keys), or a value of
        the wrong type (with the key's description).

    Examples
    --------
    >>> try:
    ...     check_keys({"cycle": 2}, {"cycles": (int, "number of cycles")}, "[iterate]")
    ... except KeywordError as exc:
    ...     print(exc)
    [iterate]: unknown key cycle (did you mean 'cycles'?); valid keys: cycles
    """
    if not isinstance(items, Mapping):
        raise KeywordError(f"{source}: expected a table of keys ({{ key = value, ... }}), got "
                           f"{type(items).__name__} {items!r}; valid keys: {', '.join(spec)}")
    for key, value in items.items():
        if key not in spec:
            raise KeywordError(f"{source}: unknown key {key_prefix}{key}{keyword_hint(key, spec)}; "
                               f"valid keys: {', '.join(spec)}")
        kind = spec[key][0]
        if (isinstance(value, bool) and kind is not bool) or not isinstance(value, kind):
            raise KeywordError(f"{source}: {key_prefix}{key} = {value!r} has the wrong type; "
                               f"expected {spec[key][1]}")
        if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 1000:
            # a 400-digit integer: float(value) overflowed later (issue 29)
            raise KeywordError(f"{source}: {key_prefix}{key} = {str(value)[:20]}... "
                               f"({len(str(abs(value)))} digits) is beyond the range of numbers; "
                               f"expected {spec[key][1]}")
