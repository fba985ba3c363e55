"""The ``--units`` option of every command that reads a history, and the units line of summaries.

A history exported in mm, mm/s, ms, kN ... is read in SI only when its units are given
(docs/formats.md "Units" and "Plausibility checks"); every command that reads a history takes
``--units KEY=UNIT[,...]`` and every summary prints the unit each channel was read in.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import click

from fretwear.history import CHANNELS


def load_case(case):
    """``fretwear.workflows.case_files.load_case``, imported when a case is given: it imports
    the wear table and scipy (about 1 s), which ``fretwear power FILE`` never needs."""
    from fretwear.workflows.case_files import load_case as load

    return load(case)

#: Help of ``--units`` (the same on every command).
UNITS_HELP = ("Units of the history file's values, converted to SI: per quantity (length=mm, "
              "force=kN, time=ms, velocity=mm/s) or per channel (dy=mm). Repeatable. Default: "
              "the units the file declares, else SI.")


def units_option(function):
    """The ``--units`` option (repeatable, ``KEY=UNIT[,KEY=UNIT...]``)."""
    return click.option("--units", "units", multiple=True, metavar="KEY=UNIT[,...]",
                        help=UNITS_HELP)(function)


def pairs(values: tuple[str, ...], option: str, what: str, split: bool = True
          ) -> dict[str, str]:
    """``("length=mm,force=kN", "dy=mm")`` -> ``{"length": "mm", "force": "kN", "dy": "mm"}``.

    Examples
    --------
    >>> pairs(("length=mm,force=kN", "dy=mm"), "--units", "KEY=UNIT")
    {'length': 'mm', 'force': 'kN', 'dy': 'mm'}
    """
    out: dict[str, str] = {}
    for value in values:
        for item in (value.split(",") if split else [value]):
            if not item.strip():
                continue
            key, sep, val = item.partition("=")
            if not sep or not key.strip() or (split and not val.strip()):
                raise click.BadParameter(f"{item!r}: give {what}", param_hint=option)
            out[key.strip()] = val.strip()
    return out


def parse_units(values: tuple[str, ...]) -> dict[str, str] | None:
    """The ``units`` mapping of ``--units`` values, or None when none was given."""
    return pairs(values, "--units", "KEY=UNIT (e.g. length=mm)") or None


def _with_units(case: dict[str, Any], units: Mapping[str, str]) -> dict[str, Any]:
    """``case`` with ``units`` added to its ``[history] units`` (the given entries win)."""
    history = dict(case.get("history", {}))
    history["units"] = {**dict(history.get("units", {})), **units}
    case["history"] = history
    return case


def with_history_units(case: Path | dict[str, Any], units: Mapping[str, str] | None
                       ) -> Path | dict[str, Any]:
    """The case (file or loaded dict) with ``--units`` added to its ``[history] units``
    (the command line's entries win)."""
    if not units:
        return case
    case = load_case(case) if not isinstance(case, dict) else case
    if "file" not in case.get("history", {}):
        raise click.UsageError("--units gives the units of a history file, but the case has no "
                               "[history] file (it gives the power)")
    return _with_units(case, units)


def with_bundle_units(case: Path | None, units: Mapping[str, str] | None
                      ) -> Path | dict[str, Any] | None:
    """The bundle's base case (file, or none) with ``--units`` added to its ``[history] units``
    (the command line's entries win): the units of every contact's history file (a manifest
    row's ``history.units`` column still overrides them for its contact)."""
    if not units:
        return case
    return _with_units(load_case(case) if case is not None else {}, units)


def units_line(units: Mapping[str, str] | None) -> str:
    """``units read: time [s], normal_force [N], ...`` (channels in canonical order).

    Examples
    --------
    >>> units_line({"vt1": "mm/s", "time": "s"})
    'units read: time [s], vt1 [mm/s] (converted to SI)'
    >>> units_line(None)
    'units: SI (no history file read)'
    """
    if not units:
        return "units: SI (no history file read)"
    items = [f"{ch} [{units[ch]}]" for ch in CHANNELS if ch in units]
    return f"units read: {', '.join(items)} (converted to SI)"
