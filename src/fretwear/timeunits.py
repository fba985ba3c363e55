"""Named time units of wear tables and case files (seconds per unit). Any layer may import it."""

from __future__ import annotations

__all__ = ["TIME_UNITS", "describe_time_units", "time_unit_name", "unit_seconds"]

#: Named time units -> seconds per unit (a year is 365 days, Code_Aster users' 31 536 000 s).
TIME_UNITS: dict[str, float] = {
    "s": 1.0, "second": 1.0, "min": 60.0, "minute": 60.0, "h": 3600.0, "hour": 3600.0,
    "day": 86400.0, "week": 604800.0, "year": 31536000.0,
}


def time_unit_name(name: str) -> str:
    """The name of :data:`TIME_UNITS` a user's spelling means: case and surrounding spaces
    ignored, a plural of a named unit taken as the unit ("years" -> "year"); other names
    returned as given (stripped), for the caller to refuse.

    >>> [time_unit_name(u) for u in (" Years", "hours", "s", "fortnight")]
    ['year', 'hour', 's', 'fortnight']
    """
    text = str(name).strip()
    for candidate in (text, text.lower()):
        if candidate in TIME_UNITS:
            return candidate
        if candidate.endswith("s") and candidate[:-1] in TIME_UNITS and len(candidate) > 2:
            return candidate[:-1]
    return text


def unit_seconds(label) -> float | None:
    """Seconds per unit [s] of a table's time-unit label: a name of :data:`TIME_UNITS` (any
    spelling :func:`time_unit_name` takes) or ``"<number> s"`` (a wear table's label of a case
    given by its scale alone); None for anything else (no label, or one not understood).

    >>> [unit_seconds(u) for u in ("year", "Hours", "3600 s", "fortnight", None)]
    [31536000.0, 3600.0, 3600.0, None, None]
    """
    if not isinstance(label, str):
        return None
    name = time_unit_name(label)
    if name in TIME_UNITS:
        return TIME_UNITS[name]
    number, _, unit = name.partition(" ")
    if unit.strip() != "s":
        return None
    try:
        seconds = float(number)
    except ValueError:
        return None
    return seconds if seconds > 0 and seconds < float("inf") else None


def describe_time_units() -> str:
    """The names of :data:`TIME_UNITS` for a help text, synonyms together, longer units with
    their length in days.

    Examples
    --------
    >>> describe_time_units()
    's/second, min/minute, h/hour, day, week or year (365 days)'
    """
    groups: dict[float, list[str]] = {}
    for name, seconds in TIME_UNITS.items():
        groups.setdefault(seconds, []).append(name)
    parts = ["/".join(names) + (f" ({seconds / 86400.0:g} days)" if seconds > 604800.0 else "")
             for seconds, names in groups.items()]
    return ", ".join(parts[:-1]) + " or " + parts[-1]
