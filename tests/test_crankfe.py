"""FE modal analysis of whole cranks: attachments, journals, torsional modes, refinement."""

import json
import re
import subprocess
import sys

import numpy as np
import pytest

import fetorsion
from fetorsion.fe.crankfe import extrapolate_refinement, run_modal
from fetorsion.solid.mesh import mesh_crank, read_mesh, write_mesh

from conftest import GEOMETRY, ROOT, plain

pytestmark = [pytest.mark.fe]


@pytest.fixture(scope="module")
def renault_fe():
    return run_modal(plain("renault21.toml"), mesh_size=0.025, modes=8)


def test_attachments_carry_the_described_inertia(renault_fe):
    # the master-level masses turn about the crank axis with the described polar inertias: a
    # unit rotation θx of every master moves each master point on a circle (pins at R)
    crank, sys_ = renault_fe.crank, renault_fe.system
    q = np.zeros(6 * len(sys_.labels))
    for k, p in enumerate(sys_.positions):
        q[6 * k + 3] = 1.0
        q[6 * k:6 * k + 3] = np.cross([1.0, 0.0, 0.0], p)
    about_axis = q @ sys_.attachment_mass @ q
    described = sum(a.polar_inertia * (crank.engine.cylinders if a.at == "pins" else 1) for a in crank.attachments)
    assert about_axis == pytest.approx(described, rel=1e-12)


def test_free_free_fe_and_condensed_crank_agree(renault_fe):
    # one attachment model and one system: the condensed crank's free-free modes are a Ritz
    # approximation of the same full model (first 10 within 1e-8, docs/condensed-crank.md); the
    # 1e-6 bound leaves the Lanczos tolerance room
    from fetorsion.fe.condensed import run_condensed

    cc = run_condensed(renault_fe.crank, system=renault_fe.system)
    np.testing.assert_allclose(cc.modes("free", 8).frequencies_hz, renault_fe.frequencies_hz[:8], rtol=1e-6)


def test_crank_fe_has_six_rigid_modes_and_a_torsional_mode_near_the_lumped_one(renault_fe):
    res = renault_fe
    f1 = res.first_torsional()
    assert len(res.rigid_body_hz) == 6 and res.rigid_body_hz.max() < 1e-3 * res.frequencies_hz[0]
    lumped = fetorsion.lumped(renault_fe.crank, 17).frequencies_hz[0]
    # Two models that differ only in the web term (empirical in the lumped one): the paper's own
    # lumped and FE first modes differ by 3.6 % (535 vs 555 Hz); allow 5 %.
    assert f1 == pytest.approx(lumped, rel=0.05)


def test_fe_pin_twist_follows_the_lumped_mode_shape(renault_fe):
    tm = renault_fe.torsional_modes(1)
    fe = tm.pin_amplitudes[0] / tm.pulley_amplitude[0]
    from fetorsion.excitation.campbell import lumped_modes
    lm = lumped_modes(renault_fe.crank, 17)
    lumped = lm.pin_amplitudes[0] / lm.pulley_amplitude[0]
    # Same shape, one node near the flywheel; the models differ by a few % in stiffness.
    assert np.abs(fe - lumped).max() < 0.1
    assert np.all(np.diff(fe) < 0)


def test_refinement_extrapolation_is_exact_for_a_power_law():
    h = np.array([10.0, 8.0, 6.4])
    out = extrapolate_refinement(h, 500.0 + 0.3 * h**2)
    assert out["extrapolated"] == pytest.approx(500.0, rel=1e-12) and out["order"] == pytest.approx(2.0)
    noisy = extrapolate_refinement(h, [500.0, 501.0, 499.5])
    assert noisy["order"] is None and noisy["error_estimate"] == pytest.approx(1.5)


def test_mesh_file_round_trip(tmp_path):
    crank = plain("peugeot_glx.toml")
    cm = mesh_crank(crank, 0.03)
    write_mesh(cm, tmp_path / "g.msh")
    back = read_mesh(tmp_path / "g.msh", crank)
    assert np.array_equal(back.tets, cm.tets) and np.array_equal(back.part, cm.part)
    assert back.part_names == cm.part_names
    for k in ("front_face", "rear_face"):
        assert np.array_equal(np.sort(back.node_sets[k]), np.sort(cm.node_sets[k]))


def test_modal_cli_json(tmp_path):
    text = (GEOMETRY / "peugeot_glx.toml").read_text()
    text = re.sub(r"^\[uncertainty\].*", "", text, flags=re.M | re.S)  # the last table
    text = re.sub(r"^(journal|pin|diameter) = (2\.5|5\.0)", r"\1 = 0.0", text, flags=re.M)
    src = tmp_path / "glx.toml"
    src.write_text(text)
    p = subprocess.run([sys.executable, "-m", "fetorsion.cli", "modal", str(src), "--mesh-size", "25", "--modes", "6",
                        "--json", "-"], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    data = json.loads(p.stdout)
    assert {"modes", "rigid_body_hz", "mesh", "material", "timings_s"} <= set(data)
    assert {"frequency_hz", "kind", "torsional_fraction", "bending_fraction", "axial_fraction"} <= set(data["modes"][0])
    assert data["first_torsional_hz"] in [m["frequency_hz"] for m in data["modes"] if m["kind"] == "torsional"]
    assert data["material"]["E"] == 210e9 and data["mesh"]["dofs"] > 1000


def test_block_solver_eigenpairs_equal_the_arpack_reference():
    from fetorsion.fe import assembly, eigen
    from fetorsion.fe.modal import default_shift
    from fetorsion.fe.tetmesh import TetMesh

    crank = plain("peugeot_glx.toml")
    cm = mesh_crank(crank, 0.03)
    tm = TetMesh(cm.nodes, cm.tets)
    m, _ = assembly.skfem_mesh(tm)
    basis = assembly.p2_basis(m)
    K = assembly.stiffness(basis, crank.material.youngs_modulus, crank.material.poisson_ratio)
    M = assembly.mass(basis, crank.material.density)
    sigma = default_shift(tm, crank.material)
    ref = eigen.lowest_modes(K, M, 20, sigma, method="lanczos")
    blk = eigen.lowest_modes(K, M, 20, sigma, method="block")
    # Both stop at a relative residual of 1e-10 on S⁻¹M: eigenvalues agree to ~1e-18 of the
    # largest θ, i.e. 1e-8 is round-off for the elastic ω² (≥ 1e7 rad²/s² here).
    np.testing.assert_allclose(blk.omega2[6:], ref.omega2[6:], rtol=1e-8)
    # Vectors: error ≤ residual / relative gap (≥ 1e-2 between these modes), so both bases span
    # the same modes to 1e-8: |x_refᵀ M x_blk| = 1 per elastic mode, and the six rigid-body
    # modes (one eigenvalue, any basis) span the same space (singular values of the overlap 1).
    overlap = ref.vectors.T @ (M @ blk.vectors)
    gaps = np.diff(ref.omega2[6:]) / ref.omega2[7:]
    assert gaps.min() > 1e-3
    np.testing.assert_allclose(np.abs(np.diag(overlap)[6:]), 1.0, atol=1e-8)
    np.testing.assert_allclose(np.linalg.svd(overlap[:6, :6], compute_uv=False), 1.0, atol=1e-8)
    np.testing.assert_allclose(blk.vectors.T @ (M @ blk.vectors), np.eye(20), atol=1e-10)


def test_straightening_untangles_folded_fillet_elements():
    from fetorsion.solid.geometry import build_solid, gmsh_session
    from fetorsion.solid.mesh import jacobian_positive, mesh_model

    crank = fetorsion.load(GEOMETRY / "peugeot_glx.toml")
    with gmsh_session():
        solid = build_solid(crank)
        cm = mesh_model({p.name: list(p.volumes) for p in solid.parts}, {}, 25.0, 5.0,
                        list(solid.fillet_faces) + list(solid.hole_faces), untangle="straighten")
    # 5 mm elements on 2.5 mm fillets fold where a fillet meets its web (hundreds of them):
    # straightened, every element is valid again.
    assert cm.quality.straightened > 0
    assert jacobian_positive(cm.nodes, cm.tets).all()


def test_jacobian_check_sees_a_folded_element():
    from fetorsion.solid.tet10 import TET10_EDGES, jacobian_positive

    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    nodes = np.vstack([vertices, vertices[TET10_EDGES].mean(axis=1)])
    straight = np.arange(10)[None]
    assert jacobian_positive(nodes, straight).all()
    folded = nodes.copy()
    folded[4] = [0.5, 0.0, 1.2]  # the 0-1 midside node pushed through the opposite face
    assert not jacobian_positive(folded, straight).any()


# The default modal mesh against a finer one: tests/test_validation.py, beside the other test of
# the reference cranks at the default mesh (one FE of each for both).
