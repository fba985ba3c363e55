"""Fluid-elastic stability of a tube's modes: Connors' critical velocity and the stability ratio.

Per mode r, the critical cross-flow velocity (Connors) and the mode-shape-weighted effective
velocity of a non-uniform flow (the form of ASME Section III, Appendix N-1330, after Pettigrew
et al.) give the stability ratio U_eff/U_c; a ratio above 1 (or above a user margin) flags the
mode as fluid-elastically unstable. docs/flow.md gives the formulas and what is left out.
"""

from __future__ import annotations

import math

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.dynamics import ModalModel
from fretwear.errors import InputError
from fretwear.flow.tube import TubeFlow

#: Default design threshold on the stability ratio U_eff/U_c [-]: a tube above it and not
#: flagged unstable is said "near-critical" (a 25 % margin on the critical velocity, the design
#: value quoted in practice; docs/flow.md §4 says where it comes from and how to change it).
NEAR_CRITICAL = 0.75


def connors_velocity(frequency, damping_ratio, diameter: float, mass_per_length,
                     density, constant: float):
    """Connors' critical velocity U_c = K·f·D·√(2π ζ m / (ρ D²)) [m/s].

    Parameters
    ----------
    frequency : float or array_like
        Natural frequency f of the mode in flow [Hz].
    damping_ratio : float or array_like
        ζ [-] (total: structural, two-phase, viscous; 2πζ is the logarithmic decrement δ).
    diameter : float
        Outer diameter D [m].
    mass_per_length : float or array_like
        m [kg/m]: tube, contents and hydrodynamic (added) mass.
    density : float or array_like
        Fluid density ρ [kg/m³].
    constant : float
        Connors' constant K [-] (an input: it depends on the array and the design margin).

    Returns
    -------
    U_c [m/s]

    Notes
    -----
    U_c/(f D) = K √(m δ/(ρ D²)), δ = 2πζ (Connors 1970).

    References
    ----------
    .. [1] Connors, H. J. (1970). Fluidelastic vibration of tube arrays excited by cross flow.
           *Flow-Induced Vibration in Heat Exchangers*, ASME, 42-56.

    Examples
    --------
    >>> round(float(connors_velocity(50.0, 0.01, 0.02, 1.0, 1000.0, 3.0)), 4)
    1.1890
    """
    for key, value in (("diameter", diameter), ("constant", constant)):
        if not (np.isfinite(value) and value > 0):
            raise InputError(f"Connors: {key!r} must be > 0, got {value!r}")
    delta = 2.0 * np.pi * np.asarray(damping_ratio, float)
    return constant * np.asarray(frequency, float) * diameter * np.sqrt(
        np.asarray(mass_per_length, float) * delta / (np.asarray(density, float) * diameter**2))


def near_critical(ratio, *, threshold: float = NEAR_CRITICAL, margin: float = 1.0):
    """Whether a stability ratio lies in the near-critical band (threshold, margin] [-].

    Parameters
    ----------
    ratio : float or array_like
        Stability ratio U_eff/U_c [-] (:func:`stability_ratios`).
    threshold : float
        The design threshold [-] (default :data:`NEAR_CRITICAL`, 0.75): a ratio above it has
        less than the design margin on the critical velocity.
    margin : float
        The instability flag's threshold [-] (a ratio above it is flagged unstable, not
        near-critical; 1 by default; ``math.inf`` where the flag is decided elsewhere).

    Returns
    -------
    bool or ndarray of bool
        ``threshold < ratio <= margin`` (NaN: False).

    Notes
    -----
    Design practice keeps U_eff/U_c below a margin on Connors' critical velocity, for the
    scatter of the constant K and of the damping (docs/flow.md §4); 0.75 is a 25 % margin.

    Examples
    --------
    >>> near_critical([0.64, 0.797, 0.957, 1.116]).tolist()
    [False, True, True, False]
    >>> bool(near_critical(0.957, threshold=0.96))
    False
    """
    for key, value in (("threshold", threshold), ("margin", margin)):
        if not (isinstance(value, (int, float)) and value > 0
                and (math.isfinite(value) or key == "margin")):
            raise InputError(f"stability: the near-critical {key} must be a stability ratio "
                             f"U_eff/U_c > 0 [-] (e.g. 0.75 for a 25 % margin), got {value!r}")
    r = np.asarray(ratio, float)
    with np.errstate(invalid="ignore"):
        return (r > threshold) & (r <= margin)


def effective_values(tube: TubeFlow, mass_per_length, reference_density: float,
                     reference_mass: float) -> tuple[np.ndarray, np.ndarray]:
    """Mode-shape-weighted effective velocity of every mode [m/s] and the weights' norm.

    Parameters
    ----------
    tube : TubeFlow
        Shapes and flow along the tube.
    mass_per_length : float or array_like
        m(s) [kg/m] on the tube's grid.
    reference_density, reference_mass : float
        ρ₀ [kg/m³] and m₀ [kg/m], the values Connors' formula is then evaluated with.

    Returns
    -------
    U_eff : ndarray, shape (n_modes,)
        [m/s].
    shape_norm : ndarray, shape (n_modes,)
        ∫ |φ_r|² ds [m] (0 flags a mode without transverse motion).

    Notes
    -----
    U_eff,r² = ∫ (ρ(s)/ρ₀) U(s)² |φ_r(s)|² ds / ∫ (m(s)/m₀) |φ_r(s)|² ds, |φ|² = φ_y² + φ_z²
    (ASME Boiler and Pressure Vessel Code, Section III, Division 1, Nonmandatory Appendix N,
    N-1330; Pettigrew, Sylvestre & Campagna 1978).

    Examples
    --------
    >>> s = np.linspace(0, 1, 2001)
    >>> t = TubeFlow(s, np.sin(np.pi * s)[:, None, None] * [[1.0], [0.0]], 0.02,
    ...              velocity=np.where(s < 0.5, 2.0, 0.0), density=1000.0)
    >>> round(float(effective_values(t, 1.0, 1000.0, 1.0)[0][0]), 2)   # √(½)·2
    1.41
    """
    m = np.broadcast_to(np.asarray(mass_per_length, float), tube.positions.shape)
    if np.any(m <= 0) or not (reference_density > 0 and reference_mass > 0):
        raise InputError("stability: masses per length [kg/m] and the reference density and "
                         "mass must be > 0")
    w = tube.weights
    phi2 = np.sum(tube.shapes**2, axis=1)  # (n_grid, n)
    num = (w * tube.density / reference_density * tube.velocity**2) @ phi2
    den = (w * m / reference_mass) @ phi2
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.sqrt(np.where(den > 0, num / den, np.nan))
    return u, w @ phi2


def stability_ratios(model: ModalModel, tube: TubeFlow, *, mass_per_length, constant: float,
                     margin: float = 1.0, reference_density: float | None = None,
                     reference_mass: float | None = None) -> pd.DataFrame:
    """Stability ratio U_eff/U_c of every mode of a tube, flagged above ``margin``.

    Parameters
    ----------
    model : ModalModel
        The modes in flow (frequencies, damping ratios), in the order of ``tube``'s shapes.
    tube : TubeFlow
        Shapes and flow.
    mass_per_length : float or array_like
        m(s) [kg/m] with the added mass.
    constant : float
        Connors' constant K [-].
    margin : float
        A mode is flagged when its ratio exceeds it (1: instability; e.g. 0.75 for a 25 %
        margin).
    reference_density, reference_mass : float, optional
        ρ₀ [kg/m³], m₀ [kg/m]; default the mean density over the points in flow and the mean mass.
        The ratio does not depend on them (both velocities scale as √(m₀/ρ₀)).

    Returns
    -------
    DataFrame
        One row per mode: ``mode``, ``frequency_hz``, ``damping_ratio``,
        ``effective_velocity_m_s``, ``critical_velocity_m_s``, ``stability_ratio`` [-],
        ``flagged`` (ratio > margin), most critical first.

    Examples
    --------
    >>> from fretwear.flow.tube import beam_tube_flow
    >>> m, t = beam_tube_flow(young_modulus=2e11, second_moment=2.5e-9, mass_per_length=0.9,
    ...                       length=1.0, n_modes=1, shock_positions=[0.5], diameter=0.019,
    ...                       velocity=0.5, density=1000.0)
    >>> r = stability_ratios(m, t, mass_per_length=0.9, constant=3.0)
    >>> bool(r["flagged"].iloc[0]), round(float(r["stability_ratio"].iloc[0]), 3)
    (False, 0.599)
    """
    if not (np.isfinite(margin) and margin > 0):
        raise InputError(f"stability: 'margin' must be > 0, got {margin!r}")
    if model.n_modes != tube.n_modes:
        raise InputError(f"stability: the model has {model.n_modes} modes, the tube's shapes "
                         f"{tube.n_modes}")
    mask = tube.in_flow()
    rho0 = (float(np.mean(tube.density[mask])) if mask.any() else float(np.mean(tube.density))
            ) if reference_density is None else float(reference_density)
    m0 = (float(np.mean(mass_per_length)) if reference_mass is None else float(reference_mass))
    u_eff, norm = effective_values(tube, mass_per_length, rho0, m0)
    u_c = connors_velocity(model.frequencies, model.damping_ratios, tube.diameter, m0, rho0,
                           constant)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where((u_c > 0) & (norm > 0), u_eff / u_c, math.nan)
    frame = pd.DataFrame({"mode": np.arange(1, model.n_modes + 1),
                          "frequency_hz": model.frequencies,
                          "damping_ratio": model.damping_ratios,
                          "effective_velocity_m_s": u_eff, "critical_velocity_m_s": u_c,
                          "stability_ratio": ratio, "flagged": ratio > margin})
    return frame.sort_values("stability_ratio", ascending=False, na_position="last",
                             kind="stable").reset_index(drop=True)
