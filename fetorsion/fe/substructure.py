"""Craig–Bampton reduction to master points, and the full model with the same supports.

Everything here works from ONE sparse Cholesky factor of S = K − σM (σ < 0, as in the
modal solver) and the block of interface solutions Y = S⁻¹Gᵀ (one multi-right-hand-side
solve, BLAS-3), where G maps the nodal displacement to the masters' six DOF
(:mod:`fetorsion.fe.couplings`). C = G Y is small and dense (6 per master).

Masters held, prescribed or loaded: x = S⁻¹b − Y μ, with the master forces μ found from a
small dense system. That one formula gives

* **constraint modes** Ψ (K Ψ + Gᵀ Λ = 0, G Ψ = I): the static shapes for a unit motion of
  each master DOF with the others held. With S = K − σM the static problem reads
  S Ψ + GᵀΛ = −σ M Ψ, solved by the fixed-point iteration Ψ ← solve(−σMΨ, G Ψ = I), which
  contracts by |σ| / (ω²_fixed,1 − σ) (a few hundredths for a crank held at every journal
  and pin): a handful of block solves, not a second factorisation of the singular K;
* **fixed-interface modes** Φ (masters held): block shift-invert Lanczos
  (:func:`fetorsion.fe.eigen.block_lanczos`) on the constrained operator;
* the **full model in supports** (:func:`supported_modes`): springs, dampers and masses on
  the masters (bearings, attachments) are the low-rank term Gᵀ D G, and held master DOF
  (rigid bearings) are constraints — the same correction, never assembled.

The reduced model u ≈ Ψ q + Φ η has the masters' DOF q as its first coordinates exactly
(G Ψ = I, G Φ = 0), so supports act on it as on the full model, and its modes converge to
the full model's from above (a Ritz approximation) as modes are added.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg
import scipy.sparse as sp

from ..errors import FetorsionError
from .eigen import EIGEN_TOL, ORTHO_DROP, block_lanczos, drop_zeros, factorize, numpy_blas_threads, shifted, svqb_coefficients

if TYPE_CHECKING:
    from collections.abc import Sequence

#: Constraint-mode iteration: stop when the update is below this share of Ψ (max norm).
PSI_TOL = 1e-11
PSI_MAX_ITER = 40
#: Rows per slice of the in-place block updates below: a slice's product is a few MB, where the
#: whole block's would be one more fresh n × m array (162 MB at 323 k DOF and 66 master DOF),
#: whose first touch costs more than its arithmetic on this project's machines
#: (docs/performance.md).
ROWS = 16384


def _subtract_product(out: np.ndarray, A: np.ndarray, c: np.ndarray | None, scale: float = 1.0) -> None:
    """out −= scale · A c (c None: scale · A) in place, slice by slice of rows (no n × k temporary)."""
    for i in range(0, out.shape[0], ROWS):
        part = A[i:i + ROWS] * scale if c is None else A[i:i + ROWS] @ c
        if c is not None and scale != 1.0:
            part *= scale
        out[i:i + ROWS] -= part


def _subtract_coupling(out: np.ndarray, G, mu: np.ndarray) -> None:
    """out −= Gᵀ μ in place, on the DOF the couplings touch (Gᵀ μ is zero on every other)."""
    G = sp.csr_array(G)
    rows = np.unique(G.indices)
    out[rows] -= G[:, rows].T @ mu


@dataclass
class Interface:
    """The factor of S = K − σM and the interface products (see module docstring).

    Attributes
    ----------
    solve : callable
        b ↦ S⁻¹ b, b of shape (n,) or (n, m).
    K, M : sparse (n, n)
        Stiffness N/m and mass kg of the bare structure.
    G : sparse (6 masters, n)
    sigma : float
        Shift, rad²/s² (negative).
    Y : ndarray (n, 6 masters)
        S⁻¹ Gᵀ.
    C : ndarray (6 masters, 6 masters)
        G S⁻¹ Gᵀ (symmetric positive definite).
    """

    solve: object
    K: sp.csr_array
    M: sp.csr_array
    G: sp.csr_array
    sigma: float
    Y: np.ndarray
    C: np.ndarray
    timings_s: dict[str, float] = field(default_factory=dict)

    @property
    def n_master_dofs(self) -> int:
        return self.G.shape[0]


def interface(K, M, G, sigma: float, backend: str = "auto", groups: np.ndarray | None = None) -> Interface:
    """Factor S = K − σM once and solve for the interface block Y = S⁻¹Gᵀ.

    Parameters
    ----------
    K, M : sparse (n, n)
        N/m and kg, symmetric; K − σM positive definite.
    G : sparse (m, n)
        Master DOF from nodal displacements (:func:`fetorsion.fe.couplings.coupling_matrix`).
    sigma : float
        Negative shift, rad²/s².
    backend : str
        Factorisation backend of :func:`fetorsion.fe.eigen.factorize`.
    groups : ndarray of int, optional
        DOF groups sharing one sparsity pattern, for the fill-reducing ordering (same function).
    """
    if sigma >= 0:
        raise ValueError("the shift must be negative")
    t0 = time.perf_counter()
    solve = factorize(shifted(K, M, sigma), backend, groups)
    t1 = time.perf_counter()
    Y = np.asarray(solve(G.T.toarray()))
    C = np.asarray(G @ Y)
    t2 = time.perf_counter()
    # M keeps K's 3 × 3 block pattern, two thirds of it explicit zeros: dropped once here, the
    # reduction's and the eigen-solves' products with M cost a third
    return Interface(solve, sp.csr_array(K), sp.csr_array(drop_zeros(M)), sp.csr_array(G), float(sigma), Y,
                     0.5 * (C + C.T),
                     {"factorize": t1 - t0, "interface": t2 - t1})


def prescribed_solver(itf: Interface):
    """x = solve(b, g): S x + Gᵀ μ = b with every master DOF prescribed, G x = g (g: (m,) or (m, k)).

    With ``forces=True`` the call returns (x, μ): the master forces, from which K x follows
    without a sparse product, K x = b + σ M x − Gᵀ μ.
    """
    C = scipy.linalg.cho_factor(itf.C)

    def solve(b, g=None, forces=False):
        x0 = np.asarray(itf.solve(b))
        r = itf.G @ x0 if g is None else itf.G @ x0 - g
        mu = scipy.linalg.cho_solve(C, r)
        _subtract_product(x0, itf.Y, mu)  # x0 is the solve's own fresh array
        return (x0, mu) if forces else x0

    return solve


def constraint_modes(itf: Interface, tol: float = PSI_TOL, iterations: int | None = None) -> tuple[np.ndarray, int]:
    """Static constraint modes Ψ (n × m): K Ψ + GᵀΛ = 0, G Ψ = I; and the iterations used.

    ``iterations`` fixes the number of fixed-point steps instead (0: the shifted modes
    Ψ_σ = Y C⁻¹, with S Ψ_σ + GᵀΛ = 0).
    """
    psi, its, _, _ = _constraint_modes(itf, tol, iterations)
    return psi, its


def _constraint_modes(itf: Interface, tol: float, iterations: int | None):
    """(Ψ, iterations, M Ψ, K Ψ): the products from the last fixed-point step's equilibrium,
    S Ψ + Gᵀ μ = −σ M Ψ_prev, so K Ψ = σ M Ψ − σ M Ψ_prev − Gᵀ μ (no sparse product with K)."""
    solve = prescribed_solver(itf)
    eye = np.eye(itf.n_master_dofs)
    C = scipy.linalg.cho_factor(itf.C)
    psi = itf.Y @ scipy.linalg.cho_solve(C, eye)
    Mpsi = np.asarray(itf.M @ psi)
    Kpsi = itf.sigma * Mpsi + itf.G.T @ scipy.linalg.cho_solve(C, eye)  # S Ψ_σ = S Y C⁻¹ = Gᵀ C⁻¹
    for it in range(1, (PSI_MAX_ITER if iterations is None else iterations) + 1):
        b = -itf.sigma * Mpsi
        new, mu = solve(b, eye, forces=True)
        change = np.abs(new - psi).max() / np.abs(new).max()
        psi = new
        Mpsi = np.asarray(itf.M @ psi)
        Kpsi = b + itf.sigma * Mpsi - itf.G.T @ mu
        if change < tol or (iterations is not None and it == iterations):
            return psi, it, Mpsi, Kpsi
    if iterations is not None:  # iterations == 0
        return psi, 0, Mpsi, Kpsi
    raise FetorsionError(f"constraint modes did not converge ({change:.2g} after {PSI_MAX_ITER} iterations); "
                         "the shift is too close to the fixed-interface frequencies")


def _constraint_modes_shared(itf: Interface, psi: np.ndarray, kpsi: np.ndarray):
    """The constraint modes after one fixed-point step, written into ``psi`` and ``kpsi``
    (K Ψ), from the block solve W₁ = A_c M Ψ_σ (G W₁ = 0) that is also the first block of the
    interior Krylov space started from Ψ_σ. Returns (M Ψ, [W₁, M W₁, K W₁]).

    The step Ψ_1 = solve(−σ M Ψ_σ, G Ψ = I) of :func:`_constraint_modes` equals Ψ_σ − σ W₁
    (both satisfy S Ψ + GᵀΛ = −σ M Ψ_σ and G Ψ = I), so the constraint modes and the first
    Ritz block share their solve; K W₁ = M Ψ_σ + σ M W₁ − Gᵀμ₁ and K Ψ_1 = σ M Ψ_1 − σ M Ψ_σ
    + Gᵀ(C⁻¹ + σ μ₁) = −σ² M W₁ + Gᵀ(C⁻¹ + σ μ₁) follow from the equilibria, without a sparse
    product with K. Four blocks of n × m are made here, M Ψ_σ becoming M Ψ_1 in place.
    """
    solve = prescribed_solver(itf)
    s = itf.sigma
    Cinv = scipy.linalg.cho_solve(scipy.linalg.cho_factor(itf.C), np.eye(itf.n_master_dofs))
    np.matmul(itf.Y, Cinv, out=psi)  # Ψ_σ for now
    Mpsi = np.asarray(itf.M @ psi)  # M Ψ_σ for now
    W, mu = solve(Mpsi, forces=True)
    MW = np.asarray(itf.M @ W)
    KW = s * MW
    KW += Mpsi
    _subtract_coupling(KW, itf.G, mu)
    _subtract_product(psi, W, None, s)  # Ψ_1 = Ψ_σ − σ W₁
    np.multiply(MW, -s * s, out=kpsi)
    _subtract_coupling(kpsi, itf.G, -(Cinv + s * mu))
    _subtract_product(Mpsi, MW, None, s)  # M Ψ_1 = M Ψ_σ − σ M W₁
    return Mpsi, [W, MW, KW]


def fixed_interface_modes(itf: Interface, count: int, tol: float = EIGEN_TOL, seed: int = 0):
    """The ``count`` lowest modes with every master held: (ω² rad²/s², Φ n × count, M-orthonormal)."""
    solve = prescribed_solver(itf)
    rng = np.random.default_rng(seed)
    with numpy_blas_threads(1):
        theta, phi = block_lanczos(lambda b: solve(b), itf.M, count, rng, tol=tol,
                                   project=lambda V: solve(itf.M @ V))
    w2 = itf.sigma + 1.0 / theta
    order = np.argsort(w2)
    return w2[order], phi[:, order]


@dataclass
class ReducedModel:
    """A Craig–Bampton model: coordinates (q: 6 per master, then η: one per fixed-interface mode).

    Attributes
    ----------
    K, M : ndarray (r, r)
        Reduced stiffness (N/m, N, N·m per unit coordinate) and mass.
    n_master_dofs : int
        Length of q (the first coordinates).
    fixed_interface_hz : ndarray
        Frequencies of the kept fixed-interface modes (for Ritz vectors: their Ritz frequencies), Hz.
    basis : ndarray (n, r), optional
        [Ψ Φ]: u = basis @ z expands a reduced solution onto the full model's DOF.
    """

    K: np.ndarray
    M: np.ndarray
    n_master_dofs: int
    fixed_interface_hz: np.ndarray
    basis: np.ndarray | None = None
    timings_s: dict[str, float] = field(default_factory=dict)
    psi_iterations: int = 0
    #: K [Ψ Φ] (n × r), the nodal forces of each basis vector (N per unit coordinate), kept with
    #: the basis: the section resultants are sums of its rows.
    basis_forces: np.ndarray | None = None
    #: ``recover`` (a linear map of nodal forces) of K [Ψ Φ], (…, r), when one was given to
    #: :func:`craig_bampton`; ``basis_forces`` is then not kept.
    recovered: np.ndarray | None = None

    @property
    def size(self) -> int:
        return self.K.shape[0]


#: Krylov blocks of interface Ritz vectors (6 per master each) kept by default. On the
#: Peugeot GLX (60 k tets, 11 masters) 3 blocks (198 vectors, 264 DOF) put the first 12
#: elastic modes within 1.6e-5 of the full model free and in bearings, where 150
#: fixed-interface eigenmodes (216 DOF) left 4.2e-4 and 48 left 3.2e-3 (docs/condensed-crank.md).
RITZ_BLOCKS = 2
#: Fixed-point steps for the constraint modes. The span would be nearly the same without
#: (Ψ − Ψ_σ lies in the first Ritz block to O(σ²)), but one step makes the rigid-body motions
#: exact to ~1e-12 in ω² (without it a rigid end tie left one at ω² ~ 3e-6 of the first elastic
#: mode), which static loads and the zero-frequency checks rely on.
PSI_ITERATIONS = 1


def craig_bampton(itf: Interface, ritz_blocks: int = RITZ_BLOCKS, modes: int = 0, keep_basis: bool = True,
                  psi_iterations: int | None = PSI_ITERATIONS, recover=None) -> ReducedModel:
    """Reduce to the masters plus interior vectors that vanish at the masters (G φ = 0).

    The interior vectors are ``ritz_blocks`` blocks of load-dependent Ritz vectors of the
    fixed-interface problem (:func:`interface_ritz_vectors`), or, with ``ritz_blocks=0``, the
    ``modes`` lowest fixed-interface eigenmodes (classical Craig–Bampton). Either way the
    reduced matrices are the exact Galerkin projection Bᵀ K B, Bᵀ M B on B = [Ψ Φ], with
    the η–η mass block the identity (Φ M-orthonormal; its stiffness block is diagonal for
    eigenmodes, full for Ritz vectors, whose Ritz frequencies ``fixed_interface_hz`` gives).

    ``recover``: a linear map of nodal forces, (n, k) ↦ (…, k) (e.g. section resultants),
    applied to K [Ψ Φ] block by block as each block is done; its result is ``recovered``
    (…, r), and the forces are never held whole (``basis_forces`` is None).
    """
    t0 = time.perf_counter()
    n, m = itf.K.shape[0], itf.n_master_dofs
    # The basis and its nodal forces are written in place, block by block, into one layout each:
    # fresh memory costs more here than the arithmetic (a first touch of a 170 MB block took
    # 0.35 s in a process holding the factor, a reused one 0.02 s), so nothing is copied twice.
    width = m * (1 + ritz_blocks) if ritz_blocks else m + modes
    # With a recovery map and the shared first solve the forces stream: K Ψ goes once Ψ's rows
    # are taken, and each Ritz block's K Q once the later blocks no longer need it (478 k DOF,
    # 90 master DOF: 1 GB less at the reduction's peak).
    stream = recover is not None and bool(ritz_blocks) and psi_iterations == 1
    basis = np.empty((n, width))
    forces = None if stream else np.empty((n, width))
    Mpsi, Kpsi, first, its = _constraint_block(itf, basis, forces, psi_iterations,
                                               bool(ritz_blocks) and psi_iterations == 1, stream)
    psi = basis[:, :m]
    Kpp, Mpp = psi.T @ Kpsi, psi.T @ Mpsi
    parts, cross = [], []  # with streaming: the recovered rows and Φᵀ K Ψ = (K Φ)ᵀ Ψ, block by block
    if stream:
        parts.append(recover(Kpsi))
        del Kpsi

    def done(a, e, KB):  # a Ritz block's nodal forces, the last time they are at hand
        cross.append(KB.T @ psi)
        parts.append(recover(KB))

    t1 = time.perf_counter()
    if ritz_blocks:
        # M Ψ starts the Krylov space unless its first block is solved already; Φᵀ M Ψ then comes
        # from the Ritz step's own M Φ, and M Ψ's memory goes before the Ritz step's solve
        start, Mpsi = (Mpsi if first is None else None), None
        k, Kq, Mqp = interface_ritz_vectors(itf, psi, ritz_blocks, mpsi=start, first=first,
                                            out=(basis[:, m:], None if stream else forces[:, m:]),
                                            on_forces=done if stream else None)
        del start
        w2 = scipy.linalg.eigvalsh(Kq)
    else:
        w2, phi = fixed_interface_modes(itf, modes) if modes else (np.zeros(0), np.zeros((n, 0)))
        Kq, k = np.diag(w2), len(w2)
        basis[:, m:], forces[:, m:] = phi, np.asarray(itf.K @ phi)
        Mqp = phi.T @ Mpsi
    r = m + k
    basis = basis[:, :r]  # a view: svqb may have dropped dependent directions
    if forces is not None:
        forces = forces[:, :r]
    phi = basis[:, m:]
    t2 = time.perf_counter()
    Kr, Mr = _reduced_matrices(Kpp, Mpp, np.vstack(cross) if stream else phi.T @ forces[:, :m], Kq, Mqp)
    t3 = time.perf_counter()
    hz = np.sqrt(np.abs(w2)) / (2 * np.pi)
    recovered = None
    if recover is not None:
        recovered = np.concatenate(parts, axis=-1) if stream else recover(forces)
        forces = None
    return ReducedModel(Kr, Mr, m, hz, basis if keep_basis else None,
                        {"constraint_modes": t1 - t0, "interior_vectors": t2 - t1, "projection": t3 - t2}, its,
                        forces if keep_basis else None, recovered)


def _constraint_block(itf: Interface, basis: np.ndarray, forces: np.ndarray | None, psi_iterations: int | None,
                      shared: bool, stream: bool):
    """Ψ written into basis[:, :m] (K Ψ into forces[:, :m] unless ``stream``): (M Ψ, K Ψ, the
    first Ritz block [W, M W, K W] when ``shared`` solved it too else None, fixed-point steps)."""
    m = itf.n_master_dofs
    if shared:
        # Ψ_1 = Ψ_σ − σ W₁ with W₁ = A_c M Ψ_σ, the first Krylov block: one block solve gives both
        Kpsi = np.empty((basis.shape[0], m)) if stream else forces[:, :m]
        Mpsi, first = _constraint_modes_shared(itf, basis[:, :m], Kpsi)
        return Mpsi, Kpsi, first, 1
    psi, its, Mpsi, Kpsi = _constraint_modes(itf, PSI_TOL, psi_iterations)
    basis[:, :m], forces[:, :m] = psi, Kpsi
    return Mpsi, forces[:, :m], None, its


def _reduced_matrices(Kpp: np.ndarray, Mpp: np.ndarray, Kqp: np.ndarray, Kq: np.ndarray, Mqp: np.ndarray):
    """The reduced (K, M) on [Ψ Φ] from their blocks, symmetrised; the η–η mass block is the identity."""
    m, r = Kpp.shape[0], Kpp.shape[0] + Kq.shape[0]
    Kr, Mr = np.zeros((r, r)), np.zeros((r, r))
    Kr[:m, :m] = Kpp
    Kr[m:, :m] = Kqp
    Kr[:m, m:] = Kr[m:, :m].T
    Kr[m:, m:] = Kq
    Mr[:m, :m] = Mpp
    Mr[m:, :m] = Mqp
    Mr[:m, m:] = Mr[m:, :m].T
    Mr[m:, m:] = np.eye(r - m)
    return 0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T)


class _MassWithMasters:
    """M + Gᵀ D_m G as an operator (``@`` on blocks), never assembled."""

    def __init__(self, M, G, Dm):
        self.M, self.G, self.Dm, self.shape = M, G, Dm, M.shape

    def __matmul__(self, V):
        return self.M @ V + self.G.T @ (self.Dm @ (self.G @ V))


def supported_solver(itf: Interface, Dk: np.ndarray, Dm: np.ndarray, held: np.ndarray):
    """x = solve(b) for (S + Gᵀ(D_k − σD_m)G) x = b − Gᵀ Eᵀλ, E G x = 0, E = the held master DOF."""
    m = itf.n_master_dofs
    D = Dk - itf.sigma * Dm
    E = np.eye(m)[np.asarray(held, dtype=np.int64)]
    ne = len(E)
    A = np.block([[np.eye(m) + itf.C @ D, itf.C @ E.T], [E, np.zeros((ne, ne))]])
    lu = scipy.linalg.lu_factor(A)

    def solve(b):
        x0 = np.asarray(itf.solve(b))
        z0 = itf.G @ x0
        rhs = np.concatenate([z0, np.zeros((ne,) + z0.shape[1:])])
        sol = scipy.linalg.lu_solve(lu, rhs)
        mu = D @ sol[:m] + E.T @ sol[m:]
        _subtract_product(x0, itf.Y, mu)  # the solve's own fresh array
        return x0

    return solve


def supported_modes(itf: Interface, count: int, Dk=None, Dm=None, held=(), tol: float = EIGEN_TOL, seed: int = 0,
                    start=None):
    """Lowest ``count`` modes of the FULL model with springs D_k (N/m …), masses D_m and held
    DOF on the masters: (ω² rad²/s² ascending, vectors n × count, M-orthonormal in M + GᵀD_mG).

    Zero-frequency modes (the motions the supports leave free) are included. ``start``
    (n × p): approximate mode shapes to start the block Lanczos from (e.g. the condensed
    crank's, expanded), else a random block.
    """
    m = itf.n_master_dofs
    Dk = np.zeros((m, m)) if Dk is None else np.asarray(Dk, float)
    Dm = np.zeros((m, m)) if Dm is None else np.asarray(Dm, float)
    solve = supported_solver(itf, Dk, Dm, held)
    Mop = _MassWithMasters(itf.M, itf.G, Dm)
    rng = np.random.default_rng(seed)
    with numpy_blas_threads(1):
        # the random start needs mapping into the constrained operator's range; a start from the
        # condensed model with the same supports lies in it already (G Ψ = I, G Φ = 0)
        project = (lambda V: solve(Mop @ V)) if start is None or len(held) else None
        theta, X = block_lanczos(solve, Mop, count, rng, tol=tol, project=project, start=start)
    w2 = itf.sigma + 1.0 / theta
    order = np.argsort(w2)
    return w2[order], X[:, order]


def ritz_error_bounds(itf: Interface, w2: np.ndarray, X: np.ndarray, Dk=None, Dm=None, held=()):
    """Guaranteed bounds on the relative frequency error of approximate modes (ω², X n × k,
    M-orthonormal in M + GᵀD_mG) of the full model with the same supports, from one block solve.

    In the shift-invert operator A = S⁻¹M̃ (self-adjoint in the M̃ inner product) a Ritz pair
    (θ = 1/(ω² − σ), x) with residual ρ = ‖A x − θ x‖_M̃ has an exact eigenvalue within ρ of θ
    (Krylov–Weinstein; Parlett, The Symmetric Eigenvalue Problem, thm 4.5.1), so the exact
    ω² lies in [σ + 1/(θ + ρ), σ + 1/(θ − ρ)]. Returns (bound, ρ/θ) per mode: the largest
    relative frequency change over that interval (inf where θ ≤ ρ), and the residual.
    """
    m = itf.n_master_dofs
    Dk = np.zeros((m, m)) if Dk is None else np.asarray(Dk, float)
    Dm = np.zeros((m, m)) if Dm is None else np.asarray(Dm, float)
    solve = supported_solver(itf, Dk, Dm, held)
    Mop = _MassWithMasters(itf.M, itf.G, Dm)
    theta = 1.0 / (np.asarray(w2, float) - itf.sigma)
    R = np.asarray(solve(Mop @ X)) - X * theta
    rho = np.sqrt(np.abs(np.einsum("ij,ij->j", R, Mop @ R)))
    w2 = np.asarray(w2, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        lo = itf.sigma + 1.0 / (theta + rho)
        hi = np.where(theta > rho, itf.sigma + 1.0 / (theta - rho), np.inf)
        bound = np.maximum(np.abs(np.sqrt(np.clip(lo, 0, None) / w2) - 1), np.abs(np.sqrt(hi / w2) - 1))
    return bound, rho / theta


def supported_matrices(red: ReducedModel, Dk: np.ndarray | None = None, Dm: np.ndarray | None = None):
    """(K, M) of the reduced model with springs ``Dk`` and masses ``Dm`` added on the masters' DOF."""
    m = red.n_master_dofs
    K, M = red.K.copy(), red.M.copy()
    if Dk is not None:
        K[:m, :m] += Dk
    if Dm is not None:
        M[:m, :m] += Dm
    return K, M


def reduced_modes(red: ReducedModel, Dk: np.ndarray | None = None, Dm: np.ndarray | None = None,
                  held: np.ndarray | Sequence[int] = ()):
    """All modes of the reduced model with the same supports: (ω² ascending, vectors r × k over the kept DOF, kept)."""
    K, M = supported_matrices(red, Dk, Dm)
    keep = np.setdiff1d(np.arange(red.size), np.asarray(held, dtype=np.int64))
    w2, V = scipy.linalg.eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)])
    return w2, V, keep


def interface_ritz_vectors(itf: Interface, psi: np.ndarray, blocks: int, drop: float = ORTHO_DROP,
                           mpsi: np.ndarray | None = None, first=None, out=None, on_forces=None):
    """Load-dependent Ritz vectors of the fixed-interface problem: an M-orthonormal basis Q of
    the block Krylov space A_c M Ψ, (A_c M)² Ψ, … (``blocks`` blocks), A_c = S⁻¹ restricted to
    G x = 0: (k, Qᵀ K Q, Qᵀ M Ψ), with Q and K Q written into the first k columns of ``out`` =
    (Q, K Q), arrays of n × (``blocks`` · Ψ's columns) (made here when not given; k is fewer where
    a block was numerically dependent).

    K Q comes from each block solve's equilibrium (S W + Gᵀ μ = M V ⇒ K W = M V + σ M W − Gᵀ μ)
    carried through the orthogonalisation, not from a sparse product with K: the dense
    updates cost a fraction of one. ``first``: a list [W, M W, K W] of the first block, emptied
    here, when the caller has solved it already (:func:`_constraint_modes_shared`); the space is
    then started from the block that W solves for, not from ``psi``. ``out`` = (Q, None) with ``on_forces``: K Q is
    not kept; each block's K Q is handed to ``on_forces(first column, end column, K Q block)``
    once no later block needs it, and dropped.
    """
    solve = prescribed_solver(itf)
    n, m = psi.shape
    Q, KQ = out if out is not None else (np.empty((n, blocks * m)), np.empty((n, blocks * m)))
    MV = np.asarray(itf.M @ psi) if mpsi is None else mpsi
    mbasis, kq, spans, j = [], [], [], 0
    Kq, Mqp = np.zeros((blocks * m, blocks * m)), np.zeros((blocks * m, m))
    for b in range(blocks):
        if b == 0 and first is not None:
            W, MW, KW = first
            first.clear()  # the caller's list: the block's memory goes when it is done here
        else:
            W, mu = solve(MV, forces=True)
            MW = np.asarray(itf.M @ W)
            KW = itf.sigma * MW
            KW += MV
            _subtract_coupling(KW, itf.G, mu)
        for _ in range(2):
            for (a, e), MB, KB in zip(spans, mbasis, kq):
                c = MB.T @ W
                _subtract_product(W, Q[:, a:e], c)
                _subtract_product(MW, MB, c)
                _subtract_product(KW, KB, c)
        C = svqb_coefficients(W, MW, drop)
        p = C.shape[1]
        np.matmul(W, C, out=Q[:, j:j + p])
        del W
        KB = np.matmul(KW, C, out=None if KQ is None else KQ[:, j:j + p])
        del KW
        Kq[:j + p, j:j + p] = Q[:, :j + p].T @ KB  # Qᵢᵀ K Qⱼ, i ≤ j: the upper triangle by blocks
        MV = MW @ C
        Mqp[j:j + p] = MV.T @ psi
        if b < blocks - 1:  # the next blocks' orthogonalisation reads M Q and K Q
            mbasis.append(MV)
            kq.append(KB)
        spans.append((j, j + p))
        if on_forces is not None and b == blocks - 1:
            for (a, e), KQb in zip(spans, kq + [KB]):
                on_forces(a, e, KQb)
        j += p
        del MW, KB  # before the next block's solve makes its own
    kq.clear()
    Kq = np.triu(Kq[:j, :j])
    return j, Kq + np.triu(Kq, 1).T, Mqp[:j]
