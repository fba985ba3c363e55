"""numba's ``njit`` when numba is installed (extra ``fast``), else a no-op decorator.

Without numba the decorated functions run as plain Python (slow, same results) and, like
numba's dispatchers, expose the original function as ``py_func``.

``cache=True`` asks numba to keep the machine code on disk, beside the module
(``__pycache__``) or, when that folder is read-only, in the user's cache folder. When neither
can be written (a read-only installation run by a user without a home, as a batch account on a
cluster may be), numba refuses the decorator itself (``RuntimeError: cannot cache function
...: no locator available``), which would make every module holding a kernel unimportable.
The function is then compiled without a disk cache: in each process at its first call, the
same machine code. ``NUMBA_CACHE_DIR`` names a writable folder to keep the cache anyway.
"""

from __future__ import annotations

from fretwear._optional import optional

_numba = optional("numba")  # the "fast" extra
HAVE_NUMBA = _numba is not None

if HAVE_NUMBA:

    def njit(*args, **kwargs):
        """``numba.njit(**kwargs)``; with ``cache=True``, without the disk cache when numba
        finds nowhere to write it (see the module docstring)."""
        if args or not kwargs.get("cache"):
            return _numba.njit(*args, **kwargs)

        def decorate(func):
            try:
                return _numba.njit(**kwargs)(func)
            except RuntimeError as exc:
                if "cannot cache" not in str(exc):
                    raise
                return _numba.njit(**{**kwargs, "cache": False})(func)

        return decorate
else:  # pragma: no cover - exercised only without numba

    def njit(*args, **kwargs):
        def wrap(func):
            func.py_func = func
            return func
        if args and callable(args[0]):
            return wrap(args[0])
        return wrap

__all__ = ["HAVE_NUMBA", "njit"]
