"""Every table and field a crank description or a chain file may hold, as data.

The readers (:mod:`fetorsion.description.crank`, ``.chain``, ``.network``, ``.tables``) ask for
each field by name; this module declares those names with their meaning and rule, and :meth:`Table.finish
<fetorsion.description.reader.Table.finish>` refuses to run when the reader has read a field
that is not declared here. The documentation's description-format page is generated from these
declarations (:func:`markdown`), so a field the reader accepts cannot be missing from the page.
The rules themselves are enforced by the reader; the ``rule`` text here says them in words.
"""

from __future__ import annotations

from dataclasses import dataclass

from .defaults import DEFAULT_DAMPING_RATIO, DEFAULT_OVERSPEED
from .model import ATTACH_POINTS, DAMPER_STATIONS, DAMPER_TYPES, PROCESSES, SURFACES, TREATMENTS
from .units import LENGTH_UNITS


@dataclass(frozen=True)
class Field:
    """One key of a table: its name, what it means (with its unit), and the rule it must obey."""

    key: str
    meaning: str
    rule: str = ""


@dataclass(frozen=True)
class Section:
    """One TOML table: ``[name]`` (``array=False``) or ``[[name]]`` (``array=True``).

    ``free`` tables take keys of the user's choosing (notes, field paths); ``fields`` then
    lists the keys that have a meaning of their own.
    """

    name: str
    intro: str
    fields: tuple[Field, ...]
    array: bool = False
    free: bool = False
    required: bool = False

    @property
    def keys(self) -> frozenset[str]:
        return frozenset(f.key for f in self.fields)

    @property
    def header(self) -> str:
        return f"[[{self.name}]]" if self.array else f"[{self.name}]"


def one_of(values) -> str:
    return "one of " + ", ".join(f"`{v}`" for v in values)


_ROUND = (
    Field("diameter", "outer diameter (file length unit)", "> 0"),
    Field("length", "axial length (file length unit)", "> 0"),
    Field("bore", "diameter of a central bore (file length unit); default 0", ">= 0, smaller than `diameter`"),
)


def _round(name: str, intro: str, required: bool) -> Section:
    return Section(name, intro, _ROUND, array=True, required=required)


META = Section("meta", "Free notes: any key is kept with the description (e.g. `source`, "
               "`measured_first_torsional_hz`).", (
    Field("name", "name used in tables and plots; default the file's name", "a string"),
), free=True)

UNITS = Section("units", "The unit of every length in the file; every other quantity carries its SI unit "
                "in its key name, angles end in `_deg`. Inside fetorsion all is SI.", (
    Field("length", "length unit", one_of(LENGTH_UNITS)),
), required=True)

MATERIAL = Section("material", "An isotropic elastic steel; the strengths feed the fatigue assessment "
                   "(see {doc}`fatigue`).", (
    Field("youngs_modulus_pa", "Young's modulus E, Pa", "> 0"),
    Field("poisson_ratio", "Poisson's ratio ν", "0 < ν < 0.5"),
    Field("density_kgm3", "density ρ, kg/m³", "> 0"),
    Field("name", "material name", "a string"),
    Field("tensile_strength_pa", "optional ultimate tensile strength, Pa; absent: the default forging steel "
          "(42CrMo4 +QT, EN 10083-3, 900 MPa)", "> 0"),
    Field("yield_strength_pa", "optional yield strength, Pa; absent: the default forging steel (650 MPa)",
          "> 0, at most `tensile_strength_pa`"),
    Field("surface", "optional fillet finish, for the Marin surface factor", one_of(SURFACES)),
    Field("process", "optional manufacturing route, for the IACS M53 factor K (1.05, 1.05, 1.0, 0.93)",
          one_of(PROCESSES)),
    Field("surface_treatment", "optional treatment of the fillets (and drilling edges): the `fe` fatigue path "
          "multiplies its local fatigue strength by `surface_treatment_factor` (fillet rolling at the fillets only, "
          "the others at the oil bores too); absent or `none`: untreated. IACS M53 as written does not credit it",
          one_of(TREATMENTS)),
    Field("surface_treatment_factor", "the factor the treatment gives the local fatigue strength (fetorsion ships "
          "none: a process test or a guideline's table)", "> 0; required with a treatment other than `none`"),
    Field("surface_treatment_source", "where `surface_treatment_factor` comes from",
          "required with a treatment other than `none`"),
    Field("source", "where the numbers come from", "a string"),
), required=True)

ENGINE = Section("engine", "The slider-crank data; read the same way in a crank description and in a "
                 "chain file.", (
    Field("cylinders", "number of cylinders N", "integer >= 1"),
    Field("cycle_strokes", "4 (default) or 2", "one of `2`, `4`"),
    Field("stroke", "piston stroke (file length unit); the crank radius is R = stroke/2", "> 0"),
    Field("rod_length", "connecting-rod length, eye centre to eye centre (file length unit)",
          "> 0, longer than R"),
    Field("bore", "cylinder bore (file length unit); needed for the gas force", ">= 0; > 0 with a synthetic cycle"),
    Field("crank_angles_deg", "angle of each throw, deg: the throw's first cylinder (in-line: its only one) "
          "reaches TDC this far after cylinder 1", "one per throw (in-line and opposed: per cylinder; vee: N/2)"),
    Field("firing_order", "cylinders in firing sequence", "a permutation of 1..N that `crank_angles_deg` (and "
          "the bank angle) can fire"),
    Field("layout", "`in-line` (default): one cylinder per throw; `opposed`: one per throw, the cylinders "
          "alternating between two banks 180° apart (2, 4 ... in the second, reaching TDC 180° after their "
          "throw's angle); `vee`: two banks sharing each throw", "one of `in-line`, `vee`, `opposed`"),
    Field("bank_angle_deg", "vee: how far after the first bank's cylinder on the same throw the second bank's "
          "reaches TDC, deg (negative: before; a 90° V8 whose second bank leads is −90)",
          "in (−180, 180], not 0; required with `layout = \"vee\"`"),
    Field("numbering", "vee: `by-bank` (default): the first bank's cylinders are 1..N/2 front to rear, the "
          "second's N/2+1..N; `alternate`: 1 and 2 on throw 1 (first bank, second bank), 3 and 4 on throw 2 …",
          "one of `by-bank`, `alternate`; vee only"),
    Field("rods", "vee: how the two rods share a pin: `side-by-side` (default; the first bank's rod in front), "
          "`fork-and-blade` (both at mid-pin), `articulated` (the first bank's master rod on the pin carries "
          "the second bank's articulated rod on a knuckle pin; both at mid-pin)",
          "one of `side-by-side`, `fork-and-blade`, `articulated`; vee only"),
    Field("knuckle_radius", "articulated rods: the knuckle pin's distance from the master rod's big-end centre "
          "(file length unit)", "> 0; required with `rods = \"articulated\"`"),
    Field("knuckle_angle_deg", "articulated rods: the knuckle pin's angle from the master rod's axis towards the "
          "second bank, deg (default: the bank angle)", "in (−180, 180]; articulated rods only"),
    Field("articulated_rod_length", "articulated rods: the articulated rod's length, knuckle pin to piston pin "
          "(file length unit)", "longer than the crank radius and `knuckle_radius` together; required with "
          "`rods = \"articulated\"`"),
    Field("rod_spacing", "vee, side by side: the distance between the two big ends' centres along the pin "
          "(file length unit)", "> 0, less than the pin's length; required with side-by-side rods on unsplit "
          "pins; not taken with split pins (each rod at its half pin's mid-length)"),
), required=True)

JOURNALS = _round("journals", "Main journals, front to rear: T + 1 of them (T throws: N in-line and opposed, N/2 vee).",
                  True)
PINS = Section("pins", "Crank pins, front to rear: one per throw, T of them. A vee's pin may be split (docs/vee-engines.md, "
               "*split pins*): two half pins of (`length` − `flying_web_thickness`)/2 each, the front one at the "
               "throw's angle carrying the first bank's rod, the rear one at the throw's angle plus "
               "`split_angle_deg` carrying the second bank's, joined by a flying web whose outline is the convex "
               "hull of the two half pins' circles.", _ROUND + (
    Field("split_angle_deg", "split pin: how far after the front half's rod the rear half's reaches TDC, through "
          "the split alone, deg (negative: before; an even-firing 90° V6 is ±30)",
          "in (−180, 180), not 0; vee with side-by-side rods only; on every pin or none; the half pins must "
          "overlap: stroke × sin(|split|/2) < `diameter`"),
    Field("flying_web_thickness", "split pin: the axial thickness of the flying web between the two half pins "
          "(file length unit)", "> 0, less than `length`; required with `split_angle_deg`; each half pin longer "
          "than the pin fillet (and with room for a pin drilling at its mid-length)"),
), array=True, required=True)
WEBS = Section("webs", "Crank webs, front to rear: 2T of them; webs 2i−1 and 2i belong to throw i. The outline "
               "is the convex hull of the circle of diameter `width_journal` around the crank axis and the "
               "circle of diameter `width_pin` around the pin centre, united with the counterweight sector.", (
    Field("thickness", "axial thickness L_b (file length unit)", "> 0"),
    Field("width_journal", "B_max: diameter of the web's circle around the crank axis (file length unit)",
          ">= its journal's diameter"),
    Field("width_pin", "B_min: diameter of the web's circle around the pin centre (file length unit)",
          ">= its pin's diameter (the pin lies inside its web)"),
    Field("counterweight_radius", "optional counterweight sector opposite the pin: its radius (file length unit)",
          ">= 0; with `counterweight_angle_deg`"),
    Field("counterweight_angle_deg", "the counterweight sector's angle, deg", "0 to 360; with `counterweight_radius`"),
), array=True, required=True)
FRONT = _round("front", "Round sections ahead of journal 1, tip first (pulley end).", False)
REAR = _round("rear", "Round sections behind the last journal, flywheel flange last.", False)

FILLETS = Section("fillets", "Fillet radii where journals and pins meet the webs.", (
    Field("journal", "journal fillet radius (file length unit); default 0", ">= 0, < half of every web's thickness"),
    Field("pin", "pin fillet radius (file length unit); default 0", ">= 0, < half of every web's thickness"),
))

OIL_HOLES = Section("oil_holes", "Diametral oil drillings.", (
    Field("diameter", "drilling diameter (file length unit); default 0", ">= 0, smaller than the length and "
          "wall of each drilled part"),
    Field("in_journals", "drill every main journal", "true or false"),
    Field("in_pins", "drill every pin", "true or false"),
))

SOLID = Section("solid", "Optional: the crank's solid from CAD in place of the one built from the dimensions. The "
                "solid's crank axis is the x axis, its front (pulley) end at x = 0, as fetorsion builds it, unless `axis` and "
                "`front_centre` say where they are in the file; the "
                "tables above still say where the journals and pins lie (the parts are cut there) and what the "
                "fillets and drillings are. Before any work the journals (cylinders coaxial with x) and pins "
                "(cylinders on the described pin axes) found on the solid are checked against the journal and pin "
                "tables (a diameter more than 2 % off is refused, naming the part); the fillets found on it (the "
                "concave tori at each journal and pin end, an undercut's several faces one fillet, its smallest "
                "radius) are reported beside `[fillets]`, which the SCF formulas keep reading.", (
    Field("step", "a STEP file (`.step`, `.stp`; path relative to the description), one closed solid; its "
          "header's unit is read (a solid whose length or journal diameters disagree with the description's by a "
          "factor of about 1000, 25.4 or 10 is refused, naming the unit slip)", "an existing file"),
    Field("axis", "`[x, y, z]`: the crank axis in the STEP file's coordinates, from the front (pulley) end to "
          "the rear; default `[1, 0, 0]`. The solid is turned to put it on x", "a direction, not zero"),
    Field("front_centre", "`[x, y, z]`: the point of the crank axis at the front end face in the STEP file's "
          "coordinates (the description's length unit); default the origin. The solid is moved to put it at "
          "x = 0, then turned about the axis so that the pin found nearest the first throw's place lies at "
          "its described angle", "three numbers"),
    Field("source", "where the solid comes from", "a string"),
))

ATTACHMENTS = Section("attachments", "Rigid bodies fixed to the shaft.", (
    Field("name", "label", "a string"),
    Field("at", "where: `front` (pulley face), `rear` (flywheel flange face), `pins` (one on every pin: piston "
          "and rod, inertia per cylinder about the crank axis)", one_of(ATTACH_POINTS)),
    Field("polar_inertia_kgm2", "polar moment of inertia about the crank axis, kg·m²", "> 0"),
    Field("mass_kg", "mass, kg; default 0", ">= 0"),
    Field("diametral_inertia_kgm2", "moment of inertia about a diameter, kg·m²; default 0", ">= 0"),
    Field("offset", "axial offset of its centre from the face (file length unit); default 0", "a number"),
    Field("source", "where the numbers come from", "a string"),
), array=True)

BEARINGS = Section("bearings", "Main bearings for the condensed crank and the FE with supports (see "
                   "{doc}`condensed-crank`). Either a radial stiffness and damping, or an oil film (`clearance`, "
                   "`oil_viscosity_pa_s`, `load_n`, `speed_rpm`). Without the table the bearings are rigid.", (
    Field("radial_stiffness_n_per_m", "main-bearing radial stiffness, N/m: one value, one per journal, or "
          "`\"rigid\"` (the default)", "> 0 or `\"rigid\"`; a list has one entry per journal"),
    Field("radial_damping_ns_per_m", "radial damping, N·s/m: one value or one per journal; default 0", ">= 0"),
    Field("clearance", "oil film: radial clearance (file length unit), one value or one per journal",
          "> 0, smaller than the journal radius; not with `radial_stiffness_n_per_m` or `radial_damping_ns_per_m`"),
    Field("oil_viscosity_pa_s", "oil film: the oil's dynamic viscosity at the film temperature, Pa·s (SAE 10W-40 "
          "near 100 °C: about 0.01)", "> 0; required with an oil film"),
    Field("load_n", "oil film: static load per journal, N, one value or one per journal; default each journal's "
          "mean load over the cycle from the crank's own gas and inertia forces", "> 0; required when there is "
          "no `[excitation]`"),
    Field("speed_rpm", "oil film: the speed the film coefficients are taken at, rpm; default the top of "
          "`[excitation] speed_range_rpm`", "> 0; required with an oil film when there is no speed range"),
    Field("width", "bearing width (file length unit), centred on the journal; default the journal's length",
          "> 0, at most the journal's length"),
    Field("axial_stiffness_n_per_m", "thrust bearing stiffness, N/m or `\"rigid\"`; default none (axially free)",
          ">= 0 or `\"rigid\"`"),
    Field("thrust_journal", "the journal (1-based) that carries the thrust bearing", "an existing journal; "
          "required with `axial_stiffness_n_per_m`"),
    Field("source", "where the numbers come from", "a string"),
))

UNCERTAINTY = Section("uncertainty", "The range of each reconstructed input, for `fetorsion study`. A key is a "
                      "field path (`\"webs.*.thickness\"`, 1-based indices, `*` = every entry) with "
                      "`[low, high]` in file units; or a group name with an inline table of such paths that move "
                      "together (low with low), e.g. a material's E and density.", (
    Field("<field path>", "`[low, high]`: the range of one input (file units)", "names a numeric field, not a "
          "count (`engine.cylinders`); low < high; contains the nominal value; the description with the input at "
          "either bound obeys every rule"),
    Field("<group name>", "`{ \"path\" = [low, high], ... }`: inputs that move together", "as above, per member"),
), free=True)

DESIGN = Section("design", "Optional: what `fetorsion design` may change to make the crank pass its fatigue "
                 "verdict, and what it minimises. Each input is a field path with `[low, high]` (file units), as "
                 "in `[uncertainty]`; a damper may be added.", (
    Field("objective", "`\"mass\"` (the crank's, and an added damper ring's; default), `\"inertia\"` (the "
          "rotating inertia) or `\"change\"` (the sum of the moved inputs' relative changes)", "one of these"),
    Field("damper", "a damper type the search may add at the pulley end: `\"rubber\"`, `\"viscous\"` or "
          "`\"tuned\"`; tuned by Den Hartog's rule to the first mode seen from the pulley", "one of these"),
    Field("damper_inertia_ratio", "`[low, high]`: the added ring's inertia over the first mode's equivalent "
          "inertia at the pulley", "0 < low < high <= 1; required with `damper`"),
    Field("damper_ring_radius", "radius of gyration of the added ring (file length unit): its mass is "
          "inertia / radius²", "> 0; required with `damper` and objective mass"),
    Field("required_safety", "the fatigue safety the design must reach; default the method's own (M53: 1.15)",
          ">= 1"),
    Field("damper_heat_rating_w", "the added damper's continuous heat rating, W: its largest mean dissipation "
          "over the speed range may not exceed it (written as its `allowed_power_w`)", "> 0; with `damper`"),
    Field("resonance_orders", "the major orders whose resonance with the first mode in the bearings (the lowest "
          "with 10 % or more of its kinetic energy in torsion) must stay out of the running range "
          "(`speed_range_rpm`) by `resonance_margin`", "a list of orders > 0; with `resonance_margin`"),
    Field("resonance_margin", "how far each resonance speed 60 f1 / q must lie outside the running range, as a "
          "share of the range's nearer end (0.1: below 0.9 × low or above 1.1 × high)", "0 < margin < 1; with "
          "`resonance_orders`"),
    Field("<field path>", "`[low, high]`: an input the search may move (file units; the given value may lie "
          "outside: a rule the design must meet)", "names a numeric field; low < high"),
), free=True)

DISTRIBUTIONS = Section("distributions", "Optional: how `fetorsion study` draws an `[uncertainty]` entry in "
                        "Monte Carlo and Sobol' studies (a group: its first member, the others at the same fraction "
                        "of their ranges). An entry not named is uniform; Morris levels and grids span the ranges.", (
    Field("<uncertainty entry>", "`\"uniform\"`, `\"triangular\"` (peaks at the nominal value) or "
          "`{ kind = \"normal\", sd = S }` (centred on the nominal value, standard deviation S in file units, "
          "truncated to the range)", "names an `[uncertainty]` entry; triangular: nominal below the high bound; "
          "normal: S > 0"),
), free=True)

EXCITATION = Section("excitation", "What drives the crank: the cylinder pressure (exactly one of `pressure_csv`, "
                     "`imep_pa`, `peak_pressure_pa`), the reciprocating mass, the speed range and the damping "
                     "assumed. Read the same way in a crank description and in a chain file.", (
    Field("reciprocating_mass_kg", "per-cylinder reciprocating mass (piston, pin, rod small-end share), kg", ">= 0"),
    Field("rotating_mass_kg", "per-cylinder mass turning with the crank pin (the rod's big-end share), kg: its "
          "centrifugal force m R Ω² adds to the radial pin force, so it loads the fatigue assessment's mean "
          "stress and an oil film's mean load, not the vibration; default 0 (left out)", ">= 0"),
    Field("speed_range_rpm", "operating range `[low, high]`, rpm (high = rated speed)", "0 < low < high"),
    Field("overspeed_factor", "the forced response, Campbell diagram and verdict cover [low, factor × high] rpm "
          f"(default {DEFAULT_OVERSPEED}: crank fatigue is checked to overspeed)", ">= 1"),
    Field("pressure_csv", "cylinder pressure: a CSV of rows `angle_deg, pressure_pa` (0 = firing TDC, over one "
          "cycle; path relative to the description)", ">= 8 rows of finite numbers, angles ascending, pressure > 0, "
          "covering one whole cycle (720° for a 4-stroke, 360° for a 2-stroke; one step short at most)"),
    Field("imep_pa", "synthetic 4-stroke cycle scaled to this indicated mean effective pressure, Pa: a value or "
          "`[[rpm, Pa], ...]`", "> 0; exactly one of `pressure_csv`, `imep_pa`, `propeller_law_imep_pa`, `peak_pressure_pa`"),
    Field("peak_pressure_pa", "synthetic 4-stroke cycle scaled to this peak pressure, Pa: a value or "
          "`[[rpm, Pa], ...]`", "above the motored peak p_intake·CR^n at every speed"),
    Field("compression_ratio", "synthetic cycle: compression ratio", "> 1; required with a synthetic cycle"),
    Field("intake_pressure_pa", "synthetic cycle: intake pressure, Pa; default 1 bar", "> 0"),
    Field("polytropic_exponent", "synthetic cycle: polytropic exponent n of compression and expansion; "
          "default 1.3", "1 < n < 1.67"),
    Field("combustion_start_deg", "synthetic cycle: start of the Wiebe heat release, deg after TDC; default −15",
          "−90 to 90"),
    Field("combustion_duration_deg", "synthetic cycle: duration of the heat release, deg; default 50",
          "0 to 180"),
    Field("wiebe_a", "synthetic cycle: Wiebe efficiency parameter a; default 5", "> 0"),
    Field("wiebe_m", "synthetic cycle: Wiebe form factor m; default 2", ">= 0"),
    Field("modal_damping_ratio", "ζ for the Campbell severities and the forced response; default "
          f"{DEFAULT_DAMPING_RATIO}", "0 < ζ < 1 (a chain that states its own damping may give 0)"),
    Field("modal_damping_band", "`[low, high]` of ζ: the verdict's sensitivity to damping (it is decided at "
          "`modal_damping_ratio`); default [1/120, 1/60] (dynamic magnifier Q = 30–60, stated as engine "
          "practice, no published table read)", "0 < low <= high < 1"),
    Field("modal_damping_source", "where the damping band comes from", "required with `modal_damping_band`"),
    Field("modal_damping_ratio_source", "where `modal_damping_ratio` comes from (a measurement, a published "
          "table); without it the verdict says its damping is assumed", "text"),
    Field("bending_damping_ratio", "ζ of the condensed crank's bending modes in its bearings (each mode "
          "takes ζ_t s + ζ_b (1 − s), s its torsion share of kinetic energy); without it every mode takes "
          "`modal_damping_ratio`, and the report gives the `fe` fatigue path at ζ_b 0.02 and 0.10 unless "
          "an oil film in `[bearings]` damps the bending", "0 < ζ_b < 1"),
    Field("bending_damping_ratio_source", "where `bending_damping_ratio` comes from",
          "required with `bending_damping_ratio`"),
    Field("tangential_harmonics", "instead of a pressure: the engine maker's tangential-pressure harmonic table "
          "(`[[excitation.tangential_harmonics]]`), read at the load's `imep_pa` or `propeller_law_imep_pa`",
          "with `harmonic_imep_pa`"),
    Field("harmonic_imep_pa", "the harmonic table's columns: mean indicated pressures, Pa; a column at 0 holds the "
          "motored cylinder's harmonics, which a misfiring cylinder follows (without it no misfire is computed)",
          ">= 0, ascending"),
    Field("tangential_pressure_unit", "the harmonic table's unit: `Pa` (default), `bar` or `MPa`", "one of these"),
    Field("propeller_law_imep_pa", "with the harmonic table or the synthetic cycle: p_mi at the top of "
          "`speed_range_rpm`, Pa, the load's p_mi ∝ n² below it (an engine on a fixed-pitch propeller's curve)",
          "> 0; or `imep_pa`"),
))

TANGENTIAL_HARMONICS = Section("excitation.tangential_harmonics", "One order q of the tangential-pressure table: "
                               "p_t(θ) = a_q sin qθ + b_q cos qθ = P_q sin(qθ + φ_q), θ from the cylinder's firing "
                               "TDC; the gas torque is p_t × piston area × crank radius (docs/propulsion-tvc.md).", (
    Field("order", "q, per crank revolution", "> 0"),
    Field("sine", "a_q, one per `harmonic_imep_pa` column", "or `amplitude` and `phase_deg`"),
    Field("cosine", "b_q, one per column", "with `sine`"),
    Field("amplitude", "P_q, one per column", "with `phase_deg`"),
    Field("phase_deg", "φ_q, deg, one per column", "with `amplitude`"),
    Field("misfire_sine", "a_q of the misfiring cylinder (its motored cycle at the running boost: the engine maker's "
          "misfire table), one value; a misfire reads these before the table's column at p_mi 0", "with "
          "`misfire_cosine`, for every order or none"),
    Field("misfire_cosine", "b_q of the misfiring cylinder, one value", "with `misfire_sine`"),
), array=True)

DAMPERS = Section("dampers", "Torsional dampers, in crank descriptions and chain files. A damper's ring is one more "
                  "degree of freedom joined to the pulley-end (or flywheel-end) station; its hub or housing adds "
                  "to that station. The forced response and the Campbell diagram include every damper; "
                  "`fetorsion damper` designs one (see {doc}`dampers`).", (
    Field("type", "`viscous` (Houdaille), `rubber` (tuned rubber) or `tuned` (plain tuned absorber)",
          one_of(DAMPER_TYPES)),
    Field("at", "`front` (pulley end, default) or `rear` (flywheel side): the first or last station of the chain; "
          "in a network the first station or the last one at the engine's speed, or a station's name (one at the "
          "engine's speed)", one_of(DAMPER_STATIONS) + "; in a network also a station's name"),
    Field("ring_inertia_kgm2", "inertia of the seismic ring, kg·m²", "> 0, required"),
    Field("housing_inertia_kgm2", "viscous: housing inertia added to the station, kg·m²; default 0",
          ">= 0; refused for the other types"),
    Field("hub_inertia_kgm2", "rubber, tuned: hub inertia added to the station, kg·m²; default 0",
          ">= 0; refused for a viscous damper"),
    Field("damping_nms_per_rad", "viscous coefficient between station and ring, N·m·s/rad",
          "viscous: > 0, required; tuned: >= 0, optional"),
    Field("stiffness_nm_per_rad", "rubber, tuned: the spring between station and ring, N·m/rad "
          "(rubber: k (1 + iη))", "> 0"),
    Field("loss_factor", "rubber: hysteretic loss factor η", "> 0"),
    Field("dynamic_table", "rubber, instead of `stiffness_nm_per_rad` / `loss_factor`: rows "
          "`[frequency_hz, stiffness_nm_per_rad, loss_factor]`, linear in frequency, held at the end rows outside; "
          "or rows `[temperature_c, frequency_hz, stiffness_nm_per_rad, loss_factor]` read linearly between the two "
          "nearest temperatures (the end one outside the range)", ">= 2 rows (per temperature), frequency "
          "ascending, k > 0, η >= 0"),
    Field("temperature_c", "the operating temperature, °C, at which a `dynamic_table` with a temperature column "
          "is read", "a finite number; only with a temperature column"),
    Field("ambient_c", "instead of `temperature_c`: the air around the damper, °C; with "
          "`thermal_conductance_w_per_k` the rubber sits at the temperature its own dissipation holds, "
          "T = T_air + P_max/G (P_max its largest mean dissipation over the speed range), found by the response",
          "a finite number; only with a temperature column and `thermal_conductance_w_per_k`; not with "
          "`temperature_c`"),
    Field("thermal_conductance_w_per_k", "the damper's heat path to the air G, W/K (with `ambient_c`)", "> 0"),
    Field("allowed_power_w", "the heat the damper may dissipate continuously (its maker's rating), W: the "
          "verdict fails when the damper's heat at the worst speed exceeds it", "> 0; optional"),
    Field("name", "label; default the type", "a string"),
    Field("source", "where the data come from", "a string"),
), array=True)

LIMITS = Section("limits", "A crank description: the fatigue verdict's overrides (every field optional; the "
                 "verdict is the fatigue assessment, its strength the material's). A chain or network file, which "
                 "has no sections: the permissible vibratory section torque (`continuous_torque_nm`). The shear "
                 "stress limits of earlier versions (`continuous_shear_pa`, `fatigue_strength_shear_pa`, "
                 "`safety_factor`, `transient_shear_pa`) are refused in a crank description: they were a second "
                 "verdict with a strength of its own.", (
    Field("continuous_torque_nm", "chain or network file: the continuous limit as a section torque amplitude, N·m",
          "> 0"),
    Field("transient_torque_nm", "chain or network file: the transient limit as a section torque amplitude, N·m; "
          "optional", ">= the continuous limit"),
    *(Field(k, "refused in a crank description (the shear-limit verdict of earlier versions); a chain or network "
          "file does not take it either", "refused") for k in ("continuous_shear_pa", "fatigue_strength_shear_pa",
                                                                "safety_factor", "transient_shear_pa")),
    Field("fatigue_method", "the method that decides a crank's verdict: `iacs-m53` (IACS UR M53 as written) or "
          "`fe` (fetorsion's own: the condensed crank's load cycle, FE SCFs, Marin factors and Goodman); "
          "the run's own choice of method overrides it", "iacs-m53 or fe; optional (default iacs-m53)"),
    Field("fatigue_strength_bending_pa", "the crank's alternating bending fatigue strength as built (a bench test "
          "of its throws, a supplier's figure), against local stresses (SCF × nominal), Pa: replaces each "
          "method's own (M53's σ_DW; the `fe` path's S_e, then with the full K_t)", ">= 0; optional "
          "(0: the method's own)"),
    Field("additional_bending_pa", "IACS UR M53's additional bending stress σ_add at the fillets (misalignment, "
          "bedplate deformation, axial and bending vibration), Pa; default M53 §4's ±10 N/mm² of a trunk-piston "
          "engine (±30 for a crosshead engine)", ">= 0; optional"),
    Field("fatigue_required_safety", "the fatigue assessment's required safety", ">= 1; optional (default the "
          "method's: M53 1.15, fe 1.0)"),
    Field("source", "where every number of the table comes from", "required, not empty"),
))

#: The tables of a crank description, in the order the documentation shows them.
CRANK_SECTIONS = (META, UNITS, MATERIAL, ENGINE, JOURNALS, PINS, WEBS, FRONT, REAR, FILLETS, OIL_HOLES, SOLID, ATTACHMENTS,
                  BEARINGS, EXCITATION, TANGENTIAL_HARMONICS, DAMPERS, LIMITS, UNCERTAINTY, DISTRIBUTIONS, DESIGN)


def schema(sections) -> dict[str, frozenset[str] | None]:
    """What :class:`~fetorsion.description.reader.Table` checks against: table name → its
    declared keys (None for a free table), and ``""`` (the file's top level) → the table names."""
    out: dict[str, frozenset[str] | None] = {s.name: None if s.free else s.keys for s in sections}
    out[""] = frozenset(s.name for s in sections)
    return out


CRANK_SCHEMA = schema(CRANK_SECTIONS)


def _cell(text: str) -> str:
    return text.replace("|", "\\|") or "—"


def markdown(sections, heading: str = "###") -> str:
    """The tables and fields of ``sections`` as Markdown: one heading and one table per TOML table.

    Examples
    --------
    >>> "youngs_modulus_pa" in markdown(CRANK_SECTIONS)
    True
    """
    parts = []
    for s in sections:
        flags = ", ".join(w for w, on in (("required", s.required), ("array of tables", s.array),
                                          ("free keys", s.free)) if on) or "optional"
        parts.append(f"{heading} `{s.header}`\n\n*{flags}.* {s.intro}\n\n| key | meaning | rule |\n|---|---|---|")
        for f in s.fields:
            # "<field path>": a key of the user's choosing, shown in italics (MyST would take <...> for HTML)
            key = f"*{f.key[1:-1]}*" if f.key.startswith("<") else f"`{f.key}`"
            parts.append(f"| {_cell(key)} | {_cell(f.meaning)} | {_cell(f.rule)} |")
        parts.append("")
    return "\n".join(parts)
