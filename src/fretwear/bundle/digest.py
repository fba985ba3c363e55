"""The bundle's bad news in a few lines: one per kind of warning the terminal must show.

A bundle's warnings are captured per contact (:attr:`BundleResult.warnings`, ``warnings.csv``);
the kinds that change what a number means reach the terminal here: a tube worn through its wall
(:class:`~fretwear.errors.PerforationWarning`) first, then a history whose units look wrong
(:class:`~fretwear.errors.UnitsWarning`: the cause of a loud mm export, whose consequence, a
:class:`~fretwear.errors.RangeWarning`, is listed among the errors), then histories sampled
too coarsely for their impacts (:class:`~fretwear.errors.ResolutionWarning`: the power itself
is off). One line per kind: how many contacts, the worst ones (in the summary's order: deepest
first) and the first one's message.
"""

from __future__ import annotations

from fretwear._lazy import pandas as pd

#: The kinds said on the terminal, in this order (bad news first).
TERMINAL_KINDS = ("PerforationWarning", "UnitsWarning", "ResolutionWarning")


def warning_lines(warnings: pd.DataFrame, order: list[str] | None = None, *,
                  kinds: tuple[str, ...] = TERMINAL_KINDS, worst: int = 3,
                  width: int = 160) -> list[str]:
    """One line per kind of warning: ``"<kind>: N contact(s) (worst: a, b, c): message"``.

    Parameters
    ----------
    warnings : DataFrame
        ``contact, category, message`` (:attr:`BundleResult.warnings`).
    order : list of str, optional
        The contacts worst first (the summary's ``contact`` column); others follow in the
        warnings' order.
    kinds : tuple of str
        The warning classes to say, in this order.
    worst : int
        Contacts named per line.
    width : int
        Characters of the first contact's message kept (cut with "...").

    Examples
    --------
    >>> w = pd.DataFrame({"contact": ["A", "B", "B"], "category": ["UnitsWarning"] * 3,
    ...                   "message": ["orbit too large", "orbit too large", "speed"]})
    >>> warning_lines(w, ["B", "A"])
    ['UnitsWarning: 2 contacts (worst: B, A): B: orbit too large']
    """
    lines = []
    rank = {c: i for i, c in enumerate(order or [])}
    for kind in kinds:
        rows = warnings[warnings["category"] == kind]
        if not len(rows):
            continue
        contacts = sorted(dict.fromkeys(rows["contact"].astype(str)),
                          key=lambda c: rank.get(c, len(rank)))
        first = rows[rows["contact"].astype(str) == contacts[0]]["message"].iloc[0]
        text = first if len(first) <= width else first[:width - 3] + "..."
        count = f"{len(contacts)} contact{'s' if len(contacts) > 1 else ''}"
        lines.append(f"{kind}: {count} (worst: {', '.join(contacts[:worst])}"
                     f"{', ...' if len(contacts) > worst else ''}): {contacts[0]}: {text}")
    return lines


def limit_lines(summary: pd.DataFrame, *, worst: int = 3) -> list[str]:
    """The counts said first: contacts and tubes through the wall, then at or past the
    plugging limit, at the last instant, the worst named (the summary's order: deepest first),
    and when: "at 40 year" (the contacts' last instant and its unit, where the summary has
    ``instant`` and ``time_unit``; a range where the contacts' last instants differ).

    Parameters
    ----------
    summary : DataFrame
        :meth:`BundleResult.summary` (``contact``, ``tube_row``, ``tube_column``,
        ``depth_fraction`` [-], ``limit_depth`` and ``wall_thickness`` [m]).

    Examples
    --------
    >>> s = pd.DataFrame({"contact": ["a", "b", "c"], "tube_row": [1, 1, 2],
    ...                   "tube_column": [1, 1, 1], "depth_fraction": [1.2, 0.5, 0.1],
    ...                   "limit_depth": [4e-4] * 3, "wall_thickness": [1e-3] * 3})
    >>> for line in limit_lines(s): print(line)
    THROUGH THE WALL: 1 contact(s) on 1 tube(s) (worst: a 120.0 %)
    PAST THE PLUGGING LIMIT: 2 contact(s) on 1 tube(s) (worst: a 120.0 %, b 50.0 %)
    >>> s["instant"], s["time_unit"] = 40.0, "year"
    >>> print(limit_lines(s)[0])
    THROUGH THE WALL at 40 year: 1 contact(s) on 1 tube(s) (worst: a 120.0 %)
    """
    need = {"depth_fraction", "limit_depth", "wall_thickness"}
    if not len(summary) or not need <= set(summary.columns):
        return []
    frac = pd.to_numeric(summary["depth_fraction"], errors="coerce")
    limit = pd.to_numeric(summary["limit_depth"], errors="coerce") \
        / pd.to_numeric(summary["wall_thickness"], errors="coerce")
    lines = []
    for name, hit in (("THROUGH THE WALL", frac >= 1.0),
                      ("PAST THE PLUGGING LIMIT", frac >= limit)):
        rows = summary[hit.fillna(False).to_numpy(bool)]
        if not len(rows):
            continue
        tubes = rows[[c for c in ("tube_row", "tube_column") if c in rows.columns]]
        count = len(tubes.drop_duplicates()) if tubes.shape[1] else len(rows)
        named = ", ".join(f"{c} {100 * f:.1f} %" for c, f in zip(
            rows["contact"].head(worst), rows["depth_fraction"].head(worst), strict=True))
        lines.append(f"{name}{_when(rows)}: {len(rows)} contact(s) on {count} tube(s) "
                     f"(worst: {named})")
    return lines


def _when(rows: pd.DataFrame) -> str:
    """" at 40 year" (the rows' last instant and unit), "" where the summary has neither."""
    if "instant" not in rows.columns:
        return ""
    t = pd.to_numeric(rows["instant"], errors="coerce").dropna()
    if not len(t):
        return ""
    units = rows["time_unit"].dropna().astype(str).unique() if "time_unit" in rows.columns \
        else []
    unit = f" {units[0]}" if len(units) == 1 else ""
    lo, hi = float(t.min()), float(t.max())
    return f" at {lo:.4g}{unit}" if lo == hi else f" at {lo:.4g}-{hi:.4g}{unit} (last instants)"
