"""Free-free 3D FE modal analysis of a shaft with rigid attachments, every mode labelled.

Pipeline (SI units throughout):

1. :func:`fetorsion.fe.assembly.stiffness` / :func:`~fetorsion.fe.assembly.mass`: curved vector-P2
   elasticity K (N/m) and consistent M (kg) on the :class:`~fetorsion.fe.tetmesh.TetMesh`.
2. :func:`fetorsion.fe.rigid.reduction`: attachments (flywheel, pulley, pistons) as rigid
   bodies tied to node sets, exact master-DOF elimination u = T q.
3. :func:`fetorsion.fe.eigen.lowest_modes`: block shift-invert Lanczos with a negative shift over
   one sparse Cholesky (PARDISO or CHOLMOD, SuperLU fallback); the six rigid-body modes come out first, are
   checked (≈ 0 against the first elastic mode) and reported apart.
4. :func:`fetorsion.fe.modeshape.identify`: rigid fits to axial slabs (crank: main journals)
   give torsional / bending / axial fractions and a label per mode.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from . import assembly

from . import eigen

from . import modeshape
from ..description.model import Material
from ..description.defaults import DEFAULT_MODES
from ..errors import FetorsionError
from ..results import from_fields
from .rigid import RigidBody, reduction, rigid_rows
from .tetmesh import TetMesh

#: A computed mode counts as rigid-body when ω² < RIGID_TOL · ω²(first elastic), i.e. its
#: frequency is below 1 % of the first elastic one; round-off gives ~1e-6 or less.
RIGID_TOL = 1e-4
#: Default shift: -(2π f)² with f this share of the first torsional frequency c/(2L) of a
#: uniform bar as long as the mesh; only the conditioning of K - σM depends on it.
SHIFT_SHARE = 0.1


@dataclass
class ModalResult:
    """Free-free natural frequencies of a 3D FE model, every elastic mode labelled.

    Attributes
    ----------
    frequencies_hz : ndarray
        Elastic natural frequencies, ascending, Hz.
    kinds : list of str
        ``torsional``, ``bending``, ``axial`` or ``other`` per mode.
    fractions : ndarray, shape (modes, 3)
        Torsional, bending and axial shares of the slabs' rigid-fit kinetic energy (rows sum to 1).
    rigid_fit : ndarray
        Share of the slabs' motion captured by their rigid fits, per mode (low: the slabs deform).
    rigid_body_hz : ndarray
        The six rigid-body roots, Hz (≈ 0; their size shows the round-off).
    nodes, elements, dofs : int
        Mesh nodes, ten-node tetrahedra, and size of the solved system.
    material : Material
    timings_s : dict
        Wall time of each step, s.
    shapes : ndarray, shape (modes, N, 3), optional
        Mode shapes at the TetMesh nodes (M-orthonormal, m/√kg), zero at unused nodes.
    body_motion : dict of str to ndarray (modes, 6), optional
        Each attachment's (t, θ) at its centre of mass per mode.
    backend, method : str
        Factorisation and eigen-method used.
    error_bound : ndarray, optional
        Guaranteed relative error of each elastic frequency against the exact eigenvalue of the
        same FE model, where the modes are Ritz approximations (the condensed crank's);
        None where the eigen-solver converged them to its own tolerance.
    """

    frequencies_hz: np.ndarray
    kinds: list[str]
    fractions: np.ndarray
    rigid_fit: np.ndarray
    rigid_body_hz: np.ndarray
    nodes: int
    elements: int
    dofs: int
    material: Material
    timings_s: dict[str, float]
    shapes: np.ndarray | None = field(default=None, repr=False)
    body_motion: dict = field(default_factory=dict, repr=False)
    backend: str = ""
    method: str = ""
    error_bound: np.ndarray | None = field(default=None, repr=False)

    def of_kind(self, kind: str) -> np.ndarray:
        """Frequencies (Hz) of the modes labelled ``kind``."""
        return self.frequencies_hz[[k == kind for k in self.kinds]]

    def first_torsional(self) -> float:
        """Frequency of the lowest mode labelled torsional, Hz.

        Raises FetorsionError when none was found among the computed modes.
        """
        tors = self.of_kind("torsional")
        if len(tors) == 0:
            raise FetorsionError(f"no torsional mode among the {len(self.frequencies_hz)} computed; "
                                 "ask for more modes")
        return float(tors[0])

    def first_carrying_torsion(self, share: float | None = None) -> float:
        """The lowest mode with at least ``share`` (default
        :data:`~fetorsion.modes.TORSION_SHARE_NOTED`) of its kinetic energy in torsion, Hz. Below
        :meth:`first_torsional` where torsion couples with bending (a crank without its flywheel,
        a flat crank of equal throws): the mode the engine's torque drives first."""
        from ..modes import TORSION_SHARE_NOTED, first_with_torsion

        return first_with_torsion(self.frequencies_hz, self.fractions, TORSION_SHARE_NOTED if share is None else share,
                                  "computed modes; ask for more modes")

    def to_dict(self) -> dict:
        """Plain JSON-ready dict (SI units): frequencies, kinds, fractions, mesh and timings."""
        return {
            "modes": [{"frequency_hz": float(f), "kind": k, "torsional_fraction": float(fr[0]),
                       "bending_fraction": float(fr[1]), "axial_fraction": float(fr[2])}
                      for f, k, fr in zip(self.frequencies_hz, self.kinds, self.fractions)],
            "rigid_body_hz": [float(f) for f in self.rigid_body_hz],
            "mesh": {"nodes": int(self.nodes), "elements": int(self.elements), "dofs": int(self.dofs)},
            "material": {"E": float(self.material.youngs_modulus), "nu": float(self.material.poisson_ratio),
                         "rho": float(self.material.density)},
            "timings_s": {k: float(v) for k, v in self.timings_s.items()},
            "method": self.method, "backend": self.backend,
            **({} if self.error_bound is None else
               {"frequency_error_bound": [float(b) for b in self.error_bound]}),
        }

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "ModalResult":
        """The result back from its :meth:`to_dict`: frequencies, labels, shares, mesh sizes and
        timings (the mode shapes, rigid fits and bodies' motion are not kept)."""
        modes = d["modes"]
        m = d["material"]
        fractions = np.array([[x["torsional_fraction"], x["bending_fraction"], x["axial_fraction"]] for x in modes],
                             dtype=float).reshape(-1, 3)
        bound = d.get("frequency_error_bound")
        return from_fields(cls, d, frequencies_hz=np.array([x["frequency_hz"] for x in modes], dtype=float),
                           kinds=[x["kind"] for x in modes], fractions=fractions, rigid_fit=np.full(len(modes), np.nan),
                           nodes=d["mesh"]["nodes"], elements=d["mesh"]["elements"], dofs=d["mesh"]["dofs"],
                           material=Material(m["E"], m["nu"], m["rho"]),
                           error_bound=None if bound is None else np.array(bound, dtype=float))

    def table(self) -> str:
        """Each elastic mode: frequency, label and the torsion/bending/axial shares."""
        lines = [f"free-free FE modes ({self.dofs} DOF, {self.elements} curved P2 tets, {self.backend}/{self.method}, "
                 f"{self.timings_s.get('total', sum(self.timings_s.values())):.1f} s)",
                 f"{'mode':>4} {'f [Hz]':>9} {'kind':>10} {'torsion':>8} {'bending':>8} {'axial':>8}"]
        lines += [f"{j + 1:>4} {f:9.1f} {k:>10} {fr[0]:8.3f} {fr[1]:8.3f} {fr[2]:8.3f}"
                  for j, (f, k, fr) in enumerate(zip(self.frequencies_hz, self.kinds, self.fractions))]
        return "\n".join(lines)

    def plot(self, ax=None):
        """Stacked torsional / bending / axial fractions per mode, frequencies on the ticks.

        Returns the matplotlib Axes.
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(9, 4))
        x = np.arange(len(self.frequencies_hz))
        bottom = np.zeros(len(x))
        for j, name in enumerate(modeshape.KINDS):
            ax.bar(x, self.fractions[:, j], bottom=bottom, label=name)
            bottom += self.fractions[:, j]
        ax.set_xticks(x, [f"{f:.0f}\n{k[:4]}" for f, k in zip(self.frequencies_hz, self.kinds)], fontsize=7)
        ax.set_xlabel("mode: frequency (Hz), label")
        ax.set_ylabel("share of slab rigid-fit kinetic energy")
        ax.legend(fontsize=8)
        ax.figure.tight_layout()
        return ax


def default_shift(mesh: TetMesh, material: Material) -> float:
    """Negative shift σ (rad²/s²) scaled on the first torsional frequency of a bar as long as the mesh."""
    x = mesh.nodes[np.unique(mesh.tets[:, :4]), 0]
    c = np.sqrt(material.shear_modulus / material.density)
    f = SHIFT_SHARE * c / (2.0 * max(x.max() - x.min(), 1e-12))
    return -(2.0 * np.pi * f) ** 2


def split_rigid(omega2: np.ndarray, sigma: float, n_rigid: int = 6):
    """Split ascending ω² (rad²/s²) into (rigid, elastic); check there are exactly ``n_rigid`` ≈ 0.

    "≈ 0" is first judged against the larger of |σ| and the largest computed ω² (a scale
    that exists even when every computed mode is rigid), then the rigid ones are checked
    against the first elastic one (:data:`RIGID_TOL`).
    """
    if len(omega2) <= n_rigid:
        raise ValueError("need more eigenvalues than rigid-body modes")
    scale = max(abs(sigma), float(np.abs(omega2).max()))
    zero = int((np.abs(omega2) < RIGID_TOL * scale).sum())
    if zero > n_rigid:
        raise FetorsionError(f"{zero} zero-frequency modes (six expected): the mesh has disconnected "
                             "parts or an attachment is tied to nothing")
    rigid, elastic = omega2[:n_rigid], omega2[n_rigid:]
    if zero < n_rigid or np.abs(rigid).max() >= RIGID_TOL * elastic[0]:
        raise FetorsionError(f"expected {n_rigid} rigid-body modes near zero, got ω² = {omega2[:n_rigid + 1]} "
                             "rad²/s²; the solve is inaccurate (mesh too distorted?)")
    return rigid, elastic


def modal(mesh: TetMesh, material: Material, *, modes: int = DEFAULT_MODES, attachments: list[RigidBody] = (),
          slabs=None, n_slabs: int = 12, backend: str = "auto", method: str = "block",
          shift: float | None = None, keep_shapes: bool = True) -> ModalResult:
    """Free-free natural frequencies and labelled modes of a solid with rigid attachments.

    Parameters
    ----------
    mesh : TetMesh
        Curved ten-node tetrahedra, coordinates in m, crank axis = x axis.
    material : Material
        E (Pa), ν (-), ρ (kg/m³).
    modes : int
        Number of elastic modes wanted (the six rigid-body modes come on top).
    attachments : list of RigidBody
        Rigid bodies tied to node sets of ``mesh`` (see :func:`fetorsion.fe.rigid.from_attachment`).
    slabs : dict of str to node indices, list of node-index arrays, or None
        Axial slabs for mode identification (crank: the main journals). None: ``n_slabs``
        equal axial slices of the mesh. Attachments centred on the x axis count as extra slabs.
    n_slabs : int
        Slices when ``slabs`` is None.
    backend : str
        ``"pardiso"``, ``"cholmod"``, ``"superlu"`` or ``"auto"`` (the first one installed).
    method : str
        ``"block"`` (block shift-invert Lanczos, default), ``"lanczos"`` (ARPACK, the
        reference) or ``"lobpcg"``; see :mod:`fetorsion.fe.eigen`.
    shift : float, optional
        Negative shift σ, rad²/s² (default from :func:`default_shift`).
    keep_shapes : bool
        Keep mode shapes in the result.

    Returns
    -------
    ModalResult

    Examples
    --------
    >>> from fetorsion.description.model import Material
    >>> from fetorsion.fe.tetmesh import cylinder_mesh
    >>> steel = Material(210e9, 0.3, 7850.0)
    >>> res = modal(cylinder_mesh(0.5, 0.05, 0.02), steel, modes=8)
    >>> round(res.first_torsional() / 3207.66, 2)  # c / (2L) with c = √(G/ρ) = 3207.66 m/s
    1.0
    """
    t_start = time.perf_counter()
    timings = {}
    t = time.perf_counter()
    m, dof_of_node = assembly.skfem_mesh(mesh)
    basis = assembly.p2_basis(m)
    timings["mesh"] = time.perf_counter() - t
    t = time.perf_counter()
    pattern = assembly.block_pattern(basis)
    K = assembly.stiffness(basis, material.youngs_modulus, material.poisson_ratio, pattern)
    d = assembly.mass_blocks(basis, material.density, pattern)
    M = assembly.diagonal_block_matrix(pattern, d)  # without K's explicit zeros: a third of the entries
    timings["assembly"] = time.perf_counter() - t
    w = node_masses(basis, material.density)
    del basis  # its shape-function tables (a tenth of the peak memory) are not needed any more

    t = time.perf_counter()
    sigma = default_shift(mesh, material) if shift is None else shift
    # S = K − σM in K's memory: K itself is not needed again (the rigid-body check reads S).
    S = K
    assembly.add_to_diagonal_blocks(S, pattern, d, -sigma)
    del K, pattern
    xyz = m.doflocs.T  # position of each scalar DOF (node), m
    bodies = [RigidBody(b.name, _map_nodes(dof_of_node, b.nodes, b.name), b.mass, b.inertia, b.centre)
              for b in attachments]
    red = reduction(S.shape[0], bodies, xyz) if bodies else None
    groups = np.arange(0, S.shape[0] + 1, 3)  # a node's three displacements share their neighbours
    rigid_motions = rigid_rows(xyz, np.zeros(3)).reshape(-1, 6)
    if red is not None:
        S, M = red.reduce(S, -sigma * red.body_blocks), red.reduce(M, red.body_blocks)
        groups = red.groups()
        rigid_motions = red.rigid_motions(rigid_motions)
    timings["attachments"] = time.perf_counter() - t

    res = eigen.lowest_modes(None, M, modes + 6, sigma, backend=backend, method=method, groups=groups,
                             null_space=rigid_motions, S=S)
    timings.update(res.timings_s)
    rigid, elastic = split_rigid(_with_rigid_rayleigh_quotients(res.omega2, res.vectors, S, M, sigma), sigma)

    t = time.perf_counter()
    q = res.vectors[:, 6:]
    full = red.T @ q if red is not None else q
    U = full.T.reshape(len(elastic), -1, 3)  # (modes, dof-nodes, 3)
    body_motion = {b.name: q[red.n_free + 6 * i: red.n_free + 6 * i + 6].T for i, b in enumerate(bodies)}
    fractions, kinds, fit = _identify(U, xyz, w, dof_of_node, slabs, n_slabs, bodies, body_motion)
    timings["identify"] = time.perf_counter() - t
    timings["total"] = time.perf_counter() - t_start

    shapes = _shapes_at_nodes(U, dof_of_node, len(mesh.nodes)) if keep_shapes else None
    hz = lambda w2: np.sqrt(np.abs(w2)) / (2 * np.pi)  # noqa: E731
    return ModalResult(hz(elastic), kinds, fractions, fit, hz(rigid), int(m.nvertices + m.nedges),
                       mesh.n_elements, S.shape[0], material, timings, shapes, body_motion,
                       res.backend, res.method)


def _with_rigid_rayleigh_quotients(omega2: np.ndarray, vectors: np.ndarray, S, M, sigma: float) -> np.ndarray:
    """ω² (rad²/s²) with its six lowest replaced by the Rayleigh quotients of their vectors."""
    omega2 = omega2.copy()
    # vᵀKv = vᵀSv + σ vᵀMv: zero in exact arithmetic, so their size shows the round-off of the
    # assembly and the solve.
    V6 = vectors[:, :6]
    omega2[:6] = np.einsum("ij,ij->j", V6, S @ V6) / np.einsum("ij,ij->j", V6, M @ V6) + sigma
    return omega2


def _identify(U: np.ndarray, xyz: np.ndarray, w: np.ndarray, dof_of_node: np.ndarray, slabs, n_slabs: int,
              bodies: list[RigidBody], body_motion: dict[str, np.ndarray]):
    """(fractions, kinds, rigid fit) of the mode shapes U on the slabs, bodies on the x axis as extra slabs."""
    if slabs is None:
        slab_idx = modeshape.axial_slabs(xyz, n_slabs)
    else:
        items = slabs.items() if isinstance(slabs, dict) else enumerate(slabs)
        slab_idx = [_map_nodes(dof_of_node, v, f"slab {k}") for k, v in items]
    on_axis = [(body_motion[b.name], b.mass, b.inertia) for b in bodies
               if np.hypot(b.centre[1], b.centre[2]) <= 1e-9 + 1e-6 * np.abs(xyz).max()]
    return modeshape.identify(U, xyz, w, slab_idx, on_axis)


def _shapes_at_nodes(U: np.ndarray, dof_of_node: np.ndarray, n_nodes: int) -> np.ndarray:
    """Mode shapes U (modes, DOF nodes, 3) at the mesh's ``n_nodes`` nodes, zero where no tetrahedron is."""
    used = dof_of_node >= 0
    shapes = np.zeros((len(U), n_nodes, 3))
    shapes[:, used] = U[:, dof_of_node[used]]
    return shapes


def node_masses(basis, density: float) -> np.ndarray:
    """Positive nodal masses (kg): each tet's mass shared equally by its ten nodes.

    The consistent P2 mass has negative row sums at vertices, unusable as fit weights.
    """
    share = density * basis.dx.sum(axis=1) / basis.element_dofs.shape[0]
    return np.bincount(basis.element_dofs.ravel(), np.tile(share, basis.element_dofs.shape[0]),
                       minlength=basis.N)


def _map_nodes(dof_of_node: np.ndarray, nodes, what: str) -> np.ndarray:
    """Mesh node indices -> scalar DOF indices, refusing nodes no tetrahedron uses."""
    nodes = np.asarray(nodes, dtype=np.int64)
    if len(nodes) == 0:
        raise FetorsionError(f"{what}: empty node set")
    if nodes.min() < 0 or nodes.max() >= len(dof_of_node):
        raise FetorsionError(f"{what}: node index out of range")
    d = dof_of_node[nodes]
    if (d < 0).any():
        raise FetorsionError(f"{what}: {int((d < 0).sum())} node(s) belong to no tetrahedron")
    return d
