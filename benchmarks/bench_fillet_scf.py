"""Fillet SCF convergence of both reference cranks (issue 14): static 3D FE of throw 1, fillet
elements r, r/2, r/3, r/4. Prints the tables and writes results/scf/<crank>.json (heavy: run once, niced).

    nice -n 5 .venv/bin/python benchmarks/bench_fillet_scf.py [renault21|peugeot_glx ...]
"""

import json
import sys
from pathlib import Path

import fetorsion
from fetorsion.io import write_text_atomic
from fetorsion.design.scf import run_fillet_scf

ROOT = Path(__file__).resolve().parents[1]

for name in sys.argv[1:] or ["renault21", "peugeot_glx"]:
    crank = fetorsion.load(ROOT / "geometry" / f"{name}.toml")
    res = run_fillet_scf(crank)
    print(res.table(), flush=True)
    for row in res.rows:
        for f in row["fillets"]:
            print(f"    {row['fillet_size_m'] * 1e3:.3f} mm  {f['name']:<24} SCF {f['scf']:.3f} "
                  f"(element-wise max {f['scf_element_max']:.3f})", flush=True)
    write_text_atomic(ROOT / "results" / "scf" / f"{name}.json", json.dumps(res.to_dict(), indent=1) + "\n")
