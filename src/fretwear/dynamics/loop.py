"""Deprecated: the coupled dynamics ↔ wear ↔ obstacle loop moved to
:mod:`fretwear.workflows.loop`."""

import warnings

from fretwear.workflows.loop import *  # noqa: F401,F403
from fretwear.workflows.loop import IterationResult, iterate_case, load_iterate_case  # noqa: F401

warnings.warn("fretwear.dynamics.loop is deprecated: import from fretwear.workflows.loop",
              DeprecationWarning, stacklevel=2)
