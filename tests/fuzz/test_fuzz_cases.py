"""Fuzz the case-file sections, the [obstacle] section and the POST_USURE facade (issue 15).

A valid case (or facade call) has one value replaced by a value of another type or an extreme
one (text, huge or negative integers, nan, inf, 1e300, booleans, lists, tables, dates), a key
removed, or an unknown key added. Only fretwear errors may come out, no example may last over
20 s, and a table that is returned has no NaN or negative depth unless a warning says why.
"""

from __future__ import annotations

import copy
import datetime
import functools

import numpy as np
import pandas as pd
from fuzzhelpers import examples, only_fretwear, small_history, workdir
from hypothesis import given
from hypothesis import strategies as st

from fretwear.io import write_history
from fretwear.obstacle import obstacle_from_config
from fretwear.workflows.aster import _F, POST_USURE
from fretwear.workflows.case_files import run_case

#: values of the wrong type or out of range, as TOML (or Python callers) can give them
ODD = st.one_of(
    st.text(max_size=12), st.integers(-10**30, 10**30), st.sampled_from([0, -1, 1, 2**63]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-300, 1e300, -1e300, 5e-324, float("nan"), float("inf")]),
    st.booleans(), st.dates(), st.just(datetime.datetime(2024, 1, 1, 12, 0)),
    st.lists(st.one_of(st.floats(), st.text(max_size=3), st.integers()), max_size=4),
    st.dictionaries(st.text(max_size=5), st.integers(), max_size=2))


@functools.lru_cache(maxsize=1)
def history_file() -> str:
    return str(write_history(small_history(n=80), workdir() / "case_history.csv"))


def base_cases() -> list[dict]:
    history = {"file": history_file(), "name": "N1"}
    return [
        {"history": history, "power": {"blocks": 2},
         "law": {"name": "ARCHARD", "materials": ["I600TT", "Z6C13"]},
         "geometry": {"contact_type": "TUBE_BAV", "mobile_radius_m": 9.525e-3,
                      "obstacle_width_m": 12.7e-3, "wall_thickness_m": 1.09e-3},
         "sectors": {"count": 4}, "time": {"instants": [0.5, 1, 2], "unit": "year"}},
        {"power": {"value_W": 0.01}, "law": {"name": "EDF_MZ", "mobile": {
            "COEF_USURE": 1e-13, "COEF_B": 1.2, "COEF_N": 2.44e-8, "COEF_S": 1.14e-16}},
         "geometry": {"contact_type": "TUBE_ALESAGE", "mobile_radius_m": 0.01,
                      "obstacle_radius_m": 0.0105, "obstacle_width_m": 0.02},
         "time": {"instants": [1.0, 10.0], "unit": "h"}},
        {"history": history, "law": {"name": "ARCHARD", "mobile": {"COEF_USURE": 30e-15},
                                     "obstacle": {"COEF_USURE": 17e-15}},
         "geometry": {"contact_type": "GRAPPE_1_ENCO", "mobile_radius_m": 4.85e-3,
                      "obstacle_radius_m": 5.25e-3, "obstacle_width_m": 20e-3},
         "sectors": {"count": 6}, "time": {"instants": [1000, 5000], "unit": "h"}},
    ]


@st.composite
def mutated_case(draw):
    case = copy.deepcopy(draw(st.sampled_from(base_cases())))
    for _ in range(draw(st.integers(1, 2))):
        section = draw(st.sampled_from(sorted(case)))
        action = draw(st.sampled_from(["value", "value", "value", "drop", "unknown", "section"]))
        if action == "section":
            case[section] = draw(ODD)
            continue
        if not isinstance(case[section], dict) or not case[section]:
            continue
        key = draw(st.sampled_from(sorted(case[section])))
        if action == "value":
            case[section][key] = draw(ODD)
        elif action == "drop":
            del case[section][key]
        else:
            case[section][draw(st.sampled_from(["extra", "Coef_Usure", "unit_s", ""]))] = \
                draw(ODD)
    return case


def _depths_explained(table: pd.DataFrame, warnings_text: list[str]) -> None:
    depths = [c for c in table.columns if c.startswith("depth")]
    values = table[depths].to_numpy(dtype=float)
    odd = np.isnan(values).any() or (values < 0).any()
    assert not odd or warnings_text, f"NaN or negative depth without a warning: {depths}"
    powers = [c for c in table.columns if "power" in c]
    assert np.isfinite(table[powers].to_numpy(dtype=float)).all() or warnings_text


@examples(60)
@given(case=mutated_case())
def test_case_sections_with_wrong_types(case):
    result, warned = only_fretwear(run_case, case)
    if result is not None:
        _depths_explained(result.table, result.warnings + [str(w.message) for w in warned])


@functools.lru_cache(maxsize=1)
def obstacle_base():
    case = base_cases()[2]
    table = run_case(case).table
    section = {"type": "circle", "wall_thickness_m": 0.47e-3, "perforation": 0.4,
               "shape": "smooth", "step_deg": 5.0, "resolution_deg": 1.0}
    return table, section, case["geometry"]


@examples(40)
@given(key=st.sampled_from(["type", "gap_m", "bore_radius_m", "plane_gap_m", "orientation_deg",
                            "closing_radius_m", "mobile_radius_m", "wall_thickness_m",
                            "width_m", "perforation", "shape", "instant", "step_deg",
                            "resolution_deg", "file", "table", "unknown_key"]),
       value=st.one_of(ODD, st.sampled_from([1e-9, 1e-6, 1e9, 0.0, -0.5, 720.0]),
                       st.sampled_from(["planes", "discrete", "circle"])),
       drop=st.booleans())
def test_obstacle_section_with_wrong_values(key, value, drop):
    table, section, geometry = obstacle_base()
    section = dict(section)
    if drop and key in section:
        del section[key]
    else:
        section[key] = value
    if section.get("type") == "planes":
        section.setdefault("plane_gap_m", 0.4e-3)

    def update():
        return obstacle_from_config(section, geometry=geometry, directory=str(workdir())
                                    ).update(table)

    result, _ = only_fretwear(update)
    if result is not None:
        assert np.isfinite(result.clearance_initial).all()


def _history():
    return small_history(n=40)


FACADE_BASE = dict(LOI_USURE="ARCHARD", CONTACT="TUBE_BAV", RAYON_MOBILE=0.0111,
                   LARGEUR_OBST=0.0127, COEF_INST=31_536_000.0, PUIS_USURE=0.012,
                   MOBILE=_F(COEF_USURE=1.2e-13), INST=(1.0, 2.0))
FACADE_KEYWORDS = ["LOI_USURE", "CONTACT", "RAYON_MOBILE", "LARGEUR_OBST", "COEF_INST",
                   "PUIS_USURE", "MOBILE", "OBSTACLE", "INST", "LIST_INST", "RESU_GENE",
                   "NB_BLOC", "INST_INIT", "INST_FIN", "SECTEUR", "ANGL_INCLI", "ANGL_ISTHME",
                   "ANGL_IMPACT", "RAYON_OBST", "MATER_USURE", "USURE_OBST", "ETAT_INIT",
                   "TUBE_NEUF", "NOEUD", "GROUP_NO", "INFO", "TITRE", "FNOR_MAXI", "COEF_USRE"]


@examples(60)
@given(changes=st.dictionaries(
    st.sampled_from(FACADE_KEYWORDS),
    st.one_of(ODD, st.just(None), st.builds(lambda v: _F(COEF_USURE=v), ODD),
              st.builds(lambda a, b: _F(ANGL_INIT=a, ANGL_FIN=b, COEF_USUR_MOBILE=1e-13),
                        ODD, ODD),
              st.builds(_history), st.just("OUI"), st.just("NON")),
    min_size=1, max_size=3))
def test_post_usure_keywords_with_wrong_values(changes):
    kw = dict(FACADE_BASE)
    kw.update(changes)
    kw = {k: v for k, v in kw.items() if v is not None}
    table, warned = only_fretwear(POST_USURE, **kw)
    if table is not None:
        depths = [c for c in table.columns if c.startswith("P_USUR")]
        values = table[depths].to_numpy(dtype=float)
        odd = np.isnan(values).any() or (values < 0).any()
        assert not odd or warned or table.attrs.get("global_depth"), depths


def dynamics_base() -> dict:
    """The [dynamics] section of a small coupled-loop case (tests/dynamics/test_loop.py)."""
    return {
        "duration_s": 0.2, "time_step_s": 2e-5, "archive_step_s": 1e-4,
        "modes": {"frequencies_Hz": [30.0, 30.0], "damping_ratios": 0.02, "masses_kg": 0.5,
                  "shock_shapes": [[[1.0, 0.0], [0.0, 1.0]]],
                  "forcing_shapes": [[[1.0, 0.0], [0.0, 1.0]]]},
        "shocks": [{"name": "bore", "obstacle": "case", "normal_stiffness_N_per_m": 1e6,
                    "normal_damping_N_s_per_m": 20.0, "friction": 0.3,
                    "tangential_stiffness_N_per_m": 1e6}],
        "forces": [{"point": 0, "direction": "y", "kind": "harmonic", "amplitude": 12.0,
                    "frequency_Hz": 25.0}],
    }


@st.composite
def mutated_dynamics(draw):
    section = copy.deepcopy(dynamics_base())
    where = draw(st.sampled_from(["top", "modes", "shocks", "forces"]))
    target = (section if where == "top" else section["modes"] if where == "modes"
              else section[where][0])
    key = draw(st.sampled_from(sorted(target) + ["unknown"]))
    if draw(st.booleans()) and key in target:
        del target[key]
    else:
        target[key] = draw(ODD)
    return section


@examples(60)
@given(section=mutated_dynamics())
def test_dynamics_section_with_wrong_types(section):
    """The [dynamics] section is validated (no simulation is run here)."""
    from fretwear.dynamics.config import dynamics_from_config

    only_fretwear(dynamics_from_config, section, directory=str(workdir()))
