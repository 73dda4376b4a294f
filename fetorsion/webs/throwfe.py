"""Static FE torsion of one crank throw: its stiffness and the web's equivalent length.

A throw (journal centre to journal centre: half a journal, web, pin, web, half a journal)
is cut from a crank description as a 1-cylinder description, so the Gmsh solid and the
curved P2 mesh of :mod:`fetorsion.solid.mesh` are reused unchanged. Its end faces are tied to two
rigid bodies (:mod:`fetorsion.fe.rigid`, exact master-DOF elimination): the front body is
held fixed, the rear body carries a pure torque T about the crank axis and is otherwise
free. Between the faces every section is free to warp and the throw free to bend, so the
section resultant is a pure torque everywhere (a throw loaded by a couple is statically
determinate). One sparse Cholesky solve of K u = f gives the twist φ of the loaded body:

    k = T / φ,        L_e = G · J(D_e) / k,       J(D_e) = π D_e⁴ / 32.

The web term of [Seyedalian] eq. (6) follows by taking off the journal and pin parts, eq.
(4)–(5), and sharing the rest between the two webs:

    L_eb = ½ (L_e − L_et − L_em).

Everything the real web has beyond the simple outline (counterweight, fillets, oil
drillings, the local flexibility where web meets journal and pin) lands in L_eb, which is
what the BICERA corrections of eq. (9)–(13) tabulate.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..fe import assembly
from ..description.model import STRENGTH_FIELDS, Crank, Engine
from ..fe.eigen import factorize
from ..errors import FetorsionError
from ..fe.rigid import RigidBody, reduction, without_block
from .sections import cylinder_equivalent_length
from ..fe.tetmesh import TetMesh

if TYPE_CHECKING:
    from ..description.model import Material
    from ..fe.condensed import CondensedCrank

#: Default global element size for a throw, as a share of the main-journal diameter.
#: Sized by the convergence study in docs/web-chart.md: at D_t/6 the throw stiffness is
#: within about 0.3 % of the finest mesh tried.
MESH_SHARE = 1.0 / 6.0
#: The same for junctions without fillets (slow convergence at the sharp edges).
SHARP_MESH_SHARE = 1.0 / 12.0
#: Element size on fillets and drillings as a share of the smallest fillet or drilling
#: radius: at r/2 the GLX throw stiffness is within about 0.1 % of the finest mesh tried
#: (at r: 0.4 %).
FILLET_SHARE = 0.5
#: Applied torque, N·m. The problem is linear: any value gives the same k.
TORQUE = 1000.0
#: Environment variable naming a user cache file (JSON) of throw results; unset: none.
CACHE_ENV = "FETORSION_THROW_CACHE"
#: Throw results shipped with the package (the reference cranks' throws at the default
#: mesh), written by ``scripts/stiffness_methods.py``; read-only.
SHIPPED_CACHE = Path(__file__).with_name("data") / "throw_fe.json"
#: Part of every cache key: bump when the FE model or its defaults change, so that no
#: stale stiffness is read back.
MODEL_VERSION = "throwfe-1"


@dataclass(frozen=True)
class TorsionResult:
    """Static torsion of one shaft piece.

    Attributes
    ----------
    stiffness : float
        k = T/φ, N·m/rad.
    length : float
        Axial length between the loaded faces, m.
    nodes, elements, dofs : int
        Mesh nodes, ten-node tetrahedra, and size of the solved system.
    mesh_size, fillet_size : float
        Element sizes asked for, m.
    seconds : float
        Wall time, meshing included, s.
    """

    stiffness: float
    length: float
    nodes: int
    elements: int
    dofs: int
    mesh_size: float
    fillet_size: float
    seconds: float

    def equivalent_length(self, shear_modulus: float, d_e: float) -> float:
        """L_e = G π D_e⁴ / (32 k), m, for G in Pa and D_e in m."""
        return shear_modulus * math.pi * d_e**4 / (32.0 * self.stiffness)


def throw_of(crank: Crank, index: int) -> Crank:
    """Throw ``index`` (0-based) of ``crank`` as a 1-cylinder description.

    Half of each neighbouring journal (journal centre to journal centre), the throw's two
    webs and its pin, the crank angle set to 0 (stiffness does not depend on it), no end
    sections, attachments or excitation: only what the stiffness depends on, so equal
    throws compare (and hash) equal.

    The journal drillings are left out. A journal's one drilling lies at its mid-length, which
    is the throw's end face, held plane by the rigid coupling: the half journal cannot hold it.
    Drilled at the half journal's own mid-length (as the solid builder places a drilling) it
    would stand a quarter journal from the web, counted once in each neighbouring throw, and
    on a short journal it meets the fillet (a 20 mm journal with a 2.5 mm fillet
    and a 5 mm drilling left 0 mm between them and Gmsh failed). The pin drilling stays.

    Parameters
    ----------
    crank : Crank
        Full description, SI units.
    index : int
        0-based throw (cylinder) index.
    """
    if not 0 <= index < crank.throws:
        raise FetorsionError(f"throw {index + 1} does not exist: the crank has {crank.throws}")
    half = lambda c: dataclasses.replace(c, length=0.5 * c.length)  # noqa: E731
    e = crank.engine
    engine = Engine(cylinders=1, strokes_per_cycle=e.strokes_per_cycle, stroke=e.stroke,
                    rod_length=e.rod_length, crank_angles=(0.0,), firing_order=(1,))
    window = None
    if crank.solid_step:  # a CAD crank: the throw is its solid's slab, journal centre to journal centre
        from ..solid.geometry import MODEL_UNIT, layout

        journals = [p for p in layout(crank) if p.kind == "journal"]
        a, b = journals[index], journals[index + 1]
        window = (0.5 * (a.x0 + a.x1) * MODEL_UNIT, 0.5 * (b.x0 + b.x1) * MODEL_UNIT, -e.crank_angles[index])
    holes = crank.oil_holes
    if holes.in_journals and not crank.solid_step:  # a CAD solid's drillings are its own
        holes = dataclasses.replace(holes, in_journals=False)
    return Crank(name="throw", material=crank.material, engine=engine,
                 journals=(half(crank.journals[index]), half(crank.journals[index + 1])),
                 pins=(crank.pins[index],), webs=(crank.webs[2 * index], crank.webs[2 * index + 1]),
                 fillets=crank.fillets, oil_holes=holes, solid_step=crank.solid_step, solid_window=window,
                 solid_placement=crank.solid_placement)


def default_mesh_size(crank: Crank) -> float:
    """Global element size (m) for a throw of ``crank``: :data:`MESH_SHARE` · D_t, or
    :data:`SHARP_MESH_SHARE` · D_t when a junction has no fillet.

    A sharp re-entrant junction is a stress singularity: the web term then converges only
    as about h^1.5 (docs/web-chart.md): at D_t/6 it comes out some 4 % short, at D_t/12
    about 1.5 % (use :mod:`fetorsion.webs.chart`'s two-mesh extrapolation for better).
    """
    share = MESH_SHARE if crank.fillets.journal > 0 and crank.fillets.pin > 0 else SHARP_MESH_SHARE
    return share * min(j.diameter for j in crank.journals)


def static_torsion(mesh: TetMesh, material, fixed: str = "front_face", loaded: str = "rear_face",
                   backend: str = "auto") -> tuple[float, int]:
    """Torsional stiffness (N·m/rad) of a solid between two rigidly coupled end faces.

    Parameters
    ----------
    mesh : TetMesh
        Curved ten-node tetrahedra, m; the torque axis is the x axis through the origin.
    material : Material
        E (Pa) and ν (-).
    fixed, loaded : str
        Node-set names of the held face and of the face loaded by the torque.
    backend : str
        Factorisation backend of :func:`fetorsion.fe.eigen.factorize`.

    Returns
    -------
    k : float
        T/φ, N·m/rad.
    dofs : int
        Size of the solved system.
    """
    sol = torsion_solution(mesh, material, fixed, loaded, backend)
    return TORQUE / sol.twist, sol.dofs


@dataclass
class TorsionSolution:
    """The static torsion field: scikit-fem mesh and scalar P2 basis, the full interleaved
    displacement ``u`` (m, 3 per DOF-numbered node) under :data:`TORQUE`, the loaded face's twist
    (rad), the solved system's size, and ``dof_of_node`` (mesh node -> DOF-numbered node)."""

    skfem_mesh: object
    basis: object
    u: np.ndarray
    twist: float
    dofs: int
    dof_of_node: np.ndarray


def torsion_solution(mesh: TetMesh, material, fixed: str = "front_face", loaded: str = "rear_face",
                     backend: str = "auto") -> TorsionSolution:
    """Solve the static torsion of :func:`static_torsion` and keep the whole displacement field
    (for stresses: :mod:`fetorsion.design.scf`). Arguments as for :func:`static_torsion`."""
    return end_load_solutions(mesh, material, (TORSION_LOAD,), fixed, loaded, backend)[0]


#: The loaded face's six generalised forces (Fx, Fy, Fz, Mx, My, Mz) of the torsion case, N and N·m.
TORSION_LOAD = (0.0, 0.0, 0.0, TORQUE, 0.0, 0.0)


def end_load_solutions(mesh: TetMesh, material: Material, loads: Sequence[Sequence[float]], fixed: str = "front_face",
                       loaded: str = "rear_face", backend: str = "auto") -> list[TorsionSolution]:
    """Static fields of a solid held at one rigidly coupled end face and loaded at the other, one
    per load in ``loads`` ((Fx, Fy, Fz, Mx, My, Mz) at the loaded face's point on the x axis, N
    and N·m), from one factorisation. A pure couple at the end loads every section by that
    couple (statics). ``twist`` is the loaded face's rotation about the load's moment axis
    (rad; torsion: θx)."""
    m, dof_of_node = assembly.skfem_mesh(mesh)
    basis = assembly.p2_basis(m)
    K = assembly.stiffness(basis, material.youngs_modulus, material.poisson_ratio)
    xyz = m.doflocs.T
    bodies = []
    for name in (fixed, loaded):
        nodes = dof_of_node[mesh.node_sets[name]]
        if len(nodes) == 0 or (nodes < 0).any():
            raise FetorsionError(f"static end load: node set {name!r} is empty or not in the mesh")
        # Reference point on the x axis in the face plane: θx there is the section's twist.
        centre = np.array([xyz[nodes, 0].mean(), 0.0, 0.0])
        bodies.append(RigidBody(name, nodes, 0.0, np.zeros((3, 3)), centre))
    red = reduction(K.shape[0], bodies, xyz)
    Kr = red.reduce(K)
    # The fixed body's six DOF are dropped (q = 0 there); what is left is positive definite.
    n = red.n_free
    keep = np.r_[np.arange(n), np.arange(n + 6, n + 12)]
    Kk = without_block(Kr, n, 6)
    F = np.zeros((len(keep), len(loads)))
    F[n:n + 6] = np.asarray(loads, float).T
    solve = factorize(Kk, backend)  # symmetric: its CSR is read as it is by every backend
    Q = np.asarray(solve(F)).reshape(len(keep), len(loads))
    out = []
    for j, load in enumerate(loads):
        moment = np.asarray(load[3:], float)
        axis = moment / np.linalg.norm(moment) if np.linalg.norm(moment) > 0 else np.zeros(3)
        turn = float(axis @ Q[n + 3:n + 6, j])
        if np.linalg.norm(moment) > 0 and not turn > 0:
            raise FetorsionError(f"static end load: non-positive rotation {turn:.3g} rad (singular model?)")
        q = np.zeros(Kr.shape[0])
        q[keep] = Q[:, j]
        out.append(TorsionSolution(m, basis, red.T @ q, turn, len(keep), dof_of_node))
    return out


def torsional_stiffness_fe(description: Crank, mesh_size: float | None = None,
                           fillet_size: float | None = None) -> TorsionResult:
    """Torsional stiffness of a crank description (front face fixed, rear face twisted).

    Parameters
    ----------
    description : Crank
        Usually a throw from :func:`throw_of`; any description works.
    mesh_size : float, optional
        Global element size, m (default :func:`default_mesh_size`).
    fillet_size : float, optional
        Element size on fillets and drillings, m (default :data:`FILLET_SHARE` times the
        smallest fillet or drilling radius, at most ``mesh_size``).

    Returns
    -------
    TorsionResult
    """
    from ..solid.mesh import default_fillet_size

    size = default_mesh_size(description) if mesh_size is None else mesh_size
    fine = FILLET_SHARE * default_fillet_size(description, size) if fillet_size is None else fillet_size
    fe = end_loaded_fe(description, size, fine)
    nodes = fe.mesh.nodes
    length = float(nodes[:, 0].max() - nodes[:, 0].min())
    return TorsionResult(TORQUE / fe.solutions[0].twist, length, len(nodes), len(fe.mesh.tets), fe.solutions[0].dofs, size,
                         fine, fe.seconds)


#: Bending in the throw's plane (about z) at the loaded face, N·m.
BENDING_LOAD = (0.0, 0.0, 0.0, 0.0, 0.0, TORQUE)
#: The six unit end loads (Fx, Fy, Fz, Mx, My, Mz) at the loaded face's centre, N and N·m: the
#: ``fe`` fatigue path's stress recovery (:func:`fetorsion.design.recovery.throw_zones`).
UNIT_LOADS = tuple(tuple(float(i == j) for i in range(6)) for j in range(6))
#: The end loads every :func:`end_loaded_fe` solves from its one factorisation: torsion (the web
#: stiffness), bending in the throw's plane (with torsion, the fillet SCFs of
#: :func:`fetorsion.design.scf.throw_scfs`) and the six unit loads (the stress recovery). A
#: right-hand side more costs a pair of triangular solves; a second mesh and factorisation of the
#: same throw cost 15-40 s.
END_LOADS = (TORSION_LOAD, BENDING_LOAD, *UNIT_LOADS)


@dataclass
class EndLoadedFE:
    """A description meshed and solved for :data:`END_LOADS` (one :class:`TorsionSolution` each):
    the mesh (:class:`fetorsion.solid.mesh.CrankMesh`), the sizes (m) and the seconds it took."""

    mesh: object
    solutions: list
    size: float
    fine: float
    seconds: float


#: The last :func:`end_loaded_fe`, by its key: one throw's web stiffness (the lumped ``fe``
#: column, in the run's bearings step) and its fillet SCFs (the verdict) are one FE, not two.
_LAST_END_LOADED: dict = {}


def end_loaded_fe(description: Crank, size: float, fine: float) -> EndLoadedFE:
    """``description`` meshed with the stress purpose (curved P2 tetrahedra, Gmsh's optimiser on
    folded elements, ``fine`` on fillets and drillings) and held at its front face, loaded at its
    rear face by each of :data:`END_LOADS` from one factorisation. The last one is kept in memory,
    so the second user of the same description and sizes finds it solved."""
    from ..solid.mesh import mesh_crank

    key = (throw_key(description, size), fine)
    if key in _LAST_END_LOADED:
        return _LAST_END_LOADED[key]
    _LAST_END_LOADED.clear()  # before the new one is built: one at a time in memory
    t0 = time.perf_counter()
    cm = mesh_crank(description, size, fine, "stress")
    mesh = TetMesh(cm.nodes, cm.tets, cm.node_sets)
    sols = end_load_solutions(mesh, description.material, END_LOADS)
    fe = _LAST_END_LOADED[key] = EndLoadedFE(cm, sols, size, fine, time.perf_counter() - t0)
    return fe


# ---------------------------------------------------------------------------
# Web equivalent length, cached per distinct throw geometry

_CACHE: dict[str, dict] = {}


def part_key(c) -> dict:
    """A journal or pin as a dict for a cache key: its split-pin fields only when it is split, so
    an unsplit part's key (and the shipped entries) stay what they were before split pins."""
    return {k: v for k, v in dataclasses.asdict(c).items() if c.split or k not in ("split_angle", "flying_web")}


def throw_key(throw: Crank, mesh_size: float | None) -> str:
    """A stable text key of a throw's stiffness-relevant data and the mesh size."""
    fields = {"material": dataclasses.asdict(throw.material), "stroke": throw.engine.stroke,
              "journals": [part_key(j) for j in throw.journals],
              "pins": [part_key(p) for p in throw.pins],
              "webs": [dataclasses.asdict(w) for w in throw.webs],
              "fillets": dataclasses.asdict(throw.fillets), "oil_holes": dataclasses.asdict(throw.oil_holes),
              "mesh_size": mesh_size, "model": MODEL_VERSION}
    if throw.solid_step:  # a CAD crank's throw: its solid's content and the slab, not the dimensions alone
        fields["solid"] = (hashlib.sha256(Path(throw.solid_step).read_bytes()).hexdigest(), throw.solid_window,
                           throw.solid_placement)
    for key in ("name", *STRENGTH_FIELDS):  # what the stiffness does not depend on
        fields["material"].pop(key, None)
    text = json.dumps(fields, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def _cache_file() -> Path | None:
    path = os.environ.get(CACHE_ENV, "")
    return Path(path) if path else None


def _load_disk(path: Path | None = None) -> dict:
    path = _cache_file() if path is None else path
    if path is None or not path.exists():
        return {}
    try:
        return json.loads(path.read_text())
    except (OSError, json.JSONDecodeError):
        return {}  # a broken cache is only a lost speed-up


def _save_disk(key: str, entry: dict) -> None:
    path = _cache_file()
    if path is None:
        return
    data = _load_disk()
    data[key] = entry
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + f".{os.getpid()}.tmp")
    tmp.write_text(json.dumps(data, indent=1, sort_keys=True))
    os.replace(tmp, path)


def stored_throw_torsion(throw: Crank, mesh_size: float | None = None) -> dict | None:
    """:func:`throw_torsion`'s entry when it needs no FE (in memory, shipped or in the user's
    file), else None."""
    key = throw_key(throw, mesh_size)
    return _CACHE.get(key) or _load_disk(SHIPPED_CACHE).get(key) or _load_disk().get(key)


def remember_throw_torsion(entries: dict[str, dict[str, float]]) -> None:
    """Keep ``{throw key: entry}`` (:func:`throw_torsion`'s, computed in another process) in memory."""
    _CACHE.update(entries)


def forget_end_loaded() -> None:
    """Let go of the last :func:`end_loaded_fe` kept in memory."""
    _LAST_END_LOADED.clear()


def throw_torsion(throw: Crank, mesh_size: float | None = None) -> dict:
    """:func:`torsional_stiffness_fe` of ``throw`` as a dict of the :class:`TorsionResult`
    fields, cached: in memory, then the package's :data:`SHIPPED_CACHE`, then the user file
    named by :data:`CACHE_ENV` (written to when set); computed only when all miss."""
    key = throw_key(throw, mesh_size)
    if key not in _CACHE:
        entry = stored_throw_torsion(throw, mesh_size)
        if entry is None:
            entry = dataclasses.asdict(torsional_stiffness_fe(throw, mesh_size))
            _save_disk(key, entry)
        _CACHE[key] = entry
    return _CACHE[key]


def throw_equivalent_length_fe(throw: Crank, d_e: float, mesh_size: float | None = None) -> float:
    """FE equivalent length of a whole throw description, reduced to D_e, m."""
    k = throw_torsion(throw, mesh_size)["stiffness"]
    return throw.material.shear_modulus * math.pi * d_e**4 / (32.0 * k)


def web_term(throw: Crank, l_throw: float, d_e: float) -> float:
    """½ (L_e − L_et − L_em): the throw length less eq. (4) for its two journal halves and
    eq. (5) for its pin, per web, m (all at D_e)."""
    l_j = sum(cylinder_equivalent_length(j, d_e) for j in throw.journals)
    l_m = cylinder_equivalent_length(throw.pins[0], d_e)
    return 0.5 * (l_throw - l_j - l_m)


def web_equivalent_length_fe(crank: Crank, web_index: int, d_e: float, mesh_size: float | None = None) -> float:
    """Web method ``fe``: L_eb (m, at D_e) of web ``web_index`` from its throw's FE stiffness.

    The two webs of a throw share the throw's web term equally.

    Parameters
    ----------
    crank : Crank
        Full description, SI units.
    web_index : int
        0-based web index.
    d_e : float
        Equivalent (reduction) diameter, m.
    mesh_size : float, optional
        Global element size, m (default :func:`default_mesh_size` of the throw).
    """
    throw = throw_of(crank, crank.throw_of_web(web_index))
    return web_term(throw, throw_equivalent_length_fe(throw, d_e, mesh_size), d_e)


# ---------------------------------------------------------------------------
# Reference shafts for the checks


def stepped_shaft_mesh(d: float, D: float, l_small: float, l_large: float, fillet: float,
                       size: float, fillet_size: float | None = None) -> TetMesh:
    """A round bar of diameter d (length l_small) then D (length l_large) along +x, the
    re-entrant corner rounded with radius ``fillet``; curved ten-node tets.

    Parameters
    ----------
    d, D : float
        Smaller and larger diameter, m.
    l_small, l_large : float
        Lengths of the two sections, m (the fillet eats into the small one).
    fillet : float
        Fillet radius, m (0: sharp corner).
    size : float
        Global element size, m.
    fillet_size : float, optional
        Element size on the fillet, m (default ``fillet / 2``).

    Returns
    -------
    TetMesh
        With node sets ``front_face`` (x = 0) and ``rear_face`` (x = l_small + l_large).
    """
    import gmsh

    from ..solid.geometry import MODEL_UNIT, circle_curves, gmsh_session
    from ..solid.mesh import mesh_model

    s = 1.0 / MODEL_UNIT
    with gmsh_session("stepped_shaft"):
        occ = gmsh.model.occ
        a = occ.addCylinder(0, 0, 0, l_small * s, 0, 0, 0.5 * d * s)
        b = occ.addCylinder(l_small * s, 0, 0, l_large * s, 0, 0, 0.5 * D * s)
        out, _ = occ.fuse([(3, a)], [(3, b)])
        vol = out[0][1]
        occ.synchronize()
        fine_faces = []
        if fillet > 0:
            edges = circle_curves(occ, l_small * s, (0.0, 0.0), 0.5 * d * s)
            vol = occ.fillet([vol], edges, [fillet * s] * len(edges))[0][1]
            occ.synchronize()
            fine_faces = [t for _, t in gmsh.model.getEntities(2) if gmsh.model.getType(2, t) == "Torus"]
        ends = {}
        for name, x in (("front_face", 0.0), ("rear_face", (l_small + l_large) * s)):
            box = (x - 1e-3, -1e9, -1e9, x + 1e-3, 1e9, 1e9)
            ends[name] = [t for _, t in gmsh.model.getEntitiesInBoundingBox(*box, 2)]
        fine = (0.5 * fillet if fillet_size is None else fillet_size) if fillet > 0 else size
        cm = mesh_model({"shaft": [vol]}, ends, size * s, fine * s, fine_faces, name="stepped shaft")
    return TetMesh(cm.nodes, cm.tets, cm.node_sets)


# ---------------------------------------------------------------------------
# Throws inside the whole crank held by rigid bearings (docs/condensed-crank.md)


def held_key(crank: Crank, mesh_size: float) -> str:
    """A stable key of what the in-bearing throw stiffnesses depend on."""
    # the engine's geometry only: its cylinders, rods and firing (vee banks, rod offsets) do not
    # change a stiffness, and a field added to the engine must not orphan the shipped entries
    engine = {"stroke": crank.engine.stroke, "crank_angles": list(crank.engine.crank_angles)}
    fields = {"material": dataclasses.asdict(crank.material), "engine": engine,
              "journals": [part_key(j) for j in crank.journals],
              "pins": [part_key(p) for p in crank.pins],
              "webs": [dataclasses.asdict(w) for w in crank.webs],
              "front": [part_key(c) for c in crank.front], "rear": [part_key(c) for c in crank.rear],
              "fillets": dataclasses.asdict(crank.fillets), "oil_holes": dataclasses.asdict(crank.oil_holes),
              "widths": list(crank.main_bearings.width), "mesh_size": mesh_size, "model": MODEL_VERSION + "-held"}
    for key in ("name", *STRENGTH_FIELDS):  # what the stiffness does not depend on
        fields["material"].pop(key, None)
    return hashlib.sha256(json.dumps(fields, sort_keys=True, default=repr).encode()).hexdigest()[:20]


def held_stiffnesses_stored(crank: Crank, mesh_size: float | None = None) -> bool:
    """True when :func:`held_throw_stiffnesses` of ``crank`` needs no FE (shipped, cached or in memory)."""
    from ..description.defaults import DEFAULT_MESH_SIZE

    key = held_key(crank, DEFAULT_MESH_SIZE if mesh_size is None else mesh_size)
    return key in _CACHE or key in _load_disk(SHIPPED_CACHE) or key in _load_disk()


def held_throw_stiffnesses(crank: Crank, mesh_size: float | None = None,
                           condensed: CondensedCrank | None = None) -> np.ndarray:
    """Torsional stiffness (N·m/rad) of each throw (journal centre to journal centre) inside the
    whole crank with every main journal held radially by a rigid bearing (distributing
    couplings over the bearing surfaces, tilt free), from one static FE solve: the front end's
    twist held, a torque on the flywheel end, k_i = T / (θ_{J i+1} − θ_{J i}).

    Unlike a single throw loaded by a couple (statically determinate: holding its ends
    sideways changes nothing), the crank in five bearings is statically indeterminate: the
    bearings resist the throws' bending under torque. Cached like :func:`throw_torsion`;
    ``condensed`` (a :class:`fetorsion.fe.condensed.CondensedCrank` of this crank at
    ``mesh_size``) saves the reduction when one exists.
    """
    from ..description.defaults import DEFAULT_MESH_SIZE
    from ..fe.condensed import run_condensed

    size = DEFAULT_MESH_SIZE if mesh_size is None else mesh_size
    key = held_key(crank, size)
    if key not in _CACHE:
        entry = _load_disk(SHIPPED_CACHE).get(key) or _load_disk().get(key)
        if entry is None:
            cc = condensed or run_condensed(dataclasses.replace(crank, attachments=(), excitation=None), size)
            entry = {"stiffness": static_throw_stiffnesses(cc).tolist(), "mesh_size": size, "full_dofs": cc.full_dofs}
            _save_disk(key, entry)
        _CACHE[key] = entry
    k = np.array(_CACHE[key]["stiffness"])
    if not np.all(k > 0):
        raise FetorsionError("in-bearing throw stiffness: a non-positive value (singular model?)")
    return k


def static_throw_stiffnesses(cc) -> np.ndarray:
    """Each throw's stiffness (N·m/rad) from a static solve of the condensed crank ``cc`` with its
    journal centres held in y and z (rigid bearings, whatever ``cc``'s own bearings are)."""
    K = cc.reduced.K
    n_j = len(cc.crank.journals)
    held = [cc.dof(f"J{j + 1}", d) for j in range(n_j) for d in ("ty", "tz")] + [cc.dof("front", "rx"),
                                                                                 cc.dof("front", "tx")]
    keep = np.setdiff1d(np.arange(K.shape[0]), held)
    f = np.zeros(K.shape[0])
    f[cc.dof("rear", "rx")] = TORQUE
    z = np.zeros(K.shape[0])
    z[keep] = np.linalg.solve(K[np.ix_(keep, keep)], f[keep])
    twist = np.array([z[cc.dof(f"J{j + 1}", "rx")] for j in range(n_j)])
    return TORQUE / np.diff(twist)


def web_equivalent_length_held(crank: Crank, web_index: int, d_e: float,
                               stiffnesses: np.ndarray | None = None) -> float:
    """Web method ``fe-held``: L_eb (m, at D_e) of web ``web_index`` from its throw's stiffness
    inside the whole crank in rigid bearings (``stiffnesses``, N·m/rad per throw; default
    :func:`held_throw_stiffnesses` at the default mesh size)."""
    i = crank.throw_of_web(web_index)
    k = (held_throw_stiffnesses(crank) if stiffnesses is None else stiffnesses)[i]
    l_throw = crank.material.shear_modulus * math.pi * d_e**4 / (32.0 * k)
    return web_term(throw_of(crank, i), l_throw, d_e)
