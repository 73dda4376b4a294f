"""A propulsion line's components as a class society's torsional vibration calculation (TVC) states
them: a shaft section's design feature (the rule's factor C_K), the propeller (inertia with its
entrained water, damping by a named model, blade-order excitation) and a flexible coupling from
its maker's data sheet. Pure data and arithmetic in SI, read by :mod:`.network` and used by the
later stages (:mod:`fetorsion.design.shaft_limits`); docs/propulsion-tvc.md has the equations.

The factor C_K of IACS UR M68 [IACSM68], by the shaft's feature. The rule's own text was not
read; the symbols, the size factor C_D = 0.35 + 0.93 d^-0.2 and the first three rows of the
table (integral flange and straight sections 1.0, shrink-fit coupling 1.0, keyway with tapered
connection 0.6) were read in Lloyd's Register's naval rules, which carry the same limits
[LRNavalTV] (Vol 2, Pt 5, Ch 1, §3.1, Table 1.3.1). The other rows are the rule's values as
they are commonly restated, not confirmed from a readable text here.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from .derived import piecewise_linear

#: The largest σ_B (Pa) the rule's formulas take, by material [LRShipsShafts]: carbon and
#: carbon-manganese steel 760 N/mm², alloy steel 800 N/mm²; a stronger steel gives no higher
#: limit without the fatigue approval the rules ask for.
SIGMA_B_CAP_PA: dict[str, float] = {"carbon": 760e6, "alloy": 800e6}

#: C_K of each shaft feature (a name a network file's ``[[chain.shafts]]`` may give as
#: ``feature``): intermediate shafts, thrust shafts outside the engine, propeller shafts.
CK_FACTORS: dict[str, float] = {
    "integral_flange": 1.0,        # intermediate shaft, integral coupling flange, straight sections [LRNavalTV]
    "shrink_fit": 1.0,             # intermediate shaft, shrink-fit coupling [LRNavalTV]
    "keyway_tapered": 0.60,        # intermediate shaft, keyway, tapered connection [LRNavalTV]
    "keyway_cylindrical": 0.45,    # intermediate shaft, keyway, cylindrical connection (unconfirmed)
    "radial_hole": 0.50,           # intermediate shaft, radial hole (unconfirmed)
    "longitudinal_slot": 0.30,     # intermediate shaft, longitudinal slot (unconfirmed)
    "thrust_collar": 0.85,         # thrust shaft, both sides of the thrust collar (unconfirmed)
    "thrust_roller_bearing": 0.85,  # thrust shaft, in way of a roller thrust bearing (unconfirmed)
    "propeller_keyless": 0.55,     # propeller shaft, flange-mounted or keyless taper-fitted propeller (unconfirmed)
    "propeller_keyed": 0.55,       # propeller shaft, key-fitted propeller (unconfirmed)
    "propeller_forward": 0.80,     # propeller shaft, aft-most bearing's forward end to the forward stern-tube seal
}


# ---------------------------------------------------------------------------
# The propeller


def propeller_law_damping(torque_nm: float, speed_rad_s: float, exponent: float = 2.0) -> float:
    """The propeller law's damping, linearised at one speed: c = ∂Q/∂ω = n Q / ω (N·m·s/rad).

    A fixed-pitch propeller's torque follows Q = Q_r (ω/ω_r)^n (n = 2: the propeller law, the
    power going as the cube of the speed). A small vibration ω + δω changes it by (∂Q/∂ω) δω, a
    torque against the velocity: a viscous damper to ground of c = n Q(ω)/ω at the running
    speed ω. It rises with the speed (c ∝ ω^(n−1)), so a frequency-domain response with one
    constant damping takes it at one speed (docs/propulsion-tvc.md).

    Parameters
    ----------
    torque_nm : float
        The propeller's mean torque at the speed, N·m (> 0).
    speed_rad_s : float
        The shaft speed at which it is linearised, rad/s (> 0).
    exponent : float
        n of Q ∝ ω^n; 2 for the propeller law.
    """
    return exponent * torque_nm / speed_rad_s


def law_torque(rated_torque_nm: float, rated_speed_rad_s: float, speed_rad_s: float, exponent: float = 2.0) -> float:
    """Q(ω) = Q_r (ω/ω_r)^n, N·m: the propeller's mean torque at a speed, from its rated point."""
    return rated_torque_nm * (speed_rad_s / rated_speed_rad_s) ** exponent


#: The propeller damping models a network file may name, each a function of (rated torque N·m,
#: rated speed rad/s, speed rad/s, exponent) → N·m·s/rad. Archer's, Frahm's and Schwanecke's
#: are not offered: no formula with a published worked value was found to test them against.
PROPELLER_DAMPING: dict[str, Callable[[float, float, float, float], float]] = {
    "propeller_law": lambda q_r, w_r, w, n: propeller_law_damping(law_torque(q_r, w_r, w, n), w, n),
}


def with_entrained_water(dry_inertia_kgm2: float, entrained_share: float) -> float:
    """The propeller's inertia in water, kg·m²: its dry inertia times (1 + the entrained share).

    The share (the water that turns with the blades over the dry inertia) is a property of the
    propeller stated by its maker or a regression such as [Parsons1983]'s for the Wageningen
    B-series; no default is assumed.
    """
    return dry_inertia_kgm2 * (1.0 + entrained_share)


def blade_orders(blades: int, multiples: int) -> tuple[int, ...]:
    """The orders a propeller excites, per shaft revolution: blades × k for k = 1 … ``multiples``."""
    return tuple(blades * k for k in range(1, multiples + 1))


def blade_excitation(mean_torque_nm: float, shares: tuple[float, ...]) -> tuple[float, ...]:
    """The blade-order torque amplitudes, N·m: each a share of the propeller's mean torque at that
    speed (the first share for order z, the next for 2z, …)."""
    return tuple(s * mean_torque_nm for s in shares)


# ---------------------------------------------------------------------------
# A flexible coupling from its maker's data sheet


def sheet_value(temperature_c: float, t_nominal_c: float, nominal: float, t_warm_c: float, warm: float) -> float:
    """A data-sheet property at a temperature: linear between its nominal and warm values, held at
    the nearer one outside them (a sheet says nothing beyond its two temperatures)."""
    if t_warm_c == t_nominal_c:
        return nominal
    return piecewise_linear(temperature_c, sorted([(t_nominal_c, nominal), (t_warm_c, warm)]))


def loss_factor_of(relative_damping: float) -> float:
    """η = ψ / 2π: the hysteretic loss factor (k (1 + iη)) of a relative damping ψ.

    ψ, the makers' relative damping, is the energy a cycle dissipates over the elastic energy at
    its amplitude [CentaxSheet] [RenoldSheet]; the hysteretic spring dissipates π η k θ² a cycle
    against the elastic ½ k θ², so ψ = 2π η (the dynamic magnifier M = 2π/ψ [RenoldSheet]).
    """
    return relative_damping / (2.0 * math.pi)


def coupling_heat(amplitudes_nm: Sequence[float], frequencies_hz: Sequence[float], stiffness_nm_per_rad: float,
                  relative_damping: float) -> float:
    """The heat a coupling's rubber dissipates, W: Σ_q f_q ψ T_q² / (2 C).

    Each order q twists the coupling with an elastic torque amplitude T_q (N·m, the spring's
    C × twist, not the total with the damping's) at f_q (Hz); a cycle dissipates ψ times the elastic
    energy T_q²/(2C), f_q cycles a second. The orders' heats add (their cross terms average out
    over the cycle: different frequencies). Compared with the sheet's permissible P_KV.

    Parameters
    ----------
    amplitudes_nm : sequence of float
        T_q of each order, N·m.
    frequencies_hz : sequence of float
        f_q of each order, Hz.
    stiffness_nm_per_rad : float
        C_Tdyn at the coupling's temperature, N·m/rad.
    relative_damping : float
        ψ at that temperature.
    """
    return sum(f * relative_damping * t**2 / (2.0 * stiffness_nm_per_rad)
               for t, f in zip(amplitudes_nm, frequencies_hz, strict=True))


# ---------------------------------------------------------------------------
# The components as a network file states them (read by :mod:`.network`)


@dataclass(frozen=True)
class ShaftSection:
    """A shaft section a class rule judges: outer ``diameter`` and ``bore`` (m), the material's
    specified minimum ``tensile_strength`` (Pa) and kind (``material``: a key of
    :data:`SIGMA_B_CAP_PA`), the design ``feature`` (a key of :data:`CK_FACTORS`)."""

    diameter: float
    tensile_strength: float
    feature: str
    bore: float = 0.0
    material: str = "carbon"

    @property
    def ck(self) -> float:
        return CK_FACTORS[self.feature]

    def stress(self, torque_nm: float) -> float:
        """The nominal torsional stress of a torque on the plain section, Pa: 16 T d / (π (d⁴ − d_i⁴))."""
        return 16.0 * torque_nm * self.diameter / (math.pi * (self.diameter**4 - self.bore**4))


@dataclass(frozen=True)
class Propeller:
    """A propeller at ``station`` (0-based) of a network: its ``blades``, the water that turns
    with it (``entrained_share`` of its ``dry_inertia``, kg·m²), its torque law Q = ``rated_torque``
    (N·m) × (ω / ``rated_speed`` (rad/s))^``exponent``, the damping model by name
    (:data:`PROPELLER_DAMPING`) linearised at ``damping_speed`` (rad/s), and the blade-order
    torques as ``order_shares`` of the mean torque (orders z, 2z, …)."""

    station: int
    blades: int
    dry_inertia: float
    entrained_share: float
    rated_torque: float
    rated_speed: float
    damping_speed: float
    damping_model: str = "propeller_law"
    exponent: float = 2.0
    order_shares: tuple[float, ...] = ()
    name: str = ""
    source: str = ""
    #: The rate station 1's speed passes a barred range at in the time-domain check, rpm/s (0: not stated).
    passage_rate: float = 0.0
    #: The frequency-domain response takes the law's damping at each speed of its sweep (no
    #: ``damping_speed_rpm`` in the file); False: the one at ``damping_speed`` at every speed. The
    #: modes' damping and the time domain take ``damping_speed``'s either way.
    damping_each_speed: bool = False

    @property
    def inertia(self) -> float:
        """The inertia in water, kg·m²."""
        return with_entrained_water(self.dry_inertia, self.entrained_share)

    def damping(self, speed_rad_s: float) -> float:
        """The damping to ground at a shaft speed, N·m·s/rad, by the named model."""
        return PROPELLER_DAMPING[self.damping_model](self.rated_torque, self.rated_speed, speed_rad_s, self.exponent)

    def excitation(self, speed_rad_s: float) -> tuple[tuple[int, ...], tuple[float, ...]]:
        """(orders, torque amplitudes N·m) of the blade orders at a shaft speed."""
        q = law_torque(self.rated_torque, self.rated_speed, speed_rad_s, self.exponent)
        return blade_orders(self.blades, len(self.order_shares)), blade_excitation(q, self.order_shares)


@dataclass(frozen=True)
class StartUp:
    """The engine's start (``[start]`` of a network file): the run from ``from_rpm`` (the speed it
    fires steadily at, station 1's) up to the lowest speed of the ``[excitation]`` range at
    ``rate_rpm_per_s``, every cylinder at the mean indicated pressure ``imep_pa`` (the start's
    load: friction and the line's acceleration, no external load). Judged against τ_T
    (:func:`fetorsion.design.barred_passage.start_passages`)."""

    from_rpm: float
    rate_rpm_per_s: float
    imep_pa: float
    source: str = ""


@dataclass(frozen=True)
class ShutDown:
    """The engine's stop (``[stop]`` of a network file): the fuel cut at ``from_rpm`` (station 1's; the
    top of the speed range unless stated), every cylinder motored, the line coasting down to ``to_rpm`` at
    ``rate_rpm_per_s`` (its friction over its inertia). Judged as the start is."""

    from_rpm: float
    to_rpm: float
    rate_rpm_per_s: float
    source: str = ""


@dataclass(frozen=True)
class Coupling:
    """A flexible coupling from its maker's data sheet, between stations ``i`` and ``j``: dynamic
    stiffness (N·m/rad) and relative damping ψ at the sheet's nominal ``temperature_c`` and, where
    given, at ``warm_temperature_c`` (linear between them, :func:`sheet_value`); the network takes
    them at ``operating_temperature_c``. Its permissible vibratory torque (N·m) and permissible heat
    P_KV (W, at the ambient ``ambient_c``, bringing the rubber to ``max_temperature_c``); 0 where
    the sheet gives none."""

    i: int
    j: int
    stiffness: float
    relative_damping: float
    temperature_c: float
    operating_temperature_c: float
    warm_stiffness: float = 0.0
    warm_relative_damping: float = 0.0
    warm_temperature_c: float = math.nan
    permissible_torque: float = 0.0
    permissible_power: float = 0.0
    ambient_c: float = math.nan
    name: str = ""
    source: str = ""
    #: The rubber's permissible continuous temperature, °C: where P_KV brings it from ``ambient_c``.
    max_temperature_c: float = math.nan
    #: The sheet's tolerance of the dynamic stiffness, a share (0: not stated): the TVC's configurations
    #: with the stiffness at both ends (:func:`fetorsion.design.tvc_cases.tolerance_cases`).
    stiffness_tolerance: float = 0.0
    #: The sheet's maximum torque T_Kmax for transient events (a start, a stop, a resonance passed), N·m
    #: (0: not stated): what the time-domain passages set the coupling's largest torque against.
    maximum_torque: float = 0.0

    def stiffness_at(self, temperature_c: float) -> float:
        """C_Tdyn at a temperature, N·m/rad."""
        if not self.warm_stiffness:
            return self.stiffness
        return sheet_value(temperature_c, self.temperature_c, self.stiffness, self.warm_temperature_c,
                           self.warm_stiffness)

    def relative_damping_at(self, temperature_c: float) -> float:
        """ψ at a temperature."""
        if math.isnan(self.warm_temperature_c):
            return self.relative_damping
        return sheet_value(temperature_c, self.temperature_c, self.relative_damping, self.warm_temperature_c,
                           self.warm_relative_damping)

    def heat(self, amplitudes_nm: Sequence[float], frequencies_hz: Sequence[float], temperature_c: float) -> float:
        """The heat of the orders' elastic torque amplitudes at a temperature, W (:func:`coupling_heat`)."""
        return coupling_heat(amplitudes_nm, frequencies_hz, self.stiffness_at(temperature_c),
                             self.relative_damping_at(temperature_c))
