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
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.assessment.calibration import (
    CONTACT_SIGMA_LN,
    POWER_SIGMA_LN,
    BundleCalibration,
    FactorPrior,
)
from fretwear.assessment.calibration_inputs import support_type
from fretwear.assessment.condition import as_found, predicted_vs_measured
from fretwear.assessment.contacts import bundle_models, field_inspections
from fretwear.assessment.growth import FactorNodes, GrowthModel
from fretwear.assessment.inspections import (
    Inspections,
    check_depths_within_walls,
    read_field_inspections,
)
from fretwear.assessment.operational import (
    BundleRisk,
    bundle_risk,
    inspection_sample,
    longest_interval,
    plugging_list,
)
from fretwear.assessment.summary import coverage_line, factor_line, probability_text
from fretwear.errors import InputError
from fretwear.keys import check_level

__all__ = ["Assessment", "assess", "calibration_fit"]

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
        ``p_any``, ``target``, ``interval``, ``longest_interval`` [time unit] (the plugging
        list plugged), ``longest_interval_before_plugging`` [time unit] (only the tubes at the
        limit as measured plugged), ``p_any_after_plugging``, ``plugging`` (tubes),
        ``must_plug`` (at or past the limit as measured), ``inspection_sample``, ``share``,
        counts of contacts and tubes past the limit and through the wall, ``worst_tube``.
    curve : DataFrame
        ``interval`` [time unit], ``p_any`` [-] (the plugging list plugged) and
        ``p_any_before_plugging`` [-] (only the tubes at the limit as measured plugged).
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
        # the technique as explicit fields with units (technique.from_record reads them back)
        payload = {"bundle": self.bundle, "inputs": {k: v.to_record() if k in ("sizing", "pod")
                                                     else v for k, v in self.inputs.items()},
                   "factor_nodes": {"log_factor": self.nodes.log_factor.tolist(),
                                    "weights": self.nodes.weights.tolist(),
                                    "contact_sigma": self.nodes.contact_sigma,
                                    "power_sigma": self.nodes.power_sigma}}
        with atomic_write(root / "assessment.json", encoding="utf-8") as handle:
            json.dump(payload, handle, indent=1, default=str)
        written.append(root / "assessment.json")
        return written

    def probability_line(self) -> str:
        """P(any), the interval counted from the outage (the inspections' last instant), and
        the target: the one wording of the terminal, the summary and the report."""
        b = self.bundle
        at = "" if b.get("outage") is None else f" at {b['outage']:g} {b['unit']}"
        compare = (f"> target {b['target']:g}" if b["p_any"] > b["target"]
                   else f"(target {b['target']:g})")
        return (f"P(any tube past its limit within {b['interval']:g} {b['unit']} after the "
                f"outage{at}) = {probability_text(b['p_any'])} {compare}")

    def bad_news(self) -> list[str]:
        """The lines said first: contacts and tubes past the limit and through the wall, the
        bundle's probability above the target, a calibrated factor beyond [1/10, 10]
        (:func:`~fretwear.assessment.summary.factor_line`), too few sized indications inside
        their predicted interval (:func:`~fretwear.assessment.summary.coverage_line`)."""
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
            lines.append(self.probability_line())
        implausible = factor_line(self.inputs.get("calibration", {}).get("factor_median",
                                                                          math.nan))
        n = int(self.fit.get("indications", 0) or 0)
        poor = coverage_line(round(self.fit["coverage"] * n), n, self.fit["level"]) if n \
            else None
        return lines + [line for line in (implausible, poor) if line]


def _group_names(table, groups) -> list | None:
    """Each contact's group name (None: no group level)."""
    if groups is None:
        return None
    if isinstance(groups, str):
        if groups != "support type":
            raise InputError(f"groups must be None, 'support type' or a mapping of contact to "
                             f"group, got {groups!r}")
        return [support_type(s) or "other" for s in table["support"].astype(str)]
    if not isinstance(groups, Mapping):
        raise InputError("groups must be None, 'support type' or a mapping of contact to group")
    return [str(groups.get(c, "other")) for c in table["contact"]]


def _inspected_contacts(ins, table) -> list:
    """The contacts an inspection row names or locates (the others give the calibration
    nothing: leaving them out changes no level's posterior)."""
    t = ins.table
    named = set(t.loc[t["contact"].astype(str) != "", "contact"].astype(str))
    located = t[t["contact"].astype(str) == ""]
    if len(located):
        spots = set(zip(located["tube_row"].astype(float), located["tube_column"].astype(float),
                        strict=True))
        where = [(float(r), float(c)) in spots for r, c in zip(table["tube_row"],
                                                               table["tube_column"], strict=True)]
        named |= set(table.loc[where, "contact"])
    return [c for c in table["contact"] if c in named]


def _calibrated(table, ins, sizing, pod, prior, names, power_sigma_ln):
    """The hierarchical calibration of the inspected contacts (None: nothing inspected)."""
    from fretwear.assessment.calibration import calibrate_bundle
    from fretwear.assessment.inspections import Technique

    if ins is None or not (ins.table["status"] != "not inspected").any():
        return None
    keep = _inspected_contacts(ins, table)
    models = dict(zip(table["contact"], table["model"], strict=True))
    tech = Technique(sizing, pod, name="assess")
    ins = Inspections(ins.table, {n: tech for n in set(ins.table["technique"])}, ins.source,
                      ins.depth_column)
    mapping = None if names is None else dict(zip(table["contact"], names, strict=True))
    return calibrate_bundle({c: models[c] for c in keep}, ins, prior=prior,
                            groups=None if mapping is None else
                            {c: mapping[c] for c in keep},
                            identity=table[["contact", "tube_row", "tube_column", "support"]],
                            power_sigma_ln=power_sigma_ln, levels_only=True)


def _factor_nodes(posterior, table, ins, sizing, pod, count, prior, groups, power_sigma_ln):
    """(FactorNodes, each contact's group index or None, what was fitted)."""
    if isinstance(posterior, FactorNodes):
        return posterior, None, {"method": "given nodes"}
    if posterior is not None and not isinstance(posterior, BundleCalibration):
        dist = getattr(posterior, "posterior", posterior)  # a single factor's posterior
        return FactorNodes.from_posterior(dist, count=count, contact_sigma=prior.contact_sigma_ln,
                                          power_sigma=power_sigma_ln), None, {"method": "given"}
    names = _group_names(table, groups)
    cal = _calibrated(table, ins, sizing, pod, prior, names, power_sigma_ln) \
        if posterior is None else posterior
    if cal is not None:
        prior = cal.prior
        s_c = float(prior.contact_sigma_ln)
        s_p = math.sqrt(max(float(np.median(np.asarray(cal.scatter) ** 2)) - s_c ** 2, 0.0))
        grid, bundle = cal.levels.grid, cal.levels.bundle
        if names is None and len(cal.groups) > 1:  # a given calibration's own groups
            own = dict(zip(cal.contacts, (cal.groups[k] for k in cal.group_of), strict=True))
            names = [own.get(c) or support_type(s) or "other"
                     for c, s in zip(table["contact"], table["support"].astype(str),
                                     strict=True)]
    else:
        s_c, s_p = float(prior.contact_sigma_ln), float(power_sigma_ln)
        half = 12.0 * math.hypot(prior.bundle.sigma_ln, prior.group_sigma_ln)
        grid = math.log(prior.bundle.median) + np.linspace(-half, half, 2401)
        bundle = np.exp(-0.5 * ((grid - math.log(prior.bundle.median))
                                / prior.bundle.sigma_ln) ** 2)
    tau_g = float(prior.group_sigma_ln)
    if names is None or tau_g == 0:
        nodes = FactorNodes.from_levels(grid, bundle, count=count, contact_sigma=s_c,
                                        power_sigma=s_p)
        group_of, labels = None, []
    else:
        labels = sorted(set(names))
        group_of = np.array([labels.index(n) for n in names])
        log_groups = np.zeros((len(labels), grid.size))
        if cal is not None:  # Σ_{i∈g} log M_i(c) of the calibrated contacts
            where = dict(zip(table["contact"], group_of, strict=True))
            np.add.at(log_groups, [where[c] for c in cal.contacts], cal.levels.log_evidence)
        nodes = FactorNodes.from_levels(grid, bundle, log_groups, tau_g,
                                        count=max(count // 2, 4), contact_sigma=s_c,
                                        power_sigma=s_p)
    fit = {"method": "hierarchical" if cal is not None else "prior", "groups": labels}
    if cal is not None:
        median, interval = cal.bundle_factor()
        fit.update(factor_median=median, factor_interval_90=interval)
    return nodes, group_of, fit


def calibration_fit(cal: BundleCalibration, sizing, *, identity=None, level: float = 0.90,
                    count: int = 16) -> tuple[pd.DataFrame, dict]:
    """Predicted against measured for a bundle calibration (``fretwear calibrate --bundle``),
    as :func:`assess` computes it: the calibrated factor's nodes, each sized indication's
    central ``level`` interval, the share inside.

    Parameters
    ----------
    cal : BundleCalibration
        :func:`~fretwear.assessment.calibration.calibrate_bundle`'s result.
    sizing : SizingModel or LogSizingModel
        The technique's sizing error the calibration used.
    identity : DataFrame, optional
        ``contact`` and ``support`` of the bundle (the support types of a calibration with
        groups).
    level : float
        The interval's probability [-].
    count : int
        Factor nodes (:func:`assess`'s ``nodes``).

    Returns
    -------
    (DataFrame, dict)
        :func:`~fretwear.assessment.condition.predicted_vs_measured` on the calibration's
        sized indications (``indications``, ``coverage`` [-], ``level``, ``rms_residual``
        [m]); :func:`~fretwear.assessment.summary.coverage_line` makes the bad news of it.
    """
    support = {} if identity is None or "support" not in identity else dict(
        zip(identity["contact"], identity["support"].astype(str), strict=True))
    table = pd.DataFrame({"contact": cal.contacts,
                          "support": [support.get(c, "") for c in cal.contacts]})
    nodes, group_of, _ = _factor_nodes(cal, table, None, sizing, None, count, cal.prior, None,
                                       0.0)
    obs = cal.observations
    sized = obs.loc[(obs["status"] == "sized") & obs["depth"].notna(),
                    ["contact", "instant", "depth"]]
    return predicted_vs_measured(cal.models, sized, nodes, sizing, level=level,
                                 group_of=None if group_of is None else dict(
                                     zip(table["contact"], group_of, strict=True)))


def assess(bundle: Any, inspections=None, *, interval: float, sizing, pod,
           target: float = 0.05, posterior=None, contact_sigma_ln: float = CONTACT_SIGMA_LN,
           power_sigma_ln: float = POWER_SIGMA_LN, group_sigma_ln: float = 0.0, groups=None,
           prior=None, share: float = 0.9, limit: float | None = None,
           horizon: float | None = None, nodes: int = 16, origin_date=None) -> Assessment:
    """Condition monitoring and operational assessment of a bundle at an outage.

    Parameters
    ----------
    bundle : BundleResult
        A finished bundle run (:func:`fretwear.bundle.run_bundle` or :func:`fretwear.bundle.load`).
    inspections : path-like, DataFrame or Inspections, optional
        The outage's inspections (:func:`fretwear.assessment.inspections.read_field_inspections`);
        None: nothing inspected (the outage at the bundle's last instant).
    interval : float
        The next operating interval [the bundle's time unit], > 0.
    sizing : SizingModel
        The technique's sizing error [m].
    pod : LogisticPOD
        The technique's probability of detection.
    target : float
        The probability target of P(any tube past its limit) [-] (commonly 0.05).
    posterior : BundleCalibration, FactorNodes, CalibrationResult or distribution, optional
        The calibrated factor. Default: the hierarchical censored calibration
        (:func:`fretwear.assessment.calibration.calibrate_bundle`) of these inspections, sized
        results through ``sizing``, NDD through 1 − ``pod``, uninspected contacts giving
        nothing, with ``prior`` (its bundle level), ``contact_sigma_ln``, ``group_sigma_ln``
        and ``power_sigma_ln``. A single factor's posterior
        (:func:`fretwear.uncertainty.calibrate`'s result, or a distribution) is also taken,
        with ``contact_sigma_ln`` and ``power_sigma_ln`` about it.
    contact_sigma_ln, power_sigma_ln, group_sigma_ln : float
        σ of ln of one contact's factor about its group's, of the factor on each contact's
        power, and of a group's factor about the bundle's [-] (0: no group level); defaults
        :data:`~fretwear.assessment.calibration.CONTACT_SIGMA_LN` and
        :data:`~fretwear.assessment.calibration.POWER_SIGMA_LN`, the commands' too.
    groups : None, "support type" or mapping of contact to group name
        The group level (default "support type" when ``group_sigma_ln`` > 0): the contacts
        of a group share its factor at every node of the assessment
        (:meth:`FactorNodes.from_levels`).
    prior : FactorPrior, optional
        The calibration's prior; default the bundle level of :class:`FactorPrior` (median 1,
        scatter 3) with the three σ above.
    share : float
        The share of the bundle's risk the next inspection's sample covers [-].
    limit : float, optional
        Plugging limit, fraction of the wall [-] (default each contact's depth_limit).
    horizon : float, optional
        The longest interval searched [time unit] (default 5 × interval).
    nodes : int
        Quadrature nodes of the bundle level's posterior.
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
    if prior is None:
        prior = FactorPrior(contact_sigma_ln=contact_sigma_ln, group_sigma_ln=group_sigma_ln)
    if groups is None and prior.group_sigma_ln > 0:
        groups = "support type"
    table = bundle_models(bundle, limit=limit)
    unit = str(table["time_unit"].dropna().iloc[0]) if table["time_unit"].notna().any() \
        else "year"
    ins = None
    if inspections is not None:
        ins = inspections if isinstance(inspections, Inspections) else \
            read_field_inspections(inspections, origin_date=origin_date, time_unit=unit)
        check_depths_within_walls(ins, table)  # a value in mm in a metres column
    insp = field_inspections(ins, table) if ins is not None else \
        pd.DataFrame({"contact": pd.Series(dtype=str), "instant": pd.Series(dtype=float),
                      "depth": pd.Series(dtype=float), "ndd": pd.Series(dtype=bool),
                      "plugged": pd.Series(dtype=bool)})
    models = dict(zip(table["contact"], table["model"], strict=True))
    unknown = sorted(set(insp["contact"]) - set(models))
    if unknown:
        raise InputError(f"inspected contacts not computed in the bundle: {unknown[:5]} "
                         "(names as in the manifest's contact column)")
    outage = float(insp["instant"].max()) if insp["instant"].notna().any() \
        else float(table["last_instant"].max())
    nodes_, group_of, fit = _factor_nodes(posterior, table, ins, sizing, pod, nodes, prior,
                                          groups, power_sigma_ln)
    table = table.merge(insp, on="contact", how="left")
    flag = lambda name: table[name].astype("boolean").fillna(False).to_numpy(bool)  # noqa: E731
    plugged_tubes = set(table.loc[flag("plugged"), "tube"])
    table["state"] = np.where(table["tube"].isin(plugged_tubes), "plugged",
                              np.where(table["instant"].isna(), "not inspected",
                                       np.where(flag("ndd"), "NDD", "sized")))
    table["found_at"] = table["instant"].fillna(outage)
    sized = table[table["state"] == "sized"]
    service = (table["state"] != "plugged").to_numpy()
    live = table[service].reset_index(drop=True)
    kind = live["state"].map({"not inspected": 0, "sized": 1, "NDD": 2}).to_numpy()
    growth = GrowthModel.build(list(live["model"]), live["found_at"], kind, live["depth"],
                               nodes_, sizing=sizing, pod=pod,
                               group_of=None if group_of is None else group_of[service])
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
    sample = inspection_sample(risk, share, exclude=plugs)  # a plugged tube is not inspected
    upper = 5 * interval if horizon is None else float(horizon)
    grid = np.linspace(0.0, upper, 41)
    risks = [risk_at(t) for t in grid]
    curve = pd.DataFrame({"interval": grid,
                          "p_any": [r.probability_any(plugs) for r in risks],
                          "p_any_before_plugging": [r.probability_any(must) for r in risks]})
    after = _longest(risk_at, plugs, target, grid, curve["p_any"].to_numpy())
    before = _longest(risk_at, must, target, grid, curve["p_any_before_plugging"].to_numpy())
    pm, pvm = predicted_vs_measured(models, sized, nodes_, sizing, group_of=None if group_of
                                    is None else dict(zip(table["contact"], group_of,
                                                          strict=True)))
    contacts = _contact_rows(table, live, growth, risk, interval, sizing)
    tubes = _tube_rows(contacts, risk, plugs, must, sample, plugged_tubes)
    bundle_row = {
        "p_any": risk.probability_any(), "target": target, "interval": interval, "unit": unit,
        "outage": outage, "longest_interval": after, "longest_interval_before_plugging": before,
        "horizon": upper, "plugging": plugs, "must_plug": must, "p_any_after_plugging":
            risk.probability_any(plugs), "inspection_sample": sample, "share": share,
        "past_limit_contacts": int(cm["past_limit"].sum()),
        "past_limit_tubes": int(cm.loc[cm["past_limit"], "tube"].nunique()),
        "through_wall_contacts": int(cm["through_wall"].sum()),
        "through_wall_tubes": int(cm.loc[cm["through_wall"], "tube"].nunique()),
        "worst_tube": tubes["tube"].iloc[0] if len(tubes) else None,
        "contacts": len(table), "tubes": int(table["tube"].nunique()),
        "plugged_already": sorted(plugged_tubes), **{f"fit_{k}": v for k, v in pvm.items()}}
    inputs = {"bundle": getattr(bundle, "output", None), "sizing": sizing, "pod": pod,
              "calibration": fit, "contact_sigma_ln": prior.contact_sigma_ln,
              "power_sigma_ln": power_sigma_ln, "group_sigma_ln": prior.group_sigma_ln,
              "limit": limit, "nodes": nodes}
    return Assessment(contacts=contacts, tubes=tubes, bundle=bundle_row, curve=curve,
                      condition=cm, predictions=pm, nodes=nodes_, inputs=inputs, fit=pvm,
                      risk=risk, models=models, growth=growth)


def _longest(risk_at, plugged, target, grid, curve) -> float:
    """The longest interval under ``target`` with the tubes ``plugged`` out of service: Brent's
    root in the cell of ``grid`` where the (non-decreasing) ``curve`` of P(any) crosses it."""
    past = np.flatnonzero(curve > target)
    if not past.size:
        return float(grid[-1])
    if past[0] == 0:
        return 0.0
    return longest_interval(lambda t: _without(risk_at(t), plugged), target,
                            lower=float(grid[past[0] - 1]), upper=float(grid[past[0]]),
                            xtol=1e-6 * float(grid[-1]))


def _without(risk: BundleRisk, tubes) -> BundleRisk:
    keep = ~np.isin(risk.tubes, np.asarray(list(tubes), dtype=risk.tubes.dtype))
    return BundleRisk(risk.tubes[keep], risk.log_survival[keep], risk.weights)


def _contact_rows(table, live, growth, risk, interval, sizing) -> pd.DataFrame:
    p = growth.probabilities(interval) @ risk.weights
    tau = growth.end_nominal_times(interval, QUANTILES)
    g50 = growth.factor_quantile(0.5)
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
