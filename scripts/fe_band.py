"""FE Monte Carlo of f1 against the lumped band (issue 15), both reference cranks.

For each crank: N Monte Carlo samples of the [uncertainty] inputs the coarse FE variant can
take (fillets and drillings are left out of it, so their three inputs stay nominal), each run
as a 3D FE modal (``--mesh-size``, no fillets or drillings) on the local Dask cluster; the
lumped 17-DOF model on the very same samples (same variant, paired), and a 2000-run lumped
Monte Carlo of the same inputs for the band. Samples are stored as they finish (the sample
store), so an interrupted run resumes. Run from the repository root, under nice:

    nice -n 5 .venv/bin/python scripts/fe_band.py [--samples 24] [--workers 2]

Writes ``results/studies/fe_band.md`` and ``fe_band.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import fetorsion  # noqa: E402
from fetorsion.description.defaults import CHECK_MESH_SIZE  # noqa: E402
from fetorsion.io import write_text_atomic  # noqa: E402
from fetorsion.studies.runner import ClusterOnDemand  # noqa: E402
from fetorsion.studies.models import FE_LEFT_OUT, FEModel, LumpedModel  # noqa: E402
from fetorsion.studies.sampling import study_inputs  # noqa: E402
from fetorsion.studies.study import run_study  # noqa: E402

OUT = ROOT / "results" / "studies"
CRANKS = ("peugeot_glx", "renault21")


def compare(crank, n: int, client, mesh_size: float, lumped_runs: int) -> dict:
    inputs, held = study_inputs(crank, exclude_prefixes=FE_LEFT_OUT)
    kw = dict(client=client, name=crank.name, held=held, seed=0)
    t0 = time.perf_counter()
    fe = run_study(FEModel(crank, mesh_size), inputs, "montecarlo", n, **kw)
    fe_wall = time.perf_counter() - t0
    paired = run_study(LumpedModel(crank, details=False), inputs, "montecarlo", n, **kw)
    band = run_study(LumpedModel(crank, details=False), inputs, "montecarlo", lumped_runs, **kw)
    ok = np.isfinite(fe.Y["f1"])
    rel = fe.Y["f1"][ok] / paired.Y["f1"][ok] - 1
    # The FE's own band, and the lumped band moved by the mean FE/lumped ratio: if the lumped
    # model has the FE's shape, the two agree to the scatter of the ratio.
    return {"crank": crank.name, "samples": n, "fe_ok": int(ok.sum()), "fe_failed": [e["error"] for e in fe.errors],
            "inputs": [i.name for i in inputs], "held_at_nominal": held, "mesh_size_m": mesh_size,
            "fe_wall_s": fe_wall,
            "fe_band": fe.bands["f1"], "lumped_same_samples_band": paired.bands["f1"],
            "lumped_band": band.bands["f1"], "lumped_runs": lumped_runs,
            "ratio_mean": float(rel.mean()), "ratio_std": float(rel.std(ddof=1)),
            "ratio_min": float(rel.min()), "ratio_max": float(rel.max()),
            "fe_cv": float(fe.Y["f1"][ok].std(ddof=1) / fe.Y["f1"][ok].mean()),
            "lumped_same_cv": float(paired.Y["f1"][ok].std(ddof=1) / paired.Y["f1"][ok].mean()),
            "fe_computed": fe.summary.computed, "fe_values": fe.Y["f1"].tolist(),
            "lumped_values": paired.Y["f1"].tolist()}


def markdown(rows: list[dict], workers: int, load: tuple[float, float]) -> str:
    lines = ["# FE Monte Carlo of f1 against the lumped band", "",
             "Written by `scripts/fe_band.py`. Each crank: Monte Carlo samples (seed 0) of every `[uncertainty]` "
             "input except fillets and drillings (left out of the coarse FE variant, held nominal), uniform over its "
             f"range; each sample a 3D FE modal without fillets or drillings at {rows[0]['mesh_size_m'] * 1e3:g} mm "
             f"on a local Dask cluster of {workers} workers (2 cores shared with other engineers' jobs, load average "
             f"{load[0]:.1f} before, {load[1]:.1f} after), and the lumped 17-DOF model (Carter) of the same variant "
             "on the same samples.", "",
             "| crank | FE runs (ok) | FE f1 5–95 % | lumped, same samples | lumped, {n} runs | FE/lumped − 1, mean ± sd "
             "(min..max) | spread (sd/mean) FE, lumped |".replace("{n}", str(rows[0]["lumped_runs"])),
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        fb, lb, bb = r["fe_band"], r["lumped_same_samples_band"], r["lumped_band"]
        lines.append(f"| {r['crank']} | {r['samples']} ({r['fe_ok']}) | {fb['p5']:.0f}–{fb['p95']:.0f} Hz | "
                     f"{lb['p5']:.0f}–{lb['p95']:.0f} Hz | {bb['p5']:.0f}–{bb['p95']:.0f} Hz | "
                     f"{100 * r['ratio_mean']:+.1f} % ± {100 * r['ratio_std']:.1f} % "
                     f"({100 * r['ratio_min']:+.1f}..{100 * r['ratio_max']:+.1f} %) | "
                     f"{100 * r['fe_cv']:.1f} %, {100 * r['lumped_same_cv']:.1f} % |")
    lines += ["", "FE wall per crank: " + ", ".join(f"{r['crank']}: {r['fe_wall_s']:.0f} s for {r['fe_computed']} "
                                                   "computed runs" for r in rows), ""]
    for r in rows:
        if r["fe_failed"]:
            lines.append(f"- {r['crank']}: {len(r['fe_failed'])} FE runs failed: {r['fe_failed'][0]}")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=24)
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--mesh-size", type=float, default=CHECK_MESH_SIZE * 1e3, help="mm")
    ap.add_argument("--lumped-runs", type=int, default=2000)
    args = ap.parse_args(argv)
    load0 = os.getloadavg()[0]
    rows = []
    with ClusterOnDemand(workers=args.workers) as client:
        for name in CRANKS:
            crank = fetorsion.load(ROOT / "geometry" / f"{name}.toml")
            rows.append(compare(crank, args.samples, client, args.mesh_size * 1e-3, args.lumped_runs))
            print(json.dumps({k: v for k, v in rows[-1].items() if not k.endswith("values")}, indent=1), flush=True)
        workers = len(client.get().scheduler_info()["workers"])
    OUT.mkdir(parents=True, exist_ok=True)
    write_text_atomic(OUT / "fe_band.json", json.dumps(rows, indent=1) + "\n")
    write_text_atomic(OUT / "fe_band.md", markdown(rows, workers, (load0, os.getloadavg()[0])))
    print((OUT / "fe_band.md").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
