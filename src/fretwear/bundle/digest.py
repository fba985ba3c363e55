"""The bundle's bad news in a few lines: one per kind of warning the terminal must show.

A bundle's warnings are captured per contact (:attr:`BundleResult.warnings`, ``warnings.csv``);
the kinds that change what a number means reach the terminal here: a tube worn through its wall
(:class:`~fretwear.errors.PerforationWarning`) first, then a history whose units look wrong
(:class:`~fretwear.errors.UnitsWarning`: the cause of a loud mm export, whose consequence, a
:class:`~fretwear.errors.RangeWarning`, is listed among the errors). One line per kind: how many
contacts, the worst ones (in the summary's order: deepest first) and the first one's message.
"""

from __future__ import annotations

from fretwear._lazy import pandas as pd

#: The kinds said on the terminal, in this order (bad news first).
TERMINAL_KINDS = ("PerforationWarning", "UnitsWarning")


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
