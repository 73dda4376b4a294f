"""The crank condensed to master points (Craig–Bampton), in its bearings or free.

Masters, 6 DOF each, in axial order: ``front`` (pulley end face centre), ``J1`` (main-journal
centre), ``P1`` (pin centre), ``J2``, … , ``rear`` (flywheel flange face centre), tied to the
mesh and carrying the attachments as :mod:`fetorsion.fe.cranksystem` describes (the same
system the free-free modal analysis solves). Bearings act as radial springs and dampers on
the journal masters' y, z translations, a rigid bearing by holding them, a thrust bearing on
one journal's x.
The reduced matrices are those of the bare crank: supports and attachments are added on the
masters for each analysis, so one reduction serves free-free and every bearing case.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from ..description.defaults import DEFAULT_MESH_SIZE, DEFAULT_TORSIONAL_MODES
from ..description.edit import document
from ..description.model import Crank
from ..errors import FetorsionError
from ..modes import TORSION_SHARE_NOTED, TorsionalModes
from ..solid.mesh import CrankMesh
from . import assembly, modeshape
from .couplings import DOF_NAMES
from .cranksystem import SYSTEM_STAGES, CrankSystem, build_system
from .substructure import RITZ_BLOCKS, Interface, ReducedModel, craig_bampton, reduced_modes, supported_modes
from .tetmesh import TetMesh

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

    from matplotlib.axes import Axes

SUPPORTS = ("free", "bearings")
#: Elastic modes the reduction is checked on (the first 10 within 0.1 %, docs/condensed-crank.md).
CHECKED_MODES = 10


def bearing_matrices(crank: Crank, labels: list[str]):
    """(K_b N/m, C_b N·s/m, held master DOF) of the main bearings on the journal masters."""
    b = crank.main_bearings
    n = 6 * len(labels)
    Kb, Cb, held = np.zeros((n, n)), np.zeros((n, n)), []
    for j in range(len(crank.journals)):
        k = labels.index(f"J{j + 1}")
        for d in (1, 2):
            i = 6 * k + d
            if math.isinf(b.radial_stiffness[j]):
                held.append(i)
            else:
                Kb[i, i] = b.radial_stiffness[j]
                Cb[i, i] = b.radial_damping[j]
    if b.axial_stiffness > 0:
        i = 6 * labels.index(f"J{b.thrust_journal + 1}")
        if math.isinf(b.axial_stiffness):
            held.append(i)
        else:
            Kb[i, i] = b.axial_stiffness
    return Kb, Cb, np.array(sorted(held), dtype=np.int64)


def section_rows(K, basis: np.ndarray, cm: CrankMesh, dof_of_node: np.ndarray, dof_xyz: np.ndarray,
                 cuts: list[tuple[float, np.ndarray]]) -> np.ndarray:
    """Recovery rows of the internal force resultant through each cut: (cuts, 6, r).

    A cut at x = x_c splits the tetrahedra by their centroid. Let w be a rigid motion (unit
    translation or rotation about the cut centre) of the nodes that belong to left elements
    only, zero elsewhere: K w is then the left elements' stiffness acting across the cut only
    (no right element touches those nodes, and the left elements alone do not resist a rigid
    motion), so the resultant that the right part exerts on the left, by virtual work, is
    −(K w)ᵀ u. In reduced coordinates u = [Ψ Φ] z: rows −(K W)ᵀ [Ψ Φ], exact for any z.
    Components: forces x, y, z (N) and moments about x, y, z through the cut centre (N·m).
    """
    from .rigid import rigid_rows

    centroid_x = cm.nodes[cm.tets[:, :4], 0].mean(axis=1)
    # A node lies only in left elements when the largest centroid x of its elements is left of
    # the cut: one pass over the elements serves every cut.
    right_most = np.full(len(cm.nodes), -np.inf)
    np.maximum.at(right_most, cm.tets.ravel(), np.repeat(centroid_x, cm.tets.shape[1]))
    out = np.empty((len(cuts), 6, basis.shape[1]))
    n = 3 * len(dof_xyz)
    for c, (x_cut, centre) in enumerate(cuts):
        only = np.flatnonzero(right_most < x_cut)
        d = dof_of_node[only]
        d = d[d >= 0]
        R = rigid_rows(dof_xyz[d], centre)  # (nodes, 3, 6)
        W = sp.csr_array((R.reshape(-1, 6).ravel(), (np.repeat((3 * d[:, None] + np.arange(3)).ravel(), 6),
                                                      np.tile(np.arange(6), 3 * len(d)))), shape=(n, 6))
        out[c] = -np.asarray((K @ W).T @ basis)
    return out


def cut_resultants(sys_: CrankSystem, forces: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """The rows of :func:`section_rows` for cuts at x = centre x, from the nodal forces of the
    basis, ``forces`` = K [Ψ Φ] over the solved DOF (n × r): (cuts, 6, r). See :func:`cut_recovery`."""
    return cut_recovery(sys_, centres)(forces)


def cut_recovery(sys_: CrankSystem, centres: np.ndarray):
    """The map forces (n × k) ↦ :func:`cut_resultants` (cuts, 6, k), its node ordering made once
    (for :func:`fetorsion.fe.substructure.craig_bampton` ``recover``, block by block).

    The resultant through a cut is −Σ Rᵢᵀ fᵢ over the DOF of nodes in left elements only
    (:func:`section_rows`): forces Σ fᵢ and moments Σ Xᵢ × fᵢ − c × Σ fᵢ. Sorting the nodes by
    the rightmost centroid of their elements turns every cut into one more slice of a running
    sum: one pass over the DOF for all cuts, no product with K. With rigid end ties the front
    body's six solved DOF carry the face's nodal forces (its generalised force about the front
    master), left of every interior cut.
    """
    cm = sys_.mesh
    centroid_x = cm.nodes[cm.tets[:, :4], 0].mean(axis=1)
    right_most = np.full(len(cm.nodes), -np.inf)
    np.maximum.at(right_most, cm.tets.ravel(), np.repeat(centroid_x, cm.tets.shape[1]))
    used = sys_.dof_of_node >= 0
    node_key = np.full(len(sys_.xyz), np.inf)
    node_key[sys_.dof_of_node[used]] = right_most[used]
    free = sys_.free_dofs
    node, comp = free // 3, free % 3
    X = sys_.xyz[node]
    on = [(comp == k).astype(float) for k in range(3)]
    coeff = np.stack([on[0], on[1], on[2],  # forces, then moments X × f about the origin
                      X[:, 1] * on[2] - X[:, 2] * on[1], X[:, 2] * on[0] - X[:, 0] * on[2],
                      X[:, 0] * on[1] - X[:, 1] * on[0]])
    order = np.argsort(node_key[node], kind="stable")
    keys = node_key[node][order]
    centres = np.asarray(centres, float).reshape(-1, 3)
    along = np.argsort(centres[:, 0], kind="stable")
    stops = np.searchsorted(keys, centres[along, 0], side="left")

    def recover(forces: np.ndarray) -> np.ndarray:
        out = np.empty((len(centres), 6, forces.shape[1]))
        running, start = np.zeros((6, forces.shape[1])), 0
        body = None
        if sys_.T is not None:
            p = sys_.positions[0]
            g = forces[len(free):len(free) + 6]
            body = (g[:3], g[3:] + np.cross(p, g[:3].T).T)  # its force, and moment about the origin
        for c, stop in zip(along, stops):
            rows = order[start:stop]
            running += coeff[:, rows] @ forces[rows]
            start = stop
            F, Mo = running[:3].copy(), running[3:].copy()
            if body is not None:
                F += body[0]
                Mo += body[1]
            out[c, :3] = -F
            out[c, 3:] = -(Mo - np.cross(centres[c], F.T).T)
        return out

    return recover


@dataclass
class CondensedModes:
    """Modes of the condensed crank in one support condition.

    Attributes
    ----------
    support : str
        ``free`` or ``bearings``.
    frequencies_hz : ndarray
        Elastic modes, Hz (the zero-frequency motions the support leaves are in ``free_motions``).
    vectors : ndarray (r, k)
        Reduced coordinates of each elastic mode (held DOF zero), unit modal mass.
    fractions : ndarray (k, 3)
        Torsion, bending, axial shares of the journals' (and end bodies') kinetic energy.
    kinds : list of str
        ``torsional``, ``bending``, ``axial`` when one share exceeds one half, else ``coupled``.
    free_motions : int
        Zero-frequency modes (6 free-free; 1 or 2 in bearings: rotation, and axial motion
        without a thrust bearing).
    """

    support: str
    frequencies_hz: np.ndarray
    vectors: np.ndarray
    fractions: np.ndarray
    kinds: list[str]
    free_motions: int

    def rows(self) -> list[dict]:
        """Each mode as JSON: its frequency, kind and kinetic-energy shares (what ``to_dict`` keeps)."""
        return [{"frequency_hz": float(f), "kind": k, "torsional_fraction": float(fr[0]),
                 "bending_fraction": float(fr[1]), "axial_fraction": float(fr[2])}
                for f, k, fr in zip(self.frequencies_hz, self.kinds, self.fractions)]

    @classmethod
    def from_rows(cls, support: str, rows: list[dict]) -> "CondensedModes":
        """The modes back from their :meth:`rows` (the vectors and the count of zero-frequency
        motions are not kept: ``vectors`` is empty, ``free_motions`` -1)."""
        fractions = np.array([[r["torsional_fraction"], r["bending_fraction"], r["axial_fraction"]] for r in rows],
                             dtype=float).reshape(-1, 3)
        return cls(support, np.array([r["frequency_hz"] for r in rows], dtype=float), np.empty((0, len(rows))),
                   fractions, [r["kind"] for r in rows], -1)

    def first(self, count: int) -> "CondensedModes":
        """The lowest ``count`` modes."""
        return CondensedModes(self.support, self.frequencies_hz[:count], self.vectors[:, :count],
                              self.fractions[:count], list(self.kinds[:count]), self.free_motions)

    def first_torsional(self) -> float:
        idx = [i for i, k in enumerate(self.kinds) if k == "torsional"]
        if not idx:
            raise FetorsionError(f"no torsional mode among the {len(self.kinds)} condensed-crank modes ({self.support})")
        return float(self.frequencies_hz[idx[0]])

    def first_carrying_torsion(self, share: float = TORSION_SHARE_NOTED) -> float:
        """The lowest mode with at least ``share`` of its kinetic energy in torsion, Hz: the first
        mode the engine's torque drives in resonance. Where a flywheel's rocking couples torsion
        with bending, it lies below :meth:`first_torsional` (the first mostly torsional mode)."""
        from ..modes import first_with_torsion

        return first_with_torsion(self.frequencies_hz, self.fractions, share, f"condensed-crank modes ({self.support})")


@dataclass
class CondensedCrank:
    """A crank reduced to masters: see the module docstring and :func:`run_condensed`.

    Attributes
    ----------
    crank : Crank
    labels : list of str
        Master labels in axial order.
    positions : ndarray (masters, 3)
        m.
    reduced : ReducedModel
        Bare crank: K, M over (q, η); q = 6 DOF per master (tx, ty, tz, rx, ry, rz).
    attachment_mass : ndarray (6m, 6m)
        Attachments on the masters, kg / kg·m / kg·m².
    bearing_stiffness, bearing_damping : ndarray (6m, 6m)
        N/m, N·s/m.
    held : ndarray of int
        Master DOF held by rigid bearings.
    sections : ndarray (masters, 6, r)
        Recovery rows of the internal forces (N) and moments (N·m, about the master point)
        through the plane x = x_master of every master (:func:`section_rows`); the end
        masters' rows are zero (nothing lies beyond them).
    full_dofs : int
        DOF of the 3D FE model it was reduced from.
    """

    crank: Crank
    labels: list[str]
    positions: np.ndarray
    reduced: ReducedModel
    attachment_mass: np.ndarray
    bearing_stiffness: np.ndarray
    bearing_damping: np.ndarray
    held: np.ndarray
    full_dofs: int
    timings_s: dict[str, float] = field(default_factory=dict)
    sections: np.ndarray | None = field(default=None, repr=False)
    mesh: CrankMesh | None = field(default=None, repr=False)
    interface: Interface | None = field(default=None, repr=False)
    #: Recovery rows (cuts, 6, r) of the resultants through extra cuts (the fillets), about each
    #: cut's centre ``cut_centres`` (cuts, 3), m; None without.
    cut_rows: np.ndarray | None = field(default=None, repr=False)
    cut_centres: np.ndarray | None = None
    #: Coriolis (gyroscopic) matrix per unit spin speed, r × r, skew: in the crank's rotating
    #: frame M z̈ + (C + Ω G) ż + K z = f (:mod:`fetorsion.fe.rotating`; crank and attachments).
    gyroscopic: np.ndarray | None = field(default=None, repr=False)
    #: The lowest free-free modes of the reduced model, rigid ones first: (ω² rad²/s² (k,),
    #: vectors on the full system's solved DOF (solved DOF, k)), Ritz pairs of the full model
    #: (:func:`run_condensed` ``start_modes``; :func:`fetorsion.fe.crankfe.run_modal` ``ritz``);
    #: None unless asked for.
    free_ritz: tuple | None = field(default=None, repr=False)
    #: Static centrifugal load of the crank's own mass per unit Ω², (r,):
    #: order 0 in the rotating frame (the mean load cycle adds Ω² times it); None without.
    centrifugal: np.ndarray | None = field(default=None, repr=False)
    #: support -> every mode of the reduced model in it (reduced_modes' output): a run asks for the
    #: bearings' modes a dozen times (Campbell, response setup, film, dampers, fatigue), each a dense
    #: generalised eigenproblem of the whole reduced size. Not an init field, so dataclasses.replace
    #: (other bearings) starts with an empty one.
    _modes: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def n_master_dofs(self) -> int:
        return 6 * len(self.labels)

    def dof(self, label: str, name: str) -> int:
        """Reduced index of master ``label``'s DOF ``name`` (tx, ty, tz, rx, ry, rz)."""
        return 6 * self.labels.index(label) + DOF_NAMES.index(name)

    def support_terms(self, support: str):
        """(D_k, D_m, held) on the masters for ``support``."""
        if support not in SUPPORTS:
            raise FetorsionError(f"unknown support {support!r}; choose from {', '.join(SUPPORTS)}")
        if support == "free":
            return np.zeros_like(self.attachment_mass), self.attachment_mass, np.zeros(0, np.int64)
        return self.bearing_stiffness, self.attachment_mass, self.held

    def modes(self, support: str = "bearings", count: int | None = None) -> CondensedModes:
        """Elastic modes of the reduced model in ``support`` (all of them unless ``count``)."""
        if support not in self._modes:
            self._modes[support] = reduced_modes(self.reduced, *self.support_terms(support))
        w2, V, keep = self._modes[support]
        scale = max(float(np.abs(w2).max()), 1.0)
        free = int((np.abs(w2) < 1e-8 * scale).sum())
        w2, V = w2[free:], V[:, free:]
        if count is not None:
            w2, V = w2[:count], V[:, :count]
        full = np.zeros((self.reduced.size, V.shape[1]))
        full[keep] = V
        fractions, kinds = self.classify(full)
        return CondensedModes(support, np.sqrt(np.abs(w2)) / (2 * np.pi), full, fractions, kinds, free)

    def torsional_modes(self, support: str = "bearings", n: int = DEFAULT_TORSIONAL_MODES) -> TorsionalModes:
        """The lowest ``n`` elastic modes in ``support``, whatever their kind, for the Campbell
        analysis: a pin's twist is its centre's tangential displacement over the crank radius
        (the work of a tangential pin force), the pulley's the front master's θx; unit modal mass.
        Each mode carries its torsion/bending share as its label, so a coupled mode shows."""
        md = self.modes(support, n)
        engine = self.crank.engine
        R = engine.crank_radius
        from ..description.cylinders import pin_master_centre, rod_centre

        pins = np.empty((len(md.frequencies_hz), engine.cylinders))
        for c in range(engine.cylinders):  # each cylinder twists with its throw's pin (or half pin)
            t, a = engine.throw_of_cylinder(c), engine.pin_angle(c)
            P = f"P{t + 1}"
            # a split pin's master lies off each half's axis: its turn θx moves the half's centre too
            dy, dz = rod_centre(engine, c) - pin_master_centre(engine, t, self.crank.pins[t].split_angle)
            rx = md.vectors[self.dof(P, "rx")]
            ty, tz = md.vectors[self.dof(P, "ty")] - dz * rx, md.vectors[self.dof(P, "tz")] + dy * rx
            pins[:, c] = (-math.sin(a) * ty + math.cos(a) * tz) / R
        labels = tuple(f"{k} ({f[0]:.2f}/{f[1]:.2f})" for k, f in zip(md.kinds, md.fractions))
        return TorsionalModes(f"condensed FE crank, {support} ({self.reduced.size} DOF)", md.frequencies_hz, pins,
                              md.vectors[self.dof("front", "rx")], np.ones(len(md.frequencies_hz)), labels)

    def classify(self, Z: np.ndarray):
        """Torsion/bending/axial fractions and labels of reduced vectors Z (r × k) from the
        journal masters (weighted as the journal slabs) and the end bodies."""
        rho = self.crank.material.density
        energies = np.zeros((Z.shape[1], 3))
        for j, c in enumerate(self.crank.journals):
            k = self.labels.index(f"J{j + 1}")
            m = rho * math.pi * c.diameter**2 / 4 * c.length
            J = np.diag([m * c.diameter**2 / 8] + [m * (3 * c.diameter**2 / 16 + c.length**2 / 12)] * 2)
            energies += modeshape.energy_split(Z[6 * k:6 * k + 6].T, m, J)
        for label in ("front", "rear"):
            if label not in self.labels:  # a model without end bodies
                continue
            k = self.labels.index(label)
            B = self.attachment_mass[6 * k:6 * k + 6, 6 * k:6 * k + 6]
            if B[0, 0] > 0:
                energies += modeshape.energy_split(Z[6 * k:6 * k + 6].T, B[0, 0], B[3:, 3:])
        total = energies.sum(axis=1, keepdims=True)
        fractions = energies / np.where(total > 0, total, 1.0)
        kinds = [modeshape.KINDS[int(f.argmax())] if f.max() > modeshape.DOMINANT else "coupled" for f in fractions]
        return fractions, kinds

    def full_modes(self, support: str, count: int) -> np.ndarray:
        """Frequencies (Hz) of the lowest ``count`` elastic modes of the FULL 3D model with the same
        couplings, supports and attachments (the reference the reduction is checked against)."""
        if self.interface is None:
            raise FetorsionError("the full model is not kept with this condensed crank (loaded from a file?)")
        Dk, Dm, held = self.support_terms(support)
        free = 6 if support == "free" else self.modes(support, 1).free_motions
        w2, _ = supported_modes(self.interface, count + free, Dk, Dm, held)
        return np.sqrt(np.abs(w2[free:])) / (2 * np.pi)

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        out = {"masters": [{"label": lb, "position_m": [float(v) for v in p]} for lb, p in zip(self.labels, self.positions)],
               "reduced_dofs": int(self.reduced.size), "master_dofs": self.n_master_dofs,
               "interior_vectors": len(self.reduced.fixed_interface_hz),
               "interior_max_hz": float(self.reduced.fixed_interface_hz.max(initial=0.0)),
               "full_dofs": int(self.full_dofs), "timings_s": {k: float(v) for k, v in self.timings_s.items()}}
        for s in SUPPORTS:
            out[s] = self.modes(s, CHECKED_MODES).rows()
        return out

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        lines = [f"condensed crank: {len(self.labels)} masters ({', '.join(self.labels)}), {self.reduced.size} DOF "
                 f"({len(self.reduced.fixed_interface_hz)} interior vectors up to "
                 f"{self.reduced.fixed_interface_hz.max(initial=0.0):.0f} Hz) from {self.full_dofs} FE DOF",
                 f"{'mode':>4} {'free [Hz]':>10} {'kind':>10} {'bearings [Hz]':>14} {'kind':>10} {'torsion':>8}"]
        a, b = self.modes("free", CHECKED_MODES), self.modes("bearings", CHECKED_MODES)
        for j in range(min(len(a.frequencies_hz), len(b.frequencies_hz))):
            lines.append(f"{j + 1:>4} {a.frequencies_hz[j]:10.1f} {a.kinds[j]:>10} {b.frequencies_hz[j]:14.1f} "
                         f"{b.kinds[j]:>10} {b.fractions[j, 0]:8.3f}")
        return "\n".join(lines)

    def plot(self, ax=None):
        """Torsion share of each mode against frequency, free and in bearings."""
        return plot_support_modes(self.modes("free", CHECKED_MODES), self.modes("bearings", CHECKED_MODES), ax)


def plot_support_modes(free: CondensedModes, held: CondensedModes, ax: Axes | None = None) -> Axes:
    """Torsion share of each mode against frequency, free (``free``) and in bearings (``held``);
    returns the Axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 4))
    for md, mk in ((free, "o"), (held, "s")):
        ax.plot(md.frequencies_hz, md.fractions[:, 0], mk, label=f"{md.support}")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("torsion share of journal kinetic energy")
    ax.set_ylim(-0.02, 1.02)
    ax.legend()
    ax.figure.tight_layout()
    return ax


#: :func:`run_condensed`'s stages and their times (the system's, then the condensation: 10.1 s on
#: the Renault 21 at 10 mm)
CONDENSE_STAGES = {**SYSTEM_STAGES, "condensing": 10.1}


def run_condensed(crank: Crank, mesh_size: float = DEFAULT_MESH_SIZE, ritz_blocks: int = RITZ_BLOCKS,
                  fixed_interface_modes: int = 0, mesh: CrankMesh | None = None, keep_full: bool = False,
                  keep_basis: bool = False, backend: str = "auto", end_ties: str = "rigid",
                  system: CrankSystem | None = None, cuts: np.ndarray | None = None, start_modes: int = 0,
                  stage: Callable[[str], None] | None = None) -> CondensedCrank:
    """Condense the crank's FE system (:func:`fetorsion.fe.cranksystem.build_system`) to its masters.

    Parameters
    ----------
    crank : Crank
        The description (its attachments, bearings and, for the pin loads, its engine).
    mesh_size : float
        Global element size, m (ignored when ``mesh`` or ``system`` is given).
    ritz_blocks : int
        Blocks of interface Ritz vectors (6 per master each; see
        :func:`fetorsion.fe.substructure.craig_bampton`).
    fixed_interface_modes : int
        With ``ritz_blocks=0``: fixed-interface eigenmodes kept instead (classical Craig–Bampton).
    mesh : CrankMesh, optional
        A mesh of the crank to condense instead of meshing it here.
    keep_full : bool
        Keep the full model's factor (for :meth:`CondensedCrank.full_modes`).
    keep_basis : bool
        Keep the recovery basis [Ψ Φ] (n × r, large) to expand solutions onto the mesh.
    backend : str
        Factorisation backend.
    end_ties : str
        ``rigid`` (default) or ``distributing``: see :func:`fetorsion.fe.cranksystem.build_system`.
    system : CrankSystem, optional
        The crank's system built already (by the free-free modal analysis of the same run):
        its factorisation is reused, nothing is meshed or assembled again.
    cuts : array_like (k, 3), optional
        Centres of extra section cuts (the planes x = centre x), m: e.g. every fillet, with the
        pin's axis as the centre of a pin fillet; their recovery rows go to ``cut_rows``.
    start_modes : int
        Keep the lowest this many free-free modes of the reduced model, expanded onto the
        system's solved DOF, as ``free_ritz`` (the free-free modes of the same run, checked:
        :func:`fetorsion.fe.crankfe.run_modal` ``ritz``).
    stage : callable, optional
        Called with each stage's name as it starts (:data:`CONDENSE_STAGES`).

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/renault21.toml")
    >>> cc = fetorsion.run_condensed(crank, mesh_size=0.02)  # doctest: +SKIP
    >>> cc.labels[:3], cc.reduced.size < cc.full_dofs  # doctest: +SKIP
    (('front', 'J1', 'P1'), True)
    >>> cc.modes("bearings").first_torsional()  # doctest: +SKIP
    """
    t0 = time.perf_counter()
    sys_ = system or build_system(crank, mesh_size, mesh, backend, end_ties, stage=stage)
    if stage is not None:
        stage("condensing")
    itf = sys_.interface
    labels, positions = sys_.labels, sys_.positions
    centres = None if cuts is None else np.asarray(cuts, float).reshape(-1, 3)
    inner = len(positions) - 2
    every = positions[1:-1] if centres is None else np.vstack([positions[1:-1], centres])
    # the section rows are taken from each block of the basis' nodal forces as it is done
    red = craig_bampton(itf, ritz_blocks, fixed_interface_modes, keep_basis=True, recover=cut_recovery(sys_, every))
    t2 = time.perf_counter()
    sections = np.zeros((len(labels), 6, red.size))
    sections[1:-1] = red.recovered[:inner]
    extra = None if centres is None else red.recovered[inner:]
    red.recovered = None
    ritz = None
    if start_modes:
        w2, V, _ = reduced_modes(red, None, sys_.attachment_mass)
        ritz = (w2[:start_modes], red.basis @ V[:, :start_modes])
    tg = time.perf_counter()
    gyro = centrifugal = None
    if sys_.node_mass_matrix is not None:
        from .rotating import attachment_rotating_matrices, node_mass_rotating_terms

        # from the basis' y and z rows on the mesh, one at a time: never the whole expanded basis
        # beside the solved one (two 490 MB blocks at 323 k DOF)
        basis = red.basis
        gyro, centrifugal = node_mass_rotating_terms(sys_.node_mass_matrix, lambda k: sys_.component(basis, k),
                                                     sys_.xyz)
        m = 6 * len(labels)
        gyro[:m, :m] += attachment_rotating_matrices(sys_.attachment_mass, positions)[0]
        # (the load: the crank's own mass only: a pin's attachment lumps the rod's rotating mass with
        # half the reciprocating one, whose mean inertia force the pin forces carry already)
    red.basis = sys_.expand(red.basis) if keep_basis else None
    t3 = time.perf_counter()
    Kb, Cb, held = bearing_matrices(crank, labels)
    timings = {**({} if system is not None else sys_.timings_s), **red.timings_s,
               "expansion": tg - t2, "gyroscopic": t3 - tg,
               "total": time.perf_counter() - t0}
    return CondensedCrank(crank, labels, positions, red, sys_.attachment_mass, Kb, Cb, held,
                          sys_.mesh_dofs, timings, sections, sys_.mesh, itf if keep_full else None, extra, centres,
                          gyro, ritz, centrifugal)


#: Layout tag of the saved file; bump when the layout changes.
NPZ_FORMAT = "fetorsion-condensed-1"


def save_condensed(cc: CondensedCrank, path: str | Path, shapes: bool = True) -> None:
    """Write ``cc`` to an ``.npz`` file atomically (layout in docs/condensed-crank.md).

    Arrays: ``K``, ``M`` (r × r, bare crank, SI), ``n_master_dofs``, ``labels``, ``positions``
    (m), ``dof_names``, ``attachment_mass``, ``bearing_stiffness`` (N/m), ``bearing_damping``
    (N·s/m), ``held``, ``sections`` (masters × 6 × r), ``interior_hz``, ``full_dofs``,
    ``description_json`` (the description it came from) and ``format``. With the recovery
    basis kept: ``shape_nodes`` (mesh vertices, m), ``shape_tets`` (their tetrahedra) and
    ``shape_basis`` (vertices × 3 × r, float32): u(vertex) = shape_basis @ z (``shapes``: write
    them). Where the crank has them: ``cut_rows`` (cuts × 6 × r), ``cut_centres`` (m),
    ``gyroscopic`` (r × r, per rad/s) and ``centrifugal`` (r, per (rad/s)²).
    """
    import json

    from ..io import atomic_output

    arrays = dict(format=NPZ_FORMAT, K=cc.reduced.K, M=cc.reduced.M, n_master_dofs=cc.n_master_dofs,
                  labels=np.array(cc.labels), positions=cc.positions, dof_names=np.array(DOF_NAMES),
                  attachment_mass=cc.attachment_mass, bearing_stiffness=cc.bearing_stiffness,
                  bearing_damping=cc.bearing_damping, held=cc.held, sections=cc.sections,
                  interior_hz=cc.reduced.fixed_interface_hz, full_dofs=cc.full_dofs,
                  description_json=json.dumps(document(cc.crank)),
                  timings_json=json.dumps({k: float(v) for k, v in (cc.timings_s or {}).items()}))
    for name in ("cut_rows", "cut_centres", "gyroscopic", "centrifugal"):
        if getattr(cc, name) is not None:
            arrays[name] = getattr(cc, name)
    if shapes and cc.reduced.basis is not None and cc.mesh is not None:
        _, dof_of_node = assembly.skfem_mesh(TetMesh(cc.mesh.nodes, cc.mesh.tets))
        corners = cc.mesh.tets[:, :4]
        vertices, local = np.unique(corners, return_inverse=True)
        d = dof_of_node[vertices]
        rows = (3 * d[:, None] + np.arange(3)).ravel()
        arrays.update(shape_nodes=cc.mesh.nodes[vertices], shape_tets=local.reshape(corners.shape),
                      shape_basis=cc.reduced.basis[rows].reshape(len(vertices), 3, -1).astype(np.float32))
    with atomic_output(path) as tmp:
        with open(tmp, "wb") as fh:
            np.savez_compressed(fh, **arrays)


def load_condensed(path, crank: Crank | None = None) -> CondensedCrank:
    """Read a file written by :func:`save_condensed`; ``crank``: the description it was built
    from, parsed already (else parsed again from the file's copy)."""
    import json

    from ..description.crank import parse_crank

    try:
        data = np.load(path, allow_pickle=False)
        if str(data["format"]) != NPZ_FORMAT:
            raise FetorsionError(f"{path}: layout {str(data['format'])!r}, this fetorsion reads {NPZ_FORMAT!r}")
        if crank is None:
            crank = parse_crank(json.loads(str(data["description_json"])), str(path), check_uncertainty=False)
        red = ReducedModel(data["K"], data["M"], int(data["n_master_dofs"]), data["interior_hz"])
        optional = {k: data[k] for k in ("cut_rows", "cut_centres", "gyroscopic", "centrifugal") if k in data.files}
        cc = CondensedCrank(crank, [str(s) for s in data["labels"]], data["positions"], red, data["attachment_mass"],
                            data["bearing_stiffness"], data["bearing_damping"], data["held"], int(data["full_dofs"]),
                            sections=data["sections"], **optional)
        if "timings_json" in data.files:  # the condensation's, when it was built (a file before: none)
            cc.timings_s = json.loads(str(data["timings_json"]))
        return cc
    except (OSError, ValueError, KeyError) as exc:
        raise FetorsionError(f"{path}: not a condensed crank written by fetorsion ({exc})") from None
