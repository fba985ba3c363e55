"""Joint acceptances: a spatial correlation projected onto the modes (PROJ_SPEC_BASE).

A turbulent load per unit length with cross-spectral density S(f)·C(s₁, s₂, f)·g(s₁)·g(s₂) gives
the generalised forces Q_r = ∫ φ_r·f ds the cross-spectral matrix

.. math:: S_{Q,ij}(f) = S(f)\\sum_{c\\in\\{y,z\\}}\\iint C(s_1,s_2,f)\\,g(s_1)\\varphi_{i,c}(s_1)
          \\,g(s_2)\\varphi_{j,c}(s_2)\\,ds_1\\,ds_2 ,

each transverse direction excited independently by the same spectrum (Code_Aster's
``TOUT_CMP='OUI'``, spect1 §5.4). The integrals are trapezoidal sums on the tube's grid.
"""

from __future__ import annotations

import numpy as np

from fretwear.errors import InputError
from fretwear.flow.tube import TubeFlow


def positive_frequencies(frequencies) -> np.ndarray:
    """Frequencies [Hz] as a 1-D array, refused unless finite and > 0."""
    f = np.asarray(frequencies, float).reshape(-1)
    if f.size == 0 or np.any(f <= 0) or not np.all(np.isfinite(f)):
        raise InputError("turbulence spectrum: frequencies [Hz] must be finite and > 0 (the "
                         "reduced spectra of SPEC_LONG_COR_3 and _4 diverge at f = 0)")
    return f


def check_positive(owner: str, **values: float) -> None:
    """Refuse any of ``values`` that is not a finite number > 0, naming it."""
    for key, value in values.items():
        if value is None or not (np.isfinite(value) and value > 0):
            raise InputError(f"{owner}: {key!r} must be a finite value > 0, got {value!r}")


def _weighted_shapes(tube: TubeFlow, weight: np.ndarray, directions) -> list[np.ndarray]:
    w = tube.weights * weight
    return [tube.shapes[:, d, :] * w[:, None] for d in directions]


def _directions(directions) -> tuple[int, ...]:
    index = {"y": 0, "z": 1}
    try:
        return tuple(index[d] for d in directions)
    except KeyError:
        raise InputError(f"joint acceptance: directions must be among 'y' and 'z', got "
                         f"{list(directions)!r}") from None


def exponential_acceptance(tube: TubeFlow, correlation_length: float, weight=None,
                           directions=("y", "z")) -> np.ndarray:
    """Joint acceptance of an exponential correlation, J_ij = Σ_c ∬ e^{−|s₁−s₂|/λ} g φ_i g φ_j.

    Parameters
    ----------
    tube : TubeFlow
        Shapes on the grid.
    correlation_length : float
        λ [m], > 0 (``math.inf``: full correlation, J_ij = Σ_c (∫gφ_i)(∫gφ_j)).
    weight : array_like, optional
        g(s) on the grid [any unit u], default 1.
    directions : sequence of {"y", "z"}
        The transverse directions excited (each independently).

    Returns
    -------
    ndarray, shape (n_modes, n_modes)
        J [u²·m²], symmetric positive semi-definite.

    Notes
    -----
    The limits: λ → 0 gives J_ij → 2λ Σ_c ∫ g² φ_i φ_j ds (the kernel integrates to 2λ);
    λ → ∞ gives the product of the single integrals. Trapezoidal sums need a grid spacing well
    below λ (4 points per λ give about 1 %).

    Examples
    --------
    >>> s = np.linspace(0, 1, 2001)
    >>> t = TubeFlow(s, np.sin(np.pi * s)[:, None, None] * [[1.0], [0.0]], 0.02)
    >>> round(float(exponential_acceptance(t, np.inf)[0, 0]), 5)   # (2/π)²
    0.40528
    """
    if not correlation_length > 0:
        raise InputError(f"joint acceptance: the correlation length must be > 0 [m], got "
                         f"{correlation_length!r}")
    g = np.ones(tube.positions.size) if weight is None else np.asarray(weight, float)
    parts = _weighted_shapes(tube, g, _directions(directions))
    if np.isinf(correlation_length):
        return sum(np.outer(a.sum(axis=0), a.sum(axis=0)) for a in parts)
    s = tube.positions
    kernel = np.exp(-np.abs(s[:, None] - s[None, :]) / correlation_length)
    out = sum(a.T @ kernel @ a for a in parts)
    return 0.5 * (out + out.T)  # symmetric to the last bit (the sum's rounding is not)


def convected_acceptance(tube: TubeFlow, frequencies, coherence, weight=None,
                         directions=("y", "z")) -> np.ndarray:
    """Joint acceptance of a frequency-dependent coherence C(Δs, f) along the tube.

    Parameters
    ----------
    tube : TubeFlow
        Shapes on the grid.
    frequencies : array_like, shape (n_f,)
        f [Hz].
    coherence : callable
        ``coherence(distance, frequency)`` → C [-], with the signed distance s₁ − s₂ [m]
        (an array) and one frequency [Hz].
    weight : array_like, optional
        g(s) [u], default 1.
    directions : sequence of {"y", "z"}
        The transverse directions excited.

    Returns
    -------
    ndarray, shape (n_f, n_modes, n_modes)
        J(f) [u²·m²].

    Examples
    --------
    >>> s = np.linspace(0, 1, 401)
    >>> t = TubeFlow(s, np.sin(np.pi * s)[:, None, None] * [[1.0], [0.0]], 0.02)
    >>> j = convected_acceptance(t, [1.0], lambda d, f: np.ones_like(d))
    >>> round(float(j[0, 0, 0]), 4)
    0.4053
    """
    f = np.asarray(frequencies, float).reshape(-1)
    g = np.ones(tube.positions.size) if weight is None else np.asarray(weight, float)
    parts = _weighted_shapes(tube, g, _directions(directions))
    s = tube.positions
    distance = s[:, None] - s[None, :]
    out = np.empty((f.size, tube.n_modes, tube.n_modes))
    for k, fk in enumerate(f):
        kernel = coherence(distance, fk)
        j = sum(a.T @ kernel @ a for a in parts)
        out[k] = 0.5 * (j + j.T)
    return out
