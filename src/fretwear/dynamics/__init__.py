"""Built-in impact-sliding dynamics: a reduced modal model with DIS_CHOC-like shocks.

Users without Code_Aster can produce contact histories (every theory §1 channel) and run the
coupled loop dynamics → wear table → obstacle update → dynamics (``fretwear iterate``).

Modules: :mod:`~fretwear.dynamics.modal` (modes, uniform beam), :mod:`~fretwear.dynamics.shocks`
(obstacles, contact law), :mod:`~fretwear.dynamics.excitation` (forces, base acceleration,
random signals), :mod:`~fretwear.dynamics.integrate` (explicit compiled integration),
:mod:`~fretwear.workflows.loop` (case files, coupled loop).
"""

from __future__ import annotations

from fretwear.dynamics.excitation import (
    SIGNALS,
    BaseAcceleration,
    NodalForce,
    Signal,
    random_signal_from_psd,
)
from fretwear.dynamics.integrate import DynamicsResult, simulate, stability_limit
from fretwear.dynamics.modal import ModalModel, beam_eigenvalues, uniform_beam_modes
from fretwear.dynamics.shocks import OBSTACLES, Shock, circle_profile

__all__ = [
    "OBSTACLES", "SIGNALS", "BaseAcceleration", "DynamicsResult", "ModalModel", "NodalForce",
    "Shock", "Signal", "beam_eigenvalues", "circle_profile", "random_signal_from_psd",
    "simulate", "stability_limit", "uniform_beam_modes",
]
