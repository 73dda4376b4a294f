"""
Lumped models against the 3D FE
===============================

Compare the 3D FE first torsional mode of a crank with its lumped models.

The documentation's gallery runs it on a coarse 30 mm mesh so that the site builds in minutes;
the default mesh (10 mm) gives the converged FE frequency.

Usage: python examples/lumped_vs_fe.py [CRANK.toml] [MESH_MM]
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt

import fetorsion

# The repository's root, so that the script runs from any folder (the documentation builds the
# gallery from inside examples/).
ROOT = Path(fetorsion.__file__).resolve().parents[1]

path = sys.argv[1] if len(sys.argv) > 1 else ROOT / "geometry/peugeot_glx.toml"
mesh_mm = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0

crank = fetorsion.load(path)
fe = fetorsion.run_modal(crank, mesh_size=mesh_mm / 1000, modes=12)
f_fe = fe.first_torsional()
print(f"{crank.name}")
print(f"  FE ({fe.dofs} DOF): first torsional {f_fe:.1f} Hz")
lumped = {}
for dof in fetorsion.PARTITIONS:
    f = lumped[dof] = fetorsion.lumped(crank, dof).frequencies_hz[0]
    print(f"  {dof:>2}-DOF lumped (Carter webs): {f:7.1f} Hz ({100 * (f / f_fe - 1):+.1f} % against FE)")
measured = crank.notes.get("measured_first_torsional_hz")
if measured:
    print(f"  measured: {measured} Hz; FE error {100 * (f_fe / measured - 1):+.1f} %")

# The first torsional frequency of each lumped partition beside the FE's (and the measurement's).
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.bar([f"{dof}-DOF" for dof in lumped], list(lumped.values()), color="tab:blue", label="lumped (Carter webs)")
ax.axhline(f_fe, color="tab:red", label=f"FE, {fe.dofs} DOF")
if measured:
    ax.axhline(float(measured), color="k", ls="--", label="measured")
ax.set_ylabel("first torsional frequency [Hz]")
ax.set_title(crank.name)
ax.legend(loc="lower right")
fig.tight_layout()
