"""From flow to wear: turbulence spectra, projection onto the modes, time signals, fluid-elastic
stability and a bundle's contact histories from its description (docs/flow.md).

Modules: :mod:`~fretwear.flow.tube` (mode shapes and flow along a tube),
:mod:`~fretwear.flow.spectra` (DEFI_SPEC_TURB families, PROJ_SPEC_BASE; GRAPPE_1 in
:mod:`~fretwear.flow.grappe1`),
:mod:`~fretwear.flow.projection` (joint acceptances), :mod:`~fretwear.flow.synthesis`
(GENE_FONC_ALEA), :mod:`~fretwear.flow.stability` (Connors), :mod:`~fretwear.flow.description`
and :mod:`~fretwear.flow.bundle` (``fretwear simulate``).
"""

from __future__ import annotations

from fretwear.flow.projection import convected_acceptance, exponential_acceptance
from fretwear.flow.spectra import SPECTRA, make_spectrum
from fretwear.flow.tube import TubeFlow, beam_tube_flow

__all__ = ["SPECTRA", "TubeFlow", "beam_tube_flow", "convected_acceptance",
           "exponential_acceptance", "make_spectrum"]
