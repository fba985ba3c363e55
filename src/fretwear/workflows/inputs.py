"""The files a case reads, so that no output of a run replaces one of them (nothing lost).

:func:`case_inputs` lists them (history, restart table given as ETAT_INIT, coefficient
databases, obstacle tables, the case file itself); the command line passes them with its outputs
to :func:`fretwear.io.atomic.check_outputs`, which refuses an output equal to an input (the
restart table only with ``--force``).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

__all__ = ["case_inputs", "RESTART_TABLE"]

#: The label of the restart table among the inputs (the only one ``--force`` lets a run replace).
RESTART_TABLE = "restart table (ETAT_INIT)"


def _resolve(case: Mapping[str, Any], value: Any) -> Path | None:
    if not isinstance(value, str) or not value:
        return None
    p = Path(value)
    return p if p.is_absolute() else Path(case.get("_directory", ".")) / p


def case_inputs(case: Mapping[str, Any], case_file: Any = None) -> dict[str, Path]:
    """``{what: path}`` of every file a (loaded) case reads.

    Parameters
    ----------
    case : mapping
        A case as :func:`fretwear.workflows.case_files.load_case` returns it (relative paths are
        relative to ``case["_directory"]``).
    case_file : path-like, optional
        The case file itself.

    Examples
    --------
    >>> case_inputs({"history": {"file": "h.csv"}, "restart": {"table": "t.tab"},
    ...              "law": {"database": ["a.csv"]}, "_directory": "/c"})
    ... # doctest: +NORMALIZE_WHITESPACE
    {'history file': PosixPath('/c/h.csv'), 'restart table (ETAT_INIT)': PosixPath('/c/t.tab'),
     'coefficient database 1': PosixPath('/c/a.csv')}
    """
    def section(name: str) -> Mapping[str, Any]:
        value = case.get(name, {})
        return value if isinstance(value, Mapping) else {}

    found: dict[str, Path | None] = {
        "history file": _resolve(case, section("history").get("file")),
        RESTART_TABLE: _resolve(case, section("restart").get("table")),
    }
    databases = section("law").get("database")
    for k, item in enumerate([databases] if isinstance(databases, str) else
                             list(databases) if isinstance(databases, list) else [], 1):
        found[f"coefficient database {k}"] = _resolve(case, item)
    found["obstacle's wear table"] = _resolve(case, section("obstacle").get("table"))
    found["obstacle table (the new obstacle)"] = _resolve(case, section("obstacle").get("file"))
    if case_file is not None:
        found["case file"] = Path(case_file)
    return {k: v for k, v in found.items() if v is not None}
