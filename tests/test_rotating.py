"""Rotating-frame terms of the condensed crank (fetorsion/fe/rotating.py): Coriolis and centrifugal."""

from types import SimpleNamespace

import numpy as np
import pytest
import scipy.linalg
from beams import cowper_circle
from shafts import assembled_shaft

from fetorsion.description.model import Material
from fetorsion.fe import substructure as ss
from fetorsion.fe.couplings import Master, coupling_matrix, point_mass_block
from fetorsion.fe.modal import default_shift
from fetorsion.fe.rigid import rigid_rows
from fetorsion.fe.rotating import (ACROSS, E_CROSS, attachment_rotating_matrices, centrifugal_load,
                                   geometric_stiffness, master_rotating_blocks, prestress,
                                   rotating_frame_matrices, rotating_harmonic, rotating_modes)

E, NU, RHO = 210e9, 0.3, 7850.0
STEEL = Material(E, NU, RHO, "steel")
L, D = 1.0, 0.05  # the shaft of tests/test_condensed.py (15 k DOF)
H = D / 4
PINNED = [0, 1, 2, 3, 7, 8]  # both ends' y, z; the front end's axial motion and twist


@pytest.fixture(scope="module")
def built():
    s = assembled_shaft(L, D, H, E, NU, RHO)
    mesh, m, dof_of_node, K, M, b, pat = s.mesh, s.m, s.dof_of_node, s.K, s.M, s.basis, s.pattern
    masters = [Master("front", np.zeros(3), mesh.node_sets["front_face"]),
               Master("rear", np.array([L, 0.0, 0.0]), mesh.node_sets["rear_face"])]
    G = coupling_matrix(masters, dof_of_node, m.doflocs.T)
    itf = ss.interface(K, M, G, default_shift(mesh, STEEL))
    red = ss.craig_bampton(itf, keep_basis=True)
    Gr, Nr = rotating_frame_matrices(M, red.basis)
    return SimpleNamespace(M=M, xyz=m.doflocs.T, red=red, Gr=Gr, Nr=Nr, itf=itf, basis=b, pattern=pat)


@pytest.fixture(scope="module")
def shaft(built):
    return built.M, built.xyz, built.red, built.Gr, built.Nr


def modes0(red, held=PINNED):
    """Ω = 0 modes over all coordinates (held rows zero), M-orthonormal."""
    w2, V, keep = ss.reduced_modes(red, held=held)
    full = np.zeros((red.size, V.shape[1]))
    full[keep] = V
    return w2, full


# (a) ------------------------------------------------------------------------------------------

def test_mass_is_scalar_mass_times_identity(shaft):
    # G = M S and N = M Π need M = m ⊗ I₃ on interleaved DOF: every component block equal, no coupling
    M = shaft[0].tocsr()
    mx = M[0::3, 0::3]
    for i in range(3):
        for j in range(3):
            blk = M[i::3, j::3]
            assert abs(blk - (mx if i == j else 0 * mx)).max() <= 1e-15 * abs(mx).max()


@pytest.mark.slow  # 22 s on 2 cores: the default run stays under 10 minutes on the slower CI machines
def test_reduced_matrices_are_skew_and_semidefinite(shaft):
    _, _, red, Gr, Nr = shaft
    scale = np.abs(red.M).max()
    # symmetrised in the function; checked here against the raw product (round-off only: 1e-12)
    MB = shaft[0] @ red.basis
    B = red.basis.reshape(-1, 3, red.basis.shape[1])  # (nodes, xyz, modes): e × at every node, not a dense kron
    raw = MB.T @ np.einsum("ij,njm->nim", 2 * E_CROSS, B).reshape(red.basis.shape)
    assert np.abs(raw + raw.T).max() < 1e-12 * scale
    np.testing.assert_allclose(Gr, raw, atol=1e-12 * scale)
    assert np.abs(Nr - Nr.T).max() == 0.0
    # N = Bᵀ (m ⊗ P) B ≤ Bᵀ M B in the Loewner order (P ≤ I): both bounds to round-off (red.M
    # sets its η block to I, exact only to the Ritz vectors' M-orthonormality: BᵀMB here)
    BMB = MB.T @ red.basis
    assert scipy.linalg.eigvalsh(Nr).min() > -1e-12 * scale
    assert scipy.linalg.eigvalsh(BMB - Nr).min() > -1e-12 * scale


def test_coriolis_of_a_twist_is_radial_and_has_no_resultant(shaft):
    """u = θ e × X: the Coriolis force 2Ω e × u̇ = −2Ωθ̇ P X points to the axis. It does no work
    (uᵀGu = 0) and, on an axisymmetric body, has no net force or moment: twisting a spinning
    shaft couples it to radial (breathing) motion only, never to bending."""
    M, xyz, _, _, _ = shaft
    u = np.cross([1.0, 0.0, 0.0], xyz).ravel()
    Px = (xyz @ ACROSS).ravel()
    Gu = M @ (u.reshape(-1, 3) @ (2 * E_CROSS).T).ravel()  # e × at every node (a dense kron of them took 17 s)
    np.testing.assert_allclose(Gu, -2 * (M @ Px), atol=1e-15 * np.abs(Gu).max())  # the identity, exactly
    assert abs(u @ Gu) < 1e-14 * np.linalg.norm(u) * np.linalg.norm(Gu)
    R = rigid_rows(xyz, np.array([L / 2, 0, 0])).reshape(-1, 6)
    resultant = R.T @ Gu  # force (N/(rad/s²)) and moment about the centre
    # scale: the same field's size if all pointed one way (ρ V R); the faceted mesh is axisymmetric
    # to its geometric error (measured 2e-6 of that), so 1e-4 bounds a real coupling by far
    scale = np.abs(M @ Px).sum() * np.array([1, 1, 1, D / 2, L, L])
    assert np.all(np.abs(resultant) < 1e-4 * scale), resultant / scale


# (b) ------------------------------------------------------------------------------------------

def timoshenko_share(n):
    """Translational share α = ρAW² / (ρAW² + ρIΨ²) of the kinetic energy of the n-th pinned–pinned
    bending mode of a Timoshenko beam (w = W sin kx, ψ = Ψ cos kx, k = nπ/L): from the shear
    equation κGA k (kW − Ψ) = ρAω²W, Ψ = kW (1 − ρAω²/(κGAk²)), ω the lower root of the frequency
    equation (as tests/test_condensed.py). Rayleigh (no shear): 1 / (1 + k²I/A)."""
    G = STEEL.shear_modulus
    A, I, kap = np.pi * D**2 / 4, np.pi * D**4 / 64, cowper_circle(NU)
    k = n * np.pi / L
    a, b, c = RHO**2 * I / (kap * G), -(RHO * A + RHO * I * k**2 * (1 + E / (kap * G))), E * I * k**4
    w2 = (-b - np.sqrt(b * b - 4 * a * c)) / (2 * a)
    psi = k * (1 - RHO * A * w2 / (kap * G * A * k**2))
    return 1.0 / (1.0 + I / A * psi**2)


@pytest.mark.parametrize("ratio", [0.1, 0.3])
def test_bending_pair_splits_by_spin_speed(shaft, ratio):
    _, _, red, Gr, Nr = shaft
    w2, V = modes0(red)
    w = np.sqrt(w2)
    spin = ratio * w[0]
    f, growth = rotating_modes(red.K, red.M, Gr, Nr, spin, held=PINNED)
    assert np.all(np.abs(growth) < 1e-6 * f.max())  # conservative: neutral stability
    for n, pair in ((1, slice(0, 2)), (2, slice(2, 4))):
        wn = w[pair].mean()
        lo, hi = np.sort(f[np.argsort(np.abs(f - wn))[:2]])  # the two rotating-frame roots around ω_n
        split = (hi - lo) / 2
        # first-order perturbation of the degenerate pair: ±Ω |φ₁ᵀ G φ₂| / 2 = ±Ω × (the mode's share
        # of kinetic energy across the axis); the Rayleigh beam's exact split is αΩ at every Ω
        Phi = V[:, pair]
        alpha = abs(Phi[:, 0] @ Gr @ Phi[:, 1]) / 2
        print(f"mode {n}: Ω/ω1 {ratio}, split/Ω {split / spin:.6f}, FE share {alpha:.6f}, "
              f"Timoshenko {timoshenko_share(n):.6f}, mean {(hi + lo) / 2 / wn - 1:.2e}")
        # the 3D share against the Timoshenko beam's (measured 2e-8 and 8e-6): the section's own
        # deformation, and the beam's Cowper coefficient, at (D/L)² ~ 3e-3 of the rotary share 1 − α
        assert alpha == pytest.approx(timoshenko_share(n), abs=2e-5)
        # the exact split against the first-order one (measured within 1e-6 at Ω = 0.3 ω₁): the
        # remaining terms couple the pair to other modes through the rotary share 1 − α only
        assert split / spin == pytest.approx(alpha, abs=1e-5)
        # the pair's centre moves by the Rayleigh beam's −α(1 − α)Ω²/(2ω_n²) (eq. R5): this is 7e-5
        # of ω₁ at Ω = 0.3 ω₁ and found to 1e-6
        mean = np.sqrt(wn**2 - alpha * (1 - alpha) * spin**2)
        assert (hi + lo) / 2 == pytest.approx(mean, rel=1e-6)


@pytest.mark.parametrize("ratio", [0.1, 0.3])
def test_torsion_in_the_rotating_frame(shaft, ratio):
    """Spin softening acts on all of a twist (its motion is across the axis): without the
    centrifugal prestress's geometric stiffness ω_t² drops by Ω² φᵀNφ = Ω² (the model here);
    with it the drop is cancelled ([Likins]; rotation about the axis is neutral) — measured
    here is the first, as the model states."""
    _, _, red, Gr, Nr = shaft
    w2, V = modes0(red)
    c = np.sqrt(STEEL.shear_modulus / RHO)
    t = int(np.argmin(np.abs(np.sqrt(w2) - 2 * np.pi * c / (4 * L))))  # fixed–free torsion, c/4L
    phi = V[:, t]
    share = phi @ Nr @ phi
    assert share == pytest.approx(1.0, abs=1e-6)  # a twist moves across the axis (measured 1 − 5e-9)
    spin = ratio * np.sqrt(w2[0])
    f, _ = rotating_modes(red.K, red.M, Gr, Nr, spin, held=PINNED)
    ft = f[np.argmin(np.abs(f - np.sqrt(w2[t])))]
    expected = np.sqrt(w2[t] - spin**2 * share)
    print(f"torsion: Ω/ω1 {ratio}: ω_t shift {ft / np.sqrt(w2[t]) - 1:.3e}, "
          f"expected {expected / np.sqrt(w2[t]) - 1:.3e}")
    # the Coriolis coupling to breathing modes (≥ 30 kHz) is O(Ω² ω_t²/ω_r²): 1e-3 of the shift
    assert ft - np.sqrt(w2[t]) == pytest.approx(expected - np.sqrt(w2[t]), rel=1e-3)


# (c) ------------------------------------------------------------------------------------------

def disc_points(radius, thickness, rings=6, sectors=12, layers=3):
    """Point masses of a uniform disc about the x axis (density 1/volume): its moments are
    axisymmetric exactly (equal angular steps ≥ 3)."""
    r = (np.arange(rings) + 0.5) / rings * radius
    a = np.arange(sectors) * 2 * np.pi / sectors
    x = (np.arange(layers) + 0.5) / layers * thickness - thickness / 2
    R, A, X = np.meshgrid(r, a, x, indexing="ij")
    pts = np.stack([X.ravel(), (R * np.cos(A)).ravel(), (R * np.sin(A)).ravel()], 1)
    mass = np.repeat(r / r.sum(), sectors * layers) / (sectors * layers)  # area ∝ r per ring
    return pts, mass


def point_sums(pts, mass, p):
    """Σ Lᵢᵀ (m_i ·) Lᵢ for the mass, 2[e]ₓ (Coriolis) and P (spin softening) of point masses."""
    Ls = rigid_rows(pts, p)
    return [np.einsum("n,nia,ij,njb->ab", mass, Ls, A, Ls) for A in (np.eye(3), 2 * E_CROSS, ACROSS)]


def rotation_matrix(theta):
    K = np.array([[0, -theta[2], theta[1]], [theta[2], 0, -theta[0]], [-theta[1], theta[0], 0]])
    return scipy.linalg.expm(K)


def exact_terms(pts, mass, p, h=1e-4):
    """Gyroscopic G and the Ω² stiffness of the rigid body from its exact rotating-frame Lagrangian
    ½Σ m|ṙ + e × r|² (Ω = 1), r = p + t + R(θ)(X − p), by central differences."""
    e = np.array([1.0, 0.0, 0.0])
    rel = pts - p

    def pos(q):
        return p + q[:3] + rel @ rotation_matrix(q[3:]).T

    def V(q):  # centrifugal potential −½ Σ m |P r|²
        return -0.5 * np.sum(mass * np.sum((pos(q) @ ACROSS) ** 2, axis=1))

    def L1(q, qd):  # Σ m ṙ · (e × r), ṙ by a difference along q̇
        rd = (pos(q + h * qd) - pos(q - h * qd)) / (2 * h)
        return np.sum(mass * np.sum(rd * np.cross(e, pos(q)), axis=1))

    I6 = np.eye(6)
    Kc = np.array([[(V(h * (a + b)) - V(h * (a - b)) - V(h * (b - a)) + V(-h * (a + b))) / (4 * h * h)
                    for b in I6] for a in I6])
    A = np.array([[(L1(h * b, a) - L1(-h * b, a)) / (2 * h) for b in I6] for a in I6])  # ∂²L₁/∂q̇_a∂q_b
    return A - A.T, Kc


@pytest.mark.parametrize("where", ["on the axis", "off the axis"])
def test_rigid_body_terms_equal_point_masses(where):
    radius, thick = 0.15, 0.03
    pts, mass = disc_points(radius, thick)
    shift = np.array([0.4, 0.0, 0.0]) if where == "on the axis" else np.array([0.4, 0.03, -0.02])
    pts = pts + shift
    p = np.array([0.35, 0.0, 0.0]) if where == "on the axis" else np.array([0.35, 0.01, 0.04])
    M6, G_pts, N_pts = point_sums(pts, mass, p)
    c = mass @ pts
    J = np.einsum("n,nij->ij", mass, np.einsum("ni,nj->nij", pts - c, pts - c))
    J = np.trace(J) * np.eye(3) - J
    np.testing.assert_allclose(M6, point_mass_block(1.0, J, c, p), atol=1e-14)
    G, N, Ks = master_rotating_blocks(M6, p)
    # the closed forms are sums of the same moments: round-off
    np.testing.assert_allclose(G, G_pts, atol=1e-14)
    np.testing.assert_allclose(N, N_pts, atol=1e-14)
    # against the exact Lagrangian with finite rotations: central differences, h² ~ 1e-8 relative
    G_ex, K_ex = exact_terms(pts, mass, p)
    np.testing.assert_allclose(G, G_ex, atol=1e-7 * np.abs(G).max())
    np.testing.assert_allclose(Ks - N, K_ex, atol=1e-7 * np.abs(N).max())
    if where == "on the axis":
        Ip, Id = J[0, 0], J[1, 1]
        # centred on its master here only for the rotation blocks' textbook form
        Gc, Nc, Kc = master_rotating_blocks(point_mass_block(1.0, J, c, c), c)
        np.testing.assert_allclose(Gc[3:, 3:], (2 * Id - Ip) * E_CROSS, atol=1e-15)
        np.testing.assert_allclose(np.diag(Nc)[3:], [Ip, Id - Ip / 2, Id - Ip / 2], atol=1e-15)
        np.testing.assert_allclose(np.diag(Kc - Nc)[3:], [0.0, Ip - Id, Ip - Id], atol=1e-15)


def test_attachment_matrices_place_blocks_on_their_masters():
    B = point_mass_block(2.0, np.diag([0.3, 0.2, 0.2]), np.array([1.1, 0, 0]), np.array([1.0, 0, 0]))
    Dm = np.zeros((12, 12))
    Dm[6:, 6:] = B
    G, N, Ks = attachment_rotating_matrices(Dm, np.array([[0.0, 0, 0], [1.0, 0, 0]]))
    for big, small in zip((G, N, Ks), master_rotating_blocks(B, np.array([1.0, 0, 0]))):
        assert np.all(big[:6] == 0) and np.all(big[6:, 6:] == small)


# (d) ------------------------------------------------------------------------------------------

def test_harmonic_without_spin_is_the_plain_solution(shaft):
    """Ω = 0: (K − ω²M + iωC) z = F solved directly equals the modal superposition that
    fetorsion.response.coupled.harmonic_solution uses (modal damping ζ on every mode)."""
    _, _, red, Gr, Nr = shaft
    zeta = 0.02
    w2, V = modes0(red)
    MV = red.M @ V
    C = MV @ np.diag(2 * zeta * np.sqrt(w2)) @ MV.T
    F = np.zeros((3, red.size), complex)
    F[:, 7] = 1.0  # rear master, y: N
    F[:, 9] = 0.1j  # rear master, twist: N·m
    omegas = np.sqrt(w2[[0, 2, 4]]) * np.array([0.7, 1.0, 1.3])
    z = rotating_harmonic(red.K, red.M, C, Gr, Nr, 0.0, F, omegas, held=PINNED)
    P = F @ V
    modal = (P / (w2 - omegas[:, None] ** 2 + 2j * zeta * np.sqrt(w2) * omegas[:, None])) @ V.T
    # two factorisations of the same well-conditioned (damped) systems: round-off, 1e-10
    np.testing.assert_allclose(z, modal, rtol=1e-10, atol=1e-10 * np.abs(modal).max())
    # with spin, the response is the solution of the rotating-frame equations at each frequency
    spin = 0.3 * np.sqrt(w2[0])
    zs = rotating_harmonic(red.K, red.M, C, Gr, Nr, spin, F, omegas, held=PINNED)
    free = np.setdiff1d(np.arange(red.size), PINNED)
    for k, w in enumerate(omegas):
        A = red.K - spin**2 * Nr - w**2 * red.M + 1j * w * (C + spin * Gr)
        np.testing.assert_allclose((A @ zs[k])[free], F[k, free], atol=1e-9 * np.abs(F).max())


def test_centrifugal_load_is_the_projected_body_force(shaft):
    # Bᵀ M Π X per unit Ω²; on the shaft the body force is radial and self-equilibrated: on the
    # masters' rigid coordinates (which B spans exactly) it sums to zero (faceting: 1e-4 as above)
    M, xyz, red, _, _ = shaft
    f = centrifugal_load(M, red.basis, xyz)
    radial = np.abs(M @ (xyz @ ACROSS).ravel()).sum()
    R = rigid_rows(xyz, np.zeros(3)).reshape(-1, 6)
    q = np.linalg.lstsq(red.basis, R, rcond=None)[0]  # rigid motions in reduced coordinates
    assert np.all(np.abs(q.T @ f) < 1e-4 * radial * np.array([1, 1, 1, D, L, L]))
    assert np.abs(f).max() > 1e-3 * radial * D  # and it is not zero: it loads the interior vectors


# stress stiffening ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def stiffening(built):
    """K_σ per unit Ω² of the shaft's centrifugal prestress, on the reduced basis: the static
    K u = M Π X (unit Ω²) with the end faces' rigid fits held at zero (by symmetry they carry no
    reaction), from the one factor of K − σM by the fixed-point step of the constraint modes."""
    itf = built.itf
    solve = ss.prescribed_solver(itf)
    b = built.M @ (built.xyz @ ACROSS).ravel()
    u = solve(b)
    for _ in range(30):
        u = solve(b - itf.sigma * (itf.M @ u))
    assert np.linalg.norm(itf.K @ u - b - itf.G.T @ np.linalg.lstsq(itf.G.T.toarray(), itf.K @ u - b, rcond=None)[0]) \
        < 1e-8 * np.linalg.norm(b)
    Ks = geometric_stiffness(built.basis, built.pattern, prestress(built.basis, u, E, NU))
    B = built.red.basis
    Kr = B.T @ (Ks @ B)
    return u, 0.5 * (Kr + Kr.T)


def test_stress_stiffening_cancels_spin_softening_of_a_twist(built, stiffening):
    _, Ks_r = stiffening
    red, Gr, Nr = built.red, built.Gr, built.Nr
    w2, V = modes0(red)
    c = np.sqrt(STEEL.shear_modulus / RHO)
    t = int(np.argmin(np.abs(np.sqrt(w2) - 2 * np.pi * c / (4 * L))))
    for ratio in (0.1, 0.3):
        spin = ratio * np.sqrt(w2[0])
        f, growth = rotating_modes(red.K, red.M, Gr, Nr - Ks_r, spin, held=PINNED)
        ft = f[np.argmin(np.abs(f - np.sqrt(w2[t])))]
        print(f"with K_σ, Ω/ω1 {ratio}: torsion shift {ft / np.sqrt(w2[t]) - 1:.3e}")
        # spin leaves an axisymmetric shaft's torsion alone up to the strain of the prestress,
        # (ΩR/c)² = 2e-6 at Ω = 0.3 ω₁ (measured 5e-9 and 2e-8); without K_σ it was −Ω²/(2ω_t²)
        assert abs(ft / np.sqrt(w2[t]) - 1) < 1e-6
        # the bending split is the translational share's (above): K_σ acts on the sections' tilt
        # and shape only, the rotary share's (1 − α)(ΩR/c)²-order (measured < 1e-9)
        for pair in (slice(0, 2), slice(2, 4)):
            wn = np.sqrt(w2[pair]).mean()
            lo, hi = np.sort(f[np.argsort(np.abs(f - wn))[:2]])
            Phi = V[:, pair]
            assert (hi - lo) / 2 / spin == pytest.approx(abs(Phi[:, 0] @ Gr @ Phi[:, 1]) / 2, abs=1e-5)


def test_reduced_coriolis_from_the_scalar_mass_equals_the_full_product(built):
    # the condensed crank builds G_r from m (M = m ⊗ I₃) alone: the same matrix as Bᵀ M (S B)
    import scipy.sparse as sp

    from fetorsion.fe.rotating import node_mass_rotating_terms

    m = sp.csr_array(sp.csr_array(built.M)[0::3][:, 0::3])
    B = built.red.basis
    np.testing.assert_allclose(node_mass_rotating_terms(m, lambda k: B[k::3])[0], built.Gr, rtol=0,
                               atol=1e-12 * np.abs(built.Gr).max())
