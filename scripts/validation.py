"""The README's validation table: FE f1 of both reference cranks against the measurements.

    nice -n 10 python scripts/validation.py [--mesh-size 0.010]

For each crank, the free-free 3D FE at the default mesh with fillets and drillings, for the
nominal description and for the two corners of its [uncertainty] band
(fetorsion.studies.validation.run_validation, the code path tests/test_validation.py runs on a
coarse model). Writes results/validation.md and results/validation.json (~6 FE runs, ~4 min).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import fetorsion  # noqa: E402
from fetorsion.description.defaults import DEFAULT_MESH_SIZE  # noqa: E402
from fetorsion.io import write_text_atomic  # noqa: E402
from fetorsion.studies.validation import FE_ERROR_BOUND, run_validation  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh-size", type=float, default=DEFAULT_MESH_SIZE, help="m")
    args = ap.parse_args(argv)
    results = [run_validation(fetorsion.load(ROOT / "geometry" / f"{n}.toml"), args.mesh_size)
               for n in ("renault21", "peugeot_glx")]
    lines = ["| crank | measured f1 [Hz] | FE f1 [Hz] | FE error | FE band [Hz] | measured in band |",
             "|---|---|---|---|---|---|", *(r.row() for r in results), "",
             f"Free-free 3D FE, {args.mesh_size * 1e3:g} mm mesh with fillets and drillings "
             f"({', '.join(f'{r.dofs:,} DOF' for r in results)}); band: the FE at the two corners of the "
             f"description's [uncertainty] ranges. Stated bound on the FE error: {100 * FE_ERROR_BOUND:.0f} %. "
             "Written by scripts/validation.py."]
    out = ROOT / "results"
    write_text_atomic(out / "validation.md", "\n".join(lines) + "\n")
    write_text_atomic(out / "validation.json", json.dumps([r.to_dict() for r in results], indent=1) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
