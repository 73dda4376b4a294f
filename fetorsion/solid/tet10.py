"""The curved ten-node tetrahedron (VTK order): the check of its Jacobian, and the
straightening of folded ones.

Snapping midside nodes onto a fillet or drilling smaller than the element folds a few curved
elements; :func:`straighten_folded` gives just those straight edges, :func:`jacobian_positive`
checks the result (:func:`fetorsion.solid.mesh.mesh_model` with ``untangle="straighten"``).
"""

from __future__ import annotations

import numpy as np


#: Rounds of straightening: a straightened element can fold a neighbour, which the next round takes.
STRAIGHTEN_ROUNDS = 4
#: Order of the barycentric lattice at which a curved tet's Jacobian is checked (35 points).
JACOBIAN_LATTICE = 4
#: VTK tet10 midside node k lies on the edge between vertices TET10_EDGES[k].
TET10_EDGES = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])


def _p2_gradients(xi: np.ndarray) -> np.ndarray:
    """Reference gradients of the ten VTK-ordered P2 shape functions at points ``xi`` (P, 3).

    Returns (P, 10, 3).
    """
    lam = np.column_stack([1.0 - xi.sum(axis=1), xi])  # barycentric (P, 4)
    dlam = np.vstack([-np.ones(3), np.eye(3)])  # ∂λ_a/∂ξ (4, 3)
    vert = (4.0 * lam - 1.0)[:, :, None] * dlam[None]
    i, j = TET10_EDGES.T
    edge = 4.0 * (lam[:, i, None] * dlam[None, j] + lam[:, j, None] * dlam[None, i])
    return np.concatenate([vert, edge], axis=1)


def _sample_points(order: int = JACOBIAN_LATTICE) -> np.ndarray:
    """Barycentric lattice of the given order on the reference tet (vertices, edges, faces, inside)."""
    g = np.arange(order + 1)
    a, b, c = np.meshgrid(g, g, g, indexing="ij")
    keep = a + b + c <= order
    return np.column_stack([a[keep], b[keep], c[keep]]) / order


def jacobian_positive(coords: np.ndarray, tets: np.ndarray, order: int = JACOBIAN_LATTICE) -> np.ndarray:
    """Whether each curved ten-node tet's Jacobian determinant is positive at a lattice of points.

    det J of a quadratic tet is a cubic polynomial; the order-4 lattice (35 points, vertices,
    edges, faces and inside) catches the folds that snapping midside nodes onto small
    fillets makes (where det J turns negative over a whole corner of the element).

    Parameters
    ----------
    coords : ndarray (N, 3)
    tets : ndarray of int (E, 10), VTK order.

    Returns
    -------
    ndarray of bool (E,)
    """
    dN = _p2_gradients(_sample_points(order))  # (P, 10, 3)
    J = np.einsum("eai,paj->epij", coords[tets], dN)
    return (np.linalg.det(J) > 0).all(axis=1)


def straighten_folded(coords: np.ndarray, tets: np.ndarray, folded: np.ndarray, rounds: int = STRAIGHTEN_ROUNDS):
    """Move the midside nodes of folded elements to their edge midpoints.

    A straight-edged tet with positive vertex orientation is valid, so each folded element
    becomes valid; a neighbour sharing a moved node gets one straight edge and is checked
    (and straightened too if it folds), for a few rounds.

    Parameters
    ----------
    coords : ndarray (N, 3)
        Node coordinates (any unit).
    tets : ndarray of int (E, 10)
        VTK order.
    folded : ndarray of bool (E,)
        Elements to straighten.
    rounds : int
        Neighbour passes.

    Returns
    -------
    coords : ndarray (N, 3)
        A new array.
    changed : ndarray of bool (E,)
        Every element with a moved node.
    """
    coords = coords.copy()
    todo = folded.copy()
    changed = np.zeros(len(tets), dtype=bool)
    for _ in range(rounds):
        mid = tets[todo, 4:]
        coords[mid.ravel()] = 0.5 * (coords[tets[todo][:, TET10_EDGES[:, 0]]]
                                     + coords[tets[todo][:, TET10_EDGES[:, 1]]]).reshape(-1, 3)
        moved = np.zeros(len(coords), dtype=bool)
        moved[mid.ravel()] = True
        touched = moved[tets].any(axis=1)
        changed |= touched
        todo = np.zeros(len(tets), dtype=bool)
        idx = np.flatnonzero(touched)
        todo[idx[~jacobian_positive(coords, tets[idx])]] = True
        if not todo.any():
            break
    return coords, changed
