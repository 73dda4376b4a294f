"""What is found on a CAD crank's solid: journals, pins, fillets and drillings, read from its faces.

A ``[solid] step`` crank is meshed from the engineer's solid, but its lumped chain, the M53 and
textbook SCFs and the part boundaries still come from the description. This module reads the
solid's own faces and checks the two against each other before any meshing work, so that a
solid and a description that are not the same crank are refused by name, and says what it found
so the report can show it:

* **journals**: cylindrical faces coaxial with the x axis, convex (metal inside; a bore is a
  concave one), whose mid-x lies in a journal of the description's layout; the largest such face
  in each journal is the bearing surface, its diameter the journal's;
* **pins**: convex cylindrical faces on an axis parallel to x through the described pin centre
  (crank radius R at the throw's angle), mid-x inside that pin;
* **fillets**: concave toroidal faces (the tube's centre lies outside the metal: a re-entrant
  corner, where stress concentrates; a convex round is not a fillet) around a journal or pin
  axis, each given to the nearest journal/web or pin/web corner of the layout. The faces of one
  corner are ONE fillet (an undercut fillet is several tangent tori of different minor radii);
  its smallest minor radius is the one reported, the one the peak stress follows;
* **drillings**: concave cylinders not parallel to x of at most the described drilling's radius.

Every face is read exactly from its surface: a torus's or cylinder's iso-parameter lines are
circles (the meridians and parallels of a torus; a cylinder's parallels), and the circle through
three points of one gives centre, radius and plane to round-off — no curvature sampling and no
tolerance on the surface itself.

Lengths inside are model units (mm, :data:`fetorsion.solid.geometry.MODEL_UNIT`, passed in); what leaves
(:class:`SolidFeatures`) is SI.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import gmsh
import numpy as np

from ..errors import GeometryError

#: Factors a solid's size (as read, over the description's) may be off by when its STEP header states
#: another unit than the one it was drawn in: the factor is the header's unit over the drawing's, so
#: a crank drawn in inches whose header says mm reads 1/25.4 of its size. Each: (drawn in, header says).
UNIT_SLIPS = {0.001: ("m", "mm"), 1000.0: ("mm", "m"), 1 / 25.4: ("in", "mm"), 25.4: ("mm", "in"),
              0.1: ("cm", "mm"), 10.0: ("mm", "cm")}


def unit_slip(ratio: float) -> str:
    """What a solid ``ratio`` times the described size says of its unit: '' when no slip of
    :data:`UNIT_SLIPS` explains it (within 5 %), else the slip in the drawing's own words."""
    slip = min(UNIT_SLIPS, key=lambda f: abs(math.log(ratio / f)))
    if abs(math.log(ratio / slip)) >= 0.05:
        return ""
    drawn, header = UNIT_SLIPS[slip]
    return (f"its unit looks wrong: drawn in {drawn} while its header says {header} (export it in {header}, or "
            f"with a header that says {drawn})")

#: Largest relative disagreement between a journal's or pin's diameter found on the solid and the
#: description's before the solid is refused: a diameter is drawn to hundredths of a mm and
#: described to a tenth; 2 % (1 mm on a 50 mm journal) is beyond any rounding, and already 8 % in
#: the journal's d⁴ torsional stiffness that the lumped chain takes from the description.
DIAMETER_TOL = 0.02

#: Largest relative disagreement between a fillet's smallest radius on the solid and the
#: description's before the report says so: the M53 bending SCF goes as r^-0.52 ([KR-M53]
#: §3.(2)(A), f(r) = 0.2081 r^-0.5231), so 5 % in r is 2.6 % in the SCF, the spread the FE SCF
#: convergence study shows between its two finest levels.
FILLET_TOL = 0.05

#: An axis "is" a journal's or pin's when its centre lies within this share of the crank radius
#: of it: far above a CAD model's precision (1e-4 mm), below any stroke one would describe wrongly.
AXIS_TOL = 0.01


@dataclass(frozen=True)
class FoundCylinder:
    """A journal or pin found on the solid (m): the part of the layout it lies in, its diameter
    (the largest convex face on the part's axis there), the x range of that face, the angle of its
    axis about the crank axis (rad; 0 for a journal) and how many faces lie on that axis there."""

    part: str
    diameter: float
    x0: float
    x1: float
    angle: float
    faces: int


@dataclass(frozen=True)
class FoundFillet:
    """One fillet found on the solid: the corner it rounds (``journal_2/web_3``, ``pin_1/web_2``),
    the x of the tube centre of its tightest face (m), its smallest minor radius (m), every face's
    minor radius (m, ascending) and the description's radius for that corner (m)."""

    end: str
    x: float
    radius: float
    radii: tuple[float, ...]
    described: float
    #: where its faces lie (m): x from, to, and the distance from the journal's or pin's axis from, to
    extent: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)

    @property
    def faces(self) -> int:
        return len(self.radii)

    @property
    def differs(self) -> bool:
        """Whether the solid's smallest radius is off the description's by more than :data:`FILLET_TOL`."""
        return abs(self.radius - self.described) > FILLET_TOL * self.described


@dataclass(frozen=True)
class FoundDrilling:
    """A drilling face: the part of the layout its axis point lies in, its diameter (m), and the
    x of its axis point (m)."""

    part: str
    diameter: float
    x: float


@dataclass(frozen=True)
class SolidFeatures:
    """What :func:`recognise` found on a CAD crank's solid (SI)."""

    step: str
    journals: tuple[FoundCylinder, ...]
    pins: tuple[FoundCylinder, ...]
    fillets: tuple[FoundFillet, ...]
    drillings: tuple[FoundDrilling, ...]
    other_tori: int  # toroidal faces that round no journal or pin end (convex rounds, grooves)

    def to_dict(self) -> dict:
        """Plain JSON-ready numbers (SI; angles in degrees)."""
        cyl = [{**asdict(c), "angle_deg": math.degrees(c.angle)} for c in self.journals + self.pins]
        for c in cyl:
            del c["angle"]
        return {"step": self.step, "journals": cyl[:len(self.journals)], "pins": cyl[len(self.journals):],
                "fillets": [{**asdict(f), "faces": f.faces, "differs": f.differs} for f in self.fillets],
                "fillet_tolerance": FILLET_TOL, "diameter_tolerance": DIAMETER_TOL,
                "drillings": [asdict(d) for d in self.drillings], "other_toroidal_faces": self.other_tori}


# ---------------------------------------------------------------------------
# Exact reading of a face


def _circle(p: np.ndarray) -> tuple[np.ndarray, float, np.ndarray] | None:
    """Centre, radius and unit normal of the circle through the three points ``p`` (3×3), or
    None when they are collinear (an iso-line that is straight: a cylinder's generator)."""
    a, b = p[1] - p[0], p[2] - p[0]
    n = np.cross(a, b)
    nn = float(n @ n)
    if nn < 1e-12 * float(a @ a) * float(b @ b):
        return None
    centre = p[0] + (np.cross(n, a) * float(b @ b) + np.cross(b, n) * float(a @ a)) / (2.0 * nn)
    return centre, float(np.linalg.norm(p[0] - centre)), n / math.sqrt(nn)


def _iso_circles(surface: int) -> list[tuple[np.ndarray, float, np.ndarray] | None]:
    """The circles (or None for straight lines) through three points of the u and the v
    iso-lines of ``surface`` at mid-range of the other parameter."""
    lo, hi = gmsh.model.getParametrizationBounds(2, surface)
    lo, hi = np.asarray(lo), np.asarray(hi)
    mid = 0.5 * (lo + hi)
    out = []
    for k in (0, 1):  # vary parameter k, hold the other at mid-range
        uv = np.tile(mid, (3, 1))
        # thirds, not the ends: a full turn's two ends are the same point
        uv[:, k] = lo[k] + (hi[k] - lo[k]) * np.array([0.0, 1.0 / 3.0, 2.0 / 3.0])
        pts = np.asarray(gmsh.model.getValue(2, surface, uv.ravel())).reshape(3, 3)
        out.append(_circle(pts))
    return out


def _face_point(surface: int) -> tuple[np.ndarray, np.ndarray]:
    """A point of ``surface`` itself (inside its trimmed domain: not in a drilling through it) and
    the face's outward normal there (OpenCASCADE orients a closed solid's faces outward; Gmsh's
    normal follows the face's orientation)."""
    lo, hi = (np.asarray(b) for b in gmsh.model.getParametrizationBounds(2, surface))
    uv = 0.5 * (lo + hi)
    for a in (0.5, 0.3, 0.7, 0.1, 0.9):
        hit = next((lo + (hi - lo) * np.array([a, b]) for b in (0.5, 0.3, 0.7, 0.1, 0.9)
                    if gmsh.model.isInside(2, surface, list(lo + (hi - lo) * np.array([a, b])), parametric=True)), None)
        if hit is not None:
            uv = hit
            break
    return np.asarray(gmsh.model.getValue(2, surface, list(uv))), np.asarray(gmsh.model.getNormal(surface, list(uv)))


def _meridian_extent(surface: int, axis_point: np.ndarray) -> tuple[float, float, float, float]:
    """(x from, to, distance from the axis from, to) of a torus face about an axis parallel to x
    through ``axis_point``: its trimmed parameter range sampled (17 × 17, the arcs' extremes to
    (1 − cos(π/32)) r, well inside the SCF zone's slack)."""
    lo, hi = (np.asarray(b) for b in gmsh.model.getParametrizationBounds(2, surface))
    t = np.linspace(0.0, 1.0, 17)
    uv = (lo + (hi - lo) * np.stack(np.meshgrid(t, t), axis=-1).reshape(-1, 2))
    xyz = np.asarray(gmsh.model.getValue(2, surface, uv.ravel())).reshape(-1, 3)
    rho = np.hypot(xyz[:, 1] - axis_point[1], xyz[:, 2] - axis_point[2])
    return float(xyz[:, 0].min()), float(xyz[:, 0].max()), float(rho.min()), float(rho.max())


def _parallel_to_x(normal: np.ndarray) -> bool:
    return abs(abs(normal[0]) - 1.0) < 1e-6


@dataclass(frozen=True)
class _Cyl:
    tag: int
    centre: tuple[float, float]  # (y, z) of the axis, mm (axes parallel to x only)
    radius: float
    x0: float
    x1: float
    area: float


def _read_faces(volume: int):
    """(cylinders parallel to x and convex, tori with axis parallel to x and concave as (tag, axis
    (y, z), tube centre (x, y, z), minor radius), convex tori count, drilling candidates as (tag,
    radius, axis point)) of ``volume``'s faces, model units.

    Convex or concave from the outward normal at a point of the face: a convex cylinder's points
    away from its axis, a concave torus's towards its tube's centre line (the metal is then
    outside the tube: a re-entrant corner). Gmsh's ``isInside`` would say the same (checked on
    both test cranks' 164 faces) at 0.2 s a call on a solid of chamfered webs."""
    occ = gmsh.model.occ
    cyls, tori, drills, convex_tori = [], [], [], 0
    for _, s in gmsh.model.getBoundary([(3, volume)], oriented=False):
        kind = gmsh.model.getType(2, s)
        if kind not in ("Cylinder", "Torus"):
            continue
        circles = _iso_circles(s)
        p, n = _face_point(s)
        if kind == "Cylinder":
            ring = next((c for c in circles if c is not None), None)
            if ring is None:
                continue
            centre, r, axis = ring
            foot = centre + float((p - centre) @ axis) * axis  # the axis point level with p
            convex = float(n @ (p - foot)) > 0
            if not _parallel_to_x(axis):
                if not convex:  # a cylinder across the crank axis with the metal outside: a drilling
                    drills.append((s, r, centre))
                continue
            if not convex:
                continue  # a bore or a hole along x: the metal is outside it
            box = gmsh.model.getBoundingBox(2, s)
            cyls.append(_Cyl(s, (float(centre[1]), float(centre[2])), r, box[0], box[3], occ.getMass(2, s)))
        else:
            if any(c is None for c in circles):
                continue
            # the parallel (plane normal to the axis) gives the axis; the meridian the tube
            ring, tube = sorted(circles, key=lambda c: -abs(c[2][0]))
            if not _parallel_to_x(ring[2]):
                continue  # a torus about another axis rounds no journal or pin end
            tube_centre, minor = tube[0], tube[1]
            # the tube's centre line is the circle of the major radius about the axis at the tube's x
            axis_pt = np.array([tube_centre[0], ring[0][1], ring[0][2]])
            major = float(np.linalg.norm(tube_centre - axis_pt))
            out = np.array([0.0, p[1] - axis_pt[1], p[2] - axis_pt[2]])
            line = axis_pt + major * out / np.linalg.norm(out)  # the tube centre nearest p
            if float(n @ (line - p)) <= 0:  # normal away from the tube's centre: a convex round
                convex_tori += 1
                continue
            tori.append((s, (float(ring[0][1]), float(ring[0][2])), tube_centre, minor, _meridian_extent(s, ring[0])))
    return cyls, tori, convex_tori, drills


def first_pin_turn(crank, pieces, volume: int, unit: float) -> float | None:
    """The turn about x (rad) that puts the first pin found on ``volume`` (crank axis x, front at
    x = 0) at its described angle: the convex cylinder parallel to x whose axis lies at the crank
    radius (within :data:`AXIS_TOL`) and whose mid-x lies in the first pin of the layout ``pieces``
    (mm), the largest such face; None when there is none (the check then names the missing pin)."""
    R = crank.engine.crank_radius / unit
    pin = next(p for p in pieces if p.kind == "pin")
    near = [c for c in _read_faces(volume)[0]
            if pin.x0 <= 0.5 * (c.x0 + c.x1) <= pin.x1 and abs(math.hypot(*c.centre) - R) < AXIS_TOL * R]
    if not near:
        return None
    c = max(near, key=lambda c: c.area)
    turn = math.atan2(pin.centre[1], pin.centre[0]) - math.atan2(c.centre[1], c.centre[0])
    return math.remainder(turn, 2 * math.pi)


# ---------------------------------------------------------------------------
# The check against the description


def recognise(crank, pieces, volume: int, name: str, unit: float) -> SolidFeatures:
    """Read the journals, pins, fillets and drillings of the imported solid ``volume`` (current
    Gmsh model, model units) and check them against the description's layout ``pieces``.

    Parameters
    ----------
    crank : Crank
        The description (SI).
    pieces : list
        Its layout (:func:`fetorsion.solid.geometry.layout`, mm).
    volume : int
        The solid, one OCC volume, crank axis x, front at x = 0.
    name : str
        The STEP file's name, for the messages.
    unit : float
        Metres per model length unit (:data:`fetorsion.solid.geometry.MODEL_UNIT`).

    Returns
    -------
    SolidFeatures

    Raises
    ------
    GeometryError
        One line naming the file: the journals' diameters off the description's by a unit
        (:data:`UNIT_SLIPS`); a journal or pin of the layout with no
        cylinder on its axis there; diameters that disagree by more than :data:`DIAMETER_TOL`
        (every such part, with both diameters).
    """
    u = unit
    R = crank.engine.crank_radius / u
    tol = AXIS_TOL * R
    cyls, tori, convex_tori, drills = _read_faces(volume)

    def on_axis(c: _Cyl, centre) -> bool:
        return math.hypot(c.centre[0] - centre[0], c.centre[1] - centre[1]) < tol

    found: dict[str, list[_Cyl]] = {}
    shafts = [p for p in pieces if p.kind in ("journal", "pin")]
    for p in shafts:
        found[p.name] = [c for c in cyls if p.x0 <= 0.5 * (c.x0 + c.x1) <= p.x1 and on_axis(c, p.centre)]

    # a unit slip shows first on the journals (coaxial whatever the scale); pins then miss their axis
    ratios = [max(found[p.name], key=lambda c: c.area).radius * 2 / (p.spec.diameter / u)
              for p in shafts if p.kind == "journal" and found[p.name]]
    if ratios:
        ratio = float(np.median(ratios))
        slip = unit_slip(ratio)
        if slip:
            raise GeometryError(f"{name}: the journals found on the solid are {ratio:.4g} times the description's "
                                f"diameters; {slip}")
    missing = []
    for p in shafts:
        if found[p.name]:
            continue
        where = f"x = {p.x0:.6g}-{p.x1:.6g} mm"
        if p.kind == "journal":
            missing.append(f"{p.name}: no cylindrical face coaxial with the x axis at {where}")
        else:
            a = _degrees(p.centre)
            near = [c for c in cyls if p.x0 <= 0.5 * (c.x0 + c.x1) <= p.x1 and math.hypot(*c.centre) > tol]
            seen = "; off-axis cylinders there: " + ", ".join(
                f"diameter {2 * c.radius:.4g} mm on an axis {math.hypot(*c.centre):.4g} mm from the crank axis "
                f"at {_degrees(c.centre)}°" for c in near[:2]) if near else ""
            missing.append(f"{p.name}: no cylindrical face on its axis (crank radius {R:.6g} mm, angle {a}°) "
                           f"at {where}{seen}")
    if missing:
        raise GeometryError(f"{name}: the solid is not the described crank: " + "; ".join(missing))
    off, journals, pins = [], [], []
    for p in shafts:
        best = max(found[p.name], key=lambda c: c.area)
        d, described = 2 * best.radius, p.spec.diameter / u
        if abs(d / described - 1.0) > DIAMETER_TOL:
            off.append(f"{p.name} is {d:.4g} mm on the solid, {described:.4g} mm in the description")
        rec = FoundCylinder(p.name, d * u, best.x0 * u, best.x1 * u,
                            math.atan2(best.centre[1], best.centre[0]) if p.kind == "pin" else 0.0, len(found[p.name]))
        (journals if p.kind == "journal" else pins).append(rec)
    if off:
        raise GeometryError(f"{name}: diameters disagree with the description by more than "
                            f"{DIAMETER_TOL:.0%}: " + "; ".join(off))

    fillets, other = _group_fillets(crank, pieces, tori, u)
    drillings = _drillings(crank, pieces, drills, u)
    return SolidFeatures(name, tuple(journals), tuple(pins), fillets, drillings, other + convex_tori)


def _drillings(crank, pieces, drills, u: float) -> tuple[FoundDrilling, ...]:
    """The drilling candidates (tag, radius, axis point; model units) no wider than the described
    oil holes, each with the part of the layout its axis point lies in."""
    hole_r = 0.5 * crank.oil_holes.diameter / u
    drillings = []
    for _, r, point in drills:
        if hole_r > 0 and r < 1.01 * hole_r:
            part = next((p.name for p in pieces if p.x0 <= point[0] <= p.x1), "outside")
            drillings.append(FoundDrilling(part, 2 * r * u, float(point[0]) * u))
    return tuple(drillings)


def _degrees(centre) -> str:
    """The angle of an axis through (y, z) = ``centre`` about the crank axis, 0-360°, to 0.1°."""
    return f"{round(math.degrees(math.atan2(centre[1], centre[0])), 1) % 360.0 + 0.0:g}"


def _corners(crank, pieces, u: float):
    """(label, x, axis centre (y, z), shaft radius, described fillet radius) of every
    journal/web and pin/web corner of the layout, model units."""
    out = []
    for i, p in enumerate(pieces):
        if p.kind != "web":
            continue
        for other, x in ((pieces[i - 1], p.x0), (pieces[i + 1], p.x1)):
            if other.kind in ("journal", "pin"):
                r = crank.fillets.pin if other.kind == "pin" else crank.fillets.journal
                out.append((f"{other.name}/{p.name}", x, other.centre, 0.5 * other.spec.diameter / u, r / u))
    return out


def _group_fillets(crank, pieces, tori, u: float) -> tuple[tuple[FoundFillet, ...], int]:
    """The concave tori grouped by the corner they round: each to the nearest corner on its axis
    whose corner point (web face, shaft surface) lies within 2 (r + r_described) of the tube centre
    (a plain fillet's centre is √2 r from its corner, an undercut's arcs lie within their radii of
    it; a groove mid-journal is farther). Returns the fillets, by x, and how many tori fit none."""
    corners = _corners(crank, pieces, u)
    groups: dict[int, list[tuple[float, float, tuple]]] = {}
    other = 0
    R = crank.engine.crank_radius / u
    for _, axis, tube, minor, extent in tori:
        best, dist = None, math.inf
        for k, (_, x, centre, radius, described) in enumerate(corners):
            if math.hypot(axis[0] - centre[0], axis[1] - centre[1]) > AXIS_TOL * R:
                continue
            rho = math.hypot(tube[1] - centre[0], tube[2] - centre[1])
            d = math.hypot(tube[0] - x, rho - radius)
            if d < dist and d <= 2.0 * (minor + described):
                best, dist = k, d
        if best is None:
            other += 1
        else:
            groups.setdefault(best, []).append((minor, float(tube[0]), extent))
    fillets = []
    for k in sorted(groups, key=lambda k: corners[k][1]):
        label, _, _, _, described = corners[k]
        faces = sorted(groups[k], key=lambda f: f[0])
        box = np.array([f[2] for f in faces])
        extent = (box[:, 0].min() * u, box[:, 1].max() * u, box[:, 2].min() * u, box[:, 3].max() * u)
        fillets.append(FoundFillet(label, faces[0][1] * u, faces[0][0] * u, tuple(f[0] * u for f in faces),
                                   described * u, tuple(float(e) for e in extent)))
    return tuple(fillets), other
