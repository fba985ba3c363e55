"""Calibration on inspections (fretwear.uncertainty.calibration) against closed forms.

Conjugate case (docs/uncertainty.md §4): Archard from a new tube, TUBE_BAV without tilt, so
ln d = ln c + (2/3)·ln(K·P·t) + (2/3)·λ, λ = ln f, with c = (1/(2R))^(1/3)·(3/(4l))^(2/3). With
the prior λ ~ N(μ₀, τ₀²) and ln y_i ~ N(ln d_i, σ_i²) the posterior is normal with
1/τ² = 1/τ₀² + Σ (2/3)²/σ_i², μ = τ²·(μ₀/τ₀² + Σ (2/3)(ln y_i − a_i)/σ_i²) (Gelman et al.,
Bayesian Data Analysis, §2.5). The grid quadrature is checked against it, and on a tilted
contact against scipy.integrate.quad of a likelihood computed through wear_table.
"""

import math
import warnings

import numpy as np
import pandas as pd
import pytest
from scipy import integrate, stats

from fretwear.errors import InputError
from fretwear.table import wear_table
from fretwear.uncertainty import GridPosterior, LogNormal, calibrate, read_inspections

R, W = 9.525e-3, 12.7e-3
K0 = 9.2e-15
YEAR = 3.15576e7
C = (1 / (2 * R)) ** (1 / 3) * (3 / (4 * W)) ** (2 / 3)
POWERS = {"R12C40": 0.01, "R30C7": 0.004}


def _table(power, **extra):
    kw = {"contact_type": "TUBE_BAV", "instants": [0.0, 10.0, 20.0], "time_scale": YEAR,
          "dimensions": {"mobile_radius": R, "obstacle_width": W},
          "coefficients": {"coefficient": K0}, "wall_thickness": 1.09e-3}
    kw.update(extra)
    return wear_table(power, **kw)  # the wall is the case's (attrs hold no state, issue 25)


INSPECTIONS = pd.DataFrame({
    "contact": ["R12C40", "R12C40", "R30C7"],
    "instant": [6.0, 12.0, 12.0],
    "depth_mm": [0.55, 0.80, 0.30],
    "measurement_sigma": [0.15, 0.1, np.nan],
})


def _closed_form(prior_median, prior_sigma, sigma_default=0.2):
    mu0, tau0 = math.log(prior_median), prior_sigma
    prec = 1 / tau0 ** 2
    num = mu0 / tau0 ** 2
    for _, row in INSPECTIONS.iterrows():
        a = math.log(C * (K0 * POWERS[row["contact"]] * row["instant"] * YEAR) ** (2 / 3))
        s = row["measurement_sigma"] if np.isfinite(row["measurement_sigma"]) else sigma_default
        y = math.log(row["depth_mm"] * 1e-3)
        prec += (2 / 3) ** 2 / s ** 2
        num += (2 / 3) * (y - a) / s ** 2
    return num / prec, math.sqrt(1 / prec)


@pytest.fixture(scope="module")
def predictions():
    return {name: _table(p) for name, p in POWERS.items()}


def test_conjugate_posterior_matches_closed_form(predictions):
    prior = LogNormal(1.0, sigma_ln=0.6)
    r = calibrate(predictions, INSPECTIONS, prior=prior, measurement_sigma=0.2)
    mean, sd = _closed_form(1.0, 0.6)
    assert r.method == "conjugate"
    assert isinstance(r.posterior, LogNormal)
    assert math.log(r.factor_median) == pytest.approx(mean, rel=1e-10, abs=1e-12)
    assert r.posterior.sigma_ln == pytest.approx(sd, rel=1e-10)
    obs = r.observations
    assert obs["depth"].tolist() == pytest.approx([0.55e-3, 0.80e-3, 0.30e-3])
    assert obs["measurement_sigma"].tolist() == [0.15, 0.1, 0.2]
    expected = C * (K0 * 0.01 * 6 * YEAR * math.exp(mean)) ** (2 / 3)
    assert obs["posterior_depth"].iloc[0] == pytest.approx(expected, rel=1e-10)


def test_grid_quadrature_agrees_with_conjugate(predictions):
    prior = LogNormal(1.0, sigma_ln=0.6)
    conj = calibrate(predictions, INSPECTIONS, prior=prior, measurement_sigma=0.2)
    grid = calibrate(predictions, INSPECTIONS, prior=prior, measurement_sigma=0.2,
                     method="grid")
    assert isinstance(grid.posterior, GridPosterior) and grid.method == "grid"
    assert grid.posterior.mean_ln == pytest.approx(math.log(conj.factor_median), abs=1e-7)
    assert grid.posterior.sigma_ln == pytest.approx(conj.posterior.sigma_ln, rel=1e-5)
    for u in (0.025, 0.5, 0.975):
        assert float(grid.posterior.ppf(u)) == pytest.approx(float(conj.posterior.ppf(u)),
                                                             rel=1e-5)


def test_forecast_quantiles_and_exceedance_in_closed_form(predictions):
    prior = LogNormal(1.0, sigma_ln=0.6)
    r = calibrate(predictions, INSPECTIONS, prior=prior, measurement_sigma=0.2, forecast=30.0)
    mean, sd = _closed_form(1.0, 0.6)
    limit = 0.4 * 1.09e-3
    fc = r.predictive.set_index("contact")
    for name, p in POWERS.items():
        row = fc.loc[name]
        for q in (0.05, 0.5, 0.95):
            f_q = math.exp(mean + sd * stats.norm.ppf(q))
            assert row[f"depth_q{100 * q:g}"] == pytest.approx(
                C * (K0 * f_q * p * 30 * YEAR) ** (2 / 3), rel=1e-10)
        f_limit = (limit / C) ** 1.5 / (K0 * p * 30 * YEAR)
        assert row["limit"] == pytest.approx(limit)
        assert row["exceedance"] == pytest.approx(
            1 - stats.norm.cdf((math.log(f_limit) - mean) / sd), abs=1e-9)
        assert row["exceedance_prior"] == pytest.approx(
            1 - stats.norm.cdf(math.log(f_limit) / 0.6), abs=1e-9)


def test_small_exceedance_probabilities_are_exact_not_rounded_to_zero(predictions):
    """Far from the limit the probability is tiny but still ranks the contacts: it is the
    normal survival function of the closed form (1 − cdf would round it to 0 below 1e-16), for
    the conjugate posterior and the prior; the grid posterior holds no mass there."""
    prior = LogNormal(1.0, sigma_ln=0.6)
    mean, sd = _closed_form(1.0, 0.6)
    limit = 0.4 * 1.09e-3
    r = calibrate(predictions, INSPECTIONS, prior=prior, measurement_sigma=0.2, forecast=1.0)
    grid = calibrate(predictions, INSPECTIONS, prior=prior, measurement_sigma=0.2,
                     forecast=1.0, method="grid")
    fc, fg = r.predictive.set_index("contact"), grid.predictive.set_index("contact")
    for name, p in POWERS.items():
        ln_f_limit = math.log((limit / C) ** 1.5 / (K0 * p * 1 * YEAR))
        exact = stats.norm.sf((ln_f_limit - mean) / sd)
        assert 0 < exact < 1e-16
        assert fc.loc[name, "exceedance"] == pytest.approx(exact, rel=1e-8, abs=0)
        assert fc.loc[name, "exceedance_prior"] == pytest.approx(
            stats.norm.sf(ln_f_limit / 0.6), rel=1e-8, abs=0)
        assert 0 <= fg.loc[name, "exceedance"] < 1e-12  # the grid holds the posterior's mass
    assert fc.loc["R12C40", "exceedance"] > fc.loc["R30C7", "exceedance"]  # more power


def test_tilted_contact_uses_the_grid_and_matches_quadrature():
    """TUBE_BAV tilted 1°, depths past l·θ: not a power law of f. The posterior mean of λ is
    checked against scipy.integrate.quad, the likelihood computed by wear_table with K·f."""
    extra = {"dimensions": {"mobile_radius": R, "obstacle_width": W, "tilt_angle": 1.0}}
    table = _table(0.01, **extra)
    insp = pd.DataFrame({"instant": [8.0, 16.0], "depth": [0.45e-3, 0.62e-3]})
    prior = LogNormal(1.0, sigma_ln=0.5)
    r = calibrate(table, insp, prior=prior, measurement_sigma=0.1)
    assert r.method == "grid"
    with pytest.raises(InputError, match="power law"):
        calibrate(table, insp, prior=prior, measurement_sigma=0.1, method="conjugate")

    def post(lam):
        t = wear_table(0.01, **{**{"contact_type": "TUBE_BAV", "instants": [8.0, 16.0],
                                   "time_scale": YEAR, "coefficients": {
                                       "coefficient": K0 * math.exp(lam)}}, **extra})
        d = t["depth_mobile"].to_numpy()
        ll = -0.5 * np.sum(((np.log(insp["depth"]) - np.log(d)) / 0.1) ** 2)
        return math.exp(ll - 0.5 * (lam / 0.5) ** 2)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        z = integrate.quad(post, -3, 3, points=[0.0, 1.0], limit=200)[0]
        m = integrate.quad(lambda x: x * post(x), -3, 3, points=[0.0, 1.0], limit=200)[0] / z
    assert r.posterior.mean_ln == pytest.approx(m, abs=1e-6)


def test_sector_inspections_and_unknown_rows():
    from fretwear.history import ContactHistory

    t = np.linspace(0, 2, 2001)
    angle = np.radians(150 * np.sin(3 * t))
    h = ContactHistory(time=t, normal_force=np.full(t.size, 2.0), vt1=np.full(t.size, 0.1),
                       vt2=np.zeros(t.size), dy=np.cos(angle), dz=np.sin(angle))
    table = wear_table(h, contact_type="TUBE_BAV", instants=[10.0], time_scale=YEAR,
                       dimensions={"mobile_radius": R, "obstacle_width": W}, sectors=4,
                       coefficients={"coefficient": K0})
    insp = pd.DataFrame({"sector": [2], "instant": [10.0], "depth": [2e-5]})
    r = calibrate(table, insp, prior=LogNormal(1.0, sigma_ln=0.5), forecast=20.0)
    # sector depth d = R − √(R² − 2V/(lΔθ)): not a power law, grid
    assert r.method == "grid"
    assert set(r.predictive["sector"].dropna()) == {1, 2, 3, 4}
    with pytest.raises(InputError, match="no sector 9"):
        calibrate(table, insp.assign(sector=[9]))
    with pytest.raises(InputError, match="unknown contact 'X'"):
        calibrate({"A": table, "B": table}, insp.assign(contact=["X"]))


def test_read_inspections_errors(tmp_path):
    path = tmp_path / "insp.csv"
    path.write_text("contact,instant,depth_mm\nA,10,0.3\nA,12,-1\n")
    # the user's column and value, not the converted metres' numpy repr
    with pytest.raises(InputError, match=r"row 2: depth_mm must be a finite number > 0 \[mm\], "
                                         r"got '-1(\.0)?'"):
        read_inspections(path)
    path.write_text("contact,instant,depth\nA,ten,3e-4\n")
    with pytest.raises(InputError, match=r"row 1: instant must be a finite number, got 'ten'"):
        read_inspections(path)
    path.write_text("contact,instant,depth_um\nA,10,0.3\n")
    with pytest.raises(InputError, match="unknown column"):
        read_inspections(path)
    path.write_text("contact,depth\nA,0.3\n")
    with pytest.raises(InputError, match="'instant' is missing"):
        read_inspections(path)
    path.write_text("# eddy-current campaign 2024\ncontact, instant, depth_mm\nA, 10, 0.3\n")
    assert read_inspections(path)["depth"].tolist() == [pytest.approx(3e-4)]
