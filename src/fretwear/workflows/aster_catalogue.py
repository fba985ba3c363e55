"""Code_Aster command catalogues as data: keywords, types, defaults, into-values, blocks, rules.

Code_Aster describes each command by a catalogue (``code_aster/Cata/Commands/<command>.py``):
simple keywords (``SIMP``: a type, a default, allowed values ``into``, ``max`` values), factor
keywords (``FACT``: a group of keywords given as ``_F(...)``, possibly repeated), conditional
blocks (``BLOC``: keywords accepted only when a condition on other keywords holds) and rules
between keywords (``UN_PARMI``, ``AU_MOINS_UN``, ``EXCLUS``, ``ENSEMBLE``, ``PRESENT_PRESENT``,
``PRESENT_ABSENT``). This module mirrors those objects so that a facade such as
:func:`fretwear.workflows.aster.POST_USURE` states its catalogue once and checks a call against
it: unknown keywords, keywords of an inactive block, wrong types, values outside ``into``, and
violated rules are :class:`~fretwear.errors.KeywordError` naming the keywords.

Rule semantics (Code_Aster's ``Noyau/N_REGLE``, ``Accas`` rules):

* ``UN_PARMI(a, b, ...)``: exactly one is present;
* ``AU_MOINS_UN(a, b, ...)``: at least one;
* ``EXCLUS(a, b, ...)``: at most one;
* ``ENSEMBLE(a, b, ...)``: all or none;
* ``PRESENT_PRESENT(a, b, ...)``: when ``a`` is present, every other one is too;
* ``PRESENT_ABSENT(a, b, ...)``: when ``a`` is present, none of the others is.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fretwear.errors import KeywordError

__all__ = ["Simp", "Fact", "Bloc", "Rule", "UN_PARMI", "AU_MOINS_UN", "EXCLUS", "ENSEMBLE",
           "PRESENT_PRESENT", "PRESENT_ABSENT", "Catalogue", "_F"]


class _F(dict):
    """A factor keyword (``MOBILE=_F(COEF_USURE=1e-13)``), a plain dict of keywords.

    Examples
    --------
    >>> _F(COEF_USURE=1e-13)["COEF_USURE"]
    1e-13
    """

    def __repr__(self) -> str:
        return "_F(" + ", ".join(f"{k}={v!r}" for k, v in self.items()) + ")"


@dataclass(frozen=True)
class Rule:
    """A rule between keywords of one level (see the module docstring for the kinds)."""

    kind: str
    names: tuple[str, ...]
    note: str = ""

    def check(self, present: set[str], where: str) -> None:
        """Raise :class:`KeywordError` when the keywords ``present`` break the rule."""
        given = [n for n in self.names if n in present]
        listed = ", ".join(self.names)
        note = f" ({self.note})" if self.note else ""
        if self.kind == "UN_PARMI" and len(given) != 1:
            what = "none" if not given else " and ".join(given)
            raise KeywordError(f"{where}: exactly one of {listed} is required, got {what}"
                               f" [UN_PARMI]{note}")
        if self.kind == "AU_MOINS_UN" and not given:
            raise KeywordError(f"{where}: at least one of {listed} is required [AU_MOINS_UN]"
                               f"{note}")
        if self.kind == "EXCLUS" and len(given) > 1:
            raise KeywordError(f"{where}: {' and '.join(given)} exclude each other; give only "
                               f"one of {listed} [EXCLUS]{note}")
        if self.kind == "ENSEMBLE" and 0 < len(given) < len(self.names):
            missing = [n for n in self.names if n not in present]
            raise KeywordError(f"{where}: {listed} go together; {', '.join(given)} given "
                               f"without {', '.join(missing)} [ENSEMBLE]{note}")
        first, others = self.names[0], self.names[1:]
        if self.kind == "PRESENT_PRESENT" and first in present:
            missing = [n for n in others if n not in present]
            if missing:
                raise KeywordError(f"{where}: {first} needs {', '.join(missing)} "
                                   f"[PRESENT_PRESENT]{note}")
        if self.kind == "PRESENT_ABSENT" and first in present:
            extra = [n for n in others if n in present]
            if extra:
                raise KeywordError(f"{where}: {first} excludes {', '.join(extra)} "
                                   f"[PRESENT_ABSENT]{note}")


def UN_PARMI(*names: str, note: str = "") -> Rule:  # noqa: N802 - Code_Aster's name
    """Exactly one of ``names``."""
    return Rule("UN_PARMI", names, note)


def AU_MOINS_UN(*names: str, note: str = "") -> Rule:  # noqa: N802
    """At least one of ``names``."""
    return Rule("AU_MOINS_UN", names, note)


def EXCLUS(*names: str, note: str = "") -> Rule:  # noqa: N802
    """At most one of ``names``."""
    return Rule("EXCLUS", names, note)


def ENSEMBLE(*names: str, note: str = "") -> Rule:  # noqa: N802
    """All of ``names`` or none."""
    return Rule("ENSEMBLE", names, note)


def PRESENT_PRESENT(*names: str, note: str = "") -> Rule:  # noqa: N802
    """The first of ``names`` needs all the others."""
    return Rule("PRESENT_PRESENT", names, note)


def PRESENT_ABSENT(*names: str, note: str = "") -> Rule:  # noqa: N802
    """The first of ``names`` excludes all the others."""
    return Rule("PRESENT_ABSENT", names, note)


#: The types a simple keyword may have: Code_Aster's name -> what fretwear accepts.
TYPES: dict[str, str] = {
    "R": "a finite real",
    "I": "a whole number",
    "TXM": "a string",
    "table": "a table: a DataFrame or the path of a table file (table_sdaster)",
    "listr8": "a sequence of reals (listr8_sdaster)",
    "history": "a contact history: a ContactHistory, a history file, a list of IMPR_FONCTION "
               "files, or a mapping node label -> either (tran_gene)",
    "material": "a material pair: a string ('I600_Z6C13') or a (mobile, obstacle) pair",
    "node": "a node label (no)",
    "group": "a node group label (grno)",
    "concept": "the concept reused (CO)",
}


@dataclass(frozen=True)
class Simp:
    """A simple keyword: Code_Aster type, status ('o' required, 'f' optional, 'c' hidden), default,
    allowed values, number of values (1 or '**') and fretwear's meaning (with its unit)."""

    type: str
    status: str = "f"
    default: Any = None
    into: tuple | None = None
    max: int | str = 1
    help: str = ""

    def value(self, value: Any, name: str) -> Any:
        """``value`` checked against the type, ``into`` and ``max``; reals as floats.

        Examples
        --------
        >>> Simp("R", max="**").value((1, 2.5), "INST")
        [1.0, 2.5]
        >>> Simp("TXM", into=("OUI",)).value("oui", "TUBE_NEUF")
        'OUI'
        """
        if self.max != 1 and self.type in ("R", "I", "TXM"):
            items = [value] if np.isscalar(value) or isinstance(value, bool) else value
            try:
                items = list(items)
            except TypeError:
                raise KeywordError(f"{name} must be {TYPES[self.type]} or a sequence of them, "
                                   f"got {value!r}") from None
            if not items:
                raise KeywordError(f"{name} needs at least one value")
            return [self._one(v, f"{name}[{i}]") for i, v in enumerate(items)]
        return self._one(value, name)

    def _one(self, value: Any, name: str) -> Any:
        kind = self.type
        if kind in ("R", "I"):
            ok = not isinstance(value, bool | str | bytes) and value is not None
            number = math.nan
            if ok:
                try:
                    number = float(value)
                except (TypeError, ValueError):
                    ok = False
            if not ok or not math.isfinite(number):
                raise KeywordError(f"{name} must be {TYPES[kind]}, got {value!r}")
            if kind == "I":
                if number != int(number):
                    raise KeywordError(f"{name} must be {TYPES[kind]}, got {value!r}")
                number = int(number)
            value = number
        elif kind in ("TXM", "node", "group"):
            if not isinstance(value, str):
                raise KeywordError(f"{name} must be {TYPES[kind]}, got {value!r}")
            value = value.strip()
        elif kind == "material":
            pair = isinstance(value, list | tuple) and len(value) == 2 \
                and all(isinstance(v, str) for v in value)
            if not (isinstance(value, str) or pair):
                raise KeywordError(f"{name} must be {TYPES[kind]}, got {value!r}")
        elif kind == "listr8":
            value = Simp("R", max="**").value(value, name)
        elif kind == "table":
            if not (hasattr(value, "columns") or isinstance(value, str | os.PathLike)):
                raise KeywordError(f"{name} must be {TYPES[kind]}, got {type(value).__name__}")
        if self.into is not None:
            folded = value.upper() if isinstance(value, str) else value
            allowed = [v.upper() if isinstance(v, str) else v for v in self.into]
            if folded not in allowed:
                raise KeywordError(f"{name}={value!r} is not allowed; choose one of "
                                   f"{list(self.into)}")
            value = self.into[allowed.index(folded)]
        return value


@dataclass(frozen=True)
class Fact:
    """A factor keyword: its keywords, how many occurrences (``max``), rules, meaning."""

    keywords: Mapping[str, Simp]
    status: str = "f"
    max: int | str = 1
    rules: tuple[Rule, ...] = ()
    help: str = ""

    def occurrences(self, value: Any, name: str) -> list[dict[str, Any]]:
        """The occurrences given, each checked (keywords, types, rules, required ones)."""
        items = list(value) if isinstance(value, list | tuple) else [value]
        if self.max == 1 and len(items) != 1:
            raise KeywordError(f"{name} takes one occurrence, got {len(items)}")
        out = []
        for i, item in enumerate(items):
            where = f"{name}[{i}]" if self.max != 1 else name
            if not isinstance(item, Mapping):
                raise KeywordError(f"{where} must be given as _F(...), got {item!r}")
            given = {k: v for k, v in item.items() if v is not None}
            unknown = sorted(set(given) - set(self.keywords))
            if unknown:
                raise KeywordError(f"unknown keyword(s) {unknown} in {where}; it accepts "
                                   f"{list(self.keywords)}")
            for rule in self.rules:
                rule.check(set(given), where)
            checked = {}
            for key, simp in self.keywords.items():
                if key in given:
                    checked[key] = simp.value(given[key], f"{where} {key}")
                elif simp.status == "o":
                    raise KeywordError(f"{where} needs {key} ({simp.help or TYPES[simp.type]})")
            out.append(checked)
        return out


@dataclass(frozen=True)
class Bloc:
    """Keywords accepted when ``condition(keywords)`` holds (``text`` says it), and their
    rules."""

    text: str
    condition: Callable[[Mapping[str, Any]], bool]
    keywords: Mapping[str, Simp | Fact]
    rules: tuple[Rule, ...] = ()


@dataclass(frozen=True)
class Catalogue:
    """A command: top-level keywords, blocks and rules (Code_Aster's ``OPER``/``MACRO``)."""

    name: str
    keywords: Mapping[str, Simp | Fact]
    blocs: tuple[Bloc, ...] = ()
    rules: tuple[Rule, ...] = ()
    source: str = ""
    notes: Mapping[str, str] = field(default_factory=dict)

    def all_keywords(self) -> dict[str, list[Simp | Fact]]:
        """Every keyword name of the command, with its definitions (one per block holding it)."""
        out: dict[str, list[Simp | Fact]] = {k: [v] for k, v in self.keywords.items()}
        for bloc in self.blocs:
            for k, v in bloc.keywords.items():
                out.setdefault(k, []).append(v)
        return out

    def check(self, keywords: Mapping[str, Any]) -> dict[str, Any]:
        """Check a call; return its keywords with checked values (factor keywords as lists of
        dicts, reals as floats), ``None`` values dropped.

        Raises
        ------
        KeywordError
            An unknown keyword, a keyword of an inactive block (the block's condition named), a
            wrong type or value, a missing required keyword, a violated rule.
        """
        given = {k: v for k, v in keywords.items() if v is not None}
        where = self.name
        known = self.all_keywords()
        unknown = sorted(k for k in given if k not in known)
        if unknown:
            raise KeywordError(f"{where}: unknown keyword(s) {unknown}; {where} accepts "
                               f"{sorted(known)}")
        out: dict[str, Any] = {}
        for key, value in given.items():  # the top level first: block conditions read it
            definition = self.keywords.get(key)
            if isinstance(definition, Fact):
                out[key] = definition.occurrences(value, key)
            elif definition is not None:
                out[key] = definition.value(value, key)
        for rule in self.rules:
            rule.check(set(given), where)
        checked = {**given, **out}
        active: dict[str, Simp | Fact] = dict(self.keywords)
        origin: dict[str, str] = {}
        rules: list[tuple[Rule, str]] = []
        for bloc in self.blocs:
            if bloc.condition(checked):
                rules += [(rule, f"{where} ({bloc.text})") for rule in bloc.rules]
                active.update(bloc.keywords)
                origin.update(dict.fromkeys(bloc.keywords, bloc.text))
        for key in given:
            if key not in active:
                texts = [b.text for b in self.blocs if key in b.keywords]
                raise KeywordError(f"{where}: {key} is accepted only when "
                                   f"{' or '.join(texts)}")
        for rule, place in rules:
            rule.check(set(given), place)
        for key, value in given.items():
            definition = active[key]
            if key in out:
                continue
            if isinstance(definition, Fact):
                out[key] = definition.occurrences(value, key)
            else:
                out[key] = definition.value(value, key)
        for key, definition in active.items():
            if key not in out and definition.status == "o":
                when = f" when {origin[key]}" if key in origin else ""
                raise KeywordError(f"{where}: {key} is required{when} ({definition.help})")
        return out

    def describe(self) -> dict[str, str]:
        """``{keyword: meaning}`` of every keyword (factor keywords list theirs)."""
        out = {}
        for name, definitions in self.all_keywords().items():
            d = definitions[0]
            if isinstance(d, Fact):
                keys = sorted({k for x in definitions if isinstance(x, Fact) for k in x.keywords})
                out[name] = f"{d.help} (_F with {', '.join(keys)})"
            else:
                out[name] = d.help or TYPES[d.type]
        return out


def exists(name: str) -> Callable[[Mapping[str, Any]], bool]:
    """Condition: ``name`` is given (Code_Aster's ``exists("NAME")``)."""
    return lambda kw: kw.get(name) is not None


def absent(name: str) -> Callable[[Mapping[str, Any]], bool]:
    """Condition: ``name`` is not given (``not exists("NAME")``)."""
    return lambda kw: kw.get(name) is None


def equal_to(name: str, value: str) -> Callable[[Mapping[str, Any]], bool]:
    """Condition: ``name`` equals ``value`` (case-blind; ``equal_to("NAME", 'VALUE')``)."""
    return lambda kw: isinstance(kw.get(name), str) and kw[name].upper() == value.upper()


def number_list(value: Any) -> list[float]:
    """A listr8-like value as a list of floats (helper for facades)."""
    return Simp("R", max="**").value(value, "values")


def first(values: Sequence[dict]) -> dict:
    """The single occurrence of a factor keyword given once (an empty dict when absent)."""
    return values[0] if values else {}
