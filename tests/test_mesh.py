"""The curved tet10 mesh, its writers, and the .inp in CalculiX."""

import math
import shutil
import subprocess
from pathlib import Path

import gmsh
import meshio
import numpy as np
import pytest

import fetorsion
from fetorsion.cli import main
from fetorsion.description.model import Material
from fetorsion.solid.geometry import crank_mass_properties, gmsh_session
from fetorsion.solid.mesh import inp_text, mesh_crank, mesh_model, write_mesh
from conftest import GEOMETRY, assert_picture

pytestmark = [pytest.mark.fe]

REFERENCE = [GEOMETRY / "peugeot_glx.toml", GEOMETRY / "renault21.toml"]
STEEL = Material(210e9, 0.3, 7850.0, "steel")

# Edges of a 10-node tet in VTK / CalculiX order: midside node 4 + k sits on EDGES[k].
EDGES = np.array([[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]])
# 4-point Gauss rule on the unit tet, exact for quadratics; weights 1/24.
_A, _B = 0.5854101966249685, 0.1381966011250105
GAUSS = np.array([[_B, _B, _B], [_A, _B, _B], [_B, _A, _B], [_B, _B, _A]])


def tet10_jacobians(nodes, tets, points):
    """det J of every element (rows) at each reference point (columns), VTK node order."""
    xi, eta, zeta = points.T
    lam = np.stack([1 - xi - eta - zeta, xi, eta, zeta])  # (4, P)
    dlam = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)  # d lambda_i / d(xi, eta, zeta)
    grads = [(4 * lam[i] - 1)[:, None] * dlam[i] for i in range(4)]
    grads += [4 * (lam[a][:, None] * dlam[b] + lam[b][:, None] * dlam[a]) for a, b in EDGES]
    g = np.stack(grads, axis=1)  # (P, 10, 3)
    jac = np.einsum("eji,pjk->epik", nodes[tets], g)  # (E, P, 3 coords, 3 ref)
    return np.linalg.det(jac)


@pytest.fixture(scope="module", params=REFERENCE, ids=lambda p: p.stem)
def reference_mesh(request):
    crank = fetorsion.load(request.param)
    return crank, mesh_crank(crank, size=0.02)


def test_reference_mesh_is_valid_and_fills_the_solid(reference_mesh):
    crank, mesh = reference_mesh
    assert mesh.tets.shape[1] == 10 and mesh.nodes.shape[1] == 3
    assert mesh.quality.min_sicn > 0
    corners = np.vstack([np.eye(3), np.zeros((1, 3))])
    det = tet10_jacobians(mesh.nodes, mesh.tets, np.vstack([GAUSS, corners]))
    assert det.min() > 0  # every curved element is valid, in the order we claim (VTK)
    volume = (det[:, :4] / 24).sum()
    solid = crank_mass_properties(crank)[0].mass / crank.material.density
    # Curved P2 faces follow the CAD to ~1e-4 of a fillet radius: the volumes agree closely.
    assert volume == pytest.approx(solid, rel=1e-3)
    assert set(np.unique(mesh.part)) == set(range(len(mesh.part_names)))
    assert np.allclose(mesh.nodes[mesh.node_sets["front_face"], 0], 0.0, atol=1e-12)
    length = mesh.nodes[:, 0].max()
    assert np.allclose(mesh.nodes[mesh.node_sets["rear_face"], 0], length, atol=1e-9)
    # Parts are stacked along x: web_1's elements lie between journal_1's and pin_1's.
    xc = mesh.nodes[mesh.tets[:, :4], 0].mean(axis=1)
    mid = {n: xc[mesh.part == k].mean() for k, n in enumerate(mesh.part_names)}
    assert mid["journal_1"] < mid["web_1"] < mid["pin_1"] < mid["web_2"] < mid["journal_2"]


def cylinder_mesh(size_mm=6.0, length_mm=200.0, radius_mm=20.0):
    with gmsh_session("cylinder"):
        v = gmsh.model.occ.addCylinder(0, 0, 0, length_mm, 0, 0, radius_mm)
        gmsh.model.occ.synchronize()
        ends = [t for _, t in gmsh.model.getBoundary([(3, v)], oriented=False) if gmsh.model.getType(2, t) == "Plane"]
        return mesh_model({"shaft": [v]}, {"front_face": ends[:1], "rear_face": ends[1:]}, size_mm,
                          name="cylinder", material=STEEL)


def read_inp(text):
    """Nodes and C3D10 connectivity back from our own .inp text."""
    lines = text.splitlines()
    n0 = lines.index("*NODE, NSET=NALL") + 1
    e0 = next(i for i, s in enumerate(lines) if s.startswith("*ELEMENT"))
    e1 = next(i for i in range(e0 + 1, len(lines)) if lines[i].startswith("*"))
    nodes = np.loadtxt(lines[n0:e0], delimiter=",")
    elems = np.loadtxt(lines[e0 + 1:e1], delimiter=",", dtype=np.int64)
    return lines, nodes, elems, lines[e0]


def test_inp_is_calculix_c3d10_with_short_fields():
    mesh = cylinder_mesh(size_mm=12.0)
    lines, nodes, elems, header = read_inp(inp_text(mesh))
    assert header == "*ELEMENT, TYPE=C3D10, ELSET=EALL"
    assert "C3D10MH" not in "\n".join(lines)
    fields = [f.strip() for s in lines if not s.startswith("*") for f in s.split(",")]
    assert max(len(f) for f in fields) <= 20  # CalculiX reads at most 20 characters per field
    assert np.array_equal(nodes[:, 0], np.arange(1, len(nodes) + 1))
    xyz, conn = nodes[:, 1:], elems[:, 1:] - 1
    assert np.abs(xyz - mesh.nodes).max() < 1e-12  # 13 significant digits of coordinates below 1 m
    # Right order: positive volumes, and midside node 4 + k in the middle of edge k (a swapped
    # pair would sit half an edge away; curving moves boundary nodes far less).
    assert tet10_jacobians(xyz, conn, GAUSS).min() > 0
    mid = 0.5 * (xyz[conn[:, EDGES[:, 0]]] + xyz[conn[:, EDGES[:, 1]]])
    edge = np.linalg.norm(xyz[conn[:, EDGES[:, 0]]] - xyz[conn[:, EDGES[:, 1]]], axis=2)
    assert (np.linalg.norm(xyz[conn[:, 4:]] - mid, axis=2) / edge).max() < 0.1


@pytest.mark.parametrize("ext", [".msh", ".vtu"])
def test_msh_and_vtu_read_back_the_same_tets(tmp_path, ext):
    mesh = cylinder_mesh(size_mm=12.0)
    back = meshio.read(write_mesh(mesh, tmp_path / f"shaft{ext}"))
    # meshio converts Gmsh's own tet10 order to VTK's on reading: an independent check of ours.
    assert np.array_equal(back.get_cells_type("tetra10"), mesh.tets)
    assert np.allclose(back.points, mesh.nodes)
    part = back.cell_data_dict["gmsh:physical" if ext == ".msh" else "part"]["tetra10"]
    assert np.array_equal(part - (ext == ".msh"), mesh.part)
    assert not list(tmp_path.glob(".*"))  # no temporary file left behind
    if ext == ".msh":  # and Gmsh itself opens it, with the part names
        with gmsh_session("read"):
            gmsh.open(str(tmp_path / "shaft.msh"))
            assert [gmsh.model.getPhysicalName(*g) for g in gmsh.model.getPhysicalGroups(3)] == ["shaft"]


def frd_displacements(path: Path) -> list[np.ndarray]:
    """(N, 3) displacements of every mode in a CalculiX .frd (ASCII) file."""
    lines = path.read_text().splitlines()
    starts = [i for i, s in enumerate(lines) if s.startswith(" -4  DISP")]
    modes = []
    for i in starts:  # one block per mode, a handful of modes
        end = next(j for j in range(i, len(lines)) if lines[j].strip() == "-3")
        rows = [s for s in lines[i:end] if s.startswith(" -1")]
        modes.append(np.genfromtxt(rows, delimiter=[3, 10, 12, 12, 12])[:, 2:])
    return modes


@pytest.mark.slow  # 9 s: CalculiX
@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) not installed: apt-get install calculix-ccx")
def test_cylinder_inp_gives_analytic_torsion_in_calculix(tmp_path):
    L, r = 0.2, 0.02
    mesh = cylinder_mesh(size_mm=6.0, length_mm=L * 1e3, radius_mm=r * 1e3)
    write_mesh(mesh, tmp_path / "shaft.inp", modes=12)
    run = subprocess.run(["ccx", "-i", "shaft"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-2000:]
    dat = (tmp_path / "shaft.dat").read_text().split("P A R T I C I P A T I O N")[0]
    freqs = np.array([float(s.split()[3]) for s in dat.splitlines() if s.strip()[:1].isdigit()])
    modes = frd_displacements(tmp_path / "shaft.frd")
    # The first elastic mode whose motion is circumferential is the first torsional mode.
    y, z = mesh.nodes[:, 1], mesh.nodes[:, 2]
    rr = np.hypot(y, z)
    keep = rr > 0.2 * r
    e_theta = np.column_stack([np.zeros(keep.sum()), -z[keep], y[keep]]) / rr[keep, None]
    share = [np.sum(np.einsum("ij,ij->i", u[keep], e_theta) ** 2) / np.sum(u[keep] ** 2) for u in modes]
    torsion = next(k for k in range(6, len(freqs)) if share[k] > 0.95)
    analytic = math.sqrt(STEEL.shear_modulus / STEEL.density) / (2 * L)
    # St-Venant torsion of a round bar is exact (no warping): 0.5 % is the bound,
    # measured ~3e-5 at this size.
    assert freqs[torsion] == pytest.approx(analytic, rel=5e-3)


def test_cli_mesh_writes_the_file_and_refuses_unknown_formats(tmp_path, capsys):
    out = tmp_path / "glx.vtu"
    assert main(["mesh", str(REFERENCE[0]), "-o", str(out), "--mesh-size", "30"]) == 0
    printed = capsys.readouterr().out
    assert "total" in printed and "minimum SICN" in printed
    assert meshio.read(out).get_cells_type("tetra10").shape[0] > 0
    assert main(["mesh", str(REFERENCE[0]), "-o", str(tmp_path / "glx.stl")]) == 2
    err = capsys.readouterr().err
    assert "-o" in err and "unknown output format" in err and ".stl" in err


@pytest.mark.slow  # 17-21 s: meshes and renders a crank
def test_cli_png_is_a_picture(tmp_path):
    pytest.importorskip("pyvista")
    out = tmp_path / "glx.png"
    assert main(["mesh", str(REFERENCE[0]), "--png", str(out)]) == 0
    assert_picture(out, min_ink=0.05)


@pytest.mark.slow  # 14 s: the crank meshed twice
def test_modal_mesh_is_the_same_on_every_run():
    # Reproducible: the same description gives the same mesh, node for node. The Renault at
    # 20 mm has folded fillet elements (75); Gmsh's optimiser placed their nodes differently on
    # each run (up to 0.06 mm) and aborted on half of them, the straightening does neither.
    crank = fetorsion.load(GEOMETRY / "renault21.toml")
    a, b = mesh_crank(crank, 0.020), mesh_crank(crank, 0.020)
    assert a.quality.straightened > 0
    np.testing.assert_array_equal(a.tets, b.tets)
    np.testing.assert_array_equal(a.nodes, b.nodes)


def test_an_optimiser_abort_is_meshed_again_once_with_the_stated_change(monkeypatch, capsys):
    # Gmsh's rare optimiser abort cannot be provoked at will: the first try is made to end as
    # such an abort does (SIGABRT in the meshing child); the second is the real meshing child,
    # with OPTIMISER_RETRY's options, and gives the same mesh as a plain first try would.
    from fetorsion.errors import FetorsionError
    from fetorsion.solid import mesh as mesh_module
    from conftest import plain, simple_crank_raw
    from fetorsion.description.crank import parse_crank

    crank = plain(parse_crank(simple_crank_raw(1)))
    real, calls = mesh_module.call_isolated, []

    def first_aborts(fn, *args, what, **kwargs):
        calls.append(args[-1])
        if len(calls) == 1:
            raise FetorsionError(f"{what} ended abnormally (signal SIGABRT): Failed to reach critical value")
        return real(fn, *args, what=what, **kwargs)

    monkeypatch.setattr(mesh_module, "call_isolated", first_aborts)
    retried = mesh_crank(crank, 0.03, purpose="stress")
    assert calls == [{}, mesh_module.OPTIMISER_RETRY]
    assert "meshing again with Mesh.HighOrderNumLayers 12" in capsys.readouterr().err
    monkeypatch.setattr(mesh_module, "call_isolated", real)
    assert retried.tets.shape == mesh_crank(crank, 0.03, purpose="stress").tets.shape

    # Not retried: an optimiser that did not run (modal meshes straighten), or a child killed
    # from outside (out of memory: it would only be killed again).
    for purpose, signal_name in (("modal", "SIGABRT"), ("stress", "SIGKILL")):
        calls.clear()

        def dies(fn, *args, what, **kwargs):
            calls.append(args[-1])
            raise FetorsionError(f"{what} ended abnormally (signal {signal_name})")

        monkeypatch.setattr(mesh_module, "call_isolated", dies)
        with pytest.raises(FetorsionError, match=signal_name):
            mesh_crank(crank, 0.03, purpose=purpose)
        assert calls == [{}]


@pytest.mark.slow  # 14 s: CalculiX and three modal solves
@pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) not installed: apt-get install calculix-ccx")
def test_calculix_and_fetorsion_differ_by_their_quadrature_alone(tmp_path):
    """CalculiX integrates a C3D10's stiffness and mass with one four-point rule (exact to degree 2;
    ``e_c3d.f``, ``mint3d=4`` under its default scheme [CalculiX]); fetorsion to degree 4. On the same
    exported mesh, fetorsion on CalculiX's rule meets CalculiX's elastic frequencies to the eigen-
    solvers' tolerance (1e-6: the crank of benchmarks/bench_calculix_quadrature.py measured 2.2e-7),
    closer than on its own rule: the quadrature is the whole difference between the two programs."""
    from unittest import mock

    from fetorsion.fe import assembly
    from fetorsion.fe.modal import modal
    from fetorsion.fe.tetmesh import TetMesh

    mesh = cylinder_mesh(size_mm=6.0, length_mm=200.0, radius_mm=20.0)
    write_mesh(mesh, tmp_path / "shaft.inp", modes=12)
    tets = TetMesh(mesh.nodes, mesh.tets)
    run = subprocess.run(["ccx", "-i", "shaft"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-2000:]
    dat = (tmp_path / "shaft.dat").read_text().split("P A R T I C I P A T I O N")[0]
    ccx = np.array([float(s.split()[3]) for s in dat.splitlines() if s.strip()[:1].isdigit()])[6:]
    stiffness, mass_blocks = assembly.stiffness, assembly.mass_blocks

    def frequencies(order):
        k = lambda basis, *a, **kw: stiffness(assembly.p2_basis(basis.mesh, order), *a, **kw)  # noqa: E731
        m = lambda basis, *a, **kw: mass_blocks(assembly.p2_basis(basis.mesh, order), *a, **kw)  # noqa: E731
        with mock.patch.object(assembly, "stiffness", k), mock.patch.object(assembly, "mass_blocks", m):
            return modal(tets, STEEL, modes=len(ccx), keep_shapes=False).frequencies_hz[: len(ccx)]

    theirs = np.abs(frequencies(2) / ccx - 1).max()
    ours = np.abs(frequencies(assembly.INTORDER) / ccx - 1).max()
    print(f"CalculiX's rule {theirs:.2e}, fetorsion's {ours:.2e}")
    assert theirs < 1e-6 and theirs < ours
