"""Compare the 3D FE first torsional mode of a crank with its lumped models.

Usage: python examples/lumped_vs_fe.py [CRANK.toml] [MESH_MM]
"""

import sys

import fetorsion

path = sys.argv[1] if len(sys.argv) > 1 else "geometry/peugeot_glx.toml"
mesh_mm = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0

crank = fetorsion.load(path)
fe = fetorsion.run_modal(crank, mesh_size=mesh_mm / 1000, modes=12)
f_fe = fe.first_torsional()
print(f"{crank.name}")
print(f"  FE ({fe.dofs} DOF): first torsional {f_fe:.1f} Hz")
for dof in fetorsion.PARTITIONS:
    f = fetorsion.lumped(crank, dof).frequencies_hz[0]
    print(f"  {dof:>2}-DOF lumped (Carter webs): {f:7.1f} Hz ({100 * (f / f_fe - 1):+.1f} % against FE)")
measured = crank.notes.get("measured_first_torsional_hz")
if measured:
    print(f"  measured: {measured} Hz; FE error {100 * (f_fe / measured - 1):+.1f} %")
