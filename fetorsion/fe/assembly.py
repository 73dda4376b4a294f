"""Stiffness and consistent mass of isotropic linear elasticity on curved P2 tetrahedra.

Displacement DOF numbering is interleaved, ``3 * s + i`` for scalar P2 DOF ``s`` (a mesh
node) and component ``i`` (x, y, z), which is also scikit-fem's ``ElementVector`` order.

The stiffness is built from the scalar gradient blocks

    G_e[i, a, j, b] = ∫_e ∂_i φ_a ∂_j φ_b dx

as  K_e[(a, i), (b, j)] = λ G_e[i, a, j, b] + μ G_e[j, a, i, b] + μ δ_ij Σ_k G_e[k, a, k, b],

the expansion of ∫ λ div u div v + 2 μ ε(u) : ε(v) for u = φ_b e_j, v = φ_a e_i. One
batched matrix product gives all G_e; measured on a 330 k-DOF crank this was 7× faster than
scikit-fem's generic vector form (:func:`stiffness_generic`, kept as the test reference).
The mass is ρ ∫ φ_a φ_b times the 3 × 3 identity.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .tetmesh import TetMesh

#: Quadrature order: exact for P2·P2 mass on straight tets; on the curved (quadratic-map)
#: tets of a smooth surface the remaining quadrature error is far below the discretisation error.
INTORDER = 4


def lame(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    """Lamé constants (λ, μ) in Pa from E (Pa) and ν (-)."""
    E, nu = youngs_modulus, poisson_ratio
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def skfem_mesh(mesh: TetMesh):
    """The scikit-fem ``MeshTet2`` of ``mesh`` and the map from mesh node to scalar DOF.

    scikit-fem renumbers a ten-node mesh (vertices first, then one DOF per edge), so the
    second value ``dof_of_node`` (length N, -1 for unused nodes) carries node indices and
    node sets over to DOF indices.
    """
    from skfem import MeshTet2

    m = MeshTet2(mesh.nodes.T.copy(), mesh.tets.T.astype(np.int32).copy())
    # The same bookkeeping as MeshTet2.__post_init__: vertices keep their sorted order,
    # mid-edge nodes land on the element's edge DOFs.
    dof_of_node = np.full(len(mesh.nodes), -1, dtype=np.int64)
    dof_of_node[np.unique(mesh.tets[:, :4])] = np.arange(m.nvertices)
    dof_of_node[mesh.tets[:, 4:].ravel()] = m.dofs.element_dofs[4:].T.ravel()
    return m, dof_of_node


def p2_basis(m, intorder: int = INTORDER):
    """Scalar curved-P2 basis on scikit-fem mesh ``m``."""
    from skfem import Basis, ElementTetP2

    return Basis(m, ElementTetP2(), intorder=intorder)


@dataclass(frozen=True)
class BlockPattern:
    """Sparsity of the node-to-node coupling: CSR ``indptr``/``indices`` over nodes, and for
    every (element, a, b) entry its position ``slot`` in that CSR (duplicates share slots).

    ``csr_indptr``/``csr_indices`` are the interleaved 3n × 3n CSR structure of the same
    pattern (3 × 3 blocks, explicit zeros kept, so K and M share it), and ``csr_base`` /
    ``csr_row3`` place component (i, j) of block ``slot`` at CSR position
    ``csr_base[slot] + i * csr_row3[slot] + j``.
    """

    n: int
    indptr: np.ndarray
    indices: np.ndarray
    slot: np.ndarray
    csr_indptr: np.ndarray = None
    csr_indices: np.ndarray = None
    csr_base: np.ndarray = None
    csr_row3: np.ndarray = None


def block_pattern(basis) -> BlockPattern:
    """The node-pair pattern of ``basis`` (scalar P2): one 3 × 3 block per pair in vector form.

    Summing element matrices by 3 × 3 blocks over this pattern (9× fewer index entries than
    a scalar COO of the vector problem) halved the assembly time at 240 k DOF. The
    interleaved CSR structure is built here once, so that :func:`stiffness` and :func:`mass`
    write their values straight into CSR order (no BSR-to-CSR conversion per matrix).
    """
    ed = basis.element_dofs.T.astype(np.int64)  # (E, 10)
    p, n = ed.shape[1], basis.N
    key = (np.repeat(ed, p, axis=1) * n + np.tile(ed, (1, p))).ravel()
    uniq, slot = np.unique(key, return_inverse=True)
    rows, cols = np.divmod(uniq, n)
    indptr = np.searchsorted(rows, np.arange(n + 1))
    # Row 3s + i of the CSR holds block row s's blocks in column order, 3 entries each.
    count = np.diff(indptr)
    row3 = (3 * count)[rows]
    base = 9 * indptr[rows] + 3 * (np.arange(len(rows)) - indptr[rows])
    # 32-bit indices where they fit (9 nb < 2³¹, ~70 M DOF): scipy would otherwise upcast the
    # indices to match a 64-bit indptr (a 25 M-entry copy per matrix at 342 k DOF), and every
    # later sparse product reads half the index bytes.
    idx = np.int32 if 9 * len(rows) < 2**31 else np.int64
    csr_indptr = np.concatenate([[0], np.cumsum(np.repeat(3 * count, 3))]).astype(idx)
    csr_indices = np.empty(9 * len(rows), dtype=idx)
    for i in range(3):  # three block rows and three columns: 9 vectorised writes
        for j in range(3):
            csr_indices[base + i * row3 + j] = 3 * cols + j
    return BlockPattern(n, indptr, cols.astype(np.int32), slot.ravel(), csr_indptr, csr_indices, base, row3)


def _csr(pat: BlockPattern, blocks) -> sp.csr_array:
    """The 3n × 3n CSR whose block ``slot`` has component (i, j) ``blocks(i, j)`` (length-nb
    arrays, or None for zeros)."""
    if pat.csr_indptr is None:  # a pattern built by hand without the CSR structure
        raise ValueError("BlockPattern lacks its CSR structure; build it with block_pattern()")
    data = np.zeros(len(pat.csr_indices))
    for i in range(3):
        for j in range(3):
            v = blocks(i, j)
            if v is not None:
                data[pat.csr_base + i * pat.csr_row3 + j] = v
    return sp.csr_array((data, pat.csr_indices, pat.csr_indptr), shape=(3 * pat.n, 3 * pat.n))


def stiffness(basis, youngs_modulus: float, poisson_ratio: float,
              pattern: BlockPattern | None = None) -> sp.csr_array:
    """Vector-P2 elasticity stiffness from scalar gradient blocks, N/m, interleaved DOFs.

    Parameters
    ----------
    basis : skfem.Basis
        Scalar ``ElementTetP2`` basis (:func:`p2_basis`).
    youngs_modulus : float
        E, Pa.
    poisson_ratio : float
        ν, -.
    pattern : BlockPattern, optional
        From :func:`block_pattern`, to share with :func:`mass`.
    """
    lam, mu = lame(youngs_modulus, poisson_ratio)
    pat = block_pattern(basis) if pattern is None else pattern
    # K is linear in G, so the nine scalar sums Σ_e G[e, i, ·, j, ·] are assembled first and
    # combined per node pair: the element-level λ/μ combination and its transposed copies
    # (E × 900 values, more than half the former stiffness time) are never formed. G is
    # symmetric (G[e, j, b, i, a] = G[e, i, a, j, b]), so only the six blocks i ≤ j are
    # integrated, one at a time (E × 100 values each instead of E × 900 at once); their
    # element-wise transposes give the other three.
    grads = np.stack([b[0].grad for b in basis.basis], axis=2)  # [i, e, a, q]
    nb = len(pat.indices)
    Gg = [[None] * 3 for _ in range(3)]
    for i in range(3):
        gi = grads[i] * basis.dx[:, None, :]
        for j in range(i, 3):
            Gij = np.matmul(gi, grads[j].transpose(0, 2, 1))  # [e, a, b]
            Gg[i][j] = np.bincount(pat.slot, Gij.ravel(), minlength=nb)
            if j > i:
                Gg[j][i] = np.bincount(pat.slot, Gij.transpose(0, 2, 1).ravel(), minlength=nb)
    trace = Gg[0][0] + Gg[1][1] + Gg[2][2]
    return _csr(pat, lambda i, j: lam * Gg[i][j] + mu * Gg[j][i] + (mu * trace if i == j else 0.0))


def mass_blocks(basis, density: float, pattern: BlockPattern) -> np.ndarray:
    """ρ ∫ φ_a φ_b per node pair of ``pattern`` (kg): the value every diagonal component of
    the pair's 3 × 3 mass block holds."""
    phi = np.stack([np.asarray(b[0]) for b in basis.basis], axis=1)  # (E, 10, Q)
    Me = np.matmul(phi * (density * basis.dx)[:, None, :], phi.transpose(0, 2, 1))
    return np.bincount(pattern.slot, Me.ravel(), minlength=len(pattern.indices))


def mass(basis, density: float, pattern: BlockPattern | None = None, compact: bool = False) -> sp.csr_array:
    """Consistent vector-P2 mass, kg, interleaved DOFs: ρ ∫ φ_a φ_b ⊗ I₃.

    ``pattern`` (from :func:`block_pattern`) may be shared with :func:`stiffness`; the result
    then has K's CSR structure (explicit zeros off the block diagonals), unless ``compact``:
    only the diagonal components, a third of the entries (:func:`diagonal_block_matrix`).
    """
    pat = block_pattern(basis) if pattern is None else pattern
    d = mass_blocks(basis, density, pat)
    if compact:
        return diagonal_block_matrix(pat, d)
    return _csr(pat, lambda i, j: d if i == j else None)


def diagonal_block_matrix(pat: BlockPattern, d: np.ndarray) -> sp.csr_array:
    """The 3n × 3n CSR with d[slot] · I₃ in every block of ``pat`` and nothing else stored."""
    count = np.diff(pat.indptr)
    first = pat.indptr[:-1]  # first slot of each block row
    row = np.repeat(np.arange(pat.n), count)
    # row 3r + i holds the blocks of block row r: it starts at 3·first[r] + i·count[r]
    indptr = np.empty(3 * pat.n + 1, dtype=np.int64)
    indptr[:-1] = (3 * first[:, None] + np.arange(3) * count[:, None]).ravel()
    indptr[-1] = 3 * len(d)
    offset = 2 * first[row] + np.arange(len(d))
    data = np.empty(3 * len(d))
    indices = np.empty(3 * len(d), dtype=np.int64)
    for i in range(3):
        data[offset + i * count[row]] = d
        indices[offset + i * count[row]] = 3 * pat.indices + i
    idx = np.int32 if 3 * len(d) < 2**31 else np.int64
    return sp.csr_array((data, indices.astype(idx), indptr.astype(idx)), shape=(3 * pat.n, 3 * pat.n))


def add_to_diagonal_blocks(A: sp.csr_array, pat: BlockPattern, d: np.ndarray, factor: float) -> None:
    """A += factor · (d ⊗ I₃) in place, for A on ``pat``'s CSR structure (:func:`stiffness`):
    K − σM without a second matrix of K's size."""
    for i in range(3):
        A.data[pat.csr_base + i * pat.csr_row3 + i] += factor * d


def stiffness_generic(m, youngs_modulus: float, poisson_ratio: float, intorder: int = INTORDER):
    """The same stiffness through scikit-fem's generic vector form (slow; test reference)."""
    from skfem import Basis, ElementTetP2, ElementVector, asm
    from skfem.models.elasticity import linear_elasticity

    lam, mu = lame(youngs_modulus, poisson_ratio)
    vb = Basis(m, ElementVector(ElementTetP2()), intorder=intorder)
    return asm(linear_elasticity(lam, mu), vb).tocsr()
