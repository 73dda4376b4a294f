"""How the first torsional frequency moves with the web thickness: lumped sweep, FE at the ends.

Usage: python examples/web_thickness_study.py [MESH_MM]
"""

import sys

import numpy as np

import fetorsion

mesh_mm = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
crank = fetorsion.load("geometry/peugeot_glx.toml")
print("web thickness [mm]   17-DOF f1 [Hz]")
thicknesses = np.linspace(18.0, 28.0, 6)
for h in thicknesses:
    variant = fetorsion.with_values(crank, {"webs.*.thickness": float(h)})
    print(f"{h:18.1f} {fetorsion.lumped(variant, 17).frequencies_hz[0]:16.1f}")
for h in thicknesses[[0, -1]]:
    variant = fetorsion.with_values(crank, {"webs.*.thickness": float(h)})
    f = fetorsion.run_modal(variant, mesh_size=mesh_mm / 1000, modes=12).first_torsional()
    print(f"FE at {h:.1f} mm: {f:.1f} Hz")
