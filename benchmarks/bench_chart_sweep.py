"""The web-chart sweep (scripts/web_chart.py) on the local Dask cluster against serial runs.

The full sweep is 109 FE runs (103 distinct) and took 655 s serially before issue 15; on a
shared 2-core machine this benchmark runs a reduced sweep by default: the convergence study's
three meshes and the chart points of one row of c (``--rows``), each point on two meshes. Both
runs start from an empty sample store (nothing reused), serially in this process and then on
the local cluster; prints the walls, their ratio and the largest difference of L_e0/D_t
between the two. Writes nothing under results/.

    nice -n 5 python benchmarks/bench_chart_sweep.py [--rows 1] [--workers 2]
    nice -n 5 python benchmarks/bench_chart_sweep.py --rows 6        # the whole grid (plus the extras: --all)
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "scripts"))

import web_chart  # noqa: E402

from fetorsion.studies.runner import ClusterOnDemand, SampleStore  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=1, help="rows of c of the grid to run (1..6)")
    ap.add_argument("--all", action="store_true", help="the full sweep: every point of scripts/web_chart.py")
    ap.add_argument("--workers", type=int, default=None)
    args = ap.parse_args(argv)
    points = web_chart.jobs()
    if not args.all:
        rows = {f"{c:g}" for c in web_chart.C_GRID[:args.rows]}
        points = [(k, kw) for k, kw in points if k.startswith("grid:") and k.split(":")[1].split(",")[0] in rows]
    runs = [dict(c=web_chart.CENTRE[0], q=web_chart.CENTRE[1], mesh_share=s) for s in web_chart.RATE_SHARES]
    runs += [dict(kw, mesh_share=s) for _, kw in points for s in web_chart.wc.MESH_SHARES]
    distinct = len({tuple(sorted(r.items())) for r in runs})
    print(f"{len(points)} chart points: {len(runs)} FE runs ({distinct} distinct); load average {os.getloadavg()[0]:.2f}")
    walls, tables = {}, {}
    for how in ("serial", "cluster"):
        with tempfile.TemporaryDirectory() as tmp, ClusterOnDemand(workers=args.workers) as client:
            if how == "cluster":
                client.get()  # the cluster's start is timed apart
            t0 = time.perf_counter()
            tables[how], fe = web_chart.sweep(points, SampleStore(tmp), client if how == "cluster" else None)
            walls[how] = time.perf_counter() - t0
        print(f"{how}: wall {walls[how]:.1f} s (FE time summed over runs {fe:.1f} s); load average "
              f"{os.getloadavg()[0]:.2f}", flush=True)
    diff = max(abs(tables["cluster"][k]["le_dt"] / tables["serial"][k]["le_dt"] - 1) for k, _ in points)
    print(f"wall ratio cluster/serial: {walls['cluster'] / walls['serial']:.3f}; largest relative difference of "
          f"L_e0/D_t between the two: {diff:.1e} (2 cores shared with other engineers' jobs)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
