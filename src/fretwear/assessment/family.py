"""Depths of many contacts at many factors, a family of alike contacts at a time.

:func:`depths_at_factors` gives ``models[i].depth(t_i, factor=f_ij)`` for every result of a
calibration at every factor of its grid; :class:`Family` groups the contacts whose nominal
depth models are one up to the rate (the same law, geometry, coefficients, limit, time scale
and origin, unworn at the origin), so that one :meth:`~fretwear.table.depth.DepthModel.time_to`
and one :meth:`~fretwear.table.depth.DepthModel.depth` call serve a whole group. Used by
:mod:`fretwear.assessment.calibration` (the likelihood's depths) and
:mod:`fretwear.assessment.growth` (the nominal times of the outage's growth). Depths [m],
times in each model's time unit.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

__all__ = ["Family", "depths_at_factors", "scalable"]

@dataclass
class Family:
    """The contacts grouped by what makes their nominal models one up to the rate: the same
    law, geometry, coefficients, limit, time scale and origin, unworn at the origin (no
    restart, no replacement, one term). Contact i's state after t at the factor g is its
    group's representative's after g·t·r_i/r_rep (the volumes linear in time and in the rate
    r, :attr:`DepthModel.rates`), so one :meth:`DepthModel.time_to` and one
    :meth:`DepthModel.depth` call serve a whole group (10⁵ contacts in a few calls).
    """

    reps: list            # representative DepthModel of each group
    group: np.ndarray     # group of each contact
    ratio: np.ndarray     # r_i / r_rep [-]
    origin: np.ndarray    # each contact's origin [time unit]

    @classmethod
    def of(cls, models) -> Family:
        keys: dict = {}
        members: list[list[int]] = []
        group = np.zeros(len(models), int)
        for i, m in enumerate(models):
            alike = scalable(m)
            key = (id(m.law), id(m.geometry), _items(m.coefficients_mobile[0]),
                   _items(m.coefficients_obstacle[0]), m.limit_depth, m.time_scale,
                   m.origin) if alike else ("own", i)
            if key not in keys:
                keys[key] = len(members)
                members.append([])
            group[i] = keys[key]
            members[group[i]].append(i)
        reps, ratio = [], np.ones(len(models))
        for idx in members:  # one law call per group: the rates of its members
            first = models[idx[0]]
            power = np.array([models[i].powers[0] for i in idx], float)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                c = first.coefficients_mobile[0]
                rate = (np.zeros(len(idx)) if c is None else np.broadcast_to(np.asarray(
                    first.law.volume(power, 1.0, **c), float), (len(idx),)))
            best = int(np.argmax(rate))
            reps.append(models[idx[best]])
            ratio[idx] = rate / rate[best] if rate[best] > 0 else 1.0
        return cls(reps, group, ratio, np.array([m.origin for m in models], float))

    def subset(self, rows) -> Family:
        rows = np.asarray(rows, int)
        return Family(self.reps, self.group[rows], self.ratio[rows], self.origin[rows])

    def nominal_time(self, depth, rows) -> np.ndarray:
        """τ: the contacts' (``rows``) nominal times to ``depth`` [m] (rows x k) after their
        origins [time unit]; 0 where depth <= 0, inf where never reached."""
        depth = np.asarray(depth, float)
        rows = np.asarray(rows, int)
        out = np.zeros(depth.shape)
        for g in np.unique(self.group[rows]):
            mine = self.group[rows] == g
            d = depth[mine]
            worn = d > 0
            if worn.any():
                rep = self.reps[g]
                t = np.zeros(d.shape)
                t[worn] = np.asarray(rep.time_to(d[worn])) - rep.origin
                with np.errstate(divide="ignore", invalid="ignore"):
                    out[mine] = np.where(t > 0, t / self.ratio[rows[mine]][:, None], t)
        return out

    def depth(self, tau, rows) -> np.ndarray:
        """The contacts' (``rows``) depths [m] at the nominal times ``tau`` (rows x k) after
        their origins [time unit] (NaN beyond the geometry's range)."""
        tau = np.asarray(tau, float)
        rows = np.asarray(rows, int)
        out = np.full(tau.shape, np.nan)
        for g in np.unique(self.group[rows]):
            mine = self.group[rows] == g
            rep = self.reps[g]
            t = np.minimum(tau[mine] * self.ratio[rows[mine]][:, None], 1e300)
            with np.errstate(invalid="ignore", over="ignore"):
                out[mine] = rep.depth(t * rep.time_scale, warn=False)
        return out


def scalable(model) -> bool:
    """Whether ``model``'s depth at the factor f after t is its nominal depth after f·t (a law
    linear in time, one power term, unworn at its origin, no sector, restart or replacement)."""
    m = model
    return (len(m.powers) == 1 and m.sector_arc is None and m.rows is None
            and m.replacement is None and m.initial_mobile == 0 and m.initial_obstacle == 0
            and m.law.linear_in_time)


def depths_at_factors(models, elapsed_s, factors, *, chunk: int = 2048) -> np.ndarray:
    """``models[i].depth(elapsed_s[i], factor=factors[i])`` [m] for every row i, shape
    (rows, k); NaN beyond a geometry's range.

    The rows of :func:`scalable` models are computed a :class:`Family` group at a time (the
    depth at f after t is the nominal one after f·t: 10⁴ rows × 10³ factors in a few calls,
    ``chunk`` rows at once), the others one model call each.

    Parameters
    ----------
    models : sequence of DepthModel
        One per row (repeats allowed).
    elapsed_s : array_like
        Time since each row's model's origin [s], shape (rows,).
    factors : array_like
        Factors f > 0 [-], shape (rows, k) or (k,) (the same for every row).
    """
    n = len(models)
    t = np.asarray(elapsed_s, float).reshape(n)
    f = np.broadcast_to(np.asarray(factors, float), (n, np.shape(factors)[-1]))
    out = np.empty(f.shape)
    fast = np.array([scalable(m) for m in models], bool)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for i in np.flatnonzero(~fast):
            out[i] = models[i].depth(np.full(f.shape[1], t[i]), factor=f[i], warn=False)
        rows = np.flatnonzero(fast)
        if rows.size and np.ndim(factors) == 1:  # one grid of factors: a shift in ln
            family = Family.of([models[i] for i in rows])
            scale = np.array([models[i].time_scale for i in rows], float)
            for g in np.unique(family.group):
                mine = np.flatnonzero(family.group == g)
                out[rows[mine]] = _shifted_depths(family.reps[g], t[rows[mine]] / scale[mine]
                                                  * family.ratio[mine], f[0], chunk)
        elif rows.size:
            family = Family.of([models[i] for i in rows])
            scale = np.array([models[i].time_scale for i in rows], float)
            for start in range(0, rows.size, chunk):
                part = np.arange(start, min(start + chunk, rows.size))
                tau = (t[rows[part]] / scale[part])[:, None] * f[rows[part]]
                out[rows[part]] = family.depth(tau, part)
    return out


_LN_STEP = 2e-4  # the step of ln(f·τ) of the shifted depths' table [-]


def _shifted_depths(rep, tau, factors, chunk) -> np.ndarray:
    """D(f_j·τ_i) [m] with D the representative's depth at the nominal time f·τ [time unit]:
    ln D tabulated once on a uniform grid of v = ln(f·τ) (step 2e-4) and read linearly at
    v = ln f_j + ln τ_i (an error of step²/8·|(ln D)''|, 0 for the power-law depths of
    TUBE_BAV and TUBE_ALESAGE), instead of a geometry call per row and factor."""
    out = np.full((tau.size, factors.size), np.nan)
    with np.errstate(divide="ignore"):
        ln_tau, ln_f = np.log(tau), np.log(factors)
    worn = np.isfinite(ln_tau)  # τ = 0: unworn at every factor
    out[~worn] = 0.0
    if not worn.any():
        return out
    lo = float(ln_f.min() + ln_tau[worn].min())
    hi = float(ln_f.max() + ln_tau[worn].max())
    v = lo + _LN_STEP * np.arange(int(math.ceil((hi - lo) / _LN_STEP)) + 2)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        ln_d = np.log(rep.depth(np.minimum(np.exp(v), 1e300) * rep.time_scale, warn=False))
    ln_d = np.where(np.isneginf(ln_d), -745.0, ln_d)  # depth 0: e^-745 = 0
    for start in range(0, tau.size, chunk):
        part = np.flatnonzero(worn)[start:start + chunk]
        pos = (ln_tau[part, None] + ln_f[None, :] - lo) / _LN_STEP
        k = np.clip(pos.astype(int), 0, v.size - 2)
        w = pos - k
        ln = (1.0 - w) * ln_d[k] + w * ln_d[k + 1]
        out[part] = np.where(ln < -700.0, 0.0, np.exp(ln))  # unworn: 0
    return out


def _items(coefficients):
    return None if coefficients is None else tuple(sorted(coefficients.items()))
