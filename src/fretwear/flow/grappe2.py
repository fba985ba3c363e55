"""GRAPPE_2 (DEFI_SPEC_TURB SPEC_EXCI_POINT): a force and a moment at one point of a control rod.

The reduced spectra S₀ / (1 + (f_r/f_rc)^β) of the force and the moment, with specep's
coefficients by configuration (ascending or descending flow, centred or eccentric rod), projected
onto the modes at the excited point (Code_Aster ``bibfor/modelisa/specep.F90``, ``scalep``;
docs/flow.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from fretwear.errors import InputError, KeywordError
from fretwear.flow.projection import check_positive, positive_frequencies
from fretwear.flow.tube import TubeFlow

#: specep's coefficients of GRAPPE_2, by configuration: (force, moment) rows of
#: (S_ref, f_r,ref, f_rc, β) for the ascending flows (S₀ = S_ref(1 + (f_r,ref/f_rc)^β)) and
#: (S₀, f_rc, β) for the descending ones.
GRAPPE_2_COEFFICIENTS: dict[str, tuple[tuple[float, ...], tuple[float, ...]]] = {
    "ASC_CEN": ((1.0e-4, 1.9e-1, 7.0e-2, 1.6), (2.7e-5, 1.9e-1, 7.0e-2, 2.1)),
    "ASC_EXC": ((1.0e-5, 5.0e-1, 2.0e-2, 2.9), (3.3e-4, 1.0e-1, 2.0e-2, 2.8)),
    "DES_CEN": ((4.0e-5, 1.9e-1, 1.6), (2.7e-5, 1.9e-1, 2.1)),
    "DES_EXC": ((1.7e-5, 2.2e-1, 2.9), (1.7e-5, 1.9e-1, 2.8)),
}


def grappe_2_spectra(configuration: str, reduced_frequency) -> tuple[np.ndarray, np.ndarray]:
    """Reduced spectra (force, moment) of GRAPPE_2: S₀ / (1 + (f_r/f_rc)^β) [-] (specep §6.2).

    Examples
    --------
    >>> f, m = grappe_2_spectra("DES_CEN", [0.0])
    >>> float(f[0]), float(m[0])
    (4e-05, 2.7e-05)
    """
    if configuration not in GRAPPE_2_COEFFICIENTS:
        raise KeywordError(f"GRAPPE_2: unknown configuration {configuration!r}; choose one of "
                           f"{list(GRAPPE_2_COEFFICIENTS)}")
    fr = np.asarray(reduced_frequency, float)
    out = []
    for row in GRAPPE_2_COEFFICIENTS[configuration]:
        if len(row) == 4:
            sref, frref, frc, beta = row
            s0 = sref * (1.0 + (frref / frc) ** beta)
        else:
            s0, frc, beta = row
        out.append(s0 / (1.0 + (fr / frc) ** beta))
    return out[0], out[1]


@dataclass(frozen=True)
class Grappe2:
    """GRAPPE_2 (SPEC_EXCI_POINT): a force and a moment at one point of a control rod.

    Parameters
    ----------
    configuration : {"ASC_CEN", "ASC_EXC", "DES_CEN", "DES_EXC"}
        Ascending/descending flow, centred/eccentric rod (GRAPPE_2).
    density : float
        ρ [kg/m³] (RHO_FLUI).
    velocity : float
        U [m/s] (PROJ_SPEC_BASE's VITE_FLUI).
    position : float
        Abscissa of the excited point along the tube [m] (NOEUD).

    Notes
    -----
    With c₁ = 282/890, c₂ = 0.77²/4, c_D = D/8.9e-2, f_r = f·D/|U| (specep):
    S_ij = ¼c₁²ρ²|U|³D³ [c₁c_D² S_F(f_r) a_i a_j + c₁c_D⁴c₂ S_M(f_r) b_i b_j], with
    a_r = φ_r,y + φ_r,z at the point (FORCE, both transverse directions, scalep) and
    b_r = dφ_r,y/ds − dφ_r,z/ds (MOMENT: rotations DRZ + DRY of a beam along x).

    Examples
    --------
    >>> Grappe2(configuration="ASC_CEN", density=1000.0, velocity=5.0, position=0.5).name
    'GRAPPE_2'
    """

    name: ClassVar[str] = "GRAPPE_2"
    configuration: str = "ASC_CEN"
    density: float = math.nan
    velocity: float = math.nan
    position: float = math.nan

    def modal_spectrum(self, frequencies, tube: TubeFlow) -> np.ndarray:
        f = positive_frequencies(frequencies)
        check_positive(self.name, density=self.density, velocity=abs(self.velocity))
        s = tube.positions
        if not s[0] <= self.position <= s[-1]:
            raise InputError(f"GRAPPE_2: 'position' {self.position!r} m lies outside the tube "
                             f"[{s[0]}, {s[-1]}] m")
        d, u = tube.diameter, abs(self.velocity)

        def at(values):  # (n_grid, 2, n) -> (2, n) at the point
            return np.array([[np.interp(self.position, s, values[:, c, r])
                              for r in range(tube.n_modes)] for c in range(2)])

        phi, rot = at(tube.shapes), at(tube.rotations)
        a, b = phi[0] + phi[1], rot[0] - rot[1]
        c1, c2, cd = 282.0 / 890.0, 0.77 * 0.77 / 4.0, d / 8.9e-2
        sf, sm = grappe_2_spectra(self.configuration, f * d / u)
        front = 0.25 * c1 * c1 * self.density**2 * u**3 * d**3
        return front * (c1 * cd**2 * sf[:, None, None] * np.outer(a, a)[None]
                        + c1 * cd**4 * c2 * sm[:, None, None] * np.outer(b, b)[None])
