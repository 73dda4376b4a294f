"""The description's data types: frozen dataclasses in SI units (m, kg, Pa, rad).

Every later stage reads a :class:`Crank` (or a chain file's :class:`~.chain_model.Chain` or
:class:`~.chain_model.Network`, in :mod:`.chain_model`); :mod:`.crank` builds them from a file and
checks every rule.
"""

from __future__ import annotations

import math

from dataclasses import dataclass, field, replace
from enum import StrEnum

from .defaults import DEFAULT_DAMPING_BAND, DEFAULT_DAMPING_BAND_SOURCE, DEFAULT_DAMPING_RATIO, DEFAULT_OVERSPEED
from .derived import firing_angles_from_lags, piecewise_linear, reference_value, table_at_temperature, temperature_groups
from .design_space import DesignSpace


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
    """A round shaft piece (journal, pin, nose or flange step), lengths in m.

    A split pin (vee only) is two half pins of ``half_length`` each with a flying web of
    ``flying_web`` (m) between them: the front half at its throw's angle, the rear half
    ``split_angle`` (rad) later to TDC (docs/vee-engines.md, *split pins*); 0: an ordinary pin.
    """

    diameter: float
    length: float
    bore: float = 0.0
    split_angle: float = 0.0
    flying_web: float = 0.0

    @property
    def split(self) -> bool:
        return self.split_angle != 0.0

    @property
    def half_length(self) -> float:
        """A split pin's half-pin length (length − flying web)/2, m; the whole length unsplit."""
        return 0.5 * (self.length - self.flying_web) if self.split else self.length


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
class Articulation:
    """A vee's master and articulated rods: the first bank's (master) rod on the pin carries a
    knuckle pin at ``knuckle_radius`` (m) from its big end's centre, ``knuckle_angle`` (rad) from
    its axis towards the second bank; the second bank's (articulated) rod of ``rod_length`` (m)
    runs on it (docs/vee-engines.md, *master and articulated rods*)."""

    knuckle_radius: float
    knuckle_angle: float
    rod_length: float


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
    positive (two rods side by side). ``half_pin_angles`` (rad, one per cylinder; empty: all 0)
    adds the angle of the cylinder's half of a split pin from its throw's angle (0 for the front
    half).
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
    half_pin_angles: tuple[float, ...] = ()
    #: A vee's master and articulated rods (None: each rod on the pin).
    articulation: Articulation | None = None

    def articulated(self, cylinder: int) -> bool:
        """Whether 0-based ``cylinder`` drives an articulated rod (a second-bank cylinder of an
        engine with master and articulated rods)."""
        return self.articulation is not None and bool(self.bank_angles) and self.bank_angles[cylinder] != 0.0

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

    def half_pin_angle(self, cylinder: int) -> float:
        """Angle (rad) of 0-based ``cylinder``'s half pin from its throw's angle (0 unsplit)."""
        return self.half_pin_angles[cylinder] if self.half_pin_angles else 0.0

    def pin_angle(self, cylinder: int) -> float:
        """Angle (rad) of the pin (or half pin) 0-based ``cylinder``'s rod runs on: a_t + s_c."""
        return self.crank_angles[self.throw_of_cylinder(cylinder)] + self.half_pin_angle(cylinder)

    def tdc_lags(self) -> tuple[float, ...]:
        """How far each cylinder's TDC lags cylinder 1's throw's first cylinder, rad: λ_c = a_t +
        s_c + ψ_c, its throw's crank angle, its half pin's split and its bank angle (mod nothing:
        :meth:`firing_angles` wraps)."""
        bank = self.bank_angles or (0.0,) * self.cylinders
        return tuple(self.pin_angle(c) + bank[c] for c in range(self.cylinders))

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
        return firing_angles_from_lags(self.tdc_lags(), self.firing_order, self.strokes_per_cycle)


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
    #: The engine maker's tangential-pressure harmonics, per order: (order, sine Pa, cosine Pa), the
    #: sine and cosine coefficients one per column of ``harmonic_imep`` (Pa, ascending): the gas
    #: pressure's tangential share p_t(θ) = Σ_q a_q sin qθ + b_q cos qθ (θ from the cylinder's firing
    #: TDC), read at the load's mean indicated pressure (``load``; ``load_kind`` "imep", or
    #: "propeller_imep": p_mi = load's value × (n / its rpm)²). Empty: a pressure curve or the cycle.
    tangential_harmonics: tuple[tuple[float, tuple[float, ...], tuple[float, ...]], ...] = ()
    harmonic_imep: tuple[float, ...] = ()
    #: The misfiring cylinder's harmonics (order, sine Pa, cosine Pa): its motored cycle at the running
    #: boost, the engine maker's misfire table. Empty: the table's column at p_mi 0, if it has one.
    misfire_harmonics: tuple[tuple[float, float, float], ...] = ()

    def running_imep(self, rpm: float) -> float:
        """The mean indicated pressure at ``rpm``, Pa: the ``load`` table's (linear between its rows,
        held outside), or the propeller law's p_rated (n / n_rated)² (``load_kind`` "propeller_imep")."""
        if self.load_kind == "propeller_imep":
            (n_rated, p_rated), = self.load
            return p_rated * (rpm / n_rated) ** 2
        return piecewise_linear(rpm, sorted(self.load))

    @property
    def checked_range(self) -> tuple[float, float]:
        """(low, overspeed × high) rpm: the speeds the forced response and the verdict cover."""
        return self.speed_range[0], self.overspeed * self.speed_range[1]


DAMPER_TYPES = ("viscous", "rubber", "tuned")
DAMPER_STATIONS = ("front", "rear")


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
        table = table_at_temperature(temperature_groups(self.temperature_table), float(temperature))
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


#: The reference values a description's ``[meta]`` may carry (checked when read; their meaning in
#: docs/description-format.md)
MEASURED_F1, PAPER_FE_F1, PAPER_LUMPED_F1 = ("measured_first_torsional_hz", "paper_fe_first_torsional_hz",
                                             "paper_lumped_first_torsional_hz")


@dataclass(frozen=True)
class Crank:
    """A complete crankshaft description in SI units.

    The shaft is stacked along +x from the front (pulley) end: ``front`` sections,
    then journal 1, web 1, pin 1, web 2, journal 2, ... journal N+1, then ``rear``
    sections. Webs 2i-1 and 2i belong to throw i.

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")  # lengths in the file's unit, SI here
    >>> crank.engine.cylinders, len(crank.journals), crank.journals[0].diameter
    (4, 5, 0.06)
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


