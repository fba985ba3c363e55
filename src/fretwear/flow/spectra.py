"""Turbulence excitation spectra of Code_Aster's DEFI_SPEC_TURB, projected onto the modes.

Every family is a frozen dataclass registered in :data:`SPECTRA` under its Code_Aster keyword,
with the catalogue's defaults (``code_aster/Cata/Commands/defi_spec_turb.py``) and one method,
``modal_spectrum(frequencies, tube)``: the one-sided cross-spectral matrix of the generalised
forces Q_r = ∫ φ_r·f ds of the modes of a :class:`~fretwear.flow.tube.TubeFlow` [N²/Hz], shape
(n_f, n_modes, n_modes) (PROJ_SPEC_BASE). The formulas follow the Fortran routines that evaluate
them (spect1, coesp1, coesp4, sfifj, dspprs, accept, coegen, corcos; GRAPPE_1 in
:mod:`~fretwear.flow.grappe1`, GRAPPE_2 (specep) in :mod:`~fretwear.flow.grappe2`; the surface
families, AU_YANG and SPEC_CORR_CONV_3, in :mod:`~fretwear.flow.surface`); docs/flow.md cites each
and says what is left out and why.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.flow.grappe1 import Grappe1
from fretwear.flow.grappe2 import Grappe2
from fretwear.flow.projection import (
    check_positive,
    convected_acceptance,
    exponential_acceptance,
    positive_frequencies,
)
from fretwear.flow.surface import (
    SpecCorrConv3,
    au_yang_acceptance,
    au_yang_parameters,
    generale_surface_acceptance,
)
from fretwear.flow.tube import TubeFlow


# --------------------------------------------------------------------------- SPEC_LONG_COR_n
def long_cor_1_coefficients(reynolds: float) -> tuple[float, float, float, float]:
    """Coefficients (φ₀, ε, f_rc, β) of SPEC_LONG_COR_1 from the Reynolds number (coesp1).

    Parameters
    ----------
    reynolds : float
        Re = Ū·D/ν [-].

    Returns
    -------
    φ₀ [-], ε [-], f_rc [-], β [-]

    Notes
    -----
    φ₀ = 1.3e-4 × (2.1808 for Re ≤ 1.5e4; 20.42 − 14.00e-4 Re − 9.81e-8 Re² + 11.97e-12 Re³
    − 35.95e-17 Re⁴ + 34.69e-22 Re⁵ up to 5e4; 38.6075 above); (ε, β) = (0.7, 3) for
    Re ≤ 3.5e4, (0.3, 4) up to 5.5e4, (0.6, 4) above; f_rc = 0.2.

    References
    ----------
    .. [1] Code_Aster, ``bibfor/modelisa/coesp1.F90``.

    Examples
    --------
    >>> [round(v, 6) for v in long_cor_1_coefficients(1e4)]
    [0.000284, 0.7, 0.2, 3.0]
    """
    re = abs(float(reynolds))
    if re <= 1.5e4:
        phi0 = 2.1808
    elif re <= 5.0e4:
        phi0 = (20.42 - 14.00e-4 * re - 9.81e-8 * re**2 + 11.97e-12 * re**3
                - 35.95e-17 * re**4 + 34.69e-22 * re**5)
    else:
        phi0 = 38.6075
    if re <= 3.5e4:
        eps, beta = 0.7, 3.0
    elif re > 5.5e4:
        eps, beta = 0.6, 4.0
    else:
        eps, beta = 0.3, 4.0
    return phi0 * 1.3e-4, eps, 0.2, beta


def long_cor_4_phi0(void_fraction: float) -> float:
    """φ₀ of SPEC_LONG_COR_4 from the void fraction α (coesp4) [SI units of (ρU)^γ].

    Notes
    -----
    φ₀ = 10^(24.042 α^0.5 − 50.421 α^1.5 + 63.483 α^2.5 − 33.284 α^3.5) / 6.8e-2.

    References
    ----------
    .. [1] Code_Aster, ``bibfor/modelisa/coesp4.F90``.

    Examples
    --------
    >>> round(long_cor_4_phi0(0.0), 4)
    14.7059
    """
    a = float(void_fraction)
    if not 0 <= a < 1:
        raise InputError(f"SPEC_LONG_COR_4: the void fraction must lie in [0, 1), got {a!r}")
    exponent = 24.042 * a**0.5 - 50.421 * a**1.5 + 63.483 * a**2.5 - 33.284 * a**3.5
    return 10.0**exponent / 6.8e-2


@dataclass(frozen=True)
class _LongCor:
    """Shared evaluation of the correlation-length families (spect1)."""

    name: ClassVar[str] = ""

    def reduced_spectrum(self, reduced_frequency: np.ndarray, tube: TubeFlow,
                         velocity: float) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def modal_spectrum(self, frequencies, tube: TubeFlow) -> np.ndarray:
        """Cross-spectral matrix of the generalised forces [N²/Hz], shape (n_f, n, n).

        S_ij(f) = ¼ D³ Ū²|Ū| · LC2_ij · S_R(f_r), f_r = f·D/|Ū|,
        LC2_ij = Σ_c ∬ e^{−|s₁−s₂|/λ} ρ(s₁)u(s₁)²φ_i(s₁) ρ(s₂)u(s₂)²φ_j(s₂) ds₁ds₂,
        λ = LONG_COR·D, u = U/Ū (spect1 §5-6, spect4).
        """
        f = positive_frequencies(frequencies)
        check_positive(self.name, long_cor=self.long_cor)
        d = tube.diameter
        u_zone = tube.zone_velocity()
        u_norm = tube.velocity / u_zone
        lc2 = exponential_acceptance(tube, self.long_cor * d, tube.density * u_norm**2)
        fr = np.abs(f * d / u_zone)
        front = 0.25 * d**3 * u_zone**2 * abs(u_zone)
        return front * lc2[None, :, :] * self.reduced_spectrum(fr, tube, u_zone)[:, None, None]


@dataclass(frozen=True)
class SpecLongCor1(_LongCor):
    """SPEC_LONG_COR_1: cross flow, single phase; coefficients from the Reynolds number.

    Parameters
    ----------
    long_cor : float
        Correlation length λ/D [-] (LONG_COR, in diameters).
    kinematic_viscosity : float
        ν [m²/s] (VISC_CINE).

    Notes
    -----
    S_R(f_r) = φ₀ / ((1 − x)² + 4ε²x), x = (f_r/f_rc)^(β/2), coefficients from
    :func:`long_cor_1_coefficients` at Re = Ū·D/ν (spect1, ispect = 1).

    Examples
    --------
    >>> SpecLongCor1(long_cor=3.0, kinematic_viscosity=1e-6).name
    'SPEC_LONG_COR_1'
    """

    name: ClassVar[str] = "SPEC_LONG_COR_1"
    long_cor: float = math.nan
    kinematic_viscosity: float = math.nan

    def reduced_spectrum(self, reduced_frequency, tube, velocity):
        check_positive(self.name, kinematic_viscosity=self.kinematic_viscosity)
        phi0, eps, frc, beta = long_cor_1_coefficients(velocity * tube.diameter
                                                       / self.kinematic_viscosity)
        x = (reduced_frequency / frc) ** (beta / 2.0)
        return phi0 / ((1.0 - x) ** 2 + 4.0 * eps * eps * x)


@dataclass(frozen=True)
class SpecLongCor2(_LongCor):
    """SPEC_LONG_COR_2: S_R(f_r) = φ₀ / (1 + (f_r/f_rc)^β) (spect1, ispect = 2).

    Parameters
    ----------
    long_cor : float
        λ/D [-].
    freq_coup, phi0, beta : float
        f_rc [-] (catalogue 0.1), φ₀ [-] (1.5e-3), β [-] (2.7).

    Examples
    --------
    >>> SpecLongCor2(long_cor=3.0).phi0
    0.0015
    """

    name: ClassVar[str] = "SPEC_LONG_COR_2"
    long_cor: float = math.nan
    freq_coup: float = 0.1
    phi0: float = 1.5e-3
    beta: float = 2.7

    def reduced_spectrum(self, reduced_frequency, tube, velocity):
        return self.phi0 / (1.0 + (reduced_frequency / self.freq_coup) ** self.beta)


@dataclass(frozen=True)
class SpecLongCor3(_LongCor):
    """SPEC_LONG_COR_3: S_R = φ₀₁/f_r^β₁ for f_r ≤ f_rc, φ₀₂/f_r^β₂ above (spect1, ispect = 3).

    Parameters
    ----------
    long_cor : float
        λ/D [-].
    freq_coup, phi0_1, beta_1, phi0_2, beta_2 : float
        Catalogue defaults 0.2, 5e-3, 0.5, 4e-5, 3.5 [-].

    Examples
    --------
    >>> SpecLongCor3(long_cor=3.4).beta_2
    3.5
    """

    name: ClassVar[str] = "SPEC_LONG_COR_3"
    long_cor: float = math.nan
    freq_coup: float = 0.2
    phi0_1: float = 5.0e-3
    beta_1: float = 0.5
    phi0_2: float = 4.0e-5
    beta_2: float = 3.5

    def reduced_spectrum(self, reduced_frequency, tube, velocity):
        low = reduced_frequency <= self.freq_coup
        return np.where(low, self.phi0_1 / reduced_frequency**self.beta_1,
                        self.phi0_2 / reduced_frequency**self.beta_2)


@dataclass(frozen=True)
class SpecLongCor4(_LongCor):
    """SPEC_LONG_COR_4: two-phase cross flow, S_R = φ₀(α) / (f_r^β (ρ̄Ū)^γ) (spect1, ispect = 4).

    Parameters
    ----------
    long_cor : float
        λ/D [-].
    void_fraction : float, optional
        α [-] (TAUX_VIDE); default: the mean of the tube's void fraction over the grid points in
        flow.
    beta, gamma : float
        Catalogue defaults 2 and 4 [-].

    Notes
    -----
    ρ̄ is the mean of the density over the grid points in flow (spect1 averages its nodes);
    φ₀ from :func:`long_cor_4_phi0`.

    Examples
    --------
    >>> SpecLongCor4(long_cor=3.0, void_fraction=0.5).gamma
    4.0
    """

    name: ClassVar[str] = "SPEC_LONG_COR_4"
    long_cor: float = math.nan
    void_fraction: float | None = None
    beta: float = 2.0
    gamma: float = 4.0

    def reduced_spectrum(self, reduced_frequency, tube, velocity):
        mask = tube.in_flow()
        alpha = (float(np.mean(tube.void_fraction[mask])) if self.void_fraction is None
                 else self.void_fraction)
        rho_u = abs(float(np.mean(tube.density[mask])) * velocity)
        return long_cor_4_phi0(alpha) / (reduced_frequency**self.beta * rho_u**self.gamma)


# --------------------------------------------------------------------------- SPEC_CORR_CONV_n
#: Coherence functions of the convected families (accept.F90), by METHODE: GENERALE and CORCOS
#: along the tube's axis, AU_YANG on its surface (:mod:`~fretwear.flow.surface`).
COHERENCES: tuple[str, ...] = ("GENERALE", "CORCOS", "AU_YANG")


def convected_coherence(method: str, distance, frequency: float, velocity: float,
                        correlation_length: float) -> np.ndarray:
    """Coherence of the convected families between two points of the tube's axis [-].

    Parameters
    ----------
    method : {"GENERALE", "CORCOS"}
        METHODE of SPEC_CORR_CONV_1/_2.
    distance : array_like
        Signed axial distance s₁ − s₂ [m].
    frequency : float
        f [Hz].
    velocity : float
        Flow velocity U [m/s]; the convection velocity is U_c = 0.65 U (accept.F90).
    correlation_length : float
        L [m] (LONG_COR_1), used by GENERALE.

    Notes
    -----
    GENERALE: e^{−|Δ|/L} cos(ω|Δ|/U_c) (coegen); CORCOS along the axis (no transverse
    separation on a line): e^{−k_l|Δ|} cos(ωΔ/U_c), k_l = 0.1 ω/U_c (corcos, accept).

    Examples
    --------
    >>> float(convected_coherence("GENERALE", 0.0, 10.0, 1.0, 0.1))
    1.0
    """
    d = np.abs(np.asarray(distance, float))
    omega = 2.0 * np.pi * frequency
    uc = 0.65 * velocity
    if method == "GENERALE":
        return np.exp(-d / correlation_length) * np.cos(omega * d / uc)
    if method == "CORCOS":
        return np.exp(-0.1 * omega / uc * d) * np.cos(omega * d / uc)
    if method == "AU_YANG":
        raise KeywordError("convected spectrum: METHODE 'AU_YANG' is a surface coherence: "
                           "fretwear.flow.surface.au_yang_coherence")
    raise KeywordError(f"convected spectrum: METHODE {method!r} is not available; choose one of "
                       f"{list(COHERENCES)}")


@dataclass(frozen=True)
class _Convected:
    name: ClassVar[str] = ""

    def point_spectrum(self, frequencies: np.ndarray) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError

    def modal_spectrum(self, frequencies, tube: TubeFlow) -> np.ndarray:
        """S_ij(f) = S_p(f) · Σ_c ∬ C(s₁−s₂, f) φ_i(s₁) φ_j(s₂) ds₁ds₂ [unit of S_p × m²]."""
        f = positive_frequencies(frequencies)
        check_positive(self.name, velocity=self.velocity)
        if self.method not in COHERENCES:
            convected_coherence(self.method, 0.0, 1.0, 1.0, 1.0)  # raises the KeywordError
        sp = self.point_spectrum(f)
        out = np.zeros((f.size, tube.n_modes, tube.n_modes))
        live = sp > 0
        if self.method == "AU_YANG":
            parameters = au_yang_parameters(self.name, self.velocity, self.coef_vite_flui_a,
                                            self.coef_vite_flui_o, self.long_cor_1,
                                            self.long_cor_2)
            if live.any():
                out[live] = sp[live, None, None] * au_yang_acceptance(tube, f[live],
                                                                      **parameters)
            return out
        length = self.long_cor_1 if self.method == "GENERALE" else 1.0
        check_positive(self.name, long_cor_1=length)
        if self.circumferential_points is not None:  # on the surface, as Code_Aster's accept
            if self.method != "GENERALE":
                raise InputError(f"{self.name}: circumferential_points integrates GENERALE on "
                                 f"the tube's surface; METHODE {self.method!r} stays along the "
                                 "axis (leave circumferential_points out) or use AU_YANG")
            if live.any():
                out[live] = sp[live, None, None] * generale_surface_acceptance(
                    tube, f[live], velocity=self.velocity, length=length,
                    circumferential_points=self.circumferential_points,
                    axial_points=self.axial_points)
            return out
        if live.any():
            acc = convected_acceptance(
                tube, f[live],
                lambda d, fk: convected_coherence(self.method, d, fk, self.velocity, length))
            out[live] = sp[live, None, None] * acc
        return out


@dataclass(frozen=True)
class SpecCorrConv1(_Convected):
    """SPEC_CORR_CONV_1: axial flow, wall-pressure spectrum K²(ρU²)²D_h³ up to a cut-off.

    Parameters
    ----------
    long_cor_1 : float
        L [m] (LONG_COR_1).
    velocity : float
        U [m/s] (VITE_FLUI).
    density : float
        ρ [kg/m³] (RHO_FLUI).
    hydraulic_diameter : float
        D_h [m] (D_FLUI).
    freq_coup : float, optional
        Cut-off frequency [Hz] (FREQ_COUP); the reduced cut-off is min(FREQ_COUP·D_h/U, 10),
        10 when not given (sfifj).
    k : float
        K [-], catalogue 5.8e-3.
    method : {"GENERALE", "CORCOS", "AU_YANG"}
        Coherence (catalogue default GENERALE).
    long_cor_2 : float, optional
        L_t [m], circumferential correlation length of AU_YANG (LONG_COR_2).
    coef_vite_flui_a, coef_vite_flui_o : float, optional
        AU_YANG's axial and circumferential convection velocities over U [-]
        (COEF_VITE_FLUI_A, COEF_VITE_FLUI_O; sfifj).
    circumferential_points, axial_points : int, optional
        With GENERALE: integrate on the tube's outer surface as Code_Aster's accept does
        (:func:`~fretwear.flow.surface.generale_surface_acceptance`; the coherence of the
        distance in space between the two points) with these points around and along (default
        along: the tube's grid), the modal matrix then in Pa²·m⁷; without, along the axis.

    Notes
    -----
    S_p(f) = K²(ρU²)²D_h³ for f·D_h/U ≤ f_c,red, 0 above (dspprs) [Pa²·m³], so the modal matrix
    is in Pa²·m⁵ with GENERALE and CORCOS, integrated along the tube's axis (Code_Aster
    integrates over a surface interface: docs/flow.md), and in Pa²·m⁷ with AU_YANG, or with
    GENERALE given ``circumferential_points``, integrated over the tube's outer surface
    (:func:`~fretwear.flow.surface.au_yang_acceptance`,
    :func:`~fretwear.flow.surface.generale_surface_acceptance`).

    Examples
    --------
    >>> s = SpecCorrConv1(long_cor_1=0.05, velocity=5.0, density=1000.0, hydraulic_diameter=0.01)
    >>> float(s.point_spectrum(np.array([100.0, 6000.0]))[1])
    0.0
    """

    name: ClassVar[str] = "SPEC_CORR_CONV_1"
    long_cor_1: float = math.nan
    velocity: float = math.nan
    density: float = math.nan
    hydraulic_diameter: float = math.nan
    freq_coup: float | None = None
    k: float = 5.8e-3
    method: str = "GENERALE"
    long_cor_2: float | None = None
    coef_vite_flui_a: float | None = None
    coef_vite_flui_o: float | None = None
    circumferential_points: int | None = None
    axial_points: int | None = None

    def point_spectrum(self, frequencies: np.ndarray) -> np.ndarray:
        check_positive(self.name, density=self.density, hydraulic_diameter=self.hydraulic_diameter)
        dh, u = self.hydraulic_diameter, self.velocity
        cut = 10.0 if self.freq_coup is None else min(self.freq_coup * dh / u, 10.0)
        level = self.k**2 * (self.density * u * u) ** 2 * dh**3
        return np.where(np.asarray(frequencies) * dh / u <= cut, level, 0.0)


@dataclass(frozen=True)
class SpecCorrConv2(_Convected):
    """SPEC_CORR_CONV_2: a user spectrum S_p(ω) with the convected coherence.

    Parameters
    ----------
    function : callable
        S_p as a function of the circular frequency ω = 2πf [rad/s] (FONCTION, NOM_PARA PULS),
        vectorised; its unit sets the unit of the result (× m²).
    velocity : float
        U [m/s] (VITE_FLUI).
    freq_coup : float, optional
        Cut-off [Hz]: S_p = 0 above (sfifj); none when not given.
    long_cor_1 : float
        L [m] of the GENERALE coherence. Code_Aster's SPEC_CORR_CONV_2 has no LONG_COR and
        reads an unset value; fretwear asks for it.
    method : {"GENERALE", "CORCOS", "AU_YANG"}
    long_cor_2, coef_vite_flui_a, coef_vite_flui_o : float, optional
        AU_YANG's parameters, as SPEC_CORR_CONV_1 (Code_Aster's sfifj leaves U_c and U_ct unset
        for SPEC_CORR_CONV_2 with AU_YANG; fretwear asks for them).
    circumferential_points, axial_points : int, optional
        GENERALE on the tube's surface, as SPEC_CORR_CONV_1 (the result then × m⁴).

    Examples
    --------
    >>> s = SpecCorrConv2(function=lambda w: 1.0 + 0 * w, velocity=2.0, freq_coup=50.0)
    >>> s.point_spectrum(np.array([10.0, 60.0])).tolist()
    [1.0, 0.0]
    """

    name: ClassVar[str] = "SPEC_CORR_CONV_2"
    function: Callable | None = None
    velocity: float = math.nan
    freq_coup: float | None = None
    long_cor_1: float = math.nan
    method: str = "GENERALE"
    long_cor_2: float | None = None
    coef_vite_flui_a: float | None = None
    coef_vite_flui_o: float | None = None
    circumferential_points: int | None = None
    axial_points: int | None = None

    def point_spectrum(self, frequencies: np.ndarray) -> np.ndarray:
        if not callable(self.function):
            raise InputError("SPEC_CORR_CONV_2: give 'function', the spectrum as a function of "
                             "ω [rad/s]")
        f = np.asarray(frequencies, float)
        values = np.broadcast_to(np.asarray(self.function(2 * np.pi * f), float), f.shape)
        if self.freq_coup is not None:
            values = np.where(f > self.freq_coup, 0.0, values)
        return np.array(values, float)


#: The turbulence spectrum families, by Code_Aster keyword.
SPECTRA: dict[str, type] = {cls.name: cls for cls in (
    SpecLongCor1, SpecLongCor2, SpecLongCor3, SpecLongCor4, SpecCorrConv1, SpecCorrConv2,
    SpecCorrConv3, Grappe1, Grappe2)}


def make_spectrum(name: str, **parameters: Any):
    """A spectrum family of :data:`SPECTRA` from its keyword and parameters.

    Parameters are the dataclass fields in lower case (Code_Aster's keywords in capitals are
    accepted: ``LONG_COR``, ``FREQ_COUP``, ``VISC_CINE`` → ``kinematic_viscosity``,
    ``TAUX_VIDE`` → ``void_fraction``...).

    Examples
    --------
    >>> make_spectrum("SPEC_LONG_COR_3", LONG_COR=3.4).long_cor
    3.4
    """
    key = str(name).upper()
    if key not in SPECTRA:
        raise KeywordError(f"unknown turbulence spectrum {name!r}; choose one of "
                           f"{list(SPECTRA)}")
    cls = SPECTRA[key]
    aliases = {"visc_cine": "kinematic_viscosity", "taux_vide": "void_fraction",
               "vite_flui": "velocity", "rho_flui": "density", "d_flui": "hydraulic_diameter",
               "methode": "method", "fonction": "function", "grappe_2": "configuration",
               "grappe_1": "flow_rate"}
    fields = {f.name for f in dataclasses.fields(cls)}
    given = {}
    for raw, value in parameters.items():
        k = aliases.get(raw.lower(), raw.lower())
        if k not in fields:
            raise KeywordError(f"{key}: unknown parameter {raw!r}; it takes {sorted(fields)}")
        given[k] = value
    return cls(**given)
