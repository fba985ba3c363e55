"""The import graph of ``src/fretwear``: no circle between files, no import of an upper layer.

Every ``import`` and ``from ... import`` statement of every module is read from its syntax tree,
wherever it stands (module top, inside a function, under ``if TYPE_CHECKING``, in a ``try``),
and so is every ``importlib.import_module("literal")`` call. Imports are resolved to files:

- ``from a.b import c`` is an edge to ``a/b/c.py`` when ``c`` is a submodule, else to
  ``a/b/__init__.py``; relative imports are resolved against the importing module's package.
- Importing ``a.b.c`` also runs the ``__init__.py`` of every package on the way (``a.b``), so an
  edge goes to each of those too, except the packages that contain the importing module itself
  (a submodule always runs inside its own package's initialisation; the root ``fretwear``
  package contains every module, so it never gets such an edge).
- A package's ``__init__.py`` importing its own submodules is an ordinary edge: it is fine as long
  as no submodule imports its package's ``__init__.py`` back (``from fretwear.table import x``
  inside ``fretwear/table/core.py``), which closes a circle and is reported.
- A private name (``_x``, or anything in a private module ``_m``) belongs to the package that
  holds it: importing it from another package is an error (it is made public in its package,
  or moved). The root's private modules (``fretwear._lazy`` ...) belong to every module.

Layers (docs/DESIGN.md), lowest first; a module may import its own layer or a lower one only:
foundation → physics → plotting → workflows → api (the root ``fretwear/__init__.py``, which
re-exports everything lazily) → cli.
"""

from __future__ import annotations

import ast
import re
from collections import defaultdict
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
ROOT = SRC / "fretwear"
DESIGN = SRC.parent / "docs" / "DESIGN.md"

#: layer names, lowest first.
LAYERS = ("foundation", "physics", "plotting", "workflows", "api", "cli")

#: first component under fretwear/ (module or package) -> layer.
LAYER_OF = {
    "errors": "foundation", "keys": "foundation", "timeunits": "foundation",
    "_optional": "foundation", "_numba": "foundation", "_version": "foundation",
    "_lazy": "foundation",
    "conftest": "foundation",
    "history": "physics", "sectors": "physics", "io": "physics", "power": "physics",
    "laws": "physics", "database": "physics", "geometry": "physics", "table": "physics",
    "obstacle": "physics", "dynamics": "physics", "assessment": "physics",
    "uncertainty": "physics",  # -> workflows if any of its modules imports workflows
    "plotting": "plotting",
    "workflows": "workflows", "bundle": "workflows", "report": "workflows",
    "flow": "workflows",  # fretwear simulate runs on the bundle's engines
    "__init__": "api",
    "cli": "cli",
}



def module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def modules() -> dict[str, Path]:
    """Dotted name -> file of every module under src/fretwear."""
    return {module_name(p): p for p in sorted(ROOT.rglob("*.py"))}


def _is_package(path: Path) -> bool:
    return path.name == "__init__.py"


def _imported_names(tree: ast.AST, name: str, path: Path):
    """(dotted module, imported attribute or None, line) of every import in ``tree``."""
    package = name if _is_package(path) else name.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, None, node.lineno
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            for alias in node.names:
                yield target, alias.name, node.lineno
        elif (isinstance(node, ast.Call) and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)
              and ((isinstance(node.func, ast.Attribute) and node.func.attr == "import_module")
                   or (isinstance(node.func, ast.Name) and node.func.id == "import_module"))):
            yield node.args[0].value, None, node.lineno


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_owner(target: str, attr: str | None, mods) -> str | None:
    """The package a private import belongs to (None: nothing private is imported): the
    package above the first private module of ``target``, else, for a private ``attr``, the
    package of ``target`` (itself when it is a package)."""
    parts = target.split(".")
    for i, part in enumerate(parts[1:], start=1):
        if _private(part):
            return ".".join(parts[:i])
    if attr and _private(attr) and f"{target}.{attr}" not in mods:
        path = mods.get(target)
        return target if path is not None and _is_package(path) else target.rpartition(".")[0]
    return None


def import_graph() -> tuple[dict[str, dict[str, int]], list[str]]:
    """(edges module -> {imported module: line}, private names imported from another
    package)."""
    mods = modules()
    edges: dict[str, dict[str, int]] = defaultdict(dict)
    private_uses = []
    for name, path in mods.items():
        edges[name]  # every module is a node
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        own = name if _is_package(path) else name.rpartition(".")[0]
        ancestors = {".".join(own.split(".")[:i]) for i in range(1, own.count(".") + 2)}
        for target, attr, line in _imported_names(tree, name, path):
            if not target or not (target == "fretwear" or target.startswith("fretwear.")):
                continue
            full = f"{target}.{attr}" if attr and f"{target}.{attr}" in mods else target
            if full not in mods:
                raise AssertionError(f"{path}:{line}: import of {full!r}, which is no module")
            owner = private_owner(target, attr, mods)
            if owner is not None and not (name == owner or name.startswith(owner + ".")):
                private_uses.append(f"{path.relative_to(SRC)}:{line} imports "
                                    f"{target}{'.' + attr if attr else ''}, private to {owner}")
            parts = full.split(".")
            reached = [".".join(parts[:i]) for i in range(2, len(parts) + 1)]
            if full == "fretwear" and name != "fretwear":
                # an explicit import of the root package (`from fretwear import x`): an edge to
                # the api layer (its implicit run as every module's parent is not one)
                edges[name].setdefault("fretwear", line)
            for dep in reached:
                if dep in ancestors or dep == name:
                    continue
                edges[name].setdefault(dep, line)
    return edges, private_uses


def strongly_connected(edges: dict[str, dict[str, int]]) -> list[list[str]]:
    """Tarjan's strongly connected components of more than one module."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def layer(name: str, edges: dict[str, dict[str, int]] | None = None) -> str:
    parts = name.split(".")
    key = parts[1] if len(parts) > 1 else "__init__"
    out = LAYER_OF.get(key)
    if out is None:
        raise AssertionError(f"{name}: no layer; add {key!r} to LAYER_OF and docs/DESIGN.md")
    if key == "uncertainty" and edges is not None and any(
            layer(d) == "workflows" for m, deps in edges.items()
            if m.split(".")[1:2] == ["uncertainty"] for d in deps):
        return "workflows"
    return out


def layer_violations(edges: dict[str, dict[str, int]]) -> list[str]:
    out = []
    for name, deps in sorted(edges.items()):
        mine = LAYERS.index(layer(name, edges))
        for dep, line in sorted(deps.items()):
            theirs = LAYERS.index(layer(dep, edges))
            if theirs > mine:
                out.append(f"{name} ({LAYERS[mine]}) imports {dep} ({LAYERS[theirs]}), "
                           f"line {line}")
    return out


@pytest.fixture(scope="module")
def graph():
    return import_graph()


def test_every_module_has_a_layer(graph):
    edges, _ = graph
    assert {layer(m) for m in edges} <= set(LAYERS)


def test_no_circle_between_files(graph):
    edges, _ = graph
    circles = strongly_connected(edges)
    assert not circles, "import circles:\n" + "\n".join(
        " <-> ".join(c) + "\n    " + "; ".join(f"{a} -> {b} (line {edges[a][b]})" for a in c
                                               for b in c if b in edges[a]) for c in circles)


def test_no_module_imports_an_upper_layer(graph):
    edges, _ = graph
    bad = layer_violations(edges)
    assert not bad, "imports of an upper layer:\n" + "\n".join(bad)


def test_no_circle_between_packages(graph):
    """The first-level packages (io, power, table, ...) depend on each other without a circle
    either (the order docs/DESIGN.md draws)."""
    edges, _ = graph
    top = defaultdict(dict)
    for name, deps in edges.items():
        for dep, line in deps.items():
            a, b = name.split(".")[:2], dep.split(".")[:2]
            if a != b:
                top[".".join(a)].setdefault(".".join(b), f"{name} -> {dep}, line {line}")
    circles = strongly_connected(top)
    assert not circles, "package circles:\n" + "\n".join(
        f"{c}: " + "; ".join(top[a][b] for a in c for b in c if b in top[a]) for c in circles)


def test_design_lists_every_module_with_its_layer(graph):
    """docs/DESIGN.md has one line per module (its table): every module, no other, each with
    the layer this test gives it."""
    edges, _ = graph
    rows = dict(re.findall(r"^\| `([\w/]+\.py)` \| (\w+) \|", DESIGN.read_text(encoding="utf-8"),
                           re.M))
    modules_ = modules()
    expected = {}
    for name in edges:
        path = modules_[name].relative_to(ROOT).as_posix()
        expected[path] = layer(name, edges)
    missing = sorted(set(expected) - set(rows))
    assert not missing, f"docs/DESIGN.md's module table lacks {missing}"
    stale = sorted(set(rows) - set(expected))
    assert not stale, f"docs/DESIGN.md's module table lists modules that do not exist: {stale}"
    wrong = {p: (rows[p], expected[p]) for p in expected if rows[p] != expected[p]}
    assert not wrong, f"layer in docs/DESIGN.md vs the import rules: {wrong}"


def test_no_private_name_is_imported_from_another_package(graph):
    _, private_uses = graph
    assert not private_uses, "\n".join(private_uses)


def test_no_re_export_shim_is_left():
    """The deprecated shims of 0.1.0's development are gone (issue 25): their old paths are no
    module."""
    old = ("case", "aster", "operator", "restart", "statistics", "kernels", "kernel_reference",
           "dynamics.loop")
    assert not [m for m in old if f"fretwear.{m}" in modules()]


def test_the_private_rule_can_fail():
    mods = modules()
    assert private_owner("fretwear.geometry._shapes", "solve_monotone", mods) == \
        "fretwear.geometry"
    assert private_owner("fretwear.io.aster", "_read", mods) == "fretwear.io"
    assert private_owner("fretwear.table", "_x", mods) == "fretwear.table"
    assert private_owner("fretwear._lazy", "pandas", mods) == "fretwear"
    assert private_owner("fretwear.io.aster", "read_aster_table", mods) is None


def test_the_checks_can_fail():
    """The circle finder and the layer rule on a small hand-made graph (they must flag it)."""
    edges = {"fretwear.table.core": {"fretwear.table.restart": 1},
             "fretwear.table.restart": {"fretwear.table.core": 2},
             "fretwear.obstacle.update": {"fretwear.workflows.loop": 3},
             "fretwear.workflows.loop": {"fretwear.cli.run": 4},
             "fretwear.cli.run": {}}
    assert strongly_connected(edges) == [["fretwear.table.core", "fretwear.table.restart"]]
    assert layer_violations(edges) == [
        "fretwear.obstacle.update (physics) imports fretwear.workflows.loop (workflows), line 3",
        "fretwear.workflows.loop (workflows) imports fretwear.cli.run (cli), line 4"]


def test_graph_sees_imports_inside_functions_and_import_module(tmp_path):
    """Imports inside functions, relative imports and import_module literals are edges."""
    source = ("import importlib\n"
              "def f():\n"
              "    from .schema import COLUMNS\n"
              "    from fretwear.io import atomic\n"
              "    return importlib.import_module('fretwear.laws.models')\n")
    found = list(_imported_names(ast.parse(source), "fretwear.table.core",
                                 ROOT / "table" / "core.py"))
    assert [(t, a) for t, a, _ in found if t != "importlib"] == [
        ("fretwear.table.schema", "COLUMNS"), ("fretwear.io", "atomic"),
        ("fretwear.laws.models", None)]
