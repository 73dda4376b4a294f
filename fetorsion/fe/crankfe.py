"""3D FE modal analysis of a crank description: its free-free modes, labelled.

The crank's FE system (:mod:`fetorsion.fe.cranksystem`: the curved P2 mesh, the pulley hub and
flywheel flange as rigid end bodies, every journal and pin coupled to a master, the piston +
rod as a point mass on each pin master through a distributing coupling) is solved free-free
from its one factorisation (:func:`fetorsion.fe.substructure.supported_modes`); the condensed
crank of the same run reduces the same system, so both give the same free-free frequencies.
The main journals are the slabs whose rigid twist identifies torsional modes.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field, fields
from typing import TYPE_CHECKING

import numpy as np

from ..modes import TorsionalModes
from ..description.model import Crank
from ..description.defaults import DEFAULT_MESH_SIZE, DEFAULT_MODES, DEFAULT_TORSIONAL_MODES
from ..errors import FetorsionError
from ..results import from_fields
from ..extrapolation import richardson
from ..solid.mesh import CrankMesh, MeshQuality
from . import modeshape
from .cranksystem import ENDS, SYSTEM_STAGES, CrankSystem, build_system, end_body
from .modal import ModalResult, split_rigid
from .modeshape import slab_fit
from .rigid import rigid_rows
from .substructure import ritz_error_bounds, supported_modes

if TYPE_CHECKING:
    from collections.abc import Callable

#: Stated error of the default modal mesh (10 mm global, fillet elements of the fillet
#: radius) on the first torsional frequency, relative: against each crank's finest (4 mm)
#: mesh, f1 is +0.11 % (Peugeot GLX, 1.15 M DOF) and +0.24 % (Renault 21, 1.03 M DOF) high
#: (docs/modal-mesh.md); ``--refine`` estimates it for other cranks.
MODAL_F1_ERROR = 2.5e-3
#: Ritz frequencies (the condensed crank's) stand for the FE model's own when their guaranteed
#: error is below this: a tenth of the default mesh's discretisation error (MODAL_F1_ERROR).
RITZ_ACCEPT = MODAL_F1_ERROR / 10


def part_nodes(cm: CrankMesh, name: str) -> np.ndarray:
    """Nodes of the elements of part ``name`` (``journal_1``, ``pin_2``, ...)."""
    try:
        k = cm.part_names.index(name)
    except ValueError:
        raise FetorsionError(f"the mesh has no part {name!r}") from None
    return np.unique(cm.tets[cm.part == k])


@dataclass
class CrankModal(ModalResult):
    """FE modal result of a crank: a :class:`~fetorsion.fe.modal.ModalResult` that also holds
    the crank, the mesh it was computed on (for pictures and the Campbell hand-off) and its FE
    system (factorised: the condensed crank of the same run reduces it)."""

    crank: Crank | None = field(default=None, repr=False)
    mesh: CrankMesh | None = field(default=None, repr=False)
    system: CrankSystem | None = field(default=None, repr=False)
    #: The mesh's quality where the mesh itself is not kept (a result read back, :meth:`from_dict`).
    quality_read: MeshQuality | None = field(default=None, repr=False)

    @property
    def quality(self) -> MeshQuality | None:
        """The quality of the mesh the modes were computed on (None: not known)."""
        return self.mesh.quality if self.mesh is not None else self.quality_read

    def to_dict(self) -> dict:
        """:meth:`ModalResult.to_dict` and the mesh's quality (``mesh_quality``: minimum SICN, folded
        elements straightened, sizes)."""
        q = self.quality
        return {**super().to_dict(), **({} if q is None else {"mesh_quality": asdict(q)})}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "CrankModal":
        """The result back from its :meth:`to_dict` (without the crank, mesh and FE system it
        held). A result written before the mesh's quality was kept gives only its minimum SICN."""
        q = d.get("mesh_quality")
        if q is None and d.get("min_sicn") is not None:  # a run's entry: its minimum SICN alone
            q = {"min_sicn": d["min_sicn"], "n_nodes": d["mesh"]["nodes"], "n_tets": d["mesh"]["elements"],
                 "size": d.get("mesh_size_m", float("nan")), "fillet_size": float("nan"), "seconds": float("nan")}
        modal = ModalResult.from_dict.__func__(cls, d)
        modal.mesh = None  # the key "mesh" holds its sizes, not a CrankMesh
        modal.quality_read = None if q is None else from_fields(MeshQuality, q)
        return modal

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
        from ..description.cylinders import per_cylinder

        pins = np.stack([twist(part_nodes(self.mesh, f"pin_{i + 1}")) for i in range(self.crank.throws)], axis=1)
        pins = per_cylinder(self.crank.engine, pins, axis=1)  # each cylinder twists with its throw
        return TorsionalModes(f"FE ({self.dofs} DOF)", self.frequencies_hz[idx], pins,
                              twist(self.mesh.node_sets["front_face"]), np.ones(len(idx)))


#: :func:`run_modal`'s stages and their times (the system's, then the eigensolve and the modes'
#: identification: 1.0 s and ~1 s on the Renault 21 at 10 mm)
MODAL_STAGES = {**SYSTEM_STAGES, "eigensolving": 2.0}


def run_modal(crank: Crank, mesh_size: float = DEFAULT_MESH_SIZE, modes: int = DEFAULT_MODES, fillet_size: float | None = None,
              mesh: CrankMesh | None = None, purpose: str = "modal", backend: str = "auto",
              system: CrankSystem | None = None, ritz: tuple[np.ndarray, np.ndarray] | None = None,
              stage: Callable[[str], None] | None = None) -> CrankModal:
    """Free-free FE modes of a crank with its attachments.

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
    backend : str
        Factorisation backend (:func:`fetorsion.fe.eigen.factorize`).
    system : CrankSystem, optional
        The crank's FE system built already (then nothing is meshed, assembled or factorised);
        the result keeps it (``.system``) for the condensed crank of the same run.
    ritz : tuple (ω² (k,), X (solved DOF, k)), optional
        Ritz pairs of this system's free-free problem, six rigid ones first (the condensed
        crank's of the same run, ``CondensedCrank.free_ritz``). They are the result when one
        block solve bounds every elastic frequency's error within :data:`RITZ_ACCEPT`
        (:func:`fetorsion.fe.substructure.ritz_error_bounds`; the bounds are kept as
        ``error_bound``); otherwise the block Lanczos starts from them.
    stage : callable, optional
        Called with each stage's name as it starts (:data:`MODAL_STAGES`).
    """
    t0 = time.perf_counter()
    sys_ = system or build_system(crank, mesh_size, mesh, backend, fillet_size=fillet_size, purpose=purpose,
                                  stage=stage)
    t1 = time.perf_counter()
    if stage is not None:
        stage("eigensolving")
    itf = sys_.interface
    method, bound = "block", None
    if ritz is not None and len(ritz[0]) >= modes + 6:
        w2, X = np.asarray(ritz[0][:modes + 6], float), np.asarray(ritz[1][:, :modes + 6])
        bound = ritz_error_bounds(itf, w2[6:], X[:, 6:], Dm=sys_.attachment_mass)[0]
        if bound.max() <= RITZ_ACCEPT:
            method = "condensed Ritz"
        else:
            bound = None
            w2, X = supported_modes(itf, modes + 6, Dm=sys_.attachment_mass, start=X)
    else:
        w2, X = supported_modes(itf, modes + 6, Dm=sys_.attachment_mass)
    rigid, elastic = split_rigid(w2, itf.sigma)
    t2 = time.perf_counter()
    cm, xyz = sys_.mesh, sys_.xyz
    U = sys_.expand(X[:, 6:]).T.reshape(len(elastic), -1, 3)  # (modes, DOF nodes, 3)
    slabs = []
    for k in range(crank.throws + 1):
        d = sys_.dof_of_node[part_nodes(cm, f"journal_{k + 1}")]
        slabs.append(d[d >= 0])
    bodies, body_motion = [], {}
    for label, at, outward in ENDS:
        body = end_body(crank, at)
        if body is None:
            continue
        mass, inertia, offset = body
        k = sys_.labels.index(label)
        q = np.asarray(itf.G[[6 * k + i for i in range(6)]] @ X[:, 6:]).T  # (modes, 6) at the master
        centre = sys_.positions[k] + np.array([outward * offset, 0.0, 0.0])
        L = np.eye(6)
        L[:3, 3:] = rigid_rows(centre[None], sys_.positions[k])[0, :, 3:]
        p = q @ L.T  # (t, θ) at the body's centre of mass
        body_motion[label] = p
        if mass > 0:
            bodies.append((p, mass, inertia))
    fractions, kinds, fit = modeshape.identify(U, xyz, sys_.node_mass, slabs, bodies)
    shapes = np.zeros((len(elastic), len(cm.nodes), 3))
    used = sys_.dof_of_node >= 0
    shapes[:, used] = U[:, sys_.dof_of_node[used]]
    t3 = time.perf_counter()
    hz = lambda w: np.sqrt(np.abs(w)) / (2 * np.pi)  # noqa: E731
    timings = {**(sys_.timings_s if system is None else {}), "eigensolve": t2 - t1, "identify": t3 - t2,
               "total": t3 - t0}
    res = ModalResult(hz(elastic), kinds, fractions, fit, hz(rigid), int(used.sum()), len(cm.tets), sys_.dofs,
                      crank.material, timings, shapes, body_motion, backend, method, bound)
    return CrankModal(**{f.name: getattr(res, f.name) for f in fields(ModalResult)}, crank=crank, mesh=cm,
                      system=sys_)


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
                   purpose: str = "modal", backend: str = "auto") -> tuple[list[CrankModal], dict]:
    """The modal analysis at three meshes (global and fillet sizes × 1, 0.8, 0.64) and the
    extrapolated first torsional frequency with its discretisation error estimate.

    ``fillet_size`` (m) defaults to :func:`fetorsion.solid.mesh.default_fillet_size` for ``purpose``.
    """
    from ..solid.mesh import default_fillet_size

    fine = fillet_size or default_fillet_size(crank, mesh_size, purpose)
    scales = [1.0, REFINE_RATIO, REFINE_RATIO**2]
    runs = [run_modal(crank, mesh_size * s, modes, fine * s, purpose=purpose, backend=backend) for s in scales]
    f1 = [r.first_torsional() for r in runs]
    out = extrapolate_refinement([mesh_size * s for s in scales], f1)
    out.update(sizes_m=[mesh_size * s for s in scales], fillet_sizes_m=[fine * s for s in scales],
               dofs=[r.dofs for r in runs], first_torsional_hz=f1)
    return runs, out

