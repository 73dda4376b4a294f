"""The propeller's blade-order excitation in a network's forced response (docs/propulsion-tvc.md).

A propeller of z blades at station s, turning f_s times as fast as station 1 (the speed the
response is swept over), excites the orders k z f_s of station 1's speed (k = 1, 2, …) with a
torque amplitude share_k × Q(f_s Ω), Q the propeller law Q_r (ω / ω_r)^n of its rated point
(:class:`fetorsion.description.marine.Propeller`). The torque acts on the station's own angle, so on
the network's coordinates q (θ = T q) as Tᵀ e_s: the virtual work of the constraint forces
vanishes, as for every other load of :mod:`fetorsion.lumped_model.network`.

**Phase.** An engine's orders carry their phase against station 1's angle θ = 0 at cylinder 1's
firing top dead centre. A propeller's blade-order torque is taken as share × Q × cos(k z θ_s + φ):
blade 1 at its reference angle (φ = 0 by default) when station 1 is at θ = 0. How the propeller is
keyed to its shaft against the crank is not known to a TVC, so where an engine order and a blade
order coincide (a direct drive) the sum holds for that stated phase only; :func:`with_propellers`
takes φ as ``phase_rad`` so the worst may be sought.

**Synthesis.** The orders of an engine (multiples of 2π / its cycle) and of a geared propeller
(multiples of z f_s) need not share a period. Where their fundamentals are in a ratio p/q with
q, p ≤ :data:`COMMENSURATE_DENOMINATOR`, the signal has the common period and is synthesised over
it with the stated phases. Otherwise the two sources' relative phase takes every value in a long
run (their frequencies rationally independent: Kronecker's theorem), so the signal's supremum is
the sum of each source's own maximum (and its infimum of their minima): the groups of
``ResponseSetup.order_groups`` (:func:`fetorsion.response.synthesis.grouped_extremes`).
"""

from __future__ import annotations

import math
from dataclasses import replace
from fractions import Fraction

import numpy as np

from ..description.chain_model import Network
from ..description.defaults import DEFAULT_DAMPING_RATIO, DEFAULT_SPEED_STEPS
from ..description.marine import Propeller, law_torque
from ..errors import FetorsionError
from ..lumped_model.lumped import lumped, stated_damping
from ..lumped_model.network import group_place, network_damper_dof, rear_coordinate, speed_factors
from ..modes import modal_damping_matrix
from .forced import ResponseSetup, response_setup

#: Largest numerator and denominator of the ratio of two sources' fundamental orders for which
#: they are synthesised over one common period (a longer common period is treated as none).
COMMENSURATE_DENOMINATOR = 12
#: The speed ratios (of the first propeller's rated speed) a network without an engine is swept
#: over by default: from a low manoeuvring speed to the top of the rule's range λ = 1.05.
DEFAULT_SPEED_RATIOS = (0.2, 1.05)


def propeller_orders(propeller: Propeller, factor: float) -> np.ndarray:
    """The orders k z f (k = 1 … the stated shares) of a propeller turning ``factor`` (f) times as
    fast as station 1, per revolution of station 1."""
    return propeller.blades * factor * np.arange(1, len(propeller.order_shares) + 1, dtype=float)


def propeller_amplitudes(propeller: Propeller, factor: float, rpm: np.ndarray) -> np.ndarray:
    """(speeds, shares) blade-order torque amplitudes, N·m: each share of the law's mean torque at
    the propeller's own speed f × ``rpm`` (rpm of station 1).

    Parameters
    ----------
    propeller : Propeller
        With ``order_shares``, ``rated_torque`` (N·m), ``rated_speed`` (rad/s) and ``exponent``.
    factor : float
        f: the propeller's speed over station 1's.
    rpm : ndarray
        Station 1's speeds, rpm.
    """
    omega = factor * np.asarray(rpm, dtype=float) * math.pi / 30.0
    q = law_torque(propeller.rated_torque, propeller.rated_speed, omega, propeller.exponent)
    return q[:, None] * np.asarray(propeller.order_shares, dtype=float)[None, :]


def propeller_forces(net: Network, T: np.ndarray, rpm: np.ndarray, orders: np.ndarray,
                     phase_rad: float = 0.0) -> np.ndarray:
    """(speeds, orders, coordinates) complex torques of every propeller's blade orders on the
    network's coordinates q (θ = T q), N·m; zero at the orders no propeller excites.

    Parameters
    ----------
    net : Network
        With its ``propellers``.
    T : ndarray (stations, coordinates)
        The gear constraint (:func:`fetorsion.lumped_model.network.gear_constraint`).
    rpm : ndarray
        Station 1's speeds, rpm.
    orders : ndarray
        The response's orders (per revolution of station 1); each blade order must be one of them.
    phase_rad : float
        φ of every blade order's torque cos(k z θ_s + φ), rad (module docs).
    """
    f = speed_factors(net)
    out = np.zeros((len(rpm), len(orders), T.shape[1]), dtype=complex)
    for p in net.propellers:
        amp = propeller_amplitudes(p, f[p.station], rpm) * np.exp(1j * phase_rad)
        for k, q in enumerate(propeller_orders(p, f[p.station])):
            out[:, _order_index(orders, q), :] += amp[:, k, None] * T[p.station][None, :]
    return out


def _order_index(orders: np.ndarray, q: float) -> int:
    """Where order ``q`` is among ``orders`` (to 1e-9 relative)."""
    hit = np.flatnonzero(np.isclose(orders, q, rtol=1e-9, atol=0.0))
    if not hit.size:
        raise FetorsionError(f"order {q:g} is not among the response's orders")
    return int(hit[0])


def common_period(first: float, second: float) -> float | None:
    """The common period (rad of station 1) of two sources with fundamental orders ``first`` and
    ``second`` (per revolution), or None when their ratio is no p/q with p, q ≤
    :data:`COMMENSURATE_DENOMINATOR` (to 1e-9)."""
    ratio = Fraction(first / second).limit_denominator(COMMENSURATE_DENOMINATOR)
    if ratio.numerator > COMMENSURATE_DENOMINATOR or abs(float(ratio) * second / first - 1.0) > 1e-9:
        return None
    # first = p b and second = q b for the common fundamental b = first / p: period 2π / b
    return 2.0 * math.pi * ratio.numerator / first


def order_groups(sources: list[tuple[np.ndarray, float]], orders: np.ndarray) -> list[tuple[np.ndarray, float]]:
    """The sources (each its orders and fundamental order) merged where commensurate
    (:func:`common_period`): [(indices into ``orders``, period rad)], one per incommensurate group."""
    groups: list[tuple[list[float], float]] = []  # (orders, fundamental)
    for qs, base in sources:
        for g, (members, gbase) in enumerate(groups):
            period = common_period(gbase, base)
            if period is not None:
                groups[g] = (members + list(qs), 2.0 * math.pi / period)
                break
        else:
            groups.append((list(qs), base))
    return [(np.array(sorted({_order_index(orders, q) for q in members})), 2.0 * math.pi / base)
            for members, base in groups]


def with_propellers(setup: ResponseSetup, net: Network, phase_rad: float = 0.0) -> ResponseSetup:
    """``setup`` (an engine's, :func:`fetorsion.response.forced.response_setup`, or the bare one of
    :func:`propeller_setup`) with every propeller's blade orders added: the orders merged (an
    order both excite carries both torques, summed with the stated phases), the engine's
    harmonics zero at the blade orders it lacks, and the synthesis period or groups
    (module docs).

    Parameters
    ----------
    setup : ResponseSetup
        Of ``net``, in its coordinates.
    net : Network
        With ``propellers``.
    phase_rad : float
        φ of the blade orders (module docs), rad.
    """
    f = speed_factors(net)
    blade = [propeller_orders(p, f[p.station]) for p in net.propellers]
    engine = setup.orders
    orders = np.array(sorted(set(setup.orders.tolist()) | {float(q) for qs in blade for q in qs}))
    old = np.array([_order_index(orders, q) for q in setup.orders], dtype=int)

    # (speeds, orders, …) onto the merged orders, zero elsewhere: a cylinder has no harmonic and
    # no phasor at a blade order (so a misfire's change, motored minus firing, adds none there)
    def widened(a: np.ndarray) -> np.ndarray:
        out = np.zeros(a.shape[:1] + (len(orders),) + a.shape[2:], dtype=a.dtype)
        out[:, old] = a
        return out

    T = lumped(net).network.T
    forces = widened(setup.forces) + propeller_forces(net, T, setup.rpm, orders, phase_rad)
    extra = None if setup.projected or not any(p.damping_each_speed for p in net.propellers) else \
        law_damping_by_speed(net, T, f, setup.rpm, setup.M.shape[0])
    sources = ([(np.asarray(engine, float), 2.0 * math.pi / setup.period)] if len(engine) else []) + [
        (qs, qs[0]) for qs in blade if len(qs)]
    groups = order_groups(sources, orders)
    period = groups[0][1] if len(groups) == 1 else setup.period
    return replace(setup, orders=orders, forces=forces, cylinder_harmonics=widened(setup.cylinder_harmonics),
                   phasors=widened(setup.phasors[None])[0], period=period,
                   order_groups=None if len(groups) == 1 else tuple(groups),
                   speed_damping=extra if setup.speed_damping is None or extra is None else setup.speed_damping + extra)


def law_damping_by_speed(net: Network, T: np.ndarray, factors: np.ndarray, rpm: np.ndarray, size: int) -> np.ndarray:
    """(speeds, coordinates) damping to ground each propeller adds at each speed of station 1 (rpm)
    beyond the one the network holds (its law's at ``damping_speed_rpm``), N·m·s/rad referred to its
    gear group's coordinate (× f², f its station's speed over the coordinate's): the law's damping
    c = n Q(ω)/ω taken at the propeller's own speed at every speed of the sweep, not at one speed
    held at all (a resonance below the linearisation speed was damped too much: by ω_lin/ω at n = 2).
    ``factors``: each station's speed over station 1's (:func:`speed_factors`)."""
    out = np.zeros((len(rpm), size))
    omega = np.asarray(rpm, float) * math.pi / 30.0
    for p in net.propellers:
        if not p.damping_each_speed:  # the file names its linearisation speed: held there
            continue
        col, f2 = group_place(T, p.station)
        own = omega * abs(factors[p.station])
        out[:, col] += f2 * (np.array([p.damping(w) for w in own]) - p.damping(p.damping_speed))
    return out


def propeller_setup(net: Network, rpm: np.ndarray | None = None, damping_ratio: float | None = None,
                    phase_rad: float = 0.0) -> ResponseSetup:
    """The forced-response setup of a network excited by its propellers, with its engine's
    excitation where it has one (:func:`with_propellers` of the engine's
    :func:`~fetorsion.response.forced.response_setup`), else by its propellers alone (a turbine's
    or an electric motor's line).

    Parameters
    ----------
    net : Network
        With at least one propeller with ``blade_order_shares``.
    rpm : array_like, optional
        Station 1's speeds, rpm; default the engine's range, or for a line without an engine
        :data:`DEFAULT_SPEED_RATIOS` of the first propeller's rated speed (referred to station 1).
    damping_ratio : float, optional
        Modal damping ratio ζ on every elastic mode; default the ``[excitation]`` table's, or
        :data:`~fetorsion.description.defaults.DEFAULT_DAMPING_RATIO` without one.
    phase_rad : float
        φ of the blade orders (module docs), rad.
    """
    if not any(p.order_shares for p in net.propellers):
        raise FetorsionError(f"{net.source or net.name}: no propeller states blade_order_shares")
    if net.excitation is not None:
        return with_propellers(response_setup(net, rpm=rpm, damping_ratio=damping_ratio), net, phase_rad)
    return with_propellers(_bare_setup(net, rpm, damping_ratio), net, phase_rad)


def _bare_setup(net: Network, rpm, damping_ratio: float | None) -> ResponseSetup:
    """A setup of the network's matrices with no force yet and no cylinder: the propellers add theirs."""
    res = lumped(net)
    M, K = res.matrices()
    zeta = DEFAULT_DAMPING_RATIO if damping_ratio is None else damping_ratio
    C_stated, H = stated_damping(net, res)
    C = modal_damping_matrix(M, K, zeta) + C_stated
    if rpm is None:
        p = next(p for p in net.propellers if p.order_shares)
        rated = p.rated_speed * 30.0 / math.pi / speed_factors(net)[p.station]
        rpm = np.linspace(DEFAULT_SPEED_RATIOS[0] * rated, DEFAULT_SPEED_RATIOS[1] * rated, DEFAULT_SPEED_STEPS)
    rpm = np.asarray(rpm, dtype=float)
    r = M.shape[0]
    orders = np.zeros(0)
    flywheel = rear_coordinate(net, res.network.masters)
    dampers_at, dampers_scale = network_damper_dof(net, res.network, flywheel)
    return ResponseSetup(net.name, res.labels, M, K + 1j * H, C, np.zeros((len(rpm), 0, r), complex), rpm, orders,
                         2.0 * math.pi, zeta, "stated dampers of the network" if net.has_dampers else "", None,
                         np.zeros((len(rpm), 0, 1)), np.zeros((0, 0), complex), np.zeros((0, 1, r)),
                         res.network.section_rows, list(res.network.section_labels), positions_m=res.positions_m,
                         pulley=0, flywheel=flywheel,
                         model=f"network of {len(res.network.labels)} stations", stiffnesses=res.stiffnesses_nm_per_rad,
                         damper_dof=dampers_at, damper_scale=dampers_scale)


def tvc_setup(net: Network) -> ResponseSetup:
    """The network's forced-response setup for a TVC: its propellers' blade orders with its engine's
    where it has both (:func:`propeller_setup`), its engine's alone without a propeller's shares."""
    if any(p.order_shares for p in net.propellers):
        return propeller_setup(net)
    return response_setup(net)


def damping_at(net: Network, rpm: float) -> Network:
    """``net`` with each propeller whose damping follows the speed (``damping_each_speed``) damped by its
    law at station 1's ``rpm`` (its station's own speed) instead of at its linearisation speed: the one
    constant damping a time-domain run can take (a steady run at that speed exactly; a passage at the
    speed it is judged at). Unchanged without such a propeller."""
    if not any(p.damping_each_speed for p in net.propellers):
        return net
    f = speed_factors(net)
    absolute, props = list(net.absolute_damping), []
    for p in net.propellers:
        if p.damping_each_speed:
            w = rpm * math.pi / 30.0 * abs(f[p.station])
            absolute[p.station] += p.damping(w) - p.damping(p.damping_speed)
            p = replace(p, damping_speed=w)
        props.append(p)
    return replace(net, absolute_damping=tuple(absolute), propellers=tuple(props))


def run_damping(model: object, rpm: float | None) -> tuple[object, list[str]]:
    """(the model a time-domain run takes, its note): a network whose propellers' law damping follows
    the speed, damped at a steady run's ``rpm`` as the frequency domain is there; a run over a range
    holds the one at their stated or rated speed, and says so. Any other model as it is."""
    if not any(p.damping_each_speed for p in getattr(model, "propellers", ())):
        return model, []
    if rpm is not None:
        return damping_at(model, rpm), []
    return model, ["the propellers' law damping held at one speed, their stated or rated one (the frequency domain "
                   "takes it at each speed)"]

