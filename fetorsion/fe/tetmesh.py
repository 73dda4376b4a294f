"""Second-order tetrahedral meshes as plain arrays: what the modal solver takes in.

A :class:`TetMesh` is the hand-over between whoever builds a mesh (the crank mesher of
``fetorsion.solid.mesh``, Gmsh directly, a file read by meshio) and :func:`fetorsion.fe.modal.modal`:
node coordinates in m, ten-node tetrahedra in meshio/VTK node order, and named node sets
(end faces, pin surfaces, journals) used for attachments and mode identification.

VTK/meshio ``tetra10`` order: vertices 0-3, then the mid-edge nodes of edges
(0,1), (1,2), (0,2), (0,3), (1,3), (2,3). Gmsh's native order swaps the last two;
:func:`cylinder_mesh` converts.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import FetorsionError

#: Gmsh tet10 node order -> VTK/meshio order (Gmsh lists edge (2,3) before (1,3)).
GMSH_TO_VTK_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])


@dataclass
class TetMesh:
    """A curved quadratic tetrahedral mesh.

    Attributes
    ----------
    nodes : ndarray, shape (N, 3)
        Node coordinates, m. The crank axis is the x axis through the origin.
    tets : ndarray of int, shape (E, 10)
        Ten-node tetrahedra in meshio/VTK order, indices into ``nodes``.
    node_sets : dict of str to ndarray of int
        Named node sets (e.g. ``front_face``, ``rear_face``, ``pin_1``, ``journal_1``),
        indices into ``nodes``.
    """

    nodes: np.ndarray
    tets: np.ndarray
    node_sets: dict[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self):
        self.nodes = np.ascontiguousarray(self.nodes, dtype=float)
        self.tets = np.ascontiguousarray(self.tets, dtype=np.int64)
        if self.nodes.ndim != 2 or self.nodes.shape[1] != 3:
            raise FetorsionError(f"mesh nodes must have shape (N, 3), got {self.nodes.shape}")
        if self.tets.ndim != 2 or self.tets.shape[1] != 10:
            raise FetorsionError(f"mesh cells must be ten-node tetrahedra (E, 10), got {self.tets.shape}")
        if self.tets.min() < 0 or self.tets.max() >= len(self.nodes):
            raise FetorsionError("mesh cells refer to nodes that do not exist")
        self.node_sets = {k: np.unique(np.asarray(v, dtype=np.int64)) for k, v in self.node_sets.items()}

    @property
    def n_nodes(self) -> int:
        """Nodes used by the tetrahedra (unused nodes, e.g. Gmsh geometry points, do not count)."""
        return int(np.unique(self.tets).size)

    @property
    def n_elements(self) -> int:
        return len(self.tets)

    def nodes_where(self, predicate) -> np.ndarray:
        """Indices of the used nodes whose coordinates satisfy ``predicate(x, y, z)`` (m)."""
        used = np.unique(self.tets)
        x, y, z = self.nodes[used].T
        return used[np.asarray(predicate(x, y, z), dtype=bool)]


def cylinder_mesh(length: float, diameter: float, size: float, *, x0: float = 0.0,
                  face_tol: float | None = None) -> TetMesh:
    """A solid round bar along +x meshed by Gmsh with curved ten-node tetrahedra.

    Parameters
    ----------
    length : float
        Bar length, m; the bar spans x0 ≤ x ≤ x0 + length.
    diameter : float
        Bar diameter, m.
    size : float
        Target element size, m.
    x0 : float
        Front face position, m.
    face_tol : float, optional
        Distance within which a node belongs to an end face, m (default 1e-9 · length).

    Returns
    -------
    TetMesh
        With node sets ``front_face`` (x = x0) and ``rear_face`` (x = x0 + length).

    Examples
    --------
    >>> from fetorsion.fe.tetmesh import cylinder_mesh
    >>> m = cylinder_mesh(0.2, 0.04, 0.02)
    >>> m.tets.shape[1], len(m.node_sets["front_face"]) > 10
    (10, True)
    """
    import gmsh

    own = not gmsh.isInitialized()
    if own:
        gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("cylinder")
        gmsh.model.occ.addCylinder(x0, 0.0, 0.0, length, 0.0, 0.0, 0.5 * diameter)
        gmsh.model.occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMin", size)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        # HighOrderOptimize = 0 keeps mid-edge nodes on the true surface without moving
        # interior ones: the mapping stays valid for these convex shapes.
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        etypes, _, enodes = gmsh.model.mesh.getElements(3)
        if list(etypes) != [11]:
            raise RuntimeError(f"Gmsh produced element types {list(etypes)}, expected tet10 (11)")
        gmsh.model.remove()
    finally:
        if own:
            gmsh.finalize()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    nodes = coords.reshape(-1, 3)
    tets = index[enodes[0].astype(np.int64)].reshape(-1, 10)[:, GMSH_TO_VTK_TET10]
    tol = 1e-9 * length if face_tol is None else face_tol
    mesh = TetMesh(nodes, tets)
    mesh.node_sets = {"front_face": mesh.nodes_where(lambda x, y, z: np.abs(x - x0) <= tol),
                      "rear_face": mesh.nodes_where(lambda x, y, z: np.abs(x - x0 - length) <= tol)}
    return mesh
