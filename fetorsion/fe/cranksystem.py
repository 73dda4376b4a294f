"""The crank's FE system, built once: mesh, assembly, ties, couplings and one factorisation.

Every FE answer about a crank comes from this one object — the free-free modes
(:func:`fetorsion.fe.crankfe.run_modal`), the condensed crank free and in its bearings
(:func:`fetorsion.fe.condensed.run_condensed`) and through it the held-throw stiffnesses — so
a run assembles one mesh and factorises one matrix, and every path attaches the crank's
bodies the same way:

* the end faces move rigidly with the pulley hub and the flywheel flange: their nodes are
  eliminated exactly (u = T q, :func:`fetorsion.fe.rigid.reduction`), each face's six DOF at
  its centre becoming the ``front`` / ``rear`` master;
* every main journal (``J1`` …) and pin (``P1`` …) has a master at its centre, tied by a
  distributing coupling (:mod:`fetorsion.fe.couplings`) to its bearing surface: the journal's
  cylindrical surface within the bearing width, the pin's whole cylindrical surface;
* attachments are masses on the masters (:func:`attachment_masses`): pulley/damper hub at
  ``front``, flywheel at ``rear``, each with its offset, and every cylinder's piston + rod as a
  point mass I/R² at its pin centre. Through the distributing coupling that mass loads the pin
  surface without making its section rigid, as the big-end bearing's oil film does; a rigid
  ring would bridge the pin's oil drilling and stiffen it (Renault 21 f1 +2.4 %,
  docs/condensed-crank.md).

Springs and masses on the masters enter the full model as the low-rank term Gᵀ D G and held
master DOF as constraints (:mod:`fetorsion.fe.substructure`); nothing is assembled twice.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from ..description.defaults import DEFAULT_MESH_SIZE
from ..description.cylinders import pin_master_centre
from ..description.model import AttachPoint, Crank
from ..errors import FetorsionError
from ..solid.mesh import CrankMesh, mesh_crank
from . import assembly
from .couplings import Master, coupling_matrix, point_mass_block
from .modal import default_shift, node_masses
from .rigid import RigidBody, reduction
from .substructure import Interface, interface
from .tetmesh import TetMesh

if TYPE_CHECKING:
    from collections.abc import Callable

#: Tolerance on a journal or pin surface: nodes within this share of the diameter of the
#: nominal cylinder belong to the bearing surface.
SURFACE_TOL = 0.005
END_TIES = ("rigid", "distributing")


def _surface(cm: CrankMesh, part: str, axis_yz, diameter: float, x_mid: float, width: float) -> np.ndarray:
    k = cm.part_names.index(part)
    nodes = np.unique(cm.tets[cm.part == k])
    p = cm.nodes[nodes]
    r = np.hypot(p[:, 1] - axis_yz[0], p[:, 2] - axis_yz[1])
    on = (np.abs(r - 0.5 * diameter) <= SURFACE_TOL * diameter) & (np.abs(p[:, 0] - x_mid) <= 0.5 * width * (1 + 1e-9))
    if on.sum() < 12:
        raise FetorsionError(f"{part}: too few surface nodes for its coupling; refine the mesh")
    return nodes[on]


def _part_mid(cm: CrankMesh, part: str) -> float:
    k = cm.part_names.index(part)
    x = cm.nodes[np.unique(cm.tets[cm.part == k]), 0]
    return 0.5 * (x.min() + x.max())


def master_labels(crank: Crank) -> list[str]:
    """The labels of a crank's masters (:func:`crank_masters`), known before any mesh: ``front``,
    ``J1``, ``P1``, ``J2``, …, ``rear``."""
    inner = [lb for j in range(len(crank.journals))
             for lb in ((f"J{j + 1}", f"P{j + 1}") if j < crank.throws else (f"J{j + 1}",))]
    return ["front", *inner, "rear"]


def crank_masters(crank: Crank, cm: CrankMesh) -> list[Master]:
    """The masters of a crank mesh, in axial order: ``front``, ``J1``, ``P1``, ``J2``, …, ``rear``."""
    bearings = crank.main_bearings
    face = lambda name: cm.node_sets[f"{name}_face"]  # noqa: E731
    masters = [Master("front", np.array([cm.nodes[face("front"), 0].mean(), 0.0, 0.0]), face("front"))]
    for j, journal in enumerate(crank.journals):
        xm = _part_mid(cm, f"journal_{j + 1}")
        masters.append(Master(f"J{j + 1}", np.array([xm, 0.0, 0.0]),
                              _surface(cm, f"journal_{j + 1}", (0.0, 0.0), journal.diameter, xm, bearings.width[j])))
        if j < crank.throws:
            masters.append(_pin_master(crank, cm, j))
    masters.append(Master("rear", np.array([cm.nodes[face("rear"), 0].mean(), 0.0, 0.0]), face("rear")))
    return masters


def _pin_master(crank: Crank, cm: CrankMesh, t: int) -> Master:
    """Pin ``t``'s master at its mid-length on its axis, tied to its bearing surface. A split pin
    keeps one master, midway between its half pins' axes (:func:`pin_master_centre`), tied to
    both halves' bearing surfaces (a distributing coupling adds no stiffness: the flying web keeps
    its own); each rod's force reaches it with its moment about it (docs/vee-engines.md)."""
    pin, name = crank.pins[t], f"pin_{t + 1}"
    yz = pin_master_centre(crank.engine, t, pin.split_angle)
    xp = _part_mid(cm, name)
    if not pin.split:
        return Master(f"P{t + 1}", np.array([xp, *yz]), _surface(cm, name, yz, pin.diameter, xp, pin.length))
    a, R, h = crank.engine.crank_angles[t], crank.engine.crank_radius, pin.half_length
    halves = [(a, xp - 0.5 * (pin.length - h)), (a + pin.split_angle, xp + 0.5 * (pin.length - h))]
    nodes = [_surface(cm, name, (R * math.cos(b), R * math.sin(b)), pin.diameter, x, h) for b, x in halves]
    return Master(f"P{t + 1}", np.array([xp, *yz]), np.union1d(*nodes))


def end_body(crank: Crank, at: str):
    """(mass kg, 3 × 3 inertia kg·m² about its centre, axial offset m outward) of the attachments
    on one end face, combined (masses add, inertias add about the common centre); None without."""
    atts = crank.attachments_at(at)
    if not atts:
        return None
    mass = sum(a.mass for a in atts)
    offset = sum(a.mass * a.offset for a in atts) / mass if mass > 0 else 0.0
    diametral = sum(a.diametral_inertia + a.mass * (a.offset - offset) ** 2 for a in atts)
    return mass, np.diag([sum(a.polar_inertia for a in atts), diametral, diametral]), offset


#: (master label, attach point, sign of the outward normal along x) of the two end faces.
ENDS = (("front", AttachPoint.FRONT, -1.0), ("rear", AttachPoint.REAR, 1.0))


def attachment_masses(crank: Crank, labels: list[str], positions: np.ndarray) -> np.ndarray:
    """Master-level mass matrix (6·masters square) of the description's attachments."""
    m = len(labels)
    Dm = np.zeros((6 * m, 6 * m))
    for label, at, outward in ENDS:
        body = end_body(crank, at)
        if body is None:
            continue
        mass, inertia, offset = body
        k = labels.index(label)
        centre = positions[k] + np.array([outward * offset, 0.0, 0.0])
        Dm[6 * k:6 * k + 6, 6 * k:6 * k + 6] += point_mass_block(mass, inertia, centre, positions[k])
    pistons = crank.attachments_at(AttachPoint.PINS)
    if pistons:
        from ..description.cylinders import cylinders_per_throw

        inertia = sum(a.polar_inertia for a in pistons)  # per cylinder: a vee's throw carries two
        for t, count in enumerate(cylinders_per_throw(crank.engine)):
            k = labels.index(f"P{t + 1}")
            r2 = float(positions[k, 1] ** 2 + positions[k, 2] ** 2)
            Dm[6 * k:6 * k + 3, 6 * k:6 * k + 3] += count * inertia / r2 * np.eye(3)
    return Dm


@dataclass
class CrankSystem:
    """A crank's FE model, assembled and factorised once (see the module docstring).

    Attributes
    ----------
    crank : Crank
    mesh : CrankMesh
    labels : list of str
        Master labels in axial order.
    positions : ndarray (masters, 3)
        m.
    interface : Interface
        The factor of K − σM over the solved DOF, and the couplings G to the masters.
    T : sparse (3·nodes, solved DOF) or None
        u = T x: the mesh displacement from the solved DOF (None: no rigid end ties).
    K : sparse or None
        Stiffness on the mesh DOF (N/m), kept only when asked (``keep_mesh_stiffness``): the
        section resultants come from the basis' nodal forces, and with rigid end ties it would
        be a second copy of the solved stiffness (280 MB at 323 k DOF) in the run's peak memory.
    dof_of_node : ndarray of int
        Mesh node → DOF node (−1: unused).
    xyz : ndarray (DOF nodes, 3)
        m.
    node_mass : ndarray (DOF nodes,)
        Positive lumped node masses, kg (weights of the mode identification).
    attachment_mass : ndarray (6·masters, 6·masters)
        Attachments on the masters.
    """

    crank: Crank
    mesh: CrankMesh
    labels: list[str]
    positions: np.ndarray
    interface: Interface
    T: sp.csr_array | None
    K: sp.csr_array | None
    dof_of_node: np.ndarray
    xyz: np.ndarray
    node_mass: np.ndarray
    attachment_mass: np.ndarray
    end_ties: str = "rigid"
    timings_s: dict[str, float] = field(default_factory=dict)
    #: Mesh DOF (interleaved x, y, z per DOF node) of the solved DOF that are not tied to an end
    #: body, in solved order; the end bodies' six DOF each follow them.
    free_dofs: np.ndarray | None = None
    #: The scalar node mass matrix m (M = m ⊗ I₃ on the mesh DOF), kg: the rotating-frame terms
    #: (:mod:`fetorsion.fe.rotating`) are products with it.
    node_mass_matrix: sp.csr_array | None = None

    @property
    def dofs(self) -> int:
        """Size of the solved system."""
        return self.interface.K.shape[0]

    @property
    def mesh_dofs(self) -> int:
        """DOF of the mesh (3 per DOF node), before the end ties."""
        return 3 * len(self.xyz)

    def expand(self, x: np.ndarray) -> np.ndarray:
        """Mesh-DOF displacements (3·nodes, …) from solved-DOF vectors (solved DOF, …)."""
        return np.asarray(self.T @ x) if self.T is not None else np.asarray(x)

    def component(self, x: np.ndarray, k: int) -> np.ndarray:
        """Displacement component ``k`` (0 x, 1 y, 2 z) of every DOF node (DOF nodes, …) from
        solved-DOF vectors: a third of :meth:`expand`, without making the rest."""
        return np.asarray(self.T[k::3] @ x) if self.T is not None else np.ascontiguousarray(x[k::3])


#: The stages of :func:`build_system` with their times on the Renault 21 at the default 10 mm mesh
#: (322 686 DOF, AMD EPYC 2 cores, a fresh clone): a progress line's shares, not a promise
SYSTEM_STAGES = {"meshing": 3.1, "assembling": 9.3, "factorising": 7.7}


def build_system(crank: Crank, mesh_size: float = DEFAULT_MESH_SIZE, mesh: CrankMesh | None = None,
                 backend: str = "auto", end_ties: str = "rigid", fillet_size: float | None = None,
                 purpose: str = "modal", keep_mesh_stiffness: bool = False,
                 stage: Callable[[str], None] | None = None) -> CrankSystem:
    """Mesh (unless ``mesh`` is given), assemble, tie, couple and factorise a crank.

    Parameters
    ----------
    crank : Crank
    mesh_size : float
        Global element size, m (ignored when ``mesh`` is given).
    mesh : CrankMesh, optional
    backend : str
        Factorisation backend (:func:`fetorsion.fe.eigen.factorize`).
    end_ties : str
        ``rigid`` (default): the end faces move with the pulley hub and the flywheel as rigid
        bodies; ``distributing``: RBE3 couplings there too (a flange face free to deform under
        the flywheel: Renault 21 free-free f1 −2.5 %).
    fillet_size : float, optional
        Element size at fillets and drillings, m (:func:`fetorsion.solid.mesh.default_fillet_size`).
    purpose : str
        ``modal`` or ``stress`` (the fillet size's default).
    keep_mesh_stiffness : bool
        Keep the stiffness on the mesh DOF as ``K`` (see :class:`CrankSystem`).
    stage : callable, optional
        Called with each stage's name as it starts (:data:`SYSTEM_STAGES`; a
        :class:`~fetorsion.io.Stages`).
    """
    stage = stage or (lambda name: None)
    if end_ties not in END_TIES:
        raise FetorsionError(f"unknown end_ties {end_ties!r}; choose from {', '.join(END_TIES)}")
    t0 = time.perf_counter()
    if mesh is None:
        stage("meshing")
    cm = mesh or mesh_crank(crank, mesh_size, fillet_size, purpose)
    t1 = time.perf_counter()
    stage("assembling")
    tm = TetMesh(cm.nodes, cm.tets, dict(cm.node_sets))
    m, dof_of_node = assembly.skfem_mesh(tm)
    basis = assembly.p2_basis(m)
    pat = assembly.block_pattern(basis)
    mat = crank.material
    K = assembly.stiffness(basis, mat.youngs_modulus, mat.poisson_ratio, pat)
    # the mass's diagonal components alone (a third of K's entries): the reduction, the shifted
    # matrix and every product with M read no explicit zeros
    M = assembly.mass(basis, mat.density, pat, compact=True)
    w = node_masses(basis, mat.density)
    m_scalar = sp.csr_array(M[0::3][:, 0::3])
    del basis, pat
    masters = crank_masters(crank, cm)
    xyz = m.doflocs.T
    G = coupling_matrix(masters, dof_of_node, xyz)
    T, Kc, Mc, free = None, K, M, np.arange(K.shape[0])
    groups = np.arange(0, K.shape[0] + 1, 3)  # a node's three displacements share their neighbours
    if end_ties == "rigid":
        # The end faces' nodes follow their bodies exactly; the bodies' six DOF (at the face
        # centres, massless here: the attachments act on the masters) are the end masters.
        ends = [RigidBody(mst.label, dof_of_node[mst.nodes], 0.0, np.zeros((3, 3)), mst.position)
                for mst in (masters[0], masters[-1])]
        red = reduction(K.shape[0], ends, xyz)
        T, free = red.T, red.free
        Kc, Mc = red.reduce(K), red.reduce(M)
        nf = red.n_free
        pick = lambda first: sp.csr_array((np.ones(6), (np.arange(6), nf + first + np.arange(6))),  # noqa: E731
                                          shape=(6, Kc.shape[0]))
        G = sp.vstack([pick(0), (G[6:-6] @ T), pick(6)]).tocsr()
        groups = red.groups()
    # the mesh's K and M are not needed past here (but as the caller's kept stiffness): freed
    # before the factorisation, the run's peak (1.2 GiB at 664 k DOF)
    K_mesh = K if keep_mesh_stiffness else None
    del K, M
    t2 = time.perf_counter()
    stage("factorising")
    itf = interface(Kc, Mc, G, default_shift(tm, mat), backend, groups=groups)
    labels = [mst.label for mst in masters]
    positions = np.array([mst.position for mst in masters])
    timings = {"meshing": cm.quality.seconds if cm.quality and mesh is None else t1 - t0, "assembly": t2 - t1,
               **itf.timings_s}
    return CrankSystem(crank, cm, labels, positions, itf, T, K_mesh, dof_of_node, xyz, w,
                       attachment_masses(crank, labels, positions), end_ties, timings, free, m_scalar)
