"""Rotating-frame terms of the condensed crank: Coriolis (gyroscopic) and centrifugal matrices.

The crank is modelled in its own frame, turning at constant speed Ω about the x axis (unit
vector e). A material point at X (in that frame) displaced by u has the inertial velocity
u̇ + Ω e × (X + u); Lagrange's equations of ½∫ρ|u̇ + Ω e × (X + u)|² − U give, per unit volume,
the rotor equations in a rotating frame of [Genta] (there for beams and discs),

    ρ ü + 2Ω ρ e × u̇ + Ω² ρ e × (e × (X + u)) + (elastic forces) = f.

With e × (e × r) = −P r, P = diag(0, 1, 1) (the part of r across the axis), and the mesh's
consistent mass M = m ⊗ I₃ (:func:`fetorsion.fe.assembly.mass`), the discrete equations read

    M ü + Ω G u̇ + (K − Ω² N) u = f + Ω² N X,                                            (R1)
    G = m ⊗ 2[e]ₓ = M S,   S = I ⊗ 2[e]ₓ   (skew: Gᵀ = −G),                              (R2)
    N = m ⊗ P = M Π,       Π = I ⊗ P      (symmetric positive semi-definite),            (R3)

(R-numbers: docs/condensed-crank.md, "Rotating-frame terms"). G and N are never assembled:
M is applied to the component-rotated (S) or component-projected (Π) vectors, so on a
Craig–Bampton basis B (n × r) the reduced terms cost one sparse-times-dense product each,

    G_r = Bᵀ M (S B),   N_r = Bᵀ M (Π B).

The constant load Ω² N X (the centrifugal body force of the undeformed crank) is static in
the rotating frame (order 0): it deforms and prestresses the crank but does not enter the
vibratory response. It is returned separately (:func:`centrifugal_load`).

Spin softening N belongs with the geometric (stress-stiffening) matrix K_σ of the centrifugal
prestress, O(Ω²) as well ([Likins]): N alone lowers every torsional ω² by Ω² × the mode's share
of motion across the axis (all of it, for torsion: −Ω²/(2ω_t²) in frequency) and puts the rigid
rotation about x at ω² = −Ω², which K_σ cancels exactly for a body in equilibrium (a rotated
steady state is again a steady state). K_σ per unit Ω² comes from the static displacement under
N X (:func:`prestress`, :func:`geometric_stiffness`); the equations with both read

    M ü + Ω G u̇ + (K + Ω² (K_σ − N)) u = f.                                               (R4)

For a rigid body the cancellation is written out in :func:`master_rotating_blocks` (its ``K_s``).
"""

from __future__ import annotations

import numpy as np

#: The spin axis, in the crank's frame.
SPIN_AXIS = np.array([1.0, 0.0, 0.0])
#: Complex systems solved at once by :func:`rotating_harmonic`: 256 × 200² × 16 B ≈ 160 MB.
HARMONIC_BATCH = 256


def _cross(v: np.ndarray) -> np.ndarray:
    """[v]ₓ (3 × 3): [v]ₓ w = v × w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


#: [e]ₓ and P = −[e]ₓ[e]ₓ = diag(0, 1, 1) for the x axis.
E_CROSS = _cross(SPIN_AXIS)
ACROSS = -E_CROSS @ E_CROSS


def _per_node(V: np.ndarray, A: np.ndarray) -> np.ndarray:
    """(I ⊗ A) V for V (3n,) or (3n, k) in interleaved x, y, z order."""
    W = np.asarray(V).reshape((-1, 3) + np.shape(V)[1:])
    return np.einsum("ij,nj...->ni...", A, W).reshape(np.shape(V))


def rotating_frame_matrices(M, basis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Reduced gyroscopic and spin-softening matrices per unit spin speed, (G_r, N_r).

    Parameters
    ----------
    M : sparse (n, n)
        Consistent mass of the mesh, kg, interleaved (x, y, z) DOF, of the form m ⊗ I₃
        (:func:`fetorsion.fe.assembly.mass`; M Π = m ⊗ P needs that form).
    basis : ndarray (n, r)
        u = basis @ z (Craig–Bampton [Ψ Φ] expanded to the mesh DOF), m per unit coordinate.

    Returns
    -------
    G_r : ndarray (r, r)
        Bᵀ M S B, skew-symmetric, kg (per rad/s of spin: the force is Ω G_r ż), eq. (R2).
    N_r : ndarray (r, r)
        Bᵀ M Π B, symmetric positive semi-definite, kg (the stiffness is −Ω² N_r), eq. (R3).

    Notes
    -----
    Cost: two sparse × dense products with n × r blocks and two r × n × r dense products
    (at 320 k DOF, r = 200: 2 × 0.5 GB of temporaries, a few seconds).
    """
    MB = M @ np.asarray(basis)  # (m ⊗ I₃) and (I ⊗ A) commute: Bᵀ M (I ⊗ A) B = (MB)ᵀ (I ⊗ A) B
    G = MB.T @ _per_node(basis, 2.0 * E_CROSS)
    N = MB.T @ _per_node(basis, ACROSS)
    return 0.5 * (G - G.T), 0.5 * (N + N.T)


def node_mass_rotating_terms(node_mass, rows, dof_xyz: np.ndarray | None = None):
    """(G_r r × r, the centrifugal load per unit Ω² (r,) or None) from the scalar node mass
    matrix m and the basis' y and z rows alone, ``rows(k)`` (DOF nodes × r; k = 1 y, 2 z) made
    on demand, so that no more than two such blocks are held.

    (R2) reads G_r = 2 (B_zᵀ m B_y − B_yᵀ m B_z), the same value as
    :func:`rotating_frame_matrices`'s first; with m symmetric, B_yᵀ m B_z = (B_zᵀ m B_y)ᵀ, so
    G_r = 2 (X − Xᵀ), X = B_zᵀ (m B_y): one product with a matrix a ninth of M's size. The load
    (``dof_xyz`` given) is :func:`centrifugal_load`'s, B_yᵀ m y + B_zᵀ m z.
    """
    By = rows(1)
    mBy = np.asarray(node_mass @ By)
    load = None if dof_xyz is None else By.T @ np.asarray(node_mass @ np.asarray(dof_xyz, float)[:, 1])
    del By
    Bz = rows(2)
    if load is not None:
        load += Bz.T @ np.asarray(node_mass @ np.asarray(dof_xyz, float)[:, 2])
    X = Bz.T @ mBy
    return 2.0 * (X - X.T), load


def centrifugal_load(M, basis: np.ndarray, dof_xyz: np.ndarray) -> np.ndarray:
    """Reduced static centrifugal load per unit Ω², Bᵀ N X (N·s² per unit coordinate).

    Order 0 in the rotating frame (a constant force): it prestresses the crank and loads the
    bearings statically, and is not part of the vibratory response, eq. (R1).

    Parameters
    ----------
    M : sparse (n, n) or (n / 3, n / 3)
        Consistent mass, kg, of the form m ⊗ I₃, or the scalar node mass m itself (then
        Bᵀ N X reads B_yᵀ m y + B_zᵀ m z, B_y, B_z the y and z rows of the basis: products with
        a matrix a ninth of M's size).
    basis : ndarray (n, r)
    dof_xyz : ndarray (n / 3, 3)
        Position of each DOF-node, m (``skfem`` ``doflocs.T``).
    """
    xyz = np.asarray(dof_xyz, float)
    if M.shape[0] == len(xyz):
        return node_mass_rotating_terms(M, lambda k: basis[k::3], xyz)[1]
    X = _per_node(xyz.ravel(), ACROSS)
    return np.asarray(basis).T @ (M @ X)


def body_moments(block: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """Mass m (kg), first moment m d (kg·m) and second moment S (kg·m²) about the master of a
    rigid body from its 6 × 6 mass block at that master.

    With L(r) = [I, −[r]ₓ] the block is Σ m_i L(r_i)ᵀ L(r_i): its tt part is m I, its tθ part
    −[m d]ₓ, its θθ part tr(S) I − S (S = Σ m_i r_i r_iᵀ), which this inverts.
    """
    B = np.asarray(block, float)
    m = float(B[0, 0])
    md = np.array([B[1, 5], B[2, 3], B[0, 4]])  # tθ = −[md]ₓ = [[0, md_z, −md_y], [−md_z, 0, md_x], …]
    Jt = 0.5 * (B[3:, 3:] + B[3:, 3:].T)
    S = 0.5 * np.trace(Jt) * np.eye(3) - Jt
    return m, md, S


def master_rotating_blocks(block: np.ndarray, position: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rotating-frame terms of a rigid body carried on a master as a 6 × 6 mass block.

    For small motions q = (t, θ) of the master at p, a point of the body at X = p + r moves
    exactly as t + R(θ) r = t + θ × r + ½ θ × (θ × r) + …. The rotating-frame Lagrangian
    ½Σ m_i|ṙ_i + Ω e × r_i|² expanded to second order gives (the disc's terms in [Genta];
    derived here for any body, and checked against point masses in tests/test_rotating.py):

    * gyroscopic, per unit Ω, ``G`` = Σ m_i L_iᵀ 2[e]ₓ L_i: tt 2m[e]ₓ, tθ −2[e]ₓ[m d]ₓ,
      θt 2[m d]ₓ[e]ₓ, θθ 2[S e]ₓ (the second-order kinematics add only a time derivative);
      for an axisymmetric body centred on the master, θθ = (2 I_d − I_p)[e]ₓ;
    * spin softening, per unit Ω², ``N`` = Σ m_i L_iᵀ P L_i: tt mP, tθ −P[m d]ₓ, θt [m d]ₓP,
      θθ tr(S) I − S − [e]ₓ S [e]ₓᵀ; axisymmetric: diag(I_p, I_d − I_p/2, I_d − I_p/2);
    * ``K_s`` per unit Ω², θθ only: the centrifugal forces Ω² m_i P X_i working on the
      second-order displacement ½θ × (θ × r_i): Σ m_i [(P X_i · r_i) I − sym(P X_i r_iᵀ)].
      In a body this is the geometric stiffness of the internal forces holding it together
      against the centrifugal load; axisymmetric on the axis: diag(I_p, I_p/2, I_p/2), so the
      net tilt stiffness Ω²(K_s − N) is Ω²(I_p − I_d) and the rotation about the axis is neutral.

    Parameters
    ----------
    block : ndarray (6, 6)
        Mass block at the master, kg, kg·m, kg·m² (:func:`fetorsion.fe.couplings.point_mass_block`).
    position : ndarray (3,)
        Master point p, m (the axis is x through the origin).

    Returns
    -------
    G, N, K_s : ndarray (6, 6)
        kg·(m, rad) per rad/s, per (rad/s)², per (rad/s)²; the equations are
        M q̈ + Ω G q̇ + (Ω² (K_s − N)) q = f.
    """
    m, md, S = body_moments(block)
    E, P, D = E_CROSS, ACROSS, _cross(md)
    G, N = np.zeros((6, 6)), np.zeros((6, 6))
    G[:3, :3], G[:3, 3:], G[3:, :3] = 2 * m * E, -2 * E @ D, 2 * D @ E
    G[3:, 3:] = 2 * _cross(S @ SPIN_AXIS)
    N[:3, :3], N[:3, 3:], N[3:, :3] = m * P, -P @ D, D @ P
    N[3:, 3:] = np.trace(S) * np.eye(3) - S - E @ S @ E.T
    Pp = P @ np.asarray(position, float)
    PS = P @ S
    Ks = np.zeros((6, 6))
    outer = np.outer(Pp, md) + PS
    Ks[3:, 3:] = (Pp @ md + np.trace(PS)) * np.eye(3) - 0.5 * (outer + outer.T)
    return 0.5 * (G - G.T), 0.5 * (N + N.T), Ks


def attachment_rotating_matrices(Dm: np.ndarray, positions: np.ndarray):
    """(G, N, K_s), each 6·masters square, of the rigid bodies in a block-diagonal master mass
    matrix ``Dm`` (kg …, :func:`fetorsion.fe.condensed.attachment_masses`) at ``positions``
    (masters × 3, m); per master :func:`master_rotating_blocks`."""
    n = len(positions)
    out = [np.zeros((6 * n, 6 * n)) for _ in range(3)]
    for k, p in enumerate(np.asarray(positions, float)):
        s = slice(6 * k, 6 * k + 6)
        if np.any(Dm[s, s]):
            for o, b in zip(out, master_rotating_blocks(Dm[s, s], p)):
                o[s, s] = b
    return tuple(out)


def _kept(A: np.ndarray, held) -> np.ndarray:
    keep = np.setdiff1d(np.arange(A.shape[-1]), np.asarray(held, dtype=np.int64))
    return A[np.ix_(keep, keep)], keep


def rotating_modes(K_r, M_r, G_r, N_r, omega: float, held=()) -> tuple[np.ndarray, np.ndarray]:
    """Natural frequencies in the rotating frame at spin speed ``omega`` (rad/s).

    The quadratic problem (λ² M + λ Ω G + K − Ω² N) z = 0 as the state-space pencil
    [[0, I], [−K', −ΩG]] x = λ [[I, 0], [0, M]] x, x = (z, λz), solved densely
    (scipy.linalg.eig). A conservative gyroscopic system has λ = ±iω.

    Parameters
    ----------
    K_r, M_r, G_r, N_r : ndarray (r, r)
        Stiffness N/m, mass kg, gyroscopic and spin-softening matrices (:func:`rotating_frame_matrices`,
        plus master-level terms), per rad/s and (rad/s)². Stress stiffening, if any, goes into ``N_r`` as −K_s.
    omega : float
        Spin speed Ω, rad/s.
    held : sequence of int
        Coordinates held at zero (rigid bearings).

    Returns
    -------
    frequencies : ndarray
        Im λ of the upper half of the spectrum (one per conjugate pair), ascending, rad/s.
    growth : ndarray
        Re λ of the same eigenvalues, 1/s (zero for a stable conservative system).
    """
    import scipy.linalg

    K, keep = _kept(np.asarray(K_r) - omega**2 * np.asarray(N_r), held)
    M, _ = _kept(np.asarray(M_r), held)
    G, _ = _kept(omega * np.asarray(G_r), held)
    k = len(keep)
    Z, eye = np.zeros((k, k)), np.eye(k)
    lam = scipy.linalg.eig(np.block([[Z, eye], [-K, -G]]), np.block([[eye, Z], [Z, M]]), right=False)
    upper = lam[np.argsort(lam.imag)][k:]  # real matrices: conjugate pairs, one of each
    order = np.argsort(upper.imag)
    return upper.imag[order], upper.real[order]


def rotating_harmonic(K_r, M_r, C_r, G_r, N_r, omega_spin, F, omegas, held=()) -> np.ndarray:
    """Reduced response z (..., r) to harmonic loads in the rotating frame.

    Solves (K − Ω²N − ω²M + iω(C + ΩG)) z = F for every load, as stacked dense solves
    (np.linalg.solve, :data:`HARMONIC_BATCH` systems at a time); held coordinates are zero.

    Parameters
    ----------
    K_r, M_r, C_r, G_r, N_r : ndarray (r, r)
        N/m, kg, N·s/m, kg per rad/s, kg per (rad/s)².
    omega_spin : float or ndarray (...)
        Spin speed Ω, rad/s, broadcast against ``omegas``.
    F : ndarray (..., r)
        Complex load amplitudes, N (and N·m) per coordinate.
    omegas : ndarray (...)
        Excitation frequency ω in the rotating frame, rad/s.
    held : sequence of int
        Coordinates held at zero.
    """
    F = np.asarray(F, complex)
    r = F.shape[-1]
    spin, om = np.broadcast_arrays(np.asarray(omega_spin, float), np.asarray(omegas, float))
    shape = np.broadcast_shapes(F.shape[:-1], om.shape)
    F = np.broadcast_to(F, shape + (r,)).reshape(-1, r)
    spin, om = np.broadcast_to(spin, shape).ravel(), np.broadcast_to(om, shape).ravel()
    keep = np.setdiff1d(np.arange(r), np.asarray(held, dtype=np.int64))
    mats = [np.asarray(A)[np.ix_(keep, keep)] for A in (K_r, M_r, C_r, G_r, N_r)]
    K, M, C, G, N = mats
    z = np.zeros(F.shape, complex)
    for s in range(0, len(om), HARMONIC_BATCH):
        w, o = om[s:s + HARMONIC_BATCH, None, None], spin[s:s + HARMONIC_BATCH, None, None]
        A = K - o**2 * N - w**2 * M + 1j * w * (C + o * G)
        z[s:s + HARMONIC_BATCH, keep] = np.linalg.solve(A, F[s:s + HARMONIC_BATCH, keep, None])[..., 0]
    return z.reshape(shape + (r,))


def prestress(basis, displacement: np.ndarray, youngs_modulus: float, poisson_ratio: float) -> np.ndarray:
    """Cauchy stress σ = λ tr ε I + 2μ ε of an interleaved P2 displacement at the quadrature
    points, Pa per unit displacement scale: shape (3, 3, elements, points).

    Parameters
    ----------
    basis : skfem.Basis
        Scalar P2 basis (:func:`fetorsion.fe.assembly.p2_basis`).
    displacement : ndarray (3 · DOF-nodes,)
        m, interleaved x, y, z.
    youngs_modulus, poisson_ratio : float
        Pa, -.
    """
    from .assembly import lame

    lam, mu = lame(youngs_modulus, poisson_ratio)
    grads = np.stack([b[0].grad for b in basis.basis], axis=2)  # [j, e, a, q]
    U = np.asarray(displacement).reshape(-1, 3)[basis.element_dofs.T]  # [e, a, i]
    du = np.einsum("eai,jeaq->ijeq", U, grads)  # ∂_j u_i
    eps = 0.5 * (du + du.transpose(1, 0, 2, 3))
    tr = np.einsum("iieq->eq", eps)
    return 2 * mu * eps + lam * tr[None, None] * np.eye(3)[:, :, None, None]


def geometric_stiffness(basis, pattern, stress: np.ndarray):
    """Geometric (stress-stiffening) matrix of a prestress, N/m, interleaved DOF:

        K_σ[(a, i), (b, j)] = δ_ij ∫ ∂_k φ_a σ_kl ∂_l φ_b dx,

    the second variation of ∫ σ : E(u), E the Green strain, about the prestressed state.

    Parameters
    ----------
    basis : skfem.Basis
        Scalar P2 basis.
    pattern : fetorsion.fe.assembly.BlockPattern
    stress : ndarray (3, 3, elements, points)
        Pa (:func:`prestress`).
    """
    from .assembly import diagonal_block_matrix

    grads = np.stack([b[0].grad for b in basis.basis], axis=2)  # [k, e, a, q]
    flux = np.einsum("kleq,leaq->keaq", stress * basis.dx[None, None], grads)  # σ ∇φ_b dx
    Se = np.einsum("keaq,kebq->eab", grads, flux)
    return diagonal_block_matrix(pattern, np.bincount(pattern.slot, Se.ravel(), minlength=len(pattern.indices)))
