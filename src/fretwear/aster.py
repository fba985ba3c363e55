"""Deprecated: the Code_Aster facade moved to :mod:`fretwear.workflows.aster`."""

import warnings

from fretwear.workflows.aster import *  # noqa: F401,F403
from fretwear.workflows.aster import _F, POST_USURE  # noqa: F401

warnings.warn("fretwear.aster is deprecated: import from fretwear.workflows.aster",
              DeprecationWarning, stacklevel=2)
