"""Cylinder pressure, cylinder torque and its harmonic orders ([Kazemi] eq. 13–19, exact).

Angles: θ is the crank angle of a cylinder measured from its *firing* TDC, over one
working cycle (720° for a 4-stroke, 360° for a 2-stroke). Cylinder c fires
``firing_angles(engine)[c]`` after cylinder 1.

The synthetic 4-stroke cycle: intake and exhaust strokes at the intake pressure; from
BDC before firing to BDC after it the charge is closed, with one polytropic exponent n
and a Wiebe heat release, whose first law d(pVⁿ) = (n − 1) Vⁿ⁻¹ dQ integrates in closed
form: p Vⁿ = p₀ V₀ⁿ + (n − 1) ∫ Vⁿ⁻¹ dQ. Pressure is affine in the heat released, so the
heat is scaled exactly to the requested IMEP (or, by root-finding, the peak pressure).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
import numpy as np

from ..description.model import Crank, Engine, Excitation
from ..errors import FetorsionError
from .kinematics import pin_forces, piston_acceleration, piston_position, tangential_torque

SAMPLES_PER_CYCLE = 1440  # 0.5° for a 4-stroke: resolves orders up to 360 (Nyquist)


def cycle_angle(engine: Engine) -> float:
    """Length of one working cycle in crank rad: 4π (4-stroke) or 2π (2-stroke)."""
    return 2 * np.pi * engine.strokes_per_cycle / 2


def cycle_grid(engine: Engine, samples: int = SAMPLES_PER_CYCLE) -> np.ndarray:
    """Uniform crank angles over one cycle starting at firing TDC, rad (endpoint excluded)."""
    return np.arange(samples) * (cycle_angle(engine) / samples)


def firing_angles(engine: Engine) -> np.ndarray:
    """Crank angle (rad) at which each cylinder (index 0..N-1) fires, cylinder 1 at 0; see
    :meth:`fetorsion.description.model.Engine.firing_angles` (a description is checked
    against it when read, so only a hand-built Engine can fail here)."""
    try:
        return np.array(engine.firing_angles())
    except ValueError as exc:
        raise FetorsionError(f"engine.firing_order {list(engine.firing_order)}: {exc} "
                             "with these crank_angles_deg") from None


def cylinder_volume(theta, engine: Engine, compression_ratio: float) -> np.ndarray:
    """Cylinder volume (m³) at crank angle θ from TDC."""
    area = math.pi / 4 * engine.bore**2
    r, l = engine.crank_radius, engine.rod_length
    clearance = area * engine.stroke / (compression_ratio - 1.0)
    return clearance + area * (r + l - piston_position(theta, r, l))


def _closed_cycle_parts(theta, engine: Engine, ex: Excitation):
    """Motored pressure and pressure per joule of heat (both Pa) on the grid ``theta``."""
    # Unwrap to [−π, 3π): the closed part runs from BDC before firing (−π) to BDC after (π).
    phi = np.where(theta >= 3 * np.pi, theta - 4 * np.pi, theta)
    closed = np.abs(phi) <= np.pi
    n = ex.polytropic_exponent
    order = np.argsort(phi)
    ph = phi[order]
    V = cylinder_volume(ph, engine, ex.compression_ratio)
    V0 = cylinder_volume(-np.pi, engine, ex.compression_ratio)
    x = np.clip((ph - ex.combustion_start) / ex.combustion_duration, 0.0, None)
    burned = 1.0 - np.exp(-ex.wiebe_a * x ** (ex.wiebe_m + 1.0))
    # p Vⁿ = p₀V₀ⁿ + (n−1) ∫ Vⁿ⁻¹ dQ, with Q = 1 J · burned fraction.
    import scipy.integrate  # here, not at the top: 0.3 s that every CLI command paid at start-up

    integral = scipy.integrate.cumulative_trapezoid(V ** (n - 1.0), burned, initial=0.0)
    motored = ex.intake_pressure * (V0 / V) ** n
    per_joule = (n - 1.0) * integral / V**n
    back = np.empty_like(order)
    back[order] = np.arange(len(order))
    motored, per_joule = motored[back], per_joule[back]
    return np.where(closed, motored, ex.intake_pressure), np.where(closed, per_joule, 0.0)


def _imep(theta, p, engine: Engine, ex: Excitation) -> float:
    V = cylinder_volume(theta, engine, ex.compression_ratio)
    work = np.sum(0.5 * (p + np.roll(p, -1)) * (np.roll(V, -1) - V))
    return work / (math.pi / 4 * engine.bore**2 * engine.stroke)


def cylinder_pressure(crank: Crank, rpm: float, theta=None, misfire: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Absolute cylinder pressure (Pa) over one cycle at ``rpm``: (θ rad, p Pa).

    From the description's pressure CSV if it has one (interpolated periodically), else
    the synthetic cycle scaled to the load at ``rpm``. ``misfire``: the cylinder does not
    fire: the synthetic cycle's compression and expansion alone (the motored pressure).
    """
    engine, ex = crank.engine, _excitation_of(crank)
    theta = cycle_grid(engine) if theta is None else np.asarray(theta, dtype=float)
    if ex.tangential_harmonics:
        raise FetorsionError("the excitation is given by tangential-pressure harmonics: no cylinder pressure curve "
                             "(nor a motored cycle for a misfire, nor a radial pin force) is known")
    if misfire:
        if not (ex.compression_ratio > 1 and engine.bore > 0):
            raise FetorsionError("a misfire needs the synthetic cycle (excitation.compression_ratio and engine.bore): "
                                 "the motored pressure of a measured pressure_csv is not known")
        return theta, _closed_cycle_parts(theta, engine, ex)[0]
    if ex.pressure_curve is not None:
        ang, p = (np.asarray(v) for v in ex.pressure_curve)
        return theta, np.interp(theta, ang, p, period=cycle_angle(engine))
    if engine.strokes_per_cycle != 4:
        raise FetorsionError("the synthetic cycle is a 4-stroke cycle; give excitation.pressure_csv for a 2-stroke")
    if not engine.bore > 0:
        raise FetorsionError("engine.bore is needed for the gas force")
    target = ex.running_imep(rpm) if ex.load_kind == "propeller_imep" else float(np.interp(rpm, *zip(*ex.load)))
    motored, per_joule = _closed_cycle_parts(theta, engine, ex)
    if ex.load_kind in ("imep", "propeller_imep"):
        q = (target - _imep(theta, motored, engine, ex)) / _imep(theta, per_joule, engine, ex)
    else:
        if motored.max() >= target:
            raise FetorsionError(f"excitation.peak_pressure_pa {target:.4g} Pa is below the motored peak "
                                 f"{motored.max():.4g} Pa")
        import scipy.optimize  # see scipy.integrate above

        q = scipy.optimize.brentq(lambda h: (motored + h * per_joule).max() - target, 0.0, 1e7)
    if q < 0:
        raise FetorsionError(f"excitation.imep_pa {target:.4g} Pa is below the motored IMEP")
    return theta, motored + q * per_joule


def _excitation_of(crank: Crank) -> Excitation:
    if crank.excitation is None:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [excitation] table")
    return crank.excitation


@dataclass(frozen=True)
class CycleTorque:
    """A torque over one working cycle on a grid of crank angles.

    Attributes
    ----------
    theta : ndarray
        Crank angle from cylinder 1's firing TDC, rad.
    total : ndarray
        The torque, N·m (gas and reciprocating inertia).
    gas, inertia : ndarray or None
        Its parts, N·m, where they are kept apart (one cylinder's).
    """

    theta: np.ndarray
    total: np.ndarray
    gas: np.ndarray | None = None
    inertia: np.ndarray | None = None


def cylinder_torque(crank: Crank, rpm: float, theta: np.ndarray | None = None, misfire: bool = False) -> CycleTorque:
    """Torque of one cylinder on the crank over a cycle at constant ``rpm``, N·m.

    Returns the angles ``theta`` (rad from firing TDC) and the ``gas``, ``inertia`` and
    ``total`` torque: the gas force A (p − p_intake) and the reciprocating inertia force m S̈
    act together on the pin through the exact rod geometry, T = r F sin(θ + β)/cos β.
    ``misfire``: the cylinder does not fire (compression and expansion only,
    :func:`cylinder_pressure`).
    """
    engine, ex = crank.engine, _excitation_of(crank)
    r, l = engine.crank_radius, engine.rod_length
    omega = rpm * 2 * np.pi / 60
    if ex.tangential_harmonics and (not misfire or has_motored_column(ex)):
        # a misfiring cylinder is motored: the maker's misfire harmonics, else the table's column at p_mi 0
        theta = cycle_grid(engine) if theta is None else np.asarray(theta, dtype=float)
        pt = (misfire_pressure(ex, theta) if misfire and ex.misfire_harmonics else
              tangential_pressure(ex, engine, rpm, theta, 0.0 if misfire else None))
        gas = math.pi / 4 * engine.bore**2 * r * pt
        inertia = tangential_torque(theta, ex.reciprocating_mass * piston_acceleration(theta, r, l, omega), r, l)
        return CycleTorque(theta, gas + inertia, gas, inertia)
    theta, p = cylinder_pressure(crank, rpm, theta, misfire)
    gas_force = math.pi / 4 * engine.bore**2 * (p - ex.intake_pressure)
    inertia_force = ex.reciprocating_mass * piston_acceleration(theta, r, l, omega)
    return CycleTorque(theta, tangential_torque(theta, gas_force + inertia_force, r, l),
                       tangential_torque(theta, gas_force, r, l), tangential_torque(theta, inertia_force, r, l))


def harmonic_coefficients(ex: Excitation, imep_pa: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(orders, sine a_q Pa, cosine b_q Pa) of a tangential-pressure harmonic table read at a mean
    indicated pressure: linear between the table's p_mi columns, held outside them."""
    orders = np.array([q for q, _, _ in ex.tangential_harmonics])
    sine = np.array([np.interp(imep_pa, ex.harmonic_imep, a) for _, a, _ in ex.tangential_harmonics])
    cosine = np.array([np.interp(imep_pa, ex.harmonic_imep, b) for _, _, b in ex.tangential_harmonics])
    return orders, sine, cosine


#: Why a misfire cannot be computed from a harmonic table without its motored column.
MOTORED_COLUMN_MISSING = ("misfire not computed: the tangential-pressure harmonic table has neither misfire_sine "
                          "and misfire_cosine (the engine maker's misfire harmonics) nor a column at harmonic_imep_pa "
                          "0 (the motored cylinder's); add one")


def has_motored_column(ex: Excitation) -> bool:
    """The harmonic table says what a misfiring cylinder does: the maker's misfire harmonics, or a column at
    p_mi 0 (the motored cylinder's harmonics at no-load boost, as [Porter1943]'s a + b p_mi give at p_mi 0)."""
    return bool(ex.tangential_harmonics) and (bool(ex.misfire_harmonics) or (
        len(ex.harmonic_imep) > 0 and ex.harmonic_imep[0] == 0.0))


def misfire_pressure(ex: Excitation, theta: np.ndarray) -> np.ndarray:
    """p_t(θ) of the misfiring cylinder from the maker's misfire harmonics, Pa: Σ_q a_q sin qθ + b_q cos qθ
    (a motored cylinder does no indicated work: no mean)."""
    q, a, b = (np.array(c, dtype=float)[:, None] for c in zip(*ex.misfire_harmonics))
    th = np.asarray(theta, dtype=float)[None, :]
    return (a * np.sin(q * th) + b * np.cos(q * th)).sum(axis=0)


def tangential_pressure(ex: Excitation, engine: Engine, rpm: float, theta: np.ndarray,
                        imep: float | None = None) -> np.ndarray:
    """p_t(θ), Pa: the gas force's tangential share per unit piston area, referred to the crank
    radius (the gas torque is p_t A r), from the harmonic table at the load's p_mi at ``rpm``
    (:meth:`~fetorsion.description.model.Excitation.running_imep`) or at ``imep`` (Pa) where given: its
    mean p_mi V_s / (A r Φ) = 2 p_mi / Φ (the indicated work p_mi V_s over the cycle Φ rad, V_s = 2 r A),
    and Σ_q a_q sin qθ + b_q cos qθ."""
    imep = ex.running_imep(rpm) if imep is None else imep
    orders, sine, cosine = harmonic_coefficients(ex, imep)
    q = orders[:, None] * np.asarray(theta, dtype=float)[None, :]
    return 2.0 * imep / cycle_angle(engine) + (sine[:, None] * np.sin(q) + cosine[:, None] * np.cos(q)).sum(axis=0)


@dataclass(frozen=True)
class Harmonics:
    """Harmonic orders of a periodic torque: T(θ) = mean + Re Σ_q T_q e^{i q θ}.

    ``orders`` in multiples of crank speed (0.5, 1, 1.5 ... for a 4-stroke), ``complex_nm``
    the complex amplitudes T_q (N·m), so the amplitude is |T_q| and the phase arg T_q.
    """

    orders: np.ndarray
    complex_nm: np.ndarray
    mean_nm: float

    @property
    def amplitude_nm(self) -> np.ndarray:
        return np.abs(self.complex_nm)

    @property
    def phase_rad(self) -> np.ndarray:
        return np.angle(self.complex_nm)

    def at(self, orders) -> np.ndarray:
        """Complex amplitudes of the given orders (0 where the order is not present)."""
        idx = np.rint(np.asarray(orders, dtype=float) / self.orders[0]).astype(int) - 1
        ok = (idx >= 0) & (idx < len(self.orders))
        return np.where(ok, self.complex_nm[np.clip(idx, 0, len(self.orders) - 1)], 0.0)


def harmonics(torque: np.ndarray, period: float) -> Harmonics:
    """Orders of a torque sampled uniformly over one ``period`` (rad), any last-axis length.

    Order q means q oscillations per crank revolution; the lowest present is 2π/period.
    """
    torque = np.asarray(torque, dtype=float)
    n = torque.shape[-1]
    c = np.fft.rfft(torque, axis=-1) / n
    base = 2 * np.pi / period
    amps = 2 * c[..., 1:]
    if n % 2 == 0:  # the Nyquist bin is real and not doubled
        amps[..., -1] /= 2
    return Harmonics(base * np.arange(1, amps.shape[-1] + 1), amps, float(np.real(c[..., 0]).mean()))


def cylinder_pin_forces(crank: Crank, rpm: float, misfire: bool = False) -> dict[str, np.ndarray]:
    """Tangential and radial force on cylinder 1's pin over a cycle at ``rpm`` (N), from its gas
    force and reciprocating inertia, and the centrifugal force of the rod's rotating big end
    (``rotating_mass``: a constant outwards, so only the mean has it); ``theta`` rad from firing
    TDC. ``misfire``: the cylinder does not fire (its motored cycle)."""
    ex = crank.excitation
    theta, p = cylinder_pressure(crank, rpm, misfire=misfire)
    e = crank.engine
    omega = rpm * 2 * np.pi / 60
    force = math.pi / 4 * e.bore**2 * (p - ex.intake_pressure) \
        + ex.reciprocating_mass * piston_acceleration(theta, e.crank_radius, e.rod_length, omega)
    f = pin_forces(theta, force, e.crank_radius, e.rod_length)
    radial = f["radial"] + ex.rotating_mass * e.crank_radius * omega**2
    return {"theta": theta, "tangential": f["tangential"], "radial": radial}


def articulated_link(engine: Engine):
    """The :class:`~fetorsion.excitation.articulated.ArticulatedLink` of an engine with master and
    articulated rods: its crank radius, master rod, knuckle, articulated rod and bank angle."""
    from .articulated import ArticulatedLink

    a = engine.articulation
    bank = next(b for b in engine.bank_angles if b != 0.0)
    return ArticulatedLink(engine.crank_radius, engine.rod_length, a.knuckle_radius, a.knuckle_angle, a.rod_length,
                           bank)


def articulated_piston_force(crank: Crank, rpm: float, theta: np.ndarray | None = None, misfire: bool = False):
    """(θ, F, link): an articulated cylinder's piston force F (N, towards the crank: gas A (p − p_intake)
    and reciprocating inertia m s̈, s its distance from the crank axis) over its cycle, θ rad from its nominal TDC (its throw's angle
    plus the bank angle, where a side-by-side rod's would be). Its own TDC lies
    :meth:`~fetorsion.excitation.articulated.ArticulatedLink.tdc_shift` later: its pressure curve
    (the engine's one curve, on the crank angle from the cylinder's own TDC) is shifted by it. The
    synthetic cycle's volume stays the slider-crank's: the articulated stroke differs from it by
    parts in ten thousand (docs/vee-engines.md)."""
    engine, ex = crank.engine, _excitation_of(crank)
    if ex.tangential_harmonics:
        raise FetorsionError("engine.rods = \"articulated\": the tangential-pressure harmonics are one slider-crank's; "
                             "give the articulated cylinders a pressure curve (imep_pa, peak_pressure_pa or pressure_csv)")
    link = articulated_link(engine)
    grid, p = cylinder_pressure(crank, rpm, misfire=misfire)
    theta = grid if theta is None else np.asarray(theta, dtype=float)
    p = np.interp(theta - link.tdc_shift(), grid, p, period=cycle_angle(engine))
    omega = rpm * 2 * np.pi / 60
    s2 = link.path(theta + link.bank)[2]
    return theta, math.pi / 4 * engine.bore**2 * (p - ex.intake_pressure) + ex.reciprocating_mass * s2 * omega**2, link


def articulated_cylinder_torque(crank: Crank, rpm: float, theta: np.ndarray | None = None,
                                misfire: bool = False) -> CycleTorque:
    """An articulated cylinder's torque on the crank over its cycle (:func:`articulated_piston_force`):
    T = F (−s′) by virtual work, gas and inertia apart."""
    engine, ex = crank.engine, _excitation_of(crank)
    theta, force, link = articulated_piston_force(crank, rpm, theta, misfire)
    _, s1, s2 = link.path(theta + link.bank)
    inertia = ex.reciprocating_mass * s2 * (rpm * 2 * np.pi / 60) ** 2 * -s1
    return CycleTorque(theta, force * -s1, (force * -s1) - inertia, inertia)


def articulated_pin_forces(crank: Crank, rpm: float, misfire: bool = False) -> dict[str, np.ndarray]:
    """An articulated cylinder's force on its throw's pin through the master rod over its cycle
    (θ rad from its nominal TDC; ``tangential``, ``radial`` N), with its rod's rotating big-end mass
    at the pin as :func:`cylinder_pin_forces` takes it (the knuckle's small circle about the pin
    neglected)."""
    theta, force, link = articulated_piston_force(crank, rpm, misfire=misfire)
    f = link.pin_forces(theta + link.bank, force)
    e, ex = crank.engine, crank.excitation
    radial = f["radial"] + ex.rotating_mass * e.crank_radius * (rpm * 2 * np.pi / 60) ** 2
    return {"theta": theta, "tangential": f["tangential"], "radial": radial}
