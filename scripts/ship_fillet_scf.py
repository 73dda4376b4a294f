"""Writes fetorsion/design/data/fillet_scf.json from the convergence studies in results/scf/
(benchmarks/bench_fillet_scf.py): each crank's finest mesh, with its change from the next
coarser one in the source text.

    .venv/bin/python scripts/ship_fillet_scf.py renault21 peugeot_glx [inline6_diesel ...]
"""

import json
import sys
from pathlib import Path

import fetorsion
from fetorsion.design.scf import SHIPPED_SCF, scf_key
from fetorsion.io import write_text_atomic

ROOT = Path(__file__).resolve().parents[1]
KEYS = {"pin": "pin_scf", "journal": "journal_scf", "pin_bending": "pin_bending_scf",
        "journal_bending": "journal_bending_scf", "pin_bending_vm": "pin_bending_vm_scf",
        "journal_bending_vm": "journal_bending_vm_scf"}

shipped = json.loads(SHIPPED_SCF.read_text()) if SHIPPED_SCF.exists() else {}
for name in sys.argv[1:]:
    study = json.loads((ROOT / "results" / "scf" / f"{name}.json").read_text())
    fine, coarse = study["rows"][-1], study["rows"][-2]
    crank = fetorsion.load(ROOT / "geometry" / f"{name}.toml")
    r = crank.fillets.pin
    change = ", ".join(f"{k} {100 * abs(fine[v] / coarse[v] - 1):.1f} %" for k, v in KEYS.items())
    shipped[scf_key(crank)] = {
        **{k: fine[v] for k, v in KEYS.items()},
        "source": (f"static 3D FE of throw 1 (results/scf/{name}.json: fillet elements {fine['fillet_size_m'] * 1e3:.3g} mm"
                   f" = r/{r / fine['fillet_size_m']:.0f}, {fine['dofs']} DOF; change from "
                   f"{coarse['fillet_size_m'] * 1e3:.3g} mm: {change}; bending under either sign of the load)")}
    print(name, {k: round(v, 3) for k, v in shipped[scf_key(crank)].items() if k != "source"})
write_text_atomic(SHIPPED_SCF, json.dumps(shipped, indent=1) + "\n")
