"""Follow-ups of issue 26 found by a new user's trial (closing2.md, "Seen and left alone"):

* the bad news says a poor predicted-against-measured coverage (a posterior split between the
  prior and the data, its median near neither, which the factor's own line misses);
* the library and the commands share one default of the power's spread.

Oracles: the binomial distribution written out term by term (math.comb), the shipped
examples/bundle inspections (four scars 20-30x the simulated wear: closing2.md, 0 of 4 inside),
the commands' declared option defaults.
"""

from __future__ import annotations

import inspect
import math
import warnings
from pathlib import Path

import pytest

from fretwear.assessment import LogisticPOD, SizingModel, calibrate_bundle
from fretwear.assessment.calibration import CONTACT_SIGMA_LN, POWER_SIGMA_LN, FactorPrior
from fretwear.assessment.outage import assess
from fretwear.assessment.summary import COVERAGE_SIGNIFICANCE, coverage_line

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bundle"


def _binomial_cdf(k: int, n: int, p: float) -> float:
    """P(K <= k), K ~ B(n, p), written out term by term (the test's own computation)."""
    return sum(math.comb(n, j) * p ** j * (1 - p) ** (n - j) for j in range(k + 1))


@pytest.mark.parametrize("n", [1, 2, 4, 10, 30])
def test_coverage_line_is_said_exactly_when_so_few_inside_is_improbable(n):
    for k in range(n + 1):
        p = _binomial_cdf(k, n, 0.9)
        line = coverage_line(k, n, 0.9)
        assert (line is not None) == (p < COVERAGE_SIGNIFICANCE), (k, n, p)
        if line:
            assert f"{k} of {n} sized indications inside their 90 % interval" in line
            assert f"probability {p:.2g}" in line


def test_coverage_line_numbers_of_its_docstring():
    # (1 - 0.9)^4 = 1e-4; 1e-4 + 4·0.9·0.1³ = 3.7e-3; + 6·0.81·0.01 = 0.0523
    assert _binomial_cdf(0, 4, 0.9) == pytest.approx(1e-4, rel=1e-12)
    assert _binomial_cdf(1, 4, 0.9) == pytest.approx(3.7e-3, rel=1e-12)
    assert coverage_line(1, 4) is not None and coverage_line(2, 4) is None
    assert coverage_line(0, 1) is None and coverage_line(0, 0) is None


def test_poor_coverage_on_the_shipped_inspections_is_bad_news(example_bundle_out):
    """The shipped scars are 20-30x the simulated wear: under the command's illustrative
    technique the calibrated factor's median is within [1/10, 10] (the factor's line is
    silent) yet none of the four indications is inside its 90 % interval."""
    from fretwear.bundle import load

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = assess(load(example_bundle_out), EXAMPLE / "inspections.csv", interval=4.0,
                        sizing=SizingModel(0.0, 1.0, 5e-5),
                        pod=LogisticPOD.from_depths(1.5e-4, 3e-4))
    fit = result.fit
    inside = round(fit["coverage"] * fit["indications"])
    assert fit["indications"] == 4 and inside == 0
    assert _binomial_cdf(inside, 4, fit["level"]) < COVERAGE_SIGNIFICANCE
    news = result.bad_news()
    said = [line for line in news if line.startswith("PREDICTED AGAINST MEASURED")]
    assert said == [coverage_line(0, 4, fit["level"])], news


def test_one_default_of_the_power_spread_for_the_library_and_the_commands():
    """closing2.md: calibrate_bundle defaulted to power_sigma_ln=0 where both commands
    default to 0.2 (fails before: 0.0 != 0.2)."""
    from fretwear.cli.assess import command as assess_command
    from fretwear.cli.calibrate import command as calibrate_command

    library = inspect.signature(calibrate_bundle).parameters["power_sigma_ln"].default
    outage = inspect.signature(assess).parameters
    assert library == outage["power_sigma_ln"].default == POWER_SIGMA_LN == 0.2
    assert outage["contact_sigma_ln"].default == FactorPrior().contact_sigma_ln \
        == CONTACT_SIGMA_LN
    for command in (assess_command, calibrate_command):
        options = {o.name: o.default for o in command.params}
        assert options["power_sigma_ln"] == POWER_SIGMA_LN, command.name
        assert options["contact_sigma_ln"] == CONTACT_SIGMA_LN, command.name
