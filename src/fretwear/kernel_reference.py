"""Deprecated: moved to :mod:`fretwear.power.reference`."""

import warnings

from fretwear.power.reference import *  # noqa: F401,F403

warnings.warn("fretwear.kernel_reference is deprecated: import from fretwear.power.reference",
              DeprecationWarning, stacklevel=2)
