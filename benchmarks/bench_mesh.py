"""Meshing time and element count of the reference cranks at two element sizes.

Run: ``PYTHONPATH=. python benchmarks/bench_mesh.py [SIZE_MM ...]`` (default 10 and 6 mm).
Each line: crank, global size, size at fillets/drillings, tets, nodes, minimum SICN, time
to build the solid and the time to mesh it (linear mesh, order 2, untangling, arrays).
Gmsh runs on one thread (see fetorsion.solid.geometry.gmsh_session).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import fetorsion
from fetorsion.solid.geometry import build_solid, gmsh_session
from fetorsion.solid.mesh import mesh_solid

ROOT = Path(__file__).resolve().parents[1]
CRANKS = ("peugeot_glx.toml", "renault21.toml")


def main(sizes_mm: list[float]) -> None:
    print(f"{'crank':<14} {'size':>6} {'fillet':>6} {'tets':>8} {'nodes':>8} {'minSICN':>8} "
          f"{'solid s':>8} {'mesh s':>8}")
    for name in CRANKS:
        crank = fetorsion.load(ROOT / "geometry" / name)
        for size in sizes_mm:
            with gmsh_session():
                t0 = time.perf_counter()
                solid = build_solid(crank)
                t1 = time.perf_counter()
                mesh = mesh_solid(solid, crank, size * 1e-3)
                t2 = time.perf_counter()
            q = mesh.quality
            print(f"{Path(name).stem:<14} {size:6.1f} {q.fillet_size * 1e3:6.2f} {q.n_tets:8d} {q.n_nodes:8d} "
                  f"{q.min_sicn:8.3f} {t1 - t0:8.2f} {t2 - t1:8.2f}", flush=True)


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [10.0, 6.0])
