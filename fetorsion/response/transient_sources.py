"""What excites a time-domain run (:mod:`fetorsion.response.transient`): the engine's cylinders (one
of them misfiring, where asked) and a network's propellers' blade orders, as one load on the
model's coordinates, and the propellers' share of a settled start.

**Cylinders.** Each cylinder's alternating torque is read from its own torque table
(:func:`fetorsion.response.transient_load.torque_table`, through the one load seam
:class:`fetorsion.excitation.loads.CylinderLoads`) at its own firing angle; a misfiring
cylinder's table is its motored cycle's (compression and expansion, no combustion), the others
fire, as in the frequency domain's :meth:`fetorsion.response.forced.ResponseSetup.with_misfire`.

**Propellers.** A propeller of z blades at station s, turning f_s times as fast as station 1,
puts on its station the torque Σ_k T_k(n) cos(k z f_s φ + φ_p), T_k(n) = share_k Q_r (f_s n/n_r)^m
(:func:`fetorsion.response.propulsion.propeller_amplitudes`) read at the mean speed n(t), φ(t)
station 1's mean angle and φ_p the stated phase: the time signal whose phasor the frequency
domain's :func:`fetorsion.response.propulsion.propeller_forces` is (Re of T_k e^{iφ_p} e^{iqφ}).
The torque acts on the network's coordinates through the gear constraint's row of its station,
Tᵀ e_s, like every load of a geared network. The propeller's damping is the station's own (its
absolute damping), so it is in the run's matrices already.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..excitation.loads import cylinder_loads
from ..lumped_model.lumped import lumped
from ..lumped_model.network import speed_factors
from .propulsion import propeller_amplitudes, propeller_orders
from .transient_load import table_load, torque_table


@dataclass(frozen=True)
class RunSources:
    """The run's load and what it is made of.

    ``load(a, b)`` → (coordinates, b − a) N·m at samples a … b − 1; ``W`` (cylinders × coordinates)
    where each cylinder acts, ``fire`` their firing angles (rad), ``grid`` (rpm), ``step`` (rad) and
    ``table`` (cylinders, speeds, samples) the torque tables (:func:`torque_table`), ``misfire`` the 0-based misfiring cylinder or None; ``blades`` [(orders per revolution of station 1, amplitude function rpm → (speeds, k)
    N·m, the station's row on the coordinates)] of each propeller, ``phase_rad`` their φ_p.
    """

    load: object
    W: np.ndarray
    fire: np.ndarray
    grid: np.ndarray
    step: float
    table: np.ndarray
    misfire: int | None = None
    blades: tuple = ()
    phase_rad: float = 0.0

    @property
    def notes(self) -> list[str]:
        """What the load holds beyond the engine's firing, for the run's notes."""
        return ([f"misfire of cylinder {self.misfire + 1} (its motored cycle)"] if self.misfire is not None else []) + (
            ["the propellers' blade orders load the run"] if self.blades else [])


def propeller_blades(net, rings: int) -> tuple:
    """Each propeller with blade-order shares of ``net`` (none for a chain or crank): (orders,
    amplitude function of rpm, its station's row of the gear constraint padded by ``rings``
    damper coordinates)."""
    props = [p for p in getattr(net, "propellers", ()) if p.order_shares]
    if not props:
        return ()
    f = speed_factors(net)
    T = lumped(net).network.T
    return tuple((propeller_orders(p, f[p.station]),
                  lambda rpm, p=p: propeller_amplitudes(p, f[p.station], rpm),
                  np.pad(T[p.station], (0, rings))) for p in props)


def blade_load(blades: tuple, phi: np.ndarray, rpm: np.ndarray, phase_rad: float = 0.0):
    """``load(a, b)`` → (coordinates, b − a): every propeller's Σ_k T_k(n) cos(q_k φ + φ_p) on the
    coordinates (module docs), at samples a … b − 1 of the mean angle ``phi`` (rad) and speed
    ``rpm``."""
    def load(a, b):
        out = 0.0
        for orders, amplitude, row in blades:
            amp = amplitude(rpm[a:b])  # (samples, k)
            wave = (amp * np.cos(np.outer(phi[a:b], orders) + phase_rad)).sum(axis=1)
            out = out + np.outer(row, wave)
        return out

    return load


def run_sources(model, setup, rings: int, speeds: tuple[float, float], phi: np.ndarray, rpm: np.ndarray,
                misfire: int | None = None, propellers: bool = True, phase_rad: float = 0.0) -> RunSources:
    """The run's load: its cylinders (``misfire``: that 0-based cylinder on its motored cycle) and,
    with ``propellers``, a network's blade orders (module docs).

    Parameters
    ----------
    model : Crank, Chain or Network
        With ``[engine]`` and ``[excitation]``.
    setup : ResponseSetup
        The model's response setup (its ``load_map``: where the cylinders act).
    rings : int
        Damper ring coordinates after the setup's (no cylinder or propeller acts on them).
    speeds : (float, float)
        The run's lowest and highest speed, rpm (the torque tables' range).
    phi, rpm : ndarray (N,)
        Station 1's mean angle (rad) and speed (rpm) at every sample.
    misfire : int, optional
        The misfiring cylinder, 0-based.
    propellers : bool
        Whether the propellers' blade orders load the run.
    phase_rad : float
        φ_p of every blade order, rad.
    """
    lo, top = speeds
    grid, step, table = torque_table(model, lo, top, misfire=misfire)
    W = np.pad(setup.load_map[:, 0, :].real, ((0, 0), (0, rings)))  # (cylinders, coordinates)
    fire = cylinder_loads(model).firing
    engine = table_load(W, fire, grid, step, table, phi, rpm)
    blades = propeller_blades(model, rings) if propellers else ()
    if not blades:
        return RunSources(engine, W, fire, grid, step, table, misfire)
    screws = blade_load(blades, phi, rpm, phase_rad)
    return RunSources(lambda a, b: engine(a, b) + screws(a, b), W, fire, grid, step, table, misfire, blades,
                      phase_rad)


def blade_state(M, K, C, blades: tuple, rpm: float, phi0: float, phase_rad: float = 0.0):
    """(q, q̇) at mean angle ``phi0`` (rad) of the propellers' steady state at constant ``rpm``:
    each blade order q_k at ω = q_k Ω, Z = (K − ω² M + iωC)⁻¹ T_k e^{iφ_p} row, q = Re(Z e^{i q_k φ₀}),
    q̇ = Re(iω Z e^{i q_k φ₀}); zeros without propellers. Added to the cylinders' periodic state, the
    settled start of a run whose load has both (the response is linear)."""
    q, v = np.zeros(len(M)), np.zeros(len(M))
    for orders, amplitude, row in blades:
        amp = amplitude(np.array([rpm]))[0]
        for qk, a in zip(orders, amp):
            w = qk * rpm * np.pi / 30
            Z = np.linalg.solve(K - w * w * M + 1j * w * C, a * np.exp(1j * phase_rad) * row)
            e = np.exp(1j * qk * phi0)
            q, v = q + np.real(Z * e), v + np.real(1j * w * Z * e)
    return q, v
