"""numba's ``njit`` when numba is installed (extra ``fast``), else a no-op decorator.

Without numba the decorated functions run as plain Python (slow, same results) and, like
numba's dispatchers, expose the original function as ``py_func``.
"""

from __future__ import annotations

from fretwear._optional import optional

_numba = optional("numba")  # the "fast" extra
HAVE_NUMBA = _numba is not None

if HAVE_NUMBA:
    njit = _numba.njit
else:  # pragma: no cover - exercised only without numba

    def njit(*args, **kwargs):
        def wrap(func):
            func.py_func = func
            return func
        if args and callable(args[0]):
            return wrap(args[0])
        return wrap

__all__ = ["HAVE_NUMBA", "njit"]
