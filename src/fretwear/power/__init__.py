"""Wear power of a contact history: total, per block and per angular sector, and the contact
statistics computed in the same pass (theory §2-§3).

Modules:

- :mod:`fretwear.power.core`: :func:`wear_power`, :class:`PowerAccumulator` (the mergeable
  streaming reduction), :class:`PowerResult`, :func:`contact_statistics`;
- :mod:`fretwear.power.statistics`: :class:`ContactStatistics` and the impact bookkeeping;
- :mod:`fretwear.power.kernels`: the fused compiled kernel (numba, with the numpy fallback);
- :mod:`fretwear.power.reference`: the plain numpy reference kernel.
"""

from fretwear.history import DEFAULT_CHUNK_SIZE
from fretwear.power.core import (
    PowerAccumulator,
    PowerResult,
    contact_statistics,
    wear_power,
)
from fretwear.power.statistics import STATISTICS_UNITS, ContactStatistics

__all__ = [
    "DEFAULT_CHUNK_SIZE",
    "STATISTICS_UNITS",
    "ContactStatistics",
    "PowerAccumulator",
    "PowerResult",
    "contact_statistics",
    "wear_power",
]
