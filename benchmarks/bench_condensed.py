"""Condensed crank (issue 13): reduction time against one modal solve of the same mesh, the
reduced size, its accuracy against the full FE, and the coupled forced-response sweep.

    nice python benchmarks/bench_condensed.py [geometry/renault21.toml] [--mesh-size 0.010]

Prints: mesh, full DOF; modal solve wall (assembly + factorisation + eigen-solve, 26 modes);
reduction wall (assembly + factorisation + interface + constraint modes + Ritz vectors +
projection) and the ratio; reduced DOF; the first 10 elastic modes, reduced vs full, free and
in rigid bearings; f1 free and in bearings; the forced-response sweep wall (300 speeds,
orders 0.5-12).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import fetorsion  # noqa: E402
from fetorsion.description.defaults import DEFAULT_MESH_SIZE  # noqa: E402
from fetorsion.fe.condensed import run_condensed  # noqa: E402
from fetorsion.fe.crankfe import run_modal  # noqa: E402
from fetorsion.response.coupled import run_coupled_response  # noqa: E402
from fetorsion.solid.mesh import mesh_crank  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", nargs="?", default=str(ROOT / "geometry" / "renault21.toml"))
    ap.add_argument("--mesh-size", type=float, default=DEFAULT_MESH_SIZE, help="m")
    ap.add_argument("--no-full", action="store_true", help="skip the full-model comparison")
    args = ap.parse_args(argv)
    crank = fetorsion.load(args.file)
    cm = mesh_crank(crank, args.mesh_size)
    print(f"{crank.name}: {len(cm.tets)} tets, mesh {cm.quality.seconds:.1f} s")
    t = time.perf_counter()
    mod = run_modal(crank, mesh=cm)
    t_modal = time.perf_counter() - t
    print(f"modal solve: {t_modal:.1f} s ({mod.dofs} DOF; {', '.join(f'{k} {v:.1f}' for k, v in mod.timings_s.items())})")
    t = time.perf_counter()
    cc = run_condensed(crank, mesh=cm, keep_full=not args.no_full)
    t_red = time.perf_counter() - t
    print(f"reduction: {t_red:.1f} s = {t_red / t_modal:.2f} x the modal solve; {cc.reduced.size} reduced DOF "
          f"({', '.join(f'{k} {v:.1f}' for k, v in cc.timings_s.items())})")
    for s in ("free", "bearings"):
        red = cc.modes(s, 10)
        line = f"{s:>8}: f1 (torsional) {red.first_torsional():.2f} Hz"
        if not args.no_full:
            full = cc.full_modes(s, 10)
            line += f"; first 10 modes reduced vs full: max {np.abs(red.frequencies_hz / full - 1).max():.2e}"
        print(line)
    if crank.excitation is not None:
        rpm = np.linspace(*crank.excitation.speed_range, 300)
        t = time.perf_counter()
        r = run_coupled_response(cc, "bearings", rpm=rpm)
        print(f"forced-response sweep: {time.perf_counter() - t:.2f} s (300 speeds, {len(r.orders)} orders)")
        print(r.table())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
