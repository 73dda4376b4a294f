"""The whole crank job against mesh size: meshing, assembly, factorisation, eigen-solve.

Each mesh size runs in its own subprocess (peak memory is its own). Prints a Markdown table.

    python benchmarks/bench_crank_modal.py                         # Peugeot GLX, 20/10/6 mm
    python benchmarks/bench_crank_modal.py --crank geometry/renault21.toml --sizes 10 5 --fillet-scale 0.7

``--fillet-scale`` multiplies the fillet/drilling element size too (default 1: 2.5 mm on the
reference cranks, which then dominates the element count at coarse global sizes).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys


def run_case(crank_path: str, size_mm: float, fillet_scale: float, modes: int) -> dict:
    import time

    import fetorsion
    from fetorsion.fe.crankfe import run_modal
    from fetorsion.solid.mesh import default_fillet_size

    crank = fetorsion.load(crank_path)
    size = size_mm * 1e-3
    t = time.perf_counter()
    fe = run_modal(crank, size, modes, fillet_size=default_fillet_size(crank, size) * fillet_scale)
    wall = time.perf_counter() - t
    r = fe.result
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    return {"size_mm": size_mm, "tets": r.elements, "dofs": r.dofs, "f1_hz": r.first_torsional(),
            "meshing_s": r.timings_s.get("meshing", 0.0), "assembly_s": r.timings_s.get("assembly", 0.0),
            "factorize_s": r.timings_s.get("factorize", 0.0), "eigensolve_s": r.timings_s.get("eigensolve", 0.0),
            "wall_s": wall, "peak_gib": peak, "backend": r.backend}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--crank", default="geometry/peugeot_glx.toml")
    p.add_argument("--sizes", type=float, nargs="+", default=[20.0, 10.0, 6.0], help="global sizes, mm")
    p.add_argument("--fillet-scale", type=float, default=1.0)
    p.add_argument("--modes", type=int, default=20)
    p.add_argument("--case", type=float, help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.case is not None:
        print(json.dumps(run_case(a.crank, a.case, a.fillet_scale, a.modes)))
        return
    print(f"{a.crank}, {a.modes} elastic modes, fillet size x{a.fillet_scale:g}")
    print("| size mm | tets | DOF | f1 Hz | mesh s | assembly s | factorise s | eigen s | wall s | peak GiB |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for size in a.sizes:
        out = subprocess.run([sys.executable, __file__, "--crank", a.crank, "--case", str(size), "--fillet-scale",
                              str(a.fillet_scale), "--modes", str(a.modes)], capture_output=True, text=True)
        if out.returncode != 0:
            print(f"| {size:g} | failed: {out.stderr.strip().splitlines()[-1]} |")
            continue
        r = json.loads(out.stdout.strip().splitlines()[-1])
        print(f"| {size:g} | {r['tets']} | {r['dofs']} | {r['f1_hz']:.1f} | {r['meshing_s']:.1f} | "
              f"{r['assembly_s']:.1f} | {r['factorize_s']:.1f} | {r['eigensolve_s']:.1f} | {r['wall_s']:.1f} | "
              f"{r['peak_gib']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
