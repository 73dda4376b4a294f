"""A crank's solid from CAD: ``[solid] step`` in place of the solid built from the dimensions
(issue 44, first part): the Renault written as STEP and read back is the same solid, its FE modes
the same; a STEP file that is not one closed solid in the right unit is refused, naming it."""

import math
from pathlib import Path

import gmsh
import pytest

import fetorsion
from fetorsion.errors import DescriptionError, FetorsionError

ROOT = Path(__file__).resolve().parent.parent
RENAULT = ROOT / "geometry" / "renault21.toml"


def with_solid(tmp_path, step_name: str) -> Path:
    path = tmp_path / "crank.toml"
    path.write_text(RENAULT.read_text() + f'\n[solid]\nstep = "{step_name}"\nsource = "test"\n')
    return path


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    from fetorsion.solid.geometry import write_step

    folder = tmp_path_factory.mktemp("step")
    return write_step(fetorsion.load(RENAULT), folder / "renault21.step")


def test_the_renault_written_as_step_reads_back_as_the_same_solid(written, tmp_path):
    """Mass and polar inertia of every part (OpenCASCADE's integration of the same body, cut at the
    same planes) to 1e-9, and the same fillet and drilling faces found on it by their surface type."""
    from fetorsion.solid.geometry import build_solid, gmsh_session, solid_mass_properties

    (tmp_path / written.name).write_bytes(written.read_bytes())
    built, read = fetorsion.load(RENAULT), fetorsion.load(with_solid(tmp_path, written.name))
    assert read.solid_step == str((tmp_path / written.name).resolve())
    out = []
    for crank in (built, read):
        with gmsh_session():
            solid = build_solid(crank)
            total, parts = solid_mass_properties(solid, crank.material.density)
            out.append((total, parts, len(solid.fillet_faces), len(solid.hole_faces)))
    (t1, p1, f1, h1), (t2, p2, f2, h2) = out
    assert (f2, h2) == (f1, h1) and f1 == 16 and h1 > 0
    assert t2.mass == pytest.approx(t1.mass, rel=1e-9) and t2.polar_inertia == pytest.approx(t1.polar_inertia, rel=1e-9)
    for name in p1:
        assert p2[name].mass == pytest.approx(p1[name].mass, rel=1e-9), name


@pytest.mark.slow
@pytest.mark.fe
def test_the_round_trip_has_the_same_free_free_modes(written, tmp_path):
    """The issue's bound: the same free-free modes within 0.3 % (the same size fields on the same
    body; only Gmsh's meshing of the imported faces may differ)."""
    from fetorsion.fe.crankfe import run_modal

    (tmp_path / written.name).write_bytes(written.read_bytes())
    a = run_modal(fetorsion.load(RENAULT), 0.02, modes=8).frequencies_hz[:8]
    b = run_modal(fetorsion.load(with_solid(tmp_path, written.name)), 0.02, modes=8).frequencies_hz[:8]
    assert b == pytest.approx(a, rel=3e-3)


def _write_shapes(path: Path, make) -> Path:
    from fetorsion.solid.geometry import gmsh_session
    from fetorsion.solid.stepimport import quiet_stdout as _quiet_stdout

    with gmsh_session("bad"):
        make(gmsh.model.occ)
        gmsh.model.occ.synchronize()
        with _quiet_stdout():
            gmsh.write(str(path))
    return path


def _load_and_build(crank_file: Path):
    from fetorsion.solid.geometry import build_solid, gmsh_session

    crank = fetorsion.load(crank_file)
    with gmsh_session():
        build_solid(crank)


def test_a_step_that_is_not_one_closed_solid_in_the_right_unit_is_refused(written, tmp_path):
    _write_shapes(tmp_path / "two.step", lambda occ: (occ.addBox(0, 0, 0, 10, 10, 10), occ.addBox(50, 0, 0, 10, 10, 10)))
    with pytest.raises(FetorsionError, match=r"two.step: 2 separate bodies, not one solid crank"):
        _load_and_build(with_solid(tmp_path, "two.step"))
    _write_shapes(tmp_path / "open.step", lambda occ: occ.addRectangle(0, 0, 0, 10, 10))
    with pytest.raises(FetorsionError, match=r"open.step: no closed volume in the file"):
        _load_and_build(with_solid(tmp_path, "open.step"))

    def inches(occ):  # the Renault's numbers taken as inches: 25.4 times too long in mm
        occ.importShapes(str(written))
        occ.dilate(occ.getEntities(3), 0, 0, 0, 25.4, 25.4, 25.4)

    _write_shapes(tmp_path / "inch.step", inches)
    with pytest.raises(FetorsionError, match=r"inch.step: the solid is .* mm long along x, the description's crank "
                                             r".* mm; its unit looks wrong: drawn in mm while its header says in"):
        _load_and_build(with_solid(tmp_path, "inch.step"))
    with pytest.raises(DescriptionError, match=r"solid.step = 'missing.step': no such file"):
        fetorsion.load(with_solid(tmp_path, "missing.step"))
    (tmp_path / "crank.iges").write_text("x")
    with pytest.raises(DescriptionError, match=r"must be a STEP file"):
        fetorsion.load(with_solid(tmp_path, "crank.iges"))


def test_a_cad_cranks_lumped_chain_takes_its_inertias_from_the_solid(written, tmp_path):
    """The lumped chain of a [solid] crank: every part's inertia OpenCASCADE's over its own solid,
    so the chain's total is the solid's polar inertia (fillets and drillings in) plus the
    attachments (pistons and rods once per pin) to round-off; on the round trip its f1 is the built
    crank's within the issue's 0.3 % (only the fillets, which the formulas leave out, differ)."""
    from fetorsion.lumped_model.lumped import lumped
    from fetorsion.solid.geometry import crank_mass_properties

    (tmp_path / written.name).write_bytes(written.read_bytes())
    built, read = fetorsion.load(RENAULT), fetorsion.load(with_solid(tmp_path, written.name))
    chain = lumped(read)
    total, _ = crank_mass_properties(read)
    attached = sum(a.polar_inertia * (len(read.pins) if a.at == "pins" else 1) for a in read.attachments)
    assert chain.inertias_kgm2.sum() == pytest.approx(total.polar_inertia + attached, rel=1e-9)
    assert chain.frequencies_hz[0] == pytest.approx(lumped(built).frequencies_hz[0], rel=3e-3)


@pytest.mark.slow  # 12 s: a rendered CAD crank
def test_the_picture_of_a_cad_crank_shows_what_was_found_on_it(written, tmp_path):
    """The report's picture of a [solid] crank: the fillet faces drawn red and the drilling faces
    green over the parts' colours (pixels of those colours in the picture), off-screen."""
    import numpy as np
    from PIL import Image

    from fetorsion.report.render import render_solid

    (tmp_path / written.name).write_bytes(written.read_bytes())
    out = render_solid(fetorsion.load(with_solid(tmp_path, written.name)), tmp_path / "solid.png", window=(800, 450))
    img = np.asarray(Image.open(out).convert("RGB")).astype(int)

    def share(rgb):  # pixels near a colour, shading allowed (a quarter of the range)
        return np.mean(np.all(np.abs(img - np.array(rgb)) < 64, axis=2))

    assert share((0xd6, 0x27, 0x28)) > 1e-4 and share((0x2c, 0xa0, 0x2c)) > 1e-5
    assert share((0x4c, 0x72, 0xb0)) > 1e-3  # the journals, for scale


@pytest.mark.slow  # 20 s: a CAD throw meshed and solved twice
def test_a_cad_cranks_throw_is_its_solids_slab(tmp_path):
    """The throw FE of a [solid] crank (web stiffness, fillet SCFs) meshes the solid's slab from
    journal centre to journal centre, turned to put its pin at angle 0. Without drillings the
    Renault's written and read-back throw 2 (pin at 180°: the turn is exercised) has the built
    throw's torsional stiffness to 1e-3 (the same body, meshed from imported faces; the round
    trip's modes agree to 3e-4). With drillings they differ, rightly: the built throw drills its
    half journals at their own centres, the real crank (and its slab) at the journal's centre,
    the slab's end face."""
    from fetorsion.solid.geometry import write_step
    from fetorsion.webs import throwfe

    text = RENAULT.read_text().replace("diameter = 5.0  # [N] typical automotive drilling", "diameter = 0.0")
    text = text.replace('"oil_holes.diameter" = [4.0, 7.0]', "")
    (tmp_path / "plain.toml").write_text(text)
    built = fetorsion.load(tmp_path / "plain.toml")
    assert built.oil_holes.diameter == 0.0 and built.engine.crank_angles[1] != 0.0
    write_step(built, tmp_path / "plain.step")
    (tmp_path / "plain_step.toml").write_text(text + '\n[solid]\nstep = "plain.step"\n')
    read = fetorsion.load(tmp_path / "plain_step.toml")
    throw = throwfe.throw_of(read, 1)
    assert throw.solid_window[2] == -built.engine.crank_angles[1]
    assert throwfe.throw_key(throw, None) != throwfe.throw_key(throwfe.throw_of(built, 1), None)
    k = [throwfe.torsional_stiffness_fe(throwfe.throw_of(c, 1), 0.02, 0.003).stiffness for c in (built, read)]
    assert k[1] == pytest.approx(k[0], rel=1e-3)


def lightened_step(crank, path, r_hole: float = 8.0, at: float = 55.0) -> float:
    """The crank's built solid with a lightening hole (radius ``r_hole`` mm, ``at`` mm from the
    axis, opposite the pin) through every web's counterweight, written as STEP: a crank whose webs
    are not the built outline. Returns the holes' volume, mm³ (each a full cylinder through a web)."""
    import math

    from fetorsion.solid.geometry import _built_solid, gmsh_session, layout
    from fetorsion.solid.stepimport import quiet_stdout as _quiet_stdout

    with gmsh_session("lightened"):
        pieces = layout(crank)
        solid = _built_solid(crank, pieces)
        occ = gmsh.model.occ
        webs = [p for p in pieces if p.kind == "web"]
        tools = [(3, occ.addCylinder(p.x0 - 1, at * math.cos(p.angle + math.pi), at * math.sin(p.angle + math.pi),
                                     p.x1 - p.x0 + 2, 0, 0, r_hole)) for p in webs]
        out, _ = occ.cut([(3, solid)], tools)
        occ.synchronize()
        assert len(out) == 1
        with _quiet_stdout():
            gmsh.write(str(path))
    return sum(math.pi * r_hole**2 * (p.x1 - p.x0) for p in webs)


#: The test crank's undercut fillet: three tangent concave arcs (mm) over 90°, 45° and 45°, from the
#: journal or pin into the web and back out to the web face (issue 44's "undercut fillet made of
#: several faces"): three toroidal faces, one fillet, 2 mm its smallest radius.
UNDERCUT = (2.0, 3.0, 4.0)


def undercut_profile(r1: float, r2: float, r3: float):
    """The undercut's profile in (ξ, η), mm: ξ into the web from its face, η out from the shaft
    surface. It leaves the shaft line at ξ = c1 along +ξ, turns 90° on r1 (centre (c1, r1)), 45° on
    r2 and 45° on r3, and meets the web face (ξ = 0) heading along −ξ; c1 = r2 − r1 + (r3 − r2)/√2
    puts the last arc's end on the face. Returns (p1, c1, p2, c2, p3, c3, p4): the arcs' ends and
    centres, each arc tangent to the next."""
    h = math.sqrt(0.5)
    c1 = r2 - r1 + (r3 - r2) * h
    p2 = (c1 + r1, r1)
    cen2 = (c1 + r1 - r2, r1)
    p3 = (cen2[0] + r2 * h, cen2[1] + r2 * h)
    cen3 = (p3[0] - r3 * h, p3[1] - r3 * h)
    p4 = (cen3[0], cen3[1] + r3)
    return (c1, 0.0), (c1, r1), p2, cen2, p3, cen3, p4


def _undercut(occ, x_w: float, into_web: float, centre, a: float, radii):
    """The void of an undercut at the corner of a shaft (radius ``a`` about an axis parallel to x
    through (y, z) = ``centre``) and a web face at x = ``x_w``, the web lying towards ``into_web``
    (±1) along x: the profile revolved about the shaft's axis (mm). It reaches 1 mm past the web
    face into the air, so none of its faces lies on one of the crank's."""
    p1, c1, p2, c2, p3, c3, p4 = undercut_profile(*radii)
    yc, zc = centre

    def pt(xi, eta):  # the profile in the plane through the shaft's axis and +y
        return occ.addPoint(x_w + into_web * xi, yc + a + eta, zc)

    P0, P1, C1, P2, C2, P3, C3, P4 = (pt(*q) for q in ((0.0, 0.0), p1, c1, p2, c2, p3, c3, p4))
    Q1, Q2 = pt(-1.0, p4[1]), pt(-1.0, 0.5)
    loop = occ.addCurveLoop([occ.addLine(P0, P1), occ.addCircleArc(P1, C1, P2), occ.addCircleArc(P2, C2, P3),
                             occ.addCircleArc(P3, C3, P4), occ.addLine(P4, Q1), occ.addLine(Q1, Q2),
                             occ.addLine(Q2, P0)])
    out = occ.revolve([(2, occ.addPlaneSurface([loop]))], x_w, yc, zc, 1, 0, 0, 2 * math.pi)
    return [dt for dt in out if dt[0] == 3]


#: The test crank's oval web (mm): an ellipse of semi-axes A along the throw and B across, centred
#: `OVAL_CENTRE` towards the pin, both outline edges chamfered by `OVAL_CHAMFER`, and a lightening
#: hole of radius `OVAL_HOLE[1]` `OVAL_HOLE[0]` from the axis opposite the pin. It covers the
#: journal's and the pin's undercuts with room to spare (at least 6.8 mm at the pin's 45° side).
OVAL_AXES, OVAL_CENTRE, OVAL_CHAMFER, OVAL_HOLE = (73.0, 48.0), 3.0, 2.0, (50.0, 8.0)


def _oval_web(occ, p):
    """The oval, chamfered, lightened web of layout piece ``p`` (mm); its volume dimTags."""
    u = (math.cos(p.angle), math.sin(p.angle))
    disk = occ.addDisk(p.x0, OVAL_CENTRE * u[0], OVAL_CENTRE * u[1], *OVAL_AXES, zAxis=[1, 0, 0], xAxis=[0, *u])
    vol = [dt for dt in occ.extrude([(2, disk)], p.x1 - p.x0, 0, 0) if dt[0] == 3]
    occ.synchronize()
    ends = [t for _, t in gmsh.model.getBoundary(vol, oriented=False) if gmsh.model.getType(2, t) == "Plane"]
    edges = [(c, f) for f in ends for _, c in gmsh.model.getBoundary([(2, f)], oriented=False)]
    vol = occ.chamfer([vol[0][1]], [c for c, _ in edges], [f for _, f in edges], [OVAL_CHAMFER])
    d, r = OVAL_HOLE
    hole = occ.addCylinder(p.x0 - 1, -d * u[0], -d * u[1], p.x1 - p.x0 + 2, 0, 0, r)
    return occ.cut(vol, [(3, hole)])[0]


def oval_step(crank, path, radii=UNDERCUT) -> Path:
    """A crank of ``crank``'s layout, journals, pins, ends and drillings whose webs are not the
    built outline (oval, chamfered, a lightening hole each) and whose every journal and pin end has
    an undercut fillet of three tangent tori (``radii``, mm), written as STEP in mm."""
    from fetorsion.solid.geometry import _hollow_cylinder, _oil_holes, gmsh_session, layout
    from fetorsion.solid.stepimport import quiet_stdout as _quiet_stdout

    with gmsh_session("oval"):
        occ = gmsh.model.occ
        pieces = layout(crank)
        parts = []
        for p in pieces:
            parts += _oval_web(occ, p) if p.kind == "web" else _hollow_cylinder(occ, p.x0, p.x1 - p.x0, p.spec,
                                                                                 p.centre, 1e3)
        solid, _ = occ.fuse(parts[:1], parts[1:])
        assert len(solid) == 1
        voids = []
        for i, p in enumerate(pieces):
            if p.kind != "web":
                continue
            for other, x_w, into_web in ((pieces[i - 1], p.x0, 1.0), (pieces[i + 1], p.x1, -1.0)):
                if other.kind in ("journal", "pin"):
                    voids += _undercut(occ, x_w, into_web, other.centre, 0.5e3 * other.spec.diameter, radii)
        solid, _ = occ.cut(solid, voids + _oil_holes(occ, crank, pieces, 1e3))
        occ.synchronize()
        assert len(solid) == 1
        with _quiet_stdout():
            gmsh.write(str(path))
    return Path(path)


@pytest.fixture(scope="module")
def oval(tmp_path_factory):
    """The oval-webbed, undercut crank of the Renault's layout, as STEP."""
    return oval_step(fetorsion.load(RENAULT), tmp_path_factory.mktemp("oval") / "oval.step")


@pytest.fixture(scope="module")
def built_chain_gap(tmp_path_factory):
    """The built Renault's 17-DOF chain (`fe` webs) against its FE f1 in bearings, at the CAD
    tests' 20 mm mesh (`fetorsion run`'s FE and bearings steps): the reference each CAD crank's
    own gap is held to, computed once for the module's two end-to-end tests."""
    from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run

    steps = tuple(s for s in DEFAULT_STEPS if s[1] in ("fe", "bearings"))
    outcome = run(RENAULT, tmp_path_factory.mktemp("built") / "built", steps=steps,
                  options=RunOptions(mesh_size=0.02, html=False))
    return outcome.bearings.chain["fe"]["vs_bearings"]


def _corners(crank):
    """(label, web face x in mm, +1 where the web lies at larger x than the shaft) of every
    journal/web and pin/web corner of ``crank``'s layout."""
    from fetorsion.solid.geometry import layout

    pieces = layout(crank)
    out = []
    for i, p in enumerate(pieces):
        if p.kind != "web":
            continue
        for other, x, into_web in ((pieces[i - 1], p.x0, 1.0), (pieces[i + 1], p.x1, -1.0)):
            if other.kind in ("journal", "pin"):
                out.append((f"{other.name}/{p.name}", x, into_web))
    return out


def test_what_is_found_on_the_round_trip_is_the_described_crank(written, tmp_path):
    """On the Renault written as STEP, the journals, pins, fillets and drillings read from the
    solid's faces are the dimensions OpenCASCADE was given (1e-9: its exact surfaces): every
    diameter, every pin at its crank angle, one face per fillet of 2.5 mm whose tube centre lies
    one radius from the web face on the shaft's side, and a 5 mm drilling through every journal and
    pin."""
    from fetorsion.solid.geometry import solid_features

    (tmp_path / written.name).write_bytes(written.read_bytes())
    crank = fetorsion.load(with_solid(tmp_path, written.name))
    found = solid_features(crank)
    assert [j.diameter for j in found.journals] == pytest.approx([j.diameter for j in crank.journals], rel=1e-9)
    assert [p.diameter for p in found.pins] == pytest.approx([p.diameter for p in crank.pins], rel=1e-9)
    turn = [math.remainder(p.angle - a, 2 * math.pi) for p, a in zip(found.pins, crank.engine.crank_angles)]
    assert turn == pytest.approx([0.0] * len(crank.pins), abs=1e-9)
    r = crank.fillets.journal
    assert crank.fillets.pin == r and [f.end for f in found.fillets] == [c[0] for c in _corners(crank)]
    for f, (_, x_w, into_web) in zip(found.fillets, _corners(crank)):
        assert f.radii == pytest.approx((r,), rel=1e-9) and not f.differs
        assert f.x == pytest.approx(x_w * 1e-3 - into_web * r, abs=1e-9)
    holes = crank.oil_holes
    assert sorted(d.part for d in found.drillings) == sorted(f"{k}_{i + 1}" for k, n in (("journal", 5), ("pin", 4))
                                                           for i in range(n))
    assert [d.diameter for d in found.drillings] == pytest.approx([holes.diameter] * 9, rel=1e-9)
    assert found.other_tori == 0


def test_an_undercut_of_three_tori_is_one_fillet_with_its_smallest_radius(oval, tmp_path):
    """The oval-webbed crank: each journal and pin end has ONE fillet of three faces whose radii are
    the undercut's (2, 3, 4 mm, 1e-9), 2 mm reported, its tightest face's tube centre c1 into the
    web (the profile's own construction); the chamfers (cones) and the lightening holes (concave,
    along x) are no journal, pin or fillet. The report lists them and says that the description's
    2.5 mm differs and which radius the formulas take."""
    from fetorsion.report.markdown import solid_features_lines
    from fetorsion.solid.geometry import solid_features

    (tmp_path / oval.name).write_bytes(oval.read_bytes())
    crank = fetorsion.load(with_solid(tmp_path, oval.name))
    found = solid_features(crank)
    assert [j.diameter for j in found.journals] == pytest.approx([j.diameter for j in crank.journals], rel=1e-9)
    assert [p.diameter for p in found.pins] == pytest.approx([p.diameter for p in crank.pins], rel=1e-9)
    c1 = undercut_profile(*UNDERCUT)[0][0]
    assert [f.end for f in found.fillets] == [c[0] for c in _corners(crank)]
    for f, (_, x_w, into_web) in zip(found.fillets, _corners(crank)):
        assert f.faces == 3 and f.radii == pytest.approx(tuple(r * 1e-3 for r in UNDERCUT), rel=1e-9)
        assert f.radius == pytest.approx(2e-3, rel=1e-9) and f.differs and f.described == crank.fillets.journal
        assert f.x == pytest.approx((x_w + into_web * c1) * 1e-3, abs=1e-9)
    assert len(found.drillings) == 9 and found.other_tori == 0
    text = "\n".join(solid_features_lines(found))
    assert "| journal_1/web_1 | 81.71 | 2.00 | 3 | 2.50 (differs) |" in text
    assert "16 of the solid's 16 fillets differ from the description's radius by more than 5%" in text
    assert "The M53 and textbook fillet SCFs (the verdict's default method) take the description's radius" in text


def test_a_solid_that_is_not_the_described_crank_is_refused_before_any_work(written, tmp_path):
    """One line naming the file, from `fetorsion run` before its report folder exists: journals a
    unit off the description's (the solid stretched 25.4 times across its axis: the length along x
    agrees), a diameter off by more than 2 % (every such part with both diameters), and pins not on
    the described crank radius."""
    import dataclasses

    from fetorsion.app.run import run
    from fetorsion.solid.geometry import GeometryError, write_step

    (tmp_path / written.name).write_bytes(written.read_bytes())
    # every size across the axis 10 times the Renault's, every length along it the same (OCC's
    # non-uniform scaling would turn the cylinders into B-splines: the crank is built so instead)
    built = fetorsion.load(RENAULT)
    wide = dataclasses.replace(
        built, engine=dataclasses.replace(built.engine, stroke=10 * built.engine.stroke),
        journals=[dataclasses.replace(c, diameter=10 * c.diameter) for c in built.journals],
        pins=[dataclasses.replace(c, diameter=10 * c.diameter) for c in built.pins],
        front=[dataclasses.replace(c, diameter=10 * c.diameter) for c in built.front],
        rear=[dataclasses.replace(c, diameter=10 * c.diameter) for c in built.rear],
        webs=[dataclasses.replace(w, width_journal=10 * w.width_journal, width_pin=10 * w.width_pin,
                                  counterweight_radius=10 * w.counterweight_radius) for w in built.webs])
    write_step(wide, tmp_path / "wide.step")
    text = RENAULT.read_text()
    cases = {
        "wide": (text + '\n[solid]\nstep = "wide.step"\n',
                 r"^wide.step: the journals found on the solid are 10 times the description's diameters; "
                 r"its unit looks wrong: drawn in mm while its header says cm \(export it in cm, or with a header "
                 r"that says mm\)$"),
        "pins": (text.replace("diameter = 48.0", "diameter = 49.5") + f'\n[solid]\nstep = "{written.name}"\n',
                 r"^renault21.step: diameters disagree with the description by more than 2%: pin_1 is 48 mm on the "
                 r"solid, 49.5 mm in the description; pin_2 is 48 mm .*; pin_4 is 48 mm on the solid, 49.5 mm in "
                 r"the description$"),
        "stroke": (text.replace("stroke = 83.5 ", "stroke = 90.0 ") + f'\n[solid]\nstep = "{written.name}"\n',
                   r"^renault21.step: the solid is not the described crank: pin_1: no cylindrical face on its axis "
                   r"\(crank radius 45 mm, angle 0°\) at x = 102-124 mm; off-axis cylinders there: diameter 48 mm on "
                   r"an axis 41.75 mm from the crank axis at 0°; pin_2: .* at 180°; pin_3: .*; pin_4: .* at 0°$"),
    }
    for name, (description, message) in cases.items():
        (tmp_path / f"{name}.toml").write_text(description)
        with pytest.raises(GeometryError, match=message):
            run(tmp_path / f"{name}.toml", tmp_path / f"out_{name}")
        assert not (tmp_path / f"out_{name}").exists()


def test_a_cad_cranks_fe_scfs_are_read_where_its_fillets_are(written, oval, tmp_path):
    """The FE SCF zones of a CAD crank's throw come from the fillets found on its solid: on the
    round trip each is the description's quarter torus (the same points of a cloud filling the
    throw, but for at most 2 on its bounds); on the undercut crank the journal
    zone of throw 1 reaches into web 1 as far as the undercut does (c1 + r1 past the web face) and
    out to its lip (the profile's height), against the description's 2.5 mm on the journal's side."""
    import numpy as np

    from fetorsion.design.scf import found_zones, fillet_zone, found_zone
    from fetorsion.webs.throwfe import throw_of

    for f in (written, oval):
        (tmp_path / f.name).write_bytes(f.read_bytes())
    crank = fetorsion.load(with_solid(tmp_path, written.name))
    throw = throw_of(crank, 0)
    zones = found_zones(crank, 0, throw)
    j1, w1, pin = throw.journals[0], throw.webs[0], throw.pins[0]
    x = np.cumsum([0.0, j1.length, w1.thickness, pin.length, throw.webs[1].thickness])
    R, r = throw.engine.crank_radius, crank.fillets.journal
    described = [(x[1], -1, (0, 0), 0.5 * j1.diameter), (x[2], +1, (R, 0), 0.5 * pin.diameter),
                 (x[3], -1, (R, 0), 0.5 * pin.diameter), (x[4], +1, (0, 0), 0.5 * throw.journals[1].diameter)]
    rng = np.random.default_rng(0)
    xyz = rng.uniform([0.0, -0.08, -0.08], [x[-1] + throw.journals[1].length, 0.12, 0.08], size=(2_000_000, 3))
    for (centre, extent, radius), (xf, side, c, a) in zip(zones, described):
        ours, theirs = found_zone(xyz, centre, extent, radius), fillet_zone(xyz, xf, side, c, a, r)
        assert theirs.sum() > 300 and np.count_nonzero(ours != theirs) <= 2
    undercut = fetorsion.load(with_solid(tmp_path, oval.name))
    (centre, (x0, x1, r0, r1), radius), *_ = found_zones(undercut, 0, throw_of(undercut, 0))
    profile = undercut_profile(*UNDERCUT)
    c1, h = profile[0][0], profile[6][1]  # where the undercut leaves the journal; its lip's height
    assert radius == pytest.approx(UNDERCUT[0] * 1e-3, rel=1e-9)
    assert (x0, x1) == pytest.approx((x[1], x[1] + (c1 + UNDERCUT[0]) * 1e-3), abs=1e-9)
    assert (r0, r1) == pytest.approx((0.5 * j1.diameter, 0.5 * j1.diameter + h * 1e-3), abs=1e-9)


@pytest.mark.slow
@pytest.mark.fe
def test_a_crank_whose_webs_are_not_the_built_outline_runs_end_to_end(built_chain_gap, tmp_path):
    """The Renault with a lightening hole through each web's counterweight, as STEP: its mass is
    the built one less the holes' (π r² t ρ each, 1e-6: OCC's integration); fetorsion run's FE
    and bearings steps run on it; and its 17-DOF chain with `fe` web stiffness (throw FE on its
    own slabs, inertias from its own solid) sits as far from its FE f1 in bearings as the built
    crank's does, within one percentage point (the issue's bound). The issue's convergence bound
    (f1 at 20 and 14 mm within 0.5 %) is held on the oval-webbed crank below, whose undercuts
    and chamfers make it the harder mesh of the two (a second 14 mm modal here cost 50 s)."""
    from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run
    from fetorsion.solid.geometry import crank_mass_properties

    built = fetorsion.load(RENAULT)
    holes = lightened_step(built, tmp_path / "lightened.step")
    src = with_solid(tmp_path, "lightened.step")
    lightened = fetorsion.load(src)
    removed = crank_mass_properties(built)[0].mass - crank_mass_properties(lightened)[0].mass
    assert removed == pytest.approx(holes * 1e-9 * built.material.density, rel=1e-6)
    steps = tuple(s for s in DEFAULT_STEPS if s[1] in ("fe", "bearings"))
    outcome = run(src, tmp_path / "lightened", steps=steps, options=RunOptions(mesh_size=0.02, html=False))
    assert "lightened.step" in (tmp_path / "lightened" / "report.md").read_text()
    assert abs(outcome.bearings.chain["fe"]["vs_bearings"] - built_chain_gap) < 0.01


def test_a_designed_cad_crank_still_finds_its_solid(written, tmp_path):
    """The designed description of a [solid] crank is written elsewhere: its step path is made
    absolute, so the written file loads with the same solid (a damper-only design)."""
    from fetorsion.description.model import Damper
    from fetorsion.design.search import Candidate, designed_text

    (tmp_path / written.name).write_bytes(written.read_bytes())
    src = tmp_path / "crank.toml"
    src.write_text(RENAULT.read_text() + f'\n[solid]\nstep = "{written.name}"\n\n[design]\ndamper = "rubber"\n'
                   'damper_inertia_ratio = [0.02, 0.3]\ndamper_ring_radius = 60.0\n')
    crank = fetorsion.load(src)
    best = Candidate({}, 0.1, Damper("rubber", "front", 0.0, 0.002, 5e4, 0.0, 0.2), 0.0, 0.0, 1.5, "", 0.0)
    (tmp_path / "elsewhere").mkdir()
    out = tmp_path / "elsewhere" / "designed.toml"
    out.write_text(designed_text(src.read_text(), crank, best))
    back = fetorsion.load(out)
    assert back.solid_step == crank.solid_step and len(back.dampers) == 1


@pytest.mark.slow  # 20-25 s: a design search on a CAD crank's solids
def test_a_cad_cranks_design_objectives_are_its_solids(written, tmp_path):
    """A [solid] crank's mass and rotating inertia in the design search are its solid's
    (OpenCASCADE, fillets and drillings in) plus the attachments', as its lumped chain's are."""
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.search import INERTIA_RATIO, ExplorerModel
    from fetorsion.solid.geometry import crank_mass_properties

    (tmp_path / written.name).write_bytes(written.read_bytes())
    src = tmp_path / "crank.toml"
    src.write_text(RENAULT.read_text() + f'\n[solid]\nstep = "{written.name}"\n\n[design]\nobjective = "inertia"\n'
                   'damper = "rubber"\ndamper_inertia_ratio = [0.02, 0.3]\ndamper_ring_radius = 60.0\n')
    crank = fetorsion.load(src)
    out = ExplorerModel(crank, verdict_scfs(crank))({INERTIA_RATIO: 0.1})
    total, _ = crank_mass_properties(crank)
    attached = sum(a.polar_inertia * (len(crank.pins) if a.at == "pins" else 1) for a in crank.attachments)
    assert out["objective"] == pytest.approx(total.polar_inertia + attached + out["ring_inertia_kgm2"], rel=1e-9)
    assert out["mass_kg"] == pytest.approx(total.mass + out["ring_inertia_kgm2"] / 0.06**2, rel=1e-12)


@pytest.mark.slow
@pytest.mark.fe
def test_an_oval_webbed_undercut_crank_runs_end_to_end(oval, built_chain_gap, tmp_path):
    """The oval-webbed, chamfered, lightened crank with an undercut of three tori at every end
    (issue 44's test crank) through every step of `fetorsion run` at 20 mm but the background
    studies (they vary the described dimensions, whose variants are built, not cut from the
    solid: nothing of the CAD path is in them; 440 s without them, quiet, 2 cores): its report and
    results.json list the 16 fillets (3 faces, 2 mm, flagged against the described 2.5 mm) and the
    fatigue verdict; its FE f1 at 20 and 14 mm agree within 0.5 % (the issue's convergence bound);
    its 17-DOF chain with `fe` web stiffness sits as far from its FE f1 in bearings as the built
    Renault's does, within one percentage point (the issue's bound; measured 0.86 pp: -2.73 %
    against -3.59 %)."""
    import json

    from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run
    from fetorsion.fe.crankfe import run_modal

    (tmp_path / oval.name).write_bytes(oval.read_bytes())
    src = with_solid(tmp_path, oval.name)
    options = RunOptions(mesh_size=0.02, html=False)
    out = run(src, tmp_path / "oval", steps=tuple(s for s in DEFAULT_STEPS if s[1] != "sensitivity"), options=options)
    results = json.loads((tmp_path / "oval" / "results.json").read_text())
    assert [f["faces"] for f in results["solid"]["fillets"]] == [3] * 16
    assert all(f["radius"] == pytest.approx(2e-3, rel=1e-9) and f["differs"] for f in results["solid"]["fillets"])
    assert results["fatigue"]["lines"]
    report = (tmp_path / "oval" / "report.md").read_text()
    assert "oval.step" in report and "| journal_1/web_1 | 81.71 | 2.00 | 3 | 2.50 (differs) |" in report
    coarse = out.fe.modal.first_torsional()
    fine = run_modal(fetorsion.load(src), 0.014, modes=8).first_torsional()
    assert fine == pytest.approx(coarse, rel=5e-3)
    assert abs(out.bearings.chain["fe"]["vs_bearings"] - built_chain_gap) < 0.01



@pytest.mark.slow
@pytest.mark.fe
@pytest.mark.parametrize("throw", [0, 1])
def test_the_round_trip_has_the_same_fillet_scfs(tmp_path, throw):
    """The fillet SCFs of the Renault's throw (the run's default stress mesh) built from its
    dimensions and cut from its STEP written and read back: the same body meshed from imported
    faces, so they agree to the spread the SCF convergence study shows between its two finest
    levels, 2.5 % (docs/fillet-stress.md; measured here 0.0-2.0 %). Drillings are left out: the
    built throw drills its half journals at their own centres, the STEP's slab at the journal's
    (test_a_cad_cranks_throw_is_its_solids_slab). Throw 2 (pin at 180°) exercises the turn."""
    from fetorsion.design.scf import DEFAULT_FILLET_SHARE, _larger_of_each, throw_scfs
    from fetorsion.solid.geometry import write_step
    from fetorsion.solid.mesh import default_fillet_size
    from fetorsion.webs.throwfe import default_mesh_size, throw_of

    text = RENAULT.read_text().replace("diameter = 5.0  # [N] typical automotive drilling", "diameter = 0.0")
    text = text.replace('"oil_holes.diameter" = [4.0, 7.0]', "")
    (tmp_path / "plain.toml").write_text(text)
    built = fetorsion.load(tmp_path / "plain.toml")
    write_step(built, tmp_path / "plain.step")
    (tmp_path / "plain_step.toml").write_text(text + '\n[solid]\nstep = "plain.step"\n')
    read = fetorsion.load(tmp_path / "plain_step.toml")
    t = throw_of(built, throw)
    size = default_mesh_size(t)
    fine = DEFAULT_FILLET_SHARE * default_fillet_size(t, size, "stress")
    b, s = (_larger_of_each(throw_scfs(c, throw, mesh_size=size, fillet_size=fine)[0]) for c in (built, read))
    assert set(b) == set(s) and len(b) == 6
    for key in b:
        assert s[key] == pytest.approx(b[key], rel=0.025), key


def _moved(written: Path, path: Path, turn: float, axis_to, shift) -> Path:
    """``written`` turned about x by ``turn`` (its own angular origin), its axis then turned onto
    ``axis_to`` by a quarter turn about y, and shifted by ``shift`` (mm): a CAD model's placement."""
    from fetorsion.solid.geometry import gmsh_session
    from fetorsion.solid.stepimport import quiet_stdout as _quiet_stdout

    with gmsh_session("move"):
        gmsh.option.setString("Geometry.OCCTargetUnit", "MM")
        with _quiet_stdout():
            gmsh.model.occ.importShapes(str(written))
        gmsh.model.occ.synchronize()
        v = gmsh.model.getEntities(3)
        gmsh.model.occ.rotate(v, 0, 0, 0, 1, 0, 0, turn)
        gmsh.model.occ.rotate(v, 0, 0, 0, 0, 1, 0, axis_to)
        gmsh.model.occ.translate(v, *shift)
        gmsh.model.occ.synchronize()
        with _quiet_stdout():
            gmsh.write(str(path))
    return path


def test_a_step_placed_elsewhere_is_read_where_its_axis_and_front_are(written, tmp_path):
    """The Renault's STEP turned 0.7 rad about its axis, its axis turned onto -z and moved by
    (10, -20, 30) mm, read with `[solid] axis = [0, 0, -1]` and `front_centre = [10, -20, 30]`:
    the same solid as the unmoved one — mass and polar inertia (OCC's integrals, 1e-9), every
    journal and pin found at its described diameter and angle. A zero axis is refused by name."""
    from fetorsion.solid.geometry import crank_mass_properties, solid_features

    _moved(written, tmp_path / "moved.step", 0.7, math.pi / 2, (10.0, -20.0, 30.0))
    (tmp_path / "m.toml").write_text(RENAULT.read_text() + '\n[solid]\nstep = "moved.step"\naxis = [0, 0, -1]\n'
                                     "front_centre = [10.0, -20.0, 30.0]\n")
    moved, plain = fetorsion.load(tmp_path / "m.toml"), fetorsion.load(with_solid(tmp_path, str(written)))
    assert moved.solid_placement == ((0.0, 0.0, -1.0), (0.01, -0.02, 0.03))
    (a, _), (b, _) = crank_mass_properties(moved), crank_mass_properties(plain)
    assert a.mass == pytest.approx(b.mass, rel=1e-9) and a.polar_inertia == pytest.approx(b.polar_inertia, rel=1e-9)
    fm, fp = solid_features(moved), solid_features(plain)
    for x, y in zip(fm.journals + fm.pins, fp.journals + fp.pins):
        assert x.diameter == pytest.approx(y.diameter, rel=1e-9)
        assert math.cos(x.angle - y.angle) == pytest.approx(1.0, abs=1e-12)
    (tmp_path / "z.toml").write_text(RENAULT.read_text() + '\n[solid]\nstep = "moved.step"\naxis = [0, 0, 0]\n')
    with pytest.raises(DescriptionError, match=r"solid.axis = \[0, 0, 0\]: must be \[x, y, z\], a direction"):
        fetorsion.load(tmp_path / "z.toml")


@pytest.mark.slow
@pytest.mark.fe
def test_a_placed_steps_throw_is_cut_and_turned_as_the_unmoved_one(written, tmp_path):
    """Throw 2 (pin at 180°) of the moved Renault STEP (previous test), its slab turned by the pin
    found on it, has the unmoved one's torsional stiffness to 1e-3: the same body meshed from
    faces placed differently, as the built and read-back throws (test_a_cad_cranks_throw_is_its_solids_slab)."""
    from fetorsion.webs import throwfe

    _moved(written, tmp_path / "moved.step", 0.7, math.pi / 2, (10.0, -20.0, 30.0))
    (tmp_path / "m.toml").write_text(RENAULT.read_text() + '\n[solid]\nstep = "moved.step"\naxis = [0, 0, -1]\n'
                                     "front_centre = [10.0, -20.0, 30.0]\n")
    moved, plain = fetorsion.load(tmp_path / "m.toml"), fetorsion.load(with_solid(tmp_path, str(written)))
    k = [throwfe.torsional_stiffness_fe(throwfe.throw_of(c, 1), 0.02, 0.003).stiffness for c in (moved, plain)]
    assert k[0] == pytest.approx(k[1], rel=1e-3)


@pytest.mark.parametrize("ratio, drawn, header", [(1 / 25.4, "in", "mm"), (25.4, "mm", "in"), (1e-3, "m", "mm"),
                                                  (10.0, "mm", "cm")])
def test_a_unit_slip_is_named_the_way_round_it_happened(ratio, drawn, header):
    """Issue 56: a crank drawn in inches whose header says mm reads 1/25.4 of its size; the message
    says "drawn in in while its header says mm" (it said "mm read as in"). A solid off by no unit
    gets no such sentence."""
    from fetorsion.solid.recognise import unit_slip

    assert unit_slip(ratio * 1.01).startswith(f"its unit looks wrong: drawn in {drawn} while its header says {header}")
    assert unit_slip(1.3) == ""
