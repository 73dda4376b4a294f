"""The crank description: one TOML file, parsed into frozen dataclasses in SI units.

Every later step (Gmsh solid, FE modal, lumped models, Campbell) reads a :class:`Crank`.
The file format is documented in ``docs/description-format.md``; ``geometry/*.toml`` are
examples. Lengths are in the unit the file names in ``[units] length``; every other
quantity carries its SI unit in its key name (``density_kgm3``, ``polar_inertia_kgm2``).

Validation collects every violated rule (field, value, rule) and raises one
:class:`~fetorsion.errors.DescriptionError` before any work starts.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .errors import DescriptionError, Problem
from .units import LENGTH_UNITS

ATTACH_POINTS = ("front", "rear", "pins")


@dataclass(frozen=True)
class Material:
    """Linear elastic isotropic material, SI units (Pa, -, kg/m³)."""

    youngs_modulus: float
    poisson_ratio: float
    density: float
    name: str = ""

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


@dataclass(frozen=True)
class Engine:
    """Cylinder layout and slider-crank data; lengths in m, angles in rad."""

    cylinders: int
    strokes_per_cycle: int
    stroke: float
    rod_length: float
    crank_angles: tuple[float, ...]
    firing_order: tuple[int, ...]
    bore: float = 0.0

    @property
    def crank_radius(self) -> float:
        """R = stroke / 2 in m."""
        return 0.5 * self.stroke


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
    at: str
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
    modal_damping_ratio: float = 0.02


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
    def cylinders(self) -> int:
        return self.engine.cylinders

    def throw_of_web(self, web_index: int) -> int:
        """0-based throw index of 0-based web ``web_index``."""
        return web_index // 2

    def journal_of_web(self, web_index: int) -> int:
        """0-based index of the journal a web is joined to (its own side)."""
        return web_index // 2 + web_index % 2

    def attachments_at(self, at: str) -> tuple[Attachment, ...]:
        return tuple(a for a in self.attachments if a.at == at)


@dataclass(frozen=True)
class Chain:
    """A torsional chain given directly: inertias (kg·m²), springs (N·m/rad), dampers.

    ``absolute_damping`` (N·m·s/rad, one per inertia, to ground) and
    ``relative_damping`` (N·m·s/rad, one per spring) are optional.
    """

    name: str
    inertias: tuple[float, ...]
    stiffnesses: tuple[float, ...]
    labels: tuple[str, ...]
    absolute_damping: tuple[float, ...] = ()
    relative_damping: tuple[float, ...] = ()
    source: str = ""


# ---------------------------------------------------------------------------
# Parsing with problem collection


class _Table:
    """Typed access to one TOML table that records problems instead of raising."""

    def __init__(self, data, path: str, problems: list[Problem], scale: float = 1.0):
        self.path = path
        self.problems = problems
        self.scale = scale
        if not isinstance(data, dict):
            problems.append(Problem(path, data, "must be a table"))
            data = {}
        self.data = data
        self.used: set[str] = set()

    def _name(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def _get(self, key: str, default):
        self.used.add(key)
        if key not in self.data:
            if default is _REQUIRED:
                self.problems.append(Problem(self._name(key), None, "is required"))
            return _MISSING if default is _REQUIRED else default
        return self.data[key]

    def number(self, key, default=None, *, length=False,
               positive=False, nonnegative=False, below=None, above=None):
        """A real number (required when ``default`` is None); ``length=True`` converts
        from the file's length unit to m."""
        raw = self._get(key, _REQUIRED if default is None else default)
        if raw is _MISSING:
            return math.nan
        if isinstance(raw, bool) or not isinstance(raw, (int, float)) or not math.isfinite(raw):
            self.problems.append(Problem(self._name(key), raw, "must be a finite number"))
            return math.nan
        value = float(raw)
        if positive and not value > 0:
            self.problems.append(Problem(self._name(key), raw, "must be > 0"))
        if nonnegative and value < 0:
            self.problems.append(Problem(self._name(key), raw, "must be >= 0"))
        if below is not None and not value < below:
            self.problems.append(Problem(self._name(key), raw, f"must be < {below}"))
        if above is not None and not value > above:
            self.problems.append(Problem(self._name(key), raw, f"must be > {above}"))
        return value * self.scale if length else value

    def integer(self, key, *, minimum=1):
        raw = self._get(key, _REQUIRED)
        if raw is _MISSING:
            return 0
        if isinstance(raw, bool) or not isinstance(raw, int) or raw < minimum:
            self.problems.append(Problem(self._name(key), raw, f"must be an integer >= {minimum}"))
            return 0
        return raw

    def text(self, key, default="", choices=None):
        raw = self._get(key, default)
        if raw is _MISSING:
            return ""
        if not isinstance(raw, str):
            self.problems.append(Problem(self._name(key), raw, "must be a string"))
            return ""
        if choices is not None and raw not in choices:
            self.problems.append(Problem(self._name(key), raw, f"must be one of {', '.join(choices)}"))
        return raw

    def flag(self, key, default=False):
        raw = self._get(key, default)
        if not isinstance(raw, bool):
            self.problems.append(Problem(self._name(key), raw, "must be true or false"))
            return False
        return raw

    def numbers(self, key, *, required=True):
        raw = self._get(key, _REQUIRED if required else [])
        if raw is _MISSING:
            return ()
        if not isinstance(raw, list) or any(
            isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in raw
        ):
            self.problems.append(Problem(self._name(key), raw, "must be a list of finite numbers"))
            return ()
        return tuple(float(v) for v in raw)

    def tables(self, key, *, required=True):
        raw = self._get(key, _REQUIRED if required else [])
        if raw is _MISSING:
            return []
        if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
            self.problems.append(Problem(self._name(key), raw, "must be an array of tables ([[...]])"))
            return []
        return [_Table(t, f"{self._name(key)}.{i + 1}", self.problems, self.scale) for i, t in enumerate(raw)]

    def table(self, key, *, required=True):
        raw = self._get(key, _REQUIRED if required else {})
        return _Table({} if raw is _MISSING else raw, self._name(key), self.problems, self.scale)

    def finish(self):
        """Report keys the reader never asked for: they are typos or unsupported."""
        for key in self.data:
            if key not in self.used:
                self.problems.append(Problem(self._name(key), self.data[key], "is not a known field here"))


_REQUIRED = object()
_MISSING = object()


def _read_toml(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise DescriptionError(str(path), [Problem("file", str(path), "does not exist")]) from None
    except tomllib.TOMLDecodeError as exc:
        raise DescriptionError(str(path), [Problem("file", str(path), f"is not valid TOML ({exc})")]) from None


def load(path) -> Crank | Chain:
    """Read a crank description or a chain file (``[chain]`` table) from TOML.

    Parameters
    ----------
    path : str or Path
        The ``.toml`` file.

    Returns
    -------
    Crank or Chain
        In SI units.

    Raises
    ------
    DescriptionError
        Listing every violated rule with its field, value and rule.

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> crank.engine.cylinders
    4
    """
    path = Path(path)
    data = _read_toml(path)
    if "chain" in data:
        return parse_chain(data, source=str(path))
    return parse_crank(data, source=str(path))


def parse_chain(data: dict, source: str = "<chain>") -> Chain:
    """Build a :class:`Chain` from a parsed TOML mapping with a ``[chain]`` table."""
    problems: list[Problem] = []
    root = _Table(data, "", problems)
    t = root.table("chain")
    root.used.add("meta")  # free-form notes, not checked
    name = t.text("name", default=Path(source).stem)
    inertias = t.numbers("inertias_kgm2")
    stiffnesses = t.numbers("stiffnesses_nm_per_rad")
    labels = t._get("labels", [])
    absolute = t.numbers("absolute_damping_nms_per_rad", required=False)
    relative = t.numbers("relative_damping_nms_per_rad", required=False)
    t.finish()
    root.finish()
    n = len(inertias)
    if inertias and n < 2:
        problems.append(Problem("chain.inertias_kgm2", list(inertias), "needs at least 2 inertias"))
    for i, v in enumerate(inertias):
        if not v > 0:
            problems.append(Problem(f"chain.inertias_kgm2[{i + 1}]", v, "must be > 0"))
    for i, v in enumerate(stiffnesses):
        if not v > 0:
            problems.append(Problem(f"chain.stiffnesses_nm_per_rad[{i + 1}]", v, "must be > 0"))
    if inertias and len(stiffnesses) != n - 1:
        problems.append(Problem("chain.stiffnesses_nm_per_rad", list(stiffnesses),
                                f"must have one spring fewer than inertias ({n - 1})"))
    if absolute and len(absolute) != n:
        problems.append(Problem("chain.absolute_damping_nms_per_rad", list(absolute),
                                f"must have one value per inertia ({n})"))
    if relative and len(relative) != n - 1:
        problems.append(Problem("chain.relative_damping_nms_per_rad", list(relative),
                                f"must have one value per spring ({n - 1})"))
    for key, values in (("absolute_damping_nms_per_rad", absolute), ("relative_damping_nms_per_rad", relative)):
        for i, v in enumerate(values):
            if v < 0:
                problems.append(Problem(f"chain.{key}[{i + 1}]", v, "must be >= 0"))
    if not isinstance(labels, list) or not all(isinstance(s, str) for s in labels) or (
        labels and len(labels) != n
    ):
        problems.append(Problem("chain.labels", labels, f"must be a list of {n} strings"))
        labels = []
    if problems:
        raise DescriptionError(source, problems)
    labels = tuple(labels) if labels else tuple(f"inertia {i + 1}" for i in range(n))
    return Chain(name, inertias, stiffnesses, labels, absolute, relative, source)


def _cylinder(t: _Table) -> Cylinder:
    d = t.number("diameter", length=True, positive=True)
    length = t.number("length", length=True, positive=True)
    bore = t.number("bore", 0.0, length=True, nonnegative=True)
    t.finish()
    if bore >= d:
        t.problems.append(Problem(f"{t.path}.bore", bore / t.scale, f"must be smaller than diameter ({d / t.scale:g})"))
    return Cylinder(d, length, bore)


def _web(t: _Table) -> Web:
    h = t.number("thickness", length=True, positive=True)
    b_max = t.number("width_journal", length=True, positive=True)
    b_min = t.number("width_pin", length=True, positive=True)
    r_cw = t.number("counterweight_radius", 0.0, length=True, nonnegative=True)
    a_cw = t.number("counterweight_angle_deg", 0.0, nonnegative=True)
    t.finish()
    if a_cw > 360:
        t.problems.append(Problem(f"{t.path}.counterweight_angle_deg", a_cw, "must be <= 360"))
    if (r_cw > 0) != (a_cw > 0):
        t.problems.append(Problem(f"{t.path}.counterweight_radius", r_cw / t.scale,
                                  "counterweight needs both counterweight_radius and counterweight_angle_deg > 0"))
    return Web(h, b_max, b_min, r_cw, math.radians(a_cw))


def read_length_unit(root: _Table, source: str) -> str:
    """Read ``[units] length`` and set the table's length scale; without a known unit no
    length can be checked, so that problem is raised at once."""
    units = root.table("units")
    unit = units.text("length", choices=tuple(LENGTH_UNITS))
    units.finish()
    if unit not in LENGTH_UNITS:
        raise DescriptionError(source, root.problems)
    root.scale = LENGTH_UNITS[unit]
    return unit


def parse_crank(data: dict, source: str = "<crank>") -> Crank:
    """Build a :class:`Crank` from a parsed TOML mapping; see :func:`load`."""
    problems: list[Problem] = []
    root = _Table(data, "", problems)
    unit = read_length_unit(root, source)

    meta = root.table("meta", required=False)
    name = meta.text("name", default=Path(source).stem)
    notes = {k: v for k, v in meta.data.items() if k != "name"}
    meta.used.update(meta.data)

    mt = root.table("material")
    material = Material(
        youngs_modulus=mt.number("youngs_modulus_pa", positive=True),
        poisson_ratio=mt.number("poisson_ratio", above=0.0, below=0.5),
        density=mt.number("density_kgm3", positive=True),
        name=mt.text("name"),
    )
    mt.used.add("source")
    mt.finish()

    et = root.table("engine")
    n = et.integer("cylinders")
    strokes = et._get("cycle_strokes", 4)
    if strokes not in (2, 4):
        problems.append(Problem("engine.cycle_strokes", strokes, "must be 2 or 4"))
    stroke = et.number("stroke", length=True, positive=True)
    rod = et.number("rod_length", length=True, positive=True)
    bore = et.number("bore", 0.0, length=True, nonnegative=True)
    angles = et.numbers("crank_angles_deg")
    firing = et._get("firing_order", _REQUIRED)
    et.finish()
    if firing is _MISSING:
        firing = []
        problems.append(Problem("engine.firing_order", None, "is required"))
    if n and len(angles) != n:
        problems.append(Problem("engine.crank_angles_deg", list(angles), f"must list one angle per cylinder ({n})"))
    if not (isinstance(firing, list) and sorted(firing) == list(range(1, n + 1))):
        problems.append(Problem("engine.firing_order", firing, f"must be a permutation of cylinders 1..{n}"))
        firing = []
    if rod <= 0.5 * stroke:
        problems.append(Problem("engine.rod_length", rod / root.scale,
                                f"must be longer than the crank radius ({0.5 * stroke / root.scale:g})"))
    engine = Engine(n, strokes if strokes in (2, 4) else 4, stroke, rod,
                    tuple(math.radians(a) for a in angles), tuple(firing), bore)

    journals = tuple(_cylinder(t) for t in root.tables("journals"))
    pins = tuple(_cylinder(t) for t in root.tables("pins"))
    webs = tuple(_web(t) for t in root.tables("webs"))
    front = tuple(_cylinder(t) for t in root.tables("front", required=False))
    rear = tuple(_cylinder(t) for t in root.tables("rear", required=False))
    for key, items, want in (("journals", journals, n + 1), ("pins", pins, n), ("webs", webs, 2 * n)):
        if n and len(items) != want:
            problems.append(Problem(key, f"{len(items)} entries", f"a {n}-cylinder crank needs {want} [[{key}]]"))

    ft = root.table("fillets", required=False)
    fillets = Fillets(ft.number("journal", 0.0, length=True, nonnegative=True),
                      ft.number("pin", 0.0, length=True, nonnegative=True))
    ft.finish()
    ot = root.table("oil_holes", required=False)
    oil = OilHoles(ot.number("diameter", 0.0, length=True, nonnegative=True),
                   ot.flag("in_journals"), ot.flag("in_pins"))
    ot.finish()

    attachments = []
    for t in root.tables("attachments", required=False):
        attachments.append(Attachment(
            name=t.text("name", default=""),
            at=t.text("at", choices=ATTACH_POINTS),
            polar_inertia=t.number("polar_inertia_kgm2", positive=True),
            mass=t.number("mass_kg", 0.0, nonnegative=True),
            diametral_inertia=t.number("diametral_inertia_kgm2", 0.0, nonnegative=True),
            offset=t.number("offset", 0.0, length=True),
        ))
        t.used.add("source")
        t.finish()
    uncertainty = _uncertainty(root.table("uncertainty", required=False), data, problems)
    excitation = None
    if "excitation" in data:
        excitation = _excitation(root.table("excitation"), Path(source).parent)
    root.finish()

    crank = Crank(name, material, engine, journals, pins, webs, front, rear, fillets, oil,
                  tuple(attachments), unit, source, notes, uncertainty, excitation, data)
    if not problems:
        problems.extend(_geometry_problems(crank, root.scale))
    if problems:
        raise DescriptionError(source, problems)
    return crank


def _excitation(t: _Table, folder: Path) -> Excitation:
    """The ``[excitation]`` table; a pressure CSV path is relative to the description file."""
    mass = t.number("reciprocating_mass_kg", nonnegative=True)
    speeds = t.numbers("speed_range_rpm")
    if speeds and not (len(speeds) == 2 and 0 < speeds[0] < speeds[1]):
        t.problems.append(Problem(f"{t.path}.speed_range_rpm", list(speeds), "must be [low, high] rpm with 0 < low < high"))
        speeds = (1.0, 2.0)
    zeta = t.number("modal_damping_ratio", 0.02, positive=True, below=1.0)
    csv = t.text("pressure_csv", default="")
    common = dict(reciprocating_mass=mass, speed_range=tuple(speeds), modal_damping_ratio=zeta)
    if csv:
        t.finish()
        return Excitation(pressure_curve=_pressure_csv(folder / csv, f"{t.path}.pressure_csv", t.problems), **common)
    kinds = [k for k in ("imep_pa", "peak_pressure_pa") if k in t.data]
    if len(kinds) != 1:
        t.problems.append(Problem(t.path, sorted(t.data), "give exactly one of imep_pa, peak_pressure_pa or pressure_csv"))
        t.finish()
        return Excitation(**common)
    raw = t._get(kinds[0], None)
    pairs = [(1.0, raw)] if isinstance(raw, (int, float)) and not isinstance(raw, bool) else raw
    if not (isinstance(pairs, list) and pairs and all(
            isinstance(p, (list, tuple)) and len(p) == 2 and all(isinstance(v, (int, float)) for v in p) and p[1] > 0
            for p in pairs) and all(a[0] < b[0] for a, b in zip(pairs, pairs[1:]))):
        t.problems.append(Problem(f"{t.path}.{kinds[0]}", raw,
                                  "must be a pressure > 0 (Pa) or a list of [rpm, Pa] pairs with rpm ascending"))
        pairs = [(1.0, 1.0)]
    ex = Excitation(
        compression_ratio=t.number("compression_ratio", above=1.0),
        load_kind="imep" if kinds[0] == "imep_pa" else "peak",
        load=tuple((float(a), float(b)) for a, b in pairs),
        intake_pressure=t.number("intake_pressure_pa", 1.0e5, positive=True),
        polytropic_exponent=t.number("polytropic_exponent", 1.3, above=1.0, below=1.67),
        combustion_start=math.radians(t.number("combustion_start_deg", -15.0, above=-90.0, below=90.0)),
        combustion_duration=math.radians(t.number("combustion_duration_deg", 50.0, positive=True, below=180.0)),
        wiebe_a=t.number("wiebe_a", 5.0, positive=True),
        wiebe_m=t.number("wiebe_m", 2.0, nonnegative=True),
        **common,
    )
    t.finish()
    return ex


def _pressure_csv(path: Path, field_name: str, problems: list[Problem]):
    """(angles rad, pressures Pa) from a CSV of crank angle (deg, 0 = firing TDC) and pressure (Pa)."""
    import numpy as np

    try:
        table = np.loadtxt(path, delimiter=",", comments="#", ndmin=2)
    except (OSError, ValueError) as exc:
        problems.append(Problem(field_name, str(path), f"could not be read as 'angle_deg, pressure_pa' rows ({exc})"))
        return None
    if table.shape[1] != 2 or len(table) < 8 or np.any(np.diff(table[:, 0]) <= 0) or np.any(table[:, 1] <= 0):
        problems.append(Problem(field_name, str(path),
                                "needs >= 8 rows of 'angle_deg, pressure_pa', angles ascending, pressures > 0"))
        return None
    return tuple(np.radians(table[:, 0])), tuple(table[:, 1])


def resolve_field(data: dict, path: str) -> list[tuple[str, object]]:
    """The (concrete path, value) pairs a dotted field path names in a raw description.

    Indices are 1-based; ``*`` stands for every entry of a list of tables.
    """
    found = [("", data)]
    for key in path.split("."):
        nxt = []
        for where, node in found:
            if isinstance(node, list) and key == "*":
                nxt += [(f"{where}.{i + 1}", v) for i, v in enumerate(node)]
            elif isinstance(node, list) and key.isdigit() and 1 <= int(key) <= len(node):
                nxt.append((f"{where}.{key}", node[int(key) - 1]))
            elif isinstance(node, dict) and key in node:
                nxt.append((f"{where}.{key}", node[key]))
        found = nxt
    return [(where.lstrip("."), v) for where, v in found]


def _uncertainty(t: _Table, data: dict, problems: list[Problem]):
    """Ranges of reconstructed inputs: ``"path" = [low, high]``, or a named group
    ``name = {"path" = [low, high], ...}`` whose members move together (low with low),
    e.g. a material's E and density. Each range must contain its nominal value."""
    out = []
    for name, spec in t.data.items():
        t.used.add(name)
        members = spec.items() if isinstance(spec, dict) else [(name, spec)]
        group = []
        for path, rng in members:
            where_name = f"uncertainty.{name}" + (f".{path}" if isinstance(spec, dict) else "")
            if not (isinstance(rng, list) and len(rng) == 2 and all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) for v in rng) and rng[0] < rng[1]):
                problems.append(Problem(where_name, rng, "must be [low, high] with low < high"))
                continue
            targets = resolve_field(data, path)
            if not targets or any(isinstance(v, bool) or not isinstance(v, (int, float)) for _, v in targets):
                problems.append(Problem(where_name, rng, f"'{path}' does not name a numeric field of this description"))
                continue
            for where, v in targets:
                if not rng[0] <= v <= rng[1]:
                    problems.append(Problem(where_name, rng, f"must contain the nominal value {where} = {v}"))
            group.append((path, float(rng[0]), float(rng[1])))
        out.append((name, tuple(group)))
    return tuple(out)


def _geometry_problems(crank: Crank, scale: float) -> list[Problem]:
    """Rules that relate parts to each other (run once every field parsed cleanly)."""
    out = []
    R = crank.engine.crank_radius
    u = crank.length_unit

    def show(x):
        return round(x / scale, 6)

    for i, web in enumerate(crank.webs):
        pin = crank.pins[crank.throw_of_web(i)]
        journal = crank.journals[crank.journal_of_web(i)]
        p = f"webs.{i + 1}"
        if web.width_pin < pin.diameter:
            out.append(Problem(f"{p}.width_pin", show(web.width_pin),
                               f"the pin (diameter {show(pin.diameter)} {u}) must lie inside its web: "
                               f"width_pin must be >= the pin diameter"))
        if web.width_journal < journal.diameter:
            out.append(Problem(f"{p}.width_journal", show(web.width_journal),
                               f"the journal (diameter {show(journal.diameter)} {u}) must lie inside its web: "
                               f"width_journal must be >= the journal diameter"))
        if abs(web.width_journal - web.width_pin) / 2 >= R:
            out.append(Problem(f"{p}.width_journal", show(web.width_journal),
                               f"web end circles ({show(web.width_journal)} and {show(web.width_pin)} {u}) "
                               f"must differ in radius by less than the crank radius {show(R)} {u}"))
        for part, radius in (("journal", crank.fillets.journal), ("pin", crank.fillets.pin)):
            if radius >= web.thickness / 2:
                out.append(Problem(f"fillets.{part}", show(radius),
                                   f"must be smaller than half the thickness of web {i + 1} ({show(web.thickness)} {u})"))
    oh = crank.oil_holes
    if oh.diameter > 0 and not (oh.in_journals or oh.in_pins):
        out.append(Problem("oil_holes.diameter", show(oh.diameter), "set in_journals and/or in_pins to place the holes"))
    for kind, parts, used in (("journals", crank.journals, oh.in_journals), ("pins", crank.pins, oh.in_pins)):
        for i, c in enumerate(parts):
            if used and oh.diameter >= min(c.length, c.diameter - c.bore):
                out.append(Problem("oil_holes.diameter", show(oh.diameter),
                                   f"must be smaller than the length and wall of {kind}.{i + 1}"))
    return out
