"""A solid round steel bar meshed and assembled: the shared model of the shaft tests."""

from __future__ import annotations

from types import SimpleNamespace

from fetorsion.fe import assembly
from fetorsion.fe.tetmesh import cylinder_mesh


def assembled_shaft(length: float, diameter: float, size: float, E: float, nu: float, rho: float) -> SimpleNamespace:
    """The bar along +x (m) as curved P2 tetrahedra of ``size`` (Gmsh): its mesh, the scikit-fem
    mesh and node → DOF map, the P2 basis and block pattern, K (N/m) and M (kg, K's pattern)."""
    mesh = cylinder_mesh(length, diameter, size)
    m, dof_of_node = assembly.skfem_mesh(mesh)
    b = assembly.p2_basis(m)
    pat = assembly.block_pattern(b)
    return SimpleNamespace(mesh=mesh, m=m, dof_of_node=dof_of_node, basis=b, pattern=pat,
                           K=assembly.stiffness(b, E, nu, pat), M=assembly.mass(b, rho, pat))
