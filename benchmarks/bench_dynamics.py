"""Time steps per second of the built-in dynamics: compiled kernel vs the same scheme in Python.

Model: 10 modes (5 bending modes of a clamped-pinned tube in each plane, FE-free analytic
modes), one shock in a drilled support (circle, radial gap 0.2 mm, penalty contact with Coulomb
friction), two random forces from a one-sided PSD. The compiled run integrates ``--steps``
steps (default 1e7) with a history archived every ``--archive-every`` steps; the reference is the
very same step function run by the Python interpreter (``advance.py_func``: plain Python loops
over numpy arrays) on ``--python-steps`` steps. Printed: steps/s of both and their ratio, plus
the compiled run with the adaptive step (coarse steps in free flight).

Usage::

    .venv/bin/python benchmarks/bench_dynamics.py
    .venv/bin/python benchmarks/bench_dynamics.py --steps 1e6 --python-steps 1e4
"""

from __future__ import annotations

import argparse
import time

from fretwear._numba import HAVE_NUMBA
from fretwear.dynamics import NodalForce, Shock, Signal, simulate, uniform_beam_modes

H = 2e-5  # time step [s]


def setup():
    model = uniform_beam_modes(young_modulus=2.0e11, second_moment=2.489e-9,
                               mass_per_length=0.87, length=1.0, n_modes=5,
                               ends=("clamped", "pinned"), damping_ratio=0.02,
                               shock_positions=[0.5], forcing_positions=[0.4])
    shock = Shock(point=0, obstacle="circle", gap=2e-4, normal_stiffness=1e7,
                  normal_damping=50.0, tangential_stiffness=1e7, tangential_damping=50.0,
                  friction=0.3)
    return model, [shock]


def loads(duration):
    return [NodalForce(0, d, Signal("random", psd_frequencies=[5.0, 200.0], psd=[s, s],
                                    duration=duration, seed=seed))
            for d, s, seed in (("y", 0.5, 1), ("z", 0.2, 2))]


def run(steps: int, archive_every: int, compiled: bool = True, adaptive: bool = False):
    model, shocks = setup()
    duration = steps * H
    t = time.perf_counter()
    r = simulate(model, shocks, loads(duration), duration=duration, time_step=H,
                 archive_step=archive_every * H, compiled=compiled, adaptive=adaptive,
                 chunk_size=100_000)
    elapsed = time.perf_counter() - t
    return steps / elapsed, r


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=float, default=1e7, help="compiled steps (default 1e7)")
    ap.add_argument("--python-steps", type=float, default=2e4,
                    help="interpreted steps (default 2e4)")
    ap.add_argument("--archive-every", type=int, default=10, help="archive every N steps")
    args = ap.parse_args()
    print(f"numba available: {HAVE_NUMBA}; 10 modes, 1 shock (circle, friction), 2 random "
          f"forces; h = {H:g} s, archive every {args.archive_every} steps")
    run(1000, args.archive_every)  # compile / load the cache
    n = int(args.steps)
    fast, r = run(n, args.archive_every)
    print(f"compiled      : {fast:12.4g} steps/s  ({n:.3g} steps, {r.end_time:g} s simulated, "
          f"contact {100 * float((r.history(0).normal_force > 0).mean()):.1f} % of samples)")
    fa, ra = run(n, args.archive_every, adaptive=True)
    print(f"compiled+adapt: {fa:12.4g} steps/s  (fine-step equivalent; {ra.n_coarse_steps:.3g} "
          f"steps taken for {ra.n_steps:.3g}, coarse step {ra.coarse_step:g} s)")
    m = int(args.python_steps)
    slow, _ = run(m, args.archive_every, compiled=False)
    print(f"plain Python  : {slow:12.4g} steps/s  ({m:.3g} steps, same step function "
          "interpreted)")
    print(f"ratio compiled / Python: {fast / slow:.0f}x")


if __name__ == "__main__":
    main()
