"""A tube in flow: its mode shapes along the axis and the flow profile along it.

A :class:`TubeFlow` holds, on a grid of abscissae s along the tube, the transverse components
(local y, z) of every mode shape of a :class:`~fretwear.dynamics.ModalModel` and the flow seen by
the tube there: the cross-flow velocity U(s), the fluid density ρ(s) and the void fraction α(s).
The turbulence spectra (:mod:`fretwear.flow.spectra`) project onto it, the fluid-elastic check
(:mod:`fretwear.flow.stability`) weights by it. :func:`beam_tube_flow` builds one from the
uniform beam of :func:`fretwear.dynamics.uniform_beam_modes`, the grid passed as its forcing
points (no beam code of its own).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from fretwear.dynamics import ModalModel, uniform_beam_modes
from fretwear.errors import InputError


def _profile(name: str, value, n: int) -> np.ndarray:
    arr = np.array(value, dtype=float, copy=True).reshape(-1)
    if arr.size == 1:
        arr = np.full(n, float(arr[0]))
    if arr.size != n:
        raise InputError(f"tube flow: {name!r} has {arr.size} values for {n} grid points; give "
                         "one value or one per point")
    if not np.all(np.isfinite(arr)):
        raise InputError(f"tube flow: {name!r} has a non-finite value")
    return arr


@dataclass(frozen=True, eq=False)
class TubeFlow:
    """Mode shapes and flow along a tube, on a grid of abscissae.

    Parameters
    ----------
    positions : array_like, shape (n_grid,)
        Abscissae s along the tube [m], strictly increasing.
    shapes : array_like, shape (n_grid, 2, n_modes)
        Mode-shape components φ_r(s) along local y and z [-] (displacement per unit modal
        coordinate, as :class:`~fretwear.dynamics.ModalModel`).
    diameter : float
        Outer diameter D of the tube [m].
    velocity : array_like or float
        Cross-flow velocity U(s) [m/s] (0 where the tube is out of the flow).
    density : array_like or float
        External fluid density ρ(s) [kg/m³] (two-phase: the homogeneous mixture density).
    void_fraction : array_like or float
        Void fraction α(s) [-], in [0, 1).
    metadata : dict
        Provenance.

    Examples
    --------
    >>> s = np.linspace(0.0, 1.0, 5)
    >>> t = TubeFlow(s, np.sin(np.pi * s)[:, None, None] * [[1.0], [0.0]], 0.02, 2.0, 1000.0)
    >>> t.n_modes, float(t.velocity[2])
    (1, 2.0)
    """

    positions: Any
    shapes: Any
    diameter: float
    velocity: Any = 0.0
    density: Any = 1000.0
    void_fraction: Any = 0.0
    metadata: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        s = np.array(self.positions, dtype=float, copy=True).reshape(-1)
        if s.size < 3 or np.any(np.diff(s) <= 0) or not np.all(np.isfinite(s)):
            raise InputError("tube flow: 'positions' [m] must hold at least 3 finite, strictly "
                             "increasing abscissae")
        phi = np.array(self.shapes, dtype=float, copy=True)
        if phi.ndim != 3 or phi.shape[0] != s.size or phi.shape[1] != 2:
            raise InputError(f"tube flow: 'shapes' must have shape ({s.size}, 2, n_modes) "
                             f"(grid points, directions y and z, modes), got {phi.shape}")
        if not (np.isfinite(self.diameter) and self.diameter > 0):
            raise InputError(f"tube flow: 'diameter' must be > 0 [m], got {self.diameter!r}")
        rho = _profile("density", self.density, s.size)
        alpha = _profile("void_fraction", self.void_fraction, s.size)
        if np.any(rho <= 0):
            raise InputError("tube flow: 'density' [kg/m³] must be > 0 everywhere")
        if np.any((alpha < 0) | (alpha >= 1)):
            raise InputError("tube flow: 'void_fraction' must lie in [0, 1)")
        values = {"positions": s, "shapes": phi, "diameter": float(self.diameter),
                  "velocity": _profile("velocity", self.velocity, s.size), "density": rho,
                  "void_fraction": alpha}
        for key, value in values.items():
            if isinstance(value, np.ndarray):
                value.flags.writeable = False
            object.__setattr__(self, key, value)

    @property
    def n_modes(self) -> int:
        """Number of modes."""
        return int(self.shapes.shape[2])

    @property
    def weights(self) -> np.ndarray:
        """Trapezoidal quadrature weights of the grid [m] (Σ w g ≈ ∫ g ds)."""
        s = self.positions
        w = np.zeros_like(s)
        d = np.diff(s)
        w[:-1] += 0.5 * d
        w[1:] += 0.5 * d
        return w

    @property
    def rotations(self) -> np.ndarray:
        """Slopes dφ/ds of the shapes [1/m], shape (n_grid, 2, n_modes) (second order)."""
        return np.gradient(self.shapes, self.positions, axis=0, edge_order=2)

    def in_flow(self) -> np.ndarray:
        """Mask of the grid points where U ≠ 0."""
        return np.abs(self.velocity) > 0.0

    def zone_velocity(self) -> float:
        """Mean velocity of the flow zone Ū [m/s]: ∫U ds over the span where U ≠ 0 divided by its
        length (Code_Aster op0146 §2.3, the zone's VMOY)."""
        mask = self.in_flow()
        if not mask.any():
            raise InputError("tube flow: the velocity is zero everywhere; no turbulence to project")
        i, j = np.flatnonzero(mask)[[0, -1]]
        s = self.positions[i:j + 1]
        if j == i:
            return float(self.velocity[i])
        return float(np.trapezoid(self.velocity[i:j + 1], s) / (s[-1] - s[0]))

    def with_flow(self, velocity=None, density=None, void_fraction=None) -> TubeFlow:
        """The same tube with another flow (each argument left out is kept)."""
        return replace(self, velocity=self.velocity if velocity is None else velocity,
                       density=self.density if density is None else density,
                       void_fraction=(self.void_fraction if void_fraction is None
                                      else void_fraction))


def beam_tube_flow(*, grid_points: int = 401, velocity=0.0, density=1000.0, void_fraction=0.0,
                   diameter: float, **beam: Any) -> tuple[ModalModel, TubeFlow]:
    """Modes of a uniform beam (:func:`~fretwear.dynamics.uniform_beam_modes`) and its
    :class:`TubeFlow` on a uniform grid of ``grid_points`` abscissae.

    Parameters
    ----------
    grid_points : int
        Number of grid points along the tube (>= 3); the turbulence's correlation length should
        span several of them.
    velocity, density, void_fraction : float or callable
        The flow: a value, or a function of the abscissa s [m] returning U [m/s], ρ [kg/m³],
        α [-].
    diameter : float
        Outer diameter D [m].
    **beam
        Keywords of :func:`~fretwear.dynamics.uniform_beam_modes` (``young_modulus``,
        ``second_moment``, ``mass_per_length``, ``length``, ``n_modes``, ``shock_positions``, ...).

    Returns
    -------
    (ModalModel, TubeFlow)
        The model as :func:`uniform_beam_modes` returns it (without the grid as forcing points)
        and the tube flow (modes in the same order: y-plane then z-plane).

    Examples
    --------
    >>> m, t = beam_tube_flow(young_modulus=2e11, second_moment=1e-8, mass_per_length=1.0,
    ...                       length=1.0, n_modes=1, shock_positions=[0.5], diameter=0.02,
    ...                       velocity=1.0, grid_points=101)
    >>> t.shapes.shape, round(float(t.shapes[50, 0, 0]), 6)
    ((101, 2, 2), 1.0)
    """
    if isinstance(grid_points, bool) or not isinstance(grid_points, int) or grid_points < 3:
        raise InputError(f"tube flow: 'grid_points' must be an integer >= 3, got {grid_points!r}")
    length = float(beam["length"])
    s = np.linspace(0.0, length, grid_points)
    full = uniform_beam_modes(**beam, forcing_positions=s)
    model = replace(full, forcing_shapes=None, forcing_names=())

    def sample(value):
        return np.array([value(x) for x in s], float) if callable(value) else value

    tube = TubeFlow(s, full.forcing_shapes[:, :2, :], diameter, sample(velocity), sample(density),
                    sample(void_fraction), metadata={"beam": full.metadata.get("beam", {})})
    return model, tube
