"""``fretwear simulate`` forces a tube in both transverse planes, y and z.

Sources: the projection Σ_c over the transverse directions c ∈ {y, z} of Code_Aster's
PROJ_SPEC_BASE with TOUT_CMP='OUI' (spect1 §6.2.3: each direction excited independently by the
same spectrum), so the y-plane and z-plane modes of a straight tube get equal autospectra and
no cross-spectrum between the planes; the Welch estimator's relative standard error 1/√K over K
independent segments (Bendat & Piersol, *Random Data*, 4th ed., §8.5.4) and, for the
cross-spectrum of two independent signals, E|Ŝ_yz|² = S_yy S_zz / K (ibid. §9.1.3).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy import signal

from fretwear.flow.bundle import modal_loads, tube_forces
from fretwear.flow.description import read_description

from .test_simulate import small_description


@pytest.fixture(scope="module")
def pipeline(tmp_path_factory):
    """The example's row-2 tube (3.5 m/s) as ``fretwear simulate`` builds it, with a 60 s
    record (the example simulates 0.4 s: too short for a spectral estimate)."""
    spec = read_description(small_description(tmp_path_factory.mktemp("d")))[1]
    spec = dataclasses.replace(spec, duration=60.0)
    model, tube, t, forces = tube_forces(spec)
    return spec, model, tube, t, forces


def test_the_target_has_both_planes_equal_and_uncoupled(pipeline):
    spec, model, tube, _, _ = pipeline
    n = model.n_modes // 2
    assert np.all(tube.shapes[:, 1, :n] == 0) and np.all(tube.shapes[:, 0, n:] == 0)
    f = np.linspace(*spec.band_hz, 50)
    from fretwear.flow.spectra import make_spectrum
    params = {k: v for k, v in spec.spectrum.items() if k != "name"}
    s = make_spectrum(spec.spectrum["name"], **params).modal_spectrum(f, tube)
    assert np.all(s[:, :n, n:] == 0)  # Σ_c φ_i,c φ_j,c = 0 for i in y, j in z
    np.testing.assert_allclose(s[:, n:, n:], s[:, :n, :n], rtol=1e-12)  # same spectrum
    assert np.all(np.diagonal(s, axis1=1, axis2=2).real > 0)


def test_y_and_z_modal_forces_match_their_target_and_are_uncorrelated(pipeline):
    spec, model, tube, t, forces = pipeline
    n = model.n_modes // 2
    fs = 1.0 / (t[1] - t[0])
    nper = int(round(fs / 2.0))  # 2 s segments (0.5 Hz), K = 30 without overlap
    k = (forces.shape[0] - 1) // nper
    f = np.linspace(*spec.band_hz, spec.frequency_points)
    from fretwear.flow.spectra import make_spectrum
    params = {key: v for key, v in spec.spectrum.items() if key != "name"}
    target = make_spectrum(spec.spectrum["name"], **params).modal_spectrum(f, tube)
    opts = {"fs": fs, "nperseg": nper, "noverlap": 0, "window": "hann"}  # low leakage: the
    # spectrum falls steeply with f; segments do not overlap, so K stays independent
    fw, py = signal.welch(forces[:-1, 0], **opts)
    _, pz = signal.welch(forces[:-1, n], **opts)
    _, pyz = signal.csd(forces[:-1, n], forces[:-1, 0], **opts)
    band = (fw > spec.band_hz[0] + 2) & (fw < spec.band_hz[1] - 2)
    tol = 5.0 / np.sqrt(k * band.sum())  # 5 standard errors of the band's mean ratio
    for got, c in ((py, 0), (pz, n)):
        want = np.interp(fw[band], f, target[:, c, c].real)
        assert np.mean(got[band] / want) == pytest.approx(1.0, abs=tol)
    # the normalised cross-spectrum of independent signals: each bin's modulus² has mean 1/K,
    # the band's mean of the complex ratio has standard error 1/√(K n)
    coherent = pyz[band] / np.sqrt(py[band] * pz[band])
    assert abs(np.mean(coherent)) < tol
    assert np.mean(np.abs(coherent) ** 2) == pytest.approx(1.0 / k, rel=5.0 / np.sqrt(
        band.sum()))


def test_each_mode_is_loaded_along_its_own_plane(pipeline):
    """The driven model's generalised force on mode r is Q_r alone, along y for the first n
    modes (bending in y) and along z for the next n."""
    _, model, tube, t, forces = pipeline
    n = model.n_modes // 2
    driven, loads = modal_loads(model, tube, t, forces)
    assert [ld.direction for ld in loads] == ["y"] * n + ["z"] * n
    for r, ld in enumerate(loads):
        i = driven.forcing_index(ld.point)
        row = driven.forcing_shapes[i, "yz".index(ld.direction), :]
        np.testing.assert_array_equal(row, np.eye(2 * n)[r])
        np.testing.assert_array_equal(ld.signal.values, forces[:, r])
