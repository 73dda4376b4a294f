"""The crank description as a Gmsh/OpenCASCADE solid, and its mass properties.

Frame (SI outside, see below for inside): the crank axis is the x axis, the shaft runs
along +x from the front (pulley) face at x = 0 to the rear (flywheel-flange) face at
x = length. Pin i sits at (y, z) = R (cos θᵢ, sin θᵢ), R = stroke/2, θᵢ =
``engine.crank_angles[i]``. Parts are stacked exactly as :class:`fetorsion.description.model.Crank`
lists them, so part boundaries are planes x = const.

Inside the Gmsh model lengths are in **millimetres** (:data:`MODEL_UNIT` metres per model
unit): OpenCASCADE's absolute tolerances (1e-7) are tuned for parts of millimetres to
metres, and a 2.5 mm fillet built in metres sits uncomfortably close to them. Everything
that leaves this module is SI.

Build order, and why:

1. every part as its own OCC volume (hollow cylinders, webs extruded from the exact outline
   of :mod:`fetorsion.solid.outline`: two tangent discs joined by their common tangents, plus the
   counterweight sector), after checking in the web plane that each web covers the pin and
   journal it carries;
2. one boolean fuse, checked to give ONE volume (a part that lands in another piece is
   named in the error);
3. fillets on the journal/web and pin/web junction circles, then the oil drillings;
4. a fragment by the part-boundary planes, so every journal, web, pin and end section is its
   own volume of a conformal whole: per-part mass properties and per-element part tags come
   from the as-built solid. A journal/web or pin/web cut lies one fillet radius inside the
   journal or pin (where the fillet starts), so fillet material belongs to the web: a cut
   in the web face would be tangent to the fillet and leave zero-angle slivers to mesh.

Use :func:`gmsh_session` around :func:`build_solid`; :func:`crank_mass_properties` does
both for a quick mass/inertia read-out.
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import gmsh
import numpy as np

from ..description.model import Crank
from ..errors import GeometryError
from .recognise import SolidFeatures
from .stepimport import imported_solid, quiet_stdout
from .webvolume import hollow_cylinder as _hollow_cylinder, split_pin_volumes, web_volume

MODEL_UNIT = 1e-3  # metres per Gmsh model length unit (the model is built in mm)

# Tolerance for "same plane / same circle" searches, model units (mm): far above
# OCC's 1e-7 and far below any real feature (≥ 0.1 mm).
_FIND_TOL = 1e-3


@dataclass(frozen=True)
class PartSolid:
    """One axial part of the built solid.

    ``name`` is ``journal_1``, ``web_3``, ``pin_2``, ``front_1``, ``rear_2`` (1-based),
    also the name of its Gmsh physical volume group. ``x0``/``x1`` in m.
    """

    name: str
    kind: str
    index: int
    x0: float  # where the part begins and ends in the split solid (see _cut_positions)
    x1: float
    volumes: tuple[int, ...]


@dataclass(frozen=True)
class CrankSolid:
    """What :func:`build_solid` leaves in the current Gmsh model.

    Tags are Gmsh OCC entity tags of the current model; lengths in m.
    """

    name: str
    length: float
    parts: tuple[PartSolid, ...]
    front_face: tuple[int, ...]  # surfaces at x = 0 (pulley end)
    rear_face: tuple[int, ...]  # surfaces at x = length (flywheel flange)
    fillet_faces: tuple[int, ...]
    hole_faces: tuple[int, ...]
    axis_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    axis_direction: tuple[float, float, float] = (1.0, 0.0, 0.0)
    #: a CAD crank's journals, pins, fillets and drillings as found on its solid (None: built)
    features: SolidFeatures | None = None

    @property
    def volumes(self) -> tuple[int, ...]:
        return tuple(v for p in self.parts for v in p.volumes)


@dataclass(frozen=True)
class Body:
    """Mass (kg), polar inertia about the crank axis (kg·m²), centre of mass (m)."""

    mass: float
    polar_inertia: float
    centre: tuple[float, float, float]


@contextmanager
def gmsh_session(model: str = "crank"):
    """Initialise Gmsh quietly (once), give a fresh model, clean it up afterwards.

    Nested use is fine: an outer session keeps Gmsh alive, each level gets its own model.
    """
    own = not gmsh.isInitialized()
    if own:
        # interruptible=False: Gmsh must not install its own SIGINT handler inside Python.
        gmsh.initialize(interruptible=False)
        gmsh.option.setNumber("General.Terminal", 0)
        # The machines this runs on are shared: one thread keeps timings honest.
        gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.model.add(model)
    try:
        yield
    finally:
        gmsh.model.remove()
        if own:
            gmsh.finalize()


# ---------------------------------------------------------------------------
# Layout


@dataclass(frozen=True)
class _Piece:
    """One part before building: where it is and what it is (model units, mm)."""

    kind: str
    index: int
    x0: float
    x1: float
    spec: object  # Cylinder or Web
    centre: tuple[float, float]  # (y, z) of a cylinder's axis; (0, 0) for webs
    angle: float  # crank angle of the throw (rad), webs and pins
    #: a split pin's rear half's axis (y, z); None: the pin is not split (docs/vee-engines.md)
    rear_centre: tuple[float, float] | None = None

    @property
    def name(self) -> str:
        return f"{self.kind}_{self.index + 1}"

    def side(self, rear: bool) -> "_Piece":
        """The piece as the web behind it (``rear``) sees it: a split pin's rear half's axis."""
        if self.rear_centre is None or not rear:
            return self
        return _Piece(self.kind, self.index, self.x0, self.x1, self.spec, self.rear_centre, self.angle)


def layout(crank: Crank) -> list[_Piece]:
    """The parts of ``crank`` in axial order with their x ranges and positions (mm)."""
    s = 1.0 / MODEL_UNIT
    R = crank.engine.crank_radius * s
    seq: list[tuple[str, int, object, float]] = []
    seq += [("front", i, c, 0.0) for i, c in enumerate(crank.front)]
    for t in range(crank.throws + 1):
        seq.append(("journal", t, crank.journals[t], 0.0))
        if t == crank.throws:
            break
        a = crank.engine.crank_angles[t]
        split = crank.pins[t].split_angle  # the rear web carries a split pin's rear half
        seq += [("web", 2 * t, crank.webs[2 * t], a), ("pin", t, crank.pins[t], a),
                ("web", 2 * t + 1, crank.webs[2 * t + 1], a + split)]
    seq += [("rear", i, c, 0.0) for i, c in enumerate(crank.rear)]
    out, x = [], 0.0
    for kind, idx, spec, a in seq:
        length = (spec.thickness if kind == "web" else spec.length) * s
        centre = (R * math.cos(a), R * math.sin(a)) if kind == "pin" else (0.0, 0.0)
        rear = None
        if kind == "pin" and spec.split:
            b = a + spec.split_angle
            rear = (R * math.cos(b), R * math.sin(b))
        out.append(_Piece(kind, idx, x, x + length, spec, centre, a, rear))
        x += length
    return out


# ---------------------------------------------------------------------------
# The solid


def _check_fillet_room(crank: Crank, pieces: list[_Piece]) -> None:
    """A fillet needs web face to run onto and part length to run along; name who lacks it."""
    s = 1.0 / MODEL_UNIT
    for i, p in enumerate(pieces):
        if p.kind != "web":
            continue
        for other in (pieces[i - 1], pieces[i + 1]):
            r = (crank.fillets.pin if other.kind == "pin" else crank.fillets.journal) * s
            if r <= 0 or other.kind not in ("pin", "journal"):
                continue
            room = 0.5 * ((p.spec.width_pin if other.kind == "pin" else p.spec.width_journal)
                          - other.spec.diameter) * s
            if room < r:
                raise GeometryError(
                    f"fillets.{other.kind} = {r:g} mm does not fit between {other.name} and {p.name}: "
                    f"the web reaches only {room:g} mm beyond the {other.kind}")
            if (other.x1 - other.x0) < 2 * r:
                raise GeometryError(f"fillets.{other.kind} = {r:g} mm: {other.name} is shorter than two fillets")


def _junction_circles(crank: Crank, pieces: list[_Piece]) -> list[tuple[float, tuple, float, float, str]]:
    """(x, centre, circle radius, fillet radius, label) of every journal/web and pin/web junction."""
    s = 1.0 / MODEL_UNIT
    out = []
    for i, p in enumerate(pieces):
        if p.kind != "web":
            continue
        for other, x in ((pieces[i - 1].side(rear=True), p.x0), (pieces[i + 1], p.x1)):
            r = (crank.fillets.pin if other.kind == "pin" else crank.fillets.journal) * s
            if r > 0 and other.kind in ("pin", "journal"):
                out.append((x, other.centre, 0.5 * other.spec.diameter * s, r, f"{other.name}/{p.name}"))
    return out


def circle_curves(occ: type[gmsh.model.occ], x: float, centre: tuple[float, float], radius: float) -> list[int]:
    """Curves of the (synchronised) model that lie on the circle of ``radius`` about
    ``centre`` in the plane x; the bore circle in the same plane is smaller and is left out."""
    y, z = centre
    t = _FIND_TOL
    found = occ.getEntitiesInBoundingBox(x - t, y - radius - t, z - radius - t,
                                         x + t, y + radius + t, z + radius + t, 1)
    out = []
    for _, c in found:
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        p = np.asarray(gmsh.model.getValue(1, c, [0.5 * (lo[0] + hi[0])]))
        if abs(math.hypot(p[1] - y, p[2] - z) - radius) < t:
            out.append(c)
    return out


def _material_point(p: _Piece, s: float) -> list[float]:
    """A point inside the metal of part ``p`` (model units): mid-length, mid-wall."""
    if p.kind == "web":
        return [0.5 * (p.x0 + p.x1), 0.0, 0.0]  # the axis is inside the journal-end disc
    r = 0.25 * (p.spec.diameter + p.spec.bore) * s
    return [0.5 * (p.x0 + p.x1), p.centre[0], p.centre[1] + r]


def _fuse_all(occ, volumes: list[list[tuple[int, int]]], pieces: list[_Piece]) -> int:
    """Fuse the part volumes into one; name the parts that end up apart from the rest."""
    flat = [dt for vols in volumes for dt in vols]
    out, _ = occ.fuse(flat[:1], flat[1:])
    solids = [t for d, t in out if d == 3]
    if len(solids) == 1:
        return solids[0]
    # OCC's input-to-output map is incomplete for fused inputs: locate each part by a
    # point of its metal instead. The piece holding the most parts is "the crank".
    occ.synchronize()
    s = 1.0 / MODEL_UNIT
    where = [next((t for t in solids if gmsh.model.isInside(3, t, _material_point(p, s))), None) for p in pieces]
    main = max(solids, key=where.count)
    loose = [p.name for p, w in zip(pieces, where) if w != main]
    raise GeometryError(f"the crank does not fuse into one solid ({len(solids)} pieces): "
                        f"{', '.join(loose)} not connected to the rest (check the diameters and "
                        f"bores where it meets its neighbours)")


def _oil_holes(occ, crank: Crank, pieces: list[_Piece], s: float) -> list[tuple[int, int]]:
    """Diametral drillings at mid-length of each journal/pin, perpendicular to the crank
    radius of the nearest throw (so pin drillings run tangentially); volumes to cut."""
    oh = crank.oil_holes
    if oh.diameter <= 0:
        return []
    tools = []
    n = crank.throws
    for p in pieces:
        if not ((p.kind == "journal" and oh.in_journals) or (p.kind == "pin" and oh.in_pins)):
            continue
        a = crank.engine.crank_angles[min(p.index, n - 1)] + 0.5 * math.pi
        half = 0.5 * p.spec.diameter * s * 1.05  # run past the surface so the cut is clean
        h = p.spec.half_length * s  # a split pin: one drilling at each half's mid-length, across its own radius
        places = ([(0.5 * (p.x0 + p.x1), p.centre, a)] if p.rear_centre is None else
                  [(p.x0 + 0.5 * h, p.centre, a), (p.x1 - 0.5 * h, p.rear_centre, a + p.spec.split_angle)])
        for xm, (y, z), b in places:
            dy, dz = half * math.cos(b), half * math.sin(b)
            tools.append((3, occ.addCylinder(xm, y - dy, z - dz, 0, 2 * dy, 2 * dz, 0.5 * oh.diameter * s)))
    return tools


def _cut_positions(crank: Crank, pieces: list[_Piece]) -> np.ndarray:
    """x (model units) where each part after the first begins in the split solid.

    A fillet is tangent to its web face, so a cut in that plane would meet the fillet at a
    zero angle and force sliver elements. The cut is moved along the journal or pin by the
    fillet radius instead, to where the fillet meets the cylinder at a right angle to the
    cut: fillet material belongs to the web.
    """
    s = 1.0 / MODEL_UNIT
    cuts = []
    for a, b in zip(pieces[:-1], pieces[1:]):
        x = a.x1
        for other, sign in ((a, -1.0), (b, 1.0)):
            if {a.kind, b.kind} in ({"web", "journal"}, {"web", "pin"}) and other.kind != "web":
                x += sign * (crank.fillets.pin if other.kind == "pin" else crank.fillets.journal) * s
        cuts.append(x)
    return np.array(cuts)


def _split_into_parts(occ, solid: int, cuts: np.ndarray, n: int) -> dict[int, list[int]]:
    """Cut the one solid by the planes x = ``cuts``; part index (0..n-1) -> volume tags."""
    xmin, ymin, zmin, xmax, ymax, zmax = occ.getBoundingBox(3, solid)
    big = 2.0 * max(abs(ymin), abs(ymax), abs(zmin), abs(zmax)) + 1.0
    discs = [(2, occ.addDisk(x, 0, 0, big, big, zAxis=[1, 0, 0], xAxis=[0, 1, 0])) for x in cuts]
    out, _ = occ.fragment([(3, solid)], discs)
    occ.synchronize()
    # Pieces of the planes outside the metal bound no volume: drop them.
    free = [(2, t) for d, t in out if d == 2 and len(gmsh.model.getAdjacencies(2, t)[0]) == 0]
    occ.remove(free, recursive=True)
    occ.synchronize()
    owner: dict[int, list[int]] = {k: [] for k in range(n)}
    for _, v in gmsh.model.getEntities(3):
        x = occ.getCenterOfMass(3, v)[0]
        owner[int(np.searchsorted(cuts, x, side="right"))].append(v)
    return owner


def _faces_at(x: float) -> tuple[int, ...]:
    """Plane surfaces of the model lying in the plane x (model units)."""
    t = _FIND_TOL
    big = 1e9
    return tuple(tag for _, tag in gmsh.model.getEntitiesInBoundingBox(x - t, -big, -big, x + t, big, big, 2))


def _built_solid(crank: Crank, pieces) -> int:
    """The crank built from its dimensions as one OCC volume (fused, filleted, drilled); its tag."""
    occ = gmsh.model.occ
    s = 1.0 / MODEL_UNIT
    R = crank.engine.crank_radius * s

    volumes = []
    for i, p in enumerate(pieces):
        if p.kind == "web":
            journal = pieces[i - 1] if pieces[i - 1].kind == "journal" else pieces[i + 1]
            pin = pieces[i + 1] if pieces[i + 1].kind == "pin" else pieces[i - 1].side(rear=True)
            volumes.append(web_volume(occ, p, journal, pin, R, s))
        elif p.rear_centre is not None:
            volumes.append(split_pin_volumes(occ, p, s))
        else:
            volumes.append(_hollow_cylinder(occ, p.x0, p.x1 - p.x0, p.spec, p.centre, s))
    _check_fillet_room(crank, pieces)  # after the webs: a web that misses its pin says so first
    solid = _fuse_all(occ, volumes, pieces)
    occ.synchronize()

    junctions = _junction_circles(crank, pieces)
    if junctions:
        curves, radii = [], []
        for x, centre, radius, r, label in junctions:
            found = circle_curves(occ, x, centre, radius)
            if not found:
                raise GeometryError(f"no edge to fillet where {label} meet (x = {x:g} mm)")
            curves += found
            radii += [r] * len(found)
        try:
            out = occ.fillet([solid], curves, radii)
        except Exception as exc:  # OCC says only "could not compute fillet"
            raise GeometryError(f"the fillets (journal {crank.fillets.journal / MODEL_UNIT:g} mm, pin "
                                f"{crank.fillets.pin / MODEL_UNIT:g} mm) could not be built: {exc}") from None
        solid = out[0][1]
        occ.synchronize()

    holes = _oil_holes(occ, crank, pieces, s)
    if holes:
        out, _ = occ.cut([(3, solid)], holes)
        if len(out) != 1:
            raise GeometryError(f"the oil drillings split the crank into {len(out)} pieces")
        solid = out[0][1]
    return solid


def write_step(crank: Crank, path: str | Path) -> Path:
    """Write ``crank`` built from its dimensions (one solid: fused, filleted, drilled) as a STEP
    file, in mm; the crank axis is x, the front end at x = 0 (what ``[solid]`` reads back)."""
    path = Path(path)
    with gmsh_session("step"):
        _built_solid(crank, layout(crank))
        gmsh.model.occ.synchronize()
        with quiet_stdout():  # OpenCASCADE's STEP writer prints to the process's stdout
            gmsh.write(str(path))
    return path


def build_solid(crank: Crank) -> CrankSolid:
    """Build ``crank`` as one OCC solid split into its parts, in the current Gmsh model.

    Call inside :func:`gmsh_session`. Leaves the model synchronised, with physical
    volume groups named after the parts (``journal_1``, ``web_1``, ``pin_1``, ...,
    ``front_1``, ``rear_1``) and physical surface groups ``front_face`` and ``rear_face``.

    Parameters
    ----------
    crank : Crank
        A validated description (SI units).

    Returns
    -------
    CrankSolid
        Entity tags and x ranges (m) of the parts, the end faces, the fillet and drilling
        faces, and the crank axis (the x axis through the origin).

    Raises
    ------
    GeometryError
        Naming the part, when a web does not cover its pin or journal, a fillet has no room,
        or the parts do not fuse into one solid.
    """
    occ = gmsh.model.occ
    s = 1.0 / MODEL_UNIT
    pieces = layout(crank)
    solid, features = imported_solid(crank, pieces, MODEL_UNIT) if crank.solid_step else (_built_solid(crank, pieces), None)
    occ.synchronize()
    n = len(gmsh.model.getEntities(3))
    if n != 1:
        raise GeometryError(f"the crank is not one solid after filleting and drilling ({n} volumes)")

    length = pieces[-1].x1
    cuts = _cut_positions(crank, pieces)
    owner = _split_into_parts(occ, solid, cuts, len(pieces))
    bounds = np.concatenate([[0.0], cuts, [length]]) * MODEL_UNIT
    parts = []
    for k, p in enumerate(pieces):
        if not owner[k]:
            raise GeometryError(f"{p.name} has no material left in the built solid")
        gmsh.model.addPhysicalGroup(3, owner[k], name=p.name)
        parts.append(PartSolid(p.name, p.kind, p.index, float(bounds[k]), float(bounds[k + 1]), tuple(owner[k])))
    front, rear = _faces_at(0.0), _faces_at(length)
    gmsh.model.addPhysicalGroup(2, list(front), name="front_face")
    gmsh.model.addPhysicalGroup(2, list(rear), name="rear_face")
    # Fillet and drilling faces survive the fragment with new tags: find them again by type.
    fillets = tuple(t for _, t in gmsh.model.getEntities(2) if gmsh.model.getType(2, t) == "Torus")
    hole_r = 0.5 * crank.oil_holes.diameter * s
    drill = tuple(t for _, t in gmsh.model.getEntities(2)
                  if hole_r > 0 and gmsh.model.getType(2, t) == "Cylinder" and _radius_of(t) < 1.01 * hole_r)
    return CrankSolid(crank.name, length * MODEL_UNIT, tuple(parts), front, rear, fillets, drill, features=features)


def _radius_of(surface: int) -> float:
    """Radius (model units) of a cylindrical surface, from its curvature at mid-parameter."""
    lo, hi = gmsh.model.getParametrizationBounds(2, surface)
    kmax, kmin = gmsh.model.getPrincipalCurvatures(surface, [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])])[:2]
    k = max(abs(kmax[0]), abs(kmin[0]))  # a cylinder's curvatures are 0 and ±1/r, sign by orientation
    return 1.0 / k if k > 0 else math.inf


def body(dim: int, tags, density: float) -> Body:
    """Mass properties of model entities ``tags`` (volumes) of uniform ``density`` (kg/m³).

    OCC gives volume, centre of mass and the inertia matrix about that centre (density 1,
    model units); the parallel-axis theorem moves it to the crank axis.
    """
    occ = gmsh.model.occ
    vols = np.array([occ.getMass(dim, t) for t in tags])
    centres = np.array([occ.getCenterOfMass(dim, t) for t in tags])
    ixx = np.array([occ.getMatrixOfInertia(dim, t)[0] for t in tags])
    polar = ixx + vols * (centres[:, 1] ** 2 + centres[:, 2] ** 2)
    u = MODEL_UNIT
    mass = density * vols.sum() * u**3
    centre = (vols[:, None] * centres).sum(axis=0) / vols.sum() * u
    return Body(float(mass), float(density * polar.sum() * u**5), tuple(float(c) for c in centre))


def solid_mass_properties(solid: CrankSolid, density: float) -> tuple[Body, dict[str, Body]]:
    """Whole-crank and per-part mass properties of a built solid.

    Parameters
    ----------
    solid : CrankSolid
        From :func:`build_solid`, in the still-open session.
    density : float
        kg/m³.

    Returns
    -------
    (Body, dict of str to Body)
        The whole crank, and each part by name (``journal_1``, ``web_1``, ...).
    """
    parts = {p.name: body(3, p.volumes, density) for p in solid.parts}
    return body(3, solid.volumes, density), parts


def cad_mass_properties(crank: Crank) -> tuple[Body, dict[str, Body]]:
    """:func:`crank_mass_properties` of a CAD crank (``[solid]``), kept per solid file, its
    state, the layout and the density: the lumped chain and the design search read them for every
    variant, and its solid does not change with them."""
    import json
    import os

    stat = os.stat(crank.solid_step)
    key = (crank.solid_step, stat.st_mtime_ns, stat.st_size, crank.solid_placement,
           json.dumps([(p.name, p.x0, p.x1) for p in layout(crank)]), crank.material.density)
    if key not in _CAD_MASS_PROPERTIES:
        _CAD_MASS_PROPERTIES[key] = crank_mass_properties(crank)
    return _CAD_MASS_PROPERTIES[key]


def solid_features(crank: Crank) -> SolidFeatures:
    """What is found on a CAD crank's solid (journals, pins, fillets, drillings;
    :func:`fetorsion.solid.recognise.recognise`), checked against its description: read in a
    private Gmsh session (the STEP import and its faces, no split, no mesh: well under a second for
    the Renault) and kept per solid file, its state and the description's layout, radii and
    drilling. ``fetorsion run`` calls it before any work, so a solid that is not the described
    crank is refused first; the report and ``results.json`` list what it found.

    Raises
    ------
    GeometryError
        As :func:`build_solid` does for the same file, naming it.
    """
    import json
    import os

    stat = os.stat(crank.solid_step)
    key = (crank.solid_step, stat.st_mtime_ns, stat.st_size, crank.solid_placement,
           json.dumps([(p.name, p.x0, p.x1, getattr(p.spec, "diameter", 0.0), p.centre) for p in layout(crank)]),
           crank.fillets.journal, crank.fillets.pin, crank.oil_holes.diameter)
    if key not in _SOLID_FEATURES:
        with gmsh_session("features"):
            _SOLID_FEATURES[key] = imported_solid(crank, layout(crank), MODEL_UNIT)[1]
    return _SOLID_FEATURES[key]


#: solid_features' results, by solid file, its state and the description's layout, radii and drilling.
_SOLID_FEATURES: dict[tuple, SolidFeatures] = {}


#: cad_mass_properties' results, by solid file, its state, the layout and the density.
_CAD_MASS_PROPERTIES: dict[tuple, tuple[Body, dict[str, Body]]] = {}


def part_inertias(crank: Crank) -> dict[str, float]:
    """Polar inertia (kg·m², about the crank axis) of every part of a CAD crank's solid by name
    (``journal_1``, ``web_1``, ``pin_1``, ...): OpenCASCADE's integral over the solid cut at the
    description's planes, fillets and drillings included; a CAD crank's lumped chain reads them
    instead of the formulas of its outline."""
    return {name: b.polar_inertia for name, b in cad_mass_properties(crank)[1].items()}


def crank_mass_properties(crank: Crank) -> tuple[Body, dict[str, Body]]:
    """Build ``crank`` in a private Gmsh session and return :func:`solid_mass_properties`."""
    with gmsh_session():
        solid = build_solid(crank)
        return solid_mass_properties(solid, crank.material.density)


def surface_triangles(solid: CrankSolid, size: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A linear triangulation of the outer surface of a built solid, for pictures.

    Parameters
    ----------
    solid : CrankSolid
        Built in the current session (the model is meshed in 2D here).
    size : float
        Largest triangle edge, m; curved faces get at least 16 triangles per turn.

    Returns
    -------
    points : (P, 3) float array, m
    triangles : (T, 3) int array of 0-based point indices
    part : (T,) int array, index into ``solid.parts`` of the part each triangle bounds
    surface : (T,) int array, the Gmsh surface each triangle lies on (``solid.fillet_faces`` ...)
    """
    gmsh.option.setNumber("Mesh.MeshSizeMax", size / MODEL_UNIT)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 16)
    gmsh.model.mesh.generate(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    lookup = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    lookup[tags.astype(np.int64)] = np.arange(tags.size)
    part_of_volume = {v: k for k, p in enumerate(solid.parts) for v in p.volumes}
    tris, part, surface = [], [], []
    for _, s in gmsh.model.getEntities(2):
        up = gmsh.model.getAdjacencies(2, s)[0]
        if len(up) != 1:  # a cut between two parts is inside the metal
            continue
        _, etags, enodes = gmsh.model.mesh.getElements(2, s)
        for et, en in zip(etags, enodes):
            tris.append(lookup[en.astype(np.int64)].reshape(et.size, -1)[:, :3])
            part.append(np.full(et.size, part_of_volume[int(up[0])]))
            surface.append(np.full(et.size, s))
    return coords.reshape(-1, 3) * MODEL_UNIT, np.concatenate(tris), np.concatenate(part), np.concatenate(surface)
