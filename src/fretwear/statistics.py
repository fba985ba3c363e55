"""Deprecated: moved to :mod:`fretwear.power.statistics` (and ``contact_statistics`` to
:mod:`fretwear.power`)."""

import warnings

from fretwear.power import contact_statistics  # noqa: F401
from fretwear.power.statistics import *  # noqa: F401,F403
from fretwear.power.statistics import ContactStatistics, merge_groups  # noqa: F401

warnings.warn("fretwear.statistics is deprecated: import from fretwear.power "
              "(contact_statistics, ContactStatistics) or fretwear.power.statistics",
              DeprecationWarning, stacklevel=2)
