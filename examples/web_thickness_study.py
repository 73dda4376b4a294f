"""
Web thickness study
===================

How the first torsional frequency moves with the web thickness: lumped sweep, FE at the ends.

The documentation's gallery runs it on a coarse 40 mm mesh so that the site builds in minutes;
the default mesh (10 mm) gives the converged FE frequency.

Usage: python examples/web_thickness_study.py [MESH_MM]
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import fetorsion

# The repository's root, so that the script runs from any folder (the documentation builds the
# gallery from inside examples/).
ROOT = Path(fetorsion.__file__).resolve().parents[1]

mesh_mm = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
crank = fetorsion.load(ROOT / "geometry/peugeot_glx.toml")
print("web thickness [mm]   17-DOF f1 [Hz]")
thicknesses = np.linspace(18.0, 28.0, 6)
f_lumped = []
for h in thicknesses:
    variant = fetorsion.with_values(crank, {"webs.*.thickness": float(h)})
    f_lumped.append(fetorsion.lumped(variant, 17).frequencies_hz[0])
    print(f"{h:18.1f} {f_lumped[-1]:16.1f}")
f_fe = []
for h in thicknesses[[0, -1]]:
    variant = fetorsion.with_values(crank, {"webs.*.thickness": float(h)})
    f_fe.append(fetorsion.run_modal(variant, mesh_size=mesh_mm / 1000, modes=12).first_torsional())
    print(f"FE at {h:.1f} mm: {f_fe[-1]:.1f} Hz")

fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(thicknesses, f_lumped, "o-", label="17-DOF lumped")
ax.plot(thicknesses[[0, -1]], f_fe, "s", color="tab:red", label=f"FE, {mesh_mm:g} mm mesh")
ax.set_xlabel("web thickness [mm]")
ax.set_ylabel("first torsional frequency [Hz]")
ax.set_title(crank.name)
ax.legend()
fig.tight_layout()
