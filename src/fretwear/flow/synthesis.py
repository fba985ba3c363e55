"""Correlated time signals from a cross-spectral matrix (Code_Aster's GENE_FONC_ALEA).

:func:`synthesize` draws seeded, stationary, jointly Gaussian signals whose one-sided
cross-spectral matrix is a given S(f), by the spectral-representation method: at each frequency
f_k = k/T of the record, S(f_k) = L Lᴴ (Cholesky; an eigen-decomposition when S is only
semi-definite, e.g. fully correlated forces), and

.. math:: x_j(t) = \\mathrm{Re}\\sum_k \\sum_m L_{jm}(f_k)\\sqrt{2\\Delta f}\\,
          e^{i(2\\pi f_k t + \\theta_{mk})},

with independent phases θ uniform on [0, 2π) and Δf = 1/T, summed by an inverse FFT. Over its
period T each record has the mean products Σ_k Re S_jl(f_k) Δf exactly.
"""

from __future__ import annotations

import numpy as np

from fretwear.dynamics.excitation import spectral_grid
from fretwear.errors import InputError


def _factor(matrix: np.ndarray) -> np.ndarray:
    """L with L Lᴴ = S for a Hermitian positive semi-definite S (n, n)."""
    try:
        return np.linalg.cholesky(matrix)
    except np.linalg.LinAlgError:
        w, v = np.linalg.eigh(matrix)
        scale = max(float(np.max(np.abs(w))), 1e-300)
        if np.min(w) < -1e-8 * scale:
            raise InputError("spectral matrix: not positive semi-definite at some frequency "
                             f"(eigenvalue {np.min(w):.3g} for a largest {scale:.3g}), so no "
                             "real signals have it (GRAPPE_1's measured matrix is such a case: "
                             "docs/flow.md)") from None
        return v * np.sqrt(np.clip(w, 0.0, None))[None, :]


def factor_matrices(matrices: np.ndarray) -> np.ndarray:
    """Per-frequency factors L(f) of a stack of spectral matrices (n_f, n, n) (same shape).

    Examples
    --------
    >>> s = np.array([[[4.0, 2.0], [2.0, 1.0]]])        # rank one: no Cholesky
    >>> l = factor_matrices(s)
    >>> np.allclose(l[0] @ l[0].conj().T, s[0])
    True
    """
    m = np.asarray(matrices)
    try:  # one batched call when every matrix is positive definite
        return np.linalg.cholesky(m)
    except np.linalg.LinAlgError:
        return np.stack([_factor(m[k]) for k in range(m.shape[0])])


def synthesize(frequencies, matrices, *, duration: float, seed: int,
               sample_rate: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Seeded correlated signals with the one-sided cross-spectral matrix S(f).

    Parameters
    ----------
    frequencies : array_like, shape (n_f,)
        Frequencies of the table [Hz], increasing, >= 0.
    matrices : array_like, shape (n_f, n, n)
        One-sided cross-spectral matrices S_jl(f) = E[X_j X_l*]-type densities [unit²/Hz],
        Hermitian positive semi-definite; linear between the table's frequencies, 0 outside.
    duration : float
        Record length T [s] (the record is periodic with this period).
    seed : int
        Seed of :func:`numpy.random.default_rng`: the same seed gives the same record.
    sample_rate : float, optional
        Samples per second [Hz], default 8 × the table's highest frequency.

    Returns
    -------
    time : ndarray, shape (N + 1,)
        [s], from 0 to T inclusive (the period's end repeats the first sample).
    values : ndarray, shape (N + 1, n)
        [unit].

    Notes
    -----
    Shinozuka & Deodatis' multivariate spectral representation (with a Cholesky factor per
    frequency, as GENE_FONC_ALEA). The mean and the Nyquist bins carry no power. Convention:
    S_jl = lim E[X_j X_l*]/T, so ``scipy.signal.csd(x_l, x_j)`` estimates S_jl.

    References
    ----------
    .. [1] Shinozuka, M., & Deodatis, G. (1991). Simulation of stochastic processes by spectral
           representation. *Applied Mechanics Reviews* 44(4), 191-204.
    .. [2] Code_Aster, GENE_FONC_ALEA (``code_aster/Cata/Commands/gene_fonc_alea.py``, op 118:
           ``bibfor/op/op0118.F90``).

    Examples
    --------
    >>> t, x = synthesize([10.0, 50.0], np.ones((2, 1, 1)), duration=10.0, seed=1)
    >>> round(float(np.mean(x[:-1, 0] ** 2)), 6)   # Σ S Δf over 10 <= f <= 50, Δf = 0.1 Hz
    40.1
    """
    f = np.asarray(frequencies, float).reshape(-1)
    s = np.asarray(matrices)
    if s.ndim != 3 or s.shape[0] != f.size or s.shape[1] != s.shape[2] or f.size < 2:
        raise InputError(f"synthesis: 'matrices' must have shape (n_f, n, n) with n_f = {f.size} "
                         f"frequencies (at least two), got {s.shape}")
    if np.any(np.diff(f) <= 0) or f[0] < 0 or not np.all(np.isfinite(f)):
        raise InputError("synthesis: frequencies [Hz] must be >= 0 and strictly increasing")
    if not np.all(np.isfinite(s)):
        raise InputError("synthesis: the spectral matrices hold a non-finite value")
    if not np.allclose(s, np.conj(np.swapaxes(s, 1, 2)), rtol=1e-10,
                       atol=1e-14 * float(np.max(np.abs(s)) or 1.0)):
        raise InputError("synthesis: the spectral matrices must be Hermitian (S_jl = conj S_lj)")
    n_t, df, fk = spectral_grid(f[-1], duration, sample_rate, "synthesis")
    inside = (fk > 0) & (fk >= f[0]) & (fk <= f[-1]) & (np.arange(fk.size) < n_t // 2)
    n = s.shape[1]
    # linear interpolation of every entry at once (a convex combination of two Hermitian
    # positive semi-definite matrices is one)
    fin = fk[inside]
    lo = np.clip(np.searchsorted(f, fin, side="right") - 1, 0, f.size - 2)
    w = ((fin - f[lo]) / (f[lo + 1] - f[lo]))[:, None, None]
    factors = np.zeros((fk.size, n, n), dtype=complex)
    factors[inside] = factor_matrices((1.0 - w) * s[lo] + w * s[lo + 1])
    rng = np.random.default_rng(seed)
    phases = np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, (fk.size, n)))
    spectrum = 0.5 * n_t * np.sqrt(2.0 * df) * (factors @ phases[:, :, None])[:, :, 0]
    x = np.fft.irfft(spectrum, n_t, axis=0)
    t = np.arange(n_t + 1) * (duration / n_t)
    return t, np.vstack([x, x[:1]])
