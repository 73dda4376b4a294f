"""3D FE modal analysis of a crank description: mesh, attachments, journals, torsional modes.

Glue between :mod:`fetorsion.solid.mesh` (the crank's curved P2 mesh with part tags) and
:mod:`fetorsion.fe.modal` (the free-free solver):

- pulley-end attachments are one rigid body tied to the ``front_face`` nodes, flywheel-end
  attachments one tied to ``rear_face`` (mass, polar and diametral inertia, offset);
- a ``pins`` attachment (piston + rod, given as its equivalent inertia about the crank
  axis) becomes, on every pin, a point mass m = I/R² at the pin centre tied to a ring of
  pin-surface nodes around the pin's mid-plane: that reproduces I about the crank axis
  and stiffens only that ring, not the pin;
- the main journals are the slabs whose rigid twist identifies torsional modes.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from ..modes import TorsionalModes
from ..description.model import Attachment, AttachPoint, Crank
from ..description.defaults import DEFAULT_MESH_SIZE, DEFAULT_MODES, DEFAULT_TORSIONAL_MODES
from ..errors import FetorsionError
from ..extrapolation import richardson
from ..solid.mesh import CrankMesh, mesh_crank
from .modal import ModalResult, modal
from .modeshape import slab_fit
from .rigid import RigidBody, from_attachment
from .tetmesh import TetMesh

#: Stated error of the default modal mesh (10 mm global, fillet elements of the fillet
#: radius) on the first torsional frequency, relative: against each crank's finest (4 mm)
#: mesh, f1 is +0.11 % (Peugeot GLX, 1.15 M DOF) and +0.24 % (Renault 21, 1.03 M DOF) high
#: (docs/modal-mesh.md); ``--refine`` estimates it for other cranks.
MODAL_F1_ERROR = 2.5e-3

#: Axial share of a pin (around its mid-plane) whose surface nodes carry the piston + rod.
PIN_RING_SHARE = 1.0 / 3.0


def part_nodes(cm: CrankMesh, name: str) -> np.ndarray:
    """Nodes of the elements of part ``name`` (``journal_1``, ``pin_2``, ...)."""
    try:
        k = cm.part_names.index(name)
    except ValueError:
        raise FetorsionError(f"the mesh has no part {name!r}") from None
    return np.unique(cm.tets[cm.part == k])


def pin_ring(cm: CrankMesh, crank: Crank, i: int) -> np.ndarray:
    """Surface nodes of pin ``i`` (0-based) within its middle third, m from its axis ≈ D/2."""
    nodes = part_nodes(cm, f"pin_{i + 1}")
    xyz = cm.nodes[nodes]
    R, angle = crank.engine.crank_radius, crank.engine.crank_angles[i]
    centre = np.array([R * np.cos(angle), R * np.sin(angle)])
    r = np.hypot(xyz[:, 1] - centre[0], xyz[:, 2] - centre[1])
    x_mid = 0.5 * (xyz[:, 0].min() + xyz[:, 0].max())
    pin = crank.pins[i]
    ring = (r > 0.5 * pin.diameter * 0.98) & (np.abs(xyz[:, 0] - x_mid) <= 0.5 * PIN_RING_SHARE * pin.length)
    if ring.sum() < 6:
        raise FetorsionError(f"pin_{i + 1}: too few surface nodes to carry its attachment; refine the mesh")
    return nodes[ring]


def attachment_bodies(crank: Crank, cm: CrankMesh) -> list[RigidBody]:
    """Rigid bodies for the description's attachments, tied to the mesh."""
    bodies = []
    for at, outward in ((AttachPoint.FRONT, -1.0), (AttachPoint.REAR, 1.0)):
        atts = crank.attachments_at(at)
        if atts:
            bodies.append(from_attachment(_combined(atts, at), cm.node_sets[f"{at}_face"], cm.nodes, outward))
    pistons = crank.attachments_at(AttachPoint.PINS)
    if pistons:
        inertia = sum(a.polar_inertia for a in pistons)
        for i in range(crank.cylinders):
            ring = pin_ring(cm, crank, i)
            r2 = float(np.sum(cm.nodes[ring].mean(axis=0)[1:] ** 2))  # the body sits at the ring's centroid
            att = Attachment(f"piston+rod {i + 1}", AttachPoint.PINS, inertia, mass=inertia / r2)
            bodies.append(from_attachment(att, ring, cm.nodes, 0.0, about_crank_axis=True))
    return bodies


def _combined(atts, at: str) -> Attachment:
    """Several bodies on one face as one: masses add, inertias add about the common axis."""
    mass = sum(a.mass for a in atts)
    offset = sum(a.mass * a.offset for a in atts) / mass if mass > 0 else 0.0
    diametral = sum(a.diametral_inertia + a.mass * (a.offset - offset) ** 2 for a in atts)
    return Attachment(" + ".join(a.name for a in atts), at, sum(a.polar_inertia for a in atts), mass, diametral, offset)


@dataclass
class CrankModal(ModalResult):
    """FE modal result of a crank: a :class:`~fetorsion.fe.modal.ModalResult` that also holds
    the crank and the mesh it was computed on (for pictures and the Campbell hand-off)."""

    crank: Crank | None = field(default=None, repr=False)
    mesh: CrankMesh | None = field(default=None, repr=False)

    def torsional_modes(self, n: int = DEFAULT_TORSIONAL_MODES) -> TorsionalModes:
        """The first ``n`` torsional modes in the form the Campbell analysis uses.

        Pin twist and pulley twist are the rigid-fit rotations about x of each pin's nodes
        and of the front face; the shapes are M-orthonormal, so every modal inertia is 1.
        """
        idx = [j for j, k in enumerate(self.kinds) if k == "torsional"][:n]
        if not idx:
            raise FetorsionError("no torsional mode among the computed modes; ask for more modes")
        U = self.shapes[idx]
        twist = lambda nodes: slab_fit(U[:, nodes], self.mesh.nodes[nodes], np.ones(len(nodes)))[0][:, 3]  # noqa: E731
        pins = np.stack([twist(part_nodes(self.mesh, f"pin_{i + 1}")) for i in range(self.crank.cylinders)], axis=1)
        return TorsionalModes(f"FE ({self.dofs} DOF)", self.frequencies_hz[idx], pins,
                              twist(self.mesh.node_sets["front_face"]), np.ones(len(idx)))


def run_modal(crank: Crank, mesh_size: float = DEFAULT_MESH_SIZE, modes: int = DEFAULT_MODES, fillet_size: float | None = None,
              mesh: CrankMesh | None = None, purpose: str = "modal", **solver) -> CrankModal:
    """Free-free FE modes of a crank with its attachments as rigid inertias.

    Parameters
    ----------
    crank : Crank
        The description.
    mesh_size : float
        Global element size, m (fillets and drillings get finer ones).
    modes : int
        Number of elastic modes.
    fillet_size : float, optional
        Element size at fillets and drillings, m (default:
        :func:`fetorsion.solid.mesh.default_fillet_size` for ``purpose``).
    mesh : CrankMesh, optional
        A mesh made earlier (``mesh_size`` is then ignored).
    purpose : str
        ``"modal"`` (default; f1 within :data:`MODAL_F1_ERROR` of a 1.15 M-DOF mesh on the
        reference cranks, docs/modal-mesh.md) or ``"stress"``; see
        :func:`fetorsion.solid.mesh.default_fillet_size`.
    **solver
        Passed to :func:`fetorsion.fe.modal.modal` (``backend``, ``method``, ``shift``).
    """
    cm = mesh or mesh_crank(crank, mesh_size, fillet_size, purpose)
    tm = TetMesh(cm.nodes, cm.tets, dict(cm.node_sets))
    slabs = {f"J{k + 1}": part_nodes(cm, f"journal_{k + 1}") for k in range(crank.cylinders + 1)}
    res = modal(tm, crank.material, modes=modes, attachments=attachment_bodies(crank, cm), slabs=slabs, **solver)
    res.timings_s["meshing"] = cm.quality.seconds if cm.quality else 0.0
    return CrankModal(**{f.name: getattr(res, f.name) for f in fields(ModalResult)}, crank=crank, mesh=cm)


def extrapolate_refinement(sizes, values) -> dict:
    """Extrapolate f(h) = f∞ + C hᵖ from three results at sizes in a constant ratio.

    Returns ``extrapolated``, ``order`` p and ``error_estimate`` (|f∞ − finest|). When the
    three values do not converge monotonically, no order can be fitted: the finest value
    is returned with the spread of the three as its error estimate.
    """
    h = np.asarray(sizes, dtype=float)
    f = np.asarray(values, dtype=float)
    ratio = h[1] / h[0]
    if len(f) != 3 or not np.isclose(h[2] / h[1], ratio):
        raise FetorsionError("Richardson extrapolation needs three sizes in a constant ratio")
    d1, d2 = f[1] - f[0], f[2] - f[1]
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return {"extrapolated": float(f[2]), "order": None, "error_estimate": float(np.ptp(f))}
    p = float(np.log(d1 / d2) / np.log(1 / ratio))
    f_inf = float(richardson(f[1], f[2], h[1], h[2], p))
    return {"extrapolated": f_inf, "order": p, "error_estimate": abs(f_inf - float(f[2]))}


REFINE_RATIO = 0.8


def run_refinement(crank: Crank, mesh_size: float, modes: int = DEFAULT_MODES, fillet_size: float | None = None,
                   purpose: str = "modal", **solver) -> tuple[list[CrankModal], dict]:
    """The modal analysis at three meshes (global and fillet sizes × 1, 0.8, 0.64) and the
    extrapolated first torsional frequency with its discretisation error estimate.

    ``fillet_size`` (m) defaults to :func:`fetorsion.solid.mesh.default_fillet_size` for ``purpose``.
    """
    from ..solid.mesh import default_fillet_size

    fine = fillet_size or default_fillet_size(crank, mesh_size, purpose)
    scales = [1.0, REFINE_RATIO, REFINE_RATIO**2]
    runs = [run_modal(crank, mesh_size * s, modes, fine * s, purpose=purpose, **solver) for s in scales]
    f1 = [r.first_torsional() for r in runs]
    out = extrapolate_refinement([mesh_size * s for s in scales], f1)
    out.update(sizes_m=[mesh_size * s for s in scales], fillet_sizes_m=[fine * s for s in scales],
               dofs=[r.dofs for r in runs], first_torsional_hz=f1)
    return runs, out

