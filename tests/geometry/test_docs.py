"""docs/geometry.md and its figure script stay in step with CONTACT_TYPES (issue 4: a figure,
drawn by a script in docs/, for each contact type).

Source: the files themselves; the script is parsed (ast), not run, so that the test stays fast
and matplotlib-free.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from fretwear.geometry import CONTACT_TYPES

DOCS = Path(__file__).resolve().parents[2] / "docs"
SCRIPT = DOCS / "figures" / "make_figures.py"
PAGE = DOCS / "geometry.md"


def _script_figures() -> tuple[set[str], set[str]]:
    """(keys of the FIGURES dict, PNG names passed to _save) of the figure script."""
    tree = ast.parse(SCRIPT.read_text(encoding="utf-8"))
    keys: set[str] = set()
    pngs: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "FIGURES" for t in node.targets):
            keys = {k.value for k in node.value.keys}
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "_save":
            pngs.add(node.args[1].value)
    return keys, pngs


def test_every_contact_type_has_a_figure_in_the_script_and_the_page():
    keys, pngs = _script_figures()
    assert set(CONTACT_TYPES) <= keys
    text = PAGE.read_text(encoding="utf-8")
    shown = set(re.findall(r"!\[[^\]]*\]\(figures/([^)]+\.png)\)", text))
    assert shown == pngs  # every drawn figure is shown, every shown figure is drawn
    for png in shown:
        assert (DOCS / "figures" / png).is_file(), png
    for name in CONTACT_TYPES:
        section = re.search(rf"^## [^\n]*{name}[^\n]*\n(.*?)(?=^## )", text, re.S | re.M)
        assert section, f"no section for {name}"
        assert "figures/" in section.group(1), f"no figure in the {name} section"
        assert "Code_Aster" in section.group(1), f"no Code_Aster difference for {name}"
        assert re.search(r"[Tt]ypos? of R7\.20\.01 resolved", section.group(1)), \
            f"no resolved typos of Code_Aster R7.20.01 for {name}"
