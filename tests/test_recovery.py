"""Stress recovery at the fillets and oil bores, and Findley with the sign of the mean."""

import math

import numpy as np
import pytest
from conftest import plain

from fetorsion.design.criterion import findley_constants, findley_surface, signed_von_mises, von_mises_amplitude


def _principal(s):
    """Largest principal stress of plane stresses (..., 3)."""
    c = 0.5 * (s[..., 0] + s[..., 1])
    return c + np.sqrt(0.25 * (s[..., 0] - s[..., 1]) ** 2 + s[..., 2] ** 2)


def test_a_compressive_mean_never_lowers_the_safety():
    """Property over random histories: adding a compressive static plane stress (negative
    semi-definite) to a node's history never lowers Findley's safety, and a tensile one never
    raises it (the mean enters through σ_n,max with its sign)."""
    rng = np.random.default_rng(52)
    k, lam = findley_constants(400e6, 400e6 / math.sqrt(3))
    for _ in range(200):
        static = rng.normal(0, 80e6, 3)
        vib = rng.normal(0, 60e6, (3, 1)) * np.sin(np.linspace(0, 2 * np.pi, 90))[None] \
            + rng.normal(0, 30e6, (3, 1)) * np.cos(np.linspace(0, 6 * np.pi, 90))[None]
        a = rng.normal(size=(2, 2))
        neg = -(a @ a.T) * rng.uniform(1e6, 2e8)  # negative semi-definite
        extra = np.array([neg[0, 0], neg[1, 1], neg[0, 1]])
        base = findley_surface(static, vib, k, lam)["safety"]
        assert findley_surface(static + extra, vib, k, lam)["safety"] >= base * (1 - 1e-12)
        assert findley_surface(static - extra, vib, k, lam)["safety"] <= base * (1 + 1e-12)


def test_findley_reduces_to_the_fatigue_limits():
    """Reversed uniaxial stress at f₋₁ and reversed shear at t₋₁ are each exactly at the limit
    (safety 1, to the 5° plane grid), whatever the static part is not (here none)."""
    f, t = 420e6, 420e6 / math.sqrt(3)
    k, lam = findley_constants(f, t)
    w = np.sin(np.linspace(0, 2 * np.pi, 361))
    bend = findley_surface(np.zeros(3), np.array([f * w, 0 * w, 0 * w]), k, lam)["safety"]
    shear = findley_surface(np.zeros(3), np.array([0 * w, 0 * w, t * w]), k, lam)["safety"]
    assert bend == pytest.approx(1.0, abs=2e-3)  # the grid's 1 − cos(2.5°)
    assert shear == pytest.approx(1.0, abs=2e-3)
    # a tensile static part lowers it by the plane's k σ_n0: analytic on the critical plane
    assert findley_surface(np.array([100e6, 0, 0]), np.array([f * w, 0 * w, 0 * w]), k, lam)["safety"] < bend


def test_findley_pass_equals_each_plane_by_hand():
    """The compiled one-pass Findley against the module docstring's formulas evaluated plane by
    plane with numpy (σ_n, τ on each plane, τ_a as half the range, s_p = (λ − k σ_n,0) / (τ_a +
    k max σ_n,v), the least over the planes) on random histories of several leading shapes,
    including nodes statically over the limit: equal to round-off (1e-12; the sums differ only in
    their order)."""
    rng = np.random.default_rng(55)
    theta = np.arange(36) * math.pi / 36
    for shape, lam in (((4,), 3e8), ((3, 5), 3e8), ((6,), 2e7)):
        static = rng.normal(0, 1e8, shape + (3,))
        vib = rng.normal(0, 5e7, shape + (3, 97))
        got = findley_surface(static, vib, 0.3, lam)
        for idx in np.ndindex(*shape):
            s_p, d_p = [], []
            for th in theta:
                c, s = math.cos(th), math.sin(th)
                n = np.array([c * c, s * s, 2 * s * c])
                t = np.array([-s * c, s * c, c * c - s * s])
                sn0, snv, tv = n @ static[idx], n @ vib[idx], t @ vib[idx]
                ta = 0.5 * (tv.max() - tv.min())
                room, grow = lam - 0.3 * sn0, ta + 0.3 * snv.max()
                s_p.append(0.0 if room <= 0 else room / grow)
                d_p.append(ta + 0.3 * (sn0 + snv.max()))
            assert got["safety"][idx] == pytest.approx(min(s_p), rel=1e-12, abs=1e-300)
            assert got["plane"][idx] == pytest.approx(theta[int(np.argmin(s_p))], rel=1e-12)
            assert got["value"][idx] == pytest.approx(max(d_p), rel=1e-12)


def test_von_mises_amplitude_and_signed_mean():
    """A proportional history's von Mises amplitude is the von Mises stress of its amplitude; a
    compressive mean reads negative."""
    w = np.cos(np.linspace(0, 2 * np.pi, 73))
    h = np.array([100e6 * w, 20e6 * w, 30e6 * w])
    assert von_mises_amplitude(h) == pytest.approx(math.sqrt(100**2 + 20**2 - 100 * 20 + 3 * 30**2) * 1e6, rel=1e-9)
    assert signed_von_mises(np.array([-100e6, 0, 0])) == pytest.approx(-100e6)


def test_cut_load_moves_to_the_rear_face_by_statics():
    """load_map: a cut resultant (F, M about c) becomes the rear load (F, M + (c − p) × F); a
    torque alone passes unchanged and a shear force at the face itself adds no moment."""
    from fetorsion.design.recovery import load_map

    A = load_map(np.eye(3), np.array([0.01, 0.0, 0.0]), np.array([0.05, 0.0, 0.0]))
    F = np.array([0.0, 1000.0, 0.0])
    out = A @ np.r_[F, 0, 0, 0]
    assert out[:3] == pytest.approx(F)
    assert out[3:] == pytest.approx(np.cross([-0.04, 0, 0], F))
    assert (A @ np.r_[0, 0, 0, 5.0, 0, 0])[3] == pytest.approx(5.0)


@pytest.mark.fe
def test_oil_bore_under_in_phase_bending_and_torsion_gives_the_plate_with_hole_peak():
    """A drilling's edge under in-phase bending s and torsion t: the recovered peak principal
    stress (the two unit fields superposed, the peak wherever it falls on the wall) equals the
    plate-with-a-hole combination of the same bar's own pure-case peaks γ_B s and γ_T t
    ((γ_B s/3)[1 + 2√(1 + (9/4)(γ_T t/(γ_B s))²)], Kirsch's 3σ₁ − σ₂ in the rule's SCF convention)
    within 2 %; the former path's sum γ_B s + γ_T t (issue 52: 283.5 against 226 MPa) is far above.

    The run's own bar (fine only near the drilling's exits, :func:`fetorsion.design.oilbore.exit_graded_expression`)
    gives the pure-case peaks of the shipped full-wall study of the same section (fine over the
    whole wall at d/24, 558 720 DOF, another mesh) within 2 %, the size of that study's own d/16 →
    d/24 change (up to 1.2 %) with room for the other mesh."""
    import json

    from fetorsion.description.model import Material
    from fetorsion.design.oilbore import SHIPPED_OIL_BORE, oil_bore_key
    from fetorsion.design.recovery import bore_zone
    from fetorsion.design.scf import nominal_bending, nominal_shear

    D, d = 0.048, 0.005
    zone = bore_zone(D, d, 0.0, Material(210e9, 0.3, 7850.0, "steel"))
    s_unit, t_unit = float(nominal_bending(1.0, D)), float(nominal_shear(1.0, D))
    gb = _principal(zone.influence[:, :, 5]).max() / s_unit
    gt = _principal(zone.influence[:, :, 3]).max() / t_unit
    shipped = json.loads(SHIPPED_OIL_BORE.read_text())[oil_bore_key(D, d, 0.0, 0.3)]
    assert gb == pytest.approx(shipped["bending"], rel=0.02)
    assert gt == pytest.approx(shipped["torsion"], rel=0.02)
    for ratio in (0.5, 1.0, 2.0):  # t / s
        s, t = 100e6, ratio * 100e6
        local = zone.influence[:, :, 5] * (s / s_unit) + zone.influence[:, :, 3] * (t / t_unit)
        peak = _principal(local).max()
        sb, st = gb * s, gt * t
        closed = sb / 3 * (1 + 2 * math.sqrt(1 + 2.25 * (st / sb) ** 2))
        assert peak == pytest.approx(closed, rel=0.02), (ratio, peak / closed)
        assert sb + st > 1.1 * peak


@pytest.mark.slow
def test_fillets_under_a_pure_shear_end_force_match_the_directly_solved_throw():
    """A throw loaded by a pure shear force at its front face (rear face held: another
    factorisation and the other end held) against the recovery (the unit fields of the throw held
    at the front, loaded at the rear, driven by the fillet cut's resultant from statics): the peak
    largest principal stress of each pin and journal fillet within 10 % (the ends' rigid ties
    are half a journal from the journal fillets). The pure-couple SCF times the cut's in-plane
    moment (the former path) is printed beside it: it misses the shear."""
    from fetorsion.design.recovery import UNIT_LOADS, dof_normals, load_map, node_stresses, zone_of
    from fetorsion.design.scf import fillet_zone
    from fetorsion.fe.tetmesh import TetMesh
    from fetorsion.solid.mesh import mesh_crank
    from fetorsion.webs.throwfe import default_mesh_size, end_load_solutions, throw_of

    crank = plain("renault21.toml")
    throw = throw_of(crank, 0)
    size = default_mesh_size(throw)
    cm = mesh_crank(throw, size, crank.fillets.pin, "stress")
    mesh = TetMesh(cm.nodes, cm.tets, cm.node_sets)
    unit = end_load_solutions(mesh, throw.material, UNIT_LOADS)
    F = 1.0e4
    direct = end_load_solutions(mesh, throw.material, [(0.0, F, 0.0, 0.0, 0.0, 0.0)], fixed="rear_face",
                                loaded="front_face")
    xyz = unit[0].skfem_mesh.doflocs.T
    normals = dof_normals(mesh, unit[0].dof_of_node, len(xyz))
    j1, j2 = throw.journals
    w1, w2 = throw.webs
    pin = throw.pins[0]
    R = throw.engine.crank_radius
    x = np.cumsum([0.0, j1.length, w1.thickness, pin.length, w2.thickness])
    front, rear = (np.array([xyz[unit[0].dof_of_node[mesh.node_sets[f]], 0].mean(), 0, 0])
                   for f in ("front_face", "rear_face"))
    cases = [("journal fillet", fillet_zone(xyz, x[1], -1, (0, 0), 0.5 * j1.diameter, crank.fillets.journal), x[1], (0, 0)),
             ("pin fillet", fillet_zone(xyz, x[2], +1, (R, 0), 0.5 * pin.diameter, crank.fillets.pin), x[2], (R, 0))]
    results = {}
    for name, mask, xc, axis in cases:
        zone = zone_of(name, "fillet", unit, throw.material, mask, normals, rear)
        dofs = np.flatnonzero(mask & (np.linalg.norm(normals, axis=1) > 0.5))
        sig = node_stresses(direct[0], throw.material, dofs)
        e1, e2 = zone.frames[:, 0], zone.frames[:, 1]
        plane = np.stack([np.einsum("ni,nij,nj->n", a, sig, b) for a, b in ((e1, e1), (e2, e2), (e1, e2))], axis=1)
        c = np.array([xc, axis[0], axis[1]])
        # the front-loaded throw's left part: the right part exerts −(front load) moved to c
        Ff = np.array([0.0, F, 0.0])
        cut = np.r_[-Ff, -np.cross(front - c, Ff)]
        rec = np.einsum("nck,k->nc", zone.influence, load_map(np.eye(3), c, zone.loaded) @ cut)
        peak_rec, peak_direct = _principal(rec).max(), _principal(plane).max()
        print(name, peak_rec / 1e6, peak_direct / 1e6, "MPa; cut moment", cut[3:])
        results[name] = (peak_rec, peak_direct)
    for name, (peak_rec, peak_direct) in results.items():
        assert peak_rec == pytest.approx(peak_direct, rel=0.10), (name, results)


@pytest.mark.slow
def test_a_rod_force_on_the_pin_is_recovered_at_the_fillets_it_loads():
    """Saint-Venant, the recovery's assumption: a throw held at its front face with a 10 kN rod
    force spread over the pin's top surface (the load where a rod puts it, not at an end face),
    against the recovery of each fillet cut's statics (the right part's external load) through
    the unit end loads. The peak von Mises stress of the journal fillet and the pin fillet on the
    loaded side within 10 % (the issue's bound for a shear-loaded fillet). Measured on the plain
    Renault 21 throw (fillet elements 1.25 mm): recovered / direct 80.6 / 80.9 and 86.1 / 83.9 MPa
    (with its pin drilling: 99.1 / 99.6 and 124.0 / 120.0). The pin fillet on the other side
    carries no section load and reads 5.9 MPa in the direct FE (22.7 with the drilling): the rod's
    pressure next to it, a local effect no end load carries, printed here, stated in docs/fatigue.md."""
    from fetorsion.design.recovery import UNIT_LOADS, dof_normals, load_map, node_stresses, zone_of
    from fetorsion.design.criterion import von_mises_plane
    from fetorsion.design.scf import fillet_zone
    from fetorsion.fe import assembly
    from fetorsion.fe.eigen import factorize
    from fetorsion.fe.rigid import RigidBody, reduction
    from fetorsion.fe.tetmesh import TetMesh
    from fetorsion.solid.mesh import mesh_crank
    from fetorsion.webs.throwfe import TorsionSolution, default_mesh_size, end_load_solutions, throw_of

    crank = plain("renault21.toml")
    throw = throw_of(crank, 0)
    cm = mesh_crank(throw, default_mesh_size(throw), 0.5 * crank.fillets.pin, "stress")
    mesh = TetMesh(cm.nodes, cm.tets, cm.node_sets)
    unit = end_load_solutions(mesh, throw.material, UNIT_LOADS)
    dof_of_node, xyz = unit[0].dof_of_node, unit[0].skfem_mesh.doflocs.T
    K = assembly.stiffness(unit[0].basis, throw.material.youngs_modulus, throw.material.poisson_ratio)
    bodies = []
    for face in ("front_face", "rear_face"):
        nodes = dof_of_node[mesh.node_sets[face]]
        bodies.append(RigidBody(face, nodes, 0.0, np.zeros((3, 3)), np.array([xyz[nodes, 0].mean(), 0, 0])))
    red = reduction(K.shape[0], bodies, xyz)
    Kr, n = red.reduce(K), red.n_free
    keep = np.r_[np.arange(n), np.arange(n + 6, n + 12)]  # the front body held, the rear one free
    j1, w1, pin = throw.journals[0], throw.webs[0], throw.pins[0]
    R, rp = throw.engine.crank_radius, crank.fillets.pin
    x = np.cumsum([0.0, j1.length, w1.thickness, pin.length])
    top = (np.abs(np.hypot(xyz[:, 1] - R, xyz[:, 2]) - 0.5 * pin.diameter) < 1e-2 * pin.diameter) \
        & (xyz[:, 0] > x[2] + rp + 1e-3) & (xyz[:, 0] < x[3] - rp - 1e-3) & (xyz[:, 1] > R + 0.25 * pin.diameter)
    f = np.zeros(K.shape[0])
    f[3 * np.flatnonzero(top) + 1] = -1.0e4 / top.sum()
    q = np.zeros(Kr.shape[0])
    q[keep] = np.asarray(factorize(Kr[keep][:, keep].tocsc(), "auto")((red.T.T @ f)[keep][:, None])).ravel()
    direct = TorsionSolution(unit[0].skfem_mesh, unit[0].basis, red.T @ q, 0.0, len(keep), dof_of_node)
    normals = dof_normals(mesh, dof_of_node, len(xyz))
    forces = f.reshape(-1, 3)
    peaks = {}
    for name, xc, axis, side, radius, r in (("journal fillet", x[1], (0, 0), -1, 0.5 * j1.diameter, crank.fillets.journal),
                                            ("pin fillet, loaded side", x[2], (R, 0), +1, 0.5 * pin.diameter, rp),
                                            ("pin fillet, other side", x[3], (R, 0), -1, 0.5 * pin.diameter, rp)):
        mask = fillet_zone(xyz, xc, side, axis, radius, r)
        zone = zone_of(name, "fillet", unit, throw.material, mask, normals, bodies[1].centre)
        c = np.array([xc, *axis])
        right = xyz[:, 0] > xc  # the right part's external load is what it exerts on the left
        cut = np.r_[forces[right].sum(axis=0), np.cross(xyz[right] - c, forces[right]).sum(axis=0)]
        rec = np.einsum("nck,k->nc", zone.influence, load_map(np.eye(3), c, zone.loaded) @ cut)
        sig = node_stresses(direct, throw.material, np.flatnonzero(mask & (np.linalg.norm(normals, axis=1) > 0.5)))
        e1, e2 = zone.frames[:, 0], zone.frames[:, 1]
        plane = np.stack([np.einsum("ni,nij,nj->n", a, sig, b) for a, b in ((e1, e1), (e2, e2), (e1, e2))], axis=1)
        peaks[name] = (von_mises_plane(rec).max(), von_mises_plane(plane).max())
    print({k: (a / 1e6, b / 1e6) for k, (a, b) in peaks.items()})
    for name in ("journal fillet", "pin fillet, loaded side"):
        assert peaks[name][0] == pytest.approx(peaks[name][1], rel=0.10), name


def test_stored_fields_load_back_rebuild_when_broken_and_stay_bounded(tmp_path, monkeypatch):
    """The recovered fields are kept under their key and read back as written; a broken file of
    ours is built again; past the bound the least recently used go first, the one just written
    stays; no temporary is left."""
    from fetorsion.design.recovery import StressZone, stored_zones
    from fetorsion.fe import store
    from fetorsion.io import store_max_bytes

    rng = np.random.default_rng(1)
    zone = StressZone("pin fillet, web 1", "pin-fillet", rng.normal(size=(50, 3)), rng.normal(size=(50, 2, 3)),
                      rng.normal(size=(50, 3, 6)), np.array([0.1, 0.0, 0.0]), 0.01)
    built = []

    def build():
        built.append(1)
        return [zone]

    key = "a" * 64
    first = stored_zones(key, build, tmp_path)[0]
    again = stored_zones(key, build, tmp_path)[0]
    assert len(built) == 1 and np.array_equal(again.influence, zone.influence) and again.name == zone.name
    assert again.normal_residual == zone.normal_residual and first is zone
    path = tmp_path / "recovery" / f"{key}.npz"
    path.write_bytes(b"not a zip")
    stored_zones(key, build, tmp_path)
    assert len(built) == 2
    size = path.stat().st_size
    monkeypatch.setattr(store, "BOUND_SHARE", 1.5 * size / store_max_bytes())
    stored_zones("b" * 64, build, tmp_path)
    names = sorted(p.name for p in (tmp_path / "recovery").iterdir())
    assert names == [f"{'b' * 64}.npz"]


def test_the_determinate_throws_cut_is_m53s_triangular_moment():
    """A radial force on the simply supported throw: at each web's centre the cut carries the
    shear and the moment of [KR-M53] §2.1's triangular diagram (m53.throw_loads: M_BRF = F (L3 −
    L2)/L3 · L1 at the front web, F L2/L3 · L1 at the rear), to round-off; the force's own torque
    about the axis is left to the vibration calculation."""
    from fetorsion.design.m53 import throw_loads, throw_spans
    from fetorsion.design.recovered import determinate_cut

    crank = plain("renault21.toml")
    spans = throw_spans(crank, 0)
    R, F = crank.engine.crank_radius, 1.0e4
    ref = throw_loads(spans, np.array([F]), np.array([0.0]))
    pin = np.array([spans.L2, R, 0.0])
    front = determinate_cut(np.array([0.0, F, 0.0]), pin, np.array([spans.L1[0], 0, 0]), spans.L3)
    rear = determinate_cut(np.array([0.0, F, 0.0]), pin, np.array([spans.L3 - spans.L1[1], 0, 0]), spans.L3)
    assert abs(front[5]) == pytest.approx(ref["M_BRF"][0, 0], rel=1e-12)
    assert abs(rear[5]) == pytest.approx(ref["M_BRF"][1, 0], rel=1e-12)
    assert abs(front[1]) == pytest.approx(ref["Q_RF"][0, 0], rel=1e-12)
    tangential = determinate_cut(np.array([0.0, 0.0, F]), pin, pin + [1e-9, 0, 0], spans.L3)
    assert tangential[3] == 0.0
    assert abs(tangential[4]) == pytest.approx(throw_loads(spans, np.array([0.0]), np.array([F]))["M_BTO"][0], rel=1e-6)
