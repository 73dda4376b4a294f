"""Second-order tetrahedral mesh of the crank solid, as numpy arrays and as files.

API for the FE modal solver
---------------------------
``mesh_crank(crank, size=DEFAULT_MESH_SIZE, fillet_size=None) -> CrankMesh`` builds the solid
(:mod:`fetorsion.solid.geometry`) and meshes it in a private Gmsh session. A :class:`CrankMesh`
holds plain numpy arrays, SI units:

``nodes``      (N, 3) float64, m; x is the crank axis, x = 0 the front (pulley) face.
``tets``       (M, 10) int64, 0-based node indices of curved 10-node tetrahedra in
               **VTK / meshio / CalculiX C3D10 order**: 4 vertices, then midside nodes on
               edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3. (Gmsh's own order swaps the last two;
               the conversion is done here, once.) Every element has positive volume.
``part``       (M,) int32, index into ``part_names`` (``journal_1``, ``web_1``, ``pin_1``,
               ..., ``front_1``, ``rear_1``): the crank part each element belongs to. Part
               boundaries are planes x = const and the mesh is conformal across them.
``part_names`` tuple of str.
``node_sets``  dict str -> (K,) int64 sorted node indices: ``front_face`` (x = 0) and
               ``rear_face`` (x = length), vertices and midside nodes.
``material``   the :class:`fetorsion.description.model.Material` (E, ν, ρ), or None.
``quality``    :class:`MeshQuality` (minimum SICN of the curved elements, counts, sizes).

``write_mesh(mesh, path)`` writes ``.msh`` (Gmsh 2.2 ASCII, part names as physical groups) or
``.vtu`` (cell data ``part``) through meshio, or
``.inp`` (CalculiX/Abaqus: C3D10, material and a free-free ``*FREQUENCY`` step), atomically.
``mesh_model(...)`` meshes whatever solid is in the current Gmsh model (used for the plain
cylinder check against CalculiX).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import gmsh
import numpy as np

from ..description.model import Crank, Material
from ..description.defaults import DEFAULT_MESH_SIZE, DEFAULT_MODES
from ..errors import FetorsionError, ParameterError
from .geometry import MODEL_UNIT, CrankSolid, build_solid, gmsh_session
from ..io import atomic_output
from .isolate import call_isolated
from .tet10 import jacobian_positive, straighten_folded

GMSH_TET10 = 11
# Gmsh numbers the last two midside nodes of a 10-node tet on edges 2-3 and 1-3; VTK,
# meshio and CalculiX put edge 1-3 first.
GMSH_TO_VTK_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])

MESH_FORMATS = (".msh", ".vtu", ".inp")


@dataclass(frozen=True)
class MeshQuality:
    """Element quality summary; sizes in m, time in s."""

    min_sicn: float  # signed inverse condition number of the curved elements, 1 is ideal, <= 0 invalid
    n_nodes: int
    n_tets: int
    size: float
    fillet_size: float
    seconds: float
    straightened: int = 0  # folded curved elements given straight edges (modal meshes)


@dataclass(frozen=True)
class CrankMesh:
    """A curved 10-node tetrahedral mesh in SI units; see the module docstring."""

    name: str
    nodes: np.ndarray
    tets: np.ndarray
    part: np.ndarray
    part_names: tuple[str, ...]
    node_sets: dict[str, np.ndarray] = field(default_factory=dict)
    material: Material | None = None
    quality: MeshQuality | None = None


def _size_fields(size: float, groups, growth: float = 1.0, expression: str = "") -> None:
    """Global size ``size``, with each ``(fine, surfaces)`` of ``groups`` setting ``fine`` on (and
    growing away from) its surfaces; model units. ``growth``: element size gained per length
    travelled away from them. ``expression``: a Gmsh MathEval size of x, y, z instead (model
    units), for a surface whose distance is known in closed form."""
    f = gmsh.model.mesh.field
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
    if expression:
        # A Distance field samples each surface at 20 x 20 parameter points: on a long, thin
        # drilling (40 mm by 12.6 mm) they lie 2 mm apart, and the mesh between them is coarser
        # than asked (a 4 mm transverse hole at "d/16" came out with 37 k nodes against 106 k at
        # 200 x 200 samples). A closed-form distance has no such gaps and costs nothing.
        m = f.add("MathEval")
        f.setString(m, "F", f"Min({size!r}, {expression})")
        f.setAsBackgroundMesh(m)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        return
    groups = [(fine, list(surfaces)) for fine, surfaces in groups if surfaces and 0 < fine < size]
    if not groups:
        return
    fields = []
    for fine, surfaces in groups:
        dist = f.add("Distance")
        f.setNumbers(dist, "SurfacesList", surfaces)
        f.setNumber(dist, "Sampling", 20)
        thr = f.add("Threshold")
        f.setNumber(thr, "InField", dist)
        f.setNumber(thr, "SizeMin", fine)
        f.setNumber(thr, "SizeMax", size)
        f.setNumber(thr, "DistMin", 0.5 * fine)
        # Size grows by about ``growth`` times the length travelled: graded, the refinement a thin
        # skin around the fillets.
        f.setNumber(thr, "DistMax", 0.5 * fine + (size - fine) / growth)
        fields.append(thr)
    if len(fields) > 1:
        smallest = f.add("Min")
        f.setNumbers(smallest, "FieldsList", fields)
        fields = [smallest]
    f.setAsBackgroundMesh(fields[0])
    # The background field decides alone; points and curvature would fight it.
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)


def mesh_model(volumes_by_part: dict[str, list[int]], node_sets: dict[str, list[int]], size: float,
               fine: float = 0.0, fine_surfaces: list[int] = (), name: str = "model",
               material: Material | None = None, untangle: str = "optimize", growth: float = 1.0,
               refine: Sequence[tuple[float, Sequence[int]]] = (), size_expression: str = "") -> CrankMesh:
    """Mesh the solid in the current (synchronised) Gmsh model with curved 10-node tets.

    Parameters
    ----------
    volumes_by_part : dict of str to list of int
        Part name -> Gmsh volume tags. Order defines the part index.
    node_sets : dict of str to list of int
        Set name -> Gmsh surface tags whose nodes form the set.
    size : float
        Global element size, model units (mm).
    fine : float
        Element size on ``fine_surfaces`` (fillets, drillings), model units; 0 for none.
    fine_surfaces : list of int
        Surface tags to refine.
    name : str
        Name carried into the result.
    material : Material, optional
        Carried into the result for writers and solvers.
    untangle : str
        What to do with curved elements that fold (midside nodes snapped onto a surface
        whose radius is below the element size): ``"optimize"`` runs Gmsh's high-order
        optimiser, which keeps every boundary node on the CAD surface (under a second when a
        few elements fold, tens of seconds for hundreds); ``"straighten"`` gives just those
        elements straight edges (:func:`~fetorsion.solid.tet10.straighten_folded`), in milliseconds, at the cost of a
        chord instead of an arc on a few fillet edges.
    growth : float
        Element size gained per length travelled away from ``fine_surfaces`` (1: the stress
        mesh's gentle grading; 2: a thinner refined skin, fewer elements).
    size_expression : str
        Element size as a Gmsh MathEval expression of x, y, z (model units), capped at ``size``;
        replaces ``fine``/``fine_surfaces``/``refine`` when given.

    Raises
    ------
    FetorsionError
        If Gmsh fails, or the curved mesh has an invalid element (SICN <= 0).
    """
    t0 = time.perf_counter()
    _size_fields(size, [(fine, fine_surfaces), *refine], growth, size_expression)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
    try:
        gmsh.model.mesh.generate(3)
        elem_tags = np.concatenate(gmsh.model.mesh.getElements(3)[1])
    except Exception as exc:
        raise FetorsionError(f"{name}: Gmsh could not mesh the solid at size {size:g} mm: {exc}") from None
    # Midside nodes snapped onto curved CAD can fold a few small elements (drillings,
    # fillet edges); Gmsh's high-order optimiser then untangles just those, in well under
    # a second. Running it always ("HighOrderOptimize") costs tens of seconds.
    if untangle == "optimize" and gmsh.model.mesh.getElementQualities(elem_tags, "minSICN").min() <= 0:
        try:
            gmsh.model.mesh.optimize("HighOrder")
        except Exception as exc:
            raise FetorsionError(f"{name}: {OPTIMISER_FAILED} at size {size:g} mm: {exc}") from None

    tags, coords, _ = gmsh.model.mesh.getNodes()
    lookup = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    lookup[tags.astype(np.int64)] = np.arange(tags.size)
    coords = coords.reshape(-1, 3)

    conn, part, elem_tags = _part_tets(volumes_by_part, lookup, name)
    sicn = gmsh.model.mesh.getElementQualities(elem_tags, "minSICN")
    straightened = 0
    if untangle == "straighten" and sicn.min() <= 0:
        coords, changed = straighten_folded(coords, conn, sicn <= 0)
        straightened = int(changed.sum())
        sicn = np.where(changed, np.inf, sicn)  # Gmsh's SICN no longer applies; checked below
        if not jacobian_positive(coords, conn[changed]).all():
            raise FetorsionError(f"{name}: straightening folded elements left {straightened} invalid; "
                                 "use a smaller fillet size")

    # Keep only nodes the tets use (Gmsh also holds nodes of lower-dimensional entities).
    used, inverse = np.unique(conn, return_inverse=True)
    renumber = np.full(coords.shape[0], -1, dtype=np.int64)
    renumber[used] = np.arange(used.size)
    sets = _surface_node_sets(node_sets, lookup, renumber)
    quality = MeshQuality(float(sicn.min()), int(used.size), int(conn.shape[0]), size * MODEL_UNIT,
                          (fine if 0 < fine < size else size) * MODEL_UNIT, time.perf_counter() - t0,
                          straightened)
    mesh = CrankMesh(name, coords[used] * MODEL_UNIT, inverse.reshape(conn.shape).astype(np.int64),
                     part, tuple(volumes_by_part), sets, material, quality)
    if quality.min_sicn <= 0:
        raise FetorsionError(f"{name}: the curved mesh at size {size:g} mm has inverted elements "
                             f"(minimum SICN {quality.min_sicn:.3f}); try another mesh size")
    return mesh


def _part_tets(volumes_by_part: dict[str, list[int]], lookup: np.ndarray, name: str):
    """(connectivity in VTK order, part index, Gmsh element tags) of the meshed volumes' tets, part by part."""
    conn, part, elem_tags = [], [], []
    for k, vols in enumerate(volumes_by_part.values()):
        for v in vols:
            types, etags, enodes = gmsh.model.mesh.getElements(3, v)
            for t, et, en in zip(types, etags, enodes):
                if t != GMSH_TET10:
                    raise FetorsionError(f"{name}: unexpected Gmsh element type {t} in volume {v}")
                conn.append(lookup[en.astype(np.int64)].reshape(-1, 10))
                part.append(np.full(et.size, k, dtype=np.int32))
                elem_tags.append(et)
    return np.concatenate(conn)[:, GMSH_TO_VTK_TET10], np.concatenate(part), np.concatenate(elem_tags)


def _surface_node_sets(node_sets: dict[str, list[int]], lookup: np.ndarray, renumber: np.ndarray) -> dict[str, np.ndarray]:
    """Set name -> sorted mesh node indices on its Gmsh surfaces (their boundaries included)."""
    sets = {}
    for set_name, surfaces in node_sets.items():
        ids = [gmsh.model.mesh.getNodes(2, s, includeBoundary=True)[0] for s in surfaces]
        ids = lookup[np.concatenate(ids).astype(np.int64)] if ids else np.zeros(0, np.int64)
        sets[set_name] = np.unique(renumber[ids])
    return sets


#: What a mesh is for: ``"modal"`` (frequencies) or ``"stress"`` (fillet stress concentration).
PURPOSES = ("modal", "stress")
#: Modal meshes: fillet and drilling elements this many times the smallest fillet or drilling
#: radius r. Chosen on f1 (docs/modal-mesh.md, Peugeot GLX, 10 mm global): 1.5 r moves f1 by
#: +0.25 % against r, 2 r by +1.0 % (with the folded elements straightened), both beyond the
#: 0.2 % the modal mesh promises, so the fillets keep their stress-mesh size r.
MODAL_FILLET_FACTOR = 1.0
#: Modal meshes: element size gained per length travelled away from the fillets. A thinner
#: refined skin (2, 18 % fewer DOF) moved the Peugeot's f1 by +0.13 % (924.05 against
#: 922.81 Hz): the fillet zone carries the frequency too, so the grading stays the stress one.
MODAL_GROWTH = 1.0


def default_fillet_size(crank: Crank, size: float, purpose: str = "stress") -> float:
    """Element size (m) on fillets and drillings, at most ``size``.

    ``"stress"``: the smallest fillet or drilling radius r; the fillet stress concentration
    needs that resolution. ``"modal"``: :data:`MODAL_FILLET_FACTOR` × r, the coarsest that
    keeps f1 within 0.2 % (docs/modal-mesh.md).
    """
    if purpose not in PURPOSES:
        raise FetorsionError(f"unknown mesh purpose {purpose!r}; choose from {PURPOSES}")
    radii = [r for r in (crank.fillets.journal, crank.fillets.pin, 0.5 * crank.oil_holes.diameter) if r > 0]
    if not radii:
        return size
    factor = MODAL_FILLET_FACTOR if purpose == "modal" else 1.0
    return float(min(factor * min(radii), size))


#: How each purpose's mesh untangles curved elements that fold on small fillets. Gmsh's
#: high-order optimiser is not deterministic (node positions differ by up to 0.06 mm between two
#: runs of the same Renault mesh) and aborts at random (ScaledJac: 6 of 12 runs of the Renault at
#: 20 mm); straightening the few folded elements (60 of 63 453 in the Renault's default mesh, 11
#: of 67 168 in the Peugeot's) is deterministic and moved f1 by +1.2e-5 and +1e-6. Stress meshes
#: keep the optimiser: a chord in a fillet would change the peak stress there.
UNTANGLE = {"modal": "straighten", "stress": "optimize"}


def mesh_solid(solid: CrankSolid, crank: Crank, size: float, fillet_size: float | None = None,
               purpose: str = "modal", untangle: str | None = None) -> CrankMesh:
    """Mesh a solid built by :func:`fetorsion.solid.geometry.build_solid` (same session).

    Parameters
    ----------
    solid : CrankSolid
    crank : Crank
        Its description (material, fillet radii).
    size : float
        Global element size, m.
    fillet_size : float, optional
        Element size on fillets and oil drillings, m; default :func:`default_fillet_size`
        for ``purpose``.
    purpose : str
        ``"modal"`` (:data:`MODAL_FILLET_FACTOR`, refinement grading :data:`MODAL_GROWTH`) or
        ``"stress"`` (fillet elements of the fillet radius, gentle grading).
    untangle : str, optional
        ``"straighten"`` or ``"optimize"`` (see :func:`mesh_model`); default :data:`UNTANGLE`
        of ``purpose``.
    """
    fine = default_fillet_size(crank, size, purpose) if fillet_size is None else fillet_size
    return mesh_model({p.name: list(p.volumes) for p in solid.parts},
                      {"front_face": list(solid.front_face), "rear_face": list(solid.rear_face)},
                      size / MODEL_UNIT, fine / MODEL_UNIT, list(solid.fillet_faces) + list(solid.hole_faces),
                      name=crank.name, material=crank.material, untangle=untangle or UNTANGLE[purpose],
                      growth=MODAL_GROWTH if purpose == "modal" else 1.0)


OPTIMISER_FAILED = "Gmsh's high-order optimiser failed"
#: The second try of a mesh whose high-order optimiser failed or aborted (ScaledJac "Failed to
#: reach critical value", seen at random under load): twice the layers of elements around each
#: folded one that the optimiser may move (Gmsh's default 6) and twice its passes (default 25),
#: so it has more room and time to untangle; the mesh itself is the same.
OPTIMISER_RETRY = {"Mesh.HighOrderNumLayers": 12, "Mesh.HighOrderPassMax": 50}


def mesh_crank(crank: Crank, size: float = DEFAULT_MESH_SIZE, fillet_size: float | None = None,
               purpose: str = "modal", untangle: str | None = None) -> CrankMesh:
    """Build and mesh ``crank`` in a private Gmsh session; see the module docstring.

    Gmsh runs in a child process (:func:`fetorsion.solid.isolate.call_isolated`), so a Gmsh
    abort is reported as a :class:`FetorsionError` instead of ending the program.

    Parameters
    ----------
    crank : Crank
    size : float
        Global element size, m.
    fillet_size : float, optional
        Element size on fillets and drillings, m (default from ``purpose``).
    purpose : str
        ``"modal"`` or ``"stress"``; see :func:`mesh_solid`.
    untangle : str, optional
        Folded-element treatment; default :data:`UNTANGLE` of ``purpose``.
    """
    what = f"{crank.name}: Gmsh, meshing at size {size * 1e3:g} mm"
    try:
        return call_isolated(_mesh_crank_here, crank, size, fillet_size, purpose, untangle, {}, what=what)
    except FetorsionError as exc:
        if (untangle or UNTANGLE[purpose]) != "optimize" or not optimiser_gave_up(exc):
            raise
        print(f"[fetorsion] {crank.name}: {exc}; meshing again with "
              + ", ".join(f"{k} {v}" for k, v in OPTIMISER_RETRY.items()), file=sys.stderr, flush=True)
    return call_isolated(_mesh_crank_here, crank, size, fillet_size, purpose, untangle, OPTIMISER_RETRY,
                         what=what + " (second try, " + ", ".join(f"{k} {v}" for k, v in OPTIMISER_RETRY.items()) + ")")


def optimiser_gave_up(exc: FetorsionError) -> bool:
    """Whether a meshing error is the high-order optimiser's: its own exception, or the meshing
    child ended by SIGABRT or SIGSEGV (Gmsh's C++ aborts past its API there; not SIGKILL, which is
    the kernel's out-of-memory killer or the user, and would only come again)."""
    text = str(exc)
    return OPTIMISER_FAILED in text or any(f"ended abnormally (signal {s})" in text for s in ("SIGABRT", "SIGSEGV"))


def _mesh_crank_here(crank: Crank, size: float, fillet_size: float | None, purpose: str,
                     untangle: str | None, options: dict) -> CrankMesh:
    with gmsh_session():
        for name, value in options.items():
            gmsh.option.setNumber(name, value)
        solid = build_solid(crank)
        return mesh_solid(solid, crank, size, fillet_size, purpose, untangle)


@dataclass(frozen=True)
class MeshEstimate:
    """Expected size of a crank mesh and of the jobs on it (about ±25 %)."""

    tets: int
    mesh_bytes: float
    modal_bytes: float
    mesh_seconds: float


# Calibrated on the plain test crank and both reference cranks at 4-20 mm (within
# -20/+10 % there): Gmsh gives about 5.5 tets per size³ of volume, and a size field graded
# away from the fine surfaces adds about 15 tets per fine-size² of their area.
_TETS_PER_CELL = 5.5
_TETS_PER_FINE_FACE = 15.0
# Peak memory per tet: 'fetorsion mesh' 0.7 kB + 0.3 GiB of libraries (247 k tets, 0.46 GiB);
# the modal job 50-62 kB (67 k tets 3.2 GiB, 247 k tets 15 GiB); both taken with margin.
_MESH_BYTES_PER_TET = 2.0e3
_MESH_BASE_BYTES = 0.35 * 2**30
_MODAL_BYTES_PER_TET = 64.0e3
_TETS_PER_SECOND = 15.0e3


def estimate_mesh(crank: Crank, size: float, fillet_size: float | None = None, purpose: str = "modal") -> MeshEstimate:
    """Estimate the tet count and peak memory of meshing ``crank`` (and of an FE modal job
    on it) from the description alone, before any Gmsh work. ``size`` and ``fillet_size`` (m) and
    ``purpose`` are :func:`mesh_crank`'s (a fillet size not given: :func:`default_fillet_size`).
    """
    from .outline import section_properties

    fine = default_fillet_size(crank, size, purpose) if fillet_size is None else min(fillet_size, size)
    shafts = (*crank.journals, *crank.pins, *crank.front, *crank.rear)
    volume = sum(0.25 * np.pi * (c.diameter**2 - c.bore**2) * c.length for c in shafts)
    volume += sum(section_properties(w, crank.engine.crank_radius)["area"] * w.thickness for w in crank.webs)
    area = 0.0  # quarter-torus fillets at both ends of every web, and the drillings' walls
    for i in range(len(crank.webs)):
        area += 0.5 * np.pi * crank.fillets.journal * np.pi * crank.journals[crank.journal_of_web(i)].diameter
        area += 0.5 * np.pi * crank.fillets.pin * np.pi * crank.pins[crank.throw_of_web(i)].diameter
    holes = crank.oil_holes
    if holes.diameter > 0:
        area += sum(np.pi * holes.diameter * c.diameter for c, used in
                    [(j, holes.in_journals) for j in crank.journals] + [(p, holes.in_pins) for p in crank.pins] if used)
    tets = _TETS_PER_CELL * volume / size**3
    if fine < size:
        tets += _TETS_PER_FINE_FACE * area * (1.0 / fine**2 - 1.0 / size**2)
    return MeshEstimate(int(tets), _MESH_BASE_BYTES + _MESH_BYTES_PER_TET * tets,
                        _MODAL_BYTES_PER_TET * tets, tets / _TETS_PER_SECOND)



# ---------------------------------------------------------------------------
# Writers


def _meshio_mesh(mesh: CrankMesh, fmt: str):
    """The mesh for meshio; the part index rides as Gmsh physical tag (1-based, named)."""
    import meshio

    if fmt == "gmsh22":
        # Format 2.2: meshio's 4.1 writer leaves out $Entities and Gmsh refuses the file.
        # meshio 5 writes int32 ElementData of an ASCII .msh as "np.int32(0)" under numpy 2,
        # which nobody can read back: the part goes in the physical tags alone.
        cell_data = {"gmsh:physical": [mesh.part + 1], "gmsh:geometrical": [mesh.part + 1]}
    else:
        cell_data = {"part": [mesh.part]}
    return meshio.Mesh(mesh.nodes, [("tetra10", mesh.tets)], cell_data=cell_data,
                       field_data={n: np.array([k + 1, 3]) for k, n in enumerate(mesh.part_names)})


def _rows(fmt: str, table: np.ndarray) -> str:
    """Format every row of ``table`` with ``fmt`` in one C-level %-operation (no row loop)."""
    if table.size == 0:
        return ""
    return ((fmt + "\n") * table.shape[0] % tuple(table.ravel().tolist())).rstrip("\n")


def _id_lines(ids: np.ndarray, per_line: int = 16) -> str:
    """1-based ids as comma-separated data lines of at most ``per_line`` entries (Abaqus limit)."""
    full = ids.size // per_line * per_line
    head = _rows(", ".join(["%d"] * per_line), ids[:full].reshape(-1, per_line))
    tail = ", ".join(str(v) for v in ids[full:].tolist())  # fewer than per_line values
    return "\n".join(t for t in (head, tail) if t)


def inp_text(mesh: CrankMesh, modes: int = DEFAULT_MODES) -> str:
    """The mesh as a CalculiX/Abaqus input deck (SI units) with a free-free frequency step.

    C3D10 elements (meshio would write C3D10MH, unknown to CalculiX), coordinates in
    fields of at most 19 characters (CalculiX rejects more than 20), element set ``EALL``
    and one per part (upper-case part name), node sets ``FRONT_FACE`` and ``REAR_FACE``.

    Parameters
    ----------
    mesh : CrankMesh
        Needs ``mesh.material``.
    modes : int
        Number of eigenfrequencies asked of ``*FREQUENCY`` (the 6 rigid-body modes included).

    Returns
    -------
    str
    """
    if mesh.material is None:
        raise FetorsionError("writing .inp needs a material")
    m = mesh.material
    n, ne = mesh.nodes.shape[0], mesh.tets.shape[0]
    # "%.12e" takes at most 19 characters for |x| < 1e100, inside CalculiX's 20; ids as
    # floats format exactly under %d (below 2⁵³).
    nodes = _rows("%d, %.12e, %.12e, %.12e", np.column_stack([np.arange(1, n + 1), mesh.nodes]))
    elements = _rows(", ".join(["%d"] * 11), np.column_stack([np.arange(1, ne + 1), mesh.tets + 1]))
    out = [f"** {mesh.name}: {ne} C3D10, {n} nodes, written by fetorsion; SI units (m, kg, s, Pa)",
           "*NODE, NSET=NALL", nodes, "*ELEMENT, TYPE=C3D10, ELSET=EALL", elements]
    elem_ids = np.arange(1, ne + 1)
    for k, name in enumerate(mesh.part_names):
        sel = elem_ids[mesh.part == k]
        if sel.size:
            out += [f"*ELSET, ELSET={name.upper()}", _id_lines(sel)]
    for name, idx in mesh.node_sets.items():
        if idx.size:
            out += [f"*NSET, NSET={name.upper()}", _id_lines(idx + 1)]
    out += ["*MATERIAL, NAME=CRANK_MATERIAL",
            "*ELASTIC", f"{m.youngs_modulus:.9e}, {m.poisson_ratio:.9f}",
            "*DENSITY", f"{m.density:.9e}",
            "*SOLID SECTION, ELSET=EALL, MATERIAL=CRANK_MATERIAL",
            "*STEP", "*FREQUENCY", f"{modes}", "*NODE FILE", "U", "*END STEP", ""]
    return "\n".join(out)


def write_mesh(mesh: CrankMesh, path: str | Path, modes: int = DEFAULT_MODES) -> Path:
    """Write ``mesh`` to ``path`` by extension (.msh, .vtu, .inp), atomically.

    Parameters
    ----------
    mesh : CrankMesh
    path : str or Path
    modes : int
        For ``.inp``: eigenfrequencies asked of the ``*FREQUENCY`` step.

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in MESH_FORMATS:
        raise FetorsionError(f"{path}: unknown mesh format '{ext}'; use one of {', '.join(MESH_FORMATS)}")
    with atomic_output(path) as tmp:
        if ext == ".inp":
            tmp.write_text(inp_text(mesh, modes), encoding="ascii")
        else:
            fmt = {".msh": "gmsh22", ".vtu": "vtu"}[ext]
            kwargs = {"binary": False} if ext == ".msh" else {}
            _meshio_mesh(mesh, fmt).write(tmp, file_format=fmt, **kwargs)
    return path


def read_mesh(path: str | Path, crank: Crank) -> CrankMesh:
    """Read back a ``.msh`` written by :func:`write_mesh` (part names ride as physical groups).

    The front and rear face node sets are found again as the nodes at x = min and x = max.
    """
    import meshio

    path = Path(path)
    if path.suffix.lower() != ".msh":
        raise ParameterError("mesh", f"{path}: give a .msh file written by fetorsion (it carries the part names)")
    try:
        m = meshio.read(path)
    except Exception as exc:  # meshio raises many kinds of errors for a bad file
        raise ParameterError("mesh", f"{path}: could not be read ({exc})") from None
    if "tetra10" not in m.cells_dict or "gmsh:physical" not in m.cell_data_dict:
        raise ParameterError("mesh", f"{path}: needs ten-node tetrahedra with physical groups")
    names = {int(v[0]): k for k, v in m.field_data.items() if int(v[1]) == 3}
    tags = np.asarray(m.cell_data_dict["gmsh:physical"]["tetra10"], dtype=int)
    part_names = tuple(names[t] for t in sorted(names))
    part = np.searchsorted(sorted(names), tags).astype(np.int32)
    tets = np.asarray(m.cells_dict["tetra10"], dtype=np.int64)
    nodes = np.asarray(m.points, dtype=float)[:, :3]
    used = np.unique(tets)
    x = nodes[used, 0]
    tol = 1e-9 * np.ptp(x) + 1e-12
    sets = {"front_face": used[x <= x.min() + tol], "rear_face": used[x >= x.max() - tol]}
    return CrankMesh(path.stem, nodes, tets, part, part_names, sets, crank.material, None)

