"""The provenance header of fretwear's table files: who wrote the numbers, how, from what.

Every table file fretwear writes (wear tables, obstacle profile tables; CSV, Parquet and
Code_Aster text) carries the same provenance: the fretwear version, the date (UTC), the kind of
table, the case name, the contact type, the wear law and every coefficient with its value and
source (user, database row, default: :class:`fretwear.table.Coefficient`), the time unit and
the float format of the text (:data:`fretwear.table.schema.FLOAT_FORMAT`).

In text it is one ``fretwear.<key> = <JSON value>`` line per item (ASCII: JSON escapes the rest),
one line per coefficient (``fretwear.coefficient.mobile.coefficient = {"value": 1.2e-13,
"source": "user"}``):

* CSV: leading comment lines ``# fretwear.version = "0.1.0"`` before the column names (pandas
  reads such a file with ``comment="#"`` or ``skiprows``; :func:`fretwear.table.read_wear_table`
  skips them);
* Code_Aster text: title lines after the table's title (``#fretwear.version = ...`` in TABLEAU,
  ``#TITRE fretwear.version = ...`` in ASTER format, which is where LIRE_TABLE reads a title);
* Parquet: the JSON of the whole provenance in the file's schema metadata, key ``fretwear``.

:func:`provenance` builds it from a table's ``attrs``; :func:`header_lines` and
:func:`parse_header` write and read the text lines.
"""

from __future__ import annotations

import datetime
import json
from collections.abc import Iterable, Mapping
from typing import Any

from fretwear._version import __version__
from fretwear.table.schema import FLOAT_FORMAT

__all__ = ["PARQUET_KEY", "PREFIX", "header_lines", "parse_header", "provenance"]

#: Prefix of a provenance line (the rest of a title is left alone).
PREFIX = "fretwear."
#: Key of the provenance JSON in a Parquet file's schema metadata.
PARQUET_KEY = b"fretwear"


def provenance(attrs: Mapping[str, Any] | None, *, kind: str = "wear table",
               **extra: Any) -> dict[str, Any]:
    """The provenance of a table from its ``attrs`` (those of :func:`fretwear.table.wear_table`).

    Parameters
    ----------
    attrs : mapping or None
        The table's ``attrs``: ``title``, ``contact_type``, ``law``, ``coefficients_mobile``,
        ``coefficients_obstacle``, ``coefficient_sources``, ``time_unit``, ``case``, ``power``
        are used when present.
    kind : str
        What the table is (``"wear table"``, ``"obstacle profile"``).
    **extra
        More items (JSON-ready), e.g. ``instant=5.0``.

    Returns
    -------
    dict
        ``kind``, ``version``, ``date`` (UTC, ISO 8601), ``name``, ``contact_type``, ``law``,
        ``coefficients`` (``"<body>.<name>"`` -> ``{"value", "source"}``: resolved, a
        history's KWU-EPRI intensity included), ``time_unit``, ``float_format``, ``case``
        (the wear case, :meth:`fretwear.table.WearCase.to_dict`: a table read back from a file
        is rebuilt into its depth model, :func:`fretwear.table.models_from_table`), ``power``
        (``total`` and ``sectors`` [W]) and ``extra``; items without a value are left out.

    Examples
    --------
    >>> p = provenance({"law": "ARCHARD", "coefficients_mobile": {"coefficient": 1e-13},
    ...                 "coefficient_sources": {"mobile.coefficient": "user"}})
    >>> p["law"], p["coefficients"], p["float_format"]
    ('ARCHARD', {'mobile.coefficient': {'value': 1e-13, 'source': 'user'}}, '%.16E')
    """
    attrs = dict(attrs or {})
    sources = dict(attrs.get("coefficient_sources") or {})
    coefficients = {}
    for body in ("mobile", "obstacle"):
        for name, value in (attrs.get(f"coefficients_{body}") or {}).items():
            key = f"{body}.{name}"
            coefficients[key] = {"value": value, "source": sources.get(key, "unknown")}
    out = {"kind": kind, "version": __version__,
           "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
           "name": attrs.get("title"), "contact_type": attrs.get("contact_type"),
           "law": attrs.get("law"), "coefficients": coefficients or None,
           "time_unit": attrs.get("time_unit"), "float_format": FLOAT_FORMAT,
           "case": attrs.get("case"), "power": _power(attrs.get("power")), **extra}
    return {k: v for k, v in out.items() if v is not None}


def _power(power: Mapping[str, Any] | None) -> dict[str, Any] | None:
    """The run's power a table's models need: ``total`` [W] and ``sectors`` [W] (None: the
    power was given as a number, it is the table's power column)."""
    if not power:
        return None
    out = {"total": power.get("total"), "sectors": power.get("sectors")}
    return {k: v for k, v in out.items() if v is not None} or None


def header_lines(prov: Mapping[str, Any]) -> list[str]:
    """The text lines of a provenance (without comment marks), one item per line.

    Examples
    --------
    >>> header_lines({"version": "0.1.0", "coefficients": {"mobile.coefficient":
    ...               {"value": 1e-13, "source": "user"}}})
    ['fretwear.version = "0.1.0"', 'fretwear.coefficient.mobile.coefficient = \
{"value": 1e-13, "source": "user"}']
    """
    lines = []
    for key, value in prov.items():
        if key == "coefficients":
            lines.extend(f"{PREFIX}coefficient.{name} = {json.dumps(item)}"
                         for name, item in value.items())
        else:
            lines.append(f"{PREFIX}{key} = {json.dumps(value)}")
    return lines


def parse_header(lines: Iterable[str]) -> dict[str, Any]:
    """The provenance in text lines (comment marks and other lines are skipped).

    Examples
    --------
    >>> parse_header(['# a title', '# fretwear.law = "ARCHARD"',
    ...               '#TITRE fretwear.coefficient.mobile.coefficient = {"value": 1e-13, '
    ...               '"source": "user"}'])
    {'law': 'ARCHARD', 'coefficients': {'mobile.coefficient': {'value': 1e-13, 'source': 'user'}}}
    """
    out: dict[str, Any] = {}
    for raw in lines:
        line = raw.lstrip("\ufeff").strip().lstrip("#").strip()
        if line.upper().startswith("TITRE"):
            line = line[len("TITRE"):].strip()
        if not line.startswith(PREFIX) or " = " not in line:
            continue
        key, _, text = line[len(PREFIX):].partition(" = ")
        try:
            value = json.loads(text)
        except ValueError:
            value = text.strip()
        if key.startswith("coefficient."):
            out.setdefault("coefficients", {})[key[len("coefficient."):]] = value
        else:
            out[key] = value
    return out
