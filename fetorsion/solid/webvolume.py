"""A crank web as an OpenCASCADE volume (model units): its exact outline, as
:mod:`fetorsion.solid.outline` draws it, extruded along x, after checking in the web plane that it
covers the pin and the journal it carries."""

from __future__ import annotations

import math

import numpy as np

from ..description.model import Cylinder, Web
from ..errors import GeometryError


def _web_face(occ, web: Web, R: float, angle: float, x0: float, s: float) -> int:
    """The exact web outline as one plane surface at x = x0 (model units); returns its tag.

    Built from its true pieces: the arc of the journal-end circle (radius r1 on the axis),
    the two common tangents, the arc of the pin-end circle (radius r2 at the pin), then
    united with the counterweight sector. Same construction as
    :func:`fetorsion.solid.outline.radial_function`.
    """
    r1, r2 = 0.5 * web.width_journal * s, 0.5 * web.width_pin * s
    u = np.array([math.cos(angle), math.sin(angle)])  # towards the pin
    v = np.array([-math.sin(angle), math.cos(angle)])

    def point(a: float, b: float) -> int:
        y, z = a * u + b * v
        return occ.addPoint(x0, y, z)

    beta = math.acos((r1 - r2) / R)  # direction of the tangents' normals
    cb, sb = math.cos(beta), math.sin(beta)
    axis, pin = point(0, 0), point(R, 0)
    t1a, t1b = point(r1 * cb, r1 * sb), point(r1 * cb, -r1 * sb)
    t2a, t2b = point(R + r2 * cb, r2 * sb), point(R + r2 * cb, -r2 * sb)
    back, tip = point(-r1, 0), point(R + r2, 0)
    # Each arc is split at its midpoint: OCC arcs through 3 points must span less than π.
    loop = occ.addCurveLoop([
        occ.addCircleArc(t2b, pin, tip), occ.addCircleArc(tip, pin, t2a), occ.addLine(t2a, t1a),
        occ.addCircleArc(t1a, axis, back), occ.addCircleArc(back, axis, t1b), occ.addLine(t1b, t2b),
    ])
    face = occ.addPlaneSurface([loop])
    rc = web.counterweight_radius * s
    if rc <= r1:  # the sector lies inside the journal-end disc: the outline is the hull
        return face
    half = 0.5 * web.counterweight_angle
    if half >= math.pi - 1e-9:
        sector = occ.addDisk(x0, 0, 0, rc, rc, zAxis=[1, 0, 0], xAxis=[0, *u])
    else:
        ends = [point(rc * math.cos(math.pi + a), rc * math.sin(math.pi + a)) for a in (-half, 0.0, half)]
        sector = occ.addPlaneSurface([occ.addCurveLoop([
            occ.addLine(axis, ends[0]), occ.addCircleArc(ends[0], axis, ends[1]),
            occ.addCircleArc(ends[1], axis, ends[2]), occ.addLine(ends[2], axis),
        ])])
    out, _ = occ.fuse([(2, face)], [(2, sector)])
    if len(out) != 1:
        raise GeometryError(f"web outline with counterweight did not give one face ({len(out)})")
    return out[0][1]


def _uncovered_area(occ, face: int, x: float, centre, diameter: float) -> float:
    """Area (model units²) of a disc at ``centre`` on plane x that lies outside ``face``."""
    disc = occ.addDisk(x, centre[0], centre[1], 0.5 * diameter, 0.5 * diameter, zAxis=[1, 0, 0], xAxis=[0, 1, 0])
    rest, _ = occ.cut([(2, disc)], [(2, face)], removeObject=True, removeTool=False)
    area = sum(occ.getMass(d, t) for d, t in rest)
    occ.remove(rest, recursive=True)
    return area


def web_volume(occ, piece, journal, pin, R: float, s: float) -> list[tuple[int, int]]:
    """The web ``piece`` extruded from its exact outline, after checking that it carries its pin and
    its journal.

    Parameters
    ----------
    occ : module
        ``gmsh.model.occ`` of the current model.
    piece, journal, pin : layout pieces
        The web, and the journal and pin it joins (:func:`fetorsion.solid.geometry.layout`,
        model units).
    R : float
        Crank radius, model units.
    s : float
        Model units per metre.

    Returns
    -------
    list of (int, int)
        The web's volume dimTags.

    Raises
    ------
    GeometryError
        Naming the web, when its outline leaves part of the pin's or journal's section uncovered.
    """
    web: Web = piece.spec
    face = _web_face(occ, web, R, piece.angle, piece.x0, s)
    for other in (pin, journal):
        d = other.spec.diameter * s
        lost = _uncovered_area(occ, face, piece.x0, other.centre, d)
        if lost > 1e-6 * d * d:
            raise GeometryError(
                f"{piece.name} does not cover {other.name}: {lost:.3g} mm² of the {other.kind} section "
                f"(diameter {d:g} mm) lies outside the web outline; widen the web "
                f"(width_{'pin' if other.kind == 'pin' else 'journal'}) or shrink the {other.kind}")
    out = occ.extrude([(2, face)], piece.x1 - piece.x0, 0, 0)
    return [dt for dt in out if dt[0] == 3]


def hollow_cylinder(occ, x0: float, length: float, c: Cylinder, centre, s: float) -> list[tuple[int, int]]:
    """A cylinder along +x, diameter ``c.diameter`` less its bore; returns volume dimTags."""
    y, z = centre
    outer = occ.addCylinder(x0, y, z, length, 0, 0, 0.5 * c.diameter * s)
    if c.bore <= 0:
        return [(3, outer)]
    inner = occ.addCylinder(x0, y, z, length, 0, 0, 0.5 * c.bore * s)
    out, _ = occ.cut([(3, outer)], [(3, inner)])
    return out


def split_pin_volumes(occ, piece, s: float) -> list[tuple[int, int]]:
    """A split pin (docs/vee-engines.md, *split pins*): the front half pin on ``piece.centre``, the
    flying web, the rear half pin on ``piece.rear_centre``, as volumes to fuse (model units).

    The flying web's outline is the convex hull of the two half pins' circles (the pin's own
    diameter, a stadium), built as one face of two arcs and their two common tangents, as a web's
    outline is (:func:`_web_face`), so no boolean meets a tangent face. It is solid: a bored half
    pin's bore ends at it.
    """
    pin = piece.spec
    h, w, r = pin.half_length * s, pin.flying_web * s, 0.5 * pin.diameter * s
    c1, c2 = np.asarray(piece.centre, float), np.asarray(piece.rear_centre, float)
    u = (c2 - c1) / np.linalg.norm(c2 - c1)
    n = np.array([-u[1], u[0]])
    x = piece.x0 + h

    def point(p) -> int:
        return occ.addPoint(x, float(p[0]), float(p[1]))

    a1, b1, tip1 = point(c1 + r * n), point(c1 - r * n), point(c1 - r * u)
    a2, b2, tip2 = point(c2 + r * n), point(c2 - r * n), point(c2 + r * u)
    o1, o2 = point(c1), point(c2)
    # each end is a half circle, split at its tip: OCC arcs through 3 points must span less than π
    loop = occ.addCurveLoop([occ.addCircleArc(a1, o1, tip1), occ.addCircleArc(tip1, o1, b1), occ.addLine(b1, b2),
                             occ.addCircleArc(b2, o2, tip2), occ.addCircleArc(tip2, o2, a2), occ.addLine(a2, a1)])
    web = [dt for dt in occ.extrude([(2, occ.addPlaneSurface([loop]))], w, 0, 0) if dt[0] == 3]
    front = hollow_cylinder(occ, piece.x0, h, pin, piece.centre, s)
    rear = hollow_cylinder(occ, piece.x1 - h, h, pin, piece.rear_centre, s)
    return front + web + rear
