"""GRAPPE_1 (DEFI_SPEC_TURB SPEC_FONC_FORME): the turbulence on a control rod in its guide.

Code_Aster describes the load on an excited window of length L = 0.971 m centred on a node by
six shape functions per transverse direction (twelve in all, each a cos/sin/cosh/sinh
combination on three segments of the window), their auto- and cross-spectra (S₀/(1 + (f/15)^4.6)
with tabulated S₀ and piecewise-constant phases) for the reference flow rates 180 and
300 m³/h. The modes are projected onto the shape functions by least squares (β = A⁻¹B, A the
functions' Gram matrix, B their products with the modes) and S_Q = βᵀ S_ff β.

Sources (code_aster repository, GitHub ehmoussi/code_aster): ``bibfor/modelisa/specff.F90``
(the spectra and the projection), ``ffgra1.F90`` (the functions), ``pha180.F90`` and
``pha300.F90`` (the phases), ``fenexc.F90`` (the window), ``deffen.F90`` (the modes on it),
``scalff.F90`` and ``scaldf.F90`` (the trapezoidal products).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.flow.tube import TubeFlow

#: Excited length of GRAPPE_1 [m] (specff).
WINDOW = 0.971

# ffgra1: the three segments (first and last point, start abscissa, reference abscissa x0) and,
# per flow rate, per function (6) and segment (3): (λ [1/m], c_cos, c_sin, c_cosh, c_sinh).
_SEGMENTS = ((0, 33, 0.0, 0.0), (34, 66, 0.337, 0.4053), (67, 99, 0.653999, 0.7228))
_COEF = {
    180: (8.92004, .0876767, 1.01885, -.0864421, .0867667, 8.92004, -.592371, -.647456, .110354,
          -.0607590, 8.92004, .716904, .678938, -.0781130, .0525716, 9.58117, -.0824166, .722287,
          .0851556, -.0900713, 9.58117, -.512911, -.647767, -.00369576, .0255866, 9.58117,
          .607072, .744850, -.000966177, -.0149861, 10.4292, -.0315180, -.670248, .0298443,
          -.0518046, 10.4292, .105637, -.255743, -.147931, .199660, 10.4292, .393381, .836201,
          .166871, -.186046, 12.1346, .0146509, .422678, -.0147882, .0332653, 12.1346, .373902,
          .698009, .216923, -.167900, 12.1346, .0139962, .498839, .252902, -.259762, 18.6172,
          -.130075, -.717144, .129807, -.130585, 18.6172, -.963054, .0725669, .00891863,
          -.00593922, 18.6172, -.550072, -.0592468, .0737335, -.0756190, 21.4486, .192720,
          -.746667, -.185555, .186725, 21.4486, .616604, .191943, .0958665, -.0986181, 21.4486,
          .552441, .395168, .0595057, -.0594600),
    300: (8.62668, -.0328857, .570796, .0323381, -.0468150, 8.62668, -.376416, -.610767,
          .0388797, .0500452, 8.62668, .670443, .688077, -.0798460, .0279372, 9.31612, -.0725227,
          .691873, .0729040, -.0819260, 9.31612, -.502377, -.642044, .0129275, .0202009, 9.31612,
          .619794, .692713, -.0370607, .0180415, 10.2233, .0147741, -.742058, -.0146033,
          -.00120140, 10.2233, .290293, -.192318, -.164685, .240156, 10.2233, .369431, .797258,
          .159602, -.186411, 11.9350, .0756823, .457934, -.0761885, .0959711, 11.9350, .329857,
          .697145, .202018, -.158517, 11.9350, -.0476558, .465654, .260041, -.275460, 17.8865,
          -.197756, -1.00842, .196719, -.196414, 17.8865, -.609465, .0974086, .123622, -.125797,
          17.8865, -.574084, -.0109550, .0456200, -.0494731, 19.8739, .571860, -.643644, -.572587,
          .573938, 19.8739, .666135, .365642, .256218, -.258155, 19.8739, .336904, .165036,
          -.0582536, .0594626),
}
#: specff's PLA180 / PLA300: S₀ of the 21 auto- and cross-spectra, packed by columns of the upper
#: triangle (entry k₂(k₂−1)/2 + k₁ for functions k₁ ≤ k₂, 1-based).
LEVELS = {
    180: (0.8, 1.0, 1.3, .15, .2, .04, .24, .34, .06, .28, .1, .02, .03, .13, .42, 1.0, 1.3, .18,
          .61, .25, 2.6),
    300: (1.1, 1.6, 2.6, .18, .32, .04, .16, .27, .04, .1, .49, .83, .03, .07, .88, 1.7, 3.0, .3,
          .32, 1.0, 4.5),
}
# pha180/pha300: the phase of each cross-spectrum k₁ < k₂ (entry (k₂−1)(k₂−2)/2 + k₁) as steps:
# ((upper frequency bounds [Hz]), (phase / π on each step, the last one above the last bound)).
_PHASES = {
    180: (((), (1,)), ((60, 120), (0, -1 / 2, -1 / 4)), ((), (1,)), ((60,), (1, 2 / 3)),
          ((55,), (0, -1 / 6)), ((), (1,)), ((15, 45, 55), (0, 1, 0, 1)),
          ((20, 45, 60, 110), (1, 0, 1, 1 / 2, 0)), ((125,), (0, 1)), ((45,), (0, 1)), ((), (1,)),
          ((65, 105), (0, 1 / 6, 0)), ((60, 120), (1, 0, 1)), ((15, 85), (5 / 6, 0, 5 / 6)),
          ((15, 45, 55), (1, 0, 1, 0))),
    300: (((), (1,)), ((70, 130), (1, -2 / 3, 1)),
          ((55, 75, 90, 115, 130), (0, 1 / 4, 2 / 3, 5 / 6, 2 / 3, 1 / 2)),
          ((30, 50, 65, 80, 110, 130), (1, 0, 1 / 3, 0, 2 / 3, 1 / 3, 0)),
          ((30, 50, 65, 80, 110), (0, 1, -1 / 2, 1, 0, -1 / 2)), ((30,), (0, 1)),
          ((5, 105), (1, 0, 1)), ((110, 125), (1, -1 / 2, -1 / 4)),
          ((50, 125), (1, 1 / 3, -2 / 3)),
          ((10, 20, 25, 110, 125), (-1 / 2, 0, -1 / 2, 1, 2 / 3, 1 / 2)), ((), (1,)),
          ((35, 45, 55, 65, 75, 90, 105, 115, 125),
           (0, -1 / 2, 0, -1 / 4, 1 / 12, 0, -1 / 6, -2 / 3, 1 / 6, 1 / 4)),
          ((30, 45, 50, 60, 90, 110, 130), (0, 1, 1 / 4, -1 / 2, 1 / 8, 1 / 4, 0, -1 / 6)),
          ((45, 55, 80, 90), (0, 1 / 4, 0, 1 / 3, 1)), ((95,), (1, 7 / 12))),
}


def shape_functions(rate: int) -> tuple[np.ndarray, np.ndarray]:
    """The 12 shape functions of GRAPPE_1 on [0, 2L] (ffgra1): abscissae (202,) [m], values
    (202, 12) [-]; functions 1-6 live on [0, L] (first transverse direction), 7-12 on [L, 2L].

    Examples
    --------
    >>> s, v = shape_functions(180)
    >>> s.shape, v.shape, round(float(s[100]), 3), float(v[150, 0])
    ((202,), (202, 12), 0.971, 0.0)
    """
    coef = np.array(_COEF[rate]).reshape(6, 3, 5)
    disc = np.empty(101)
    x = 0.01
    for first, last, start, _ in _SEGMENTS:  # the abscissae as ffgra1 accumulates them
        disc[first] = start
        for i in range(first + 1, last + 1):
            disc[i] = x
            x += 0.01
    disc[100] = WINDOW
    values = np.zeros((202, 12))
    for m in range(6):
        for t, (first, last, _, x0) in enumerate(_SEGMENTS):
            lam, c1, c2, c3, c4 = coef[m, t]
            idx = np.arange(first, last + 1 if t < 2 else 101)
            z = lam * (disc[idx] - x0)
            values[idx, m] = c1 * np.cos(z) + c2 * np.sin(z) + c3 * np.cosh(z) + c4 * np.sinh(z)
        values[101:, m + 6] = values[:101, m]
    return np.concatenate([disc, disc + WINDOW]), values


def function_spectra(rate: int, frequencies) -> np.ndarray:
    """The 6 × 6 Hermitian cross-spectral matrix of the shape functions (specff §6.2) [N²/Hz],
    shape (n_f, 6, 6): S₀/(1 + (f/15)^4.6) with phases e^{iφ(f)} above the diagonal.

    Examples
    --------
    >>> s = function_spectra(180, [15.0])
    >>> float(s[0, 0, 0].real), complex(s[0, 0, 1])   # 0.8/2; S₀ = 1.0 at phase π
    (0.4, (-0.5+6.123233995736766e-17j))
    """
    f = np.asarray(frequencies, float).reshape(-1)
    shape = 1.0 / (1.0 + (f / 15.0) ** 4.6)
    out = np.zeros((f.size, 6, 6), complex)
    for b in range(6):
        for a in range(b + 1):
            level = LEVELS[rate][(b + 1) * b // 2 + a] * shape
            if a == b:
                out[:, a, a] = level
                continue
            bounds, phases = _PHASES[rate][b * (b - 1) // 2 + a]
            phi = math.pi * np.asarray(phases)[np.searchsorted(bounds, f, side="left")]
            out[:, a, b] = level * np.exp(1j * phi)
            out[:, b, a] = np.conj(out[:, a, b])
    return out


@dataclass(frozen=True)
class Grappe1:
    """GRAPPE_1: a control rod's excited window, DEBIT_180 or DEBIT_300 (SPEC_FONC_FORME).

    Parameters
    ----------
    flow_rate : {"DEBIT_180", "DEBIT_300"}
        The reference flow rate (180 or 300 m³/h).
    position : float
        Abscissa of the window's centre along the tube [m] (NOEUD); the window
        [position − L/2, position + L/2], L = 0.971 m, must lie on the tube (fenexc).

    Notes
    -----
    S_Q(f) = βᵀ S_ff(f) β, β = A⁻¹B, A_kl = ∫ g_k g_l ds, B_kr = ∫ g_k φ_r ds over [0, 2L]
    (trapezoids on ffgra1's abscissae, the modes interpolated linearly on them: the first
    direction (y) on [0, L], the second (z) on [L, 2L]), S_ff block-diagonal with the same 6 × 6
    matrix for both directions. The frequency is in Hz (not reduced): the spectra hold for the
    reference configuration of the measurements only.

    The measured 6 × 6 function matrix is not positive semi-definite: its smallest eigenvalue
    is negative at every frequency (down to −9 % of the largest for DEBIT_180, −25 % for
    DEBIT_300), so the modal matrix may not be either; it serves a spectral response, and
    :func:`~fretwear.flow.synthesis.synthesize` refuses it where it is not
    (``positive_semidefinite = False``).

    Examples
    --------
    >>> Grappe1(flow_rate="DEBIT_300", position=1.0).name
    'GRAPPE_1'
    """

    name: ClassVar[str] = "GRAPPE_1"
    #: the family's matrices are not guaranteed positive semi-definite (see Notes)
    positive_semidefinite: ClassVar[bool] = False
    flow_rate: str = "DEBIT_180"
    position: float = math.nan

    def projection(self, tube: TubeFlow) -> np.ndarray:
        """β (12, n_modes): the least-squares coordinates of the modes on the functions [-]."""
        rate = {"DEBIT_180": 180, "DEBIT_300": 300}.get(self.flow_rate)
        if rate is None:
            raise KeywordError(f"GRAPPE_1: flow_rate must be 'DEBIT_180' or 'DEBIT_300', got "
                               f"{self.flow_rate!r}")
        s = tube.positions
        start = self.position - WINDOW / 2
        tol = 1e-9 * max(1.0, abs(s[-1]))
        if not (start >= s[0] - tol and self.position + WINDOW / 2 <= s[-1] + tol):
            raise InputError(f"GRAPPE_1: the excited window [{start:.4g}, "
                             f"{self.position + WINDOW / 2:.4g}] m (L = {WINDOW} m around "
                             f"'position') must lie on the tube [{s[0]}, {s[-1]}] m")
        disc, g = shape_functions(rate)
        local = np.where(np.arange(disc.size) < 101, disc, disc - WINDOW) + start
        modes = np.empty((disc.size, tube.n_modes))
        for r in range(tube.n_modes):
            modes[:101, r] = np.interp(local[:101], s, tube.shapes[:, 0, r])
            modes[101:, r] = np.interp(local[101:], s, tube.shapes[:, 1, r])
        w = np.zeros(disc.size)
        d = np.diff(disc)
        w[:-1] += d / 2
        w[1:] += d / 2
        gram = g.T @ (w[:, None] * g)
        return np.linalg.solve(gram, g.T @ (w[:, None] * modes))

    def modal_spectrum(self, frequencies, tube: TubeFlow) -> np.ndarray:
        """Cross-spectral matrix of the generalised forces [N²/Hz], shape (n_f, n, n)."""
        f = np.asarray(frequencies, float).reshape(-1)
        if f.size == 0 or np.any(f <= 0) or not np.all(np.isfinite(f)):
            raise InputError("GRAPPE_1: frequencies [Hz] must be finite and > 0")
        beta = self.projection(tube)
        rate = 180 if self.flow_rate == "DEBIT_180" else 300
        six = function_spectra(rate, f)
        full = np.zeros((f.size, 12, 12), complex)
        full[:, :6, :6] = six
        full[:, 6:, 6:] = six
        return np.einsum("ki,fkl,lj->fij", beta, full, beta)
