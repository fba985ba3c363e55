"""The ``[dynamics]`` section of a case file: modal model, shocks and excitations from TOML.

Keys carry their unit in their name, like the rest of the case file. Every key is listed in
:data:`DYNAMICS_KEYS` (the source of ``fretwear iterate --help`` and ``docs/dynamics.md``);
an unknown key is an error naming it and the closest valid one. Example::

    [dynamics]
    duration_s = 2.0
    archive_step_s = 1e-4
    [dynamics.beam]
    young_modulus_Pa = 2.0e11
    second_moment_m4 = 1.6e-9
    mass_per_length_kg_per_m = 0.45
    length_m = 1.0
    modes = 4
    ends = ["clamped", "pinned"]
    damping_ratio = 0.02
    [[dynamics.shocks]]
    name = "AVB"
    position_m = 0.5
    obstacle = "case"                  # the [obstacle] section's new obstacle
    normal_stiffness_N_per_m = 2e6
    friction = 0.3
    tangential_stiffness_N_per_m = 2e6
    [[dynamics.forces]]
    position_m = 0.3
    direction = "y"
    kind = "random"
    psd_frequencies_Hz = [5, 80]
    psd = [0.02, 0.02]                 # [N²/Hz]
    seed = 1
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from fretwear.dynamics.excitation import BaseAcceleration, NodalForce, Signal
from fretwear.dynamics.modal import ModalModel, uniform_beam_modes
from fretwear.dynamics.shocks import Shock
from fretwear.errors import InputError, KeywordError
from fretwear.keys import check_keys
from fretwear.obstacle.discret_file import read_discret

_NUM = (int, float)
_SIGNAL_KEYS = {
    "kind": (str, "harmonic, table or random"),
    "amplitude": (_NUM, "harmonic amplitude [N] (force) or [m/s²] (base)"),
    "frequency_Hz": (_NUM, "harmonic frequency [Hz]"),
    "phase_deg": (_NUM, "harmonic phase [deg]"),
    "times_s": (list, "table: instants [s]"),
    "values": (list, "table: values [N] or [m/s²]"),
    "psd_frequencies_Hz": (list, "random: frequencies of the one-sided PSD [Hz]"),
    "psd": (list, "random: one-sided PSD [N²/Hz] or [(m/s²)²/Hz]"),
    "seed": (int, "random: seed (same seed, same signal)"),
    "sample_rate_Hz": (_NUM, "random: samples per second [Hz] (default 8 × highest PSD "
                             "frequency)"),
    "scale": (_NUM, "multiplies the signal [-] (default 1)"),
}
#: section -> key -> (type, description with unit)
DYNAMICS_KEYS: dict[str, dict[str, tuple[Any, str]]] = {
    "dynamics": {
        "duration_s": (_NUM, "simulated time per computation [s] (required)"),
        "time_step_s": (_NUM, "fine time step [s] (default: safety × stability limit)"),
        "archive_step_s": (_NUM, "sampling of the contact histories [s] (default 1e-4 s, "
                                 "or the time step if larger)"),
        "adaptive": (bool, "coarse steps in free flight, fine near contact (default false)"),
        "safety": (_NUM, "fraction of the stability limits for default steps (default 0.5)"),
        "initial_displacement": (list, "modal coordinates at t = 0 [-] (default 0)"),
        "initial_velocity": (list, "modal velocities at t = 0 [1/s] (default 0)"),
        "chunk_size": (int, "archive samples per chunk streamed to disk (default 200000)"),
    },
    "dynamics.beam": {
        "young_modulus_Pa": (_NUM, "Young's modulus E [Pa]"),
        "second_moment_m4": (_NUM, "second moment of area I [m⁴]"),
        "mass_per_length_kg_per_m": (_NUM, "mass per length ρA incl. fluid and added mass "
                                           "[kg/m]"),
        "length_m": (_NUM, "length L [m]"),
        "modes": (int, "bending modes per plane (the model has twice as many: y and z)"),
        "ends": (list, "end conditions at x = 0 and L: pinned, clamped, free"),
        "supports_m": (list, "intermediate pinned supports [m] (FE eigen-solve)"),
        "damping_ratio": (_NUM, "modal damping ratio [-] (default 0.01)"),
        "method": (str, "auto, analytic or fe (default auto)"),
    },
    "dynamics.modes": {
        "frequencies_Hz": (list, "natural frequencies [Hz]"),
        "damping_ratios": ((list, int, float), "modal damping ratios [-]"),
        "masses_kg": ((list, int, float), "modal masses [kg]"),
        "shock_shapes": (list, "per shock point: [[y components], [z components]] (optionally "
                               "a third list, axial x) of every mode [-]"),
        "forcing_shapes": (list, "per forcing point, same layout [-]"),
        "participation_kg": (list, "[[Γ_y per mode], [Γ_z per mode]] for base excitation [kg]"),
        "shock_names": (list, "names of the shock points"),
    },
    "dynamics.shocks": {
        "name": (str, "name of the shock (its history)"),
        "position_m": (_NUM, "beam: abscissa of the shock point [m]"),
        "point": ((int, str), "modes: index or name of the shock point"),
        "obstacle": (str, "plane, two_planes, circle, profile, or case (the clearance "
                          "figure of the [obstacle] section's new obstacle as a profile, then "
                          "the worn one)"),
        "gap_m": (_NUM, "clearance [m] (plane, two_planes, circle)"),
        "angle_deg": (_NUM, "plane normal / preload direction in the y-z plane [deg]"),
        "profile_file": (str, "profile: DISCRET table of the clearance (THETA [deg], JEU [m])"),
        "origin_m": (list, "obstacle centre relative to the mobile at rest, [y, z] [m]"),
        "normal_stiffness_N_per_m": (_NUM, "penalty normal stiffness [N/m] (RIGI_NOR)"),
        "normal_damping_N_s_per_m": (_NUM, "normal damping [N·s/m] (AMOR_NOR)"),
        "tangential_stiffness_N_per_m": (_NUM, "stick stiffness [N/m] (RIGI_TAN)"),
        "tangential_damping_N_s_per_m": (_NUM, "tangential damping [N·s/m] (AMOR_TAN; "
                                               "default: Code_Aster's value, critical on the "
                                               "mode sliding most, dtmprep_noli_choc)"),
        "friction": (_NUM, "dynamic Coulomb coefficient [-] (COULOMB, or COULOMB_DYNA)"),
        "static_friction": (_NUM, "static Coulomb coefficient [-] (COULOMB_STAT; default "
                                  "friction)"),
        "preload_N": (_NUM, "constant force towards the obstacle [N]"),
    },
    "dynamics.forces": {
        "position_m": (_NUM, "beam: abscissa of the force [m]"),
        "point": ((int, str), "modes: index or name of the forcing point"),
        "direction": (str, "y, z or x"),
        **_SIGNAL_KEYS,
    },
    "dynamics.base": {"direction": (str, "y, z or x"), **_SIGNAL_KEYS},
}


def _check(section: str, items: Mapping[str, Any], where: str) -> None:
    check_keys(items, DYNAMICS_KEYS[section], where)


def _need(items: Mapping, key: str, where: str, section: str):
    if key not in items:
        raise KeywordError(f"{where} needs {key} ({DYNAMICS_KEYS[section][key][1]})")
    return items[key]


def _path(directory, value: str) -> Path:
    p = Path(value)
    return p if p.is_absolute() or directory is None else Path(directory) / p


def _signal(item: Mapping[str, Any], where: str, duration: float) -> Signal:
    kind = item.get("kind", "harmonic")
    if kind == "harmonic":
        return Signal("harmonic", amplitude=float(_need(item, "amplitude", where, "dynamics.base")),
                      frequency=float(_need(item, "frequency_Hz", where, "dynamics.base")),
                      phase=float(item.get("phase_deg", 0.0)), scale=float(item.get("scale", 1)))
    if kind == "table":
        return Signal("table", times=_need(item, "times_s", where, "dynamics.base"),
                      values=_need(item, "values", where, "dynamics.base"),
                      scale=float(item.get("scale", 1.0)))
    if kind == "random":
        return Signal("random", psd_frequencies=_need(item, "psd_frequencies_Hz", where,
                                                      "dynamics.base"),
                      psd=_need(item, "psd", where, "dynamics.base"),
                      seed=int(_need(item, "seed", where, "dynamics.base")), duration=duration,
                      sample_rate=item.get("sample_rate_Hz"), scale=float(item.get("scale", 1)))
    raise KeywordError(f"{where} kind = {kind!r}; choose harmonic, table or random")


@dataclass
class DynamicsSetup:
    """A validated ``[dynamics]`` section.

    Attributes
    ----------
    model : ModalModel
    shocks : list of Shock
        As configured; shocks with ``obstacle = "case"`` get the profile passed to
        :meth:`shocks_with`.
    excitations : list of NodalForce / BaseAcceleration
    options : dict
        Keyword arguments of :func:`fretwear.dynamics.simulate` (duration, steps...).
    case_obstacle : list of bool
        Which shocks take the case's obstacle profile.
    """

    model: ModalModel
    shocks: list[Shock]
    excitations: list
    options: dict[str, Any]
    case_obstacle: list[bool]

    def shocks_with(self, profiles: Mapping[int, tuple[np.ndarray, np.ndarray]]) -> list[Shock]:
        """The shocks, shock ``i`` given the discrete profile ``profiles[i]`` = (angles [deg],
        gaps [m]) when present; every ``obstacle = "case"`` shock needs one."""
        out = []
        for i, s in enumerate(self.shocks):
            if i in profiles:
                s = replace(s, obstacle="profile", profile_angles=profiles[i][0],
                            profile_gaps=profiles[i][1])
            elif self.case_obstacle[i]:
                raise InputError(f"shock {s.label!r} has obstacle = \"case\" but no [obstacle] "
                                 "profile was given")
            out.append(s)
        return out


#: Most samples a [dynamics] section may archive per shock (beyond, memory and time explode:
#: 1e9 samples of 11 channels are 88 GB).
MAX_ARCHIVED = 1e9


def _tables(sub: Mapping[str, Any], name: str) -> list:
    """The ``[[dynamics.<name>]]`` array of tables, or a :class:`KeywordError`."""
    value = sub.get(name, [])
    if isinstance(value, Mapping):
        value = [value]
    if not isinstance(value, (list, tuple)) or not all(isinstance(v, Mapping) for v in value):
        raise KeywordError(f"[dynamics] {name} = {value!r}: give an array of tables, "
                           f"[[dynamics.{name}]] blocks (docs/dynamics.md)")
    return list(value)


def dynamics_from_config(section: Mapping[str, Any], *, directory=None) -> DynamicsSetup:
    """Build the modal model, shocks and excitations of a ``[dynamics]`` section.

    Parameters
    ----------
    section : mapping
        The ``[dynamics]`` table (with sub-tables ``beam`` or ``modes``, arrays of tables
        ``shocks``, ``forces``, ``base``).
    directory : path-like, optional
        Folder relative paths (profile files) are resolved against.

    Returns
    -------
    DynamicsSetup

    Raises
    ------
    KeywordError
        Unknown or missing keys, wrong types, both or neither of ``beam`` and ``modes``.

    Examples
    --------
    >>> s = dynamics_from_config({"duration_s": 0.1, "modes": {"frequencies_Hz": [10.0],
    ...     "damping_ratios": 0.01, "masses_kg": 1.0, "shock_shapes": [[[1.0], [0.0]]]},
    ...     "shocks": [{"obstacle": "circle", "gap_m": 1e-4, "normal_stiffness_N_per_m": 1e5}]})
    >>> s.model.n_modes, s.shocks[0].obstacle, s.options["duration"]
    (1, 'circle', 0.1)
    """
    sub = {k: section[k] for k in ("beam", "modes", "shocks", "forces", "base") if k in section}
    top = {k: v for k, v in section.items() if k not in sub}
    _check("dynamics", top, "[dynamics]")
    duration = float(_need(top, "duration_s", "[dynamics]", "dynamics"))
    if not (np.isfinite(duration) and duration > 0):
        raise InputError(f"[dynamics] duration_s must be > 0 [s], got {duration}")
    if ("beam" in sub) == ("modes" in sub):
        raise KeywordError("[dynamics] needs exactly one of [dynamics.beam] (a uniform beam) and "
                           "[dynamics.modes] (modes given by the user)")
    shocks_cfg = _tables(sub, "shocks")
    if not shocks_cfg:
        raise KeywordError("[dynamics] needs at least one [[dynamics.shocks]] table")
    forces_cfg = _tables(sub, "forces")
    base_cfg = _tables(sub, "base")
    for i, item in enumerate(shocks_cfg):
        _check("dynamics.shocks", item, f"[[dynamics.shocks]] #{i + 1}")
    for i, item in enumerate(forces_cfg):
        _check("dynamics.forces", item, f"[[dynamics.forces]] #{i + 1}")
    for i, item in enumerate(base_cfg):
        _check("dynamics.base", item, f"[[dynamics.base]] #{i + 1}")
    names = [item.get("name", f"shock{i + 1}") for i, item in enumerate(shocks_cfg)]
    if "beam" in sub:
        b = sub["beam"]
        _check("dynamics.beam", b, "[dynamics.beam]")
        w = "[dynamics.beam]"
        positions = [float(_need(it, "position_m", f"[[dynamics.shocks]] #{i + 1}",
                                 "dynamics.shocks")) for i, it in enumerate(shocks_cfg)]
        fpos = [float(_need(it, "position_m", f"[[dynamics.forces]] #{i + 1}", "dynamics.forces"))
                for i, it in enumerate(forces_cfg)]
        model = uniform_beam_modes(
            young_modulus=float(_need(b, "young_modulus_Pa", w, "dynamics.beam")),
            second_moment=float(_need(b, "second_moment_m4", w, "dynamics.beam")),
            mass_per_length=float(_need(b, "mass_per_length_kg_per_m", w, "dynamics.beam")),
            length=float(_need(b, "length_m", w, "dynamics.beam")),
            n_modes=int(_need(b, "modes", w, "dynamics.beam")), shock_positions=positions,
            ends=tuple(b.get("ends", ("pinned", "pinned"))), supports=b.get("supports_m", ()),
            damping_ratio=float(b.get("damping_ratio", 0.01)), forcing_positions=fpos,
            shock_names=names, method=b.get("method", "auto"))
        points = list(range(len(shocks_cfg)))
        fpoints = list(range(len(forces_cfg)))
    else:
        m = sub["modes"]
        _check("dynamics.modes", m, "[dynamics.modes]")
        w = "[dynamics.modes]"
        model = ModalModel(
            frequencies=_need(m, "frequencies_Hz", w, "dynamics.modes"),
            damping_ratios=_need(m, "damping_ratios", w, "dynamics.modes"),
            masses=_need(m, "masses_kg", w, "dynamics.modes"),
            shock_shapes=_need(m, "shock_shapes", w, "dynamics.modes"),
            forcing_shapes=m.get("forcing_shapes"), participation=m.get("participation_kg"),
            shock_names=tuple(m.get("shock_names", ())))
        points = [it.get("point", i) for i, it in enumerate(shocks_cfg)]
        fpoints = [_need(it, "point", f"[[dynamics.forces]] #{i + 1}", "dynamics.forces")
                   for i, it in enumerate(forces_cfg)]
    shocks, case_obstacle = [], []
    for i, item in enumerate(shocks_cfg):
        where = f"[[dynamics.shocks]] #{i + 1}"
        kind = item.get("obstacle", "circle")
        extra: dict[str, Any] = {}
        is_case = kind == "case"
        if is_case:  # placeholder until the case's profile is known
            kind, extra = "circle", {"gap": 1.0}
        elif kind == "profile":
            prof = read_discret(_path(directory, _need(item, "profile_file", where,
                                                       "dynamics.shocks")))
            extra = {"profile_angles": prof.angles, "profile_gaps": prof.gaps}
        shocks.append(Shock(
            point=points[i], obstacle=kind, name=names[i],
            normal_stiffness=float(_need(item, "normal_stiffness_N_per_m", where,
                                         "dynamics.shocks")),
            gap=float(item.get("gap_m", extra.pop("gap", 0.0))),
            angle=float(item.get("angle_deg", 0.0)),
            normal_damping=float(item.get("normal_damping_N_s_per_m", 0.0)),
            tangential_stiffness=float(item.get("tangential_stiffness_N_per_m", 0.0)),
            tangential_damping=(float(item["tangential_damping_N_s_per_m"])
                                if "tangential_damping_N_s_per_m" in item else None),
            friction=float(item.get("friction", 0.0)), preload=float(item.get("preload_N", 0.0)),
            static_friction=(float(item["static_friction"]) if "static_friction" in item
                             else None),
            origin=tuple(item.get("origin_m", (0.0, 0.0))), **extra))
        case_obstacle.append(is_case)
    archive = float(top.get("archive_step_s", max(1e-4, float(top.get("time_step_s", 0.0)))))
    # random records cover the simulated span, a whole number of archive steps (simulate)
    if not (np.isfinite(archive) and archive > 0) or duration / archive > MAX_ARCHIVED:
        raise InputError(f"[dynamics] archive_step_s = {archive!r} s: give a step > 0 that "
                         f"archives at most {MAX_ARCHIVED:.0e} samples over duration_s = "
                         f"{duration!r} s")
    span = max(duration, round(duration / archive) * archive)
    excitations: list = []
    for i, item in enumerate(forces_cfg):
        where = f"[[dynamics.forces]] #{i + 1}"
        excitations.append(NodalForce(fpoints[i], _need(item, "direction", where,
                                                        "dynamics.forces"),
                                      _signal(item, where, span)))
    for i, item in enumerate(base_cfg):
        where = f"[[dynamics.base]] #{i + 1}"
        excitations.append(BaseAcceleration(_need(item, "direction", where, "dynamics.base"),
                                            _signal(item, where, span)))
    options: dict[str, Any] = {"duration": duration, "adaptive": bool(top.get("adaptive", False)),
                               "safety": float(top.get("safety", 0.5))}
    if "time_step_s" in top:
        options["time_step"] = float(top["time_step_s"])
    options["archive_step"] = archive
    for key in ("initial_displacement", "initial_velocity"):
        if key in top:
            options[key] = np.array(top[key], dtype=float)
    if "chunk_size" in top:
        options["chunk_size"] = int(top["chunk_size"])
    return DynamicsSetup(model=model, shocks=shocks, excitations=excitations, options=options,
                         case_obstacle=case_obstacle)


def keys_help() -> str:
    """Every ``[dynamics]`` key with its description, as plain text."""
    lines = []
    for section, keys in DYNAMICS_KEYS.items():
        bracket = f"[[{section}]]" if section in ("dynamics.shocks", "dynamics.forces",
                                                  "dynamics.base") else f"[{section}]"
        lines.append(bracket)
        lines.extend(f"  {k}: {d}" for k, (_, d) in keys.items())
    return "\n".join(lines)
