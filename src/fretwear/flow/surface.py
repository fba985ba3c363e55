"""Wall-pressure correlations on the tube's surface (axial × circumferential) projected onto
the beam modes: Code_Aster's AU_YANG coherence and SPEC_CORR_CONV_3.

A wall pressure p(s, θ) on the outer surface of a tube of radius R = D/2 (s along the axis, θ
around it, measured from the local y axis) loads a beam mode r of transverse components
φ_r,y(s), φ_r,z(s) through the normal component of its displacement,
w_r(s, θ) = φ_r,y(s) cos θ + φ_r,z(s) sin θ, so that the generalised force is
Q_r = −∬ p w_r R dθ ds and

.. math:: S_{Q,ij}(f) = \\iiiint S_p(s_1,θ_1,s_2,θ_2,f)\\,w_i(s_1,θ_1)\\,w_j(s_2,θ_2)
          \\,R^2\\,dθ_1\\,dθ_2\\,ds_1\\,ds_2 .

Sources (code_aster, GitHub ``ehmoussi/code_aster``): ``bibfor/algorith/coyang.F90`` (the
Au-Yang coherence, with its factor R²), ``bibfor/modelisa/accept.F90`` (its use, U_c and U_ct
from COEF_VITE_FLUI_A/O in ``sfifj.F90``), ``bibfor/modelisa/accep1.F90`` (the angle of a point
by atan2 in (−π, π], the distance |θ₁ − θ₂| on the unrolled surface), ``sfifj.F90``,
``evalis.F90`` (SPEC_CORR_CONV_3: φᵀ·S·φ over the surface's Gauss points with a user function
of the two points' coordinates and the frequency).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from fretwear.errors import InputError
from fretwear.flow.projection import check_positive, positive_frequencies
from fretwear.flow.tube import TubeFlow

#: Gauss-Legendre nodes per panel of the circumferential integral over t ∈ [0, 2π].
_NODES = 200


@functools.cache
def _legendre() -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.legendre.leggauss(_NODES)


def au_yang_coherence(axial, angular, frequency: float, *, radius: float,
                      axial_velocity: float, circumferential_velocity: float,
                      axial_length: float, circumferential_length: float) -> np.ndarray:
    """Au-Yang's coherence between two points of a cylinder's surface, with the factor R² [m²].

    Parameters
    ----------
    axial : array_like
        Axial separation |s₁ − s₂| [m].
    angular : array_like
        Angular separation |θ₁ − θ₂| [rad] on the unrolled surface.
    frequency : float
        f [Hz].
    radius : float
        R [m].
    axial_velocity, circumferential_velocity : float
        Convection velocities U_c, U_ct [m/s] (COEF_VITE_FLUI_A·U, COEF_VITE_FLUI_O·U).
    axial_length, circumferential_length : float
        Correlation lengths L, L_t [m] (LONG_COR_1, LONG_COR_2).

    Notes
    -----
    C = e^{−|Δs|/L} cos(ω|Δs|/U_c) · e^{−R|Δθ|/L_t} cos(Rω|Δθ|/U_ct) · R², ω = 2πf
    (coyang.F90; the R² is the Jacobian of R dθ at both points).

    Examples
    --------
    >>> float(au_yang_coherence(0.0, 0.0, 50.0, radius=0.01, axial_velocity=1.0,
    ...                         circumferential_velocity=1.0, axial_length=0.1,
    ...                         circumferential_length=0.01))
    0.0001
    """
    d = np.abs(np.asarray(axial, float))
    a = np.abs(np.asarray(angular, float))
    omega = 2.0 * np.pi * frequency
    along = np.exp(-d / axial_length) * np.cos(omega * d / axial_velocity)
    around = (np.exp(-radius * a / circumferential_length)
              * np.cos(radius * omega * a / circumferential_velocity))
    return along * around * radius * radius


def circumferential_factors(frequency: float, *, radius: float, circumferential_velocity: float,
                            circumferential_length: float) -> tuple[float, float]:
    """Θ_yy, Θ_zz [m²]: the circumferential part of Au-Yang's coherence seen by a beam mode.

    Θ_cc = R² ∬ e^{−R|θ₁−θ₂|/L_t} cos(Rω|θ₁−θ₂|/U_ct) n_c(θ₁) n_c(θ₂) dθ₁dθ₂ over (−π, π]²,
    n_y = cos θ, n_z = sin θ (Θ_yz = 0: the kernel is even in (θ₁, θ₂) → (−θ₁, −θ₂)).

    Notes
    -----
    With t = θ₁ − θ₂ and g(t) the angular coherence, the square reduces to
    Θ_yy/R² = ∫₀^{2π} g(t)[(2π − t) cos t − sin t] dt and Θ_zz/R² = ∫₀^{2π} g(t)[(2π − t) cos t
    + sin t] dt, evaluated by Gauss-Legendre. Limits: L_t → 0 gives Θ = 2πR·L_t (both); a fully
    correlated pressure (g = 1) gives 0 (a uniform pressure has no resultant).

    Examples
    --------
    >>> yy, zz = circumferential_factors(0.0, radius=0.01, circumferential_velocity=1.0,
    ...                                  circumferential_length=1e-5)
    >>> round(yy / (2 * np.pi * 0.01 * 1e-5), 3), round(zz / (2 * np.pi * 0.01 * 1e-5), 3)
    (1.0, 1.0)
    """
    x, wx = _legendre()
    # two panels, the first over the kernel's decay (20 L_t/R) where it is narrow
    edges = [0.0, min(2 * np.pi, 20.0 * circumferential_length / radius), 2 * np.pi]
    panels = list(zip(edges[:-1], edges[1:], strict=True))
    t = np.concatenate([a + (b - a) * (x + 1) / 2 for a, b in panels])
    w = np.concatenate([(b - a) / 2 * wx for a, b in panels])
    omega = 2.0 * np.pi * frequency
    g = (np.exp(-radius * t / circumferential_length)
         * np.cos(radius * omega * t / circumferential_velocity))
    base, odd = (2 * np.pi - t) * np.cos(t), np.sin(t)
    r2 = radius * radius
    return float(r2 * np.sum(w * g * (base - odd))), float(r2 * np.sum(w * g * (base + odd)))


def au_yang_acceptance(tube: TubeFlow, frequencies, *, axial_velocity: float,
                       circumferential_velocity: float, axial_length: float,
                       circumferential_length: float) -> np.ndarray:
    """Joint acceptance of the Au-Yang coherence on the tube's surface [m⁴], (n_f, n, n).

    J_ij(f) = Σ_c Θ_cc(f) ∬ e^{−|Δs|/L} cos(ω|Δs|/U_c) φ_i,c(s₁) φ_j,c(s₂) ds₁ds₂, the axial
    double integral a trapezoidal sum on the tube's grid, Θ from
    :func:`circumferential_factors` with R = D/2.

    Examples
    --------
    >>> s = np.linspace(0, 1, 201)
    >>> t = TubeFlow(s, np.sin(np.pi * s)[:, None, None] * [[1.0], [0.0]], 0.02)
    >>> j = au_yang_acceptance(t, [10.0], axial_velocity=1.3, circumferential_velocity=1.3,
    ...                        axial_length=0.1, circumferential_length=0.005)
    >>> bool(j[0, 0, 0] > 0)
    True
    """
    f = positive_frequencies(frequencies)
    radius = 0.5 * tube.diameter
    s, w = tube.positions, tube.weights
    distance = np.abs(s[:, None] - s[None, :])
    out = np.empty((f.size, tube.n_modes, tube.n_modes))
    for k, fk in enumerate(f):
        omega = 2.0 * np.pi * fk
        kernel = np.exp(-distance / axial_length) * np.cos(omega * distance / axial_velocity)
        theta = circumferential_factors(fk, radius=radius,
                                        circumferential_velocity=circumferential_velocity,
                                        circumferential_length=circumferential_length)
        parts = [tube.shapes[:, c, :] * w[:, None] for c in (0, 1)]
        j = sum(th * (a.T @ kernel @ a) for th, a in zip(theta, parts, strict=True))
        out[k] = 0.5 * (j + j.T)
    return out


def surface_points(tube: TubeFlow, circumferential_points: int):
    """Quadrature points of the tube's surface: s [m], θ [rad] in (−π, π), weights [m²] and the
    normal displacements w_r [-] there, shape (n_points, n_modes)."""
    n = int(circumferential_points)
    if n < 4:
        raise InputError(f"surface quadrature: circumferential_points must be ≥ 4, got {n}")
    theta = -np.pi + (np.arange(n) + 0.5) * 2.0 * np.pi / n      # midpoints (periodic rule)
    radius = 0.5 * tube.diameter
    s = np.repeat(tube.positions, n)
    th = np.tile(theta, tube.positions.size)
    weight = np.repeat(tube.weights, n) * radius * 2.0 * np.pi / n
    normal = (np.repeat(tube.shapes[:, 0, :], n, axis=0) * np.cos(th)[:, None]
              + np.repeat(tube.shapes[:, 1, :], n, axis=0) * np.sin(th)[:, None])
    return s, th, weight, normal


def resampled(tube: TubeFlow, points: int) -> TubeFlow:
    """The tube on ``points`` equally spaced abscissae over the same span, every profile and
    mode shape interpolated linearly.

    Examples
    --------
    >>> t = TubeFlow(np.linspace(0, 1, 11), np.ones((11, 2, 1)), 0.02)
    >>> resampled(t, 5).positions.tolist()
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """
    n = int(points)
    if n < 2:
        raise InputError(f"surface quadrature: axial_points must be ≥ 2, got {points!r}")
    s0 = tube.positions
    s = np.linspace(s0[0], s0[-1], n)
    flat = tube.shapes.reshape(s0.size, -1)
    shapes = np.column_stack([np.interp(s, s0, col) for col in flat.T])
    return TubeFlow(s, shapes.reshape(n, *tube.shapes.shape[1:]), tube.diameter,
                    np.interp(s, s0, tube.velocity), np.interp(s, s0, tube.density),
                    np.interp(s, s0, tube.void_fraction), dict(tube.metadata))


@dataclass(frozen=True)
class SpecCorrConv3:
    """SPEC_CORR_CONV_3: a user cross-spectral density of the wall pressure between two points
    of the tube's surface, projected onto the beam modes.

    Parameters
    ----------
    function : callable
        ``function(s1, theta1, s2, theta2, f)`` → S_p [Pa²/Hz] (any unit u: the result is
        u·m⁴), vectorised over arrays of abscissae s [m] and angles θ [rad] in (−π, π)
        measured from the local y axis; one frequency f [Hz]. It must be Hermitian,
        S(p, q) = S(q, p)*, and a valid cross-spectral density (positive semi-definite).
    circumferential_points : int
        Points around the circumference (midpoint rule), default 16.
    axial_points : int, optional
        Points along the tube (trapezoidal rule), the mode shapes interpolated linearly onto
        them; default: the tube's grid. The cost grows as (axial × circumferential points)².

    Notes
    -----
    S_Q,ij = Σ_p Σ_q w_i(p) S(p, q, f) w_j(q) a_p a_q over the surface points p, q with areas a
    (evalis.F90: φᵀ·S·φ over the Gauss points). Code_Aster reads the function from a table on an
    interface mesh (TABLE_FONCTION, parameters X1, Y1, Z1, X2, Y2, Z2, FREQ); fretwear takes a
    function of the cylinder's coordinates instead.

    Examples
    --------
    >>> s = np.linspace(0, 1, 21)
    >>> t = TubeFlow(s, np.sin(np.pi * s)[:, None, None] * [[1.0], [0.0]], 0.02)
    >>> spec = SpecCorrConv3(function=lambda s1, t1, s2, t2, f: np.exp(-abs(s1 - s2) / 0.1)
    ...                      * np.exp(-0.01 * abs(t1 - t2) / 0.002))
    >>> spec.modal_spectrum([10.0], t).shape
    (1, 1, 1)
    """

    name: ClassVar[str] = "SPEC_CORR_CONV_3"
    function: Callable | None = None
    circumferential_points: int = 16
    axial_points: int | None = None

    def modal_spectrum(self, frequencies, tube: TubeFlow) -> np.ndarray:
        """S_ij(f) [u·m⁴], shape (n_f, n_modes, n_modes)."""
        if not callable(self.function):
            raise InputError("SPEC_CORR_CONV_3: give 'function', the cross-spectral density "
                             "function(s1, theta1, s2, theta2, f)")
        f = positive_frequencies(frequencies)
        if self.axial_points is not None:
            tube = resampled(tube, self.axial_points)
        s, th, weight, normal = surface_points(tube, self.circumferential_points)
        a = normal * weight[:, None]
        out = np.empty((f.size, tube.n_modes, tube.n_modes), dtype=complex)
        for k, fk in enumerate(f):
            kernel = np.asarray(self.function(s[:, None], th[:, None], s[None, :], th[None, :],
                                              fk))
            if kernel.shape != (s.size, s.size) or not np.all(np.isfinite(kernel)):
                raise InputError(f"SPEC_CORR_CONV_3: 'function' must return finite values of "
                                 f"shape {(s.size, s.size)} for arrays of points, got "
                                 f"{kernel.shape} at f = {fk} Hz")
            j = a.T @ kernel @ a
            out[k] = 0.5 * (j + j.conj().T)
        return out.real.copy() if np.all(out.imag == 0) else out


def au_yang_parameters(owner: str, velocity: float, coef_a, coef_o, long_1, long_2) -> dict:
    """The keyword arguments of :func:`au_yang_acceptance` from Code_Aster's keywords, checked:
    U_c = COEF_VITE_FLUI_A·U, U_ct = COEF_VITE_FLUI_O·U (sfifj), L = LONG_COR_1, L_t =
    LONG_COR_2 [m]."""
    given = {"coef_vite_flui_a": coef_a, "coef_vite_flui_o": coef_o, "long_cor_1": long_1,
             "long_cor_2": long_2}
    missing = [k for k, v in given.items()
               if v is None or (isinstance(v, float) and math.isnan(v))]
    if missing:
        raise InputError(f"{owner}: METHODE='AU_YANG' needs {missing} (the Au-Yang coherence's "
                         "convection-velocity factors [-] and correlation lengths [m])")
    check_positive(owner, coef_vite_flui_a=coef_a, coef_vite_flui_o=coef_o,
                   long_cor_1=long_1, long_cor_2=long_2)
    return {"axial_velocity": coef_a * abs(velocity),
            "circumferential_velocity": coef_o * abs(velocity),
            "axial_length": long_1, "circumferential_length": long_2}


def generale_surface_coherence(s1, theta1, s2, theta2, frequency: float, *, radius: float,
                               velocity: float, length: float) -> np.ndarray:
    """GENERALE's coherence between two points of the tube's surface [-] (coegen, accept).

    Parameters
    ----------
    s1, theta1, s2, theta2 : array_like
        The points' abscissae s [m] and angles θ [rad] (broadcast together).
    frequency : float
        f [Hz].
    radius : float
        R [m].
    velocity : float
        Flow velocity U [m/s]; the convection velocity is U_c = 0.65 U (accept.F90).
    length : float
        L [m] (LONG_COR_1).

    Notes
    -----
    C = e^{−d/L} cos(ωd/U_c) with d the distance in space between the two points,
    d² = (s₁ − s₂)² + (2R sin((θ₁ − θ₂)/2))² (coegen's √(Δx² + Δy² + Δz²) between the
    interface's Gauss points).

    Examples
    --------
    >>> float(generale_surface_coherence(0.0, 0.0, 0.0, np.pi, 0.0, radius=0.01, velocity=1.0,
    ...                                  length=0.02))   # across the diameter: e^{-0.02/0.02}
    0.36787944117144233
    """
    chord = 2.0 * radius * np.sin(0.5 * (np.asarray(theta1) - np.asarray(theta2)))
    d = np.sqrt((np.asarray(s1) - np.asarray(s2)) ** 2 + chord**2)
    return np.exp(-d / length) * np.cos(2.0 * np.pi * frequency * d / (0.65 * velocity))


def generale_surface_acceptance(tube: TubeFlow, frequencies, *, velocity: float, length: float,
                                circumferential_points: int, axial_points: int | None = None
                                ) -> np.ndarray:
    """Σ_p Σ_q w_i(p) C(p, q, f) w_j(q) a_p a_q [m⁴] with GENERALE's surface coherence
    (:func:`generale_surface_coherence`), shape (n_f, n_modes, n_modes): the modal matrix per
    unit wall-pressure spectrum, as Code_Aster's accept integrates it over the interface.
    Points as :class:`SpecCorrConv3` (``circumferential_points`` midpoints around,
    ``axial_points`` or the tube's grid along)."""
    radius = 0.5 * tube.diameter

    def kernel(s1, t1, s2, t2, f):
        return generale_surface_coherence(s1, t1, s2, t2, f, radius=radius, velocity=velocity,
                                          length=length)

    return SpecCorrConv3(function=kernel, circumferential_points=circumferential_points,
                         axial_points=axial_points).modal_spectrum(frequencies, tube)
