"""The outage decision (condition monitoring and operational assessment), its foundations:

- :mod:`fretwear.assessment.technique`: an inspection technique's sizing error and its
  probability of detection;
- :mod:`fretwear.assessment.inspections`: the field's inspection file (sized, NDD, not
  inspected, plugged; per contact or tube location) with its technique models;
- :mod:`fretwear.assessment.calibration`: the hierarchical calibration of the factor on those
  inspections (censored by the POD), per-contact posteriors and forecasts;
- :mod:`fretwear.assessment.contacts`, :mod:`~fretwear.assessment.growth`,
  :mod:`~fretwear.assessment.condition`, :mod:`~fretwear.assessment.outage`: :func:`assess`, the
  outage decision of a bundle (condition monitoring and operational assessment);
- :mod:`fretwear.assessment.operational`: the probability that any tube of a bundle exceeds its
  limit over an interval, the longest interval under a target, the preventive-plugging list and
  the inspection sample, from the contacts' probabilities of exceeding the limit.

The contacts' probabilities come from the depth model of each contact and the calibrated factor;
``fretwear assess`` ties them to a bundle's results (docs/assessment.md).
"""

from fretwear.assessment.calibration import BundleCalibration, FactorPrior, calibrate_bundle
from fretwear.assessment.inspections import (
    Inspections,
    Technique,
    read_field_inspections,
)
from fretwear.assessment.operational import (
    BundleRisk,
    bundle_risk,
    inspection_sample,
    longest_interval,
    plugging_list,
)
from fretwear.assessment.technique import LogisticPOD, LogSizingModel, SizingModel

__all__ = ["BundleCalibration", "BundleRisk", "FactorPrior", "Inspections", "LogSizingModel",
           "LogisticPOD", "SizingModel", "Technique", "bundle_risk", "calibrate_bundle",
           "inspection_sample", "longest_interval", "plugging_list", "read_field_inspections"]
