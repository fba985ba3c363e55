"""fretwear: fretting-wear analysis of impact-sliding contacts.

From the contact time histories of a transient dynamic computation (normal force, sliding
velocities, contact position), fretwear computes the wear power, applies a wear law (Archard,
KWU-EPRI, EDF-MZ), turns worn volumes into worn depths for eight contact geometries, splits it by
angular sectors, extrapolates over years of service, continues from an earlier state, and updates
the obstacle's clearance profile.

Everything is SI inside: m, m³, N, m/s, s, W, Pa⁻¹. User angles are in degrees.
"""

from __future__ import annotations

import importlib
from typing import Any

from fretwear._version import __version__  # noqa: F401
from fretwear.errors import (  # noqa: F401
    FretwearError,
    FretwearWarning,
    HistoryError,
    InputError,
)
from fretwear.history import ContactHistory  # noqa: F401

# Public names resolved lazily from their modules (keeps `import fretwear` fast).
_LAZY: dict[str, str] = {
    "read_history": "fretwear.io",
    "write_history": "fretwear.io",
    "iter_history_chunks": "fretwear.io",
    "read_aster_table": "fretwear.io.aster",
    "write_aster_table": "fretwear.io.aster",
    "power": "fretwear.power",
    "io": "fretwear.io",
    "wear_power": "fretwear.power",
    "PowerResult": "fretwear.power",
    "PowerAccumulator": "fretwear.power",
    "ContactStatistics": "fretwear.power",
    "contact_statistics": "fretwear.power",
    "laws": "fretwear.laws",
    "WEAR_LAWS": "fretwear.laws",
    "WearLaw": "fretwear.laws",
    "archard": "fretwear.laws",
    "kwu_epri": "fretwear.laws",
    "edf_mz": "fretwear.laws",
    "edf_mz_equivalent_time": "fretwear.laws",
    "kwu_epri_statistics": "fretwear.laws",
    "KwuEpriStatistics": "fretwear.laws",
    "KwuEpriAccumulator": "fretwear.laws",
    "kwu_epri_statistics_from_chunks": "fretwear.laws",
    "get_law": "fretwear.laws",
    "database": "fretwear.database",
    "load_database": "fretwear.database",
    "geometry": "fretwear.geometry",
    "contact_geometry": "fretwear.geometry",
    "CONTACT_TYPES": "fretwear.geometry",
    "sector_depth_mobile": "fretwear.geometry",
    "sector_depth_obstacle": "fretwear.geometry",
    "table": "fretwear.table",
    "wear_table": "fretwear.table",
    "WearCase": "fretwear.table",
    "wear_table_from_case": "fretwear.table",
    "write_wear_table": "fretwear.table",
    "to_aster_names": "fretwear.table",
    "from_aster_names": "fretwear.table",
    "replace_tube": "fretwear.table",
    "initial_state": "fretwear.table",
    "read_wear_table": "fretwear.table",
    "workflows": "fretwear.workflows",
    "case_files": "fretwear.workflows.case_files",
    "run_case": "fretwear.workflows.case_files",
    "load_case": "fretwear.workflows.case_files",
    "CaseResult": "fretwear.workflows.case_files",
    "POST_USURE": "fretwear.workflows.aster",
    "obstacle": "fretwear.obstacle",
    "update_obstacle": "fretwear.obstacle",
    "update_obstacle_from_table": "fretwear.obstacle",
    "load_obstacle_profile": "fretwear.obstacle",
    "obstacle_from_config": "fretwear.obstacle",
    "dynamics": "fretwear.dynamics",
    "simulate": "fretwear.dynamics",
    "ModalModel": "fretwear.dynamics",
    "Shock": "fretwear.dynamics",
    "uniform_beam_modes": "fretwear.dynamics",
    "NodalForce": "fretwear.dynamics",
    "BaseAcceleration": "fretwear.dynamics",
    "Signal": "fretwear.dynamics",
    "iterate_case": "fretwear.workflows.loop",
    "IterationResult": "fretwear.workflows.loop",
    "uncertainty": "fretwear.uncertainty",
    "monte_carlo": "fretwear.uncertainty",
    "calibrate": "fretwear.uncertainty",
    "LogNormal": "fretwear.uncertainty",
    "report": "fretwear.report",
}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'fretwear' has no attribute {name!r}")
    mod = importlib.import_module(module)
    return mod if module.endswith("." + name) else getattr(mod, name)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
