"""Draw the example bundle's inspection campaign from a known true factor (issue 26, point 8).

A synthetic eddy-current campaign of ``examples/bundle`` (illustrative, not measurements), for
the calibration to show it recovers what the campaign was drawn from:

* **truth**: each contact's factor on its wear coefficient is f_i = F·exp(s·z_i), z_i standard
  normal (seeded): a bundle factor F = 1.6 and a contact scatter s = 0.35; its true depth at
  the outage is its prediction's at f_i (``DepthModel.depth``, the one depth model);
* **outage**: 2022-01-01, the predictions' instant 0 being 2012-01-01 (10.008 years);
  9 of the 12 tubes inspected (a seeded draw), every support of an inspected tube;
* **technique** (illustrative values, labelled so): a bobbin probe sizing measured = true + e,
  σ = 0.03 mm, and detecting with a logistic POD in ln depth of a50 = 0.05 mm, a90 = 0.10 mm;
  a flaw is detected with probability POD(true depth) (seeded), then sized (measured depth in
  % through-wall, rounded to 1 % as a field report is); NDD otherwise.

Writes ``campaign.csv`` (tube_row, tube_column, support, date, technique, depth_pct, inspected,
wall_thickness) and ``campaign_truth.csv`` (contact, true factor, true depth [m]) next to this
script. Rerun it whenever the example's histories change (the predictions change with them)::

    fretwear bundle examples/bundle/manifest.csv --case examples/bundle/bundle.toml -o build/bundle
    python examples/bundle/make_inspections.py --bundle build/bundle

Calibrate on it (docs/assessment.md)::

    fretwear calibrate examples/bundle/campaign.csv --bundle build/bundle \\
        --origin-date 2012-01-01 --sizing-sigma-mm 0.03 --pod-a50-mm 0.05 --pod-a90-mm 0.10 \\
        --forecast 30
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent

TRUE_FACTOR = 1.6
CONTACT_SIGMA_LN = 0.35
SEED = 2026
ORIGIN_DATE = "2012-01-01"
OUTAGE_DATE = "2022-01-01"
SIZING_SIGMA = 3e-5   # [m]
POD_A50, POD_A90 = 5e-5, 1e-4   # [m]
TUBES_INSPECTED = 9
TECHNIQUE = "bobbin (illustrative)"
PCT_DECIMALS = 0   # the depths are written in whole % of the wall, as a field report gives them


def technique():
    """The campaign's technique model (illustrative values)."""
    from fretwear.assessment import LogisticPOD, SizingModel, Technique

    return Technique(SizingModel(0.0, 1.0, SIZING_SIGMA), LogisticPOD.from_depths(POD_A50, POD_A90),
                     name=TECHNIQUE, illustrative=True)


def draw_campaign(models: dict, identity: pd.DataFrame, seed: int = SEED
                  ) -> tuple[pd.DataFrame, pd.DataFrame]:
    """(campaign, truth) drawn from the contacts' depth models (``{contact: DepthModel}``)."""
    rng = np.random.default_rng(seed)
    tech = technique()
    ident = identity.drop_duplicates("contact").set_index("contact").loc[sorted(models)]
    tubes = sorted({(int(r), int(c)) for r, c in zip(ident["tube_row"], ident["tube_column"],
                                                    strict=True)})
    chosen = {tubes[k] for k in rng.choice(len(tubes), TUBES_INSPECTED, replace=False)}
    years = (pd.Timestamp(OUTAGE_DATE) - pd.Timestamp(ORIGIN_DATE)).total_seconds() / 31536000.0
    rows, truth = [], []
    for contact in ident.index:
        model = models[contact]
        factor = TRUE_FACTOR * float(np.exp(CONTACT_SIGMA_LN * rng.standard_normal()))
        depth = float(model.depth((years - model.origin) * model.time_scale, factor=factor))
        detect, noise = rng.random(), rng.standard_normal()
        tube = (int(ident.loc[contact, "tube_row"]), int(ident.loc[contact, "tube_column"]))
        wall = float(model.wall.thickness)
        row = {"tube_row": tube[0], "tube_column": tube[1],
               "support": ident.loc[contact, "support"], "date": OUTAGE_DATE,
               "technique": TECHNIQUE, "depth_pct": "", "inspected": "yes",
               "wall_thickness": wall}
        if tube not in chosen:
            row["inspected"] = "no"
        elif detect < float(tech.pod(depth)):
            measured = depth + SIZING_SIGMA * noise
            step = 10.0 ** -PCT_DECIMALS
            pct = max(round(100 * measured / wall, PCT_DECIMALS), step)
            row["depth_pct"] = f"{pct:.{PCT_DECIMALS}f}"
        else:
            row["depth_pct"] = "NDD"
        rows.append(row)
        truth.append({"contact": contact, "true_factor": factor, "true_depth_m": depth})
    return pd.DataFrame(rows), pd.DataFrame(truth)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bundle", type=Path, required=True,
                        help="the output directory of fretwear bundle on this example")
    parser.add_argument("--output", type=Path, default=HERE)
    parser.add_argument("--seed", type=int, default=SEED)
    args = parser.parse_args()
    from fretwear.report.predictions import bundle_predictions
    from fretwear.table import models_from_table

    tables, identity = bundle_predictions(args.bundle)
    models = {c: models_from_table(t, name=c)["global"] for c, t in tables.items()}
    campaign, truth = draw_campaign(models, identity, args.seed)
    header = (f"# Example inspection campaign of examples/bundle (synthetic, illustrative): drawn "
              f"by make_inspections.py\n# from a true bundle factor {TRUE_FACTOR} (contact "
              f"scatter sigma_ln {CONTACT_SIGMA_LN}, seed {args.seed}); technique: sizing sigma "
              f"{SIZING_SIGMA * 1e3:g} mm,\n# POD a50 {POD_A50 * 1e3:g} mm, a90 "
              f"{POD_A90 * 1e3:g} mm. Predictions' instant 0 is {ORIGIN_DATE}.\n")
    args.output.mkdir(parents=True, exist_ok=True)
    (args.output / "campaign.csv").write_text(header + campaign.to_csv(index=False),
                                               encoding="utf-8")
    truth.to_csv(args.output / "campaign_truth.csv", index=False, float_format="%.6e")
    print(f"wrote {args.output / 'campaign.csv'} ({(campaign['depth_pct'] == 'NDD').sum()} NDD, "
          f"{(campaign['inspected'] == 'no').sum()} not inspected of {len(campaign)} contacts)")


if __name__ == "__main__":
    main()
