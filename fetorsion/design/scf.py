"""Torsional stress concentration factors at fillets from fetorsion's own static 3D FE.

A throw (or a stepped shaft) is twisted by a pure torque T between two rigid end faces
(:func:`fetorsion.webs.throwfe.torsion_solution`). A throw loaded by a couple about the crank
axis is statically determinate: every pin and journal section carries exactly the torque T
(a moment about an axis parallel to its own), so its nominal shear stress is the elementary

    τ_nom = 16 T D / (π (D⁴ − d_i⁴))      (D the section's diameter, d_i its bore),

and the stress concentration factor of a fillet is the peak of the largest shear stress
(σ₁ − σ₃)/2 on that fillet over τ_nom. Stresses are recovered at the nodes: each element's
P2 displacement gradient is evaluated at its own ten nodes and the stress tensors of the
elements sharing a node are averaged (the usual nodal averaging; the peak lies on the
surface, where quadrature points never are).

The check against a published value is the stepped round bar in torsion: the curve fit of
Peterson's chart for a shoulder fillet in torsion (Pilkey & Pilkey, *Peterson's Stress
Concentration Factors*, 3rd ed., Wiley 2008, chapter 3, stepped bar of circular cross
section in torsion), as printed by eng-calculations.com ("Peterson's Stress Concentration
Factors / Shoulder fillets / Torsion of a shaft with a shoulder fillet", 0.25 ≤ t/r ≤ 4) and by
AMES Web ("Stepped shaft with shoulder fillet", torsion) — see :func:`peterson_stepped_torsion`.

The classification societies' empirical crank fillet factors (IACS UR M53, "Calculation of
crankshafts for I.C. engines", Rev.1 Dec 2004 / Rev.2 Jan 2011: §2.2 alternating torsional
stresses, §3.2–3.3 SCFs of crankpin and journal fillets, §3.4 oil bore outlet, Appendix III an
FE procedure for the SCFs) are not implemented: no readable text of their formulas was found
(the copies seen give the table of contents or a garbled extraction), and they are not
reconstructed from memory.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..description.model import Crank
from ..errors import FetorsionError
from ..fe.assembly import lame
from ..webs.throwfe import BENDING_LOAD, TORQUE, TORSION_LOAD, default_mesh_size, stepped_shaft_mesh, throw_of
from .scfset import SCFSet

#: Nodes within this share of the fillet radius outside the fillet's nominal zone still count
#: as the fillet (the curved mesh's nodes sit on the true surface up to round-off).
ZONE_SLACK = 0.05


def peterson_stepped_torsion(D: float, d: float, r: float) -> float:
    """Kts of a stepped round bar in torsion (shoulder fillet), Peterson's curve fit.

    Kts = C1 + C2 (2h/D) + C3 (2h/D)² + C4 (2h/D)³, h = (D − d)/2, with C_i = a + b √(h/r) + c h/r
    from Pilkey & Pilkey, *Peterson's Stress Concentration Factors* (3rd ed., 2008), shoulder
    fillets, stepped bar of circular cross section in torsion, as printed (with its signs) on
    eng-calculations.com, "Torsion of a shaft with a shoulder fillet" (0.25 ≤ t/r ≤ 4.0; the same
    coefficients on AMES Web's "Stepped shaft with shoulder fillet"). Nominal stress
    τ_nom = 16 T / (π d³).

    Parameters
    ----------
    D, d : float
        Larger and smaller diameter, m (any one length unit).
    r : float
        Fillet radius, same unit.
    """
    h = 0.5 * (D - d)
    hr = h / r
    if not 0.25 <= hr <= 4.0:
        raise FetorsionError(f"Peterson's torsion fit holds for 0.25 <= h/r <= 4, got h/r = {hr:.3g}")
    s = math.sqrt(hr)
    c = (0.905 + 0.783 * s - 0.075 * hr, -0.437 - 1.969 * s + 0.553 * hr,
         1.557 + 1.073 * s - 0.578 * hr, -1.061 + 0.171 * s + 0.086 * hr)
    t = 2 * h / D
    return c[0] + c[1] * t + c[2] * t**2 + c[3] * t**3


def _shoulder_fit(D: float, d: float, r: float, low, high, hr_min: float, name: str) -> float:
    """Kt = C1 + C2 (2h/D) + C3 (2h/D)² + C4 (2h/D)³ with C_i = a + b √(h/r) + c h/r, the (a, b, c)
    rows ``low`` for h/r ≤ 2 and ``high`` above (hr_min ≤ h/r ≤ 20)."""
    h = 0.5 * (D - d)
    hr = h / r
    if not hr_min <= hr <= 20.0:
        raise FetorsionError(f"{name}'s bending fit holds for {hr_min:g} <= h/r <= 20, got h/r = {hr:.3g}")
    s = math.sqrt(hr)
    t = 2 * h / D
    return sum((a + b * s + c * hr) * t**k for k, (a, b, c) in enumerate(low if hr <= 2.0 else high))


def peterson_stepped_bending(D: float, d: float, r: float) -> float:
    """Kt of a stepped round bar in bending (shoulder fillet), Peterson's curve fit (Pilkey &
    Pilkey, *Peterson's Stress Concentration Factors*, 3rd ed., chapter 3, stepped bar in
    bending), as printed on AMES Web, "Stepped shaft with shoulder fillet" (0.1 ≤ h/r ≤ 20; one
    coefficient set to h/r = 2, another above). Same form and nominal stress as
    :func:`roark_stepped_bending`."""
    return _shoulder_fit(D, d, r, ((0.947, 1.206, -0.131), (0.022, -3.405, 0.915), (0.869, 1.777, -0.555),
                                   (-0.810, 0.422, -0.260)),
                         ((1.232, 0.832, -0.008), (-3.813, 0.968, -0.260), (7.423, -4.868, 0.869),
                          (-3.839, 3.070, -0.600)), 0.1, "Peterson")


def roark_stepped_bending(D: float, d: float, r: float) -> float:
    """Kt of a stepped round bar in bending (square shoulder with a fillet), the curve fit of
    [Roark] Table 17.1 (after Peterson's charts), as printed on eng-calculations.com, "Square
    shoulder with fillet in circular shaft for elastic stress, bending" (0.25 ≤ h/r ≤ 20):
    Kt = C1 + C2 (2h/D) + C3 (2h/D)² + C4 (2h/D)³, C_i = a + b √(h/r) + c h/r, one coefficient
    set for h/r ≤ 2 and another above. Nominal stress σ_nom = 32 M / (π d³).

    Parameters
    ----------
    D, d : float
        Larger and smaller diameter (any one length unit).
    r : float
        Fillet radius, same unit.
    """
    return _shoulder_fit(D, d, r, ((0.927, 1.149, -0.086), (0.015, -3.281, 0.837), (0.847, 1.716, -0.506),
                                   (-0.790, 0.417, -0.246)),
                         ((1.225, 0.831, -0.010), (-3.790, 0.958, -0.257), (7.374, -4.834, 0.862),
                          (-3.809, 3.046, -0.595)), 0.25, "Roark")


def nominal_bending(moment, diameter: float, bore: float = 0.0):
    """σ_nom = 32 M D / (π (D⁴ − d_i⁴)), Pa, for a bending moment M (N·m), outer diameter D and bore d_i (m)."""
    return 32.0 * np.asarray(moment) * diameter / (math.pi * (diameter**4 - bore**4))


def nominal_shear(torque, diameter: float, bore: float = 0.0):
    """τ_nom = 16 T D / (π (D⁴ − d_i⁴)), Pa, for torque T (N·m, scalar or array), outer
    diameter D and bore d_i (m)."""
    return 16.0 * np.asarray(torque) * diameter / (math.pi * (diameter**4 - bore**4))


def nodes_basis(skfem_mesh, elements=None):
    """The scalar P2 basis of ``skfem_mesh`` (``elements`` only, default all) whose quadrature
    "points" are each element's own ten nodes: the gradient there, element by element."""
    from skfem import Basis, ElementTetP2

    elem = ElementTetP2()
    return Basis(skfem_mesh, elem, quadrature=(elem.doflocs.T, np.full(10, 1.0 / 60.0)),
                 **({} if elements is None else {"elements": elements}))


def element_node_stresses(sol, material, elements=None, basis=None) -> tuple[np.ndarray, np.ndarray]:
    """Each element's stress at its own ten nodes, from its P2 gradient there: (9, E·10) tensor
    components (Pa, element-major) and the DOF-numbered node of each column. ``elements``: those
    elements only (default all); ``basis``: :func:`nodes_basis` of them, built already."""
    at_nodes = nodes_basis(sol.skfem_mesh, elements) if basis is None else basis
    u = sol.u.reshape(-1, 3)
    # Σ_i u(node i of the element) ∇φ_i at the element's nodes, as scikit-fem's interpolate sums it,
    # without its per-call split of the basis (a np.unique over every element's DOFs: 1 s of a
    # throw's stress recovery, 108 calls)
    dphi = np.stack([field[0].grad for field in at_nodes.basis])  # (10 shape functions, dir, E, 10 nodes)
    grad = np.einsum("iec,ideq->cdeq", u[at_nodes.element_dofs], dphi, optimize=True)  # (comp, dir, E, 10)
    eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
    lam, mu = lame(material.youngs_modulus, material.poisson_ratio)
    sig = 2 * mu * eps + lam * np.trace(eps)[None, None] * np.eye(3)[:, :, None, None]
    return sig.reshape(9, -1), at_nodes.element_dofs.T.ravel()  # element-major, matching sig's (E, 10)


def nodal_stress(sol, material, measure=None) -> tuple[np.ndarray, np.ndarray]:
    """Stress at every DOF-numbered node, from each element's P2 gradient at its own nodes.

    Returns the stress tensors averaged over the elements sharing each node (Pa, shape
    (nodes, 3, 3)) and, per node, the largest shear (σ₁ − σ₃)/2 of any one of those elements
    (Pa, shape (nodes,)): the averaged value is the usual nodal stress, the element-wise largest
    an upper estimate; their gap measures the discretisation error at a peak. ``measure``: the
    element-wise quantity instead of the largest shear (e.g. :func:`max_principal`), or a tuple
    of them (then a list of element-wise values, one per measure).
    """
    flat, dofs = element_node_stresses(sol, material)
    n = sol.skfem_mesh.doflocs.shape[1]
    total = np.stack([np.bincount(dofs, flat[k], minlength=n) for k in range(9)], axis=1)
    count = np.bincount(dofs, minlength=n)
    tensors = flat.T.reshape(-1, 3, 3)
    each = []
    for m in (measure if isinstance(measure, (tuple, list)) else (measure or max_shear,)):
        e = np.zeros(n)
        np.maximum.at(e, dofs, m(tensors))
        each.append(e)
    avg = (total / np.maximum(count, 1)[:, None]).reshape(n, 3, 3)
    return avg, (each if isinstance(measure, (tuple, list)) else each[0])


def max_principal(stress: np.ndarray) -> np.ndarray:
    """σ₁, the largest principal stress of tensors (..., 3, 3), Pa."""
    return np.linalg.eigvalsh(stress)[..., -1]


def largest_either_sign(stress: np.ndarray) -> np.ndarray:
    """max(σ₁, −σ₃) of tensors (..., 3, 3), Pa: the largest tensile principal stress under the
    load and under the same load reversed. A crank's bending alternates, so a fillet point in
    compression under one sign is in tension under the other (the journal fillet's overlap side
    under the in-plane couple)."""
    w = np.linalg.eigvalsh(stress)
    return np.maximum(w[..., -1], -w[..., 0])


def von_mises_tensor(stress: np.ndarray) -> np.ndarray:
    """The von Mises equivalent stress √(3 J₂) of tensors (..., 3, 3), Pa (the same under either
    sign of the load): the measure [IACSM53] Appendix III takes for the bending SCFs."""
    dev = stress - np.trace(stress, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) / 3.0
    return np.sqrt(1.5 * np.einsum("...ij,...ij->...", dev, dev))


def max_shear(stress: np.ndarray) -> np.ndarray:
    """(σ₁ − σ₃)/2 of stress tensors (..., 3, 3), Pa."""
    w = np.linalg.eigvalsh(stress)
    return 0.5 * (w[..., -1] - w[..., 0])


def fillet_zone(xyz: np.ndarray, x_face: float, side: int, centre, radius: float, fillet: float) -> np.ndarray:
    """Nodes of a fillet between a shaft (radius ``radius`` about an axis parallel to x through
    ``centre`` (y, z)) and a face at x = ``x_face``, the shaft lying on the ``side`` (−1: x <
    x_face, +1: x > x_face): the quarter torus r ≤ ρ ≤ r + fillet, |x − x_face| ≤ fillet."""
    rho = np.hypot(xyz[:, 1] - centre[0], xyz[:, 2] - centre[1])
    ax = side * (xyz[:, 0] - x_face)
    slack = ZONE_SLACK * fillet
    return (rho <= radius + fillet + slack) & (rho >= radius - slack) & (ax >= -slack) & (ax <= fillet + slack)


def found_zone(xyz: np.ndarray, centre, extent, fillet: float) -> np.ndarray:
    """Nodes of a fillet found on a CAD solid (:class:`fetorsion.solid.recognise.FoundFillet`):
    within ``extent`` (x from, to; distance from the axis through ``centre`` (y, z) from, to; m,
    the throw's frame) of its faces, with the slack of :func:`fillet_zone` on its smallest radius
    ``fillet``. For a plain fillet it is :func:`fillet_zone`'s quarter torus; an undercut's zone
    reaches into the web as far as its faces do."""
    rho = np.hypot(xyz[:, 1] - centre[0], xyz[:, 2] - centre[1])
    x0, x1, r0, r1 = extent
    slack = ZONE_SLACK * fillet
    return (xyz[:, 0] >= x0 - slack) & (xyz[:, 0] <= x1 + slack) & (rho >= r0 - slack) & (rho <= r1 + slack)


def found_zones(crank: Crank, index: int, throw: Crank) -> list[tuple] | None:
    """For a CAD crank, the four fillets of throw ``index`` as found on its solid (journal, web 1;
    pin, web 1; pin, web 2; journal, web 2), each as (axis centre, extent, smallest radius) in the
    throw's frame (its slab moved to x = 0, its pin turned to +y: distances from an axis do not
    turn); None for a crank built from its dimensions, or a fillet the solid lacks."""
    if not getattr(crank, "solid_step", None) or crank.solid_window is not None:
        return None
    from ..solid.geometry import solid_features

    by_end = {f.end: f for f in solid_features(crank).fillets}
    i = index + 1
    ends = (f"journal_{i}/web_{2 * i - 1}", f"pin_{i}/web_{2 * i - 1}", f"pin_{i}/web_{2 * i}", f"journal_{i + 1}/web_{2 * i}")
    if not all(e in by_end for e in ends):
        return None
    lo = throw.solid_window[0]
    R = throw.engine.crank_radius
    out = []
    for e in ends:
        f = by_end[e]
        x0, x1, r0, r1 = f.extent
        out.append(((R, 0.0) if e.startswith("pin") else (0.0, 0.0), (x0 - lo, x1 - lo, r0, r1), f.radius))
    return out


@dataclass(frozen=True)
class FilletStress:
    """Peak shear over nominal at one fillet.

    Attributes
    ----------
    scf : float
        Peak (σ₁ − σ₃)/2 on the fillet over τ_nom.
    peak_pa, nominal_pa : float
        The two stresses under the FE's torque, Pa.
    scf_element_max : float
        The same with the largest single-element value at the nodes (an upper estimate).
    where_m : tuple of float
        Position of the peak, m.
    """

    name: str
    scf: float
    peak_pa: float
    nominal_pa: float
    where_m: tuple
    scf_element_max: float = math.nan


def stepped_shaft_scf(d: float, D: float, fillet: float, size: float, fillet_size: float | None = None,
                      material=None, load: str = "torsion") -> tuple[FilletStress, dict]:
    """FE SCF of a stepped round bar (lengths 3 d and 2 D either side of the step) under a pure
    end couple: ``torsion`` (peak largest shear over 16 T/(π d³)) or ``bending`` (peak largest
    principal stress over 32 M/(π d³)).

    Returns the fillet's :class:`FilletStress` and the mesh figures (``nodes``, ``elements``,
    ``dofs``, ``seconds``).
    """
    from ..description.model import Material
    from ..webs.throwfe import end_load_solutions

    if load not in SCF_LOADS:
        raise FetorsionError(f"load must be one of {', '.join(SCF_LOADS)}, got {load!r}")
    material = material or Material(210e9, 0.3, 7850.0, "steel")
    t0 = time.perf_counter()
    l_small, l_large = 3 * d, 2 * D
    from ..solid.isolate import call_isolated

    # Gmsh in a child process: a mesher abort becomes a message, not the end of the caller.
    mesh = call_isolated(stepped_shaft_mesh, d, D, l_small, l_large, fillet, size, fillet_size,
                         what="Gmsh, stepped shaft")
    sol = end_load_solutions(mesh, material, (SCF_LOADS[load],))[0]
    xyz = sol.skfem_mesh.doflocs.T
    zone = fillet_zone(xyz, l_small, -1, (0.0, 0.0), 0.5 * d, fillet)
    if load == "torsion":
        res = _peak("step fillet", _shear(sol, material), xyz, zone, float(nominal_shear(TORQUE, d)))
    else:
        res = _peak("step fillet", _principal(sol, material), xyz, zone, float(nominal_bending(TORQUE, d)))
    return res, {"nodes": int(mesh.n_nodes), "elements": int(mesh.n_elements), "dofs": int(sol.dofs),
                 "seconds": time.perf_counter() - t0}


def _peak(name: str, stress, xyz: np.ndarray, zone: np.ndarray, nominal: float) -> FilletStress:
    tau, each = stress
    if not zone.any():
        raise FetorsionError(f"{name}: no mesh node on the fillet (is the fillet radius > 0?)")
    i = np.flatnonzero(zone)[np.argmax(tau[zone])]
    return FilletStress(name, float(tau[i] / nominal), float(tau[i]), nominal, tuple(float(v) for v in xyz[i]),
                        float(each[zone].max() / nominal))


def _shear(sol, material):
    avg, each = nodal_stress(sol, material)
    return max_shear(avg), each


def _principal(sol, material):
    """(max(σ₁, −σ₃) of the averaged nodal stress, its element-wise largest): the largest tensile
    principal stress under either sign of the load."""
    avg, each = nodal_stress(sol, material, largest_either_sign)
    return largest_either_sign(avg), each


def _bending_measures(sol, material):
    """{"principal": …, "von_mises": …} (in that order): each as (averaged nodal value, element-wise largest),
    from one stress recovery."""
    avg, (each_p, each_v) = nodal_stress(sol, material, (largest_either_sign, von_mises_tensor))
    return {"principal": (largest_either_sign(avg), each_p), "von_mises": (von_mises_tensor(avg), each_v)}


#: The SCF load cases at the loaded face by name: torsion about x, and bending about z (for a
#: throw at crank angle 0, whose pin lies on +y: bending in the throw's plane), N·m.
SCF_LOADS = {"torsion": TORSION_LOAD, "bending": BENDING_LOAD}


def throw_scfs(crank: Crank, index: int = 0, mesh_size: float | None = None, fillet_size: float | None = None,
               loads=tuple(SCF_LOADS)) -> tuple[dict, dict]:
    """FE SCFs of the four fillets of throw ``index`` (0-based) of ``crank`` under each of ``loads``.

    The throw (journal centre to journal centre, crank angle 0: its pin on +y) is meshed with the
    mesher's ``stress`` purpose and loaded between its rigid end faces by a pure couple, every
    case from one factorisation: ``torsion`` (about x; peak largest shear over 16 T D/(π(D⁴ − d⁴)))
    and ``bending`` in the throw's plane (about z), which gives two cases: ``bending`` (peak
    max(σ₁, −σ₃), the largest tensile principal stress under either sign of the alternating
    load, over 32 M D/(π(D⁴ − d⁴))) and ``bending_vm`` (peak von Mises stress over the same).
    A couple loads every pin and journal section by itself (statics). Returns {case: the fillets
    (journal, web 1), (pin, web 1), (pin, web 2), (journal, web 2)} and the mesh figures.
    """
    from ..solid.mesh import default_fillet_size
    from ..webs.throwfe import END_LOADS, end_loaded_fe

    if not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
        raise FetorsionError(f"{crank.name}: fillet SCFs need fillets.journal and fillets.pin > 0")
    unknown = [k for k in loads if k not in SCF_LOADS]
    if unknown:
        raise FetorsionError(f"load must be one of {', '.join(SCF_LOADS)}, got {unknown[0]!r}")
    throw = throw_of(crank, index)
    size = default_mesh_size(throw) if mesh_size is None else mesh_size
    fine = default_fillet_size(throw, size, "stress") if fillet_size is None else fillet_size
    # the same FE as the throw's web stiffness (lumped method ``fe``) at these sizes: solved once
    fe = end_loaded_fe(throw, size, fine)
    sols = [fe.solutions[END_LOADS.index(SCF_LOADS[k])] for k in loads]
    j1, j2 = throw.journals
    w1, w2 = throw.webs
    pin = throw.pins[0]
    R = throw.engine.crank_radius
    x = np.cumsum([0.0, j1.length, w1.thickness, pin.length, w2.thickness])  # faces of the stack
    rj, rp = crank.fillets.journal, crank.fillets.pin
    found = found_zones(crank, index, throw)
    out = {}
    for load, sol in zip(loads, sols):
        xyz = sol.skfem_mesh.doflocs.T
        nominal = nominal_shear if load == "torsion" else nominal_bending
        # bending: the largest principal stress of either sign ("bending") and the von Mises
        # stress ("bending_vm", [IACSM53] Appendix III's measure), from one stress recovery
        measures = ({"torsion": _shear(sol, throw.material)} if load == "torsion" else
                    dict(zip(("bending", "bending_vm"), _bending_measures(sol, throw.material).values())))
        zones = ([found_zone(xyz, *f) for f in found] if found else
                 [fillet_zone(xyz, x[1], -1, (0, 0), 0.5 * j1.diameter, rj),
                  fillet_zone(xyz, x[2], +1, (R, 0), 0.5 * pin.diameter, rp),
                  fillet_zone(xyz, x[3], -1, (R, 0), 0.5 * pin.diameter, rp),
                  fillet_zone(xyz, x[4], +1, (0, 0), 0.5 * j2.diameter, rj)])
        for case, stress in measures.items():
            out[case] = [
                _peak("journal fillet, web 1", stress, xyz, zones[0], float(nominal(TORQUE, j1.diameter, j1.bore))),
                _peak("pin fillet, web 1", stress, xyz, zones[1], float(nominal(TORQUE, pin.diameter, pin.bore))),
                _peak("pin fillet, web 2", stress, xyz, zones[2], float(nominal(TORQUE, pin.diameter, pin.bore))),
                _peak("journal fillet, web 2", stress, xyz, zones[3], float(nominal(TORQUE, j2.diameter, j2.bore))),
            ]
    return out, {"nodes": len(fe.mesh.nodes), "elements": len(fe.mesh.tets), "dofs": int(sols[0].dofs),
                 "mesh_size_m": size, "fillet_size_m": fine, "seconds": fe.seconds}


@dataclass
class FilletSCFResult:
    """Pin and journal fillet SCFs of a crank's throw at a sequence of meshes (a convergence study).

    ``rows`` hold per mesh: ``mesh_size_m``, ``fillet_size_m``, ``nodes``, ``elements``, ``dofs``,
    ``seconds``, ``pin_scf`` and ``journal_scf`` (the larger of each pair of fillets).
    """

    name: str
    throw: int
    rows: list[dict] = field(default_factory=list)

    @property
    def pin_scf(self) -> float:
        """The finest mesh's pin fillet SCF."""
        return self.rows[-1]["pin_scf"]

    @property
    def journal_scf(self) -> float:
        """The finest mesh's journal fillet SCF."""
        return self.rows[-1]["journal_scf"]

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"name": self.name, "throw": self.throw + 1, "rows": self.rows,
                "pin_scf": self.pin_scf, "journal_scf": self.journal_scf,
                "definition": "torsion: peak (sigma1 - sigma3)/2 on the fillet / (16 T D / (pi (D^4 - d_i^4))); "
                              "bending in the throw's plane: peak max(sigma1, -sigma3) (either sign of the load) "
                              "and peak von Mises (bending_vm), each / (32 M D / (pi (D^4 - d_i^4)))"}

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        head = (f"{'size [mm]':>9} {'fillet [mm]':>11} {'elements':>9} {'DOF':>9} {'time [s]':>8} "
                f"{'pin SCF':>8} {'journal SCF':>11} {'pin bending':>11} {'journal bending':>15} "
                f"{'pin von Mises':>13} {'journal von Mises':>17}")
        lines = [f"{self.name}: SCFs at the fillets of throw {self.throw + 1} (static 3D FE; torsion, and bending "
                 "in the throw's plane)", head]
        lines += [f"{r['mesh_size_m'] * 1e3:9.2f} {r['fillet_size_m'] * 1e3:11.3f} {r['elements']:9d} {r['dofs']:9d} "
                  f"{r['seconds']:8.1f} {r['pin_scf']:8.3f} {r['journal_scf']:11.3f} "
                  f"{r.get('pin_bending_scf', float('nan')):11.3f} {r.get('journal_bending_scf', float('nan')):15.3f} "
                  f"{r.get('pin_bending_vm_scf', float('nan')):13.3f} {r.get('journal_bending_vm_scf', float('nan')):17.3f}"
                  for r in self.rows]
        return "\n".join(lines)

    def plot(self, ax=None):
        """SCF against the fillet element size (converging to the left). Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        h = [r["fillet_size_m"] * 1e3 for r in self.rows]
        ax.plot(h, [r["pin_scf"] for r in self.rows], "o-", label="pin fillet")
        ax.plot(h, [r["journal_scf"] for r in self.rows], "s-", label="journal fillet")
        ax.set_xlabel("element size on the fillets [mm]")
        ax.set_ylabel("torsional SCF [-]")
        ax.set_title(f"{self.name}: fillet SCF convergence", fontsize=10, wrap=True)
        ax.legend(fontsize=8)
        return ax


def run_fillet_scf(crank: Crank, refinements=(1.0, 0.5, 0.33, 0.25), throw: int = 0,
                   mesh_size: float | None = None) -> FilletSCFResult:
    """Fillet SCFs of one throw at the mesher's ``stress`` fillet size times each of ``refinements``.

    Parameters
    ----------
    crank : Crank
        With fillet radii > 0.
    refinements : sequence of float
        Factors on the default fillet element size (the fillet radius), coarse to fine; the
        global size stays (the peak is set by the fillet's elements: on the stepped shaft,
        fillet elements of r/2, r/4, r/16 gave 1.546, 1.556, 1.553).
    throw : int
        0-based throw.
    mesh_size : float, optional
        Global element size at factor 1, m (default the throw's :func:`default_mesh_size`).
    """
    from ..solid.mesh import default_fillet_size

    base = default_mesh_size(throw_of(crank, throw)) if mesh_size is None else mesh_size
    fine = default_fillet_size(throw_of(crank, throw), base, "stress")
    res = FilletSCFResult(crank.name, throw)
    for f in refinements:
        cases, info = throw_scfs(crank, throw, base, fine * f)
        res.rows.append({**info, **_larger_of_each(cases), "fillets": [s.__dict__ for s in cases["torsion"]],
                         "bending_fillets": [s.__dict__ for s in cases["bending"]],
                         "bending_vm_fillets": [s.__dict__ for s in cases["bending_vm"]]})
    return res


def _larger_of_each(cases: dict) -> dict:
    """The larger SCF of each pair of fillets (pin, journal), per load case."""
    out = {}
    for load, fillets in cases.items():
        tag = "" if load == "torsion" else f"_{load}"
        for kind in ("pin", "journal"):
            out[f"{kind}{tag}_scf"] = max(s.scf for s in fillets if s.name.startswith(kind))
    return out


#: Fillet SCFs of the reference cranks' throws from the convergence study
#: (``benchmarks/bench_fillet_scf.py``, finest mesh), keyed by :func:`scf_key`; read-only.
SHIPPED_SCF = Path(__file__).with_name("data") / "fillet_scf.json"
#: Fillet element size, as a share of the fillet radius, when a crank's SCFs are computed
#: here (not shipped): r/2 was within 2 % of r/4 on both reference cranks.
DEFAULT_FILLET_SHARE = 0.5


def scf_key(crank: Crank, throw: int = 0) -> str:
    """The key of a throw's SCFs: its stiffness key (geometry, material) tagged for stress."""
    from ..webs.throwfe import throw_key

    return throw_key(throw_of(crank, throw), "fillet-scf")


def stored_fillet_scfs(crank: Crank, throw: int = 0) -> SCFSet | None:
    """:func:`fillet_scfs` of ``crank`` when they are shipped (no FE needed), else None."""
    shipped = json.loads(SHIPPED_SCF.read_text()) if SHIPPED_SCF.exists() else {}
    entry = shipped.get(scf_key(crank, throw))
    return None if entry is None else SCFSet.from_dict(entry)


def fillet_scfs(crank: Crank, throw: int = 0) -> SCFSet:
    """Pin and journal fillet SCFs of ``crank`` (its throw ``throw`` stands for all): shipped
    values of the reference cranks' convergence study when the throw matches, else one static FE
    at fillet elements of :data:`DEFAULT_FILLET_SHARE` · r. Returns the torsion factors (peak
    largest shear over τ_nom), the bending ones in the throw's plane (peak largest principal
    stress under either sign of the load over the pin or journal section's σ_nom), the same with
    the von Mises stress ([IACSM53] Appendix III's measure) and how they were obtained.
    Every factor is against the fillet's own section (32 M D/(π(D⁴ − d⁴))); :mod:`.m53`
    converts them to the rule's web-section convention."""
    entry = stored_fillet_scfs(crank, throw)
    if entry is not None:
        return entry
    from ..solid.mesh import default_fillet_size

    t = throw_of(crank, throw)
    fine = DEFAULT_FILLET_SHARE * default_fillet_size(t, default_mesh_size(t), "stress")
    cases, info = throw_scfs(crank, throw, fillet_size=fine)
    each = _larger_of_each(cases)
    return SCFSet.of(each["pin_scf"], each["journal_scf"],
                     f"static 3D FE of throw {throw + 1}, fillet elements {fine * 1e3:.2f} mm, {info['dofs']} DOF",
                     each["pin_bending_scf"], each["journal_bending_scf"], each["pin_bending_vm_scf"],
                     each["journal_bending_vm_scf"])
