"""Workflows above the physics: TOML case files (:mod:`~fretwear.workflows.case_files`), the
coupled dynamics ↔ wear ↔ obstacle loop (:mod:`~fretwear.workflows.loop`) and the Code_Aster
facade (:mod:`~fretwear.workflows.aster`: ``POST_USURE``, ``_F``).

The submodules are imported on first use, so ``import fretwear.workflows`` stays light.
"""

from __future__ import annotations

import importlib
from typing import Any

_SUBMODULES = ("case_files", "loop", "aster")


def __getattr__(name: str) -> Any:
    if name in _SUBMODULES:
        return importlib.import_module(f"fretwear.workflows.{name}")
    raise AttributeError(f"module 'fretwear.workflows' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_SUBMODULES))
