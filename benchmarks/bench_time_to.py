"""DepthModel.time_to on Monte Carlo arrays where it solves (EDF-MZ: depth(t) not linear in
time): fretwear.table.limit.time_to_depth, its bracket grown by
``scipy.optimize.elementwise.bracket_root`` and narrowed by the numba-compiled Chandrupatla
step (``narrow="compiled"``, "after") or by ``scipy.optimize.elementwise.find_root``
(``narrow="scipy"``), against the hand-written bracket loop it replaced ("before",
``--base DIR``: that function loaded from the checkout DIR, e.g. a worktree of the commit
before, ``git worktree add /tmp/base HEAD~1``); all in this process, taking turns.

Printed: milliseconds per call (best of ``--repeat``) for 1, 100 and 10 000 samples of the
wear-coefficient factor, the ratios to before, and the largest relative difference of the
times to before.

Usage::

    .venv/bin/python benchmarks/bench_time_to.py --base /tmp/base
"""

from __future__ import annotations

import argparse
import functools
import importlib.util
import os
import time
from pathlib import Path

import numpy as np

from fretwear.geometry import contact_geometry
from fretwear.laws import get_law
from fretwear.table import Wall, depth, limit
from fretwear.table.depth import DepthModel

YEAR = 3.15576e7  # [s]
#: EDF-MZ coefficients of examples/grappe_alesage.toml (A [m³/(s·W^b)] set per body)
COEFFICIENTS = {"power_exponent": 1.0, "decay_constant": 2.44e-8, "asymptotic_rate": 1.14e-16}


def _model() -> DepthModel:
    g = contact_geometry("TUBE_BAV", mobile_radius=9.525e-3, obstacle_width=12.7e-3)
    return DepthModel(law=get_law("EDF_MZ"), geometry=g, powers=(0.05,),
                      coefficients_mobile=(dict(COEFFICIENTS, rate_coefficient=2.6e-15),),
                      coefficients_obstacle=(dict(COEFFICIENTS, rate_coefficient=3.7e-15),),
                      time_scale=YEAR, wall=Wall(1.07e-3))


def _best(fn, repeat: int) -> float:
    out = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        out.append(time.perf_counter() - start)
    return min(out)


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--base", required=True, help="checkout with the solver before")
    p.add_argument("--repeat", type=int, default=7)
    args = p.parse_args(argv)
    spec = importlib.util.spec_from_file_location(
        "base_limit", Path(args.base) / "src" / "fretwear" / "table" / "limit.py")
    base = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(base)
    model = _model()
    target = 0.4 * model.wall.thickness
    print(f"load average {os.getloadavg()[0]:.2f}; EDF_MZ, TUBE_BAV, depth 0.4 x wall")
    print(f"{'samples':>8} {'before [ms]':>12} {'after [ms]':>11} {'ratio':>6} "
          f"{'max rel diff':>13} {'all scipy [ms]':>15} {'ratio':>6} {'max rel diff':>13}")
    rng = np.random.default_rng(1)
    for n in (1, 100, 10_000):
        factor = rng.lognormal(0.0, 0.5, n)
        new = model.time_to(target, factor=factor)
        try:  # the same model, its solver the base's
            depth.time_to_depth = base.time_to_depth
            old = model.time_to(target, factor=factor)
            before = _best(lambda f=factor: model.time_to(target, factor=f), args.repeat)
        finally:
            depth.time_to_depth = limit.time_to_depth
        after = _best(lambda f=factor: model.time_to(target, factor=f), args.repeat)
        try:  # narrowed by scipy's find_root too
            depth.time_to_depth = functools.partial(limit.time_to_depth, narrow="scipy")
            scipy_all = model.time_to(target, factor=factor)
            every = _best(lambda f=factor: model.time_to(target, factor=f), args.repeat)
        finally:
            depth.time_to_depth = limit.time_to_depth

        def diff(values, old=old):
            return float(np.max(np.abs(np.asarray(values) / np.asarray(old) - 1)))

        print(f"{n:>8} {1e3 * before:>12.2f} {1e3 * after:>11.2f} {after / before:>6.2f} "
              f"{diff(new):>13.2e} {1e3 * every:>15.2f} {every / before:>6.2f} "
              f"{diff(scipy_all):>13.2e}", flush=True)


if __name__ == "__main__":
    main()
