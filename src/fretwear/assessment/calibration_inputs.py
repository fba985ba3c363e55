"""The inputs of a bundle's calibration (:func:`fretwear.assessment.calibration.calibrate_bundle`):
each contact's depth model, the inspections resolved to contacts, the groups and each
contact's scatter [-], and the check that the power's spread is a factor on the wear.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Mapping

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import InputError, RangeWarning
from fretwear.table.depth import DepthModel
from fretwear.table.depth_build import models_from_table

__all__ = ["check_power_proportional", "contact_scatter", "group_index", "prediction_models",
           "resolve_inspections", "support_type"]


def prediction_models(predictions) -> dict[str, DepthModel]:
    """Each contact's global depth model from a mapping of contact to a DepthModel or a wear
    table (with its attrs)."""
    if not isinstance(predictions, Mapping) or not predictions:
        raise InputError("predictions must be a mapping of contact name to a DepthModel or a "
                         "wear table (with its attrs), e.g. bundle_predictions(OUT)[0]")
    out = {}
    for name, item in predictions.items():
        if isinstance(item, DepthModel):
            out[str(name)] = item
        elif isinstance(item, pd.DataFrame):
            out[str(name)] = models_from_table(item, name=str(name))["global"]
        else:
            raise InputError(f"prediction {name!r}: give a DepthModel or a wear table, got "
                             f"{type(item).__name__}")
    return out


def support_type(support: str) -> str:
    """The support type of a support name: its letters without the number ("AVB3" -> "AVB").

    >>> support_type("AVB3"), support_type("TSP 02"), support_type("")
    ('AVB', 'TSP', '')
    """
    return re.sub(r"[\s\d_\-]+$", "", str(support).strip())


def resolve_inspections(table: pd.DataFrame, contacts: list, identity) -> pd.DataFrame:
    """One row per (inspection, contact): a tube location without support covers its
    contacts; an unknown contact or location is an InputError naming the line."""
    index = {c: i for i, c in enumerate(contacts)}
    rows = []
    for r in table.to_dict("records"):
        if r["contact"]:
            if r["contact"] not in index:
                raise InputError(f"inspections line {r['line']}: unknown contact "
                                 f"{r['contact']!r} (the predictions have e.g. "
                                 f"{contacts[:3]})")
            rows.append({**r, "index": index[r["contact"]]})
            continue
        if identity is None:
            raise InputError(f"inspections line {r['line']}: a tube location needs the bundle's "
                             "identity table (contact, tube_row, tube_column, support)")
        hit = identity[(identity["tube_row"] == r["tube_row"])
                       & (identity["tube_column"] == r["tube_column"])]
        if r["support"]:
            hit = hit[hit["support"].astype(str) == r["support"]]
        hit = hit[hit["contact"].isin(index)]
        if hit.empty:
            raise InputError(f"inspections line {r['line']}: no contact at tube row "
                             f"{r['tube_row']:g}, column {r['tube_column']:g}"
                             + (f", support {r['support']!r}" if r["support"] else ""))
        if r["status"] == "sized" and len(hit) > 1:
            raise InputError(f"inspections line {r['line']}: a sized depth on a tube with "
                             f"{len(hit)} contacts; name the support")
        for c in hit["contact"]:
            rows.append({**r, "contact": c, "index": index[c]})
    return pd.DataFrame(rows)


def group_index(contacts, groups, identity) -> tuple[list, np.ndarray]:
    """The group names and each contact's group (None: one group, \"bundle\")."""
    if groups is None:
        return ["bundle"], np.zeros(len(contacts), int)
    if groups == "support type":
        if identity is None:
            raise InputError("groups='support type' needs the identity table (support)")
        support = dict(zip(identity["contact"], identity["support"].astype(str), strict=False))
        groups = {c: support_type(support.get(c, "")) or "other" for c in contacts}
    if not isinstance(groups, Mapping):
        raise InputError("groups must be None, 'support type' or a mapping contact -> group")
    names = sorted({str(groups.get(c, "other")) for c in contacts})
    return names, np.array([names.index(str(groups.get(c, "other"))) for c in contacts])


def contact_scatter(contacts, contact_sigma_ln: float, power_sigma_ln) -> np.ndarray:
    """Each contact's scatter about its group [-]: √(σ_c² + σ_P,i²), σ_P,i its power's
    log-spread (a float for every contact or a mapping of contact to float)."""
    if isinstance(power_sigma_ln, Mapping):
        sp = np.array([float(power_sigma_ln.get(c, 0.0)) for c in contacts])
    else:
        sp = np.full(len(contacts), float(power_sigma_ln or 0.0))
    if not (np.isfinite(sp) & (sp >= 0)).all():
        raise InputError("power_sigma_ln must be finite numbers >= 0 [-]")
    return np.sqrt(float(contact_sigma_ln) ** 2 + sp ** 2)


def check_power_proportional(models, contacts, scatter_power) -> None:
    """σ_P enters as a factor only where the worn volume is proportional to the power (checked
    once per law, coefficients and geometry: the property of the law, not of the power)."""
    seen = set()
    for i, c in enumerate(contacts):
        if scatter_power[i] <= 0:
            continue
        m = models[c]
        if not m.power:  # no wear: a factor on it changes nothing
            continue
        key = (id(m.law), id(m.geometry), repr(m.coefficients_mobile),
               repr(m.coefficients_obstacle), len(m.powers), m.sector_arc is None)
        if key in seen:
            continue
        seen.add(key)
        t = m.time_scale
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RangeWarning)
            v2 = m.volumes(t, power=2.0 * m.power)[0]
            v1 = m.volumes(t, factor=2.0)[0]
        if not np.allclose(v1, v2, rtol=1e-9):
            raise InputError(f"contact {c!r}: its {m.law.name} volume is not proportional to "
                             "the power, so the power's spread is not a factor on it; give "
                             "power_sigma_ln=0 for it")
