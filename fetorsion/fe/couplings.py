"""Distributing couplings (RBE3-type): a master point whose six DOF follow a set of nodes.

A master at point p carries the translation t and small rotation θ of the least-squares
rigid fit of its slave nodes' displacements,

    q = (t, θ) = (Rᵀ R)⁻¹ Rᵀ u_s,      R = [I, −[X − p]ₓ] stacked over the slaves,

one row block G_c = (RᵀR)⁻¹Rᵀ of a sparse 6·m × n matrix G. The master is a *dependent*
quantity: nothing ties the slaves to each other, so a coupling adds no stiffness (a rigid
ring would: +1.2 % on the Peugeot f1). Loads put on the master reach the slaves as Gᵀ F, which
is the statically equivalent distribution of the fit; springs and masses on the master
(bearings, attachments) enter the full model as Gᵀ D G, a low-rank term that
:mod:`fetorsion.fe.substructure` never assembles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..errors import FetorsionError
from .rigid import rigid_rows

#: The six DOF of a master, in order.
DOF_NAMES = ("tx", "ty", "tz", "rx", "ry", "rz")


@dataclass(frozen=True)
class Master:
    """A master point and the mesh nodes it is coupled to.

    Attributes
    ----------
    label : str
        ``J1`` … (main journal centres), ``P1`` … (pin centres), ``front``, ``rear``.
    position : ndarray, shape (3,)
        m.
    nodes : ndarray of int
        Mesh node indices of the slaves.
    """

    label: str
    position: np.ndarray
    nodes: np.ndarray


def fit_rows(slave_xyz: np.ndarray, position: np.ndarray) -> np.ndarray:
    """The 6 × 3n map (RᵀR)⁻¹Rᵀ from slave displacements (interleaved x, y, z) to (t, θ) at ``position``."""
    R = rigid_rows(slave_xyz, position).reshape(-1, 6)
    A = R.T @ R
    if np.linalg.cond(A) > 1e12:
        raise FetorsionError("a coupling's nodes do not fix all six rigid motions (collinear or too few)")
    return np.linalg.solve(A, R.T)


def coupling_matrix(masters: list[Master], dof_of_node: np.ndarray, dof_xyz: np.ndarray) -> sp.csr_array:
    """G (6·len(masters) × 3·len(dof_xyz)): master DOF from the interleaved nodal displacement.

    Parameters
    ----------
    masters : list of Master
    dof_of_node : ndarray of int
        Mesh node index → DOF-node index (−1 for nodes no element uses).
    dof_xyz : ndarray, shape (N, 3)
        Coordinates of the DOF-nodes, m.
    """
    rows, cols, vals = [], [], []
    for k, mst in enumerate(masters):
        d = dof_of_node[np.asarray(mst.nodes, dtype=np.int64)]
        if len(d) < 3 or (d < 0).any():
            raise FetorsionError(f"coupling {mst.label}: its node set is empty or not in the mesh")
        Gc = fit_rows(dof_xyz[d], np.asarray(mst.position, float))
        c = (3 * d[:, None] + np.arange(3)).ravel()
        rows.append(np.repeat(6 * k + np.arange(6), len(c)))
        cols.append(np.tile(c, 6))
        vals.append(Gc.ravel())
    n = 3 * len(dof_xyz)
    return sp.csr_array((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                        shape=(6 * len(masters), n))


def point_mass_block(mass: float, inertia: np.ndarray, centre: np.ndarray, position: np.ndarray) -> np.ndarray:
    """6 × 6 mass matrix, at a master at ``position``, of a rigid body (kg, kg·m² about its centre ``centre``).

    The body's centre moves as t + θ × (c − p), so M = Lᵀ diag(m I, J) L with L = [I, −[c − p]ₓ; 0, I].
    """
    L = np.eye(6)
    L[:3, 3:] = rigid_rows(np.asarray(centre, float)[None], np.asarray(position, float))[0, :, 3:]
    B = np.zeros((6, 6))
    B[:3, :3] = mass * np.eye(3)
    B[3:, 3:] = inertia
    return L.T @ B @ L
