"""pandas imported at its first use, so that a command that never builds a table starts faster.

``from fretwear._lazy import pandas as pd`` gives a stand-in module: the first attribute asked of
it (``pd.DataFrame``, ``pd.read_csv`` ...) imports pandas and caches that attribute, and every
later one comes from pandas itself. Nothing else changes: ``isinstance(x, pd.DataFrame)`` and
every call behave as with ``import pandas as pd``. Importing pandas takes about 0.2 s (on top of
pyarrow); ``fretwear power FILE.parquet`` streams a Parquet file with pyarrow and never needs it.

Examples
--------
>>> from fretwear._lazy import pandas as pd
>>> pd.DataFrame({"a": [1.0]})["a"].tolist()
[1.0]
"""

from __future__ import annotations

import importlib
import types
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
