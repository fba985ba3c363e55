"""The shipped example of a calibration that learns (examples/support_plate, docs/assessment.md
"Worked example: a campaign that calibrates"): ``fretwear bundle`` then ``fretwear calibrate
--bundle --forecast 20`` on eight sized indications move the bundle factor from its prior
(median 1, 90 % in [0.40, 2.5]) to about 2.4 with the campaign's true 2.5 inside.

Independent source: the conjugate normal-normal closed form. The example's depth is linear in
the factor (Archard, uniform wear of a drilled hole: d = f·K·P·t/(2π·l·R), computed here from
the manifest's powers, not by fretwear's depth model) and every indication is sized with a
log-normal error, so y_i = ln(m_i/d_i(1, t)) = μ + η_i + ε_i with μ ~ N(0, τ0²) (the prior,
τ0 = ln 3/1.96), η_i ~ N(0, s_c² + s_P²) (contact scatter 0.35, power 0.2) and ε_i ~ N(0, σ²)
(σ = 0.1): μ's posterior is normal with precision 1/τ0² + Σ 1/(s² + σ²), and contact i's
ln f_i = μ + η_i is normal with mean (1 − k)·m + k·y_i and variance (1 − k)²·v + k·σ²,
k = s²/(s² + σ²). fretwear's posterior is a grid quadrature (fretwear.assessment.posterior).
"""

from __future__ import annotations

import importlib.util
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm

from fretwear.cli import main

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "support_plate"
K, R, L, YEAR = 5.2e-14, 9.525e-3, 20e-3, 31_536_000.0  # Pa⁻¹, m, m, s (case.toml)
TAU0 = math.log(3.0) / norm.ppf(0.975)  # the default prior: scatter 3 at 95 %
S2, SIGMA2 = 0.35 ** 2 + 0.2 ** 2, 0.1 ** 2  # contact + power scatter; sizing (ln)
Z90 = norm.ppf(0.95)


def _closed_form():
    """(mean, variance) of μ | y and, per inspected contact, (mean, variance) of ln f_i | y."""
    manifest = pd.read_csv(EXAMPLE / "manifest.csv")
    campaign = pd.read_csv(EXAMPLE / "campaign.csv")
    sized = campaign[campaign["inspected"] == "yes"].merge(
        manifest, on=["tube_row", "tube_column", "support"])
    nominal = K * sized["power.value_W"] * sized["instant"] * YEAR / (2 * math.pi * L * R)
    y = np.log(sized["depth_mm"] * 1e-3 / nominal).to_numpy()
    precision = 1 / TAU0 ** 2 + len(y) / (S2 + SIGMA2)
    m, v = (y.sum() / (S2 + SIGMA2)) / precision, 1 / precision
    k = S2 / (S2 + SIGMA2)
    contacts = pd.DataFrame({"contact": sized["contact"], "mean": (1 - k) * m + k * y,
                             "var": (1 - k) ** 2 * v + k * SIGMA2})
    return m, v, contacts


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("plate")
    assert main(["bundle", str(EXAMPLE / "manifest.csv"), "--case", str(EXAMPLE / "case.toml"),
                 "--scheduler", "serial", "-q", "-o", str(out / "plate")]) == 0
    return out


def test_calibrate_moves_the_factor_to_the_closed_form(run, capsys):
    capsys.readouterr()
    code = main(["calibrate", str(EXAMPLE / "campaign.csv"), "--bundle", str(run / "plate"),
                 "--forecast", "20", "--top", "5", "-o", str(run / "calibration.csv")])
    text = capsys.readouterr().out
    assert code in (0, None), text
    found = re.search(r"bundle factor: median ([\d.]+), 90 % \[([\d.]+), ([\d.]+)\]", text)
    m, v, contacts = _closed_form()
    expected = [math.exp(m), math.exp(m - Z90 * math.sqrt(v)), math.exp(m + Z90 * math.sqrt(v))]
    # printed at 4 significant digits (5e-4 relative), the grid's own error well under it
    assert [float(g) for g in found.groups()] == pytest.approx(expected, rel=1e-3), text
    prior = (math.exp(-Z90 * TAU0), math.exp(Z90 * TAU0))  # 0.40, 2.5
    assert expected[1] > 1.0 and expected[1] < 2.5 < expected[2]  # the prior's 1 left; truth in
    # the interval narrowed, 3.9 times in ln f
    assert math.log(expected[2] / expected[1]) < 0.3 * math.log(prior[1] / prior[0])
    lines = text.splitlines()
    assert lines[0].startswith("at instant 20: 2 contact(s) (2 tube(s)) at or past the limit")
    assert "8 sized, 0 NDD, 4 not inspected" in text

    table = pd.read_csv(run / "calibration.csv").merge(contacts, on="contact")
    assert len(table) == 8  # every inspected contact's own factor, at full precision (grid: 1e-6)
    np.testing.assert_allclose(np.log(table["factor_median"]), table["mean"], atol=1e-5)
    np.testing.assert_allclose(table["factor_sigma_ln"], np.sqrt(table["var"]), rtol=1e-5)


def test_the_campaign_script_writes_the_shipped_files(tmp_path):
    spec = importlib.util.spec_from_file_location("make_campaign",
                                                  EXAMPLE / "make_campaign.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    script.HERE = tmp_path
    script.main()
    for name in ("manifest.csv", "campaign.csv", "campaign_truth.csv"):
        mine, shipped = pd.read_csv(tmp_path / name), pd.read_csv(EXAMPLE / name)
        # seeded: the same draws on any machine, to the files' rounding (4 digits)
        pd.testing.assert_frame_equal(mine, shipped, check_exact=False, rtol=1e-3)


def test_assess_reads_the_given_powers(run, tmp_path):
    """A bundle whose manifest gives each contact's power (``power.value_W``, no history):
    the contact's power is the given one [W] (it was None: `assess` stopped on an internal
    TypeError), and `fretwear assess` runs on it. Source: the manifest's own column."""
    from fretwear.bundle import load

    contacts = load(run / "plate").contacts.set_index("contact")["power"]
    manifest = pd.read_csv(EXAMPLE / "manifest.csv").set_index("contact")["power.value_W"]
    assert contacts.astype(float).to_dict() == manifest.astype(float).to_dict()
    assert main(["assess", str(run / "plate"), str(EXAMPLE / "campaign.csv"), "--interval", "4",
                 "-o", str(tmp_path / "oa")]) == 0
