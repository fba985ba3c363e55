"""Every fenced ```python snippet of README.md and docs/*.md runs as written.

The snippets of one file run in order in one namespace (a later snippet may use what an earlier
one made), in a temporary folder holding a copy of the shipped ``examples/`` (so the paths the
docs use, ``examples/data/...``, resolve as from the repository root, and nothing a snippet writes
lands in the repository). A snippet that must not run (a Code_Aster command file, a cluster
address) is marked by an HTML comment ``<!-- no-run -->`` (or ``<!-- no-run: reason -->``) on the
line just before its fence; markers are counted, so that they stay rare.
"""

from __future__ import annotations

import re
import shutil
import sys
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)
NO_RUN = re.compile(r"<!--\s*no-run\b[^>]*-->\s*\Z")
#: most snippets that may be marked no-run, all documents together
MAX_NO_RUN = 4


def collect(text: str) -> list[tuple[int, str, bool]]:
    """(line of the fence, code, runs) of every ```python block of a markdown text."""
    out = []
    for m in FENCE.finditer(text):
        before = text[:m.start()].rstrip("\n").splitlines()[-1:] or [""]
        out.append((text[:m.start()].count("\n") + 1, m.group(1),
                    not NO_RUN.search(before[0])))
    return out


def snippets(path: Path) -> list[tuple[int, str, bool]]:
    return collect(path.read_text(encoding="utf-8"))


def test_the_collector_finds_blocks_and_markers():
    text = ("intro\n```python\nx = 1\n```\n<!-- no-run: a cluster -->\n```python\nboom()\n```\n"
            "```sh\nls\n```\n")
    assert collect(text) == [(2, "x = 1\n", True), (6, "boom()\n", False)]


def test_no_run_markers_stay_rare():
    marked = [f"{p.name}:{line}" for p in DOCUMENTS for line, _, runs in snippets(p) if not runs]
    assert len(marked) <= MAX_NO_RUN, f"too many <!-- no-run --> snippets: {marked}"


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    shutil.copytree(ROOT / "examples", tmp_path / "examples",
                    ignore=shutil.ignore_patterns("__pycache__", "build", "iterate"))
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("document", [p for p in DOCUMENTS if snippets(p)],
                         ids=lambda p: p.relative_to(ROOT).as_posix())
def test_snippets_run(document, workdir):
    namespace: dict = {"__name__": "__docs__"}
    ran = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the docs show results; warnings are tested elsewhere
        for line, code, runs in snippets(document):
            if not runs:
                continue
            where = f"{document.relative_to(ROOT)}:{line}"
            try:
                exec(compile(code, where, "exec"), namespace)  # noqa: S102 - the docs' own code
            except Exception as exc:  # noqa: BLE001 - say which snippet failed
                raise AssertionError(f"the snippet at {where} fails: "
                                     f"{type(exc).__name__}: {exc}") from exc
            ran += 1
    assert ran > 0
    plt = sys.modules.get("matplotlib.pyplot")
    if plt is not None:
        plt.close("all")
