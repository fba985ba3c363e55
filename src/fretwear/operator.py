"""Deprecated: the wear table moved to :mod:`fretwear.table` (``wear_table``, ``COLUMNS``,
``to_aster_names``, ``from_aster_names``)."""

import warnings

from fretwear.table.core import *  # noqa: F401,F403
from fretwear.table.core import law_coefficients, wear_table  # noqa: F401
from fretwear.table.schema import (  # noqa: F401
    _TIME_TOL,
    COLUMNS,
    GLOBAL_COLUMNS,
    SECTOR_COLUMNS,
    from_aster_names,
    to_aster_names,
)

warnings.warn("fretwear.operator is deprecated: import from fretwear.table", DeprecationWarning,
              stacklevel=2)
