"""Oil-bore SCF convergence of both reference cranks' drilled sections (issue 27): a bar with the
section's diameter and bore, drilled through by the crank's oil hole, at wall elements d/16 and
d/24 (``fetorsion.design.oilbore``), plus the published check (a 4 mm hole in a 40 mm bar).
Prints the tables, writes results/scf/oil_bore.json and the shipped
fetorsion/design/data/oil_bore_scf.json (the finer level). Heavy (~6 min on 2 cores): run once, niced.

    nice -n 5 .venv/bin/python benchmarks/bench_oil_bore_scf.py
"""

import json
import platform
from pathlib import Path

import fetorsion
from fetorsion.design.oilbore import SHIPPED_OIL_BORE, oil_bore_key, run_oil_bore_scf
from fetorsion.io import write_text_atomic

ROOT = Path(__file__).resolve().parents[1]

sections = {("check", "bar"): (0.040, 0.004, 0.0, 0.3)}
for name in ("renault21", "peugeot_glx"):
    crank = fetorsion.load(ROOT / "geometry" / f"{name}.toml")
    for kind, parts in (("pin", crank.pins), ("journal", crank.journals)):
        p = parts[0]
        sections[(name, kind)] = (p.diameter, crank.oil_holes.diameter, p.bore, crank.material.poisson_ratio)

study, shipped = {}, {}
for (name, kind), (D, d, di, nu) in sections.items():
    res = run_oil_bore_scf(D, d, di)
    print(f"{name} {kind}:", res.table(), f"change d/16 -> d/24: torsion {100 * res.change('torsion'):.2f} %, "
          f"bending {100 * res.change('bending'):.2f} %", sep="\n", flush=True)
    study[f"{name} {kind}"] = res.to_dict()
    if name != "check":
        shipped[oil_bore_key(D, d, di, nu)] = {
            "bending": res.bending, "torsion": res.torsion,
            "source": (f"static 3D FE of a bar with a transverse hole (results/scf/oil_bore.json: wall elements "
                       f"{res.rows[-1]['wall_size_m'] * 1e3:.3f} mm = d/24, {res.rows[-1]['dofs']} DOF; torsion "
                       f"{100 * res.change('torsion'):.1f} %, bending {100 * res.change('bending'):.1f} % from d/16)")}
study["machine"] = f"{platform.processor() or platform.machine()}, {__import__('os').cpu_count()} cores"
write_text_atomic(ROOT / "results" / "scf" / "oil_bore.json", json.dumps(study, indent=1) + "\n")
write_text_atomic(SHIPPED_OIL_BORE, json.dumps(shipped, indent=1, sort_keys=True) + "\n")
