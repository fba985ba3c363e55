"""numba's ``njit`` when numba is installed (extra ``fast``), else a no-op decorator.

Without numba the decorated functions run as plain Python (slow, same results) and, like
numba's dispatchers, expose the original function as ``py_func``.
"""

from __future__ import annotations

try:  # numba is an optional dependency ("fast" extra)
    from numba import njit

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False

    def njit(*args, **kwargs):
        def wrap(func):
            func.py_func = func
            return func
        if args and callable(args[0]):
            return wrap(args[0])
        return wrap

__all__ = ["HAVE_NUMBA", "njit"]
