"""A tube bundle from its description (TOML): tubes, supports, gaps, flow, simulation.

:func:`read_description` reads the file of ``fretwear simulate`` (docs/flow.md, "Bundle
description") and returns one :class:`TubeSpec` per tube: everything a worker needs to build the
tube's modes, its turbulence and its shocks, the seeded gaps already drawn (so a rerun, or a
resumed run, gives every contact the same gap). Every unknown key, wrong type or bad value is
said with its place in the file and the fix.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.flow.spectra import SPECTRA, make_spectrum
from fretwear.io.guard import readable_file, reading
from fretwear.io.text_tables import decode_text

#: Support types: the obstacle family of fretwear.dynamics.Shock each one becomes.
SUPPORT_TYPES: dict[str, str] = {"AVB": "two_planes", "plate": "circle"}

_SECTIONS: dict[str, dict[str, Any]] = {
    "": {"title": "", "seed": 0, "tubes": None, "supports": None, "flow": None,
         "simulation": None},
    "tubes": {"rows": None, "columns": None, "span_lengths_m": "", "u_bend_radii_m": "",
              "straight_leg_m": 0.0, "ends": ["clamped", "clamped"],
              "outer_diameter_m": None, "wall_thickness_m": None, "young_modulus_pa": None,
              "material_density_kg_m3": None, "internal_fluid_density_kg_m3": 0.0,
              "added_mass_coefficient": 1.0, "modes": 4, "damping_ratio": None},
    "supports": {"name": None, "position_m": "", "angle_deg": "", "type": "AVB", "gap_m": None,
                 "normal_stiffness_n_m": None, "normal_damping_n_s_m": 0.0,
                 "tangential_stiffness_n_m": 0.0, "tangential_damping_n_s_m": 0.0,
                 "friction": 0.0},
    "flow": {"spectrum": None, "parameters": {}, "connors_constant": None,
             "stability_margin": 1.0, "band_hz": None, "regions": None},
    "flow.regions": {"rows": None, "velocity_m_s": None, "density_kg_m3": None,
                     "void_fraction": 0.0, "span": [0.0, 1.0]},
    "simulation": {"duration_s": None, "archive_step_s": None, "grid_points": 241,
                   "frequency_points": 400},
}


def _table(raw: dict, section: str, where: str) -> dict[str, Any]:
    known = _SECTIONS[section]
    if not isinstance(raw, dict):
        raise InputError(f"{where}: expected a table, got {type(raw).__name__}")
    unknown = sorted(set(raw) - set(known))
    if unknown:
        raise KeywordError(f"{where}: unknown key(s) {unknown}; it takes {sorted(known)}")
    out = {}
    for key, default in known.items():
        if key in raw:
            out[key] = raw[key]
        elif default is None and section:
            raise KeywordError(f"{where}: missing key {key!r}")
        else:
            out[key] = default
    return out


#: The largest magnitude of a number of the description (SI: the stiffest support is 1e9 N/m,
#: Young's modulus 2e11 Pa): products of a few of them stay in the float range.
MAGNITUDE_MAX = 1e30


def _number(value, where: str, *, positive=False, nonnegative=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or (isinstance(value, int) and value.bit_length() > 1000) \
            or not math.isfinite(value):  # a 400-digit integer overflows float()
        shown = f"an integer of {len(str(abs(value)))} digits" if isinstance(value, int) \
            and not isinstance(value, bool) else repr(value)
        raise InputError(f"{where}: expected a finite number, got {shown}")
    if abs(value) > MAGNITUDE_MAX:   # a diameter of 1e77 m overflowed d**4
        raise InputError(f"{where}: {value!r} is beyond any physical value in SI units (at "
                         f"most {MAGNITUDE_MAX:g}); check the units")
    if positive and value <= 0:
        raise InputError(f"{where}: must be > 0, got {value!r}")
    if nonnegative and value < 0:
        raise InputError(f"{where}: must be >= 0, got {value!r}")
    return float(value)


def u_bend_span_length(radius: float, straight_leg: float = 0.0) -> float:
    """Developed length of a U-bend span [m]: the half circle and its two straight legs.

    Parameters
    ----------
    radius : float
        Bend radius R of the tube's centre line [m].
    straight_leg : float
        Length of each straight leg between the end support and the start of the bend [m].

    Returns
    -------
    float
        L = π·R + 2·leg [m].

    Examples
    --------
    >>> round(u_bend_span_length(0.5, 0.1), 6)
    1.770796
    """
    return math.pi * radius + 2.0 * straight_leg


def u_bend_abscissa(radius: float, straight_leg: float, angle_deg: float) -> float:
    """Abscissa along a U-bend span of the point at ``angle_deg`` into the bend [m].

    The angle [°] is measured at the bend's centre from the start of the bend (0) to its end
    (180; 90 is the apex): s = leg + R·θ.

    Examples
    --------
    >>> u_bend_abscissa(0.5, 0.1, 90.0) == u_bend_span_length(0.5, 0.1) / 2
    True
    """
    return straight_leg + radius * math.radians(angle_deg)


def _u_bend_radii(value, rows: int) -> list[float]:
    where = "[tubes].u_bend_radii_m"
    if isinstance(value, dict):
        if set(value) != {"first", "pitch"}:
            raise KeywordError(f"{where}: a table is {{ first = R₁, pitch = p }} (row r has "
                               f"R₁ + (r − 1)·p [m]); got keys {sorted(value)}")
        first = _number(value["first"], f"{where}.first", positive=True)
        pitch = _number(value["pitch"], f"{where}.pitch", nonnegative=True)
        return [first + (r - 1) * pitch for r in range(1, rows + 1)]
    values = value if isinstance(value, list) else [value] * rows
    if len(values) != rows:
        raise InputError(f"{where}: one value, one per row ({rows}) or {{ first, pitch }}; got "
                         f"{len(values)} values")
    return [_number(v, where, positive=True) for v in values]


def _span_lengths(tubes: dict, rows: int) -> tuple[list[float], list[float] | None, float]:
    """Span length per row [m], the U-bend radii per row (None for straight spans), the leg."""
    spans, radii = tubes["span_lengths_m"], tubes["u_bend_radii_m"]
    if (spans == "") == (radii == ""):
        raise KeywordError("[tubes]: give either span_lengths_m or u_bend_radii_m (with "
                           "straight_leg_m), not both and not neither")
    leg = _number(tubes["straight_leg_m"], "[tubes].straight_leg_m", nonnegative=True)
    if radii != "":
        radii = _u_bend_radii(radii, rows)
        return [u_bend_span_length(r, leg) for r in radii], radii, leg
    if leg:
        raise KeywordError("[tubes].straight_leg_m: only with u_bend_radii_m")
    spans = [spans] * rows if not isinstance(spans, list) else spans
    if len(spans) != rows:
        raise InputError(f"[tubes].span_lengths_m: one value or one per row ({rows}), got "
                         f"{len(spans)}")
    return [_number(v, "[tubes].span_lengths_m", positive=True) for v in spans], None, leg


def _position(sup: dict, where: str, row: int, length: float, radii, leg: float) -> float:
    if (sup["position_m"] == "") == (sup["angle_deg"] == ""):
        raise KeywordError(f"{where}: give either position_m or angle_deg, not both and not "
                           "neither")
    if sup["angle_deg"] != "":
        if radii is None:
            raise KeywordError(f"{where}.angle_deg: only with [tubes].u_bend_radii_m (give "
                               "position_m for straight spans)")
        angle = _number(sup["angle_deg"], f"{where}.angle_deg")
        if not 0 <= angle <= 180:
            raise InputError(f"{where}.angle_deg: in [0, 180] (from the start of the bend), got "
                             f"{angle}")
        pos = u_bend_abscissa(radii[row - 1], leg, angle)
    else:
        pos = _number(sup["position_m"], f"{where}.position_m", positive=True)
    if not 0 < pos < length:
        raise InputError(f"{where}: position {pos} m lies beyond the span of row {row} "
                         f"(0 < s < {length} m)")
    return pos

#: The largest count of each key (a larger one exhausts memory before any work: grid points
#: of 1e400 raised numpy's 'Maximum allowed size exceeded').
COUNT_MAX = {"modes": 200, "grid_points": 100_000, "frequency_points": 100_000,
             "rows": 10_000, "columns": 10_000}
#: The most samples of one tube's simulation (duration_s / archive_step_s).
SAMPLES_MAX = 10**8


def _count(value, where: str) -> int:
    most = COUNT_MAX.get(where.rsplit(".", 1)[-1], 10**9)
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= most:
        shown = f"an integer of {len(str(abs(value)))} digits" if isinstance(value, int) \
            and abs(value) > 10**30 else repr(value)
        raise InputError(f"{where}: expected an integer in [1, {most}], got {shown}")
    return value


def _ends(value, where: str) -> tuple:
    if not (isinstance(value, list) and len(value) == 2 and all(isinstance(v, str) for v in value)):
        raise InputError(f"{where}: expected two end conditions, e.g. [\"clamped\", "
                         f"\"pinned\"], got {value!r}")
    return tuple(value)


@dataclass(frozen=True)
class TubeSpec:
    """One tube of the bundle, as a worker builds and runs it (every value in SI units).

    ``beam`` holds the keywords of :func:`fretwear.dynamics.uniform_beam_modes`; ``supports``
    one dict per contact (name, position_m, obstacle, gap_m and the contact law); ``regions``
    the flow along the span ((start_m, end_m, U [m/s], ρ [kg/m³], α [-]) per region);
    ``spectrum`` the family and its parameters.
    """

    tube: str
    row: int
    column: int
    diameter: float
    wall_thickness: float
    mass_per_length: float
    beam: dict
    supports: tuple
    regions: tuple
    spectrum: dict
    band_hz: tuple
    connors_constant: float
    stability_margin: float
    duration: float
    archive_step: float
    grid_points: int
    frequency_points: int
    seed: int
    extra: dict = field(default_factory=dict)

    def signature(self) -> str:
        """A digest of every input: a resumed run reuses a tube whose signature is unchanged."""
        text = json.dumps(dataclasses.asdict(self), sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _gap(value, where: str, rng: np.random.Generator) -> float:
    if isinstance(value, dict):
        if value.get("distribution") != "lognormal" or set(value) != {"distribution", "median",
                                                                         "sigma_ln"}:
            raise KeywordError(f"{where}: a drawn gap is {{ distribution = \"lognormal\", "
                               f"median = ..., sigma_ln = ... }} (median [m], σ of ln [-]); got "
                               f"{value!r}")
        median = _number(value["median"], f"{where}.median", positive=True)
        sigma = _number(value["sigma_ln"], f"{where}.sigma_ln", nonnegative=True)
        return float(median * math.exp(sigma * rng.standard_normal()))
    return _number(value, where)


def _beam(tubes: dict, where: str, rho_external: float, length: float) -> tuple[dict, float]:
    d = _number(tubes["outer_diameter_m"], f"{where}.outer_diameter_m", positive=True)
    e = _number(tubes["wall_thickness_m"], f"{where}.wall_thickness_m", positive=True)
    if 2 * e >= d:
        raise InputError(f"{where}: wall_thickness_m {e} must be below half the diameter {d}")
    di = d - 2 * e
    area_wall, area_in, area_out = (math.pi / 4 * (d * d - di * di), math.pi / 4 * di * di,
                                    math.pi / 4 * d * d)
    mass = (_number(tubes["material_density_kg_m3"], f"{where}.material_density_kg_m3",
                    positive=True) * area_wall
            + _number(tubes["internal_fluid_density_kg_m3"],
                      f"{where}.internal_fluid_density_kg_m3", nonnegative=True) * area_in
            + _number(tubes["added_mass_coefficient"], f"{where}.added_mass_coefficient",
                      nonnegative=True) * rho_external * area_out)
    beam = {"young_modulus": _number(tubes["young_modulus_pa"], f"{where}.young_modulus_pa",
                                     positive=True),
            "second_moment": math.pi / 64 * (d**4 - di**4), "mass_per_length": mass,
            "length": length, "n_modes": _count(tubes["modes"], f"{where}.modes"),
            "ends": _ends(tubes["ends"], f"{where}.ends"),
            "damping_ratio": _number(tubes["damping_ratio"], f"{where}.damping_ratio",
                                     nonnegative=True)}
    return beam, mass


def _regions(flow: dict, rows: int, lengths: list[float]) -> dict[int, list[tuple]]:
    regions = flow["regions"]
    if not isinstance(regions, list) or not regions:
        raise InputError("[flow]: give at least one [[flow.regions]]")
    out: dict[int, list[tuple]] = {r: [] for r in range(1, rows + 1)}
    for k, raw in enumerate(regions, 1):
        where = f"[[flow.regions]] #{k}"
        reg = _table(raw, "flow.regions", where)
        span = reg["span"]
        if (not isinstance(span, list) or len(span) != 2
                or not 0 <= _number(span[0], f"{where}.span") < _number(span[1], f"{where}.span")
                <= 1):
            raise InputError(f"{where}: span = [start, end] as fractions of the span, "
                             f"0 <= start < end <= 1; got {span!r}")
        values = (_number(reg["velocity_m_s"], f"{where}.velocity_m_s"),
                  _number(reg["density_kg_m3"], f"{where}.density_kg_m3", positive=True),
                  _number(reg["void_fraction"], f"{where}.void_fraction", nonnegative=True))
        if values[2] >= 1:
            raise InputError(f"{where}: void_fraction must be < 1, got {values[2]}")
        for row in reg["rows"] if isinstance(reg["rows"], list) else [reg["rows"]]:
            if isinstance(row, bool) or not isinstance(row, int) or row not in out:
                raise InputError(f"{where}: row {row!r} is not one of the bundle's rows 1..{rows}")
            length = lengths[row - 1]
            item = (span[0] * length, span[1] * length, *values)
            if any(a < item[1] and item[0] < b for a, b, *_ in out[row]):
                raise InputError(f"{where}: overlaps another region on row {row}")
            out[row].append(item)
    missing = [r for r, items in out.items() if not items]
    if missing:
        raise InputError(f"[flow]: rows {missing} have no [[flow.regions]]; give each row its flow")
    return out


def read_description(path: str | Path) -> list[TubeSpec]:
    """The tubes of a bundle description (TOML), gaps drawn with its seed.

    Each drawn gap [m] of the contact (row, column, support k) has its own random stream,
    ``np.random.default_rng([seed, row, column, k])`` (rows, columns and supports counted
    from 1, supports in file order): a tube's gaps, like its force seed
    ``seed * 100003 + 1000 * row + column``, depend on the seed and on the tube's place only,
    not on the bundle's size (R4C1 is the same tube in a 4x1 and a 4x3 bundle).

    Examples
    --------
    >>> from pathlib import Path
    >>> specs = read_description(Path("examples/bundle/bundle_geometry.toml"))
    >>> len(specs), specs[0].tube, [s["name"] for s in specs[0].supports]
    (12, 'R1C1', ['AVB1', 'AVB2'])
    """
    path = readable_file(path, "bundle description")   # a FIFO or a device is refused
    try:
        with reading(path, "TOML", "bundle description"):   # UTF-8 (BOM or not) or UTF-16
            raw = tomllib.loads(decode_text(path.read_bytes(), f"bundle description {path}"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not valid TOML ({exc})") from None
    top = _table(raw, "", str(path))
    for key in ("tubes", "supports", "flow", "simulation"):
        if top[key] is None:
            raise KeywordError(f"{path}: missing section [{key}] (docs/flow.md)")
    tubes = _table(top["tubes"], "tubes", "[tubes]")
    flow = _table(top["flow"], "flow", "[flow]")
    sim = _table(top["simulation"], "simulation", "[simulation]")
    rows, cols = _count(tubes["rows"], "[tubes].rows"), _count(tubes["columns"], "[tubes].columns")
    lengths, radii, leg = _span_lengths(tubes, rows)
    if not isinstance(flow["spectrum"], str) or flow["spectrum"] not in SPECTRA:
        raise KeywordError(f"[flow].spectrum: unknown {flow['spectrum']!r}; choose one of "
                           f"{list(SPECTRA)}")
    if not isinstance(flow["parameters"], dict):
        raise InputError(f"[flow].parameters: expected a table of the spectrum's parameters, "
                         f"e.g. {{ long_cor = 3.0 }}, got {flow['parameters']!r}")
    make_spectrum(flow["spectrum"], **flow["parameters"])  # parameters checked here
    band = flow["band_hz"]
    if (not isinstance(band, list) or len(band) != 2
            or not 0 < _number(band[0], "[flow].band_hz") < _number(band[1], "[flow].band_hz")):
        raise InputError(f"[flow].band_hz: [low, high] with 0 < low < high [Hz], got {band!r}")
    regions = _regions(flow, rows, lengths)
    supports = top["supports"]
    if not isinstance(supports, list) or not supports:
        raise InputError("give at least one [[supports]]")
    seed = top["seed"]
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InputError(f"seed: expected an integer >= 0, got {seed!r}")
    specs = []
    for row in range(1, rows + 1):
        rho_ext = float(np.mean([r[3] for r in regions[row]]))
        beam, mass = _beam(tubes, "[tubes]", rho_ext, lengths[row - 1])
        for col in range(1, cols + 1):
            contacts = []
            for k, s in enumerate(supports, 1):
                where = f"[[supports]] #{k}"
                sup = _table(s, "supports", where)
                if not isinstance(sup["type"], str) or sup["type"] not in SUPPORT_TYPES:
                    raise KeywordError(f"{where}.type: {sup['type']!r}; choose one of "
                                       f"{list(SUPPORT_TYPES)}")
                pos = _position(sup, where, row, lengths[row - 1], radii, leg)
                contacts.append({
                    "name": str(sup["name"]), "position_m": pos,
                    "obstacle": SUPPORT_TYPES[sup["type"]], "type": sup["type"],
                    "gap_m": _gap(sup["gap_m"], f"{where}.gap_m",
                                  np.random.default_rng([seed, row, col, k])),
                    **{key: _number(sup[key], f"{where}.{key}", nonnegative=True) for key in (
                        "normal_stiffness_n_m", "normal_damping_n_s_m",
                        "tangential_stiffness_n_m", "tangential_damping_n_s_m", "friction")}})
            specs.append(TubeSpec(
                tube=f"R{row}C{col}", row=row, column=col,
                diameter=float(tubes["outer_diameter_m"]),
                wall_thickness=float(tubes["wall_thickness_m"]), mass_per_length=mass,
                beam=beam, supports=tuple(contacts), regions=tuple(regions[row]),
                spectrum={"name": flow["spectrum"], **flow["parameters"]},
                band_hz=(float(band[0]), float(band[1])),
                connors_constant=_number(flow["connors_constant"], "[flow].connors_constant",
                                         positive=True),
                stability_margin=_number(flow["stability_margin"], "[flow].stability_margin",
                                         positive=True),
                duration=_number(sim["duration_s"], "[simulation].duration_s", positive=True),
                archive_step=_number(sim["archive_step_s"], "[simulation].archive_step_s",
                                     positive=True),
                grid_points=_count(sim["grid_points"], "[simulation].grid_points"),
                frequency_points=_count(sim["frequency_points"], "[simulation].frequency_points"),
                seed=seed * 100_003 + 1000 * row + col,
                extra={} if radii is None else {"u_bend_radius_m": radii[row - 1],
                                                "straight_leg_m": leg}))
    samples = specs[0].duration / specs[0].archive_step if specs else 0.0
    if specs and not samples >= 2.0:  # a duration of 5e-324 s gave NaN modal forces
        raise InputError(f"[simulation]: duration_s / archive_step_s = {samples:.3g} samples per "
                         "tube: the duration must hold at least two archive steps; check the "
                         "units (seconds)")
    if samples > SAMPLES_MAX:
        raise InputError(f"[simulation]: duration_s / archive_step_s = {samples:.3g} samples per "
                         f"tube, more than {SAMPLES_MAX:g}; check the units (seconds)")
    return specs
