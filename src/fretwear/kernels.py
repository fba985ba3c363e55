"""Deprecated: moved to :mod:`fretwear.power.kernels`."""

import warnings

from fretwear.power.kernels import *  # noqa: F401,F403

warnings.warn("fretwear.kernels is deprecated: import from fretwear.power.kernels",
              DeprecationWarning, stacklevel=2)
