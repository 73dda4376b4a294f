"""The hand-off between the model stages and the analyses: a set of torsional modes.

Both the lumped chain (:meth:`fetorsion.lumped_model.lumped.LumpedResult.torsional_modes`)
and the 3D FE crank (:meth:`fetorsion.fe.crankfe.CrankModal.torsional_modes`) produce a
:class:`TorsionalModes`; the Campbell diagram and the severity of its crossings consume it
without knowing which model it came from.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class TorsionalModes:
    """What the Campbell severity needs of a set of torsional modes, SI units.

    ``pin_amplitudes[j, c]`` is mode j's twist at the pin of cylinder c, ``pulley_amplitude[j]``
    its twist at the pulley, ``modal_inertia[j]`` = φ_jᵀ M φ_j with the same scaling;
    ``labels[j]``, when given, says what kind of mode it is (a coupled model's torsion and
    bending shares).
    """

    source: str
    frequencies_hz: np.ndarray
    pin_amplitudes: np.ndarray
    pulley_amplitude: np.ndarray
    modal_inertia: np.ndarray
    labels: tuple[str, ...] = ()
