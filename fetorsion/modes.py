"""The hand-off between the model stages and the analyses: a set of torsional modes, and the
one builder of a modal damping matrix every model uses (the lumped chain, a network, the
condensed crank).

Both the lumped chain (:meth:`fetorsion.lumped_model.lumped.LumpedResult.torsional_modes`)
and the 3D FE crank (:meth:`fetorsion.fe.crankfe.CrankModal.torsional_modes`) produce a
:class:`TorsionalModes`; the Campbell diagram and the severity of its crossings consume it
without knowing which model it came from.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


#: A mode with at least this share of its kinetic energy in torsion carries torsion: the
#: engine's torque drives it (the report names such modes below the first mostly torsional one).
TORSION_SHARE_NOTED = 0.10
#: The headline f1 of a model whose modes mix torsion with bending (the 3D FE crank, free or in
#: its bearings) is the first mode with at least this share of its kinetic energy in torsion: a
#: coupled mode the engine's torque drives is not skipped for a purer one above it.
F1_TORSION_SHARE = 0.3


def first_with_torsion(frequencies_hz, fractions, share: float, what: str) -> float:
    """The lowest of ``frequencies_hz`` (Hz) whose mode has at least ``share`` of its kinetic
    energy in torsion (``fractions[:, 0]``); ``what`` names the mode set in the error."""
    idx = np.flatnonzero(np.asarray(fractions)[:, 0] >= share)
    if not len(idx):
        from .errors import FetorsionError

        raise FetorsionError(f"no mode with {100 * share:.0f} % torsion among the {len(frequencies_hz)} {what}")
    return float(np.asarray(frequencies_hz)[idx[0]])


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


def modal_damping(M: np.ndarray, shapes: np.ndarray, omegas: np.ndarray, ratio: float) -> np.ndarray:
    """C = M Φ diag(2 ζ ω) Φᵀ M: the damping ratio ``ratio`` on each mode of ``shapes`` (the
    M-orthonormal columns Φ) at its ``omegas`` (rad/s; 0 leaves a mode undamped), and none
    outside their span."""
    MV = M @ shapes
    return (MV * (2.0 * ratio * np.asarray(omegas, float))) @ MV.T


def modal_damping_matrix(M: np.ndarray, K: np.ndarray, ratio: float) -> np.ndarray:
    """C with the damping ratio ``ratio`` on every elastic mode of (K, M); a rigid-body mode
    (ω² within 1e-8 of the largest, as round-off leaves it: a free chain's first mode) stays
    undamped, and a grounded network's first mode, elastic, is damped."""
    import scipy.linalg

    lam, Phi = scipy.linalg.eigh(K, M)  # Φᵀ M Φ = I, eigenvalues ascending
    omega = np.sqrt(np.clip(lam, 0.0, None))
    omega[np.abs(lam) <= 1e-8 * np.abs(lam).max()] = 0.0
    return modal_damping(M, Phi, omega, ratio)
