"""Deprecated: restarts moved to :mod:`fretwear.table` (``initial_state``, ``replace_tube``,
``read_wear_table``)."""

import warnings

from fretwear.table.files import read_wear_table  # noqa: F401
from fretwear.table.restart import InitialState, initial_state, replace_tube  # noqa: F401

warnings.warn("fretwear.restart is deprecated: import from fretwear.table", DeprecationWarning,
              stacklevel=2)
