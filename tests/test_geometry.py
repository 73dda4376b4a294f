"""The Gmsh crank solid against independent analytic numbers."""

import copy
import dataclasses
import math
import tomllib

import gmsh
import pytest

import fetorsion
from fetorsion.description.crank import parse_crank
from fetorsion.description.model import OilHoles
from fetorsion.solid.geometry import GeometryError, build_solid, crank_mass_properties, gmsh_session, solid_mass_properties
from fetorsion.lumped_model.parts import build_parts, cylinder_inertia
from fetorsion.solid.outline import mass_properties as web_mass

from conftest import GEOMETRY, plain

pytestmark = [pytest.mark.fe]

REFERENCE = [GEOMETRY / "peugeot_glx.toml", GEOMETRY / "renault21.toml"]


def analytic_mass(crank) -> float:
    rho, R = crank.material.density, crank.engine.crank_radius
    cyl = crank.front + crank.journals + crank.pins + crank.rear
    return (sum(rho * math.pi / 4 * (c.diameter**2 - c.bore**2) * c.length for c in cyl)
            + sum(web_mass(w, R, rho)["mass"] for w in crank.webs))


@pytest.mark.parametrize("path", REFERENCE, ids=lambda p: p.stem)
def test_plain_solid_matches_analytic_part_sums(path):
    crank = plain(fetorsion.load(path))
    total, parts = crank_mass_properties(crank)
    # Same geometry on both sides; only fetorsion.solid.outline's midpoint quadrature differs (~6e-5 at
    # the counterweight's jumps), so 1e-3 is margin, well inside the 0.5 %.
    assert total.mass == pytest.approx(analytic_mass(crank), rel=1e-3)
    assert total.polar_inertia == pytest.approx(sum(p.inertia for p in build_parts(crank).parts), rel=1e-3)
    # Cylindrical parts are exact in OCC: eq. (14)/(16) to round-off.
    R = crank.engine.crank_radius
    assert parts["pin_2"].polar_inertia == pytest.approx(cylinder_inertia(crank.pins[1], crank.material.density, R),
                                                         rel=1e-9)
    assert parts["journal_3"].polar_inertia == pytest.approx(
        cylinder_inertia(crank.journals[2], crank.material.density), rel=1e-9)
    # A balanced inline-4 (0/180/180/0) has its centre of mass on the axis.
    assert math.hypot(*total.centre[1:]) < 1e-6


def fillet_ring_volume(a: float, r: float) -> float:
    """Volume added by a concave fillet of radius r around a circle of radius a (Pappus):
    section r²(1 − π/4), centroid 0.2234 r = r(10 − 3π)/(3(4 − π)) out from the corner."""
    return 2 * math.pi * (a + r * (10 - 3 * math.pi) / (3 * (4 - math.pi))) * r**2 * (1 - math.pi / 4)


@pytest.mark.parametrize("path", REFERENCE, ids=lambda p: p.stem)
def test_reference_crank_is_one_solid_with_named_parts_and_faces(path):
    crank = fetorsion.load(path)
    no_holes = dataclasses.replace(crank, oil_holes=OilHoles())
    with gmsh_session():
        solid = build_solid(crank)
        names = {gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()}
        front = sum(gmsh.model.occ.getMass(2, t) for t in solid.front_face) * 1e-6
        rear = sum(gmsh.model.occ.getMass(2, t) for t in solid.rear_face) * 1e-6
        # The parts share faces: together they are one connected solid.
        adjacency = {v: set() for v in solid.volumes}
        for _, s in gmsh.model.getEntities(2):
            up = [int(v) for v in gmsh.model.getAdjacencies(2, s)[0]]
            for v in up:
                adjacency[v].update(up)
        seen, todo = set(), [solid.volumes[0]]
        while todo:
            v = todo.pop()
            if v not in seen:
                seen.add(v)
                todo += adjacency[v] - seen
        assert seen == set(solid.volumes)
    assert len(solid.parts) == 2 * crank.throws + crank.throws + crank.throws + 1 + 2 + 2
    assert {"front_face", "rear_face", "journal_1", "web_8", "pin_4", "front_1", "rear_2"} <= names
    assert len(solid.fillet_faces) == 4 * crank.throws  # one per journal/web and pin/web junction
    assert len(solid.hole_faces) == 2 * crank.throws + 1
    assert front == pytest.approx(math.pi / 4 * crank.front[0].diameter**2, rel=1e-9)
    assert rear == pytest.approx(math.pi / 4 * crank.rear[-1].diameter**2, rel=1e-9)
    # Fillets add exactly their rings (Pappus; OCC's exact torus to round-off).
    rho = crank.material.density
    added = crank_mass_properties(no_holes)[0].mass - crank_mass_properties(plain(crank))[0].mass
    # Inner journals and every pin meet two webs, the end journals one.
    webs_met = [1] + [2] * (crank.throws - 1) + [1]
    rings = sum(n * fillet_ring_volume(c.diameter / 2, crank.fillets.journal) for n, c in zip(webs_met, crank.journals)) \
        + 2 * sum(fillet_ring_volume(c.diameter / 2, crank.fillets.pin) for c in crank.pins)
    assert added == pytest.approx(rho * rings, rel=1e-6)


def raw(path) -> dict:
    with open(path, "rb") as fh:
        return tomllib.load(fh)


def test_web_that_does_not_cover_its_pin_is_named():
    crank = fetorsion.load(REFERENCE[0])
    webs = list(crank.webs)
    # Narrower than the pin: the description rules forbid it, a Crank built in code need not.
    webs[2] = dataclasses.replace(webs[2], width_pin=0.6 * crank.pins[1].diameter)
    with pytest.raises(GeometryError, match=r"web_3 does not cover pin_2"), gmsh_session():
        build_solid(dataclasses.replace(crank, webs=tuple(webs)))


def test_front_section_whose_bore_misses_the_journal_is_named():
    data = copy.deepcopy(raw(REFERENCE[0]))
    # A valid hollow step (bore < diameter) whose bore is wider than journal 1: it touches
    # nothing, and neither does the nose beyond it.
    data["front"][1].update(diameter=100.0, bore=70.0)
    crank = parse_crank(data)  # passes the description rules
    with pytest.raises(GeometryError, match=r"front_1, front_2 not connected"), gmsh_session():
        build_solid(crank)


def test_fillet_without_web_to_run_onto_is_named():
    data = copy.deepcopy(raw(REFERENCE[1]))
    data["webs"][0]["width_journal"] = data["journals"][0]["diameter"]  # allowed: >= the journal
    del data["uncertainty"]  # its ranges bracket the nominal web width
    crank = parse_crank(data)
    with pytest.raises(GeometryError, match=r"does not fit between journal_1 and web_1"), gmsh_session():
        build_solid(crank)


def test_hollow_parts_keep_their_bores():
    crank = plain(fetorsion.load(REFERENCE[1]))
    bored = dataclasses.replace(crank, pins=tuple(dataclasses.replace(p, bore=0.02) for p in crank.pins),
                                journals=tuple(dataclasses.replace(j, bore=0.015) for j in crank.journals))
    with gmsh_session():
        solid = build_solid(bored)
        _, parts = solid_mass_properties(solid, bored.material.density)
    R, rho = bored.engine.crank_radius, bored.material.density
    assert parts["pin_1"].polar_inertia == pytest.approx(cylinder_inertia(bored.pins[0], rho, R), rel=1e-9)
    assert parts["journal_2"].polar_inertia == pytest.approx(cylinder_inertia(bored.journals[1], rho), rel=1e-9)
    # the bore is really in the solid: the hollow pin is lighter than the solid one by the bore's volume
    solid_pin = cylinder_inertia(crank.pins[0], rho, R)
    assert parts["pin_1"].polar_inertia < solid_pin
