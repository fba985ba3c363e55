"""Optional heavy dependencies, imported when first needed and never at the top of a module.

fretwear's core needs numpy, scipy, pandas, click and rich only. Everything else is an extra of
``pyproject.toml``; :data:`EXTRAS` maps each optional top-level module to the extra that installs
it. :func:`require` imports one or raises :class:`~fretwear.errors.MissingDependencyError`
naming the extra (never a bare ``ModuleNotFoundError``); :func:`optional` returns ``None``
instead, for code with a fallback (numba → plain Python, pyarrow's CSV writer → pandas). Any
layer may import this module.
"""

from __future__ import annotations

import importlib
from types import ModuleType

from fretwear.errors import MissingDependencyError

__all__ = ["EXTRAS", "extra_of", "optional", "require"]

#: optional top-level module -> extra of ``pyproject.toml`` that installs it.
EXTRAS: dict[str, str] = {
    "numba": "fast",
    "pyarrow": "formats",
    "h5py": "formats",
    "netCDF4": "formats",
    "matplotlib": "plot",
    "dask": "bundle",
    "distributed": "bundle",
    "xarray": "bundle",
    "zarr": "bundle",
    "SALib": "uncertainty",
    "jinja2": "report",
    "openturns": "openturns",
}


def extra_of(module: str) -> str:
    """The extra that installs ``module`` (a dotted name; its top-level package counts).

    Examples
    --------
    >>> extra_of("pyarrow.parquet")
    'formats'
    """
    top = module.partition(".")[0]
    try:
        return EXTRAS[top]
    except KeyError:
        raise KeyError(f"{module!r} is not an optional dependency of fretwear; "
                       f"add it to fretwear._optional.EXTRAS (known: {', '.join(EXTRAS)})"
                       ) from None


def _missing(exc: ImportError, module: str) -> bool:
    """True when ``exc`` says ``module`` itself (or a parent package) is absent, not broken."""
    name = getattr(exc, "name", None) or ""
    return isinstance(exc, ModuleNotFoundError) and (
        module == name or module.startswith(name + "."))


def require(module: str, extra: str | None = None, purpose: str | None = None) -> ModuleType:
    """Import an optional dependency, or raise an error that names the extra to install.

    Parameters
    ----------
    module : str
        Dotted module name (``"pyarrow.parquet"``, ``"matplotlib.pyplot"``).
    extra : str, optional
        The extra that installs it; default from :data:`EXTRAS`.
    purpose : str, optional
        What needs it, for the message (``"reading Parquet"``).

    Returns
    -------
    module

    Raises
    ------
    MissingDependencyError
        The package is not installed (``pip install 'fretwear[<extra>]'``), or it is installed
        but fails to import (the cause is given). Also an ``ImportError``.

    Examples
    --------
    >>> require("pyarrow.parquet", "formats", "reading Parquet").__name__
    'pyarrow.parquet'
    >>> import sys
    >>> saved, sys.modules["h5py"] = sys.modules.get("h5py"), None  # as if not installed
    >>> try:
    ...     require("h5py", purpose="reading HDF5")
    ... except ImportError as exc:
    ...     print(exc)
    reading HDF5 needs the optional package 'h5py': pip install 'fretwear[formats]'
    >>> if saved is None: del sys.modules["h5py"]
    ... else: sys.modules["h5py"] = saved
    """
    extra = extra or extra_of(module)
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        what = purpose or "this"
        if _missing(exc, module):
            raise MissingDependencyError(
                f"{what} needs the optional package {module!r}: "
                f"pip install 'fretwear[{extra}]'") from None
        raise MissingDependencyError(
            f"{what} needs the optional package {module!r}, which is installed but cannot be "
            f"imported ({type(exc).__name__}: {exc}); reinstall it: "
            f"pip install --force-reinstall 'fretwear[{extra}]'") from exc


def optional(module: str) -> ModuleType | None:
    """Import an optional dependency that has a fallback: the module, or ``None`` if absent.

    Only absence gives ``None``: a package that is installed but broken still raises (as
    :func:`require`), so a broken install is not silently replaced by the slow fallback.

    Examples
    --------
    >>> optional("numba") is None or optional("numba").__name__ == "numba"
    True
    """
    extra_of(module)  # only known optional modules
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        if _missing(exc, module):
            return None
        return require(module)
