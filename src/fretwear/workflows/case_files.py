"""TOML case files: one file describes one wear computation (``fretwear run CASE.toml``).

Keys carry their unit in their name (``mobile_radius_m``, ``tilt_angle_deg``, ``value_W``);
every key is listed in :data:`KEYS` (the single source of ``fretwear run --help`` and of
``docs/case_files.md``). Unknown keys are errors naming them, so typos are caught. The sections
``[obstacle]`` and ``[dynamics]`` belong to other commands and are ignored here. Paths are
relative to the case file.

Example::

    [history]
    file = "data/oscillator_gap.csv"
    [law]
    name = "ARCHARD"
    mobile = { COEF_USURE = 1.2e-13 }
    [geometry]
    contact_type = "TUBE_BAV"
    mobile_radius_m = 9.525e-3
    obstacle_width_m = 12.7e-3
    [time]
    instants = [1, 2, 5, 10]
    unit = "year"
"""

from __future__ import annotations

import os
import tomllib
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.errors import FretwearWarning, InputError, KeywordError
from fretwear.geometry import CONTACT_TYPES
from fretwear.geometry.base import ASTER_KEYWORDS, DIMENSION_DESCRIPTIONS, DIMENSION_UNITS
from fretwear.io import FORMATS, units_read
from fretwear.io.guard import readable_file, reading
from fretwear.keys import check_keys, keyword_hint  # noqa: F401 - re-exported
from fretwear.laws import WEAR_LAWS
from fretwear.power import PowerAccumulator, wear_power
from fretwear.table import (
    DEFAULT_DEPTH_LIMIT,
    WearCase,
    read_wear_table,
    wear_table_from_case,
)
from fretwear.table.keywords import check_keywords
from fretwear.timeunits import TIME_UNITS, describe_time_units, time_unit_name  # noqa: F401

#: section -> key -> (expected type, description with unit). "*" sections are free tables.
KEYS: dict[str, dict[str, tuple[type | tuple[type, ...], str]]] = {
    "": {
        "title": (str, "a title for the summary and the table metadata"),
    },
    "history": {
        "file": (str, f"contact history file ({', '.join(FORMATS)}), relative to the case "
                      "file (RESU_GENE)"),
        "format": (str, f"file format when the suffix does not tell it: {', '.join(FORMATS)}"),
        "name": (str, "label of the shock point (NOEUD) for the summary"),
        "units": (dict, "units of the file's values, converted to SI, e.g. { length = \"mm\", "
                        "force = \"kN\" } or per channel { dy = \"mm\" }"),
        "columns": (dict, "column -> channel overrides, e.g. { VINT1 = \"normal_force\" }"),
        "node": (str, "shock point (NOEUD / GROUP_NO): its rows or tables in a Code_Aster file "
                      "holding several; an error when the file's node column does not hold it"),
        "options": (dict, "options of the format's reader, e.g. { select = \"NOEUD=N12\" }, "
                          "{ index = 1 }, { delimiter = \";\" }, { functions = [\"fn\", "
                          "\"vt1\", \"vt2\"] } (docs/formats.md)"),
    },
    "power": {
        "value_W": ((int, float), "a given wear power [W] instead of a history (PUIS_USURE)"),
        "t_start_s": ((int, float), "start of the history window [s] (INST_INIT)"),
        "t_end_s": ((int, float), "end of the history window [s] (INST_FIN)"),
        "blocks": (int, "number of blocks of equal duration (NB_BLOC), default 1"),
        "stationarity_threshold": ((int, float), "block spread (max-min)/mean above which a "
                                                 "warning is given [-], default 0.1"),
    },
    "law": {
        "name": (str, f"{', '.join(WEAR_LAWS)} (LOI_USURE), default ARCHARD"),
        "mobile": (dict, "law coefficients of the mobile: the law's parameter names or "
                         "Code_Aster keywords, SI (e.g. { COEF_USURE = 1.2e-13 } [1/Pa])"),
        "obstacle": (dict, "law coefficients of the obstacle (it wears only if given)"),
        "materials": (list, "[mobile, obstacle] materials of the database instead "
                            "(MATER_USURE), e.g. [\"I600\", \"Z10C13\"]"),
        "obstacle_wear": (bool, "take the obstacle coefficient from the database "
                                "(USURE_OBST), default false"),
        "database": ((list, str), "your coefficient CSV file(s) (format of docs/laws.md) "
                                  "extending/overriding the built-in table for materials, "
                                  "relative to the case file; later files win (fretwear "
                                  "extension)"),
        "force_max_N": ((int, float), "KWU_EPRI force class range [N] (FNOR_MAXI)"),
        "speed_max_m_per_s": ((int, float), "KWU_EPRI speed class range [m/s] (VTAN_MAXI)"),
    },
    "geometry": {
        "contact_type": (str, f"{', '.join(CONTACT_TYPES)} (CONTACT)"),
        **{f"{name}_{DIMENSION_UNITS[name]}": (
            (int, float), f"{DIMENSION_DESCRIPTIONS[name]} [{DIMENSION_UNITS[name]}] ({keyword})")
           for name, keyword in ASTER_KEYWORDS.items()},
        "wall_thickness_m": ((int, float), "wall thickness of the mobile (tube) [m]: the table "
                                           "gains the depth over the wall and the instant of "
                                           "reaching the limit (fretwear extension)"),
        "depth_limit": ((int, float), f"depth limit as a fraction of the wall [-], default "
                                      f"{DEFAULT_DEPTH_LIMIT} (plugging criterion)"),
    },
    "sectors": {
        "count": (int, "number of equal angular sectors over -180..180 deg"),
        "edges_deg": (list, "sector edges [deg], increasing from -180 to 180 (instead of count)"),
        "mobile_coefficients_per_Pa": (list, "Archard coefficient of the mobile per sector "
                                             "[1/Pa] (COEF_USUR_MOBILE), default the law's"),
        "obstacle_coefficients_per_Pa": (list, "Archard coefficient of the obstacle per sector "
                                               "[1/Pa] (COEF_USUR_OBST)"),
    },
    "time": {
        "instants": (list, "durations of service after the origin [unit] (INST)"),
        "unit": (str, f"{describe_time_units()}, default s"),
        "seconds_per_unit": ((int, float), "seconds per time unit [s] (COEF_INST), instead "
                                           "of unit"),
        "tube_replacement": ((int, float), "instant [unit] at which the tube is replaced by a "
                                           "new one (TUBE_NEUF)"),
    },
    "restart": {
        "table": (str, "previous wear table to continue (ETAT_INIT TABL_USURE): CSV, Parquet "
                       "or Code_Aster text table, relative to the case file"),
        "instant": ((int, float), "instant of that table to continue from (INST_INIT), "
                                  "default its last"),
        "table_index": (int, "which table (0-based) of a Code_Aster file holding several"),
    },
}
#: Sections owned by other commands (``fretwear obstacle``, ``fretwear iterate``), accepted and
#: ignored by ``fretwear run``.
FOREIGN_SECTIONS: tuple[str, ...] = ("obstacle", "dynamics", "iterate", "uncertainty")
#: ``[geometry]`` key -> dimension (the geometry's names with their unit: ``mobile_radius_m``).
_DIMENSIONS = {f"{name}_{DIMENSION_UNITS[name]}": name for name in ASTER_KEYWORDS}


def keys_help() -> str:
    """Every case-file key with its description, as plain text (``fretwear run --help``).

    Examples
    --------
    >>> keys_help().splitlines()[2]
    '[history]'
    """
    lines = []
    for section, keys in KEYS.items():
        lines.append(f"[{section}]" if section else "(top level)")
        lines.extend(f"  {k}: {desc}" for k, (_, desc) in keys.items())
    lines.append(f"[{'], ['.join(FOREIGN_SECTIONS)}]: used by other commands, ignored here")
    return "\n".join(lines)


def validate_case(case: Mapping[str, Any], source: str = "case") -> dict[str, Any]:
    """Check the sections, keys and value types of a case; returns a plain-dict copy.

    Raises
    ------
    KeywordError
        An unknown section or key (with the closest valid name), or a value of the wrong type.

    Examples
    --------
    >>> validate_case({"geometry": {"contact_type": "TUBE_BAV"}})["geometry"]
    {'contact_type': 'TUBE_BAV'}
    >>> try:
    ...     validate_case({"geometry": {"mobile_radus_m": 0.01}})
    ... except KeywordError as exc:
    ...     print(str(exc).split(";")[0])
    case: unknown key [geometry] mobile_radus_m (did you mean 'mobile_radius_m'?)
    """
    out: dict[str, Any] = {}
    sections = [s for s in KEYS if s] + list(FOREIGN_SECTIONS)
    problems: list[str] = []  # every unknown name and wrong type, said at once
    for name, value in case.items():
        if isinstance(value, Mapping) and name not in KEYS[""]:
            if name in FOREIGN_SECTIONS:
                out[name] = dict(value)
                continue
            if name not in KEYS:
                problems.append(f"{source}: unknown section [{name}]"
                                f"{keyword_hint(name, sections)}; valid sections: "
                                f"{', '.join(sections)}")
                continue
            out[name] = dict(value)
            for key, item in out[name].items():
                _collect(problems, check_keys, {key: item}, KEYS[name], source,
                         key_prefix=f"[{name}] ")
        else:
            out[name] = value
            _collect(problems, check_keys, {name: value}, KEYS[""], source)
    problems += _named_values(out, source)
    if problems:
        raise KeywordError("\n".join(problems))
    return out


def _named_values(case: Mapping[str, Any], source: str) -> list[str]:
    """A wear law or contact type not in its registry, named with its file, key and the closest
    name (the registries' own errors say neither file nor key)."""
    problems = []
    for section, key, names, what in (("law", "name", list(WEAR_LAWS), "wear law (LOI_USURE)"),
                                      ("geometry", "contact_type", list(CONTACT_TYPES),
                                       "contact type (CONTACT)")):
        part = case.get(section)
        value = part.get(key) if isinstance(part, Mapping) else None
        if isinstance(value, str) and value.strip().upper() not in names:
            problems.append(f"{source}: [{section}] {key} = {value!r} is not a {what}"
                            f"{keyword_hint(value.strip().upper(), names)}; choose one of "
                            f"{', '.join(names)}")
    return problems


def _collect(problems: list[str], check, *args, **keywords) -> None:
    """Run one check; its KeywordError's message joins ``problems`` instead of stopping."""
    try:
        check(*args, **keywords)
    except KeywordError as exc:
        problems.append(str(exc))


def load_case(path: str | os.PathLike) -> dict[str, Any]:
    """Read and validate a TOML case file; relative paths become absolute.

    Parameters
    ----------
    path : path-like
        The ``.toml`` case file.

    Returns
    -------
    dict
        The validated case, with ``"_directory"`` the file's folder.

    Examples
    --------
    >>> import tempfile
    >>> p = Path(tempfile.mkdtemp()) / "case.toml"
    >>> _ = p.write_text('[time]\\ninstants = [1, 2]\\nunit = "year"\\n')
    >>> load_case(p)["time"]
    {'instants': [1, 2], 'unit': 'year'}
    """
    raw, directory = read_case_toml(path)
    case = validate_case(raw, source=str(path))
    case["_directory"] = directory
    return case


def read_case_toml(path: str | os.PathLike) -> tuple[dict[str, Any], str]:
    """The raw (unvalidated) TOML content of a case file and the file's folder.

    Raises
    ------
    InputError
        The file does not exist or is not valid TOML (with the parser's line and column).
    """
    p = readable_file(path, "case file")
    try:
        with reading(p, "TOML", "case file"):
            text = p.read_text(encoding="utf-8-sig")  # a BOM is dropped
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"case file {str(p)!r} is not valid TOML: {exc}") from None
    return raw, str(p.resolve().parent)


@dataclass
class CaseResult:
    """What a case run produced.

    Attributes
    ----------
    table : DataFrame
        The wear table, native column names (:mod:`fretwear.table`).
    power : PowerResult or float
        The power computation (or the given power [W]).
    warnings : list of str
        Every warning raised during the run, as text.
    case : dict
        The validated case.
    history : ContactHistory or None
        The contact history, when the caller read it whole (``run_case`` streams the history
        file and leaves None).
    wear_case : WearCase or None
        The validated wear case the table was built from.
    units : dict or None
        The unit each channel of the history file was read in (``{channel: unit}``).
    """

    table: pd.DataFrame
    power: Any
    warnings: list[str] = field(default_factory=list)
    case: dict[str, Any] = field(default_factory=dict)
    history: Any = None
    wear_case: WearCase | None = None
    units: dict[str, str] | None = None

    @property
    def total_power(self) -> float:
        """Global wear power [W]."""
        return float(getattr(self.power, "total", self.power))


def _path(case: Mapping[str, Any], value: str) -> Path:
    p = Path(value)
    return p if p.is_absolute() else Path(case.get("_directory", ".")) / p


def case_arguments(case: Mapping[str, Any], *, history_elsewhere: bool = False
                   ) -> dict[str, Any]:
    """The keyword arguments of :func:`fretwear.table.wear_table` for a validated case.

    Parameters
    ----------
    case : mapping
        A validated case (:func:`validate_case`).
    history_elsewhere : bool
        The history does not come from the case's ``[history]`` or ``[power]`` (``fretwear
        iterate`` simulates it): neither ``[history] file`` nor ``[power] value_W`` is asked
        for.

    Raises
    ------
    KeywordError
        Inconsistent keys (both or neither of ``[history] file`` and ``[power] value_W``, a
        missing ``contact_type`` or ``instants``, ``unit`` with ``seconds_per_unit``, ...).

    Examples
    --------
    >>> args = case_arguments({"power": {"value_W": 0.01},
    ...                        "geometry": {"contact_type": "TUBE_BAV", "mobile_radius_m": 0.01},
    ...                        "time": {"instants": [1], "unit": "h"}})
    >>> args["time_scale"], args["dimensions"]
    (3600.0, {'mobile_radius': 0.01})
    """
    history, power = case.get("history", {}), case.get("power", {})
    law, geometry = case.get("law", {}), case.get("geometry", {})
    sectors, time, restart = case.get("sectors", {}), case.get("time", {}), case.get("restart", {})
    if not history_elsewhere and ("file" in history) == ("value_W" in power):
        raise KeywordError("case: give exactly one of [history] file (a contact history) and "
                           "[power] value_W (a given power)")
    if "value_W" in power:
        extra = [k for k in ("t_start_s", "t_end_s", "blocks", "stationarity_threshold")
                 if k in power]
        if extra:
            raise KeywordError(f"case: [power] {', '.join(extra)} apply to a history, not to a "
                               "given power value_W; remove them")
    if "contact_type" not in geometry:
        raise KeywordError("case: [geometry] contact_type is required")
    if "instants" not in time:
        raise KeywordError("case: [time] instants is required (durations of service)")
    if "unit" in time and "seconds_per_unit" in time:
        raise KeywordError("case: give [time] unit or seconds_per_unit, not both")
    scale = float(time.get("seconds_per_unit", 1.0))
    # "years", "Year": the unit "year" (the user's dict is not changed)
    unit = time_unit_name(time["unit"]) if isinstance(time.get("unit"), str) \
        else time.get("unit")
    if "unit" in time:
        if unit not in TIME_UNITS:
            raise KeywordError(f"case: [time] unit = {time['unit']!r} is not one of "
                               f"{', '.join(TIME_UNITS)} (or their plurals); or give "
                               "seconds_per_unit")
        scale = TIME_UNITS[unit]
    if "count" in sectors and "edges_deg" in sectors:
        raise KeywordError("case: give [sectors] count or edges_deg, not both")
    sector_spec = sectors.get("count", sectors.get("edges_deg"))
    if sectors and sector_spec is None:
        raise KeywordError("case: [sectors] needs count or edges_deg")
    pairs = None
    if "mobile_coefficients_per_Pa" in sectors:
        km = sectors["mobile_coefficients_per_Pa"]
        ko = sectors.get("obstacle_coefficients_per_Pa", [None] * len(km))
        if len(ko) != len(km):
            raise KeywordError("case: [sectors] mobile_coefficients_per_Pa and "
                               "obstacle_coefficients_per_Pa must have the same length")
        pairs = list(zip(km, ko, strict=True))
    elif "obstacle_coefficients_per_Pa" in sectors:
        raise KeywordError("case: [sectors] obstacle_coefficients_per_Pa needs "
                           "mobile_coefficients_per_Pa too")
    materials = law.get("materials")
    files = _database_files(case, law.get("database"))
    given = case.get("obstacle", {}).get("wall_thickness_m")
    wall = geometry.get("wall_thickness_m", given)
    # compared as text: a NaN given twice is the same key (its own check names it), not two walls
    if given is not None and repr(wall) != repr(given) and wall != given:
        raise KeywordError(f"case: [geometry] wall_thickness_m = {wall} and [obstacle] "
                           f"wall_thickness_m = {given} differ; "
                           "give the tube's wall once, in [geometry]")
    # the rules between the keys (materials a pair, database files need materials, sectors
    # Archard only, ...) are the wear case's: fretwear.table.WearCase checks them once
    args = dict(
        contact_type=geometry["contact_type"],
        dimensions={_DIMENSIONS[k]: float(v) for k, v in geometry.items() if k in _DIMENSIONS},
        instants=time["instants"], law=law.get("name"),
        coefficients=law.get("mobile"), obstacle_coefficients=law.get("obstacle"),
        materials=None if materials is None else tuple(materials),
        obstacle_wear=law.get("obstacle_wear"), sectors=sector_spec,
        sector_coefficients=pairs, time_scale=scale,
        initial_state=_restart_table(case, restart),
        initial_instant=restart.get("instant"), tube_replacement=time.get("tube_replacement"),
        t_start=power.get("t_start_s"), t_end=power.get("t_end_s"), blocks=power.get("blocks"),
        stationarity_threshold=power.get("stationarity_threshold"),
        force_max=law.get("force_max_N"), speed_max=law.get("speed_max_m_per_s"),
        coefficient_files=files or None, time_unit=unit, name=case.get("title"),
        wall_thickness=wall, depth_limit=geometry.get("depth_limit"))
    # a key not given: the keyword's default, written once (fretwear.table.keywords.KEYWORDS)
    return check_keywords({k: v for k, v in args.items() if v is not None}, "case")


def wear_case(case: Mapping[str, Any], *, history_elsewhere: bool = False) -> WearCase:
    """The validated :class:`~fretwear.table.WearCase` of a validated case file.

    ``WearCase.from_keywords(**case_arguments(case))``: the database row of ``[law] materials``
    is looked up and the ``[restart] table`` read here, once.

    Examples
    --------
    >>> c = wear_case({"power": {"value_W": 0.01}, "law": {"mobile": {"COEF_USURE": 1e-14}},
    ...                "geometry": {"contact_type": "TUBE_BAV", "mobile_radius_m": 0.01,
    ...                             "obstacle_width_m": 0.02},
    ...                "time": {"instants": [1], "unit": "h"}})
    >>> c.time_scale, c.coefficients["coefficient"].source
    (3600.0, 'user')
    """
    return WearCase.from_keywords(**case_arguments(case, history_elsewhere=history_elsewhere))


def _database_files(case: Mapping[str, Any], files) -> list[str]:
    """The ``[law] database`` files, relative to the case file, each checked to exist."""
    if files is None:
        return []
    items = [files] if isinstance(files, str) else list(files)
    out = []
    for item in items:
        if not isinstance(item, str):
            raise KeywordError(f"case: [law] database = {files!r}: give file names (strings), "
                               "e.g. [\"my_coefficients.csv\"]")
        path = _path(case, item)
        if not path.is_file():
            raise InputError(f"case: [law] database file {str(path)!r} does not exist (paths are "
                             "relative to the case file)")
        out.append(str(path))
    return out


def _restart_table(case: Mapping[str, Any], restart: Mapping[str, Any]):
    """The ``[restart]`` table: its path, or the chosen table of a multi-table file."""
    if "table" not in restart:
        if "table_index" in restart or "instant" in restart:
            raise KeywordError("case: [restart] table_index and instant need [restart] table "
                               "(the wear table to continue)")
        return None
    path = _path(case, restart["table"])
    if "table_index" not in restart:
        return path
    return read_wear_table(path, index=restart["table_index"])


def run_case(case: str | os.PathLike | Mapping[str, Any], *, progress=None) -> CaseResult:
    """Run a case (file or dict): read the history, compute the power and the wear table.

    Parameters
    ----------
    case : path-like or mapping
        A TOML case file, or the same content as a dict (relative paths then relative to the
        current directory, or to ``case["_directory"]``).
    progress : callable, optional
        ``progress(description, done=None, total=None)`` called before each stage (reading,
        power, table) and after each chunk of a long history's power computation (``done`` of
        ``total`` samples).

    Returns
    -------
    CaseResult
        The table, the power, the warnings as text.

    Examples
    --------
    >>> r = run_case({"power": {"value_W": 0.01}, "law": {"mobile": {"COEF_USURE": 1e-14}},
    ...               "geometry": {"contact_type": "TUBE_ALESAGE", "mobile_radius_m": 0.01,
    ...                            "obstacle_width_m": 0.02},
    ...               "time": {"instants": [1.0], "unit": "h"}})
    >>> r.table["volume_mobile"].tolist()
    [3.6e-13]
    """
    if isinstance(case, Mapping):
        directory = case.get("_directory")
        case = validate_case({k: v for k, v in case.items() if k != "_directory"})
        if directory is not None:
            case["_directory"] = directory
    else:
        case = load_case(case)
    step = progress or (lambda description, done=None, total=None: None)
    history_spec = case.get("history", {})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        args = case_arguments(case)
        wear = WearCase.from_keywords(**args)  # every rule checked before the history is read
        units = None
        if "file" in history_spec:
            path = _path(case, history_spec["file"])
            options = history_options(history_spec)
            units = units_read(path, **options)
            if "name" in history_spec:
                options["name"] = history_spec["name"]
            step("computing the wear power")
            # streamed in one pass (the history is never held whole); KWU_EPRI's class counts
            # come in the same pass when FNOR_MAXI and VTAN_MAXI are given, else in a second one
            power = wear_power(
                path, **wear.power_options,
                progress=lambda done: step("computing the wear power", done, None), **options)
        else:
            power = float(case["power"]["value_W"])
        step("building the wear table")
        table = wear_table_from_case(wear, power)
    seen = list(dict.fromkeys(  # keep order, drop repeats
        f"{w.category.__name__}: {w.message}" for w in caught
        if issubclass(w.category, FretwearWarning | UserWarning)))
    return CaseResult(table=table, power=power, warnings=seen, case=case, wear_case=wear,
                      units=units)


#: Histories longer than this many samples get their power computed chunk by chunk (progress).
CHUNK_SAMPLES = 200_000


def history_options(spec: Mapping[str, Any]) -> dict[str, Any]:
    """The :func:`fretwear.io.read_history` options of a ``[history]`` section.

    ``format``, ``units``, ``columns``, ``node`` (the shock point: POST_USURE's NOEUD) and the
    reader's own ``options`` table (``select``, ``index``, ``delimiter`` ...).

    Examples
    --------
    >>> history_options({"file": "n12.tab", "node": "N12", "options": {"index": 1}})
    {'node': 'N12', 'index': 1}
    """
    options = {k: spec[k] for k in ("format", "units", "columns", "node") if k in spec}
    extra = dict(spec.get("options", {}))
    clash = sorted(set(extra) & (set(options) | {"name", "file"}))
    if clash:
        raise KeywordError(f"case: [history] options = {{{', '.join(clash)} = ...}}: give "
                           f"{', '.join(clash)} as [history] keys, not reader options")
    return {**options, **extra}


def chunked_power(history, args: Mapping[str, Any], progress=None, *,
                  chunk_samples: int = CHUNK_SAMPLES):
    """Wear power of an in-memory history, in chunks when it is long, reporting progress.

    The chunks share their boundary sample, so the result equals
    :func:`fretwear.power.wear_power` on the whole history (the reduction is exact, theory §2).

    Parameters
    ----------
    history : ContactHistory
    args : mapping
        ``t_start``, ``t_end`` [s], ``blocks``, ``sectors``, ``stationarity_threshold``.
    progress : callable, optional
        ``progress(description, done, total)`` after each chunk (samples).
    chunk_samples : int
        Samples per chunk (>= 2).
    """
    step = progress or (lambda description, done=None, total=None: None)
    options = dict(t_start=args.get("t_start"), t_end=args.get("t_end"),
                   blocks=args.get("blocks", 1), sectors=args.get("sectors"))
    n = len(history)
    if n <= chunk_samples:
        step("computing the wear power", n, n)
        return wear_power(history, stationarity_threshold=args.get("stationarity_threshold", 0.1),
                          **options)
    if options["t_start"] is None:
        options["t_start"] = float(history.time[0])
    if options["t_end"] is None:
        options["t_end"] = float(history.time[-1])
    acc = PowerAccumulator(**options)
    lo = int(np.searchsorted(history.time, options["t_start"], side="right")) - 1
    hi = int(np.searchsorted(history.time, options["t_end"], side="left")) + 1
    lo, hi = max(lo, 0), min(hi, n)
    for a in range(lo, hi - 1, chunk_samples - 1):
        b = min(a + chunk_samples, hi)
        acc.update(history.replace(**{c: getattr(history, c)[a:b] for c in history.channels}))
        step("computing the wear power", b - lo, hi - lo)
    return acc.result(stationarity_threshold=args.get("stationarity_threshold", 0.1))
