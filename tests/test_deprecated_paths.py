"""The old import paths keep working as thin re-export shims that warn (issue 10)."""

from __future__ import annotations

import importlib
import sys

import pytest

# old module -> (a name it exported, the new home of that name)
SHIMS = {
    "fretwear.operator": ("wear_table", "fretwear.table"),
    "fretwear.restart": ("replace_tube", "fretwear.table"),
    "fretwear.case": ("run_case", "fretwear.workflows.case_files"),
    "fretwear.aster": ("POST_USURE", "fretwear.workflows.aster"),
    "fretwear.statistics": ("contact_statistics", "fretwear.power"),
    "fretwear.kernels": ("fused_numba", "fretwear.power.kernels"),
    "fretwear.kernel_reference": ("fused_numpy", "fretwear.power.reference"),
    "fretwear.dynamics.loop": ("iterate_case", "fretwear.workflows.loop"),
}


@pytest.mark.parametrize("old", sorted(SHIMS))
def test_old_path_warns_and_re_exports(old):
    name, new = SHIMS[old]
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=new.replace(".", r"\.")):
        module = importlib.import_module(old)
    assert getattr(module, name) is getattr(importlib.import_module(new), name)


@pytest.mark.parametrize("name", ["power", "io", "table", "workflows", "case_files"])
def test_subpackages_resolve_as_attributes(name):
    import fretwear

    assert getattr(fretwear, name).__name__.startswith("fretwear.")
