"""Rigid attachments (flywheel, pulley, piston + rod) by master-DOF elimination.

Each attachment is a rigid body tied to a set of mesh nodes. Its six master DOF are the
translation t and small rotation θ of the body at its centre of mass c; a tied node at X
moves as u = t + θ × (X - c) = t - [X - c]ₓ θ. With the free DOF kept as they are, the
full displacement is u = T q, and the reduced problem is

    Tᵀ K T q = ω² (Tᵀ M T + M_body) q,

exact for a rigid body (no penalty, no Lagrange multipliers), symmetric positive
(semi-)definite as before, so the same Cholesky shift-invert solver applies.
M_body = diag(m, m, m, J) with J the 3 × 3 inertia tensor about c.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numba import njit

from ..errors import FetorsionError


@dataclass(frozen=True)
class RigidBody:
    """A rigid body tied to mesh nodes.

    Attributes
    ----------
    name : str
        Label (e.g. ``"flywheel"``).
    nodes : ndarray of int
        Mesh node indices (of the :class:`~fetorsion.fe.tetmesh.TetMesh`) moving with the body.
    mass : float
        kg.
    inertia : ndarray, shape (3, 3)
        Inertia tensor about the centre of mass, axes x (crank axis), y, z, kg·m².
    centre : ndarray, shape (3,)
        Centre of mass, m.
    """

    name: str
    nodes: np.ndarray
    mass: float
    inertia: np.ndarray
    centre: np.ndarray

    @classmethod
    def axisymmetric(cls, name, nodes, mass=0.0, polar_inertia=0.0, diametral_inertia=0.0,
                     centre=(0.0, 0.0, 0.0)) -> "RigidBody":
        """A body symmetric about an axis parallel to x through ``centre``.

        Parameters
        ----------
        name : str
        nodes : array of int
            Tied mesh nodes.
        mass : float
            kg.
        polar_inertia : float
            About the body's own axis (parallel to x through the centre of mass), kg·m².
        diametral_inertia : float
            About any diameter through the centre of mass, kg·m².
        centre : sequence of 3 floats
            Centre of mass, m.
        """
        J = np.diag([polar_inertia, diametral_inertia, diametral_inertia]).astype(float)
        return cls(name, np.asarray(nodes, dtype=np.int64), float(mass), J, np.asarray(centre, dtype=float))


def from_attachment(att, nodes: np.ndarray, node_xyz: np.ndarray, outward: float = 0.0,
                    about_crank_axis: bool = False) -> RigidBody:
    """A :class:`RigidBody` from a :class:`fetorsion.description.model.Attachment` tied to ``nodes``.

    Parameters
    ----------
    att : fetorsion.description.model.Attachment
        Mass (kg), polar and diametral inertia (kg·m²), axial offset of the centre of mass
        from the face (m, positive outwards).
    nodes : array of int
        Mesh nodes of the face the body is fixed to.
    node_xyz : ndarray, shape (N, 3)
        All mesh node coordinates, m.
    outward : float
        +1 if the face's outward normal is +x (rear face), -1 if -x (front face),
        0 for pins (no offset applied).
    about_crank_axis : bool
        True when ``att.polar_inertia`` is about the crank axis (the ``pins`` convention:
        equivalent inertia per cylinder); the parallel-axis part m r² is then taken off so
        that the body's inertia about the crank axis equals ``att.polar_inertia``.

    The body's axis is the crank axis for end faces and the x-parallel line through the
    nodes' centroid for pins.
    """
    nodes = np.asarray(nodes, dtype=np.int64)
    c = node_xyz[nodes].mean(axis=0)
    c[0] += outward * att.offset
    if outward != 0.0:
        c[1:] = 0.0  # an end-face body sits on the crank axis, whatever the face's node pattern
    polar = att.polar_inertia
    if about_crank_axis:
        polar = polar - att.mass * float(c[1] ** 2 + c[2] ** 2)
        if polar < 0:
            raise FetorsionError(f"attachment {att.name!r}: polar inertia about the crank axis "
                                 f"{att.polar_inertia} kg·m² is below m·r² of its mass at the pin")
    return RigidBody.axisymmetric(att.name, nodes, att.mass, polar, att.diametral_inertia, c)


def _skew(r: np.ndarray) -> np.ndarray:
    """[r]ₓ for each row of r (n, 3): [r]ₓ θ = r × θ; shape (n, 3, 3)."""
    z = np.zeros(len(r))
    x, y, w = r.T
    return np.stack([np.stack([z, -w, y], -1), np.stack([w, z, -x], -1), np.stack([-y, x, z], -1)], 1)


def rigid_rows(xyz: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """Per node the 3 × 6 map from (t, θ) at ``centre`` to its displacement: [I, -[X - c]ₓ]."""
    R = np.empty((len(xyz), 3, 6))
    R[:, :, :3] = np.eye(3)
    R[:, :, 3:] = -_skew(xyz - centre)
    return R


@dataclass
class Reduction:
    """u = T q: the full interleaved displacement from the reduced DOF q.

    q holds the untied DOF (in their original order) then 6 DOF per body
    (tx, ty, tz, θx, θy, θz at the body's centre of mass). ``free`` and ``tied`` are the full
    DOF indices of the two kinds, ``R`` (tied × 6 bodies) the rigid map of the tied ones.
    """

    T: sp.csr_array
    n_free: int
    body_mass: sp.csr_array  # reduced-size, the bodies' 6 × 6 blocks
    free: np.ndarray = None
    tied: np.ndarray = None
    R: sp.csr_array = None

    @property
    def body_blocks(self) -> np.ndarray:
        """The bodies' 6 × 6 mass blocks as one dense block-diagonal array (``body_mass``'s
        body rows and columns), for :meth:`reduce`."""
        return self.body_mass[self.n_free:, self.n_free:].toarray()

    def groups(self) -> np.ndarray:
        """Pointers of the reduced DOF groups (three per untied node, six per body), for
        :func:`fetorsion.fe.eigen.factorize`."""
        return np.concatenate([np.arange(0, self.n_free, 3), self.n_free + 6 * np.arange(self.R.shape[1] // 6 + 1)])

    def rigid_motions(self, full: np.ndarray) -> np.ndarray:
        """The reduced DOF of the rigid-body motions whose full DOF are ``full`` (n × 6, about
        the origin): the untied DOF as they are, each body's (t, θ) at its centre."""
        bodies = []
        for k in range(self.R.shape[1] // 6):
            bodies.append(self._body_motion(full, k))
        return np.vstack([full[self.free], *bodies]) if bodies else full[self.free]

    def _body_motion(self, full: np.ndarray, k: int) -> np.ndarray:
        """(t, θ) at body k's centre for each rigid motion: least squares over its tied DOF
        (exact for rigid motions, whose restriction to the body is R's column space)."""
        Rk = self.R[:, 6 * k:6 * k + 6].toarray()
        rows = np.flatnonzero(np.abs(Rk).sum(axis=1))
        return np.linalg.lstsq(Rk[rows], full[self.tied[rows]], rcond=None)[0]

    def reduce(self, A: sp.csr_array, bodies: np.ndarray | None = None) -> sp.csr_array:
        """Tᵀ A T, symmetric for a symmetric A, plus ``bodies`` (6 per body square, dense) on the
        bodies' DOF when given (their masses: no second sparse matrix and addition).

        By blocks, [[A_ff, A_ft R], [Rᵀ A_tf, Rᵀ A_tt R]]: A_ff is A's CSR arrays with the tied
        rows and columns masked out and the few coupling entries A_ft R placed after each row's
        own, written straight into CSR order (the sparse triple product and its symmetrisation
        took 1.9 s per matrix at 320 k DOF, scipy's block stacking 1.6 s; the masking done with
        numpy's whole-array passes 1.9 s, two compiled passes over the rows (:func:`_fill_free_rows`) 0.2 s).
        """
        A = sp.csr_array(A)
        A.sort_indices()
        nf = self.n_free
        new = np.full(A.shape[0], -1, dtype=np.int64)
        new[self.free] = np.arange(nf)
        B = (self.R.T @ A[self.tied]).tocsr()  # bodies × n: Rᵀ A_t·
        Bf = sp.csr_array(B[:, self.free])
        Bf.sort_indices()
        BfT = sp.csr_array(Bf.T)
        BfT.sort_indices()
        D = (B[:, self.tied] @ self.R).toarray()
        D = 0.5 * (D + D.T)
        if bodies is not None:
            D = D + bodies
        # free rows: A_ff's entries (columns < nf, ascending), then A_ft R's (columns ≥ nf); then
        # the body rows: Rᵀ A_tf and Rᵀ A_tt R (dense, 6 per body), written into the same arrays
        b_ptr, b_idx = BfT.indptr.astype(np.int64), BfT.indices.astype(np.int64)
        top = _free_row_lengths(A.indptr, A.indices, new, nf, b_ptr)
        nb = D.shape[0]
        bottom_len = np.diff(Bf.indptr) + nb
        indptr = np.concatenate([top, top[-1] + np.cumsum(bottom_len)])
        idx = np.int32 if indptr[-1] < 2**31 else np.int64
        indices = np.empty(indptr[-1], dtype=idx)
        data = np.empty(indptr[-1])
        _fill_free_rows(A.indptr, A.indices, A.data, new, nf, b_ptr, b_idx, BfT.data, top, indices, data)
        for i in range(nb):
            cols = np.concatenate([Bf.indices[Bf.indptr[i]:Bf.indptr[i + 1]], nf + np.arange(nb)])
            indices[indptr[nf + i]:indptr[nf + i + 1]] = cols
            data[indptr[nf + i]:indptr[nf + i + 1]] = np.concatenate([Bf.data[Bf.indptr[i]:Bf.indptr[i + 1]], D[i]])
        return sp.csr_array((data, indices, indptr.astype(idx)), shape=(nf + nb, nf + nb))


def reduction(n_dofs: int, bodies: list[RigidBody], node_xyz: np.ndarray) -> Reduction:
    """Build T for ``bodies``, whose ``nodes`` are scalar DOF (node) indices with coordinates node_xyz.

    Parameters
    ----------
    n_dofs : int
        Size of the full interleaved displacement vector (3 × nodes).
    bodies : list of RigidBody
        ``nodes`` given as DOF-numbered nodes; sets must not overlap.
    node_xyz : ndarray, shape (n_dofs / 3, 3)
        Coordinates of every DOF-numbered node, m.
    """
    tied_nodes = np.concatenate([b.nodes for b in bodies]) if bodies else np.zeros(0, np.int64)
    if len(np.unique(tied_nodes)) != len(tied_nodes):
        raise FetorsionError("two attachments share mesh nodes; give each its own face or node set")
    tied = (3 * tied_nodes[:, None] + np.arange(3)).ravel()
    free = np.setdiff1d(np.arange(n_dofs), tied)
    n_free = len(free)
    rows, cols, vals = [], [], []
    blocks = []
    for k, b in enumerate(bodies):
        R = rigid_rows(node_xyz[b.nodes], b.centre)  # (n, 3, 6)
        r = np.broadcast_to((3 * b.nodes[:, None] + np.arange(3))[:, :, None], R.shape)
        c = np.broadcast_to(6 * k + np.arange(6), R.shape)
        rows.append(r.ravel()), cols.append(c.ravel()), vals.append(R.ravel())
        Mb = np.zeros((6, 6))
        Mb[:3, :3] = b.mass * np.eye(3)
        Mb[3:, 3:] = b.inertia
        blocks.append(Mb)
    n_body = 6 * len(bodies)
    rows = np.concatenate(rows) if bodies else np.zeros(0, np.int64)
    cols = np.concatenate(cols) if bodies else np.zeros(0, np.int64)
    vals = np.concatenate(vals) if bodies else np.zeros(0)
    # tied DOF index -> its row in R (tied is the concatenation of the bodies' DOFs, in order)
    position = np.empty(n_dofs, dtype=np.int64)
    position[tied] = np.arange(len(tied))
    R = sp.csr_array((vals, (position[rows], cols)), shape=(len(tied), n_body))
    R.eliminate_zeros()
    T = sp.csr_array((np.concatenate([np.ones(n_free), vals]),
                      (np.concatenate([free, rows]), np.concatenate([np.arange(n_free), n_free + cols]))),
                     shape=(n_dofs, n_free + n_body))
    T.eliminate_zeros()
    n_red = n_free + n_body
    body_mass = sp.block_diag([sp.csr_array((n_free, n_free))] + blocks, format="csr") if bodies \
        else sp.csr_array((n_red, n_red))
    return Reduction(T, n_free, sp.csr_array(body_mass), free, tied, R)


@njit(cache=True)
def _free_row_lengths(indptr, indices, new, nf, b_indptr):
    """CSR row pointers of the free rows of (indptr, indices) renumbered by ``new`` (-1: tied,
    dropped with its columns), each followed by its row of the CSR ``b_indptr``: one pass."""
    out = np.zeros(nf + 1, np.int64)
    for r in range(len(indptr) - 1):
        nr = new[r]
        if nr < 0:
            continue
        c = 0
        for k in range(indptr[r], indptr[r + 1]):
            if new[indices[k]] >= 0:
                c += 1
        out[nr + 1] = c + b_indptr[nr + 1] - b_indptr[nr]
    for r in range(nf):
        out[r + 1] += out[r]
    return out


@njit(cache=True)
def _fill_free_rows(indptr, indices, data, new, nf, b_indptr, b_indices, b_data, out_ptr, out_idx, out_data):
    """Writes the rows :func:`_free_row_lengths` counted into ``out_idx``/``out_data`` at
    ``out_ptr``: each free row's kept entries renumbered (ascending where A's are), then its
    row of the b CSR shifted by ``nf`` columns."""
    for r in range(len(indptr) - 1):
        nr = new[r]
        if nr < 0:
            continue
        p = out_ptr[nr]
        for k in range(indptr[r], indptr[r + 1]):
            j = new[indices[k]]
            if j >= 0:
                out_idx[p] = j
                out_data[p] = data[k]
                p += 1
        for k in range(b_indptr[nr], b_indptr[nr + 1]):
            out_idx[p] = b_indices[k] + nf
            out_data[p] = b_data[k]
            p += 1


def without_block(A: sp.csr_matrix, start: int, count: int) -> sp.csr_matrix:
    """A CSR matrix with its rows and columns ``start`` to ``start + count`` removed (a held
    body's DOF), by one mask over its entries: ``A[keep][:, keep]`` sliced twice and converted
    cost 0.3 s a throw, this 0.03 s."""
    A = sp.csr_matrix(A)
    n = A.shape[0]
    stop = start + count
    row = np.repeat(np.arange(n), np.diff(A.indptr))
    keep = ((A.indices < start) | (A.indices >= stop)) & ((row < start) | (row >= stop))
    cols = A.indices[keep]
    cols = np.where(cols >= stop, cols - count, cols).astype(A.indices.dtype)
    lengths = np.bincount(row[keep], minlength=n)
    lengths = np.r_[lengths[:start], lengths[stop:]]
    indptr = np.zeros(n - count + 1, dtype=A.indptr.dtype)
    np.cumsum(lengths, out=indptr[1:])
    return sp.csr_matrix((A.data[keep], cols, indptr), shape=(n - count, A.shape[1] - count))

