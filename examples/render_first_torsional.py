"""Render the first torsional FE mode of a crank off-screen, and its 17-DOF lumped shape.

Usage: python examples/render_first_torsional.py [CRANK.toml] [OUT_DIR] [MESH_MM]
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import fetorsion
from fetorsion.report.render import render_mode

path = sys.argv[1] if len(sys.argv) > 1 else "geometry/renault21.toml"
out = Path(sys.argv[2] if len(sys.argv) > 2 else "out/examples")
mesh_mm = float(sys.argv[3]) if len(sys.argv) > 3 else 10.0
out.mkdir(parents=True, exist_ok=True)

crank = fetorsion.load(path)
fe = fetorsion.run_modal(crank, mesh_size=mesh_mm / 1000, modes=12)
res = fe
j = res.kinds.index("torsional")
png = render_mode(fe.mesh.nodes, fe.mesh.tets, res.shapes[j], out / "first_torsional.png",
                  title=f"{crank.name}: {res.frequencies_hz[j]:.1f} Hz, torsional")
print(f"FE first torsional {res.frequencies_hz[j]:.1f} Hz -> {png}")
ax = fetorsion.lumped(crank, 17).plot(modes=2)
ax.figure.savefig(out / "lumped_17dof_modes.png", dpi=110)
print(f"17-DOF mode shapes -> {out / 'lumped_17dof_modes.png'}")
