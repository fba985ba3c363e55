"""``fretwear calibrate --bundle`` says the predicted-against-measured coverage as ``assess``
does (a new user's trial: no such line; the same scars, 0 of 4 inside, said only by assess):
the same line, from the same function (summary.coverage_line), first after the FEI line.

Sources: the log-normal sizing's interval in closed form, d·exp(±z₀.₉₅ σ_ln) around the median
d for a factor known exactly; and assess's own count on the same bundle, inspections and
technique (its calibration runs through assess's path, not the command's).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.stats import norm

from fretwear.assessment import LogisticPOD, LogSizingModel, SizingModel
from fretwear.assessment.condition import predicted_vs_measured
from fretwear.assessment.growth import FactorNodes
from fretwear.assessment.outage import assess
from fretwear.assessment.summary import coverage_line
from fretwear.bundle import load
from fretwear.cli import main
from fretwear.report.predictions import bundle_predictions
from fretwear.table import models_from_table

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


def test_log_normal_sizing_interval_is_the_closed_form(example_bundle_out):
    tables, _ = bundle_predictions(example_bundle_out)
    contact = "R4C2-AVB1"
    model = models_from_table(tables[contact], name=contact)["global"]
    d = float(model.depth((10.0 - model.origin) * model.time_scale, factor=1.0, warn=False))
    s = 0.1
    sized = pd.DataFrame({"contact": [contact, contact], "instant": [10.0, 10.0],
                          "depth": [d * math.exp(2 * s), d * math.exp(1 * s)]})
    nodes = FactorNodes(np.array([0.0]), np.array([1.0]))  # the factor 1 exactly, no scatter
    frame, stats = predicted_vs_measured({contact: model}, sized, nodes, LogSizingModel(s))
    z = norm.ppf(0.95)
    # brentq's xtol 1e-12 m on depths of ~1e-5 m: 1e-6 relative
    np.testing.assert_allclose(frame["predicted"], d, rtol=1e-6)
    np.testing.assert_allclose(frame["low"], d * math.exp(-z * s), rtol=1e-6)
    np.testing.assert_allclose(frame["high"], d * math.exp(z * s), rtol=1e-6)
    assert frame["inside"].tolist() == [False, True] and stats["coverage"] == 0.5


def test_calibrate_bundle_says_the_coverage_line_of_assess(example_bundle_out, capsys):
    sizing, pod = SizingModel(0.0, 1.0, 5e-5), LogisticPOD.from_depths(1.5e-4, 3e-4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = assess(load(example_bundle_out), EXAMPLE / "inspections.csv", interval=4.0,
                     sizing=sizing, pod=pod).fit
    n = fit["indications"]
    expected = coverage_line(round(fit["coverage"] * n), n, fit["level"])
    assert expected is not None  # 0 of 4 on the shipped scars
    assert main(["calibrate", str(EXAMPLE / "inspections.csv"), "--bundle",
                 str(example_bundle_out), "--sizing-sigma-mm", "0.05", "--pod-a50-mm", "0.15",
                 "--pod-a90-mm", "0.30"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == expected, lines  # no FEI line (no tubes.csv); one line (soft wrap)
    assert f"predicted against measured: {n} indications, 0% inside" in "\n".join(lines)
