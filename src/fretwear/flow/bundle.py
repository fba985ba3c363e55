"""``fretwear simulate``: a bundle's contact histories from its description, on Dask.

For each tube (one task): the modes of its span (:func:`~fretwear.flow.tube.beam_tube_flow`),
the turbulence of its flow projected onto them (:mod:`~fretwear.flow.spectra`), correlated modal
forces synthesised from that matrix (:func:`~fretwear.flow.synthesis.synthesize`), the shock
dynamics (:func:`fretwear.dynamics.simulate`) and the stability ratios of its modes
(:func:`~fretwear.flow.stability.stability_ratios`). Each tube's folder is written atomically
with a ``tube.json`` carrying its inputs' signature, so a rerun into the same directory skips
the tubes already done (``force`` recomputes); a tube that fails is recorded and the others go
on. The manifest (``manifest.csv``) is the one ``fretwear bundle`` reads.
"""

from __future__ import annotations

import dataclasses
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.bundle.cluster import open_engine
from fretwear.dynamics import NodalForce, Shock, Signal, simulate
from fretwear.errors import InputError
from fretwear.flow.description import TubeSpec, read_description
from fretwear.flow.spectra import make_spectrum
from fretwear.flow.stability import NEAR_CRITICAL, near_critical, stability_ratios
from fretwear.flow.synthesis import synthesize
from fretwear.flow.tube import beam_tube_flow
from fretwear.io import write_history
from fretwear.io.atomic import atomic_folder, atomic_write
from fretwear.io.text_tables import number, read_text_table

#: Columns of the manifest written (``fretwear bundle`` reads them as they are).
MANIFEST_COLUMNS = ("contact", "history", "tube_row", "tube_column", "support",
                    "wall_thickness_m")


def _profile(spec: TubeSpec, index: int) -> Callable[[float], float]:
    def value(s: float) -> float:
        for start, end, *values in spec.regions:
            if start <= s <= end:
                return values[index]
        return 0.0 if index == 0 else float(np.mean([r[2 + index] for r in spec.regions]))
    return value


def tube_forces(spec: TubeSpec):
    """The tube's modal model, its flow, and its synthesised modal forces (time [s], (N, n) [N])."""
    model, tube = beam_tube_flow(
        **spec.beam, shock_positions=[s["position_m"] for s in spec.supports],
        shock_names=[s["name"] for s in spec.supports], diameter=spec.diameter,
        grid_points=spec.grid_points, velocity=_profile(spec, 0), density=_profile(spec, 1),
        void_fraction=_profile(spec, 2))
    params = {k: v for k, v in spec.spectrum.items() if k != "name"}
    spectrum = make_spectrum(spec.spectrum["name"], **params)
    f = np.linspace(*spec.band_hz, spec.frequency_points)
    matrices = spectrum.modal_spectrum(f, tube)
    t, forces = synthesize(f, matrices, duration=spec.duration, seed=spec.seed)
    return model, tube, t, forces


def modal_loads(model, tube, times, forces) -> tuple:
    """The model driven by its generalised forces, each along its own mode's plane.

    Every mode r of a straight tube bends in one transverse plane, y or z (its largest shape
    component on the grid); its synthesised generalised force Q_r(t) [N] (the turbulence of
    both transverse directions projected onto it, :mod:`fretwear.flow.spectra`) is applied at a
    forcing point ``mode<r>`` whose shape is 1 on mode r alone, along that plane.

    Parameters
    ----------
    model : ModalModel
        The tube's modes (n of them).
    tube : TubeFlow
        Its shapes along y and z on the grid [-] (to find each mode's plane).
    times : ndarray, shape (N,)
        [s].
    forces : ndarray, shape (N, n)
        Generalised forces Q_r(t) [N].

    Returns
    -------
    (ModalModel, list of NodalForce)
        The model with one forcing point per mode, and one load per mode.

    Examples
    --------
    >>> from fretwear.flow.tube import beam_tube_flow
    >>> m, tube = beam_tube_flow(young_modulus=2e11, second_moment=1e-8, mass_per_length=1.0,
    ...                          length=1.0, n_modes=1, shock_positions=[0.5], diameter=0.02)
    >>> driven, loads = modal_loads(m, tube, np.array([0.0, 1.0]), np.ones((2, 2)))
    >>> [(ld.point, ld.direction) for ld in loads]
    [('mode1', 'y'), ('mode2', 'z')]
    """
    n = model.n_modes
    plane = np.argmax(np.max(np.abs(tube.shapes), axis=0), axis=0)  # (n,): 0 = y, 1 = z
    shapes = np.zeros((n, 2, n))
    shapes[np.arange(n), plane, np.arange(n)] = 1.0
    names = tuple(f"mode{r + 1}" for r in range(n))
    driven = dataclasses.replace(model, forcing_shapes=shapes, forcing_names=names)
    loads = [NodalForce(names[r], "yz"[plane[r]],
                        Signal("table", times=times, values=forces[:, r])) for r in range(n)]
    return driven, loads


def simulate_tube(spec: TubeSpec, folder: str | Path) -> dict:
    """Run one tube and write its histories and ``tube.json`` into ``folder`` (atomically).

    Returns
    -------
    dict
        The tube's record: ``tube``, ``row``, ``column``, ``signature``, ``contacts`` (contact,
        history relative to the output directory, support, gap_m), ``modes`` (the stability
        table's rows), ``max_stability_ratio``, ``flagged``, ``simulated_s``, ``elapsed_s``.
    """
    start = time.perf_counter()
    model, tube, t, forces = tube_forces(spec)
    driven, loads = modal_loads(model, tube, t, forces)
    shocks = [Shock(point=s["name"], obstacle=s["obstacle"], gap=s["gap_m"],
                    normal_stiffness=s["normal_stiffness_n_m"],
                    normal_damping=s["normal_damping_n_s_m"],
                    tangential_stiffness=s["tangential_stiffness_n_m"],
                    tangential_damping=s["tangential_damping_n_s_m"], friction=s["friction"],
                    name=s["name"]) for s in spec.supports]
    result = simulate(driven, shocks, loads, duration=spec.duration,
                      archive_step=spec.archive_step)
    modes = stability_ratios(model, tube, mass_per_length=spec.mass_per_length,
                             constant=spec.connors_constant, margin=spec.stability_margin)
    folder = Path(folder)
    contacts = []
    with atomic_folder(folder) as tmp:
        for s in spec.supports:
            contact = f"{spec.tube}-{s['name']}"
            write_history(result.history(s["name"]).replace(name=contact),
                          tmp / f"{s['name']}.parquet")
            contacts.append({"contact": contact, "support": s["name"], "gap_m": s["gap_m"],
                             "history": f"tubes/{spec.tube}/{s['name']}.parquet"})
        record = {"tube": spec.tube, "row": spec.row, "column": spec.column,
                  "signature": spec.signature(), "contacts": contacts,
                  "wall_thickness_m": spec.wall_thickness, "span_length_m": spec.beam["length"],
                  **spec.extra,
                  "modes": json.loads(modes.to_json(orient="records")),
                  "max_stability_ratio": float(modes["stability_ratio"].max()),
                  "flagged": bool(modes["flagged"].any()),
                  "wear_power_w": dict(zip(result.shock_names, result.wear_power.tolist(),
                                           strict=True)),
                  "simulated_s": float(result.end_time - result.start_time),
                  "elapsed_s": time.perf_counter() - start}
        (tmp / "tube.json").write_text(json.dumps(record, indent=1), encoding="utf-8")
    return record


def _guarded(spec: TubeSpec, folder: Path) -> dict | str:
    """:func:`simulate_tube`, a failure returned as its message (isolated from the others)."""
    try:
        return simulate_tube(spec, folder)
    except Exception as exc:  # noqa: BLE001 - one tube's failure is recorded, the rest go on
        return f"{type(exc).__name__}: {exc}"


def _done(folder: Path, spec: TubeSpec) -> dict | None:
    try:
        record = json.loads((folder / "tube.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if record.get("signature") != spec.signature():
        return None
    if not all((folder.parent.parent / c["history"]).exists() for c in record["contacts"]):
        return None
    return record


@dataclass
class SimulateResult:
    """Output of :func:`run_simulate`: one record per tube done, the failures, the files."""

    output: Path
    records: list[dict]
    errors: dict[str, str]
    reused: list[str]

    def tubes(self) -> pd.DataFrame:
        """One row per tube: row, column, max stability ratio, flagged, worst wear power [W];
        the flagged tubes first, then by decreasing ratio (bad news first)."""
        rows = [{"tube": r["tube"], "row": r["row"], "column": r["column"],
                 "max_stability_ratio": r["max_stability_ratio"], "flagged": r["flagged"],
                 "max_wear_power_w": max(r["wear_power_w"].values()),
                 "simulated_s": r["simulated_s"], "elapsed_s": r["elapsed_s"]}
                for r in self.records]
        frame = pd.DataFrame(rows, columns=["tube", "row", "column", "max_stability_ratio",
                                            "flagged", "max_wear_power_w", "simulated_s",
                                            "elapsed_s"])
        return frame.sort_values(["flagged", "max_stability_ratio"], ascending=False,
                                 kind="stable").reset_index(drop=True)

    def manifest(self) -> pd.DataFrame:
        """The manifest of ``fretwear bundle`` (:data:`MANIFEST_COLUMNS`)."""
        rows = [{"contact": c["contact"], "history": c["history"], "tube_row": r["row"],
                 "tube_column": r["column"], "support": c["support"],
                 "wall_thickness_m": r["wall_thickness_m"]}
                for r in sorted(self.records, key=lambda r: (r["row"], r["column"]))
                for c in r["contacts"]]
        return pd.DataFrame(rows, columns=list(MANIFEST_COLUMNS))


def _write_tables(result: SimulateResult) -> None:
    out = result.output
    with atomic_write(out / "manifest.csv") as fh:
        result.manifest().to_csv(fh, index=False)
    with atomic_write(out / "tubes.csv") as fh:
        result.tubes().to_csv(fh, index=False, float_format="%.6g")
    modes = [{"tube": r["tube"], **m} for r in result.records for m in r["modes"]]
    with atomic_write(out / "stability.csv") as fh:
        pd.DataFrame(modes).to_csv(fh, index=False, float_format="%.6g")
    gaps = [{"contact": c["contact"], "gap_m": c["gap_m"]} for r in result.records
            for c in r["contacts"]]
    with atomic_write(out / "gaps.csv") as fh:
        pd.DataFrame(gaps, columns=["contact", "gap_m"]).to_csv(fh, index=False,
                                                                 float_format="%.6g")
    with atomic_write(out / "errors.csv") as fh:
        pd.DataFrame(sorted(result.errors.items()), columns=["tube", "error"]).to_csv(
            fh, index=False)


def run_simulate(description, output, *, scheduler=None, workers: int | None = None,
                 force: bool = False, progress: Callable[[str, bool], None] | None = None
                 ) -> SimulateResult:
    """Simulate every tube of a bundle description into ``output`` (resumable).

    Parameters
    ----------
    description : path or list of TubeSpec
        The bundle description (TOML, :func:`read_description`) or its tubes.
    output : path
        Output directory: ``tubes/<tube>/<support>.parquet`` and ``tube.json`` per tube,
        ``manifest.csv`` (for ``fretwear bundle``), ``tubes.csv`` (stability ratio and wear power
        per tube), ``stability.csv`` (per mode), ``gaps.csv``, ``errors.csv``.
    scheduler : None, "serial", address or dask Client
        As ``fretwear bundle``: a local cluster (None), this process ("serial"), or a cluster.
    workers : int, optional
        Worker processes of the local cluster (default: one per core).
    force : bool
        Recompute the tubes already done.
    progress : callable, optional
        Called as ``progress(tube, ok)`` when each tube finishes (or is reused).

    Returns
    -------
    SimulateResult
    """
    specs = read_description(description) if isinstance(description, (str, Path)) \
        else list(description)
    if not specs:
        raise InputError("simulate: the description has no tube")
    out = Path(output)
    if out.exists() and not out.is_dir():
        raise InputError(f"simulate: output {str(out)!r} is a file; give a directory")
    records, errors, reused, todo = [], {}, [], []
    for spec in specs:
        record = None if force else _done(out / "tubes" / spec.tube, spec)
        if record is not None:
            records.append(record)
            reused.append(spec.tube)
            if progress:
                progress(spec.tube, True)
        else:
            todo.append(spec)
    if todo:
        engine = open_engine(scheduler, workers)
        try:
            handles = {engine.submit(_guarded, spec, out / "tubes" / spec.tube, retries=0,
                                     key=f"simulate-{spec.tube}-{spec.signature()}"): spec
                       for spec in todo}
            for handle, value in engine.results(list(handles)):
                spec = handles[handle]
                ok = isinstance(value, dict)
                if ok:
                    records.append(value)
                else:  # the task's own message, or the exception of a task lost by Dask
                    errors[spec.tube] = (value if isinstance(value, str)
                                         else f"{type(value).__name__}: {value}")
                if progress:
                    progress(spec.tube, ok)
        finally:
            engine.close()
    result = SimulateResult(out, sorted(records, key=lambda r: (r["row"], r["column"])), errors,
                            reused)
    _write_tables(result)
    return result


#: The columns of ``tubes.csv`` that :func:`simulate_bundle` writes beside its manifest.
TUBES_COLUMNS = ("tube", "max_stability_ratio", "flagged")
#: The columns of the flagged tubes (:func:`unstable_tubes`, ``unstable_tubes.csv``).
UNSTABLE_COLUMNS = ("tube", "tube_row", "tube_column", "max_stability_ratio")


def _simulated_tubes(manifest: str | Path) -> pd.DataFrame | None:
    """The ``tubes.csv`` of a simulation beside ``manifest``: ``tube``, ``tube_row``,
    ``tube_column``, ``max_stability_ratio`` [-], ``flagged``; None without one."""
    path = Path(manifest).parent / "tubes.csv"
    if not path.is_file():
        return None
    frame = read_text_table(path, "simulation's tube table")
    if not set(TUBES_COLUMNS) <= set(frame.columns):
        return None  # a tubes.csv of another origin: not the simulation's
    return pd.DataFrame({"tube": frame["tube"].astype(str),
                         "tube_row": [int(number(v)) for v in frame["row"]],
                         "tube_column": [int(number(v)) for v in frame["column"]],
                         "max_stability_ratio": [number(v) for v in
                                                 frame["max_stability_ratio"]],
                         "flagged": frame["flagged"].str.lower().isin(("true", "1", "yes"))})


def unstable_tubes(manifest: str | Path) -> pd.DataFrame | None:
    """The tubes a simulation flagged fluid-elastically unstable, read from the ``tubes.csv``
    that ``fretwear simulate`` writes beside ``manifest``.

    Above Connors' critical velocity the tube's amplitude is no longer bounded by the
    turbulence it was simulated under, so a wear forecast computed from its histories is
    not valid: ``fretwear bundle`` says these tubes first.

    Parameters
    ----------
    manifest : path-like
        The bundle's manifest (``manifest.csv`` of ``fretwear simulate``).

    Returns
    -------
    DataFrame or None
        ``tube``, ``tube_row``, ``tube_column`` (the manifest's identity columns) and
        ``max_stability_ratio`` [-] (U_eff/U_c, the largest over the tube's modes) of every
        flagged tube, largest ratio first; empty when none is flagged;
        None when no ``tubes.csv`` of a simulation sits beside the manifest (a manifest
        written by hand, or by Code_Aster's results).

    Examples
    --------
    >>> tubes = unstable_tubes("examples/bundle/manifest.csv")
    >>> list(tubes["tube"]), float(tubes["max_stability_ratio"].iloc[0])
    (['R4C1', 'R4C2', 'R4C3'], 1.11602)
    """
    frame = _simulated_tubes(manifest)
    if frame is None:
        return None
    return frame.loc[frame["flagged"], list(UNSTABLE_COLUMNS)].sort_values(
        "max_stability_ratio", ascending=False, kind="stable").reset_index(drop=True)


def near_critical_tubes(manifest: str | Path, threshold: float = NEAR_CRITICAL
                        ) -> pd.DataFrame | None:
    """The tubes of a simulation in the near-critical band: not flagged unstable, but with a
    stability ratio U_eff/U_c above the design ``threshold`` (read from the ``tubes.csv`` that
    ``fretwear simulate`` writes beside ``manifest``).

    Parameters
    ----------
    manifest : path-like
        The bundle's manifest (``manifest.csv`` of ``fretwear simulate``).
    threshold : float
        Design threshold on U_eff/U_c [-] (default
        :data:`~fretwear.flow.stability.NEAR_CRITICAL`, 0.75: a 25 % margin on the critical
        velocity).

    Returns
    -------
    DataFrame or None
        ``tube``, ``tube_row``, ``tube_column``, ``max_stability_ratio`` [-] and
        ``threshold`` [-] of every such tube, largest ratio first (empty when none); None when
        no simulation's ``tubes.csv`` sits beside the manifest.

    Examples
    --------
    >>> tubes = near_critical_tubes("examples/bundle/manifest.csv")
    >>> list(tubes["tube"]), float(tubes["max_stability_ratio"].iloc[0])
    (['R3C1', 'R3C2', 'R3C3', 'R2C1', 'R2C2', 'R2C3'], 0.95659)
    >>> list(near_critical_tubes("examples/bundle/manifest.csv", 0.9)["tube"])
    ['R3C1', 'R3C2', 'R3C3']
    """
    frame = _simulated_tubes(manifest)
    if frame is None:
        return None
    band = ~frame["flagged"] & near_critical(frame["max_stability_ratio"].to_numpy(),
                                             threshold=threshold, margin=math.inf)
    out = frame.loc[band, list(UNSTABLE_COLUMNS)].assign(threshold=float(threshold))
    return out.sort_values("max_stability_ratio", ascending=False,
                           kind="stable").reset_index(drop=True)


UNSTABLE_FILE = "unstable_tubes.csv"
"""The flagged tubes, kept in a bundle's output directory by ``fretwear bundle`` so that
``fretwear assess`` and ``fretwear calibrate --bundle`` say them first without the manifest."""

NEAR_CRITICAL_FILE = "near_critical_tubes.csv"
"""The near-critical tubes (:func:`near_critical_tubes`), kept beside :data:`UNSTABLE_FILE`."""


def record_unstable(output: str | Path, tubes: pd.DataFrame | None,
                    name: str = UNSTABLE_FILE) -> Path | None:
    """Keep the tubes a simulation flagged unstable in a bundle's output directory.

    Parameters
    ----------
    output : path-like
        The bundle's output directory (``fretwear bundle -o OUT``).
    tubes : DataFrame or None
        :func:`unstable_tubes` of the bundle's manifest. None (no simulation beside the
        manifest) writes nothing; an empty frame writes the header only, so that a rerun on
        a manifest whose tubes are now stable replaces an earlier list.
        :func:`near_critical_tubes` with ``name=NEAR_CRITICAL_FILE``.
    name : str
        The file's name in ``output``.

    Returns
    -------
    Path or None
        ``OUT/unstable_tubes.csv`` (or ``name``; written atomically), or None.
    """
    if tubes is None:
        return None
    path = Path(output) / name
    with atomic_write(path, newline="") as f:
        tubes.to_csv(f, index=False)
    return path


def recorded_unstable(output: str | Path, name: str = UNSTABLE_FILE) -> pd.DataFrame | None:
    """The flagged tubes :func:`record_unstable` kept in a bundle's output directory.

    Parameters
    ----------
    output : path-like
        The bundle's output directory.
    name : str
        :data:`UNSTABLE_FILE`, or :data:`NEAR_CRITICAL_FILE` for the near-critical tubes.

    Returns
    -------
    DataFrame or None
        ``tube``, ``tube_row``, ``tube_column``, ``max_stability_ratio`` [-] (and
        ``threshold`` [-] for the near-critical tubes), largest ratio first (empty when none);
        None where the bundle was not simulated by ``fretwear simulate`` (no such file).

    Examples
    --------
    >>> import tempfile
    >>> out = tempfile.mkdtemp()
    >>> _ = record_unstable(out, unstable_tubes("examples/bundle/manifest.csv"))
    >>> list(recorded_unstable(out)["tube"])
    ['R4C1', 'R4C2', 'R4C3']
    >>> recorded_unstable(tempfile.mkdtemp()) is None
    True
    """
    path = Path(output) / name
    if not path.is_file():
        return None
    frame = read_text_table(path, "bundle's unstable tubes")
    need = UNSTABLE_COLUMNS + (("threshold",) if name == NEAR_CRITICAL_FILE else ())
    if not set(need) <= set(frame.columns):
        raise InputError(f"{path}: not the tubes fretwear bundle writes (columns "
                         f"{', '.join(need)}); remove the file, or rerun fretwear bundle")
    out = pd.DataFrame({"tube": frame["tube"].astype(str),
                        "tube_row": [int(number(v)) for v in frame["tube_row"]],
                        "tube_column": [int(number(v)) for v in frame["tube_column"]],
                        "max_stability_ratio": [number(v) for v in
                                                frame["max_stability_ratio"]]})
    if "threshold" in need:
        out["threshold"] = [number(v) for v in frame["threshold"]]
    return out


def _named(tubes: pd.DataFrame, count: int = 5) -> tuple[str, str]:
    """The first ``count`` tubes with their stability ratio, and how many more."""
    worst = ", ".join(f"{t} ({r:.3g})" for t, r in zip(tubes["tube"][:count],
                                                      tubes["max_stability_ratio"][:count],
                                                      strict=True))
    return worst, f" and {len(tubes) - count} more" if len(tubes) > count else ""


def instability_lines(tubes) -> list[str]:
    """The first line of ``fretwear bundle``, ``assess``, ``calibrate --bundle`` and the
    bundle's reports when ``fretwear simulate`` flagged tubes unstable (``tubes``: of
    :func:`unstable_tubes` or :func:`recorded_unstable`, or its records as an assessment's
    ``inputs["unstable_tubes"]`` keeps them; None or empty: no line)."""
    if tubes is None or not len(tubes):
        return []
    tubes = pd.DataFrame(tubes)
    worst, more = _named(tubes)
    return [f"FLUID-ELASTICALLY UNSTABLE: {len(tubes)} tube(s) flagged by the simulation "
            f"(tubes.csv beside the manifest; stability ratio U_eff/U_c): {worst}{more}. "
            "Above the critical velocity the amplitude is not bounded by the turbulence "
            "simulated: these tubes' wear and forecasts below are NOT valid."]


def near_critical_lines(tubes) -> list[str]:
    """The line that follows the bad news of ``fretwear bundle``, ``assess``, ``calibrate
    --bundle`` and the bundle's reports when tubes sit in the near-critical band (``tubes``:
    of :func:`near_critical_tubes` or :func:`recorded_unstable` with
    :data:`NEAR_CRITICAL_FILE`, or its records; None or empty: no line).

    Examples
    --------
    >>> near_critical_lines(near_critical_tubes("examples/bundle/manifest.csv", 0.9))[0][:60]
    'NEAR-CRITICAL (fluid-elastic): 3 tube(s) with a stability ra'
    """
    if tubes is None or not len(tubes):
        return []
    tubes = pd.DataFrame(tubes)
    worst, more = _named(tubes)
    threshold = float(tubes["threshold"].iloc[0])
    return [f"NEAR-CRITICAL (fluid-elastic): {len(tubes)} tube(s) with a stability ratio "
            f"U_eff/U_c above the design threshold {threshold:g} but not flagged unstable: "
            f"{worst}{more}. Less than the design margin on the critical velocity is left "
            "for the scatter of Connors' constant and of the damping: their forecasts hold "
            "only at the flow simulated (threshold: --near-critical)."]
