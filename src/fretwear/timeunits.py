"""Named time units of wear tables and case files (seconds per unit). Any layer may import it."""

from __future__ import annotations

__all__ = ["TIME_UNITS"]

#: Named time units -> seconds per unit (a year is 365 days, Code_Aster users' 31 536 000 s).
TIME_UNITS: dict[str, float] = {
    "s": 1.0, "second": 1.0, "min": 60.0, "minute": 60.0, "h": 3600.0, "hour": 3600.0,
    "day": 86400.0, "week": 604800.0, "year": 31536000.0,
}
