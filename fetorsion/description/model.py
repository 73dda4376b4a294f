"""The description's data types: frozen dataclasses in SI units (m, kg, Pa, rad).

Every later stage reads a :class:`Crank` (or a :class:`Chain`); :mod:`.crank` builds them
from a file and checks every rule.
"""

from __future__ import annotations

import math

from dataclasses import dataclass, field, replace
from enum import StrEnum

from .defaults import (DEFAULT_DAMPING_BAND, DEFAULT_DAMPING_BAND_SOURCE, DEFAULT_DAMPING_RATIO, DEFAULT_OVERSPEED,
                       DEFAULT_STICK_FACTOR)

class AttachPoint(StrEnum):
    """Where a rigid attachment sits: the pulley end face, the flywheel flange face, or one copy
    on every crank pin. A str, so ``"front" == AttachPoint.FRONT``."""

    FRONT = "front"
    REAR = "rear"
    PINS = "pins"


ATTACH_POINTS = tuple(p.value for p in AttachPoint)


#: Surface finishes of the Marin surface factor (Budynas–Nisbett Table 6-2): ``[material] surface``.
SURFACES = ("ground", "machined", "cold-drawn", "hot-rolled", "as-forged")
#: Manufacturing routes of the IACS UR M53 fatigue-strength factor K: ``[material] process``.
PROCESSES = ("continuous-grain-flow", "drop-forged", "free-form-forged", "cast-cold-rolled")
#: Surface treatments a fillet (or a drilling's edge) may have had: ``[material]
#: surface_treatment``; each other than ``none`` raises the local fatigue strength by the factor
#: the description states with its source (fetorsion ships no constant for them).
TREATMENTS = ("none", "fillet-rolled", "nitrided", "induction-hardened", "shot-peened")
#: The Material fields that only fatigue reads (not the elastic stiffness): caches keyed on
#: stiffness leave them out.
STRENGTH_FIELDS = ("tensile_strength", "yield_strength", "surface", "process", "surface_treatment",
                   "surface_treatment_factor", "surface_treatment_source")


@dataclass(frozen=True)
class Material:
    """Linear elastic isotropic material, SI units (Pa, -, kg/m³).

    The strength fields are optional (None: not given; fatigue then uses a stated default steel,
    :data:`fetorsion.design.fatigue.DEFAULT_FORGING_STEEL`): ``tensile_strength`` and
    ``yield_strength`` in Pa, ``surface`` one of :data:`SURFACES`, ``process`` one of
    :data:`PROCESSES`.
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float
    name: str = ""
    tensile_strength: float | None = None
    yield_strength: float | None = None
    surface: str | None = None
    process: str | None = None
    #: One of :data:`TREATMENTS` (None: not given, untreated), the factor on the local fatigue
    #: strength the treatment gives and where that factor comes from.
    surface_treatment: str | None = None
    surface_treatment_factor: float | None = None
    surface_treatment_source: str = ""

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + ν)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class Cylinder:
    """A round shaft piece (journal, pin, nose or flange step), lengths in m."""

    diameter: float
    length: float
    bore: float = 0.0


@dataclass(frozen=True)
class Web:
    """A crank web (arm) joining a journal to a pin, lengths in m, angle in rad.

    The outline is the convex hull of a circle of diameter ``width_journal`` (B_max)
    around the crank axis and one of diameter ``width_pin`` (B_min) around the pin
    centre, united with an optional counterweight sector of radius
    ``counterweight_radius`` and full angle ``counterweight_angle`` centred opposite
    the pin.
    """

    thickness: float
    width_journal: float
    width_pin: float
    counterweight_radius: float = 0.0
    counterweight_angle: float = 0.0


#: Engine layouts: one cylinder per throw in one plane, two banks sharing each throw, two
#: opposed banks with a throw per cylinder.
LAYOUTS = ("in-line", "vee", "opposed")


@dataclass(frozen=True)
class Engine:
    """Cylinder layout and slider-crank data; lengths in m, angles in rad.

    ``crank_angles`` has one angle per throw: how far the TDC of the throw's first cylinder
    (its lowest-numbered one) lags cylinder 1's. In an in-line engine each cylinder is its
    throw's only one. ``cylinder_throws`` (0-based, one per cylinder; empty: cylinder c on
    throw c) puts several cylinders on one throw (a vee). ``bank_angles`` (one per cylinder;
    empty: all 0) adds to a cylinder's TDC lag the angle between its bank's axis and the first
    bank's (a vee's bank angle, an opposed engine's 180°). ``rod_offsets`` (m, one per cylinder;
    empty: all 0) places each big end along its pin, from the pin's mid-length, rearwards
    positive (two rods side by side).
    """

    cylinders: int
    strokes_per_cycle: int
    stroke: float
    rod_length: float
    crank_angles: tuple[float, ...]
    firing_order: tuple[int, ...]
    bore: float = 0.0
    layout: str = "in-line"
    cylinder_throws: tuple[int, ...] = ()
    bank_angles: tuple[float, ...] = ()
    rod_offsets: tuple[float, ...] = ()

    @property
    def crank_radius(self) -> float:
        """R = stroke / 2 in m."""
        return 0.5 * self.stroke

    @property
    def throws(self) -> int:
        """Number of crank throws (pins)."""
        return len(self.crank_angles)

    def throw_of_cylinder(self, cylinder: int) -> int:
        """0-based throw of 0-based ``cylinder``."""
        return self.cylinder_throws[cylinder] if self.cylinder_throws else cylinder

    def rod_offset(self, cylinder: int) -> float:
        """Axial position (m) of 0-based ``cylinder``'s big end from its pin's mid-length."""
        return self.rod_offsets[cylinder] if self.rod_offsets else 0.0

    def tdc_lags(self) -> tuple[float, ...]:
        """How far each cylinder's TDC lags cylinder 1's throw's first cylinder, rad: its throw's
        crank angle plus its bank angle (mod nothing: :meth:`firing_angles` wraps)."""
        bank = self.bank_angles or (0.0,) * self.cylinders
        return tuple(self.crank_angles[self.throw_of_cylinder(c)] + bank[c] for c in range(self.cylinders))

    def firing_angles(self) -> tuple[float, ...]:
        """Crank angle (rad) at which each cylinder (index 0..N-1) fires, cylinder 1 at 0.

        :meth:`tdc_lags` gives how far cylinder c's TDC lags cylinder 1's; each cylinder has
        ``strokes_per_cycle / 2`` TDCs per cycle, and the firing order picks, cylinder by
        cylinder, the first TDC after the previous firing.

        Raises
        ------
        ValueError
            If some cylinder has no TDC left in the cycle after the one before it fired: the
            crank angles cannot produce this firing order.
        """
        period = math.pi * self.strokes_per_cycle
        turn = 2 * math.pi
        lags = self.tdc_lags()
        tdc = [(a - lags[0]) % turn for a in lags]
        out = [0.0] * self.cylinders
        order = list(self.firing_order)
        start = order.index(1)
        previous = 0.0
        for c in order[start + 1:] + order[:start]:
            t = tdc[c - 1]
            if t <= previous + 1e-9:
                t += turn * math.ceil((previous + 1e-9 - t) / turn)
            if t >= period:
                raise ValueError(f"cylinder {c} has no TDC left in the {math.degrees(period):.0f}° cycle after "
                                 f"the cylinder before it fired at {math.degrees(previous):.1f}°")
            out[c - 1] = previous = t
        return tuple(out)


@dataclass(frozen=True)
class Fillets:
    """Fillet radii at journal/web and pin/web junctions, m."""

    journal: float = 0.0
    pin: float = 0.0


@dataclass(frozen=True)
class OilHoles:
    """Diametral oil drillings of diameter ``diameter`` (m) through each pin/journal."""

    diameter: float = 0.0
    in_journals: bool = False
    in_pins: bool = False


@dataclass(frozen=True)
class Attachment:
    """A rigid body fixed to the crank.

    ``at`` is ``"front"`` (pulley end face), ``"rear"`` (flywheel flange face) or
    ``"pins"`` (one copy on every crank pin, e.g. piston + connecting rod, its
    ``polar_inertia`` being the equivalent inertia about the crank axis per cylinder).
    Inertias in kg·m², mass in kg, offset (axial distance of its centre of mass from
    the face, outwards) in m.
    """

    name: str
    at: AttachPoint
    polar_inertia: float
    mass: float = 0.0
    diametral_inertia: float = 0.0
    offset: float = 0.0


@dataclass(frozen=True)
class Excitation:
    """Cylinder pressure and operating data for the Campbell diagram and forced response.

    Either ``pressure_curve`` (crank angle rad from firing TDC over one cycle, absolute
    pressure Pa) or the synthetic cycle: polytropic compression/expansion with a Wiebe
    heat release scaled to ``load`` ((rpm, value) pairs, linear in between; value is the
    IMEP or the peak pressure in Pa as ``load_kind`` says).
    """

    reciprocating_mass: float  # kg per cylinder (piston, pin, rod small-end share)
    speed_range: tuple[float, float]  # rpm
    #: kg per cylinder turning with the pin (the rod's big-end share): its centrifugal force
    #: m R Ω² adds to the radial pin force, a constant, so it loads the mean and no order
    rotating_mass: float = 0.0
    compression_ratio: float = 0.0
    load_kind: str = "imep"  # "imep" or "peak"
    load: tuple[tuple[float, float], ...] = ()
    intake_pressure: float = 1.0e5  # Pa, absolute
    polytropic_exponent: float = 1.3
    combustion_start: float = -0.2618  # rad from firing TDC (−15°)
    combustion_duration: float = 0.8727  # rad (50°)
    wiebe_a: float = 5.0
    wiebe_m: float = 2.0
    pressure_curve: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    modal_damping_ratio: float = DEFAULT_DAMPING_RATIO
    overspeed: float = DEFAULT_OVERSPEED  # the checked range's top over the rated speed
    #: (low, high) of the modal damping ratio the verdict is also given at, and where it comes from
    damping_band: tuple[float, float] = DEFAULT_DAMPING_BAND
    damping_source: str = DEFAULT_DAMPING_BAND_SOURCE
    #: Where ``modal_damping_ratio`` comes from ("": not stated, the verdict then says its damping
    #: is assumed).
    modal_damping_ratio_source: str = ""
    #: ζ of the condensed crank's bending (None: the torsional ``modal_damping_ratio`` on every
    #: mode, the bending's damping then assumed unless an oil film gives it) and its source.
    bending_damping_ratio: float | None = None
    bending_damping_ratio_source: str = ""

    @property
    def checked_range(self) -> tuple[float, float]:
        """(low, overspeed × high) rpm: the speeds the forced response and the verdict cover."""
        return self.speed_range[0], self.overspeed * self.speed_range[1]


DAMPER_TYPES = ("viscous", "rubber", "tuned")
DAMPER_STATIONS = ("front", "rear")


def table_at_temperature(groups: dict, temperature: float) -> tuple[tuple[float, float, float], ...]:
    """A frequency table (f, k, η) at ``temperature`` from tables at several temperatures
    (``groups``: temperature -> rows [f, k, η], f ascending): linear in temperature between the two
    nearest, each read linearly in frequency on the union of their frequencies; the end
    temperature's table outside the range (no extrapolation of a measured property)."""
    import numpy as np

    temps = sorted(groups)
    lo = max([T for T in temps if T <= temperature], default=temps[0])
    hi = min([T for T in temps if T >= temperature], default=temps[-1])
    w = 0.0 if hi == lo else (temperature - lo) / (hi - lo)
    f = np.union1d([r[0] for r in groups[lo]], [r[0] for r in groups[hi]])

    def at(T, col):
        g = groups[T]
        return np.interp(f, [r[0] for r in g], [r[col] for r in g])

    k = (1 - w) * at(lo, 1) + w * at(hi, 1)
    eta = (1 - w) * at(lo, 2) + w * at(hi, 2)
    return tuple((float(a), float(b), float(c)) for a, b, c in zip(f, k, eta))



@dataclass(frozen=True)
class Damper:
    """A torsional damper: a seismic ring joined to the pulley-end (``front``) or flywheel-side
    (``rear``) station of the chain.

    ``kind`` is ``"viscous"`` (Houdaille: housing + ring in silicone fluid, ``damping`` only),
    ``"rubber"`` (hub + ring on a rubber spring of ``stiffness`` with hysteretic
    ``loss_factor``, optionally ``table`` rows (frequency Hz, dynamic stiffness N·m/rad, loss
    factor) interpolated linearly in frequency, held constant outside) or ``"tuned"`` (a plain
    tuned absorber: spring ``stiffness`` and an optional viscous ``damping``). Inertias kg·m²;
    ``hub_inertia`` is the housing (viscous) or hub (rubber, tuned), added to the station;
    ``allowed_power`` the continuous heat it may dissipate (W), checked by the verdict.
    """

    kind: str
    at: str = "front"
    hub_inertia: float = 0.0
    ring_inertia: float = 0.0
    stiffness: float = 0.0
    damping: float = 0.0
    loss_factor: float = 0.0
    table: tuple[tuple[float, float, float], ...] = ()
    name: str = ""
    source: str = ""
    #: The heat the damper may dissipate continuously, W (its maker's rating); 0: not given.
    allowed_power: float = 0.0
    #: A rubber's dynamic table at several temperatures: rows (°C, Hz, N·m/rad, loss factor);
    #: ``table`` is its frequency table at ``temperature_c``.
    temperature_table: tuple = ()
    temperature_c: float = math.nan
    #: Heat-following rubber: the air around it (°C) and its heat path to that air (W/K); the
    #: response puts it at the temperature its own dissipation holds
    #: (:func:`fetorsion.response.forced.solve_theta`). 0: the stated ``temperature_c``.
    ambient_c: float = math.nan
    thermal_conductance: float = 0.0

    @property
    def follows_heat(self) -> bool:
        return self.thermal_conductance > 0 and bool(self.temperature_table)

    def at_temperature(self, temperature: float) -> "Damper":
        """This damper with its rubber's frequency table read at ``temperature`` (°C)."""
        groups: dict = {}
        for T, f, k, e in self.temperature_table:
            groups.setdefault(T, []).append((f, k, e))
        table = table_at_temperature(groups, float(temperature))
        return replace(self, table=table, stiffness=table[0][1], loss_factor=table[0][2],
                       temperature_c=float(temperature))


@dataclass(frozen=True)
class Limits:
    """Permissible vibratory values (amplitudes: half peak-to-peak) and where they come from.

    Stress limits in Pa (``continuous_shear``, ``transient_shear``) or torque limits in N·m
    (``continuous_torque``, ``transient_torque``); a fatigue strength in shear and a safety
    factor give ``continuous_shear`` = strength / factor. 0 means not given. ``source`` says
    where every number comes from.
    """

    continuous_shear: float = 0.0
    transient_shear: float = 0.0
    continuous_torque: float = 0.0
    transient_torque: float = 0.0
    fatigue_strength: float = 0.0
    safety_factor: float = 0.0
    source: str = ""
    #: The user's alternating bending fatigue strength of the crank as built, against local
    #: stresses (SCF × nominal), Pa: replaces the fatigue assessment's own strength (M53's σ_DW,
    #: the textbook's S_e) when > 0.
    fatigue_strength_bending: float = 0.0
    #: The fatigue assessment's required safety, when > 0 (else the method's own).
    fatigue_required_safety: float = 0.0
    #: [IACSM53] §4's additional bending stress σ_add at the fillets (misalignment, bedplate
    #: deformation, axial and bending vibration), Pa, added to the fillets' alternating bending by
    #: the M53 path; 0: M53 §4's value for a trunk-piston engine (±10 N/mm²)
    additional_bending: float = 0.0
    #: The fatigue method that decides the verdict (``iacs-m53`` or ``fe``); "": the default.
    fatigue_method: str = ""

    @property
    def kind(self) -> str:
        """``"stress"`` or ``"torque"``: what the limits bound."""
        return "torque" if self.continuous_torque > 0 else "stress"

    @property
    def continuous(self) -> float:
        """The continuous-running limit, Pa (stress) or N·m (torque)."""
        return self.continuous_torque if self.kind == "torque" else self.continuous_shear

    @property
    def transient(self) -> float:
        """The passing-through limit (0: none given)."""
        return self.transient_torque if self.kind == "torque" else self.transient_shear


@dataclass(frozen=True)
class OilFilm:
    """Plain oil-film main bearings at one operating point, SI units.

    Radial clearance m and static load N per journal, dynamic viscosity Pa·s, journal speed rad/s;
    the static eccentricity ratio ε and attitude angle (rad) per journal that the short-bearing
    theory gives there (:mod:`fetorsion.description.oilfilm`). The film's stiffness and damping depend on
    load and speed: they are taken at this one point. ``load`` None: each journal's mean load
    from the crank's own forces, not found yet (``eccentricity`` and ``attitude`` then empty).
    """

    clearance: tuple[float, ...]
    viscosity: float
    load: tuple[float, ...] | None
    speed: float
    eccentricity: tuple[float, ...]
    attitude: tuple[float, ...]


@dataclass(frozen=True)
class Bearings:
    """Main bearings, acting radially on each main journal's bearing surface.

    Stiffness N/m and damping N·s/m per journal (``inf`` = rigid), axial stiffness N/m at the
    thrust journal (0: none, the crank is then free axially; ``inf``: rigid), bearing widths m
    per journal (centred on the journal; by default the journal's length).

    With ``oil_film`` the radial stiffness and damping are the film's isotropic equivalents
    (:func:`fetorsion.description.oilfilm.isotropic_equivalent`) at the operating point it records.

    Without a ``[bearings]`` table the bearings are rigid radially and there is no thrust
    bearing (:func:`default_bearings`): no source gives the oil-film stiffness of the
    reference engines, and the rigid limit is where a torsion-only chain belongs.
    """

    radial_stiffness: tuple[float, ...]
    radial_damping: tuple[float, ...]
    width: tuple[float, ...]
    axial_stiffness: float = 0.0
    thrust_journal: int = 0
    given: bool = True
    oil_film: OilFilm | None = None

    @property
    def rigid(self) -> bool:
        return all(math.isinf(k) for k in self.radial_stiffness)


def default_bearings(journals) -> Bearings:
    """Rigid radial bearings as wide as the journals, no thrust bearing (see :class:`Bearings`)."""
    n = len(journals)
    return Bearings((math.inf,) * n, (0.0,) * n, tuple(j.length for j in journals), given=False)


#: What a design search may minimise: the crank's mass (and an added damper ring's), its rotating
#: inertia, or the change from the given design (the sum of the moved inputs' relative changes).
DESIGN_OBJECTIVES = ("mass", "inertia", "change")


@dataclass(frozen=True)
class DesignSpace:
    """``[design]``: the inputs a design search may move and their bounds (field paths, file
    units), what it minimises, and the damper it may add.

    ``damper`` (``rubber``, ``viscous`` or ``tuned``; None: none added) with its ring inertia as a
    share of the first mode's equivalent inertia seen from the pulley (``damper_inertia_ratio``,
    the bounds) and the ring's radius of gyration (``damper_ring_radius``, m), which turns its
    inertia into mass. ``required_safety``: None for the fatigue method's own.
    ``damper_heat_rating``: the added damper's continuous heat rating, W (None: not rated).
    ``resonance_orders`` and ``resonance_margin``: each resonance speed 60 f1 / q of these orders
    with the first mode in the bearings lies outside the running range by this share of its nearer
    end (empty: no such constraint).
    """

    inputs: tuple[tuple[str, float, float], ...]
    objective: str = "mass"
    damper: str | None = None
    damper_inertia_ratio: tuple[float, float] | None = None
    damper_ring_radius: float | None = None
    required_safety: float | None = None
    damper_heat_rating: float | None = None
    resonance_orders: tuple[float, ...] = ()
    resonance_margin: float = 0.0


#: The reference values a description's ``[meta]`` may carry (checked when read; their meaning in
#: docs/description-format.md)
MEASURED_F1, PAPER_FE_F1, PAPER_LUMPED_F1 = ("measured_first_torsional_hz", "paper_fe_first_torsional_hz",
                                             "paper_lumped_first_torsional_hz")


def reference_value(notes: dict, key: str) -> float | None:
    """A reference frequency of ``[meta]`` as a float, None where absent."""
    value = notes.get(key)
    return None if value is None else float(value)


@dataclass(frozen=True)
class Crank:
    """A complete crankshaft description in SI units.

    The shaft is stacked along +x from the front (pulley) end: ``front`` sections,
    then journal 1, web 1, pin 1, web 2, journal 2, ... journal N+1, then ``rear``
    sections. Webs 2i-1 and 2i belong to throw i.
    """

    name: str
    material: Material
    engine: Engine
    journals: tuple[Cylinder, ...]
    pins: tuple[Cylinder, ...]
    webs: tuple[Web, ...]
    front: tuple[Cylinder, ...] = ()
    rear: tuple[Cylinder, ...] = ()
    fillets: Fillets = Fillets()
    oil_holes: OilHoles = OilHoles()
    attachments: tuple[Attachment, ...] = ()
    length_unit: str = "m"
    source: str = ""
    notes: dict = field(default_factory=dict, compare=False)
    uncertainty: tuple[tuple[str, tuple[tuple[str, float, float], ...]], ...] = ()
    excitation: Excitation | None = None
    raw: dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def measured_f1_hz(self) -> float | None:
        """``[meta] measured_first_torsional_hz``: the crank's measured free-free first torsional
        frequency, Hz (checked a positive number when read), or None."""
        return reference_value(self.notes, MEASURED_F1)

    @property
    def paper_fe_f1_hz(self) -> float | None:
        """``[meta] paper_fe_first_torsional_hz``: a published FE first torsional frequency, Hz, or None."""
        return reference_value(self.notes, PAPER_FE_F1)

    @property
    def paper_lumped_f1_hz(self) -> dict[str, float]:
        """``[meta] paper_lumped_first_torsional_hz``: published lumped f1 by partition (``"17"``), Hz."""
        return dict(self.notes.get(PAPER_LUMPED_F1, {}))
    dampers: tuple[Damper, ...] = ()
    limits: Limits | None = None
    bearings: Bearings | None = None
    #: ``[distributions]``: (uncertainty entry, kind, standard deviation or None); an entry not
    #: named is uniform over its range.
    distributions: tuple[tuple[str, str, float | None], ...] = ()
    #: ``[design]``: what ``fetorsion design`` may change, and what it minimises.
    design: DesignSpace | None = None
    #: ``[solid] step``: the CAD solid (absolute path) the FE analyses mesh in place of the built one.
    solid_step: str | None = None
    #: ``[solid] axis`` and ``front_centre``: the crank axis (unit vector, front to rear) and the
    #: point of it at the front end face (m), in the STEP file's coordinates; None: the x axis
    #: through the origin, as fetorsion builds a crank.
    solid_placement: tuple[tuple[float, float, float], tuple[float, float, float]] | None = None
    #: A throw cut from that solid (:func:`fetorsion.webs.throwfe.throw_of`): its slab of the whole
    #: crank's (x from, x to, m) and the turn (rad, about x) that puts its pin at angle 0.
    solid_window: tuple[float, float, float] | None = None

    @property
    def throws(self) -> int:
        """Number of throws (crank pins); as many as cylinders in an in-line engine."""
        return len(self.pins)

    @property
    def main_bearings(self) -> Bearings:
        """The ``[bearings]`` table, or :func:`default_bearings`."""
        return self.bearings if self.bearings is not None else default_bearings(self.journals)

    def throw_of_web(self, web_index: int) -> int:
        """0-based throw index of 0-based web ``web_index``."""
        return web_index // 2

    def journal_of_web(self, web_index: int) -> int:
        """0-based index of the journal a web is joined to (its own side)."""
        return web_index // 2 + web_index % 2

    def attachments_at(self, at: AttachPoint | str) -> tuple[Attachment, ...]:
        """The attachments at ``at`` (``front``, ``rear`` or ``pins``), in the file's order."""
        return tuple(a for a in self.attachments if a.at == at)


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
    its hysteretic η (k (1 + iη) in a steady-state solve).
    """

    i: int
    j: int
    stiffness: float
    damping: float = 0.0
    loss_factor: float = 0.0


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
        import numpy as np

        x = np.asarray(x, dtype=float)
        a = np.abs(x)
        torque = np.zeros_like(a)
        for coast in (False, True):
            stiffnesses, angles = self.curve(coast)
            edges = (0.0, *angles)
            side = np.zeros_like(a)
            for s, k in enumerate(stiffnesses):
                hi = edges[s + 1] if s + 1 < len(edges) else np.inf
                side += k * np.clip(a - edges[s], 0.0, hi - edges[s])
            torque = np.where((x < 0) == coast, side, torque)
        return np.sign(x) * torque

    @property
    def operating_twist(self) -> float:
        """x0 with elastic(x0) = ``preload``, rad (the curve is increasing, so x0 is unique)."""
        stiffnesses, angles = self.curve(self.preload < 0)
        edges = (0.0, *angles)
        target, x, torque = abs(self.preload), 0.0, 0.0
        for s, k in enumerate(stiffnesses):
            width = edges[s + 1] - edges[s] if s + 1 < len(edges) else math.inf
            if torque + k * width >= target:
                x += (target - torque) / k
                break
            x, torque = x + width, torque + k * width
        return math.copysign(x, self.preload)

    @property
    def tangent(self) -> float:
        """The stiffness of the stage at the operating point (the upper one on a boundary), N·m/rad."""
        stiffnesses, angles = self.curve(self.preload < 0)
        x0 = abs(self.operating_twist)
        stage = sum(1 for a in angles if x0 >= a)
        return stiffnesses[stage]


#: The lumped partitions of a crank (:mod:`fetorsion.lumped_model.lumped`), named by their number of
#: stations on an inline four.
PARTITIONS = (5, 6, 17, 19, 21)
#: The web-stiffness methods' names (the registry :data:`fetorsion.webs.methods.WEB_METHODS` holds the
#: functions and checks it has exactly these): a description may name one before the webs stage is loaded.
WEB_METHOD_NAMES = ("carter", "ker-wilson", "beam", "fe", "fe-held", "chart")
#: ``[[chain.cranks]] dof`` naming the condensed FE crank instead of a lumped partition.
CONDENSED = "condensed"
#: What a network may call a crank's first and last station besides their own labels.
CRANK_END_ALIASES = ("pulley", "flywheel")


def partition_labels(cylinders: int, partition: int) -> tuple[str, ...]:
    """The station labels of a crank's lumped ``partition`` (one of :data:`PARTITIONS`) for a crank
    of ``cylinders`` throws, front to rear: journals ``J1`` …, webs ``W1`` …, pins ``P1`` …, the end
    stations ``front``/``rear`` (``front inner``/``rear inner`` in the 21-DOF model), ``throw k`` in
    the 6-DOF model. The one source of the names (:func:`fetorsion.lumped_model.parts.stations`)."""
    n = cylinders
    if partition == 5:
        return ("front", *(f"J{j + 1}" for j in range(1, n)), "rear")
    if partition == 6:
        return ("front", *(f"throw {t + 1}" for t in range(n)), "rear")
    body = tuple(x for t in range(n) for x in (f"J{t + 1}", f"W{2 * t + 1}", f"P{t + 1}", f"W{2 * t + 2}")) + (f"J{n + 1}",)
    if partition == 17:
        return body
    if partition == 19:
        return ("front", *body, "rear")
    if partition == 21:
        return ("front", "front inner", *body, "rear inner", "rear")
    raise ValueError(f"{partition!r} is not a partition; choose from {PARTITIONS}")


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

    @property
    def linear_shafts(self) -> tuple[Shaft, ...]:
        """The shafts, then each nonlinear element as a shaft of its stage's stiffness at its
        operating point: what the steady-state analyses (modes, Campbell, response) see."""
        return self.shafts + tuple(Shaft(e.i, e.j, e.tangent) for e in self.nonlinear)

    @property
    def has_dampers(self) -> bool:
        """Whether the file states any absolute, relative or hysteretic damping."""
        return any(v > 0 for v in (*self.absolute_damping, *(s.damping for s in self.shafts),
                                   *(s.loss_factor for s in self.shafts)))

    @property
    def loss_factors(self) -> tuple[float, ...]:
        return tuple(s.loss_factor for s in self.shafts)
