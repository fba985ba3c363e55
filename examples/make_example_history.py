"""Build the demo contact history: a tube section rattling in a circular support gap.

Model (the classical single-span picture of a steam-generator tube at a loose support, reduced to
the tube's section at the support):

* a rigid section of mass ``m`` = 0.5 kg with two lateral degrees of freedom ``y``, ``z``
  (springs ``k = m·(2π·30 Hz)²``, damping ratio 1.5 %) and one axial degree of freedom ``x``
  (47 Hz, 2 %), so that sliding has a circumferential and an axial component;
* inside a circular hole of radial clearance ``g`` = 0.2 mm; contact by a penalty spring
  ``k_c`` = 10⁶ N/m: ``Fn = k_c·(r − g)`` when ``r = √(y² + z²) > g``, along the outward normal
  ``n = (y, z)/r``;
* regularised Coulomb friction (μ = 0.3) in the tangent plane, spanned by the circumferential
  direction ``e1 = (−n_z, n_y)`` and the axis ``e2 = x``: ``Ft = −μ·Fn·v_t / max(‖v_t‖, v_reg)``,
  with ``v_reg`` = 1 mm/s. A contact sample with ``‖v_t‖ < v_reg`` is flagged sticking;
* excited by a harmonic force along ``y`` (28 Hz, near the lateral resonance, as a stand-in for
  the periodic part of the flow forces) plus band-limited Gaussian turbulence (< 150 Hz) on all
  three axes, from a seeded generator (reproducible).

Time integration: semi-implicit (symplectic) Euler with a fixed step dt = 10 µs, far below the
stability limits 2/ω_contact ≈ 1.4 ms (contact frequency √((k + k_c)/m)/2π ≈ 227 Hz) and
2m·v_reg/(μ·Fn_max) for the friction regularisation (checked at run time). One second of
warm-up is discarded; 3 s are archived at 5 kHz.

Archived channels (theory §1, SI units, shock-local frame): ``time`` [s], ``normal_force`` [N],
``ft1``, ``ft2`` [N] (friction on the tube along e1, e2), ``vn`` [m/s] (``v·n``, positive moving
into the obstacle), ``vt1``, ``vt2`` [m/s] (sliding velocity along e1, e2), ``dy``, ``dz`` [m]
(section displacement, whose angle ``atan2(dz, dy)`` is the contact angle), ``stick`` [-].

Usage::

    python examples/make_example_history.py            # writes examples/data/oscillator_gap.csv
    python examples/make_example_history.py --seed 3 --duration 5 --output other.csv
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from scipy import signal

from fretwear import ContactHistory
from fretwear.io import write_history

try:  # numba makes the 400 000 steps take a fraction of a second; plain Python also works
    from numba import njit
except ImportError:  # pragma: no cover - optional dependency
    def njit(*args, **kwargs):
        return (lambda f: f) if not (args and callable(args[0])) else args[0]

#: Model parameters (SI), recorded in the metadata of the written history.
PARAMETERS = {
    "mass": 0.5,                 # [kg] section mass
    "lateral_frequency": 30.0,   # [Hz]
    "lateral_damping": 0.015,    # [-] damping ratio
    "axial_frequency": 47.0,     # [Hz]
    "axial_damping": 0.02,       # [-]
    "clearance": 0.2e-3,         # [m] radial gap
    "contact_stiffness": 1.0e6,  # [N/m] penalty
    "friction": 0.3,             # [-] Coulomb coefficient
    "regularisation_speed": 1.0e-3,  # [m/s]
    "harmonic_force": 0.6,       # [N] amplitude along y
    "harmonic_frequency": 28.0,  # [Hz]
    "turbulence_rms": (0.5, 0.5, 0.3),  # [N] RMS along y, z, x
    "turbulence_cutoff": 150.0,  # [Hz]
    "time_step": 1.0e-5,         # [s]
    "archive_rate": 5000.0,      # [Hz]
    "warm_up": 1.0,              # [s] discarded
}


# No on-disk cache (cache=False, compile ~1 s): this script runs as __main__ and is also loaded
# from its file by the tests; numba's cache records the defining module by name and cannot
# reload an entry written under the other identity (ModuleNotFoundError '<dynamic>').
@njit(cache=False)
def integrate(force, dt, stride, skip, m, k_lat, c_lat, k_ax, c_ax, gap, k_c, mu, v_reg):
    """Semi-implicit Euler over the excitation ``force`` (steps × 3: y, z, x) [N].

    Returns the archive (rows × 10: time, Fn, Ft1, Ft2, Vn, Vt1, Vt2, Dy, Dz, stick) of every
    ``stride``-th step after ``skip`` steps, and the largest friction stability number
    ``μ·Fn·dt/(m·v_reg)`` met (must stay below 2).
    """
    n = force.shape[0]
    rows = (n - 1 - skip) // stride + 1
    out = np.zeros((rows, 10))
    y = z = x = 0.0
    vy = vz = vx = 0.0
    worst = 0.0
    row = 0
    for i in range(n):
        r = math.sqrt(y * y + z * z)
        fn = 0.0
        ny = 1.0
        nz = 0.0
        if r > 0.0:
            ny = y / r
            nz = z / r
        vt1 = -nz * vy + ny * vz
        vt2 = vx
        vn = ny * vy + nz * vz
        ft1 = 0.0
        ft2 = 0.0
        stick = 0.0
        if r > gap:
            fn = k_c * (r - gap)
            speed = math.sqrt(vt1 * vt1 + vt2 * vt2)
            scale = mu * fn / max(speed, v_reg)
            ft1 = -scale * vt1
            ft2 = -scale * vt2
            if speed < v_reg:
                stick = 1.0
            worst = max(worst, mu * fn * dt / (m * v_reg))
        if i >= skip and (i - skip) % stride == 0 and row < rows:
            out[row, 0] = (i - skip) * dt
            out[row, 1] = fn
            out[row, 2] = ft1
            out[row, 3] = ft2
            out[row, 4] = vn
            out[row, 5] = vt1
            out[row, 6] = vt2
            out[row, 7] = y
            out[row, 8] = z
            out[row, 9] = stick
            row += 1
        # obstacle force on the tube: -Fn along n, friction along e1 = (-nz, ny) and e2 = x
        fy = force[i, 0] - k_lat * y - c_lat * vy - fn * ny - ft1 * nz
        fz = force[i, 1] - k_lat * z - c_lat * vz - fn * nz + ft1 * ny
        fx = force[i, 2] - k_ax * x - c_ax * vx + ft2
        vy += dt * fy / m
        vz += dt * fz / m
        vx += dt * fx / m
        y += dt * vy
        z += dt * vz
        x += dt * vx
    return out, worst


def excitation(n_steps: int, dt: float, seed: int, p: dict) -> np.ndarray:
    """Harmonic force along y plus band-limited Gaussian turbulence on y, z, x [N] (steps × 3)."""
    rng = np.random.default_rng(seed)
    sos = signal.butter(4, p["turbulence_cutoff"], fs=1.0 / dt, output="sos")
    noise = signal.sosfilt(sos, rng.standard_normal((3, n_steps)), axis=1)
    noise /= noise.std(axis=1, keepdims=True)
    noise *= np.asarray(p["turbulence_rms"])[:, None]
    t = np.arange(n_steps) * dt
    force = noise.T.copy()
    force[:, 0] += p["harmonic_force"] * np.cos(2.0 * np.pi * p["harmonic_frequency"] * t)
    return force


def simulate(duration: float = 3.0, seed: int = 20261121, parameters: dict | None = None
             ) -> ContactHistory:
    """Run the model and return the archived contact history (SI units)."""
    p = dict(PARAMETERS, **(parameters or {}))
    dt = p["time_step"]
    stride = int(round(1.0 / (p["archive_rate"] * dt)))
    skip = int(round(p["warm_up"] / dt))
    n_steps = skip + int(round(duration / dt)) + 1
    m = p["mass"]
    w_lat = 2.0 * np.pi * p["lateral_frequency"]
    w_ax = 2.0 * np.pi * p["axial_frequency"]
    out, worst = integrate(excitation(n_steps, dt, seed, p), dt, stride, skip, m,
                           m * w_lat**2, 2.0 * p["lateral_damping"] * m * w_lat,
                           m * w_ax**2, 2.0 * p["axial_damping"] * m * w_ax,
                           p["clearance"], p["contact_stiffness"], p["friction"],
                           p["regularisation_speed"])
    if worst >= 2.0:
        raise RuntimeError(f"friction regularisation unstable (number {worst:.2f} >= 2): reduce "
                           "time_step or raise regularisation_speed")
    columns = ("time", "normal_force", "ft1", "ft2", "vn", "vt1", "vt2", "dy", "dz", "stick")
    meta = {"model": "tube section in a circular gap (examples/make_example_history.py)",
            "seed": seed, **{k: v for k, v in p.items()}}
    return ContactHistory(**{c: out[:, j] for j, c in enumerate(columns)},
                          name="oscillator_gap", metadata=meta)


def main(argv: list[str] | None = None) -> Path:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = Path(__file__).resolve().parent
    parser.add_argument("--output", type=Path, default=here / "data" / "oscillator_gap.csv")
    parser.add_argument("--duration", type=float, default=3.0, help="archived seconds")
    parser.add_argument("--seed", type=int, default=20261121)
    args = parser.parse_args(argv)
    history = simulate(args.duration, args.seed)
    # 8 significant digits: 0.1 ns on time, far below the 0.2 ms archive step; keeps < 3 MB
    write_history(history, args.output, float_format="%.8g")
    fn = history.normal_force
    contact = fn > 0
    starts = np.count_nonzero(contact[1:] & ~contact[:-1])
    print(f"{args.output}: {len(history)} samples over {history.duration:g} s; "
          f"contact {contact.mean():.1%} of the time, {starts} impacts, "
          f"max Fn {fn.max():.1f} N, stick {np.mean(history.stick[contact]):.1%} of contact, "
          f"size {args.output.stat().st_size / 1e6:.2f} MB")
    return args.output


if __name__ == "__main__":
    main()
