"""Wear laws (theory §4): Archard, KWU-EPRI, EDF-MZ, their registry and the KWU-EPRI statistics.

=================== ====================================================================
``archard``         V = K·P·t
``kwu_epri``        V = (k_r·w/w_r)·P·t
``edf_mz``          V = ((A·P^b − S)/n)·(1 − e^(−n·t)) + S·t
``WEAR_LAWS``       registry of :class:`WearLaw` keyed by Code_Aster names
``kwu_epri_statistics`` the 5×5 class statistics and the wear-intensity factor w
=================== ====================================================================

SI units: power [W], duration [s], volume [m³], Archard coefficients [Pa⁻¹].
"""

from fretwear.laws.kwu_history import kwu_epri_statistics, kwu_epri_statistics_from_chunks
from fretwear.laws.kwu_statistics import (
    IMPACT_MASK,
    N_CLASSES,
    SLIDING_MASK,
    KwuEpriAccumulator,
    KwuEpriStatistics,
    force_classes,
    speed_classes,
)
from fretwear.laws.kwu_stream import KwuEpriMaxima
from fretwear.laws.models import (
    EDF_MZ_DEFAULTS,
    archard,
    edf_mz,
    edf_mz_equivalent_time,
    edf_mz_rate,
    kwu_epri,
    linear_equivalent_time,
)
from fretwear.laws.registry import WEAR_LAWS, WearLaw, get_law

__all__ = [
    "EDF_MZ_DEFAULTS", "IMPACT_MASK", "N_CLASSES", "SLIDING_MASK", "WEAR_LAWS",
    "KwuEpriAccumulator", "KwuEpriMaxima", "KwuEpriStatistics", "WearLaw", "archard", "edf_mz",
    "edf_mz_equivalent_time", "edf_mz_rate", "force_classes", "get_law", "kwu_epri",
    "kwu_epri_statistics", "kwu_epri_statistics_from_chunks", "linear_equivalent_time",
    "speed_classes",
]
