"""Explicit time integration of the modal model with nonlinear shocks: :func:`simulate`.

The loop runs compiled (numba, ``cache=True``) in :mod:`fretwear.dynamics._kernel`; this module
prepares the arrays, checks the time step against the stability limit of the scheme with the
contact stiffness (:func:`stability_limit`), streams the archived samples to memory or to Parquet
files in chunks (bounded memory), and returns a :class:`DynamicsResult` with one
:class:`~fretwear.history.ContactHistory` per shock (every theory §1 channel).
"""

from __future__ import annotations

import contextlib
import math
import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import require
from fretwear.dynamics import _kernel as K
from fretwear.dynamics.excitation import BaseAcceleration, NodalForce
from fretwear.dynamics.modal import DIRECTIONS, ModalModel
from fretwear.dynamics.shocks import Shock, with_code_aster_damping
from fretwear.errors import InputError, StabilityError
from fretwear.history import CHANNELS, ContactHistory
from fretwear.io.atomic import atomic_path

#: Largest number of archived samples × shocks kept in memory without ``output_dir``.
MAX_IN_MEMORY = 20_000_000


def _compliance(model: ModalModel, point: int) -> float:
    """Largest eigenvalue of Σ_r φ_r φ_rᵀ/m_r at a shock point [1/kg]."""
    phi = model.shock_shapes[point]  # (3, n)
    g = (phi / model.masses) @ phi.T
    return float(np.max(np.linalg.eigvalsh(g)))


def stability_limit(model: ModalModel, shocks: Sequence[Shock] = ()) -> dict[str, float]:
    """Critical time step of the explicit scheme, with and without the contact stiffness.

    Parameters
    ----------
    model : ModalModel
        The modes.
    shocks : sequence of Shock
        The contacts (their normal and tangential stiffness and damping).

    Returns
    -------
    dict
        ``time_step_limit`` [s] (in contact), ``free_time_step_limit`` [s] (modes alone, ``inf``
        when every mode is rigid), ``omega_max`` [rad/s], ``damping_ratio`` [-].

    Notes
    -----
    Central difference / velocity Verlet is stable for h ≤ (2/ω_max)(√(1+ξ²) − ξ) (Belytschko
    et al. 2000, eq. 6.3.33). In contact the stiffness matrix gains k·φφᵀ/m at each shock, so by
    Weyl's inequality ω_max² ≤ max_r ω_r² + Σ_shocks (k_n + k_t)·g_i with
    g_i = λ_max(Σ_r φ_r φ_rᵀ/m_r)
    the point's modal compliance [1/kg] (exact for one mode, one shock, no friction). ξ is the
    largest of the modal damping ratios and the contact ratios c·g/(2√(k·g)).

    References
    ----------
    .. [1] Belytschko, T., Liu, W. K., & Moran, B. (2000). *Nonlinear Finite Elements for Continua
           and Structures*. Wiley, §6.3.

    Examples
    --------
    >>> m = ModalModel(frequencies=[0.0], damping_ratios=0.0, masses=1.0,
    ...                shock_shapes=[[[1.0], [0.0]]])
    >>> s = Shock(point=0, obstacle="plane", normal_stiffness=1e6)
    >>> stability_limit(m, [s])["time_step_limit"]   # 2/√(k/m)
    0.002
    """
    shocks = with_code_aster_damping(model, shocks)
    omega = model.omega
    w2 = float(np.max(omega) ** 2)
    xi_modes = float(np.max(model.damping_ratios))
    xi = xi_modes
    extra = 0.0
    for s in shocks:
        g = _compliance(model, model.shock_index(s.point))
        extra += (s.normal_stiffness + s.tangential_stiffness) * g
        for k, c in ((s.normal_stiffness, s.normal_damping),
                     (s.tangential_stiffness, s.tangential_damping)):
            if k > 0 and g > 0:
                xi = max(xi, c * g / (2.0 * math.sqrt(k * g)))
    wmax = math.sqrt(w2 + extra)

    def limit(w: float, z: float) -> float:
        return math.inf if w == 0 else 2.0 / w * (math.sqrt(1.0 + z * z) - z)

    return {"time_step_limit": limit(wmax, xi),
            "free_time_step_limit": limit(math.sqrt(w2), xi_modes),
            "omega_max": wmax, "damping_ratio": xi}


@dataclass
class DynamicsResult:
    """Output of :func:`simulate`.

    Attributes
    ----------
    shock_names : list of str
        One per shock, in the order given.
    time_step : float
        Fine (contact) time step h [s]. ``coarse_step`` [s]: the free-flight step (adaptive).
    archive_step : float
        Sampling of the histories [s].
    n_steps, n_coarse_steps : int
        Fine steps covered and steps actually taken.
    wear_power : ndarray
        Wear power of each shock integrated at every time step (not only the archived samples),
        P = (1/T)∫Fn‖Vt‖dt with the stick rule of theory §2 [W]; compare with
        :func:`fretwear.power.wear_power` on the history to check the archiving step.
    energy : dict
        ``external_work``, ``preload_work``, ``modal_damping_dissipation``,
        ``contact_damping_dissipation``, ``friction_dissipation``, ``stored_initial``,
        ``stored_final``, ``balance_residual`` [J] (residual = ΔE − W_in + D; O(h²)).
    files : dict or None
        Shock name → Parquet file of its history when streamed to disk.
    final_displacement, final_velocity : ndarray
        Modal state at the end [-], [1/s] (to continue a computation).
    elapsed : float
        Wall time [s].
    """

    shock_names: list[str]
    time_step: float
    coarse_step: float
    archive_step: float
    start_time: float
    end_time: float
    n_steps: int
    n_coarse_steps: int
    wear_power: np.ndarray
    energy: dict[str, float]
    final_displacement: np.ndarray
    final_velocity: np.ndarray
    elapsed: float
    files: dict[str, Path] | None = None
    _histories: list[ContactHistory | None] | None = field(default=None, repr=False)

    @property
    def histories(self) -> list[ContactHistory]:
        """One :class:`ContactHistory` per shock (read back from disk when streamed)."""
        return [self.history(i) for i in range(len(self.shock_names))]

    def history(self, shock: int | str = 0) -> ContactHistory:
        """The history of one shock, by index or name (only its file is read when streamed)."""
        if isinstance(shock, str):
            if shock not in self.shock_names:
                raise InputError(f"unknown shock {shock!r}; the result has {self.shock_names}")
            shock = self.shock_names.index(shock)
        if self._histories is None:
            self._histories = [None] * len(self.shock_names)
        if self._histories[shock] is None:
            require("pyarrow.parquet", purpose="reading the dynamics' Parquet histories")
            name = self.shock_names[shock]
            self._histories[shock] = ContactHistory.from_frame(
                pd.read_parquet(self.files[name]), name=name,
                metadata={"source": str(self.files[name])})
        return self._histories[shock]

    def summary(self) -> dict[str, Any]:
        """JSON-ready summary (steps, steps per second, wear powers, energy)."""
        return {"shocks": self.shock_names, "time_step": self.time_step,
                "coarse_step": self.coarse_step, "archive_step": self.archive_step,
                "start_time": self.start_time, "end_time": self.end_time,
                "n_steps": self.n_steps, "n_steps_taken": self.n_coarse_steps,
                "elapsed": self.elapsed,
                "wear_power": dict(zip(self.shock_names, self.wear_power.tolist(), strict=True)),
                "energy": self.energy,
                "files": {k: str(v) for k, v in (self.files or {}).items()}}


def _loads(model: ModalModel, excitations: Sequence[NodalForce | BaseAcceleration]):
    n = model.n_modes
    rows, kinds, hps, tts, tvs, offs = [], [], [], [], [], [0]
    for i, ex in enumerate(excitations):
        d = DIRECTIONS[ex.direction]
        if isinstance(ex, NodalForce):
            if model.forcing_shapes.shape[0] == 0:
                raise InputError(f"excitation {i}: a nodal force needs forcing points in the modal "
                                 "model (forcing_shapes / forcing_positions)")
            rows.append(model.forcing_shapes[model.forcing_index(ex.point), d, :])
        elif isinstance(ex, BaseAcceleration):
            if model.participation is None:
                raise InputError(f"excitation {i}: base acceleration needs the modal participation "
                                 "factors (ModalModel.participation [kg])")
            rows.append(-model.participation[d, :])
        else:
            raise InputError(f"excitation {i}: expected NodalForce or BaseAcceleration, got "
                             f"{type(ex).__name__}")
        sig = ex.signal
        kinds.append(sig.code)
        if sig.code == 0:
            hps.append([sig.amplitude * sig.scale, sig.frequency, math.radians(sig.phase)])
            tts.append(np.zeros(1))
            tvs.append(np.zeros(1))
        else:
            hps.append([0.0, 0.0, 0.0])
            tts.append(np.asarray(sig.table[0], float))
            tvs.append(np.asarray(sig.table[1], float) * sig.scale)
        offs.append(offs[-1] + tts[-1].size)
    if not rows:
        return (np.zeros((0, n)), np.zeros(0, np.int64), np.zeros((0, 3)), np.zeros(1),
                np.zeros(1), np.zeros(1, np.int64))
    return (np.array(rows, float), np.array(kinds, np.int64), np.array(hps, float),
            np.concatenate(tts), np.concatenate(tvs), np.array(offs, np.int64))


def _shock_arrays(model: ModalModel, shocks: Sequence[Shock]):
    ns = len(shocks)
    idx = [model.shock_index(s.point) for s in shocks]
    shapes = np.ascontiguousarray(model.shock_shapes[idx])
    skind = np.array([s.code for s in shocks], np.int64)
    sgap = np.array([s.gap for s in shocks], float)
    sangle = np.radians([s.angle for s in shocks]).astype(float)
    sorig = np.array([s.origin for s in shocks], float).reshape(ns, 2)
    kn = np.array([s.normal_stiffness for s in shocks], float)
    cn = np.array([s.normal_damping for s in shocks], float)
    kt = np.array([s.tangential_stiffness for s in shocks], float)
    ct = np.array([s.tangential_damping for s in shocks], float)
    mu = np.array([s.friction for s in shocks], float)
    mus = np.array([s.static_friction for s in shocks], float)
    spre = np.column_stack([np.cos(sangle), np.sin(sangle)]) * np.array(
        [s.preload for s in shocks], float)[:, None]
    pa, pr, po = [], [], [0]
    for s in shocks:
        if s.obstacle == "profile":
            pa.append(np.radians(s.profile_angles))
            pr.append(np.asarray(s.profile_gaps, float))
        po.append(po[-1] + (pa[-1].size if s.obstacle == "profile" else 0))
    prof_a = np.concatenate(pa) if pa else np.zeros(1)
    prof_r = np.concatenate(pr) if pr else np.zeros(1)
    return (shapes, skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, mus, spre, prof_a, prof_r,
            np.array(po, np.int64))


def _stored(q, v, model, chan, fs, kn, kt) -> tuple[float, float]:
    """(kinetic + modal strain + normal contact spring energy, tangential spring energy) [J]."""
    e = 0.5 * float(np.sum(model.masses * v**2)) + 0.5 * float(
        np.sum(model.masses * model.omega**2 * q**2))
    d = np.clip(chan[:, K.C_DELTA], 0.0, None)
    e += 0.5 * float(np.sum(kn * d**2))
    safe = np.where(kt > 0, kt, 1.0)
    vts = float(np.sum(np.where(kt > 0, np.sum(fs**2, axis=1) / (2 * safe), 0.0)))
    return e, vts


def simulate(model: ModalModel, shocks: Sequence[Shock],
             excitations: Sequence[NodalForce | BaseAcceleration] = (), *, duration: float,
             time_step: float | None = None, archive_step: float | None = None,
             adaptive: bool = False, safety: float = 0.5, initial_displacement=None,
             initial_velocity=None, start_time: float = 0.0,
             output_dir: str | Path | None = None, chunk_size: int = 200_000,
             compiled: bool = True) -> DynamicsResult:
    """Integrate the modal model with its shocks and excitations; one history per shock.

    Parameters
    ----------
    model : ModalModel
        The modes.
    shocks : sequence of Shock
        At least one shock.
    excitations : sequence of NodalForce or BaseAcceleration
        The loads (none: free vibration from the initial state).
    duration : float
        Simulated time [s] (rounded to a whole number of archive steps).
    time_step : float, optional
        Fine time step h [s]; default ``safety × time_step_limit``. Larger than the stability
        limit: :class:`~fretwear.errors.StabilityError`. Reduced so that the archive step is a
        whole number of steps (to the archive step itself when that is smaller).
    archive_step : float, optional
        Sampling of the histories [s], default every step.
    adaptive : bool
        Take coarse steps (``safety × free_time_step_limit``, a divisor of the archive step) while
        every shock is clear of its obstacle by more than twice the distance it can travel in one
        coarse step; fine steps near and in contact.
    safety : float
        Fraction of the stability limits used by default steps, in (0, 1].
    initial_displacement, initial_velocity : array_like, optional
        Modal coordinates q(0) [-] and q̇(0) [1/s], default zero.
    start_time : float
        Time of the first sample [s].
    output_dir : path, optional
        Stream each shock's history to ``<output_dir>/<shock name>.parquet`` in chunks of
        ``chunk_size`` samples (bounded memory); histories are then read back on demand.
    chunk_size : int
        Archive samples per chunk.
    compiled : bool
        Use the numba kernel (``False``: the same code as plain Python, slow; for checks).

    Returns
    -------
    DynamicsResult

    Raises
    ------
    StabilityError
        The step exceeds the stability limit, or the state became non-finite.
    InputError
        Inconsistent inputs (sizes, no shock, too many samples to hold in memory).

    Notes
    -----
    Velocity Verlet (central difference) on the modal coordinates, the shock forces evaluated
    with the predicted velocity v_n + h·a_n: second order in h. Energy bookkeeping (trapezoid on
    the step powers) gives ``energy['balance_residual']``, an O(h²) check of the integration.

    References
    ----------
    .. [1] Code_Aster Reference Manual R5.06.04, *Algorithmes d'intégration temporelle de
           DYNA_VIBRA* (DIFF_CENTRE), EDF R&D.

    Examples
    --------
    >>> from fretwear.dynamics.modal import ModalModel
    >>> m = ModalModel(frequencies=[10.0], damping_ratios=0.0, masses=1.0,
    ...                shock_shapes=[[[1.0], [0.0]]])
    >>> s = Shock(point=0, obstacle="plane", gap=1.0, normal_stiffness=1e4)
    >>> r = simulate(m, [s], duration=0.1, time_step=1e-4, archive_step=1e-3,
    ...              initial_displacement=[1e-3])
    >>> h = r.history(0)
    >>> len(h), round(float(h.dy[-1]), 6)   # 1e-3·cos(2π·10·0.1)
    (101, 0.001)
    """
    t_wall = _time.perf_counter()
    shocks = list(shocks)
    if not shocks:
        raise InputError("simulate: give at least one shock (a Shock per contact point)")
    shocks = with_code_aster_damping(model, shocks)  # tangential_damping=None: Code_Aster's
    if not (0 < safety <= 1):
        raise InputError(f"simulate: 'safety' must be in (0, 1], got {safety}")
    if not (np.isfinite(duration) and duration > 0):
        raise InputError(f"simulate: 'duration' must be > 0 [s], got {duration}")
    lim = stability_limit(model, shocks)
    hcrit = lim["time_step_limit"]
    if time_step is None:
        if not math.isfinite(hcrit):
            raise InputError("simulate: give 'time_step' [s] (no stiffness to derive one)")
        time_step = safety * hcrit
    time_step = float(time_step)
    if not (np.isfinite(time_step) and time_step > 0):
        raise InputError(f"simulate: 'time_step' must be > 0 [s], got {time_step}")
    if time_step > hcrit:
        raise StabilityError(
            f"time_step = {time_step:.4g} s exceeds the stability limit {hcrit:.4g} s of the "
            f"explicit scheme (ω_max = {lim['omega_max']:.4g} rad/s from the highest mode and the "
            f"contact stiffness, damping ratio {lim['damping_ratio']:.3g}); use time_step <= "
            f"{0.5 * hcrit:.3g} s (half the limit, for accuracy), lower the contact stiffness, or "
            "leave time_step unset to get it chosen")
    archive_step = time_step if archive_step is None else float(archive_step)
    if not (np.isfinite(archive_step) and archive_step > 0):
        raise InputError(f"simulate: 'archive_step' must be > 0 [s], got {archive_step}")
    every = max(1, math.ceil(archive_step / time_step - 1e-9))
    h = archive_step / every
    n_archive = int(round(duration / archive_step))
    if n_archive < 1:
        raise InputError(f"simulate: duration {duration} s is shorter than one archive step "
                         f"{archive_step} s")
    m_coarse = 1
    if adaptive:
        free = lim["free_time_step_limit"]
        m_max = every if not math.isfinite(free) else max(1, int(safety * free / h))
        m_coarse = max(d for d in range(1, every + 1) if every % d == 0 and d <= m_max)
    n = model.n_modes
    q = np.zeros(n) if initial_displacement is None else np.array(initial_displacement, float)
    v = np.zeros(n) if initial_velocity is None else np.array(initial_velocity, float)
    for key, arr in (("initial_displacement", q), ("initial_velocity", v)):
        if arr.shape != (n,) or not np.all(np.isfinite(arr)):
            raise InputError(f"simulate: {key!r} must hold {n} finite modal values, got shape "
                             f"{arr.shape}")
    ns = len(shocks)
    names = [s.label if s.name else (model.shock_names[model.shock_index(s.point)]) for s in shocks]
    if len(set(names)) != ns:
        names = [f"{nm}_{i + 1}" for i, nm in enumerate(names)]
    n_samples = n_archive + 1
    if output_dir is None and n_samples * ns > MAX_IN_MEMORY:
        raise InputError(f"simulate: {n_samples} samples × {ns} shocks exceed the in-memory limit "
                         f"({MAX_IN_MEMORY}); give output_dir=... to stream to Parquet, or a "
                         "larger archive_step")
    t_final = float(start_time) + n_archive * archive_step
    for i, ex in enumerate(excitations):
        sig = getattr(ex, "signal", None)
        if getattr(sig, "kind", None) == "random" and sig.table[0][-1] < t_final * (1 - 1e-12):
            raise InputError(
                f"excitation {i}: its random signal covers [0, {sig.table[0][-1]:g}] s but the "
                f"simulation runs to {t_final:g} s (beyond its end the signal would stay "
                f"constant); give the Signal a duration >= {t_final:g} s")
    lshape, lkind, lhp, tab_t, tab_v, tab_off = _loads(model, excitations)
    (shapes, skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, mus, spre, prof_a, prof_r,
     prof_off) = _shock_arrays(model, shocks)
    omega = np.ascontiguousarray(model.omega, dtype=float)
    zeta = np.ascontiguousarray(model.damping_ratios, dtype=float)
    mass = np.ascontiguousarray(model.masses, dtype=float)
    invmass = 1.0 / mass
    a = np.zeros(n)
    ptr = tab_off[:-1].copy() if lkind.size else np.zeros(0, np.int64)
    fs = np.zeros((ns, 3))
    uprev = np.einsum("icr,r->ic", shapes, q)
    incontact = np.zeros(ns, np.int64)
    frame = np.zeros((ns, 2))
    chan = np.zeros((ns, 10))
    energy = np.zeros(K.N_ENERGY)
    wear = np.zeros(ns)
    pprev = np.zeros(5)
    adv = K.advance if compiled else K.advance.py_func
    common_loads = (lshape, lkind, lhp, tab_t, tab_v, tab_off, ptr)
    common_shocks = (skind, sgap, sangle, sorig, kn, cn, kt, ct, mu, mus, spre, prof_a, prof_r,
                     prof_off, fs, uprev, incontact, frame, chan)
    counters = np.zeros(2, np.int64)
    adv(0, False, True, 0, float(start_time), h, m_coarse, every, adaptive, q, v, a, omega,
        zeta, invmass, mass, shapes, *common_loads, *common_shocks, energy, wear, pprev,
        np.empty((0, ns, 10)), counters)
    e0, vts0 = _stored(q, v, model, chan, fs, kn, kt)

    chunk = max(2, int(chunk_size))
    buffers: list[np.ndarray] = []
    files: dict[str, Path] | None = None
    with contextlib.ExitStack() as stack:
        writers = None
        if output_dir is not None:  # pyarrow only when streaming to Parquet
            pa = require("pyarrow", purpose="streaming the dynamics to Parquet (output_dir)")
            pq = require("pyarrow.parquet",
                         purpose="streaming the dynamics to Parquet (output_dir)")
            out_dir = Path(output_dir)
            files = {nm: out_dir / f"{nm}.parquet" for nm in names}
            schema = pa.schema([(c, pa.float64()) for c in CHANNELS])
            writers = []
            for nm in names:
                tmp = stack.enter_context(atomic_path(files[nm]))
                writers.append(stack.enter_context(pq.ParquetWriter(tmp, schema)))
        k = 0
        remaining = n_samples
        first = True
        while remaining > 0:
            n_out = min(chunk, remaining)
            out = np.empty((n_out, ns, 10))
            k = adv(n_out, first, False, k, float(start_time), h, m_coarse, every, adaptive,
                    q, v, a, omega, zeta, invmass, mass, shapes, *common_loads,
                    *common_shocks, energy, wear, pprev, out, counters)
            if k < 0:
                raise StabilityError(
                    f"the integration became unstable (non-finite state) with time_step {h:.4g} s "
                    f"(limit estimate {hcrit:.4g} s); reduce time_step"
                    + (" or disable adaptive" if adaptive else ""))
            if writers is not None:
                for i, w in enumerate(writers):
                    w.write_table(pa.table({c: out[:, i, j] for j, c in enumerate(CHANNELS)}))
            else:
                buffers.append(out)
            remaining -= n_out
            first = False
    e1, vts1 = _stored(q, v, model, chan, fs, kn, kt)
    t_end = float(start_time) + k * h
    total = t_end - float(start_time)
    energy_d = {
        "external_work": float(energy[K.E_EXT]),
        "preload_work": float(energy[K.E_PRE]),
        "modal_damping_dissipation": float(energy[K.E_DAMP]),
        "contact_damping_dissipation": float(energy[K.E_CN]),
        "friction_dissipation": float(-energy[K.E_FRIC] - (vts1 - vts0)),
        "stored_initial": e0 + vts0,
        "stored_final": e1 + vts1,
    }
    energy_d["balance_residual"] = (
        energy_d["stored_final"] - energy_d["stored_initial"] - energy_d["external_work"]
        - energy_d["preload_work"] + energy_d["modal_damping_dissipation"]
        + energy_d["contact_damping_dissipation"] + energy_d["friction_dissipation"])
    histories = None
    if files is None:
        data = np.concatenate(buffers, axis=0)
        histories = []
        for i, nm in enumerate(names):
            cols = {c: data[:, i, j] for j, c in enumerate(CHANNELS)}
            histories.append(ContactHistory(**cols, name=nm, metadata={
                "source": "fretwear.dynamics.simulate", "shock": nm,
                "obstacle": shocks[i].obstacle, "time_step": h, "archive_step": archive_step,
                "tangential_damping": shocks[i].tangential_damping}))
    return DynamicsResult(
        shock_names=names, time_step=h, coarse_step=h * m_coarse, archive_step=archive_step,
        start_time=float(start_time), end_time=t_end, n_steps=int(counters[0]),
        n_coarse_steps=int(counters[1]), wear_power=wear / total, energy=energy_d,
        final_displacement=q.copy(), final_velocity=v.copy(),
        elapsed=_time.perf_counter() - t_wall, files=files, _histories=histories)
