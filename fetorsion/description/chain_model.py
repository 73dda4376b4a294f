"""The data types of a chain file: a :class:`Chain` (inertias and springs in a line) and a
:class:`Network` (stations joined by shafts, gear pairs and nonlinear elements, branches allowed,
crank descriptions as parts), frozen dataclasses in SI units beside :mod:`.model`'s crank.

:mod:`.chain` and :mod:`.network` build them from a file and check every rule.
"""

from __future__ import annotations

import math

from dataclasses import dataclass, field

from .defaults import DEFAULT_STICK_FACTOR
from .derived import piecewise_torque, twist_at_torque
from .marine import Coupling, Propeller, ShaftSection, ShutDown, StartUp
from .model import Crank, Damper, Engine, Excitation, Limits, partition_labels


@dataclass(frozen=True)
class Chain:
    """A torsional chain given directly: inertias (kg·m²), springs (N·m/rad), dampers.

    ``absolute_damping`` (N·m·s/rad, one per inertia, to ground), ``relative_damping``
    (N·m·s/rad, one per spring) and ``loss_factors`` (hysteretic η, one per spring: the spring
    is k (1 + iη) in a steady-state solve) are optional. With ``engine`` and ``excitation``
    the chain can be excited like a crank: ``cylinder_stations[c]`` is the 0-based station that
    carries cylinder c + 1 (its inertia must already hold that cylinder's rotating and mean
    reciprocating inertia; the reciprocating mass that makes the inertia torque is
    ``excitation.reciprocating_mass``).

    Examples
    --------
    >>> import fetorsion
    >>> chain = fetorsion.load("examples/mendes2008/mwm6_chain.toml")
    >>> res = fetorsion.lumped(chain)  # its own stations: no partition of a crank
    >>> res.dof, len(res.frequencies_hz) == res.dof - 1
    (9, True)
    """

    name: str
    inertias: tuple[float, ...]
    stiffnesses: tuple[float, ...]
    labels: tuple[str, ...]
    absolute_damping: tuple[float, ...] = ()
    relative_damping: tuple[float, ...] = ()
    source: str = ""
    loss_factors: tuple[float, ...] = ()
    cylinder_stations: tuple[int, ...] = ()
    engine: Engine | None = None
    excitation: Excitation | None = None
    length_unit: str = "m"
    raw: dict = field(default_factory=dict, compare=False, repr=False)
    dampers: tuple[Damper, ...] = ()
    limits: Limits | None = None
    #: ``[uncertainty]`` and ``[distributions]``, as a crank description's (paths such as
    #: ``chain.inertias_kgm2.3`` or ``chain.stiffnesses_nm_per_rad.*``)
    uncertainty: tuple = ()
    distributions: tuple = ()

    @property
    def has_dampers(self) -> bool:
        """Whether the file states any absolute, relative or hysteretic damping."""
        return any(v > 0 for v in (*self.absolute_damping, *self.relative_damping, *self.loss_factors))


#: The name a shaft's end takes in a network to be joined to ground (a ground spring).
GROUND = "ground"


@dataclass(frozen=True)
class Shaft:
    """A torsional spring of a network between two stations (0-based; ``j`` = -1: ground).

    ``stiffness`` N·m/rad; ``damping`` a viscous damper across it, N·m·s/rad; ``loss_factor``
    its hysteretic η (k (1 + iη) in a steady-state solve); ``section``: its cross-section and
    material where a class rule's stress limit is to judge it.
    """

    i: int
    j: int
    stiffness: float
    damping: float = 0.0
    loss_factor: float = 0.0
    section: ShaftSection | None = None


@dataclass(frozen=True)
class GearPair:
    """A rigid gear mesh between stations ``i`` and ``j`` (0-based): θ_j = ``ratio`` θ_i, the
    ratio being the speed of j over the speed of i (the pitch radius of i over that of j).
    The rotation's sense is left out: a reversal flips the sign of one branch's angles and
    changes no frequency, amplitude or torque magnitude."""

    i: int
    j: int
    ratio: float


@dataclass(frozen=True)
class NonlinearSpring:
    """A nonlinear element of a network between stations ``i`` and ``j`` (0-based; ``j`` = -1:
    ground): a clutch (its damper's springs, its plates' slip) or a dual-mass flywheel's springs.

    The elastic torque is piecewise linear in the twist x = θ_i − θ_j (rad): on the drive side
    (x ≥ 0) ``stiffnesses[0]`` (N·m/rad) up to ``stage_angles[0]`` (rad), ``stiffnesses[1]`` beyond
    it, …; on the coast side (x < 0) the same curve mirrored, or ``coast_stiffnesses`` from 0 to
    −``coast_stage_angles[0]``, … where given. In parallel a Coulomb friction ``friction`` (N·m, the
    hysteresis) that sticks through ``stick_stiffness`` (N·m/rad; an elastic-perfectly-plastic
    element, its loop a parallelogram). ``preload`` (N·m) is the mean torque it carries: it sets the
    operating point x0 on the elastic curve, and the steady-state analyses take the stage's stiffness
    there (:meth:`tangent`). ``slip_torque`` (N·m; 0: it never slips) is a clutch's capacity: the
    plates in series with the damper slip while the total torque it transmits (the mean ``preload``
    plus the vibratory part) would exceed it either way.
    """

    i: int
    j: int
    stiffnesses: tuple[float, ...]
    stage_angles: tuple[float, ...] = ()
    friction: float = 0.0
    stick_stiffness: float = 0.0
    preload: float = 0.0
    name: str = ""
    source: str = ""
    coast_stiffnesses: tuple[float, ...] = ()
    coast_stage_angles: tuple[float, ...] = ()
    slip_torque: float = 0.0

    def __post_init__(self):
        if not self.stick_stiffness > 0:  # the default: stiff against every stage
            object.__setattr__(self, "stick_stiffness",
                               DEFAULT_STICK_FACTOR * max(tuple(self.stiffnesses) + tuple(self.coast_stiffnesses)))

    def curve(self, coast: bool) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """(stiffnesses N·m/rad, stage angles rad) of the drive side or, with ``coast``, the coast side."""
        if coast and self.coast_stiffnesses:
            return tuple(self.coast_stiffnesses), tuple(self.coast_stage_angles)
        return tuple(self.stiffnesses), tuple(self.stage_angles)

    def elastic(self, x):
        """The elastic torque at twist ``x`` (rad, array), N·m: piecewise linear, continuous, of the
        twist's sign."""
        return piecewise_torque(x, self.curve(False), self.curve(True))

    @property
    def operating_twist(self) -> float:
        """x0 with elastic(x0) = ``preload``, rad (the curve is increasing, so x0 is unique)."""
        stiffnesses, angles = self.curve(self.preload < 0)
        return math.copysign(twist_at_torque(stiffnesses, angles, abs(self.preload)), self.preload)

    @property
    def tangent(self) -> float:
        """The stiffness of the stage at the operating point (the upper one on a boundary), N·m/rad."""
        stiffnesses, angles = self.curve(self.preload < 0)
        x0 = abs(self.operating_twist)
        stage = sum(1 for a in angles if x0 >= a)
        return stiffnesses[stage]


@dataclass(frozen=True)
class NetworkCrank:
    """A crank description as one part of a network (``[[chain.cranks]]``): its lumped
    ``partition`` with the web method ``web_method``, its stations named ``"<name>.<label>"``
    (:func:`partition_labels`) from station ``first`` (0-based) of the network on. ``drives``:
    its pins carry the network's cylinders (the chain file gives no ``[engine]`` of its own).
    The stations' inertias and the shafts between them are the lumped model's
    (:func:`fetorsion.lumped_model.network.resolved`)."""

    name: str
    crank: Crank
    partition: int
    web_method: str
    first: int = 0
    drives: bool = True
    #: ``dof = "condensed"``: the condensed FE crank in its bearings (the engine model of
    #: ``fetorsion run``) where the forced response is solved (:mod:`fetorsion.response.driveline`);
    #: the lumped ``partition`` names its stations and stands in where an analysis takes no FE crank.
    condensed: bool = False

    @property
    def labels(self) -> tuple[str, ...]:
        return tuple(f"{self.name}.{lb}" for lb in partition_labels(self.crank.throws, self.partition))


@dataclass(frozen=True)
class Network:
    """A torsional network: named stations joined by shafts and gear pairs, branches allowed.

    The file form of a chain with ``[[chain.stations]]``, ``[[chain.shafts]]`` and
    ``[[chain.gears]]`` (docs/networks-and-transients.md). Inertias kg·m² per station,
    ``absolute_damping`` N·m·s/rad per station (to ground). With ``engine`` and ``excitation``
    the cylinders act on ``cylinder_stations`` (0-based, as a :class:`Chain`'s). The first
    station is the "pulley" of the tables: the reference of the speed (its speed is the
    engine's).

    Examples
    --------
    >>> import fetorsion
    >>> line = fetorsion.load("examples/networks/gunter_chen_8_1_marine_turbine.toml")
    >>> res = fetorsion.lumped(line)  # one coordinate per gear group's station after the gears
    >>> print(", ".join(f"{60 * f:.1f}" for f in res.frequencies_hz[:3]))  # cycles per minute, as Gunter & Chen print them
    177.7, 220.2, 1282.6
    """

    name: str
    labels: tuple[str, ...]
    inertias: tuple[float, ...]
    shafts: tuple[Shaft, ...]
    gears: tuple[GearPair, ...] = ()
    absolute_damping: tuple[float, ...] = ()
    source: str = ""
    cylinder_stations: tuple[int, ...] = ()
    engine: Engine | None = None
    excitation: Excitation | None = None
    length_unit: str = "m"
    raw: dict = field(default_factory=dict, compare=False, repr=False)
    limits: Limits | None = None
    dampers: tuple[Damper, ...] = ()  # at "front" (the first station) or "rear" (the last at the engine speed)
    #: ``[uncertainty]`` and ``[distributions]``, as a crank description's (``chain.stations.2.inertia_kgm2``)
    uncertainty: tuple = ()
    distributions: tuple = ()
    nonlinear: tuple[NonlinearSpring, ...] = ()
    #: The crank descriptions that are parts of the network; until they are resolved
    #: (:func:`fetorsion.lumped_model.network.resolved`) their stations' inertias are NaN and the
    #: shafts between them absent, so an unresolved network cannot be analysed by mistake.
    cranks: tuple[NetworkCrank, ...] = ()
    #: (cylinders × stations) share of each cylinder's torque on each station, when it is not all on
    #: one station (a crank's pins spread as its lumped model spreads them); empty: ``cylinder_stations``.
    cylinder_weights: tuple[tuple[float, ...], ...] = ()
    #: ``[[chain.propellers]]``: each propeller's station already holds its inertia in water and
    #: its damping linearised at its ``damping_speed`` (in ``inertias`` and ``absolute_damping``).
    propellers: tuple[Propeller, ...] = ()
    #: ``[[chain.couplings]]``: each is also a shaft (its data sheet's stiffness and η = ψ/2π at
    #: its operating temperature), after the ``[[chain.shafts]]`` in ``shafts``.
    couplings: tuple[Coupling, ...] = ()
    #: ``[start]``: the engine's start, judged against τ_T in the time domain; None: not stated.
    start: StartUp | None = None
    #: ``[stop]``: the engine's coast-down after its fuel is cut, judged likewise; None: not stated.
    stop: ShutDown | None = None
    #: ``[chain] constant_speed``: held at a constant speed anywhere in the ``[excitation]`` range (a
    #: generating set): a barred range there cannot be avoided and fails the shafts.
    constant_speed: bool = False

    @property
    def linear_shafts(self) -> tuple[Shaft, ...]:
        """The shafts, then each nonlinear element as a shaft of its stage's stiffness at its
        operating point: what the steady-state analyses (modes, Campbell, response) see."""
        return self.shafts + tuple(Shaft(e.i, e.j, e.tangent) for e in self.nonlinear)

    def condensed_crank(self) -> Crank | None:
        """The crank whose report a run of this network writes when one of its cranks is condensed (its
        engine model in this driveline): that crank with the network's dampers (at its pulley); None
        without a condensed crank."""
        from dataclasses import replace

        part = next((c for c in self.cranks if c.condensed), None)
        return None if part is None else replace(part.crank, dampers=tuple(self.dampers))

    @property
    def has_dampers(self) -> bool:
        """Whether the file states any absolute, relative or hysteretic damping."""
        return any(v > 0 for v in (*self.absolute_damping, *(s.damping for s in self.shafts),
                                   *(s.loss_factor for s in self.shafts)))

    @property
    def loss_factors(self) -> tuple[float, ...]:
        return tuple(s.loss_factor for s in self.shafts)
