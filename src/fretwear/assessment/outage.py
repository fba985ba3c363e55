"""The outage decision of a bundle: :func:`assess` (``fretwear assess``).

From a finished bundle run and one outage's inspections: the condition monitoring (the
as-found state against the limit, the prediction against every indication) and the
operational assessment (each contact's depth at the end of the next interval, each tube's
probability of exceeding its limit, the bundle's, the longest interval under the target, the
tubes to plug and the next inspection's sample). docs/assessment.md explains it in the
users' terms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.assessment.condition import as_found, predicted_vs_measured
from fretwear.assessment.contacts import bundle_models, field_inspections
from fretwear.assessment.growth import FactorNodes, GrowthModel
from fretwear.assessment.operational import (
    BundleRisk,
    bundle_risk,
    inspection_sample,
    longest_interval,
    plugging_list,
)
from fretwear.errors import InputError
from fretwear.keys import check_level

__all__ = ["Assessment", "assess"]

QUANTILES = (0.05, 0.5, 0.95)


@dataclass
class Assessment:
    """The result of :func:`assess`.

    Attributes
    ----------
    contacts : DataFrame
        One row per contact: ``contact``, ``tube``, ``tube_row``, ``tube_column``,
        ``support``, ``state`` (``sized``, ``NDD``, ``not inspected``, ``plugged``),
        ``measured`` [m], ``as_found`` [m] (the sized true depth, else the prediction's median
        at the outage), ``limit_depth``, ``wall_thickness`` [m], ``depth_end_q5``,
        ``depth_end_q50``, ``depth_end_q95`` [m] (end of the interval), ``p_exceed`` [-].
    tubes : DataFrame
        One row per tube, riskiest first: ``tube``, ``tube_row``, ``tube_column``,
        ``contacts``, ``worst_contact``, ``as_found_fraction``, ``end_fraction_q50`` [-],
        ``p_exceed`` [-], ``plugged`` (already), ``plug`` (recommended), ``reason``,
        ``inspect`` (in the next sample).
    bundle : dict
        ``p_any``, ``target``, ``interval``, ``longest_interval`` [time unit],
        ``p_any_after_plugging``, ``plugging`` (tubes), ``must_plug`` (at or past the limit
        as measured), ``inspection_sample``, ``share``, counts of contacts and tubes past the
        limit and through the wall, ``worst_tube``.
    curve : DataFrame
        ``interval`` [time unit] and ``p_any`` [-] (the tubes at the limit as measured plugged).
    condition : DataFrame
        The as-found sized indications (:func:`fretwear.assessment.condition.as_found`).
    predictions : DataFrame
        Predicted against measured (:func:`~fretwear.assessment.condition.predicted_vs_measured`).
    nodes : FactorNodes
    inputs : dict
        Provenance: the bundle, the inspections, the technique, the interval, the target.
    """

    contacts: pd.DataFrame
    tubes: pd.DataFrame
    bundle: dict
    curve: pd.DataFrame
    condition: pd.DataFrame
    predictions: pd.DataFrame
    nodes: FactorNodes
    inputs: dict = field(default_factory=dict)
    fit: dict = field(default_factory=dict)
    risk: BundleRisk | None = None
    models: dict = field(default_factory=dict, repr=False)
    growth: GrowthModel | None = field(default=None, repr=False)

    def fan(self, contact: str, intervals, q=QUANTILES) -> np.ndarray:
        """Quantiles ``q`` of ``contact``'s depth [m] at the end of each of ``intervals``
        [time unit] after the outage, shape (len(intervals), len(q))."""
        live = self.contacts[self.contacts["state"] != "plugged"].reset_index(drop=True)
        where = np.flatnonzero(live["contact"].to_numpy() == contact)
        if not where.size:
            raise InputError(f"contact {contact!r} is not assessed (plugged, or not computed)")
        model = self.models[contact]
        out = []
        for t in np.atleast_1d(intervals):
            tau = self.growth.end_nominal_times(float(t), q, rows=where)[0]
            with np.errstate(invalid="ignore"):
                out.append(model.depth(np.minimum(tau, 1e300) * model.time_scale, warn=False))
        return np.asarray(out)

    def write(self, directory) -> list:
        """Write ``contacts.csv``, ``tubes.csv``, ``condition.csv``, ``predictions.csv``,
        ``curve.csv`` and ``assessment.json`` (the bundle's numbers and the inputs) into
        ``directory`` (created), each atomically; returns the paths."""
        import json
        from pathlib import Path

        from fretwear.io.atomic import atomic_write
        from fretwear.table.schema import FLOAT_FORMAT

        root = Path(directory)
        root.mkdir(parents=True, exist_ok=True)
        written = []
        for name, frame in (("contacts", self.contacts), ("tubes", self.tubes),
                            ("condition", self.condition), ("predictions", self.predictions),
                            ("curve", self.curve)):
            with atomic_write(root / f"{name}.csv", encoding="utf-8", newline="") as handle:
                frame.to_csv(handle, index=False, float_format=FLOAT_FORMAT)
            written.append(root / f"{name}.csv")
        payload = {"bundle": self.bundle, "inputs": {k: repr(v) if k in ("sizing", "pod")
                                                     else v for k, v in self.inputs.items()},
                   "factor_nodes": {"log_factor": self.nodes.log_factor.tolist(),
                                    "weights": self.nodes.weights.tolist(),
                                    "contact_sigma": self.nodes.contact_sigma,
                                    "power_sigma": self.nodes.power_sigma}}
        with atomic_write(root / "assessment.json", encoding="utf-8") as handle:
            json.dump(payload, handle, indent=1, default=str)
        written.append(root / "assessment.json")
        return written

    def bad_news(self) -> list[str]:
        """The lines said first: contacts and tubes past the limit and through the wall."""
        b = self.bundle
        lines = []
        if b["through_wall_tubes"]:
            lines.append(f"{b['through_wall_contacts']} contact(s) on {b['through_wall_tubes']} "
                         f"tube(s) THROUGH THE WALL as measured")
        if b["past_limit_tubes"]:
            lines.append(f"{b['past_limit_contacts']} contact(s) on {b['past_limit_tubes']} "
                         f"tube(s) AT OR PAST THE PLUGGING LIMIT as measured: "
                         f"{', '.join(b['must_plug'][:10])}")
        if b["p_any"] > b["target"]:
            lines.append(f"P(any tube past its limit by the end of {b['interval']:g} "
                         f"{b['unit']}) = {b['p_any']:.3g} > target {b['target']:g}")
        return lines


def _posterior_nodes(posterior, models, sized, sizing, count, contact_sigma, power_sigma):
    if isinstance(posterior, FactorNodes):
        return posterior, {"method": "given nodes"}
    if hasattr(posterior, "levels") and hasattr(posterior, "scatter"):
        # the hierarchical calibration (fretwear.assessment.calibration.BundleCalibration):
        # its bundle-level posterior at nodes, its contact scatter and power spread
        from fretwear.uncertainty.calibration import GridPosterior

        levels = posterior.levels
        dist = GridPosterior(log_factor=np.asarray(levels.grid, float),
                             density=np.asarray(levels.bundle, float).reshape(-1))
        s_c = float(posterior.prior.contact_sigma_ln)
        s_p = math.sqrt(max(float(np.median(np.asarray(posterior.scatter) ** 2)) - s_c ** 2,
                            0.0))
        return (FactorNodes.from_posterior(dist, count=count, contact_sigma=s_c,
                                           power_sigma=s_p),
                {"method": "hierarchical", "factor_median": posterior.bundle_factor()[0]})
    if posterior is not None:  # a CalibrationResult or a distribution of the factor
        dist = getattr(posterior, "posterior", posterior)
        return FactorNodes.from_posterior(dist, count=count, contact_sigma=contact_sigma,
                                          power_sigma=power_sigma), {"method": "given"}
    from fretwear.uncertainty.calibration import DEFAULT_PRIOR, calibrate

    if sized.empty:
        return FactorNodes.from_posterior(DEFAULT_PRIOR, count=count,
                                          contact_sigma=contact_sigma,
                                          power_sigma=power_sigma), {"method": "prior"}
    true = np.asarray(sizing.true_depth(sized["depth"].to_numpy(float)))
    keep = true > 0
    rows = pd.DataFrame({"contact": sized["contact"].to_numpy()[keep],
                         "instant": sized["instant"].to_numpy(float)[keep],
                         "depth": true[keep],
                         "measurement_sigma": sizing.true_depth_sigma() / true[keep]})
    cal = calibrate({c: models[c] for c in rows["contact"]}, rows)
    return (FactorNodes.from_posterior(cal.posterior, count=count, contact_sigma=contact_sigma,
                                       power_sigma=power_sigma),
            {"method": cal.method, "factor_median": cal.factor_median,
             "factor_interval_95": cal.factor_interval(0.95)})


def assess(bundle: Any, inspections=None, *, interval: float, sizing, pod,
           target: float = 0.05, posterior=None, contact_sigma: float = 0.0,
           power_sigma: float = 0.0, share: float = 0.9, limit: float | None = None,
           horizon: float | None = None, nodes: int = 16, origin_date=None) -> Assessment:
    """Condition monitoring and operational assessment of a bundle at an outage.

    Parameters
    ----------
    bundle : BundleResult
        A finished bundle run (:func:`fretwear.bundle.run_bundle` or :func:`fretwear.bundle.load`).
    inspections : path-like or DataFrame, optional
        The outage's inspections (:func:`fretwear.assessment.contacts.field_inspections`);
        None: nothing inspected (the outage at the bundle's last instant).
    interval : float
        The next operating interval [the bundle's time unit], > 0.
    sizing : SizingModel
        The technique's sizing error [m].
    pod : LogisticPOD
        The technique's probability of detection.
    target : float
        The probability target of P(any tube past its limit) [-] (commonly 0.05).
    posterior : FactorNodes, BundleCalibration, CalibrationResult or distribution, optional
        The calibrated factor: nodes, the hierarchical calibration
        (:func:`fretwear.assessment.calibration.calibrate_bundle`: its bundle-level posterior,
        contact scatter and power spread; a group level is not carried), a calibration or a
        distribution; default :func:`fretwear.uncertainty.calibrate` on the sized indications
        (their true depths, σ_ln = (σ/b)/d).
    contact_sigma, power_sigma : float
        σ_ln of one contact's factor about the bundle's, and of the factor on its power [-].
    share : float
        The share of the bundle's risk the next inspection's sample covers [-].
    limit : float, optional
        Plugging limit, fraction of the wall [-] (default each contact's depth_limit).
    horizon : float, optional
        The longest interval searched [time unit] (default 5 × interval).
    nodes : int
        Quadrature nodes of the factor's posterior.
    origin_date : str, optional
        The date of the bundle's instant 0, for inspections dated (ISO 8601).

    Returns
    -------
    Assessment
    """
    target = check_level(target, "target")
    interval = float(interval)
    if not (math.isfinite(interval) and interval > 0):
        raise InputError(f"interval must be a time > 0 [the bundle's time unit], got "
                         f"{interval!r}")
    table = bundle_models(bundle, limit=limit)
    models = dict(zip(table["contact"], table["model"], strict=True))
    unit = str(table["time_unit"].dropna().iloc[0]) if table["time_unit"].notna().any() \
        else "year"
    insp = field_inspections(inspections, table, origin_date=origin_date, time_unit=unit) \
        if inspections is not None else \
        pd.DataFrame({"contact": pd.Series(dtype=str), "instant": pd.Series(dtype=float),
                      "depth": pd.Series(dtype=float), "ndd": pd.Series(dtype=bool),
                      "plugged": pd.Series(dtype=bool)})
    unknown = sorted(set(insp["contact"]) - set(models))
    if unknown:
        raise InputError(f"inspected contacts not computed in the bundle: {unknown[:5]} "
                         "(names as in the manifest's contact column)")
    outage = float(insp["instant"].max()) if insp["instant"].notna().any() \
        else float(table["last_instant"].max())
    table = table.merge(insp, on="contact", how="left")
    flag = lambda name: table[name].astype("boolean").fillna(False).to_numpy(bool)  # noqa: E731
    plugged_tubes = set(table.loc[flag("plugged"), "tube"])
    table["state"] = np.where(table["tube"].isin(plugged_tubes), "plugged",
                              np.where(table["instant"].isna(), "not inspected",
                                       np.where(flag("ndd"), "NDD", "sized")))
    table["found_at"] = table["instant"].fillna(outage)
    sized = table[table["state"] == "sized"]
    nodes_, fit = _posterior_nodes(posterior, models, sized, sizing, nodes, contact_sigma,
                                   power_sigma)
    live = table[table["state"] != "plugged"].reset_index(drop=True)
    kind = live["state"].map({"not inspected": 0, "sized": 1, "NDD": 2}).to_numpy()
    growth = GrowthModel.build(list(live["model"]), live["found_at"], kind, live["depth"],
                               nodes_, sizing=sizing, pod=pod)
    unit = str(live["time_unit"].iloc[0]) if len(live) else ""

    codes, names = pd.factorize(live["tube"])  # once: the tube of each contact

    def risk_at(t: float) -> BundleRisk:
        r = bundle_risk(growth.probabilities(t), codes, nodes_.weights)
        return BundleRisk(np.asarray(names, dtype=object)[r.tubes], r.log_survival, r.weights)

    risk = risk_at(interval)
    cm = as_found(sized[["contact", "tube", "depth", "limit_depth", "wall_thickness"]], sizing)
    must = list(dict.fromkeys(cm.loc[cm["past_limit"], "tube"]))
    must = [t for t in must if t in set(risk.tubes.tolist())]
    plugs = plugging_list(risk, target, always=must)
    sample = inspection_sample(risk, share)
    upper = 5 * interval if horizon is None else float(horizon)
    with_must = lambda t: _without(risk_at(t), must)  # noqa: E731
    try:
        longest = longest_interval(with_must, target, upper=upper, xtol=1e-6 * upper)
    except InputError:
        longest = 0.0
    grid = np.linspace(0.0, upper, 41)
    curve = pd.DataFrame({"interval": grid,
                          "p_any": [with_must(t).probability_any() for t in grid]})
    pm, pvm = predicted_vs_measured(models, sized, nodes_, sizing)
    contacts = _contact_rows(table, live, growth, risk, interval, sizing)
    tubes = _tube_rows(contacts, risk, plugs, must, sample, plugged_tubes)
    bundle_row = {
        "p_any": risk.probability_any(), "target": target, "interval": interval, "unit": unit,
        "outage": outage, "longest_interval": longest, "horizon": upper,
        "plugging": plugs, "must_plug": must, "p_any_after_plugging":
            risk.probability_any(plugs), "inspection_sample": sample, "share": share,
        "past_limit_contacts": int(cm["past_limit"].sum()),
        "past_limit_tubes": int(cm.loc[cm["past_limit"], "tube"].nunique()),
        "through_wall_contacts": int(cm["through_wall"].sum()),
        "through_wall_tubes": int(cm.loc[cm["through_wall"], "tube"].nunique()),
        "worst_tube": tubes["tube"].iloc[0] if len(tubes) else None,
        "contacts": len(table), "tubes": int(table["tube"].nunique()),
        "plugged_already": sorted(plugged_tubes), **{f"fit_{k}": v for k, v in pvm.items()}}
    inputs = {"bundle": getattr(bundle, "output", None), "sizing": sizing, "pod": pod,
              "calibration": fit, "contact_sigma": contact_sigma, "power_sigma": power_sigma,
              "limit": limit, "nodes": nodes}
    return Assessment(contacts=contacts, tubes=tubes, bundle=bundle_row, curve=curve,
                      condition=cm, predictions=pm, nodes=nodes_, inputs=inputs, fit=pvm,
                      risk=risk, models=models, growth=growth)


def _without(risk: BundleRisk, tubes) -> BundleRisk:
    keep = ~np.isin(risk.tubes, np.asarray(list(tubes), dtype=risk.tubes.dtype))
    return BundleRisk(risk.tubes[keep], risk.log_survival[keep], risk.weights)


def _contact_rows(table, live, growth, risk, interval, sizing) -> pd.DataFrame:
    p = growth.probabilities(interval) @ risk.weights
    tau = growth.end_nominal_times(interval, QUANTILES)
    g50 = float(np.exp(growth.nodes.quantiles([0.5])[0]))
    rows = np.arange(len(live))
    ends = growth.family.depth(tau, rows)
    found = growth.family.depth((growth.found * g50)[:, None], rows)[:, 0]
    sized = (live["state"] == "sized").to_numpy()
    found[sized] = np.asarray(sizing.true_depth(live["depth"].to_numpy(float)[sized]))
    out = live[["contact", "tube", "tube_row", "tube_column", "support", "state",
                "limit_depth", "wall_thickness"]].copy()
    out["measured"] = live["depth"]
    out["as_found"] = found
    for j, q in enumerate(QUANTILES):
        out[f"depth_end_q{100 * q:g}"] = ends[:, j]
    out["p_exceed"] = p
    plugged = table[table["state"] == "plugged"][list(out.columns[:8])]
    return pd.concat([out, plugged], ignore_index=True) if len(plugged) else out


def _tube_rows(contacts, risk, plugs, must, sample, plugged_tubes) -> pd.DataFrame:
    frame = contacts.assign(found_fraction=contacts["as_found"] / contacts["wall_thickness"],
                            end_fraction=contacts["depth_end_q50"] / contacts["wall_thickness"])
    worst = frame.sort_values("p_exceed", ascending=False, kind="stable").groupby(
        "tube", sort=False).head(1).set_index("tube")
    agg = frame.groupby("tube").agg(tube_row=("tube_row", "first"),
                                    tube_column=("tube_column", "first"),
                                    contacts=("contact", "size"),
                                    as_found_fraction=("found_fraction", "max"),
                                    end_fraction_q50=("end_fraction", "max"))
    p_t = pd.Series(risk.tube_probabilities(), index=risk.tubes)
    agg["worst_contact"] = worst["contact"].reindex(agg.index)
    agg["p_exceed"] = p_t.reindex(agg.index).fillna(0.0)
    agg["plugged"] = agg.index.isin(list(plugged_tubes))
    agg["plug"] = agg.index.isin(plugs)
    agg["inspect"] = agg.index.isin(sample)
    reasons = {t: "at or past the plugging limit as measured" for t in must}
    for t in plugs:
        reasons.setdefault(t, "preventive: P(any) over the target without it")
    for t in plugged_tubes:
        reasons[t] = "plugged already"
    agg["reason"] = [reasons.get(t, "") for t in agg.index]
    agg = agg.reset_index().sort_values(["plugged", "p_exceed"], ascending=[True, False],
                                        kind="stable")
    return agg.reset_index(drop=True)
