"""Imported or compiled at first use: pandas, and the numba kernels of the geometry and laws.

``from fretwear._lazy import pandas as pd`` gives a stand-in module: the first attribute asked of
it (``pd.DataFrame``, ``pd.read_csv`` ...) imports pandas and caches that attribute, and every
later one comes from pandas itself. Nothing else changes: ``isinstance(x, pd.DataFrame)`` and
every call behave as with ``import pandas as pd``. Importing pandas takes about 0.2 s (on top of
pyarrow); ``fretwear power FILE.parquet`` streams a Parquet file with pyarrow and never needs it.

:func:`compiled_when_used` does the same for numba kernels: plain Python functions compiled
(or loaded from numba's cache) at their first use, numba itself imported only then.

Examples
--------
>>> from fretwear._lazy import pandas as pd
>>> pd.DataFrame({"a": [1.0]})["a"].tolist()
[1.0]
"""

from __future__ import annotations

import importlib
import types
from collections.abc import Callable
from typing import Any


class LazyModule(types.ModuleType):
    """A module imported at the first attribute asked of it (that attribute is then cached)."""

    def __getattr__(self, attribute: str) -> Any:
        if attribute.startswith("__") and attribute.endswith("__"):
            raise AttributeError(attribute)  # copy, pickle and inspect probe these: not a use
        value = getattr(importlib.import_module(self.__name__), attribute)
        setattr(self, attribute, value)
        return value

    def __repr__(self) -> str:
        return f"<lazily imported module {self.__name__!r}>"


#: pandas, imported at its first use.
pandas = LazyModule("pandas")


def compiled_when_used(*functions: Callable) -> Callable[[], tuple[Callable, ...] | None]:
    """A getter of ``functions`` compiled by numba (``cache=True``, ``error_model="numpy"``):
    its first call imports numba and compiles them (or loads them from numba's cache), every
    call returns the same tuple; None without numba (the callers then take their numpy path).

    Examples
    --------
    >>> from fretwear.laws.models import _psi2_series, _psi2_series_kernel
    >>> kernels = _psi2_series_kernel  # compiled_when_used(_psi2_series)
    >>> kernels() is kernels() and (kernels() is None or kernels()[0].py_func is _psi2_series)
    True
    """
    made: list[tuple[Callable, ...] | None] = []

    def kernels() -> tuple[Callable, ...] | None:
        if not made:
            from fretwear._numba import HAVE_NUMBA, njit

            made.append(tuple(njit(cache=True, error_model="numpy")(f) for f in functions)
                        if HAVE_NUMBA else None)
        return made[0]

    return kernels
