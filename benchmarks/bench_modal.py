"""Assembly and eigen-solve time against DOFs on free-free steel bars (curved P2 tets).

Each case runs in its own subprocess, one after the other, so its peak memory (max RSS)
is its own. Prints a Markdown table; ``--json`` also writes the rows.

    python benchmarks/bench_modal.py                       # default sizes, CHOLMOD + Lanczos
    python benchmarks/bench_modal.py --sizes 0.012 0.008 --solvers cholmod:lanczos superlu:lanczos
    python benchmarks/bench_modal.py --generic-upto 150000 # also time the generic skfem form

The bar (0.45 m long, 70 mm diameter) is about as long and as thick as a four-cylinder
crank's envelope; element sizes in m.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

LENGTH, DIAMETER = 0.45, 0.07
DEFAULT_SIZES = (0.016, 0.011, 0.0075)


def run_case(size: float, backend: str, method: str, modes: int, generic_upto: int) -> dict:
    """One mesh size and solver, in this process: timings (s), sizes and peak memory (GiB)."""
    import numpy as np

    from fetorsion.fe import assembly, eigen
    from fetorsion.description.model import Material
    from fetorsion.fe.modal import default_shift, split_rigid
    from fetorsion.fe.tetmesh import cylinder_mesh

    steel = Material(210e9, 0.3, 7850.0)
    t = time.perf_counter()
    mesh = cylinder_mesh(LENGTH, DIAMETER, size)
    t_mesh = time.perf_counter() - t
    t = time.perf_counter()
    m, _ = assembly.skfem_mesh(mesh)
    basis = assembly.p2_basis(m)
    pattern = assembly.block_pattern(basis)
    K = assembly.stiffness(basis, steel.youngs_modulus, steel.poisson_ratio, pattern)
    M = assembly.mass(basis, steel.density, pattern)
    t_asm = time.perf_counter() - t
    row = {"size_m": size, "elements": mesh.n_elements, "dofs": K.shape[0], "backend": backend,
           "method": method, "modes": modes, "gmsh_s": t_mesh, "assembly_s": t_asm}
    if K.shape[0] <= generic_upto:
        t = time.perf_counter()
        Kg = assembly.stiffness_generic(m, steel.youngs_modulus, steel.poisson_ratio)
        row["generic_assembly_s"] = time.perf_counter() - t
        row["generic_rel_diff"] = float(abs(K - Kg).max() / abs(Kg).max())
        del Kg
    sigma = default_shift(mesh, steel)
    res = eigen.lowest_modes(K, M, modes + 6, sigma, backend=backend, method=method)
    _, elastic = split_rigid(res.omega2, sigma)
    row.update(factorize_s=res.timings_s["factorize"], eigensolve_s=res.timings_s["eigensolve"])
    row["solve_total_s"] = row["assembly_s"] + row["factorize_s"] + row["eigensolve_s"]
    row["first_hz"] = float(np.sqrt(elastic[0]) / (2 * np.pi))
    row["peak_gib"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    return row


def table(rows: list[dict]) -> str:
    head = ("| DOFs | elements | solver | assembly s | generic form s | factorize s | eigensolve s "
            "| asm + solve s | peak GiB | f1 Hz |")
    lines = [head, "|" + "---|" * 10]
    for r in rows:
        gen = f"{r['generic_assembly_s']:.1f}" if "generic_assembly_s" in r else "-"
        if "error" in r:
            lines.append(f"| {r.get('dofs', '?')} | | {r['backend']}:{r['method']} | {r['error']} |||||||")
            continue
        lines.append(f"| {r['dofs']} | {r['elements']} | {r['backend']}:{r['method']} | {r['assembly_s']:.1f} "
                     f"| {gen} | {r['factorize_s']:.1f} | {r['eigensolve_s']:.1f} | {r['solve_total_s']:.1f} "
                     f"| {r['peak_gib']:.2f} | {r['first_hz']:.2f} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=float, nargs="+", default=DEFAULT_SIZES, help="element sizes, m")
    ap.add_argument("--solvers", nargs="+", default=["cholmod:lanczos"],
                    help="backend:method pairs, e.g. cholmod:lanczos superlu:lanczos cholmod:lobpcg")
    ap.add_argument("--modes", type=int, default=20, help="elastic modes per solve")
    ap.add_argument("--generic-upto", type=int, default=0,
                    help="also time scikit-fem's generic elasticity form up to this many DOFs")
    ap.add_argument("--timeout", type=float, default=900, help="per case, s")
    ap.add_argument("--json", type=Path, help="write the rows here")
    ap.add_argument("--case", help=argparse.SUPPRESS)  # internal: size,backend,method
    args = ap.parse_args(argv)

    if args.case:
        size, backend, method = args.case.split(",")
        print(json.dumps(run_case(float(size), backend, method, args.modes, args.generic_upto)))
        return
    rows = []
    for size in args.sizes:
        for solver in args.solvers:
            backend, method = solver.split(":")
            cmd = [sys.executable, __file__, "--case", f"{size},{backend},{method}", "--modes", str(args.modes),
                   "--generic-upto", str(args.generic_upto)]
            try:
                out = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
                row = json.loads(out.stdout.strip().splitlines()[-1]) if out.returncode == 0 else \
                    {"size_m": size, "backend": backend, "method": method,
                     "error": f"failed (rc {out.returncode}): {out.stderr.strip().splitlines()[-1:]}"}
            except subprocess.TimeoutExpired:
                row = {"size_m": size, "backend": backend, "method": method, "error": f"> {args.timeout:.0f} s"}
            rows.append(row)
            print(json.dumps(row), file=sys.stderr, flush=True)
    print(table(rows))
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
