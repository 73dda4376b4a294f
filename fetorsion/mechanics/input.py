"""The small TOML file read by ``fetorsion kinematics | balance | flywheel``.

One file may hold any of the tables below; each command needs only its own. Lengths are
in ``[units] length`` (m, cm, mm, in); other quantities carry their unit in the key name.
Unknown keys and tables are rejected; every violated rule is reported at once.
Examples: ``geometry/b112_single.toml`` ([Asgari]), ``geometry/planetary_ismailov.toml``
([Ismailov]).

.. code-block:: toml

    [meta]                       # free-form: name, source, notes
    name = "Kiasa B112"
    [units]
    length = "mm"

    [slider_crank]               # kinematics, balance
    crank_radius = 35.5
    rod_length = 117.5           # eye centre to eye centre
    speed_rpm = 3000.0

    [masses]                     # balance ([Asgari] §2)
    rod_kg = 0.625
    rod_centroid_to_big_end = 33.923
    rod_centroid_to_small_end = 83.577
    piston_kg = 0.661            # piston group
    crank_kg = 1.233             # unbalanced crank part
    crank_centroid_radius = 28.706

    [balance]                    # balance
    share_c = 0.5                # part of m1 in the counterweight (0.5-0.63)
    counterweight_radius = 31.34
    shaft_radius = 21.512        # optional: balance-shaft mass centroid radius
    overbalance_k = 0.6          # optional: a counterweight k = m_b r_b/(m_j r) ...
    overbalance_alpha_deg = 5.0  # ... advanced by alpha, whose residual locus is shown

    [flywheel]                   # flywheel ([Asgari] §3)
    power_w = 7000.0
    speed_rpm = 3000.0
    speed_fluctuation = 0.04     # C_s
    outer_diameter = 270.0       # optional, with inner_diameter: mass and checks
    inner_diameter = 210.0
    material = "steel"           # optional: "steel" or "cast_iron" rim-speed limits
    stroke = 85.0                # optional: mean-diameter check (default 2 x crank_radius)
    other_inertia_kgm2 = 0.11    # optional: I_F/I_T check
    cycle_strokes = 4            # optional: 4 or 2

    [planetary]                  # kinematics ([Ismailov])
    kind = "epicycloid"          # or "hypocycloid"
    fixed_diameter = 60.0
    planet_diameters = [20.0, 30.0, 40.0]
    rod_length = 200.0
    eccentricity = 10.0          # optional: big end off the satellite centre (default d_p/2)
    pin_phase_deg = 0.0          # optional
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..description.reader import Table, read_length_unit, read_toml
from ..errors import DescriptionError, Problem
from .flywheel import RIM_SPEED_LIMITS

TABLES = ("meta", "units", "slider_crank", "masses", "balance", "flywheel", "planetary")


@dataclass(frozen=True)
class SliderCrank:
    crank_radius: float
    rod_length: float
    speed_rpm: float


@dataclass(frozen=True)
class Masses:
    rod_kg: float
    rod_centroid_to_big_end: float
    rod_centroid_to_small_end: float
    piston_kg: float
    crank_kg: float
    crank_centroid_radius: float


@dataclass(frozen=True)
class BalanceSpec:
    share_c: float
    counterweight_radius: float
    shaft_radius: float | None
    overbalance_k: float | None
    overbalance_alpha_deg: float | None


@dataclass(frozen=True)
class FlywheelSpec:
    power_w: float
    speed_rpm: float
    speed_fluctuation: float
    outer_diameter: float | None
    inner_diameter: float | None
    material: str | None
    stroke: float | None
    other_inertia_kgm2: float | None
    cycle_strokes: int


@dataclass(frozen=True)
class PlanetarySpec:
    kind: str
    fixed_diameter: float
    planet_diameters: tuple[float, ...]
    rod_length: float
    eccentricity: float | None
    pin_phase_deg: float


@dataclass(frozen=True)
class MechanicsInput:
    """Parsed mechanics file, SI units; absent tables are None."""

    name: str
    source: str
    slider_crank: SliderCrank | None = None
    masses: Masses | None = None
    balance: BalanceSpec | None = None
    flywheel: FlywheelSpec | None = None
    planetary: PlanetarySpec | None = None

    def need(self, *tables: str) -> None:
        """Raise a DescriptionError naming every table a command needs but the file lacks."""
        missing = [Problem(t, None, "this command needs the table") for t in tables if getattr(self, t) is None]
        if missing:
            raise DescriptionError(self.source, missing)


def _optional(t: Table, key: str, **rules):
    return t.number(key, **rules) if key in t.data else (t.used.add(key) or None)


def parse_mechanics(data: dict, source: str = "<mechanics>") -> MechanicsInput:
    """Build a :class:`MechanicsInput` from a parsed TOML mapping; see the module docs."""
    problems: list[Problem] = []
    root = Table(data, "", problems)
    read_length_unit(root, source)
    meta = root.table("meta", required=False)
    name = meta.text("name", default=Path(source).stem)
    meta.used.update(meta.data)
    readers = {"slider_crank": _slider_crank, "masses": _masses, "balance": _balance, "flywheel": _flywheel,
               "planetary": _planetary}
    out = {key: read(root) for key, read in readers.items() if key in data}
    for key in TABLES[2:]:
        root.used.add(key)
    root.finish()
    if problems:
        raise DescriptionError(source, problems)
    return MechanicsInput(name, source, **out)


def _slider_crank(root: Table) -> SliderCrank:
    """``[slider_crank]``: crank radius, rod length (eye to eye) and speed."""
    t = root.table("slider_crank")
    sc = SliderCrank(t.number("crank_radius", length=True, positive=True),
                     t.number("rod_length", length=True, positive=True),
                     t.number("speed_rpm", positive=True))
    t.finish()
    if sc.rod_length <= sc.crank_radius:
        root.problems.append(Problem("slider_crank.rod_length", sc.rod_length / root.scale,
                                     f"must be longer than crank_radius ({sc.crank_radius / root.scale:g})"))
    return sc


def _masses(root: Table) -> Masses:
    """``[masses]``: the rod, piston and crank masses and the rod's centroid distances ([Asgari] §2)."""
    t = root.table("masses")
    m = Masses(t.number("rod_kg", positive=True),
               t.number("rod_centroid_to_big_end", length=True, nonnegative=True),
               t.number("rod_centroid_to_small_end", length=True, nonnegative=True),
               t.number("piston_kg", nonnegative=True), t.number("crank_kg", nonnegative=True),
               t.number("crank_centroid_radius", length=True, nonnegative=True))
    t.finish()
    if m.rod_centroid_to_big_end + m.rod_centroid_to_small_end <= 0:
        root.problems.append(Problem("masses.rod_centroid_to_small_end", 0.0, "the two rod distances cannot both be 0"))
    return m


def _balance(root: Table) -> BalanceSpec:
    """``[balance]``: the counterweight's share and radius, a balance shaft's radius and an
    over-balancing counterweight (k and its advance, given together)."""
    t = root.table("balance")
    b = BalanceSpec(t.number("share_c", nonnegative=True, below=1.0),
                    t.number("counterweight_radius", length=True, positive=True),
                    _optional(t, "shaft_radius", length=True, positive=True),
                    _optional(t, "overbalance_k", nonnegative=True),
                    _optional(t, "overbalance_alpha_deg"))
    t.finish()
    if (b.overbalance_k is None) != (b.overbalance_alpha_deg is None):
        root.problems.append(Problem("balance.overbalance_k", b.overbalance_k,
                                     "give overbalance_k and overbalance_alpha_deg together"))
    return b


def _flywheel(root: Table) -> FlywheelSpec:
    """``[flywheel]``: power, speed and fluctuation, and the optional rim (diameters, material), stroke
    and other inertia of the checks."""
    t = root.table("flywheel")
    strokes = t.choice("cycle_strokes", (2, 4), 4)
    material = t.text("material", default="", choices=tuple(RIM_SPEED_LIMITS)) if "material" in t.data else None
    t.used.add("material")
    f = FlywheelSpec(t.number("power_w", positive=True), t.number("speed_rpm", positive=True),
                     t.number("speed_fluctuation", positive=True, below=1.0),
                     _optional(t, "outer_diameter", length=True, positive=True),
                     _optional(t, "inner_diameter", length=True, nonnegative=True),
                     material, _optional(t, "stroke", length=True, positive=True),
                     _optional(t, "other_inertia_kgm2", positive=True),
                     strokes)
    t.finish()
    if (f.outer_diameter is None) != (f.inner_diameter is None):
        root.problems.append(Problem("flywheel.inner_diameter", f.inner_diameter,
                                     "give outer_diameter and inner_diameter together"))
    elif f.outer_diameter is not None and not f.inner_diameter < f.outer_diameter:
        root.problems.append(Problem("flywheel.inner_diameter", f.inner_diameter / root.scale,
                                     f"must be smaller than outer_diameter ({f.outer_diameter / root.scale:g})"))
    return f


def _planetary(root: Table) -> PlanetarySpec:
    """``[planetary]``: the gear kind, fixed and planet diameters, rod length, eccentricity and pin phase."""
    t = root.table("planetary")
    kind = t.text("kind", choices=("epicycloid", "hypocycloid"))
    fixed = t.number("fixed_diameter", length=True, positive=True)
    planets = tuple(v * root.scale for v in t.numbers("planet_diameters"))
    spec = PlanetarySpec(kind, fixed, planets, t.number("rod_length", length=True, positive=True),
                         _optional(t, "eccentricity", length=True, nonnegative=True),
                         t.number("pin_phase_deg", 0.0))
    t.finish()
    for i, d in enumerate(planets):
        if not d > 0 or (kind == "hypocycloid" and not d < fixed):
            root.problems.append(Problem(f"planetary.planet_diameters[{i + 1}]", d / root.scale,
                                         "must be > 0" + (" and smaller than fixed_diameter" if kind == "hypocycloid" else "")))
    return spec


def load_mechanics(path) -> MechanicsInput:
    """Read a mechanics TOML file (module docs) into SI units.

    Examples
    --------
    >>> spec = load_mechanics("geometry/b112_single.toml")
    >>> round(spec.slider_crank.crank_radius, 4), spec.balance.share_c
    (0.0355, 0.5)
    """
    path = Path(path)
    return parse_mechanics(read_toml(path), source=str(path))


def is_crank_description(data: dict) -> bool:
    """A full crank description (``fetorsion.load``) rather than a mechanics file."""
    return "engine" in data and "slider_crank" not in data
