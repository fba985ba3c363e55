"""Wear power of a contact history: total, per block and per angular sector, and the contact
statistics computed in the same pass (theory §2-§3).

Modules:

- :mod:`fretwear.power.core`: :func:`wear_power`, :class:`PowerAccumulator` (the mergeable
  streaming reduction), :func:`contact_statistics`;
- :mod:`fretwear.power.result`: :class:`PowerResult` (total, block and sector powers, statistics,
  confidence intervals);
- :mod:`fretwear.power.confidence`: confidence intervals of the power (batch means);
- :mod:`fretwear.power.statistics`: :class:`ContactStatistics` and the impact bookkeeping;
- :mod:`fretwear.power.impacts`: :func:`impacts` (every impact of a window, one row each) and
  :func:`channel_statistics` (mean, std, RMS, extrema of a channel), POST_DYNA_MODA_T-like;
- :mod:`fretwear.power.kernels`: the fused compiled kernel (numba, with the numpy fallback);
- :mod:`fretwear.power.reference`: the plain numpy reference kernel.
"""

from fretwear.history import DEFAULT_CHUNK_SIZE
from fretwear.power.contact import contact_statistics
from fretwear.power.core import PowerAccumulator, wear_power
from fretwear.power.impacts import IMPACT_UNITS, channel_statistics, impacts
from fretwear.power.result import PowerResult
from fretwear.power.statistics import STATISTICS_UNITS, ContactStatistics

__all__ = [
    "DEFAULT_CHUNK_SIZE",
    "IMPACT_UNITS",
    "STATISTICS_UNITS",
    "ContactStatistics",
    "PowerAccumulator",
    "PowerResult",
    "channel_statistics",
    "contact_statistics",
    "impacts",
    "wear_power",
]
