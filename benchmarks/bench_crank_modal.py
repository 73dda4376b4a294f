"""The whole crank job against mesh size: meshing, assembly, factorisation, eigen-solve.

Each case runs in its own subprocess (peak memory is its own), one after the other.
Prints a Markdown table.

    python benchmarks/bench_crank_modal.py                         # Peugeot GLX, modal mesh, 20/10/6 mm
    python benchmarks/bench_crank_modal.py --sizes 10 --fillet-scale 1 1.5 2 2.5 --reference-hz 921.8
    python benchmarks/bench_crank_modal.py --purpose stress --sizes 4.3  # the ~1 M DOF case
    python benchmarks/bench_crank_modal.py --crank geometry/renault21.toml --purpose stress --sizes 4

``--purpose`` picks the default fillet/drilling element size (:func:`fetorsion.solid.mesh.default_fillet_size`:
``stress`` the smallest fillet radius, 2.5 mm on the reference cranks; ``modal`` twice that);
``--fillet-scale`` multiplies the *stress* fillet size instead (one case per value, the
fillet-size convergence study of docs/modal-mesh.md). ``--reference-hz`` adds the f1 error
against a reference value (e.g. the 1.15 M-DOF f1).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys


def run_case(crank_path: str, size_mm: float, purpose: str, fillet_scale: float | None, modes: int) -> dict:
    import time

    import fetorsion
    from fetorsion.fe.crankfe import run_modal
    from fetorsion.solid.mesh import default_fillet_size

    crank = fetorsion.load(crank_path)
    size = size_mm * 1e-3
    fillet = None if fillet_scale is None else default_fillet_size(crank, size, "stress") * fillet_scale
    t = time.perf_counter()
    fe = run_modal(crank, size, modes, fillet_size=fillet, purpose=purpose)
    wall = time.perf_counter() - t
    r, q = fe, fe.mesh.quality
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    return {"size_mm": size_mm, "fillet_mm": q.fillet_size * 1e3, "tets": r.elements, "dofs": r.dofs,
            "f1_hz": r.first_torsional(), "meshing_s": r.timings_s.get("meshing", 0.0),
            "assembly_s": r.timings_s.get("assembly", 0.0), "factorize_s": r.timings_s.get("factorize", 0.0),
            "eigensolve_s": r.timings_s.get("eigensolve", 0.0), "wall_s": wall, "peak_gib": peak,
            "backend": r.backend, "method": r.method}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--crank", default="geometry/peugeot_glx.toml")
    p.add_argument("--sizes", type=float, nargs="+", default=[20.0, 10.0, 6.0], help="global sizes, mm")
    p.add_argument("--purpose", choices=("modal", "stress"), default="modal")
    p.add_argument("--fillet-scale", type=float, nargs="+", help="fillet size = scale x the stress fillet size")
    p.add_argument("--modes", type=int, default=20)
    p.add_argument("--reference-hz", type=float, help="f1 reference for the error column")
    p.add_argument("--case", type=float, help=argparse.SUPPRESS)
    p.add_argument("--scale", type=float, help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.case is not None:
        print(json.dumps(run_case(a.crank, a.case, a.purpose, a.scale, a.modes)))
        return
    print(f"{a.crank}, {a.modes} elastic modes, {a.purpose} mesh")
    print("| size mm | fillet mm | tets | DOF | f1 Hz | f1 error | mesh s | assembly s | factorise s | eigen s "
          "| wall s | peak GiB |")
    print("|" + "---|" * 12)
    for size in a.sizes:
        for scale in a.fillet_scale or [None]:
            cmd = [sys.executable, __file__, "--crank", a.crank, "--case", str(size), "--purpose", a.purpose,
                   "--modes", str(a.modes)] + ([] if scale is None else ["--scale", str(scale)])
            out = subprocess.run(cmd, capture_output=True, text=True)
            if out.returncode != 0:
                print(f"| {size:g} | x{scale} | failed: {out.stderr.strip().splitlines()[-1]} |", flush=True)
                continue
            r = json.loads(out.stdout.strip().splitlines()[-1])
            err = f"{100 * (r['f1_hz'] / a.reference_hz - 1):+.3f} %" if a.reference_hz else "-"
            print(f"| {size:g} | {r['fillet_mm']:g} | {r['tets']} | {r['dofs']} | {r['f1_hz']:.2f} | {err} | "
                  f"{r['meshing_s']:.1f} | {r['assembly_s']:.1f} | {r['factorize_s']:.1f} | "
                  f"{r['eigensolve_s']:.1f} | {r['wall_s']:.1f} | {r['peak_gib']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
