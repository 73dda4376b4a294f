"""The oil-bore SCFs of a solid section (d_i = 0, ν = 0.3) against d/D, shipped as a table that the
run interpolates for a user's crank instead of meshing a drilled bar (issue 26: the main job stays
fast). The bar is the one of ``fetorsion.design.oilbore`` at the finer wall size (d/24). Writes
fetorsion/design/data/oil_bore_table.json. Heavy (~9 min on 2 cores): run once, niced.

    nice -n 5 .venv/bin/python benchmarks/bench_oil_bore_table.py
"""

import json

from fetorsion.design.oilbore import OIL_BORE_SHARES, OIL_BORE_TABLE, TABLE_RATIOS, transverse_hole_scfs
from fetorsion.io import write_text_atomic

D = 0.050
rows = []
for ratio in TABLE_RATIOS:
    peaks, info = transverse_hole_scfs(D, ratio * D, 0.0, OIL_BORE_SHARES[-1])
    rows.append({"d_over_D": ratio, "torsion": peaks["torsion"].scf, "bending": peaks["bending"].scf,
                 "dofs": info["dofs"], "seconds": round(info["seconds"], 1)})
    print(rows[-1], flush=True)
write_text_atomic(OIL_BORE_TABLE, json.dumps({"poisson_ratio": 0.3, "bore_over_D": 0.0,
                                              "wall_size": "d/24", "rows": rows}, indent=1) + "\n")
