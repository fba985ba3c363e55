"""Monte Carlo propagation: time per contact type, and convergence of Sobol' against random.

1. Time of ``monte_carlo`` for every contact type: 10⁴ random samples (and 2¹⁴ Sobol' points)
   × 20 instants, lognormal coefficient and power, obstacle worn where the type allows.
2. Convergence on the analytic case of docs/uncertainty.md §5 (Archard, TUBE_BAV without tilt,
   K lognormal σ = 0.7, fixed power): root-mean-square error over 40 seeds of the mean depth
   (capped at the tube radius, where the flat reaches the axis and the depth leaves the range) and
   of the probability of exceeding 40 % of a 1.09 mm wall at 20 years, against N, for scrambled
   Sobol' and for random sampling; the fitted rate is the slope of log(RMSE) against log(N).

Run: ``.venv/bin/python benchmarks/bench_uncertainty.py``.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
from scipy import stats

from fretwear.errors import RangeWarning
from fretwear.geometry import CONTACT_TYPES
from fretwear.uncertainty import LogNormal, monte_carlo

YEAR = 3.15576e7


def timing() -> None:
    print("1. monte_carlo time, 20 instants (K and P lognormal)")
    print(f"{'contact type':16s} {'random 10^4 [s]':>16s} {'sobol 2^14 [s]':>15s}")
    instants = np.linspace(1.0, 20.0, 20)
    for name, cls in CONTACT_TYPES.items():
        case = {"contact_type": name, "dimensions": dict(cls.example), "instants": instants,
                "time_scale": YEAR, "coefficients": {"coefficient": 1e-15},
                "obstacle_coefficients": {"coefficient": 5e-16}}
        if name == "TUBE_ALESAGE" and "obstacle_radius" not in cls.example:
            case.pop("obstacle_coefficients")
        row = []
        for method, n in (("random", 10_000), ("sobol", 2 ** 14)):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RangeWarning)
                start = time.perf_counter()
                monte_carlo(case, 0.002, coefficients={"coefficient": LogNormal(sigma_ln=0.7)},
                            power_scatter=LogNormal(sigma_ln=0.2), samples=n, method=method)
                row.append(time.perf_counter() - start)
        print(f"{name:16s} {row[0]:16.3f} {row[1]:15.3f}")


def convergence() -> None:
    r, w, k0, sigma, p, t = 9.525e-3, 12.7e-3, 9.2e-15, 0.7, 0.01, 20.0
    c = (1 / (2 * r)) ** (1 / 3) * (3 / (4 * w)) ** (2 / 3)
    median = c * (k0 * p * t * YEAR) ** (2 / 3)
    s_d = 2 * sigma / 3
    # E[min(D, R)]: past the tube's radius the depth is beyond the relation's range (inf);
    # partial expectation of a lognormal: E[D; D < R] = m·e^(s²/2)·Φ((ln(R/m) − s²)/s)
    z = math.log(r / median) / s_d
    exact_mean = (median * math.exp(s_d ** 2 / 2) * stats.norm.cdf(z - s_d)
                  + r * stats.norm.sf(z))
    limit = 0.4 * 1.09e-3
    exact_p = 1 - stats.norm.cdf(math.log(limit / median) / s_d)
    case = {"contact_type": "TUBE_BAV", "instants": [t], "time_scale": YEAR,
            "dimensions": {"mobile_radius": r, "obstacle_width": w},
            "coefficients": {"coefficient": k0}, "wall_thickness": 1.09e-3}
    sizes = [2 ** m for m in range(8, 15)]
    seeds = range(40)
    print("\n2. RMSE over 40 seeds (analytic case, 20 years): mean of min(depth, R_m) "
          "[relative], exceedance probability [absolute]")
    print(f"{'N':>6s} {'mean: sobol':>12s} {'random':>10s} {'ratio':>7s} "
          f"{'P: sobol':>10s} {'random':>10s} {'ratio':>7s}")
    rmse = {(m, q): [] for m in ("sobol", "random") for q in ("mean", "p")}
    for n in sizes:
        for method in ("sobol", "random"):
            em, ep = [], []
            for s in seeds:
                res = monte_carlo(case, p, coefficients={"coefficient": LogNormal(
                    sigma_ln=sigma)}, samples=n, method=method, seed=s)
                em.append(np.minimum(res.depth[:, 0], r).mean() / exact_mean - 1)
                ep.append(res.exceedance()["probability"].iloc[0] - exact_p)
            rmse[(method, "mean")].append(math.sqrt(np.mean(np.square(em))))
            rmse[(method, "p")].append(math.sqrt(np.mean(np.square(ep))))
        i = len(rmse[("sobol", "mean")]) - 1
        sm, rm = rmse[("sobol", "mean")][i], rmse[("random", "mean")][i]
        sp, rp = rmse[("sobol", "p")][i], rmse[("random", "p")][i]
        print(f"{n:6d} {sm:12.2e} {rm:10.2e} {rm / sm:7.1f} {sp:10.2e} {rp:10.2e} "
              f"{rp / sp:7.1f}")
    x = np.log(sizes)
    print("fitted rates (RMSE ∝ N^rate):")
    for q, label in (("mean", "mean depth"), ("p", "exceedance probability")):
        rates = {m: np.polyfit(x, np.log(rmse[(m, q)]), 1)[0] for m in ("sobol", "random")}
        print(f"  {label:24s} sobol {rates['sobol']:+.2f}   random {rates['random']:+.2f}")


if __name__ == "__main__":
    timing()
    convergence()
