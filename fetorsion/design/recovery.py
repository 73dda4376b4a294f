"""Local stress at the fillets and oil bores, recovered from unit end loads and the cut loads.

A fillet's stress is not its pure-couple SCF times the cut's bending moment: a throw's sections
carry shear forces, axial force and moments about both axes as well, and under a rod force the
fillets' stress follows the shear as much as the moment (the pin fillet reads 0.64x and the
journal fillet 2.19x the pure-couple prediction in an independent recovery). Quasi-static stress recovery, as
FEMFAT and AVL EXCITE do with unit loads ([Rennert]'s local approach takes the local stress
tensor so found):

    σ(x, t) = Σ_j S_j(x) L_j(t),        j = 1 … 6,

S_j the stress field of the sub-model under a unit end load j (three forces, three moments at the
loaded face's centre; front face held; one factorisation, six right-hand sides) and L(t) the
section load history of the cut at the location, moved into the sub-model's frame and carried
to the loaded face by statics. A sub-model held at its front face and loaded at its rear face
carries that load through every section (a statically determinate cantilever), so any cut
between the faces sees exactly the rear load moved to the cut's centre: L_rear = (F, M + (c − p)
× F) for a cut resultant (F, M) about c and the loaded face's centre p.

Sub-models: each throw (:func:`fetorsion.webs.throwfe.throw_of`, journal centre to journal
centre, its pin drilling kept, the journal drillings left to the bar below: they sit on the
throw's end faces), whose four fillet zones (the nodes of :func:`fetorsion.design.scf.fillet_zone`
on the surface) read their own cut; and each drilled kind of section as the bar with a
transverse hole of :mod:`fetorsion.design.oilbore` (the drilling's wall), which reads the mean
of its pin's (journal's) fillet cuts moved to the drilling's centre.

Only surface nodes are kept, with their tangent frame: at a free surface the stress is plane,
(σ₁₁, σ₂₂, σ₁₂) in (e₁, e₂); the criterion (:mod:`fetorsion.design.criterion`) reads those.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..errors import FetorsionError
from ..webs.throwfe import UNIT_LOADS  # the six unit end loads, N and N·m

if TYPE_CHECKING:
    from collections.abc import Callable
    from ..description.model import Crank

#: Part of every stored field's key: bump when the sub-models or the zones change.
MODEL_VERSION = "recovery-2"
#: The recovered fields' folder in the store.
FOLDER = "recovery"

#: Faces of a tetrahedron by the vertex each one leaves out, and the VTK 10-node mid-edge node of
#: each vertex pair.
_FACES = ((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2))
_EDGE = {(0, 1): 4, (1, 2): 5, (0, 2): 6, (0, 3): 7, (1, 3): 8, (2, 3): 9}


def surface_normals(nodes: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Outward unit normal at every node of a 10-node tetrahedral mesh on its boundary (area-weighted
    over the boundary faces it belongs to), zero at interior nodes: (nodes, 3)."""
    faces = tets[:, :4][:, _FACES]  # (E, 4, 3)
    n = len(nodes)
    key = np.sort(faces, axis=2).astype(np.int64)
    code = (key[..., 0] * n + key[..., 1]) * n + key[..., 2]
    _, inv, count = np.unique(code.ravel(), return_inverse=True, return_counts=True)
    e, k = np.divmod(np.flatnonzero(count[inv] == 1), 4)
    a, b, c = (nodes[faces[e, k, i]] for i in range(3))
    normal = np.cross(b - a, c - a)
    opposite = nodes[tets[e, k]]
    normal *= np.where(np.einsum("ij,ij->i", normal, opposite - a) > 0, -1.0, 1.0)[:, None]
    out = np.zeros((n, 3))
    for i in range(3):
        np.add.at(out, faces[e, k, i], normal)
    verts = np.array(_FACES)[k]  # local vertex numbers of each boundary face
    for i, j in ((0, 1), (1, 2), (0, 2)):
        lo, hi = np.minimum(verts[:, i], verts[:, j]), np.maximum(verts[:, i], verts[:, j])
        mid = np.array([_EDGE[(int(p), int(q))] for p, q in zip(lo, hi)], dtype=np.int64)
        np.add.at(out, tets[e, mid], normal)
    length = np.linalg.norm(out, axis=1)
    on = length > 0
    out[on] /= length[on, None]
    return out


def tangent_frames(normals: np.ndarray) -> np.ndarray:
    """(nodes, 2, 3): e₁, e₂ tangent to the surface (e₁ as near the x axis as the normal allows,
    e₂ = n × e₁)."""
    ref = np.where(np.abs(normals[:, :1]) < 0.9, np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, 1.0, 0.0]]))
    e1 = ref - np.einsum("ij,ij->i", ref, normals)[:, None] * normals
    e1 /= np.linalg.norm(e1, axis=1)[:, None]
    return np.stack([e1, np.cross(normals, e1)], axis=1)


def node_stresses(sol, material, dofs: np.ndarray) -> np.ndarray:
    """Stress tensors (len(dofs), 3, 3), Pa, at DOF-numbered nodes ``dofs`` of a solution, each the
    average over the elements sharing the node of the element's P2 gradient at that node (the
    nodal averaging of :func:`fetorsion.design.scf.nodal_stress`, on those elements only)."""
    return node_stresses_of([sol], material, dofs)[0]


def node_stresses_of(sols, material, dofs: np.ndarray) -> np.ndarray:
    """:func:`node_stresses` of each of ``sols`` (solutions on one mesh), (len(sols), len(dofs), 3,
    3) Pa: the elements at the nodes and their basis found once for all of them."""
    from .scf import element_node_stresses, nodes_basis

    element_dofs = sols[0].basis.element_dofs  # (10, E): the solutions' scalar P2 numbering
    wanted = np.zeros(element_dofs.max() + 1, bool)
    wanted[dofs] = True
    at_nodes = nodes_basis(sols[0].skfem_mesh, np.flatnonzero(wanted[element_dofs].any(axis=0)))
    slot = np.full(wanted.size, -1)
    slot[dofs] = np.arange(len(dofs))
    out = np.empty((len(sols), len(dofs), 3, 3))
    for j, sol in enumerate(sols):
        flat, local = element_node_stresses(sol, material, basis=at_nodes)
        keep = slot[local] >= 0
        idx = slot[local[keep]]
        total = np.stack([np.bincount(idx, flat[c, keep], minlength=len(dofs)) for c in range(9)], axis=1)
        count = np.bincount(idx, minlength=len(dofs))
        out[j] = (total / np.maximum(count, 1)[:, None]).reshape(-1, 3, 3)
    return out


@dataclass(frozen=True)
class StressZone:
    """The surface nodes of one fillet or drilling in its sub-model, with their unit-load stresses.

    Attributes
    ----------
    name : str
        ``journal fillet, web 1``, …, ``oil bore``.
    kind : str
        ``pin-fillet``, ``journal-fillet`` or ``oil-bore``.
    xyz : ndarray (nodes, 3)
        Positions in the sub-model's frame, m.
    frames : ndarray (nodes, 2, 3)
        Tangent unit vectors e₁, e₂ at each node.
    influence : ndarray (nodes, 3, 6)
        (σ₁₁, σ₂₂, σ₁₂) in (e₁, e₂) per unit end load (Pa per N, Pa per N·m).
    loaded : ndarray (3,)
        The loaded face's centre, where the unit loads act, m.
    normal_residual : float
        The largest traction on the surface |σ n| at any node and load over the largest stress:
        zero at an exact free surface (the nodal averaging's error there).
    """

    name: str
    kind: str
    xyz: np.ndarray
    frames: np.ndarray
    influence: np.ndarray
    loaded: np.ndarray
    normal_residual: float = 0.0


def zone_of(name: str, kind: str, sols, material, mask: np.ndarray, normals: np.ndarray, loaded) -> StressZone:
    """The :class:`StressZone` of the DOF nodes ``mask`` that lie on the surface (``normals``
    over DOF nodes) under the six unit solutions ``sols``."""
    dofs = np.flatnonzero(mask & (np.linalg.norm(normals, axis=1) > 0.5))
    if len(dofs) == 0:
        raise FetorsionError(f"{name}: no surface node in the zone (is its radius > 0?)")
    frames = tangent_frames(normals[dofs])
    n = normals[dofs]
    influence = np.empty((len(dofs), 3, 6))
    residual, largest = 0.0, 0.0
    e1, e2 = frames[:, 0], frames[:, 1]
    for j, sig in enumerate(node_stresses_of(sols, material, dofs)):
        influence[:, 0, j] = np.einsum("ni,nij,nj->n", e1, sig, e1)
        influence[:, 1, j] = np.einsum("ni,nij,nj->n", e2, sig, e2)
        influence[:, 2, j] = np.einsum("ni,nij,nj->n", e1, sig, e2)
        residual = max(residual, float(np.linalg.norm(np.einsum("nij,nj->ni", sig, n), axis=1).max()))
        largest = max(largest, float(np.abs(sig).max()))
    xyz = sols[0].skfem_mesh.doflocs.T[dofs]
    return StressZone(name, kind, xyz, frames, influence, np.asarray(loaded, float),
                      residual / largest if largest > 0 else 0.0)


def dof_normals(mesh, dof_of_node: np.ndarray, count: int) -> np.ndarray:
    """:func:`surface_normals` of a TetMesh carried onto the DOF-numbered nodes."""
    normals = surface_normals(mesh.nodes, mesh.tets)
    out = np.zeros((count, 3))
    used = dof_of_node >= 0
    out[dof_of_node[used]] = normals[used]
    return out


def _loaded_centre(sol, mesh, name: str = "rear_face") -> np.ndarray:
    xyz = sol.skfem_mesh.doflocs.T
    nodes = sol.dof_of_node[mesh.node_sets[name]]
    return np.array([xyz[nodes, 0].mean(), 0.0, 0.0])


def throw_zones(crank, index: int, size: float | None = None, fine: float | None = None) -> list[StressZone]:
    """The four fillet zones of throw ``index`` (journal, web 1; pin, web 1; pin, web 2; journal,
    web 2) under the six unit end loads at its rear face (front face held): the throw's one FE
    (:func:`fetorsion.webs.throwfe.end_loaded_fe`, the same mesh and factorisation as its web
    stiffness and fillet SCFs at these sizes)."""
    from ..solid.mesh import default_fillet_size
    from ..webs.throwfe import END_LOADS, default_mesh_size, end_loaded_fe, throw_of
    from .scf import DEFAULT_FILLET_SHARE, found_zones, fillet_zone, found_zone

    throw = throw_of(crank, index)
    size = default_mesh_size(throw) if size is None else size
    fine = DEFAULT_FILLET_SHARE * default_fillet_size(throw, size, "stress") if fine is None else fine
    fe = end_loaded_fe(throw, size, fine)
    mesh = fe.mesh
    sols = [fe.solutions[END_LOADS.index(u)] for u in UNIT_LOADS]
    xyz = sols[0].skfem_mesh.doflocs.T
    normals = dof_normals(mesh, sols[0].dof_of_node, len(xyz))
    j1, j2 = throw.journals
    w1, w2 = throw.webs
    pin = throw.pins[0]
    R = throw.engine.crank_radius
    x = np.cumsum([0.0, j1.length, w1.thickness, pin.length, w2.thickness])
    rj, rp = crank.fillets.journal, crank.fillets.pin
    found = found_zones(crank, index, throw)
    masks = ([found_zone(xyz, *f) for f in found] if found
             else [fillet_zone(xyz, x[1], -1, (0, 0), 0.5 * j1.diameter, rj),
                   fillet_zone(xyz, x[2], +1, (R, 0), 0.5 * pin.diameter, rp),
                   fillet_zone(xyz, x[3], -1, (R, 0), 0.5 * pin.diameter, rp),
                   fillet_zone(xyz, x[4], +1, (0, 0), 0.5 * j2.diameter, rj)])
    loaded = _loaded_centre(sols[0], mesh)
    names = ("journal fillet, web 1", "pin fillet, web 1", "pin fillet, web 2", "journal fillet, web 2")
    kinds = ("journal-fillet", "pin-fillet", "pin-fillet", "journal-fillet")
    return [zone_of(nm, kd, sols, throw.material, m, normals, loaded) for nm, kd, m in zip(names, kinds, masks)]


def bore_zone(diameter: float, hole: float, bore: float, material, share: float | None = None,
              exits_only: bool = True) -> StressZone:
    """The drilling's wall of the bar with a transverse hole (:func:`fetorsion.design.oilbore.transverse_hole_mesh`:
    bar along x, 2 · 1.5 D long, hole along y at mid-length) under the six unit end loads at its
    rear face. ``exits_only``: the wall is fine near the drilling's exits only, where the peaks
    are (a quarter of the time: on the Renault's pin, 10 862 wall nodes against 36 026, 7.6 s
    against 29.3 s, pure-case peaks within 0.6 % of the fully refined wall's)."""
    from ..solid.isolate import call_isolated
    from ..webs.throwfe import end_load_solutions
    from .oilbore import HALF_LENGTH, OIL_BORE_SHARES, WALL_SLACK, check_hole, transverse_hole_mesh

    check_hole(diameter, hole, bore)
    share = OIL_BORE_SHARES[0] if share is None else share
    mesh = call_isolated(transverse_hole_mesh, diameter, hole, bore, share * hole, exits_only,
                         what="Gmsh, transverse hole")
    sols = end_load_solutions(mesh, material, UNIT_LOADS)
    xyz = sols[0].skfem_mesh.doflocs.T
    normals = dof_normals(mesh, sols[0].dof_of_node, len(xyz))
    wall = np.hypot(xyz[:, 0] - HALF_LENGTH * diameter, xyz[:, 2]) <= 0.5 * hole * (1 + WALL_SLACK)
    return zone_of("oil bore", "oil-bore", sols, material, wall, normals, _loaded_centre(sols[0], mesh))


# ---------------------------------------------------------------------------
# Stored fields


def _key(payload: dict) -> str:
    from ..io import code_hash

    text = json.dumps({**payload, "model": MODEL_VERSION, "code": code_hash()}, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


def _material_key(material) -> dict:
    return {"E": material.youngs_modulus, "nu": material.poisson_ratio}


def throw_zone_key(crank, index: int) -> str:
    """The stored key of throw ``index``'s zones: its geometry, material's elasticity, the code."""
    from ..webs.throwfe import throw_key, throw_of

    return _key({"throw": throw_key(throw_of(crank, index), None), "kind": "throw"})


def bore_zone_key(diameter: float, hole: float, bore: float, material) -> str:
    """The stored key of a drilled section's zone."""
    return _key({"bar": [diameter, hole, bore], "material": _material_key(material), "kind": "bore"})


def _folder(store=None) -> Path:
    from ..io import default_store

    return Path(store if store is not None else default_store()) / FOLDER


def _save(zones: list[StressZone], path: Path) -> None:
    from ..io import atomic_output

    data = {}
    for i, z in enumerate(zones):
        data.update({f"{i}_xyz": z.xyz, f"{i}_frames": z.frames, f"{i}_influence": z.influence,
                     f"{i}_loaded": z.loaded, f"{i}_meta": np.array(json.dumps([z.name, z.kind, z.normal_residual]))})
    with atomic_output(path) as tmp:
        with open(tmp, "wb") as fh:
            np.savez(fh, count=np.array(len(zones)), **data)


def _load(path: Path) -> list[StressZone] | None:
    try:
        with np.load(path) as d:
            out = []
            for i in range(int(d["count"])):
                name, kind, residual = json.loads(str(d[f"{i}_meta"]))
                out.append(StressZone(name, kind, d[f"{i}_xyz"], d[f"{i}_frames"], d[f"{i}_influence"],
                                      d[f"{i}_loaded"], float(residual)))
            return out
    except Exception:  # noqa: BLE001 - any unreadable file of ours is built again, never trusted
        return None


def stored_zones(key: str, build, store=None) -> list[StressZone]:
    """The zones stored under ``key``, else ``build()``'s, stored (atomically) for the next run;
    the least recently used fields go first once the folder passes the share of the store's bound
    the condensed cranks have (:func:`fetorsion.fe.store.trim`, a folder of its own)."""
    from ..fe.store import trim

    path = _folder(store) / f"{key}.npz"
    if path.exists():
        zones = _load(path)
        if zones is not None:
            os.utime(path)  # least recently used goes first
            return zones
        path.unlink(missing_ok=True)  # ours, unreadable: built again
    zones = build()
    try:
        _save(zones, path)
        trim(path.parent, keep=path)
    except OSError:
        pass  # a store that cannot be written is only a lost speed-up
    return zones


# ---------------------------------------------------------------------------
# The crank's locations: which zone reads which cuts, and how


def throw_rotation(angle: float) -> np.ndarray:
    """Rotation about x by ``angle`` (rad)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _skew(v) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def load_map(rotation: np.ndarray, cut: np.ndarray, loaded: np.ndarray) -> np.ndarray:
    """The 6 × 6 map from a cut resultant (F, M about the cut's centre; crank frame) to the
    sub-model's rear-face load: F' = R F, M' = R M + (c' − p) × R F, with ``cut`` c' the cut's
    centre and ``loaded`` p the loaded face's centre, both in the sub-model's frame."""
    A = np.zeros((6, 6))
    A[:3, :3] = rotation
    A[3:, 3:] = rotation
    A[3:, :3] = _skew(np.asarray(cut) - np.asarray(loaded)) @ rotation
    return A


@dataclass(frozen=True)
class Location:
    """One assessed place of the crank: its zone, the cuts it reads and how.

    ``cuts`` are indices into the load cycle's cuts; ``maps`` (len(cuts), 6, 6) take each cut's
    resultant to the zone's rear-face load, and the location reads their mean (an oil bore: the
    two fillet cuts of its pin moved to the drilling's centre). ``diameter`` (m) is the section's,
    ``notch_radius`` (m) the fillet's radius or half the drilling's diameter."""

    label: str
    kind: str
    zone: StressZone
    cuts: tuple
    maps: np.ndarray
    diameter: float
    notch_radius: float

    def rear_loads(self, history: np.ndarray) -> np.ndarray:
        """(..., 6, angles) rear-face loads from a cycle's history (..., cuts, 6, angles)."""
        h = history[..., list(self.cuts), :, :]
        return np.einsum("cij,...cjt->...it", self.maps, h) / len(self.cuts)

    def stresses(self, loads: np.ndarray, nodes=None) -> np.ndarray:
        """(..., nodes, 3, angles) in-plane stress at the zone's nodes (all, or ``nodes``) under
        rear-face loads (..., 6, angles)."""
        P = self.zone.influence if nodes is None else self.zone.influence[nodes]
        return np.einsum("nck,...kt->...nct", P, loads, optimize=True)


def throw_index(crank, fillets, f) -> int:
    """0-based throw whose web the fillet ``f`` meets."""
    if f.kind == "pin":
        i = f.index
    else:
        i = f.index if f.x >= _journal_centre(crank, fillets, f) else f.index - 1
    return min(max(i, 0), crank.throws - 1)


def _bar_sections(crank):
    """{kind: (diameter, drilling, bore)} of each drilled kind of section (its first pin or journal
    stands for all: one number in practice, as :func:`fetorsion.design.oilbore.oil_bore_scfs`)."""
    holes = crank.oil_holes
    if holes is None or not holes.diameter > 0:
        return {}
    out = {}
    for kind, drilled, parts in (("pin", holes.in_pins, crank.pins), ("journal", holes.in_journals, crank.journals)):
        if drilled and parts:
            out[kind] = (parts[0].diameter, holes.diameter, parts[0].bore)
    return out


def stored_throw_zones(crank: Crank, index: int, store: str | Path | None = None) -> list[StressZone]:
    """:func:`throw_zones` of throw ``index`` from the store, or computed and stored."""
    return stored_zones(throw_zone_key(crank, index), lambda: throw_zones(crank, index), store)


def crank_zones(crank: Crank, store: str | Path | None = None, progress: Callable[[str], None] | None = None) -> dict:
    """Every distinct throw's fillet zones and every drilled kind of section's bar zone of ``crank``,
    from the store or computed once each (and stored): ``{("throw", i): [4 zones], ("bar", kind):
    zone}``. The run computes them in its background process, first, beside the FE steps."""
    say = progress or (lambda m: None)
    out, seen = {}, {}
    for i in range(crank.throws):
        key = throw_zone_key(crank, i)
        if key not in seen:
            if not (_folder(store) / f"{key}.npz").exists():
                say(f"  stress recovery: throw {i + 1} under six unit end loads (static 3D FE) ...")
            seen[key] = stored_throw_zones(crank, i, store)
        out[("throw", i)] = seen[key]
    for kind, (D, d, bore) in _bar_sections(crank).items():
        key = bore_zone_key(D, d, bore, crank.material)
        if key not in seen:
            if not (_folder(store) / f"{key}.npz").exists():
                say(f"  stress recovery: the {kind} oil bore under six unit end loads (static 3D FE) ...")
            seen[key] = stored_zones(key, lambda D=D, d=d, bore=bore: [bore_zone(D, d, bore, crank.material)], store)
        out[("bar", kind)] = seen[key][0]
    return out


def zones_stored(crank: Crank, store: str | Path | None = None) -> bool:
    """True when every zone :func:`crank_zones` needs is in the store."""
    keys = {throw_zone_key(crank, i) for i in range(crank.throws)}
    keys |= {bore_zone_key(D, d, b, crank.material) for D, d, b in _bar_sections(crank).values()}
    return all((_folder(store) / f"{k}.npz").exists() for k in keys)


def crank_locations(crank, fillets, cut_centres: np.ndarray, store=None, progress=None,
                    zones: dict | None = None) -> list[Location]:
    """Every fillet of ``fillets`` (the load cycle's cuts, about ``cut_centres`` (cuts, 3), m) as a
    :class:`Location` in its throw's zone, then every drilled pin and journal in its bar's
    (:func:`fetorsion.design.assessment.oil_bore_sections`), on ``zones`` (default
    :func:`crank_zones`)."""
    from .assessment import oil_bore_sections

    zones = crank_zones(crank, store, progress) if zones is None else zones
    angles = np.asarray(crank.engine.crank_angles, float)
    origins = [throw_origin(crank, fillets, i) for i in range(crank.throws)]  # one throw_of each
    out = []
    for k, f in enumerate(fillets):
        i = throw_index(crank, fillets, f)
        throw = zones[("throw", i)]
        if f.kind == "pin":
            lo, hi = _pin_span(fillets, i)
            z = throw[1] if f.x < 0.5 * (lo + hi) else throw[2]
        else:
            z = throw[0] if f.index == i else throw[3]
        R = throw_rotation(-angles[i])
        c = R @ (cut_centres[k] - np.array([origins[i], 0.0, 0.0]))
        radius = crank.fillets.pin if f.kind == "pin" else crank.fillets.journal
        out.append(Location(f.label, z.kind, z, (k,), load_map(R, c, z.loaded)[None], f.diameter, radius))
    for b in oil_bore_sections(crank, fillets):
        z = zones[("bar", b.kind)]
        # the bar's frame: x along the section's axis, y along the drilling (the throw's tangent
        # e_t at angle a), z = x × y = −e_r; the drilling at its mid-length on the axis
        a = b.angle
        rows = np.array([[1.0, 0.0, 0.0], [0.0, -math.sin(a), math.cos(a)], [0.0, -math.cos(a), -math.sin(a)]])
        axis = cut_centres[b.cuts[0]][1:]
        centre = np.array([_section_mid(crank, fillets, b), axis[0], axis[1]])
        hole = np.array([0.5 * z.loaded[0], 0.0, 0.0])
        maps = np.array([load_map(rows, rows @ (cut_centres[j] - centre) + hole, z.loaded) for j in b.cuts])
        out.append(Location(b.label, "oil-bore", z, tuple(b.cuts), maps, b.diameter, 0.5 * crank.oil_holes.diameter))
    return out


def _journal_centre(crank, fillets, f) -> float:
    """x of the centre of the journal a journal fillet ``f`` sits on, m."""
    same = [g.x for g in fillets if g.kind == "journal" and g.index == f.index]
    length = crank.journals[f.index].length
    if len(same) == 2:
        return 0.5 * (same[0] + same[1])
    # an end journal has one fillet: its web is on the side towards the crank's middle
    return f.x - 0.5 * length if f.index == 0 else f.x + 0.5 * length


def throw_origin(crank, fillets, i: int) -> float:
    """x (crank frame) of throw ``i``'s front journal centre (the throw model's x = 0), m; a CAD
    crank's throw slab starts where its window does."""
    from ..webs.throwfe import throw_of

    t = throw_of(crank, i)
    if t.solid_window is not None:
        return float(t.solid_window[0])
    front = [g for g in fillets if g.kind == "journal" and g.index == i]
    return _journal_centre(crank, fillets, front[-1]) if front else 0.0


def _pin_span(fillets, i: int) -> tuple[float, float]:
    xs = [g.x for g in fillets if g.kind == "pin" and g.index == i]
    return min(xs), max(xs)


def _section_mid(crank, fillets, b) -> float:
    """x (crank frame) of a drilled section's mid-length (its drilling), m."""
    i = int(b.label[1:].split(" ")[0]) - 1
    if b.kind == "pin":
        lo, hi = _pin_span(fillets, i)
        return 0.5 * (lo + hi)
    f = [g for g in fillets if g.kind == "journal" and g.index == i][0]
    return _journal_centre(crank, fillets, f)
